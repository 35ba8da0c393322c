// Seed 003 `specular_strip`: the program's uniforms as one block (shared by both stages).
layout(set = 0, binding = 0) uniform Strip {
    mat4 projectionMatrix;  // camera projection, depth mapped to wgpu's 0..1
    mat4 viewMatrix;        // camera view
    mat4 modelMatrix;       // identity
    vec3 lightPos;          // (0, 0, 0) (course)
    vec3 viewPos;           // camera position
};
