#version 450
// Seed 001 `toon`: non-photorealistic shading (SPEC §1.6). The course's colours and two tests,
// with N, L, E of its modified-Phong vertex shader: the test runs per vertex into
// gl_FrontColor, so bands blend across triangles and the black silhouette appears only where
// vertices fall within the 0.1 band (course behaviour).
#include "transform.glsl"
#include "gl_light.glsl"

layout(location = 0) out vec4 color;  // gl_FrontColor

const vec4 yellow = vec4(1.0, 1.0, 0.0, 1.0);
const vec4 red = vec4(1.0, 0.0, 0.0, 1.0);
const vec4 black = vec4(0.0, 0.0, 0.0, 1.0);

void main()
{
    vec4 vertex = vec4(vertex_position, 1.0);  // gl_Vertex
    gl_Position = mvp * vertex;
    vec4 eyePosition = modelview * vertex;
    vec4 eyeLightPos = LightSource[0].position;
    vec3 N = normalize(normal_matrix * vertex_normal);
    vec3 L = normalize(eyeLightPos.xyz - eyePosition.xyz);
    vec3 E = -normalize(eyePosition.xyz);
    if(dot(L, N) > 0.5) color = yellow;
    else color = red;
    if(abs(dot(E, N)) < 0.1) color = black;
}
