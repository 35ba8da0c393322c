// Shared snippet (seed 001): GL 2.0's built-in light and material state as one uniform block,
// filled from the CPU by src/course/seed001/gl_light.rs. The names are GLSL's without the
// reserved `gl_` prefix: gl_LightSource[0] is LightSource[0], gl_FrontMaterial is FrontMaterial,
// gl_FrontLightProduct[0] is FrontLightProduct[0]. Only the members the course reads are kept.
struct LightSourceParameters {
    vec4 ambient;   // Acli
    vec4 diffuse;   // Dcli
    vec4 specular;  // Scli
    vec4 position;  // Ppli, eye space (set while the modelview is the identity)
};

struct MaterialParameters {
    vec4 emission;    // Ecm
    vec4 ambient;     // Acm
    vec4 diffuse;     // Dcm
    vec4 specular;    // Scm
    float shininess;  // Srm
};

struct LightProducts {
    vec4 ambient;   // Acm * Acli
    vec4 diffuse;   // Dcm * Dcli
    vec4 specular;  // Scm * Scli
};

layout(set = 0, binding = 1) uniform GlLight {
    LightSourceParameters LightSource[1];  // gl_LightSource[0]
    MaterialParameters FrontMaterial;      // gl_FrontMaterial
    LightProducts FrontLightProduct[1];    // gl_FrontLightProduct[0]
};
