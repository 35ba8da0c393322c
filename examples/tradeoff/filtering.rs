//! Seed 004 texture filtering on `texparams`' receding floor: GL's MIN filters (NEAREST,
//! LINEAR, LINEAR_MIPMAP_NEAREST, LINEAR_MIPMAP_LINEAR = trilinear) × MAG filters against a
//! 16 × 16-supersampled, box-filtered ground truth (the floor drawn 16 times larger with
//! NEAREST from level 0, each pixel the mean of its 256 point samples): the classic chart of
//! aliasing (the far squares shimmer) against blur (mipmaps average them to grey), with time;
//! and anisotropic filtering (4 and 16 samples, the port's `aniso`) beside them.

use std::fmt::Write as _;

use image::RgbImage;
use plotters::prelude::*;
use shaderlab::metrics::{box_downsample, rmse};
use shaderlab::offscreen::to_rgb;
use shaderlab::shell::{bench, screenshot};
use shaderlab::{course, Gpu};

use super::chart::{axes, legend, pareto_line, MS_AXIS};
use super::Summary;

const W: u32 = 640;
const H: u32 = 480;
/// Samples per pixel side of the ground truth.
const SS: u32 = 16;

const MINS: [&str; 4] = ["nearest", "linear", "linear_mipmap_nearest", "linear_mipmap_linear"];
/// The anisotropic rows' labels (in the `min` column).
const ANISO: [&str; 2] = ["aniso 4", "aniso 16"];
const MAGS: [&str; 2] = ["nearest", "linear"];

#[derive(Clone, Debug)]
struct Row {
    min: &'static str,
    mag: &'static str,
    ms: f64,
    rmse: f64,
    /// RMSE over the far half of the floor (rows above the middle): where minification is.
    far_rmse: f64,
    pareto: bool,
}

/// The top `rows` rows of an image.
fn top(image: &RgbImage, rows: u32) -> RgbImage {
    image::imageops::crop_imm(image, 0, 0, image.width(), rows).to_image()
}

pub fn study(out: &mut super::chart::Outputs, frames: u32, gpu: &Gpu) -> anyhow::Result<Summary> {
    let cx = super::chart::context(gpu);
    let mut lab = (course::TEXPARAMS.new)(&cx)?;
    lab.params_mut().set_str("min", "nearest")?;
    lab.params_mut().set_str("mag", "nearest")?;
    eprintln!("filtering: drawing the {}x{} ground truth", W * SS, H * SS);
    let truth = box_downsample(&to_rgb(&screenshot(gpu, lab.as_mut(), W * SS, H * SS)?), SS);
    let mut rows = Vec::new();
    let configs = MINS
        .iter()
        .flat_map(|min| MAGS.iter().map(move |mag| (*min, *mag, "1")))
        .chain([("aniso 4", "linear", "4"), ("aniso 16", "linear", "16")]);
    for (min, mag, aniso) in configs {
        {
            if aniso == "1" {
                lab.params_mut().set_str("min", min)?;
                lab.params_mut().set_str("mag", mag)?;
            }
            lab.params_mut().set_str("aniso", aniso)?;
            let image = to_rgb(&screenshot(gpu, lab.as_mut(), W, H)?);
            let timing = bench(gpu, lab.as_mut(), frames, W, H, true)?;
            let row = Row {
                min,
                mag,
                ms: timing.gpu_ms.unwrap_or(timing.ms_per_frame),
                rmse: rmse(&image, &truth).unwrap_or(f64::INFINITY),
                far_rmse: rmse(&top(&image, H / 2), &top(&truth, H / 2)).unwrap_or(f64::INFINITY),
                pareto: false,
            };
            eprintln!(
                "filtering min {min} mag {mag}: {:.3} ms, RMSE {:.2} (far half {:.2})",
                row.ms, row.rmse, row.far_rmse
            );
            rows.push(row);
        }
    }
    let front = super::chart::pareto(&rows, |_, _| true, |r| r.ms, |r| r.rmse);
    for (r, on) in rows.iter_mut().zip(front) {
        r.pareto = on;
    }
    let mut text = String::from("min,mag,ms_per_frame,rmse,far_half_rmse,pareto\n");
    for r in &rows {
        writeln!(
            text,
            "{},{},{:.4},{:.3},{:.3},{}",
            r.min, r.mag, r.ms, r.rmse, r.far_rmse, r.pareto
        )?;
    }
    let mut chart = String::new();
    draw(&rows, &mut chart)?;
    super::chart::write(out, "filtering", &text, &chart)?;
    let get = |min: &str, mag: &str| rows.iter().find(|r| r.min == min && r.mag == mag).cloned();
    let lesson = match (
        get("nearest", "nearest"),
        get("linear", "linear"),
        get("linear_mipmap_nearest", "nearest"),
        get("linear_mipmap_linear", "linear"),
        get("aniso 16", "linear"),
        get("aniso 4", "linear"),
    ) {
        (Some(n), Some(l), Some(course), Some(tri), Some(an), Some(an4)) => format!(
            "Against the 16×16-supersampled floor (RMSE over the picture, then over its far half), NEAREST aliases ({:.1}, {:.1}) \
             and LINEAR ({:.1}, {:.1}) still does: one sample per pixel cannot stand for many texels; the course's LINEAR_MIPMAP_NEAREST \
             gives {:.1} ({:.1}) and trilinear {:.1} ({:.1}), for {:.3} and {:.3} ms against NEAREST's {:.3} ms: in the distance the \
             right answer is the squares averaged to grey, which is what a mipmap holds. Anisotropic filtering (16 samples, a \
             port addition) gives {:.1} ({:.1}) for {:.3} ms{}: it keeps the squares that a round mip footprint blurs.",
            n.rmse, n.far_rmse, l.rmse, l.far_rmse, course.rmse, course.far_rmse, tri.rmse, tri.far_rmse, course.ms, tri.ms, n.ms,
            an.rmse, an.far_rmse, an.ms,
            if (an.rmse - an4.rmse).abs() < 0.005 { " (4 samples draw the same picture on this rasterizer)" } else { "" }
        ),
        _ => String::new(),
    };
    Ok(Summary {
        name: "filtering",
        title: "Seed 004: texture filtering against a 16×16-supersampled ground truth",
        lesson,
    })
}

fn draw(rows: &[Row], svg: &mut String) -> anyhow::Result<()> {
    let root = SVGBackend::with_string(svg, (800, 480)).into_drawing_area();
    root.fill(&WHITE)?;
    let max_ms = rows.iter().map(|r| r.ms).fold(0.0, f64::max) * 1.3;
    let min_ms = rows.iter().map(|r| r.ms).fold(f64::INFINITY, f64::min) * 0.7;
    let max_y = rows.iter().map(|r| r.rmse).fold(0.0, f64::max) * 1.2;
    let mut c = axes(
        &root,
        "texparams floor: MIN x MAG filter",
        (min_ms..max_ms, MS_AXIS),
        (0.0..max_y, "RMSE vs 16x16-supersampled ground truth"),
    )?;
    let colours = [
        RGBColor(120, 120, 120),
        RGBColor(214, 39, 40),
        RGBColor(31, 119, 180),
        RGBColor(44, 160, 44),
    ];
    let purple = RGBColor(148, 103, 189);
    c.draw_series(
        rows.iter()
            .filter(|r| ANISO.contains(&r.min))
            .map(|r| TriangleMarker::new((r.ms, r.rmse), 8, purple.filled())),
    )?
    .label("anisotropic 4, 16 (port)")
    .legend(move |(x, y)| TriangleMarker::new((x + 10, y), 8, purple.filled()));
    for (min, col) in MINS.iter().zip(colours) {
        c.draw_series(rows.iter().filter(|r| r.min == *min).map(|r| {
            if r.mag == "nearest" {
                Circle::new((r.ms, r.rmse), 6, col.filled())
            } else {
                Circle::new((r.ms, r.rmse), 6, col.stroke_width(2))
            }
        }))?
        .label(format!("MIN {min} (filled: MAG nearest)"))
        .legend(move |(x, y)| Circle::new((x + 10, y), 5, col.filled()));
    }
    pareto_line(
        &mut c,
        rows.iter().filter(|r| r.pareto).map(|r| (r.ms, r.rmse)).collect(),
    )?;
    legend(&mut c, SeriesLabelPosition::UpperRight)?;
    root.present()?;
    Ok(())
}
