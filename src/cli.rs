//! The command line every lab example shares, and the offscreen paths (`--screenshot`,
//! `--bench`). Usage errors exit with status 2 and list what is valid; runtime errors
//! (no adapter, broken shader, unwritable file) print one clear message and exit with 1.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use clap::{CommandFactory, FromArgMatches, Parser};
use glam::Vec3;

use crate::effect::{Effect, Lab, Object, Shading, Tess};
use crate::error::Error;
use crate::gpu::Gpu;
use crate::offscreen::{save_png, Offscreen, COLOR_FORMAT};
use crate::shader::ShaderSource;

/// Arguments of every lab example.
#[derive(Parser, Debug, Clone)]
#[command(version, about = "A CMP211 Lab05 shader exercise on wgpu")]
pub struct LabArgs {
    /// Object to draw: cube, sphere, torus or teapot.
    #[arg(long, default_value = "teapot", value_parser = parse_object)]
    pub object: Object,
    /// Rotation in degrees, applied as glRotatef X, then Y, then Z.
    #[arg(long, value_name = "X,Y,Z", default_value = "0,0,0", value_parser = parse_vec3)]
    pub rotate: Vec3,
    /// The time uniform in seconds (noise labs). Default: 0 offscreen, a clock in a window.
    #[arg(long, value_name = "T", value_parser = parse_finite)]
    pub time: Option<f32>,
    /// Image or window size.
    #[arg(long, value_name = "WxH", default_value = "640x360", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Set a parameter by its GLSL uniform name, e.g. Ka=0.2 or diffuseColor=1,0.5,0 (repeatable).
    #[arg(long = "set", value_name = "NAME=VALUE", value_parser = parse_set)]
    pub set: Vec<(String, Vec<f32>)>,
    /// Render one frame offscreen (no window), write it to this PNG and exit.
    #[arg(long, value_name = "FILE.png")]
    pub screenshot: Option<PathBuf>,
    /// Render N frames offscreen, waiting for each, and print ms_per_frame (and gpu_ms).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub bench: Option<u32>,
    /// Read shaders from this directory instead of the built-in copies (same file names as shaders_glsl/).
    #[arg(long, value_name = "DIR")]
    pub shaders: Option<PathBuf>,
    /// Shading model of the phong example: flat, gouraud, phong (the original) or blinn.
    #[arg(long, value_parser = parse_shading)]
    pub shading: Option<Shading>,
    /// Tessellation of sphere, torus and teapot: a level (slices = stacks, sides = rings, teapot
    /// grid; 3 to 512) or `auto` (smallest level with silhouette error under half a pixel).
    /// Default: GLUT's (24, 24, teapot 8), as the original; `auto` with a port-only mode
    /// (`--shading` other than phong, `--set smooth=1`).
    #[arg(long, value_name = "N|auto", value_parser = parse_tess)]
    pub tess: Option<Tess>,
}

fn parse_shading(s: &str) -> Result<Shading, String> {
    Shading::from_name(s).ok_or_else(|| format!("unknown shading `{s}`; valid: flat, gouraud, phong, blinn"))
}

fn parse_tess(s: &str) -> Result<Tess, String> {
    if s == "auto" {
        return Ok(Tess::Auto {
            budget_px: crate::tess::DEFAULT_BUDGET_PX,
        });
    }
    match s.parse::<u32>() {
        Ok(n) if (crate::tess::MIN_LEVEL..=crate::tess::MAX_LEVEL).contains(&n) => Ok(Tess::Level(n)),
        _ => Err(format!("`{s}`: expected `auto` or a level from 3 to 512")),
    }
}

fn parse_object(s: &str) -> Result<Object, String> {
    Object::from_name(s).ok_or_else(|| format!("unknown object `{s}`; valid: cube, sphere, torus, teapot"))
}

fn parse_finite(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(format!("`{s}` is not a finite number")),
    }
}

/// Parses comma-separated finite numbers.
pub fn parse_numbers(s: &str) -> Result<Vec<f32>, String> {
    s.split(',').map(parse_finite).collect()
}

fn parse_vec3(s: &str) -> Result<Vec3, String> {
    match parse_numbers(s)?.as_slice() {
        [x, y, z] => Ok(Vec3::new(*x, *y, *z)),
        _ => Err(format!("`{s}`: expected three numbers X,Y,Z")),
    }
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let bad = || format!("`{s}`: expected WxH with each side between 1 and 8192, e.g. 640x360");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let (w, h) = (
        w.trim().parse::<u32>().map_err(|_| bad())?,
        h.trim().parse::<u32>().map_err(|_| bad())?,
    );
    if !(1..=8192).contains(&w) || !(1..=8192).contains(&h) {
        return Err(bad());
    }
    Ok((w, h))
}

fn parse_set(s: &str) -> Result<(String, Vec<f32>), String> {
    let (name, value) = s
        .split_once('=')
        .ok_or_else(|| format!("`{s}`: expected NAME=VALUE, e.g. Ka=0.2"))?;
    Ok((name.trim().to_owned(), parse_numbers(value)?))
}

impl LabArgs {
    /// Parses the process arguments for effect `E`; prints usage and exits 2 on a bad flag.
    pub fn parse_for<E: Effect>() -> Self {
        let command =
            LabArgs::command()
                .name(E::NAME)
                .about(format!("{} {}: {}", E::TITLE, E::LABEL, "CMP211 Lab05 on wgpu"));
        let matches = command.get_matches();
        LabArgs::from_arg_matches(&matches).unwrap_or_else(|e| e.exit())
    }

    /// The shader source chosen by `--shaders` (built-in copies otherwise).
    pub fn shader_source(&self) -> Result<ShaderSource, Error> {
        match &self.shaders {
            Some(dir) => ShaderSource::dir(dir),
            None => Ok(ShaderSource::Embedded),
        }
    }

    /// Applies object, rotation, time and `--set` values to a lab.
    pub fn apply<E: Effect>(&self, lab: &mut Lab<E>) -> Result<(), Error> {
        lab.scene.object = self.object;
        lab.scene.angles = self.rotate;
        lab.scene.time = f64::from(self.time.unwrap_or(0.0));
        if let Some(shading) = self.shading {
            if !E::SHADING_MODELS && shading != Shading::Phong {
                return Err(Error::Param(format!(
                    "{} has no shading models; --shading applies to phong",
                    E::NAME
                )));
            }
            lab.options.shading = shading;
        }
        for (name, values) in &self.set {
            lab.set(name, values)?;
        }
        // GLUT's meshes by default, as the original; once a port-only mode is asked for (another
        // shading model, welded normals) faithfulness is not the point, and the default becomes
        // the smallest tessellation that keeps the silhouette within half a pixel.
        let faithful = lab.options.shading == Shading::Phong && !lab.options.smooth;
        lab.options.tess = match self.tess {
            Some(tess) => tess,
            None if faithful => Tess::Glut,
            None => Tess::Auto {
                budget_px: crate::tess::DEFAULT_BUDGET_PX,
            },
        };
        Ok(())
    }
}

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

/// Entry point of every lab example: parses arguments, then renders offscreen or opens a window.
pub fn main<E: Effect>() -> ExitCode {
    let args = LabArgs::parse_for::<E>();
    let result = if args.screenshot.is_some() || args.bench.is_some() {
        run_offscreen::<E>(&args)
    } else if !crate::app::has_display() {
        // No display: still do something useful.
        let path = PathBuf::from(format!("{}.png", E::NAME));
        eprintln!(
            "{}: no display found (DISPLAY/WAYLAND_DISPLAY unset); writing a screenshot to {} instead",
            E::NAME,
            path.display()
        );
        let args = LabArgs {
            screenshot: Some(path),
            ..args
        };
        run_offscreen::<E>(&args)
    } else {
        crate::app::run_window::<E>(&args).map_err(Failure::from)
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => {
            eprintln!("{}: error: {}", E::NAME, failure.error);
            ExitCode::from(failure.code)
        }
    }
}

/// `--screenshot` and `--bench`.
pub fn run_offscreen<E: Effect>(args: &LabArgs) -> Result<(), Failure> {
    let gpu = Gpu::headless()?;
    let mut lab = Lab::<E>::new(&gpu, args.shader_source()?, COLOR_FORMAT)?;
    args.apply(&mut lab)?;
    // Build the chosen shading model now, so that a broken shader file is reported before rendering.
    lab.set_shading(&gpu, lab.options.shading)?;
    let (width, height) = args.size;
    if let Some(frames) = args.bench {
        let result = bench(&gpu, &mut lab, frames, width, height)?;
        println!("{}", result.line::<E>(lab.scene.object, width, height, frames));
    }
    if let Some(path) = &args.screenshot {
        let image = lab.screenshot(&gpu, width, height)?;
        save_png(&image, path)?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// What `--bench` measured.
#[derive(Clone, Copy, Debug)]
pub struct BenchResult {
    /// Wall-clock milliseconds per frame (encode, submit, wait).
    pub ms_per_frame: f64,
    /// GPU milliseconds per frame from timestamp queries, where available.
    pub gpu_ms: Option<f64>,
}

impl BenchResult {
    /// The one line `--bench` prints.
    pub fn line<E: Effect>(&self, object: Object, width: u32, height: u32, frames: u32) -> String {
        let gpu = self.gpu_ms.map(|g| format!(" gpu_ms={g:.3}")).unwrap_or_default();
        format!(
            "effect={} object={} size={width}x{height} frames={frames} ms_per_frame={:.3}{gpu}",
            E::NAME,
            object.name(),
            self.ms_per_frame
        )
    }
}

/// Renders `frames` frames offscreen, waiting for each, like the original's swap + glFinish.
pub fn bench<E: Effect>(
    gpu: &Gpu,
    lab: &mut Lab<E>,
    frames: u32,
    width: u32,
    height: u32,
) -> Result<BenchResult, Error> {
    let target = Offscreen::new(gpu, width, height);
    // Warm up: the first frames compile shaders in the driver.
    for _ in 0..3 {
        lab.render(gpu, &target.color, &target.depth, width, height);
        gpu.wait()?;
    }
    let queries = gpu.timestamps.then(|| {
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
    let start = Instant::now();
    for frame in 0..frames {
        let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("bench.encoder"),
        });
        let writes = queries.as_ref().map(|(set, _, _)| wgpu::RenderPassTimestampWrites {
            query_set: set,
            beginning_of_pass_write_index: Some(0),
            end_of_pass_write_index: Some(1),
        });
        let view = crate::effect::FrameTarget {
            color: &target.color,
            depth: &target.depth,
            width,
            height,
        };
        lab.encode(gpu, &mut encoder, view, writes);
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
                let view = slice.get_mapped_range().map_err(|e| Error::Wgpu {
                    context: "reading timestamps".into(),
                    message: e.to_string(),
                })?;
                bytemuck::cast_slice(&view).to_vec()
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
