//! Adaptive tessellation against the exact reference: the level `--tess auto` picks keeps the
//! silhouette error within its budget (half a pixel), and the next coarser level does not.
//! Silhouettes are measured at 4x4 supersampling so that pixel-centre sampling does not hide
//! the error; distances are reported in pixels of the real (1x) image.

mod common;

use common::*;
use glam::Vec3;
use shaderlab::course;
use shaderlab::course::seed000::geometry::{GeometryConfig, GlutGeometry, PARAMS_000};
use shaderlab::exact::{silhouette_error, ExactScene, Shape};
use shaderlab::metrics::mask;
use shaderlab::params::Params;
use shaderlab::Object;

const SS: u32 = 4;

fn measured_error(object: Object, shape: Shape, level: u32, angles: [f32; 3], camera: [f32; 3]) -> f64 {
    let (w, h) = (640 * SS, 360 * SS);
    let mut lab = lab(course::PHONG);
    lab.set_object(object);
    lab.set_angles(angles);
    lab.set("camera", &camera).expect("camera");
    lab.set("tess", &[level as f32]).expect("tess");
    let image = shaderlab::offscreen::to_rgb(&lab.screenshot(gpu(), w, h).expect("render"));
    let rendered = mask(&image, [13, 26, 51], 0);
    let exact = ExactScene {
        shape,
        angles: angles.map(f64::from),
        camera: camera.map(f64::from),
        ..Default::default()
    };
    silhouette_error(&exact, &rendered, w, h).expect("sizes match").max_px / SS as f64
}

/// The views of the sweep: the predicted error bounds the silhouette error over all views, and
/// which facets a silhouette crosses depends on the view, so the worst case needs several views.
/// Rotations step through a fraction of one facet so that some silhouette crosses facet centres.
fn views(level: u32) -> Vec<[f32; 3]> {
    let facet = 360.0 / level as f32;
    let mut v = Vec::new();
    for x in [0.0f32, 35.0, 70.0] {
        for k in 0..4 {
            v.push([x, k as f32 * facet / 4.0, 0.0]);
        }
    }
    v
}

fn worst(object: Object, shape: Shape, level: u32, camera: [f32; 3]) -> (f64, f64) {
    let errors: Vec<f64> = views(level)
        .into_iter()
        .map(|a| measured_error(object, shape, level, a, camera))
        .collect();
    (
        errors.iter().cloned().fold(0.0, f64::max),
        errors.iter().cloned().fold(f64::INFINITY, f64::min),
    )
}

/// Distances are chosen where the level step is clear of the budget on both sides (predicted
/// 0.48 and 0.54 px for the sphere at 17, 0.49 and 0.53 for the torus at 12): the measurement at
/// 4x4 supersampling over 12 views comes within about 2% of the bound, so a closer call would
/// test the sampling rather than the predictor.
fn check(object: Object, shape: Shape, camera: [f32; 3]) {
    let level = auto_level(object, camera, 360, -1.0);
    let distance = Vec3::from_array(camera).length() as f64;
    let (chosen, chosen_best) = worst(object, shape, level, camera);
    let (coarser, coarser_best) = worst(object, shape, level - 1, camera);
    println!(
        "{} at distance {distance:.1}: auto level {level} (predicted {:.3} px): silhouette error over {} views {chosen_best:.3}..{chosen:.3} px; level {} (predicted {:.3}): {coarser_best:.3}..{coarser:.3} px",
        object.name(),
        shaderlab::tess::silhouette_error_px(object, level, distance, 360),
        views(level).len(),
        level - 1,
        shaderlab::tess::silhouette_error_px(object, level - 1, distance, 360),
    );
    assert!(
        chosen <= 0.5,
        "{object:?}: chosen level {level} has error {chosen:.3} px > 0.5"
    );
    assert!(
        coarser > 0.5,
        "{object:?}: level {} meets the budget in every view ({coarser:.3} px)",
        level - 1
    );
}

#[test]
fn auto_sphere_meets_the_budget_minimally() {
    check(Object::Sphere, Shape::Sphere, [0.0, 0.0, 17.0]);
}

#[test]
fn auto_torus_meets_the_budget_minimally() {
    check(Object::Torus, Shape::Torus, [0.0, 0.0, 12.0]);
}

/// The level the phong lab's geometry draws for `object` seen from `camera` (`tess` -1 is auto).
fn auto_level(object: Object, camera: [f32; 3], height: u32, tess: f64) -> u32 {
    let mut p = Params::new(PARAMS_000);
    p.set_str("object", object.name()).expect("object");
    p.set("tess", &[tess]).expect("tess");
    let geometry = GlutGeometry::new(
        gpu(),
        "test",
        GeometryConfig {
            perspective: (45.0, 1.0, 100.0),
            eye: Vec3::from_array(camera),
        },
    );
    geometry.level(&p, height, true)
}

#[test]
fn auto_level_follows_the_view() {
    let near = auto_level(Object::Sphere, [0.0, 0.0, 5.0], 360, -1.0);
    let far = auto_level(Object::Sphere, [0.0, 0.0, 20.0], 360, -1.0);
    assert!(far < near, "a farther sphere needs fewer triangles: {near} -> {far}");
    assert!(
        auto_level(Object::Sphere, [0.0, 0.0, 20.0], 1440, -1.0) > far,
        "a bigger window needs more"
    );
    // The GLUT default is what the original draws.
    assert_eq!(auto_level(Object::Sphere, [0.0, 0.0, 20.0], 360, 0.0), 24);
}
