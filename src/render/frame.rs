//! One frame being recorded: the encoder and the target, for window, offscreen and tests alike.

use crate::gpu::Gpu;
use crate::offscreen::DEPTH_FORMAT;

use super::log::{DrawLog, Scissor, Viewport};

/// What a render pass does with the target first.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Load {
    /// Clear colour to this RGB (alpha 1) and depth to 1 (`glClear`).
    Clear([f64; 3]),
    /// Keep what earlier passes drew.
    Keep,
}

/// Where and with what a lab records one frame.
pub struct Frame<'a> {
    /// The device and queue (uniform uploads before the pass).
    pub gpu: &'a Gpu,
    /// The encoder the passes go into; the shell submits it.
    pub encoder: &'a mut wgpu::CommandEncoder,
    /// Colour target.
    pub color: &'a wgpu::TextureView,
    /// Depth target ([`DEPTH_FORMAT`]).
    pub depth: &'a wgpu::TextureView,
    /// Target width in pixels.
    pub width: u32,
    /// Target height in pixels.
    pub height: u32,
    /// Timestamp writes for the first pass (`--bench --gpu-time`), taken by [`Frame::pass`].
    pub timestamps: Option<wgpu::RenderPassTimestampWrites<'a>>,
    /// Where the draws are written down, when the debugger asks ([`DrawLog`]).
    pub log: Option<&'a DrawLog>,
}

impl<'a> Frame<'a> {
    /// A frame drawn into `color` and `depth` (`width` × `height`), recorded into `encoder`.
    pub fn new(
        gpu: &'a Gpu,
        encoder: &'a mut wgpu::CommandEncoder,
        color: &'a wgpu::TextureView,
        depth: &'a wgpu::TextureView,
        width: u32,
        height: u32,
    ) -> Frame<'a> {
        Frame {
            gpu,
            encoder,
            color,
            depth,
            width,
            height,
            timestamps: None,
            log: None,
        }
    }

    /// With every draw written down in `log` (what the debugger replays on the CPU).
    pub fn logged(self, log: &'a DrawLog) -> Frame<'a> {
        Frame { log: Some(log), ..self }
    }

    /// Begins a render pass over the whole target.
    pub fn pass(&mut self, label: &str, load: Load) -> Pass<'_> {
        let (color_load, depth_load) = match load {
            Load::Clear([r, g, b]) => (
                wgpu::LoadOp::Clear(wgpu::Color { r, g, b, a: 1.0 }),
                wgpu::LoadOp::Clear(1.0),
            ),
            Load::Keep => (wgpu::LoadOp::Load, wgpu::LoadOp::Load),
        };
        let _ = DEPTH_FORMAT; // the depth view is always of this format
        if let Some(log) = self.log {
            log.begin_pass(load, self.width, self.height);
        }
        let pass = self.encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(label),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: self.color,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: color_load,
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: self.depth,
                depth_ops: Some(wgpu::Operations {
                    load: depth_load,
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: self.timestamps.take(),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        Pass {
            pass,
            log: self.log,
            viewport: Viewport::whole(self.width, self.height),
            scissor: [0, 0, self.width, self.height],
        }
    }

    /// Width over height as the originals compute it: `(float)w / h`, height 0 taken as 1.
    pub fn aspect(&self) -> f32 {
        self.width as f32 / self.height.max(1) as f32
    }
}

/// A render pass of a [`Frame`]: wgpu's pass, the frame's [`DrawLog`] when the debugger asked
/// for one ([`Program::draw`](super::Program::draw) writes each draw into it), and the pass
/// state a draw is written down with. Labs change that state through the pass's own methods,
/// never wgpu's, so what the debugger replays is what the GPU drew.
pub struct Pass<'p> {
    pass: wgpu::RenderPass<'p>,
    log: Option<&'p DrawLog>,
    viewport: Viewport,
    scissor: Scissor,
}

impl<'p> Pass<'p> {
    /// Where the draws that follow land (`glViewport`, `glDepthRange`).
    pub fn set_viewport(&mut self, viewport: Viewport) {
        let Viewport {
            x,
            y,
            width,
            height,
            min_depth,
            max_depth,
        } = viewport;
        self.pass.set_viewport(x, y, width, height, min_depth, max_depth);
        self.viewport = viewport;
    }

    /// The pixels the draws that follow may write (`glScissor`).
    pub fn set_scissor(&mut self, scissor: Scissor) {
        let [x, y, width, height] = scissor;
        self.pass.set_scissor_rect(x, y, width, height);
        self.scissor = scissor;
    }

    /// The viewport the next draw lands in.
    pub fn viewport(&self) -> Viewport {
        self.viewport
    }

    /// The scissor rectangle of the next draw.
    pub fn scissor(&self) -> Scissor {
        self.scissor
    }

    /// Where draws are written down.
    pub(crate) fn log(&self) -> Option<&'p DrawLog> {
        self.log
    }

    /// wgpu's pass, for the draw calls themselves.
    pub(crate) fn raw(&mut self) -> &mut wgpu::RenderPass<'p> {
        &mut self.pass
    }
}
