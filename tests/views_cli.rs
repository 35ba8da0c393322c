//! `shaderlab view NAME --line FILE:LINE | --cost` and the labs' `--line` / `--cost` / `--npy` /
//! `--diff` flags: the picture written is the library's picture of the library's view of the
//! same frame, the `.npy` array holds the debugger's traced values, `--json` sums the view up,
//! a cost view equals `shaderlab debug --json`'s `cost`, `--bench` times a view, and bad input
//! gets one line and the usage status, with nothing written.

mod common;

use std::path::{Path, PathBuf};

use common::gpu;
use shaderlab::debug::view::{self, Probe, ValueFrame};
use shaderlab::debug::{picture, Captured, Inspection, Stage};
use shaderlab::lab::{BuildContext, Lab, UserFiles};
use shaderlab::offscreen::COLOR_FORMAT;
use shaderlab::render::DrawLog;
use shaderlab::shader::ShaderSource;

const WIDTH: u32 = 320;
const HEIGHT: u32 = 180;
const SIZE: &str = "320x180";

fn ok(out: &std::process::Output) -> String {
    assert!(
        out.status.success(),
        "status {:?}: {}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// The 1-based line of the built-in `file` that holds `needle`.
fn line_of(file: &str, needle: &str) -> u32 {
    let text = shaderlab::shader::embedded_source(file).expect("a built-in shader");
    text.lines().position(|l| l.contains(needle)).expect("the line") as u32 + 1
}

/// The lab at its defaults but for `set`, its frame recorded at the tests' size.
fn frame(name: &str, set: &[(&str, &str)]) -> (DrawLog, Captured) {
    let entry = shaderlab::course::find(name).expect("a lab");
    let files = UserFiles::default();
    let cx = BuildContext::new(gpu(), &ShaderSource::Embedded, COLOR_FORMAT, &files);
    let mut lab: Box<dyn Lab> = (entry.new)(&cx).expect("the lab builds");
    for (k, v) in set {
        lab.params_mut().set_str(k, v).expect("a parameter");
    }
    view::capture(gpu(), lab.as_mut(), WIDTH, HEIGHT).expect("the frame")
}

/// The file of the frame, as the lab names it, whose path ends with `suffix`.
fn shown(captured: &Captured, suffix: &str) -> String {
    captured
        .draws
        .iter()
        .flat_map(|d| [&d.vertex, &d.fragment])
        .flat_map(|s| s.source.files.iter().map(|(p, _)| p.clone()))
        .find(|p| p.ends_with(suffix))
        .expect("the file is drawn")
}

/// A NumPy file: its shape and its float32 values, the header parsed as NumPy's format says.
fn read_npy(path: &Path) -> (Vec<usize>, Vec<f32>) {
    common::parse_npy(&std::fs::read(path).expect("the .npy file"))
}

/// Up to `n` indices where `pick` holds, spread evenly over them in scan order.
fn spread(len: usize, n: usize, pick: impl Fn(usize) -> bool) -> Vec<usize> {
    let all: Vec<usize> = (0..len).filter(|&i| pick(i)).collect();
    let step = (all.len() / n.max(1)).max(1);
    all.into_iter().skip(step / 2).step_by(step).take(n).collect()
}

fn close(a: f32, b: f64) -> bool {
    (f64::from(a) - b).abs() <= 1e-3 * b.abs().max(1.0)
}

/// The picture the library makes of a view frame (a fragment ran where the trace has steps).
fn library_picture(frame: &ValueFrame) -> image::RgbaImage {
    let drawn: Vec<bool> = frame.cost.iter().map(|&c| c > 0).collect();
    match frame.resolved {
        Some(_) => {
            picture::values(
                frame.width,
                frame.height,
                frame.components as usize,
                &frame.values,
                &frame.ran,
                &drawn,
            )
            .0
        }
        None => picture::cost(frame.width, frame.height, &frame.cost, &drawn).0,
    }
}

#[test]
fn the_view_command_writes_the_librarys_picture_and_the_debuggers_values() {
    let dir = common::fresh_dir("views_cli_line");
    let line = line_of("phong.frag", "max(dot(N, L), 0.0)");
    let at = format!("phong.frag:{line}");
    let out = common::shaderlab_in(
        &dir,
        &[
            "view", "phong", "--line", &at, "--object", "teapot", "--size", SIZE, "--out", "v.png", "--npy", "v.npy",
            "--json",
        ],
    );
    let summary: serde_json::Value = serde_json::from_str(&ok(&out)).expect("one JSON object");

    // The same frame in this process, and the library's view of it.
    let (log, captured) = frame("phong", &[("object", "teapot")]);
    let file = shown(&captured, "phong.frag");
    let probe = Probe::Line {
        file: file.clone(),
        line,
        name: None,
        stage: None,
    };
    let lib = view::draw_view(gpu(), &log, &probe, WIDTH, HEIGHT).expect("the library's view");

    // The picture is the library's picture of that view, pixel for pixel.
    let png = image::open(dir.join("v.png")).expect("the picture").to_rgba8();
    let expected = library_picture(&lib);
    assert_eq!(png.dimensions(), expected.dimensions());
    let differing = png.pixels().zip(expected.pixels()).filter(|(a, b)| a != b).count();
    assert_eq!(differing, 0, "pixels of v.png unlike the library's picture");

    // The array: height x width x components, the debugger's traced value where the line ran.
    let (shape, values) = read_npy(&dir.join("v.npy"));
    assert_eq!(shape, vec![HEIGHT as usize, WIDTH as usize, 4]);
    let ran = |i: usize| !values[i * 4].is_nan();
    let samples = spread((WIDTH * HEIGHT) as usize, 10, ran);
    assert!(samples.len() >= 10, "the line ran at {} sampled pixels", samples.len());
    for i in samples {
        let (x, y) = (i as u32 % WIDTH, i as u32 / WIDTH);
        let ins = Inspection::new("phong", &captured, x, y).expect("the inspection");
        let traced = ins
            .steps
            .iter()
            .rfind(|s| s.stage == Stage::Fragment && s.file == file && s.line == line && s.name == "Idiff")
            .unwrap_or_else(|| panic!("{x},{y}: the array has a value, the trace never reaches the line"));
        for c in 0..4 {
            let got = values[i * 4 + c];
            assert!(
                close(got, traced.value[c]),
                "{x},{y} component {c}: array {got}, debugger {:?}",
                traced.value
            );
        }
    }
    // Where no fragment ran, NaN; the counts agree with the library's view.
    let drawn = lib.cost.iter().filter(|&&c| c > 0).count();
    let nans = (0..(WIDTH * HEIGHT) as usize).filter(|&i| !ran(i)).count();
    assert_eq!(nans, (WIDTH * HEIGHT) as usize - drawn, "NaN where no fragment ran");

    // The summary.
    assert_eq!(summary["view"], "line", "{summary}");
    assert_eq!(summary["file"], file.as_str(), "{summary}");
    assert_eq!(summary["line"], line, "{summary}");
    assert_eq!(summary["name"], "Idiff", "{summary}");
    assert_eq!(summary["stage"], "fragment", "{summary}");
    assert_eq!(summary["vertex"], false, "{summary}");
    assert_eq!(summary["components"], 4, "{summary}");
    assert_eq!(summary["drawn"], drawn, "{summary}");
    assert_eq!(summary["not_run"], 0, "{summary}");
    assert_eq!(summary["nan"], 0, "{summary}");
    assert_eq!(summary["inf"], 0, "{summary}");
    let finite: Vec<f32> = values.iter().copied().filter(|v| v.is_finite()).collect();
    let lo = finite.iter().copied().fold(f32::INFINITY, f32::min);
    let hi = finite.iter().copied().fold(f32::NEG_INFINITY, f32::max);
    assert_eq!(summary["range"]["min"].as_f64(), Some(f64::from(lo)), "{summary}");
    assert_eq!(summary["range"]["max"].as_f64(), Some(f64::from(hi)), "{summary}");
    assert!(lo < hi, "the diffuse term varies over the teapot: {lo}..{hi}");
}

#[test]
fn a_vertex_line_through_the_labs_flags_is_said_to_be_interpolated() {
    let dir = common::fresh_dir("views_cli_vertex");
    let line = line_of("phong.vert", "v = vec3(modelview * vertex)");
    let at = format!("phong.vert:{line}");
    let out = common::shaderlab_in(
        &dir,
        &[
            "run",
            "phong",
            "--line",
            &at,
            "--size",
            SIZE,
            "--json",
            "--screenshot",
            "v.png",
        ],
    );
    let summary: serde_json::Value = serde_json::from_str(&ok(&out)).expect("one JSON object");
    assert_eq!(summary["vertex"], true, "{summary}");
    assert_eq!(summary["stage"], "vertex", "{summary}");
    assert_eq!(summary["components"], 3, "{summary}");
    // Eye-space positions lie in front of the eye: z below 0 somewhere, so a range across 0.
    assert!(summary["range"]["min"].as_f64().is_some_and(|m| m < 0.0), "{summary}");
    assert!(image::open(dir.join("v.png")).is_ok(), "the picture");
    // Without --json the summary is one line of words, saying so.
    let out = common::shaderlab_in(
        &dir,
        &["view", "phong", "--line", &at, "--size", SIZE, "--out", "w.png"],
    );
    let text = ok(&out);
    assert!(text.contains("interpolated as a varying"), "{text}");
    assert_eq!(text.lines().count(), 1, "{text}");
}

#[test]
fn a_cost_view_from_the_command_equals_the_debuggers_cost() {
    let dir = common::fresh_dir("views_cli_cost");
    let out = common::shaderlab_in(
        &dir,
        &[
            "view",
            "uniform_arrays",
            "--cost",
            "--size",
            SIZE,
            "--out",
            "c.png",
            "--npy",
            "c.npy",
            "--json",
        ],
    );
    let summary: serde_json::Value = serde_json::from_str(&ok(&out)).expect("one JSON object");
    let (shape, cost) = read_npy(&dir.join("c.npy"));
    assert_eq!(shape, vec![HEIGHT as usize, WIDTH as usize, 1]);
    let drawn: Vec<usize> = (0..cost.len()).filter(|&i| !cost[i].is_nan()).collect();
    let lo = drawn.iter().map(|&i| cost[i]).fold(f32::INFINITY, f32::min);
    let hi = drawn.iter().map(|&i| cost[i]).fold(f32::NEG_INFINITY, f32::max);
    assert!(lo < hi, "the if/else chain costs more in some bands: {lo}..{hi}");
    assert_eq!(summary["view"], "cost", "{summary}");
    assert_eq!(summary["cost"]["min"].as_f64(), Some(f64::from(lo)), "{summary}");
    assert_eq!(summary["cost"]["max"].as_f64(), Some(f64::from(hi)), "{summary}");
    assert_eq!(summary["drawn"], drawn.len(), "{summary}");
    let mean = drawn.iter().map(|&i| f64::from(cost[i])).sum::<f64>() / drawn.len() as f64;
    assert!(
        summary["cost"]["mean"]
            .as_f64()
            .is_some_and(|m| (m - mean).abs() < 1e-9),
        "{summary}"
    );
    // At sampled pixels of each count, and one where nothing was drawn: the debugger's `cost`.
    let mut pixels: Vec<usize> = Vec::new();
    for c in [lo, hi] {
        pixels.extend(spread(cost.len(), 2, |i| cost[i] == c));
    }
    pixels.extend(spread(cost.len(), 2, |i| !cost[i].is_nan()));
    pixels.extend(spread(cost.len(), 1, |i| cost[i].is_nan()));
    for i in pixels {
        let (x, y) = (i as u32 % WIDTH, i as u32 / WIDTH);
        let out = common::shaderlab_in(
            &dir,
            &[
                "debug",
                "uniform_arrays",
                "--pixel",
                &format!("{x},{y}"),
                "--size",
                SIZE,
                "--json",
            ],
        );
        let inspection: serde_json::Value = serde_json::from_str(&ok(&out)).expect("the debugger's JSON");
        let expected = inspection["cost"].as_f64().expect("a cost");
        let got = if cost[i].is_nan() { 0.0 } else { f64::from(cost[i]) };
        assert_eq!(
            got, expected,
            "pixel {x},{y}: the cost view counts {got}, the debugger {expected}"
        );
    }
    // The picture is the library's picture of the counts.
    let png = image::open(dir.join("c.png")).expect("the picture").to_rgba8();
    let counts: Vec<u32> = cost.iter().map(|c| if c.is_nan() { 0 } else { *c as u32 }).collect();
    let drawn_mask: Vec<bool> = cost.iter().map(|c| !c.is_nan()).collect();
    let (expected, max) = picture::cost(WIDTH, HEIGHT, &counts, &drawn_mask);
    assert_eq!(f64::from(max), f64::from(hi));
    assert!(png == expected, "c.png is the library's picture of the cost");
}

#[test]
fn bench_with_a_view_times_the_view() {
    let dir = common::fresh_dir("views_cli_bench");
    let line = line_of("phong.frag", "max(dot(N, L), 0.0)");
    for view in [
        vec!["--line".to_owned(), format!("phong.frag:{line}")],
        vec!["--cost".to_owned()],
    ] {
        let mut args = vec!["run", "phong", "--size", SIZE, "--bench", "3"];
        args.extend(view.iter().map(String::as_str));
        let text = ok(&common::shaderlab_in(&dir, &args));
        assert_eq!(text.lines().count(), 1, "{text}");
        // The view as the window and the page draw it, the plain frame beside it, their
        // ratio, and the view read back.
        let field = |key: &str| -> f64 {
            text.split(&format!(" {key}="))
                .nth(1)
                .and_then(|s| s.split_whitespace().next())
                .and_then(|s| s.parse().ok())
                .unwrap_or_else(|| panic!("{key}: {text}"))
        };
        for key in ["ms_per_frame", "plain_ms_per_frame", "ratio", "values_ms_per_frame"] {
            let v = field(key);
            assert!(v > 0.0 && v.is_finite(), "{key}: {text}");
        }
        let ratio = field("ms_per_frame") / field("plain_ms_per_frame");
        assert!((ratio - field("ratio")).abs() < 0.01 + 0.01 * ratio, "{text}");
        assert!(text.contains(" view="), "{text}");
    }
    assert_eq!(
        std::fs::read_dir(&dir).expect("the folder").count(),
        0,
        "a benchmark writes no file"
    );
}

#[test]
fn the_labs_diff_flag_is_shaderlab_diff() {
    let dir = common::fresh_dir("views_cli_diff");
    let shaders = dir.join("copy");
    common::copy_shaders(&shaders);
    let frag = shaders.join("phong.frag");
    let text = std::fs::read_to_string(&frag).expect("the copy");
    std::fs::write(&frag, text.replacen("max(dot(N, L), 0.0)", "max(dot(N, L), 0.5)", 1)).expect("the bug");
    let copy = shaders.to_str().expect("utf-8");
    let out = common::shaderlab_in(
        &dir,
        &["run", "phong", "--diff", copy, "--json", "--screenshot", "d.png"],
    );
    let v: serde_json::Value = serde_json::from_str(&ok(&out)).expect("one JSON object");
    assert_eq!(
        v["first_divergence"]["line"],
        line_of("phong.frag", "max(dot(N, L), 0.0)"),
        "{v}"
    );
    assert_eq!(v["first_divergence"]["name"], "Idiff", "{v}");
    assert!(image::open(dir.join("d.png")).is_ok(), "the picture of the difference");
    let out = common::shaderlab_in(&dir, &["diff", "phong", "--shaders", copy, "--json"]);
    let w: serde_json::Value = serde_json::from_str(&ok(&out)).expect("one JSON object");
    assert_eq!(v, w, "--diff DIR and shaderlab diff --shaders DIR say the same");
}

/// Runs `args` in `dir` expecting refusal with `code`: stderr holding `says` (in one line, for a
/// view's own errors and the watchdog's; a usage error adds where help is), nothing on stdout,
/// and no file left in `dir` but those there before.
fn refused(dir: &Path, args: &[&str], code: i32, says: &str) {
    refused_in(dir, args, code, says, true)
}

fn usage_error(dir: &Path, args: &[&str], says: &str) {
    refused_in(dir, args, 2, says, false)
}

fn refused_in(dir: &Path, args: &[&str], code: i32, says: &str, one_line: bool) {
    let before: Vec<PathBuf> = list(dir);
    let out = common::shaderlab_in(dir, args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(code), "{args:?}: {err}");
    assert!(err.contains(says), "{args:?}: {err}");
    if one_line {
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: one line: {err}");
    }
    assert!(
        out.stdout.is_empty(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stdout)
    );
    assert_eq!(list(dir), before, "{args:?}: no file written");
}

fn list(dir: &Path) -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = std::fs::read_dir(dir)
        .expect("the folder")
        .map(|e| e.expect("an entry").path())
        .collect();
    out.sort();
    out
}

#[test]
fn bad_views_get_one_line_and_write_nothing() {
    let dir = common::fresh_dir("views_cli_bad");
    let comment = line_of("phong.frag", "// The course's lines");
    let l = line_of("phong.frag", "vec3 L = safe_normalize");
    let view = |more: &[&str]| -> Vec<String> {
        let mut a: Vec<String> = ["view", "phong", "--size", SIZE, "--out", "v.png", "--npy", "v.npy"]
            .map(str::to_owned)
            .to_vec();
        a.extend(more.iter().map(|s| s.to_string()));
        a
    };
    let run = |more: &[&str], code: i32, says: &str| {
        let args = view(more);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        refused(&dir, &args, code, says);
    };
    run(
        &["--line", &format!("phong.frag:{comment}")],
        2,
        "assigns nothing; the nearest line",
    );
    run(
        &["--line", "nowhere.frag:3"],
        2,
        "nowhere.frag is not a file of a shader this lab draws",
    );
    run(
        &["--line", &format!("phong.frag:{l}"), "--name", "Q"],
        2,
        "does not assign `Q`; it assigns `L`",
    );
    let usage = |more: &[&str], says: &str| {
        let args = view(more);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        usage_error(&dir, &args, says);
    };
    usage(&["--line", "phong.frag"], "expected FILE:LINE");
    usage(&["--line", "phong.frag:0"], "expected FILE:LINE");
    usage(&["--line", "phong.frag:3", "--cost"], "cannot be used with");
    // Outputs refused before anything is drawn.
    usage_error(
        &dir,
        &["view", "phong", "--cost", "--out", "v.jpg"],
        "only PNG is written",
    );
    usage_error(&dir, &["view", "phong", "--cost", "--npy", "v.txt"], "use a .npy name");
    refused(
        &dir,
        &["view", "phong", "--cost", "--out", "missing/v.png"],
        1,
        "does not exist",
    );
    usage_error(&dir, &["view", "phong"], "which view?");
    usage_error(
        &dir,
        &["run", "phong", "--npy", "v.npy"],
        "add --line FILE:LINE or --cost",
    );
    usage_error(&dir, &["run", "phong", "--json"], "`--json` goes with");

    // A line of an include both stages use: choose the stage.
    let shaders = dir.join("both");
    common::copy_shaders(&shaders);
    std::fs::write(
        shaders.join("shared.glsl"),
        "vec3 twice(vec3 x) {\n    vec3 y = x * 2.0;\n    return y * 0.5;\n}\n",
    )
    .expect("the include");
    let edit = |file: &str, from: &str, to: &str| {
        let path = shaders.join(file);
        let text = std::fs::read_to_string(&path).expect("the copy");
        assert!(text.contains(from), "{file} holds {from}");
        std::fs::write(&path, text.replacen(from, to, 1)).expect("the edit");
    };
    edit(
        "phong.vert",
        "#include \"transform.glsl\"",
        "#include \"transform.glsl\"\n#include \"shared.glsl\"",
    );
    edit(
        "phong.vert",
        "N = normalize(normal_matrix * vertex_normal);",
        "N = twice(normalize(normal_matrix * vertex_normal));",
    );
    edit(
        "phong.frag",
        "#include \"safe_math.glsl\"",
        "#include \"safe_math.glsl\"\n#include \"shared.glsl\"",
    );
    edit(
        "phong.frag",
        "vec3 E = safe_normalize(-v);",
        "vec3 E = twice(safe_normalize(-v));",
    );
    let copy = shaders.to_str().expect("utf-8").to_owned();
    run(&["--shaders", &copy, "--line", "shared.glsl:2"], 2, "choose the stage");
    // With the stage chosen, the view is drawn.
    for stage in ["vertex", "fragment"] {
        let out = common::shaderlab_in(
            &dir,
            &[
                "view",
                "phong",
                "--shaders",
                &copy,
                "--line",
                "shared.glsl:2",
                "--stage",
                stage,
                "--size",
                SIZE,
                "--json",
            ],
        );
        let v: serde_json::Value = serde_json::from_str(&ok(&out)).expect("one JSON object");
        assert_eq!(v["stage"], stage, "{v}");
    }
}

/// A fragment shader that loops until its float stops growing: on lavapipe about a minute and
/// a half for a 2048² picture, which the watchdog gives up on.
const ENDLESS_FRAG: &str =
    "void main() {\n    float x = gl_FragCoord.x;\n    while (x >= 0.0) x += 1.0;\n    gl_FragColor = vec4(x);\n}\n";

#[test]
fn a_cost_view_of_a_shader_that_never_ends_meets_the_watchdog() {
    let dir = common::fresh_dir("views_cli_watchdog");
    std::fs::write(dir.join("v.vert"), "void main() { gl_Position = ftransform(); }\n").expect("v.vert");
    std::fs::write(dir.join("endless.frag"), ENDLESS_FRAG).expect("endless.frag");
    let before = list(&dir);
    let args = [
        "view",
        "legacy",
        "v.vert",
        "endless.frag",
        "--cost",
        "--size",
        "2048x2048",
        "--timeout",
        "1",
        "--out",
        "c.png",
    ];
    // Two lavapipe threads, so that the CPU the watchdog's second costs is the same on any
    // machine.
    let (out, cpu) = common::output_with_cpu(
        std::process::Command::new(env!("CARGO_BIN_EXE_shaderlab"))
            .current_dir(&dir)
            .args(args)
            .env("LP_NUM_THREADS", "2"),
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("the GPU did not finish a frame within 1 s: most likely a shader never ends"),
        "{err}"
    );
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    assert!(out.stdout.is_empty(), "{}", String::from_utf8_lossy(&out.stdout));
    assert_eq!(list(&dir), before, "no file written");
    // Ended by the watchdog, not by the frame (minutes of CPU): CPU seconds, which a busy
    // machine does not inflate.
    assert!(cpu < 20.0, "{cpu:.1} s of CPU");
}

#[test]
fn a_course_glsl_110_file_is_viewed_with_the_users_lines_and_names() {
    let dir = common::fresh_dir("views_cli_course");
    let course = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/course/seed000");
    for file in ["lab3.vert", "lab3.frag"] {
        std::fs::copy(course.join(file), dir.join(file)).expect("the course's file");
    }
    let text = std::fs::read_to_string(dir.join("lab3.frag")).expect("lab3.frag");
    let line = text.lines().position(|l| l.contains("vec4 Idiff =")).expect("the line") as u32 + 1;
    let at = format!("lab3.frag:{line}");
    let out = common::shaderlab_in(
        &dir,
        &[
            "view",
            "legacy",
            "lab3.vert",
            "lab3.frag",
            "--set",
            "object=teapot",
            "--line",
            &at,
            "--size",
            SIZE,
            "--json",
            "--npy",
            "v.npy",
        ],
    );
    let v: serde_json::Value = serde_json::from_str(&ok(&out)).expect("one JSON object");
    assert!(v["file"].as_str().is_some_and(|f| f.ends_with("lab3.frag")), "{v}");
    assert_eq!(v["line"], line, "{v}");
    assert_eq!(v["name"], "Idiff", "the user's name: {v}");
    assert_eq!(v["components"], 4, "{v}");
    assert!(v["drawn"].as_u64().is_some_and(|n| n > 1000), "{v}");
    let (shape, values) = read_npy(&dir.join("v.npy"));
    assert_eq!(shape, vec![HEIGHT as usize, WIDTH as usize, 4]);
    // Alpha is 1 wherever the line ran: the value is the course's vec4(…, 1.0).
    let ran: Vec<f32> = values
        .chunks_exact(4)
        .filter(|p| !p[0].is_nan())
        .map(|p| p[3])
        .collect();
    assert_eq!(ran.len() as u64, v["drawn"].as_u64().expect("drawn"));
    assert!(ran.iter().all(|&a| a == 1.0));
}

#[test]
fn the_view_command_is_listed_and_has_help() {
    let dir = common::fresh_dir("views_cli_help");
    let usage = ok(&common::shaderlab_in(&dir, &["--help"]));
    assert!(usage.contains("shaderlab view NAME --line FILE:LINE"), "{usage}");
    assert!(usage.contains("shaderlab view NAME --cost"), "{usage}");
    let help = ok(&common::shaderlab_in(&dir, &["view", "--help"]));
    for needle in [
        "Usage: shaderlab view NAME",
        "--line FILE:LINE",
        "--npy FILE.npy",
        "default NAME-view.png",
    ] {
        assert!(help.contains(needle), "{needle}: {help}");
    }
    let lab = ok(&common::shaderlab_in(&dir, &["view", "phong", "--help"]));
    for needle in ["--line <FILE:LINE>", "--cost", "--npy <FILE.npy>", "--diff <DIR>"] {
        assert!(lab.contains(needle), "{needle}: {lab}");
    }
    // Without an output asked for, the picture goes to NAME-cost.png here.
    let text = ok(&common::shaderlab_in(
        &dir,
        &["view", "phong", "--cost", "--size", SIZE],
    ));
    assert!(text.starts_with("cost: "), "{text}");
    let png = image::open(dir.join("phong-cost.png")).expect("the default picture");
    assert_eq!(png.height(), HEIGHT + picture::LEGEND_HEIGHT);
}

/// A big view holds about twice the memory of its plain frame at the same size, not four
/// times: its targets are read back band by band and given back as they are read. Measured as
/// a ratio of the two runs' peak resident memory (load cannot move it).
#[test]
fn a_big_view_holds_about_twice_the_memory_of_its_frame() {
    let dir = common::fresh_dir("views_cli_memory");
    let size = "4096x4096";
    let peak = |args: &[&str]| {
        let mut command = std::process::Command::new(env!("CARGO_BIN_EXE_shaderlab"));
        command.current_dir(&dir).args(args);
        let (out, usage) = common::output_with_usage(&mut command);
        ok(&out);
        assert!(usage.peak_kb > 0, "the system reports the peak");
        usage.peak_kb as f64
    };
    let plain = peak(&["run", "phong", "--size", size, "--screenshot", "plain.png"]);
    let line = format!("phong.frag:{}", line_of("phong.frag", "vec4 Idiff ="));
    for (what, args) in [
        (
            "cost",
            vec!["view", "phong", "--cost", "--size", size, "--out", "cost.png"],
        ),
        (
            "vec4 line",
            vec!["view", "phong", "--line", &line, "--size", size, "--out", "line.png"],
        ),
        (
            "vec4 line as an array",
            vec!["view", "phong", "--line", &line, "--size", size, "--npy", "line.npy"],
        ),
    ] {
        let ratio = peak(&args) / plain;
        assert!(
            ratio < 2.5,
            "{what}: the view's peak is {ratio:.2} times the plain frame's ({plain:.0} kB)"
        );
    }
}
