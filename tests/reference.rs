//! The port against the original: every exercise and object at rotation 0,0 and time 0 must
//! match the original C/GLUT program's image (Mesa llvmpipe, freeglut 3.4.0) with PSNR >= 35 dB.
//! On failure the port's image and a difference image are written to `target/test-output/`.

mod common;

use common::*;
use shaderlab::lab::LabEntry;
use shaderlab::labs;
use shaderlab::metrics::{diff_image, psnr};
use shaderlab::Object;

const MIN_PSNR: f64 = 35.0;

fn check(entry: &LabEntry, exercise: u32) {
    let mut failures = Vec::new();
    for object in Object::ALL {
        let name = format!("lab{exercise}_{}_x0_y0_t0.png", object.name());
        let expected = reference(&name);
        let actual = render(entry, object, [0.0; 3], 0.0, &[]);
        let db = psnr(&actual, &expected).expect("same size");
        println!("{name}: PSNR {db:.2} dB");
        if db < MIN_PSNR {
            let out = output_dir();
            let _ = actual.save(out.join(name.replace(".png", ".actual.png")));
            if let Some(d) = diff_image(&actual, &expected) {
                let _ = d.save(out.join(name.replace(".png", ".diff.png")));
            }
            failures.push(format!("{name}: {db:.2} dB < {MIN_PSNR}"));
        }
    }
    assert!(failures.is_empty(), "images differ from the original: {failures:?}");
}

#[test]
fn position_rgb_matches_original() {
    check(labs::POSITION_RGB, 1);
}

#[test]
fn normal_rgb_matches_original() {
    check(labs::NORMAL_RGB, 2);
}

#[test]
fn phong_matches_original() {
    check(labs::PHONG, 3);
}

#[test]
fn noise_matches_original() {
    check(labs::NOISE, 4);
}

#[test]
fn displacement_matches_original() {
    check(labs::DISPLACEMENT, 5);
}
