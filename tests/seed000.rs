//! Pixel statistics that a wrong port would break, for every exercise: coverage, mean colour of
//! regions, the highlight's position and how parameters move it, symmetry, noise statistics and
//! how time changes them, displacement growing the silhouette, the light marker.

mod common;

use common::*;
use image::RgbImage;
use shaderlab::course;
use shaderlab::metrics::{bounding_box, coverage, highlight, luma_stats, mask, mean_color, psnr};
use shaderlab::Object;

const BLACK: [u8; 3] = [0, 0, 0];
/// glClearColor(0.05, 0.1, 0.2) as 8-bit.
const PHONG_BG: [u8; 3] = [13, 26, 51];

fn mirrored(image: &RgbImage) -> RgbImage {
    image::imageops::flip_horizontal(image)
}

/// The projected radius in pixels of a unit sphere at distance d (gluPerspective 45°, 360 rows).
fn sphere_radius_px(d: f64) -> f64 {
    180.0 / (22.5f64).to_radians().tan() / (d * d - 1.0).sqrt()
}

#[test]
fn position_rgb_maps_z_y_x_to_red_green_blue() {
    let cube = render(course::POSITION_RGB, Object::Cube, [0.0; 3], 0.0, &[]);
    // The front face is z = +0.75: colour = normalize(z, y, x, 1) + 0.5 — red above 0.5 everywhere,
    // blue growing to the right (x), green growing upwards (y).
    let left = mean_color(&cube, (250, 150, 300, 210), Some(BLACK));
    let right = mean_color(&cube, (340, 150, 390, 210), Some(BLACK));
    let top = mean_color(&cube, (295, 110, 345, 160), Some(BLACK));
    let bottom = mean_color(&cube, (295, 200, 345, 250), Some(BLACK));
    assert!(
        right[2] > left[2] + 40.0,
        "blue must follow x: left {left:?} right {right:?}"
    );
    assert!(
        top[1] > bottom[1] + 40.0,
        "green must follow y: top {top:?} bottom {bottom:?}"
    );
    assert!(
        left[0] > 200.0 && right[0] > 200.0,
        "red must be high on the z = +0.75 face: {left:?} {right:?}"
    );
    // Turned around (yAngle 180) the visible face is z = -0.75: red drops.
    let back = render(course::POSITION_RGB, Object::Cube, [0.0, 180.0, 0.0], 0.0, &[]);
    let back_mid = mean_color(&back, (300, 160, 340, 200), Some(BLACK));
    assert!(back_mid[0] < 110.0, "the back face must be darker red: {back_mid:?}");
    // The cube, seen face on, is a square: glutSolidCube(1.5) at distance 4 - 0.75.
    let (x0, y0, x1, y1) = bounding_box(&cube, BLACK).expect("cube visible");
    let side = 0.75 / 3.25 * 180.0 / (22.5f64).to_radians().tan() * 2.0;
    assert!(
        ((x1 - x0 + 1) as f64 - side).abs() <= 2.0,
        "cube width {} vs {side:.1}",
        x1 - x0 + 1
    );
    assert!(
        ((y1 - y0 + 1) as f64 - side).abs() <= 2.0,
        "cube height {} vs {side:.1}",
        y1 - y0 + 1
    );
}

#[test]
fn normal_rgb_shows_eye_space_normals() {
    let sphere = render(course::NORMAL_RGB, Object::Sphere, [0.0; 3], 0.0, &[]);
    let r = sphere_radius_px(4.0) as u32;
    let right = mean_color(&sphere, (320 + r - 20, 170, 320 + r - 5, 190), None);
    let left = mean_color(&sphere, (320 - r + 5, 170, 320 - r + 20, 190), None);
    let top = mean_color(&sphere, (310, 180 - r + 5, 330, 180 - r + 20), None);
    let centre = mean_color(&sphere, (315, 175, 325, 185), None);
    assert!(
        right[0] > 180.0 && left[0] < 5.0,
        "red = +x normals: left {left:?} right {right:?}"
    );
    assert!(top[1] > 180.0 && top[0] < 10.0, "green = +y normals: {top:?}");
    assert!(
        centre[2] > 245.0 && centre[0] < 15.0 && centre[1] < 15.0,
        "blue = towards the eye: {centre:?}"
    );
    // Rotating the sphere must not change a sphere's normal image much (eye-space normals).
    let turned = render(course::NORMAL_RGB, Object::Sphere, [0.0, 90.0, 0.0], 0.0, &[]);
    assert!(psnr(&sphere, &turned).expect("size") > 25.0);
}

#[test]
fn phong_sphere_highlight_follows_the_light() {
    let base = render(course::PHONG, Object::Sphere, [0.0; 3], 0.0, &[]);
    // Coverage: a unit sphere at distance 5.
    let r = sphere_radius_px(5.0);
    let expected = std::f64::consts::PI * r * r / (640.0 * 360.0);
    let cov = coverage(&base, PHONG_BG);
    assert!(
        (cov - expected).abs() < 0.01 * expected + 0.002,
        "coverage {cov:.4} vs {expected:.4}"
    );
    // With the light at (0,1,1) the highlight sits above the centre, on the vertical axis.
    let (hx, hy) = highlight(&base, 2.0);
    assert!(
        (hx - 319.5).abs() < 3.0 && hy < 175.0 && hy > 180.0 - r,
        "highlight at ({hx:.1}, {hy:.1})"
    );
    // The scene is left-right symmetric.
    assert!(
        psnr(&base, &mirrored(&base)).expect("size") > 35.0,
        "sphere must be mirror-symmetric"
    );
    // Moving the light right moves the highlight right; up moves it up.
    let right = render(
        course::PHONG,
        Object::Sphere,
        [0.0; 3],
        0.0,
        &[("lightPosition", &[2.0, 1.0, 1.0])],
    );
    let (rx, _) = highlight(&right, 2.0);
    assert!(rx > hx + 10.0, "highlight must move right: {hx:.1} -> {rx:.1}");
    let down = render(
        course::PHONG,
        Object::Sphere,
        [0.0; 3],
        0.0,
        &[("lightPosition", &[0.0, -1.0, 1.0])],
    );
    let (_, dy) = highlight(&down, 2.0);
    assert!(dy > hy + 10.0, "highlight must move down: {hy:.1} -> {dy:.1}");
    // The object's colour is orange: red > green > blue in the lit region.
    let lit = mean_color(&base, (300, 150, 340, 200), Some(PHONG_BG));
    assert!(lit[0] > lit[1] && lit[1] > lit[2], "orange expected: {lit:?}");
}

#[test]
fn phong_coefficients_move_the_image() {
    let white_area = |img: &RgbImage| img.pixels().filter(|p| p[2] > 200).count();
    let base = render(course::PHONG, Object::Sphere, [0.0; 3], 0.0, &[]);
    let sharp = render(course::PHONG, Object::Sphere, [0.0; 3], 0.0, &[("shininess", &[128.0])]);
    assert!(
        white_area(&sharp) * 2 < white_area(&base),
        "higher shininess must shrink the highlight"
    );
    let no_spec = render(course::PHONG, Object::Sphere, [0.0; 3], 0.0, &[("Ks", &[0.0])]);
    assert_eq!(white_area(&no_spec), 0, "Ks = 0 removes the white highlight");
    let dim = render(course::PHONG, Object::Sphere, [0.0; 3], 0.0, &[("Kd", &[0.5])]);
    let side = (250, 200, 280, 230);
    assert!(mean_color(&dim, side, Some(PHONG_BG))[0] < mean_color(&base, side, Some(PHONG_BG))[0] - 20.0);
    let green = render(
        course::PHONG,
        Object::Sphere,
        [0.0; 3],
        0.0,
        &[("diffuseColor", &[0.0, 1.0, 0.0])],
    );
    let g = mean_color(&green, side, Some(PHONG_BG));
    assert!(
        g[1] > g[0] + 50.0,
        "a green diffuse colour must turn the sphere green: {g:?}"
    );
    // Ambient only: a flat colour Ka * ambientColor (0.1 * 0.1 -> 3/255) on the dark side.
    let flat = render(
        course::PHONG,
        Object::Sphere,
        [0.0; 3],
        0.0,
        &[
            ("Kd", &[0.0]),
            ("Ks", &[0.0]),
            ("Ka", &[1.0]),
            ("ambientColor", &[0.5, 0.5, 0.5]),
        ],
    );
    let c = mean_color(&flat, (300, 160, 340, 200), None);
    assert!(c.iter().all(|v| (v - 127.5).abs() < 1.5), "ambient only: {c:?}");
}

#[test]
fn phong_light_marker_appears_in_front_of_the_camera() {
    // Default light (0,1,1) is behind the eye: no marker. At (1.2, 0.8, -2.5) it projects to about
    // (528.6, 41.0) with a radius of about 8 pixels.
    let base = render(course::PHONG, Object::Sphere, [0.0; 3], 0.0, &[]);
    assert_eq!(base.get_pixel(528, 41).0, PHONG_BG);
    let moved = render(
        course::PHONG,
        Object::Sphere,
        [0.0; 3],
        0.0,
        &[("lightPosition", &[1.2, 0.8, -2.5])],
    );
    assert_eq!(moved.get_pixel(528, 41).0, [255, 255, 255], "white marker at the light");
    let white = moved
        .enumerate_pixels()
        .filter(|(x, y, p)| *x > 500 && *y < 80 && p.0 == [255, 255, 255])
        .count();
    assert!((60..400).contains(&white), "marker size {white} pixels");
}

#[test]
fn phong_camera_moves_the_view() {
    let base = render(course::PHONG, Object::Sphere, [0.0; 3], 0.0, &[]);
    let closer = render(
        course::PHONG,
        Object::Sphere,
        [0.0; 3],
        0.0,
        &[("camera", &[0.0, 0.0, 3.0])],
    );
    assert!(
        coverage(&closer, PHONG_BG) > 2.0 * coverage(&base, PHONG_BG),
        "a closer camera makes the sphere bigger"
    );
    let left = render(
        course::PHONG,
        Object::Sphere,
        [0.0; 3],
        0.0,
        &[("camera", &[-1.0, 0.0, 5.0])],
    );
    let (x0, _, x1, _) = bounding_box(&left, PHONG_BG).expect("visible");
    assert!((x0 + x1) / 2 > 330, "moving the camera left moves the sphere right");
}

#[test]
fn noise_statistics_and_time() {
    let t0 = render(course::NOISE, Object::Sphere, [0.0; 3], 0.0, &[]);
    let m = mask(&t0, BLACK, 0);
    let (mean, var) = luma_stats(&t0, &m);
    // |snoise| over a surface: mean around 0.2-0.35, clearly varying.
    assert!(
        (0.1..0.45).contains(&mean) && var > 0.01,
        "noise mean {mean:.3} variance {var:.4}"
    );
    // Grey: shade (1,1,1) gives r = g = b.
    assert!(t0.pixels().all(|p| p[0] == p[1] && p[1] == p[2]));
    // Time moves the pattern but keeps its statistics.
    let t1 = render(course::NOISE, Object::Sphere, [0.0; 3], 0.5, &[]);
    let (mean1, var1) = luma_stats(&t1, &mask(&t1, BLACK, 0));
    assert!(psnr(&t0, &t1).expect("size") < 25.0, "time must change the pattern");
    assert!((mean1 - mean).abs() < 0.1 && var1 > 0.01);
    // Shade (1,0,0) keeps only red.
    let red = render(
        course::NOISE,
        Object::Sphere,
        [0.0; 3],
        0.0,
        &[("shade", &[1.0, 0.0, 0.0])],
    );
    assert!(red.pixels().all(|p| p[1] == 0 && p[2] == 0));
    assert!(red.pixels().any(|p| p[0] > 100));
}

#[test]
fn displacement_grows_the_silhouette() {
    let flat = render(
        course::DISPLACEMENT,
        Object::Sphere,
        [0.0; 3],
        0.0,
        &[("displacement", &[0.0]), ("shade", &[1.0, 1.0, 1.0])],
    );
    let full = render(
        course::DISPLACEMENT,
        Object::Sphere,
        [0.0; 3],
        0.0,
        &[("displacement", &[1.0])],
    );
    // With no displacement the silhouette is the sphere's; its pixels are drawn even where
    // the noise is dark, so measure shape from depth-independent coverage: any non-black pixel
    // or the sphere's own disc.
    let r = sphere_radius_px(4.0);
    let bbox = |img: &RgbImage| bounding_box(img, BLACK).expect("visible");
    let (fx0, fy0, fx1, fy1) = bbox(&flat);
    assert!(((fx1 - fx0) as f64) < 2.0 * r + 2.0 && ((fy1 - fy0) as f64) < 2.0 * r + 2.0);
    let (gx0, gy0, gx1, gy1) = bbox(&full);
    let grown = (gx1 - gx0) + (gy1 - gy0);
    assert!(
        grown as f64 > 4.0 * r * 1.1,
        "displacement 1 must push the silhouette out: {grown} vs {:.0}",
        4.0 * r
    );
    // The default (0.5) lies in between, and the value clamps at 1.
    let half = render(course::DISPLACEMENT, Object::Sphere, [0.0; 3], 0.0, &[]);
    let (hx0, hy0, hx1, hy1) = bbox(&half);
    let half_size = (hx1 - hx0) + (hy1 - hy0);
    assert!(half_size > (fx1 - fx0) + (fy1 - fy0) && half_size < grown);
    let over = render(
        course::DISPLACEMENT,
        Object::Sphere,
        [0.0; 3],
        0.0,
        &[("displacement", &[3.0])],
    );
    assert_eq!(
        psnr(&over, &full),
        Some(f64::INFINITY),
        "displacement is clamped to [0, 1] by the shader"
    );
}

#[test]
fn rotation_turns_the_teapot() {
    let front = render(course::NORMAL_RGB, Object::Teapot, [0.0; 3], 0.0, &[]);
    let side = render(course::NORMAL_RGB, Object::Teapot, [0.0, 90.0, 0.0], 0.0, &[]);
    let (x0, _, x1, _) = bounding_box(&front, BLACK).expect("visible");
    let (s0, _, s1, _) = bounding_box(&side, BLACK).expect("visible");
    assert!(
        (s1 - s0) * 10 < (x1 - x0) * 8,
        "seen from the side (spout towards the eye) the teapot is narrower"
    );
    // The spout points to +x at rest: the right half holds more pixels than the body alone would.
    let (_, y0, _, y1) = bounding_box(&front, BLACK).expect("visible");
    assert!(x1 - x0 > y1 - y0, "the teapot is wider than tall");
}

#[test]
fn sizes_and_aspect() {
    // A square viewport keeps the sphere round and centred.
    let img = render_sized(course::NORMAL_RGB, Object::Sphere, [0.0; 3], 0.0, &[], 300, 300);
    let (x0, y0, x1, y1) = bounding_box(&img, BLACK).expect("visible");
    assert!((x1 - x0).abs_diff(y1 - y0) <= 1 && (x0 + x1).abs_diff(299) <= 1 && (y0 + y1).abs_diff(299) <= 1);
    // One-pixel-high targets (the original clamps height 0 to 1) render without error.
    let tiny = render_sized(course::PHONG, Object::Teapot, [0.0; 3], 0.0, &[], 64, 1);
    assert_eq!(tiny.dimensions(), (64, 1));
}

#[test]
fn rotated_states_agree_with_the_exact_reference() {
    // The reference images are all at rotation 0; the exact ray caster (its own f64 rotation
    // code) checks other states. The torus has no rotational symmetry that would hide a wrong
    // order or sign of the glRotatef calls; a wrong one costs far more than the 24x24 facets do.
    use shaderlab::exact::{image_error, ExactScene, Shape};
    for angles in [
        [30.0f32, 45.0, 0.0],
        [60.0, 0.0, 20.0],
        [10.0, 80.0, 40.0],
        [-35.0, 120.0, -70.0],
    ] {
        let port = render(course::PHONG, Object::Torus, angles, 0.0, &[]);
        let exact = ExactScene {
            shape: Shape::Torus,
            angles: angles.map(f64::from),
            ..Default::default()
        };
        let right = image_error(&exact.render(640, 360), &port).expect("same size").psnr;
        let swapped = ExactScene {
            angles: [angles[2], angles[1], angles[0]].map(f64::from),
            ..exact.clone()
        };
        let wrong = image_error(&swapped.render(640, 360), &port).expect("same size").psnr;
        println!("torus at {angles:?}: {right:.1} dB against the exact torus (swapped X/Z angles: {wrong:.1} dB)");
        assert!(right > 33.0, "rotation {angles:?}: {right:.1} dB");
        assert!(
            wrong < right - 5.0,
            "the test must be able to tell rotations apart at {angles:?}"
        );
    }
}
