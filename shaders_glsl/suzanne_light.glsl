// Seed 004's lighting uniforms (`uniform vec4 Ka, Kd, Ks; uniform float shininess;
// uniform vec3 lightpos;`) as one block (std140: lightpos and shininess share 16 bytes).
layout(set = 0, binding = 1) uniform Light {
    vec4 Ka;
    vec4 Kd;
    vec4 Ks;
    vec3 lightpos; // eye space
    float shininess;
};
