#version 450
// Seed 002 `double_vision`: two texture reads averaged (verbatim). The course's
// `uniform sampler2D texture;` is renamed `tex`: `texture` is a built-in function from
// GLSL 1.30 on (SPEC §6.2 #3).

layout(set = 0, binding = 0) uniform texture2D tex;
layout(set = 0, binding = 1) uniform sampler tex_sampler;
layout(set = 0, binding = 2) uniform DoubleVision {
    vec2 left_separation;   // course: (0.1, 0)
    vec2 right_separation;  // course: (-0.1, 0)
};

layout(location = 0) in vec2 tex_coord0;  // gl_TexCoord[0].st
layout(location = 0) out vec4 frag_color;

void main()
{
    vec2 left_tex_coord = tex_coord0 + left_separation;
    vec2 right_tex_coord = tex_coord0 + right_separation;
    vec4 left_color = texture(sampler2D(tex, tex_sampler), left_tex_coord);
    vec4 right_color = texture(sampler2D(tex, tex_sampler), right_tex_coord);
    frag_color = (left_color + right_color) * 0.5;
}
