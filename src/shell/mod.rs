//! The shell: the command line every example shares, the offscreen paths (`--screenshot`,
//! `--bench`) and the window. It drives any [`Lab`](crate::lab::Lab) through its [`LabEntry`] and never names an
//! exercise.
//!
//! This file is the folder's face: its modules, what they export, and the entry points that
//! send a command line to the offscreen paths (`headless`) or the window. What every
//! command-line program shares (exit statuses, stdout, clap's parsing) lives in `cli`, the
//! command line's flags in `args`.
//!
//! Usage errors exit with status 2 and say what is valid; they are found before anything is
//! rendered (parameters are checked against the lab's declaration before the GPU is opened).
//! Runtime errors (no adapter, broken shader, unwritable file) print one clear message and exit
//! with 1.
//!
//! In the browser build (wasm32) the page's shell (`web`) takes the window's place, with
//! [`session`], [`inspector`], [`views`], [`surface`], [`clock`], [`panel`] and [`defaults`]: the command line, the offscreen paths, recording and
//! the native window need processes, files, a terminal and blocking on the GPU.

#[cfg(not(target_arch = "wasm32"))]
mod args;
pub mod check;
#[cfg(not(target_arch = "wasm32"))]
pub mod check_verb;
#[cfg(not(target_arch = "wasm32"))]
mod cli;
pub mod clock;
#[cfg(not(target_arch = "wasm32"))]
pub mod diff_verb;
#[cfg(not(target_arch = "wasm32"))]
mod headless;
pub mod inspector;
pub mod link;
#[cfg(not(target_arch = "wasm32"))]
pub mod link_verb;
pub mod panel;
#[cfg(not(target_arch = "wasm32"))]
pub mod record;
#[cfg(not(target_arch = "wasm32"))]
pub mod reload;
pub mod session;
pub mod surface;
#[cfg(not(target_arch = "wasm32"))]
pub mod tools;
#[cfg(not(target_arch = "wasm32"))]
pub mod verbs;
#[cfg(not(target_arch = "wasm32"))]
pub mod view_verb;
pub mod views;
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
pub use crate::lab::frame::{render_into, screenshot};
#[cfg(not(target_arch = "wasm32"))]
pub use args::{Args, PixelFlag};
#[cfg(not(target_arch = "wasm32"))]
pub use cli::{ensure_runtime_dir, exit_on_clap_error, one_line, parse_command_line, print, say, tool_exit, Failure};
#[cfg(not(target_arch = "wasm32"))]
pub use headless::{bench, progress_bar, BenchResult};

#[cfg(not(target_arch = "wasm32"))]
use crate::error::Error;
use crate::lab::LabEntry;
use crate::params::Params;

/// Entry point of every example: parses arguments, then renders offscreen or opens a window.
#[cfg(not(target_arch = "wasm32"))]
pub fn main(entry: &'static LabEntry) -> ExitCode {
    main_from(entry, std::env::args_os().collect())
}

/// Installs [`crate::memory::SayWhenExhausted`] as the program's allocator (where it exists):
/// out of memory is then a message and exit status 1, not an abort.
#[macro_export]
macro_rules! say_when_exhausted {
    () => {
        #[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
        #[global_allocator]
        static ALLOCATOR: $crate::memory::SayWhenExhausted = $crate::memory::SayWhenExhausted;
    };
}

/// The `main` of a lab's example (`examples/NAME.rs`): the lab is the one registered under the
/// example's own name, so the example names it nowhere.
#[macro_export]
macro_rules! lab_example {
    () => {
        $crate::say_when_exhausted!();

        fn main() -> std::process::ExitCode {
            $crate::shell::main_named(env!("CARGO_CRATE_NAME"))
        }
    };
}

/// [`main`] for the lab registered as `name` (an example's crate name): status 2 and the list
/// of labs when there is none.
#[cfg(not(target_arch = "wasm32"))]
pub fn main_named(name: &str) -> ExitCode {
    match crate::course::find(name) {
        Some(entry) => main(entry),
        None => {
            let names: Vec<&str> = crate::course::ALL.iter().map(|e| e.info.name).collect();
            let _ = writeln!(
                std::io::stderr(),
                "no lab called `{name}`; the labs are: {}",
                names.join(", ")
            );
            ExitCode::from(2)
        }
    }
}

/// [`main`] with the command line given (program name first): what `shaderlab run NAME …` calls.
#[cfg(not(target_arch = "wasm32"))]
pub fn main_from(entry: &'static LabEntry, argv: Vec<std::ffi::OsString>) -> ExitCode {
    ensure_runtime_dir();
    let args = Args::parse_from_for(entry, argv);
    main_parsed(entry, args)
}

/// `shaderlab debug NAME --pixel X,Y …` (program name first): the lab's command line with the
/// pixel as `--pixel` ([`Args::parse_debug_command`]); status 2 when no pixel is given.
#[cfg(not(target_arch = "wasm32"))]
pub fn debug_main_from(entry: &'static LabEntry, argv: Vec<std::ffi::OsString>) -> ExitCode {
    ensure_runtime_dir();
    let args = Args::parse_debug_command(entry, argv);
    if args.debug.is_none() {
        let _ = writeln!(
            std::io::stderr(),
            "shaderlab debug: which pixel? Usage: shaderlab debug NAME --pixel X,Y [--json] [FLAGS…]"
        );
        return ExitCode::from(2);
    }
    main_parsed(entry, args)
}

#[cfg(not(target_arch = "wasm32"))]
fn main_parsed(entry: &'static LabEntry, args: Args) -> ExitCode {
    let name = entry.info.name;
    if args.screenshot.is_some()
        || args.bench.is_some()
        || args.record.is_some()
        || args.debug.is_some()
        || offscreen_view(&args)
    {
        cli::skip_display_device_select();
    }
    let result = run(entry, args);
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => {
            // A view's probe that does not fit the shaders says all there is in its one line.
            let hint = if failure.code == 2 && !matches!(failure.error, Error::View { .. }) {
                "\n\nFor more information, try '--help'."
            } else {
                ""
            };
            let _ = writeln!(std::io::stderr(), "{name}: error: {}{hint}", failure.error);
            if crate::gpu::hung() {
                // The driver still runs the frame that never ends: end without waiting for it.
                crate::fsutil::signals::exit_now(i32::from(failure.code));
            }
            ExitCode::from(failure.code)
        }
    }
}

#[cfg(not(target_arch = "wasm32"))]
fn run(entry: &'static LabEntry, args: Args) -> Result<(), Failure> {
    // Everything the user typed is checked before a GPU is opened or a frame drawn: first
    // that each flag does something in this run.
    verbs::check(entry, &args, verbs::Mode::of(&args))?;
    let params = args.params(entry)?;
    if let Some(path) = &args.screenshot {
        headless::check_png_path(path)?;
    }
    if let Some(dir) = &args.diff {
        // `--diff DIR` is `shaderlab diff NAME --shaders DIR`, the picture to --screenshot.
        let own = diff_verb::Own {
            out: args.screenshot.clone(),
            json: args.json,
            reference: None,
        };
        let args = Args {
            shaders: Some(dir.clone()),
            screenshot: None,
            ..args
        };
        return diff_verb::run(entry, &args, &own);
    }
    if let Some(path) = &args.record {
        record::Output::parse(path, entry.info.name)?;
    }
    args.shader_source()?;
    let files = args.files(entry)?;
    if args.screenshot.is_some()
        || args.bench.is_some()
        || args.record.is_some()
        || args.debug.is_some()
        || offscreen_view(&args)
    {
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

/// A view (`--line`, `--cost`) or a comparison (`--diff`): drawn offscreen, never in a window.
#[cfg(not(target_arch = "wasm32"))]
fn offscreen_view(args: &Args) -> bool {
    args.line.is_some() || args.cost || args.diff.is_some()
}

/// The parameters of a lab at their defaults (for tests and `--help`).
pub fn defaults(entry: &LabEntry) -> Params {
    (entry.params)()
}
