#version 450
// Exercise 3 with flat shading (per polygon): the normal is the triangle's own, rebuilt from the
// screen-space derivatives of the eye-space position, so every pixel of a triangle shares one
// normal; the Phong formula is otherwise unchanged. Uses phong.vert.
#include "phong_params.glsl"
#include "safe_math.glsl"

layout(location = 0) in vec3 N;
layout(location = 1) in vec3 v;
layout(location = 0) out vec4 frag_color;

void main() {
    // wgpu's framebuffer y points down, GL's up: this cross product faces the viewer for
    // front faces; pick the side that agrees with the interpolated normal so that the
    // teapot's clockwise triangles light the same way.
    vec3 face = safe_normalize(cross(dFdx(v), dFdy(v)));
    vec3 n = dot(face, N) < 0.0 ? -face : face;
    vec3 L = safe_normalize(lightPosition.xyz - v);
    vec3 E = safe_normalize(-v);
    vec3 R = safe_normalize(-reflect(L, n));
    vec4 Iamb = vec4(ambientColor, 1.0);
    vec4 Idiff = vec4(diffuseColor * max(dot(n, L), 0.0), 1.0);
    vec4 Ispec = vec4(specularColor * safe_pow(max(dot(R, E), 0.0), shininess), 1.0);
    frag_color = clamp(Ka * Iamb + Kd * Idiff + Ks * Ispec, 0.0, 1.0);
}
