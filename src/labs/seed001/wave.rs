//! Seed 001 `wave` (SPEC §1.3): the course's wave-motion vertex shader lifts a flat checkered
//! 40×40 grid by `h·sin(time + xs·x) + h·sin(time + zs·z)`; the crests travel with time (in
//! seconds: the course's idle callback sends milliseconds, which would flicker, §6.1). Seen
//! from (0, 3.5, 6.5).
//!
//! Keys: Space pauses the clock; `h`/`H` h ∓0.02; `x`/`X` xs ∓0.5; `z`/`Z` zs ∓0.5; left drag
//! rotates.

use std::f64::consts::TAU;

use glam::Vec3;

use crate::geometry::shapes::{wave_grid, ColorVertex};
use crate::lab::{Key::C, KeyRow, Keys, Look, Pass, Recipe, Shaded};
use crate::params::{ParamSpec, Params};
use crate::render::{Computed, GpuMesh};

use crate::labs::seed001::stage::{OnMesh, UstcStage, ROTATION};

/// Seed 001, §1.3: the `Wave` block's `xs`, `zs`, `h` are parameters, its `time` the wrapped
/// clock ([`wave_time`]).
pub static RECIPE: Recipe = Recipe {
    info: super::info(
        "wave",
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
    params: &[
        &[
            ParamSpec::real("time", &[0.0], -1e9, 1e9, "seconds (a clock in a window; Space pauses)"),
            ParamSpec::real("h", &[0.1], -10.0, 10.0, "height scale (h H)"),
            ParamSpec::real("xs", &[3.0], -100.0, 100.0, "frequency along x (x X)"),
            ParamSpec::real("zs", &[2.0], -100.0, 100.0, "frequency along z (z Z)"),
        ],
        ROTATION,
    ],
    animated: true,
    title: None,
    build: |cx, p| {
        let stage = OnMesh {
            stage: UstcStage::new(cx.gpu, "wave", Vec3::new(0.0, 3.5, 6.5)),
            mesh: GpuMesh::new(cx.gpu, "wave.grid", &wave_grid(), None),
        };
        Shaded::build(cx, "wave", p, stage, &LOOK, Vec::new())
    },
};

static LOOK: Look = Look::new(&[Pass::new("wave.vert", "pass_color.frag")])
    .hook(|p: &Params, c: &mut Computed| c.set("time", &[wave_time(p)]));

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
