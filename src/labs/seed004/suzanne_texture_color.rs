//! Seed 004 §4.5: the texture of 4.4 modulated by the normal colour of 4.2, `texture(tex, texcoord)
//! * color`.
//!
//! Keys: `t` toggles checker / BMP; left drag rotates (0.5° per pixel).

use crate::lab::{FilesTaken, LabEntry, LabInfo};

use crate::labs::seed004::textured::{self, Textured};

/// Seed 004 §4.5.
pub static INFO: LabInfo = LabInfo {
    name: "suzanne_texture_color",
    title: "OpenGL III",
    label: "texture × colour",
    lecture: "004 OpenGL III – Basic Shaders",
    size: (640, 480),
    keys: crate::lab::Keys::text("t: checker / BMP texture; left drag rotates (0.5 degrees per pixel)"),
    files: FilesTaken {
        model: true,
        texture: true,
        ..FilesTaken::NONE
    },
};

static TEXTURED: Textured = Textured {
    info: &INFO,
    frag: "suzanne_texture_color.frag",
};

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params: textured::params,
    new: |cx| textured::new(cx, &TEXTURED),
};
