#version 450
// Exercise 3 with Gouraud shading (per vertex): the Phong formula evaluated at each vertex and
// the colour interpolated across the triangle, as fixed-function GL lighting does.
#include "transform.glsl"
#include "phong_params.glsl"
#include "safe_math.glsl"

layout(location = 0) out vec4 color;

void main() {
    vec4 vertex = vec4(vertex_position, 1.0);
    vec3 v = vec3(modelview * vertex);
    vec3 N = safe_normalize(normal_matrix * vertex_normal);
    vec3 L = safe_normalize(lightPosition.xyz - v);
    vec3 E = safe_normalize(-v);
    vec3 R = safe_normalize(-reflect(L, N));
    vec4 Iamb = vec4(ambientColor, 1.0);
    vec4 Idiff = vec4(diffuseColor * max(dot(N, L), 0.0), 1.0);
    vec4 Ispec = vec4(specularColor * safe_pow(max(dot(R, E), 0.0), shininess), 1.0);
    color = clamp(Ka * Iamb + Kd * Idiff + Ks * Ispec, 0.0, 1.0);
    gl_Position = mvp * vertex;
}
