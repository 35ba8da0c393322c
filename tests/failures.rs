//! Where methods fail: for each known weakness of the original method, a test that finds the
//! failure and shows the port holds. Run with `--nocapture` to see the measured figures (the
//! README's "Where methods fail" section quotes them).

mod common;

use common::*;
use glam::{Mat3, Vec3};
use image::RgbImage;
use shaderlab::course::{self, NOISE_PERIOD};
use shaderlab::exact::{image_error, ExactScene, Shape};
use shaderlab::metrics::{luma_stats, mask, psnr};
use shaderlab::shader::ShaderSource;
use shaderlab::Object;

/// Fraction of horizontally adjacent object pixels with exactly the same value: smooth noise has
/// some (8-bit steps), a pattern frozen into blocks by f32 rounding has many more.
fn blockiness(image: &RgbImage) -> f64 {
    let (w, h) = image.dimensions();
    let (mut same, mut pairs) = (0usize, 0usize);
    for y in 0..h {
        for x in 0..w - 1 {
            let (a, b) = (image.get_pixel(x, y), image.get_pixel(x + 1, y));
            if a[0] > 8 && b[0] > 8 {
                pairs += 1;
                same += (a == b) as usize;
            }
        }
    }
    same as f64 / pairs.max(1) as f64
}

fn noise_at(time: f64, wrap: bool) -> RgbImage {
    let mut lab = lab(course::NOISE);
    lab.set_object(Object::Sphere);
    lab.set_time(time);
    lab.set("wrap_time", &[if wrap { 1.0 } else { 0.0 }])
        .expect("wrap_time");
    lab.rgb(640, 360)
}

#[test]
fn noise_time_precision_and_period() {
    // Frames a whole number of periods apart are identical in the port.
    let a = noise_at(10.25, true);
    let b = noise_at(10.25 + 3.0 * 144.5, true);
    assert_eq!(psnr(&a, &b), Some(f64::INFINITY), "t and t + 3 periods must match");
    // ... and (the period is real) the original, unwrapped, agrees at a small multiple.
    let c = noise_at(10.25 + 144.5, false);
    assert!(
        psnr(&a, &c).expect("size") > 30.0,
        "the pattern repeats after 144.5 s in the original too"
    );
    let base_block = blockiness(&a);
    println!("noise time precision (sphere, 640x360): blockiness at t=10.25: {base_block:.3}");
    println!("| t | original: PSNR vs exact pattern | original blockiness | port: PSNR | port blockiness |");
    let mut original_psnr = Vec::new();
    for t in [1e3f64, 1e5, 1e6] {
        let original = noise_at(t, false);
        let port = noise_at(t, true);
        // The exact pattern at t is the pattern at t mod 144.5 (a small time, where f32 is
        // precise), rendered on its own: the port at t must be exactly that.
        let truth = noise_at(t.rem_euclid(NOISE_PERIOD), false);
        assert_eq!(
            psnr(&port, &truth),
            Some(f64::INFINITY),
            "the port at t={t} must show the exact pattern"
        );
        let p = psnr(&original, &truth).expect("size");
        println!(
            "| {t:e} | {p:.1} dB | {:.3} | inf dB | {:.3} |",
            blockiness(&original),
            blockiness(&port)
        );
        original_psnr.push(p);
        // The port never degrades: same statistics as at small t.
        assert!((blockiness(&port) - base_block).abs() < 0.1, "port blockiness at t={t}");
        let (mean, var) = luma_stats(&port, &mask(&port, [0, 0, 0], 0));
        assert!(var > 0.01 && mean > 0.1, "port noise at t={t}: mean {mean} var {var}");
    }
    // The original drifts from the exact pattern as t grows (f32 spacing at 1e5 is 0.008, at 1e6
    // 0.06 object units): measured 72 dB at 1e3, 46 dB at 1e5, 27 dB and blocky at 1e6.
    assert!(
        original_psnr[0] > original_psnr[1] && original_psnr[1] > original_psnr[2],
        "original PSNR: {original_psnr:?}"
    );
    assert!(
        original_psnr[1] < 60.0 && original_psnr[2] < 35.0,
        "original PSNR: {original_psnr:?}"
    );
    assert!(
        blockiness(&noise_at(1e6, false)) > base_block + 0.2,
        "the original turns blocky at t = 1e6"
    );
}

fn phong_sphere(shading: &str, level: u32) -> RgbImage {
    let mut lab = lab(course::PHONG);
    lab.set_object(Object::Sphere);
    lab.set("tess", &[level as f32]).expect("tess");
    lab.set_str("shading", shading).expect("shading");
    lab.rgb(640, 360)
}

fn peak(image: &RgbImage) -> u8 {
    image.pixels().map(|p| p[2]).max().unwrap_or(0)
}

#[test]
fn gouraud_loses_the_highlight_on_coarse_meshes() {
    let exact = ExactScene {
        shape: Shape::Sphere,
        ..Default::default()
    }
    .render(640, 360);
    println!(
        "| level | Gouraud RMSE | Gouraud peak blue | Phong RMSE | Phong peak blue | exact peak blue {} |",
        peak(&exact)
    );
    let mut rows = Vec::new();
    for level in [6u32, 12, 24, 48, 96] {
        let g = phong_sphere("gouraud", level);
        let p = phong_sphere("phong", level);
        let (eg, ep) = (
            image_error(&exact, &g).expect("sizes match"),
            image_error(&exact, &p).expect("sizes match"),
        );
        println!(
            "| {level} | {:.2} | {} | {:.2} | {} |",
            eg.rmse,
            peak(&g),
            ep.rmse,
            peak(&p)
        );
        rows.push((level, eg.rmse, peak(&g), ep.rmse, peak(&p)));
    }
    // Per-pixel Phong keeps the highlight at every level; Gouraud loses it on coarse meshes
    // (the highlight falls between vertices) and only recovers it as the mesh gets fine.
    for &(level, eg, pg, ep, pp) in &rows {
        assert!(pp >= peak(&exact) - 10, "Phong keeps the highlight at level {level}");
        assert!(eg > ep, "Gouraud is less accurate than Phong at level {level}");
        if level <= 12 {
            assert!(
                pg + 40 < peak(&exact),
                "Gouraud loses the highlight at level {level}: {pg}"
            );
        }
    }
    assert!(rows[0].1 > 2.0 * rows[4].1, "Gouraud error must fall with tessellation");
}

#[test]
fn normal_matrix_under_non_uniform_scale() {
    let scale = Vec3::new(1.0, 0.35, 1.0);
    let m = Mat3::from_diagonal(scale);
    // Exact: normals of the scaled sphere (an ellipsoid) transform by the inverse transpose.
    let mesh = shaderlab::mesh::Mesh::sphere(1.0, 24, 24);
    let (mut worst, mut sum) = (0.0f32, 0.0f32);
    for v in &mesh.vertices {
        let n = Vec3::from(v.normal);
        let right = (m.inverse().transpose() * n).normalize();
        let naive = (m * n).normalize();
        let angle = right.dot(naive).clamp(-1.0, 1.0).acos().to_degrees();
        worst = worst.max(angle);
        sum += angle;
    }
    let mean = sum / mesh.vertices.len() as f32;
    println!("normals of a sphere scaled (1, 0.35, 1): modelview instead of inverse transpose errs by {mean:.1} deg on average, {worst:.1} deg at worst");
    assert!(worst > 30.0, "the naive matrix must be badly wrong under this scale");
    // In the image: the true normals of the flattened sphere point up and down far more (green).
    let render = |naive: bool| {
        let mut lab = lab(course::NORMAL_RGB);
        lab.set_object(Object::Sphere);
        lab.set("scale", &scale.to_array()).expect("scale");
        lab.set("naive_nm", &[if naive { 1.0 } else { 0.0 }]).expect("naive_nm");
        lab.rgb(640, 360)
    };
    let (right, naive) = (render(false), render(true));
    let green = |img: &RgbImage| shaderlab::metrics::mean_color(img, (300, 145, 340, 165), None)[1];
    println!(
        "mean green just above the centre: inverse transpose {:.0}, modelview {:.0}; PSNR between them {:.1} dB",
        green(&right),
        green(&naive),
        psnr(&right, &naive).expect("size")
    );
    assert!(green(&right) > green(&naive) + 30.0);
    // Uniform transforms (the labs' rotations) are unaffected: the port uses the inverse transpose anyway.
    let r = shaderlab::camera::lab_rotation(Vec3::new(30.0, 45.0, 10.0));
    let nm = shaderlab::camera::normal_matrix(r);
    assert!((nm - Mat3::from_mat4(r)).abs_diff_eq(Mat3::ZERO, 1e-5));
}

/// The course's phong.frag without the port's guards, to show where the original fails.
const ORIGINAL_PHONG_FRAG: &str = r#"#version 450
#include "phong_params.glsl"
layout(location = 0) in vec3 N;
layout(location = 1) in vec3 v;
layout(location = 0) out vec4 frag_color;
void main() {
    vec3 L = normalize(lightPosition.xyz - v);
    vec3 E = normalize(-v);
    vec3 R = normalize(-reflect(L, N));
    vec4 Iamb = vec4(ambientColor, 1.0);
    vec4 Idiff = vec4(diffuseColor * max(dot(N, L), 0.0), 1.0);
    vec4 Ispec = vec4(specularColor * pow(max(dot(R, E), 0.0), shininess), 1.0);
    frag_color = Ka * Iamb + Kd * Idiff + Ks * Ispec;
}
"#;

/// `--set`-style parameters: (uniform name, values).
type Settings<'a> = &'a [(&'a str, &'a [f32])];

fn non_finite(pixels: &[[f32; 4]]) -> usize {
    pixels.iter().filter(|p| p.iter().any(|c| !c.is_finite())).count()
}

#[test]
fn degenerate_inputs_never_reach_the_image_as_nan() {
    let dir = output_dir().join("original_phong_shaders");
    std::fs::create_dir_all(&dir).expect("temp dir");
    for name in shaderlab::shader::embedded_names() {
        let text = shaderlab::shader::embedded_source(name).expect("embedded");
        std::fs::write(dir.join(name), text).expect("write");
    }
    std::fs::write(dir.join("phong.frag"), ORIGINAL_PHONG_FRAG).expect("write");
    let cases: &[(&str, Settings)] = &[
        ("shininess 0 (pow(0, 0))", &[("shininess", &[0.0])]),
        ("shininess 0.5", &[("shininess", &[0.5])]),
        ("shininess -1 (pow(0, -1))", &[("shininess", &[-1.0])]),
        ("light on the surface (L = 0)", &[("lightPosition", &[0.0, 0.0, -4.0])]),
        (
            "coefficients outside [0,1]",
            &[("Ka", &[-2.0]), ("Kd", &[7.5]), ("Ks", &[-1.0])],
        ),
        ("huge coefficients", &[("Kd", &[3.0e38]), ("Ks", &[3.0e38])]),
    ];
    for (what, set) in cases {
        for (label, source) in [
            ("original", ShaderSource::Dir(dir.clone())),
            ("port", ShaderSource::Embedded),
        ] {
            let mut lab = lab_with(course::PHONG, &source, wgpu::TextureFormat::Rgba32Float);
            lab.set_object(Object::Sphere);
            for (n, v) in *set {
                lab.set(n, v).expect("set");
            }
            let pixels = lab.render_f32(320, 180).expect("render");
            let bad = non_finite(&pixels);
            println!("{what}: {label}: {bad} NaN/inf pixels of {}", pixels.len());
            if label == "port" {
                assert_eq!(bad, 0, "{what}: the port must never output NaN or infinity");
                assert!(pixels.iter().all(|p| p.iter().all(|c| (0.0..=1.0).contains(c))));
            } else if what.starts_with("huge") {
                // Kd * diffuse + Ks * specular overflows f32: infinity reaches the framebuffer.
                assert!(bad > 1000, "the original's sum must overflow to infinity");
            } else if what.starts_with("shininess -1") {
                // pow(x, -1) near the terminator: unbounded values (hundreds) in the original.
                let max = pixels.iter().flat_map(|p| p.iter()).cloned().fold(0.0f32, f32::max);
                println!("  original's largest output with shininess -1: {max}");
                assert!(max > 100.0);
            }
        }
    }
    // Every exercise on every object, including the teapot's degenerate poles: all finite.
    for entry in [
        course::POSITION_RGB,
        course::NORMAL_RGB,
        course::PHONG,
        course::NOISE,
        course::DISPLACEMENT,
    ] {
        let mut lab = lab_with(entry, &ShaderSource::Embedded, wgpu::TextureFormat::Rgba32Float);
        for object in Object::ALL {
            lab.set_object(object);
            lab.set_time(3.0);
            let pixels = lab.render_f32(320, 180).expect("render");
            assert_eq!(non_finite(&pixels), 0, "{} on {object:?}", entry.info.name);
        }
    }
}

#[test]
fn displacement_cracks_and_the_smooth_variant() {
    use shaderlab::noise::max_crack;
    use shaderlab::tess::pixels_per_unit;
    println!("| object | crack, original (object units) | in pixels | crack, smooth=1 |");
    for object in [Object::Cube, Object::Teapot, Object::Sphere] {
        let mesh = object.mesh();
        let welded = mesh.welded();
        let (open, closed) = (max_crack(&mesh, 0.0, 0.5), max_crack(&welded, 0.0, 0.5));
        let px = open as f64 * pixels_per_unit(object, 4.0, 360);
        println!("| {} | {open:.3} | {px:.1} | {closed:.3} |", object.name());
        assert_eq!(closed, 0.0, "welded meshes never crack");
        if object != Object::Sphere {
            assert!(open > 0.05, "{object:?}: GLUT's split normals crack open");
        }
    }
    // The smooth variant renders, and differs from the cracked one where the cracks were (at
    // t = 1 the cube's faces are lit and the original shows dark gaps between them).
    let render = |smooth: f32| {
        render(
            course::DISPLACEMENT,
            Object::Cube,
            [30.0, 45.0, 0.0],
            1.0,
            &[("smooth", &[smooth])],
        )
    };
    let (cracked, smooth) = (render(0.0), render(1.0));
    let p = psnr(&cracked, &smooth).expect("size");
    println!("cube at t = 1, cracked vs smooth: PSNR {p:.1} dB");
    assert!(p < 30.0);
}
