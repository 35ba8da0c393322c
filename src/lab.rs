//! The contract between an exercise and the shell that drives it.
//!
//! The shell (window, `--screenshot`, `--bench`, tests) drives any [`Lab`] without naming one:
//! it turns window events into GLUT-shaped [`Input`], sets parameters by name through
//! [`Lab::params_mut`], and asks the lab to [`render`](Lab::render) into a [`Frame`]. A lab never
//! sees winit, and no lab knows another.

use std::path::{Path, PathBuf};

use crate::error::Result;
use crate::geometry::images::{load_image, Image};
use crate::geometry::obj::{load_obj, ObjModel};
use crate::gpu::Gpu;
use crate::params::Params;
use crate::render::Frame;
use crate::shader::ShaderSource;

/// What identifies an exercise.
#[derive(Debug)]
pub struct LabInfo {
    /// The name shared by its module, shaders, example and tests (`phong`, `suzanne_flat`).
    pub name: &'static str,
    /// The original's window title (`Lab05-3`).
    pub title: &'static str,
    /// Human name of the effect.
    pub label: &'static str,
    /// The lecture it comes from.
    pub lecture: &'static str,
    /// Default window and image size.
    pub size: (u32, u32),
    /// The keys and mouse, for `--help` and the README.
    pub keys: &'static str,
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

/// What a lab is built with.
pub struct LabContext<'a> {
    /// The device.
    pub gpu: &'a Gpu,
    /// Where shader files come from.
    pub source: &'a ShaderSource,
    /// The colour format of the targets it will draw into.
    pub format: wgpu::TextureFormat,
    /// Files the user named for the lab to draw instead of its built-in data.
    pub files: &'a UserFiles,
}

/// Files named on the command line (`--model`, `--texture`), already read and checked, for the
/// labs that draw a model or a picture texture; a lab that has no use for one ignores it.
#[derive(Clone, Debug, Default)]
pub struct UserFiles {
    /// `--model FILE.obj`: a Wavefront OBJ, parsed.
    pub model: Option<UserFile<ObjModel>>,
    /// `--texture FILE`: a PNG or BMP, decoded, its top row first (the lab decides the upload
    /// order).
    pub texture: Option<UserFile<Image>>,
}

/// A file the user named, and what was read from it.
#[derive(Clone, Debug)]
pub struct UserFile<T> {
    /// The file, for messages about what is found later (e.g. a texture too large for the GPU).
    pub path: PathBuf,
    /// Its content.
    pub data: T,
}

/// No files: every lab draws its own data (tests, the bench, labs building parts lazily).
pub static NO_FILES: UserFiles = UserFiles {
    model: None,
    texture: None,
};

impl UserFiles {
    /// Reads and checks the files; errors name the file (and the line, for an OBJ).
    pub fn load(model: Option<&Path>, texture: Option<&Path>) -> Result<UserFiles> {
        fn read<T>(path: Option<&Path>, load: fn(&Path) -> Result<T>) -> Result<Option<UserFile<T>>> {
            path.map(|path| {
                load(path).map(|data| UserFile {
                    path: path.to_path_buf(),
                    data,
                })
            })
            .transpose()
        }
        Ok(UserFiles {
            model: read(model, load_obj)?,
            texture: read(texture, load_image)?,
        })
    }
}

/// One exercise, ready to draw.
pub trait Lab {
    /// Its name, title and size.
    fn info(&self) -> &'static LabInfo;
    /// Its parameters.
    fn params(&self) -> &Params;
    /// Its parameters, to change.
    fn params_mut(&mut self) -> &mut Params;
    /// An input event; returns whether anything changed (the title is rewritten then).
    fn input(&mut self, input: Input) -> bool;
    /// Compiles its shaders again (live reload). On failure the last good pipelines stay.
    fn reload(&mut self, cx: &LabContext) -> Result<()>;
    /// Records one frame.
    fn render(&mut self, frame: &mut Frame<'_>) -> Result<()>;
    /// Whether a clock drives its `time` parameter in a window (Space pauses it).
    fn animated(&self) -> bool {
        false
    }
    /// The window title: the original's, then the lab's state.
    fn title(&self) -> String {
        let info = self.info();
        let p = self.params();
        let state: Vec<String> = p
            .specs()
            .iter()
            .filter(|s| p.get(s.name) != Some(s.default))
            .map(|s| format!("{}={}", s.name, p.text(s.name)))
            .collect();
        if state.is_empty() {
            format!("{} {}", info.title, info.label)
        } else {
            format!("{} {} | {}", info.title, info.label, state.join(" "))
        }
    }
    /// An error found while drawing that the window should show once (e.g. a model whose
    /// shader is broken); `None` when all is well.
    fn take_error(&mut self) -> Option<crate::Error> {
        None
    }
}

/// An entry of the one list of labs ([`crate::labs::ALL`]).
pub struct LabEntry {
    /// Its name and size.
    pub info: &'static LabInfo,
    /// Its parameters at their defaults (checked before a GPU is opened).
    pub params: fn() -> crate::params::Params,
    /// Builds it.
    pub new: fn(&LabContext) -> Result<Box<dyn Lab>>,
}

impl std::fmt::Debug for LabEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LabEntry").field("info", &self.info).finish()
    }
}
