//! Seed 004 §4.7, flat shading (pinned): the Gouraud shaders with `flat` interpolation on the
//! face-normal VBO, one colour per triangle, lit at its first vertex.
//!
//! Keys: see [`crate::course::seed004::suzanne`] (`1`/`2`/`3` switch to flat, Gouraud, Phong).

use crate::course::seed004::suzanne::{lit, shade, Shading};
use crate::lab::Recipe;

/// Seed 004 §4.7.
pub static RECIPE: Recipe = lit(lab_name!(), "Flat shading", Shading::Flat, |cx, p| {
    shade(cx, p, RECIPE.info.name)
});
