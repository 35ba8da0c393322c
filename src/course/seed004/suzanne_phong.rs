//! Seed 004 §4.9, Phong shading: the same lighting evaluated per fragment with the interpolated,
//! renormalized normal; highlights stay sharp.
//!
//! Keys: see [`crate::course::seed004::suzanne`] (`1`/`2`/`3` switch to flat, Gouraud, Phong).

use crate::course::seed004::suzanne::{lit, shade, Shading};
use crate::lab::Recipe;

/// Seed 004 §4.9.
pub static RECIPE: Recipe = lit(lab_name!(), "Phong shading", Shading::Phong, |cx, p| {
    shade(cx, p, RECIPE.info.name)
});
