#version 450
// Seed 001 `phong_fragment`: the course's modified Phong (Blinn) fragment shader (SPEC §1.8,
// verbatim but for the GLSL 450 names of GL's built-ins).
#include "gl_light.glsl"

layout(location = 0) in vec3 N;
layout(location = 1) in vec3 L;
layout(location = 2) in vec3 E;
layout(location = 0) out vec4 frag_color;  // gl_FragColor

void main()
{
    vec3 Normal = normalize(N);
    vec3 Light  = normalize(L);
    vec3 Eye    = normalize(E);
    vec3 Half   = normalize(Eye + Light);
    float f = 1.0;
    float Kd = max(dot(Normal, Light), 0.0);
    float Ks = pow(max(dot(Half, Normal), 0.0), FrontMaterial.shininess);
    vec4 diffuse = Kd * FrontLightProduct[0].diffuse;
    if (dot(Normal, Light) < 0.0) f = 0.0;
    vec4 specular = f * Ks * FrontLightProduct[0].specular;
    vec4 ambient = FrontLightProduct[0].ambient;
    frag_color = ambient + diffuse + specular;
}
