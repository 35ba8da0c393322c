#version 450
// Exercise 5, DISPLACEMENT SHADER: fragment shader.
#include "displacement_params.glsl"

layout(location = 0) in float noise;
layout(location = 0) out vec4 frag_color;

void main() {
    frag_color = vec4(shade * clamp(noise, 0.0, 1.0), 1.0);
}
