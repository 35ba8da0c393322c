//! What the window and the page both do with the surface they draw into, from start to end: a
//! [`Swapchain`] chooses the surface's format, configures it, keeps the depth buffer of its
//! size, follows resizes and acquires each frame's texture; [`on_trouble`] hears from the
//! device when it fails. What a shell does about an outdated or lost surface is its own (the
//! window asks its window for the size and makes a lost surface anew; the page configures the
//! canvas's surface again).

use std::sync::Arc;

use crate::error::{Error, Result};
use crate::gpu::targets::depth_texture;
use crate::gpu::Gpu;

/// A surface configured to draw into, and the depth buffer of its size.
pub struct Swapchain {
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    depth: wgpu::TextureView,
}

/// What [`Swapchain::acquire`] found.
pub enum Acquired {
    /// The frame's texture, to draw into and present.
    Frame(wgpu::SurfaceTexture),
    /// No frame this time (the surface timed out or is occluded): draw at the next chance.
    Skipped,
    /// The surface no longer matches its window: configure it again ([`Swapchain::resize`]).
    Outdated,
    /// The surface is lost: make it anew ([`Swapchain::renew`]), or configure it again.
    Lost,
    /// wgpu reported an error getting the texture (the device's error handler said which).
    Invalid,
}

impl Swapchain {
    /// `surface` (`what` names it in errors: `the window surface`, `the canvas`) configured for
    /// `gpu` at `size` (each side clamped to 1..=the device's largest
    /// texture) in its plain UNORM [`format`], presenting with the first of `present_modes` it
    /// offers (else `Fifo`), with a depth buffer of its size. A surface with no formats, or one
    /// that cannot be configured, is an error.
    pub fn new(
        gpu: &Gpu,
        what: &str,
        surface: wgpu::Surface<'static>,
        size: (u32, u32),
        present_modes: &[wgpu::PresentMode],
    ) -> Result<Swapchain> {
        let caps = surface.get_capabilities(&gpu.adapter);
        let format = format(&caps).ok_or_else(|| Error::Surface(format!("{what} supports no formats")))?;
        let present_mode = present_modes
            .iter()
            .copied()
            .find(|m| caps.present_modes.contains(m))
            .unwrap_or(wgpu::PresentMode::Fifo);
        let max = gpu.device.limits().max_texture_dimension_2d;
        let config = config(&caps, format, size, max, present_mode);
        // A surface that was never configured makes wgpu panic on the first frame: check it.
        gpu.checked(&format!("configuring {what}"), || {
            surface.configure(&gpu.device, &config)
        })?;
        let depth = depth_texture(&gpu.device, config.width, config.height);
        Ok(Swapchain { surface, config, depth })
    }

    /// The colour format the lab's pipelines draw in.
    pub fn format(&self) -> wgpu::TextureFormat {
        self.config.format
    }

    /// The size frames are drawn at.
    pub fn size(&self) -> (u32, u32) {
        (self.config.width, self.config.height)
    }

    /// The depth buffer of the frames' size.
    pub fn depth(&self) -> &wgpu::TextureView {
        &self.depth
    }

    /// Configures the surface again at `size` (each side clamped to 1..=the device's largest
    /// texture), with a depth buffer of that size.
    pub fn resize(&mut self, gpu: &Gpu, (width, height): (u32, u32)) {
        let max = gpu.device.limits().max_texture_dimension_2d;
        self.config.width = width.clamp(1, max);
        self.config.height = height.clamp(1, max);
        self.surface.configure(&gpu.device, &self.config);
        self.depth = depth_texture(&gpu.device, self.config.width, self.config.height);
    }

    /// Draws through `surface` from now on, the lost one's replacement (configure it next,
    /// [`Swapchain::resize`]).
    pub fn renew(&mut self, surface: wgpu::Surface<'static>) {
        self.surface = surface;
    }

    /// The next frame's texture, or what came instead.
    pub fn acquire(&self) -> Acquired {
        match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(frame) | wgpu::CurrentSurfaceTexture::Suboptimal(frame) => {
                Acquired::Frame(frame)
            }
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => Acquired::Skipped,
            wgpu::CurrentSurfaceTexture::Outdated => Acquired::Outdated,
            wgpu::CurrentSurfaceTexture::Lost => Acquired::Lost,
            wgpu::CurrentSurfaceTexture::Validation => Acquired::Invalid,
        }
    }
}

/// The surface's colour format: GL's default framebuffer does no sRGB encoding, so a plain
/// UNORM format, `Bgra8Unorm` or `Rgba8Unorm` in the order the surface lists them (its
/// preferred first: another costs the browser a copy); else any format without sRGB encoding,
/// else the first. `None` for a surface with no formats.
pub fn format(caps: &wgpu::SurfaceCapabilities) -> Option<wgpu::TextureFormat> {
    caps.formats
        .iter()
        .copied()
        .find(|f| matches!(f, wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Rgba8Unorm))
        .or_else(|| caps.formats.iter().copied().find(|f| !f.is_srgb()))
        .or_else(|| caps.formats.first().copied())
}

/// The configuration of a `width` × `height` surface in `format` (each side clamped to
/// 1..=`max`, the device's largest texture), presenting with `present_mode`, opaque where the
/// surface allows it.
pub fn config(
    caps: &wgpu::SurfaceCapabilities,
    format: wgpu::TextureFormat,
    (width, height): (u32, u32),
    max: u32,
    present_mode: wgpu::PresentMode,
) -> wgpu::SurfaceConfiguration {
    let alpha_mode = if caps.alpha_modes.contains(&wgpu::CompositeAlphaMode::Opaque) {
        wgpu::CompositeAlphaMode::Opaque
    } else {
        caps.alpha_modes
            .first()
            .copied()
            .unwrap_or(wgpu::CompositeAlphaMode::Auto)
    };
    wgpu::SurfaceConfiguration {
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
        format,
        color_space: Default::default(),
        width: width.clamp(1, max),
        height: height.clamp(1, max),
        desired_maximum_frame_latency: 2,
        present_mode,
        alpha_mode,
        view_formats: Vec::new(),
    }
}

/// What went wrong on the device, from wgpu's callbacks (which run on other threads).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Trouble {
    /// The device is gone: destroyed, or lost for the driver's reason. Nothing more can be
    /// drawn.
    Lost(String),
    /// The GPU ran out of memory. Nothing more can be drawn.
    OutOfMemory,
    /// Any other error nobody captured (a validation error): said, and drawing goes on.
    Error(String),
}

impl std::fmt::Display for Trouble {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Trouble::Lost(why) => write!(f, "the GPU device was lost ({why})"),
            Trouble::OutOfMemory => f.write_str("the GPU ran out of memory"),
            Trouble::Error(e) => write!(f, "wgpu error: {e}"),
        }
    }
}

/// Hands every [`Trouble`] of `gpu`'s device to `report`. Call it before anything can fail on
/// the device: wgpu panics on errors nobody handles.
pub fn on_trouble(gpu: &Gpu, report: impl Fn(Trouble) + Send + Sync + 'static) {
    let report = Arc::new(report);
    let lost = report.clone();
    gpu.device.set_device_lost_callback(move |reason, message| {
        let why = match reason {
            wgpu::DeviceLostReason::Destroyed => "destroyed".to_string(),
            _ if message.is_empty() => "driver error".to_string(),
            _ => message,
        };
        lost(Trouble::Lost(why));
    });
    gpu.device.on_uncaptured_error(Arc::new(move |e| {
        report(match e {
            wgpu::Error::OutOfMemory { .. } => Trouble::OutOfMemory,
            e => Trouble::Error(e.to_string()),
        })
    }));
}
