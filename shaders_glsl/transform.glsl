// Shared snippet: the fixed-function matrices of OpenGL 2.0 as one uniform block, and the
// vertex inputs glutSolid* feeds. Spliced into a lab's vertex shader by shaderlab's loader.
#include "transform_block.glsl"

// gl_Vertex and gl_Normal, as glutSolid* passes them.
layout(location = 0) in vec3 vertex_position;
layout(location = 1) in vec3 vertex_normal;
