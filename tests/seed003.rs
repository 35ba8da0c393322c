//! Seed 003, LETI lab report 5 (SPEC §3): `specular_strip`, the Bézier strip with specular
//! light seen through the report's fly camera. Its first state against the reference image of
//! the original GL program, the camera states, keys and mouse, and the course's quirks.

mod common;

use common::{build, seed_reference as reference, shot};
use glam::Vec3;
use image::RgbImage;
use shaderlab::camera::fly::{FlyCamera, FlyStart};
use shaderlab::course;
use shaderlab::lab::{Input, Special};
use shaderlab::mesh::shapes::bezier_strip;
use shaderlab::metrics::{bounding_box, coverage, mean_color, psnr};
use shaderlab::Lab;

const BLACK: [u8; 3] = [0, 0, 0];

/// Renders the strip at its default size with `key=value` parameters (as `--set` does).
fn render(set: &[(&str, &str)]) -> RgbImage {
    let mut lab = build(course::SPECULAR_STRIP);
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

fn covered(image: &RgbImage) -> usize {
    image.pixels().filter(|p| p.0 != BLACK).count()
}

fn same(a: &RgbImage, b: &RgbImage) -> bool {
    psnr(a, b) == Some(f64::INFINITY)
}

/// Feeds inputs to a lab, each of which must change something.
fn feed(lab: &mut dyn Lab, inputs: &[Input]) {
    for &input in inputs {
        assert!(lab.input(input), "{input:?} must change something");
    }
}

/// Where a strip vertex lands in the 640x480 picture for a camera.
fn project(camera: &FlyCamera, vertex: usize) -> (f32, f32) {
    let strip = bezier_strip();
    let p = camera.projection(640.0 / 480.0) * camera.view() * Vec3::from_array(strip[vertex].position).extend(1.0);
    ((p.x / p.w + 1.0) * 320.0, (1.0 - p.y / p.w) * 240.0)
}

#[test]
fn vertex_201_zero_normal_shows_no_stray_pixel() {
    // Vertex 201 keeps the normal (0, 0, 0) (SPEC §6.3 #2): normalize() of it is NaN, but only
    // exactly at the vertex; the fragments of the last triangle around it interpolate a
    // non-zero normal and are lit like their neighbours, as in the reference.
    let strip = bezier_strip();
    assert_eq!(strip[201].normal, [0.0; 3]);
    let image = render(&[]);
    let (x, y) = project(&FlyCamera::from_start(&FlyStart::default()), 201);
    assert!((x - 525.19).abs() < 0.05 && (y - 308.43).abs() < 0.05, "({x}, {y})");
    let reference = reference("003_specular_strip_default.png");
    let (xi, yi) = (x as u32, y as u32);
    let mut lit = 0;
    for yy in yi - 4..=yi + 4 {
        for xx in xi - 4..=xi + 4 {
            let (p, r) = (image.get_pixel(xx, yy).0, reference.get_pixel(xx, yy).0);
            assert_eq!(p, r, "pixel ({xx}, {yy})");
            if p != BLACK {
                assert!(p[0] >= 90 && p[1] >= 90 && p[2] == 0, "({xx}, {yy}): {p:?}");
                lit += 1;
            }
        }
    }
    assert!(lit >= 5, "the corner is drawn: {lit} pixels");
}

#[test]
fn front_preset_is_the_constructor_camera() {
    let front = render(&[("preset", "1")]);
    // pos (0, 0, 3) looking down −z: x(t) = 0.75(2t − 1) spans ±0.75 about the axis, so the
    // strip is centred horizontally (its near edge, z = +0.5, is the widest).
    let (x0, y0, x1, _) = bounding_box(&front, BLACK).expect("visible");
    let (centre, width) = ((x0 + x1) as f64 / 2.0, (x1 - x0 + 1) as f64);
    let half = 0.75 / 2.5 / (22.5f64).to_radians().tan() * 240.0;
    assert!((centre - 319.5).abs() <= 1.5, "centre {centre}");
    assert!(
        (width / 2.0 - half).abs() <= 2.0,
        "half width {} vs {half:.1}",
        width / 2.0
    );
    // The strip lies below the eye (y from −0.62 to −0.3): all of it in the lower half.
    assert!(y0 > 240, "{y0}");
    assert!(!same(&front, &render(&[])));
}

#[test]
fn moving_forward_grows_the_strip() {
    let default = render(&[]);
    let (a0, a1, a2) = (
        covered(&default),
        covered(&render(&[("forward", "1")])),
        covered(&render(&[("forward", "2")])),
    );
    println!("covered: forward 0 {a0}, 1 {a1}, 2 {a2}");
    assert!(
        a1 as f64 > a0 as f64 * 1.2 && a2 as f64 > a1 as f64 * 1.2,
        "{a0} {a1} {a2}"
    );
    let back = covered(&render(&[("forward", "-2")]));
    assert!((back as f64) < a0 as f64 * 0.8, "{back} vs {a0}");
    // "closer": forward=3 yaw=-10 (the moves go along the front before the turn, which swings
    // the view left, past the strip's left end).
    let closer = render(&[("forward", "3"), ("yaw", "-10")]);
    assert!(covered(&closer) > a0, "{}", covered(&closer));
    // Moving up and looking down ("above") shows the strip from above: its lit top face, and
    // the whole strip below the horizon line.
    let above = render(&[("up", "2"), ("pitch", "-30")]);
    let (_, y0, _, y1) = bounding_box(&above, BLACK).expect("visible");
    let (_, d0, _, d1) = bounding_box(&default, BLACK).unwrap();
    assert!(
        y1 - y0 > d1 - d0,
        "seen from above the strip looks deeper: {} vs {}",
        y1 - y0,
        d1 - d0
    );
}

#[test]
fn pitch_stops_at_89_degrees() {
    // From the constructor camera 3 up (or down) and 6 forward: straight over (under) the
    // strip's centre, looking down (up) at it.
    let over = [("preset", "1"), ("up", "3"), ("forward", "6")];
    let under = [("preset", "1"), ("up", "-6"), ("forward", "6")];
    let at = |base: &[(&'static str, &'static str)], pitch: &'static str| {
        let mut set = base.to_vec();
        set.push(("pitch", pitch));
        render(&set)
    };
    let down89 = at(&over, "-89");
    assert!(covered(&down89) > 50_000, "the strip is seen from above");
    assert!(same(&down89, &at(&over, "-150")));
    assert!(same(&down89, &at(&over, "-400")));
    assert!(!same(&down89, &at(&over, "-80")), "below the clamp the pitch counts");
    let up89 = at(&under, "89");
    assert!(covered(&up89) > 50_000, "the strip is seen from below");
    assert!(same(&up89, &at(&under, "120")));
    assert!(!same(&up89, &at(&under, "80")));
    // Keys: ↑ 60 times (2° each) ends at 89°, the same picture as the state.
    let mut lab = build(course::SPECULAR_STRIP);
    for (k, v) in under {
        lab.params_mut().set_str(k, v).unwrap();
    }
    feed(lab.as_mut(), &[Input::Special(Special::Up); 60]);
    assert!(same(&shot(lab.as_mut()), &up89));
    assert!(lab.title().contains("pitch 89.0"), "{}", lab.title());
}

#[test]
fn keys_and_mouse_drive_the_live_camera() {
    // W W W ← is forward=3 yaw=-2; E E then ↓ × 15 is "above" (up=2 pitch=-30).
    let mut lab = build(course::SPECULAR_STRIP);
    let title = lab.title();
    feed(
        lab.as_mut(),
        &[
            Input::Key('w'),
            Input::Key('W'),
            Input::Key('w'),
            Input::Special(Special::Left),
        ],
    );
    assert!(same(&shot(lab.as_mut()), &render(&[("forward", "3"), ("yaw", "-2")])));
    assert_ne!(lab.title(), title, "the title shows the moved camera");
    assert!(
        lab.params().f64("forward") == 0.0,
        "keys move the camera, not the parameters"
    );
    feed(lab.as_mut(), &[Input::Key('r')]);
    assert_eq!(lab.title(), title);
    feed(lab.as_mut(), &[Input::Key('e'), Input::Key('E')]);
    feed(lab.as_mut(), &[Input::Special(Special::Down); 15]);
    assert!(same(&shot(lab.as_mut()), &render(&[("up", "2"), ("pitch", "-30")])));
    // S, A, Q undo W, D, E.
    let before = shot(lab.as_mut());
    feed(lab.as_mut(), &[Input::Key('w'), Input::Key('d'), Input::Key('e')]);
    assert!(!same(&shot(lab.as_mut()), &before));
    feed(lab.as_mut(), &[Input::Key('s'), Input::Key('a'), Input::Key('q')]);
    assert!(psnr(&shot(lab.as_mut()), &before).unwrap() > 45.0);
    // Left drag: rotate(0.1·dx, −0.1·dy) per event; 10 px right is yaw +1°, 20 px up pitch +2°.
    let mut lab = build(course::SPECULAR_STRIP);
    assert!(!lab.input(Input::Press(100, 100)));
    feed(lab.as_mut(), &[Input::Drag(110, 100)]);
    assert!(!lab.input(Input::Drag(110, 100)), "no motion, no change");
    feed(lab.as_mut(), &[Input::Drag(110, 80)]);
    assert!(same(&shot(lab.as_mut()), &render(&[("yaw", "1"), ("pitch", "2")])));
    // A state parameter set afterwards puts the camera into the state it names.
    lab.params_mut().set_str("yaw", "5").unwrap();
    assert!(same(&shot(lab.as_mut()), &render(&[("yaw", "5")])));
}

#[test]
fn light_position_moves_the_lighting() {
    let default = render(&[]);
    // The light under the strip (normals ≈ +y): no diffuse, no specular, ambient 0.1 only.
    let below = render(&[("lighty", "-5")]);
    let colours: std::collections::BTreeSet<[u8; 3]> = below.pixels().map(|p| p.0).filter(|&p| p != BLACK).collect();
    println!("light below: {colours:?}");
    assert!(
        colours.iter().all(|p| matches!(p, [25 | 26, 25 | 26, 0])),
        "{colours:?}"
    );
    // High above, straight over the strip: brighter than the default light at the origin.
    let above = render(&[("lighty", "5")]);
    let mean = |i: &RgbImage| mean_color(i, (0, 0, 639, 479), Some(BLACK))[0];
    assert!(mean(&above) > mean(&default), "{} vs {}", mean(&above), mean(&default));
    let side = render(&[("lightx", "3"), ("lightz", "-2")]);
    assert!(!same(&side, &default));
    assert_eq!(coverage(&side, BLACK), coverage(&default, BLACK));
}

/// `segments` (port addition): the course's float loop is `segments=100`; other counts step t
/// exactly from 0 to 1; the picture converges on a finely tessellated strip, and `auto` picks
/// a count from the curve's bend and the camera (more when the camera comes closer).
#[test]
fn strip_segments_converge_and_auto_follows_the_camera() {
    use shaderlab::mesh::shapes::{bezier_point, bezier_strip_n};
    let exact = bezier_strip_n(10);
    assert_eq!(exact.len(), 22);
    let [x, y] = bezier_point(1.0);
    assert_eq!(&exact[20].position[..2], &[x, y], "the last step ends at t = 1");
    let at = |segments: &str, forward: &str| {
        let mut lab = build(course::SPECULAR_STRIP);
        lab.params_mut().set_str("segments", segments).unwrap();
        lab.params_mut().set_str("forward", forward).unwrap();
        let image = shot(lab.as_mut());
        (image, lab.title())
    };
    let (course, _) = at("100", "0");
    assert_eq!(
        course,
        shot(build(course::SPECULAR_STRIP).as_mut()),
        "segments=100 is the course's strip"
    );
    let (reference, _) = at("2000", "0");
    let off = |a: &RgbImage| shaderlab::metrics::pixels_off(a, &reference, 25).expect("same size");
    let (coarse, _) = at("8", "0");
    let (auto, title) = at("auto", "0");
    println!(
        "px off the 2000-segment strip: 8: {}; course 100: {}; auto: {} ({title})",
        off(&coarse),
        off(&course),
        off(&auto)
    );
    // Measured: 3208, 263, 178 (auto 146).
    assert!(off(&coarse) > 5 * off(&course));
    assert!(
        off(&auto) <= off(&course),
        "auto is at least as close as the course's 100"
    );
    assert!(title.contains("segments auto: "), "{title}");
    let count = |t: &str| -> u32 {
        t.split("segments auto: ")
            .nth(1)
            .and_then(|s| s.split(|c: char| !c.is_ascii_digit()).next())
            .and_then(|s| s.parse().ok())
            .unwrap()
    };
    let (_, closer) = at("auto", "4");
    assert!(count(&closer) >= count(&title), "{closer} vs {title}");
    // One lab whose camera and picture height change: auto's choice is cached by eye position,
    // field of view and height, and must follow each. At most eyes the normal's turn sets it
    // (146 at any height); one step down and four forward put the eye beside the strip's edge, where
    // a 4800-pixel-tall picture needs 162 for its chords: a cache that missed the eye or the
    // height would keep 146 there.
    let tall = |lab: &mut dyn Lab| {
        shaderlab::shell::screenshot(common::gpu(), lab, 64, 4800).expect("a tall screenshot");
        count(&lab.title())
    };
    let mut lab = build(course::SPECULAR_STRIP);
    lab.params_mut().set_str("segments", "auto").unwrap();
    shot(lab.as_mut());
    let far = lab.title();
    shot(lab.as_mut());
    assert_eq!(lab.title(), far, "the same state keeps its choice");
    assert_eq!(
        tall(lab.as_mut()),
        146,
        "at the start eye the turn bound decides at any height"
    );
    lab.params_mut().set_str("up", "-1").unwrap();
    lab.params_mut().set_str("forward", "4").unwrap();
    assert_eq!(tall(lab.as_mut()), 162, "the eye moved: the choice follows it");
    shot(lab.as_mut());
    assert_eq!(
        count(&lab.title()),
        146,
        "back to 480 rows: the choice follows the height"
    );
    assert_eq!(tall(lab.as_mut()), 162, "and back to 4800");
}
