//! 2D textures with GL's texture parameters, as seed 004 sets them (`glTexParameteri` wrap,
//! MIN and MAG filters, `glGenerateMipmap`), and the lecture's two pictures: the course's
//! checker and its "BMP" texture (`assets/uvgrid.bmp`, or the user's `--texture FILE`).
//!
//! GL picks the magnification filter where the level of detail λ ≤ 0 and the minification
//! filter where λ > 0, also for the non-mipmapped minification filters `GL_NEAREST` and
//! `GL_LINEAR`, which then read level 0. A wgpu sampler clamped to level 0 (`lod_max_clamp`
//! 0) clamps λ itself and so never minifies; here such a texture is sampled through a view of
//! level 0 alone with an unclamped sampler, so λ — and GL's switch point between the two
//! filters — stays GL's.

use std::path::Path;

use crate::error::{Error, Result};
use crate::geometry::images::{self, Image};
use crate::gpu::Gpu;
use crate::lab::UserFile;
use crate::render::{sampler, Bind, SamplerDesc, Texture};

/// `GL_TEXTURE_MIN_FILTER`, numbered as texparams' `min` parameter.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MinFilter {
    /// `GL_LINEAR_MIPMAP_NEAREST` (the course's).
    LinearMipmapNearest,
    /// `GL_NEAREST` (level 0 only).
    Nearest,
    /// `GL_LINEAR` (level 0 only).
    Linear,
    /// `GL_LINEAR_MIPMAP_LINEAR` (trilinear).
    LinearMipmapLinear,
}

/// The names of [`MinFilter`] in order, for a choice parameter.
pub const MIN_FILTERS: &[&str] = &["linear_mipmap_nearest", "nearest", "linear", "linear_mipmap_linear"];
/// `GL_TEXTURE_MAG_FILTER` names in order (0 `GL_NEAREST`, 1 `GL_LINEAR`).
pub const MAG_FILTERS: &[&str] = &["nearest", "linear"];
/// `GL_TEXTURE_WRAP_*` names in order (0 `GL_REPEAT`, 1 `GL_CLAMP_TO_EDGE`).
pub const WRAPS: &[&str] = &["repeat", "clamp_to_edge"];

impl MinFilter {
    /// The filter with index `i` of [`MIN_FILTERS`].
    pub fn from_index(i: usize) -> MinFilter {
        [
            MinFilter::LinearMipmapNearest,
            MinFilter::Nearest,
            MinFilter::Linear,
            MinFilter::LinearMipmapLinear,
        ][i.min(3)]
    }
}

/// GL texture parameters of one texture.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TexParams {
    /// `GL_TEXTURE_WRAP_S`, `GL_TEXTURE_WRAP_T`: clamp to edge (else repeat).
    pub clamp: [bool; 2],
    /// `GL_TEXTURE_MIN_FILTER`.
    pub min: MinFilter,
    /// `GL_TEXTURE_MAG_FILTER` is `GL_LINEAR` (else `GL_NEAREST`).
    pub mag_linear: bool,
}

impl TexParams {
    /// The course's checker: REPEAT, MIN `GL_LINEAR_MIPMAP_NEAREST`, MAG `GL_NEAREST`.
    pub const CHECKER: TexParams = TexParams {
        clamp: [false, false],
        min: MinFilter::LinearMipmapNearest,
        mag_linear: false,
    };
    /// The course's `loadTextureFromBMP`: REPEAT, MIN `GL_LINEAR_MIPMAP_NEAREST`, MAG `GL_LINEAR`.
    pub const BMP: TexParams = TexParams {
        clamp: [false, false],
        min: MinFilter::LinearMipmapNearest,
        mag_linear: true,
    };

    /// Whether the MIN filter reads the mipmaps.
    pub fn mipmapped(&self) -> bool {
        matches!(self.min, MinFilter::LinearMipmapNearest | MinFilter::LinearMipmapLinear)
    }

    fn sampler_desc(&self) -> SamplerDesc {
        use wgpu::{AddressMode, FilterMode, MipmapFilterMode};
        let wrap = |clamp| {
            if clamp {
                AddressMode::ClampToEdge
            } else {
                AddressMode::Repeat
            }
        };
        let filter = |linear| {
            if linear {
                FilterMode::Linear
            } else {
                FilterMode::Nearest
            }
        };
        let (min, mipmap) = match self.min {
            MinFilter::LinearMipmapNearest => (FilterMode::Linear, MipmapFilterMode::Nearest),
            MinFilter::LinearMipmapLinear => (FilterMode::Linear, MipmapFilterMode::Linear),
            // Level 0 comes from the view (see the module doc); λ stays unclamped.
            MinFilter::Nearest => (FilterMode::Nearest, MipmapFilterMode::Nearest),
            MinFilter::Linear => (FilterMode::Linear, MipmapFilterMode::Nearest),
        };
        SamplerDesc {
            wrap: [wrap(self.clamp[0]), wrap(self.clamp[1]), AddressMode::Repeat],
            mag: filter(self.mag_linear),
            min,
            mipmap: Some(mipmap),
        }
    }
}

/// A 2D texture with its `glGenerateMipmap` levels, and the same texture seen as level 0 alone.
pub struct GlTexture {
    texture: Texture,
    base_level: Texture,
}

impl GlTexture {
    /// Uploads `image` (row 0 first, sampled at t ≈ 0) and its box-filtered mip chain.
    /// `path` names the picture in the error for one larger than the GPU takes.
    pub fn new(gpu: &Gpu, label: &str, image: &Image, path: &Path) -> Result<GlTexture> {
        let max = gpu.device.limits().max_texture_dimension_2d;
        if image.width > max || image.height > max {
            return Err(Error::Image {
                path: path.to_path_buf(),
                source: image::ImageError::Limits(image::error::LimitError::from_kind(
                    image::error::LimitErrorKind::DimensionError,
                )),
            });
        }
        let levels: Vec<Vec<u8>> = images::mip_chain(image).into_iter().map(|level| level.rgba).collect();
        let texture = Texture::new(gpu, label, image.width, image.height, 1, &levels);
        let base_level = Texture {
            texture: texture.texture.clone(),
            view: texture.texture.create_view(&wgpu::TextureViewDescriptor {
                label: Some(&format!("{label}.level0")),
                base_mip_level: 0,
                mip_level_count: Some(1),
                ..Default::default()
            }),
            dimension: texture.dimension,
        };
        Ok(GlTexture { texture, base_level })
    }

    /// The texture bound to the GLSL `texture2D` called `texture` and a sampler with `params`
    /// bound to the `sampler` called `sampler_name`.
    pub fn bind(&self, gpu: &Gpu, texture: &str, sampler_name: &str, params: TexParams) -> [Bind; 2] {
        let levels = if params.mipmapped() {
            &self.texture
        } else {
            &self.base_level
        };
        [
            Bind::texture(texture, levels),
            Bind::sampler(
                sampler_name,
                &sampler(gpu, &format!("{texture}.sampler"), &params.sampler_desc()),
            ),
        ]
    }
}

/// The course's `createTexureChecker()` texture (SPEC §0.1.2) with its mipmaps.
pub fn checker(gpu: &Gpu) -> Result<GlTexture> {
    GlTexture::new(gpu, "texture.checker", &images::checker(), Path::new("checker"))
}

/// The shipped "BMP" texture: the uvgrid of SPEC §0.1.1 as a 24-bit BMP file.
pub const UVGRID_BMP: &[u8] = include_bytes!("../../assets/uvgrid.bmp");
/// Its name in messages.
pub const UVGRID_BMP_PATH: &str = "assets/uvgrid.bmp";

/// A picture in GL's upload order: its bottom row first, so that t = 0 is the bottom of the
/// picture, as the course's BMP loader (which uploads a BMP's bottom-up rows in file order) and
/// OBJ texture coordinates have it.
pub fn bottom_row_first(picture: &Image) -> Image {
    let row = picture.width as usize * 4;
    let mut rgba = Vec::with_capacity(picture.rgba.len());
    for line in picture.rgba.chunks_exact(row.max(1)).rev() {
        rgba.extend_from_slice(line);
    }
    Image {
        width: picture.width,
        height: picture.height,
        layers: picture.layers,
        rgba,
    }
}

/// The "BMP" texture: the user's `--texture`, else `assets/uvgrid.bmp`, decoded and uploaded
/// bottom row first (for the shipped file: exactly the bytes of [`images::uvgrid`]).
pub fn bmp(gpu: &Gpu, user: Option<&UserFile<Image>>) -> Result<GlTexture> {
    match user {
        Some(file) => GlTexture::new(gpu, "texture.user", &bottom_row_first(&file.data), &file.path),
        None => {
            let path = Path::new(UVGRID_BMP_PATH);
            let picture = images::decode_image(path, UVGRID_BMP)?;
            GlTexture::new(gpu, "texture.bmp", &bottom_row_first(&picture), path)
        }
    }
}
