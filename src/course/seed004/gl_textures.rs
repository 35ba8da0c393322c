//! 2D textures with GL's texture parameters, as seed 004 sets them (`glTexParameteri` wrap,
//! MIN and MAG filters, `glGenerateMipmap`), and the lecture's two pictures: the course's
//! checker and its "BMP" texture (`assets/uvgrid.bmp`, or the user's `--texture FILE`); and
//! the scene of the labs that sample them ([`Sampled`]), switching textures and parameters.
//!
//! GL picks the magnification filter where the level of detail λ ≤ 0 and the minification
//! filter where λ > 0, also for the non-mipmapped minification filters `GL_NEAREST` and
//! `GL_LINEAR`, which then read level 0: `render::Texture::view_for` binds level 0 alone for
//! those, with the level of detail unclamped, so GL's switch point stays GL's.

use std::path::Path;

use crate::error::Result;
use crate::gpu::Gpu;
use crate::images::{self, Image};
use crate::lab::{BuildContext, Geometry, Input, Scene, ShaderPair, UserFile};
use crate::params::Params;
use crate::render::{sampler, AnyProgram, Bind, Frame, Load, Program, SamplerDesc, Texture};

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
    /// `GL_TEXTURE_MAX_ANISOTROPY_EXT` (a port addition; 1: off). Above 1 the sampler is
    /// trilinear whatever `min` and `mag` say, as anisotropic filtering requires.
    pub anisotropy: u16,
}

impl TexParams {
    /// The course's checker: REPEAT, MIN `GL_LINEAR_MIPMAP_NEAREST`, MAG `GL_NEAREST`.
    pub const CHECKER: TexParams = TexParams {
        clamp: [false, false],
        min: MinFilter::LinearMipmapNearest,
        mag_linear: false,
        anisotropy: 1,
    };
    /// The course's `loadTextureFromBMP`: REPEAT, MIN `GL_LINEAR_MIPMAP_NEAREST`, MAG `GL_LINEAR`.
    pub const BMP: TexParams = TexParams {
        clamp: [false, false],
        min: MinFilter::LinearMipmapNearest,
        mag_linear: true,
        anisotropy: 1,
    };

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
            MinFilter::LinearMipmapNearest => (FilterMode::Linear, Some(MipmapFilterMode::Nearest)),
            MinFilter::LinearMipmapLinear => (FilterMode::Linear, Some(MipmapFilterMode::Linear)),
            // Level 0 alone: `view_for` binds it.
            MinFilter::Nearest => (FilterMode::Nearest, None),
            MinFilter::Linear => (FilterMode::Linear, None),
        };
        if self.anisotropy > 1 {
            return SamplerDesc {
                wrap: [wrap(self.clamp[0]), wrap(self.clamp[1]), AddressMode::Repeat],
                mag: FilterMode::Linear,
                min: FilterMode::Linear,
                mipmap: Some(MipmapFilterMode::Linear),
                anisotropy: self.anisotropy,
            };
        }
        SamplerDesc {
            wrap: [wrap(self.clamp[0]), wrap(self.clamp[1]), AddressMode::Repeat],
            mag: filter(self.mag_linear),
            min,
            mipmap,
            anisotropy: 1,
        }
    }
}

/// A 2D texture with its `glGenerateMipmap` levels.
pub struct GlTexture {
    texture: Texture,
}

impl GlTexture {
    /// Uploads `image` (row 0 first, sampled at t ≈ 0) and its box-filtered mip chain.
    /// `path` names the picture in the error for one larger than the GPU takes.
    pub fn new(gpu: &Gpu, label: &str, image: &Image, path: &Path) -> Result<GlTexture> {
        crate::render::check_texture_size(gpu, path, image.width, image.height)?;
        let levels: Vec<Vec<u8>> = images::mip_chain(image).into_iter().map(|level| level.rgba).collect();
        let texture = Texture::new(gpu, label, image.width, image.height, 1, &levels);
        Ok(GlTexture { texture })
    }

    /// The texture bound to the GLSL `texture2D` called `texture` and a sampler with `params`
    /// bound to the `sampler` called `sampler_name`.
    pub fn bind(&self, gpu: &Gpu, texture: &str, sampler_name: &str, params: TexParams) -> [Bind; 2] {
        let desc = params.sampler_desc();
        [
            Bind::texture_for(texture, &self.texture, &desc),
            Bind::sampler(sampler_name, &sampler(gpu, &format!("{texture}.sampler"), &desc)),
        ]
    }
}

/// The course's `createTexureChecker()` texture (SPEC §0.1.2) with its mipmaps.
pub fn checker(gpu: &Gpu) -> Result<GlTexture> {
    GlTexture::new(gpu, "texture.checker", &images::checker(), Path::new("checker"))
}

/// The shipped "BMP" texture: the uvgrid of SPEC §0.1.1 as a 24-bit BMP file.
pub const UVGRID_BMP: &[u8] = include_bytes!("../../../assets/uvgrid.bmp");
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

/// A geometry drawn by one shader pair sampling texture unit 0 (`tex`, `tex_sampler`): the texture and
/// the GL parameters `pick` chooses for the parameters, bound again when they change
/// (`glBindTexture`, `glTexParameteri`).
pub struct Sampled<S: Geometry> {
    label: String,
    geometry: S,
    program: Program<S::Vertex>,
    textures: Vec<GlTexture>,
    pick: fn(&Params) -> (usize, TexParams),
    bound: Option<(usize, TexParams)>,
}

impl<S: Geometry> Sampled<S> {
    /// Compiles `pair`; the first frame binds the geometry's blocks and the texture picked.
    pub fn build(
        cx: &BuildContext,
        name: &str,
        geometry: S,
        pair: ShaderPair,
        textures: Vec<GlTexture>,
        pick: fn(&Params) -> (usize, TexParams),
    ) -> Result<Box<dyn Scene>> {
        Ok(Box::new(Sampled {
            label: name.to_owned(),
            geometry,
            program: Program::new(cx, name, pair.vert, pair.frag, pair.state)?,
            textures,
            pick,
            bound: None,
        }))
    }
}

impl<S: Geometry> Scene for Sampled<S> {
    fn input(&mut self, p: &mut Params, input: Input) -> bool {
        self.geometry.input(p, input)
    }
    fn programs(&mut self) -> Vec<&mut dyn AnyProgram> {
        vec![&mut self.program]
    }
    fn render(&mut self, p: &Params, frame: &mut Frame<'_>) -> Result<()> {
        let want = (self.pick)(p);
        if self.bound != Some(want) {
            let (i, params) = want;
            let mut binds = self.geometry.binds();
            binds.extend(self.textures[i].bind(frame.gpu, "tex", "tex_sampler", params));
            self.program.bind(frame.gpu, binds)?;
            self.bound = Some(want);
        }
        let mesh = self.geometry.prepare(frame.gpu, p, frame.width, frame.height);
        let mut pass = frame.pass(&self.label, Load::Clear([0.0; 3]));
        self.program.draw(&mut pass, mesh);
        Ok(())
    }
}
