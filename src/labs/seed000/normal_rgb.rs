//! Exercise 2, normal → RGB (`Lab05-2`): `normalize(gl_NormalMatrix * gl_Normal)` in eye space
//! as colour; negative components clamp to 0. Keys: `1`-`4` objects, mouse drag rotates.

use crate::lab::{FilesTaken, LabEntry, LabInfo};

use crate::labs::seed000::plain::{self, Plain};
use crate::tess::Object;

/// Exercise 2.
pub static INFO: LabInfo = LabInfo {
    name: "normal_rgb",
    title: "Lab05-2",
    label: "normal to RGB",
    lecture: "000 CMP211 Lab05",
    size: (640, 360),
    keys: crate::lab::Keys::text("1-4: cube, sphere, torus, teapot; left drag rotates"),
    files: FilesTaken::NONE,
};

const PLAIN: Plain = Plain {
    info: &INFO,
    vert: "normal_rgb.vert",
    frag: "normal_rgb.frag",
    // Measured (issue 14, `--set faces=mesh` against `outside_first`, 7 alternating pairs):
    // torus 0.97-0.98; sphere 1.04-1.12, teapot 1.00-1.09, cube 0.99-1.00: the cheap shader
    // does not pay for the second pass over the geometry there.
    split: &[Object::Torus],
};

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params: plain::params,
    new: |cx| plain::new(cx, &PLAIN),
};
