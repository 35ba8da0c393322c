#version 450
// Seed 001 `uniform_arrays`: fragment shader (SPEC §1.2, pinned): the course's uniform values
// (specIntensity, specColor, t[2], colors[3]) as a banded "toon" shading.
#include "gl_light.glsl"

// The course's loose uniforms as one std140 block. `uniform float t[2]` becomes `vec4 t[2]`,
// read as t[k].x: std140 gives every element of a float array its own 16-byte slot, which is
// exactly what vec4 t[2] lays out. naga accepts `float t[2]` (with stride 16) but its WGSL
// output cannot express that stride, so the block declares the std140 layout as it is.
layout(set = 0, binding = 2) uniform UniformArrays {
    float specIntensity;
    vec4 specColor;
    vec4 t[2];       // float t[2]: the thresholds in .x
    vec4 colors[3];
};

layout(location = 0) in vec3 N;
layout(location = 1) in vec3 P;
layout(location = 0) out vec4 frag_color;  // gl_FragColor

void main()
{
    vec3 L = normalize(LightSource[0].position.xyz - P);
    float intensity = dot(L, normalize(N));
    if (intensity > specIntensity) frag_color = specColor;
    else if (intensity > t[0].x) frag_color = colors[0];
    else if (intensity > t[1].x) frag_color = colors[1];
    else frag_color = colors[2];
}
