// Shared snippet: the Phong exercise's uniforms (glslSetUniform* in the original).
// A vec3 followed by a float packs into 16 bytes under std140.
layout(set = 0, binding = 1) uniform PhongParams {
    vec3 lightPosition;  // eye space
    float Ka;
    vec3 ambientColor;
    float Kd;
    vec3 diffuseColor;
    float Ks;
    vec3 specularColor;
    float shininess;
};
