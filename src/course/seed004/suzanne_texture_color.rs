//! Seed 004 §4.5: the texture of 4.4 modulated by the normal colour of 4.2, `texture(tex, texcoord)
//! * color`.
//!
//! Keys: `t` toggles checker / BMP; left drag rotates (0.5° per pixel).

use crate::course::common::FaceOrder;
use crate::course::seed004::suzanne::{sample, textured};
use crate::lab::Recipe;

/// Seed 004 §4.5.
pub static RECIPE: Recipe = textured(lab_name!(), "texture × colour", |cx, _| {
    // Mesh order: facing the eye first gained nothing measurable (docs/speed.md).
    sample(cx, RECIPE.info.name, "suzanne_texture_color.frag", |_| FaceOrder::Mesh)
});
