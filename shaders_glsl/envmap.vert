#version 450
// Seed 001 `envmap`: vertex shader (SPEC §1.10, pinned after the course's advice: compute in
// world coordinates with the model matrix passed as a uniform).
#include "transform.glsl"

layout(set = 0, binding = 1) uniform EnvMap {
    mat4 modelMatrix;  // Rx(xangle)*Ry(yangle), read back from the GL matrix stack
    vec3 eyeWorld;     // (0,0,4)
};

layout(location = 0) out vec3 R;

void main()
{
    vec4 vertex = vec4(vertex_position, 1.0);  // gl_Vertex
    gl_Position = mvp * vertex;
    vec3 P = (modelMatrix * vertex).xyz;
    vec3 N = normalize((modelMatrix * vec4(vertex_normal, 0.0)).xyz);
    R = reflect(P - eyeWorld, N);
}
