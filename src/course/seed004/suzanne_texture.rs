//! Seed 004 §4.4: the model (vertex-normal VBO) textured from unit 0, `texture(tex, texcoord)` at
//! the exported Smart-UV-Project coordinates: the course's checker (`tex=0`) or its "BMP" texture,
//! the uvgrid (`tex=1`, or `--texture FILE`).
//!
//! Keys: `t` toggles checker / BMP; left drag rotates (0.5° per pixel).

use crate::course::common::FaceOrder;
use crate::course::seed004::suzanne::{sample, textured};
use crate::lab::Recipe;

/// Seed 004 §4.4.
pub static RECIPE: Recipe = textured(lab_name!(), "texture", |cx, _| {
    // Facing the eye first: 0.947 of mesh order (wall, 9 alternating pairs; CPU 0.939).
    sample(cx, RECIPE.info.name, "suzanne_texture.frag", |_| FaceOrder::FacingFirst)
});
