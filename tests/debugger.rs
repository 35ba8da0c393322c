//! The debugger agrees with the GPU: for every lab (and the legacy runner with each of the
//! course's five seed-000 pairs), pixels on the drawn surface chosen by a fixed seed, plus
//! pixels along the object's edges, replayed on the CPU store the colour `--screenshot`'s
//! picture has there, within 2/255 per channel, for at least 99 % of them; every miss is named
//! with its lab, pixel and both colours.

mod common;

use std::path::{Path, PathBuf};

use common::gpu;
use shaderlab::debug::{capture_lab, Inspection};
use shaderlab::lab::{BuildContext, Lab, UserFiles};
use shaderlab::offscreen::COLOR_FORMAT;
use shaderlab::shader::ShaderSource;

/// Pixels checked on the surface, and along its edges.
const SURFACE: usize = 200;
const EDGES: usize = 60;

/// xorshift64*: the fixed sequence of pixels.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

fn build(name: &str, files: &UserFiles, set: &[(&str, &str)]) -> Box<dyn Lab> {
    let entry = shaderlab::labs::find(name).expect("a lab");
    let source = ShaderSource::Embedded;
    let cx = BuildContext {
        gpu: gpu(),
        source: &source,
        format: COLOR_FORMAT,
        files,
        lab: "",
    };
    let mut lab = (entry.new)(&cx).unwrap_or_else(|e| panic!("{name} builds: {e}"));
    for (k, v) in set {
        lab.params_mut()
            .set_str(k, v)
            .unwrap_or_else(|e| panic!("{name} --set {k}={v}: {e}"));
    }
    lab
}

/// The pixels of `image` checked: `SURFACE` on the drawn surface (not the clear colour) and
/// `EDGES` drawn pixels next to an undrawn one, chosen by `seed`.
fn pixels(image: &image::RgbaImage, clear: [u8; 4], seed: u64) -> Vec<(u32, u32)> {
    let (w, h) = image.dimensions();
    let drawn = |x: u32, y: u32| image.get_pixel(x, y).0 != clear;
    let mut surface = Vec::new();
    let mut edges = Vec::new();
    for y in 0..h {
        for x in 0..w {
            if !drawn(x, y) {
                continue;
            }
            surface.push((x, y));
            let near = [(x.wrapping_sub(1), y), (x + 1, y), (x, y.wrapping_sub(1)), (x, y + 1)];
            if near.iter().any(|&(a, b)| a < w && b < h && !drawn(a, b)) {
                edges.push((x, y));
            }
        }
    }
    let mut rng = Rng(seed | 1);
    let mut out = Vec::new();
    for _ in 0..SURFACE.min(surface.len()) {
        out.push(surface[rng.below(surface.len())]);
    }
    for _ in 0..EDGES.min(edges.len()) {
        out.push(edges[rng.below(edges.len())]);
    }
    // A few of the background too.
    for _ in 0..8 {
        out.push((rng.below(w as usize) as u32, rng.below(h as usize) as u32));
    }
    out
}

/// Checks one state; returns (pixels checked, misses).
fn agreement(name: &str, mut lab: Box<dyn Lab>, seed: u64) -> (usize, Vec<String>) {
    let (w, h) = lab.info().size;
    eprintln!("checking {name}");
    let (image, captured) = capture_lab(gpu(), lab.as_mut(), w, h, true).unwrap_or_else(|e| panic!("{name}: {e}"));
    let image = image.expect("the picture");
    let clear = captured
        .passes
        .last()
        .map(|p| match p.0 {
            shaderlab::render::Load::Clear(c) => {
                [c[0], c[1], c[2]].map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
            }
            shaderlab::render::Load::Keep => [0, 0, 0],
        })
        .unwrap_or([0, 0, 0]);
    let clear = [clear[0], clear[1], clear[2], 255];
    let mut misses = Vec::new();
    let list = pixels(&image, clear, seed);
    for &(x, y) in &list {
        let gpu_px = image.get_pixel(x, y).0;
        if std::env::var("DEBUGGER_TEST_VERBOSE").is_ok() {
            eprintln!("  {x},{y}");
        }
        match Inspection::new(name, &captured, x, y) {
            Ok(i) => {
                let cpu = i.replayed.pixel;
                let off = (0..4).map(|k| (i32::from(cpu[k]) - i32::from(gpu_px[k])).abs()).max().unwrap_or(0);
                if off > 2 {
                    misses.push(format!("{name} pixel {x},{y}: debugger {cpu:?}, GPU {gpu_px:?}"));
                }
            }
            Err(e) => misses.push(format!("{name} pixel {x},{y}: {e}")),
        }
    }
    (list.len(), misses)
}

fn course(lab: u32) -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/course");
    let pick = |name: String| {
        if name == "lab4.frag" || name == "lab5.vert" {
            dir.join(format!("seed000-mended/{name}"))
        } else {
            dir.join(format!("seed000/{name}"))
        }
    };
    vec![pick(format!("lab{lab}.vert")), pick(format!("lab{lab}.frag"))]
}

/// The states checked: every lab at its defaults, plus states with textures, time, the fly
/// camera and other objects.
fn states() -> Vec<(String, Box<dyn Lab>)> {
    let none = UserFiles::default();
    let mut out: Vec<(String, Box<dyn Lab>)> = Vec::new();
    for entry in shaderlab::labs::ALL {
        let name = entry.info.name;
        if name == "legacy" {
            continue;
        }
        // At time 0 every particle is still at the fountain's mouth: a few pixels.
        let set: &[(&str, &str)] = if name == "particles" { &[("time", "2")] } else { &[] };
        out.push((name.to_owned(), build(name, &none, set)));
    }
    for lab in 1..=5 {
        let files = UserFiles {
            inputs: course(lab),
            ..UserFiles::default()
        };
        let set: &[(&str, &str)] = if lab >= 4 {
            &[("object", "teapot"), ("shade", "1,0.8,0.5"), ("time", "1.7")]
        } else {
            &[("object", "teapot")]
        };
        out.push((format!("legacy lab{lab}"), build("legacy", &files, set)));
    }
    let extra: &[(&str, &[(&str, &str)])] = &[
        ("phong", &[("object", "torus"), ("xangle", "30"), ("yangle", "40")]),
        ("noise", &[("object", "sphere"), ("time", "2.5")]),
        ("displacement", &[("object", "teapot"), ("time", "1.25")]),
        ("wave", &[("time", "3.5")]),
        ("particles", &[("time", "3.3"), ("xangle", "20")]),
        ("morph", &[("time", "1.5")]),
        ("texparams", &[("min", "linear_mipmap_linear"), ("mag", "linear")]),
        ("texparams", &[("min", "nearest"), ("wrap_s", "clamp_to_edge")]),
        ("specular_strip", &[("forward", "5"), ("yaw", "20"), ("pitch", "-10")]),
    ];
    for (name, set) in extra {
        let label = format!(
            "{name} {}",
            set.iter().map(|(k, v)| format!("{k}={v}")).collect::<Vec<_>>().join(" ")
        );
        out.push((label, build(name, &none, set)));
    }
    out
}

#[test]
fn the_debugger_stores_the_pixel_the_gpu_stores() {
    let mut report = Vec::new();
    let mut failures = Vec::new();
    let mut seed = 0x5eed_0001u64;
    for (name, lab) in states() {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        let (checked, misses) = agreement(&name, lab, seed);
        let agree = 100.0 * (checked - misses.len()) as f64 / checked.max(1) as f64;
        report.push(format!("| {name} | {checked} | {agree:.1} % |"));
        if checked < SURFACE || agree < 99.0 {
            failures.push(format!("{name}: {checked} pixels, {agree:.1} % agree"));
        }
        for m in misses.iter().take(6) {
            report.push(format!("    miss: {m}"));
        }
    }
    println!("| state | pixels | within 2/255 |\n|---|---|---|\n{}", report.join("\n"));
    assert!(failures.is_empty(), "{}\n{}", failures.join("\n"), report.join("\n"));
}
