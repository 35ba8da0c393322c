#version 450
// Seed 002 `normal_world`: the normal as colour (verbatim).

layout(location = 0) in vec3 normal;
layout(location = 0) out vec4 frag_color;

void main()
{
    vec3 n = normalize(normal);
    vec3 color = (n + vec3(1.0, 1.0, 1.0)) * 0.5;
    frag_color = vec4(color, 1);
}
