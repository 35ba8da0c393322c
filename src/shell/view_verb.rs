//! Whole-frame views from the command line: `shaderlab view NAME --line FILE:LINE | --cost`
//! and a lab's `--line` / `--cost` flags. One frame is encoded, drawn again on the GPU by
//! [`crate::debug::view`] and written as a picture with its legend ([`crate::debug::picture`]),
//! as raw values (`--npy`), as a summary (`--json`), or timed (`--bench N`).

use std::ffi::OsString;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use super::args::Args;
use super::cli::{say, Failure};
use crate::debug::paint::{self, Painter};
use crate::debug::picture::{self, Legend, Scale};
use crate::debug::view::{self, Probe, ValueFrame, ViewDrawer};
use crate::debug::Stage;
use crate::error::{Error, Result};
use crate::fsutil::Dest;
use crate::gpu::Gpu;
use crate::lab::{Lab, LabEntry};
use crate::offscreen::Offscreen;

/// The usage line.
pub const USAGE: &str = "shaderlab view NAME (--line FILE:LINE [--name VAR] [--stage vertex|fragment] | --cost) \
[--out FILE.png] [--npy FILE.npy] [--json] [--bench N] [FLAGS…]";

/// `shaderlab view NAME …` (program name first): the lab's command line, with `--out FILE`
/// standing for `--screenshot FILE`; status 2 when neither `--line` nor `--cost` is given.
pub fn view_main_from(entry: &'static LabEntry, argv: Vec<OsString>) -> ExitCode {
    super::ensure_runtime_dir();
    let mut words = Vec::with_capacity(argv.len());
    for word in argv {
        let text = word.to_string_lossy();
        if text == "--out" {
            words.push(OsString::from("--screenshot"));
        } else if let Some(path) = text.strip_prefix("--out=") {
            words.push(OsString::from(format!("--screenshot={path}")));
        } else {
            words.push(word);
        }
    }
    let args = Args::parse_from_for(entry, words);
    if args.line.is_none() && !args.cost {
        let _ = writeln!(
            std::io::stderr(),
            "shaderlab view: which view? give --line FILE:LINE (a line's value) or --cost (the statements run)\n\nUsage: {USAGE}"
        );
        return ExitCode::from(2);
    }
    super::main_parsed(entry, args)
}

/// A view asked for on the command line, with its outputs checked.
pub(super) struct Plan {
    probe: Probe,
    /// The picture (`--screenshot`, `shaderlab view`'s `--out`, or the default name).
    out: Option<PathBuf>,
    npy: Option<PathBuf>,
    json: bool,
    bench: Option<u32>,
}

/// Checks that `path` can take a NumPy array: an output path ending in `.npy`, writable; a
/// stream (`/dev/stdout`, a FIFO, a device, or a link to one) takes it whatever its name, as
/// `--screenshot`'s does.
fn check_npy_path(path: &Path) -> Result<()> {
    crate::fsutil::check_output_path(path)?;
    let is_npy = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("npy"));
    let stream = matches!(Dest::of(path)?, Dest::Stream(_));
    if !is_npy && !stream {
        return Err(Error::Param(format!(
            "{}: --npy writes a NumPy array; use a .npy name",
            path.display()
        )));
    }
    crate::fsutil::check_writable(path)
}

impl Plan {
    /// The view `args` ask for (none without `--line` or `--cost`), its outputs checked before
    /// anything is drawn. Without `--screenshot`, `--npy`, `--json` or `--bench` the picture
    /// goes to `NAME-view.png` (`NAME-cost.png`) in the current folder.
    pub(super) fn of(entry: &LabEntry, args: &Args) -> Result<Option<Plan>> {
        let probe = match (&args.line, args.cost) {
            (Some((file, line)), _) => Probe::Line {
                file: file.clone(),
                line: *line,
                name: args.name.clone(),
                stage: args.stage.as_deref().map(|s| match s {
                    "vertex" => Stage::Vertex,
                    _ => Stage::Fragment,
                }),
            },
            (None, true) => Probe::Cost,
            (None, false) => return Ok(None),
        };
        let asked = args.screenshot.is_some() || args.npy.is_some() || args.json || args.bench.is_some();
        let out = match &args.screenshot {
            Some(path) => Some(path.clone()),
            None if !asked => Some(PathBuf::from(format!(
                "{}-{}.png",
                entry.info.name,
                if probe == Probe::Cost { "cost" } else { "view" }
            ))),
            None => None,
        };
        if let Some(path) = &out {
            crate::fsutil::check_png_path(path)?;
            crate::fsutil::check_writable(path)?;
        }
        if let Some(path) = &args.npy {
            check_npy_path(path)?;
        }
        if let (Some(a), Some(b)) = (&out, &args.npy) {
            // The same file, or the same stream, through any name or link.
            if a == b || Dest::of(a)? == Dest::of(b)? {
                return Err(Error::Param(format!(
                    "{}: the picture and the array would be the same file",
                    a.display()
                )));
            }
        }
        Ok(Some(Plan {
            probe,
            out,
            npy: args.npy.clone(),
            json: args.json,
            bench: args.bench,
        }))
    }

    /// Checks the outputs again once the lab has read its inputs (no output may replace one).
    pub(super) fn check_inputs(&self) -> Result<()> {
        for path in self.out.iter().chain(&self.npy) {
            crate::fsutil::check_output_path(path)?;
        }
        Ok(())
    }

    /// Draws the view of `lab`'s frame at `width` × `height` and writes what was asked.
    pub(super) fn run(&self, gpu: &Gpu, lab: &mut dyn Lab, name: &str, width: u32, height: u32) -> Result<(), Failure> {
        let mut drawer = ViewDrawer::new();
        let log = view::encode(gpu, lab, width, height)?;
        let probe = self.probe.clone();
        let frame = if self.bench.is_some() {
            drawer.draw(gpu, &log, &probe, width, height)
        } else {
            // Drawn once: its targets are given back as they are read.
            std::mem::take(&mut drawer).draw_once(gpu, &log, &probe, width, height)
        }
        .map_err(failure)?;
        drop(log);
        let timings = match self.bench {
            Some(frames) => Some((frames, bench(gpu, lab, &mut drawer, &probe, frames, width, height)?)),
            None => None,
        };
        let (image, legend) = frame.picture();
        if let Some(path) = &self.out {
            crate::offscreen::save_png(&image, path)?;
            eprintln!("wrote {}", path.display());
        }
        if let Some(path) = &self.npy {
            write_npy(&frame, path)?;
            eprintln!("wrote {}", path.display());
        }
        if self.json {
            // One JSON document: the summary, with the timings in it.
            let mut summary = summary(name, &frame, legend.as_ref());
            if let (Some((frames, t)), Some(map)) = (&timings, summary.as_object_mut()) {
                let number = crate::debug::json_number;
                map.insert(
                    "bench".into(),
                    serde_json::json!({
                        "frames": frames,
                        "ms_per_frame": number(t.painted),
                        "plain_ms_per_frame": number(t.plain),
                        "ratio": number(t.ratio()),
                        "values_ms_per_frame": number(t.values),
                    }),
                );
            }
            say(&summary.to_string())?;
        } else if let Some((frames, t)) = &timings {
            let object = if lab.params().has("object") {
                format!(" object={}", lab.params().text("object"))
            } else {
                String::new()
            };
            say(&format!(
                "effect={name}{object} size={width}x{height} frames={frames} {} ms_per_frame={:.3} plain_ms_per_frame={:.3} ratio={:.2} values_ms_per_frame={:.3}",
                probe_words(&frame),
                t.painted,
                t.plain,
                t.ratio(),
                t.values
            ))?;
        } else {
            say(&text(&frame, legend.as_ref()))?;
        }
        Ok(())
    }
}

/// A view error is the user's probe that does not fit the lab's shaders (status 2), but for a
/// rewritten shader the GPU refused or a frame of another size (status 1).
fn failure(e: Error) -> Failure {
    let usage = matches!(&e, Error::View { usage: true, .. });
    Failure {
        code: if usage { 2 } else { 1 },
        error: e,
    }
}

/// What [`bench`] measured, in milliseconds per frame.
struct Timings {
    /// The lab's plain frame, drawn and waited for (as `--bench` without a view).
    plain: f64,
    /// The view drawn and its picture painted on the GPU, waited for with its legend: what a
    /// window or a page showing the view does each frame.
    painted: f64,
    /// The view drawn and its values read back (what `--out`, `--npy` and `--json` do).
    values: f64,
}

impl Timings {
    /// How many times the plain frame's time the painted view takes.
    fn ratio(&self) -> f64 {
        self.painted / self.plain.max(1e-9)
    }
}

/// Times `frames` frames of `lab` three ways, side by side in turn (the machine's load falls
/// on all three alike): the plain frame, the view as the window and the page show it, and the
/// view read back. An animated lab's time advances 1/60 s per frame, as in `--bench` without a
/// view.
fn bench(
    gpu: &Gpu,
    lab: &mut dyn Lab,
    drawer: &mut ViewDrawer,
    probe: &Probe,
    frames: u32,
    width: u32,
    height: u32,
) -> Result<Timings, Failure> {
    let target = Offscreen::new(gpu, width, height);
    let scratch = Offscreen::new(gpu, width, height);
    let mut painter = Painter::new(&gpu.device);
    let plain = |lab: &mut dyn Lab| -> Result<(), Failure> {
        crate::lab::frame::render_into(gpu, lab, &target)?;
        gpu.wait()?;
        Ok(())
    };
    let mut painted = |lab: &mut dyn Lab, drawer: &mut ViewDrawer| -> Result<(), Failure> {
        let log = view::encode_to(gpu, lab, &scratch)?;
        paint::paint_and_wait(gpu, drawer, &mut painter, &log, probe, width, height).map_err(failure)?;
        Ok(())
    };
    let values = |lab: &mut dyn Lab, drawer: &mut ViewDrawer| -> Result<(), Failure> {
        let log = view::encode_to(gpu, lab, &scratch)?;
        drawer.draw(gpu, &log, probe, width, height).map_err(failure)?;
        Ok(())
    };
    for _ in 0..2 {
        plain(lab)?;
        painted(lab, drawer)?;
        values(lab, drawer)?;
    }
    let animated = lab.animated() && lab.params().has("time");
    let mut spent = [std::time::Duration::ZERO; 3];
    for _ in 0..frames {
        if animated {
            let t = lab.params().f64("time") + 1.0 / 60.0;
            lab.params_mut().set_unchecked("time", &[t]);
        }
        let start = Instant::now();
        plain(lab)?;
        let between = Instant::now();
        painted(lab, drawer)?;
        let then = Instant::now();
        values(lab, drawer)?;
        spent[0] += between - start;
        spent[1] += then - between;
        spent[2] += then.elapsed();
    }
    let ms = |d: std::time::Duration| d.as_secs_f64() * 1000.0 / f64::from(frames);
    Ok(Timings {
        plain: ms(spent[0]),
        painted: ms(spent[1]),
        values: ms(spent[2]),
    })
}

/// Writes the view's raw values: a line's value (NaN where it did not run or no fragment
/// ran), or the cost (NaN where no fragment ran).
fn write_npy(frame: &ValueFrame, path: &Path) -> Result<()> {
    let drawn = frame.drawn();
    if frame.resolved.is_none() {
        let values: Vec<[f32; 4]> = frame.cost.iter().map(|&c| [c as f32, 0.0, 0.0, 0.0]).collect();
        return picture::write_npy(path, frame.width, frame.height, 1, &values, &drawn);
    }
    let ran: Vec<bool> = frame.ran.iter().zip(&drawn).map(|(r, d)| *r && *d).collect();
    picture::write_npy(
        path,
        frame.width,
        frame.height,
        frame.components as usize,
        &frame.values,
        &ran,
    )
}

fn stage_name(stage: Stage) -> &'static str {
    match stage {
        Stage::Vertex => "vertex",
        Stage::Fragment => "fragment",
    }
}

/// The view in a benchmark's words: `view=line file=… line=17 name=Idiff stage=fragment`, or
/// `view=cost`.
fn probe_words(frame: &ValueFrame) -> String {
    match &frame.resolved {
        Some(r) => format!(
            "view=line file={} line={} name={} stage={}",
            r.site.file,
            r.site.line,
            r.site.name.as_deref().unwrap_or("?"),
            stage_name(r.stage)
        ),
        None => "view=cost".into(),
    }
}

/// The smallest and largest finite component where the line ran and a fragment ran.
fn range(frame: &ValueFrame) -> Option<(f64, f64)> {
    let comps = (frame.components as usize).clamp(1, 4);
    let mut out: Option<(f64, f64)> = None;
    for (k, v) in frame.values.iter().enumerate() {
        if !frame.ran[k] || frame.cost[k] == 0 || v[..comps].iter().any(|x| !x.is_finite()) {
            continue;
        }
        for x in &v[..comps] {
            let x = f64::from(*x);
            out = Some(out.map_or((x, x), |(lo, hi)| (lo.min(x), hi.max(x))));
        }
    }
    out
}

/// The cost's smallest, largest and mean count over the pixels where a fragment ran.
fn cost_figures(frame: &ValueFrame) -> Option<(u32, u32, f64)> {
    let drawn: Vec<u32> = frame.cost.iter().copied().filter(|&c| c > 0).collect();
    let (lo, hi) = (drawn.iter().min()?, drawn.iter().max()?);
    let sum: u64 = drawn.iter().map(|&c| u64::from(c)).sum();
    Some((*lo, *hi, sum as f64 / drawn.len() as f64))
}

/// The view's summary as one JSON object.
pub fn summary(name: &str, frame: &ValueFrame, legend: Option<&Legend>) -> serde_json::Value {
    use serde_json::{json, Value};
    let number = |v: f64| crate::debug::json_number(v);
    let drawn = frame.cost.iter().filter(|&&c| c > 0).count();
    let mut out = json!({
        "lab": name,
        "size": [frame.width, frame.height],
        "drawn": drawn,
        "background": frame.cost.len() - drawn,
    });
    let map = out.as_object_mut().expect("an object");
    match &frame.resolved {
        Some(r) => {
            map.insert("view".into(), "line".into());
            map.insert("file".into(), r.site.file.clone().into());
            map.insert("line".into(), r.site.line.into());
            map.insert("name".into(), r.site.name.clone().map_or(Value::Null, Value::from));
            map.insert("stage".into(), stage_name(r.stage).into());
            map.insert("vertex".into(), frame.vertex.into());
            map.insert("components".into(), frame.components.into());
            let (min, max) = range(frame).map_or((Value::Null, Value::Null), |(a, b)| (number(a), number(b)));
            map.insert("range".into(), json!({"min": min, "max": max}));
            if let Some(l) = legend {
                let scale = match l.scale {
                    Scale::Sequential => "sequential",
                    Scale::Diverging => "diverging",
                    Scale::Rgb => "rgb",
                };
                map.insert(
                    "legend".into(),
                    json!({"scale": scale, "min": number(l.min), "max": number(l.max)}),
                );
                map.insert("nan".into(), l.nan.into());
                map.insert("inf".into(), (l.pos_inf + l.neg_inf).into());
                map.insert("not_run".into(), l.not_run.into());
            }
        }
        None => {
            map.insert("view".into(), "cost".into());
            let cost = cost_figures(frame).map_or(
                Value::Null,
                |(lo, hi, mean)| json!({"min": lo, "max": hi, "mean": number(mean)}),
            );
            map.insert("cost".into(), cost);
        }
    }
    out
}

/// The view's summary in words.
pub fn text(frame: &ValueFrame, legend: Option<&Legend>) -> String {
    let drawn = frame.cost.iter().filter(|&&c| c > 0).count();
    match (&frame.resolved, legend) {
        (Some(r), Some(l)) => {
            let range = range(frame).map_or("no finite value".into(), |(a, b)| {
                format!("values {} … {}", picture::short(a), picture::short(b))
            });
            format!(
                "{}:{} `{}` ({} shader{}, {} component{}): {range}; {}; {drawn} pixels drawn",
                r.site.file,
                r.site.line,
                r.site.name.as_deref().unwrap_or("?"),
                stage_name(r.stage),
                if frame.vertex {
                    ", its value at the corners interpolated as a varying"
                } else {
                    ""
                },
                frame.components,
                if frame.components == 1 { "" } else { "s" },
                l.text()
            )
        }
        _ => match cost_figures(frame) {
            Some((lo, hi, mean)) => format!(
                "cost: the fragment shader ran {lo} … {hi} statements a pixel (mean {}) over {drawn} pixels drawn",
                picture::short(mean)
            ),
            None => "cost: no fragment ran".into(),
        },
    }
}
