#version 450
// The Phong exercise's light marker: glutSolidSphere(0.05, 4, 4) drawn without a shader.
#include "transform.glsl"

void main() {
    gl_Position = mvp * vec4(vertex_position, 1.0);
}
