#version 450
// Seed 001 `particles`: the course's particle-system vertex shader (SPEC §1.5, verbatim but
// for the GLSL 450 declarations): x(t) = x0 + v t, y(t) = y0 + vy t + g t²/(2m).
#include "transform_block.glsl"

// uniform float g, m, t;
layout(set = 0, binding = 1) uniform Particles {
    float g, m, t;
};

layout(location = 0) in vec3 vertex_position;  // gl_Vertex: the start, (0, -1, 0)
layout(location = 1) in vec3 vel;              // attribute vec3 vel; // initial velocity

void main()
{
    vec3 object_pos;
    object_pos.x = vertex_position.x + vel.x * t;
    object_pos.y = vertex_position.y + vel.y * t + g/(2.0*m)*t*t;
    object_pos.z = vertex_position.z + vel.z * t;
    gl_Position =
        mvp *
        vec4(object_pos,1);
}
