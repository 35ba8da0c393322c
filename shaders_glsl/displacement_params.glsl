// Shared snippet: the displacement exercise's uniforms.
layout(set = 0, binding = 1) uniform DisplacementParams {
    vec3 shade;          // colour of the noise
    float time;          // seconds
    float displacement;  // strength, clamped to [0, 1] by the shader
};
