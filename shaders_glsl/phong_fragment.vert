#version 450
// Seed 001 `phong_fragment`: the course's vertex shader for per-fragment lighting (SPEC §1.8,
// verbatim but for the GLSL 450 names of GL's built-ins): N, L, E as varyings.
#include "transform.glsl"
#include "gl_light.glsl"

// varying vec3 N, L, E;
layout(location = 0) out vec3 N;
layout(location = 1) out vec3 L;
layout(location = 2) out vec3 E;

void main()
{
    vec4 vertex = vec4(vertex_position, 1.0);  // gl_Vertex
    gl_Position = mvp * vertex;

    vec4 eyePosition = modelview * vertex;
    vec4 eyeLightPos = LightSource[0].position;

    N = normalize(normal_matrix * vertex_normal);
    L = normalize(eyeLightPos.xyz - eyePosition.xyz);
    E = -normalize(eyePosition.xyz);
}
