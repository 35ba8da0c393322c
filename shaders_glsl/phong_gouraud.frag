#version 450
// Exercise 3 with Gouraud shading: the interpolated vertex colour.
layout(location = 0) in vec4 color;
layout(location = 0) out vec4 frag_color;

void main() {
    frag_color = color;
}
