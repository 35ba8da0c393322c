//! Exercise 2, normal → RGB (`Lab05-2`): the eye-space normal `normalize(gl_NormalMatrix *
//! gl_Normal)` as colour; negative components clamp to 0, so faces turned right are red, up
//! green, towards the viewer blue. Keys: `1`-`4` objects, mouse drag rotates.

use crate::effect::{Effect, NoUniforms};

/// Exercise 2.
pub struct NormalRgb;

impl Effect for NormalRgb {
    type Uniforms = NoUniforms;
    const NAME: &'static str = "normal_rgb";
    const TITLE: &'static str = "Lab05-2";
    const LABEL: &'static str = "normal to RGB";
    const CLEAR: [f64; 3] = [0.0, 0.0, 0.0];

    fn defaults() -> NoUniforms {
        NoUniforms::default()
    }

    fn summary(_uniforms: &NoUniforms) -> String {
        "drag to rotate, 1-4 objects".into()
    }
}
