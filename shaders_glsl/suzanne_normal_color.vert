#version 450
// 4.1 "Hello Suzanne" (course, verbatim): the object-space normal as colour.
#include "suzanne_transform.glsl"
layout(location = 0) in vec4 v_coord;
layout(location = 1) in vec2 v_texcoord;
layout(location = 2) in vec3 v_normal;
layout(location = 0) out vec4 color;
layout(location = 1) out vec2 texcoord;
void main()
{
    // pass texcoord to fragment shader (not used for the moment)
    texcoord = v_texcoord;
    // display normals
    color = vec4(abs(v_normal),1.0);
    gl_Position = MVP*v_coord;
}
