//! Seed 001 `phong_vertex` (SPEC §1.7): the course's modified Phong (Blinn) lighting; the lighting is computed per vertex and its colour interpolated: on the teapot the highlight is blotchy, shaped by the triangles.
//! See [`crate::course::seed001::modified_phong`] for the light, the keys and `compare` (both halves side by side).

use crate::lab::Recipe;

use crate::course::seed001::modified_phong::{self, Shading};

/// Seed 001, §1.7.
pub static RECIPE: Recipe = Recipe::new(
    super::info(
        lab_name!(),
        "ref001",
        "modified Phong, per vertex",
        modified_phong::KEYS,
    ),
    modified_phong::PARAMS,
    |cx, _| modified_phong::build(cx, "phong_vertex", Shading::Vertex),
);
