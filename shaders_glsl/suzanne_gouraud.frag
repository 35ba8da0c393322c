#version 450
// 4.8 Gouraud (course, with the missing ';' after "out vec4 fColor" added).
layout(location = 0) in vec4 color;
layout(location = 0) out vec4 fColor;
void main()
{
    fColor = color;
}
