#version 450
// Seed 001 `texture`: vertex shader (SPEC §1.9, pinned: the course shows only the sampler).
#include "transform_block.glsl"

layout(location = 0) in vec3 vertex_position;  // gl_Vertex
layout(location = 1) in vec2 vertex_texcoord;  // gl_MultiTexCoord0 = (s, t, 0, 1)
layout(location = 0) out vec4 TexCoord0;       // gl_TexCoord[0]

void main()
{
    TexCoord0 = vec4(vertex_texcoord, 0.0, 1.0);
    gl_Position = mvp * vec4(vertex_position, 1.0);
}
