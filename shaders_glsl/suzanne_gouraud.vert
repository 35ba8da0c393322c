#version 450
// 4.8 Gouraud (the course's "..." body filled with its slides' formulas, SPEC 4.7): the
// lighting evaluated per vertex, the colour interpolated.
#include "suzanne_transform.glsl"
#include "suzanne_light.glsl"
layout(location = 0) in vec4 v_coord;
layout(location = 2) in vec3 v_normal;
layout(location = 0) out vec4 color;
void main()
{
    gl_Position = MVP*v_coord;
    vec3 P = vec3(MV * v_coord);
    vec3 N = normalize(NM * v_normal);
    vec3 L = normalize(lightpos - P);
    vec3 V = normalize(-P);
    vec3 R = reflect(-L, N);
    vec4 lightColor = vec4(1.0);
    float facing = dot(N, L) > 0.0 ? 1.0 : 0.0;
    vec4 amb = Ka * lightColor;
    vec4 diff = Kd * lightColor * max(dot(N, L), 0.0);
    vec4 spec = Ks * lightColor * facing * pow(max(dot(R, V), 0.0), shininess);
    color = amb + diff + spec;
    color = clamp(color, 0.0, 1.0);
}
