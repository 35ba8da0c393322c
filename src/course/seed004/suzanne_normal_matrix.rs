//! Seed 004 §4.2 (course vertex shader, verbatim): the face normal turned by the normal matrix NM =
//! transpose(inverse(mat3(MV))) as colour, so the colours follow the view: what faces the eye is
//! blue however the model turns.
//!
//! Keys: left drag rotates (0.5° per pixel).

use crate::course::seed004::geometry::Normals;
use crate::course::seed004::suzanne::{colour, draw};
use crate::lab::{Material, Recipe, ShaderPair};

/// Seed 004 §4.2.
pub static RECIPE: Recipe = colour(lab_name!(), "normal matrix", |cx, p| {
    draw(cx, p, RECIPE.info.name, &MATERIAL, |_| Normals::Face)
});

static MATERIAL: Material = Material::new(&[ShaderPair::new(
    "suzanne_normal_matrix.vert",
    "suzanne_normal_color.frag",
)]);
