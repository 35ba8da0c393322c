#version 450
// Seed 001 `height`: a custom vertex attribute (SPEC §1.1; the body is pinned, the course shows
// only `attribute float height;`).
#include "transform_block.glsl"

layout(location = 0) in vec2 vertex_position;  // glVertex2f: gl_Vertex = (x, y, 0, 1)
layout(location = 1) in float height;          // attribute float height;
layout(location = 0) out vec4 color;           // gl_FrontColor

void main()
{
    gl_Position = mvp * vec4(vertex_position, 0.0, 1.0);
    float s = (height + 2.0) / 4.0;
    color = vec4(s, 0.25, 1.0 - s, 1.0);
}
