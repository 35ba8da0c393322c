// Shared snippet: the fixed-function matrices of OpenGL 2.0 as one uniform block, for vertex
// shaders that declare their own inputs (transform.glsl adds GLUT's position and normal).
layout(set = 0, binding = 0) uniform Transform {
    mat4 modelview;      // gl_ModelViewMatrix
    mat4 mvp;            // gl_ModelViewProjectionMatrix, depth mapped to wgpu's 0..1
    mat3 normal_matrix;  // gl_NormalMatrix: inverse transpose of modelview's upper 3x3
};
