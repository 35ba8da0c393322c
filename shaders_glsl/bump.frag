#version 450
// Seed 001 `bump`: tangent-space diffuse bump mapping, fragment shader (SPEC §1.11, pinned):
// the normal comes from the normal map, the light direction is normalized per fragment.
#include "gl_light.glsl"

// uniform sampler2D texMap; on texture unit 0: the normal map and unit 0's sampler state.
layout(set = 0, binding = 2) uniform texture2D texMap;
layout(set = 0, binding = 3) uniform sampler texMapSampler;

layout(location = 0) in vec3 L;
layout(location = 1) in vec3 V;          // computed and unused, kept from the original
layout(location = 2) in vec4 TexCoord0;  // gl_TexCoord[0]
layout(location = 0) out vec4 frag_color;  // gl_FragColor

void main()
{
    vec4 N = texture(sampler2D(texMap, texMapSampler), TexCoord0.st);
    vec3 NN = normalize(2.0 * N.xyz - 1.0);
    vec3 LL = normalize(L);
    float Kd = max(dot(NN, LL), 0.0);
    frag_color = Kd * FrontLightProduct[0].diffuse;
}
