#version 450
// Exercise 3, PHONG SHADING: fragment shader for one light.
#include "phong_params.glsl"

layout(location = 0) in vec3 N;
layout(location = 1) in vec3 v;
layout(location = 0) out vec4 frag_color;

void main() {
    vec3 L = normalize(lightPosition.xyz - v);  // direction to the light
    vec3 E = normalize(-v);                     // direction to the eye
    vec3 R = normalize(-reflect(L, N));         // reflection vector
    vec4 Iamb = vec4(ambientColor, 1.0);
    vec4 Idiff = vec4(diffuseColor * max(dot(N, L), 0.0), 1.0);
    // The course writes vec4(specularColor * pow(...)), a vec4 built from a vec3, which strict
    // compilers (Mesa, naga) reject; the reference images use vec4(..., 1.0), and so do we.
    vec4 Ispec = vec4(specularColor * pow(max(dot(R, E), 0.0), shininess), 1.0);
    frag_color = Ka * Iamb + Kd * Idiff + Ks * Ispec;
}
