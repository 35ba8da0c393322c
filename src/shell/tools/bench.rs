//! `shaderlab bench` and `cargo run --release --example bench`: every lab of `labs::ALL` (on every object where it has
//! a choice of objects), offscreen at its default size, rotated 30/45 degrees where it has
//! angles, N frames each (submit + wait per frame, like the originals' swap + glFinish; animated
//! labs advance their time by 1/60 s per frame). Prints the port's milliseconds per frame only:
//! a comparison with the original is measured side by side, alternating, with
//! `../shared/original/bench-vs-original`, never against stored figures.

use crate::lab::BuildContext;
use crate::offscreen::COLOR_FORMAT;
use crate::params::Kind;
use crate::shader::ShaderSource;
use crate::shell::bench;
use crate::shell::{say, tool_exit};
use crate::{labs, Gpu};
use clap::{CommandFactory, FromArgMatches, Parser};

#[derive(Parser)]
#[command(name = "bench", about = "Benchmark every lab (and object) offscreen")]
struct Args {
    /// Frames per case.
    #[arg(long, default_value_t = 300, value_parser = clap::value_parser!(u32).range(1..=100_000))]
    frames: u32,
    /// Only labs whose name contains this.
    #[arg(long)]
    only: Option<String>,
    /// Also time each frame on the GPU with timestamp queries.
    #[arg(long)]
    gpu_time: bool,
}

/// `bench`'s `main`: the command line of the process.
pub fn main() -> std::process::ExitCode {
    crate::shell::ensure_runtime_dir();
    tool_exit("bench", run(std::env::args_os()))
}

/// The benchmark for a command line (program name first); `shaderlab bench` calls it too.
pub fn run(argv: impl IntoIterator<Item = std::ffi::OsString>) -> anyhow::Result<()> {
    let matches = crate::shell::parse_command_line(Args::command(), argv);
    let args = Args::from_arg_matches(&matches).unwrap_or_else(|e| crate::shell::exit_on_clap_error("bench", e));
    let gpu = Gpu::headless()?;
    say(&format!("adapter: {}; {} frames per case", gpu.describe(), args.frames))?;
    say("| lab | object | size | ms/frame | gpu ms |")?;
    say("|---|---|---|---|---|")?;
    let source = ShaderSource::Embedded;
    let cx = BuildContext {
        gpu: &gpu,
        source: &source,
        format: COLOR_FORMAT,
        files: &crate::lab::NO_FILES,
        lab: "",
    };
    let bar = crate::shell::progress_bar(labs::ALL.len() as u64, "labs");
    for entry in labs::ALL {
        bar.inc(1);
        if args
            .only
            .as_ref()
            .is_some_and(|o| !entry.info.name.contains(o.as_str()))
        {
            continue;
        }
        let mut lab = (entry.new)(&cx)?;
        for (name, value) in [("xangle", 30.0), ("yangle", 45.0)] {
            if lab.params().has(name) {
                lab.params_mut().set(name, &[value])?;
            }
        }
        let objects: Vec<&str> = lab
            .params()
            .specs()
            .iter()
            .find(|s| s.name == "object")
            .and_then(|s| match s.kind {
                Kind::Choice(names) => Some(names.to_vec()),
                _ => None,
            })
            .unwrap_or_else(|| vec!["-"]);
        let (w, h) = entry.info.size;
        for object in objects {
            if object != "-" {
                lab.params_mut().set_str("object", object)?;
            }
            let r = bench(&gpu, lab.as_mut(), args.frames, w, h, args.gpu_time)?;
            bar.suspend(|| {
                say(&format!(
                    "| {} | {object} | {w}x{h} | {:.3} | {} |",
                    entry.info.name,
                    r.ms_per_frame,
                    r.gpu_ms.map(|g| format!("{g:.3}")).unwrap_or_else(|| "-".into())
                ))
            })?;
        }
    }
    bar.finish_and_clear();
    Ok(())
}
