//! Seed 002 (Lecture 12, P. Khungurn) `twist`, SPEC §2.1: 2D twisting. The course's 100×100
//! `GL_QUADS` grid over [−0.5, 0.5]² (`twist_grid`, float loop) is given in clip space — no
//! matrices, no camera — and the vertex shader turns each vertex by
//! `twisting · length(gl_Vertex.xy)` radians. Depth test off (2D, nothing overlaps).
//!
//! Course quirk kept (SPEC §6.2 #4): `color` = (0.5, 9.0, 0.5); the 9.0 clamps to 1 in the
//! UNORM framebuffer, so the shape is (128, 255, 128).
//!
//! Port addition (opt-in, SPEC keeps 100): `grid` sets the quads per side, and `grid=auto`
//! picks the coarsest grid whose every edge stays within half a pixel of the spiral arc it
//! stands for, for the current `twisting` and picture size
//! ([`crate::mesh::twist::auto_grid`]).
//!
//! Keys: `+`/`-` twisting ±0.25.

use std::collections::HashMap;

use crate::gpu::Gpu;
use crate::lab::{Geometry, Key::C, KeyRow, Keys, Material, MaterialScene, Recipe, ShaderPair};
use crate::mesh::shapes::{indexed_quads, twist_grid_n};
use crate::mesh::twist::{auto_grid, grid_error_px, COURSE_GRID, DEFAULT_BUDGET_PX, MAX_GRID};
use crate::params::{ParamSpec, Params};
use crate::render::{note_once, GpuMesh, RenderState};

/// One vertex of the grid: `glVertex2f(x, y)`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct TwistVertex {
    /// Clip-space x, y.
    pub position: [f32; 2],
}
crate::vertex_type!(TwistVertex, { position: "vertex_position" => Float32x2 });

/// `twist`: the `Twist` block's `twisting` and `color` are its parameters.
pub static RECIPE: Recipe = Recipe::new(
    super::info(
        lab_name!(),
        "ref002",
        "2D twisting",
        Keys::rows(&[KeyRow::step(&[C('-'), C('+')], "twisting", 0.25)], ""),
    ),
    &[&[
        ParamSpec::real(
            "twisting",
            &[4.25],
            -1e4,
            1e4,
            "radians of turn per unit of radius (+/-)",
        ),
        ParamSpec::real(
            "color",
            &[0.5, 9.0, 0.5],
            -100.0,
            100.0,
            "uniform colour (course: 9.0 clamps to 1 in the framebuffer)",
        ),
        ParamSpec::int(
            "grid",
            &[COURSE_GRID as f64],
            0.0,
            MAX_GRID as f64,
            "port: quads per side (course: 100); auto (0): the coarsest whose edges stay within half a pixel of the exact spiral",
        )
        .with_auto(0.0),
    ]],
    |cx, p| {
        let mut geometry = Grid::default();
        geometry.mesh(cx.gpu, COURSE_GRID);
        MaterialScene::build(cx, p, geometry, &MATERIAL)
    },
);

/// The grid, built for each size asked for (the course's first) and kept.
#[derive(Default)]
struct Grid {
    meshes: HashMap<u32, GpuMesh<TwistVertex>>,
    /// `auto`'s last choice: (twisting, width, height) → quads per side.
    auto: Option<((f64, u32, u32), u32)>,
    /// The grid drawn last.
    drawn: u32,
}

impl Grid {
    fn mesh(&mut self, gpu: &Gpu, n: u32) -> &GpuMesh<TwistVertex> {
        self.meshes.entry(n).or_insert_with(|| {
            let grid: Vec<TwistVertex> = twist_grid_n(n)
                .into_iter()
                .map(|position| TwistVertex { position })
                .collect();
            // Indexed: each distinct corner is turned once instead of six times. A corner is
            // shared between quads only where its bits agree: the course computes a quad's far
            // corner as x + size, which in float is not always its neighbour's near corner
            // (100x100: 26,244 corners of 40,000; 60,000 before indexing).
            let (corners, indices) = indexed_quads(&grid);
            GpuMesh::new(gpu, "twist.grid", &corners, Some(&indices))
        })
    }

    /// The grid for the state: `grid`, or for `auto` the coarsest within budget (chosen again
    /// only when `twisting` or the size changes).
    fn size(&mut self, p: &Params, width: u32, height: u32) -> u32 {
        match p.f64("grid") as u32 {
            0 => {
                let key = (p.f64("twisting"), width, height);
                match self.auto {
                    Some((k, n)) if k == key => n,
                    _ => {
                        let n = auto_grid(key.0, width, height, DEFAULT_BUDGET_PX);
                        self.auto = Some((key, n));
                        if grid_error_px(n, key.0, width, height) > DEFAULT_BUDGET_PX {
                            note_once(format!(
                                "twist: grid=auto: twisting {} needs more than {MAX_GRID} quads a side (the most auto draws) \
                                 to keep the spiral's outline within half a pixel; drawing {n}",
                                key.0
                            ));
                        }
                        n
                    }
                }
            }
            n => n,
        }
    }
}

impl Geometry for Grid {
    type Vertex = TwistVertex;
    fn prepare(&mut self, gpu: &Gpu, p: &Params, width: u32, height: u32) -> &GpuMesh<TwistVertex> {
        let n = self.size(p, width, height);
        // Keep the course's grid and the one in use.
        if !self.meshes.contains_key(&n) {
            self.meshes.retain(|&k, _| k == COURSE_GRID || k == self.drawn);
        }
        self.drawn = n;
        self.mesh(gpu, n)
    }
    fn title(&self, info: &crate::lab::LabInfo, p: &Params) -> String {
        crate::lab::params_title(info, p)
            + &{
                if p.f64("grid") == 0.0 {
                    format!(" | grid auto: {}", self.drawn)
                } else {
                    String::new()
                }
            }
    }
}

static MATERIAL: Material =
    Material::new(&[ShaderPair::new("twist.vert", "twist.frag").state(RenderState::GL.no_depth())]);
