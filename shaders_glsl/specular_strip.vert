#version 450
// Seed 003 (LETI lab 5) `specular_strip`, SPEC §3: vertex shader (verbatim; the loose uniforms
// form one block).
#include "specular_strip_params.glsl"

layout(location = 0) in vec3 objectPosition;
layout(location = 1) in vec3 objectColor;
layout(location = 2) in vec3 normal;

layout(location = 0) out vec3 Color;
layout(location = 1) out vec3 FragPos;
layout(location = 2) out vec3 Normal;

void main()
{
    vec4 objectPos = vec4(objectPosition, 1.0);
    mat4 modelViewMatrix = viewMatrix * modelMatrix;
    gl_Position = projectionMatrix * modelViewMatrix * objectPos;
    Color = objectColor;
    FragPos = vec3(modelMatrix * objectPos);
    Normal = mat3(transpose(inverse(modelMatrix))) * normal;
}
