//! `shaderlab diff NAME --shaders DIR`: a copy with a planted bug is found at the bug's file
//! and line (in either stage, and through a function's argument), an identical copy differs
//! nowhere, and a copy that does not compile or takes other inputs gets one clear message.

mod common;

use std::path::{Path, PathBuf};

use common::gpu;
use shaderlab::lab::UserFiles;
use shaderlab::metrics::psnr;
use shaderlab::offscreen::{to_rgb, COLOR_FORMAT};
use shaderlab::shader::ShaderSource;
use shaderlab::shell::session::Sources;

/// The built-in shaders in a folder, `file` changed by replacing `from` with `to`.
fn copy_with(tag: &str, file: &str, from: &str, to: &str) -> PathBuf {
    let dir = common::output_dir().join(format!("diff_{tag}"));
    let _ = std::fs::remove_dir_all(&dir);
    common::copy_shaders(&dir);
    let path = dir.join(file);
    let text = std::fs::read_to_string(&path).expect("the shader");
    assert!(text.contains(from), "{file} has `{from}`");
    std::fs::write(&path, text.replacen(from, to, 1)).expect("write the copy");
    dir
}

/// The 1-based line of `file` in `dir` that holds `what`.
fn line_of(dir: &Path, file: &str, what: &str) -> u64 {
    let text = std::fs::read_to_string(dir.join(file)).expect("the shader");
    text.lines().position(|l| l.contains(what)).expect("the line") as u64 + 1
}

fn shaderlab(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_shaderlab"))
        .args(args)
        .output()
        .expect("shaderlab runs")
}

fn diff_json(name: &str, dir: &Path, more: &[&str]) -> serde_json::Value {
    let mut args = vec!["diff", name, "--shaders", dir.to_str().expect("utf-8"), "--json"];
    args.extend_from_slice(more);
    let out = shaderlab(&args);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("one JSON object")
}

#[test]
fn a_bug_planted_in_a_fragment_shader_is_found_at_its_line() {
    let dir = copy_with("frag", "phong.frag", "max(dot(N, L), 0.0)", "max(dot(N, L), 0.5)");
    let png = common::output_dir().join("diff_frag.png");
    let v = diff_json("phong", &dir, &["--out", png.to_str().expect("utf-8")]);
    let first = &v["first_divergence"];
    assert!(first["file"].as_str().is_some_and(|f| f.ends_with("phong.frag")), "{v}");
    assert_eq!(first["line"], line_of(&dir, "phong.frag", "max(dot(N, L), 0.5)"), "{v}");
    assert_eq!(first["name"], "Idiff", "{v}");
    assert_ne!(first["mine"], first["reference"], "{v}");
    // The figures are the two pictures': the copy's and the built-in shaders', as the library
    // draws them.
    let picture_of = |source: &ShaderSource| {
        let entry = shaderlab::course::find("phong").expect("phong");
        let mut lab = Sources::new(source.clone(), UserFiles::default(), COLOR_FORMAT)
            .build(gpu(), entry)
            .expect("phong builds");
        shaderlab::shell::screenshot(gpu(), lab.as_mut(), 640, 360).expect("a picture")
    };
    let mine = picture_of(&ShaderSource::dir(&dir).expect("the copy"));
    let reference = picture_of(&ShaderSource::Embedded);
    let differing = mine.pixels().zip(reference.pixels()).filter(|(a, b)| a != b).count();
    assert!(differing > 100, "the planted bug changes {differing} pixels");
    assert_eq!(v["differing"], differing, "{v}");
    let want = psnr(&to_rgb(&mine), &to_rgb(&reference)).expect("one size");
    let got = v["psnr"].as_f64().unwrap_or(f64::NAN);
    assert!(
        (got - want).abs() < 0.01,
        "psnr {got}, not the pictures' {want:.3}: {v}"
    );
    let worst = &v["worst"];
    assert_ne!(worst["mine"], worst["reference"], "{v}");
    let at = |key: &str| worst[key].as_u64().expect("a coordinate") as u32;
    let (wx, wy) = (at("x"), at("y"));
    assert_eq!(worst["mine"], serde_json::json!(mine.get_pixel(wx, wy).0), "{v}");
    assert_eq!(
        worst["reference"],
        serde_json::json!(reference.get_pixel(wx, wy).0),
        "{v}"
    );
    // The picture of the difference, with its legend under it.
    let picture = image::open(&png).expect("the difference picture").to_rgb8();
    assert_eq!(
        picture.dimensions(),
        (640, 360 + shaderlab::debug::picture::LEGEND_HEIGHT)
    );
    let (x, y) = (
        worst["x"].as_u64().expect("x") as u32,
        worst["y"].as_u64().expect("y") as u32,
    );
    assert_ne!(picture.get_pixel(x, y).0, [0, 0, 0], "the worst pixel is highlighted");
}

#[test]
fn a_bug_in_an_argument_or_in_the_vertex_shader_is_found_at_its_line() {
    // The eye vector's sign flipped inside a call: the call's line, the argument named.
    let dir = copy_with("argument", "phong.frag", "safe_normalize(-v)", "safe_normalize(v) ");
    let v = diff_json("phong", &dir, &[]);
    let first = &v["first_divergence"];
    assert!(first["file"].as_str().is_some_and(|f| f.ends_with("phong.frag")), "{v}");
    assert_eq!(first["line"], line_of(&dir, "phong.frag", "safe_normalize(v) "), "{v}");
    assert!(first["name"].as_str().is_some_and(|n| n.contains("argument v")), "{v}");
    // The vertex stage: the position in eye space moved.
    let dir = copy_with(
        "vertex",
        "phong.vert",
        "v = vec3(modelview * vertex);",
        "v = vec3(modelview * vertex) * 1.1;",
    );
    let v = diff_json("phong", &dir, &[]);
    let first = &v["first_divergence"];
    assert_eq!(first["stage"], "vertex", "{v}");
    assert!(first["file"].as_str().is_some_and(|f| f.ends_with("phong.vert")), "{v}");
    assert_eq!(first["line"], line_of(&dir, "phong.vert", "* 1.1;"), "{v}");
    assert_eq!(first["name"], "v", "{v}");
    // Another lab: noise's time scaled.
    let dir = copy_with(
        "noise",
        "noise.frag",
        "position + time * speed",
        "position + time * speed * 2.0",
    );
    let v = diff_json("noise", &dir, &["--set", "time=1.5"]);
    let first = &v["first_divergence"];
    assert!(first["file"].as_str().is_some_and(|f| f.ends_with("noise.frag")), "{v}");
    assert_eq!(first["line"], line_of(&dir, "noise.frag", "* 2.0"), "{v}");
    assert_eq!(first["name"], "v", "{v}");
}

#[test]
fn an_identical_copy_differs_nowhere_and_says_so() {
    let dir = common::output_dir().join("diff_same");
    let _ = std::fs::remove_dir_all(&dir);
    common::copy_shaders(&dir);
    let v = diff_json("phong", &dir, &["--set", "object=torus"]);
    assert_eq!(v["differing"], 0, "{v}");
    assert_eq!(v["psnr"], "Infinity", "{v}");
    assert_eq!(v["worst"], serde_json::Value::Null, "{v}");
    assert_eq!(v["first_divergence"], serde_json::Value::Null, "{v}");
    let out = shaderlab(&["diff", "phong", "--shaders", dir.to_str().expect("utf-8")]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("the pictures are identical"), "{text}");
}

#[test]
fn a_broken_copy_a_copy_with_other_inputs_and_no_copy_get_one_clear_message() {
    let dir = copy_with("broken", "phong.frag", "    frag_color = ", "    frag_color = nope + ");
    let out = shaderlab(&["diff", "phong", "--shaders", dir.to_str().expect("utf-8")]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    let line = line_of(&dir, "phong.frag", "nope");
    assert!(
        err.contains(&format!("phong.frag:{line}:")) && err.contains("nope") && err.contains('^'),
        "{err}"
    );
    let dir = copy_with(
        "inputs",
        "transform.glsl",
        "layout(location = 1) in vec3 vertex_normal;",
        "layout(location = 1) in vec4 vertex_normal;",
    );
    std::fs::write(
        dir.join("phong.vert"),
        std::fs::read_to_string(dir.join("phong.vert"))
            .expect("phong.vert")
            .replace("normal_matrix * vertex_normal", "normal_matrix * vertex_normal.xyz"),
    )
    .expect("write phong.vert");
    let out = shaderlab(&["diff", "phong", "--shaders", dir.to_str().expect("utf-8")]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("takes different inputs from the built-in shaders"),
        "{err}"
    );
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    let out = shaderlab(&["diff", "--help"]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("Usage: shaderlab diff NAME --shaders DIR"));
    let out = shaderlab(&["diff", "phong"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("which copy?"));
    let out = shaderlab(&["diff", "phong", "--shaders", "/nonexistent-shaderlab-dir"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("/nonexistent-shaderlab-dir: shader directory not found"),
        "{err}"
    );
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

/// The library refuses to compare frames whose shaders take different inputs (here two labs'),
/// naming the first difference, and compares a frame with itself as identical.
#[test]
fn frames_of_shaders_with_other_inputs_are_refused_by_the_library() {
    let files = UserFiles::default();
    let open = |name: &str| {
        let entry = shaderlab::course::find(name).expect("a lab");
        Sources::new(ShaderSource::Embedded, files.clone(), COLOR_FORMAT)
            .build(gpu(), entry)
            .expect("the lab builds")
    };
    let (mut phong, mut noise) = (open("phong"), open("noise"));
    let (_, a) = shaderlab::debug::capture_lab(gpu(), phong.as_mut(), 320, 180, true).expect("phong");
    let (_, b) = shaderlab::debug::capture_lab(gpu(), noise.as_mut(), 320, 180, true).expect("noise");
    let err = shaderlab::debug::diff::diff("phong", &a, &b).expect_err("other inputs");
    assert!(
        err.to_string().contains("take different inputs from the reference's"),
        "{err}"
    );
    let same = shaderlab::debug::diff::diff("phong", &a, &a).expect("the same frame");
    assert_eq!(
        (same.differing, same.psnr, same.worst.clone()),
        (0, f64::INFINITY, None)
    );
    assert!(same.text().contains("identical"), "{}", same.text());
}

/// A vertex-shader bug that moves the surface is found at its line, compared vertex by vertex
/// (the same draw and vertex index in both frames), not at a pixel that other triangles cover
/// in the two frames: the planted line, the name it assigns, the stage and the vertex.
#[test]
fn a_vertex_bug_that_moves_the_surface_is_found_at_its_line_vertex_by_vertex() {
    let cases: [(&str, &str, &str, &str, &str, &str); 3] = [
        (
            "wave",
            "wave.vert",
            "h*sin(time + xs*vertex_position.x)",
            "h*sin(time + xs*vertex_position.x*1.5)",
            "xs*vertex_position.x*1.5",
            "t.y",
        ),
        (
            "displacement",
            "noise.glsl",
            "vec3 i = floor(v + dot(v, C.yyy));",
            "vec3 i = floor(v + dot(v, C.yyy) + 0.3);",
            "C.yyy) + 0.3",
            "i",
        ),
        (
            "phong",
            "phong.vert",
            "gl_Position = mvp * vertex;",
            "gl_Position = mvp * (vertex + vec4(0.1, 0.0, 0.0, 0.0));",
            "vec4(0.1, 0.0, 0.0, 0.0)",
            "gl_Position",
        ),
    ];
    for (lab, file, from, to, planted, name) in cases {
        let dir = copy_with(&format!("moves_{lab}"), file, from, to);
        let v = diff_json(lab, &dir, &[]);
        assert!(v["differing"].as_u64().is_some_and(|n| n > 100), "{lab}: {v}");
        let first = &v["first_divergence"];
        assert_eq!(first["stage"], "vertex", "{lab}: {v}");
        assert!(first["file"].as_str().is_some_and(|f| f.ends_with(file)), "{lab}: {v}");
        assert_eq!(first["line"], line_of(&dir, file, planted), "{lab}: {v}");
        assert_eq!(first["name"], name, "{lab}: {v}");
        assert_eq!(first["why"], "the value differs", "{lab}: {v}");
        assert!(
            first["vertex"]["index"].is_u64() && first["vertex"]["draw"].is_u64(),
            "{lab}: {v}"
        );
        assert_ne!(first["mine"], first["reference"], "{lab}: {v}");
        let text = shaderlab(&["diff", lab, "--shaders", dir.to_str().expect("utf-8")]);
        let text = String::from_utf8_lossy(&text.stdout);
        assert!(
            text.contains(&format!(
                "{}:{} (vertex shader, draw {} vertex {})",
                file, first["line"], first["vertex"]["draw"], first["vertex"]["index"]
            )),
            "{lab}: {text}"
        );
    }
}

/// The lecture's side-by-side (`compare=1`) draws each program in its own viewport: a bug
/// planted in the right-hand program's fragment shader is found at its line, at a worst pixel
/// of the right half.
#[test]
fn a_bug_in_a_draw_with_its_own_viewport_is_found_at_its_line() {
    let dir = copy_with(
        "viewport",
        "phong_fragment.frag",
        "vec4 diffuse = Kd * FrontLightProduct[0].diffuse;",
        "vec4 diffuse = 0.5 * Kd * FrontLightProduct[0].diffuse;",
    );
    let v = diff_json("phong_fragment", &dir, &["--set", "compare=1"]);
    let first = &v["first_divergence"];
    assert_eq!(first["stage"], "fragment", "{v}");
    assert!(
        first["file"]
            .as_str()
            .is_some_and(|f| f.ends_with("phong_fragment.frag")),
        "{v}"
    );
    assert_eq!(first["line"], line_of(&dir, "phong_fragment.frag", "0.5 * Kd"), "{v}");
    assert_eq!(first["name"], "diffuse", "{v}");
    let (x, width) = (v["worst"]["x"].as_u64(), v["width"].as_u64());
    assert!(x.zip(width).is_some_and(|(x, w)| x >= w / 2), "{v}");
}
