//! Seed 001 `phong_fragment` (SPEC §1.8): the course's modified Phong (Blinn) lighting; N, L and E are interpolated and the lighting is computed per fragment: the highlight is round.
//! See [`crate::labs::seed001::modified_phong`] for the light, the keys and `compare` (both halves side by side).

use crate::error::Result;
use crate::lab::{FilesTaken, Lab, LabContext, LabEntry, LabInfo};

use crate::labs::seed001::modified_phong::{self, Shading};

/// Seed 001, §1.8.
pub static INFO: LabInfo = LabInfo {
    name: "phong_fragment",
    title: "ref001",
    label: "modified Phong, per fragment",
    lecture: "001 USTC GLSL (III)",
    size: (512, 512),
    keys: crate::lab::Keys::text(modified_phong::KEYS),
    files: FilesTaken::NONE,
};

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params: modified_phong::params,
    new,
};

fn new(cx: &LabContext) -> Result<Box<dyn Lab>> {
    modified_phong::new(cx, &INFO, Shading::Fragment)
}
