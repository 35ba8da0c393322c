//! Seed 004, OpenGL III – Basic Shaders: the model ([`geometry`]) with normals as colour,
//! textured ([`gl_textures`]) and lit, each family of exercises a recipe builder
//! ([`suzanne`]), and the texture parameters on a floor ([`texparams`]).

pub mod geometry;

pub mod gl_textures;
pub mod suzanne;

pub mod suzanne_flat;
pub mod suzanne_gouraud;
pub mod suzanne_normal_color;
pub mod suzanne_normal_matrix;
pub mod suzanne_phong;
pub mod suzanne_smooth;
pub mod suzanne_texture;
pub mod suzanne_texture_color;
pub mod texparams;

use crate::lab::{FilesTaken, Keys, LabInfo};

/// The lecture's exercise `name`: the course's window title, 640 × 480.
pub const fn info(name: &'static str, label: &'static str, keys: Keys, files: FilesTaken) -> LabInfo {
    LabInfo {
        name,
        original_title: "OpenGL III",
        label,
        lecture: "004 OpenGL III – Basic Shaders",
        size: (640, 480),
        keys,
        files,
    }
}
