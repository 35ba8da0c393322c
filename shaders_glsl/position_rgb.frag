#version 450
// Exercise 1, POSITION TO RGB MAPPING: fragment shader.
layout(location = 0) in vec4 color;
layout(location = 0) out vec4 frag_color;

void main() {
    frag_color = color;  // values above 1 clamp in the framebuffer, as in GL
}
