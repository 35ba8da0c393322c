#version 450
// Exercise 3, PHONG SHADING: fragment shader for one light.
#include "phong_params.glsl"
#include "safe_math.glsl"

layout(location = 0) in vec3 N;
layout(location = 1) in vec3 v;
layout(location = 0) out vec4 frag_color;

void main() {
    // The course's lines, with normalize and pow made total (identical wherever the original
    // is defined; finite where it would give NaN, e.g. shininess 0 or a light on the surface).
    vec3 L = safe_normalize(lightPosition.xyz - v);  // direction to the light
    vec3 E = safe_normalize(-v);                     // direction to the eye
    vec3 R = safe_normalize(-reflect(L, N));         // reflection vector
    vec4 Iamb = vec4(ambientColor, 1.0);
    vec4 Idiff = vec4(diffuseColor * max(dot(N, L), 0.0), 1.0);
    // The course writes vec4(specularColor * pow(...)), a vec4 built from a vec3, which strict
    // compilers (Mesa, naga) reject; the reference images use vec4(..., 1.0), and so do we.
    vec4 Ispec = vec4(specularColor * safe_pow(max(dot(R, E), 0.0), shininess), 1.0);
    frag_color = clamp(Ka * Iamb + Kd * Idiff + Ks * Ispec, 0.0, 1.0);
}
