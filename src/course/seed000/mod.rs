//! Seed 000, CMP211 Lab05 (GLUT, GLSL 4.5 through the port's matrices): five exercises on one
//! geometry ([`geometry`]): position and normal as colour, Phong, simplex noise, displacement.

pub mod geometry;

pub mod displacement;
pub mod noise;
pub mod normal_rgb;
pub mod phong;
pub mod position_rgb;

use crate::lab::{Key::C, KeyRow, Keys, LabInfo};
use crate::params::{ParamSpec, Params};

use geometry::title_000;

/// The simplex noise is periodic in `time` along (1,1,1): its lattice repeats every 289 skewed
/// units, and a shift of t along (1,1,1) moves the skewed coordinates by 2t, so t = 289/2.
pub const NOISE_PERIOD: f64 = 144.5;

/// The clock of exercises 4 and 5, and the port's wrap of it by the noise period.
pub(crate) const NOISE_PARAMS: &[ParamSpec] = &[
    ParamSpec::real("time", &[0.0], -1e9, 1e9, "seconds (a clock in a window)"),
    ParamSpec::flag(
        "wrap_time",
        &[1.0],
        "port: wrap time by the noise period (144.5 s) so f32 never loses precision",
    ),
];

/// The time uniform of exercises 4 and 5: kept in f64 by the clock and wrapped by the noise
/// period before it is narrowed, so a long-running window keeps full precision.
pub(crate) fn noise_time(p: &Params) -> f32 {
    let t = p.f64("time");
    (if p.on("wrap_time") {
        t.rem_euclid(NOISE_PERIOD)
    } else {
        t
    }) as f32
}

/// The shade keys of exercises 4 and 5: `r/R`, `g/G`, `b/B` ∓/±0.05 on the noise colour,
/// within [0, 1] (`--set` takes any value).
pub(crate) const SHADE_KEYS: &[KeyRow] = &[
    KeyRow::channel(&[C('r'), C('R')], "shade", 0, 0.05, 0.0, 1.0),
    KeyRow::channel(&[C('g'), C('G')], "shade", 1, 0.05, 0.0, 1.0),
    KeyRow::channel(&[C('b'), C('B')], "shade", 2, 0.05, 0.0, 1.0),
];

/// The keys of the exercises that are the geometry alone (1 and 2).
pub(crate) const GEOMETRY_KEYS: Keys = Keys::text("1-4: cube, sphere, torus, teapot; left drag rotates");

/// The title of the exercises that are the geometry alone (1 and 2).
pub(crate) fn geometry_title(info: &LabInfo, p: &Params) -> String {
    title_000(info, p, "drag to rotate, 1-4 objects", "")
}

lecture!("000 CMP211 Lab05", (640, 360));
