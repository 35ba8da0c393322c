//! Seed 001 `wave` (SPEC §1.3): the course's wave-motion vertex shader lifts a flat checkered
//! 40×40 grid by `h·sin(time + xs·x) + h·sin(time + zs·z)`; the crests travel with time (in
//! seconds: the course's idle callback sends milliseconds, which would flicker, §6.1). Seen
//! from (0, 3.5, 6.5).
//!
//! Port addition (opt-in; SPEC's grid is `subdiv=1`): `subdiv` splits each checker cell into
//! k × k quads of its colour, and `subdiv=auto` picks the smallest k whose flat triangles stay
//! within half a pixel of the sine surface for the current `h`, `xs`, `zs` ([`auto_subdiv`]).
//!
//! Keys: Space pauses the clock; `h`/`H` h ∓0.02; `x`/`X` xs ∓0.5; `z`/`Z` zs ∓0.5; left drag
//! rotates.

use std::collections::HashMap;
use std::f64::consts::TAU;

use glam::Vec3;

use crate::gpu::Gpu;
use crate::lab::{Geometry, Input, Key::C, KeyRow, Keys, Material, MaterialScene, Recipe, ShaderPair};
use crate::mesh::shapes::{indexed_quads, wave_grid_sub, ColorVertex};
use crate::params::{ParamSpec, Params};
use crate::render::{note_once, Bind, Derived, GpuMesh, LARGE_MESH_TRIANGLES};

use crate::course::seed001::geometry::{UstcCamera, ROTATION};

/// The finest `subdiv` (each cell 32 × 32 quads: 9.8 million vertices).
pub const MAX_SUBDIV: u32 = 32;

/// The error `subdiv=auto` allows, in pixels.
pub const SUBDIV_BUDGET_PX: f64 = 0.5;

/// How far the flat triangles of cells split `k` × `k` stray from the surface
/// `h·sin(t + xs·x) + h·sin(t + zs·z)` at most, in world units: linear interpolation over a
/// triangle of legs d = 0.1/k errs by at most d²/2 · max|∂²y/∂x²| + … ≤ d²/2 · |h|·(xs² + zs²)
/// (the bound on the interpolation error of a C² function over a right triangle; the sagitta
/// of one edge is a quarter of it).
pub fn subdiv_error(k: u32, h: f64, xs: f64, zs: f64) -> f64 {
    let d = 0.1 / f64::from(k.max(1));
    0.5 * d * d * h.abs() * (xs * xs + zs * zs)
}

/// Pixels per world unit at the nearest the grid can come to the eye (its corners at
/// √8 from the centre, lifted by at most 2|h|), in a picture `height` pixels tall seen through
/// seed 001's 45° field of view.
fn pixels_per_unit(eye: Vec3, h: f64, height: u32) -> f64 {
    let nearest = (f64::from(eye.length()) - 8f64.sqrt() - 2.0 * h.abs()).max(0.1);
    f64::from(height) / (2.0 * (22.5f64).to_radians().tan() * nearest)
}

/// The checker cells of the grid (40 × 40), each split `subdiv` × `subdiv` into two triangles
/// per quad.
const CELLS: u64 = 40 * 40;

/// The most `subdiv` an automatic choice takes: at most [`LARGE_MESH_TRIANGLES`] triangles
/// (17: 0.92 M; 32 would be 3.3 M and 0.8 GB).
pub fn max_auto_subdiv() -> u32 {
    (1..=MAX_SUBDIV)
        .take_while(|&k| CELLS * 2 * u64::from(k * k) <= LARGE_MESH_TRIANGLES)
        .last()
        .unwrap_or(1)
}

/// Whether cells split `k` × `k` stay within [`SUBDIV_BUDGET_PX`] of the surface in a picture
/// `height` pixels tall.
pub fn subdiv_fits(k: u32, p: &Params, eye: Vec3, height: u32) -> bool {
    let (h, xs, zs) = (p.f64("h"), p.f64("xs"), p.f64("zs"));
    subdiv_error(k, h, xs, zs) * pixels_per_unit(eye, h, height) <= SUBDIV_BUDGET_PX
}

/// The smallest `subdiv` whose error ([`subdiv_error`]) is within [`SUBDIV_BUDGET_PX`] in a
/// picture `height` pixels tall, at most [`max_auto_subdiv`] (a wave too steep for that is
/// drawn at it, and said: [`subdiv_fits`] is then false).
pub fn auto_subdiv(p: &Params, eye: Vec3, height: u32) -> u32 {
    let max = max_auto_subdiv();
    (1..=max).find(|&k| subdiv_fits(k, p, eye, height)).unwrap_or(max)
}

/// Seed 001, §1.3: the `Wave` block's `xs`, `zs`, `h` are parameters, its `time` the wrapped
/// clock ([`wave_time`]).
pub static RECIPE: Recipe = Recipe::new(
    super::info(
        lab_name!(),
        "ref001",
        "wave motion",
        Keys::rows(
            &[
                KeyRow::step(&[C('h'), C('H')], "h", 0.02),
                KeyRow::step(&[C('x'), C('X')], "xs", 0.5),
                KeyRow::step(&[C('z'), C('Z')], "zs", 0.5),
            ],
            "Space pauses the clock; left drag rotates",
        ),
    ),
    &[
        &[
            ParamSpec::real("time", &[0.0], -1e9, 1e9, "seconds (a clock in a window; Space pauses)"),
            ParamSpec::real("h", &[0.1], -10.0, 10.0, "height scale (h H)"),
            ParamSpec::real("xs", &[3.0], -100.0, 100.0, "frequency along x (x X)"),
            ParamSpec::real("zs", &[2.0], -100.0, 100.0, "frequency along z (z Z)"),
            ParamSpec::int(
                "subdiv",
                &[1.0],
                0.0,
                MAX_SUBDIV as f64,
                "port: quads per checker cell side (course: 1); auto (0): the fewest within half a pixel of the sine surface",
            )
            .with_auto(0.0),
        ],
        ROTATION,
    ],
    |cx, p| {
        let mut geometry = WaveGrid {
            camera: UstcCamera::new(cx.gpu, cx.name, Vec3::new(0.0, 3.5, 6.5)),
            meshes: HashMap::new(),
            drawn: 1,
            capped: false,
        };
        geometry.mesh(cx.gpu, 1);
        MaterialScene::build(cx, p, geometry, &MATERIAL)
    },
)
.animated();

/// Seed 001's frame over the grid, built for each `subdiv` asked for (the course's first).
struct WaveGrid {
    camera: UstcCamera,
    meshes: HashMap<u32, GpuMesh<ColorVertex>>,
    drawn: u32,
    /// Whether `auto` stopped at its most without meeting its budget.
    capped: bool,
}

impl WaveGrid {
    fn mesh(&mut self, gpu: &Gpu, k: u32) -> &GpuMesh<ColorVertex> {
        self.meshes.entry(k).or_insert_with(|| {
            // Indexed: each distinct corner is shaded once instead of in each triangle (40x40:
            // 3,358 corners, 6,400 per quad, 9,600 as a triangle list).
            let (corners, indices) = indexed_quads(&wave_grid_sub(k));
            GpuMesh::new(gpu, "wave.grid", &corners, Some(&indices))
        })
    }
}

impl Geometry for WaveGrid {
    type Vertex = ColorVertex;
    fn input(&mut self, p: &mut Params, input: Input) -> bool {
        self.camera.input(p, input)
    }
    fn binds(&self) -> Vec<Bind> {
        vec![self.camera.transform.bind()]
    }
    fn prepare(&mut self, gpu: &Gpu, p: &Params, width: u32, height: u32) -> &GpuMesh<ColorVertex> {
        self.camera.upload(gpu, p, width, height);
        let k = match p.f64("subdiv") as u32 {
            0 => {
                let k = auto_subdiv(p, self.camera.eye, height);
                self.capped = !subdiv_fits(k, p, self.camera.eye, height);
                if self.capped {
                    note_once(format!(
                        "wave: subdiv=auto: this wave (h={}, xs={}, zs={}) needs more than {k} quads a cell side to stay \
                         within half a pixel of the surface; auto draws at most {LARGE_MESH_TRIANGLES} triangles, so {k}",
                        p.f64("h"),
                        p.f64("xs"),
                        p.f64("zs")
                    ));
                }
                k
            }
            k => k,
        };
        if !self.meshes.contains_key(&k) {
            let drawn = self.drawn;
            self.meshes.retain(|&m, _| m == 1 || m == drawn);
        }
        self.drawn = k;
        self.mesh(gpu, k)
    }
    fn title(&self, info: &crate::lab::LabInfo, p: &Params) -> String {
        crate::lab::params_title(info, p)
            + &{
                if p.f64("subdiv") == 0.0 {
                    let capped = if self.capped {
                        " (its most; over half a pixel)"
                    } else {
                        ""
                    };
                    format!(" | subdiv auto: {}{capped}", self.drawn)
                } else {
                    String::new()
                }
            }
    }
}

static MATERIAL: Material = Material::new(&[ShaderPair::new("wave.vert", "pass_color.frag")])
    .derive(|p: &Params, c: &mut Derived| c.set("time", &[wave_time(p)]));

// gl_Vertex and glColor3f's colour.
crate::vertex_type!(ColorVertex, {
    position: "vertex_position" => Float32x3,
    color: "vertex_color" => Float32x3,
});

/// The `time` uniform. `time` only enters through `sin(time + …)`, so it is wrapped by 2π in
/// double before it becomes a float: the same value below 2π, and no lost precision in a window
/// left running for hours.
pub fn wave_time(p: &Params) -> f32 {
    p.f64("time").rem_euclid(TAU) as f32
}
