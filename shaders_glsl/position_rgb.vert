#version 450
// Exercise 1, POSITION TO RGB MAPPING: vertex shader.
#include "transform.glsl"

layout(location = 0) out vec4 color;

void main() {
    vec4 vertex = vec4(vertex_position, 1.0);
    // normalize the vertex (all four components, w = 1 included) and map it into RGB space
    color = normalize(vertex.zyxw) + vec4(0.5, 0.5, 0.5, 1.0);
    gl_Position = mvp * vertex;
}
