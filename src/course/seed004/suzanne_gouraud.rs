//! Seed 004 §4.8, Gouraud shading: ambient + diffuse + specular evaluated per vertex on the
//! vertex-normal VBO and interpolated; a highlight that falls between vertices smears or vanishes.
//!
//! Keys: see [`crate::course::seed004::suzanne`] (`1`/`2`/`3` switch to flat, Gouraud, Phong).

use crate::course::seed004::suzanne::{lit, shade, Shading};
use crate::lab::Recipe;

/// Seed 004 §4.8.
pub static RECIPE: Recipe = lit(lab_name!(), "Gouraud shading", Shading::Gouraud, |cx, p| {
    shade(cx, p, RECIPE.info.name)
});
