#version 450
// Seed 001 `envmap`: the course's reflection-map fragment shader (SPEC §1.10, verbatim but for
// the GLSL 450 sampler declaration).

// uniform samplerCube texMap; on texture unit 0: the cube map and unit 0's sampler state.
layout(set = 0, binding = 2) uniform textureCube texMap;
layout(set = 0, binding = 3) uniform sampler texMapSampler;

layout(location = 0) in vec3 R;
layout(location = 0) out vec4 frag_color;  // gl_FragColor

void main(void)
{
    frag_color = texture(samplerCube(texMap, texMapSampler), R);  // textureCube(texMap, R)
}
