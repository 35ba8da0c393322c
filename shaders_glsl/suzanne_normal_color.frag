#version 450
// 4.1 "Hello Suzanne" (course, verbatim); also the fragment shader of 4.2 and 4.3.
layout(location = 0) in vec4 color;
layout(location = 1) in vec2 texcoord;
layout(location = 0) out vec4 fColor; // final fragment color
void main()
{
    fColor = color;
}
