//! Seed 003, LETI lab report 5 (SPEC §3): `specular_strip`, the Bézier strip with specular
//! light seen through the report's fly camera. Its first state against the reference image of
//! the original GL program, the camera states, keys and mouse, and the course's quirks.

use std::sync::OnceLock;

use image::RgbImage;
use shaderlab::lab::{Input, LabContext, LabEntry, Special};
use shaderlab::labs;
use shaderlab::metrics::{bounding_box, coverage, mean_color, psnr};
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

/// Renders the strip at its default size with `key=value` parameters (as `--set` does).
fn render(set: &[(&str, &str)]) -> RgbImage {
    let mut lab = build(labs::SPECULAR_STRIP);
    for (k, v) in set {
        lab.params_mut().set_str(k, v).expect("parameter");
    }
    let image = shot(lab.as_mut());
    let name = std::iter::once("specular_strip".to_string())
        .chain(set.iter().map(|(k, v)| format!("{k}{v}")))
        .collect::<Vec<_>>()
        .join("_");
    let _ = image.save(std::env::temp_dir().join(format!("l003_{name}.png")));
    image
}

fn reference(name: &str) -> RgbImage {
    let path = format!("{REFERENCES}{name}");
    image::open(&path)
        .unwrap_or_else(|e| panic!("reference {path} missing or unreadable ({e}); it is never generated"))
        .to_rgb8()
}

#[test]
fn specular_strip_matches_reference() {
    let image = render(&[]);
    let file = "003_specular_strip_default.png";
    let db = psnr(&image, &reference(file)).expect("same size");
    println!("{file}: PSNR {db:.2} dB");
    assert!(db >= 40.0, "{file}: PSNR {db:.2} dB < 40");
}
