//! Drawing a lab into an offscreen target: one place for `--screenshot`, `--record`, F10, F12
//! and the debugger's capture (it uses the lab and the offscreen target, nothing above).

use crate::error::Result;
use crate::gpu::Gpu;
use crate::lab::Lab;
use crate::offscreen::{Offscreen, COLOR_FORMAT};
use crate::render::{DrawLog, Frame};

/// Records one frame of `lab` into `target` and submits it.
pub fn render_into(gpu: &Gpu, lab: &mut dyn Lab, target: &Offscreen) -> Result<()> {
    let frame = record(gpu, lab, target, None)?;
    gpu.queue.submit([frame]);
    Ok(())
}

/// Records one frame of `lab` into `target` without submitting it, writing every draw into
/// `log` when given (the debugger's capture: the draws' data can be read back before, or
/// without, the frame running on the GPU). The frame's uniform uploads go with the next
/// submission.
pub fn record(gpu: &Gpu, lab: &mut dyn Lab, target: &Offscreen, log: Option<&DrawLog>) -> Result<wgpu::CommandBuffer> {
    let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("shaderlab.frame"),
    });
    gpu.checked(&format!("{}.render", lab.info().name), || {
        let frame = Frame::new(
            gpu,
            &mut encoder,
            &target.color,
            &target.depth,
            target.width,
            target.height,
        );
        lab.render(&mut match log {
            Some(log) => frame.logged(log),
            None => frame,
        })
    })??;
    if let Some(e) = lab.take_error() {
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
