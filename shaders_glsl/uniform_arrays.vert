#version 450
// Seed 001 `uniform_arrays`: vertex shader (SPEC §1.2, pinned; the course shows no shader using
// its uniforms): eye-space normal and position for the fragment shader.
#include "transform.glsl"

layout(location = 0) out vec3 N;
layout(location = 1) out vec3 P;

void main()
{
    vec4 vertex = vec4(vertex_position, 1.0);  // gl_Vertex
    gl_Position = mvp * vertex;
    N = normal_matrix * vertex_normal;
    P = vec3(modelview * vertex);
}
