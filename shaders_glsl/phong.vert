#version 450
// Exercise 3, PHONG SHADING: vertex shader.
#include "transform.glsl"

layout(location = 0) out vec3 N;  // interpolated normal
layout(location = 1) out vec3 v;  // vertex position in eye space

void main() {
    vec4 vertex = vec4(vertex_position, 1.0);
    v = vec3(modelview * vertex);
    N = normalize(normal_matrix * vertex_normal);
    gl_Position = mvp * vertex;
}
