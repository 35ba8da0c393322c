//! The exercises, one module each, and [`ALL`]: the one list that examples, the bench and the
//! tests iterate. Each module names its shaders (`shaders_glsl/NAME.*`), its example
//! (`examples/NAME.rs`) and its tests after itself.

pub mod gl_light;
pub mod glut_stage;
pub mod immediate;
pub mod modified_phong;
pub mod tangent_bump;
pub mod ustc_stage;

pub mod displacement;
pub mod double_vision;
pub mod height;
pub mod lecture12;
pub mod legacy;
pub mod morph;
pub mod noise;
pub mod normal_rgb;
pub mod normal_world;
pub mod particles;
pub mod phong;
pub mod phong_dir;
mod plain;
pub mod position_rgb;
pub mod specular_strip;
pub mod twist;

pub mod gl_textures;
pub mod suzanne_lit;
pub mod suzanne_plain;
pub mod suzanne_stage;
pub mod suzanne_textured;

pub mod bump;
pub mod envmap;
pub mod normmap;
pub mod phong_fragment;
pub mod phong_vertex;
pub mod suzanne_flat;
pub mod suzanne_gouraud;
pub mod suzanne_normal_color;
pub mod suzanne_normal_matrix;
pub mod suzanne_phong;
pub mod suzanne_smooth;
pub mod suzanne_texture;
pub mod suzanne_texture_color;
pub mod texparams;
pub mod texture;
pub mod toon;
pub mod uniform_arrays;
pub mod wave;

use crate::lab::LabEntry;
use crate::params::{ParamSpec, Params};

/// Seed 000, CMP211 Lab05 exercise 1.
pub static POSITION_RGB: &LabEntry = &position_rgb::ENTRY;
/// Seed 000, exercise 2.
pub static NORMAL_RGB: &LabEntry = &normal_rgb::ENTRY;
/// Seed 000, exercise 3.
pub static PHONG: &LabEntry = &phong::ENTRY;
/// Seed 000, exercise 4.
pub static NOISE: &LabEntry = &noise::ENTRY;
/// Seed 000, exercise 5.
pub static DISPLACEMENT: &LabEntry = &displacement::ENTRY;
/// Seed 002, Lecture 12: 2D twisting.
pub static TWIST: &LabEntry = &twist::ENTRY;
/// Seed 002, Lecture 12: double vision.
pub static DOUBLE_VISION: &LabEntry = &double_vision::ENTRY;
/// Seed 002, Lecture 12: normal as colour in world space.
pub static NORMAL_WORLD: &LabEntry = &normal_world::ENTRY;
/// Seed 002, Lecture 12: Phong with a directional light.
pub static PHONG_DIR: &LabEntry = &phong_dir::ENTRY;
/// Seed 003, LETI lab 5: Bézier strip with specular light.
pub static SPECULAR_STRIP: &LabEntry = &specular_strip::ENTRY;

/// Seed 004 §4.1, "Hello Suzanne".
pub static SUZANNE_NORMAL_COLOR: &LabEntry = &suzanne_normal_color::ENTRY;
/// Seed 004 §4.2, normals turned by the normal matrix.
pub static SUZANNE_NORMAL_MATRIX: &LabEntry = &suzanne_normal_matrix::ENTRY;
/// Seed 004 §4.3, "Smooth Suzanne".
pub static SUZANNE_SMOOTH: &LabEntry = &suzanne_smooth::ENTRY;
/// Seed 004 §4.4, textured model.
pub static SUZANNE_TEXTURE: &LabEntry = &suzanne_texture::ENTRY;
/// Seed 004 §4.5, texture times normal colour.
pub static SUZANNE_TEXTURE_COLOR: &LabEntry = &suzanne_texture_color::ENTRY;
/// Seed 004 §4.6, texture parameters.
pub static TEXPARAMS: &LabEntry = &texparams::ENTRY;
/// Seed 004 §4.7, flat shading.
pub static SUZANNE_FLAT: &LabEntry = &suzanne_flat::ENTRY;
/// Seed 004 §4.8, Gouraud shading.
pub static SUZANNE_GOURAUD: &LabEntry = &suzanne_gouraud::ENTRY;
/// Seed 004 §4.9, Phong shading.
pub static SUZANNE_PHONG: &LabEntry = &suzanne_phong::ENTRY;

/// Seed 001 §1.1: a custom vertex attribute.
pub static HEIGHT: &LabEntry = &height::ENTRY;

/// Seed 001 §1.2: uniform vectors and arrays.
pub static UNIFORM_ARRAYS: &LabEntry = &uniform_arrays::ENTRY;

/// Seed 001 §1.3, wave-motion vertex shader.
pub static WAVE: &LabEntry = &wave::ENTRY;

/// Seed 001 §1.4, morphing vertex shader.
pub static MORPH: &LabEntry = &morph::ENTRY;

/// Seed 001 §1.5, particle-system vertex shader.
pub static PARTICLES: &LabEntry = &particles::ENTRY;

/// Seed 001 §1.6, toon (non-photorealistic) shading.
pub static TOON: &LabEntry = &toon::ENTRY;

/// Seed 001 §1.7, modified Phong per vertex.
pub static PHONG_VERTEX: &LabEntry = &phong_vertex::ENTRY;

/// Seed 001 §1.8, modified Phong per fragment.
pub static PHONG_FRAGMENT: &LabEntry = &phong_fragment::ENTRY;

/// Seed 001 §1.9, texture mapping with a sampler.
pub static TEXTURE: &LabEntry = &texture::ENTRY;

/// Seed 001 §1.10, cube-map environment (reflection) map.
pub static ENVMAP: &LabEntry = &envmap::ENTRY;

/// Seed 001 §1.11, tangent-space bump mapping.
pub static BUMP: &LabEntry = &bump::ENTRY;

/// Seed 001 §1.12, normalization cube map.
pub static NORMMAP: &LabEntry = &normmap::ENTRY;

/// A course's own GLSL 1.10/1.20 shaders (`legacy VERT FRAG`).
pub static LEGACY: &LabEntry = &legacy::ENTRY;

/// Every lab, in lecture order.
pub static ALL: &[&LabEntry] = &[
    &position_rgb::ENTRY,
    &normal_rgb::ENTRY,
    &phong::ENTRY,
    &noise::ENTRY,
    &displacement::ENTRY,
    &height::ENTRY,
    &uniform_arrays::ENTRY,
    &wave::ENTRY,
    &morph::ENTRY,
    &particles::ENTRY,
    &toon::ENTRY,
    &phong_vertex::ENTRY,
    &phong_fragment::ENTRY,
    &texture::ENTRY,
    &envmap::ENTRY,
    &bump::ENTRY,
    &normmap::ENTRY,
    &twist::ENTRY,
    &double_vision::ENTRY,
    &normal_world::ENTRY,
    &phong_dir::ENTRY,
    &specular_strip::ENTRY,
    &suzanne_normal_color::ENTRY,
    &suzanne_normal_matrix::ENTRY,
    &suzanne_smooth::ENTRY,
    &suzanne_texture::ENTRY,
    &suzanne_texture_color::ENTRY,
    &texparams::ENTRY,
    &suzanne_flat::ENTRY,
    &suzanne_gouraud::ENTRY,
    &suzanne_phong::ENTRY,
    &legacy::ENTRY,
];

/// The lab called `name`.
pub fn find(name: &str) -> Option<&'static LabEntry> {
    ALL.iter().copied().find(|e| e.info.name == name)
}

/// The simplex noise is periodic in `time` along (1,1,1): its lattice repeats every 289 skewed
/// units, and a shift of t along (1,1,1) moves the skewed coordinates by 2t, so t = 289/2.
pub const NOISE_PERIOD: f64 = 144.5;

/// The clock of exercises 4 and 5, and the port's wrap of it by the noise period.
const NOISE_PARAMS: &[ParamSpec] = &[
    ParamSpec::real("time", &[0.0], -1e9, 1e9, "seconds (a clock in a window)"),
    ParamSpec::flag(
        "wrap_time",
        &[1.0],
        "port: wrap time by the noise period (144.5 s) so f32 never loses precision",
    ),
];

/// The time uniform of exercises 4 and 5: kept in f64 by the clock and wrapped by the noise
/// period before it is narrowed, so a long-running window keeps full precision.
fn noise_time(p: &Params) -> f32 {
    let t = p.f64("time");
    (if p.on("wrap_time") {
        t.rem_euclid(NOISE_PERIOD)
    } else {
        t
    }) as f32
}

/// The shade keys of exercises 4 and 5: `R/G/B` +0.05, `r/g/b` -0.05 on the noise colour.
fn shade_key(p: &mut Params, key: char) -> bool {
    let (channel, delta) = match key {
        'R' => (0, 0.05),
        'r' => (0, -0.05),
        'G' => (1, 0.05),
        'g' => (1, -0.05),
        'B' => (2, 0.05),
        'b' => (2, -0.05),
        _ => return false,
    };
    p.step_clamped("shade", channel, delta, 0.0, 1.0);
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_labs_taking_user_files_are_the_ones_built_on_them() {
        let with = |which: fn(crate::lab::FilesTaken) -> bool| -> Vec<&str> {
            ALL.iter()
                .filter(|e| which(e.info.files))
                .map(|e| e.info.name)
                .collect()
        };
        // SuzanneStage (the model) is built by suzanne_plain, suzanne_textured and suzanne_lit.
        assert_eq!(
            with(|t| t.model),
            [
                "suzanne_normal_color",
                "suzanne_normal_matrix",
                "suzanne_smooth",
                "suzanne_texture",
                "suzanne_texture_color",
                "suzanne_flat",
                "suzanne_gouraud",
                "suzanne_phong"
            ]
        );
        // `cx.files.texture` is read by suzanne_textured, texparams and legacy.
        assert_eq!(
            with(|t| t.texture),
            ["suzanne_texture", "suzanne_texture_color", "texparams", "legacy"]
        );
        assert_eq!(with(|t| t.named_textures), ["legacy"]);
    }
}
