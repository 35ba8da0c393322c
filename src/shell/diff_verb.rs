//! `shaderlab diff NAME --shaders DIR [FLAGS…] [--out FILE.png] [--json]`: a lab drawn with
//! the copy of its shaders in DIR and with the built-in ones, at the same state, compared
//! ([`crate::debug::diff`]): PSNR, the pixels that differ, the worst pixel, and the first line
//! where the copy's trace there departs from the reference's.

use std::ffi::OsString;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use super::args::Args;
use super::cli::{say, Failure};
use crate::error::Error;
use crate::lab::LabEntry;
use crate::offscreen::COLOR_FORMAT;
use crate::shader::ShaderSource;

/// The usage line.
pub const USAGE: &str = "shaderlab diff NAME --shaders DIR [--out FILE.png] [--json] [FLAGS…]";

/// What `diff` takes besides the lab's flags.
pub(super) struct Own {
    /// The picture of the difference.
    pub(super) out: Option<PathBuf>,
    /// One JSON object instead of the text.
    pub(super) json: bool,
}

/// Takes `--out FILE`, `--out=FILE` and `--json` out of `argv` (the lab's flags stay).
fn take_own(argv: Vec<OsString>) -> Result<(Own, Vec<OsString>), String> {
    let mut own = Own { out: None, json: false };
    let mut rest = Vec::with_capacity(argv.len());
    let mut words = argv.into_iter();
    while let Some(word) = words.next() {
        let text = word.to_string_lossy();
        if text == "--json" {
            own.json = true;
        } else if text == "--out" {
            match words.next() {
                Some(path) if !path.to_string_lossy().starts_with('-') => own.out = Some(PathBuf::from(path)),
                _ => return Err("`--out` needs a file: --out FILE.png".into()),
            }
        } else if let Some(path) = text.strip_prefix("--out=") {
            own.out = Some(PathBuf::from(path));
        } else {
            rest.push(word);
        }
    }
    Ok((own, rest))
}

/// `shaderlab diff NAME …` (program name first): status 0 with the comparison on stdout, 2 for
/// a usage error, 1 for a copy that does not build or cannot be compared.
pub fn diff_main_from(entry: &'static LabEntry, argv: Vec<OsString>) -> ExitCode {
    super::ensure_runtime_dir();
    let name = entry.info.name;
    let (own, argv) = match take_own(argv) {
        Ok(split) => split,
        Err(e) => {
            let _ = writeln!(std::io::stderr(), "shaderlab diff: {e}\n\nUsage: {USAGE}");
            return ExitCode::from(2);
        }
    };
    let args = Args::parse_from_for(entry, argv);
    if args.shaders.is_none() {
        let _ = writeln!(
            std::io::stderr(),
            "shaderlab diff: which copy? give the folder of the copied shaders with --shaders DIR\n\nUsage: {USAGE}"
        );
        return ExitCode::from(2);
    }
    super::cli::skip_display_device_select();
    match run(entry, &args, &own) {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => {
            let _ = writeln!(std::io::stderr(), "{name}: error: {}", failure.error);
            if crate::gpu::hung() {
                crate::fsutil::signals::exit_now(i32::from(failure.code));
            }
            ExitCode::from(failure.code)
        }
    }
}

pub(super) fn run(entry: &'static LabEntry, args: &Args, own: &Own) -> Result<(), Failure> {
    for (flag, given) in [
        ("--screenshot", args.screenshot.is_some()),
        ("--bench", args.bench.is_some()),
        ("--record", args.record.is_some()),
        ("--debug", args.debug.is_some()),
    ] {
        if given {
            return Err(Error::Param(format!("`{flag}` is not for `shaderlab diff`; usage: {USAGE}")).into());
        }
    }
    let params = args.params(entry)?;
    if let Some(path) = &own.out {
        crate::fsutil::check_png_path(path)?;
        crate::fsutil::check_writable(path)?;
    }
    let copy = args.shader_source()?;
    let files = args.files(entry)?;
    let mut gpu = crate::gpu::Gpu::headless()?;
    gpu.watchdog = args.watchdog();
    gpu.bounded_compiles = true;
    let dir = args
        .shaders
        .as_ref()
        .map(|d| d.display().to_string())
        .unwrap_or_default();
    let mut mine =
        super::session::Session::open_lab(entry, &gpu, &copy, COLOR_FORMAT, &files).map_err(|e| match e {
            Error::Layout(why) | Error::Binding(why) => Error::Debug(format!(
            "the copy in {dir} takes different inputs from the built-in shaders, so the two cannot be compared: {why}"
        )),
            e => e,
        })?;
    let mut reference = super::session::Session::open_lab(entry, &gpu, &ShaderSource::Embedded, COLOR_FORMAT, &files)?;
    if let Some(path) = &own.out {
        // The lab has read its shaders and the files they include: no output may replace one.
        crate::fsutil::check_output_path(path)?;
    }
    *mine.params_mut() = params.clone();
    *reference.params_mut() = params;
    let (width, height) = args.size(entry);
    let diff = crate::debug::diff::diff_labs(
        &gpu,
        entry.info.name,
        mine.as_mut(),
        reference.as_mut(),
        (width, height),
    )?;
    if let Some(path) = &own.out {
        crate::offscreen::save_png(&diff.picture, path)?;
        eprintln!("wrote {}", path.display());
    }
    if own.json {
        say(&diff.json())?;
    } else {
        super::cli::print(&diff.text())?;
    }
    Ok(())
}
