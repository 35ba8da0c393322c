//! The window: winit events mapped to the original's GLUT callbacks ([`Input`]), a surface that
//! follows resizes (height 0 is treated as 1, minimising pauses drawing), F12 screenshots, live
//! shader reload and the clock of animated labs (Space pauses it). Labs never see winit; this
//! module drives any [`Lab`] through its plain methods.
//!
//! Nothing is drawn when nothing changes: a lab that is not animated is redrawn after input,
//! a resize, an expose or a reload only, so an idle window costs no CPU (the originals redraw
//! continuously from `glutIdleFunc`).
//!
//! Failure handling: a surface that is `Outdated` is reconfigured and a `Lost` one is created
//! again, then drawing goes on; a lost GPU device (or a GPU out of memory) ends the event loop
//! with one clear message and exit status 1, never a panic. While the window has no area
//! (zero-sized or minimised) or is fully covered, nothing is drawn and the loop sleeps until
//! the next window event instead of spinning, and frames are paced near the monitor's refresh
//! rate ([`frame_interval`]) for drivers whose FIFO presentation does not wait for vertical sync.
//!
//! Test hooks: `SHADERLAB_TEST_LOSE_DEVICE=SECONDS` destroys the GPU device that many seconds
//! after the window opens, so the tests can check what a lost device looks like.
//! `SHADERLAB_TEST_LOG=1` writes the window's own signals to stderr, so that a test waits for
//! the program instead of for a time a busy machine can exceed: `shaderlab-test: frame N` after
//! each frame is shown, `shaderlab-test: sync` when the key F11 arrives (every event sent before
//! it has then been handled), and `shaderlab-test: idle` when the window has nothing more to
//! draw after one of those.

use std::path::PathBuf;
use std::sync::{mpsc, Arc, Mutex};
use std::time::{Duration, Instant};

use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, KeyEvent, MouseButton, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::{Key, NamedKey};
use winit::window::{Window, WindowId};

use crate::error::{Error, Result};
use crate::gpu::Gpu;
use crate::lab::{Input, Lab, LabContext, LabEntry, Special, UserFiles};
use crate::offscreen::{depth_texture, save_png, Offscreen};
use crate::params::Params;
use crate::render::Frame;
use crate::shader::ShaderSource;

use super::Args;

#[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
use super::shm::ShmPresenter as Presenter;

/// No shared-memory presenter on this platform: always the swapchain.
#[cfg(not(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android")))))]
struct Presenter {
    color: wgpu::TextureView,
    depth_view: wgpu::TextureView,
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

/// Frames per second when the monitor does not say its refresh rate.
const DEFAULT_REFRESH_HZ: f64 = 60.0;

/// How many frames in a row may fail with `Lost`/`Outdated` (each one followed by a fresh
/// surface) or a validation error before the window gives up with an error instead of
/// retrying for ever.
const MAX_SURFACE_RETRIES: u32 = 120;

/// The time between frames for a monitor refresh rate (mHz, if known): 10% shorter than the
/// refresh period, so a driver that really waits for vertical sync (FIFO) still sets the pace,
/// while one that does not (a software driver presenting with PutImage, as lavapipe under X11
/// does) is held near the refresh rate instead of drawing as fast as the CPU allows.
pub fn frame_interval(refresh_millihertz: Option<u32>) -> Duration {
    let hz = refresh_millihertz
        .map(|mhz| f64::from(mhz) / 1000.0)
        .filter(|hz| (20.0..=1000.0).contains(hz))
        .unwrap_or(DEFAULT_REFRESH_HZ);
    Duration::from_secs_f64(1.0 / (hz * 1.1))
}

/// Whether a window can be opened: this build talks X11 (also through XWayland), so a
/// display must be named in `DISPLAY`.
pub fn has_display() -> bool {
    std::env::var_os("DISPLAY").is_some_and(|d| !d.is_empty())
}

/// Why [`has_display`] is false, in words a user can act on.
pub fn no_display_reason() -> &'static str {
    if std::env::var_os("WAYLAND_DISPLAY").is_some_and(|d| !d.is_empty()) {
        "WAYLAND_DISPLAY is set but DISPLAY is not; shaderlab windows use X11, so start XWayland or set DISPLAY"
    } else {
        "DISPLAY is unset"
    }
}

/// The surface size for a window size, or `None` when the window has no area (zero width or
/// height, as when minimised on some platforms): then nothing is drawn until it grows again.
pub fn surface_size(size: PhysicalSize<u32>) -> Option<(u32, u32)> {
    (size.width > 0 && size.height > 0).then_some((size.width, size.height))
}

/// Opens the lab in a window and runs until Esc or close.
pub fn run(entry: &'static LabEntry, args: &Args, params: Params, files: UserFiles) -> Result<()> {
    let event_loop = EventLoop::<Wake>::with_user_event().build().map_err(|e| {
        // winit's message names its own source file ("os error at /…/registry/…/x11/mod.rs:N:
        // reason"): keep the reason only.
        let message = e.to_string();
        let reason = match message.find(" at /") {
            Some(at) => message[at..].split_once(": ").map_or(&message[..at], |(_, r)| r),
            None => &message,
        };
        Error::Surface(format!(
            "cannot open a window on DISPLAY={}: {}",
            std::env::var("DISPLAY").unwrap_or_default(),
            reason.lines().next().unwrap_or("")
        ))
    })?;
    event_loop.set_control_flow(ControlFlow::Poll);
    // SIGINT, SIGTERM and SIGHUP end the window through its own loop, so that a recording
    // running is finished and kept; the process then ends as the signal asked (when `_deferred`
    // is dropped, on the way out of this function).
    let _deferred = crate::fsutil::signals::defer();
    wake_on_signal(event_loop.create_proxy());
    // Live reload needs files: --shaders DIR, else shaders_glsl/ of the source tree, else the built-in copies.
    let source = match args.shader_source()? {
        ShaderSource::Embedded => ShaderSource::source_tree().unwrap_or(ShaderSource::Embedded),
        dir => dir,
    };
    let mut app = App {
        entry,
        args: args.clone(),
        params: Some(params),
        source,
        files: Arc::new(files),
        state: None,
        error: None,
    };
    // winit panics inside its X11 backend when another program destroys the window
    // (`xdotool windowclose`): turn that into an error instead of a crash report.
    let previous_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| event_loop.run_app(&mut app)));
    std::panic::set_hook(previous_hook);
    // A recording still running is kept, not lost, however the window ended: Esc, closed by
    // the window manager or destroyed by another program, a signal, an error. Its frames are
    // drawn offscreen, so the window is not needed to finish it.
    if let Some(state) = app.state.as_mut() {
        state.finish_capture();
    }
    if crate::gpu::hung() {
        // A frame never ended: dropping the window's GPU objects would wait for it for ever.
        eprintln!(
            "{}: error: the GPU did not finish a frame (said above); ended without waiting for it",
            app.entry.info.name
        );
        crate::fsutil::signals::exit_now(1);
    }
    match outcome {
        Ok(result) => result.map_err(|e| Error::Surface(format!("event loop failed: {e}")))?,
        Err(_) => {
            return Err(Error::Surface(
                "the window was closed or destroyed by another program".into(),
            ))
        }
    }
    match app.error {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

/// What wakes the window's event loop from outside it.
#[derive(Debug, Clone, Copy)]
enum Wake {
    /// A deferred signal (its number).
    Signal(i32),
}

/// Starts a thread that turns a deferred signal into a [`Wake::Signal`] for the event loop: the
/// handler writes the signal's number into a pipe, and the thread, blocked reading it, sends the
/// event. Without a pipe the window still ends at the signal, at its next frame or event.
fn wake_on_signal(proxy: winit::event_loop::EventLoopProxy<Wake>) {
    #[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
    {
        let mut fds = [0; 2];
        // SAFETY: pipe2 fills two descriptors that this function then owns.
        if unsafe { libc::pipe2(fds.as_mut_ptr(), libc::O_CLOEXEC) } != 0 {
            return;
        }
        let read = fds[0];
        crate::fsutil::signals::set_wake_fd(fds[1]);
        let spawned = std::thread::Builder::new()
            .name("shaderlab-signals".into())
            .spawn(move || loop {
                let mut byte = 0u8;
                // SAFETY: a one-byte read into a valid buffer from our own pipe.
                let n = unsafe { libc::read(read, (&mut byte as *mut u8).cast(), 1) };
                if n == 1 {
                    let _ = proxy.send_event(Wake::Signal(i32::from(byte)));
                } else if n == 0 || io_error_is_fatal() {
                    return;
                }
            });
        if spawned.is_err() {
            crate::fsutil::signals::set_wake_fd(-1);
        }
    }
    #[cfg(not(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android")))))]
    let _ = proxy;
}

/// Whether the last failed read should end the signal thread (anything but an interrupted call).
#[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
fn io_error_is_fatal() -> bool {
    std::io::Error::last_os_error().kind() != std::io::ErrorKind::Interrupted
}

struct App {
    entry: &'static LabEntry,
    args: Args,
    params: Option<Params>,
    source: ShaderSource,
    files: Arc<UserFiles>,
    state: Option<WindowState>,
    error: Option<Error>,
}

/// Why the device can no longer be used, set from wgpu's callbacks (other threads).
type Fatal = Arc<Mutex<Option<String>>>;

fn set_fatal(fatal: &Fatal, message: String) {
    if let Ok(mut slot) = fatal.lock() {
        slot.get_or_insert(message);
    }
}

struct WindowState {
    entry: &'static LabEntry,
    source: ShaderSource,
    files: Arc<UserFiles>,
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    depth: wgpu::TextureView,
    gpu: Gpu,
    lab: Box<dyn Lab>,
    /// The window's start: the clock's second 0.
    start: Instant,
    /// Drives an animated lab's `time` (Space pauses it).
    clock: super::clock::Clock,
    /// Frames still to draw for a lab that is not animated (input, resize, reload).
    dirty: u32,
    unpaced: bool,
    /// Whether the window was said to be larger than the device can draw.
    said_too_large: bool,
    /// Presenting through X shared memory (CPU adapters under X11), else the swapchain.
    shm: Option<Presenter>,
    /// With `--unpaced`: frames drawn since `counted_since` (the frame-time report).
    counted: u32,
    counted_since: Instant,
    cursor: (i32, i32),
    buttons: u32,
    /// The window has no area: nothing to draw.
    minimised: bool,
    /// The window is fully covered (X11 visibility): nothing to draw.
    occluded: bool,
    /// Frames in a row that found the surface `Lost` or `Outdated`.
    surface_retries: u32,
    /// Shortest time between two frames, and when the next one is due.
    frame_interval: Duration,
    next_frame: Instant,
    shader_error: bool,
    fatal: Fatal,
    lose_device_at: Option<Instant>,
    reload: Option<(notify::RecommendedWatcher, mpsc::Receiver<()>)>,
    screenshots: u32,
    /// F10's recording, while one runs.
    capture: Option<super::capture::Capture>,
    /// F1's parameter panel.
    panel: super::panel::Panel,
    /// The last shader error, while one stands (shown in the panel).
    shader_message: Option<String>,
    /// Milliseconds between frames, smoothed, and when the last frame was drawn.
    frame_ms: f64,
    last_frame: Instant,
    /// When the frame being drawn started.
    frame_started: Instant,
    /// Why drawing stopped for good: a frame did not finish within the watchdog (a shader that
    /// never ends). The window then only answers Esc and close.
    stuck: Option<String>,
    /// `SHADERLAB_TEST_LOG`: frames shown so far, and whether one was shown (or F11 arrived)
    /// since the last `idle` was written.
    test_log: Option<TestLog>,
}

/// The window's signals for tests (see the module docs).
#[derive(Default)]
struct TestLog {
    frames: u64,
    busy: bool,
}

impl TestLog {
    fn say(&mut self, what: &str) {
        if what != "idle" {
            self.busy = true;
        }
        eprintln!("shaderlab-test: {what}");
    }
}

impl App {
    /// A surface for `window` and a device that can present to it, from `instance`.
    fn connect(instance: wgpu::Instance, window: &Arc<Window>) -> Result<(Gpu, wgpu::Surface<'static>)> {
        let surface = match instance.create_surface(window.clone()) {
            Ok(surface) => surface,
            // With no usable driver at all wgpu only says "Failed to create surface for any
            // enabled backend": say what is really missing, as the offscreen path does.
            Err(e) => {
                return Err(
                    match pollster::block_on(instance.request_adapter(&Default::default())) {
                        Err(no_adapter) => Error::NoAdapter(no_adapter.to_string()),
                        Ok(_) => Error::Surface(format!("cannot create a surface for the window: {e}")),
                    },
                )
            }
        };
        let gpu = pollster::block_on(Gpu::for_window(instance, &surface))?;
        Ok((gpu, surface))
    }

    fn init(&mut self, event_loop: &ActiveEventLoop) -> Result<WindowState> {
        let entry = self.entry;
        let (width, height) = self.args.size(entry);
        let attributes = Window::default_attributes()
            .with_title(format!("{} {}", entry.info.title, entry.info.label))
            .with_inner_size(PhysicalSize::new(width, height));
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .map_err(|e| Error::Surface(format!("cannot create a window: {e}")))?,
        );
        // The primary backends first, GL only where they cannot draw into this window.
        let (gpu, surface) = match Self::connect(Gpu::new_instance(), &window) {
            Err(e @ (Error::NoAdapter(_) | Error::Surface(_))) => match Gpu::fallback_instance() {
                Some(gl) => Self::connect(gl, &window).map_err(|fallback| match fallback {
                    Error::NoAdapter(_) | Error::Surface(_) => e,
                    other => other,
                })?,
                None => return Err(e),
            },
            result => result?,
        };
        let mut gpu = gpu;
        gpu.watchdog = self.args.watchdog();
        // Before anything can fail on the device: wgpu panics on errors nobody handles.
        let fatal: Fatal = Arc::new(Mutex::new(None));
        let lost = fatal.clone();
        gpu.device.set_device_lost_callback(move |reason, message| {
            let why = match reason {
                wgpu::DeviceLostReason::Destroyed => "destroyed".to_string(),
                _ if message.is_empty() => "driver error".to_string(),
                _ => message,
            };
            set_fatal(&lost, format!("the GPU device was lost ({why})"));
        });
        let oom = fatal.clone();
        gpu.device.on_uncaptured_error(Arc::new(move |e| {
            if let wgpu::Error::OutOfMemory { .. } = e {
                set_fatal(&oom, "the GPU ran out of memory".into());
            } else {
                eprintln!("wgpu error: {e}");
            }
        }));
        let caps = surface.get_capabilities(&gpu.adapter);
        // GL's default framebuffer does no sRGB encoding: prefer a plain UNORM format.
        let format = [wgpu::TextureFormat::Bgra8Unorm, wgpu::TextureFormat::Rgba8Unorm]
            .into_iter()
            .find(|f| caps.formats.contains(f))
            .or_else(|| caps.formats.first().copied())
            .ok_or_else(|| Error::Surface("the surface supports no formats".into()))?;
        let size = window.inner_size();
        let present_mode = if self.args.unpaced {
            [wgpu::PresentMode::Immediate, wgpu::PresentMode::Mailbox]
                .into_iter()
                .find(|m| caps.present_modes.contains(m))
                .unwrap_or(wgpu::PresentMode::Fifo)
        } else {
            wgpu::PresentMode::Fifo
        };
        let max = gpu.device.limits().max_texture_dimension_2d;
        let config = wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            format,
            color_space: Default::default(),
            width: size.width.clamp(1, max),
            height: size.height.clamp(1, max),
            desired_maximum_frame_latency: 2,
            present_mode,
            alpha_mode: caps
                .alpha_modes
                .first()
                .copied()
                .unwrap_or(wgpu::CompositeAlphaMode::Auto),
            view_formats: vec![],
        };
        // A surface that was never configured makes wgpu panic on the first frame: check it.
        gpu.checked("configuring the window surface", || {
            surface.configure(&gpu.device, &config)
        })?;
        let depth = depth_texture(&gpu.device, config.width, config.height);
        // A CPU adapter under X11 presents through shared memory; anything else, or a
        // presenter that cannot start, keeps the swapchain (said with SHADERLAB_PRESENT=shm).
        let shm = if format == wgpu::TextureFormat::Bgra8Unorm {
            Presenter::new(&gpu, &window, config.width, config.height)
        } else {
            Err(format!("the window's format is {format:?}"))
        };
        let asked_shm = matches!(std::env::var("SHADERLAB_PRESENT").as_deref(), Ok("shm" | "shm-copy"));
        let shm = match shm {
            Ok(p) => {
                if let (true, Some(why)) = (asked_shm, p.copying()) {
                    eprintln!("{}: shared-memory presenter copies each frame: {why}", entry.info.name);
                }
                Some(p)
            }
            Err(why) => {
                if asked_shm {
                    eprintln!("{}: presenting with the swapchain: {why}", entry.info.name);
                }
                None
            }
        };
        let said_too_large = too_large(entry.info.name, size, max, false);
        let mut lab = (entry.new)(&LabContext {
            gpu: &gpu,
            source: &self.source,
            format,
            files: &self.files,
        })?;
        if let Some(params) = self.params.take() {
            *lab.params_mut() = params;
        }
        // Live reload watches the shader folder and the folders of the lab's input files.
        let mut dirs: Vec<std::path::PathBuf> = match &self.source {
            ShaderSource::Dir(dir) => vec![dir.clone()],
            ShaderSource::Embedded | ShaderSource::Edited(_) => Vec::new(),
        };
        for input in &self.files.inputs {
            let dir = match input.parent() {
                Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
                _ => std::path::PathBuf::from("."),
            };
            if !dirs.contains(&dir) {
                dirs.push(dir);
            }
        }
        let reload = watch(&dirs, &self.files.inputs);
        let env_seconds = |name: &str| {
            std::env::var(name)
                .ok()
                .and_then(|s| s.trim().parse::<f64>().ok())
                .filter(|s| s.is_finite() && *s >= 0.0)
        };
        let clock_scale = env_seconds("SHADERLAB_CLOCK_SCALE").filter(|s| *s > 0.0).unwrap_or(1.0);
        let lose_device_at = env_seconds("SHADERLAB_TEST_LOSE_DEVICE")
            .and_then(|s| Duration::try_from_secs_f64(s).ok())
            .map(|d| Instant::now() + d);
        let refresh_millihertz = window.current_monitor().and_then(|m| m.refresh_rate_millihertz());
        window.set_title(&lab.title());
        let clock = super::clock::Clock::new(lab.as_ref(), 0.0, clock_scale);
        let panel = super::panel::Panel::new(&window);
        Ok(WindowState {
            entry,
            source: self.source.clone(),
            files: self.files.clone(),
            clock,
            dirty: 2,
            unpaced: self.args.unpaced,
            said_too_large,
            shm,
            counted: 0,
            counted_since: Instant::now(),
            minimised: surface_size(size).is_none(),
            window,
            surface,
            config,
            depth,
            gpu,
            lab,
            start: Instant::now(),
            cursor: (0, 0),
            buttons: 0,
            occluded: false,
            surface_retries: 0,
            frame_interval: frame_interval(refresh_millihertz),
            next_frame: Instant::now(),
            shader_error: false,
            fatal,
            lose_device_at,
            reload,
            screenshots: 0,
            capture: None,
            panel,
            shader_message: None,
            frame_ms: 0.0,
            last_frame: Instant::now(),
            frame_started: Instant::now(),
            stuck: None,
            test_log: std::env::var_os("SHADERLAB_TEST_LOG").map(|_| TestLog::default()),
        })
    }
}

fn watch(
    dirs: &[std::path::PathBuf],
    inputs: &[std::path::PathBuf],
) -> Option<(notify::RecommendedWatcher, mpsc::Receiver<()>)> {
    use notify::Watcher;
    if dirs.is_empty() {
        return None;
    }
    let names: Vec<std::ffi::OsString> = inputs
        .iter()
        .filter_map(|p| p.file_name().map(|n| n.to_owned()))
        .collect();
    let (tx, rx) = mpsc::channel();
    let mut watcher = notify::recommended_watcher(move |event: notify::Result<notify::Event>| {
        if let Ok(event) = event {
            // Only shader files and the lab's inputs: a screenshot written into the folder is
            // not an edit.
            let shader = event.paths.iter().any(|p| {
                matches!(
                    p.extension().and_then(|e| e.to_str()),
                    Some("vert" | "frag" | "glsl" | "comp")
                ) || p.file_name().is_some_and(|n| names.iter().any(|m| m == n))
            });
            if shader && (event.kind.is_modify() || event.kind.is_create()) {
                let _ = tx.send(());
            }
        }
    })
    .map_err(|e| eprintln!("live reload disabled: {e}"))
    .ok()?;
    for dir in dirs {
        watcher
            .watch(dir, notify::RecursiveMode::NonRecursive)
            .map_err(|e| eprintln!("live reload disabled: cannot watch {}: {e}", dir.display()))
            .ok()?;
    }
    Some((watcher, rx))
}

impl WindowState {
    fn name(&self) -> &'static str {
        self.entry.info.name
    }

    fn update_title(&self) {
        let mut title = self.lab.title();
        if self.shader_error {
            title.push_str(" | SHADER ERROR (see terminal)");
        }
        if self.stuck.is_some() {
            title.push_str(" | GPU STUCK: a frame never finished (see terminal); Esc quits");
        }
        if let Some(c) = &self.capture {
            title.push_str(&format!(" | REC {} frames (F10 stops)", c.frames()));
        }
        self.window.set_title(&title);
    }

    /// Whether drawing is paused (nothing visible to draw into).
    fn paused(&self) -> bool {
        self.minimised || self.occluded || self.stuck.is_some()
    }

    /// Stops drawing for good after a frame that never ended ([`crate::gpu::hung`]): says
    /// why once, in the terminal and the title.
    fn give_up(&mut self, why: String) {
        if self.stuck.is_none() {
            eprintln!("{}: {why}", self.name());
            self.stuck = Some(why);
            self.update_title();
        }
    }

    /// The error that ends the window, if the device became unusable.
    fn fatal_error(&self) -> Option<Error> {
        let message = self.fatal.lock().ok()?.clone()?;
        Some(Error::Wgpu {
            context: format!("the {} window", self.name()),
            message,
        })
    }

    fn resize(&mut self, size: PhysicalSize<u32>) {
        // The original treats height 0 as 1; a surface cannot be 0 pixels, so a zero-sized
        // (minimised) window is simply not drawn until it has a size again.
        let Some((width, height)) = surface_size(size) else {
            self.minimised = true;
            return;
        };
        self.minimised = false;
        self.dirty = 2;
        let max = self.gpu.device.limits().max_texture_dimension_2d;
        self.said_too_large = too_large(self.entry.info.name, size, max, self.said_too_large);
        self.config.width = width.min(max);
        self.config.height = height.min(max);
        self.surface.configure(&self.gpu.device, &self.config);
        self.depth = depth_texture(&self.gpu.device, self.config.width, self.config.height);
        if let Some(shm) = &mut self.shm {
            if let Err(why) = shm.resize(&self.gpu, self.config.width, self.config.height) {
                if !shm.window_gone() {
                    eprintln!("{}: shared-memory presenter: {why}; using the swapchain", self.name());
                }
                self.shm = None;
            }
        }
    }

    /// A `Lost` surface must be created again from the window, then configured.
    fn recreate_surface(&mut self) -> Result<()> {
        self.surface = self
            .gpu
            .instance
            .create_surface(self.window.clone())
            .map_err(|e| Error::Surface(format!("cannot create the window surface again: {e}")))?;
        let size = self.window.inner_size();
        self.resize(size);
        Ok(())
    }

    fn check_reload(&mut self) {
        let Some((_, rx)) = &self.reload else { return };
        if rx.try_recv().is_err() {
            return;
        }
        // Editors write in several steps: let them finish, then drain the queue.
        std::thread::sleep(Duration::from_millis(50));
        while rx.try_recv().is_ok() {}
        self.dirty = 2;
        let cx = LabContext {
            gpu: &self.gpu,
            source: &self.source,
            format: self.config.format,
            files: &self.files,
        };
        match self.lab.reload(&cx) {
            Ok(()) => {
                if self.shader_error {
                    eprintln!("{}: shaders reloaded, error fixed", self.name());
                } else {
                    eprintln!("{}: shaders reloaded", self.name());
                }
                self.shader_error = false;
                self.shader_message = None;
            }
            Err(e) => {
                eprintln!("{}: shader error (keeping the last good pipeline):\n{e}", self.name());
                self.shader_error = true;
                self.shader_message = Some(e.to_string());
            }
        }
        self.update_title();
    }

    /// A fresh name in the current directory: `NAME-SECONDS-PID-N.EXT` (F12 and F10).
    fn fresh_name(&mut self, extension: &str) -> PathBuf {
        self.screenshots += 1;
        let stamp = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map(|d| d.as_secs())
            .unwrap_or(0);
        // The process id keeps two windows started in the same second apart.
        loop {
            let path = PathBuf::from(format!(
                "{}-{stamp}-{}-{}.{extension}",
                self.name(),
                std::process::id(),
                self.screenshots
            ));
            if !path.exists() {
                return path;
            }
            self.screenshots += 1;
        }
    }

    /// F10: starts or stops recording what the window shows.
    fn toggle_capture(&mut self) {
        match self.capture.take() {
            Some(capture) => report_capture(self.name(), capture),
            None => {
                let path = self.fresh_name("gif");
                match super::capture::Capture::start(&path) {
                    Ok(capture) => {
                        eprintln!("{}: recording to {} (F10 stops)", self.name(), path.display());
                        self.capture = Some(capture);
                        self.dirty = self.dirty.max(2);
                    }
                    Err(e) => eprintln!("{}: cannot record: {e}", self.name()),
                }
            }
        }
        self.update_title();
    }

    /// Finishes F10's recording if one runs, without touching the window (which may be gone).
    fn finish_capture(&mut self) {
        if let Some(capture) = self.capture.take() {
            report_capture(self.name(), capture);
        }
    }

    /// Adds the frame just shown to F10's recording.
    fn capture_frame(&mut self) {
        if self.stuck.is_some() {
            return;
        }
        let Some(capture) = self.capture.as_mut() else { return };
        let (w, h) = (self.config.width, self.config.height);
        if let Err(e) = capture.add(&self.gpu, self.lab.as_mut(), w, h, self.config.format) {
            eprintln!("{}: recording stopped: {e}", self.name());
            self.capture = None;
        }
        self.update_title();
    }

    /// Draws the panel (when shown) over what the lab drew into `view`, and acts on what it
    /// changed or asked for.
    fn draw_panel(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        view: &wgpu::TextureView,
        format: wgpu::TextureFormat,
        size: (u32, u32),
    ) {
        let now = Instant::now();
        let ms = now.duration_since(self.last_frame).as_secs_f64() * 1000.0;
        self.last_frame = now;
        self.frame_ms = if self.frame_ms == 0.0 {
            ms
        } else {
            0.9 * self.frame_ms + 0.1 * ms
        };
        if !self.panel.shown {
            return;
        }
        let draw_ms = self.frame_started.elapsed().as_secs_f64() * 1000.0;
        let mut files: Vec<(String, String)> = Vec::new();
        for program in self.lab.programs() {
            let (v, f) = program.files();
            files.push((v.to_owned(), f.to_owned()));
        }
        let source = match (&self.source, self.reload.is_some()) {
            (ShaderSource::Dir(dir), true) => format!("from {} (reloads live)", dir.display()),
            (ShaderSource::Dir(dir), false) => format!("from {}", dir.display()),
            (ShaderSource::Embedded, _) => "built in".to_owned(),
            (ShaderSource::Edited(_), _) => "edited in memory".to_owned(),
        };
        let status = super::panel::Status {
            frame_ms: (self.animated() || self.unpaced).then_some(self.frame_ms),
            draw_ms,
            files,
            source,
            error: self.shader_message.as_deref(),
            recording: self.capture.as_ref().map(super::capture::Capture::frames),
        };
        let (changed, request) = self.panel.draw(
            &self.gpu,
            &self.window,
            encoder,
            view,
            format,
            size,
            self.lab.as_mut(),
            &status,
        );
        if changed {
            self.dirty = self.dirty.max(2);
            self.update_title();
        }
        if self.panel.repaint {
            self.dirty = self.dirty.max(2);
        }
        if request == Some(super::panel::Request::WriteShaders) {
            self.write_shaders();
        }
    }

    /// The panel's button: the built-in shaders into `./NAME-shaders/` (a fresh name), then
    /// live reload from there, as `--shaders DIR` would.
    fn write_shaders(&mut self) {
        let mut dir = PathBuf::from(format!("{}-shaders", self.name()));
        let mut n = 1;
        while dir.exists() {
            n += 1;
            dir = PathBuf::from(format!("{}-shaders-{n}", self.name()));
        }
        let written = std::fs::create_dir(&dir).and_then(|()| {
            crate::shader::embedded_names().try_for_each(|name| {
                let text = crate::shader::embedded_source(name).unwrap_or_default();
                std::fs::write(dir.join(name), text)
            })
        });
        if let Err(e) = written {
            eprintln!("{}: cannot write the shaders to {}: {e}", self.name(), dir.display());
            return;
        }
        let dir = std::fs::canonicalize(&dir).unwrap_or(dir);
        self.source = ShaderSource::Dir(dir.clone());
        self.reload = watch(std::slice::from_ref(&dir), &self.files.inputs);
        println!("shaders: {} (edit them; the lab reloads live)", dir.display());
    }

    fn screenshot(&mut self) {
        if self.stuck.is_some() {
            eprintln!(
                "{}: no screenshot: the GPU is stuck in a frame that never ends",
                self.name()
            );
            return;
        }
        let path = self.fresh_name("png");
        let (w, h) = (self.config.width, self.config.height);
        // Drawn by the window's own pipelines (its format), read back as RGB.
        let target = Offscreen::with_format(&self.gpu, w, h, self.config.format);
        match super::render_into(&self.gpu, self.lab.as_mut(), &target)
            .and_then(|()| target.read(&self.gpu))
            .and_then(|image| save_png(&image, &path))
        {
            Ok(()) => println!("screenshot: {}", std::fs::canonicalize(&path).unwrap_or(path).display()),
            Err(e) => eprintln!("{}: screenshot failed: {e}", self.name()),
        }
    }

    fn redraw(&mut self) -> Result<()> {
        if let Some(at) = self.lose_device_at {
            if Instant::now() >= at {
                self.lose_device_at = None;
                eprintln!("{}: SHADERLAB_TEST_LOSE_DEVICE: destroying the GPU device", self.name());
                self.gpu.device.destroy();
                // The device-lost callback runs when the device is next maintained.
                let _ = self.gpu.device.poll(wgpu::PollType::Poll);
            }
        }
        if let Some(e) = self.fatal_error() {
            return Err(e);
        }
        if self.paused() {
            return Ok(());
        }
        self.frame_started = Instant::now();
        // Pace from the previous deadline (no drift), but never plan a burst to catch up.
        let now = Instant::now();
        self.next_frame = (self.next_frame + self.frame_interval).max(now);
        self.tick();
        self.dirty = self.dirty.saturating_sub(1);
        if self.shm.is_some() {
            return self.redraw_shm();
        }
        let frame = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(frame) | wgpu::CurrentSurfaceTexture::Suboptimal(frame) => frame,
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => return Ok(()),
            status @ (wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost) => {
                self.surface_retries += 1;
                if self.surface_retries > MAX_SURFACE_RETRIES {
                    return Err(Error::Surface(format!(
                        "the window surface stays unusable ({status:?} {MAX_SURFACE_RETRIES} frames in a row)"
                    )));
                }
                if matches!(status, wgpu::CurrentSurfaceTexture::Lost) {
                    self.recreate_surface()?;
                } else {
                    let size = self.window.inner_size();
                    self.resize(size);
                }
                return Ok(());
            }
            wgpu::CurrentSurfaceTexture::Validation => {
                // The uncaptured-error handler printed why; a lost device ends here, and an error
                // that repeats every frame ends the window instead of flooding the terminal.
                self.surface_retries += 1;
                if self.surface_retries > MAX_SURFACE_RETRIES {
                    return Err(Error::Surface(format!(
                        "cannot get a frame from the window surface ({MAX_SURFACE_RETRIES} frames in a row)"
                    )));
                }
                return self.fatal_error().map_or(Ok(()), Err);
            }
        };
        self.surface_retries = 0;
        let view = frame.texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some("window.frame"),
            ..Default::default()
        });
        let (w, h) = (self.config.width, self.config.height);
        let mut encoder = self.gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("window.frame"),
        });
        let rendered = {
            let mut frame = Frame {
                gpu: &self.gpu,
                encoder: &mut encoder,
                color: &view,
                depth: &self.depth,
                width: w,
                height: h,
                timestamps: None,
            };
            self.lab.render(&mut frame)
        };
        if let Err(e) = rendered {
            eprintln!("{}: {e}", self.name());
        }
        let format = self.config.format;
        self.draw_panel(&mut encoder, &view, format, (w, h));
        let submission = self.gpu.queue.submit([encoder.finish()]);
        // On a CPU adapter the frame is waited for under the watchdog before it is presented:
        // lavapipe's present (and its next submit) would block for ever behind a frame that never
        // ends. It copies the finished frame to the window anyway, so the wait costs nothing. A
        // GPU's driver has a watchdog of its own and reports a lost device.
        if self.gpu.watchdog.is_some() && self.gpu.adapter.get_info().device_type == wgpu::DeviceType::Cpu {
            let wait = wgpu::PollType::Wait {
                submission_index: Some(submission),
                timeout: self.gpu.watchdog,
            };
            if let Err(e) = self.gpu.device.poll(wait) {
                let error = self.gpu.wait_error(e);
                if crate::gpu::hung() {
                    // The frame is never presented (nor dropped: that waits too).
                    std::mem::forget(frame);
                    self.give_up(error.to_string());
                    return Ok(());
                }
                return Err(error);
            }
        }
        // A lab may rebuild a program while drawing (a shading model chosen by key); a broken
        // shader file leaves the previous one in place, and the error is shown once.
        if let Some(e) = self.lab.take_error() {
            eprintln!("{}: {e}", self.name());
            self.shader_error = true;
            self.update_title();
        }
        self.window.pre_present_notify();
        self.gpu.queue.present(frame);
        self.frame_shown();
        if self.unpaced {
            self.report_frame_time();
        }
        Ok(())
    }

    /// A frame drawn offscreen and shown through X shared memory; on failure the swapchain
    /// takes over from the next frame.
    fn redraw_shm(&mut self) -> Result<()> {
        let Some(shm) = self.shm.as_mut() else { return Ok(()) };
        let mut encoder = self.gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("window.frame"),
        });
        let rendered = {
            let mut frame = Frame {
                gpu: &self.gpu,
                encoder: &mut encoder,
                color: &shm.color,
                depth: &shm.depth_view,
                width: shm.width,
                height: shm.height,
                timestamps: None,
            };
            self.lab.render(&mut frame)
        };
        if let Err(e) = rendered {
            eprintln!("{}: {e}", self.entry.info.name);
        }
        let (view, size) = (shm.color.clone(), (shm.width, shm.height));
        self.draw_panel(&mut encoder, &view, Presenter::FORMAT, size);
        let Some(shm) = self.shm.as_mut() else { return Ok(()) };
        self.window.pre_present_notify();
        // Drawing as fast as possible keeps one frame in flight (shown while the next renders).
        let presented = shm
            .present(&self.gpu, encoder, self.unpaced)
            .map_err(|why| (why, shm.window_gone()));
        if let Some(e) = self.lab.take_error() {
            eprintln!("{}: {e}", self.name());
            self.shader_error = true;
            self.update_title();
        }
        if let Err((why, gone)) = presented {
            if crate::gpu::hung() {
                // Keep the presenter: dropping it would wait for the frame that never ends.
                self.give_up(why);
                return Ok(());
            }
            // A destroyed window is said once, by the `Destroyed` event that follows.
            if !gone {
                eprintln!("{}: shared-memory presenter: {why}; using the swapchain", self.name());
            }
            self.shm = None;
            self.dirty = 2;
        }
        if let Some(e) = self.fatal_error() {
            return Err(e);
        }
        self.frame_shown();
        if self.unpaced {
            self.report_frame_time();
        }
        Ok(())
    }

    /// `SHADERLAB_TEST_LOG`: a frame was shown.
    fn frame_shown(&mut self) {
        if let Some(log) = self.test_log.as_mut() {
            log.frames += 1;
            let n = log.frames;
            log.say(&format!("frame {n}"));
        }
    }

    /// With `--unpaced`: every 2 s, one line on stderr with the mean time per frame drawn and
    /// presented (`NAME: window N frames in S s: ms_per_frame=X`), to compare with the original.
    fn report_frame_time(&mut self) {
        self.counted += 1;
        let elapsed = self.counted_since.elapsed();
        if elapsed >= Duration::from_secs(2) {
            let secs = elapsed.as_secs_f64();
            eprintln!(
                "{}: window {} frames in {secs:.2} s: ms_per_frame={:.3}",
                self.name(),
                self.counted,
                secs * 1000.0 / f64::from(self.counted)
            );
            self.counted = 0;
            self.counted_since = Instant::now();
        }
    }

    /// Whether the lab's clock runs (an animated lab, not paused with Space).
    fn animated(&self) -> bool {
        self.clock.runs(self.lab.as_ref())
    }

    /// Advances an animated lab's `time` to the clock's.
    fn tick(&mut self) {
        let now = self.start.elapsed().as_secs_f64();
        self.clock.tick(self.lab.as_mut(), now);
    }

    /// Space: pauses or resumes the clock of an animated lab, keeping its time.
    fn toggle_clock(&mut self) {
        if self.clock.toggle(self.lab.as_ref(), self.start.elapsed().as_secs_f64()) {
            self.dirty = 2;
        }
    }

    fn input(&mut self, input: Input) {
        self.dirty = 2;
        if self.lab.input(input) {
            self.update_title();
        }
    }

    fn key(&mut self, event: &KeyEvent, event_loop: &ActiveEventLoop) {
        if event.state != ElementState::Pressed {
            return;
        }
        match &event.logical_key {
            Key::Named(NamedKey::Escape) => event_loop.exit(),
            Key::Named(NamedKey::F12) => self.screenshot(),
            Key::Named(NamedKey::F10) => self.toggle_capture(),
            Key::Named(NamedKey::F1) => {
                self.panel.shown = !self.panel.shown;
                self.dirty = self.dirty.max(2);
                self.window.request_redraw();
            }
            Key::Named(NamedKey::Space) if self.lab.animated() => self.toggle_clock(),
            Key::Named(named) => {
                let special = match named {
                    NamedKey::ArrowLeft => Special::Left,
                    NamedKey::ArrowRight => Special::Right,
                    NamedKey::ArrowUp => Special::Up,
                    NamedKey::ArrowDown => Special::Down,
                    NamedKey::PageUp => Special::PageUp,
                    NamedKey::PageDown => Special::PageDown,
                    _ => {
                        // Space and other named keys that type a character.
                        if let Some(c) = event.text.as_deref().and_then(single_char) {
                            self.input(Input::Key(c));
                        }
                        return;
                    }
                };
                self.input(Input::Special(special));
            }
            _ => {
                let text = event.text.as_deref().or(match &event.logical_key {
                    Key::Character(s) => Some(s.as_str()),
                    _ => None,
                });
                if let Some(c) = text.and_then(single_char) {
                    self.input(Input::Key(c));
                }
            }
        }
    }
}

/// Finishes a recording and says where it is (or why it failed).
fn report_capture(name: &str, capture: super::capture::Capture) {
    let frames = capture.frames();
    match capture.finish() {
        Ok(path) => {
            let path = std::fs::canonicalize(&path).unwrap_or(path);
            let _ = super::say(&format!("recording: {} ({frames} frames)", path.display()));
        }
        Err(e) => eprintln!("{name}: recording failed: {e}"),
    }
}

fn single_char(s: &str) -> Option<char> {
    let mut chars = s.chars();
    match (chars.next(), chars.next()) {
        (Some(c), None) => Some(c),
        _ => None,
    }
}

impl ApplicationHandler<Wake> for App {
    fn user_event(&mut self, event_loop: &ActiveEventLoop, event: Wake) {
        match event {
            // The recording is finished on the way out (`run`), then the signal ends the process.
            Wake::Signal(signal) => {
                self.error = Some(Error::Interrupted { signal });
                event_loop.exit();
            }
        }
    }

    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.state.is_some() {
            return;
        }
        match self.init(event_loop) {
            Ok(state) => self.state = Some(state),
            Err(e) => {
                self.error = Some(e);
                event_loop.exit();
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let Some(state) = self.state.as_mut() else { return };
        if let (Some(log), WindowEvent::KeyboardInput { event: key, .. }) = (state.test_log.as_mut(), &event) {
            if key.state == ElementState::Pressed && key.logical_key == Key::Named(NamedKey::F11) {
                log.say("sync");
                return;
            }
        }
        if let Some(e) = state.fatal_error() {
            self.error = Some(e);
            event_loop.exit();
            return;
        }
        let is_f1 =
            matches!(&event, WindowEvent::KeyboardInput { event: k, .. } if k.logical_key == Key::Named(NamedKey::F1));
        if !is_f1 && state.panel.event(&state.window, &event) {
            // The panel took it (a click on it, a key typed into one of its fields).
            state.dirty = state.dirty.max(2);
            state.window.request_redraw();
            if let WindowEvent::MouseInput {
                state: ElementState::Released,
                ..
            } = event
            {
                state.buttons = 0;
            }
            return;
        }
        if state.panel.shown && !matches!(event, WindowEvent::RedrawRequested) {
            // egui answers hover and focus on the next frame.
            state.dirty = state.dirty.max(2);
        }
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            // Another program destroyed the window (`xdotool windowclose`): nothing is left to
            // draw into, and winit would fail on the next request about it.
            WindowEvent::Destroyed => {
                self.error = Some(Error::Surface(
                    "the window was closed or destroyed by another program".into(),
                ));
                event_loop.exit();
            }
            WindowEvent::Resized(size) => state.resize(size),
            WindowEvent::Occluded(occluded) => state.occluded = occluded,
            // winit invents ("synthetic") presses for keys already held when the window gets the
            // focus; GLUT never saw those, and acting on them doubles the key that focused it.
            WindowEvent::KeyboardInput {
                event,
                is_synthetic: false,
                ..
            } => state.key(&event, event_loop),
            WindowEvent::CursorMoved { position, .. } => {
                state.cursor = (position.x as i32, position.y as i32);
                if state.buttons != 0 {
                    // glutMotionFunc: called while any button is held.
                    state.input(Input::Drag(state.cursor.0, state.cursor.1));
                }
            }
            WindowEvent::MouseInput {
                state: button_state,
                button,
                ..
            } => {
                let bit = match button {
                    MouseButton::Left => 1,
                    MouseButton::Right => 2,
                    MouseButton::Middle => 4,
                    _ => 8,
                };
                if button_state == ElementState::Pressed {
                    state.buttons |= bit;
                    if button == MouseButton::Left {
                        state.input(Input::Press(state.cursor.0, state.cursor.1));
                    }
                } else {
                    state.buttons &= !bit;
                    if button == MouseButton::Left {
                        state.input(Input::Release(state.cursor.0, state.cursor.1));
                    }
                }
            }
            WindowEvent::RedrawRequested => {
                state.check_reload();
                if let Err(e) = state.redraw() {
                    self.error = Some(e);
                    event_loop.exit();
                }
                state.capture_frame();
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        if let Some(state) = self.state.as_mut() {
            let drawing = !state.paused() && (state.unpaced || state.animated() || state.dirty > 0);
            if let Some(log) = state.test_log.as_mut().filter(|l| l.busy && !drawing) {
                log.busy = false;
                log.say("idle");
            }
        }
        let Some(state) = &self.state else { return };
        let now = Instant::now();
        if state.paused() {
            // Nothing to draw: sleep until a window event (resize, map, uncover, key) wakes the
            // loop, instead of spinning at 100% CPU. The test hook still needs its deadline.
            match state.lose_device_at {
                Some(at) if now >= at => state.window.request_redraw(),
                Some(at) => event_loop.set_control_flow(ControlFlow::WaitUntil(at)),
                None => event_loop.set_control_flow(ControlFlow::Wait),
            }
        } else if !state.unpaced && !state.animated() && state.dirty == 0 {
            // Nothing changes: sleep until an event (input, resize, expose) wakes the loop,
            // looking at the shader folder a few times a second for live reload.
            if state.reload.is_some() {
                let Some(state) = self.state.as_mut() else { return };
                state.check_reload();
                let wake = now + Duration::from_millis(100);
                event_loop.set_control_flow(ControlFlow::WaitUntil(wake));
                if state.dirty > 0 {
                    state.window.request_redraw();
                }
            } else {
                event_loop.set_control_flow(ControlFlow::Wait);
            }
        } else if state.unpaced || now >= state.next_frame {
            event_loop.set_control_flow(ControlFlow::Poll);
            state.window.request_redraw();
        } else {
            // Input still wakes the loop at once; only drawing waits for its turn.
            event_loop.set_control_flow(ControlFlow::WaitUntil(state.next_frame));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zero_sized_windows_are_not_drawn() {
        assert_eq!(surface_size(PhysicalSize::new(640, 360)), Some((640, 360)));
        assert_eq!(surface_size(PhysicalSize::new(50, 1)), Some((50, 1)));
        assert_eq!(surface_size(PhysicalSize::new(200, 0)), None);
        assert_eq!(surface_size(PhysicalSize::new(0, 200)), None);
        assert_eq!(surface_size(PhysicalSize::new(0, 0)), None);
    }

    #[test]
    fn frames_are_paced_a_little_faster_than_the_monitor() {
        let ms = |d: Duration| d.as_secs_f64() * 1000.0;
        assert!((ms(frame_interval(Some(60_000))) - 1000.0 / 66.0).abs() < 0.01);
        assert!((ms(frame_interval(Some(144_000))) - 1000.0 / 158.4).abs() < 0.01);
        // Unknown or absurd rates: 60 Hz.
        for unknown in [None, Some(0), Some(5_000), Some(10_000_000)] {
            assert!(
                (ms(frame_interval(unknown)) - 1000.0 / 66.0).abs() < 0.01,
                "{unknown:?}"
            );
        }
    }
}
