//! `shaderlab check NAME --shaders DIR`: a copy checked against the course's shaders across
//! the lab's states. A clean copy passes everywhere; a planted bug that the base state hides
//! fails at the states where it shows, each failing state naming the planted line; every
//! state's figures are `shaderlab diff`'s at that state; the report holds every picture; the
//! same command checks the same states; legacy pairs are checked with the user's own files and
//! lines; bad flags are usage errors.

mod common;

use std::path::{Path, PathBuf};

fn shaderlab(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_shaderlab"))
        .args(args)
        .output()
        .expect("shaderlab runs")
}

/// The built-in shaders in a fresh folder, `file` changed by replacing `from` with `to`.
fn copy_with(tag: &str, file: &str, from: &str, to: &str) -> PathBuf {
    let dir = common::output_dir().join(format!("check_{tag}"));
    let _ = std::fs::remove_dir_all(&dir);
    common::copy_shaders(&dir);
    if !from.is_empty() {
        let path = dir.join(file);
        let text = std::fs::read_to_string(&path).expect("the shader");
        assert!(text.contains(from), "{file} has `{from}`");
        std::fs::write(&path, text.replacen(from, to, 1)).expect("write the copy");
    }
    dir
}

fn line_of(path: &Path, what: &str) -> u64 {
    let text = std::fs::read_to_string(path).expect("the shader");
    text.lines().position(|l| l.contains(what)).expect("the line") as u64 + 1
}

fn check_json(args: &[&str]) -> (Option<i32>, serde_json::Value) {
    let mut all = vec!["check"];
    all.extend_from_slice(args);
    all.push("--json");
    let out = shaderlab(&all);
    let v = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!(
            "one JSON document ({e}); stderr:\n{}",
            String::from_utf8_lossy(&out.stderr)
        )
    });
    (out.status.code(), v)
}

#[test]
fn a_clean_copy_passes_at_every_state_and_the_states_are_the_same_for_the_same_seed() {
    let dir = copy_with("clean", "", "", "");
    let d = dir.to_str().expect("utf-8");
    let (code, v) = check_json(&["phong", "--shaders", d, "--states", "5", "--seed", "7"]);
    let states = v["states"].as_array().expect("states");
    assert_eq!(code, Some(0), "{v}");
    assert_eq!(v["failed"], 0, "{v}");
    assert_eq!(v["passed"].as_u64(), Some(states.len() as u64), "{v}");
    // The base state, every object, the states of record and 5 random ones.
    let origins = |w: &str| states.iter().filter(|s| s["origin"] == w).count();
    assert_eq!((origins("base"), origins("random")), (1, 5), "{v}");
    assert!(origins("object") >= 3 && origins("record") >= 3, "{v}");
    for s in states {
        assert_eq!(
            (s["differing"].as_u64(), s["pass"].as_bool()),
            (Some(0), Some(true)),
            "{s}"
        );
        assert_eq!(s["first_divergence"], serde_json::Value::Null, "{s}");
    }
    let sets = |v: &serde_json::Value| -> Vec<serde_json::Value> {
        v["states"]
            .as_array()
            .expect("states")
            .iter()
            .map(|s| s["set"].clone())
            .collect()
    };
    let (_, again) = check_json(&["phong", "--shaders", d, "--states", "5", "--seed", "7"]);
    assert_eq!(sets(&v), sets(&again), "the same seed, the same states");
    let (_, other) = check_json(&["phong", "--shaders", d, "--states", "5", "--seed", "8"]);
    assert_ne!(sets(&v), sets(&other), "another seed, other random states");
}

/// A diffuse term that never reaches 0 (`max(dot(N, L), 0.2)`): at the base state the light
/// is in front and the copy passes at 40 dB; with the light behind the surface it fails.
#[test]
fn a_planted_bug_fails_where_it_shows_at_its_line_with_diffs_figures_and_a_report() {
    let dir = copy_with("plant", "phong.frag", "max(dot(N, L), 0.0)", "max(dot(N, L), 0.2)");
    let d = dir.to_str().expect("utf-8");
    let planted = line_of(&dir.join("phong.frag"), "max(dot(N, L), 0.2)");
    let report = common::output_dir().join("check_report");
    let _ = std::fs::remove_dir_all(&report);
    let r = report.to_str().expect("utf-8");
    let (code, v) = check_json(&["phong", "--shaders", d, "--states", "12", "--report", r]);
    assert_eq!(code, Some(1), "{v}");
    let states = v["states"].as_array().expect("states");
    let failing: Vec<&serde_json::Value> = states.iter().filter(|s| s["pass"] == false).collect();
    assert!(!failing.is_empty(), "the bug shows somewhere: {v}");
    assert!(
        states[0]["pass"] == true && states[0]["differing"].as_u64() > Some(0),
        "the base state hides it: {v}"
    );
    assert_eq!(v["failed"].as_u64(), Some(failing.len() as u64), "{v}");
    for s in &failing {
        let first = &s["first_divergence"];
        assert!(first["file"].as_str().is_some_and(|f| f.ends_with("phong.frag")), "{s}");
        assert_eq!(first["line"], planted, "{s}");
        assert_eq!(first["name"], "Idiff", "{s}");
        assert!(s["psnr"].as_f64().is_some_and(|p| p < 40.0), "{s}");
    }
    // Each state's figures are `shaderlab diff`'s at that state: a failing one and a passing one.
    let passing = states
        .iter()
        .find(|s| s["pass"] == true && s["differing"].as_u64() > Some(0));
    for s in [Some(failing[0]), passing].into_iter().flatten() {
        let mut args = vec!["diff", "phong", "--shaders", d, "--json"];
        let sets: Vec<String> = s["set"]
            .as_array()
            .expect("a set list")
            .iter()
            .map(|w| w.as_str().expect("NAME=VALUE").to_owned())
            .collect();
        for w in &sets {
            args.extend(["--set", w.as_str()]);
        }
        let out = shaderlab(&args);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let diff: serde_json::Value = serde_json::from_slice(&out.stdout).expect("diff's JSON");
        assert_eq!(
            (&diff["psnr"], &diff["differing"], &diff["worst"]),
            (&s["psnr"], &s["differing"], &s["worst"]),
            "{s}"
        );
        if s["pass"] == false {
            assert_eq!(diff["first_divergence"], s["first_divergence"], "{s}");
        }
    }
    // The report: a page that holds each state's three pictures, the copy's source at the line.
    let html = std::fs::read_to_string(report.join("index.html")).expect("the report");
    let pictures: Vec<&str> = html.split("src=\"data:image/png;base64,").skip(1).collect();
    assert_eq!(pictures.len(), 3 * states.len(), "three pictures a state");
    use base64::Engine as _;
    let first = pictures[0].split('"').next().expect("a picture");
    let png = base64::engine::general_purpose::STANDARD.decode(first).expect("base64");
    let image = image::load_from_memory(&png).expect("a PNG");
    assert_eq!((image.width(), image.height()), (640, 360));
    assert!(html.contains("max(dot(N, L), 0.2)"), "the copy's line in the report");
    assert!(html.contains("class=\"at\""), "the line marked");
    assert!(
        !html.contains("http://") && !html.contains("https://"),
        "nothing from the network"
    );
}

/// legacy's pair against another pair: the user's own file and line.
#[test]
fn a_legacy_pair_is_checked_against_its_reference_with_the_users_lines() {
    let dir = common::output_dir().join("check_legacy");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("a folder");
    let course = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/course/seed000");
    for name in ["lab3.vert", "lab3.frag"] {
        std::fs::copy(course.join(name), dir.join(name)).expect("copy");
    }
    let mine = dir.join("mine.frag");
    let text = std::fs::read_to_string(course.join("lab3.frag")).expect("lab3.frag");
    let (needle, planted) = ("Kd * Idiff", "0.5 * Kd * Idiff");
    assert!(text.contains(needle));
    std::fs::write(&mine, text.replacen(needle, planted, 1)).expect("the copy");
    let p = |n: &str| dir.join(n).to_str().expect("utf-8").to_owned();
    let (vert, frag, mine_s) = (p("lab3.vert"), p("lab3.frag"), p("mine.frag"));
    // The pair's uniforms are parameters that start at 0: light it.
    let lit = [
        "--set",
        "Kd=0.8",
        "--set",
        "diffuseColor=1,0.5,0.2",
        "--set",
        "lightPosition=2,2,2",
    ];
    let run = |copy: &str| {
        let mut args = vec!["legacy", &vert, copy, "--reference", &vert, &frag, "--states", "2"];
        args.extend(lit);
        check_json(&args)
    };
    let (code, v) = run(&mine_s);
    assert_eq!(code, Some(1), "{v}");
    let failing: Vec<&serde_json::Value> = v["states"]
        .as_array()
        .expect("states")
        .iter()
        .filter(|s| s["pass"] == false)
        .collect();
    assert!(!failing.is_empty(), "{v}");
    let line = line_of(&mine, planted);
    for s in failing {
        let first = &s["first_divergence"];
        assert!(first["file"].as_str().is_some_and(|f| f.ends_with("mine.frag")), "{s}");
        assert_eq!(first["line"], line, "{s}");
    }
    let (code, v) = run(&frag);
    assert_eq!((code, &v["failed"]), (Some(0), &serde_json::json!(0)), "{v}");
}

#[test]
fn bad_flags_are_usage_errors_that_say_why() {
    let dir = copy_with("usage", "", "", "");
    let d = dir.to_str().expect("utf-8");
    for (args, says) in [
        (vec!["check", "phong"], "which copy?"),
        (vec!["check", "phong", "--shaders", d, "--states", "x"], "--states x"),
        (
            vec!["check", "phong", "--shaders", d, "--states", "100000"],
            "--states 100000",
        ),
        (vec!["check", "phong", "--shaders", d, "--min-db", "-3"], "--min-db -3"),
        (vec!["check", "phong", "--shaders", d, "--seed", "-1"], "--seed"),
        (
            vec!["check", "phong", "--shaders", d, "--screenshot", "x.png"],
            "--screenshot",
        ),
        (vec!["check", "legacy"], "--reference VERT0 FRAG0"),
        (vec!["check", "nosuchlab", "--shaders", d], "no lab called"),
    ] {
        let out = shaderlab(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}
