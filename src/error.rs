//! The crate's error type: one enum for every layer, so callers can match on what went wrong.

use std::path::PathBuf;

/// Everything that can go wrong in shaderlab's library code.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// No GPU adapter (not even a software one) was found.
    #[error(
        "no GPU adapter found ({0}). On Debian/Ubuntu install the Vulkan CPU driver lavapipe: \
         `sudo apt-get install -y mesa-vulkan-drivers`"
    )]
    NoAdapter(String),
    /// The adapter refused to create a device.
    #[error("could not create a GPU device: {0}")]
    Device(String),
    /// A shader failed to parse or validate. `message` is already formatted as
    /// `path:line:column: message` plus the offending line and a caret.
    #[error("{message}")]
    Shader {
        /// The file the error is in (after resolving snippets spliced in by the loader).
        file: String,
        /// 1-based line number in `file`.
        line: u32,
        /// 1-based column number.
        column: u32,
        /// The formatted diagnostic.
        message: String,
    },
    /// A shader file could not be found.
    #[error("shader file {0} not found")]
    ShaderNotFound(String),
    /// A Rust uniform struct does not match the GLSL block it feeds.
    #[error("uniform layout mismatch: {0}")]
    Layout(String),
    /// A program's bindings or vertex inputs do not match what the lab provides.
    #[error("binding mismatch: {0}")]
    Binding(String),
    /// A parameter name or value is not valid for an effect.
    #[error("{0}")]
    Param(String),
    /// wgpu reported an error (validation, out of memory, device lost).
    #[error("wgpu error in {context}: {message}")]
    Wgpu {
        /// What we were doing.
        context: String,
        /// wgpu's message.
        message: String,
    },
    /// Reading or writing a file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// Encoding or decoding an image failed.
    #[error("{path}: {source}")]
    Image {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: image::ImageError,
    },
    /// A signal (SIGINT, SIGTERM, SIGHUP) stopped the work; what it had written was removed or,
    /// for a window's recording, finished and kept.
    #[error("stopped by {}", signal_name(*.signal))]
    Interrupted {
        /// The signal's number.
        signal: i32,
    },
    /// Something is larger than the GPU or the machine can hold (a model, a mesh); said before
    /// anything is made.
    #[error("{0}")]
    Limit(String),
    /// The debugger could not replay a pixel: a pixel outside the picture, an operation the
    /// interpreter does not run (named, with its file and line), a shader past the step budget.
    #[error("{0}")]
    Debug(String),
    /// A whole-frame view cannot be drawn: a line that assigns nothing, a file the lab does
    /// not draw, a name the line does not assign, a stage to choose.
    #[error("{message}")]
    View {
        /// The view's error in words.
        message: String,
        /// Whether the probe does not fit the lab's shaders (a usage error), rather than a
        /// rewritten shader the GPU refused or a frame of another size.
        usage: bool,
        /// What the user may choose between to make the view drawable.
        choose: Choose,
    },
    /// The GPU did not finish a frame within the watchdog's bound (a shader that never ends).
    #[error("{0}")]
    Hang(String),
    /// A window surface could not be created or configured.
    #[error("surface error: {0}")]
    Surface(String),
    /// A fault inside the program or a library it uses (a panic, caught): what it said and
    /// where.
    #[error("internal error: {0}")]
    Internal(String),
    /// A Wavefront OBJ file is malformed or unusable; shown as `file:line: message`
    /// (`file: message` when no single line is to blame).
    #[error("{}: {message}", obj_location(.path, .line))]
    Obj {
        /// The file (or the name the text was given).
        path: PathBuf,
        /// 1-based line number of the offending line, if there is one.
        line: Option<usize>,
        /// What is wrong.
        message: String,
    },
}

/// The name of a signal, for messages: `SIGINT`, `SIGTERM`, `SIGHUP` (their numbers on every
/// Unix) or `signal N`.
pub fn signal_name(signal: i32) -> String {
    match signal {
        1 => "SIGHUP".into(),
        2 => "SIGINT".into(),
        15 => "SIGTERM".into(),
        n => format!("signal {n}"),
    }
}

fn obj_location(path: &std::path::Path, line: &Option<usize>) -> String {
    match line {
        Some(line) => format!("{}:{line}", path.display()),
        None => path.display().to_string(),
    }
}

/// Shorthand for results with [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// What a view's user may choose between where a line alone does not say what to show.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum Choose {
    /// Nothing: the view cannot be drawn as asked.
    #[default]
    Nothing,
    /// One of the names the line assigns.
    Name(Vec<String>),
    /// The vertex or the fragment shader (a line of a file both include).
    Stage,
}
