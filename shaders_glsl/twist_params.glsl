// Seed 002 `twist`: the course's two uniforms as one block (shared by both stages).
layout(set = 0, binding = 0) uniform Twist {
    vec3 color;       // uniform vec3 color (course: (0.5, 9.0, 0.5); 9.0 clamps to 1)
    float twisting;   // uniform float twisting (course: 4.25)
};
