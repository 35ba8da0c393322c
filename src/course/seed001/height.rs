//! Seed 001 `height` (SPEC §1.1): a custom vertex attribute, `attribute float height`, coloured
//! `(s, 0.25, 1 − s)` with `s = (height + 2)/4`: a square, red at the top, blue at the bottom.
//!
//! The course feeds `height` two ways, and both are here as `mode`: 0 per-vertex calls
//! (`glBegin(GL_TRIANGLE_STRIP)`, `glVertexAttrib1f(loc, h)` before each `glVertex2f`), 1 client
//! arrays (`vertices[8]`, `heights[4]`, `glVertexPointer` + `glVertexAttribPointer`,
//! `glDrawArrays(GL_TRIANGLE_STRIP, 0, 4)`). They give the same image. Keys: `v` toggles the
//! mode; left drag rotates.

use glam::Vec3;

use crate::lab::{Key::C, KeyRow, Keys, Material, MaterialScene, Recipe, ShaderPair};
use crate::mesh::shapes::HeightVertex;
use crate::params::ParamSpec;
use crate::render::{GpuMesh, RenderState};

use crate::course::seed001::geometry::{ChosenGeometry, UstcCamera, ROTATION};
use crate::course::seed001::immediate::Immediate;

/// Seed 001, §1.1: no uniform block besides the Transform; `mode` picks the strip.
pub static RECIPE: Recipe = Recipe::new(
    super::info(
        lab_name!(),
        "ref001",
        "custom vertex attribute",
        Keys::rows(&[KeyRow::cycle(&[C('v')], "mode")], "left drag rotates"),
    ),
    &[
        &[ParamSpec::choice(
            "mode",
            &[0.0],
            &["immediate", "arrays"],
            "how height is fed: 0 glVertexAttrib1f per vertex, 1 attribute arrays (v)",
        )],
        ROTATION,
    ],
    |cx, p| {
        let geometry = ChosenGeometry {
            camera: UstcCamera::new(cx.gpu, cx.name, Vec3::new(0.0, 0.0, 4.0)),
            meshes: vec![
                GpuMesh::new(cx.gpu, "height.immediate", &immediate_strip(), None),
                GpuMesh::new(cx.gpu, "height.arrays", &array_strip(), None),
            ],
            choice: "mode",
        };
        MaterialScene::build(cx, p, geometry, &MATERIAL)
    },
);

static MATERIAL: Material = Material::new(&[ShaderPair::new("height.vert", "pass_color.frag")
    .state(RenderState::GL.topology(wgpu::PrimitiveTopology::TriangleStrip))]);

// glVertex2f's x, y and the `height` attribute (GL converts both to the shader's types).
crate::vertex_type!(HeightVertex, {
    position: "vertex_position" => Float32x2,
    height: "height" => Float32,
});

/// Mode 0, the course's first listing: `glBegin(GL_TRIANGLE_STRIP)`, then
/// `glVertexAttrib1f(loc, h); glVertex2f(x, y);` four times.
pub fn immediate_strip() -> Vec<HeightVertex> {
    let mut strip = Immediate::begin(HeightVertex {
        position: [0.0; 2],
        height: 0.0, // glVertexAttrib's default x
    });
    for (h, x, y) in [(2.0, -1.0, 1.0), (2.0, 1.0, 1.0), (-2.0, -1.0, -1.0), (-2.0, 1.0, -1.0)] {
        strip.attrib(|v| v.height = h);
        strip.vertex(|v| v.position = [x, y]);
    }
    strip.end()
}

/// Mode 1, the course's second listing: `float vertices[8] = {-1,1, 1,1, -1,-1, 1,-1};
/// float heights[4] = {2,2,-2,-2};` read as `glVertexPointer(2, GL_FLOAT, 0, vertices)` and
/// `glVertexAttribPointer(loc, 1, GL_FLOAT, 0, 0, heights)` (tightly packed arrays; the vertex
/// buffer holds them interleaved).
pub fn array_strip() -> Vec<HeightVertex> {
    let vertices: [f32; 8] = [-1.0, 1.0, 1.0, 1.0, -1.0, -1.0, 1.0, -1.0];
    let heights: [f32; 4] = [2.0, 2.0, -2.0, -2.0];
    vertices
        .chunks_exact(2)
        .zip(heights)
        .map(|(xy, height)| HeightVertex {
            position: [xy[0], xy[1]],
            height,
        })
        .collect()
}
