#version 450
// Seed 001 `bump` and `normmap`: tangent-space bump mapping, vertex shader (SPEC §1.11, pinned
// whole in the style of Angel's example; the lecture gives only the idea): the light and view
// directions in the tangent frame (T, B, N) of each vertex.
#include "transform_block.glsl"
#include "gl_light.glsl"

layout(location = 0) in vec3 vertex_position;  // gl_Vertex
layout(location = 1) in vec3 vertex_normal;    // gl_Normal
layout(location = 2) in vec4 objTangent;       // attribute vec4 objTangent;
layout(location = 3) in vec2 vertex_texcoord;  // gl_MultiTexCoord0 = (s, t, 0, 1)

// varying vec3 L; varying vec3 V; and gl_TexCoord[0]
layout(location = 0) out vec3 L;
layout(location = 1) out vec3 V;
layout(location = 2) out vec4 TexCoord0;

void main()
{
    vec4 vertex = vec4(vertex_position, 1.0);
    gl_Position = mvp * vertex;
    TexCoord0 = vec4(vertex_texcoord, 0.0, 1.0);
    vec3 eyePosition = vec3(modelview * vertex);
    vec3 eyeLightPos = LightSource[0].position.xyz;
    vec3 N = normalize(normal_matrix * vertex_normal);
    vec3 T = normalize(normal_matrix * objTangent.xyz);
    vec3 B = cross(N, T);
    L.x = dot(T, eyeLightPos - eyePosition);
    L.y = dot(B, eyeLightPos - eyePosition);
    L.z = dot(N, eyeLightPos - eyePosition);
    L = normalize(L);
    V.x = dot(T, -eyePosition);
    V.y = dot(B, -eyePosition);
    V.z = dot(N, -eyePosition);
    V = normalize(V);
}
