//! Exercise 1, position → RGB (`Lab05-1`): each vertex's colour is `normalize(gl_Vertex.zyxw)
//! + 0.5` — a 4-component normalize with w = 1 — so the object shows its position as colour,
//! z as red, y as green, x as blue; values above 1 clamp. Keys: `1`-`4` objects, mouse drag rotates.

use crate::effect::{Effect, NoUniforms};

/// Exercise 1.
pub struct PositionRgb;

impl Effect for PositionRgb {
    type Uniforms = NoUniforms;
    const NAME: &'static str = "position_rgb";
    const TITLE: &'static str = "Lab05-1";
    const LABEL: &'static str = "position to RGB";
    const CLEAR: [f64; 3] = [0.0, 0.0, 0.0];

    fn defaults() -> NoUniforms {
        NoUniforms::default()
    }

    fn summary(_uniforms: &NoUniforms) -> String {
        "drag to rotate, 1-4 objects".into()
    }
}
