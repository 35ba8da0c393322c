#version 450
// Exercise 2, NORMAL TO RGB MAPPING: fragment shader.
layout(location = 0) in vec3 normal;
layout(location = 0) out vec4 frag_color;

void main() {
    frag_color = vec4(normal, 1.0);  // negative components clamp to 0
}
