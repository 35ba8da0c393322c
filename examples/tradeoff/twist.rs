//! Seed 002 `twist`: the course draws a 100 × 100 grid (60,000 vertices; the lab shades its
//! 26,244 distinct corners) and turns each vertex;
//! the exact picture is known per pixel (`shaderlab::study::twist`). Grid resolution against
//! pixels wrong and frame time, at the course's `twisting` and two stronger ones, and where
//! `grid=auto` lands.

use std::fmt::Write as _;

use shaderlab::mesh::shapes::{indexed_quads, twist_grid_n};
use shaderlab::offscreen::to_rgb;
use shaderlab::shell::{bench, screenshot};
use shaderlab::study::twist::{auto_grid, exact_mask, grid_error_px, COURSE_GRID, DEFAULT_BUDGET_PX};
use shaderlab::{course, Gpu};

use super::chart::{sweep_chart, Point};
use super::Summary;

/// The lab's picture size.
const W: u32 = 512;
const H: u32 = 512;

/// The course's twisting, a strong one and one no grid here follows.
const TWISTINGS: [f64; 3] = [4.25, 20.0, 100.0];

#[derive(Clone, Debug)]
struct Row {
    twisting: f64,
    grid: u32,
    /// Distinct corners the lab shades: the course's 6·N² `glVertex` calls welded where their
    /// bits agree (`shapes::indexed_quads`).
    corners: usize,
    ms: f64,
    wrong_px: usize,
    grid_px: f64,
    auto: bool,
    pareto: bool,
}

pub fn study(out: &mut super::chart::Outputs, frames: u32, quick: bool, gpu: &Gpu) -> anyhow::Result<Summary> {
    let grids: &[u32] = if quick {
        &[4, 16, 64, 100, 400]
    } else {
        &[2, 4, 6, 8, 12, 16, 24, 32, 48, 64, 100, 150, 200, 300, 400]
    };
    let cx = super::chart::context(gpu);
    let mut lab = (course::TWIST.new)(&cx)?;
    let mut rows = Vec::new();
    let total = TWISTINGS.len() * (grids.len() + 1);
    let bar = shaderlab::shell::progress_bar(total as u64, "configurations");
    for twisting in TWISTINGS {
        lab.params_mut().set("twisting", &[twisting])?;
        let exact = exact_mask(twisting, W, H);
        let auto = auto_grid(twisting, W, H, DEFAULT_BUDGET_PX);
        let mut sizes: Vec<(u32, bool)> = grids.iter().map(|&g| (g, false)).collect();
        sizes.push((auto, true));
        for (grid, is_auto) in sizes {
            // auto is measured through the lab's own `grid=auto`, the rest by number.
            lab.params_mut()
                .set("grid", &[if is_auto { 0.0 } else { f64::from(grid) }])?;
            let timing = bench(gpu, lab.as_mut(), frames, W, H, true)?;
            let image = to_rgb(&screenshot(gpu, lab.as_mut(), W, H)?);
            // The shape is (128, 255, 128) on black.
            let wrong_px = image
                .pixels()
                .zip(&exact)
                .filter(|(p, &inside)| (p.0[1] > 127) != inside)
                .count();
            let row = Row {
                twisting,
                grid,
                corners: indexed_quads(&twist_grid_n(grid)).0.len(),
                ms: timing.gpu_ms.unwrap_or(timing.ms_per_frame),
                wrong_px,
                grid_px: grid_error_px(grid, twisting, W, H),
                auto: is_auto,
                pareto: false,
            };
            bar.inc(1);
            let line = format!(
                "twist twisting {twisting:>6} grid {grid:>3}{}: {:.3} ms, {wrong_px} px wrong, edges within {:.2} px",
                if is_auto { " (auto)" } else { "" },
                row.ms,
                row.grid_px
            );
            super::chart::say(&bar, line);
            rows.push(row);
        }
    }
    bar.finish_and_clear();
    let front = super::chart::pareto(&rows, |a, b| a.twisting == b.twisting, |r| r.ms, |r| r.wrong_px as f64);
    for (r, on) in rows.iter_mut().zip(front) {
        r.pareto = on;
    }
    let mut text =
        String::from("twisting,grid,vertices,corners,ms_per_frame,wrong_px,wrong_pct,grid_error_px,auto,pareto\n");
    for r in &rows {
        writeln!(
            text,
            "{},{},{},{},{:.4},{},{:.4},{:.4},{},{}",
            r.twisting,
            r.grid,
            6 * r.grid * r.grid,
            r.corners,
            r.ms,
            r.wrong_px,
            100.0 * r.wrong_px as f64 / f64::from(W * H),
            r.grid_px,
            r.auto,
            r.pareto
        )?;
    }
    let mut chart_text = String::new();
    draw(&rows, &mut chart_text)?;
    super::chart::write(out, "twist", &text, &chart_text)?;
    Ok(Summary {
        name: "twist",
        title: "Seed 002: twist grid resolution against the exact spiral",
        lesson: lesson(&rows),
    })
}

/// The sentence the index prints, from the rows.
fn lesson(rows: &[Row]) -> String {
    let find = |t: f64, pick: &dyn Fn(&Row) -> bool| rows.iter().find(|r| r.twisting == t && pick(r)).cloned();
    let course = find(TWISTINGS[0], &|r| r.grid == COURSE_GRID && !r.auto);
    let auto = find(TWISTINGS[0], &|r| r.auto);
    let finest_strong = rows
        .iter()
        .filter(|r| r.twisting == TWISTINGS[2])
        .max_by_key(|r| r.grid)
        .cloned();
    match (course, auto, finest_strong) {
        (Some(c), Some(a), Some(f)) => format!(
            "At the course's twisting {} the course's {}×{} grid ({} vertices, drawn as {} distinct corners) leaves {} px wrong in {:.3} ms; \
             `grid=auto` picks {}×{} ({} vertices, {} corners, every edge within {} px of its arc) and leaves {} px wrong in {:.3} ms ({:.1}× faster). \
             Per-vertex twisting fails when the turn between neighbouring vertices grows: at twisting {} even the \
             {}×{} grid leaves {} px wrong (edges off their arcs by up to {:.1} px), because straight edges between vertices cut the spiral.",
            c.twisting,
            c.grid,
            c.grid,
            6 * c.grid * c.grid,
            c.corners,
            c.wrong_px,
            c.ms,
            a.grid,
            a.grid,
            6 * a.grid * a.grid,
            a.corners,
            DEFAULT_BUDGET_PX,
            a.wrong_px,
            a.ms,
            c.ms / a.ms.max(1e-9),
            f.twisting,
            f.grid,
            f.grid,
            f.wrong_px,
            f.grid_px
        ),
        _ => "(a quick run: the course's grid was not measured)".into(),
    }
}

fn draw(rows: &[Row], svg: &mut String) -> anyhow::Result<()> {
    let panels = TWISTINGS
        .iter()
        .map(|&twisting| {
            let points = rows
                .iter()
                .filter(|r| r.twisting == twisting)
                .map(|r| Point {
                    ms: r.ms,
                    error: r.wrong_px as f64,
                    label: r.grid.to_string(),
                    auto: r.auto,
                    pareto: r.pareto,
                })
                .collect();
            (format!("twist, twisting = {twisting}"), points)
        })
        .collect();
    sweep_chart(
        svg,
        (1500, 500),
        panels,
        "pixels wrong vs exact (512x512; 0 drawn at 0.5)",
        "grid N×N",
        "grid=auto",
    )
}
