//! `shaderlab diff NAME --shaders DIR [FLAGS…] [--out FILE.png] [--json]`: a lab drawn with
//! the copy of its shaders in DIR and with the built-in ones, at the same state, compared
//! ([`crate::debug::diff`]): PSNR, the pixels that differ, the worst pixel, and the first line
//! where the copy's trace there departs from the reference's. A lab that draws the shader
//! files it is given (`legacy VERT FRAG`) is compared with another pair,
//! `--reference VERT0 FRAG0`.

use std::ffi::OsString;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use super::args::Args;
use super::cli::{say, Failure};
use super::session::Sources;
use super::verbs::{self, Mode};
use crate::error::Error;
use crate::lab::LabEntry;
use crate::offscreen::COLOR_FORMAT;
use crate::shader::ShaderSource;

/// The usage line.
pub const USAGE: &str = "shaderlab diff NAME --shaders DIR [--out FILE.png] [--json] [FLAGS…]\n       \
shaderlab diff legacy VERT FRAG --reference VERT0 FRAG0 [--out FILE.png] [--json] [FLAGS…]";

/// What `diff` takes besides the lab's flags.
pub(super) struct Own {
    /// The picture of the difference.
    pub(super) out: Option<PathBuf>,
    /// One JSON object instead of the text.
    pub(super) json: bool,
    /// `--reference VERT0 FRAG0`: the pair a lab that draws the files it is given is compared
    /// with.
    pub(super) reference: Option<Vec<PathBuf>>,
}

/// Takes `--out FILE`, `--out=FILE`, `--json` and `--reference VERT0 FRAG0` out of `argv`
/// (the lab's flags stay).
fn take_own(argv: Vec<OsString>) -> Result<(Own, Vec<OsString>), String> {
    let mut own = Own {
        out: None,
        json: false,
        reference: None,
    };
    let mut rest = Vec::with_capacity(argv.len());
    let mut words = argv.into_iter();
    let value = |word: Option<OsString>| word.filter(|w| !w.to_string_lossy().starts_with('-'));
    while let Some(word) = words.next() {
        let text = word.to_string_lossy();
        if text == "--json" {
            own.json = true;
        } else if text == "--out" {
            match value(words.next()) {
                Some(path) => own.out = Some(PathBuf::from(path)),
                None => return Err("`--out` needs a file: --out FILE.png".into()),
            }
        } else if let Some(path) = text.strip_prefix("--out=") {
            own.out = Some(PathBuf::from(path));
        } else if text == "--reference" {
            match (value(words.next()), value(words.next())) {
                (Some(vert), Some(frag)) => own.reference = Some(vec![PathBuf::from(vert), PathBuf::from(frag)]),
                _ => return Err("`--reference` needs two files: --reference VERT0 FRAG0".into()),
            }
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
    if let Some(which) = which(entry, &args, own.reference.is_some(), "compare with") {
        let _ = writeln!(std::io::stderr(), "shaderlab diff: {which}\n\nUsage: {USAGE}");
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

/// Why a comparison cannot start, as a question (status 2): no copy (`--shaders DIR`), or for a
/// lab that draws the pair it is given, no pair to `what` (`--reference VERT0 FRAG0`).
pub(super) fn which(entry: &LabEntry, args: &Args, reference: bool, what: &str) -> Option<String> {
    let name = entry.info.name;
    if verbs::draws_named_files(entry) {
        (!reference && !args.given.iter().any(|g| g == "shaders")).then(|| {
            format!("which pair to {what}? name it with --reference VERT0 FRAG0 ({name} draws the pair VERT FRAG it is given)")
        })
    } else {
        args.shaders
            .is_none()
            .then(|| "which copy? give the folder of the copied shaders with --shaders DIR".to_owned())
    }
}

/// The two labs a comparison draws, built once on one device: the copy and the reference,
/// each with its parameters, and the size to draw them at.
pub(super) struct Pair {
    pub(super) gpu: crate::gpu::Gpu,
    pub(super) mine: Box<dyn crate::lab::Lab>,
    pub(super) reference: Box<dyn crate::lab::Lab>,
    /// The copy's parameters (the lab's defaults with `--set`).
    pub(super) params: crate::params::Params,
    /// The reference's (a pair of its own may declare other uniforms).
    pub(super) reference_params: crate::params::Params,
    pub(super) size: (u32, u32),
}

/// Builds the copy (`--shaders DIR`, or the pair `legacy` is given) and the reference (the
/// built-in shaders, or `reference`, the pair `--reference` names) of `entry`'s lab for
/// `verb` (`diff`, `check`), checking `outputs` before anything is drawn and again once the
/// labs have read their inputs.
pub(super) fn pair(
    entry: &'static LabEntry,
    args: &Args,
    reference: Option<&Vec<PathBuf>>,
    mode: Mode,
    outputs: &[&std::path::Path],
) -> Result<Pair, Failure> {
    for (flag, given) in [
        ("--screenshot", args.screenshot.is_some()),
        ("--bench", args.bench.is_some()),
        ("--record", args.record.is_some()),
        ("--debug", args.debug.is_some()),
    ] {
        if given {
            return Err(Error::Param(format!(
                "`{flag}` is not for `shaderlab {}`",
                if mode == Mode::Check { "check" } else { "diff" }
            ))
            .into());
        }
    }
    verbs::check(entry, args, mode)?;
    let name = entry.info.name;
    let pair = verbs::draws_named_files(entry);
    if reference.is_some() && !pair {
        return Err(Error::Param(format!(
            "`--reference` names the pair a lab that draws the files it is given (legacy) is compared with, and does nothing for {name}, whose reference is its built-in shaders: give the copy with --shaders DIR"
        ))
        .into());
    }
    let params = args.params(entry)?;
    // The reference: the built-in shaders, or the pair `--reference` names (with the
    // parameters that pair declares).
    let reference_args = reference.map(|files| Args {
        files: files.clone(),
        ..args.clone()
    });
    let in_reference = |e: Error| match e {
        Error::Param(why) => Error::Param(format!("the reference pair (--reference): {why}")),
        e => e,
    };
    let reference_params = match &reference_args {
        Some(r) => r.params(entry).map_err(in_reference)?,
        None => params.clone(),
    };
    for path in outputs {
        crate::fsutil::check_writable(path)?;
    }
    let copy = args.shader_source()?;
    let files = args.files(entry)?;
    let reference_files = match &reference_args {
        Some(r) => Some(r.files(entry).map_err(in_reference)?),
        None => None,
    };
    let mut gpu = crate::gpu::Gpu::headless()?;
    gpu.watchdog = args.watchdog();
    gpu.bounded_compiles = true;
    let show = |paths: &[PathBuf]| {
        paths
            .iter()
            .map(|p| p.display().to_string())
            .collect::<Vec<_>>()
            .join(" ")
    };
    let (copy_words, reference_words) = match reference {
        Some(pair) => (
            format!("the pair {}", show(&args.files)),
            format!("the pair {}", show(pair)),
        ),
        None => (
            format!(
                "the copy in {}",
                args.shaders
                    .as_ref()
                    .map(|d| d.display().to_string())
                    .unwrap_or_default()
            ),
            "the built-in shaders".to_owned(),
        ),
    };
    let mine = Sources::new(copy.clone(), files.clone(), COLOR_FORMAT)
        .build(&gpu, entry)
        .map_err(|e| match e {
            Error::Layout(why) | Error::Binding(why) => Error::Debug(format!(
                "{copy_words} takes different inputs from {reference_words}, so the two cannot be compared: {why}"
            )),
            e => e,
        })?;
    let reference_files = reference_files.unwrap_or_else(|| files.clone());
    let reference = Sources::new(ShaderSource::Embedded, reference_files, COLOR_FORMAT).build(&gpu, entry)?;
    for path in outputs {
        // Both labs have read their shaders and the files they include: no output may replace
        // one.
        crate::fsutil::check_output_path(path)?;
    }
    Ok(Pair {
        gpu,
        mine,
        reference,
        params,
        reference_params,
        size: args.size(entry),
    })
}

pub(super) fn run(entry: &'static LabEntry, args: &Args, own: &Own) -> Result<(), Failure> {
    if let Some(path) = &own.out {
        crate::fsutil::check_png_path(path)?;
    }
    let outputs: Vec<&std::path::Path> = own.out.iter().map(PathBuf::as_path).collect();
    let Pair {
        gpu,
        mut mine,
        mut reference,
        params,
        reference_params,
        size: (width, height),
    } = pair(entry, args, own.reference.as_ref(), Mode::Diff, &outputs)?;
    let name = entry.info.name;
    *mine.params_mut() = params;
    *reference.params_mut() = reference_params;
    let diff = crate::debug::diff::diff_labs(&gpu, name, mine.as_mut(), reference.as_mut(), (width, height))?;
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
