#version 450
// glColor3f(1, 1, 1) with lighting off: plain white.
layout(location = 0) out vec4 frag_color;

void main() {
    frag_color = vec4(1.0, 1.0, 1.0, 1.0);
}
