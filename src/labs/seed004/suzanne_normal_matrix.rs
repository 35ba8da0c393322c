//! Seed 004 §4.2 (course vertex shader, verbatim): the face normal turned by the normal matrix NM =
//! transpose(inverse(mat3(MV))) as colour, so the colours follow the view: what faces the eye is
//! blue however the model turns.
//!
//! Keys: left drag rotates (0.5° per pixel).

use crate::lab::{FilesTaken, LabEntry, LabInfo};

use crate::labs::seed004::plain::{self, Plain};
use crate::labs::seed004::stage::Normals;

/// Seed 004 §4.2.
pub static INFO: LabInfo = LabInfo {
    name: "suzanne_normal_matrix",
    title: "OpenGL III",
    label: "normal matrix",
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
    normals: Normals::Face,
};

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params: plain::params,
    new: |cx| plain::new(cx, &PLAIN),
};
