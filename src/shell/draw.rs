//! Drawing a lab into an offscreen target: one place for `--screenshot`, `--record`, F10 and
//! F12 (a leaf of the shell: it uses the lab and the offscreen target, nothing of the shell).

use crate::error::Result;
use crate::gpu::Gpu;
use crate::lab::Lab;
use crate::offscreen::{Offscreen, COLOR_FORMAT};
use crate::render::Frame;

/// Records one frame of `lab` into `target` and submits it.
pub fn render_into(gpu: &Gpu, lab: &mut dyn Lab, target: &Offscreen) -> Result<()> {
    let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("shaderlab.frame"),
    });
    gpu.checked(&format!("{}.render", lab.info().name), || {
        lab.render(&mut Frame::new(
            gpu,
            &mut encoder,
            &target.color,
            &target.depth,
            target.width,
            target.height,
        ))
    })??;
    gpu.queue.submit([encoder.finish()]);
    if let Some(e) = lab.take_error() {
        return Err(e);
    }
    Ok(())
}

/// Renders one frame offscreen at `width` x `height` (RGBA8) and reads it back, top row first.
pub fn screenshot(gpu: &Gpu, lab: &mut dyn Lab, width: u32, height: u32) -> Result<image::RgbaImage> {
    let target = Offscreen::with_format(gpu, width, height, COLOR_FORMAT);
    render_into(gpu, lab, &target)?;
    target.read(gpu)
}
