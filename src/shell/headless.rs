//! Rendering without a window: `--screenshot`, `--bench`, and the tests.

use std::path::Path;
use std::time::Instant;

use crate::error::{Error, Result};
use crate::gpu::Gpu;
use crate::lab::{Lab, LabEntry, UserFiles};
use crate::offscreen::{save_png, Offscreen, COLOR_FORMAT};
use crate::params::Params;
use crate::render::Frame;

use super::args::Args;
use super::cli::{say, Failure};
use super::session::Sources;
use crate::lab::frame::{render_into, screenshot};

/// Checks a `--screenshot` name before anything is rendered or written.
pub(crate) fn check_png_path(path: &Path) -> Result<()> {
    crate::fsutil::check_png_path(path)
}

pub(super) fn run(entry: &'static LabEntry, args: &Args, params: Params, files: &UserFiles) -> Result<(), Failure> {
    if let Some(path) = &args.screenshot {
        // A read-only folder is found now, not after the GPU was opened and the frame drawn.
        crate::fsutil::check_writable(path)?;
    }
    let recording = match &args.record {
        Some(path) => {
            let recording = super::record::Recording {
                output: super::record::Output::parse(path, entry.info.name)?,
                frames: args.frames.unwrap_or(1),
                fps: args.fps.unwrap_or(25.0),
                from: args
                    .from
                    .unwrap_or_else(|| if params.has("time") { params.f64("time") } else { 0.0 }),
            };
            check_times(entry.info.name, &params, &recording, args.from.is_some())?;
            recording.output.check(recording.frames)?;
            Some(recording)
        }
        None => None,
    };
    let plan = super::view_verb::Plan::of(entry, args)?;
    let mut gpu = Gpu::headless()?;
    gpu.watchdog = args.watchdog();
    gpu.bounded_compiles = true;
    let source = args.shader_source()?;
    let mut lab = Sources::new(source, files.clone(), COLOR_FORMAT).build(&gpu, entry)?;
    // The lab has read its shaders and every file they include: inputs too, which no output
    // may replace. Checked again now, before any frame is drawn.
    if let Some(path) = &args.screenshot {
        crate::fsutil::check_output_path(path)?;
    }
    if let Some(recording) = &recording {
        recording.output.check(recording.frames)?;
    }
    *lab.params_mut() = params;
    let (width, height) = args.size(entry);
    if let Some(plan) = &plan {
        plan.check_inputs()?;
        return plan.run(&gpu, lab.as_mut(), entry.info.name, width, height);
    }
    if let Some(frames) = args.bench {
        if args.gpu_time && !gpu.timestamps {
            eprintln!(
                "{}: note: --gpu-time: this adapter ({}) has no timestamp queries, so no gpu_ms is measured",
                entry.info.name,
                gpu.describe()
            );
        }
        let result = bench(&gpu, lab.as_mut(), frames, width, height, args.gpu_time)?;
        say(&result.line(entry.info.name, lab.params(), width, height, frames))?;
    }
    if let Some(recording) = &recording {
        if let (super::record::Output::Gif(_), (_, Some(note))) =
            (&recording.output, super::record::gif_delay(recording.fps))
        {
            eprintln!("{}: note: {note}", entry.info.name);
        }
        let bar = progress_bar(u64::from(recording.frames), "frames");
        super::record::record(&gpu, lab.as_mut(), recording, width, height, &mut |k| {
            bar.set_position(u64::from(k))
        })?;
        bar.finish_and_clear();
        say(&match &recording.output {
            super::record::Output::Pngs(names) => format!(
                "wrote {} frames: {} … {}",
                recording.frames,
                names.name(0).display(),
                names.name(recording.frames - 1).display()
            ),
            super::record::Output::Gif(path) | super::record::Output::Video(path, _) => {
                format!("wrote {} frames to {}", recording.frames, path.display())
            }
        })?;
    }
    if let Some((x, y)) = args.debug {
        if x >= width || y >= height {
            return Err(Error::Param(format!(
                "{} {x},{y}: the pixel is outside the {width}x{height} picture (x 0..{}, y 0..{})",
                args.pixel_flag.flag(),
                width - 1,
                height - 1
            ))
            .into());
        }
        // The replay first, the frame after: a shader that never ends is explained by the
        // replay's error before the GPU is asked to run it.
        let capture = crate::debug::Capture::encode(&gpu, lab.as_mut(), width, height)?;
        let mut inspection = crate::debug::Inspection::new(entry.info.name, &capture.captured, x, y)?;
        let image = match capture.draw(&gpu) {
            Ok((image, _)) => Some(image),
            // The replay stands without the GPU's pixel; the report says why it has none.
            Err(Error::Hang(why)) if args.screenshot.is_none() => {
                inspection
                    .caveats
                    .push(format!("the pixel the GPU stores is not known: {why}"));
                None
            }
            Err(e) => return Err(e.into()),
        };
        if let Some(image) = &image {
            inspection.gpu_pixel = Some(image.get_pixel(x, y).0);
        }
        if let (Some(path), Some(image)) = (&args.screenshot, &image) {
            save_png(image, path)?;
            eprintln!("wrote {}", path.display());
        }
        if args.json {
            say(&inspection.json())?;
        } else {
            super::cli::print(&inspection.text())?;
        }
        if crate::gpu::hung() {
            // The driver still runs the frame that never ends: end without waiting for it.
            crate::fsutil::signals::exit_now(0);
        }
        return Ok(());
    }
    if let Some(path) = &args.screenshot {
        let image = screenshot(&gpu, lab.as_mut(), width, height)?;
        save_png(&image, path)?;
        say(&format!("wrote {}", path.display()))?;
    }
    Ok(())
}

/// Checks, before anything is rendered, that every frame's time is one the lab's `time`
/// takes (its range is an interval: the first and last frames suffice), and says so in terms
/// of `--from` and `--fps`; a lab without `time` draws every frame the same, so `--from` is a
/// usage error there.
fn check_times(name: &str, params: &Params, recording: &super::record::Recording, from: bool) -> Result<(), Failure> {
    use crate::params::value_text;
    if !params.has("time") {
        if from {
            return Err(Error::Param(format!(
                "`--from`: {name} has no `time` parameter (it does not animate), so every frame would be the same"
            ))
            .into());
        }
        return Ok(());
    }
    let mut probe = params.clone();
    for (k, t) in [(0, recording.time(0)), (recording.frames - 1, recording.last_time())] {
        if probe.set("time", &[t]).is_err() {
            let spec = params.specs().iter().find(|s| s.name == "time");
            let range = spec
                .map(|s| {
                    format!(
                        "{}..{}",
                        crate::params::bound_text(s.min),
                        crate::params::bound_text(s.max)
                    )
                })
                .unwrap_or_default();
            return Err(Error::Param(format!(
                "--from {} --fps {}: frame {k} would be at time {}, outside the lab's `time` range {range}",
                value_text(recording.from),
                value_text(recording.fps),
                value_text(t)
            ))
            .into());
        }
    }
    Ok(())
}

/// A progress bar on stderr when it is a terminal; hidden otherwise (logs and pipes stay clean).
pub fn progress_bar(len: u64, unit: &str) -> indicatif::ProgressBar {
    use std::io::IsTerminal;
    if !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(len);
    let style = indicatif::ProgressStyle::with_template(&format!("{{bar:40}} {{pos}}/{{len}} {unit} {{elapsed}}"))
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar());
    bar.set_style(style);
    bar
}

/// What `--bench` measured.
#[derive(Clone, Copy, Debug)]
pub struct BenchResult {
    /// Wall-clock milliseconds per frame (upload, encode, submit, wait).
    pub ms_per_frame: f64,
    /// GPU milliseconds per frame from timestamp queries (`--gpu-time`).
    pub gpu_ms: Option<f64>,
}

impl BenchResult {
    /// The one line `--bench` prints.
    pub fn line(&self, name: &str, params: &Params, width: u32, height: u32, frames: u32) -> String {
        let gpu = self.gpu_ms.map(|g| format!(" gpu_ms={g:.3}")).unwrap_or_default();
        let object = if params.has("object") {
            format!(" object={}", params.text("object"))
        } else {
            String::new()
        };
        format!(
            "effect={name}{object} size={width}x{height} frames={frames} ms_per_frame={:.3}{gpu}",
            self.ms_per_frame
        )
    }
}

/// Renders `frames` frames offscreen, waiting for each (like the original's swap + glFinish).
/// An animated lab's time advances 1/60 s per frame, as the originals' benchmarks do.
pub fn bench(
    gpu: &Gpu,
    lab: &mut dyn Lab,
    frames: u32,
    width: u32,
    height: u32,
    gpu_time: bool,
) -> Result<BenchResult> {
    let target = Offscreen::new(gpu, width, height);
    // Warm up: the first frames compile shaders in the driver.
    for _ in 0..3 {
        render_into(gpu, lab, &target)?;
        gpu.wait()?;
    }
    let queries = (gpu_time && gpu.timestamps).then(|| {
        let set = gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("bench.timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count: 2,
        });
        let resolve = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("bench.resolve"),
            size: 16,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let read = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("bench.read"),
            size: 16 * frames as u64,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        (set, resolve, read)
    });
    let animated = lab.animated() && lab.params().has("time");
    let start = Instant::now();
    for frame in 0..frames {
        if animated {
            let t = lab.params().f64("time") + 1.0 / 60.0;
            lab.params_mut().set_unchecked("time", &[t]);
        }
        let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("bench.encoder"),
        });
        let writes = queries.as_ref().map(|(set, _, _)| wgpu::RenderPassTimestampWrites {
            query_set: set,
            beginning_of_pass_write_index: Some(0),
            end_of_pass_write_index: Some(1),
        });
        {
            let mut f = Frame {
                timestamps: writes,
                ..Frame::new(gpu, &mut encoder, &target.color, &target.depth, width, height)
            };
            lab.render(&mut f)?;
        }
        if let Some((set, resolve, read)) = &queries {
            encoder.resolve_query_set(set, 0..2, resolve, 0);
            encoder.copy_buffer_to_buffer(resolve, 0, read, 16 * frame as u64, 16);
        }
        gpu.queue.submit([encoder.finish()]);
        gpu.wait()?;
    }
    let ms_per_frame = start.elapsed().as_secs_f64() * 1000.0 / frames as f64;
    let gpu_ms = match &queries {
        Some((_, _, read)) => {
            let slice = read.slice(..);
            slice.map_async(wgpu::MapMode::Read, |_| {});
            gpu.wait()?;
            let ticks: Vec<u64> = {
                let mapped = slice.get_mapped_range().map_err(|e| Error::Wgpu {
                    context: "reading timestamps".into(),
                    message: e.to_string(),
                })?;
                bytemuck::cast_slice(&mapped).to_vec()
            };
            read.unmap();
            let period = gpu.queue.get_timestamp_period() as f64;
            let total: f64 = ticks
                .chunks_exact(2)
                .map(|t| t[1].saturating_sub(t[0]) as f64 * period)
                .sum();
            Some(total / 1e6 / frames as f64)
        }
        None => None,
    };
    Ok(BenchResult { ms_per_frame, gpu_ms })
}
