//! `cargo run --release --example tradeoff -- --study NAME|all --out DIR`: speed against
//! accuracy, one study per lecture's choice, each written as `DIR/NAME.csv` (the Pareto front
//! marked), `DIR/NAME.svg` and `DIR/NAME.md` (its section: chart, lesson, machine, date), with
//! `DIR/index.md` gathering every study's section found in DIR.
//!
//! `phong000` (seed 000's Phong exercise) sweeps shading model (flat, Gouraud, Phong, Blinn-Phong) x tessellation level for the
//! sphere and the torus, plus Phong with back-face culling (`--set cull=1`, the opt-in that is not
//! byte-identical; its `changed_px` counts the pixels it changes against the same configuration
//! drawn whole), measures frame time (GPU timestamps where available, else wall time) and
//! the error against the exact f64 ray-cast reference (RMSE, maximum per-pixel error, silhouette
//! error), and writes `phong000.csv` and `phong000.svg` (error against time, Pareto front marked).
//!
//! `wave` (seed 001) splits each checker cell k × k against a converged 32 × 32 split, at the
//! course's wave and a stronger one, and shows where `subdiv=auto` lands.
//!
//! `lighting` (seed 001) sets per-vertex against per-fragment lighting (`phong_vertex`,
//! `phong_fragment`, `toon`) at increasing tessellation against converged references.
//!
//! `normmap` (seed 001) times the lecture's normalization cube map against `normalize`, and
//! measures what the lookup costs in accuracy.
//!
//! `bezier` (seed 003) sets the strip's curve tessellation against a converged strip, and where
//! `segments=auto` lands.
//!
//! `suzanne` (seed 004) compares flat, Gouraud and Phong on Suzanne with a 4 × 4-supersampled
//! per-pixel reference.
//!
//! `filtering` (seed 004) sets GL's texture filters on `texparams`' floor against a
//! 16 × 16-supersampled ground truth.
//!
//! `twist` (seed 002) sweeps the grid (quads per side) at three `twisting`s against the exact
//! per-pixel picture (`shaderlab::study::twist`): pixels wrong, the outline's error in pixels and
//! frame time, and where `grid=auto` lands.
//!
//! Every file is written whole (a temporary file renamed into place): an interrupted or failed run
//! leaves the previous ones as they were, and a folder it would have made is not made.

use std::fmt::Write as _;
use std::path::PathBuf;

use chart::Outputs;
use clap::{CommandFactory, FromArgMatches, Parser};
use plotters::prelude::*;
use shaderlab::exact::{image_error, silhouette_error, ExactScene, Shape, Specular};
use shaderlab::fsutil::{check_output_path, check_writable, Dest, NewDir};
use shaderlab::metrics::mask;
use shaderlab::offscreen::to_rgb;
use shaderlab::shell::{bench, say, screenshot};
use shaderlab::{course, Gpu, Object};

shaderlab::say_when_exhausted!();

/// The phong lab's shading models (its `shading` parameter).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Shading {
    Flat,
    Gouraud,
    Phong,
    Blinn,
}

impl Shading {
    const ALL: [Shading; 4] = [Shading::Flat, Shading::Gouraud, Shading::Phong, Shading::Blinn];
    fn name(self) -> &'static str {
        match self {
            Shading::Flat => "flat",
            Shading::Gouraud => "gouraud",
            Shading::Phong => "phong",
            Shading::Blinn => "blinn",
        }
    }
}

/// The studies, in the order `all` runs them.
const STUDIES: [&str; 8] = [
    "phong000",
    "wave",
    "lighting",
    "normmap",
    "twist",
    "bezier",
    "suzanne",
    "filtering",
];

#[derive(Parser)]
#[command(about = "Chart speed against accuracy in each lecture, against exact references")]
struct Args {
    /// Which study: phong000 (seed 000: shading model x tessellation), wave (seed 001: grid
    /// subdivision), lighting (seed 001: per-vertex against per-fragment), normmap (seed 001:
    /// cube map against normalize), twist (seed 002: grid resolution), suzanne (seed 004: flat,
    /// Gouraud and Phong), filtering (seed 004: texture filters), bezier (seed 003: curve
    /// tessellation), or all.
    #[arg(long, default_value = "all", value_parser = ["all", "phong000", "wave", "lighting", "normmap", "twist", "bezier", "suzanne", "filtering"])]
    study: String,
    /// Output directory for NAME.csv, NAME.svg and index.md.
    #[arg(long, default_value = "tradeoff")]
    out: PathBuf,
    /// Frames timed per configuration.
    #[arg(long, default_value_t = 40, value_parser = clap::value_parser!(u32).range(1..=10_000))]
    frames: u32,
    /// Fewer levels (for a quick look).
    #[arg(long)]
    quick: bool,
}

#[derive(Clone, Debug)]
struct Row {
    shape: &'static str,
    shading: Shading,
    level: u32,
    triangles: usize,
    ms: f64,
    rmse: f64,
    max: u8,
    silhouette_px: f64,
    /// Back-face culling on (`cull=1`).
    cull: bool,
    /// Pixels that differ from the same configuration without culling (0 without culling).
    changed_px: usize,
    pareto: bool,
}

const W: u32 = 640;
const H: u32 = 360;

/// What a study found, for the index.
struct Summary {
    name: &'static str,
    title: &'static str,
    /// One sentence of what it teaches, with the CSV's figures.
    lesson: String,
}

fn main() -> std::process::ExitCode {
    shaderlab::shell::ensure_runtime_dir();
    let matches = shaderlab::shell::parse_command_line(Args::command(), std::env::args_os());
    let args = Args::from_arg_matches(&matches).unwrap_or_else(|e| shaderlab::shell::exit_on_clap_error("tradeoff", e));
    shaderlab::shell::tool_exit("tradeoff", run(&args))
}

fn run(args: &Args) -> anyhow::Result<()> {
    let chosen: Vec<&str> = STUDIES
        .into_iter()
        .filter(|s| args.study == "all" || args.study == *s)
        .collect();
    // Before the sweeps, not after them: the folder can be made (it is made only when the
    // files are moved in, so a failed run leaves no new empty folder) and takes files, and no
    // output name in it is a directory, a FIFO or one of the run's inputs.
    NewDir::check(&args.out)?;
    if args.out.is_dir() {
        check_writable(&args.out.join("index.md"))?;
        for name in &chosen {
            for ext in ["csv", "svg", "md"] {
                let path = args.out.join(format!("{name}.{ext}"));
                check_output_path(&path)?;
                if !matches!(Dest::of(&path)?, Dest::File(_)) {
                    anyhow::bail!(
                        "{}: not a regular file (a FIFO or device); the studies write files",
                        path.display()
                    );
                }
            }
        }
    }
    let gpu = Gpu::headless()?;
    let mut out = Outputs::new(&args.out);
    let mut summaries = Vec::new();
    for name in chosen {
        summaries.push(match name {
            "phong000" => phong000(args, &mut out, &gpu)?,
            "wave" => wave::study(&mut out, args.frames, args.quick, &gpu)?,
            "suzanne" => suzanne::study(&mut out, args.frames, &gpu)?,
            "normmap" => normmap::study(&mut out, args.frames, &gpu)?,
            "lighting" => lighting::study(&mut out, args.frames, args.quick, &gpu)?,
            "filtering" => filtering::study(&mut out, args.frames, &gpu)?,
            "bezier" => bezier::study(&mut out, args.frames, &gpu)?,
            _ => twist::study(&mut out, args.frames, args.quick, &gpu)?,
        });
    }
    // Each study's section is kept in NAME.md, so that one study run again leaves the others'
    // sections in the index as they were.
    for s in &summaries {
        let section = format!(
            "## {}\n\n![{}]({}.svg)\n\n{}\n\nData: [`{}.csv`]({}.csv); written by `--study {}` on {} ({}).\n",
            s.title,
            s.name,
            s.name,
            s.lesson,
            s.name,
            s.name,
            s.name,
            gpu.describe(),
            today()
        );
        out.file(&format!("{}.md", s.name), section);
    }
    let mut text = String::from(
        "# Speed against accuracy\n\nWritten by `cargo run --release --example tradeoff -- --study NAME|all --out DIR`. \
         Each chart plots error against frame time; the CSV beside it marks the Pareto front.\n",
    );
    for name in STUDIES {
        let md = format!("{name}.md");
        let section = match out.get(&md) {
            Some(section) => Some(section.to_owned()),
            None => std::fs::read_to_string(args.out.join(&md)).ok(),
        };
        if let Some(section) = section {
            write!(text, "\n{section}")?;
        }
    }
    out.file("index.md", text);
    let written = out.commit()?;
    let names: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
    say(&format!("wrote {}", names.join(", ")))?;
    Ok(())
}

/// Today's date (UTC), for the index.
fn today() -> String {
    let days = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs() / 86_400)
        .unwrap_or(0) as i64;
    // Civil from days (H. Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!("{year:04}-{month:02}-{day:02}")
}

#[path = "tradeoff/bezier.rs"]
mod bezier;
#[path = "tradeoff/chart.rs"]
mod chart;
#[path = "tradeoff/filtering.rs"]
mod filtering;
#[path = "tradeoff/lighting.rs"]
mod lighting;
#[path = "tradeoff/normmap.rs"]
mod normmap;
#[path = "tradeoff/suzanne.rs"]
mod suzanne;
#[path = "tradeoff/twist.rs"]
mod twist;
#[path = "tradeoff/wave.rs"]
mod wave;

/// Seed 000's Phong exercise: shading model x tessellation on the sphere and the torus.
fn phong000(args: &Args, out: &mut Outputs, gpu: &Gpu) -> anyhow::Result<Summary> {
    let levels: &[u32] = if args.quick {
        &[4, 8, 16, 32, 64]
    } else {
        &[4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128, 192]
    };
    let shapes = [(Object::Sphere, Shape::Sphere), (Object::Torus, Shape::Torus)];
    let total = shapes.len() * (Shading::ALL.len() + 1) * levels.len();
    eprintln!(
        "adapter: {}; {total} configurations, {} frames each, {W}x{H}",
        gpu.describe(),
        args.frames
    );
    let cx = chart::context(gpu);
    let mut lab = (course::PHONG.new)(&cx)?;
    let mut rows = Vec::new();
    let mut done = 0;
    // A bar on a terminal; in a log, one line per configuration as before.
    let bar = shaderlab::shell::progress_bar(total as u64, "configurations");
    for (object, shape) in shapes {
        lab.params_mut().set_str("object", object.name())?;
        let exact_phong = ExactScene {
            shape,
            ..Default::default()
        };
        let exact_blinn = ExactScene {
            shape,
            specular: Specular::Blinn,
            ..Default::default()
        };
        let (phong_img, blinn_img) = (exact_phong.render(W, H), exact_blinn.render(W, H));
        for shading in Shading::ALL {
            lab.params_mut().set_str("shading", shading.name())?;
            let (exact, exact_img) = if shading == Shading::Blinn {
                (&exact_blinn, &blinn_img)
            } else {
                (&exact_phong, &phong_img)
            };
            for &level in levels {
                lab.params_mut().set("tess", &[f64::from(level)])?;
                // Phong is also measured with back-face culling, against its own whole image.
                let culls: &[bool] = if shading == Shading::Phong {
                    &[false, true]
                } else {
                    &[false]
                };
                let mut whole: Option<image::RgbImage> = None;
                for &cull in culls {
                    lab.params_mut().set("cull", &[if cull { 1.0 } else { 0.0 }])?;
                    let timing = bench(gpu, lab.as_mut(), args.frames, W, H, true)?;
                    let image = to_rgb(&screenshot(gpu, lab.as_mut(), W, H)?);
                    let err = image_error(exact_img, &image)?;
                    let sil = silhouette_error(exact, &mask(&image, [13, 26, 51], 0), W, H)?;
                    let triangles = shaderlab::tess::mesh(object, level).triangle_count();
                    let ms = timing.gpu_ms.unwrap_or(timing.ms_per_frame);
                    let changed_px = whole
                        .as_ref()
                        .map_or(0, |w| w.pixels().zip(image.pixels()).filter(|(a, b)| a != b).count());
                    done += 1;
                    bar.set_position(done as u64);
                    let line = format!(
                        "[{done:>3}/{total}] {:<6} {:<7}{} level {level:>3} ({triangles:>6} triangles): {ms:.3} ms, RMSE {:.2}, max {}, silhouette {:.2} px{}",
                        object.name(),
                        shading.name(),
                        if cull { " cull" } else { "" },
                        err.rmse,
                        err.max,
                        sil.max_px,
                        if cull { format!(", {changed_px} px changed by culling") } else { String::new() }
                    );
                    chart::say(&bar, line);
                    rows.push(Row {
                        shape: object.name(),
                        shading,
                        level,
                        triangles,
                        ms,
                        rmse: err.rmse,
                        max: err.max,
                        silhouette_px: sil.max_px,
                        cull,
                        changed_px,
                        pareto: false,
                    });
                    whole.get_or_insert(image);
                }
                lab.params_mut().set("cull", &[0.0])?;
            }
        }
    }
    mark_pareto(&mut rows);
    let mut svg = String::new();
    draw_chart(&rows, &mut svg)?;
    chart::write(out, "phong000", &csv_text(&rows)?, &svg)?;
    let mut fronts = Vec::new();
    for shape in ["sphere", "torus"] {
        let front: Vec<String> = rows
            .iter()
            .filter(|r| r.shape == shape && r.pareto)
            .map(|r| {
                let cull = if r.cull { " cull" } else { "" };
                format!(
                    "{}{cull} {} ({:.2} ms, RMSE {:.2})",
                    r.shading.name(),
                    r.level,
                    r.ms,
                    r.rmse
                )
            })
            .collect();
        say(&format!("{shape} Pareto front: {}", front.join("; ")))?;
        fronts.push(format!("{shape}: {}", front.join("; ")));
    }
    // Which shading models make the front, per shape.
    let makeup: Vec<String> = ["sphere", "torus"]
        .iter()
        .map(|shape| {
            let on: Vec<&Row> = rows.iter().filter(|r| r.shape == *shape && r.pareto).collect();
            let count = |f: &dyn Fn(&Row) -> bool| on.iter().filter(|r| f(r)).count();
            format!(
                "{shape}: {} Gouraud, {} Phong with culling, {} Phong, {} Blinn-Phong, {} flat",
                count(&|r| r.shading == Shading::Gouraud),
                count(&|r| r.shading == Shading::Phong && r.cull),
                count(&|r| r.shading == Shading::Phong && !r.cull),
                count(&|r| r.shading == Shading::Blinn),
                count(&|r| r.shading == Shading::Flat)
            )
        })
        .collect();
    Ok(Summary {
        name: "phong000",
        title: "Seed 000: shading model × tessellation (Phong exercise)",
        lesson: format!(
            "On a software rasterizer per-pixel work is what costs: the Pareto front is mostly Gouraud on coarse meshes \
             and per-pixel Phong drawn with back-face culling on finer ones ({}). The front (shading level: ms per frame, \
             RMSE against the exact ray caster): {}.",
            makeup.join("; "),
            fronts.join("; ")
        ),
    })
}

/// A configuration is on the Pareto front when no other one of the same shape is both faster
/// and more accurate (RMSE).
fn mark_pareto(rows: &mut [Row]) {
    let snapshot = rows.to_vec();
    for r in rows.iter_mut() {
        r.pareto = !snapshot
            .iter()
            .any(|o| o.shape == r.shape && o.ms <= r.ms && o.rmse <= r.rmse && (o.ms < r.ms || o.rmse < r.rmse));
    }
}

fn csv_text(rows: &[Row]) -> anyhow::Result<String> {
    let mut text = String::from(
        "shape,shading,level,triangles,ms_per_frame,rmse,max_error,silhouette_max_px,pareto,cull,changed_px\n",
    );
    for r in rows {
        writeln!(
            text,
            "{},{},{},{},{:.4},{:.4},{},{:.4},{},{},{}",
            r.shape,
            r.shading.name(),
            r.level,
            r.triangles,
            r.ms,
            r.rmse,
            r.max,
            r.silhouette_px,
            r.pareto,
            r.cull,
            r.changed_px
        )?;
    }
    Ok(text)
}

fn color(shading: Shading) -> RGBColor {
    match shading {
        Shading::Flat => RGBColor(120, 120, 120),
        Shading::Gouraud => RGBColor(214, 39, 40),
        Shading::Phong => RGBColor(31, 119, 180),
        Shading::Blinn => RGBColor(44, 160, 44),
    }
}

fn draw_chart(rows: &[Row], svg: &mut String) -> anyhow::Result<()> {
    let root = SVGBackend::with_string(svg, (1200, 520)).into_drawing_area();
    root.fill(&WHITE)?;
    let panels = root.split_evenly((1, 2));
    for (panel, shape) in panels.iter().zip(["sphere", "torus"]) {
        let mine: Vec<&Row> = rows.iter().filter(|r| r.shape == shape).collect();
        let max_ms = mine.iter().map(|r| r.ms).fold(0.0, f64::max) * 1.1;
        let min_ms = mine.iter().map(|r| r.ms).fold(f64::INFINITY, f64::min) * 0.9;
        let max_rmse = mine.iter().map(|r| r.rmse).fold(0.0, f64::max) * 1.5;
        let min_rmse = mine.iter().map(|r| r.rmse).fold(f64::INFINITY, f64::min).max(0.01) * 0.7;
        let mut c = chart::axes(
            panel,
            &format!("Phong exercise, {shape}: error against frame time"),
            ((min_ms..max_ms).log_scale(), chart::MS_AXIS),
            (
                (min_rmse..max_rmse).log_scale(),
                "RMSE vs exact ray-cast (8-bit levels)",
            ),
        )?;
        for shading in Shading::ALL {
            let col = color(shading);
            let pts: Vec<(f64, f64)> = mine
                .iter()
                .filter(|r| r.shading == shading && !r.cull)
                .map(|r| (r.ms, r.rmse.max(min_rmse)))
                .collect();
            c.draw_series(pts.iter().map(|&p| Circle::new(p, 4, col.filled())))?
                .label(shading.name())
                .legend(move |(x, y)| Circle::new((x + 10, y), 4, col.filled()));
        }
        let col = color(Shading::Phong);
        let culled: Vec<(f64, f64)> = mine
            .iter()
            .filter(|r| r.cull)
            .map(|r| (r.ms, r.rmse.max(min_rmse)))
            .collect();
        c.draw_series(culled.iter().map(|&p| Circle::new(p, 5, col.stroke_width(2))))?
            .label("phong, cull=1 (not exact)")
            .legend(move |(x, y)| Circle::new((x + 10, y), 5, col.stroke_width(2)));
        let mut front: Vec<(f64, f64)> = mine
            .iter()
            .filter(|r| r.pareto)
            .map(|r| (r.ms, r.rmse.max(min_rmse)))
            .collect();
        front.sort_by(|a, b| a.0.total_cmp(&b.0));
        chart::pareto_line(&mut c, front.clone())?;
        c.draw_series(front.iter().map(|&p| Circle::new(p, 7, BLACK.stroke_width(1))))?;
        chart::legend(&mut c, SeriesLabelPosition::UpperRight)?;
    }
    root.present()?;
    Ok(())
}
