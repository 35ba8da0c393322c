//! Seed 004 §4.1, "Hello Suzanne" (course shaders, verbatim): the object-space face normal as
//! colour, `abs(v_normal)`. The colours belong to the model's surface as exported, not to the view:
//! turned, the model shows the same colours on the same faces.
//!
//! Keys: left drag rotates (0.5° per pixel).

use crate::lab::{FilesTaken, LabEntry, LabInfo};

use crate::labs::seed004::plain::{self, Plain};
use crate::labs::seed004::stage::Normals;

/// Seed 004 §4.1.
pub static INFO: LabInfo = LabInfo {
    name: "suzanne_normal_color",
    title: "OpenGL III",
    label: "normal colour",
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
    vert: "suzanne_normal_color.vert",
    frag: "suzanne_normal_color.frag",
    normals: Normals::Face,
};

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params: plain::params,
    new: |cx| plain::new(cx, &PLAIN),
};
