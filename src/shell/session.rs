//! What every front end does with the lab it shows, written once: the window
//! ([`super::window`]) and the page (`shell::web`, in the browser build) each hold a
//! [`Session`], turn their events into its calls and present what it drew; they keep only what
//! their platform forces (where events come from, acquiring and presenting the surface, the
//! panel's widgets, files and signals in the window, the DOM and the link on the page).
//!
//! A session opens the lab from its [`Sources`] (where its shaders come from, the user's files,
//! the format it draws in; [`Sources::build`] builds a lab the same way for the headless runs
//! and the window's live reload), and draws a frame in one call ([`Session::frame`]): the clock,
//! the view asked for or else the lab's frame through the one checked render
//! ([`crate::lab::frame::draw`]), the inspector's capture and its replay, the diff. What does
//! not fit in a frame goes on between frames ([`Session::poll`]) the platform's way, given once
//! when the session opens ([`Platform`]: a replay on a thread and read-backs waited for
//! natively, inline and polled on the page). It holds the lab (its parameters with it, every
//! write checked, [`Session::set_values`]), the clock of an animated lab, the frames still to
//! draw after a change, the mouse (GLUT's drag rule: the motion callback runs while any button
//! is held, the press and release callbacks are the left button's), the standing shader error,
//! and turns key names into the original's callbacks. It lists and resolves the lab's shader
//! files ([`Session::shader_files`], [`Session::find_file`]) and builds the diff's reference
//! itself. The panel's model (which control each parameter gets, in which group) is
//! [`super::panel::widgets`], and the surface drawn into is [`super::surface::Swapchain`], both
//! shared too.

use std::sync::Arc;

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
    sources: Sources,
    platform: Platform,
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
    /// The check of the lab's shaders against its built-in ones across its states, while one
    /// runs or its report stays.
    check: Option<super::check::Checking>,
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

/// What a lab is built from: where its shaders come from, the user's files (pictures, a model,
/// `legacy`'s pair), and the colour format its pipelines draw in.
#[derive(Clone)]
pub struct Sources {
    /// The shaders: built in, a folder, or texts edited on the page.
    pub source: ShaderSource,
    /// The user's files.
    pub files: Arc<UserFiles>,
    /// The format of the targets the lab draws into.
    pub format: wgpu::TextureFormat,
}

impl Sources {
    /// Sources of `source` and `files`, drawing in `format`.
    pub fn new(source: ShaderSource, files: UserFiles, format: wgpu::TextureFormat) -> Sources {
        Sources {
            source,
            files: Arc::new(files),
            format,
        }
    }

    /// The same files and format, with the shaders of `source`.
    pub fn with_source(&self, source: ShaderSource) -> Sources {
        Sources { source, ..self.clone() }
    }

    /// Builds `entry`'s lab on `gpu`: how every front end builds one (the headless runs and
    /// the window's live reload too).
    pub fn build(&self, gpu: &Gpu, entry: &'static LabEntry) -> Result<Box<dyn Lab>> {
        (entry.new)(&BuildContext::new(gpu, &self.source, self.format, &self.files))
    }
}

/// How the platform runs what does not fit in a frame: an inspection's replay and the read-back
/// of a diff's frames.
#[derive(Clone, Copy)]
pub struct Platform {
    /// Runs an inspection's replay once its capture is back (or says why it cannot).
    pub replay: fn(Job) -> std::result::Result<(), String>,
    /// Whether a read-back may be waited for; otherwise it is polled over frames.
    pub waits: bool,
}

impl Platform {
    /// A process with threads that may block: the replay runs on a worker thread of its own,
    /// a diff's frames are waited for.
    #[cfg(not(target_arch = "wasm32"))]
    pub const NATIVE: Platform = Platform {
        replay: super::inspector::on_a_thread,
        waits: true,
    };

    /// A browser page with one thread that must never block: the replay runs inline, a diff's
    /// frames are read back over frames.
    pub const PAGE: Platform = Platform {
        replay: super::inspector::inline,
        waits: false,
    };
}

/// Where a frame is drawn: the surface's colour target and depth buffer, and its size (in the
/// session's format, [`Sources::format`]).
pub struct Target<'a> {
    /// The colour target.
    pub color: &'a wgpu::TextureView,
    /// Its depth buffer.
    pub depth: &'a wgpu::TextureView,
    /// Its size in pixels.
    pub size: (u32, u32),
}

/// What a frame or a poll made, for the shell to show.
#[derive(Debug, Default)]
pub struct Outcome {
    /// An error to show once: the frame's own, or one the lab found (a shading model whose
    /// shader is broken, which then also stands as [`Session::shader_error`]).
    pub error: Option<Error>,
    /// The view made a new picture, legend or error ([`Session::view_shown`]).
    pub view: bool,
    /// A new inspection arrived, or the last one failed ([`Session::inspection`]).
    pub inspection: bool,
    /// The check checked a state, or stopped ([`Session::checking`]).
    pub check: bool,
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
    /// A session of `entry`'s lab built from `sources` on `gpu`, running what does not fit in a
    /// frame the `platform`'s way, its clock starting at `now` (seconds on the front end's
    /// clock) and running `scale` times real time.
    pub fn open(
        entry: &'static LabEntry,
        gpu: &Gpu,
        sources: Sources,
        platform: Platform,
        now: f64,
        scale: f64,
    ) -> Result<Session> {
        let lab = sources.build(gpu, entry)?;
        let clock = Clock::new(lab.as_ref(), now, scale);
        Ok(Session {
            entry,
            lab,
            sources,
            platform,
            clock,
            dirty: FRAMES_AFTER_A_CHANGE,
            buttons: 0,
            cursor: (0, 0),
            shader_error: None,
            version: 0,
            inspect: Inspect::default(),
            inspector: Inspector::default(),
            views: Views::default(),
            check: None,
        })
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

    /// The lab, to change (its parameters only through [`Session::set_values`] and
    /// [`Session::set`], which check them).
    pub fn lab_mut(&mut self) -> &mut dyn Lab {
        self.lab.as_mut()
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

    /// Advances an animated lab's `time` to the clock at `now` ([`Session::frame`] does).
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

    /// Whether something goes on between frames that [`Session::poll`] moves on: an
    /// inspection being captured or replayed, a view waiting for the GPU.
    pub fn busy(&self) -> bool {
        self.inspector.busy() || self.views.busy() || self.check.as_ref().is_some_and(|c| !c.finished())
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
        self.change(|p| p.set_str(name, value).map(drop))
    }

    /// Sets a parameter to `values` (the panel's controls), with the checks of
    /// [`Session::set`].
    pub fn set_values(&mut self, name: &str, values: &[f64]) -> Result<()> {
        self.change(|p| p.set(name, values).map(drop))
    }

    /// Sets every parameter back to its default (the panel's Reset all), with the checks of
    /// [`Session::set`].
    pub fn reset(&mut self) -> Result<()> {
        self.change(|p| {
            let specs: Vec<crate::params::ParamSpec> = p.specs().to_vec();
            specs
                .iter()
                .try_for_each(|spec| p.set(spec.name, spec.default).map(drop))
        })
    }

    /// Every parameter write: `write`, then the lab's rules between parameters; a refused
    /// change is undone whole, a taken one draws and inspects again.
    fn change(&mut self, write: impl FnOnce(&mut Params) -> Result<()>) -> Result<()> {
        let p = self.lab.params_mut();
        let before = p.clone();
        let result = write(p).and_then(|()| p.check());
        match &result {
            Err(_) => *p = before,
            Ok(()) => self.touched(),
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

    /// From now on, runs what does not fit in a frame `platform`'s way.
    pub fn set_platform(&mut self, platform: Platform) {
        self.platform = platform;
    }

    /// Where the lab is built from.
    pub fn sources(&self) -> &Sources {
        &self.sources
    }

    /// Compiles the lab's shaders again from `source` (an edit on the page), in place, with its
    /// files and format; later reloads and the diff's copy read from `source` too. A failure
    /// keeps the last good pipelines and stands as [`Session::shader_error`] until a reload
    /// succeeds.
    pub fn reload(&mut self, gpu: &Gpu, source: ShaderSource) -> Result<()> {
        self.sources.source = source;
        self.touched();
        let sources = &self.sources;
        match (self.lab).reload(&BuildContext::new(gpu, &sources.source, sources.format, &sources.files)) {
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

    /// From now on the shaders come from `source`, which holds the texts the lab draws with
    /// already (the built-in shaders written into a folder to edit): nothing is built again.
    pub fn moved_to(&mut self, source: ShaderSource) {
        self.sources.source = source;
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

    /// The lab's shader file that `given` names, as the lab shows it ([`Session::shader_files`]'
    /// display paths): the file of that path, the one file whose path ends with it
    /// (`phong.frag` for `shaders_glsl/phong.frag`), or the same file through another path;
    /// otherwise why not, naming the lab's files.
    pub fn find_file(&mut self, given: &str) -> std::result::Result<String, String> {
        let mut files: Vec<String> = Vec::new();
        for program in self.shader_files() {
            for file in program.spliced {
                if !files.contains(&file) {
                    files.push(file);
                }
            }
        }
        crate::debug::view::find_file(&files, given).ok_or_else(|| {
            format!(
                "{given} is not a file of this lab's shaders; its files are {}",
                files.join(", ")
            )
        })
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

    /// When a pixel is inspected, the lab changed since its last inspection was captured and
    /// none is in flight: the lab's frame is recorded again offscreen at `size` with its draws
    /// written down, and their read-back starts ([`Session::poll`] moves it on). The same state
    /// draws the same frame, so the capture is the frame shown. Returns whether
    /// [`Session::inspection`] changed (the capture failed; then draw again).
    fn capture(&mut self, gpu: &Gpu, size: (u32, u32)) -> bool {
        let Some(pixel) = self.inspected() else {
            return false;
        };
        if self.inspect.taken == Some(self.version) || self.inspector.busy() {
            return false;
        }
        self.inspect.taken = Some(self.version);
        let changed = self
            .inspector
            .start(gpu, self.lab.as_mut(), size, self.sources.format, pixel);
        if changed {
            self.changed();
        }
        changed
    }

    /// Moves on, without drawing, what goes on between frames, the platform's way: the
    /// inspection (a finished read-back replayed on a thread or inline, a finished replay
    /// taken), the view asked for (drawn again when the lab changed since its last picture,
    /// its legend or a diff's frames taken when they are back), then a capture of the
    /// inspected pixel's frame at `size` when the lab changed since the last. Says what it
    /// made; something made draws again.
    pub fn poll(&mut self, gpu: &Gpu, size: (u32, u32)) -> Outcome {
        let mut out = Outcome::default();
        if self.inspector.busy() && self.inspector.poll(gpu, self.entry.info.name, self.platform.replay) {
            out.inspection = true;
            self.changed();
        }
        let made = self.views.update(
            gpu,
            self.lab.as_mut(),
            self.version,
            size,
            self.sources.format,
            self.platform.waits,
        );
        if made {
            out.view = true;
            self.changed();
        }
        if let Some(check) = self.check.as_mut() {
            out.check = check.poll(gpu, self.platform.waits);
        }
        // Captured last: the capture started here is moved on by the next poll.
        out.inspection |= self.capture(gpu, size);
        out
    }

    /// The lab built from its built-in shaders, with the session's files: what a diff and a
    /// check compare the shaders drawn with to.
    fn builtin(&self, gpu: &Gpu) -> Result<Box<dyn Lab>> {
        self.sources.with_source(ShaderSource::Embedded).build(gpu, self.entry)
    }

    /// Starts checking the lab's shaders (as the session draws them) against its built-in ones
    /// across its states ([`super::check`]): from the lab's state now, the base state, every
    /// object, the lab's states of record and `random` states drawn with `seed`, at `size`,
    /// passing at `min_db`; [`Session::poll`] moves it on a state at a time. Both labs are
    /// built here, once. Says why it cannot start.
    pub fn check_start(
        &mut self,
        gpu: &Gpu,
        size: (u32, u32),
        random: usize,
        seed: u64,
        min_db: f64,
    ) -> Option<String> {
        if (self.entry.params)().file_args().is_some() {
            return Some(format!(
                "{} draws the pair it is given: check it against another pair with `shaderlab check {} VERT FRAG --reference VERT0 FRAG0`",
                self.name(),
                self.name()
            ));
        }
        let built = (self.sources.build(gpu, self.entry)).and_then(|mine| Ok((mine, self.builtin(gpu)?)));
        let (mut mine, mut reference) = match built {
            Ok(labs) => labs,
            Err(e) => return Some(format!("cannot check: {e}")),
        };
        let base = self.lab.params().clone();
        let states = super::check::states(self.entry, &base, random, seed);
        *reference.params_mut() = base.clone();
        *mine.params_mut() = base;
        self.check = Some(super::check::Checking::new(
            self.entry,
            (mine, reference),
            states,
            (size, self.sources.format),
            min_db,
        ));
        self.changed();
        None
    }

    /// The check started last, while it runs and after.
    pub fn checking(&self) -> Option<&super::check::Checking> {
        self.check.as_ref()
    }

    /// A frame that could not be drawn (the surface had no frame to give this time): the clock
    /// still moves to `now` and the frame counts as drawn, as one that reached the screen.
    pub fn skipped(&mut self, now: f64) {
        self.tick(now);
        self.drawn();
    }

    /// Draws one frame into `target`, recorded into `encoder` (the shell submits it, with what
    /// it draws over it, and presents): the clock advanced to `now`, what goes on between
    /// frames moved on ([`Session::poll`]), then the view asked for, or else the lab's frame
    /// ([`Session::encode`]).
    pub fn frame(&mut self, gpu: &Gpu, encoder: &mut wgpu::CommandEncoder, target: &Target, now: f64) -> Outcome {
        self.tick(now);
        self.drawn();
        let mut out = self.poll(gpu, target.size);
        out.error = self.encode(gpu, encoder, target);
        out
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

    /// Encodes what the session shows into `target` in `encoder`, without moving anything on:
    /// the view's picture when one is asked for and drawn, or else the lab's frame, as every
    /// frame is drawn ([`crate::lab::frame::draw`], checked). Returns the error to show once
    /// (see [`Outcome::error`]).
    pub fn encode(&mut self, gpu: &Gpu, encoder: &mut wgpu::CommandEncoder, target: &Target) -> Option<Error> {
        if self.views.encode(gpu, encoder, target.color, self.sources.format) {
            return None;
        }
        match crate::lab::frame::draw(
            gpu,
            encoder,
            self.lab.as_mut(),
            target.color,
            target.depth,
            target.size,
            None,
        ) {
            Err(e) => Some(e),
            Ok(found) => {
                if let Some(e) = &found {
                    self.shader_error = Some(e.to_string());
                }
                found
            }
        }
    }

    /// What the session shows at `size`, drawn offscreen and read back (F12): the view's
    /// picture, or the lab's frame.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn picture(&mut self, gpu: &Gpu, (w, h): (u32, u32)) -> Result<image::RgbaImage> {
        if let Some(picture) = self.views.read(gpu) {
            return picture.map(|image| image::imageops::crop_imm(&image, 0, 0, w, h).to_image());
        }
        let target = crate::offscreen::Offscreen::with_format(gpu, w, h, self.sources.format);
        crate::lab::frame::render_into(gpu, self.lab.as_mut(), &target)?;
        target.read(gpu)
    }

    /// The whole-frame view asked for (none: the lab's picture shows).
    pub fn view(&self) -> Option<&Wanted> {
        self.views.wanted()
    }

    /// Shows `wanted` in place of the lab's picture, or the picture again when it is the view
    /// shown (F3, F4, a line clicked in the inspector); as [`Session::show_view`].
    pub fn toggle_view(&mut self, gpu: &Gpu, wanted: Wanted) -> Option<String> {
        if self.views.wanted() == Some(&wanted) {
            self.show_view(gpu, None)
        } else {
            self.show_view(gpu, Some(wanted))
        }
    }

    /// Shows `wanted` in place of the lab's picture (none: the picture again). A diff compares
    /// with the lab built from its built-in shaders, built here. Returns words to say where a
    /// diff cannot be made (the lab draws with its built-in shaders, or they do not build): the
    /// view then shows why, over the lab's picture.
    pub fn show_view(&mut self, gpu: &Gpu, wanted: Option<Wanted>) -> Option<String> {
        let mut said = None;
        let reference = match &wanted {
            Some(Wanted::Diff) if matches!(self.sources.source, ShaderSource::Embedded) => {
                said = Some(
                    "the lab draws with its built-in shaders; run it with --shaders DIR to compare a copy with them"
                        .to_owned(),
                );
                None
            }
            Some(Wanted::Diff) => match self.builtin(gpu) {
                Ok(lab) => Some(lab),
                Err(e) => {
                    said = Some(format!("cannot build the lab with its built-in shaders: {e}"));
                    None
                }
            },
            _ => None,
        };
        self.views.set(wanted, reference);
        self.changed();
        said
    }

    /// The view's last picture, or why there is none; `None` while no view is asked for.
    pub fn view_shown(&self) -> Option<&std::result::Result<Picture, String>> {
        self.views.shown()
    }

    /// What may be chosen where the view could not be drawn as asked: each choice's words and
    /// the view it asks for.
    pub fn view_choices(&self) -> &[(String, Wanted)] {
        self.views.choices()
    }

    /// Whether the view waits for the GPU (its legend or a diff's frames on their way).
    pub fn view_busy(&self) -> bool {
        self.views.busy()
    }
}
