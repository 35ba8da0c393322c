//! Seed 001: per-vertex against per-fragment lighting (`phong_vertex`, `phong_fragment`,
//! `toon`) on GLUT's sphere and torus at increasing tessellation (the port's `tess`), each
//! against a converged reference of its own formula: the per-fragment program (`toon`: itself)
//! on a 256-level mesh, sampled at the same pixel centres (a supersampled reference would
//! charge every level the same silhouette aliasing and hide the lighting's own error).

use std::fmt::Write as _;

use plotters::prelude::*;
use shaderlab::lab::LabEntry;
use shaderlab::metrics::rmse;
use shaderlab::offscreen::to_rgb;
use shaderlab::shell::{bench, screenshot};
use shaderlab::{course, Gpu};

use super::chart::{axes, legend, MS_AXIS};
use super::Summary;

const W: u32 = 512;
const H: u32 = 512;
const REFERENCE_LEVEL: &str = "256";

#[derive(Clone, Debug)]
struct Row {
    object: &'static str,
    lab: &'static str,
    level: u32,
    ms: f64,
    rmse: f64,
    pareto: bool,
}

/// (lab, the lab whose formula per fragment is its reference).
fn labs_compared() -> [(&'static LabEntry, &'static LabEntry); 3] {
    [
        (course::PHONG_VERTEX, course::PHONG_FRAGMENT),
        (course::PHONG_FRAGMENT, course::PHONG_FRAGMENT),
        (course::TOON, course::TOON),
    ]
}

pub fn study(out: &mut super::chart::Outputs, frames: u32, quick: bool, gpu: &Gpu) -> anyhow::Result<Summary> {
    let levels: &[u32] = if quick {
        &[8, 24, 64]
    } else {
        &[6, 8, 12, 16, 24, 32, 48, 64, 96, 128]
    };
    let cx = super::chart::context(gpu);
    let mut rows = Vec::new();
    let bar = shaderlab::shell::progress_bar((2 * 3 * levels.len()) as u64, "configurations");
    for object in ["sphere", "torus"] {
        for (entry, reference_entry) in labs_compared() {
            let mut reference_lab = (reference_entry.new)(&cx)?;
            reference_lab.params_mut().set_str("object", object)?;
            reference_lab.params_mut().set_str("tess", REFERENCE_LEVEL)?;
            let reference = to_rgb(&screenshot(gpu, reference_lab.as_mut(), W, H)?);
            let mut lab = (entry.new)(&cx)?;
            lab.params_mut().set_str("object", object)?;
            for &level in levels {
                lab.params_mut().set("tess", &[f64::from(level)])?;
                let image = to_rgb(&screenshot(gpu, lab.as_mut(), W, H)?);
                let timing = bench(gpu, lab.as_mut(), frames, W, H, true)?;
                let row = Row {
                    object,
                    lab: entry.info.name,
                    level,
                    ms: timing.gpu_ms.unwrap_or(timing.ms_per_frame),
                    rmse: rmse(&image, &reference).unwrap_or(f64::INFINITY),
                    pareto: false,
                };
                bar.inc(1);
                let line = format!(
                    "{object} {} level {level}: {:.3} ms, RMSE {:.2}",
                    row.lab, row.ms, row.rmse
                );
                super::chart::say(&bar, line);
                rows.push(row);
            }
        }
    }
    bar.finish_and_clear();
    // The front among the two Phong programs (same formula, same reference); toon is its own.
    let family = |lab: &str| if lab == "toon" { "toon" } else { "phong" };
    let front = super::chart::pareto(
        &rows,
        |a, b| a.object == b.object && family(a.lab) == family(b.lab),
        |r| r.ms,
        |r| r.rmse,
    );
    for (r, on) in rows.iter_mut().zip(front) {
        r.pareto = on;
    }
    let mut text = String::from("object,lab,level,ms_per_frame,rmse,pareto\n");
    for r in &rows {
        writeln!(
            text,
            "{},{},{},{:.4},{:.3},{}",
            r.object, r.lab, r.level, r.ms, r.rmse, r.pareto
        )?;
    }
    let mut chart = String::new();
    draw(&rows, &mut chart)?;
    super::chart::write(out, "lighting", &text, &chart)?;
    let find = |lab: &str, level: u32| {
        rows.iter()
            .find(|r| r.object == "sphere" && r.lab == lab && r.level == level)
            .cloned()
    };
    // The coarsest per-fragment level at least as accurate as per-vertex at the finest level.
    let finest = levels.last().copied().unwrap_or(24);
    let lesson = match (
        find("phong_vertex", 24),
        find("phong_fragment", 24),
        find("phong_vertex", finest),
        find("phong_fragment", finest),
    ) {
        (Some(v), Some(f), Some(vf), Some(ff)) => {
            let why = if v.rmse < 1.25 * f.rmse {
                "at the course's light and shininess the mesh (its silhouette and facet normals), not where the lighting is \
                 evaluated, sets the error, and per-fragment lighting buys little at any level"
            } else {
                "per-vertex lighting loses the highlight between vertices, which per-fragment lighting keeps on the same mesh"
            };
            format!(
                "On the sphere at GLUT's level 24 per-vertex lighting is off by RMSE {:.2} ({:.3} ms) and per-fragment by {:.2} \
                 ({:.3} ms); at level {finest} by {:.2} ({:.3} ms) and {:.2} ({:.3} ms): {why}.",
                v.rmse, v.ms, f.rmse, f.ms, vf.rmse, vf.ms, ff.rmse, ff.ms
            )
        }
        _ => "(a quick run)".into(),
    };
    Ok(Summary {
        name: "lighting",
        title: "Seed 001: per-vertex against per-fragment lighting at increasing tessellation",
        lesson,
    })
}

fn draw(rows: &[Row], svg: &mut String) -> anyhow::Result<()> {
    let root = SVGBackend::with_string(svg, (1200, 500)).into_drawing_area();
    root.fill(&WHITE)?;
    let panels = root.split_evenly((1, 2));
    for (panel, object) in panels.iter().zip(["sphere", "torus"]) {
        let mine: Vec<&Row> = rows.iter().filter(|r| r.object == object).collect();
        let max_ms = mine.iter().map(|r| r.ms).fold(0.0, f64::max) * 1.2;
        let min_ms = mine.iter().map(|r| r.ms).fold(f64::INFINITY, f64::min) * 0.8;
        let max_y = mine.iter().map(|r| r.rmse).fold(0.0, f64::max) * 1.5;
        let min_y = mine.iter().map(|r| r.rmse).fold(f64::INFINITY, f64::min).max(0.05) * 0.7;
        let mut c = axes(
            panel,
            &format!("seed 001 lighting, {object}"),
            ((min_ms..max_ms).log_scale(), MS_AXIS),
            ((min_y..max_y).log_scale(), "RMSE vs converged per-fragment reference"),
        )?;
        let colours = [
            ("phong_vertex", RGBColor(214, 39, 40)),
            ("phong_fragment", RGBColor(31, 119, 180)),
            ("toon", RGBColor(44, 160, 44)),
        ];
        for (lab, col) in colours {
            let pts: Vec<(f64, f64)> = mine
                .iter()
                .filter(|r| r.lab == lab)
                .map(|r| (r.ms, r.rmse.max(min_y)))
                .collect();
            c.draw_series(LineSeries::new(pts.clone(), col.stroke_width(1)))?;
            c.draw_series(pts.iter().map(|&p| Circle::new(p, 4, col.filled())))?
                .label(lab)
                .legend(move |(x, y)| Circle::new((x + 10, y), 4, col.filled()));
        }
        let mut front: Vec<(f64, f64)> = mine
            .iter()
            .filter(|r| r.pareto && r.lab != "toon")
            .map(|r| (r.ms, r.rmse.max(min_y)))
            .collect();
        front.sort_by(|a, b| a.0.total_cmp(&b.0));
        c.draw_series(front.iter().map(|&p| Circle::new(p, 7, BLACK.stroke_width(1))))?
            .label("Pareto front (Phong)")
            .legend(|(x, y)| Circle::new((x + 10, y), 6, BLACK.stroke_width(1)));
        legend(&mut c, SeriesLabelPosition::UpperRight)?;
    }
    root.present()?;
    Ok(())
}
