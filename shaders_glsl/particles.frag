#version 450
// Seed 001 `particles`: fragment shader (SPEC §1.5, pinned: the course gives none).
layout(location = 0) out vec4 frag_color;  // gl_FragColor

void main()
{
    frag_color = vec4(1.0, 0.8, 0.3, 1.0);
}
