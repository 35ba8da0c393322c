//! Seed 001 `morph` (SPEC §1.4): the course's morphing vertex shader blends each vertex of a
//! 16-gon (`gl_Vertex`) with its partner on an 8-pointed star (`attribute vec4 vertices2`) by
//! `s = 0.5·(1 + sin(0.001·time))`, `time` in milliseconds as the course's
//! `glutGet(GLUT_ELAPSED_TIME)` (the `time` parameter is in seconds; the shader gets ×1000).
//! s = 0 is the circle (time 4.712389 s), s = 1 the star (time 1.570796 s).
//!
//! The course's draw loop is kept: `glBegin(GL_TRIANGLES)`, then for each of its N = 50
//! vertices `glVertexAttrib3fv(vertices2, two[i]); glVertex3fv(one[i]);` — 16 triangles, the last
//! 2 vertices dropped by GL. The attribute is looked up as an attribute (the course's
//! `glGetUniformLocation` would leave it (0,0,0,1) and nothing would morph, §6.1). White: the
//! course sets no colour.
//!
//! Keys: Space pauses the clock; left drag rotates.

use std::f64::consts::TAU;

use glam::Vec3;

use crate::lab::{Keys, Material, MaterialScene, Recipe, ShaderPair};
use crate::mesh::shapes::{morph_vertices, MorphVertex};
use crate::params::{ParamSpec, Params};
use crate::render::{Derived, GpuMesh};

use crate::course::seed001::geometry::{MeshGeometry, UstcCamera, ROTATION};
use crate::course::seed001::immediate::Immediate;

/// Seed 001, §1.4: the `Morph` block's `time` is [`time_uniform`] of the clock.
pub static RECIPE: Recipe = Recipe::new(
    super::info(
        lab_name!(),
        "ref001",
        "morphing",
        Keys::text("Space pauses the clock; left drag rotates"),
    ),
    &[
        &[ParamSpec::real(
            "time",
            &[0.0],
            -1e9,
            1e9,
            "seconds (the shader gets milliseconds; a clock in a window, Space pauses)",
        )],
        ROTATION,
    ],
    |cx, p| {
        let geometry = MeshGeometry {
            camera: UstcCamera::new(cx.gpu, cx.name, Vec3::new(0.0, 0.0, 4.0)),
            mesh: GpuMesh::new(cx.gpu, "morph.triangles", &course_triangles()[..DRAWN], None),
        };
        MaterialScene::build(cx, p, geometry, &MATERIAL)
    },
)
.animated();

static MATERIAL: Material = Material::new(&[ShaderPair::new("morph.vert", "pass_color.frag")])
    .derive(|p: &Params, c: &mut Derived| c.set("time", &[time_uniform(p.f64("time"))]));

// gl_Vertex (vertices_one) and the vertices2 attribute (vertices_two).
crate::vertex_type!(MorphVertex, {
    one: "vertex_position" => Float32x3,
    two: "vertices2" => Float32x3,
});

/// Vertices GL draws of the course's 50: whole triangles only (the mesh holds those).
const DRAWN: usize = 48;

/// The `time` uniform: the state's seconds × 1000. The shader only uses `sin(0.001·time)`, so
/// the seconds are wrapped by 2π first (in double): the same value below 2π s, and a window left
/// running keeps full float precision.
pub fn time_uniform(seconds: f64) -> f32 {
    (seconds.rem_euclid(TAU) * 1000.0) as f32
}

/// The course's loop: `glBegin(GL_TRIANGLES)`, for i < N: `glVertexAttrib3fv(vertices2Param,
/// vertices_two[i]); glVertex3fv(vertices_one[i]);`, `glEnd()`.
pub fn course_triangles() -> Vec<MorphVertex> {
    let shapes = morph_vertices();
    let mut triangles = Immediate::begin(MorphVertex {
        one: [0.0; 3],
        two: [0.0; 3], // glVertexAttrib's default (0, 0, 0, 1)
    });
    for v in &shapes {
        triangles.attrib(|c| c.two = v.two);
        triangles.vertex(|c| c.one = v.one);
    }
    triangles.end()
}
