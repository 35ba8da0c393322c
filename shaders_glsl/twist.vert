#version 450
// Seed 002 (Lecture 12) `twist`: 2D twisting, SPEC §2.1 (verbatim but for GLSL 450 I/O).
// No matrices: the vertex shader writes clip coordinates directly.
#include "twist_params.glsl"

layout(location = 0) in vec2 vertex_position;  // gl_Vertex.xy (glVertex2f: z = 0, w = 1)

void main()
{
    vec4 vertex = vec4(vertex_position, 0.0, 1.0);  // gl_Vertex
    float angle = twisting * length(vertex.xy);
    float s = sin(angle);
    float c = cos(angle);
    gl_Position.x = c * vertex.x - s * vertex.y;
    gl_Position.y = s * vertex.x + c * vertex.y;
    gl_Position.z = 0.0;
    gl_Position.w = 1.0;
}
