//! `shaderlab bench` and `cargo run --release --example bench`: every lab of `course::ALL` (on every object where it has
//! a choice of objects), offscreen at its default size, rotated 30/45 degrees where it has
//! angles, N frames each (submit + wait per frame, like the originals' swap + glFinish; animated
//! labs advance their time by 1/60 s per frame). Prints the port's milliseconds per frame only:
//! a comparison with the original is measured side by side, alternating, with the originals'
//! `bench-vs-original` script (see `docs/speed.md`), never against stored figures. `--debugger`
//! times the debugger's capture and traces instead, `--diff` a diff of two frames.

use crate::course;
use crate::gpu::Gpu;
use crate::lab::BuildContext;
use crate::offscreen::COLOR_FORMAT;
use crate::params::Kind;
use crate::shader::ShaderSource;
use crate::shell::bench;
use crate::shell::cli::{self, say, tool_exit};
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
    /// Time the debugger instead: per lab, the capture of a frame, the first trace of a pixel
    /// (which shades every vertex for the positions) and later traces (median and slowest of
    /// `--frames` pixels on the drawn surface).
    #[arg(long)]
    debugger: bool,
    /// Time `diff` instead: a diff of two 640x360 phong frames with its two traces (a copy of
    /// the built-in shaders with a planted bug against them), from the labs built to the
    /// comparison, `--frames` times (at most 1000): the median and the slowest.
    #[arg(long, conflicts_with_all = ["gpu_time", "debugger", "only"])]
    diff: bool,
}

/// `bench`'s `main`: the command line of the process.
pub fn main() -> std::process::ExitCode {
    cli::ensure_runtime_dir();
    tool_exit("bench", run(std::env::args_os()))
}

/// The benchmark for a command line (program name first); `shaderlab bench` calls it too.
pub fn run(argv: impl IntoIterator<Item = std::ffi::OsString>) -> anyhow::Result<()> {
    let matches = cli::parse_command_line(Args::command(), argv);
    let args = Args::from_arg_matches(&matches).unwrap_or_else(|e| cli::exit_on_clap_error("bench", e));
    check(&args);
    let gpu = Gpu::headless()?;
    if args.debugger {
        return debugger(&gpu, &args);
    }
    if args.diff {
        return diff(&gpu, &args);
    }
    say(&format!("adapter: {}; {} frames per case", gpu.describe(), args.frames))?;
    say("| lab | object | size | ms/frame | gpu ms |")?;
    say("|---|---|---|---|---|")?;
    let source = ShaderSource::Embedded;
    let cx = BuildContext::new(&gpu, &source, COLOR_FORMAT, &crate::lab::NO_FILES);
    let bar = crate::shell::progress_bar(course::ALL.len() as u64, "labs");
    for entry in course::ALL {
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

/// The tool's command line as clap describes it (for `shaderlab`'s manual pages and completion
/// scripts).
pub fn command() -> clap::Command {
    Args::command()
}

/// Ends the process with a usage error (status 2) for a flag that does nothing: `--gpu-time`
/// with `--debugger` (which times no frame), `--only` that no lab's name contains.
fn check(args: &Args) {
    let refuse = |why: String| -> ! {
        cli::exit_on_clap_error(
            "bench",
            Args::command().error(clap::error::ErrorKind::ArgumentConflict, why),
        )
    };
    if args.debugger && args.gpu_time {
        refuse("`--gpu-time` times frames on the GPU, and does nothing with --debugger, which times the debugger on the CPU".into());
    }
    if let Some(only) = &args.only {
        if !course::ALL.iter().any(|e| e.info.name.contains(only.as_str())) {
            let names: Vec<&str> = course::ALL.iter().map(|e| e.info.name).collect();
            refuse(format!(
                "`--only {only}`: no lab's name contains `{only}`; the labs are: {}",
                names.join(", ")
            ));
        }
    }
}

/// `bench --debugger`: how long the debugger takes per lab.
fn debugger(gpu: &Gpu, args: &Args) -> anyhow::Result<()> {
    use std::time::Instant;
    let pixels = args.frames.min(1000) as usize;
    say(&format!(
        "adapter: {}; debugger: capture, first trace, then {pixels} traces at pixels on the drawn surface",
        gpu.describe()
    ))?;
    say("| lab | size | capture ms | first trace ms | trace ms (median) | trace ms (slowest) |")?;
    say("|---|---|---|---|---|---|")?;
    let source = ShaderSource::Embedded;
    let cx = BuildContext::new(gpu, &source, COLOR_FORMAT, &crate::lab::NO_FILES);
    for entry in course::ALL {
        if args
            .only
            .as_ref()
            .is_some_and(|o| !entry.info.name.contains(o.as_str()))
        {
            continue;
        }
        let Ok(mut lab) = (entry.new)(&cx) else { continue };
        if lab.params().has("time") {
            lab.params_mut().set("time", &[2.0])?;
        }
        let (w, h) = entry.info.size;
        let start = Instant::now();
        let (image, captured) = crate::debug::capture_lab(gpu, lab.as_mut(), w, h, true)?;
        let image = image.unwrap_or_default();
        let capture = start.elapsed();
        // Pixels unlike the top-left one (the background), spread by a fixed stride.
        let background = *image.get_pixel(0, 0);
        let drawn: Vec<(u32, u32)> = image
            .enumerate_pixels()
            .filter(|(_, _, p)| **p != background)
            .map(|(x, y, _)| (x, y))
            .collect();
        let pick = |k: usize| -> (u32, u32) {
            if drawn.is_empty() {
                (w / 2, h / 2)
            } else {
                drawn[(k * 7919) % drawn.len()]
            }
        };
        let (x, y) = pick(0);
        let start = Instant::now();
        crate::debug::Inspection::new(entry.info.name, &captured, x, y)?;
        let first = start.elapsed();
        let mut times = Vec::with_capacity(pixels);
        for k in 1..=pixels {
            let (x, y) = pick(k);
            let start = Instant::now();
            crate::debug::Inspection::new(entry.info.name, &captured, x, y)?;
            times.push(start.elapsed().as_secs_f64() * 1e3);
        }
        times.sort_by(f64::total_cmp);
        let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
        say(&format!(
            "| {} | {w}x{h} | {:.1} | {:.2} | {:.2} | {:.2} |",
            entry.info.name,
            ms(capture),
            ms(first),
            times.get(times.len() / 2).copied().unwrap_or(0.0),
            times.last().copied().unwrap_or(0.0)
        ))?;
    }
    Ok(())
}

/// `bench --diff`: how long a diff of two frames with its traces takes.
fn diff(gpu: &Gpu, args: &Args) -> anyhow::Result<()> {
    use crate::shell::session::Sources;
    use std::time::Instant;
    let runs = args.frames.min(1000) as usize;
    let entry = course::find("phong").ok_or_else(|| anyhow::anyhow!("no phong lab"))?;
    // The copy: the built-in shaders, phong.frag's diffuse term floored at 0.5.
    let dir = std::env::temp_dir().join(format!("shaderlab-bench-diff-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    let planted = (|| -> anyhow::Result<ShaderSource> {
        for name in crate::shader::embedded_names() {
            let text = crate::shader::embedded_source(name).ok_or_else(|| anyhow::anyhow!("no {name}"))?;
            let text = if name == "phong.frag" {
                anyhow::ensure!(
                    text.contains("max(dot(N, L), 0.0)"),
                    "phong.frag has no `max(dot(N, L), 0.0)` to plant the bug in"
                );
                text.replacen("max(dot(N, L), 0.0)", "max(dot(N, L), 0.5)", 1)
            } else {
                text.to_string()
            };
            std::fs::write(dir.join(name), text)?;
        }
        Ok(ShaderSource::dir(&dir)?)
    })();
    let timed = planted.and_then(|copy| {
        let files = &crate::lab::NO_FILES;
        let mut mine = Sources::new(copy, files.clone(), COLOR_FORMAT).build(gpu, entry)?;
        let mut reference = Sources::new(ShaderSource::Embedded, files.clone(), COLOR_FORMAT).build(gpu, entry)?;
        let mut times = Vec::with_capacity(runs);
        for _ in 0..runs {
            let start = Instant::now();
            let d = crate::debug::diff::diff_labs(gpu, "phong", mine.as_mut(), reference.as_mut(), (640, 360))?;
            times.push(start.elapsed().as_secs_f64() * 1e3);
            anyhow::ensure!(d.first_divergence.is_some(), "the diff found no divergence");
        }
        Ok(times)
    });
    let _ = std::fs::remove_dir_all(&dir);
    let mut times = timed?;
    times.sort_by(f64::total_cmp);
    say(&format!(
        "adapter: {}; a diff of two 640x360 phong frames with two traces, {runs} times: median {:.1} ms, slowest {:.1} ms",
        gpu.describe(),
        times[times.len() / 2],
        times[times.len() - 1]
    ))?;
    Ok(())
}
