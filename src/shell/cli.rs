//! What every command-line program of the crate shares (the labs' examples, `shaderlab`, the
//! tools): a failure's exit status ([`Failure`], [`tool_exit`]), lines on stdout that never
//! panic ([`say`], [`print`]), clap's parsing with its requests and errors
//! ([`parse_command_line`]), and the process's environment, set before any thread starts
//! ([`ensure_runtime_dir`]).

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use crate::error::Error;

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
/// runs may share it at once). Call it first thing in `main`, before any thread starts; the
/// lab examples do it through [`main`](super::main), the other examples call it themselves.
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
pub(super) fn skip_display_device_select() {
    if std::env::var_os("MESA_VK_DEVICE_SELECT").is_some() || std::env::var_os("NODEVICE_SELECT").is_some() {
        return;
    }
    // SAFETY: called from main before any other thread exists (argument parsing starts none).
    unsafe { std::env::set_var("NODEVICE_SELECT", "1") };
}

/// Prints a line to stdout; a closed or full stdout is a clean error, not a panic. When an
/// output of this run is standard output itself (`--screenshot /dev/stdout`), the line goes to
/// stderr instead, so the bytes stay clean.
pub fn say(line: &str) -> Result<(), Error> {
    print(&format!("{line}\n"))
}

/// Writes `text` to stdout (stderr when an output took stdout, see [`say`]) and flushes it; a
/// closed or full stdout is [`Error::Io`] on `<stdout>`, never a panic.
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
