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
#[cfg(not(target_arch = "wasm32"))]
mod headless;
pub mod panel;
#[cfg(not(target_arch = "wasm32"))]
pub mod record;
pub mod session;
#[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
mod shm;
pub mod surface;
#[cfg(not(target_arch = "wasm32"))]
pub mod tools;
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
pub use crate::lab::draw::{render_into, screenshot};
#[cfg(not(target_arch = "wasm32"))]
pub use args::{Args, PixelFlag};
#[cfg(not(target_arch = "wasm32"))]
pub use headless::{bench, progress_bar, BenchResult};

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
/// while the adapters are listed, which lengthens every start (figures: `docs/speed.md`,
/// "Start-up"). An offscreen run (`--screenshot`, `--bench`) draws into no display, so it
/// skips the layer, unless the user steers it (`MESA_VK_DEVICE_SELECT`, or `NODEVICE_SELECT`
/// set either way).
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
    match crate::labs::find(name) {
        Some(entry) => main(entry),
        None => {
            let names: Vec<&str> = crate::labs::ALL.iter().map(|e| e.info.name).collect();
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
    if args.screenshot.is_some() || args.bench.is_some() || args.record.is_some() || args.debug.is_some() {
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
    // Everything the user typed is checked before a GPU is opened or a frame drawn.
    if args.record.is_none() {
        for (flag, given) in [
            ("--frames", args.frames.is_some()),
            ("--fps", args.fps.is_some()),
            ("--from", args.from.is_some()),
        ] {
            if given {
                return Err(Error::Param(format!(
                    "`{flag}` is for recordings: add --record OUT (or run `shaderlab record {} OUT …`)",
                    entry.info.name
                ))
                .into());
            }
        }
    }
    let params = args.params(entry)?;
    if let Some(path) = &args.screenshot {
        headless::check_png_path(path)?;
    }
    if let Some(path) = &args.record {
        record::Output::parse(path, entry.info.name)?;
    }
    args.shader_source()?;
    let files = args.files(entry)?;
    if args.screenshot.is_some() || args.bench.is_some() || args.record.is_some() || args.debug.is_some() {
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

/// Prints a line to stdout; a closed or full stdout is a clean error, not a panic. When an
/// output of this run is standard output itself (`--screenshot /dev/stdout`), the line goes to
/// stderr instead, so the bytes stay clean.
#[cfg(not(target_arch = "wasm32"))]
pub fn say(line: &str) -> Result<(), Error> {
    print(&format!("{line}\n"))
}

/// Writes `text` to stdout (stderr when an output took stdout, see [`say`]) and flushes it; a
/// closed or full stdout is [`Error::Io`] on `<stdout>`, never a panic.
#[cfg(not(target_arch = "wasm32"))]
pub fn print(text: &str) -> Result<(), Error> {
    let fail = |source| Error::Io {
        path: PathBuf::from("<stdout>"),
        source,
    };
    if crate::fsutil::stdout_taken() {
        let mut err = std::io::stderr().lock();
        return err.write_all(text.as_bytes()).map_err(fail);
    }
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes()).and_then(|()| out.flush()).map_err(fail)
}

/// Parses a command line with clap, for every command and example: `--help` and `--version`
/// are written to stdout with [`print()`] (a write that fails ends the process with one line and
/// status 1, instead of clap's panic or silent loss), usage errors go to stderr with status 2.
#[cfg(not(target_arch = "wasm32"))]
pub fn parse_command_line(
    command: clap::Command,
    argv: impl IntoIterator<Item = impl Into<std::ffi::OsString> + Clone>,
) -> clap::ArgMatches {
    let name = command.get_name().to_owned();
    match command.try_get_matches_from(argv) {
        Ok(matches) => matches,
        Err(e) => exit_on_clap_error(&name, e),
    }
}

/// The end of a tool's `main` (`bench`, `tradeoff`, `labs`): status 0, or one line
/// `NAME: error: what: why` (anyhow's causes joined, no backtrace) and status 1; a run stopped by
/// a signal ends as the signal asked.
#[cfg(not(target_arch = "wasm32"))]
pub fn tool_exit(name: &str, result: anyhow::Result<()>) -> ExitCode {
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            if let Some(Error::Interrupted { signal }) = e.downcast_ref::<Error>() {
                crate::fsutil::signals::end_by(*signal);
            }
            let _ = writeln!(std::io::stderr(), "{name}: error: {}", one_line(&e));
            ExitCode::from(1)
        }
    }
}

/// An error and its causes on one line, each cause once (shaderlab's errors already name
/// their cause, which anyhow's chain would repeat).
#[cfg(not(target_arch = "wasm32"))]
pub fn one_line(e: &anyhow::Error) -> String {
    let mut text = e.to_string();
    for cause in e.chain().skip(1) {
        let cause = cause.to_string();
        if !text.contains(&cause) {
            text.push_str(": ");
            text.push_str(&cause);
        }
    }
    text
}

/// Ends the process for a clap error or request as [`parse_command_line`] describes.
#[cfg(not(target_arch = "wasm32"))]
pub fn exit_on_clap_error(name: &str, e: clap::Error) -> ! {
    if e.use_stderr() {
        let _ = e.print();
        std::process::exit(e.exit_code());
    }
    let text = e.render().to_string();
    match print(&text) {
        Ok(()) => std::process::exit(0),
        Err(failure) => {
            let _ = writeln!(std::io::stderr(), "{name}: error: {failure}");
            std::process::exit(1)
        }
    }
}

/// The parameters of a lab at their defaults (for tests and `--help`).
pub fn defaults(entry: &LabEntry) -> Params {
    (entry.params)()
}
