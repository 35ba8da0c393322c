//! Seed 004 §4.3, "Smooth Suzanne": the shaders of 4.2 on the vertex-normal VBO (each vertex the
//! normalized sum of the normals of its faces), so the colours blend across faces instead of one
//! per triangle.
//!
//! Keys: left drag rotates (0.5° per pixel).

use crate::lab::{FilesTaken, LabEntry, LabInfo};

use crate::labs::seed004::plain::{self, Plain};
use crate::labs::seed004::stage::Normals;

/// Seed 004 §4.3.
pub static INFO: LabInfo = LabInfo {
    name: "suzanne_smooth",
    title: "OpenGL III",
    label: "smooth",
    lecture: "004 OpenGL III – Basic Shaders",
    size: (640, 480),
    keys: crate::lab::Keys::text("left drag rotates (0.5° per pixel)"),
    files: FilesTaken {
        model: true,
        ..FilesTaken::NONE
    },
};

static PLAIN: Plain = Plain {
    info: &INFO,
    vert: "suzanne_normal_matrix.vert",
    frag: "suzanne_normal_color.frag",
    normals: Normals::Vertex,
};

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params: plain::params,
    new: |cx| plain::new(cx, &PLAIN),
};
