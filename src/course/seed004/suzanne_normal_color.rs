//! Seed 004 §4.1, "Hello Suzanne" (course shaders, verbatim): the object-space face normal as
//! colour, `abs(v_normal)`. The colours belong to the model's surface as exported, not to the view:
//! turned, the model shows the same colours on the same faces.
//!
//! Keys: left drag rotates (0.5° per pixel).

use crate::course::seed004::geometry::Normals;
use crate::course::seed004::suzanne::{colour, draw};
use crate::lab::{Material, Recipe, ShaderPair};

/// Seed 004 §4.1.
pub static RECIPE: Recipe = colour(lab_name!(), "normal colour", |cx, p| {
    draw(cx, p, RECIPE.info.name, &MATERIAL, |_| Normals::Face)
});

static MATERIAL: Material = Material::new(&[ShaderPair::new(
    "suzanne_normal_color.vert",
    "suzanne_normal_color.frag",
)]);
