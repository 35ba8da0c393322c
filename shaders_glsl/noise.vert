#version 450
// Exercise 4, SIMPLEX NOISE SHADER: vertex shader.
#include "transform.glsl"

layout(location = 0) out vec3 position;  // object-space vertex for the fragment shader

void main() {
    position = vertex_position;
    gl_Position = mvp * vec4(vertex_position, 1.0);
}
