//! Seed 004 §4.4: the model (vertex-normal VBO) textured from unit 0, `texture(tex, texcoord)` at
//! the exported Smart-UV-Project coordinates: the course's checker (`tex=0`) or its "BMP" texture,
//! the uvgrid (`tex=1`, or `--texture FILE`).
//!
//! Keys: `t` toggles checker / BMP; left drag rotates (0.5° per pixel).

use crate::lab::{FilesTaken, LabEntry, LabInfo};

use crate::labs::seed004::textured::{self, Textured};

/// Seed 004 §4.4.
pub static INFO: LabInfo = LabInfo {
    name: "suzanne_texture",
    title: "OpenGL III",
    label: "texture",
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
    frag: "suzanne_texture.frag",
};

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params: textured::params,
    new: |cx| textured::new(cx, &TEXTURED),
};
