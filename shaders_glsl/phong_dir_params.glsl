// Seed 002 `phong_dir`: the course's loose uniforms as one block, and the port's switch.
layout(set = 0, binding = 1) uniform PhongDir {
    vec3 material_ambient;
    float material_shininess;
    vec3 material_diffuse;
    int fixpos;                // port: 0 = the course's gl_Position bug, 1 = gl_Vertex
    vec3 material_specular;
    vec3 material_emission;
    vec3 light_ambient;
    vec3 light_intensity;
    vec3 light_direction;      // world space, toward the light
    vec3 eye;
    mat4 mvp_gl;               // gl_ModelViewProjectionMatrix in GL's depth convention (-w..w)
};
