// Shared snippet: the noise exercise's uniforms.
layout(set = 0, binding = 1) uniform NoiseParams {
    vec3 shade;  // colour of the noise
    float time;  // seconds
};
