#version 450
// 4.2 (course, verbatim): the normal turned by the normal matrix, so the colours turn with the
// model; also the vertex shader of 4.3 smooth, 4.4/4.5 texture and 4.6 texparams.
#include "suzanne_transform.glsl"
layout(location = 0) in vec4 v_coord;
layout(location = 1) in vec2 v_texcoord;
layout(location = 2) in vec3 v_normal;
layout(location = 0) out vec4 color;
layout(location = 1) out vec2 texcoord;
void main()
{
    texcoord = v_texcoord;
    vec3 N = normalize(NM * v_normal);
    color = vec4(abs(N), 1.0f);
    gl_Position = MVP*v_coord;
}
