//! Seed 001 `phong_vertex` (SPEC §1.7): the course's modified Phong (Blinn) lighting; the lighting is computed per vertex and its colour interpolated: on the teapot the highlight is blotchy, shaped by the triangles.
//! See [`crate::labs::seed001::modified_phong`] for the light, the keys and `compare` (both halves side by side).

use crate::error::Result;
use crate::lab::{FilesTaken, Lab, LabContext, LabEntry, LabInfo};

use crate::labs::seed001::modified_phong::{self, Shading};

/// Seed 001, §1.7.
pub static INFO: LabInfo = LabInfo {
    name: "phong_vertex",
    title: "ref001",
    label: "modified Phong, per vertex",
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
    modified_phong::new(cx, &INFO, Shading::Vertex)
}
