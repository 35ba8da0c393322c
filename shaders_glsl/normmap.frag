#version 450
// Seed 001 `normmap`: the bump shader with a normalization cube map (SPEC §1.12, pinned): the
// lecture's idea, "store the normalized value of the vector in a cube map; a lookup replaces
// sqrt, mults and adds", applied to the light direction.
#include "gl_light.glsl"

// uniform sampler2D texMap; on texture unit 0: the normal map and unit 0's sampler state.
layout(set = 0, binding = 2) uniform texture2D texMap;
layout(set = 0, binding = 3) uniform sampler texMapSampler;
// uniform samplerCube normMap; on texture unit 1: the normalization cube map.
layout(set = 0, binding = 4) uniform textureCube normMap;
layout(set = 0, binding = 5) uniform sampler normMapSampler;

layout(location = 0) in vec3 L;
layout(location = 1) in vec3 V;          // computed and unused, kept from the original
layout(location = 2) in vec4 TexCoord0;  // gl_TexCoord[0]
layout(location = 0) out vec4 frag_color;  // gl_FragColor

void main()
{
    vec4 N = texture(sampler2D(texMap, texMapSampler), TexCoord0.st);
    vec3 NN = normalize(2.0 * N.xyz - 1.0);
    vec3 LL = 2.0 * texture(samplerCube(normMap, normMapSampler), L).xyz - 1.0;  // instead of normalize(L)
    float Kd = max(dot(NN, LL), 0.0);
    frag_color = Kd * FrontLightProduct[0].diffuse;
}
