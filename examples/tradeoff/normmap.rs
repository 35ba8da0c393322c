//! Seed 001 `bump` against `normmap`: the lecture claims a normalization cube-map lookup beats
//! `normalize`. Both labs draw the same bump-mapped quad; `bump`'s `normalize(L)` is the exact
//! formula, so `normmap`'s error is its picture against `bump`'s, and the time is each lab's
//! frame time, alternated in one run, at three light positions.

use std::fmt::Write as _;
use std::path::Path;

use plotters::prelude::*;
use shaderlab::fsutil::write_atomic;
use shaderlab::lab::{LabContext, NO_FILES};
use shaderlab::metrics::psnr;
use shaderlab::offscreen::{to_rgb, COLOR_FORMAT};
use shaderlab::shader::ShaderSource;
use shaderlab::shell::{bench, screenshot};
use shaderlab::{labs, Gpu};

use super::Summary;

const W: u32 = 512;
const H: u32 = 512;

/// Light positions (eye space): the course's, one low and grazing, one close.
const LIGHTS: [[&str; 3]; 3] = [["1.5", "1.5", "-2"], ["3", "0", "-0.5"], ["0", "0", "-1"]];

/// Alternations of the timing (bump, normmap, bump, …).
const ROUNDS: usize = 3;

#[derive(Clone, Debug)]
struct Row {
    light: usize,
    lab: &'static str,
    ms: f64,
    psnr: f64,
}

pub fn study(out: &Path, frames: u32, gpu: &Gpu) -> anyhow::Result<Summary> {
    let source = ShaderSource::Embedded;
    let cx = LabContext {
        gpu,
        source: &source,
        format: COLOR_FORMAT,
        files: &NO_FILES,
    };
    let mut bump = (labs::BUMP.new)(&cx)?;
    let mut normmap = (labs::NORMMAP.new)(&cx)?;
    let mut rows = Vec::new();
    for (l, light) in LIGHTS.iter().enumerate() {
        for lab in [&mut bump, &mut normmap] {
            for (name, value) in ["blx", "bly", "blz"].iter().zip(light) {
                lab.params_mut().set_str(name, value)?;
            }
        }
        let exact = to_rgb(&screenshot(gpu, bump.as_mut(), W, H)?);
        let cube = to_rgb(&screenshot(gpu, normmap.as_mut(), W, H)?);
        let (mut t_bump, mut t_cube) = (Vec::new(), Vec::new());
        for _ in 0..ROUNDS {
            let b = bench(gpu, bump.as_mut(), frames, W, H, true)?;
            t_bump.push(b.gpu_ms.unwrap_or(b.ms_per_frame));
            let c = bench(gpu, normmap.as_mut(), frames, W, H, true)?;
            t_cube.push(c.gpu_ms.unwrap_or(c.ms_per_frame));
        }
        let median = |mut v: Vec<f64>| {
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        };
        let db = psnr(&cube, &exact).unwrap_or(0.0);
        for (lab, ms, db) in [
            ("bump (normalize)", median(t_bump), f64::INFINITY),
            ("normmap (cube 32)", median(t_cube), db),
        ] {
            eprintln!("light {:?}: {lab}: {ms:.3} ms, {db:.1} dB against bump", light);
            rows.push(Row {
                light: l,
                lab,
                ms,
                psnr: db,
            });
        }
    }
    let csv = out.join("normmap.csv");
    let mut text = String::from("light,lab,ms_per_frame,psnr_vs_normalize_db,pareto\n");
    for r in &rows {
        // Two configurations per light: the faster is on the front, and the exact one is.
        let other = rows.iter().find(|o| o.light == r.light && o.lab != r.lab);
        let pareto = r.psnr.is_infinite() || other.is_none_or(|o| r.ms < o.ms);
        writeln!(
            text,
            "\"{}\",{},{:.4},{},{}",
            LIGHTS[r.light].join(","),
            r.lab,
            r.ms,
            if r.psnr.is_infinite() {
                "inf".to_owned()
            } else {
                format!("{:.2}", r.psnr)
            },
            pareto
        )?;
    }
    write_atomic(&csv, |w| w.write_all(text.as_bytes()))?;
    let svg = out.join("normmap.svg");
    let mut chart = String::new();
    draw(&rows, &mut chart)?;
    write_atomic(&svg, |w| w.write_all(chart.as_bytes()))?;
    println!("wrote {} and {}", csv.display(), svg.display());
    let pairs: Vec<(f64, f64)> = (0..LIGHTS.len())
        .filter_map(|l| {
            let b = rows.iter().find(|r| r.light == l && r.psnr.is_infinite())?;
            let c = rows.iter().find(|r| r.light == l && r.psnr.is_finite())?;
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
    Ok(Summary {
        name: "normmap",
        title: "Seed 001: a normalization cube map against normalize",
        lesson: format!(
            "{verdict}: the cube-map lookup's frame time is {} that of `normalize` (normmap/bump at each light \
             position, median of {ROUNDS} alternations), for a picture that only approximates it.",
            ratio.join(", ")
        ),
    })
}

fn draw(rows: &[Row], svg: &mut String) -> anyhow::Result<()> {
    let root = SVGBackend::with_string(svg, (700, 420)).into_drawing_area();
    root.fill(&WHITE)?;
    let max_ms = rows.iter().map(|r| r.ms).fold(0.0, f64::max) * 1.2;
    let mut c = ChartBuilder::on(&root)
        .caption("bump (normalize) against normmap (cube map)", ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(55)
        .build_cartesian_2d(0.0..max_ms, 20.0..70.0)?;
    c.configure_mesh()
        .light_line_style(TRANSPARENT)
        .bold_line_style(RGBColor(225, 225, 225))
        .x_desc("ms per frame (GPU timestamps, lavapipe; median of 3 alternations)")
        .y_desc("PSNR vs normalize, dB (normalize itself drawn at 70)")
        .draw()?;
    let (blue, red) = (RGBColor(31, 119, 180), RGBColor(214, 39, 40));
    c.draw_series(
        rows.iter()
            .filter(|r| r.psnr.is_infinite())
            .map(|r| Circle::new((r.ms, 70.0), 6, blue.filled())),
    )?
    .label("bump: normalize")
    .legend(move |(x, y)| Circle::new((x + 10, y), 5, blue.filled()));
    c.draw_series(
        rows.iter()
            .filter(|r| r.psnr.is_finite())
            .map(|r| TriangleMarker::new((r.ms, r.psnr.min(70.0)), 8, red.filled())),
    )?
    .label("normmap: 32x32 cube")
    .legend(move |(x, y)| TriangleMarker::new((x + 10, y), 8, red.filled()));
    c.configure_series_labels()
        .position(SeriesLabelPosition::LowerRight)
        .border_style(BLACK)
        .background_style(WHITE.mix(0.9))
        .draw()?;
    root.present()?;
    Ok(())
}
