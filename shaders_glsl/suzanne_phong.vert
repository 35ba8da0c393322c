#version 450
// 4.9 Phong (the course's "..." body filled with its slides' formulas, SPEC 4.7): eye-space
// position and normal passed on, the lighting evaluated per fragment.
#include "suzanne_transform.glsl"
layout(location = 0) in vec4 v_coord;
layout(location = 2) in vec3 v_normal;
layout(location = 0) out vec3 P;
layout(location = 1) out vec3 N;
void main()
{
    P = vec3(MV * v_coord);
    N = normalize(NM * v_normal);
    gl_Position = MVP*v_coord;
}
