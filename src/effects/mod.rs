//! One module per exercise of CMP211 Lab05. Each names its shaders (`shaders_glsl/NAME.*`),
//! its example (`examples/NAME.rs`) and its tests after the module.

pub mod displacement;
pub mod noise;
pub mod normal_rgb;
pub mod phong;
pub mod position_rgb;

pub use displacement::Displacement;
pub use noise::Noise;
pub use normal_rgb::NormalRgb;
pub use phong::Phong;
pub use position_rgb::PositionRgb;

/// Adds `delta` and clamps to `[lo, hi]`: the original's keys step values with bounds checks
/// that let them step just past the bounds; the port clamps.
pub(crate) fn step(value: &mut f32, delta: f32, lo: f32, hi: f32) {
    *value = (*value + delta).clamp(lo, hi);
}

/// The shade keys of exercises 4 and 5: `R/G/B` +0.05, `r/g/b` -0.05 on the noise colour.
pub(crate) fn shade_key(key: char, shade: &mut [f32; 3]) -> bool {
    let (channel, delta) = match key {
        'R' => (0, 0.05),
        'r' => (0, -0.05),
        'G' => (1, 0.05),
        'g' => (1, -0.05),
        'B' => (2, 0.05),
        'b' => (2, -0.05),
        _ => return false,
    };
    step(&mut shade[channel], delta, 0.0, 1.0);
    true
}
