//! Exercise 5, displacement (`Lab05-5`): each vertex moves along its normal by simplex noise
//! of its direction (`snoise(normalize(v)*2 + time)`) times `clamp(displacement, 0, 1)`, and is
//! coloured `shade * clamp(noise, 0, 1)`. On GLUT's meshes the shapes look jagged, and the cube
//! and teapot crack open where vertices share a position but not a normal — as in the original.
//! `--set smooth=1` (a port addition) welds shared vertices and averages their normals, which
//! closes the cracks. Keys: `[`/`]` displacement ∓0.01 (clamped to [0, 1]), `R/r G/g B/b` ±0.05 on the shade,
//! `1`-`4` objects, mouse drag rotates.

use super::{shade_key, step};
use crate::effect::{Effect, Scene};

/// Exercise 5.
pub struct Displacement;

/// The `DisplacementParams` block of `displacement_params.glsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct DisplacementUniforms {
    /// `shade`: colour of the noise.
    pub shade: [f32; 3],
    /// `time` in seconds.
    pub time: f32,
    /// `displacement`: strength.
    pub displacement: f32,
    /// std140 rounds the block up to 16 bytes.
    pub _pad: [f32; 3],
}
crate::uniform_block!(DisplacementUniforms, "DisplacementParams", {
    shade: "shade",
    time: "time",
    displacement: "displacement",
});

impl Effect for Displacement {
    type Uniforms = DisplacementUniforms;
    const NAME: &'static str = "displacement";
    const TITLE: &'static str = "Lab05-5";
    const LABEL: &'static str = "displacement";
    const CLEAR: [f64; 3] = [0.0, 0.0, 0.0];
    const SMOOTH_OPTION: bool = true;

    fn defaults() -> DisplacementUniforms {
        DisplacementUniforms {
            shade: [1.0, 1.0, 1.0],
            time: 0.0,
            displacement: 0.5,
            _pad: [0.0; 3],
        }
    }

    fn key(key: char, u: &mut DisplacementUniforms, _scene: &mut Scene) -> bool {
        match key {
            '[' => step(&mut u.displacement, -0.01, 0.0, 1.0),
            ']' => step(&mut u.displacement, 0.01, 0.0, 1.0),
            _ => return shade_key(key, &mut u.shade),
        }
        true
    }

    fn summary(u: &DisplacementUniforms) -> String {
        let [r, g, b] = u.shade;
        format!(
            "displacement {:.2} shade ({r:.2},{g:.2},{b:.2}) time {:.1}",
            u.displacement, u.time
        )
    }
}
