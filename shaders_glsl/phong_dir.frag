#version 450
// Seed 002 `phong_dir`: Phong with a directional light and emission (verbatim).
#include "phong_dir_params.glsl"

layout(location = 0) in vec3 normal;
layout(location = 1) in vec3 position;
layout(location = 0) out vec4 frag_color;

void main()
{
    vec3 l = normalize(light_direction);
    vec3 color = material_emission;
    color += light_ambient * material_ambient;
    vec3 n = normalize(normal);
    float cos_theta = max(dot(n, l), 0.0);
    color += light_intensity * material_diffuse * cos_theta;
    vec3 r = n * 2.0 * dot(n, l) - l;
    vec3 v = normalize(eye - position);
    float cos_alpha = dot(r, v);
    if (cos_theta > 0.0 && cos_alpha > 0.0)
        color += light_intensity * material_specular * pow(cos_alpha, material_shininess);
    frag_color = vec4(color, 1);
}
