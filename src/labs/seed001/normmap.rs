//! Seed 001 `normmap` (SPEC §1.12): the `bump` lab with a normalization cube map. The lecture's
//! idea — store the normalized value of every direction in a cube map, so a lookup replaces
//! sqrt, multiplications and additions — replaces `normalize(L)` by `2·textureCube(normMap,
//! L) − 1`. The cube map (SPEC §0.1) is 32×32 per face, `GL_LINEAR`, `GL_CLAMP_TO_EDGE`,
//! seamless, on unit 1. The image matches `bump` up to the 8-bit quantization of the lookup.
//!
//! Keys: as `bump` (light keys move blx, bly, blz; left drag rotates).

use crate::geometry::images;
use crate::lab::{Look, Pass, Recipe};
use crate::render::{sampler, Bind, SamplerDesc, Texture};

use crate::labs::seed001::tangent_bump;

/// Seed 001, §1.12: `bump` with the cube map on unit 1.
pub static RECIPE: Recipe = Recipe {
    info: super::info("normmap", "ref001", "normalization cube map", tangent_bump::KEYS),
    params: tangent_bump::PARAMS,
    animated: false,
    title: None,
    build: |cx, p| {
        let faces = images::normalization_cube(CUBE_SIZE);
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
        tangent_bump::build(cx, "normmap", p, &LOOK, unit1)
    },
};

/// Texels per side of each face of the normalization cube map.
const CUBE_SIZE: u32 = 32;

static LOOK: Look = Look::new(&[Pass::new("bump.vert", "normmap.frag")]);
