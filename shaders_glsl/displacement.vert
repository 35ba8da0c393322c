#version 450
// Exercise 5, DISPLACEMENT SHADER: vertex shader.
#include "transform.glsl"
#include "displacement_params.glsl"
#include "noise.glsl"
#include "safe_math.glsl"

layout(location = 0) out float noise;  // value for the fragment shader

const float speed = 1.0;  // animation speed
const float scale = 2.0;  // noise scale

void main() {
    // safe_normalize: normalize(0) is undefined; no GLUT mesh has a vertex at the origin, but a user mesh may.
    noise = snoise(safe_normalize(vertex_position) * scale + (time * speed));
    vec3 pos = vertex_position + vertex_normal * noise * vec3(clamp(displacement, 0.0, 1.0));
    gl_Position = mvp * vec4(pos, 1.0);
}
