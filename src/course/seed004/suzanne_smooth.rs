//! Seed 004 §4.3, "Smooth Suzanne": the shaders of 4.2 on the vertex-normal VBO (each vertex the
//! normalized sum of the normals of its faces), so the colours blend across faces instead of one
//! per triangle.
//!
//! Keys: left drag rotates (0.5° per pixel).

use crate::course::seed004::geometry::Normals;
use crate::course::seed004::suzanne::{colour, draw};
use crate::lab::{Material, Recipe, ShaderPair};

/// Seed 004 §4.3.
pub static RECIPE: Recipe = colour(lab_name!(), "smooth", |cx, p| {
    draw(cx, p, RECIPE.info.name, &MATERIAL, |_| Normals::Vertex)
});

static MATERIAL: Material = Material::new(&[ShaderPair::new(
    "suzanne_normal_matrix.vert",
    "suzanne_normal_color.frag",
)]);
