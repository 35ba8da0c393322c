//! How a frame reaches the window: the swapchain, or, for a CPU adapter under X11, the X
//! server's shared memory ([`super::shm`]), which the lab draws into directly. The
//! window asks for a [`Target`], encodes the lab and the panel into it, and hands it back to
//! [`Screen::present`]; everything that differs between the two paths lives here.
//!
//! A surface that is `Outdated` is reconfigured and a `Lost` one is created again, then drawing
//! goes on; a presenter that fails falls back to the swapchain, except when the X server refused
//! its frame because another program destroyed the window: then the window is [`Gone`] and
//! ends.

use std::sync::Arc;

use winit::dpi::PhysicalSize;
use winit::window::Window;

use crate::error::{Error, Result};
use crate::gpu::Gpu;

use super::super::surface::{Acquired, Swapchain};
use super::gone::{self, Gone};

#[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
use super::shm::ShmPresenter as Presenter;

/// No shared-memory presenter on this platform: always the swapchain.
#[cfg(not(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android")))))]
struct Presenter {
    color: wgpu::TextureView,
    depth_target: wgpu::TextureView,
    width: u32,
    height: u32,
}

#[cfg(not(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android")))))]
impl Presenter {
    const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Bgra8Unorm;
    fn new(_: &Gpu, _: &Arc<Window>, _: u32, _: u32) -> std::result::Result<Self, String> {
        Err("no shared-memory presenter on this platform".into())
    }
    fn resize(&mut self, _: &Gpu, _: u32, _: u32) -> std::result::Result<(), String> {
        Ok(())
    }
    fn present(&mut self, _: &Gpu, _: wgpu::CommandEncoder, _: bool) -> std::result::Result<(), String> {
        Ok(())
    }
    fn window_gone(&self) -> bool {
        false
    }
    fn copying(&self) -> Option<&str> {
        None
    }
}

/// How many frames in a row may fail with `Lost`/`Outdated` (each one followed by a fresh
/// surface) or a validation error before the window gives up with an error instead of
/// retrying for ever.
const MAX_SURFACE_RETRIES: u32 = 120;

/// The window's swapchain (its surface and depth buffer) and presenter.
pub(super) struct Screen {
    name: &'static str,
    window: Arc<Window>,
    swapchain: Swapchain,
    shm: Option<Presenter>,
    unpaced: bool,
    /// Frames in a row that found the surface unusable.
    retries: u32,
    /// Whether the window was said to be larger than the device can draw.
    said_too_large: bool,
    /// Set when another program destroyed the window: no frame is drawn after it.
    gone: Gone,
}

/// Where one frame is drawn.
pub(super) struct Target {
    /// The colour target.
    pub color: wgpu::TextureView,
    /// The depth target of its size.
    pub depth: wgpu::TextureView,
    /// Its colour format.
    pub format: wgpu::TextureFormat,
    /// Its size.
    pub size: (u32, u32),
    /// The swapchain's frame, to present; `None` for the shared-memory presenter's.
    frame: Option<wgpu::SurfaceTexture>,
}

/// How a presented frame ended.
pub(super) enum Shown {
    /// On the screen.
    Yes,
    /// Not this time: the presenter failed and the swapchain takes over; draw again.
    Again,
    /// Never: the GPU did not finish it within the watchdog ([`crate::gpu::hung`]); why.
    Stuck(String),
}

impl Screen {
    /// The screen of `window` drawn by `gpu` through `surface`: the swapchain configured
    /// ([`Swapchain::new`], presenting as fast as it can when `unpaced`), and the shared-memory
    /// presenter where it can start (said with `SHADERLAB_PRESENT=shm`). The screen marks
    /// `gone` when the X server says that the window no longer exists.
    pub fn new(
        name: &'static str,
        gpu: &Gpu,
        window: Arc<Window>,
        surface: wgpu::Surface<'static>,
        unpaced: bool,
        gone: Gone,
    ) -> Result<Screen> {
        let unpaced_modes = [wgpu::PresentMode::Immediate, wgpu::PresentMode::Mailbox];
        let present_modes: &[wgpu::PresentMode] = if unpaced { &unpaced_modes } else { &[] };
        let size = window.inner_size();
        let max = gpu.device.limits().max_texture_dimension_2d;
        let swapchain = Swapchain::new(
            gpu,
            "the window surface",
            surface,
            (size.width, size.height),
            present_modes,
        )?;
        let (format, (width, height)) = (swapchain.format(), swapchain.size());
        let shm = if format == wgpu::TextureFormat::Bgra8Unorm {
            Presenter::new(gpu, &window, width, height)
        } else {
            Err(format!("the window's format is {format:?}"))
        };
        let asked_shm = matches!(std::env::var("SHADERLAB_PRESENT").as_deref(), Ok("shm" | "shm-copy"));
        let shm = match shm {
            Ok(p) => {
                if let (true, Some(why)) = (asked_shm, p.copying()) {
                    eprintln!("{name}: shared-memory presenter copies each frame: {why}");
                }
                Some(p)
            }
            Err(why) => {
                if asked_shm {
                    eprintln!("{name}: presenting with the swapchain: {why}");
                }
                None
            }
        };
        let said_too_large = too_large(name, size, max, false);
        Ok(Screen {
            name,
            window,
            swapchain,
            shm,
            unpaced,
            retries: 0,
            said_too_large,
            gone,
        })
    }

    /// The colour format the lab's pipelines draw in.
    pub fn format(&self) -> wgpu::TextureFormat {
        self.swapchain.format()
    }

    /// The size frames are drawn at.
    pub fn size(&self) -> (u32, u32) {
        self.swapchain.size()
    }

    /// Follows a resize of the window to `size` (at most the device's largest texture, said
    /// once). A window without an area is not drawn; returns whether it has one.
    pub fn resize(&mut self, gpu: &Gpu, size: PhysicalSize<u32>) -> bool {
        // The original treats height 0 as 1; a surface cannot be 0 pixels, so a zero-sized
        // (minimised) window is simply not drawn until it has a size again.
        let Some((width, height)) = surface_size(size) else {
            return false;
        };
        let max = gpu.device.limits().max_texture_dimension_2d;
        self.said_too_large = too_large(self.name, size, max, self.said_too_large);
        self.swapchain.resize(gpu, (width, height));
        let (width, height) = self.swapchain.size();
        if let Some(shm) = &mut self.shm {
            if let Err(why) = shm.resize(gpu, width, height) {
                if shm.window_gone() {
                    self.gone.set();
                } else {
                    eprintln!("{}: shared-memory presenter: {why}; using the swapchain", self.name);
                }
                self.shm = None;
            }
        }
        true
    }

    /// A `Lost` surface must be created again from the window, then configured.
    fn recreate_surface(&mut self, gpu: &Gpu) -> Result<()> {
        let surface = gpu
            .instance
            .create_surface(self.window.clone())
            .map_err(|e| Error::Surface(format!("cannot create the window surface again: {e}")))?;
        self.swapchain.renew(surface);
        let size = self.window.inner_size();
        self.resize(gpu, size);
        Ok(())
    }

    /// The target of the next frame; `None` when there is none to draw into this time (the
    /// surface timed out, is occluded, or was just made anew). `fatal` says whether the device
    /// became unusable meanwhile. A window another program destroyed is an error.
    pub fn target(&mut self, gpu: &Gpu, fatal: impl Fn() -> Option<Error>) -> Result<Option<Target>> {
        if self.gone.is() {
            return Err(gone::error());
        }
        if let Some(shm) = &self.shm {
            return Ok(Some(Target {
                color: shm.color.clone(),
                depth: shm.depth_target.clone(),
                format: Presenter::FORMAT,
                size: (shm.width, shm.height),
                frame: None,
            }));
        }
        let frame = match self.swapchain.acquire() {
            Acquired::Frame(frame) => frame,
            Acquired::Skipped => return Ok(None),
            status @ (Acquired::Outdated | Acquired::Lost) => {
                // A window destroyed by another program loses its surface: it is not made
                // again (nor asked its size, which winit cannot answer for a window gone).
                if self.gone.is() {
                    return Err(gone::error());
                }
                self.retries += 1;
                let lost = matches!(status, Acquired::Lost);
                if self.retries > MAX_SURFACE_RETRIES {
                    let status = if lost { "Lost" } else { "Outdated" };
                    return Err(Error::Surface(format!(
                        "the window surface stays unusable ({status} {MAX_SURFACE_RETRIES} frames in a row)"
                    )));
                }
                if lost {
                    self.recreate_surface(gpu)?;
                } else {
                    let size = self.window.inner_size();
                    self.resize(gpu, size);
                }
                return Ok(None);
            }
            Acquired::Invalid => {
                // The uncaptured-error handler printed why; a lost device ends here, and an error
                // that repeats every frame ends the window instead of flooding the terminal.
                self.retries += 1;
                if self.retries > MAX_SURFACE_RETRIES {
                    return Err(Error::Surface(format!(
                        "cannot get a frame from the window surface ({MAX_SURFACE_RETRIES} frames in a row)"
                    )));
                }
                return fatal().map_or(Ok(None), Err);
            }
        };
        self.retries = 0;
        let color = frame.texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some("window.frame"),
            ..Default::default()
        });
        Ok(Some(Target {
            color,
            depth: self.swapchain.depth().clone(),
            format: self.swapchain.format(),
            size: self.size(),
            frame: Some(frame),
        }))
    }

    /// Submits `encoder` (the frame recorded into `target`) and puts the frame on the screen.
    pub fn present(&mut self, gpu: &Gpu, target: Target, encoder: wgpu::CommandEncoder) -> Result<Shown> {
        match target.frame {
            Some(frame) => {
                let submission = gpu.queue.submit([encoder.finish()]);
                // On a CPU adapter the frame is waited for under the watchdog before it is
                // presented: lavapipe's present (and its next submit) would block for ever behind
                // a frame that never ends. It copies the finished frame to the window anyway, so
                // the wait costs nothing. A GPU's driver has a watchdog of its own and reports a
                // lost device.
                if gpu.watchdog.is_some() && gpu.adapter.get_info().device_type == wgpu::DeviceType::Cpu {
                    let wait = wgpu::PollType::Wait {
                        submission_index: Some(submission),
                        timeout: gpu.watchdog,
                    };
                    if let Err(e) = gpu.device.poll(wait) {
                        let error = gpu.wait_error(e);
                        if crate::gpu::hung() {
                            // Never presented (nor dropped: that waits too).
                            std::mem::forget(frame);
                            return Ok(Shown::Stuck(error.to_string()));
                        }
                        return Err(error);
                    }
                }
                self.window.pre_present_notify();
                gpu.queue.present(frame);
                Ok(Shown::Yes)
            }
            None => {
                let Some(shm) = self.shm.as_mut() else {
                    return Ok(Shown::Yes);
                };
                self.window.pre_present_notify();
                // Drawing as fast as possible keeps one frame in flight (shown while the next
                // renders).
                match shm.present(gpu, encoder, self.unpaced) {
                    Ok(()) => Ok(Shown::Yes),
                    // Keep the presenter: dropping it would wait for the frame that never ends.
                    Err(why) if crate::gpu::hung() => Ok(Shown::Stuck(why)),
                    Err(_) if shm.window_gone() => {
                        // The server refused the frame because another program destroyed the
                        // window: it ends now, whether or not winit says so too.
                        self.gone.set();
                        self.shm = None;
                        Err(gone::error())
                    }
                    Err(why) => {
                        eprintln!("{}: shared-memory presenter: {why}; using the swapchain", self.name);
                        self.shm = None;
                        Ok(Shown::Again)
                    }
                }
            }
        }
    }
}

/// Says once per window that it is larger than the device can draw (the surface is clamped to
/// the device's limit); returns whether it has been said.
fn too_large(name: &str, size: PhysicalSize<u32>, max: u32, said: bool) -> bool {
    let large = size.width > max || size.height > max;
    if large && !said {
        eprintln!(
            "{name}: the window ({}x{}) is larger than the GPU can draw ({max}x{max}); drawing the part that fits",
            size.width, size.height
        );
    }
    said || large
}

/// The surface size for a window size, or `None` when the window has no area (zero width or
/// height, as when minimised on some platforms): then nothing is drawn until it grows again.
pub fn surface_size(size: PhysicalSize<u32>) -> Option<(u32, u32)> {
    (size.width > 0 && size.height > 0).then_some((size.width, size.height))
}
