//! The window: winit events mapped to the original's GLUT callbacks, a surface that follows
//! resizes (height 0 is treated as 1, minimising pauses drawing), F12 screenshots and live
//! shader reload. Effects never see winit; this module calls [`Lab`]'s plain methods.

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Arc};
use std::time::{Duration, Instant};

use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, KeyEvent, MouseButton, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::{Key, NamedKey};
use winit::window::{Window, WindowId};

use crate::cli::LabArgs;
use crate::effect::{Effect, Lab};
use crate::error::{Error, Result};
use crate::gpu::Gpu;
use crate::offscreen::{depth_texture, save_png};
use crate::shader::ShaderSource;

/// Whether a window can be opened (an X11 or Wayland display is named in the environment).
pub fn has_display() -> bool {
    std::env::var_os("DISPLAY").is_some_and(|d| !d.is_empty())
        || std::env::var_os("WAYLAND_DISPLAY").is_some_and(|d| !d.is_empty())
}

/// Opens the lab in a window and runs until Esc or close.
pub fn run_window<E: Effect>(args: &LabArgs) -> Result<()> {
    let event_loop = EventLoop::new().map_err(|e| Error::Surface(format!("cannot open a window: {e}")))?;
    event_loop.set_control_flow(ControlFlow::Poll);
    // Live reload needs files: --shaders DIR, else shaders_glsl/ of the source tree, else the built-in copies.
    let source = match args.shader_source()? {
        ShaderSource::Embedded => ShaderSource::source_tree().unwrap_or(ShaderSource::Embedded),
        dir => dir,
    };
    let mut app = App::<E> { args: args.clone(), source, state: None, error: None };
    event_loop
        .run_app(&mut app)
        .map_err(|e| Error::Surface(format!("event loop failed: {e}")))?;
    match app.error {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

struct App<E: Effect> {
    args: LabArgs,
    source: ShaderSource,
    state: Option<WindowState<E>>,
    error: Option<Error>,
}

struct WindowState<E: Effect> {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    depth: wgpu::TextureView,
    gpu: Gpu,
    lab: Lab<E>,
    start: Instant,
    clock_scale: f64,
    time_offset: f32,
    cursor: (i32, i32),
    buttons: u32,
    minimised: bool,
    shader_error: bool,
    device_lost: Arc<AtomicBool>,
    reload: Option<(notify::RecommendedWatcher, mpsc::Receiver<()>)>,
    screenshots: u32,
}

impl<E: Effect> App<E> {
    fn init(&mut self, event_loop: &ActiveEventLoop) -> Result<WindowState<E>> {
        let (width, height) = self.args.size;
        let attributes = Window::default_attributes()
            .with_title(format!("{} {}", E::TITLE, E::LABEL))
            .with_inner_size(PhysicalSize::new(width, height));
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .map_err(|e| Error::Surface(format!("cannot create a window: {e}")))?,
        );
        let instance = Gpu::new_instance();
        let surface = instance
            .create_surface(window.clone())
            .map_err(|e| Error::Surface(e.to_string()))?;
        let gpu = pollster::block_on(Gpu::new(instance, Some(&surface)))?;
        let caps = surface.get_capabilities(&gpu.adapter);
        // GL's default framebuffer does no sRGB encoding: prefer a plain UNORM format.
        let format = [wgpu::TextureFormat::Bgra8Unorm, wgpu::TextureFormat::Rgba8Unorm]
            .into_iter()
            .find(|f| caps.formats.contains(f))
            .or_else(|| caps.formats.first().copied())
            .ok_or_else(|| Error::Surface("the surface supports no formats".into()))?;
        let size = window.inner_size();
        let config = wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            format,
            color_space: Default::default(),
            width: size.width.max(1),
            height: size.height.max(1),
            desired_maximum_frame_latency: 2,
            present_mode: wgpu::PresentMode::Fifo,
            alpha_mode: caps.alpha_modes.first().copied().unwrap_or(wgpu::CompositeAlphaMode::Auto),
            view_formats: vec![],
        };
        surface.configure(&gpu.device, &config);
        let device_lost = Arc::new(AtomicBool::new(false));
        let lost = device_lost.clone();
        gpu.device.set_device_lost_callback(move |_, _| lost.store(true, Ordering::SeqCst));
        gpu.device.on_uncaptured_error(Arc::new(|e| eprintln!("wgpu error: {e}")));
        let depth = depth_texture(&gpu.device, config.width, config.height);
        let mut lab = Lab::<E>::new(&gpu, self.source.clone(), format)?;
        self.args.apply(&mut lab)?;
        let reload = match &self.source {
            ShaderSource::Dir(dir) => watch(dir),
            ShaderSource::Embedded => None,
        };
        let clock_scale = std::env::var("SHADERLAB_CLOCK_SCALE")
            .ok()
            .and_then(|s| s.parse::<f64>().ok())
            .filter(|s| s.is_finite() && *s > 0.0)
            .unwrap_or(1.0);
        window.set_title(&lab.title());
        Ok(WindowState {
            window,
            surface,
            config,
            depth,
            gpu,
            lab,
            start: Instant::now(),
            clock_scale,
            time_offset: self.args.time.unwrap_or(0.0),
            cursor: (0, 0),
            buttons: 0,
            minimised: false,
            shader_error: false,
            device_lost,
            reload,
            screenshots: 0,
        })
    }
}

fn watch(dir: &std::path::Path) -> Option<(notify::RecommendedWatcher, mpsc::Receiver<()>)> {
    use notify::Watcher;
    let (tx, rx) = mpsc::channel();
    let mut watcher = notify::recommended_watcher(move |event: notify::Result<notify::Event>| {
        if let Ok(event) = event {
            if event.kind.is_modify() || event.kind.is_create() {
                let _ = tx.send(());
            }
        }
    })
    .map_err(|e| eprintln!("live reload disabled: {e}"))
    .ok()?;
    watcher
        .watch(dir, notify::RecursiveMode::NonRecursive)
        .map_err(|e| eprintln!("live reload disabled: cannot watch {}: {e}", dir.display()))
        .ok()?;
    Some((watcher, rx))
}

impl<E: Effect> WindowState<E> {
    fn update_title(&self) {
        let mut title = self.lab.title();
        if self.shader_error {
            title.push_str(" | SHADER ERROR (see terminal)");
        }
        self.window.set_title(&title);
    }

    fn resize(&mut self, size: PhysicalSize<u32>) {
        // The original treats height 0 as 1; a surface cannot be 0 pixels, so a zero-sized
        // (minimised) window is simply not drawn until it has a size again.
        self.minimised = size.width == 0 || size.height == 0;
        if self.minimised {
            return;
        }
        self.config.width = size.width;
        self.config.height = size.height;
        self.surface.configure(&self.gpu.device, &self.config);
        self.depth = depth_texture(&self.gpu.device, size.width, size.height);
    }

    fn check_reload(&mut self) {
        let Some((_, rx)) = &self.reload else { return };
        if rx.try_recv().is_err() {
            return;
        }
        // Editors write in several steps: let them finish, then drain the queue.
        std::thread::sleep(Duration::from_millis(50));
        while rx.try_recv().is_ok() {}
        match self.lab.reload(&self.gpu) {
            Ok(()) => {
                if self.shader_error {
                    eprintln!("{}: shaders reloaded, error fixed", E::NAME);
                } else {
                    eprintln!("{}: shaders reloaded", E::NAME);
                }
                self.shader_error = false;
            }
            Err(e) => {
                eprintln!("{}: shader error (keeping the last good pipeline):\n{e}", E::NAME);
                self.shader_error = true;
            }
        }
        self.update_title();
    }

    fn screenshot(&mut self) {
        self.screenshots += 1;
        let stamp = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map(|d| d.as_secs())
            .unwrap_or(0);
        let path = PathBuf::from(format!("{}-{stamp}-{}.png", E::NAME, self.screenshots));
        let (w, h) = (self.config.width, self.config.height);
        match self.lab.screenshot(&self.gpu, w, h).and_then(|image| save_png(&image, &path)) {
            Ok(()) => println!("screenshot: {}", std::fs::canonicalize(&path).unwrap_or(path).display()),
            Err(e) => eprintln!("{}: screenshot failed: {e}", E::NAME),
        }
    }

    fn redraw(&mut self) -> Result<()> {
        if self.device_lost.load(Ordering::SeqCst) {
            return Err(Error::Device("the GPU device was lost".into()));
        }
        if self.minimised {
            return Ok(());
        }
        if self.args_time_is_clock() {
            let elapsed = self.start.elapsed().as_secs_f64() * self.clock_scale;
            self.lab.scene.time = self.time_offset + elapsed as f32;
        }
        let frame = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(frame) | wgpu::CurrentSurfaceTexture::Suboptimal(frame) => frame,
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => return Ok(()),
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                let size = self.window.inner_size();
                self.resize(size);
                return Ok(());
            }
            other => return Err(Error::Surface(format!("cannot get a frame: {other:?}"))),
        };
        let view = frame.texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some("window.frame"),
            ..Default::default()
        });
        let (w, h) = (self.config.width, self.config.height);
        self.lab.render(&self.gpu, &view, &self.depth, w, h);
        self.window.pre_present_notify();
        self.gpu.queue.present(frame);
        Ok(())
    }

    fn args_time_is_clock(&self) -> bool {
        self.lab.params_layout().member("time").is_some()
    }

    fn key(&mut self, event: &KeyEvent, event_loop: &ActiveEventLoop) {
        if event.state != ElementState::Pressed {
            return;
        }
        match &event.logical_key {
            Key::Named(NamedKey::Escape) => event_loop.exit(),
            Key::Named(NamedKey::F12) => self.screenshot(),
            _ => {
                let text = event.text.as_deref().or(match &event.logical_key {
                    Key::Character(s) => Some(s.as_str()),
                    _ => None,
                });
                let mut chars = text.unwrap_or("").chars();
                if let (Some(c), None) = (chars.next(), chars.next()) {
                    if self.lab.key(c) {
                        self.update_title();
                    }
                }
            }
        }
    }
}

impl<E: Effect> ApplicationHandler for App<E> {
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
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => state.resize(size),
            WindowEvent::KeyboardInput { event, .. } => state.key(&event, event_loop),
            WindowEvent::CursorMoved { position, .. } => {
                state.cursor = (position.x as i32, position.y as i32);
                if state.buttons != 0 {
                    // glutMotionFunc: called while any button is held.
                    state.lab.mouse_motion(state.cursor.0, state.cursor.1);
                }
            }
            WindowEvent::MouseInput { state: button_state, button, .. } => {
                let bit = match button {
                    MouseButton::Left => 1,
                    MouseButton::Right => 2,
                    MouseButton::Middle => 4,
                    _ => 8,
                };
                if button_state == ElementState::Pressed {
                    state.buttons |= bit;
                    if button == MouseButton::Left {
                        state.lab.mouse_press(state.cursor.0, state.cursor.1);
                    }
                } else {
                    state.buttons &= !bit;
                }
            }
            WindowEvent::RedrawRequested => {
                state.check_reload();
                if let Err(e) = state.redraw() {
                    self.error = Some(e);
                    event_loop.exit();
                }
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, _event_loop: &ActiveEventLoop) {
        if let Some(state) = &self.state {
            state.window.request_redraw();
        }
    }
}
