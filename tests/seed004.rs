//! Seed 004, "OpenGL III – Basic Shaders": every effect's first state against the reference
//! renderer's image (PSNR ≥ 40 dB), pixel statistics that a wrong port would break at other
//! states, the keys and the mouse, the shipped "BMP" texture, and bad `--model` files through
//! the example binaries.
//!
//! Run alone with `cargo test --release --test seed004`. Images the tests render are written to
//! `target/test-output/seed004/` for people to look at.

mod common;

use common::{build as lab, example, render_state as render, shot};
use std::path::{Path, PathBuf};
use std::process::Command;

use image::RgbImage;
use shaderlab::course::{self, seed004::gl_textures};
use shaderlab::images;
use shaderlab::lab::{Input, Special};
use shaderlab::metrics::{mean_color, psnr};

/// Where the tests leave their images.
fn output_dir() -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/test-output/seed004");
    std::fs::create_dir_all(&dir).expect("create target/test-output/seed004");
    dir
}

fn save(image: &RgbImage, name: &str) {
    image.save(output_dir().join(name)).expect("write a test image");
}

/// Writes `assets/uvgrid.bmp` from [`images::uvgrid`]: run deliberately with
/// `scripts/write-uvgrid-bmp` (`SHADERLAB_WRITE_REFERENCES=1 cargo test --release --test
/// seed004 -- --ignored --exact write_uvgrid_bmp`; without the variable it fails, so that
/// `--include-ignored` does not rewrite the file `uvgrid_bmp_uploads_uvgrid` reads). The picture is stored upside down (the grid's row 0 at the
/// bottom, a 24-bit BMP's first stored row), so that the course's loader, uploading the BMP's
/// rows in file order, uploads exactly uvgrid's rows; `uvgrid_bmp_uploads_uvgrid` checks it.
#[test]
#[ignore = "writes assets/uvgrid.bmp; run deliberately"]
fn write_uvgrid_bmp() {
    common::require_write_opt_in("scripts/write-uvgrid-bmp");
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

const BLACK: [u8; 3] = [0, 0, 0];

/// Mean colour of the pixels that are not background.
fn object_mean(image: &RgbImage) -> [f64; 3] {
    mean_color(image, (0, 0, image.width(), image.height()), Some(BLACK))
}

/// Number of distinct colours among the pixels that are not background.
fn distinct_colors(image: &RgbImage) -> usize {
    let mut colors: Vec<[u8; 3]> = image.pixels().map(|p| p.0).filter(|c| *c != BLACK).collect();
    colors.sort_unstable();
    colors.dedup();
    colors.len()
}

/// Luma (0..255) of a pixel.
fn luma(p: [u8; 3]) -> f64 {
    0.299 * f64::from(p[0]) + 0.587 * f64::from(p[1]) + 0.114 * f64::from(p[2])
}

/// Mean and standard deviation of luma over a rectangle [x0, x1) × [y0, y1).
fn luma_in(image: &RgbImage, (x0, y0, x1, y1): (u32, u32, u32, u32)) -> (f64, f64) {
    let values: Vec<f64> = (y0..y1)
        .flat_map(|y| (x0..x1).map(move |x| (x, y)))
        .map(|(x, y)| luma(image.get_pixel(x, y).0))
        .collect();
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n;
    (mean, var.sqrt())
}

#[test]
fn normals_turn_with_the_model_only_under_the_normal_matrix() {
    // At rest MV has no rotation, NM is the identity: both exercises draw the same image.
    let still = psnr(
        &render(course::SUZANNE_NORMAL_COLOR, &[]),
        &render(course::SUZANNE_NORMAL_MATRIX, &[]),
    )
    .expect("same size");
    assert!(
        still > 60.0,
        "at rest normal_color and normal_matrix agree: {still:.1} dB"
    );
    // Turned 90° about y, Suzanne shows her left side. In object space (normal_color) those
    // normals point along x: red. Turned by NM (normal_matrix) they face the eye: blue.
    let object = render(course::SUZANNE_NORMAL_COLOR, &[("yangle", "90")]);
    let eye = render(course::SUZANNE_NORMAL_MATRIX, &[("yangle", "90")]);
    save(&object, "normal_color_yangle90.png");
    save(&eye, "normal_matrix_yangle90.png");
    let (o, e) = (object_mean(&object), object_mean(&eye));
    assert!(o[0] > o[2] + 50.0, "object-space normals of the side are red: {o:?}");
    assert!(e[2] > e[0] + 50.0, "eye-space normals of the side are blue: {e:?}");
    // The same silhouette: only the colours differ, and red and blue swap.
    assert!((o[0] - e[2]).abs() < 2.0 && (o[2] - e[0]).abs() < 2.0, "{o:?} vs {e:?}");
}

#[test]
fn vertex_normals_blend_what_face_normals_keep_flat() {
    let state = [("xangle", "30"), ("yangle", "45")];
    let faces = render(course::SUZANNE_NORMAL_MATRIX, &state);
    let smooth = render(course::SUZANNE_SMOOTH, &state);
    save(&smooth, "smooth_rotated.png");
    // Face normals: one colour per triangle (967 in all, fewer visible). Vertex normals: a
    // gradient across every triangle, tens of thousands of colours.
    let (nf, ns) = (distinct_colors(&faces), distinct_colors(&smooth));
    assert!(nf < 967, "face normals give at most one colour per triangle: {nf}");
    assert!(ns > 20 * nf, "vertex normals blend across faces: {ns} colours vs {nf}");
    // Inside a face, neighbours are the same colour; with vertex normals they rarely are.
    let (ef, es) = (equal_neighbours(&faces), equal_neighbours(&smooth));
    assert!(ef > 0.8 && es < 0.5, "equal neighbours: faces {ef:.3}, smooth {es:.3}");
}

/// Fraction of horizontally adjacent object pixels with exactly the same colour.
fn equal_neighbours(image: &RgbImage) -> f64 {
    let (mut pairs, mut equal) = (0usize, 0usize);
    for y in 0..image.height() {
        for x in 0..image.width() - 1 {
            let (p, q) = (image.get_pixel(x, y).0, image.get_pixel(x + 1, y).0);
            if p != BLACK && q != BLACK {
                pairs += 1;
                equal += usize::from(p == q);
            }
        }
    }
    equal as f64 / pairs.max(1) as f64
}

#[test]
fn mipmaps_average_the_far_checker_to_grey_and_nearest_aliases() {
    let mipmapped = render(course::TEXPARAMS, &[]);
    let nomip = render(course::TEXPARAMS, &[("min", "1")]);
    let trilinear = render(course::TEXPARAMS, &[("mag", "1"), ("min", "3")]);
    save(&nomip, "texparams_nomip.png");
    save(&trilinear, "texparams_linear.png");
    // Far away (rows 160-200, centre) a pixel covers many squares.
    let far = (280, 160, 360, 200);
    for (name, image) in [("default", &mipmapped), ("linear", &trilinear)] {
        let (mean, sd) = luma_in(image, far);
        assert!(
            (mean - 128.0).abs() < 3.0 && sd < 20.0,
            "{name}: mipmaps average to grey: {mean:.1} ± {sd:.1}"
        );
    }
    let (mean, sd) = luma_in(&nomip, far);
    assert!(
        sd > 100.0,
        "GL_NEAREST picks single texels, black or white: {mean:.1} ± {sd:.1}"
    );
    // Near the eye the floor is magnified: MAG NEAREST keeps only black and white, LINEAR blends.
    let near = (200, 465, 440, 480);
    let greys = |image: &RgbImage| {
        (near.1..near.3)
            .flat_map(|y| (near.0..near.2).map(move |x| (x, y)))
            .filter(|&(x, y)| (20.0..235.0).contains(&luma(image.get_pixel(x, y).0)))
            .count()
    };
    let total = ((near.2 - near.0) * (near.3 - near.1)) as usize;
    assert!(
        greys(&mipmapped) * 50 < total,
        "MAG NEAREST: sharp squares ({} greys)",
        greys(&mipmapped)
    );
    assert!(
        greys(&trilinear) * 10 > total,
        "MAG LINEAR: blended edges ({} greys)",
        greys(&trilinear)
    );
}

#[test]
fn non_mipmapped_min_filters_switch_with_mag_where_gl_does() {
    // GL minifies with GL_NEAREST where λ > 0 even when MAG is GL_LINEAR: far away mag=1 min=1
    // aliases like min=1 alone, and mag=0 min=2 blends like min=2 alone (a sampler clamped to
    // level 0 would use the MAG filter everywhere).
    let far = (280, 160, 360, 200);
    let nearest = luma_in(&render(course::TEXPARAMS, &[("mag", "1"), ("min", "1")]), far).1;
    let linear = luma_in(&render(course::TEXPARAMS, &[("mag", "0"), ("min", "2")]), far).1;
    let linear_alone = luma_in(&render(course::TEXPARAMS, &[("mag", "1"), ("min", "2")]), far).1;
    assert!(nearest > 100.0, "min NEAREST far away: black or white ({nearest:.1})");
    assert!(
        (linear - linear_alone).abs() < 1.0 && linear < nearest,
        "min LINEAR far away ({linear:.1} vs {linear_alone:.1})"
    );
}

/// The pixel where the floor point (x, −1, z) of texparams appears.
fn floor_pixel(x: f32, z: f32) -> (f64, f64) {
    let p = course::seed004::geometry::projection(640.0 / 480.0) * course::seed004::texparams::view();
    let clip = p * glam::Vec4::new(x, -1.0, z, 1.0);
    let (nx, ny) = (f64::from(clip.x / clip.w), f64::from(clip.y / clip.w));
    ((nx + 1.0) * 320.0, (1.0 - ny) * 240.0)
}

#[test]
fn clamp_to_edge_repeats_the_edge_texels() {
    let repeat = render(course::TEXPARAMS, &[]);
    let clamp = render(course::TEXPARAMS, &[("wrap_s", "1")]);
    save(&clamp, "texparams_clamp_s.png");
    // The bottom rows, where the floor is magnified (GL_NEAREST on level 0: exact texels).
    for y in (455..480).step_by(4) {
        // The floor's depth z at this row (rows move up as z goes away), by bisection.
        let (mut near, mut far) = (3.0f32, -16.0f32);
        for _ in 0..60 {
            let mid = 0.5 * (near + far);
            if floor_pixel(0.0, mid).1 > f64::from(y) + 0.5 {
                near = mid;
            } else {
                far = mid;
            }
        }
        // u = (x + 2) / 2 − 0.5: x = −2, −1, 1, 2 are u = −0.5, 0, 1, 1.5.
        let [left, u0, u1, right] = [-2.0, -1.0, 1.0, 2.0].map(|x| floor_pixel(x, near).0);
        let row = |image: &RgbImage, a: f64, b: f64| -> Vec<f64> {
            let (a, b) = ((a.max(0.0) + 2.0).ceil() as u32, (b.min(639.0) - 2.0).floor() as u32);
            (a..=b).map(|x| luma(image.get_pixel(x, y).0)).collect()
        };
        let (l, r) = (row(&clamp, left, u0), row(&clamp, u1, right));
        assert!(
            l.len() > 20 && r.len() > 20,
            "row {y}: strips of {} and {} px",
            l.len(),
            r.len()
        );
        // Clamped: one texel column (0, resp. 255) all across each strip: its value changes only
        // where GL switches between the MAG and MIN filters (λ varies along the row), never in
        // squares. The checker's edge columns complement each other (column 0 is black where
        // 255 is white), and the strips mirror each other's λ.
        let edges = |v: &[f64]| v.windows(2).filter(|w| w[0] != w[1]).count();
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
        assert!(
            edges(&l) <= 2 && edges(&r) <= 2,
            "row {y}: clamped strips have no squares: {l:?} {r:?}"
        );
        assert!(
            (mean(&l) + mean(&r) - 255.0).abs() < 10.0,
            "row {y}: edge columns 0 and 255 complement"
        );
        // Repeated: the squares go on (u from −0.5 to 0 is 16 squares, a few of them on screen).
        let squares = edges(&row(&repeat, left, u0));
        assert!(squares >= 4, "row {y}: repeat keeps the squares ({squares} edges)");
        // Between u = 0 and 1 the two agree.
        assert_eq!(
            row(&repeat, u0, u1),
            row(&clamp, u0, u1),
            "row {y}: inside 0..1 nothing changes"
        );
    }
}

#[test]
fn gouraud_loses_the_highlight_that_phong_keeps() {
    let top = [("xangle", "60"), ("yangle", "-30"), ("shininess", "100")];
    let gouraud = render(course::SUZANNE_GOURAUD, &top);
    let phong = render(course::SUZANNE_PHONG, &top);
    save(&gouraud, "gouraud_top.png");
    save(&phong, "phong_top.png");
    let max = |i: &RgbImage| i.pixels().map(|q| luma(q.0)).fold(0.0, f64::max);
    let bright = |i: &RgbImage| i.pixels().filter(|q| luma(q.0) > 230.0).count();
    // Same diffuse picture, but the sharp highlight between vertices survives per fragment only.
    assert!(
        max(&phong) > 250.0 && bright(&phong) > 100,
        "Phong: highlight ({} px)",
        bright(&phong)
    );
    assert!(
        max(&gouraud) < 220.0 && bright(&gouraud) == 0,
        "Gouraud: none (max {:.1})",
        max(&gouraud)
    );
    let (g, p) = (object_mean(&gouraud), object_mean(&phong));
    assert!(
        (0..3).all(|c| (g[c] - p[c]).abs() < 12.0),
        "same diffuse shading: {g:?} vs {p:?}"
    );
    // Orange by default: Kd = (0.8, 0.5, 0.2).
    assert!(p[0] > p[1] && p[1] > p[2], "{p:?}");
}

#[test]
fn flat_shading_has_one_colour_per_triangle() {
    let flat = render(course::SUZANNE_FLAT, &[("xangle", "30"), ("yangle", "45")]);
    let gouraud = render(course::SUZANNE_GOURAUD, &[("xangle", "30"), ("yangle", "45")]);
    let (nf, ng) = (distinct_colors(&flat), distinct_colors(&gouraud));
    let (ef, eg) = (equal_neighbours(&flat), equal_neighbours(&gouraud));
    assert!(nf < 967 && ng > nf, "flat {nf} colours, Gouraud {ng}");
    assert!(ef > 0.8 && eg < 0.5, "equal neighbours: flat {ef:.3}, Gouraud {eg:.3}");
}

#[test]
fn lighting_parameters_change_the_picture_as_spec_says() {
    // The `params` state: a blue material lit from the left.
    let params = [
        ("ka", "0.1"),
        ("kdr", "0.2"),
        ("kdg", "0.6"),
        ("kdb", "0.9"),
        ("ks", "1"),
        ("shininess", "8"),
        ("lightx", "-3"),
        ("lighty", "1"),
        ("lightz", "1"),
    ];
    let image = render(course::SUZANNE_PHONG, &params);
    save(&image, "phong_params.png");
    let m = object_mean(&image);
    assert!(m[2] > m[1] && m[1] > m[0], "blue-green material: {m:?}");
    let left = mean_color(&image, (0, 0, 320, 480), Some(BLACK));
    let right = mean_color(&image, (320, 0, 640, 480), Some(BLACK));
    assert!(
        luma(left.map(|c| c as u8)) > luma(right.map(|c| c as u8)) + 10.0,
        "lit from the left: {left:?} {right:?}"
    );
    // No light at all but the ambient term: Ka·white everywhere, 0.2 → 51.
    let ambient = render(
        course::SUZANNE_PHONG,
        &[("kdr", "0"), ("kdg", "0"), ("kdb", "0"), ("ks", "0")],
    );
    let a = object_mean(&ambient);
    assert!(a.iter().all(|c| (c - 51.0).abs() < 1.0), "ambient only: {a:?}");
}

#[test]
fn keys_and_mouse_follow_spec() {
    let mut lit = lab(course::SUZANNE_GOURAUD);
    assert_eq!(lit.params().text("shading"), "gouraud");
    for input in [
        Input::Key('A'),
        Input::Key('r'),
        Input::Key('G'),
        Input::Key('b'),
        Input::Key('s'),
        Input::Key('H'),
        Input::Special(Special::Left),
        Input::Special(Special::Up),
        Input::Special(Special::PageDown),
    ] {
        assert!(lit.input(input), "{input:?} changes the state");
    }
    let p = lit.params();
    let got: Vec<f32> = [
        "ka",
        "kdr",
        "kdg",
        "kdb",
        "ks",
        "shininess",
        "lightx",
        "lighty",
        "lightz",
    ]
    .iter()
    .map(|k| p.f(k))
    .collect();
    assert_eq!(got, [0.25, 0.75, 0.55, 0.15, 0.75, 36.0, 1.75, 2.25, 1.75]);
    for _ in 0..30 {
        lit.input(Input::Key('a'));
        lit.input(Input::Key('h'));
    }
    assert_eq!(
        (lit.params().f("ka"), lit.params().f("shininess")),
        (0.0, 1.0),
        "clamped to [0,1] and [1,256]"
    );
    lit.input(Input::Key('3'));
    assert_eq!(lit.params().text("shading"), "phong");
    lit.input(Input::Key('1'));
    assert_eq!(lit.params().text("shading"), "flat");

    // Left drag: 0.5° per pixel, x motion turns about y, y motion about x.
    let mut plain = lab(course::SUZANNE_NORMAL_MATRIX);
    assert!(!plain.input(Input::Drag(10, 10)), "no drag without a press");
    plain.input(Input::Press(100, 100));
    assert!(plain.input(Input::Drag(110, 96)));
    assert!(plain.input(Input::Drag(130, 96)));
    assert_eq!((plain.params().f("yangle"), plain.params().f("xangle")), (15.0, 358.0));
    plain.input(Input::Release(130, 96));
    assert!(!plain.input(Input::Drag(200, 200)), "released");

    // `t` toggles the texture; texparams' w/W/m/M cycle.
    let mut textured = lab(course::SUZANNE_TEXTURE);
    let checker = shot(textured.as_mut());
    textured.input(Input::Key('t'));
    assert_eq!(textured.params().text("tex"), "bmp");
    assert!(
        psnr(&checker, &shot(textured.as_mut())).expect("size") < 20.0,
        "t shows the other texture"
    );
    textured.input(Input::Key('t'));
    assert_eq!(textured.params().text("tex"), "checker");
    let mut tp = lab(course::TEXPARAMS);
    for key in ['w', 'W', 'm', 'm', 'm', 'M', 'M'] {
        tp.input(Input::Key(key));
    }
    let p = tp.params();
    assert_eq!(
        ["wrap_s", "wrap_t", "min", "mag"].map(|k| p.index_of(k)),
        [1, 1, 3, 0],
        "w, W cycle the wraps, m the four MIN filters, M the two MAG filters"
    );
}

/// What a run of an example printed and how it ended.
struct Run {
    code: Option<i32>,
    stdout: String,
    stderr: String,
}

/// Runs `example args` in `dir` with no display.
fn run_example(dir: &Path, name: &str, args: &[&str]) -> Run {
    let out = Command::new(example(name))
        .args(args)
        .current_dir(dir)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("RUST_BACKTRACE")
        .output()
        .expect("run the example");
    let run = Run {
        code: out.status.code(),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
    };
    println!(
        "$ {name} {}\n[exit {:?}]\n{}{}",
        args.join(" "),
        run.code,
        run.stdout,
        run.stderr
    );
    assert!(!run.stderr.contains("panicked"), "no panic");
    run
}

/// A fresh directory for one test.
fn test_dir(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("seed004").join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create the test directory");
    dir
}

#[test]
fn bad_models_are_refused_before_anything_is_drawn() {
    let dir = test_dir("bad_models");
    let cases: &[(&str, Option<&str>, &str)] = &[
        ("missing.obj", None, "No such file"),
        ("empty.obj", Some(""), "empty file"),
        (
            "bad_index.obj",
            Some("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"),
            "out of range",
        ),
        (
            "not_a_number.obj",
            Some("v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n"),
            "not a number",
        ),
        (
            "two_corners.obj",
            Some("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n"),
            "face with 2 corner",
        ),
    ];
    for (file, text, phrase) in cases {
        if let Some(text) = text {
            std::fs::write(dir.join(file), text).expect("write the model");
        }
        let png = format!("{file}.png");
        let run = run_example(&dir, "suzanne_normal_color", &["--model", file, "--screenshot", &png]);
        assert_eq!(run.code, Some(1), "{file}: runtime error status");
        let lines: Vec<&str> = run.stderr.lines().collect();
        assert_eq!(lines.len(), 1, "{file}: one message: {:?}", run.stderr);
        assert!(
            lines[0].contains(file) && lines[0].contains(phrase),
            "{file}: {}",
            lines[0]
        );
        // The line of the OBJ is named where one is to blame.
        if text.is_some_and(|t| !t.is_empty()) {
            assert!(
                lines[0].contains(&format!("{file}:")),
                "{file}: line number in {}",
                lines[0]
            );
        }
        assert!(!dir.join(&png).exists(), "{file}: no PNG written");
    }
    // A bad --texture is refused the same way.
    std::fs::write(dir.join("junk.png"), b"not a picture").expect("write junk");
    let run = run_example(
        &dir,
        "suzanne_texture",
        &["--texture", "junk.png", "--screenshot", "t.png"],
    );
    assert_eq!(run.code, Some(1));
    assert!(
        run.stderr.lines().count() == 1 && run.stderr.contains("junk.png"),
        "{}",
        run.stderr
    );
    assert!(!dir.join("t.png").exists());
}

#[test]
fn user_model_and_texture_replace_the_course_data() {
    let dir = test_dir("user_files");
    // A square facing the eye, two triangles, no `vt` and no `vn`.
    std::fs::write(
        dir.join("square.obj"),
        "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n",
    )
    .expect("write the model");
    let run = run_example(
        &dir,
        "suzanne_normal_color",
        &["--model", "square.obj", "--screenshot", "square.png"],
    );
    assert_eq!(run.code, Some(0));
    let notices: Vec<&str> = run.stderr.lines().collect();
    assert_eq!(notices.len(), 2, "one line each for missing vt and vn: {notices:?}");
    assert!(notices.iter().any(|l| l.contains("square.obj") && l.contains("`vt`")));
    assert!(notices.iter().any(|l| l.contains("square.obj") && l.contains("`vn`")));
    let square = image::open(dir.join("square.png")).expect("written").to_rgb8();
    // Its face normal (0, 0, 1) is blue, and it covers a square of 2 units at distance 4.
    let side = 2.0 / 4.0 / (22.5f64).to_radians().tan() * 240.0;
    let blue = square.pixels().filter(|p| p.0 == [0, 0, 255]).count() as f64;
    assert!(
        (blue - side * side).abs() < 4.0 * side,
        "{blue} px vs {:.0}",
        side * side
    );

    // A 2×2 picture as the "BMP" texture: top row red/green, bottom row blue/white. Uploaded
    // bottom row first, t = 0 is its bottom: the course's BMP loader's orientation.
    let picture = RgbImage::from_fn(2, 2, |x, y| {
        image::Rgb(match (x, y) {
            (0, 0) => [255, 0, 0],
            (1, 0) => [0, 255, 0],
            (0, 1) => [0, 0, 255],
            _ => [255, 255, 255],
        })
    });
    picture.save(dir.join("tiny.png")).expect("write the picture");
    let run = run_example(
        &dir,
        "suzanne_texture",
        &[
            "--texture",
            "tiny.png",
            "--set",
            "tex=bmp",
            "--screenshot",
            "tiny_suzanne.png",
        ],
    );
    assert_eq!(run.code, Some(0));
    let shot = image::open(dir.join("tiny_suzanne.png")).expect("written").to_rgb8();
    let m = object_mean(&shot);
    assert!(m.iter().all(|c| *c > 40.0), "all four texels show: {m:?}");
    let loaded = images::load_image(&dir.join("tiny.png")).expect("decode");
    assert_eq!(
        &gl_textures::bottom_row_first(&loaded).rgba[..8],
        &[0, 0, 255, 255, 255, 255, 255, 255]
    );
}

/// `aniso` (port addition): against a supersampled ground truth (the floor drawn 4 × 4 larger
/// with NEAREST, box-filtered down), anisotropic filtering is closer in the far half of the
/// picture than trilinear filtering (the best of GL's own filters there), which averages the
/// far squares along the view as much as across it.
#[test]
fn texparams_anisotropic_filtering_is_closer_to_the_supersampled_floor() {
    let mut lab = lab(course::TEXPARAMS);
    common::set_state(lab.as_mut(), &[("min", "nearest"), ("mag", "nearest")]);
    let big =
        shaderlab::offscreen::to_rgb(&shaderlab::shell::screenshot(common::gpu(), lab.as_mut(), 2560, 1920).unwrap());
    let truth = shaderlab::metrics::box_downsample(&big, 4);
    let far_rmse = |image: &RgbImage| {
        let n = (640 * 240 * 3) as f64;
        let sum: f64 = (0..240)
            .flat_map(|y| (0..640).map(move |x| (x, y)))
            .flat_map(|(x, y)| (0..3).map(move |c| (x, y, c)))
            .map(|(x, y, c)| (f64::from(image.get_pixel(x, y).0[c]) - f64::from(truth.get_pixel(x, y).0[c])).powi(2))
            .sum();
        (sum / n).sqrt()
    };
    let trilinear = render(course::TEXPARAMS, &[("min", "linear_mipmap_linear"), ("mag", "linear")]);
    let aniso = render(course::TEXPARAMS, &[("aniso", "16")]);
    let (t, a) = (far_rmse(&trilinear), far_rmse(&aniso));
    println!("far-half RMSE against the 4x4-supersampled floor: trilinear {t:.2}, anisotropic 16 {a:.2}");
    assert!(a < 0.95 * t, "anisotropic {a:.2} against trilinear {t:.2}");
}
