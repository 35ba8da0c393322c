//! `shaderlab glsl2wgsl FILE` and `cargo run --release --example glsl2wgsl -- FILE`: translates a GLSL 450 shader to WGSL with naga.
//!
//! The stage comes from the extension (`.vert`, `.frag`, `.comp`). `#include "x.glsl"` resolves
//! relative to the file's directory, then to the snippets built into shaderlab.
//!
//! ```text
//! glsl2wgsl FILE              # WGSL on stdout
//! glsl2wgsl FILE -o OUT.wgsl  # WGSL into a file
//! glsl2wgsl --all DIR OUTDIR  # every .vert/.frag/.comp of DIR to OUTDIR/NAME.EXT.wgsl
//! glsl2wgsl --legacy VERT FRAG # a GLSL 1.10/1.20 pair: the GLSL 450 it becomes, then the WGSL
//! ```
//!
//! Shader errors print as `path:line:column: message` with the line and a caret, and exit 1.
//! Output files are written whole (a temporary file renamed into place; `--all` moves all of
//! them in at the end, so a failure leaves OUTDIR as it was, and an OUTDIR that did not exist
//! does not either), and never over an input: `-o` naming the input file or a file it
//! `#include`s, through any path or link, is refused with exit status 2
//! ([`crate::fsutil::inputs`]). `-o` onto a FIFO or a device (`/dev/stdout`, `/dev/null`)
//! writes into it and never replaces it. A closed or full stdout is one line and status 1.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use crate::fsutil::{check_output_path, inputs, write_atomic, Batch, NewDir};
use crate::shader::compile_file;
use crate::shell::cli;
use anyhow::{bail, Context};
use clap::{CommandFactory, FromArgMatches, Parser};

/// Translate GLSL 450 shaders to WGSL with naga.
#[derive(Parser, Debug)]
#[command(name = "glsl2wgsl", arg_required_else_help = true)]
struct Args {
    /// A .vert, .frag or .comp file.
    #[arg(required_unless_present_any = ["all", "legacy"], conflicts_with_all = ["all", "legacy"])]
    file: Option<PathBuf>,
    /// Write the WGSL here instead of stdout.
    #[arg(short, long, value_name = "OUT", conflicts_with = "all")]
    output: Option<PathBuf>,
    /// Translate every .vert/.frag/.comp of DIR into OUTDIR as NAME.EXT.wgsl.
    #[arg(long, num_args = 2, value_names = ["DIR", "OUTDIR"])]
    all: Option<Vec<PathBuf>>,
    /// Translate a GLSL 1.10/1.20 vertex and fragment shader (as the legacy example runs them):
    /// prints the GLSL 450 of both, then their WGSL.
    #[arg(long, num_args = 2, value_names = ["VERT", "FRAG"], conflicts_with_all = ["all", "output"])]
    legacy: Option<Vec<PathBuf>>,
}

/// The GLSL 450 and WGSL of a GLSL 1.10/1.20 pair.
fn legacy(vert: &Path, frag: &Path) -> anyhow::Result<String> {
    let translation = crate::legacy::Translation::from_files(vert, frag)?;
    let (vs, fs) = translation.compile()?;
    let mut out = String::new();
    for (t, compiled) in [(&translation.vertex, &vs), (&translation.fragment, &fs)] {
        out.push_str(&format!("// ==== {}: GLSL 450 ====\n{}", t.source.path, t.output.text));
        out.push_str(&format!(
            "\n// ==== {}: WGSL ====\n{}\n",
            t.source.path,
            compiled.to_wgsl()?
        ));
    }
    Ok(out)
}

/// A mistake in the command line (exit status 2).
#[derive(Debug)]
struct Usage(String);

impl std::fmt::Display for Usage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Usage {}

/// Refuses an output that is one of the inputs (noted before, [`inputs::note`]), a
/// directory, or in a missing directory.
fn check_output(output: &Path) -> anyhow::Result<()> {
    check_output_path(output).map_err(output_error)
}

/// An output's error: a usage error (status 2) for a name that cannot take the output (an
/// input, a directory), else the library's message.
fn output_error(e: crate::error::Error) -> anyhow::Error {
    match e {
        crate::error::Error::Param(message) => Usage(message).into(),
        e => lib(e),
    }
}

/// A library error as one message (its Display already names the cause).
fn lib(e: crate::error::Error) -> anyhow::Error {
    anyhow::anyhow!("{e}")
}

/// Reads, splices, validates and translates one file.
fn translate(path: &Path) -> anyhow::Result<String> {
    compile_file(path).and_then(|shader| shader.to_wgsl()).map_err(lib)
}

fn write(path: &Path, text: &str) -> anyhow::Result<()> {
    write_atomic(path, |w| w.write_all(text.as_bytes())).map_err(output_error)
}

fn run(args: &Args) -> anyhow::Result<()> {
    if let Some([vert, frag]) = args.legacy.as_deref() {
        cli::print(&legacy(vert, frag)?).map_err(lib)?;
        return Ok(());
    }
    if let Some([dir, out_dir]) = args.all.as_deref() {
        let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
            .with_context(|| format!("cannot read directory {}", dir.display()))?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.is_file() && matches!(p.extension().and_then(|e| e.to_str()), Some("vert" | "frag" | "comp")))
            .collect();
        files.sort();
        if files.is_empty() {
            bail!("no .vert, .frag or .comp files in {}", dir.display());
        }
        let outputs: Vec<PathBuf> = files
            .iter()
            .map(|file| {
                out_dir.join(format!(
                    "{}.wgsl",
                    file.file_name().unwrap_or_default().to_string_lossy()
                ))
            })
            .collect();
        for file in &files {
            inputs::note(file, "shader files");
        }
        // OUTDIR is made only once everything is translated; the names in one that exists are
        // checked now.
        NewDir::check(out_dir).map_err(lib)?;
        if out_dir.is_dir() {
            for out in &outputs {
                check_output(out)?;
            }
        }
        let mut wgsl = Vec::with_capacity(files.len());
        for file in &files {
            wgsl.push(translate(file)?);
        }
        // All translated, then all moved in: a broken shader leaves OUTDIR as it was (and a
        // missing one missing). A signal meanwhile is held until the files and a folder made
        // here are removed again (the guards are dropped in the reverse order of their making).
        let _deferred = crate::fsutil::signals::defer();
        let new_dir = NewDir::create(out_dir).map_err(lib)?;
        let mut batch = Batch::new(true);
        for (text, out) in wgsl.iter().zip(&outputs) {
            batch
                .write(out, |w| w.write_all(text.as_bytes()))
                .map_err(output_error)?;
        }
        crate::fsutil::signals::check().map_err(lib)?;
        batch.commit().map_err(lib)?;
        new_dir.keep();
        for (file, out) in files.iter().zip(&outputs) {
            eprintln!("{} -> {}", file.display(), out.display());
        }
        return Ok(());
    }
    let file = args.file.as_deref().context("no input file")?;
    if let Some(out) = &args.output {
        inputs::note(file, "shader files");
        check_output(out)?;
    }
    let wgsl = translate(file)?;
    match &args.output {
        Some(out) => write(out, &wgsl)?,
        None => cli::print(&wgsl).map_err(lib)?,
    }
    Ok(())
}

/// `glsl2wgsl`'s `main`: the command line of the process.
pub fn main() -> ExitCode {
    cli::ensure_runtime_dir();
    main_from(std::env::args_os())
}

/// The tool's command line as clap describes it (for `shaderlab`'s manual pages and completion
/// scripts).
pub fn command() -> clap::Command {
    Args::command()
}

/// The translator for a command line (program name first); `shaderlab glsl2wgsl` calls it too.
pub fn main_from(argv: impl IntoIterator<Item = std::ffi::OsString>) -> ExitCode {
    let matches = cli::parse_command_line(Args::command(), argv);
    let args = Args::from_arg_matches(&matches).unwrap_or_else(|e| cli::exit_on_clap_error("glsl2wgsl", e));
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("glsl2wgsl: error: {}", cli::one_line(&e));
            ExitCode::from(if e.is::<Usage>() { 2 } else { 1 })
        }
    }
}
