//! `cargo run --release --example bench`: every exercise on every object, offscreen at 640x360,
//! rotated 30/45 degrees as the original's timing runs were, N frames each (submit + wait per
//! frame, like the original's swap + glFinish). Prints ms per frame, GPU ms from timestamp
//! queries, and the ratio to the original C/GLUT program on the same machine (lower is faster).

use clap::Parser;
use glam::Vec3;
use shaderlab::cli::bench;
use shaderlab::effects::*;
use shaderlab::offscreen::COLOR_FORMAT;
use shaderlab::shader::ShaderSource;
use shaderlab::{Effect, Gpu, Lab, Object};

/// The original's milliseconds per frame (shared/reference/README.md), cube, sphere, torus, teapot.
const ORIGINAL: [[f64; 4]; 5] = [
    [0.91, 1.39, 2.48, 2.77],
    [1.01, 1.89, 2.31, 2.10],
    [0.96, 2.28, 2.99, 2.69],
    [1.43, 2.29, 5.12, 4.29],
    [1.13, 2.58, 3.42, 4.04],
];

#[derive(Parser)]
#[command(about = "Benchmark every lab exercise and object against the original's figures")]
struct Args {
    /// Frames per case.
    #[arg(long, default_value_t = 300, value_parser = clap::value_parser!(u32).range(1..=100_000))]
    frames: u32,
}

fn run<E: Effect>(gpu: &Gpu, exercise: usize, frames: u32, ratios: &mut Vec<f64>) -> anyhow::Result<()> {
    let mut lab = Lab::<E>::new(gpu, ShaderSource::Embedded, COLOR_FORMAT)?;
    lab.scene.angles = Vec3::new(30.0, 45.0, 0.0);
    for (i, object) in Object::ALL.into_iter().enumerate() {
        lab.scene.object = object;
        let r = bench(gpu, &mut lab, frames, 640, 360)?;
        let original = ORIGINAL[exercise - 1][i];
        let ratio = r.ms_per_frame / original;
        ratios.push(ratio);
        println!(
            "| {exercise} {:<13} | {:<6} | {:>8.3} | {:>8} | {:>8.2} | {:>5.2} |",
            E::NAME,
            object.name(),
            r.ms_per_frame,
            r.gpu_ms.map(|g| format!("{g:.3}")).unwrap_or_else(|| "-".into()),
            original,
            ratio
        );
    }
    Ok(())
}

fn main() -> anyhow::Result<()> {
    let args = Args::parse();
    let gpu = Gpu::headless()?;
    println!(
        "adapter: {}; {} frames per case at 640x360, rotated 30,45,0",
        gpu.describe(),
        args.frames
    );
    println!("| exercise        | object | ms/frame |   gpu ms | original | ratio |");
    println!("|---|---|---|---|---|---|");
    let mut ratios = Vec::new();
    run::<PositionRgb>(&gpu, 1, args.frames, &mut ratios)?;
    run::<NormalRgb>(&gpu, 2, args.frames, &mut ratios)?;
    run::<Phong>(&gpu, 3, args.frames, &mut ratios)?;
    run::<Noise>(&gpu, 4, args.frames, &mut ratios)?;
    run::<Displacement>(&gpu, 5, args.frames, &mut ratios)?;
    let geo = (ratios.iter().map(|r| r.ln()).sum::<f64>() / ratios.len() as f64).exp();
    let worst = ratios.iter().cloned().fold(0.0, f64::max);
    println!("geometric mean ratio (port / original): {geo:.2}; worst case: {worst:.2}");
    Ok(())
}
