//! `shaderlab`: every lab and tool of the course in one command (`cargo install --path .`).
//! The labs run through the same code as the examples (`shaderlab run phong …` is
//! `cargo run --example phong -- …`), and so do the tools (`shaderlab::shell::tools`).

use std::ffi::OsString;
use std::io::Write;
use std::process::ExitCode;

use shaderlab::course;

use shaderlab::shell::tools::{bench, glsl2wgsl};

shaderlab::say_when_exhausted!();

const USAGE: &str = "shaderlab: the GLSL course labs on wgpu

Usage:
  shaderlab list                      every lab, by lecture
  shaderlab run NAME [FLAGS…]         run a lab (shaderlab run NAME --help lists its flags)
  shaderlab record NAME OUT [FLAGS…]  run NAME --record OUT (needs --frames N; OUT.gif, OUT.mp4,
                                      OUT.webm, frames-%04d.png or a directory)
  shaderlab legacy VERT FRAG [FLAGS…] a course's own GLSL 1.10/1.20 pair
  shaderlab debug NAME --pixel X,Y [--json] [FLAGS…]
                                      why pixel X,Y has its colour: the covering triangle,
                                      the shaders line by line with their values
  shaderlab diff NAME --shaders DIR [--out FILE.png] [--json] [FLAGS…]
                                      where a copy of the lab's shaders draws differently
                                      from the built-in ones: PSNR, the pixels that differ,
                                      the worst one, and the first line whose value departs
  shaderlab view NAME --line FILE:LINE [--name VAR] [--stage vertex|fragment] [FLAGS…]
  shaderlab view NAME --cost [FLAGS…]
                                      a line's value, or the statements the fragment shader
                                      ran, at every pixel, drawn on the GPU: --out FILE.png
                                      (default NAME-view.png, NAME-cost.png), --npy FILE.npy,
                                      --json, --bench N
  shaderlab glsl2wgsl [ARGS…]         translate GLSL to WGSL (shaderlab glsl2wgsl --help)
  shaderlab bench [ARGS…]             time every lab offscreen (shaderlab bench --help)
  shaderlab completions bash|zsh|fish|elvish|powershell
                                      the shell's completion script (lab names, verbs, flags)
  shaderlab man                       the manual page (roff: shaderlab man > shaderlab.1)
  shaderlab --version

Each lab is also an example: cargo run --release --example NAME -- [FLAGS…]";

/// `shaderlab VERB --help`: what the verb does, its usage, and where the lab's flags are listed.
fn verb_help(verb: &str) -> String {
    let (what, usage, flags) = match verb {
        "run" => (
            "run a lab in a window, or offscreen with --screenshot, --bench, --record or --debug",
            "shaderlab run NAME [FLAGS…]",
            "",
        ),
        "record" => (
            "record a lab's frames offscreen at a fixed time step into OUT: NAME.gif, NAME.mp4,\n\
             NAME.webm (through ffmpeg), a PNG sequence (frames-%04d.png) or a directory",
            "shaderlab record NAME OUT --frames N [--fps F] [--from T] [FLAGS…]",
            "",
        ),
        "diff" => (
            "draw a lab with the copy of its shaders in DIR and with the built-in ones, at the same\n\
             state, and compare: the difference as a picture (--out), PSNR, the pixels that differ,\n\
             the worst one, and there the first line, in the order the shaders ran, whose value\n\
             departs from the built-in shader's (file, line, name, both values)",
            shaderlab::shell::diff_verb::USAGE,
            "\n  --shaders DIR  the copy of the lab's shaders (same file names as shaders_glsl/)\n  \
             --out FILE.png the difference as a picture, with its legend\n  \
             --json         print one JSON object (psnr, differing, worst, first_divergence)",
        ),
        "view" => (
            "show a value over the whole frame, drawn on the GPU by an instrumented copy of the\n\
             lab's own shaders: the value line LINE of FILE assigns at every pixel (--line), or how\n\
             many statements the fragment shader ran there (--cost, the `cost` of shaderlab debug)",
            shaderlab::shell::view_verb::USAGE,
            "\n  --line FILE:LINE   a line of one of the lab's shader files (phong.frag:17); a vertex\n                     \
             shader line shows its value at the corners, interpolated as a varying\n  \
             --name VAR         the name to show, where the line assigns several things\n  \
             --stage STAGE      vertex or fragment, where both shaders include the file\n  \
             --cost             the statements the fragment shader ran at each pixel\n  \
             --out FILE.png     the picture, with its legend (default NAME-view.png or\n                     \
             NAME-cost.png here, unless --npy, --json or --bench is given)\n  \
             --npy FILE.npy     the raw values: height x width x components, float32, NaN where\n                     \
             the line did not run\n  \
             --json             print one JSON object (range, counts; cost min, max, mean)\n  \
             --bench N          time N views (each: the frame, the view, read back)",
        ),
        _ => (
            "why pixel X,Y of a lab's picture has its colour: the triangle that covers it, the vertex\n\
             shader at its corners, the interpolated inputs, the fragment shader line by line with\n\
             every value, and the stored colour (no window)",
            "shaderlab debug NAME --pixel X,Y [--json] [FLAGS…]",
            "\n  --pixel X,Y  the pixel: column and row from the top left, as in --screenshot's PNG\n  \
             --json       print one JSON object (pixel, covered, trace, ...) instead of the text",
        ),
    };
    let names: Vec<&str> = course::ALL.iter().map(|e| e.info.name).collect();
    format!(
        "shaderlab {verb}: {what}\n\nUsage: {usage}\n\n  NAME         a lab: {}{flags}\n  \
         FLAGS…       the lab's own flags (--set, --size, --shaders, ...): shaderlab {verb} NAME --help lists them\n",
        names.join(", ")
    )
}

/// Writes `text` to stdout: status 0, or 1 with one line when stdout is closed or full
/// (`shaderlab list | head -c 1`, `> /dev/full`).
fn print(text: &str) -> ExitCode {
    match shaderlab::shell::print(text) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let _ = writeln!(std::io::stderr(), "shaderlab: error: {e}");
            ExitCode::from(1)
        }
    }
}

/// The command line as clap describes it, for completion scripts and the manual page: the
/// verbs, each lab's name, and the labs' own flags (the same definitions `--help` prints). The
/// verbs themselves are dispatched by hand below, since each hands the rest of its command line
/// to a lab's or tool's own parser.
fn described() -> clap::Command {
    use clap::{Arg, Command, CommandFactory};
    let names: Vec<&'static str> = course::ALL.iter().map(|e| e.info.name).collect();
    let lab = || {
        Arg::new("NAME")
            .required(true)
            .help("the lab")
            .value_parser(clap::builder::PossibleValuesParser::new(names.clone()))
    };
    let flags: Vec<Arg> = shaderlab::shell::Args::command()
        .get_arguments()
        .filter(|a| a.get_id() != "files")
        .cloned()
        .collect();
    let with_flags =
        |name: &'static str, about: &'static str| Command::new(name).about(about).arg(lab()).args(flags.clone());
    Command::new("shaderlab")
        .version(env!("CARGO_PKG_VERSION"))
        .about("the GLSL course labs on wgpu: 32 labs in a window or offscreen, a course's own GLSL 1.10 files, and a GLSL debugger")
        .subcommand_required(true)
        .subcommand(Command::new("list").about("every lab, by lecture"))
        .subcommand(with_flags("run", "run a lab in a window, or offscreen with --screenshot, --bench, --record or --debug"))
        .subcommand(
            with_flags("record", "record a lab's frames offscreen into OUT (GIF, MP4, WebM, PNGs)")
                .arg(Arg::new("OUT").required(true).index(2).value_hint(clap::ValueHint::FilePath)),
        )
        .subcommand(
            Command::new("legacy")
                .about("a course's own GLSL 1.10/1.20 pair")
                .arg(Arg::new("VERT").value_hint(clap::ValueHint::FilePath))
                .arg(Arg::new("FRAG").value_hint(clap::ValueHint::FilePath))
                .args(flags.clone()),
        )
        .subcommand(with_flags("debug", "why a pixel has its colour, line by line"))
        .subcommand(with_flags("diff", "where a copy of the lab's shaders (--shaders DIR) draws differently, and from which line"))
        .subcommand(with_flags("view", "a line's value (--line FILE:LINE) or the fragment shader's cost (--cost) at every pixel"))
        .subcommand(Command::new("glsl2wgsl").about("translate GLSL to WGSL (shaderlab glsl2wgsl --help)"))
        .subcommand(Command::new("bench").about("time every lab offscreen (shaderlab bench --help)"))
        .subcommand(
            Command::new("completions")
                .about("the shell's completion script")
                .arg(Arg::new("SHELL").required(true).value_parser(clap::value_parser!(clap_complete::Shell))),
        )
        .subcommand(Command::new("man").about("the manual page, in roff"))
}

/// `shaderlab completions SHELL`: the completion script on stdout.
fn completions(shell: Option<&str>) -> ExitCode {
    let shell = shell.and_then(|s| <clap_complete::Shell as clap::ValueEnum>::from_str(s, true).ok());
    let Some(shell) = shell else {
        eprintln!("shaderlab completions: which shell? bash, zsh, fish, elvish or powershell\n\nUsage: shaderlab completions SHELL");
        return ExitCode::from(2);
    };
    let mut script = Vec::new();
    clap_complete::generate(shell, &mut described(), "shaderlab", &mut script);
    print(&String::from_utf8_lossy(&script))
}

/// `shaderlab man`: the manual page (roff) on stdout.
fn man() -> ExitCode {
    let mut page = Vec::new();
    match clap_mangen::Man::new(described()).render(&mut page) {
        Ok(()) => print(&String::from_utf8_lossy(&page)),
        Err(e) => {
            let _ = writeln!(std::io::stderr(), "shaderlab man: {e}");
            ExitCode::from(1)
        }
    }
}

fn main() -> ExitCode {
    shaderlab::shell::ensure_runtime_dir();
    let mut argv: Vec<OsString> = std::env::args_os().collect();
    let words: Vec<String> = argv.iter().map(|a| a.to_string_lossy().into_owned()).collect();
    match words.get(1).map(String::as_str) {
        None | Some("help" | "--help" | "-h") => print(&format!("{USAGE}\n")),
        Some("--version" | "-V") => print(&format!("shaderlab {}\n", env!("CARGO_PKG_VERSION"))),
        Some("list") => {
            let mut lines = Vec::new();
            let mut lecture = "";
            for entry in course::ALL {
                let info = entry.info;
                if info.lecture != lecture {
                    lecture = info.lecture;
                    lines.push(lecture.to_owned());
                }
                lines.push(format!(
                    "  {:<22} {} {} ({}x{})",
                    info.name, info.original_title, info.label, info.size.0, info.size.1
                ));
            }
            lines.push(String::new());
            print(&lines.join("\n"))
        }
        Some(verb @ ("run" | "record" | "debug" | "diff" | "view"))
            if matches!(words.get(2).map(String::as_str), Some("--help" | "-h")) =>
        {
            print(&verb_help(verb))
        }
        Some(verb @ ("run" | "record" | "legacy" | "debug" | "diff" | "view")) => {
            let (name, rest) = if verb == "legacy" {
                (Some("legacy"), 2)
            } else {
                (words.get(2).map(String::as_str), 3)
            };
            let Some(entry) = name.and_then(course::find) else {
                let names: Vec<&str> = course::ALL.iter().map(|e| e.info.name).collect();
                eprintln!(
                    "shaderlab {verb}: {}; the labs are: {}\n\nUsage: shaderlab {verb} NAME{} [FLAGS…]",
                    match name {
                        Some(n) if !n.starts_with('-') => format!("no lab called `{n}`"),
                        _ => "which lab?".to_owned(),
                    },
                    names.join(", "),
                    if verb == "record" { " OUT" } else { "" }
                );
                return ExitCode::from(2);
            };
            let program = if verb == "legacy" {
                "shaderlab legacy".to_owned()
            } else {
                format!("shaderlab {verb} {}", entry.info.name)
            };
            let mut args: Vec<OsString> = vec![program.into()];
            if verb == "record" {
                match argv.get(3) {
                    Some(out) if !out.to_string_lossy().starts_with('-') => {
                        args.extend([OsString::from("--record"), out.clone()])
                    }
                    _ => {
                        eprintln!("shaderlab record: where to? Usage: shaderlab record NAME OUT --frames N [FLAGS…]");
                        return ExitCode::from(2);
                    }
                }
                args.extend(argv.drain(4..));
            } else {
                args.extend(argv.drain(rest.min(argv.len())..));
            }
            if verb == "debug" {
                shaderlab::shell::debug_main_from(entry, args)
            } else if verb == "view" {
                shaderlab::shell::view_verb::view_main_from(entry, args)
            } else if verb == "diff" {
                shaderlab::shell::diff_verb::diff_main_from(entry, args)
            } else {
                shaderlab::shell::main_from(entry, args)
            }
        }
        Some("completions") => completions(words.get(2).map(String::as_str)),
        Some("man") => man(),
        Some("glsl2wgsl") => glsl2wgsl::main_from(argv.drain(1..)),
        Some("bench") => shaderlab::shell::tool_exit("shaderlab bench", bench::run(argv.drain(1..))),
        Some(other) => {
            eprintln!("shaderlab: unknown command `{other}`\n\n{USAGE}");
            ExitCode::from(2)
        }
    }
}
