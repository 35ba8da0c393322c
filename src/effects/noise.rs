//! Exercise 4, simplex noise (`Lab05-4`): Ashima/McEwan 3D simplex noise evaluated per
//! fragment at the object-space position plus `time`, shown as `shade * |snoise|`; it animates
//! with a clock in seconds. Keys: `R/r G/g B/b` ±0.05 on the shade colour (clamped to [0, 1]),
//! `1`-`4` objects, mouse drag rotates.

use super::shade_key;
use crate::effect::{Effect, Scene};

/// Exercise 4.
pub struct Noise;

/// The `NoiseParams` block of `noise_params.glsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct NoiseUniforms {
    /// `shade`: colour of the noise.
    pub shade: [f32; 3],
    /// `time` in seconds.
    pub time: f32,
}
crate::uniform_block!(NoiseUniforms, "NoiseParams", { shade: "shade", time: "time" });

impl Effect for Noise {
    type Uniforms = NoiseUniforms;
    const NAME: &'static str = "noise";
    const TITLE: &'static str = "Lab05-4";
    const LABEL: &'static str = "simplex noise";
    const CLEAR: [f64; 3] = [0.0, 0.0, 0.0];

    fn defaults() -> NoiseUniforms {
        NoiseUniforms {
            shade: [1.0, 1.0, 1.0],
            time: 0.0,
        }
    }

    fn key(key: char, u: &mut NoiseUniforms, _scene: &mut Scene) -> bool {
        shade_key(key, &mut u.shade)
    }

    fn summary(u: &NoiseUniforms) -> String {
        let [r, g, b] = u.shade;
        format!("shade ({r:.2},{g:.2},{b:.2}) time {:.1}", u.time)
    }
}
