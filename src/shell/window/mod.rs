//! The window: winit's events turned into the [`Session`]'s (the lab, its clock, keys and
//! mouse, written once for the window and the page), a `Screen` the frames reach (the
//! swapchain or X shared memory), and what only a desktop window has: F12 screenshots, F10
//! recordings, the F1 panel drawn with egui, whole-frame views in place of the picture (a line
//! clicked in F2's listing, F3 cost, F4 diff: [`super::views`]), live shader reload from
//! files, pacing near the
//! monitor's refresh rate, and signals. Labs never see winit.
//!
//! Nothing is drawn when nothing changes: a lab that is not animated is redrawn after input,
//! a resize, an expose or a reload only, so an idle window costs no CPU (the originals redraw
//! continuously from `glutIdleFunc`). While the window has no area (zero-sized or minimised)
//! or is fully covered, nothing is drawn and the loop sleeps until the next window event, and
//! frames are paced near the monitor's refresh rate ([`frame_interval`]) for drivers whose FIFO
//! presentation does not wait for vertical sync.
//!
//! A window another program destroyed ends the process with one clear message and exit status
//! 1 whatever the window is doing (drawing, paused, recording), noticed by winit or by the
//! window's own watch on the X server ([`gone`]); a recording running is kept.
//!
//! A lost GPU device (or a GPU out of memory) ends the event loop with one clear message and
//! exit status 1, never a panic; a frame that never ends (the watchdog, `--timeout`) stops
//! drawing with the title saying so, and Esc or close then end the process at once. A panic
//! ends it as an internal error with the panic's message and place, except winit's on a window
//! another program destroyed, which says so.
//!
//! Live reload compiles off the frame loop ([`super::reload`]): a saved shader builds the lab
//! anew on a worker thread while the last good pipeline keeps drawing; a compile that fails or
//! panics leaves it drawing, with SHADER ERROR in the title and the message in the terminal.
//!
//! Test hooks: `SHADERLAB_TEST_LOSE_DEVICE=SECONDS` destroys the GPU device that many seconds
//! after the window opens, so the tests can check what a lost device looks like.
//! `SHADERLAB_TEST_LOG=1` writes the window's own signals to stderr, so that a test waits for
//! the program instead of for a time a busy machine can exceed: `shaderlab-test: frame N` after
//! each frame is shown, `shaderlab-test: sync` when the key F11 arrives (every event sent before
//! it has then been handled), `shaderlab-test: idle` when the window has nothing more to
//! draw after one of those, `shaderlab-test: inspected X,Y rgba(R, G, B, A)` when F2's
//! inspector has a new result, and `shaderlab-test: compile N started` / `compile N ended`
//! around live reload's compile of the Nth save, `shaderlab-test: view WxH` (or `view error:
//! …`) when a whole-frame view has a new picture. `SHADERLAB_TEST_VIEW=FILE:LINE` chooses that
//! line's view when the first inspection arrives, as a click on it in the inspector's listing
//! does. `SHADERLAB_TEST_PANIC=init` panics while the
//! window opens, `=reload` inside each live reload's compile, so that the tests can check
//! what a panic looks like.
//! `SHADERLAB_TEST_PANEL=1` opens with F1's panel shown, for a display the tests cannot send
//! keys to (a headless Wayland compositor). `SHADERLAB_TEST_IGNORE_DESTROYED=1` ignores winit's
//! `WindowEvent::Destroyed`, so that the tests can check that a window whose destruction winit
//! does not report still ends ([`gone`]).

mod gone;
mod recording;
mod screen;
#[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
mod shm;

use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, KeyEvent, MouseButton, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::{Key, NamedKey};
use winit::window::{Window, WindowId};

use crate::error::{Error, Result};
use crate::gpu::Gpu;
use crate::lab::{LabEntry, UserFiles};
use crate::offscreen::save_png;
use crate::params::Params;
use crate::shader::ShaderSource;

use super::args::Args;
use super::reload::{self, LiveReload};
use super::session::{Button, Platform, Session, Sources};
use screen::{Screen, Shown};

pub use screen::surface_size;

/// Frames per second when the monitor does not say its refresh rate.
const DEFAULT_REFRESH_HZ: f64 = 60.0;

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

/// Whether a window can be opened: a Wayland compositor named in `WAYLAND_DISPLAY` or an X
/// server named in `DISPLAY` (winit prefers Wayland when both are set).
pub fn has_display() -> bool {
    let named = |var: &str| std::env::var_os(var).is_some_and(|d| !d.is_empty());
    named("WAYLAND_DISPLAY") || named("DISPLAY")
}

/// Why [`has_display`] is false, in words a user can act on.
pub fn no_display_reason() -> &'static str {
    "neither WAYLAND_DISPLAY nor DISPLAY is set"
}

/// The display the window opens on, for messages: `WAYLAND_DISPLAY=…` or `DISPLAY=…`.
fn display_named() -> String {
    match std::env::var("WAYLAND_DISPLAY") {
        Ok(d) if !d.is_empty() => format!("WAYLAND_DISPLAY={d}"),
        _ => format!("DISPLAY={}", std::env::var("DISPLAY").unwrap_or_default()),
    }
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
            "cannot open a window on {}: {}",
            display_named(),
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
        proxy: event_loop.create_proxy(),
        args: args.clone(),
        params: Some(params),
        source,
        files: Arc::new(files),
        state: None,
        error: None,
        gone: gone::Gone::default(),
    };
    // A panic in the window is said as an error of its own, not as a crash report: winit's X11
    // backend panics when another program destroys the window (`xdotool windowclose`), and
    // anything else is an internal error, with the panic's message and place.
    let outcome = crate::panics::contained(|| event_loop.run_app(&mut app));
    // A recording still running is kept, not lost, however the window ended: Esc, closed by
    // the window manager or destroyed by another program, a signal, an error. Its frames are
    // drawn offscreen, so the window is not needed to finish it.
    if let Some(state) = app.state.as_mut() {
        state.finish_recording();
    }
    if crate::gpu::hung() {
        // A frame never ended: dropping the window's GPU objects would wait for it for ever.
        eprintln!(
            "{}: error: the GPU did not finish a frame (said above); ended without waiting for it",
            app.entry.info.name
        );
        crate::fsutil::signals::exit_now(1);
    }
    let error = match outcome {
        Ok(Ok(())) => app.error.take(),
        Ok(Err(e)) => Some(Error::Surface(format!("event loop failed: {e}"))),
        Err(report) if report.window_destroyed() => Some(gone::error()),
        Err(report) => Some(report.into_error()),
    };
    if app.state.as_ref().is_some_and(|s| s.reload.compiling()) {
        // A compile still runs on a worker thread, maybe for minutes inside the driver's
        // compiler, and can be neither stopped nor waited for: end the process now, as it
        // would have ended.
        match error {
            Some(Error::Interrupted { signal }) => crate::fsutil::signals::end_by(signal),
            Some(e) => {
                eprintln!("{}: error: {e}", app.entry.info.name);
                crate::fsutil::signals::exit_now(1)
            }
            None => crate::fsutil::signals::exit_now(0),
        }
    }
    match error {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

/// What wakes the window's event loop from outside it.
#[derive(Debug, Clone, Copy)]
enum Wake {
    /// A deferred signal (its number).
    Signal(i32),
    /// A compile on a worker thread ended ([`Compiles`]).
    Compiled,
    /// Another program destroyed the window ([`gone`]).
    Gone,
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
                } else if n == 0 || std::io::Error::last_os_error().kind() != std::io::ErrorKind::Interrupted {
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

struct App {
    entry: &'static LabEntry,
    /// Wakes the event loop from other threads.
    proxy: winit::event_loop::EventLoopProxy<Wake>,
    args: Args,
    params: Option<Params>,
    source: ShaderSource,
    files: Arc<UserFiles>,
    state: Option<WindowState>,
    error: Option<Error>,
    /// Whether another program destroyed the window, from the window's opening on.
    gone: gone::Gone,
}

/// Why the device can no longer be used, set from wgpu's callbacks (other threads).
type Fatal = Arc<Mutex<Option<String>>>;

/// When frames are drawn, and how long they take.
struct Pacing {
    /// `--unpaced`: as fast as possible, with a frame-time report every 2 s.
    unpaced: bool,
    /// Shortest time between two frames, and when the next one is due.
    interval: Duration,
    next: Instant,
    /// With `--unpaced`: frames drawn since `counted_since`.
    counted: u32,
    counted_since: Instant,
    /// Milliseconds between frames, smoothed, and when the last frame was drawn.
    frame_ms: f64,
    last: Instant,
    /// When the frame being drawn started.
    started: Instant,
}

struct WindowState {
    window: Arc<Window>,
    /// Shared with the compiles running on worker threads.
    gpu: Arc<Gpu>,
    screen: Screen,
    session: Session,
    /// Live reload from the shader files and the lab's input files.
    reload: LiveReload,
    /// The window's start: the clock's second 0.
    start: Instant,
    pacing: Pacing,
    /// The window has no area: nothing to draw.
    minimised: bool,
    /// The window is fully covered (X11 visibility): nothing to draw.
    occluded: bool,
    /// Whether another program destroyed the window, and the watch that notices it.
    gone: gone::Gone,
    _watch: Option<gone::Watch>,
    /// `SHADERLAB_TEST_IGNORE_DESTROYED`: winit's `Destroyed` is not acted on.
    ignore_destroyed: bool,
    fatal: Fatal,
    lose_device_at: Option<Instant>,
    /// Screenshots and recordings named so far (`NAME-SECONDS-PID-N.EXT`).
    named: u32,
    /// F10's recording, while one runs.
    recording: Option<recording::Recording>,
    /// F1's parameter panel.
    panel: super::panel::Panel,
    /// Why drawing stopped for good: a frame did not finish within the watchdog (a shader that
    /// never ends). The window then only answers Esc and close.
    stuck: Option<String>,
    /// `SHADERLAB_TEST_LOG`'s signals.
    test_log: Option<TestLog>,
    /// `SHADERLAB_TEST_VIEW`'s line (`FILE:LINE`), chosen as a click on it in the inspector's
    /// listing would when the first inspection arrives.
    test_view: Option<String>,
}

/// The window's signals for tests (see the module docs).
#[derive(Default)]
struct TestLog {
    frames: u64,
    /// Whether a frame was shown (or F11 arrived) since the last `idle` was written.
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
        if std::env::var("SHADERLAB_TEST_PANIC").as_deref() == Ok("init") {
            panic!("SHADERLAB_TEST_PANIC=init");
        }
        let (width, height) = self.args.size(entry);
        let attributes = Window::default_attributes()
            .with_title(format!("{} {}", entry.info.original_title, entry.info.label))
            .with_inner_size(PhysicalSize::new(width, height));
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .map_err(|e| Error::Surface(format!("cannot create a window: {e}")))?,
        );
        let proxy = self.proxy.clone();
        let watch = gone::watch(&window, self.gone.clone(), move || {
            let _ = proxy.send_event(Wake::Gone);
        });
        self.open(window.clone(), watch).map_err(|e| {
            // A window destroyed while it opens fails in words that do not say so (no adapter
            // can draw into it, say): say what happened instead.
            if self.gone.is() || !gone::exists(&window) {
                gone::error()
            } else {
                e
            }
        })
    }

    /// The rest of [`Self::init`]: the GPU, the screen and the lab for `window`.
    fn open(&mut self, window: Arc<Window>, gone_watch: Option<gone::Watch>) -> Result<WindowState> {
        let entry = self.entry;
        let panic_in_compile = std::env::var("SHADERLAB_TEST_PANIC").is_ok_and(|p| p == "reload");
        // The primary backends first, GL only where they cannot draw into this window.
        let (mut gpu, surface) = match Self::connect(Gpu::new_instance(), &window) {
            Err(e @ (Error::NoAdapter(_) | Error::Surface(_))) => match Gpu::fallback_instance() {
                Some(gl) => Self::connect(gl, &window).map_err(|fallback| match fallback {
                    Error::NoAdapter(_) | Error::Surface(_) => e,
                    other => other,
                })?,
                None => return Err(e),
            },
            result => result?,
        };
        gpu.watchdog = self.args.watchdog();
        let fatal: Fatal = Arc::new(Mutex::new(None));
        let slot = fatal.clone();
        super::surface::on_trouble(&gpu, move |trouble| match trouble {
            super::surface::Trouble::Error(_) => eprintln!("{trouble}"),
            fatal => {
                if let Ok(mut slot) = slot.lock() {
                    slot.get_or_insert(fatal.to_string());
                }
            }
        });
        let screen = Screen::new(
            entry.info.name,
            &gpu,
            window.clone(),
            surface,
            self.args.unpaced,
            self.gone.clone(),
        )?;
        let size = window.inner_size();
        let env_seconds = |name: &str| {
            std::env::var(name)
                .ok()
                .and_then(|s| s.trim().parse::<f64>().ok())
                .filter(|s| s.is_finite() && *s >= 0.0)
        };
        let clock_scale = env_seconds("SHADERLAB_CLOCK_SCALE").filter(|s| *s > 0.0).unwrap_or(1.0);
        // The first build has no last good pipeline to keep drawing: it is bounded as the
        // command line's are, and live reloads compile beside the window instead.
        gpu.bounded_compiles = true;
        let sources = Sources {
            source: self.source.clone(),
            files: self.files.clone(),
            format: screen.format(),
        };
        let mut session = Session::open(entry, &gpu, sources, Platform::NATIVE, 0.0, clock_scale)?;
        gpu.bounded_compiles = false;
        if let Some(params) = self.params.take() {
            session = session.with_params(params);
        }
        let lose_device_at = env_seconds("SHADERLAB_TEST_LOSE_DEVICE")
            .and_then(|s| Duration::try_from_secs_f64(s).ok())
            .map(|d| Instant::now() + d);
        let refresh_millihertz = window.current_monitor().and_then(|m| m.refresh_rate_millihertz());
        window.set_title(&session.title());
        let mut panel = super::panel::Panel::new(&window);
        panel.shown = std::env::var_os("SHADERLAB_TEST_PANEL").is_some();
        let now = Instant::now();
        let proxy = self.proxy.clone();
        let wake = Arc::new(move || {
            let _ = proxy.send_event(Wake::Compiled);
        });
        let reload = LiveReload::new(session.sources(), wake, panic_in_compile);
        Ok(WindowState {
            gpu: Arc::new(gpu),
            screen,
            session,
            reload,
            start: now,
            pacing: Pacing {
                unpaced: self.args.unpaced,
                interval: frame_interval(refresh_millihertz),
                next: now,
                counted: 0,
                counted_since: now,
                frame_ms: 0.0,
                last: now,
                started: now,
            },
            minimised: surface_size(size).is_none(),
            occluded: false,
            gone: self.gone.clone(),
            _watch: gone_watch,
            ignore_destroyed: std::env::var_os("SHADERLAB_TEST_IGNORE_DESTROYED").is_some(),
            window,
            fatal,
            lose_device_at,
            named: 0,
            recording: None,
            panel,
            stuck: None,
            test_log: std::env::var_os("SHADERLAB_TEST_LOG").map(|_| TestLog::default()),
            test_view: std::env::var("SHADERLAB_TEST_VIEW").ok(),
        })
    }
}

impl WindowState {
    fn name(&self) -> &'static str {
        self.session.name()
    }

    /// Seconds since the window opened, the clock's time base.
    fn now(&self) -> f64 {
        self.start.elapsed().as_secs_f64()
    }

    fn update_title(&self) {
        let mut title = self.session.title();
        if self.session.shader_error().is_some() {
            title.push_str(" | SHADER ERROR (see terminal)");
        }
        if self.reload.says_compiling() {
            title.push_str(" | compiling the shaders saved");
        }
        if self.stuck.is_some() {
            title.push_str(" | GPU STUCK: a frame never finished (see terminal); Esc quits");
        }
        if let Some(c) = &self.recording {
            title.push_str(&format!(" | REC {} frames (F10 stops)", c.frames()));
        }
        if let Some(view) = self.session.view() {
            title.push_str(&format!(" | VIEW {}", view.words()));
            if let Some(Err(_)) = self.session.view_shown() {
                title.push_str(" failed (see the panel)");
            }
        }
        self.window.set_title(&title);
    }

    /// Whether drawing is paused (nothing visible to draw into, or a frame that never ended).
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
        self.minimised = !self.screen.resize(&self.gpu, size);
        if !self.minimised {
            self.session.touched();
        }
    }

    /// Live reload, never blocking the frame loop ([`LiveReload::check`]): says what it did
    /// in the terminal, the title and the tests' signals.
    fn check_reload(&mut self) {
        let events = self.reload.check(&mut self.session, &self.gpu);
        let name = self.name();
        for event in &events {
            match event {
                reload::Event::Started(n) | reload::Event::Ended(n) => {
                    if let Some(log) = self.test_log.as_mut() {
                        let what = if matches!(event, reload::Event::Started(_)) {
                            "started"
                        } else {
                            "ended"
                        };
                        log.say(&format!("compile {n} {what}"));
                    }
                }
                reload::Event::Reloaded { fixed: true } => eprintln!("{name}: shaders reloaded, error fixed"),
                reload::Event::Reloaded { fixed: false } => eprintln!("{name}: shaders reloaded"),
                reload::Event::Failed(e) => eprintln!("{name}: shader error (keeping the last good pipeline):\n{e}"),
                reload::Event::Compiling(_) => {}
            }
        }
        let shown = events
            .iter()
            .any(|e| matches!(e, reload::Event::Reloaded { .. } | reload::Event::Failed(_)));
        if shown || events.iter().any(|e| matches!(e, reload::Event::Compiling(_))) {
            self.update_title();
        }
        if shown {
            self.window.request_redraw();
        }
    }

    /// A fresh name in the current directory: `NAME-SECONDS-PID-N.EXT` (F12 and F10).
    fn fresh_name(&mut self, extension: &str) -> PathBuf {
        self.named += 1;
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
                self.named
            ));
            if !path.exists() {
                return path;
            }
            self.named += 1;
        }
    }

    /// F10: starts or stops recording what the window shows.
    fn toggle_recording(&mut self) {
        match self.recording.take() {
            Some(recording) => report_recording(self.name(), recording),
            None => {
                let path = self.fresh_name("gif");
                match recording::Recording::start(&path) {
                    Ok(recording) => {
                        eprintln!("{}: recording to {} (F10 stops)", self.name(), path.display());
                        self.recording = Some(recording);
                        self.session.changed();
                    }
                    Err(e) => eprintln!("{}: cannot record: {e}", self.name()),
                }
            }
        }
        self.update_title();
    }

    /// Finishes F10's recording if one runs, without touching the window (which may be gone).
    fn finish_recording(&mut self) {
        if let Some(recording) = self.recording.take() {
            report_recording(self.name(), recording);
        }
    }

    /// Adds the frame just shown to F10's recording.
    fn record_frame(&mut self) {
        if self.stuck.is_some() {
            return;
        }
        let Some(recording) = self.recording.as_mut() else {
            return;
        };
        let (w, h) = self.screen.size();
        if let Err(e) = recording.add(&self.gpu, self.session.lab_mut(), w, h, self.screen.format()) {
            eprintln!("{}: recording stopped: {e}", self.session.name());
            self.recording = None;
        }
        self.update_title();
    }

    /// Draws the panel (when shown) over what the session drew into `target`, and hands what
    /// it changed or asked for to the session.
    fn draw_panel(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        format: wgpu::TextureFormat,
        size: (u32, u32),
    ) {
        let now = Instant::now();
        let ms = now.duration_since(self.pacing.last).as_secs_f64() * 1000.0;
        self.pacing.last = now;
        self.pacing.frame_ms = if self.pacing.frame_ms == 0.0 {
            ms
        } else {
            0.9 * self.pacing.frame_ms + 0.1 * ms
        };
        if !self.panel.shown && !self.session.inspecting() {
            self.panel.inspecting = false;
            return;
        }
        let draw_ms = self.pacing.started.elapsed().as_secs_f64() * 1000.0;
        let files: Vec<(String, String)> = (self.session.shader_files().into_iter())
            .map(|program| (program.vertex, program.fragment))
            .collect();
        let source = match (&self.session.sources().source, self.reload.watching()) {
            (ShaderSource::Dir(dir), true) => format!("from {} (reloads live)", dir.display()),
            (ShaderSource::Dir(dir), false) => format!("from {}", dir.display()),
            (ShaderSource::Embedded, _) => "built in".to_owned(),
            (ShaderSource::Edited(_), _) => "edited in memory".to_owned(),
        };
        let error = self.session.shader_error().map(str::to_owned);
        let words = self.view_words();
        let choices = self.session.view_choices().to_vec();
        let status = super::panel::Status {
            frame_ms: (self.session.animated() || self.pacing.unpaced).then_some(self.pacing.frame_ms),
            draw_ms,
            files,
            source,
            error: error.as_deref(),
            recording: self.recording.as_ref().map(recording::Recording::frames),
            view: words.clone(),
            choices: choices.clone(),
            can_diff: !matches!(self.session.sources().source, ShaderSource::Embedded),
        };
        let (inspecting, pixel, busy) = (
            self.session.inspecting(),
            self.session.inspected(),
            self.session.inspect_busy(),
        );
        let line = self
            .session
            .view()
            .and_then(super::views::Wanted::line_shown)
            .map(|(file, line)| (file.to_owned(), line));
        // A view shown keeps its legend strip in sight below the panels.
        let legend = if self.session.view().is_some() && !matches!(self.session.view_shown(), Some(Err(_))) {
            crate::debug::picture::LEGEND_HEIGHT
        } else {
            0
        };
        let inspect = inspecting.then_some(super::panel::InspectPanel {
            pixel,
            result: self.session.inspection(),
            busy,
            line,
            view: words,
            choices,
        });
        let (edits, request) = self.panel.draw(
            &self.gpu,
            &self.window,
            encoder,
            target,
            format,
            size,
            legend,
            self.session.lab(),
            &status,
            inspect.as_ref(),
        );
        for edit in &edits {
            let written = match edit {
                super::panel::Edit::Set(name, values) => self.session.set_values(name, values),
                super::panel::Edit::Reset => self.session.reset(),
            };
            if let Err(e) = written {
                eprintln!("{}: {e}", self.name());
            }
        }
        if !edits.is_empty() {
            self.update_title();
        }
        if self.panel.repaint {
            self.session.changed();
        }
        match request {
            Some(super::panel::Request::WriteShaders) => self.write_shaders(),
            Some(super::panel::Request::View(wanted)) => self.toggle_view(wanted),
            Some(super::panel::Request::Picture) => {
                self.session.show_view(&self.gpu, None);
                self.update_title();
            }
            None => {}
        }
    }

    /// The view shown, in words: what it is, then its legend or why it failed.
    fn view_words(&self) -> Option<String> {
        let wanted = self.session.view()?;
        Some(match self.session.view_shown() {
            None => format!("{} (drawing)", wanted.words()),
            Some(Ok(p)) => p.text.clone(),
            Some(Err(e)) => format!("{}: {e}", wanted.words()),
        })
    }

    /// Shows `wanted` in place of the picture (F3, F4, a line clicked in the inspector), or
    /// the picture again when it is the view shown ([`Session::toggle_view`]).
    fn toggle_view(&mut self, wanted: super::views::Wanted) {
        if let Some(words) = self.session.toggle_view(&self.gpu, wanted) {
            eprintln!("{}: {words}", self.name());
        }
        self.update_title();
        self.window.request_redraw();
    }

    /// The panel's button: the built-in shaders into `./NAME-shaders/` (a fresh name), then
    /// live reload from there, as `--shaders DIR` would. The folder is made empty (never an
    /// existing one) and its files appear together or not at all.
    fn write_shaders(&mut self) {
        let mut dir = PathBuf::from(format!("{}-shaders", self.name()));
        let mut n = 1;
        loop {
            match std::fs::create_dir(&dir) {
                Ok(()) => break,
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists && n < 10_000 => {
                    n += 1;
                    dir = PathBuf::from(format!("{}-shaders-{n}", self.name()));
                }
                Err(e) => {
                    eprintln!("{}: cannot write the shaders to {}: {e}", self.name(), dir.display());
                    return;
                }
            }
        }
        let mut batch = crate::fsutil::Batch::new(false);
        let written = crate::shader::embedded_names().try_for_each(|name| {
            let text = crate::shader::embedded_source(name).unwrap_or_default();
            batch.write(&dir.join(name), |w| w.write_all(text.as_bytes()))
        });
        if let Err(e) = written.and_then(|()| batch.commit()) {
            eprintln!("{}: cannot write the shaders to {}: {e}", self.name(), dir.display());
            let _ = std::fs::remove_dir(&dir);
            return;
        }
        let dir = std::fs::canonicalize(&dir).unwrap_or(dir);
        self.session.moved_to(ShaderSource::Dir(dir.clone()));
        self.reload.watch(self.session.sources());
        let _ = super::cli::say(&format!("shaders: {} (edit them; the lab reloads live)", dir.display()));
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
        // What the window shows (a view's picture, or the lab's frame drawn by the window's
        // own pipelines in its format), read back.
        let size = self.screen.size();
        match self
            .session
            .picture(&self.gpu, size)
            .and_then(|image| save_png(&image, &path))
        {
            Ok(()) => {
                let path = std::fs::canonicalize(&path).unwrap_or(path);
                let _ = super::cli::say(&format!("screenshot: {}", path.display()));
            }
            Err(e) => eprintln!("{}: screenshot failed: {e}", self.name()),
        }
    }

    /// Draws one frame: the lab, then the panel, into the screen's target, and shows it.
    fn redraw(&mut self) -> Result<()> {
        if self.gone.is() {
            return Err(gone::error());
        }
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
        self.pacing.started = Instant::now();
        // Pace from the previous deadline (no drift), but never plan a burst to catch up.
        let now = Instant::now();
        self.pacing.next = (self.pacing.next + self.pacing.interval).max(now);
        let clock = self.now();
        let fatal = self.fatal.clone();
        let name = self.name();
        let Some(target) = self.screen.target(&self.gpu, || {
            let message = fatal.lock().ok()?.clone()?;
            Some(Error::Wgpu {
                context: format!("the {name} window"),
                message,
            })
        })?
        else {
            // No frame to draw into this time (the surface was renewed).
            self.session.skipped(clock);
            return Ok(());
        };
        let mut encoder = self.gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("window.frame"),
        });
        let (w, h) = target.size;
        let drawn = super::session::Target {
            color: &target.color,
            depth: &target.depth,
            size: target.size,
        };
        let outcome = self.session.frame(&self.gpu, &mut encoder, &drawn, clock);
        if outcome.inspection {
            self.inspected();
        }
        if outcome.view {
            self.viewed((w, h));
        }
        if let Some(e) = outcome.error {
            // A lab may rebuild a program while drawing (a shading model chosen by key); a
            // broken shader file leaves the previous one in place, and the error is shown once.
            eprintln!("{}: {e}", self.name());
            self.update_title();
        }
        let color = target.color.clone();
        self.draw_panel(&mut encoder, &color, target.format, target.size);
        let shown = self.screen.present(&self.gpu, target, encoder)?;
        match shown {
            Shown::Yes => {}
            Shown::Again => self.session.changed(),
            Shown::Stuck(why) => {
                self.give_up(why);
                return Ok(());
            }
        }
        if let Some(e) = self.fatal_error() {
            return Err(e);
        }
        self.frame_shown();
        if self.pacing.unpaced {
            self.report_frame_time();
        }
        Ok(())
    }

    /// The view made a new picture, legend or error at `(w, h)`: the title, and the tests'
    /// signal.
    fn viewed(&mut self, (w, h): (u32, u32)) {
        self.update_title();
        if let Some(log) = self.test_log.as_mut() {
            log.say(&match self.session.view_shown() {
                Some(Ok(_)) => format!("view {w}x{h}"),
                Some(Err(e)) => format!("view error: {}", e.lines().next().unwrap_or("")),
                None => "view none".into(),
            });
        }
    }

    /// A new inspection arrived: the tests' signal, and the test hook's line chosen once as a
    /// click in the listing would.
    fn inspected(&mut self) {
        if let (Some(log), Some(shown)) = (self.test_log.as_mut(), self.session.inspection()) {
            log.say(&match shown {
                Ok(i) => {
                    let p = i.replayed.pixel;
                    format!("inspected {},{} rgba({}, {}, {}, {})", i.x, i.y, p[0], p[1], p[2], p[3])
                }
                Err(e) => format!("inspected error: {}", e.lines().next().unwrap_or("")),
            });
        }
        if let Some(wanted) = self.test_view.take().and_then(|t| super::views::Wanted::from_link(&t)) {
            self.toggle_view(wanted);
        }
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
        let pacing = &mut self.pacing;
        pacing.counted += 1;
        let elapsed = pacing.counted_since.elapsed();
        if elapsed >= Duration::from_secs(2) {
            let secs = elapsed.as_secs_f64();
            eprintln!(
                "{}: window {} frames in {secs:.2} s: ms_per_frame={:.3}",
                self.session.name(),
                pacing.counted,
                secs * 1000.0 / f64::from(pacing.counted)
            );
            pacing.counted = 0;
            pacing.counted_since = Instant::now();
        }
    }

    fn key(&mut self, event: &KeyEvent, event_loop: &ActiveEventLoop) {
        if event.state != ElementState::Pressed {
            return;
        }
        match &event.logical_key {
            Key::Named(NamedKey::Escape) => event_loop.exit(),
            Key::Named(NamedKey::F12) => self.screenshot(),
            Key::Named(NamedKey::F10) => self.toggle_recording(),
            Key::Named(NamedKey::F2) => {
                self.session.toggle_inspect();
                self.window.request_redraw();
            }
            Key::Named(NamedKey::F3) => self.toggle_view(super::views::Wanted::COST),
            Key::Named(NamedKey::F4) => self.toggle_view(super::views::Wanted::Diff),
            Key::Named(NamedKey::F1) => {
                self.panel.shown = !self.panel.shown;
                self.session.changed();
                self.window.request_redraw();
            }
            _ => {
                if let Some(name) = dom_key(event) {
                    let now = self.now();
                    if self.session.key(&name, now) {
                        self.update_title();
                    }
                }
            }
        }
    }
}

/// A key's name as the DOM's `KeyboardEvent.key` gives it, which [`Session::key`] reads: the
/// named keys GLUT knows by their names (`ArrowLeft`, `PageUp`), any other key by the one
/// character it types (Space is `" "`); `None` for a key that types nothing.
fn dom_key(event: &KeyEvent) -> Option<String> {
    let single = |s: &str| {
        let mut chars = s.chars();
        matches!((chars.next(), chars.next()), (Some(_), None)).then(|| s.to_owned())
    };
    match &event.logical_key {
        Key::Named(
            named @ (NamedKey::ArrowLeft
            | NamedKey::ArrowRight
            | NamedKey::ArrowUp
            | NamedKey::ArrowDown
            | NamedKey::PageUp
            | NamedKey::PageDown),
        ) => Some(format!("{named:?}")),
        Key::Named(_) => event.text.as_deref().and_then(single),
        Key::Character(s) => event.text.as_deref().or(Some(s.as_str())).and_then(single),
        _ => None,
    }
}

/// Finishes a recording and says where it is (or why it failed).
fn report_recording(name: &str, recording: recording::Recording) {
    let frames = recording.frames();
    match recording.finish() {
        Ok(path) => {
            let path = std::fs::canonicalize(&path).unwrap_or(path);
            let _ = super::cli::say(&format!("recording: {} ({frames} frames)", path.display()));
        }
        Err(e) => eprintln!("{name}: recording failed: {e}"),
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
            Wake::Compiled => {
                if let Some(state) = self.state.as_mut() {
                    state.check_reload();
                }
            }
            // The recording is finished on the way out (`run`), as for any other ending.
            Wake::Gone => {
                self.error.get_or_insert_with(gone::error);
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
            // The panel took it (a click on it, a key typed into one of its fields). The lab sees
            // nothing of it, but where the pointer is stays known: the next click on the
            // picture is where the pointer then is, not where it last left the picture.
            if let WindowEvent::CursorMoved { position, .. } = event {
                state.session.moved_over_panel(position.x as i32, position.y as i32);
            }
            state.session.changed();
            state.window.request_redraw();
            if let WindowEvent::MouseInput {
                state: ElementState::Released,
                ..
            } = event
            {
                state.session.release_all();
            }
            return;
        }
        if state.panel.shown && !matches!(event, WindowEvent::RedrawRequested) {
            // egui answers hover and focus on the next frame.
            state.session.changed();
        }
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            // Another program destroyed the window (`xdotool windowclose`): nothing is left to
            // draw into, and winit would fail on the next request about it.
            WindowEvent::Destroyed if !state.ignore_destroyed => {
                state.gone.set();
                self.error = Some(gone::error());
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
            WindowEvent::CursorMoved { position, .. } if state.session.moved(position.x as i32, position.y as i32) => {
                state.update_title();
            }
            WindowEvent::MouseInput {
                state: button_state,
                button,
                ..
            } => {
                let button = match button {
                    MouseButton::Left => Button::Left,
                    MouseButton::Right => Button::Right,
                    MouseButton::Middle => Button::Middle,
                    _ => Button::Other,
                };
                if state.session.button(button, button_state == ElementState::Pressed) {
                    state.update_title();
                }
            }
            WindowEvent::RedrawRequested => {
                state.check_reload();
                if let Err(e) = state.redraw() {
                    self.error = Some(e);
                    event_loop.exit();
                }
                state.record_frame();
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        let Some(state) = self.state.as_mut() else { return };
        if state.gone.is() {
            // However it was noticed (winit, the watch, the presenter): the window ends.
            self.error.get_or_insert_with(gone::error);
            event_loop.exit();
            return;
        }
        // What goes on between frames: a new inspection to show (the replay runs on a worker
        // thread of its own), a view waiting for the GPU.
        if state.session.busy() {
            let outcome = state.session.poll(&state.gpu, state.screen.size());
            if outcome.inspection {
                state.inspected();
            }
            if outcome.view {
                state.viewed(state.screen.size());
            }
        }
        let drawing = !state.paused() && (state.pacing.unpaced || state.session.wants_frame());
        if let Some(log) = state.test_log.as_mut().filter(|l| l.busy && !drawing) {
            log.busy = false;
            log.say("idle");
        }
        let now = Instant::now();
        if state.paused() {
            // Nothing to draw: sleep until a window event (resize, map, uncover, key) wakes the
            // loop, instead of spinning at 100% CPU. The test hook still needs its deadline.
            match state.lose_device_at {
                Some(at) if now >= at => state.window.request_redraw(),
                Some(at) => event_loop.set_control_flow(ControlFlow::WaitUntil(at)),
                None => event_loop.set_control_flow(ControlFlow::Wait),
            }
        } else if !state.pacing.unpaced && !state.session.wants_frame() {
            // Nothing changes: sleep until an event (input, resize, expose) wakes the loop,
            // looking at the shader folder a few times a second for live reload.
            if state.reload.watching() {
                state.check_reload();
                let wake = (now + Duration::from_millis(100))
                    .min(state.reload.wake_at().unwrap_or(now + Duration::from_secs(1)));
                event_loop.set_control_flow(ControlFlow::WaitUntil(wake));
                if state.session.dirty() > 0 {
                    state.window.request_redraw();
                }
            } else {
                event_loop.set_control_flow(ControlFlow::Wait);
            }
        } else if state.pacing.unpaced || now >= state.pacing.next {
            event_loop.set_control_flow(ControlFlow::Poll);
            state.window.request_redraw();
        } else {
            // Input still wakes the loop at once; only drawing waits for its turn.
            event_loop.set_control_flow(ControlFlow::WaitUntil(state.pacing.next));
        }
        if state.session.busy() {
            // An inspection in flight is looked at every few milliseconds until it is done.
            let soon = Instant::now() + Duration::from_millis(8);
            match event_loop.control_flow() {
                ControlFlow::Wait => event_loop.set_control_flow(ControlFlow::WaitUntil(soon)),
                ControlFlow::WaitUntil(t) if t > soon => event_loop.set_control_flow(ControlFlow::WaitUntil(soon)),
                _ => {}
            }
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
