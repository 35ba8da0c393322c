//! Offscreen rendering: a colour and depth target, readback to an RGBA image, PNG export.
//!
//! The colour format is `Rgba8Unorm`, not an sRGB one: GL's default framebuffer does no sRGB
//! encoding, so this is what matches the original's pixels. Readback gives the top row first
//! (glReadPixels gives the bottom row first; the reference PNGs are stored top row first too).

use std::path::Path;

use crate::error::{Error, Result};
use crate::gpu::Gpu;

use crate::gpu::targets::depth_texture;
pub use crate::gpu::targets::{
    copyable_color, padded_row, readback_buffer, target_descriptor, COLOR_FORMAT, DEPTH_FORMAT,
};

/// An offscreen colour + depth target that can be read back.
pub struct Offscreen {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    texture: wgpu::Texture,
    /// View of the colour texture.
    pub color: wgpu::TextureView,
    /// View of the depth texture.
    pub depth: wgpu::TextureView,
    readback: wgpu::Buffer,
    padded_row: u32,
    format: wgpu::TextureFormat,
}

impl Offscreen {
    /// The colour format it draws in.
    pub fn format(&self) -> wgpu::TextureFormat {
        self.format
    }

    /// A target of `width` x `height` (each at least 1) in [`COLOR_FORMAT`].
    pub fn new(gpu: &Gpu, width: u32, height: u32) -> Self {
        Self::with_format(gpu, width, height, COLOR_FORMAT)
    }

    /// A target in `format`: `Rgba8Unorm` or `Bgra8Unorm` (a window's format, for screenshots
    /// drawn by the window's pipelines); readback always gives RGBA.
    pub fn with_format(gpu: &Gpu, width: u32, height: u32, format: wgpu::TextureFormat) -> Self {
        let (width, height) = (width.max(1), height.max(1));
        let (texture, color) = copyable_color(&gpu.device, "shaderlab.offscreen.color", width, height, format);
        let depth = depth_texture(&gpu.device, width, height);
        let padded_row = padded_row(format.block_copy_size(None).unwrap_or(4), width);
        let readback = readback_buffer(&gpu.device, "shaderlab.offscreen.readback", padded_row, height);
        Offscreen {
            width,
            height,
            texture,
            color,
            depth,
            readback,
            padded_row,
            format,
        }
    }

    /// Copies the colour target to the CPU (top row first) as 8-bit RGBA.
    pub fn read(&self, gpu: &Gpu) -> Result<image::RgbaImage> {
        if self.format == wgpu::TextureFormat::Rgba32Float {
            let pixels = self.read_f32(gpu)?;
            let bytes = pixels
                .iter()
                .flat_map(|p| p.map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8))
                .collect();
            return image::RgbaImage::from_raw(self.width, self.height, bytes).ok_or_else(|| Error::Wgpu {
                context: "reading back the image".into(),
                message: "short buffer".into(),
            });
        }
        self.map_and_wait(gpu)?;
        self.mapped_rgba()
    }

    /// Copies an `Rgba32Float` target to the CPU: the shader's outputs before any 8-bit rounding
    /// or clamping, so NaN and infinity can be seen.
    pub fn read_f32(&self, gpu: &Gpu) -> Result<Vec<[f32; 4]>> {
        if self.format != wgpu::TextureFormat::Rgba32Float {
            return Err(Error::Param(format!(
                "read_f32 needs an Rgba32Float target, not {:?}",
                self.format
            )));
        }
        let bytes = self.read_rows(gpu, 16)?;
        Ok(bytes
            .chunks_exact(16)
            .map(|p| std::array::from_fn(|c| f32::from_ne_bytes([p[4 * c], p[4 * c + 1], p[4 * c + 2], p[4 * c + 3]])))
            .collect())
    }

    fn read_rows(&self, gpu: &Gpu, bytes_per_pixel: u32) -> Result<Vec<u8>> {
        self.map_and_wait(gpu)?;
        self.mapped_rows(bytes_per_pixel)
    }

    /// [`Offscreen::request_read`], blocking until the buffer is mapped.
    fn map_and_wait(&self, gpu: &Gpu) -> Result<()> {
        // The frame first, under the watchdog: on lavapipe a submit behind a frame that never
        // ends blocks in the driver, where no timeout reaches.
        if gpu.watchdog.is_some() {
            gpu.wait()?;
        }
        let (tx, rx) = std::sync::mpsc::channel();
        self.request_read(gpu, move |r| {
            let _ = tx.send(r);
        });
        gpu.wait()?;
        rx.recv()
            .map_err(|e| read_error(e.to_string()))?
            .map_err(|e| read_error(e.to_string()))
    }

    /// Copies the colour target into the readback buffer and asks for it to be mapped;
    /// `mapped` is called once it is (or with why not), after which [`Offscreen::mapped_rgba`]
    /// has the pixels. [`Offscreen::read`] waits for it; a browser cannot wait, and polls.
    pub fn request_read(
        &self,
        gpu: &Gpu,
        mapped: impl FnOnce(std::result::Result<(), wgpu::BufferAsyncError>) + wgpu::WasmNotSend + 'static,
    ) {
        let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("shaderlab.offscreen.copy"),
        });
        crate::gpu::targets::copy_to_buffer(
            &mut encoder,
            &self.texture,
            &self.readback,
            self.padded_row,
            (self.width, self.height),
        );
        gpu.queue.submit([encoder.finish()]);
        self.readback.slice(..).map_async(wgpu::MapMode::Read, mapped);
    }

    /// The pixels of an 8-bit target once [`Offscreen::request_read`] has mapped them, as RGBA
    /// with the top row first; the buffer is unmapped for the next read.
    pub fn mapped_rgba(&self) -> Result<image::RgbaImage> {
        let mut pixels = self.mapped_rows(4)?;
        if matches!(
            self.format,
            wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb
        ) {
            pixels.chunks_exact_mut(4).for_each(|p| p.swap(0, 2));
        }
        image::RgbaImage::from_raw(self.width, self.height, pixels).ok_or_else(|| read_error("short buffer".into()))
    }

    fn mapped_rows(&self, bytes_per_pixel: u32) -> Result<Vec<u8>> {
        let row_bytes = (bytes_per_pixel * self.width) as usize;
        let mut pixels = Vec::with_capacity(row_bytes * self.height as usize);
        {
            let data = self
                .readback
                .slice(..)
                .get_mapped_range()
                .map_err(|e| read_error(e.to_string()))?;
            for row in data.chunks(self.padded_row as usize).take(self.height as usize) {
                pixels.extend_from_slice(&row[..row_bytes]);
            }
        }
        self.readback.unmap();
        Ok(pixels)
    }
}

fn read_error(message: String) -> Error {
    Error::Wgpu {
        context: "reading back the image".into(),
        message,
    }
}

/// Drops alpha: the original's window is RGB, and so are the reference images.
pub fn to_rgb(image: &image::RgbaImage) -> image::RgbImage {
    image::DynamicImage::ImageRgba8(image.clone()).to_rgb8()
}

/// Writes an RGB PNG. The path is checked first ([`check_png_path`](crate::fsutil::check_png_path):
/// a `.png` name, not a directory, in a directory that exists), then the file is written
/// all at once ([`write_atomic`](crate::fsutil::write_atomic)): a failure leaves an existing
/// file as it was.
pub fn save_png(image: &image::RgbaImage, path: &Path) -> Result<()> {
    crate::fsutil::check_png_path(path)?;
    crate::fsutil::write_atomic(path, |out| write_png(image, out))
}

/// Encodes `image` as an RGB PNG (alpha dropped, see [`to_rgb`]) into `out`.
pub fn write_png(image: &image::RgbaImage, out: &mut dyn std::io::Write) -> std::io::Result<()> {
    use image::ImageEncoder;
    let rgb = to_rgb(image);
    image::codecs::png::PngEncoder::new(out)
        .write_image(rgb.as_raw(), rgb.width(), rgb.height(), image::ExtendedColorType::Rgb8)
        .map_err(|e| match e {
            image::ImageError::IoError(e) => e,
            e => std::io::Error::other(e),
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fsutil::sorted_names;
    use std::fs;

    fn test_dir(name: &str) -> crate::fsutil::ScratchDir {
        crate::fsutil::ScratchDir::new(&format!("offscreen-{name}"))
    }

    #[test]
    fn save_png_refuses_other_formats_and_keeps_the_file() {
        let dir = test_dir("formats");
        let image = image::RgbaImage::from_pixel(4, 3, image::Rgba([10, 20, 30, 255]));
        for name in ["x.jpg", "x.bmp", "x.gif", "x.tiff", "x"] {
            let path = dir.join(name);
            fs::write(&path, b"a holiday photo").unwrap();
            let err = save_png(&image, &path).unwrap_err();
            assert!(matches!(err, Error::Param(_)), "{name}: {err:?}");
            assert!(
                err.to_string().contains("only PNG is written; use a .png name"),
                "{name}: {err}"
            );
            assert_eq!(fs::read(&path).unwrap(), b"a holiday photo", "{name} was touched");
        }
        assert_eq!(sorted_names(&dir), ["x", "x.bmp", "x.gif", "x.jpg", "x.tiff"]);
    }

    #[test]
    fn save_png_writes_replaces_and_rejects_directories() {
        let dir = test_dir("write");
        let image = image::RgbaImage::from_pixel(4, 3, image::Rgba([10, 20, 30, 255]));
        let path = dir.join("shot.PNG");
        fs::write(&path, b"old").unwrap();
        save_png(&image, &path).unwrap();
        let back = image::open(&path).unwrap().to_rgb8();
        assert_eq!(back.dimensions(), (4, 3));
        assert_eq!(back.get_pixel(1, 1).0, [10, 20, 30]);
        assert_eq!(sorted_names(&dir), ["shot.PNG"]);
        fs::create_dir(dir.join("d.png")).unwrap();
        let err = save_png(&image, &dir.join("d.png")).unwrap_err();
        assert!(err.to_string().contains("is a directory"), "{err}");
        let err = save_png(&image, &dir.join("missing/x.png")).unwrap_err();
        assert!(err.to_string().contains("does not exist"), "{err}");
    }
}
