#version 450
// Seed 001 `morph`: the course's morphing vertex shader (SPEC §1.4, verbatim but for the
// GLSL 450 declarations).
#include "transform_block.glsl"

// uniform float time;
layout(set = 0, binding = 1) uniform Morph {
    float time;  // milliseconds, as the course's glutGet(GLUT_ELAPSED_TIME)
};

layout(location = 0) in vec3 vertex_position;  // glVertex3fv: gl_Vertex = (x, y, z, 1)
layout(location = 1) in vec3 vertices2;        // glVertexAttrib3fv: attribute vec4 vertices2 = (x, y, z, 1)
layout(location = 0) out vec4 color;           // gl_FrontColor

// gl_Color: GL's current colour, which the course never sets: white.
const vec4 current_color = vec4(1.0, 1.0, 1.0, 1.0);

void main()
{
    float s = 0.5*(1.0+sin(0.001*time));
    vec4 t = mix(vec4(vertex_position, 1.0), vec4(vertices2, 1.0), s);
    gl_Position = mvp*t;
    color = current_color;
}
