#version 450
// Seed 001 `phong_vertex`: the course's modified Phong (Blinn) vertex shader, without distance
// term (SPEC §1.7, verbatim but for the GLSL 450 names of GL's built-ins).
#include "transform.glsl"
#include "gl_light.glsl"

layout(location = 0) out vec4 color;  // gl_FrontColor

void main(void)
/*modified Phong vertex shader (without distance term)*/
{
    vec4 vertex = vec4(vertex_position, 1.0);  // gl_Vertex
    gl_Position = mvp * vertex;
    vec4 ambient, diffuse, specular;
    vec4 eyePosition = modelview * vertex;
    vec4 eyeLightPos = LightSource[0].position;
    vec3 N = normalize(normal_matrix * vertex_normal);
    vec3 L = normalize(eyeLightPos.xyz - eyePosition.xyz);
    vec3 E = -normalize(eyePosition.xyz);
    vec3 H = normalize(L + E);
    /*compute diffuse, ambient, and specular contributions*/
    float f = 1.0;
    float Kd = max(dot(L, N), 0.0);
    float Ks = pow(max(dot(N, H), 0.0), FrontMaterial.shininess);
    if (dot(L,N) < 0.0) f = 0.0;
    ambient = FrontLightProduct[0].ambient;
    diffuse = Kd*FrontLightProduct[0].diffuse;
    specular = f*Ks*FrontLightProduct[0].specular;
    // GL clamps gl_FrontColor to [0, 1] before interpolating it (GL_CLAMP_VERTEX_COLOR): a
    // highlight brighter than white stays white between vertices.
    color = clamp(ambient + diffuse + specular, 0.0, 1.0);
}
