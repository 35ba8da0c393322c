//! Bad input and what the user sees: each test runs a lab example (no window: `DISPLAY` is
//! removed, and `--screenshot` renders offscreen) with one bad input and checks the exit status
//! (2 for usage errors, 1 for runtime errors) and a key phrase of the one message, and that
//! nothing panicked. The table in the README's "Bad input and what you see" lists the same rows.
//! The window-only rows (zero-height window, failures after the window opened) are in
//! `tests/e2e_window.rs`.
//!
//! Run alone with `cargo test --release --test bad_input`. The examples are built first (one
//! nested `cargo build --examples` per test binary).

mod common;

use common::example;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A fresh directory for one test: `target/tmp/bad_input/<test>/`.
fn test_dir(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("bad_input").join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("xdg")).expect("create the test directory");
    dir
}

/// What a run printed and how it ended.
struct Run {
    code: Option<i32>,
    stdout: String,
    stderr: String,
}

/// Runs `example args` in `dir`, with no display, and the extra environment.
fn run_in(dir: &Path, example_name: &str, args: &[&str], env: &[(&str, &str)]) -> Run {
    let mut command = Command::new(example(example_name));
    command
        .args(args)
        .current_dir(dir)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("RUST_BACKTRACE")
        .env("XDG_RUNTIME_DIR", dir.join("xdg"));
    for (k, v) in env {
        command.env(k, v);
    }
    let Output { status, stdout, stderr } = command.output().expect("run the example");
    let run = Run {
        code: status.code(),
        stdout: String::from_utf8_lossy(&stdout).into_owned(),
        stderr: String::from_utf8_lossy(&stderr).into_owned(),
    };
    println!(
        "$ {example_name} {}\n[exit {:?}]\n{}{}",
        args.join(" "),
        run.code,
        run.stdout,
        run.stderr
    );
    for bad in ["panicked", "RUST_BACKTRACE"] {
        assert!(
            !run.stdout.contains(bad) && !run.stderr.contains(bad),
            "{example_name} {args:?} printed `{bad}`:\n{}{}",
            run.stdout,
            run.stderr
        );
    }
    run
}

/// Runs a bad input and checks the exit status and that stderr says `phrases`.
fn expect_failure(test: &str, args: &[&str], env: &[(&str, &str)], code: i32, phrases: &[&str]) -> Run {
    let dir = test_dir(test);
    let run = run_in(&dir, "phong", args, env);
    assert_eq!(run.code, Some(code), "{args:?}: exit status\n{}", run.stderr);
    for phrase in phrases {
        assert!(
            run.stderr.contains(phrase),
            "{args:?}: stderr lacks `{phrase}`:\n{}",
            run.stderr
        );
    }
    // One message, not a wall of text.
    assert!(
        run.stderr.lines().count() <= 12,
        "{args:?}: too much output:\n{}",
        run.stderr
    );
    // A failed run writes no picture.
    let pngs = std::fs::read_dir(&dir)
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .is_ok_and(|e| e.path().extension().is_some_and(|x| x == "png"))
        })
        .count();
    assert_eq!(pngs, 0, "{args:?}: a failed run wrote a PNG");
    run
}

#[test]
fn broken_shader_names_file_line_and_column() {
    let dir = test_dir("broken_shader_files");
    let shaders = dir.join("shaders");
    common::copy_shaders(&shaders);
    let frag = shaders.join("phong.frag");
    let text = std::fs::read_to_string(&frag).unwrap();
    let line = text
        .lines()
        .position(|l| l.contains("void main"))
        .expect("phong.frag has main")
        + 1;
    std::fs::write(&frag, text.replacen("void main", "void main oops", 1)).unwrap();
    let shaders = shaders.to_str().unwrap();
    let run = expect_failure(
        "broken_shader",
        &["--shaders", shaders, "--screenshot", "out.png"],
        &[],
        1,
        &[&format!("phong.frag:{line}:"), "oops", "^"],
    );
    assert!(run.stderr.starts_with("phong: error: "), "{}", run.stderr);
}

#[test]
fn missing_shader_directory() {
    expect_failure(
        "missing_shader_dir",
        &["--shaders", "/nonexistent", "--screenshot", "out.png"],
        &[],
        1,
        &["phong: error: /nonexistent: shader directory not found"],
    );
}

#[test]
fn unknown_object() {
    expect_failure(
        "unknown_object",
        &["--object", "cone"],
        &[],
        2,
        &["unknown object `cone`; valid: cube, sphere, torus, teapot", "--help"],
    );
}

#[test]
fn rotation_with_two_numbers() {
    expect_failure(
        "rotate_two",
        &["--rotate", "1,2"],
        &[],
        2,
        &["`1,2`: expected three numbers X,Y,Z"],
    );
}

#[test]
fn zero_size() {
    expect_failure(
        "size_zero",
        &["--size", "0x0"],
        &[],
        2,
        &["expected WxH with each side between 1 and 8192"],
    );
}

#[test]
fn unknown_parameter_lists_the_valid_ones() {
    expect_failure(
        "set_unknown",
        &["--set", "Kx=1", "--screenshot", "out.png"],
        &[],
        2,
        &[
            "unknown parameter `Kx` for phong; valid: lightPosition, Ka,",
            "shininess",
        ],
    );
}

#[test]
fn nan_parameter() {
    expect_failure(
        "set_nan",
        &["--set", "Ka=nan", "--screenshot", "out.png"],
        &[],
        2,
        &["`nan` is not a finite number"],
    );
}

#[test]
fn zero_bench_frames() {
    expect_failure("bench_zero", &["--bench", "0"], &[], 2, &["0 is not in 1..=100000"]);
}

#[test]
fn unwritable_screenshot_path() {
    expect_failure(
        "screenshot_unwritable",
        &["--screenshot", "/nonexistent/x.png"],
        &[],
        1,
        &["phong: error: /nonexistent/x.png: the directory /nonexistent does not exist"],
    );
}

#[test]
fn no_gpu_adapter_says_what_to_install() {
    // Hide lavapipe (the Vulkan ICD) and allow only Vulkan, so wgpu finds no adapter at all.
    expect_failure(
        "no_adapter",
        &["--screenshot", "out.png"],
        &[("VK_ICD_FILENAMES", "/nonexistent"), ("WGPU_BACKEND", "vulkan")],
        1,
        &["no GPU adapter found", "apt-get install -y mesa-vulkan-drivers"],
    );
}

#[test]
fn no_display_writes_a_screenshot_instead() {
    let dir = test_dir("no_display");
    let run = run_in(&dir, "phong", &[], &[]);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert!(run.stderr.contains("no display found"), "{}", run.stderr);
    assert!(run.stdout.contains("wrote phong.png"), "{}", run.stdout);
    let image = image::open(dir.join("phong.png")).expect("phong.png").to_rgb8();
    assert_eq!(image.dimensions(), (640, 360));
}

#[test]
fn help_and_version_exit_zero() {
    let dir = test_dir("help");
    let run = run_in(&dir, "phong", &["--help"], &[]);
    assert_eq!(run.code, Some(0));
    assert!(
        run.stdout.contains("--screenshot") && run.stdout.contains("--set"),
        "{}",
        run.stdout
    );
}

#[test]
fn port_options_reject_bad_values() {
    expect_failure(
        "shading_unknown",
        &["--shading", "toon"],
        &[],
        2,
        &["unknown shading `toon`; valid: flat, gouraud, phong, blinn"],
    );
    expect_failure(
        "tess_too_small",
        &["--tess", "2"],
        &[],
        2,
        &["expected `auto` or a level from 3 to 512"],
    );
    let dir = test_dir("port_options_elsewhere");
    let run = run_in(
        &dir,
        "position_rgb",
        &["--shading", "flat", "--screenshot", "x.png"],
        &[],
    );
    assert_eq!(run.code, Some(2), "{}", run.stderr);
    assert!(run.stderr.contains("--shading applies to phong"), "{}", run.stderr);
    let run = run_in(
        &dir,
        "displacement",
        &["--set", "smooth=2", "--screenshot", "x.png"],
        &[],
    );
    assert_eq!(run.code, Some(2), "{}", run.stderr);
    assert!(run.stderr.contains("`smooth` takes 0 or 1"), "{}", run.stderr);
    assert!(!dir.join("x.png").exists());
}

#[test]
fn port_options_work_from_the_command_line() {
    let dir = test_dir("port_options_ok");
    let run = run_in(
        &dir,
        "phong",
        &[
            "--object",
            "torus",
            "--shading",
            "gouraud",
            "--tess",
            "auto",
            "--screenshot",
            "g.png",
        ],
        &[],
    );
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    let run = run_in(
        &dir,
        "displacement",
        &["--object", "cube", "--set", "smooth=1", "--screenshot", "s.png"],
        &[],
    );
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert!(dir.join("g.png").is_file() && dir.join("s.png").is_file());
}
