//! Seed 001 `wave`: the course lifts a 40 × 40 checker grid by two sines in the vertex shader;
//! its flat triangles stand for a curved surface. Each cell split k × k (`subdiv`) against a
//! converged grid (k = 32, 9.8 million vertices): pixels off, RMSE and frame time, at the
//! course's state and a stronger wave, and where `subdiv=auto` lands.

use std::fmt::Write as _;

use shaderlab::metrics::{pixels_off, psnr};
use shaderlab::offscreen::to_rgb;
use shaderlab::shell::screenshot;
use shaderlab::{course, Gpu};

use super::chart::{measure_settings, sweep_chart, Point};
use super::Summary;

const W: u32 = 512;
const H: u32 = 512;

/// The converged reference.
const REFERENCE: u32 = 32;

/// (name, assignments): the course's wave at t = 0.7, and a taller, faster one.
const STATES: [(&str, &[(&str, &str)]); 2] = [
    ("course (h 0.1, xs 3, zs 2)", &[("time", "0.7")]),
    (
        "strong (h 0.3, xs 10, zs 8)",
        &[("time", "0.7"), ("h", "0.3"), ("xs", "10"), ("zs", "8")],
    ),
];

#[derive(Clone, Debug)]
struct Row {
    state: usize,
    subdiv: u32,
    auto: bool,
    ms: f64,
    off_px: usize,
    psnr: f64,
    pareto: bool,
}

pub fn study(out: &mut super::chart::Outputs, frames: u32, quick: bool, gpu: &Gpu) -> anyhow::Result<Summary> {
    let subdivs: &[u32] = if quick { &[1, 2, 4] } else { &[1, 2, 3, 4, 6, 8, 12, 16] };
    let cx = super::chart::context(gpu);
    let mut rows = Vec::new();
    let bar = shaderlab::shell::progress_bar((STATES.len() * (subdivs.len() + 1)) as u64, "configurations");
    for (s, (name, state)) in STATES.iter().enumerate() {
        let mut lab = (course::WAVE.new)(&cx)?;
        for (k, v) in *state {
            lab.params_mut().set_str(k, v)?;
        }
        lab.params_mut().set("subdiv", &[f64::from(REFERENCE)])?;
        let reference = to_rgb(&screenshot(gpu, lab.as_mut(), W, H)?);
        // bench moves an animated lab's clock: the state's time goes back after it.
        let measured = measure_settings(
            gpu,
            lab.as_mut(),
            "subdiv",
            subdivs,
            "subdiv auto: ",
            frames,
            (W, H),
            &|lab| Ok(lab.params_mut().set_str("time", "0.7")?),
        )?;
        for m in measured {
            let row = Row {
                state: s,
                subdiv: m.setting,
                auto: m.auto,
                ms: m.ms,
                off_px: pixels_off(&m.image, &reference, 25).unwrap_or(usize::MAX),
                psnr: psnr(&m.image, &reference).unwrap_or(0.0),
                pareto: false,
            };
            bar.inc(1);
            let line = format!(
                "wave {name} subdiv {:>2}{}: {:.3} ms, {} px off, {:.1} dB",
                row.subdiv,
                if row.auto { " (auto)" } else { "" },
                row.ms,
                row.off_px,
                row.psnr
            );
            super::chart::say(&bar, line);
            rows.push(row);
        }
    }
    bar.finish_and_clear();
    let front = super::chart::pareto(&rows, |a, b| a.state == b.state, |r| r.ms, |r| r.off_px as f64);
    for (r, on) in rows.iter_mut().zip(front) {
        r.pareto = on;
    }
    let mut text = String::from("state,subdiv,vertices,ms_per_frame,off_px,psnr_db,auto,pareto\n");
    for r in &rows {
        writeln!(
            text,
            "{},{},{},{:.4},{},{:.2},{},{}",
            STATES[r.state].0,
            r.subdiv,
            9600 * r.subdiv * r.subdiv,
            r.ms,
            r.off_px,
            r.psnr,
            r.auto,
            r.pareto
        )?;
    }
    let mut chart = String::new();
    draw(&rows, &mut chart)?;
    super::chart::write(out, "wave", &text, &chart)?;
    let pick = |s: usize, f: &dyn Fn(&Row) -> bool| rows.iter().find(|r| r.state == s && f(r)).cloned();
    let lesson = match (pick(0, &|r| r.subdiv == 1 && !r.auto), pick(0, &|r| r.auto), pick(1, &|r| r.subdiv == 1 && !r.auto), pick(1, &|r| r.auto)) {
        (Some(c), Some(a), Some(sc), Some(sa)) => format!(
            "At the course's wave its 40×40 grid is {} px off a grid split 32×32 ({:.1} dB, {:.3} ms); `subdiv=auto` splits \
             each cell {}×{} ({} px off, {:.1} dB, {:.3} ms). On a taller, faster wave the course's grid cuts the crests ({} px off, \
             {:.1} dB) and auto's {}×{} split brings it to {} px off ({:.1} dB) for {:.3} ms against {:.3} ms: the error follows \
             h·(xs² + zs²), so a grid fixed for one wave is too coarse or too fine for another.",
            c.off_px, c.psnr, c.ms, a.subdiv, a.subdiv, a.off_px, a.psnr, a.ms, sc.off_px, sc.psnr, sa.subdiv, sa.subdiv, sa.off_px, sa.psnr, sa.ms, sc.ms
        ),
        _ => "(a quick run)".into(),
    };
    Ok(Summary {
        name: "wave",
        title: "Seed 001: wave grid subdivision against a converged grid",
        lesson,
    })
}

fn draw(rows: &[Row], svg: &mut String) -> anyhow::Result<()> {
    let panels = (0..STATES.len())
        .map(|s| {
            let points = rows
                .iter()
                .filter(|r| r.state == s)
                .map(|r| Point {
                    ms: r.ms,
                    error: r.off_px as f64,
                    label: r.subdiv.to_string(),
                    auto: r.auto,
                    pareto: r.pareto,
                })
                .collect();
            (format!("wave, {}", STATES[s].0), points)
        })
        .collect();
    sweep_chart(
        svg,
        (1100, 480),
        panels,
        "pixels off vs 32x32-split grid (0 at 0.5)",
        "subdiv k",
        "subdiv=auto",
    )
}
