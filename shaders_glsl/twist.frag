#version 450
// Seed 002 `twist`: fragment shader (verbatim; gl_FragColor becomes an output).
#include "twist_params.glsl"

layout(location = 0) out vec4 frag_color;

void main()
{
    frag_color = vec4(color, 1);
}
