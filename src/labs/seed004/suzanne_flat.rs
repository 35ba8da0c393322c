//! Seed 004 §4.7, flat shading (pinned): the Gouraud shaders with `flat` interpolation on the
//! face-normal VBO, one colour per triangle, lit at its first vertex.
//!
//! Keys: see [`crate::labs::seed004::lit`] (`1`/`2`/`3` switch to flat, Gouraud, Phong).

use crate::lab::{FilesTaken, LabEntry, LabInfo};
use crate::params::{ParamSpec, Params};

use crate::labs::seed004::lit::{self, Lit, SHADINGS};

/// Seed 004 §4.7.
pub static INFO: LabInfo = LabInfo {
    name: "suzanne_flat",
    title: "OpenGL III",
    label: "Flat shading",
    lecture: "004 OpenGL III – Basic Shaders",
    size: (640, 480),
    keys: crate::lab::Keys::text(lit::KEYS),
    files: FilesTaken {
        model: true,
        ..FilesTaken::NONE
    },
};

const SHADING: &[ParamSpec] = &[ParamSpec::choice("shading", &[0.0], SHADINGS, "shading model (1/2/3)")];

fn params() -> Params {
    lit::params(SHADING)
}

static LIT: Lit = Lit { info: &INFO, params };

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params,
    new: |cx| lit::new(cx, &LIT),
};
