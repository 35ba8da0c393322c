//! Seed 002 (Lecture 12, P. Khungurn) `twist`, SPEC §2.1: 2D twisting. The course's 100×100
//! `GL_QUADS` grid over [−0.5, 0.5]² ([`twist_grid`], float loop) is given in clip space — no
//! matrices, no camera — and the vertex shader turns each vertex by
//! `twisting · length(gl_Vertex.xy)` radians. Depth test off (2D, nothing overlaps).
//!
//! Course quirk kept (SPEC §6.2 #4): `color` = (0.5, 9.0, 0.5); the 9.0 clamps to 1 in the
//! UNORM framebuffer, so the shape is (128, 255, 128).
//!
//! Keys: `+`/`-` twisting ±0.25.

use crate::geometry::shapes::twist_grid;
use crate::lab::{Flat, Key::C, KeyRow, Keys, Look, Pass, Recipe, Shaded};
use crate::params::ParamSpec;
use crate::render::{GpuMesh, RenderState};

/// One vertex of the grid: `glVertex2f(x, y)`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct TwistVertex {
    /// Clip-space x, y.
    pub position: [f32; 2],
}
crate::vertex_type!(TwistVertex, { position: "vertex_position" => Float32x2 });

/// `twist`: the `Twist` block's `twisting` and `color` are its parameters.
pub static RECIPE: Recipe = Recipe {
    info: super::info(
        "twist",
        "ref002",
        "2D twisting",
        Keys::rows(&[KeyRow::step(&[C('-'), C('+')], "twisting", 0.25)], ""),
    ),
    params: &[&[
        ParamSpec::real(
            "twisting",
            &[4.25],
            -1000.0,
            1000.0,
            "radians of turn per unit of radius (+/-)",
        ),
        ParamSpec::real(
            "color",
            &[0.5, 9.0, 0.5],
            -100.0,
            100.0,
            "uniform colour (course: 9.0 clamps to 1 in the framebuffer)",
        ),
    ]],
    animated: false,
    title: None,
    build: |cx, p| {
        let grid: Vec<TwistVertex> = twist_grid()
            .into_iter()
            .map(|position| TwistVertex { position })
            .collect();
        let stage = Flat(GpuMesh::new(cx.gpu, "twist.grid", &grid, None));
        Shaded::build(cx, "twist", p, stage, &LOOK, Vec::new())
    },
};

static LOOK: Look = Look::new(&[Pass::new("twist.vert", "twist.frag").state(RenderState::GL.no_depth())]);
