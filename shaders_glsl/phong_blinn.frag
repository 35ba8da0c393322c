#version 450
// Exercise 3 with the Blinn-Phong specular term (seed 001, "modified Phong"): the halfway vector
// H = normalize(L + E) replaces the reflection vector, and there is no specular light where the
// surface faces away from the light (f = 0 when N·L < 0). Per pixel, with phong.vert.
#include "phong_params.glsl"
#include "safe_math.glsl"

layout(location = 0) in vec3 N;
layout(location = 1) in vec3 v;
layout(location = 0) out vec4 frag_color;

void main() {
    vec3 L = safe_normalize(lightPosition.xyz - v);
    vec3 E = safe_normalize(-v);
    vec3 H = safe_normalize(L + E);
    float NdotL = dot(N, L);
    float f = NdotL > 0.0 ? 1.0 : 0.0;
    vec4 Iamb = vec4(ambientColor, 1.0);
    vec4 Idiff = vec4(diffuseColor * max(NdotL, 0.0), 1.0);
    vec4 Ispec = vec4(specularColor * f * safe_pow(max(dot(N, H), 0.0), shininess), 1.0);
    frag_color = clamp(Ka * Iamb + Kd * Idiff + Ks * Ispec, 0.0, 1.0);
}
