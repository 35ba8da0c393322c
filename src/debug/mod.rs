//! The GLSL debugger: why a pixel has its colour.
//!
//! A frame is drawn as usual with its draws written down ([`crate::render::DrawLog`]), the
//! buffers they drew from are read back ([`capture`]), and the frame is replayed on the CPU for
//! one pixel ([`mod@replay`]): the vertex shader over every vertex for the positions, the
//! rasteriser's coverage, depth test and `discard` for which fragment stays ([`raster`]), then
//! that fragment traced — its triangle's corners through the vertex shader and its 2×2 quad
//! through the fragment shader ([`interp`], naga's IR of the very module the pipeline was built
//! from, with textures filtered on the CPU by [`sample`]). Each step names the file and line of
//! the GLSL the user edits (through `#include`s and the course translator's source map).
//!
//! [`Inspection`] is the result, the report (its own file, `report.rs`): the stored pixel, the
//! covering draw and primitive, the corner values, the interpolated inputs and the steps;
//! [`Inspection::text`] and [`Inspection::json`] write it for people and programs. This file
//! is the module's face: the capture that starts an inspection, and the placing of a step in
//! the user's file and under the user's names.

pub mod capture;
pub mod diff;
pub mod error;
pub mod instrument;
pub mod interp;
mod math;
pub mod paint;
pub mod picture;
pub mod positions;
pub mod raster;
pub mod replay;
mod report;
pub mod sample;
pub mod value;
pub mod view;

use crate::error::Result;
use crate::shader::CompiledShader;

pub use capture::{Captured, CapturedDraw, Pending};
pub use replay::{replay, Fragment, Named, Replayed};
pub use report::{caveats, json_number, Dropped, Inspection, Row, Stage, TraceStep, GPU_TOLERANCE};

/// The file and line of a span of `shader`'s source (through its includes or source map).
pub fn locate(shader: &CompiledShader, span: naga::Span) -> Option<(String, u32)> {
    let range = span.to_range()?;
    if range.start == 0 && range.end == 0 {
        return None;
    }
    let text = &shader.source.text;
    let start = range.start.min(text.len());
    let line = text.as_bytes()[..start].iter().filter(|&&b| b == b'\n').count() as u32 + 1;
    Some(shader.source.origin(line))
}

/// The text of `line` of `file` as its author wrote it.
pub fn source_line<'s>(shader: &'s CompiledShader, file: &str, line: u32) -> Option<&'s str> {
    let (_, text) = shader.source.files.iter().find(|(p, _)| p == file)?;
    text.lines().nth(line.checked_sub(1)? as usize)
}

/// A name of `shader` as the user wrote it: a translated shader's through the translator's
/// rule ([`crate::legacy::names::user_name`]), any other's as it is.
pub fn user_name(shader: &CompiledShader, name: &str) -> String {
    if shader.translated {
        crate::legacy::names::user_name(name)
    } else {
        name.to_owned()
    }
}

/// Encodes one frame of `lab` at `width` × `height` offscreen (in `format`, the one its
/// pipelines were built for) with its draws written down, without running it, and starts
/// reading their buffers back: the target and the frame (to submit for its picture) come with
/// the read-back.
fn encode_logged(
    gpu: &crate::gpu::Gpu,
    lab: &mut dyn crate::lab::Lab,
    (width, height): (u32, u32),
    format: wgpu::TextureFormat,
) -> Result<(crate::offscreen::Offscreen, wgpu::CommandBuffer, Pending)> {
    let target = crate::offscreen::Offscreen::with_format(gpu, width, height, format);
    let log = crate::render::DrawLog::new();
    let frame = crate::lab::frame::encode(gpu, lab, &target, Some(&log))?;
    let pending = Pending::start(gpu, &log);
    Ok((target, frame, pending))
}

/// Starts a capture of `lab`'s frame at `size` in the screen's `format` (the window's and the
/// page's inspector): recorded again offscreen with its draws written down, its buffers read
/// back while the shell goes on ([`Pending::ready`], then [`Pending::finish`]), and the frame
/// then run offscreen for the picture the GPU stores ([`Captured::picture`], each inspection's
/// `gpu_pixel`). The same state draws the same frame, so this is the frame on screen.
pub fn capture_start(
    gpu: &crate::gpu::Gpu,
    lab: &mut dyn crate::lab::Lab,
    size: (u32, u32),
    format: wgpu::TextureFormat,
) -> Result<Pending> {
    let (target, frame, pending) = encode_logged(gpu, lab, size, format)?;
    Ok(pending.draw(gpu, target, frame))
}

/// A frame of a lab recorded with its draws written down and brought to the CPU, not yet
/// run: a shader that never ends can be replayed before the GPU is asked to draw it.
#[cfg(not(target_arch = "wasm32"))]
pub struct Capture {
    /// The frame's draws on the CPU.
    pub captured: Captured,
    target: crate::offscreen::Offscreen,
    frame: wgpu::CommandBuffer,
}

#[cfg(not(target_arch = "wasm32"))]
impl Capture {
    /// Encodes one frame of `lab` at `width` × `height` with its draws written down and brings
    /// them to the CPU, without running it.
    pub fn encode(gpu: &crate::gpu::Gpu, lab: &mut dyn crate::lab::Lab, width: u32, height: u32) -> Result<Capture> {
        let (target, frame, pending) = encode_logged(gpu, lab, (width, height), crate::offscreen::COLOR_FORMAT)?;
        let captured = pending.wait(gpu)?;
        Ok(Capture {
            captured,
            target,
            frame,
        })
    }

    /// Runs the recorded frame and reads back what the GPU drew (as `--screenshot` writes
    /// it), kept in [`Captured::picture`] too; a frame that never ends is the watchdog's
    /// [`crate::error::Error::Hang`].
    pub fn draw(mut self, gpu: &crate::gpu::Gpu) -> Result<(image::RgbaImage, Captured)> {
        gpu.queue.submit([self.frame]);
        let image = self.target.read(gpu)?;
        self.captured.picture = Some(std::sync::Arc::new(image.clone()));
        Ok((image, self.captured))
    }
}

/// Encodes one frame of `lab` at `width` × `height` with its draws written down and brings
/// them to the CPU before running the frame on the GPU (so that a shader that never ends can
/// still be captured); with `picture`, then runs it and reads back what the GPU drew (as
/// `--screenshot` would write it, and in [`Captured::picture`]).
#[cfg(not(target_arch = "wasm32"))]
pub fn capture_lab(
    gpu: &crate::gpu::Gpu,
    lab: &mut dyn crate::lab::Lab,
    width: u32,
    height: u32,
    picture: bool,
) -> Result<(Option<image::RgbaImage>, Captured)> {
    let capture = Capture::encode(gpu, lab, width, height)?;
    if !picture {
        return Ok((None, capture.captured));
    }
    let (image, captured) = capture.draw(gpu)?;
    Ok((Some(image), captured))
}
