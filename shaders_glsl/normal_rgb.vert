#version 450
// Exercise 2, NORMAL TO RGB MAPPING: vertex shader.
#include "transform.glsl"

layout(location = 0) out vec3 normal;

void main() {
    normal = normalize(normal_matrix * vertex_normal);  // eye space
    gl_Position = mvp * vec4(vertex_position, 1.0);
}
