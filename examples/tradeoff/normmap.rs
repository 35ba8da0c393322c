//! Seed 001 `bump` against `normmap`: the lecture claims a normalization cube-map lookup beats
//! `normalize`. Both labs draw the same bump-mapped quad; `bump`'s `normalize(L)` is the exact
//! formula, so `normmap`'s error is its picture against `bump`'s, and the time is each lab's
//! frame time, alternated in one run, at three light positions and for cube maps of 4 to 128
//! texels per side (the course's: 32).

use std::fmt::Write as _;

use plotters::prelude::*;
use shaderlab::course::seed001::normmap::{with_cube, CUBE_SIZES};
use shaderlab::metrics::psnr;
use shaderlab::offscreen::to_rgb;
use shaderlab::shell::{bench, screenshot};
use shaderlab::{course, Gpu};

use super::chart::{axes, legend};
use super::Summary;

const W: u32 = 512;
const H: u32 = 512;

/// Light positions (eye space): the course's, one low and grazing, one close.
const LIGHTS: [[&str; 3]; 3] = [["1.5", "1.5", "-2"], ["3", "0", "-0.5"], ["0", "0", "-1"]];

/// Alternations of the timing (bump, normmap, bump, …).
const ROUNDS: usize = 5;

#[derive(Clone, Debug)]
struct Row {
    light: usize,
    /// Texels per side of the cube map; 0 for `bump` (normalize).
    cube: u32,
    ms: f64,
    psnr: f64,
}

pub fn study(out: &mut super::chart::Outputs, frames: u32, gpu: &Gpu) -> anyhow::Result<Summary> {
    let cx = super::chart::context(gpu);
    let mut bump = (course::BUMP.new)(&cx)?;
    let mut cubes = Vec::new();
    for size in CUBE_SIZES {
        let lab = with_cube(&cx, size).ok_or_else(|| anyhow::anyhow!("no cube of {size}"))??;
        cubes.push((size, lab));
    }
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let mut rows = Vec::new();
    for (l, light) in LIGHTS.iter().enumerate() {
        for lab in std::iter::once(&mut bump).chain(cubes.iter_mut().map(|(_, lab)| lab)) {
            for (name, value) in ["blx", "bly", "blz"].iter().zip(light) {
                lab.params_mut().set_str(name, value)?;
            }
        }
        let exact = to_rgb(&screenshot(gpu, bump.as_mut(), W, H)?);
        let mut t_bump = Vec::new();
        let mut t_cube: Vec<Vec<f64>> = vec![Vec::new(); cubes.len()];
        for _ in 0..ROUNDS {
            let b = bench(gpu, bump.as_mut(), frames, W, H, true)?;
            t_bump.push(b.gpu_ms.unwrap_or(b.ms_per_frame));
            for (i, (_, lab)) in cubes.iter_mut().enumerate() {
                let c = bench(gpu, lab.as_mut(), frames, W, H, true)?;
                t_cube[i].push(c.gpu_ms.unwrap_or(c.ms_per_frame));
            }
        }
        let ms = median(t_bump);
        eprintln!("light {light:?}: bump (normalize): {ms:.3} ms");
        rows.push(Row {
            light: l,
            cube: 0,
            ms,
            psnr: f64::INFINITY,
        });
        for (i, (size, lab)) in cubes.iter_mut().enumerate() {
            let image = to_rgb(&screenshot(gpu, lab.as_mut(), W, H)?);
            let db = psnr(&image, &exact).unwrap_or(0.0);
            let ms = median(std::mem::take(&mut t_cube[i]));
            eprintln!("light {light:?}: normmap cube {size}: {ms:.3} ms, {db:.1} dB against bump");
            rows.push(Row {
                light: l,
                cube: *size,
                ms,
                psnr: db,
            });
        }
    }
    let mut text = String::from("light,method,cube_size,ms_per_frame,psnr_vs_normalize_db,pareto\n");
    for r in &rows {
        let pareto = !rows
            .iter()
            .any(|o| o.light == r.light && o.ms <= r.ms && o.psnr >= r.psnr && (o.ms < r.ms || o.psnr > r.psnr));
        writeln!(
            text,
            "\"{}\",{},{},{:.4},{},{}",
            LIGHTS[r.light].join(","),
            if r.cube == 0 { "normalize" } else { "cube map" },
            r.cube,
            r.ms,
            if r.psnr.is_infinite() {
                "inf".to_owned()
            } else {
                format!("{:.2}", r.psnr)
            },
            pareto
        )?;
    }
    let mut chart = String::new();
    draw(&rows, &mut chart)?;
    super::chart::write(out, "normmap", &text, &chart)?;
    let pairs: Vec<(f64, f64)> = (0..LIGHTS.len())
        .filter_map(|l| {
            let b = rows.iter().find(|r| r.light == l && r.cube == 0)?;
            let c = rows.iter().find(|r| r.light == l && r.cube == 32)?;
            Some((c.ms / b.ms, c.psnr))
        })
        .collect();
    let ratio: Vec<String> = pairs.iter().map(|(r, db)| format!("{r:.2}× at {db:.1} dB")).collect();
    let verdict = if pairs.iter().all(|(r, _)| *r > 1.0) {
        "The lecture's claim does not carry to this rasterizer"
    } else if pairs.iter().all(|(r, _)| *r < 1.0) {
        "The lecture's claim holds on this rasterizer"
    } else {
        "The lecture's claim is a wash on this rasterizer"
    };
    let sizes: Vec<String> = rows
        .iter()
        .filter(|r| r.light == 0 && r.cube > 0)
        .map(|r| format!("{} texels {:.1} dB", r.cube, r.psnr))
        .collect();
    let lesson = format!(
        "{verdict}: the course's 32-texel cube map takes {} the frame time of `normalize` (normmap/bump at each light \
         position, median of {ROUNDS} alternations), for a picture that only approximates it; at the course's light \
         the table's size buys accuracy ({}).",
        ratio.join(", "),
        sizes.join(", ")
    );
    Ok(Summary {
        name: "normmap",
        title: "Seed 001: a normalization cube map against normalize",
        lesson,
    })
}

fn draw(rows: &[Row], svg: &mut String) -> anyhow::Result<()> {
    let root = SVGBackend::with_string(svg, (760, 440)).into_drawing_area();
    root.fill(&WHITE)?;
    let max_ms = rows.iter().map(|r| r.ms).fold(0.0, f64::max) * 1.2;
    let min_db = rows.iter().map(|r| r.psnr).fold(f64::INFINITY, f64::min).min(60.0) - 5.0;
    let mut c = axes(
        &root,
        "bump (normalize) against normmap (cube maps of 4 to 128 texels)",
        (
            0.0..max_ms,
            "ms per frame (GPU timestamps, lavapipe; median of 5 alternations)",
        ),
        (min_db..100.0, "PSNR vs normalize, dB (normalize itself drawn at 100)"),
    )?;
    let (blue, red) = (RGBColor(31, 119, 180), RGBColor(214, 39, 40));
    c.draw_series(
        rows.iter()
            .filter(|r| r.cube == 0)
            .map(|r| Circle::new((r.ms, 100.0), 6, blue.filled())),
    )?
    .label("bump: normalize")
    .legend(move |(x, y)| Circle::new((x + 10, y), 5, blue.filled()));
    c.draw_series(
        rows.iter()
            .filter(|r| r.cube > 0)
            .map(|r| TriangleMarker::new((r.ms, r.psnr.min(100.0)), 7, red.filled())),
    )?
    .label("normmap: cube map (texels per side)")
    .legend(move |(x, y)| TriangleMarker::new((x + 10, y), 7, red.filled()));
    c.draw_series(rows.iter().filter(|r| r.cube > 0 && r.light == 0).map(|r| {
        Text::new(
            format!("{}", r.cube),
            (r.ms, r.psnr.min(100.0)),
            ("sans-serif", 11).into_font().color(&RGBColor(90, 90, 90)),
        )
    }))?;
    legend(&mut c, SeriesLabelPosition::LowerRight)?;
    root.present()?;
    Ok(())
}
