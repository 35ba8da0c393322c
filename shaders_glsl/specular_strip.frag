#version 450
// Seed 003 `specular_strip`: fragment shader (verbatim). Vertex 201's normal is (0, 0, 0)
// (SPEC §6.3 #2): normalize() of it is NaN, at that vertex only.
#include "specular_strip_params.glsl"

layout(location = 0) in vec3 Color;
layout(location = 1) in vec3 FragPos;
layout(location = 2) in vec3 Normal;

layout(location = 0) out vec4 color;

void main()
{
    vec3 lightColor = vec3(1.0f, 1.0f, 1.0f);
    float ambientStrength = 0.1f;
    vec3 ambient = ambientStrength * lightColor;
    vec3 norm = normalize(Normal);
    vec3 lightDir = normalize(lightPos - FragPos);
    float diff = max(dot(norm, lightDir), 0.0);
    vec3 diffuse = diff * lightColor;
    float specularStrength = 0.5f;
    vec3 viewDir = normalize(viewPos - FragPos);
    vec3 reflectDir = reflect(-lightDir, norm);
    float spec = pow(max(dot(viewDir, reflectDir), 0.0), 64);
    vec3 specular = specularStrength * spec * lightColor;
    vec3 result = (ambient + diffuse + specular) * Color;
    color = vec4(result, 1.0f);
}
