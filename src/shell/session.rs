//! What every front end does with the lab it shows, written once: the window
//! ([`super::window`]) and the page (`shell::web`, in the browser build) each hold a
//! [`Session`] and keep only what their platform forces (where events come from, how a frame
//! reaches the screen, how the inspector's replay runs).
//!
//! A session opens the lab ([`Session::open`]; [`Session::open_lab`] builds one without a
//! session, for the headless runs and the window's live reload), lists its shader files
//! ([`Session::shader_files`]), draws the lab's frame into a view it is given
//! ([`Session::draw`]; [`Session::record`] leaves the encoder open for the window's panel)
//! through the one checked render ([`crate::lab::frame::draw`]), with the error to show, and
//! inspects a pixel of the frame it drew ([`Session::inspect_frame`], [`Session::inspect_poll`]
//! with the replay's runner handed in; [`super::inspector`]). It holds the lab (its parameters
//! with it), the clock of an animated lab, the frames still to draw after a change, the mouse
//! (GLUT's drag rule: the motion callback runs while any button is held, the press and release
//! callbacks are the left button's), the standing shader error, and turns key names into the
//! original's callbacks. The panel's model (which control each parameter gets, in which group)
//! is [`super::panel::widgets`], and the surface drawn into is [`super::surface::Swapchain`],
//! both shared too.

use super::clock::Clock;
use super::inspector::{Inspector, Job, Shown};
use super::views::{Picture, Views, Wanted};
use crate::error::{Error, Result};
use crate::gpu::Gpu;
use crate::lab::{Input, Lab, LabEntry, Special, UserFiles};
use crate::params::Params;
use crate::render::BuildContext;
use crate::shader::ShaderSource;

/// A mouse button.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Button {
    /// The left (primary) button: GLUT's press and release callbacks.
    Left,
    /// The middle button.
    Middle,
    /// The right button.
    Right,
    /// Any other.
    Other,
}

impl Button {
    fn bit(self) -> u32 {
        match self {
            Button::Left => 1,
            Button::Middle => 2,
            Button::Right => 4,
            Button::Other => 8,
        }
    }

    /// The DOM's `MouseEvent.button` number (0 left, 1 middle, 2 right).
    pub fn from_dom(button: i32) -> Button {
        match button {
            0 => Button::Left,
            1 => Button::Middle,
            2 => Button::Right,
            _ => Button::Other,
        }
    }
}

/// The lab a front end shows, and its state between frames (see the module docs).
pub struct Session {
    entry: &'static LabEntry,
    lab: Box<dyn Lab>,
    clock: Clock,
    /// Frames still to draw for a lab that is not animated (input, resize, reload).
    dirty: u32,
    buttons: u32,
    cursor: (i32, i32),
    shader_error: Option<String>,
    /// Bumped whenever what the lab draws may have changed (input, parameters, reload, time).
    version: u64,
    inspect: Inspect,
    /// The inspector's capture and replay in flight, and its last result.
    inspector: Inspector,
    /// The whole-frame view asked for, and its last picture.
    views: Views,
}

/// The pixel inspector's state: whether clicks pick a pixel (F2 in the window, the page's
/// inspect toggle), the pixel picked, and the state of the lab its last inspection was of.
#[derive(Clone, Debug, Default)]
struct Inspect {
    on: bool,
    pixel: Option<(u32, u32)>,
    /// The session's version the last capture was taken at.
    taken: Option<u64>,
    /// Where the left button went down in inspect mode: a click there picks the pixel, a
    /// drag still turns the object.
    press: Option<(i32, i32)>,
}

/// How far (in pixels) the mouse may move between press and release for a click.
const CLICK_SLOP: i32 = 2;

/// Frames drawn after a change: two, as a double-buffered window needs both its buffers new.
const FRAMES_AFTER_A_CHANGE: u32 = 2;

/// The shader files of one of the lab's programs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ProgramFiles {
    /// The vertex shader's file, as the lab names it.
    pub vertex: String,
    /// The fragment shader's file, as the lab names it.
    pub fragment: String,
    /// Every file the two shaders were spliced from (the files they include too), by display
    /// path, each once, in the order their lines come.
    pub spliced: Vec<String>,
}

impl Session {
    /// Builds `entry`'s lab on `gpu` from `source`, to draw in `format`, with the user's `files`:
    /// how every front end opens a lab (the headless runs and the window's live reload too).
    pub fn open_lab(
        entry: &'static LabEntry,
        gpu: &Gpu,
        source: &ShaderSource,
        format: wgpu::TextureFormat,
        files: &UserFiles,
    ) -> Result<Box<dyn Lab>> {
        (entry.new)(&BuildContext::new(gpu, source, format, files))
    }

    /// A session of `entry`'s lab, opened as [`Session::open_lab`] does, its clock starting at
    /// `now` (seconds on the front end's clock) and running `scale` times real time.
    pub fn open(
        entry: &'static LabEntry,
        gpu: &Gpu,
        source: &ShaderSource,
        format: wgpu::TextureFormat,
        files: &UserFiles,
        now: f64,
        scale: f64,
    ) -> Result<Session> {
        let lab = Session::open_lab(entry, gpu, source, format, files)?;
        Ok(Session::new(entry, lab, now, scale))
    }

    /// A session of `lab`, `entry`'s, its clock starting at `now` and running `scale` times
    /// real time.
    fn new(entry: &'static LabEntry, lab: Box<dyn Lab>, now: f64, scale: f64) -> Session {
        let clock = Clock::new(lab.as_ref(), now, scale);
        Session {
            entry,
            lab,
            clock,
            dirty: FRAMES_AFTER_A_CHANGE,
            buttons: 0,
            cursor: (0, 0),
            shader_error: None,
            version: 0,
            inspect: Inspect::default(),
            inspector: Inspector::default(),
            views: Views::default(),
        }
    }

    /// With the lab's parameters replaced by `params` (the command line's) before its first
    /// frame: the clock starts from their `time`.
    pub fn with_params(mut self, params: Params) -> Session {
        *self.lab.params_mut() = params;
        self.clock = self.clock.restarted(self.lab.as_ref());
        self
    }

    /// With the clock paused (a link that keeps its `time`).
    pub fn paused(mut self) -> Session {
        self.clock = self.clock.paused();
        self
    }

    /// The lab's list entry.
    pub fn entry(&self) -> &'static LabEntry {
        self.entry
    }

    /// The lab's name.
    pub fn name(&self) -> &'static str {
        self.entry.info.name
    }

    /// The lab.
    pub fn lab(&self) -> &dyn Lab {
        self.lab.as_ref()
    }

    /// The lab, to change.
    pub fn lab_mut(&mut self) -> &mut dyn Lab {
        self.lab.as_mut()
    }

    /// The lab, to change, beside the last inspection (the window's panel shows the one and
    /// edits the other's parameters).
    pub fn lab_and_inspection(&mut self) -> (&mut dyn Lab, Option<&Shown>) {
        (self.lab.as_mut(), self.inspector.shown())
    }

    /// Whether the clock is paused.
    pub fn is_paused(&self) -> bool {
        self.clock.is_paused()
    }

    /// Whether the lab's clock runs (an animated lab, not paused): such a lab is drawn every
    /// frame, others only after a change.
    pub fn animated(&self) -> bool {
        self.clock.runs(self.lab.as_ref())
    }

    /// Advances an animated lab's `time` to the clock at `now`.
    pub fn tick(&mut self, now: f64) {
        if self.animated() {
            self.version += 1;
        }
        self.clock.tick(self.lab.as_mut(), now);
    }

    /// Whether a frame should be drawn now (a view being read back is moved on by frames too).
    pub fn wants_frame(&self) -> bool {
        self.animated() || self.dirty > 0 || self.views.busy()
    }

    /// Frames still to draw after the last change.
    pub fn dirty(&self) -> u32 {
        self.dirty
    }

    /// Something changed (input, a resize, a reload, the panel): draw again.
    pub fn changed(&mut self) {
        self.dirty = self.dirty.max(FRAMES_AFTER_A_CHANGE);
    }

    /// The lab's state changed (a parameter, input, a reload): draw again, and inspect again.
    pub fn touched(&mut self) {
        self.changed();
        self.version += 1;
    }

    /// A frame was drawn.
    pub fn drawn(&mut self) {
        self.dirty = self.dirty.saturating_sub(1);
    }

    /// A key, by the DOM's name for it (`KeyboardEvent.key`, which winit's named keys share):
    /// the arrows and Page Up/Down are GLUT's special keys, Space pauses an animated lab's clock
    /// (at `now`), any other single character is the original's keyboard callback. Returns
    /// whether the session took it (the page then keeps the browser from scrolling).
    pub fn key(&mut self, key: &str, now: f64) -> bool {
        if key == " " && self.clock.toggle(self.lab.as_ref(), now) {
            self.touched();
            return true;
        }
        let special = match key {
            "ArrowLeft" => Some(Special::Left),
            "ArrowRight" => Some(Special::Right),
            "ArrowUp" => Some(Special::Up),
            "ArrowDown" => Some(Special::Down),
            "PageUp" => Some(Special::PageUp),
            "PageDown" => Some(Special::PageDown),
            _ => None,
        };
        if let Some(special) = special {
            self.input(Input::Special(special));
            return true;
        }
        let mut chars = key.chars();
        match (chars.next(), chars.next()) {
            (Some(c), None) => {
                self.input(Input::Key(c));
                true
            }
            _ => false,
        }
    }

    /// A mouse button went down or up at the cursor; returns whether the lab's state (and so
    /// its title) changed.
    pub fn button(&mut self, button: Button, down: bool) -> bool {
        let (x, y) = self.cursor;
        if self.inspect.on && button == Button::Left {
            if down {
                self.inspect.press = Some((x, y));
            } else if let Some((px, py)) = self.inspect.press.take() {
                // A click (not a drag) picks the pixel under the cursor.
                if (x - px).abs() <= CLICK_SLOP && (y - py).abs() <= CLICK_SLOP && x >= 0 && y >= 0 {
                    self.inspect_pixel(Some((x as u32, y as u32)));
                }
            }
        }
        if down {
            self.buttons |= button.bit();
        } else {
            self.buttons &= !button.bit();
        }
        button == Button::Left && self.input(if down { Input::Press(x, y) } else { Input::Release(x, y) })
    }

    /// Every button went up without the lab seeing it (a click the panel took).
    pub fn release_all(&mut self) {
        self.buttons = 0;
    }

    /// The mouse moved to (x, y), window pixels from the top left: a drag while any button is
    /// held (`glutMotionFunc`). Returns whether the lab's state (and so its title) changed.
    pub fn moved(&mut self, x: i32, y: i32) -> bool {
        self.cursor = (x, y);
        self.buttons != 0 && self.input(Input::Drag(x, y))
    }

    /// The mouse moved to (x, y) over something drawn above the lab (the window's panels): the
    /// lab sees no motion, but a button pressed next is where the mouse is.
    pub fn moved_over_panel(&mut self, x: i32, y: i32) {
        self.cursor = (x, y);
    }

    /// Hands `input` to the lab; returns whether its state (and so its title) changed.
    pub fn input(&mut self, input: Input) -> bool {
        self.touched();
        self.lab.input(input)
    }

    /// Sets a parameter from text, as `--set name=value`, checking the lab's rules between
    /// parameters; a refused value is undone.
    pub fn set(&mut self, name: &str, value: &str) -> Result<()> {
        let p = self.lab.params_mut();
        let before = p.clone();
        let result = p.set_str(name, value).and_then(|_| p.check());
        if result.is_err() {
            *p = before;
        } else {
            self.touched();
        }
        result
    }

    /// The lab's title: the original's, then its state.
    pub fn title(&self) -> String {
        self.lab.title()
    }

    /// The shader error that stands (its message), if the last reload or a shading model chosen
    /// by key failed; the last good pipeline draws meanwhile.
    pub fn shader_error(&self) -> Option<&str> {
        self.shader_error.as_deref()
    }

    /// Compiles the lab's shaders again from `source` (an edit on the page), with what it was
    /// opened with otherwise; a failure keeps the last good pipelines and stands as
    /// [`Session::shader_error`] until a reload succeeds.
    pub fn reload(
        &mut self,
        gpu: &Gpu,
        source: &ShaderSource,
        format: wgpu::TextureFormat,
        files: &UserFiles,
    ) -> Result<()> {
        self.touched();
        match self.lab.reload(&BuildContext::new(gpu, source, format, files)) {
            Ok(()) => {
                self.shader_error = None;
                Ok(())
            }
            Err(e) => {
                self.shader_error = Some(e.to_string());
                Err(e)
            }
        }
    }

    /// Shows `lab`, built anew from the shaders just saved, in place of the lab shown (the
    /// window's live reload, which builds off its frame loop): the parameters carry over by
    /// name where the count of numbers is the same, and the standing shader error clears.
    pub fn rebuilt(&mut self, mut lab: Box<dyn Lab>) {
        let old = self.lab.params();
        let new = lab.params_mut();
        for spec in old.specs() {
            if let (Some(value), Some(default)) = (old.get(spec.name), new.get(spec.name)) {
                if value.len() == default.len() {
                    new.set_unchecked(spec.name, value);
                }
            }
        }
        self.lab = lab;
        self.shader_error = None;
        self.touched();
    }

    /// A rebuild of the lab failed with `error`: the lab shown keeps drawing, and the error
    /// stands as [`Session::shader_error`] until a reload succeeds.
    pub fn rebuild_failed(&mut self, error: String) {
        self.shader_error = Some(error);
        self.changed();
    }

    /// The shader files of each of the lab's programs (the window's panel lists them, the page
    /// offers them to edit).
    pub fn shader_files(&mut self) -> Vec<ProgramFiles> {
        let mut all = Vec::new();
        for program in self.lab.programs() {
            let (vertex, fragment) = program.files();
            let mut spliced: Vec<String> = Vec::new();
            let (v, f) = program.shaders();
            for shader in [v, f] {
                for (file, _) in &shader.source.line_map {
                    if !spliced.contains(file) {
                        spliced.push(file.clone());
                    }
                }
            }
            all.push(ProgramFiles {
                vertex: vertex.to_owned(),
                fragment: fragment.to_owned(),
                spliced,
            });
        }
        all
    }

    /// Turns inspect mode on or off (F2): on, a click picks the pixel to inspect; off, the
    /// last inspection is forgotten.
    pub fn toggle_inspect(&mut self) {
        self.inspect.on = !self.inspect.on;
        self.inspect.press = None;
        if !self.inspect.on {
            self.inspector.clear();
        }
        self.changed();
    }

    /// Whether inspect mode is on.
    pub fn inspecting(&self) -> bool {
        self.inspect.on
    }

    /// The pixel inspected, if one was picked (it stays while inspect mode is on).
    pub fn inspected(&self) -> Option<(u32, u32)> {
        self.inspect.pixel.filter(|_| self.inspect.on)
    }

    /// Picks the pixel to inspect (or none), turning inspect mode on for a pixel.
    pub fn inspect_pixel(&mut self, pixel: Option<(u32, u32)>) {
        if pixel.is_some() {
            self.inspect.on = true;
        }
        self.inspect.pixel = pixel;
        self.inspect.taken = None;
        self.touched();
    }

    /// The frame just drawn, at `size` in `format`: when a pixel is inspected, the lab changed
    /// since its last inspection was captured and none is in flight, the frame is recorded
    /// again offscreen with its draws written down, and their read-back starts
    /// ([`Session::inspect_poll`] moves it on). The same state draws the same frame, so the
    /// capture is the frame shown. Returns whether [`Session::inspection`] changed (the
    /// capture failed; then draw again).
    pub fn inspect_frame(&mut self, gpu: &Gpu, size: (u32, u32), format: wgpu::TextureFormat) -> bool {
        let Some(pixel) = self.inspected() else {
            return false;
        };
        if self.inspect.taken == Some(self.version) || self.inspector.busy() {
            return false;
        }
        self.inspect.taken = Some(self.version);
        let changed = self.inspector.start(gpu, self.lab.as_mut(), size, format, pixel);
        if changed {
            self.changed();
        }
        changed
    }

    /// Moves the inspection on without blocking: a finished read-back is replayed by `run`
    /// (a worker thread in the window, [`super::inspector::inline`] on the page), a finished
    /// replay becomes [`Session::inspection`]. Returns whether that changed (then draw again).
    pub fn inspect_poll(&mut self, gpu: &Gpu, run: impl FnOnce(Job) -> std::result::Result<(), String>) -> bool {
        if !self.inspector.busy() {
            return false;
        }
        let changed = self.inspector.poll(gpu, self.entry.info.name, run);
        if changed {
            self.changed();
        }
        changed
    }

    /// Whether an inspection is being captured or replayed.
    pub fn inspect_busy(&self) -> bool {
        self.inspector.busy()
    }

    /// The last inspection of the inspected pixel, or why it failed; `None` before the first
    /// and while inspect mode is off.
    pub fn inspection(&self) -> Option<&Shown> {
        self.inspector.shown()
    }

    /// Records the lab's frame into `encoder`, drawing into `color` with its `depth` buffer,
    /// `size` pixels, as every frame is drawn ([`crate::lab::frame::draw`], checked); returns
    /// an error to show once (the frame's own, or one the lab found, such as a shading model
    /// whose shader is broken, which then also stands as the shader error). The window records
    /// its panel into the same encoder, and submits it as it presents.
    pub fn record(
        &mut self,
        gpu: &Gpu,
        encoder: &mut wgpu::CommandEncoder,
        color: &wgpu::TextureView,
        depth: &wgpu::TextureView,
        size: (u32, u32),
    ) -> Option<Error> {
        match crate::lab::frame::draw(gpu, encoder, self.lab.as_mut(), color, depth, size, None) {
            Err(e) => Some(e),
            Ok(found) => {
                if let Some(e) = &found {
                    self.shader_error = Some(e.to_string());
                }
                found
            }
        }
    }

    /// Records the lab's frame as [`Session::record`] does, in an encoder of its own named
    /// `label`, and submits it; returns the error to show once. The caller presents or reads
    /// back what was drawn.
    pub fn draw(
        &mut self,
        gpu: &Gpu,
        label: &str,
        color: &wgpu::TextureView,
        depth: &wgpu::TextureView,
        size: (u32, u32),
    ) -> Option<Error> {
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(label) });
        let error = self.record(gpu, &mut encoder, color, depth, size);
        gpu.queue.submit([encoder.finish()]);
        error
    }

    /// The whole-frame view asked for (none: the lab's picture shows).
    pub fn view(&self) -> Option<&Wanted> {
        self.views.wanted()
    }

    /// Shows `wanted` in place of the lab's picture, or the picture again when it is the view
    /// shown; `reference` is the lab built from its built-in shaders, for a diff.
    pub fn toggle_view(&mut self, wanted: Wanted, reference: Option<Box<dyn Lab>>) {
        self.views.toggle(wanted, reference);
        self.changed();
    }

    /// Shows `wanted` in place of the lab's picture (none: the picture again).
    pub fn set_view(&mut self, wanted: Option<Wanted>, reference: Option<Box<dyn Lab>>) {
        self.views.set(wanted, reference);
        self.changed();
    }

    /// The view's last picture, or why there is none; `None` while no view is asked for.
    pub fn view_shown(&self) -> Option<&std::result::Result<Picture, String>> {
        self.views.shown()
    }

    /// Moves the view asked for on at `size` (the surface's, in whose `format` the lab draws):
    /// draws it again when the lab changed since its last picture (parameters, input, the
    /// clock, a reload) or the size did, and takes what came back ([`super::views::Views::update`]);
    /// returns whether a new picture, legend or error was made (then draw again). A diff is
    /// made at once here (the window).
    #[cfg(not(target_arch = "wasm32"))]
    pub fn view_frame(&mut self, gpu: &Gpu, size: (u32, u32), format: wgpu::TextureFormat) -> bool {
        self.update_view(gpu, size, format, true)
    }

    /// Moves the view asked for on as [`Session::view_frame`] does, without ever blocking (the
    /// page's way): a diff's frames are read back over calls.
    pub fn view_poll(&mut self, gpu: &Gpu, size: (u32, u32), format: wgpu::TextureFormat) -> bool {
        self.update_view(gpu, size, format, false)
    }

    /// [`super::views::Views::update`] at the lab's state; something made is drawn again.
    fn update_view(&mut self, gpu: &Gpu, size: (u32, u32), format: wgpu::TextureFormat, wait: bool) -> bool {
        let made = self
            .views
            .update(gpu, self.lab.as_mut(), self.version, size, format, wait);
        if made {
            self.changed();
        }
        made
    }

    /// What may be chosen where the view could not be drawn as asked: each choice's words and
    /// the view it asks for.
    pub fn view_choices(&self) -> &[(String, Wanted)] {
        self.views.choices()
    }

    /// The view's picture as the surface shows it, read back (blocking); `None` while there
    /// is none.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn view_picture(&self, gpu: &Gpu) -> Option<Result<image::RgbaImage>> {
        self.views.read(gpu)
    }

    /// Whether the view waits for the GPU (its legend or a diff's frames on their way).
    pub fn view_busy(&self) -> bool {
        self.views.busy()
    }

    /// Records the view's picture into `color` (of `format`) in place of the lab's frame;
    /// returns whether there was one (otherwise record the lab's frame, [`Session::record`]).
    pub fn record_view(
        &mut self,
        gpu: &Gpu,
        encoder: &mut wgpu::CommandEncoder,
        color: &wgpu::TextureView,
        format: wgpu::TextureFormat,
    ) -> bool {
        self.views.record(gpu, encoder, color, format)
    }
}
