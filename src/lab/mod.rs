//! The contract between an exercise and the shell that drives it.
//!
//! The shell (window, `--screenshot`, `--bench`, tests) drives any [`Lab`] without naming one:
//! it turns window events into GLUT-shaped [`Input`], sets parameters by name through
//! [`Lab::params_mut`], and asks the lab to [`render`](Lab::render) into a [`Frame`]. A lab never
//! sees winit, and no lab knows another.

pub mod frame;
mod keys;
mod runner;

pub use keys::{Act, Key, KeyRow, Keys, DOWN, LEFT, PAGE_DOWN, PAGE_UP, RIGHT, UP};
pub use runner::{Derive, Geometry, Material, MaterialScene, PairChoice, Recipe, Runner, Scene, ShaderPair};

use crate::error::Result;
use crate::params::Params;
use crate::render::Frame;

/// What identifies an exercise.
#[derive(Debug)]
pub struct LabInfo {
    /// The name shared by its module, shaders, example and tests (`phong`, `suzanne_flat`).
    pub name: &'static str,
    /// The original's window title (`Lab05-3`); the live title, with the lab's state, is
    /// [`Lab::title`].
    pub original_title: &'static str,
    /// Human name of the effect.
    pub label: &'static str,
    /// The lecture it comes from.
    pub lecture: &'static str,
    /// Default window and image size.
    pub size: (u32, u32),
    /// The keys and mouse, for `--help` and the README.
    pub keys: Keys,
    /// Which files named on the command line the lab draws (the shell refuses the others
    /// before reading them, so a picture is decoded only for a lab that samples it).
    pub files: FilesTaken,
}

impl LabInfo {
    /// A lab that takes no files named on the command line.
    pub const fn new(
        name: &'static str,
        title: &'static str,
        label: &'static str,
        lecture: &'static str,
        size: (u32, u32),
        keys: Keys,
    ) -> LabInfo {
        LabInfo {
            name,
            original_title: title,
            label,
            lecture,
            size,
            keys,
            files: FilesTaken::NONE,
        }
    }
}

/// Which files named on the command line a lab draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FilesTaken {
    /// `--model FILE.obj`: the labs built on the Suzanne geometry (every `suzanne_*`).
    pub model: bool,
    /// `--texture FILE`: the labs sampling a picture (004's textured Suzannes and
    /// `texparams`' floor, `legacy`'s first sampler2D).
    pub texture: bool,
    /// `--texture NAME=FILE`: `legacy`, whose shaders name their samplers.
    pub named_textures: bool,
}

impl FilesTaken {
    /// No files: the lab draws only its own data.
    pub const NONE: FilesTaken = FilesTaken {
        model: false,
        texture: false,
        named_textures: false,
    };
}

/// A special key (GLUT's `glutSpecialFunc` keys).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Special {
    /// ←
    Left,
    /// →
    Right,
    /// ↑
    Up,
    /// ↓
    Down,
    /// Page Up
    PageUp,
    /// Page Down
    PageDown,
}

/// Input as the originals' callbacks saw it, in window pixels (origin top left).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Input {
    /// A character key (`glutKeyboardFunc`).
    Key(char),
    /// A special key (`glutSpecialFunc`).
    Special(Special),
    /// The left button went down at (x, y).
    Press(i32, i32),
    /// The left button went up at (x, y).
    Release(i32, i32),
    /// The mouse moved to (x, y) with the left button down (`glutMotionFunc`).
    Drag(i32, i32),
}

pub use crate::render::BuildContext;
pub use crate::user_files::{UserFile, UserFiles, NO_FILES};

/// One exercise, ready to draw. A lab can move between threads (outside the browser): the
/// window builds a new one from saved shaders on a worker thread while the old one draws.
pub trait Lab: wgpu::WasmNotSend {
    /// Its name, title and size.
    fn info(&self) -> &'static LabInfo;
    /// Its parameters.
    fn params(&self) -> &Params;
    /// Its parameters, to change.
    fn params_mut(&mut self) -> &mut Params;
    /// An input event; returns whether anything changed (the title is rewritten then).
    fn input(&mut self, input: Input) -> bool;
    /// Compiles its shaders again (live reload). On failure the last good pipelines stay.
    fn reload(&mut self, cx: &BuildContext) -> Result<()>;
    /// Records one frame.
    fn render(&mut self, frame: &mut Frame<'_>) -> Result<()>;
    /// Its programs, for checks that swap a pipeline (the GLSL-versus-WGSL round trip).
    fn programs(&mut self) -> Vec<&mut dyn crate::render::AnyProgram> {
        Vec::new()
    }
    /// Whether a clock drives its `time` parameter in a window (Space pauses it).
    fn animated(&self) -> bool {
        false
    }
    /// The window title: the original's, then the lab's state.
    fn title(&self) -> String {
        params_title(self.info(), self.params())
    }
    /// An error found while drawing that the window should show once (e.g. a model whose
    /// shader is broken); `None` when all is well.
    fn take_error(&mut self) -> Option<crate::error::Error> {
        None
    }
}

/// The default window title: the original's title and the lab's label, then every parameter
/// that differs from its default (`ref002 2D twisting | twisting=4.5`).
pub fn params_title(info: &LabInfo, p: &Params) -> String {
    let state: Vec<String> = p.changed().map(|(name, text)| format!("{name}={text}")).collect();
    if state.is_empty() {
        format!("{} {}", info.original_title, info.label)
    } else {
        format!("{} {} | {}", info.original_title, info.label, state.join(" "))
    }
}

/// An entry of the one list of labs ([`crate::course::ALL`]).
pub struct LabEntry {
    /// Its name and size.
    pub info: &'static LabInfo,
    /// Its parameters at their defaults (checked before a GPU is opened).
    pub params: fn() -> crate::params::Params,
    /// Builds it.
    pub new: fn(&BuildContext) -> Result<Box<dyn Lab>>,
}

impl std::fmt::Debug for LabEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LabEntry").field("info", &self.info).finish()
    }
}
