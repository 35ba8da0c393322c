#version 450
// Exercise 4, SIMPLEX NOISE SHADER: fragment shader.
#include "noise_params.glsl"
#include "noise.glsl"

layout(location = 0) in vec3 position;
layout(location = 0) out vec4 frag_color;

const float speed = 1.0;

void main() {
    vec3 v = position + time * speed;
    frag_color = vec4(shade, 1.0) * vec4(abs(vec3(snoise(v))), 1.0);
}
