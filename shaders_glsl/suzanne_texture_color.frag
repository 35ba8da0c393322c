#version 450
// 4.5 (course): the texture modulated by the normal colour of the vertex shader.
layout(location = 0) in vec4 color; // abs(N) from the vertex shader
layout(location = 1) in vec2 texcoord; // the interpolated UV coordinates
layout(set = 0, binding = 1) uniform texture2D tex; // the currently bound texture
layout(set = 0, binding = 2) uniform sampler tex_sampler; // its wrap and filter parameters
layout(location = 0) out vec4 fColor; // final fragment color
void main()
{
    fColor = texture(sampler2D(tex, tex_sampler), texcoord) * color;
}
