//! Textures and samplers as data: RGBA8 images (2D or six cube faces) with their mip levels
//! given by the caller, so the bytes are the same on every device (mip levels are built on the
//! CPU, not by a GPU blit), and GL's sampler state expressed as wgpu's.

use std::path::Path;
use std::sync::Arc;

use crate::error::{Error, Result};
use crate::gpu::Gpu;

/// Checks that a `width`×`height` picture fits this device's 2D textures
/// (`max_texture_dimension_2d`; a cube map's faces are 2D images of the same limit), so that a
/// picture too large is an error naming the file (`path`), its size and the limit instead of a
/// wgpu validation panic. Pictures read from files are already held to
/// [`crate::images::MAX_IMAGE_SIDE`], the limit every device offers; this catches a
/// device with a smaller one.
pub fn check_texture_size(gpu: &Gpu, path: &Path, width: u32, height: u32) -> Result<()> {
    texture_size_error(path, width, height, gpu.device.limits().max_texture_dimension_2d).map_or(Ok(()), Err)
}

fn texture_size_error(path: &Path, width: u32, height: u32, max: u32) -> Option<Error> {
    (width > max || height > max).then(|| Error::Io {
        path: path.to_path_buf(),
        source: std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("the picture is {width}x{height} pixels; this GPU takes textures of at most {max} pixels a side"),
        ),
    })
}

/// A texture and its view.
pub struct Texture {
    /// The texture.
    pub texture: wgpu::Texture,
    /// A view of all its levels (and faces).
    pub view: wgpu::TextureView,
    /// A view of level 0 alone (and all faces): what GL's non-mipmapped minification filters
    /// read. See [`Texture::view_for`].
    pub base_view: wgpu::TextureView,
    /// `D2` or `Cube`.
    pub dimension: wgpu::TextureViewDimension,
    /// The texels as uploaded, kept for the debugger's CPU lookups.
    pub texels: Arc<super::Texels>,
}

impl Texture {
    /// An RGBA8 (UNORM, no sRGB: GL's `GL_RGB8`) texture from `levels`, level 0 first; each
    /// level holds `layers` images of its size, row 0 first (uploaded in the order GL's
    /// `glTexImage2D` takes them). `layers` is 1 for a 2D texture and 6 for a cube map
    /// (+X, -X, +Y, -Y, +Z, -Z).
    pub fn new(gpu: &Gpu, label: &str, width: u32, height: u32, layers: u32, levels: &[Vec<u8>]) -> Texture {
        let dimension = if layers == 6 {
            wgpu::TextureViewDimension::Cube
        } else {
            wgpu::TextureViewDimension::D2
        };
        let size = wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: layers,
        };
        let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size,
            mip_level_count: levels.len().max(1) as u32,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba8Unorm,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        for (level, data) in levels.iter().enumerate() {
            let (w, h) = ((width >> level).max(1), (height >> level).max(1));
            gpu.queue.write_texture(
                wgpu::TexelCopyTextureInfo {
                    texture: &texture,
                    mip_level: level as u32,
                    origin: wgpu::Origin3d::ZERO,
                    aspect: wgpu::TextureAspect::All,
                },
                data,
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(4 * w),
                    rows_per_image: Some(h),
                },
                wgpu::Extent3d {
                    width: w,
                    height: h,
                    depth_or_array_layers: layers,
                },
            );
        }
        let view = texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some(&format!("{label}.view")),
            dimension: Some(dimension),
            ..Default::default()
        });
        let base_view = texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some(&format!("{label}.level0")),
            dimension: Some(dimension),
            base_mip_level: 0,
            mip_level_count: Some(1),
            ..Default::default()
        });
        Texture {
            texture,
            view,
            base_view,
            dimension,
            texels: Arc::new(super::Texels {
                width,
                height,
                layers,
                levels: levels.to_vec(),
            }),
        }
    }
}

impl Texture {
    /// The view a sampler with `desc` reads, as GL does: all levels for a mipmapped
    /// minification filter, level 0 alone for `GL_NEAREST`/`GL_LINEAR`. Restricting the view,
    /// not clamping the sampler's level of detail, keeps λ — and with it GL's switch between the
    /// magnification and the minification filter — as GL computes it.
    pub fn view_for(&self, desc: &SamplerDesc) -> &wgpu::TextureView {
        if desc.mipmap.is_some() {
            &self.view
        } else {
            &self.base_view
        }
    }
}

/// GL's texture parameters (`GL_TEXTURE_WRAP_*`, `GL_TEXTURE_MIN/MAG_FILTER`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SamplerDesc {
    /// Wrap along s, t, r (`GL_REPEAT` = Repeat, `GL_CLAMP_TO_EDGE` = ClampToEdge).
    pub wrap: [wgpu::AddressMode; 3],
    /// Magnification filter.
    pub mag: wgpu::FilterMode,
    /// Minification filter within a level.
    pub min: wgpu::FilterMode,
    /// Between levels: `None` for GL's NEAREST / LINEAR (level 0 only: bind
    /// [`Texture::view_for`] this description), else the
    /// `*_MIPMAP_NEAREST` / `*_MIPMAP_LINEAR` choice.
    pub mipmap: Option<wgpu::MipmapFilterMode>,
    /// Anisotropic filtering: samples along the footprint (1: off, as GL without
    /// `EXT_texture_filter_anisotropic`; above 1 all three filters must be linear).
    pub anisotropy: u16,
}

impl Default for SamplerDesc {
    /// REPEAT, LINEAR/LINEAR, no mipmaps.
    fn default() -> Self {
        SamplerDesc {
            wrap: [wgpu::AddressMode::Repeat; 3],
            mag: wgpu::FilterMode::Linear,
            min: wgpu::FilterMode::Linear,
            mipmap: None,
            anisotropy: 1,
        }
    }
}

/// A sampler and the GL state it stands for (what the debugger filters with).
#[derive(Clone, Debug)]
pub struct Sampler {
    /// The sampler.
    pub sampler: wgpu::Sampler,
    /// Its state.
    pub desc: SamplerDesc,
}

/// A sampler for `desc`.
pub fn sampler(gpu: &Gpu, label: &str, desc: &SamplerDesc) -> Sampler {
    let sampler = gpu.device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some(label),
        address_mode_u: desc.wrap[0],
        address_mode_v: desc.wrap[1],
        address_mode_w: desc.wrap[2],
        mag_filter: desc.mag,
        min_filter: desc.min,
        // Without mipmaps GL reads level 0 only: the texture's view does that (`view_for`), so
        // the level of detail stays unclamped and GL's mag/min switch point is kept.
        mipmap_filter: desc.mipmap.unwrap_or(wgpu::MipmapFilterMode::Nearest),
        anisotropy_clamp: desc.anisotropy.max(1),
        ..Default::default()
    });
    Sampler { sampler, desc: *desc }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_texture_beyond_the_device_limit_names_file_size_and_limit() {
        let err = texture_size_error(Path::new("w.png"), 8193, 1, 8192).expect("refused");
        assert_eq!(
            err.to_string(),
            "w.png: the picture is 8193x1 pixels; this GPU takes textures of at most 8192 pixels a side"
        );
        assert!(texture_size_error(Path::new("w.png"), 8192, 8192, 8192).is_none());
        assert!(texture_size_error(Path::new("w.png"), 1, 9000, 8192).is_some());
    }
}
