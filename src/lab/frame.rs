//! One frame of a lab: drawn into views it is given ([`draw`], which the shells' session and
//! everything offscreen go through), offscreen ([`encode`], [`render_into`]: `--screenshot`,
//! `--record`, F10, F12 and the debugger's capture), and read back ([`screenshot`]). It uses
//! the lab and the render targets, nothing above.

use crate::error::{Error, Result};
use crate::gpu::Gpu;
use crate::lab::Lab;
use crate::offscreen::{Offscreen, COLOR_FORMAT};
use crate::render::{DrawLog, Frame};

/// Encodes one frame of `lab` into `encoder`, drawing into `color` with its `depth` buffer,
/// `width` × `height` pixels, writing every draw into `log` when given; under [`Gpu::checked`],
/// so an error wgpu reports, or a panic inside it, comes back rather than reaching the device's
/// handler. `Err` when the frame failed; `Ok(Some(e))` when it was drawn but the lab found `e`
/// while drawing (a shading model whose shader is broken: the last good pipeline drew).
pub fn draw(
    gpu: &Gpu,
    encoder: &mut wgpu::CommandEncoder,
    lab: &mut dyn Lab,
    color: &wgpu::TextureView,
    depth: &wgpu::TextureView,
    (width, height): (u32, u32),
    log: Option<&DrawLog>,
) -> Result<Option<Error>> {
    gpu.checked(&format!("{}.render", lab.info().name), || {
        let frame = Frame::new(gpu, encoder, color, depth, width, height);
        lab.render(&mut match log {
            Some(log) => frame.logged(log),
            None => frame,
        })
    })??;
    Ok(lab.take_error())
}

/// Encodes one frame of `lab` into `target` and submits it.
pub fn render_into(gpu: &Gpu, lab: &mut dyn Lab, target: &Offscreen) -> Result<()> {
    let frame = encode(gpu, lab, target, None)?;
    gpu.queue.submit([frame]);
    Ok(())
}

/// Encodes one frame of `lab` into `target` without submitting it, writing every draw into
/// `log` when given (the debugger's capture: the draws' data can be read back before, or
/// without, the frame running on the GPU). The frame's uniform uploads go with the next
/// submission. An error the lab found while drawing fails the frame.
pub fn encode(gpu: &Gpu, lab: &mut dyn Lab, target: &Offscreen, log: Option<&DrawLog>) -> Result<wgpu::CommandBuffer> {
    let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("shaderlab.frame"),
    });
    let size = (target.width, target.height);
    if let Some(e) = draw(gpu, &mut encoder, lab, &target.color, &target.depth, size, log)? {
        return Err(e);
    }
    Ok(encoder.finish())
}

/// Renders one frame offscreen at `width` x `height` (RGBA8) and reads it back, top row first.
pub fn screenshot(gpu: &Gpu, lab: &mut dyn Lab, width: u32, height: u32) -> Result<image::RgbaImage> {
    let target = Offscreen::with_format(gpu, width, height, COLOR_FORMAT);
    render_into(gpu, lab, &target)?;
    target.read(gpu)
}
