#version 450
// Seed 002 (Lecture 12) `double_vision`, SPEC §2.2. The slide sets no matrices, so
// ftransform() multiplies by identity projection and modelview: the triangle is given in clip
// space and passed through.

layout(location = 0) in vec2 vertex_position;  // gl_Vertex.xy
layout(location = 1) in vec2 vertex_st;        // gl_MultiTexCoord0.st

layout(location = 0) out vec2 tex_coord0;      // gl_TexCoord[0].st

void main()
{
    gl_Position = vec4(vertex_position, 0.0, 1.0);  // ftransform() with identity matrices
    tex_coord0 = vertex_st;                          // gl_TexCoord[0] = gl_MultiTexCoord0
}
