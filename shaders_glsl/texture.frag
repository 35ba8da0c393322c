#version 450
// Seed 001 `texture`: the course's sampler snippet made whole (SPEC §1.9): `myTexture` (the
// course samples `mytexture`, a typo) at gl_TexCoord[0].st.

// uniform sampler2D myTexture; on texture unit 0: the texture and unit 0's sampler state.
layout(set = 0, binding = 1) uniform texture2D myTexture;
layout(set = 0, binding = 2) uniform sampler myTextureSampler;

layout(location = 0) in vec4 TexCoord0;  // gl_TexCoord[0]
layout(location = 0) out vec4 frag_color;  // gl_FragColor

void main()
{
    vec2 texcoord = TexCoord0.st;
    vec4 texcolor = texture(sampler2D(myTexture, myTextureSampler), texcoord);
    frag_color = texcolor;
}
