//! Seed 002, "Lecture 12" (SPEC §2): `twist`, `double_vision`, `normal_world`, `phong_dir`.
//! Each effect's first state against the reference image of the original GL program, and
//! pixel statistics of other SPEC states that a wrong port would break.

use std::sync::OnceLock;

use image::RgbImage;
use shaderlab::lab::{Input, LabContext, LabEntry, Special};
use shaderlab::labs;
use shaderlab::metrics::{bounding_box, mean_color, psnr};
use shaderlab::offscreen::{to_rgb, COLOR_FORMAT};
use shaderlab::shader::ShaderSource;
use shaderlab::{Gpu, Lab};

const REFERENCES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/reference/seeds/");
const BLACK: [u8; 3] = [0, 0, 0];

fn gpu() -> &'static Gpu {
    static GPU: OnceLock<Gpu> = OnceLock::new();
    GPU.get_or_init(|| match Gpu::headless() {
        Ok(gpu) => gpu,
        Err(e) => panic!("GPU tests need an adapter (lavapipe): {e}"),
    })
}

fn build(entry: &LabEntry) -> Box<dyn Lab> {
    let source = ShaderSource::Embedded;
    let cx = LabContext {
        gpu: gpu(),
        source: &source,
        format: COLOR_FORMAT,
    };
    (entry.new)(&cx).expect("lab builds")
}

fn shot(lab: &mut dyn Lab) -> RgbImage {
    let (w, h) = lab.info().size;
    to_rgb(&shaderlab::shell::screenshot(gpu(), lab, w, h).expect("screenshot"))
}

/// Renders `entry` at its default size with `key=value` parameters (as `--set` does).
fn render(entry: &LabEntry, set: &[(&str, &str)]) -> RgbImage {
    let mut lab = build(entry);
    for (k, v) in set {
        lab.params_mut().set_str(k, v).expect("parameter");
    }
    let image = shot(lab.as_mut());
    let name = std::iter::once(entry.info.name.to_string())
        .chain(set.iter().map(|(k, v)| format!("{k}{v}")))
        .collect::<Vec<_>>()
        .join("_");
    let _ = image.save(std::env::temp_dir().join(format!("l002_{name}.png")));
    image
}

fn reference(name: &str) -> RgbImage {
    let path = format!("{REFERENCES}{name}");
    image::open(&path)
        .unwrap_or_else(|e| panic!("reference {path} missing or unreadable ({e}); it is never generated"))
        .to_rgb8()
}

fn check_reference(entry: &LabEntry, file: &str) -> RgbImage {
    let image = render(entry, &[]);
    let db = psnr(&image, &reference(file)).expect("same size");
    println!("{file}: PSNR {db:.2} dB");
    assert!(db >= 40.0, "{file}: PSNR {db:.2} dB < 40");
    image
}

#[test]
fn twist_matches_reference() {
    check_reference(labs::TWIST, "002_twist_default.png");
}

#[test]
fn double_vision_matches_reference() {
    check_reference(labs::DOUBLE_VISION, "002_double_vision_default.png");
}

#[test]
fn normal_world_matches_reference() {
    check_reference(labs::NORMAL_WORLD, "002_normal_world_default.png");
}

#[test]
fn phong_dir_matches_reference() {
    check_reference(labs::PHONG_DIR, "002_phong_dir_default.png");
}
