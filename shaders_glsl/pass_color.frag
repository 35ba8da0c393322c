#version 450
// Seed 001's "pass FS" (SPEC §1): gl_FragColor = gl_Color; the colour the vertex shader wrote
// to gl_FrontColor, interpolated across the primitive.
layout(location = 0) in vec4 color;  // gl_Color
layout(location = 0) out vec4 frag_color;

void main() {
    frag_color = color;
}
