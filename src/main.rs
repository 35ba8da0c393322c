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
  shaderlab diff legacy VERT FRAG --reference VERT0 FRAG0 [FLAGS…]
                                      the same for two GLSL 1.10/1.20 pairs
  shaderlab check NAME --shaders DIR [--states N] [--seed S] [--min-db D] [--json]
                [--report DIR] [FLAGS…]
                                      a copy of the lab's shaders against the built-in ones
                                      at every object, the lab's states of record and N seeded
                                      random states: per state the PSNR, the pixels that
                                      differ, and where one fails the first line that departs
  shaderlab check legacy VERT FRAG --reference VERT0 FRAG0 [FLAGS…]
                                      the same for two GLSL 1.10/1.20 pairs
  shaderlab view NAME --line FILE:LINE [--name VAR] [--stage vertex|fragment] [FLAGS…]
  shaderlab view NAME --cost [FLAGS…]
                                      a line's value, or the statements the fragment shader
                                      ran, at every pixel, drawn on the GPU: --out FILE.png
                                      (default NAME-view.png, NAME-cost.png), --npy FILE.npy,
                                      --json, --bench N
  shaderlab link NAME [--shaders DIR] [--set NAME=VALUE…] [--base URL]
  shaderlab link legacy VERT FRAG [--set NAME=VALUE…] [--base URL]
                                      the page's link to NAME at that state, carrying the files
                                      of DIR that differ from the built-in ones (or the pair)
  shaderlab open LINK [--into DIR] [FLAGS…]
                                      write a link's files into DIR (default ./NAME-shaders/)
                                      and run the lab from there, as run NAME --shaders DIR
  shaderlab glsl2wgsl [ARGS…]         translate GLSL to WGSL (shaderlab glsl2wgsl --help)
  shaderlab bench [ARGS…]             time every lab offscreen (shaderlab bench --help)
  shaderlab completions bash|zsh|fish|elvish|powershell
                                      the shell's completion script (lab names, verbs, flags)
  shaderlab man [VERB]                the manual page, shaderlab's or a verb's (roff:
                                      shaderlab man view > shaderlab-view.1); --dir DIR
                                      writes every page into DIR
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
             --reference VERT0 FRAG0\n                 \
             for legacy, which draws the pair VERT FRAG: the pair to compare it with\n  \
             --out FILE.png the difference as a picture, with its legend\n  \
             --json         print one JSON object (psnr, differing, worst, first_divergence)",
        ),
        "check" => (
            "draw a lab with the copy of its shaders in DIR and with the built-in ones at many\n\
             states, and compare each as shaderlab diff does: the base state (the lab's defaults\n\
             with --set), every object, the lab's states of record, and N random states drawn\n\
             with seed S across each parameter's slider range. Status 0 when every state passes\n\
             (at least D dB, or identical), 1 when one fails",
            shaderlab::shell::check_verb::USAGE,
            "\n  --shaders DIR  the copy of the lab's shaders (same file names as shaders_glsl/)\n  \
             --reference VERT0 FRAG0\n                 \
             for legacy, which draws the pair VERT FRAG: the pair to check it against\n  \
             --states N     random states to add (default 8, at most 1000)\n  \
             --seed S       their seed (default 0): the same command checks the same states\n  \
             --min-db D     the PSNR a state must reach to pass (default 40)\n  \
             --report DIR   DIR/index.html: each state's three pictures, and where one fails the\n                 \
             copy's source around the line that departs, with both values\n  \
             --json         print one JSON document (lab, states, passed, failed)",
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

/// `shaderlab completions SHELL`: the completion script on stdout.
fn completions(words: &[String]) -> ExitCode {
    let shell = match words {
        [shell] => <clap_complete::Shell as clap::ValueEnum>::from_str(shell, true).ok(),
        _ => None,
    };
    let Some(shell) = shell else {
        let why = match words {
            [_, extra, ..] => format!("`{extra}`: one shell, and nothing after it"),
            _ => "which shell? bash, zsh, fish, elvish or powershell".to_owned(),
        };
        eprintln!("shaderlab completions: {why}\n\nUsage: shaderlab completions bash|zsh|fish|elvish|powershell");
        return ExitCode::from(2);
    };
    print(&shaderlab::shell::verbs::completion_script(shell))
}

/// `shaderlab man [VERB]`: a manual page (roff) on stdout, shaderlab's or a verb's;
/// `shaderlab man --dir DIR`: every page written into DIR (made if missing), all or none.
fn man(words: &[String]) -> ExitCode {
    const MAN_USAGE: &str = "Usage: shaderlab man [VERB] | shaderlab man --dir DIR";
    let pages = match shaderlab::shell::verbs::manual_pages() {
        Ok(pages) => pages,
        Err(e) => {
            let _ = writeln!(std::io::stderr(), "shaderlab man: error: {e}");
            return ExitCode::from(1);
        }
    };
    let usage = |why: String| {
        let _ = writeln!(std::io::stderr(), "shaderlab man: {why}\n\n{MAN_USAGE}");
        ExitCode::from(2)
    };
    let words: Vec<&str> = words.iter().map(String::as_str).collect();
    let dir = match words.as_slice() {
        [] => return print(&String::from_utf8_lossy(&pages[0].1)),
        ["--dir", dir] => (*dir).to_owned(),
        [dir] if dir.starts_with("--dir=") => dir["--dir=".len()..].to_owned(),
        ["--dir"] => return usage("`--dir` needs a folder: --dir DIR".into()),
        [verb] if !verb.starts_with('-') => {
            let file = format!("shaderlab-{verb}.1");
            return match pages.iter().find(|(name, _)| *name == file) {
                Some((_, page)) => print(&String::from_utf8_lossy(page)),
                None => {
                    let verbs: Vec<&str> = pages
                        .iter()
                        .filter_map(|(name, _)| name.strip_prefix("shaderlab-")?.strip_suffix(".1"))
                        .collect();
                    usage(format!("no page for `{verb}`; the verbs are: {}", verbs.join(", ")))
                }
            };
        }
        _ => return usage(format!("`{}`: expected one VERB or --dir DIR", words.join(" "))),
    };
    match write_pages(std::path::Path::new(&dir), &pages) {
        Ok(()) => {
            eprintln!("wrote {} pages into {dir}", pages.len());
            ExitCode::SUCCESS
        }
        Err(e) => {
            let _ = writeln!(std::io::stderr(), "shaderlab man: error: {e}");
            ExitCode::from(if matches!(e, shaderlab::Error::Param(_)) { 2 } else { 1 })
        }
    }
}

/// Writes `pages` into `dir` together ([`shaderlab::fsutil::Batch`]): each to a temporary
/// file, then all moved into place, or none; never over anything but a regular file; `dir` made
/// only then, if missing, and removed again if that fails.
fn write_pages(dir: &std::path::Path, pages: &[(String, Vec<u8>)]) -> Result<(), shaderlab::Error> {
    use shaderlab::fsutil::{signals, Batch, NewDir};
    NewDir::check(dir)?;
    if dir.is_dir() {
        for (name, _) in pages {
            let path = dir.join(name);
            if let shaderlab::fsutil::Dest::Stream(_) = shaderlab::fsutil::Dest::of(&path)? {
                return Err(shaderlab::Error::Param(format!(
                    "{}: not a regular file (a FIFO or device); the pages are files, and replace nothing else",
                    path.display()
                )));
            }
            shaderlab::fsutil::check_output_path(&path)?;
        }
    }
    let _deferred = signals::defer();
    let made = NewDir::create(dir)?;
    let mut batch = Batch::new(true);
    for (name, page) in pages {
        batch.write(&dir.join(name), |w| w.write_all(page))?;
    }
    signals::check()?;
    batch.commit()?;
    made.keep();
    Ok(())
}

/// Status 2 for words after a verb that takes none (`shaderlab list extra`; `help` takes a
/// verb that has its own help).
fn nothing_after(verb: &str, words: &[String]) -> Option<ExitCode> {
    let extra = words.first()?;
    let usage = if verb == "help" {
        "shaderlab help [run|record|debug|diff|check|view|link|open]".to_owned()
    } else {
        format!("shaderlab {verb}")
    };
    eprintln!("shaderlab {verb}: `{extra}`: this takes nothing after it\n\nUsage: {usage}");
    Some(ExitCode::from(2))
}

fn main() -> ExitCode {
    shaderlab::shell::ensure_runtime_dir();
    let mut argv: Vec<OsString> = std::env::args_os().collect();
    let words: Vec<String> = argv.iter().map(|a| a.to_string_lossy().into_owned()).collect();
    let after = words.get(2..).unwrap_or_default();
    match words.get(1).map(String::as_str) {
        None => print(&format!("{USAGE}\n")),
        Some("help" | "--help" | "-h") if matches!(after, [v] if ["run", "record", "debug", "diff", "check", "view"].contains(&v.as_str())) => {
            print(&verb_help(&after[0]))
        }
        Some("help" | "--help" | "-h") if matches!(after, [v] if v == "link" || v == "open") => {
            let argv = vec![OsString::from(&after[0]), OsString::from("--help")];
            if after[0] == "link" {
                shaderlab::shell::link_verb::link_main(argv)
            } else {
                shaderlab::shell::link_verb::open_main(argv)
            }
        }
        Some(verb @ ("help" | "--help" | "-h")) => match nothing_after(verb, after) {
            Some(refused) => refused,
            None => print(&format!("{USAGE}\n")),
        },
        Some(verb @ ("--version" | "-V")) => match nothing_after(verb, after) {
            Some(refused) => refused,
            None => print(&format!("shaderlab {}\n", env!("CARGO_PKG_VERSION"))),
        },
        Some("list") => {
            if let Some(refused) = nothing_after("list", after) {
                return refused;
            }
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
        Some(verb @ ("run" | "record" | "debug" | "diff" | "check" | "view"))
            if matches!(words.get(2).map(String::as_str), Some("--help" | "-h")) =>
        {
            print(&verb_help(verb))
        }
        Some(verb @ ("run" | "record" | "legacy" | "debug" | "diff" | "check" | "view")) => {
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
            } else if verb == "check" {
                shaderlab::shell::check_verb::check_main_from(entry, args)
            } else {
                shaderlab::shell::main_from(entry, args)
            }
        }
        Some("link") => shaderlab::shell::link_verb::link_main(argv.drain(1..).collect()),
        Some("open") => shaderlab::shell::link_verb::open_main(argv.drain(1..).collect()),
        Some("completions") => completions(after),
        Some("man") => man(after),
        Some("glsl2wgsl") => glsl2wgsl::main_from(argv.drain(1..)),
        Some("bench") => shaderlab::shell::tool_exit("shaderlab bench", bench::run(argv.drain(1..))),
        Some(other) => {
            eprintln!("shaderlab: unknown command `{other}`\n\n{USAGE}");
            ExitCode::from(2)
        }
    }
}
