//! Seed 004 §4.8, Gouraud shading: ambient + diffuse + specular evaluated per vertex on the
//! vertex-normal VBO and interpolated; a highlight that falls between vertices smears or vanishes.
//!
//! Keys: see [`crate::labs::seed004::lit`] (`1`/`2`/`3` switch to flat, Gouraud, Phong).

use crate::lab::{FilesTaken, LabEntry, LabInfo};
use crate::params::{ParamSpec, Params};

use crate::labs::seed004::lit::{self, Lit, SHADINGS};

/// Seed 004 §4.8.
pub static INFO: LabInfo = LabInfo {
    name: "suzanne_gouraud",
    title: "OpenGL III",
    label: "Gouraud shading",
    lecture: "004 OpenGL III – Basic Shaders",
    size: (640, 480),
    keys: crate::lab::Keys::text(lit::KEYS),
    files: FilesTaken {
        model: true,
        ..FilesTaken::NONE
    },
};

const SHADING: &[ParamSpec] = &[ParamSpec::choice("shading", &[1.0], SHADINGS, "shading model (1/2/3)")];

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
