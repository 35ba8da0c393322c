//! What the window and the page both do with the surface they draw into: choose its format,
//! configure it, and hear from the device when it fails.

use std::sync::Arc;

use crate::gpu::Gpu;

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
