// Shared snippet: the fixed-function matrices of OpenGL 2.0 as one uniform block.
// Spliced into every lab's vertex shader by shaderlab's loader (naga has no #include).
layout(set = 0, binding = 0) uniform Transform {
    mat4 modelview;      // gl_ModelViewMatrix
    mat4 mvp;            // gl_ModelViewProjectionMatrix, depth mapped to wgpu's 0..1
    mat3 normal_matrix;  // gl_NormalMatrix: inverse transpose of modelview's upper 3x3
};

// gl_Vertex and gl_Normal, as glutSolid* passes them.
layout(location = 0) in vec3 vertex_position;
layout(location = 1) in vec3 vertex_normal;
