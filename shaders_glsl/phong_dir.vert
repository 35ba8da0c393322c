#version 450
// Seed 002 (Lecture 12) `phong_dir`, SPEC §2.4: vertex shader. The view is folded into the
// projection, so `modelview` is the model (glRotated(rx, 1,0,0)) and positions and normals are
// in world space.
#include "transform.glsl"
#include "phong_dir_params.glsl"

layout(location = 0) out vec3 normal;
layout(location = 1) out vec3 position;

void main()
{
    vec4 vertex = vec4(vertex_position, 1.0);  // gl_Vertex
    vec4 clip_gl = mvp_gl * vertex;             // ftransform() as GL computes it (depth -w..w)
    gl_Position = mvp * vertex;                // the same point with wgpu's depth (0..w)
    normal = normal_matrix * vertex_normal;
    // Course bug (SPEC §6.2 #1), kept: the clip-space position times the modelview.
    // fixpos = 1 renders the intent, (gl_ModelViewMatrix * gl_Vertex).xyz.
    position = (modelview * (fixpos != 0 ? vertex : clip_gl)).xyz;
}
