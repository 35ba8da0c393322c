//! Seed 001 `normmap` (SPEC §1.12): the `bump` lab with a normalization cube map. The lecture's
//! idea — store the normalized value of every direction in a cube map, so a lookup replaces
//! sqrt, multiplications and additions — replaces `normalize(L)` by `2·textureCube(normMap,
//! L) − 1`. The cube map (SPEC §0.1) is 32×32 per face, `GL_LINEAR`, `GL_CLAMP_TO_EDGE`,
//! seamless, on unit 1. The image matches `bump` up to the 8-bit quantization of the lookup.
//!
//! Keys: as `bump` (light keys move blx, bly, blz; left drag rotates).

use crate::error::Result;
use crate::images;
use crate::lab::{BuildContext, Lab, Material, Recipe, Runner, Scene, ShaderPair};
use crate::params::Params;
use crate::render::{sampler, Bind, SamplerDesc, Texture};

use crate::course::seed001::tangent_bump;

/// Seed 001, §1.12: `bump` with the cube map on unit 1.
pub static RECIPE: Recipe = recipe::<CUBE_SIZE>();

/// The lab with a cube map of `SIZE` texels per side (the course's is [`CUBE_SIZE`]).
const fn recipe<const SIZE: u32>() -> Recipe {
    Recipe::new(
        super::info(lab_name!(), "ref001", "normalization cube map", tangent_bump::KEYS),
        tangent_bump::PARAMS,
        build::<SIZE>,
    )
}

/// The sizes and their labs from one list, so the two cannot disagree.
macro_rules! cube_sizes {
    ($($size:literal),*) => {
        /// The cube-map sizes [`with_cube`] offers (the speed/accuracy study's sweep).
        pub const CUBE_SIZES: [u32; [$($size),*].len()] = [$($size),*];
        static SIZED: [Recipe; CUBE_SIZES.len()] = [$(recipe::<$size>()),*];
    };
}
cube_sizes!(4, 8, 16, 32, 64, 128);

/// `normmap` with a cube map of `size` texels per side, one of [`CUBE_SIZES`] (`None` for
/// another): the lecture's trade between the table's size and its accuracy, for the study.
pub fn with_cube(cx: &BuildContext, size: u32) -> Option<Result<Box<dyn Lab>>> {
    let i = CUBE_SIZES.iter().position(|&s| s == size)?;
    Some(Runner::boxed(cx, &SIZED[i]))
}

fn build<const SIZE: u32>(cx: &BuildContext, p: &Params) -> Result<Box<dyn Scene>> {
    let faces = images::normalization_cube(SIZE);
    let cube = Texture::new(cx.gpu, "normmap.cube", faces.width, faces.height, 6, &[faces.rgba]);
    let clamp = wgpu::AddressMode::ClampToEdge;
    let sampler = sampler(
        cx.gpu,
        "normmap.cube_sampler",
        &SamplerDesc {
            wrap: [clamp; 3],
            ..SamplerDesc::default()
        },
    );
    let unit1 = vec![
        Bind::texture("normMap", &cube),
        Bind::sampler("normMapSampler", &sampler),
    ];
    tangent_bump::build(cx, "normmap", p, &MATERIAL, unit1)
}

/// Texels per side of each face of the normalization cube map.
const CUBE_SIZE: u32 = 32;

static MATERIAL: Material = Material::new(&[ShaderPair::new("bump.vert", "normmap.frag")]);
