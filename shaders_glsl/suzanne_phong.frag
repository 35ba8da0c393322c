#version 450
// 4.9 Phong (course structure, SPEC 4.7 body).
#include "suzanne_light.glsl"
layout(location = 0) in vec3 P;
layout(location = 1) in vec3 N;
// The course also declares `uniform sampler2D tex;` here, which nothing reads (SPEC 6.4 #2);
// an unused texture would still need a binding in wgpu, so the port leaves it out.
layout(location = 0) out vec4 fColor;
void main()
{
    vec3 n = normalize(N);               // renormalize the interpolated normal
    vec3 L = normalize(lightpos - P);
    vec3 V = normalize(-P);
    vec3 R = reflect(-L, n);
    vec4 lightColor = vec4(1.0);
    float facing = dot(n, L) > 0.0 ? 1.0 : 0.0;
    vec4 amb = Ka * lightColor;
    vec4 diff = Kd * lightColor * max(dot(n, L), 0.0);
    vec4 spec = Ks * lightColor * facing * pow(max(dot(R, V), 0.0), shininess);
    fColor = amb + diff + spec;
    fColor = clamp(fColor, 0.0, 1.0);
}
