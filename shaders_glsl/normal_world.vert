#version 450
// Seed 002 (Lecture 12) `normal_world`, SPEC §2.3 (verbatim). The view is folded into the
// projection (the slide's trick), so `modelview` is the model alone and gl_NormalMatrix *
// gl_Normal is a world-space normal.
#include "transform.glsl"

layout(location = 0) out vec3 normal;

void main()
{
    gl_Position = mvp * vec4(vertex_position, 1.0);  // ftransform()
    normal = (normal_matrix * vertex_normal).xyz;
}
