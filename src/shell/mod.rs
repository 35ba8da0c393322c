//! The shell: the command line every example shares, the offscreen paths (`--screenshot`,
//! `--bench`) and the window. It drives any [`Lab`](crate::lab::Lab) through its [`LabEntry`] and never names an
//! exercise.
//!
//! Usage errors exit with status 2 and say what is valid; they are found before anything is
//! rendered (parameters are checked against the lab's declaration before the GPU is opened).
//! Runtime errors (no adapter, broken shader, unwritable file) print one clear message and exit
//! with 1.
//!
//! In the browser build (wasm32) the page's shell (`web`) takes the window's place, with
//! [`clock`], [`panel`] and [`defaults`]: the command line, the offscreen paths, recording and
//! the native window need processes, files, a terminal and blocking on the GPU.

#[cfg(not(target_arch = "wasm32"))]
mod args;
#[cfg(not(target_arch = "wasm32"))]
mod capture;
pub mod clock;
#[cfg(not(target_arch = "wasm32"))]
mod headless;
pub mod panel;
#[cfg(not(target_arch = "wasm32"))]
pub mod record;
#[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
mod shm;
#[cfg(target_arch = "wasm32")]
pub mod web;
#[cfg(not(target_arch = "wasm32"))]
pub mod window;

#[cfg(not(target_arch = "wasm32"))]
use std::io::Write;
#[cfg(not(target_arch = "wasm32"))]
use std::path::PathBuf;
#[cfg(not(target_arch = "wasm32"))]
use std::process::ExitCode;

#[cfg(not(target_arch = "wasm32"))]
pub use args::Args;
#[cfg(not(target_arch = "wasm32"))]
pub use headless::{bench, progress_bar, render_into, screenshot, BenchResult};

use crate::error::Error;
use crate::lab::LabEntry;
use crate::params::Params;

/// A failure with the exit status it deserves.
#[derive(Debug)]
pub struct Failure {
    /// 1 for runtime errors, 2 for usage errors.
    pub code: u8,
    /// What to print.
    pub error: Error,
}

impl From<Error> for Failure {
    fn from(error: Error) -> Self {
        let code = if matches!(error, Error::Param(_)) { 2 } else { 1 };
        Failure { code, error }
    }
}

/// Mesa prints two warnings on every run when `XDG_RUNTIME_DIR` is unset, which makes a
/// newcomer's first, successful run look broken: give the process a private one instead
/// (`$TMP/shaderlab-runtime-UID`, created mode 0700 and used only if it is this user's own
/// directory with that mode; it is kept and reused by the next run, never removed, as several
/// runs may share it at once). Call it first thing in `main`, before any thread
/// starts; the lab examples do it through [`main`], the other examples call it themselves.
#[cfg(not(target_arch = "wasm32"))]
pub fn ensure_runtime_dir() {
    if std::env::var_os("XDG_RUNTIME_DIR").is_some_and(|d| !d.is_empty()) {
        return;
    }
    // One directory per user, reused by every run (nothing to clean up), and used only if it
    // is ours alone. Only where Mesa runs (and `libc` is a dependency).
    #[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
    {
        use std::os::unix::fs::{DirBuilderExt, MetadataExt, PermissionsExt};
        // SAFETY: getuid has no preconditions.
        let uid = unsafe { libc::getuid() };
        let dir = std::env::temp_dir().join(format!("shaderlab-runtime-{uid}"));
        let _ = std::fs::DirBuilder::new().mode(0o700).create(&dir);
        let ours = std::fs::symlink_metadata(&dir)
            .is_ok_and(|m| m.is_dir() && m.uid() == uid && m.permissions().mode() & 0o777 == 0o700);
        if ours {
            // SAFETY: called first thing in main, before any other thread exists.
            unsafe { std::env::set_var("XDG_RUNTIME_DIR", &dir) };
        }
    }
}

/// Mesa's implicit Vulkan layer `VK_LAYER_MESA_device_select` orders the GPUs so that the one
/// driving the display comes first: to know it, it connects to the X server (and Wayland) twice
/// while the adapters are listed, ~25 ms of every start under Xvfb. An offscreen run
/// (`--screenshot`, `--bench`) draws into no display, so it skips the layer, unless the user
/// steers it (`MESA_VK_DEVICE_SELECT`, or `NODEVICE_SELECT` set either way).
#[cfg(not(target_arch = "wasm32"))]
fn skip_display_device_select() {
    if std::env::var_os("MESA_VK_DEVICE_SELECT").is_some() || std::env::var_os("NODEVICE_SELECT").is_some() {
        return;
    }
    // SAFETY: called from main before any other thread exists (argument parsing starts none).
    unsafe { std::env::set_var("NODEVICE_SELECT", "1") };
}

/// Entry point of every example: parses arguments, then renders offscreen or opens a window.
#[cfg(not(target_arch = "wasm32"))]
pub fn main(entry: &'static LabEntry) -> ExitCode {
    main_from(entry, std::env::args_os().collect())
}

/// [`main`] with the command line given (program name first): what `shaderlab run NAME …` calls.
#[cfg(not(target_arch = "wasm32"))]
pub fn main_from(entry: &'static LabEntry, argv: Vec<std::ffi::OsString>) -> ExitCode {
    ensure_runtime_dir();
    let name = entry.info.name;
    let args = Args::parse_from_for(entry, argv);
    if args.screenshot.is_some() || args.bench.is_some() || args.record.is_some() {
        skip_display_device_select();
    }
    let result = run(entry, args);
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => {
            let hint = if failure.code == 2 {
                "\n\nFor more information, try '--help'."
            } else {
                ""
            };
            let _ = writeln!(std::io::stderr(), "{name}: error: {}{hint}", failure.error);
            ExitCode::from(failure.code)
        }
    }
}

#[cfg(not(target_arch = "wasm32"))]
fn run(entry: &'static LabEntry, args: Args) -> Result<(), Failure> {
    // Everything the user typed is checked before a GPU is opened or a frame drawn.
    let params = args.params(entry)?;
    if let Some(path) = &args.screenshot {
        headless::check_png_path(path)?;
    }
    if let Some(path) = &args.record {
        record::Output::parse(path, entry.info.name)?;
    }
    args.shader_source()?;
    let files = args.files(entry)?;
    if args.screenshot.is_some() || args.bench.is_some() || args.record.is_some() {
        headless::run(entry, &args, params, &files)
    } else if !window::has_display() {
        // No display: still do something useful.
        let path = PathBuf::from(format!("{}.png", entry.info.name));
        eprintln!(
            "{}: no display found ({}); writing a screenshot to {} instead",
            entry.info.name,
            window::no_display_reason(),
            path.display()
        );
        let args = Args {
            screenshot: Some(path),
            ..args
        };
        headless::run(entry, &args, params, &files)
    } else {
        window::run(entry, &args, params, files).map_err(Failure::from)
    }
}

/// Prints a line to stdout; a closed or full stdout is a clean error, not a panic.
#[cfg(not(target_arch = "wasm32"))]
pub(crate) fn say(line: &str) -> Result<(), Error> {
    let mut out = std::io::stdout().lock();
    writeln!(out, "{line}")
        .and_then(|_| out.flush())
        .map_err(|source| Error::Io {
            path: PathBuf::from("<stdout>"),
            source,
        })
}

/// The parameters of a lab at their defaults (for tests and `--help`).
pub fn defaults(entry: &LabEntry) -> Params {
    (entry.params)()
}
