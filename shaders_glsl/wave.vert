#version 450
// Seed 001 `wave`: the course's wave-motion vertex shader (SPEC §1.3). The course's
// `uniform float xs, zs, // frequencies` does not compile (a comma for the `;`); fixed, and
// `gl_FrontColor = gl_Color;` added (SPEC's pinned line: the course's shader writes no colour).
#include "transform_block.glsl"

// uniform float time; uniform float xs, zs; uniform float h;
layout(set = 0, binding = 1) uniform Wave {
    float time;    // seconds
    float xs, zs;  // frequencies
    float h;       // height scale
};

layout(location = 0) in vec3 vertex_position;  // gl_Vertex
layout(location = 1) in vec3 vertex_color;     // glColor3f
layout(location = 0) out vec4 color;           // gl_FrontColor

void main()
{
    vec4 t = vec4(vertex_position, 1.0);
    t.y = vertex_position.y + h*sin(time + xs*vertex_position.x)
        + h*sin(time + zs*vertex_position.z);
    gl_Position = mvp*t;
    color = vec4(vertex_color, 1.0);
}
