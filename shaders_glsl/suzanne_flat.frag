#version 450
// 4.7 flat (pinned): the Gouraud fragment shader with "flat in vec4 color;".
layout(location = 0) flat in vec4 color;
layout(location = 0) out vec4 fColor;
void main()
{
    fColor = color;
}
