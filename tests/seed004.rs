//! Seed 004, "OpenGL III – Basic Shaders": every effect's first state against the reference
//! renderer's image (PSNR ≥ 40 dB), pixel statistics that a wrong port would break at other
//! states, the keys and the mouse, the shipped "BMP" texture, and bad `--model` files through
//! the example binaries.
//!
//! Run alone with `cargo test --release --test seed004`. Images the tests render are written to
//! `target/test-output/seed004/` for people to look at.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use image::RgbImage;
use shaderlab::geometry::images;
use shaderlab::lab::{Input, LabContext, LabEntry, Special, NO_FILES};
use shaderlab::labs::{self, gl_textures};
use shaderlab::metrics::{diff_image, mean_color, psnr};
use shaderlab::offscreen::{to_rgb, COLOR_FORMAT};
use shaderlab::shader::ShaderSource;
use shaderlab::{Gpu, Lab};

const MIN_PSNR: f64 = 40.0;

/// The shared headless GPU. No adapter is a failure, never a skip.
fn gpu() -> &'static Gpu {
    static GPU: OnceLock<Gpu> = OnceLock::new();
    GPU.get_or_init(|| match Gpu::headless() {
        Ok(gpu) => gpu,
        Err(e) => panic!("GPU tests need an adapter (lavapipe: `apt-get install mesa-vulkan-drivers`): {e}"),
    })
}

/// A lab with the built-in shaders and data.
fn lab(entry: &LabEntry) -> Box<dyn Lab> {
    let source = ShaderSource::Embedded;
    let cx = LabContext {
        gpu: gpu(),
        source: &source,
        format: COLOR_FORMAT,
        files: &NO_FILES,
    };
    (entry.new)(&cx).unwrap_or_else(|e| panic!("{} builds: {e}", entry.info.name))
}

/// One frame of `lab` at its default size.
fn shot(lab: &mut dyn Lab) -> RgbImage {
    let (w, h) = lab.info().size;
    to_rgb(&shaderlab::shell::screenshot(gpu(), lab, w, h).expect("screenshot"))
}

/// `entry` rendered at a state given as `key=value` assignments (as `--set` takes them).
fn render(entry: &LabEntry, state: &[(&str, &str)]) -> RgbImage {
    let mut lab = lab(entry);
    for (key, value) in state {
        lab.params_mut()
            .set_str(key, value)
            .unwrap_or_else(|e| panic!("{}: {key}={value}: {e}", entry.info.name));
    }
    shot(lab.as_mut())
}

/// Where the tests leave their images.
fn output_dir() -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/test-output/seed004");
    std::fs::create_dir_all(&dir).expect("create target/test-output/seed004");
    dir
}

fn save(image: &RgbImage, name: &str) {
    image.save(output_dir().join(name)).expect("write a test image");
}

/// `/work/shared/reference/seeds/004_<effect>_<state>.png`.
fn reference(name: &str) -> RgbImage {
    let path = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/reference/seeds/")).join(name);
    image::open(&path)
        .unwrap_or_else(|e| {
            panic!(
                "reference {} missing or unreadable ({e}); references come from the reference renderer and are never written by tests",
                path.display()
            )
        })
        .to_rgb8()
}

/// Renders `entry` at its first state and compares it with the reference `004_<name>.png`.
fn check_reference(entry: &LabEntry, reference_name: &str, state: &[(&str, &str)]) -> f64 {
    let actual = render(entry, state);
    let expected = reference(&format!("004_{reference_name}.png"));
    let db = psnr(&actual, &expected).expect("same size");
    println!("004_{reference_name}: PSNR {db:.2} dB");
    save(&actual, &format!("{reference_name}.png"));
    if db < MIN_PSNR {
        if let Some(d) = diff_image(&actual, &expected) {
            save(&d, &format!("{reference_name}.diff.png"));
        }
    }
    assert!(db >= MIN_PSNR, "004_{reference_name}: {db:.2} dB < {MIN_PSNR}");
    db
}

#[test]
fn normal_color_matches_reference() {
    check_reference(labs::SUZANNE_NORMAL_COLOR, "normal_color_default", &[]);
}

#[test]
fn normal_matrix_matches_reference() {
    check_reference(labs::SUZANNE_NORMAL_MATRIX, "normal_matrix_default", &[]);
}

#[test]
fn smooth_matches_reference() {
    check_reference(labs::SUZANNE_SMOOTH, "smooth_default", &[]);
}

#[test]
fn texture_matches_reference() {
    check_reference(labs::SUZANNE_TEXTURE, "texture_checker", &[("tex", "0")]);
}

#[test]
fn texture_color_matches_reference() {
    check_reference(labs::SUZANNE_TEXTURE_COLOR, "texture_color_checker", &[("tex", "0")]);
}

#[test]
fn texparams_matches_reference() {
    check_reference(labs::TEXPARAMS, "texparams_default", &[]);
}

#[test]
fn flat_matches_reference() {
    check_reference(labs::SUZANNE_FLAT, "flat_default", &[]);
}

#[test]
fn gouraud_matches_reference() {
    check_reference(labs::SUZANNE_GOURAUD, "gouraud_default", &[]);
}

#[test]
fn phong_matches_reference() {
    check_reference(labs::SUZANNE_PHONG, "phong_default", &[]);
}

/// Writes `assets/uvgrid.bmp` from [`images::uvgrid`]: run deliberately with
/// `cargo test --release --test seed004 -- --ignored write_uvgrid_bmp` (or
/// `scripts/write-uvgrid-bmp`). The picture is stored upside down (the grid's row 0 at the
/// bottom, a 24-bit BMP's first stored row), so that the course's loader, uploading the BMP's
/// rows in file order, uploads exactly uvgrid's rows; `uvgrid_bmp_uploads_uvgrid` checks it.
#[test]
#[ignore = "writes assets/uvgrid.bmp; run deliberately"]
fn write_uvgrid_bmp() {
    let grid = images::uvgrid();
    let picture = RgbImage::from_fn(grid.width, grid.height, |x, y| {
        let t = grid.texel(0, x, grid.height - 1 - y).expect("inside");
        image::Rgb([t[0], t[1], t[2]])
    });
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(gl_textures::UVGRID_BMP_PATH);
    picture
        .save_with_format(&path, image::ImageFormat::Bmp)
        .expect("write assets/uvgrid.bmp");
    println!("wrote {}", path.display());
}

#[test]
fn uvgrid_bmp_uploads_uvgrid() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(gl_textures::UVGRID_BMP_PATH);
    let bytes = std::fs::read(&path).expect("assets/uvgrid.bmp");
    assert_eq!(bytes, gl_textures::UVGRID_BMP, "the compiled-in copy is the file");
    assert_eq!(&bytes[..2], b"BM", "a BMP file");
    // Decoded through the project's loader and put in upload order: uvgrid, byte for byte.
    let loaded = images::load_image(&path).expect("decode assets/uvgrid.bmp");
    let uploaded = gl_textures::bottom_row_first(&loaded);
    let grid = images::uvgrid();
    assert_eq!((uploaded.width, uploaded.height, uploaded.layers), (256, 256, 1));
    assert!(uploaded.rgba == grid.rgba, "assets/uvgrid.bmp does not upload uvgrid()");
    // The first uploaded row (t ≈ 0, uvgrid's row 0, a grid line) is the picture's bottom row.
    assert_eq!(loaded.texel(0, 40, 255), Some([255, 255, 255, 255]));
    assert_eq!(loaded.texel(0, 40, 254), Some([40, 1, 96, 255]));
}
