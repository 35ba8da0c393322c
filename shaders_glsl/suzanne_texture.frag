#version 450
// 4.4 (course): the texture at the interpolated UV; also 4.6 texparams. GL's
// `uniform sampler2D tex` (unit 0) is a texture plus a sampler holding its texture parameters.
layout(location = 0) in vec4 color; // ignored
layout(location = 1) in vec2 texcoord; // the interpolated UV coordinates
layout(set = 0, binding = 1) uniform texture2D tex; // the currently bound texture
layout(set = 0, binding = 2) uniform sampler tex_sampler; // its wrap and filter parameters
layout(location = 0) out vec4 fColor; // final fragment color
void main()
{
    fColor = texture(sampler2D(tex, tex_sampler), texcoord);
}
