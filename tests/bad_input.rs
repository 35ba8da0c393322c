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
use std::process::{Command, Output, Stdio};

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
    /// CPU seconds the run used (user + system, all its threads): its work, which a busy
    /// machine does not inflate as it does the wall clock.
    cpu: f64,
}

/// Runs `example args` in `dir`, with no display, and the extra environment.
fn run_in(dir: &Path, example_name: &str, args: &[&str], env: &[(&str, &str)]) -> Run {
    run_via(&[], dir, example_name, args, env)
}

/// `run_in` with the example run by `wrapper` (`wrapper... example args`) when it is not empty.
fn run_via(wrapper: &[String], dir: &Path, example_name: &str, args: &[&str], env: &[(&str, &str)]) -> Run {
    let mut command = match wrapper.split_first() {
        Some((program, rest)) => {
            let mut command = Command::new(program);
            command.args(rest).arg(example(example_name));
            command
        }
        None => Command::new(example(example_name)),
    };
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
    let (Output { status, stdout, stderr }, cpu) = common::output_with_cpu(command.stdin(Stdio::null()));
    let run = Run {
        code: status.code(),
        stdout: String::from_utf8_lossy(&stdout).into_owned(),
        stderr: String::from_utf8_lossy(&stderr).into_owned(),
        cpu,
    };
    println!(
        "$ {example_name} {}\n[exit {:?}, {cpu:.2} s of CPU]\n{}{}",
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
    assert!(
        run.stderr.contains("position_rgb has no shading models"),
        "{}",
        run.stderr
    );
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

// ---------------------------------------------------------------------------------------------
// Nothing a user types loses a file (issue 9)

#[test]
fn screenshot_refuses_other_formats_and_keeps_the_file() {
    let dir = test_dir("screenshot_jpg");
    std::fs::write(dir.join("x.jpg"), b"a holiday photo").unwrap();
    for name in ["x.jpg", "x.bmp", "x"] {
        let run = run_in(&dir, "phong", &["--screenshot", name], &[]);
        assert_eq!(run.code, Some(2), "{name}: {}", run.stderr);
        assert!(
            run.stderr
                .contains(&format!("phong: error: {name}: only PNG is written; use a .png name")),
            "{name}: {}",
            run.stderr
        );
    }
    assert_eq!(std::fs::read(dir.join("x.jpg")).unwrap(), b"a holiday photo");
    assert_eq!(common::names_in(&dir), ["x.jpg", "xdg"]);
}

#[test]
fn screenshot_into_a_directory_says_so() {
    let dir = test_dir("screenshot_dir");
    std::fs::create_dir(dir.join("shots.png")).unwrap();
    let run = run_in(&dir, "phong", &["--screenshot", "shots.png"], &[]);
    assert_eq!(run.code, Some(2), "{}", run.stderr);
    assert!(run.stderr.contains("shots.png: is a directory"), "{}", run.stderr);
    assert_eq!(common::names_in(&dir), ["shots.png", "xdg"]);
    assert!(common::names_in(&dir.join("shots.png")).is_empty());
}

/// A copy of the shaders in `dir/shaders` with `line` inserted after `#version` in phong.frag.
fn shaders_with(dir: &Path, line: &str) -> String {
    let shaders = dir.join("shaders");
    common::copy_shaders(&shaders);
    let frag = shaders.join("phong.frag");
    let text = std::fs::read_to_string(&frag).unwrap();
    std::fs::write(
        &frag,
        text.replacen("#version 450\n", &format!("#version 450\n{line}\n"), 1),
    )
    .unwrap();
    shaders.to_str().unwrap().to_owned()
}

#[test]
fn includes_cannot_reach_outside_the_shader_directory() {
    for (include, phrase) in [
        ("/etc/passwd", "/etc/passwd is an absolute path"),
        ("/dev/zero", "/dev/zero is an absolute path"),
        (
            "../../../../../../../../etc/passwd",
            "lies outside the shader directory",
        ),
    ] {
        let dir = test_dir("include_outside");
        let shaders = shaders_with(&dir, &format!("#include \"{include}\""));
        let run = run_in(&dir, "phong", &["--shaders", &shaders, "--screenshot", "out.png"], &[]);
        assert_eq!(run.code, Some(1), "{include}: {}", run.stderr);
        assert!(run.stderr.contains("phong.frag:2:1: cannot include"), "{}", run.stderr);
        assert!(run.stderr.contains(phrase), "{include}: {}", run.stderr);
        assert!(
            !run.stderr.contains("root:"),
            "{include}: leaked a file:\n{}",
            run.stderr
        );
        assert!(!dir.join("out.png").exists());
    }
}

#[test]
fn unclear_loader_cases_get_clear_messages() {
    for (what, line, phrase) in [
        (
            "self",
            "#include \"phong.frag\"",
            "phong.frag:2:1: phong.frag includes itself",
        ),
        ("comment", "#include \"safe_math.glsl\" // helpers", ""),
        (
            "junk",
            "#include \"safe_math.glsl\" junk",
            "unexpected `junk` after #include",
        ),
    ] {
        let dir = test_dir("loader_messages");
        let shaders = shaders_with(&dir, line);
        let run = run_in(&dir, "phong", &["--shaders", &shaders, "--screenshot", "out.png"], &[]);
        if phrase.is_empty() {
            assert_eq!(run.code, Some(0), "{what}: {}", run.stderr);
        } else {
            assert_eq!(run.code, Some(1), "{what}: {}", run.stderr);
            assert!(run.stderr.contains(phrase), "{what}: {}", run.stderr);
        }
    }
    // An empty file: named, and called empty.
    let dir = test_dir("loader_empty");
    let shaders = shaders_with(&dir, "");
    std::fs::write(Path::new(&shaders).join("phong.frag"), "").unwrap();
    let run = run_in(&dir, "phong", &["--shaders", &shaders, "--screenshot", "out.png"], &[]);
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    assert!(
        run.stderr
            .contains("shaders/phong.frag: the file is empty; a fragment shader needs"),
        "{}",
        run.stderr
    );
    // A member of another type than its parameter feeds (the block is filled by name).
    let dir = test_dir("loader_int_ka");
    let shaders = shaders_with(&dir, "");
    let params = Path::new(&shaders).join("phong_params.glsl");
    let text = std::fs::read_to_string(&params).unwrap();
    std::fs::write(&params, text.replace("float Ka;", "int Ka;")).unwrap();
    let run = run_in(&dir, "phong", &["--shaders", &shaders, "--screenshot", "out.png"], &[]);
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    assert!(
        run.stderr.contains("parameter `Ka` (int Ka) takes whole numbers"),
        "{}",
        run.stderr
    );
    assert!(!dir.join("out.png").exists());
}

#[test]
fn glsl2wgsl_refuses_to_overwrite_its_input() {
    let dir = test_dir("glsl2wgsl_same_file");
    common::copy_shaders(&dir.join("shaders"));
    std::fs::create_dir(dir.join("shaders/sub")).unwrap();
    let frag = dir.join("shaders/phong.frag");
    let original = std::fs::read(&frag).unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(&frag, dir.join("link.wgsl")).unwrap();
    for out in [
        "shaders/phong.frag",
        "shaders/sub/../phong.frag",
        "./shaders/phong.frag",
        "link.wgsl",
    ] {
        if !dir.join(out).exists() {
            continue;
        }
        let run = run_in(&dir, "glsl2wgsl", &["shaders/phong.frag", "-o", out], &[]);
        assert_eq!(run.code, Some(2), "-o {out}: {}", run.stderr);
        assert!(
            run.stderr
                .contains("shaders/phong.frag, one of the shader files this run reads"),
            "-o {out}: {}",
            run.stderr
        );
        assert_eq!(std::fs::read(&frag).unwrap(), original, "-o {out} changed the source");
    }
    // A different file is fine, and written whole.
    let run = run_in(&dir, "glsl2wgsl", &["shaders/phong.frag", "-o", "phong.wgsl"], &[]);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert!(std::fs::read_to_string(dir.join("phong.wgsl"))
        .unwrap()
        .contains("fn main"));
    assert!(
        !common::names_in(&dir)
            .iter()
            .any(|n| n.starts_with(".sl-") || n.contains(".tmp")),
        "{:?}",
        common::names_in(&dir)
    );
}

// ---------------------------------------------------------------------------------------------
// Issue 9: a hostile-input sweep's defects, each reproduced here.

#[test]
fn negative_numbers_after_a_space_parse() {
    let dir = test_dir("negative_numbers");
    for args in [
        &["--rotate", "-30,0,0", "--screenshot", "a.png"][..],
        &["--time", "-5", "--screenshot", "b.png"],
        &["--set", "xangle=-45", "--screenshot", "c.png"],
    ] {
        let run = run_in(&dir, "noise", args, &[]);
        assert_eq!(run.code, Some(0), "{args:?}: {}", run.stderr);
    }
    // Still validated.
    let run = run_in(&dir, "phong", &["--size", "-1x5"], &[]);
    assert_eq!(run.code, Some(2), "{}", run.stderr);
    assert!(run.stderr.contains("expected WxH"), "{}", run.stderr);
}

#[test]
fn a_closed_or_full_stdout_is_an_error_not_a_panic() {
    use std::process::Stdio;
    let dir = test_dir("closed_stdout");
    // `phong --bench 5 | true`: the reader is gone before the line is written.
    let mut child = Command::new(example("phong"))
        .args(["--bench", "5"])
        .current_dir(&dir)
        .env_remove("DISPLAY")
        .env("XDG_RUNTIME_DIR", dir.join("xdg"))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run phong");
    drop(child.stdout.take());
    let out = child.wait_with_output().expect("wait");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(!err.contains("panicked") && err.contains("stdout"), "{err}");
    // `> /dev/full`
    if let Ok(full) = std::fs::OpenOptions::new().write(true).open("/dev/full") {
        let out = Command::new(example("phong"))
            .args(["--bench", "5"])
            .current_dir(&dir)
            .env_remove("DISPLAY")
            .env("XDG_RUNTIME_DIR", dir.join("xdg"))
            .stdout(full)
            .output()
            .expect("run phong");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{err}");
        assert!(!err.contains("panicked"), "{err}");
    }
}

#[test]
fn usage_errors_come_before_any_rendering() {
    let dir = test_dir("usage_first");
    let run = run_in(&dir, "phong", &["--bench", "100000", "--set", "Kx=1"], &[]);
    assert_eq!(run.code, Some(2), "{}", run.stderr);
    assert!(run.stdout.is_empty(), "nothing may be benchmarked: {}", run.stdout);
    // 100,000 frames take minutes of CPU; the error comes before the GPU is opened.
    assert!(run.cpu < 2.0, "the error must come first: {:.1} s of CPU", run.cpu);
    let run = run_in(&dir, "phong", &["--set", "Ka=2,3"], &[]);
    assert_eq!(run.code, Some(2), "{}", run.stderr);
    assert!(
        !run.stderr.contains("writing a screenshot instead"),
        "validated before falling back: {}",
        run.stderr
    );
}

#[test]
fn shaders_flag_naming_a_file_says_so() {
    let dir = test_dir("shaders_file");
    std::fs::write(dir.join("afile"), "x").unwrap();
    let run = run_in(&dir, "phong", &["--shaders", "afile", "--screenshot", "x.png"], &[]);
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    assert!(run.stderr.contains("is not a directory"), "{}", run.stderr);
}

#[test]
fn no_display_at_all_falls_back_to_a_screenshot_and_says_why() {
    let dir = test_dir("no_display");
    let run = run_in(&dir, "phong", &[], &[]);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert!(
        run.stderr.contains("neither WAYLAND_DISPLAY nor DISPLAY is set"),
        "{}",
        run.stderr
    );
    assert!(dir.join("phong.png").is_file());
}

#[test]
fn a_bad_display_names_no_source_path() {
    let dir = test_dir("bad_display");
    let run = run_in(&dir, "phong", &[], &[("DISPLAY", ":4321")]);
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    assert!(run.stderr.contains(":4321"), "{}", run.stderr);
    assert!(
        !run.stderr.contains(".cargo") && !run.stderr.contains("registry"),
        "{}",
        run.stderr
    );
}

#[test]
fn no_runtime_dir_prints_no_mesa_warnings() {
    let dir = test_dir("no_xdg");
    let out = Command::new(example("phong"))
        .args(["--screenshot", "x.png"])
        .current_dir(&dir)
        .env_remove("DISPLAY")
        .env_remove("XDG_RUNTIME_DIR")
        .output()
        .expect("run phong");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(!err.contains("XDG_RUNTIME_DIR"), "{err}");
}

// ---------------------------------------------------------------------------------------------
// Issue 17: user files, pictures and output files.

/// A PNG whose IHDR says `width`x`height` (colour type `colour`: 0 grey, 2 RGB) and which has no
/// pixel data: a decompression bomb as its header shows it, a few dozen bytes.
fn png_header(width: u32, height: u32, colour: u8) -> Vec<u8> {
    fn crc32(bytes: &[u8]) -> u32 {
        let mut crc = !0u32;
        for &b in bytes {
            crc ^= u32::from(b);
            for _ in 0..8 {
                crc = if crc & 1 == 1 {
                    (crc >> 1) ^ 0xEDB8_8320
                } else {
                    crc >> 1
                };
            }
        }
        !crc
    }
    fn chunk(kind: &[u8; 4], data: &[u8]) -> Vec<u8> {
        let mut c = (data.len() as u32).to_be_bytes().to_vec();
        c.extend_from_slice(kind);
        c.extend_from_slice(data);
        c.extend_from_slice(&crc32(&c[4..]).to_be_bytes());
        c
    }
    let mut ihdr = width.to_be_bytes().to_vec();
    ihdr.extend_from_slice(&height.to_be_bytes());
    ihdr.extend_from_slice(&[8, colour, 0, 0, 0]);
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    png.extend(chunk(b"IHDR", &ihdr));
    png.extend(chunk(b"IEND", &[]));
    png
}

/// A 24-bit BMP header for `width`x`height` followed by `pixels`.
fn bmp(width: i32, height: i32, pixels: &[u8]) -> Vec<u8> {
    let mut b = b"BM".to_vec();
    b.extend_from_slice(&(54 + pixels.len() as u32).to_le_bytes());
    b.extend_from_slice(&[0; 4]);
    b.extend_from_slice(&54u32.to_le_bytes());
    b.extend_from_slice(&40u32.to_le_bytes());
    b.extend_from_slice(&width.to_le_bytes());
    b.extend_from_slice(&height.to_le_bytes());
    b.extend_from_slice(&1u16.to_le_bytes());
    b.extend_from_slice(&24u16.to_le_bytes());
    b.extend_from_slice(&[0; 24]);
    b.extend_from_slice(pixels);
    b
}

/// A GLSL 1.10 pair for `legacy` sampling `uniform sampler2D tex`.
fn legacy_texture_shaders(dir: &Path) {
    std::fs::write(
        dir.join("t.vert"),
        "varying vec2 uv;\nvoid main() { uv = gl_MultiTexCoord0.st; gl_Position = ftransform(); }\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("t.frag"),
        "uniform sampler2D tex;\nvarying vec2 uv;\nvoid main() { gl_FragColor = texture2D(tex, uv); }\n",
    )
    .unwrap();
}

/// Runs `example args` in `dir` and checks a failure: exit status, one short message holding
/// each phrase, no PNG written.
fn expect_failure_of(dir: &Path, example_name: &str, args: &[&str], code: i32, phrases: &[&str]) -> Run {
    let run = run_in(dir, example_name, args, &[]);
    assert_eq!(run.code, Some(code), "{args:?}: exit status\n{}", run.stderr);
    for phrase in phrases {
        assert!(
            run.stderr.contains(phrase),
            "{args:?}: stderr lacks `{phrase}`:\n{}",
            run.stderr
        );
    }
    assert!(
        run.stderr.len() < 1000 && run.stderr.lines().count() <= 3,
        "{args:?}: too much output:\n{}",
        run.stderr
    );
    assert!(!dir.join("o.png").exists(), "{args:?}: a failed run wrote a PNG");
    run
}

#[test]
fn legacy_texture_wider_than_textures_go_is_an_error_not_a_panic() {
    let dir = test_dir("legacy_wide_texture");
    legacy_texture_shaders(&dir);
    image::GrayImage::new(16385, 1).save(dir.join("w.png")).unwrap();
    expect_failure_of(
        &dir,
        "legacy",
        &["t.vert", "t.frag", "--texture", "tex=w.png", "--screenshot", "o.png"],
        1,
        &["legacy: error: w.png: the picture is 16385x1 pixels; textures are limited to 16384 pixels a side"],
    );
    // At the limit it is drawn.
    image::GrayImage::new(16384, 1).save(dir.join("w.png")).unwrap();
    let run = run_in(
        &dir,
        "legacy",
        &[
            "t.vert",
            "t.frag",
            "--texture",
            "tex=w.png",
            "--screenshot",
            "o.png",
            "--size",
            "8x8",
        ],
        &[],
    );
    assert_eq!(run.code, Some(0), "{}", run.stderr);
}

#[test]
fn picture_bombs_are_refused_from_their_header() {
    let dir = test_dir("picture_bombs");
    std::fs::write(dir.join("bomb.png"), png_header(22600, 22600, 0)).unwrap();
    std::fs::write(dir.join("rgb.png"), png_header(13000, 13000, 2)).unwrap();
    let bomb = expect_failure_of(
        &dir,
        "texparams",
        &["--texture", "bomb.png", "--screenshot", "o.png"],
        1,
        &["texparams: error: bomb.png: the picture is 22600x22600 pixels; textures are limited to 16384 pixels a side"],
    );
    let rgb = expect_failure_of(
        &dir,
        "suzanne_texture",
        &["--texture", "rgb.png", "--screenshot", "o.png"],
        1,
        &["rgb.png: the picture is 13000x13000 pixels (169000000 pixels); pictures are limited to 67108864 pixels (256 MiB as RGBA, e.g. 8192x8192)"],
    );
    // Nothing was decoded: CPU seconds (the unfixed run took 17 s and 4 GB for the first).
    for (name, run) in [("bomb.png", bomb), ("rgb.png", rgb)] {
        assert!(run.cpu < 5.0, "{name}: {:.1} s of CPU", run.cpu);
    }
}

#[test]
fn labs_that_draw_no_picture_or_model_refuse_the_flags() {
    let dir = test_dir("files_not_taken");
    std::fs::write(dir.join("bomb.png"), png_header(22600, 22600, 0)).unwrap();
    // Refused before the file is even read: the bomb is not looked at.
    expect_failure_of(
        &dir,
        "phong",
        &["--texture", "bomb.png", "--screenshot", "o.png"],
        2,
        &["phong: error: `--texture bomb.png`: phong samples no picture from a file (the labs that do: suzanne_texture, suzanne_texture_color, texparams, legacy)"],
    );
    expect_failure_of(
        &dir,
        "phong",
        &["--model", "missing.obj", "--screenshot", "o.png"],
        2,
        &["phong: error: `--model missing.obj`: phong draws no model from a file (the labs that do: suzanne_"],
    );
    expect_failure_of(
        &dir,
        "suzanne_texture",
        &["--texture", "tex=bomb.png", "--screenshot", "o.png"],
        2,
        &["suzanne_texture takes one picture, --texture FILE, without a NAME="],
    );
}

#[test]
fn user_files_must_be_regular_files_within_a_size_cap() {
    let dir = test_dir("user_file_rule");
    legacy_texture_shaders(&dir);
    // A FIFO stands for /dev/zero and friends: not a regular file (and opening it would block).
    let status = Command::new("mkfifo")
        .arg(dir.join("fifo"))
        .status()
        .expect("run mkfifo");
    assert!(status.success());
    for (example_name, args, what) in [
        ("legacy", &["fifo", "t.frag"][..], "shader files"),
        ("legacy", &["t.vert", "t.frag", "--texture", "tex=fifo"][..], "pictures"),
        ("suzanne_phong", &["--model", "fifo"][..], "OBJ models"),
    ] {
        let args: Vec<&str> = args.iter().copied().chain(["--screenshot", "o.png"]).collect();
        expect_failure_of(
            &dir,
            example_name,
            &args,
            1,
            &[&format!(
                "fifo: not a regular file (a device, pipe or socket); {what} must be regular files"
            )],
        );
    }
    // Sparse files of 1 GiB: refused from their size, nothing read, nothing echoed.
    for name in ["big.frag", "big.obj", "big.png"] {
        std::fs::File::create(dir.join(name)).unwrap().set_len(1 << 30).unwrap();
    }
    expect_failure_of(
        &dir,
        "legacy",
        &["t.vert", "big.frag", "--screenshot", "o.png"],
        1,
        &["big.frag: 1073741824 bytes (1 GiB); shader files are limited to 1048576 bytes (1 MiB)"],
    );
    expect_failure_of(
        &dir,
        "suzanne_phong",
        &["--model", "big.obj", "--screenshot", "o.png"],
        1,
        &["big.obj: 1073741824 bytes (1 GiB); OBJ models are limited to 268435456 bytes (256 MiB)"],
    );
    expect_failure_of(
        &dir,
        "texparams",
        &["--texture", "big.png", "--screenshot", "o.png"],
        1,
        &["big.png: 1073741824 bytes (1 GiB); pictures are limited to 67108864 bytes (64 MiB)"],
    );
}

#[test]
fn damaged_pictures_say_what_is_wrong() {
    let dir = test_dir("damaged_pictures");
    let whole = bmp(4, 2, &[64; 24]);
    std::fs::write(dir.join("cut.bmp"), &whole[..60]).unwrap();
    std::fs::write(dir.join("zero.bmp"), bmp(0, 2, &[])).unwrap();
    expect_failure_of(
        &dir,
        "suzanne_texture",
        &["--texture", "cut.bmp", "--screenshot", "o.png"],
        1,
        &["suzanne_texture: error: cut.bmp: the BMP file (4x2 pixels) ends early: it is cut short or damaged"],
    );
    expect_failure_of(
        &dir,
        "suzanne_texture",
        &["--texture", "zero.bmp", "--screenshot", "o.png"],
        1,
        &["suzanne_texture: error: zero.bmp: the BMP header says 0x2 pixels; a picture needs at least 1x1"],
    );
}

#[test]
fn negative_bench_frames_are_out_of_range() {
    expect_failure(
        "bench_negative",
        &["--bench", "-1"],
        &[],
        2,
        &["invalid value '-1' for '--bench <N>': -1 is not in 1..=100000"],
    );
}

/// How a child runs with the folder `ro` of its directory not writable to it, even as root.
#[cfg(unix)]
struct ReadOnly {
    /// The command the child runs under (empty: none).
    wrapper: Vec<String>,
    /// The folder made immutable, made mutable again when dropped.
    immutable: Option<PathBuf>,
}

#[cfg(unix)]
impl Drop for ReadOnly {
    fn drop(&mut self) {
        if let Some(ro) = &self.immutable {
            let _ = Command::new("chattr").arg("-i").arg(ro).status();
        }
    }
}

/// Makes `dir/ro` unwritable to a child: mode 0555 where that is enough (a normal user), else a
/// read-only bind mount of it in a user and mount namespace of the child's own (`unshare -rm`,
/// which leaves nothing behind), else the immutable attribute (`chattr +i`). None of them
/// working is a failure saying what each answered, never a skip.
#[cfg(unix)]
fn read_only_folder(dir: &Path) -> ReadOnly {
    use std::os::unix::fs::PermissionsExt;
    let ro = dir.join("ro");
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o555)).unwrap();
    let writable = |d: &Path| {
        let probe = d.join("probe");
        let ok = std::fs::write(&probe, b"").is_ok();
        let _ = std::fs::remove_file(&probe);
        ok
    };
    if !writable(&ro) {
        return ReadOnly {
            wrapper: Vec::new(),
            immutable: None,
        };
    }
    let mut tried = vec!["mode 0555: still writable (root)".to_string()];
    let mount = "mount -o bind,ro ro ro";
    let probe = Command::new("unshare")
        .args(["-rm", "sh", "-c"])
        .arg(format!("{mount} && ! (: > ro/probe) 2>/dev/null"))
        .current_dir(dir)
        .output();
    match probe {
        Ok(out) if out.status.success() => {
            let wrapper = ["unshare", "-rm", "sh", "-c", &format!("{mount} && exec \"$@\""), "sh"];
            return ReadOnly {
                wrapper: wrapper.map(String::from).to_vec(),
                immutable: None,
            };
        }
        Ok(out) => tried.push(format!(
            "unshare -rm sh -c '{mount}': {} {}",
            out.status,
            String::from_utf8_lossy(&out.stderr).trim()
        )),
        Err(e) => tried.push(format!("unshare: {e} (util-linux)")),
    }
    let _ = std::fs::remove_file(ro.join("probe"));
    match Command::new("chattr").arg("+i").arg(&ro).output() {
        Ok(out) if out.status.success() => {
            let made = ReadOnly {
                wrapper: Vec::new(),
                immutable: Some(ro.clone()),
            };
            if !writable(&ro) {
                return made;
            }
            tried.push("chattr +i: still writable".to_string());
        }
        Ok(out) => tried.push(format!(
            "chattr +i: {} {}",
            out.status,
            String::from_utf8_lossy(&out.stderr).trim()
        )),
        Err(e) => tried.push(format!("chattr: {e} (e2fsprogs)")),
    }
    panic!(
        "cannot make a folder this test's child cannot write; run it as a normal user, or allow \
         user namespaces (unshare -rm) or chattr +i:\n  {}",
        tried.join("\n  ")
    );
}

#[test]
#[cfg(unix)]
fn a_read_only_screenshot_folder_is_found_before_the_gpu_is_opened() {
    let dir = test_dir("read_only_folder");
    std::fs::create_dir(dir.join("ro")).unwrap();
    let ro = read_only_folder(&dir);
    // With no GPU to be found, a run that got as far as opening one would say so instead.
    let run = run_via(
        &ro.wrapper,
        &dir,
        "phong",
        &["--screenshot", "ro/x.png"],
        &[("VK_ICD_FILENAMES", "/nonexistent"), ("WGPU_BACKEND", "vulkan")],
    );
    drop(ro);
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    assert!(
        run.stderr
            .starts_with("phong: error: ro/x.png: cannot create a file in ro: "),
        "{}",
        run.stderr
    );
    assert!(!run.stderr.contains("GPU"), "{}", run.stderr);
    assert!(!dir.join("ro/x.png").exists(), "ro/x.png was written");
}

#[test]
fn screenshot_names_up_to_255_bytes_work() {
    let dir = test_dir("long_names");
    let name = format!("{}.png", "a".repeat(251));
    let run = run_in(&dir, "phong", &["--screenshot", &name, "--size", "8x8"], &[]);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    let names: Vec<String> = common::names_in(&dir).into_iter().filter(|n| n != "xdg").collect();
    assert_eq!(names, [name]);
}

/// Issue 17: hostile shaders — a 10,000-term sum, 10,000 nested `(`, 40 nested macros that
/// double, 40 functions that each call the last twice, a 5 MB file — were stack overflows
/// (exit 134, killing a `glsl2wgsl --all` batch), gigabytes, a driver crash or minutes. They
/// are now errors at the file and line, in every front end, in well under a second each.
#[test]
fn hostile_shaders_are_errors_at_their_line() {
    let dir = test_dir("hostile_shaders");
    let write = |name: &str, text: &str| std::fs::write(dir.join(name), text).unwrap();
    let sum = format!("float deep(float x) {{ return {}; }}", vec!["x"; 10_000].join(" + "));
    let parens = format!(
        "float deep(float x) {{ return {}x{}; }}",
        "(".repeat(10_000),
        ")".repeat(10_000)
    );
    let macros: String = (0..40).map(|i| format!("#define A{} (A{i}+A{i})\n", i + 1)).collect();
    let macros = format!("#define A0 1.0\n{macros}float bomb() {{ return A40; }}");
    let chain: String = (0..40)
        .map(|i| format!("float f{}(float x) {{ return f{i}(x) + f{i}(x); }}\n", i + 1))
        .collect();
    let chain = format!("float f0(float x) {{ return x; }}\n{chain}");
    write("v.vert", "void main() { gl_Position = ftransform(); }\n");
    let legacy_main = "\nvoid main() { gl_FragColor = vec4(1.0); }\n";
    for (name, body) in [
        ("sum", &sum),
        ("parens", &parens),
        ("macros", &macros),
        ("chain", &chain),
    ] {
        write(&format!("{name}.frag"), &format!("{body}{legacy_main}"));
    }
    let limits = [
        ("sum", 1, "nests too deeply"),
        ("parens", 1, "nests too deeply"),
        ("macros", 42, "`A40`: the shader's macro expansions pass 262144 tokens"),
        ("chain", 14, "`f13` is "),
    ];
    let mut runs = Vec::new();
    for (name, line, phrase) in limits {
        let at = format!("{name}.frag:{line}:");
        for (example, args) in [
            (
                "legacy",
                vec!["v.vert", &format!("{name}.frag") as &str, "--screenshot", "out.png"],
            ),
            ("glsl2wgsl", vec!["--legacy", "v.vert", &format!("{name}.frag")]),
        ] {
            let run = run_in(&dir, example, &args, &[]);
            assert_eq!(run.code, Some(1), "{example} {name}: {}", run.stderr);
            assert!(
                run.stderr.contains(&at) && run.stderr.contains(phrase),
                "{example} {name}: {}",
                run.stderr
            );
            runs.push((format!("{example} {name}"), run.cpu));
        }
    }
    // The GLSL 450 loader: `phong --shaders DIR` and a `glsl2wgsl --all` batch.
    for ((name, line, phrase), body) in limits.into_iter().zip([&sum, &parens, &macros, &chain]) {
        let case = dir.join(name);
        std::fs::create_dir_all(&case).unwrap();
        let shaders = shaders_with(&case, body);
        let run = run_in(&case, "phong", &["--shaders", &shaders, "--screenshot", "out.png"], &[]);
        assert_eq!(run.code, Some(1), "phong {name}: {}", run.stderr);
        let at = format!("phong.frag:{}:", line + 1);
        assert!(
            run.stderr.contains(&at) && run.stderr.contains(phrase),
            "phong {name}: {}",
            run.stderr
        );
        runs.push((format!("phong {name}"), run.cpu));
        let run = run_in(&case, "glsl2wgsl", &["--all", &shaders, "wgsl"], &[]);
        assert_eq!(run.code, Some(1), "glsl2wgsl --all {name}: {}", run.stderr);
        assert!(
            run.stderr.contains(&at) && run.stderr.contains(phrase),
            "glsl2wgsl --all {name}: {}",
            run.stderr
        );
        runs.push((format!("glsl2wgsl --all {name}"), run.cpu));
    }
    // A legacy file is a shader file like any other: at most 1 MiB.
    write(
        "big.frag",
        &format!("{}{legacy_main}", "// a comment line of a big file\n".repeat(160_000)),
    );
    let run = run_in(&dir, "legacy", &["v.vert", "big.frag", "--screenshot", "out.png"], &[]);
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    assert!(
        run.stderr
            .contains("big.frag: 5120043 bytes (4.9 MiB); shader files are limited to 1048576 bytes (1 MiB)"),
        "{}",
        run.stderr
    );
    runs.push(("legacy big.frag".to_string(), run.cpu));
    // Each an error in well under a second of CPU (busy machines do not inflate it), where the
    // unfixed runs took minutes or gigabytes.
    println!("CPU seconds: {runs:?}");
    for (what, cpu) in runs {
        assert!(cpu < 1.0, "{what}: {cpu:.2} s of CPU");
    }
}

/// Issue 17: `uniform float a[1000]` took 18 to 24 s to compile (the translation copied the
/// whole array into a private one per invocation); it is read in place now. Larger than a
/// uniform block (16 KiB) is an error naming the uniform.
#[test]
fn large_legacy_uniform_arrays_compile_fast_or_are_named() {
    let dir = test_dir("legacy_uniform_arrays");
    std::fs::write(dir.join("v.vert"), "void main() { gl_Position = ftransform(); }\n").unwrap();
    let frag = |n: u32| {
        format!(
            "uniform float a[{n}];\nvoid main() {{ gl_FragColor = vec4(a[3], a[{}], 0.0, 1.0); }}\n",
            n - 1
        )
    };
    std::fs::write(dir.join("a1000.frag"), frag(1000)).unwrap();
    std::fs::write(dir.join("a100000.frag"), frag(100_000)).unwrap();
    let mut command = Command::new(example("legacy"));
    command
        .args(["v.vert", "a1000.frag", "--screenshot", "out.png"])
        .current_dir(&dir)
        .env_remove("DISPLAY")
        .env("XDG_RUNTIME_DIR", dir.join("xdg"));
    let (out, cpu) = common::output_with_cpu(&mut command);
    assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
    // CPU seconds (a busy machine does not inflate them): 18 to 24 s before issue 17.
    assert!(cpu < 8.0, "{cpu:.1} s of CPU");
    let run = run_in(
        &dir,
        "legacy",
        &["v.vert", "a100000.frag", "--screenshot", "out.png"],
        &[],
    );
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    assert!(
        run.stderr.contains("a100000.frag:1:15: uniform `a` (float[100000]) takes 1600000 bytes of the uniform block (16 per element); the limit is 16384 bytes, 1024 elements"),
        "{}",
        run.stderr
    );
}

/// Issue 33: 16,000 `uniform float` lines took 23 s before they were refused, both shaders at
/// 16,000 over 60 s (each uniform was looked up in lists and line numbers counted from the top
/// of the file: quadratic). Now linear: a fraction of a second of CPU.
#[test]
fn thousands_of_legacy_uniforms_take_linear_time() {
    let dir = test_dir("legacy_many_uniforms");
    let n = 16_000;
    let decls: String = (0..n).map(|i| format!("uniform float u{i};\n")).collect();
    std::fs::write(
        dir.join("v.vert"),
        format!("{decls}void main() {{ gl_Position = ftransform() + vec4(u0 * 0.0); }}\n"),
    )
    .unwrap();
    std::fs::write(
        dir.join("f.frag"),
        format!("{decls}void main() {{ gl_FragColor = vec4(u0 + u{}); }}\n", n - 1),
    )
    .unwrap();
    let mut command = Command::new(example("legacy"));
    command
        .args(["v.vert", "f.frag", "--screenshot", "out.png"])
        .current_dir(&dir)
        .env_remove("DISPLAY")
        .env("XDG_RUNTIME_DIR", dir.join("xdg"));
    let (out, cpu) = common::output_with_cpu(&mut command);
    let err = String::from_utf8_lossy(&out.stderr);
    // 16,000 floats are 64,000 bytes: more than a uniform block takes, said with the largest.
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("the uniforms need 64000 bytes"), "{err}");
    assert!(err.contains("and 15995 more"), "{err}");
    // CPU seconds, which a busy machine does not inflate: 0.6 s here, over 60 s before.
    assert!(cpu < 10.0, "{cpu:.1} s of CPU for {n} uniforms");
}

/// Issue 33: an automatic choice has a budget and says when it hits it (`wave` subdiv=auto on
/// a steep wave took 8.6 s and 810 MB at 32 quads a cell side; now at most 1 M triangles, 17),
/// and a mesh a user asks for beyond that budget says what it costs before it is drawn.
#[test]
fn automatic_choices_keep_a_budget_and_extremes_say_their_cost() {
    let dir = test_dir("auto_budget");
    let steep = [
        "--set",
        "subdiv=auto",
        "--set",
        "h=10",
        "--set",
        "xs=100",
        "--set",
        "zs=100",
    ];
    let run = run_in(
        &dir,
        "wave",
        &[&steep[..], &["--size", "64x64", "--screenshot", "w.png"]].concat(),
        &[],
    );
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert!(
        run.stderr.contains("needs more than 17 quads a cell side")
            && run.stderr.contains("auto draws at most 1000000 triangles"),
        "{}",
        run.stderr
    );
    let run = run_in(
        &dir,
        "twist",
        &[
            "--set",
            "grid=auto",
            "--set",
            "twisting=1e4",
            "--size",
            "64x64",
            "--screenshot",
            "t.png",
        ],
        &[],
    );
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert!(
        run.stderr.contains("needs more than 400 quads a side"),
        "{}",
        run.stderr
    );
    // The course's wave, auto: within budget, nothing to say.
    let run = run_in(
        &dir,
        "wave",
        &["--set", "subdiv=auto", "--size", "64x64", "--screenshot", "w.png"],
        &[],
    );
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert!(run.stderr.is_empty(), "{}", run.stderr);
    // A user's extreme is drawn, and its cost said first.
    let run = run_in(
        &dir,
        "phong_fragment",
        &["--tess", "512", "--size", "32x32", "--screenshot", "p.png"],
        &[],
    );
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert!(run.stderr.contains("16711744 triangles"), "{}", run.stderr);
    assert!(run.stdout.contains("wrote p.png"), "{}", run.stdout);
}

/// Issue 33: a model larger than the machine can draw is one line before anything is made (a
/// 10 M-face model took 6.4 GB and ended in wgpu's out-of-memory panic); the memory the check
/// sees is faked so the test needs no such machine.
#[test]
fn a_model_too_large_for_the_machine_is_one_line() {
    let dir = test_dir("large_model");
    let obj = grid_obj(100);
    std::fs::write(dir.join("grid.obj"), obj).unwrap();
    let args = ["--model", "grid.obj", "--screenshot", "m.png"];
    let run = run_in(
        &dir,
        "suzanne_phong",
        &args,
        &[("SHADERLAB_TEST_AVAILABLE_MEMORY", "10000000")],
    );
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    assert!(
        run.stderr
            .contains("grid.obj (20000 triangles), drawn on this CPU adapter (whose GPU memory is the machine's), needs about 14.3 MiB of memory")
            && run.stderr.contains("may take 9.5 MiB now"),
        "{}",
        run.stderr
    );
    assert_eq!(
        run.stderr.lines().filter(|l| l.contains("error")).count(),
        1,
        "{}",
        run.stderr
    );
    assert!(!dir.join("m.png").exists());
    let run = run_in(&dir, "suzanne_phong", &args, &[]);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
}

/// A fragment shader that loops until its float stops growing: on lavapipe about a minute and
/// a half for a 2048² picture (65,535 iterations a pixel), which the watchdog gives up on.
const ENDLESS_FRAG: &str =
    "void main() {\n    float x = gl_FragCoord.x;\n    while (x >= 0.0) x += 1.0;\n    gl_FragColor = vec4(x);\n}\n";

/// Issue 33: a frame that does not finish within the watchdog (`--timeout`, 10 s by default)
/// ends the run with a message naming the likely cause, instead of running for minutes.
#[test]
fn a_shader_that_never_ends_meets_the_watchdog() {
    let dir = test_dir("watchdog");
    std::fs::write(dir.join("v.vert"), "void main() { gl_Position = ftransform(); }\n").unwrap();
    std::fs::write(dir.join("endless.frag"), ENDLESS_FRAG).unwrap();
    // Two lavapipe threads, so that the CPU the second of waiting costs is the same on any
    // machine.
    let run = run_in(
        &dir,
        "legacy",
        &[
            "v.vert",
            "endless.frag",
            "--size",
            "2048x2048",
            "--timeout",
            "1",
            "--screenshot",
            "out.png",
        ],
        &[("LP_NUM_THREADS", "2")],
    );
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    assert!(
        run.stderr
            .contains("the GPU did not finish a frame within 1 s: most likely a shader never ends"),
        "{}",
        run.stderr
    );
    assert!(!dir.join("out.png").exists());
    // Ended by the watchdog, not by the frame: the frame alone takes minutes of CPU, the watchdog
    // a second of two threads' (CPU seconds, which a busy machine does not inflate).
    assert!(run.cpu < 20.0, "{:.1} s of CPU", run.cpu);
    let run = run_in(&dir, "legacy", &["--timeout", "-1"], &[]);
    assert_eq!(run.code, Some(2), "{}", run.stderr);
    assert!(
        run.stderr.contains("expected seconds from 0 (no limit) to 86400"),
        "{}",
        run.stderr
    );
}

/// A copy of the shaders in `dir/shaders` with position_rgb.frag replaced by `frag`.
fn position_rgb_with(dir: &Path, frag: &str) -> String {
    let shaders = dir.join("shaders");
    common::copy_shaders(&shaders);
    std::fs::write(shaders.join("position_rgb.frag"), frag).unwrap();
    shaders.to_str().unwrap().to_owned()
}

/// A shader with no loop that the driver compiles for minutes (a large local array)
/// meets the watchdog while the pipeline is built, and the message says so; a frame that does
/// not finish with no loop in any shader is not called "a shader that never ends".
#[test]
fn a_shader_too_large_to_compile_meets_the_watchdog() {
    let dir = test_dir("compile_watchdog");
    let shaders = position_rgb_with(
        &dir,
        "#version 450\nlayout(location = 0) in vec4 color;\nlayout(location = 0) out vec4 frag_color;\n\
         void main() {\n    float a[100000];\n    int k = int(color.x * 100.0);\n    a[k] = color.y;\n    \
         frag_color = vec4(a[k], color.yz, 1.0);\n}\n",
    );
    let run = run_in(
        &dir,
        "position_rgb",
        &["--shaders", &shaders, "--timeout", "1", "--screenshot", "out.png"],
        &[],
    );
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    assert!(
        run.stderr
            .contains("the GPU's driver was still compiling position_rgb's shaders after 1 s (the watchdog"),
        "{}",
        run.stderr
    );
    assert!(!run.stderr.contains("never ends"), "{}", run.stderr);
    assert!(!dir.join("out.png").exists());
}

/// A shader whose compilation takes more memory than the process may have (a chain of
/// 2,000 functions: gigabytes in the driver's compiler, which then crashes without a word) ends
/// with a message before the limit, here `prlimit --as` as a container sets it.
#[test]
fn a_shader_too_large_to_compile_meets_the_memory_bound() {
    let dir = test_dir("compile_memory");
    let mut frag = String::from(
        "#version 450\nlayout(location = 0) in vec4 color;\nlayout(location = 0) out vec4 frag_color;\n\
         float f0(float x) { return x * 0.5 + 0.1; }\n",
    );
    for i in 1..2000 {
        frag.push_str(&format!(
            "float f{i}(float x) {{ return f{}(x) * 0.999 + 0.001; }}\n",
            i - 1
        ));
    }
    frag.push_str("void main() { frag_color = vec4(f1999(color.x), color.yz, 1.0); }\n");
    let shaders = position_rgb_with(&dir, &frag);
    let run = run_limited(
        &dir,
        1_500_000_000,
        "position_rgb",
        &["--shaders", &shaders, "--timeout", "0", "--screenshot", "out.png"],
    );
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    assert!(
        run.stderr.contains("of memory compiling position_rgb's shaders") && run.stderr.contains("`ulimit -v`"),
        "{}",
        run.stderr
    );
    assert!(!dir.join("out.png").exists());
}

/// Runs `example args` in `dir` as [`run_in`] does, under an address-space limit of `bytes`
/// (`prlimit --as`, as a container or a shared machine sets one).
fn run_limited(dir: &Path, bytes: u64, example_name: &str, args: &[&str]) -> Run {
    let wrapper = ["prlimit".to_string(), format!("--as={bytes}")];
    run_via(&wrapper, dir, example_name, args, &[])
}

/// Under a memory limit, what does not fit is one clear message (exit status 1),
/// never wgpu's panicking handler or an abort on a failed allocation: a mesh the GPU runs out of
/// memory for, a model and a picture too large for what the process may take.
#[test]
fn out_of_memory_under_a_limit_is_a_message() {
    let dir = test_dir("out_of_memory");
    let said = |run: &Run, phrase: &str| {
        assert_eq!(run.code, Some(1), "{}", run.stderr);
        assert!(run.stderr.contains(phrase), "{}", run.stderr);
        assert!(
            !run.stderr.contains("panicked") && !run.stderr.contains("memory allocation of"),
            "{}",
            run.stderr
        );
        assert!(!dir.join("out.png").exists());
    };
    // 16.7 M triangles: the GPU's buffer cannot be made.
    let run = run_limited(
        &dir,
        1_500_000_000,
        "displacement",
        &["--tess", "512", "--screenshot", "out.png"],
    );
    said(&run, "the GPU ran out of memory");
    // The debugger of 4 M triangles under less: an allocation of the program's own fails, which
    // no estimate foresaw (it was Rust's abort, exit status 134).
    let run = run_limited(
        &dir,
        800_000_000,
        "displacement",
        &["--tess", "256", "--debug", "320,180"],
    );
    said(&run, "out of memory");
    // An 8192×8192 picture (a small file: one colour).
    let png = dir.join("big.png");
    image::RgbImage::from_pixel(8192, 8192, image::Rgb([255, 128, 0]))
        .save(&png)
        .unwrap();
    let run = run_limited(
        &dir,
        1_200_000_000,
        "suzanne_texture",
        &["--texture", "big.png", "--screenshot", "out.png"],
    );
    said(&run, "big.png (8192×8192 pixels) needs about");
    // A model of 2 M triangles, refused before it is read under a tight limit, and before it is
    // uploaded under a looser one.
    let obj = grid_obj(1000);
    std::fs::write(dir.join("grid.obj"), obj).unwrap();
    let run = run_limited(
        &dir,
        800_000_000,
        "suzanne_phong",
        &["--model", "grid.obj", "--screenshot", "out.png"],
    );
    said(&run, "reading grid.obj needs about");
    let run = run_limited(
        &dir,
        2_000_000_000,
        "suzanne_phong",
        &["--model", "grid.obj", "--screenshot", "out.png"],
    );
    said(&run, "grid.obj (2000000 triangles), drawn on this CPU adapter");
}

/// An OBJ grid of `n`×`n` squares in the unit square, two triangles each.
fn grid_obj(n: u32) -> String {
    let mut obj = String::new();
    for j in 0..=n {
        for i in 0..=n {
            obj.push_str(&format!(
                "v {} {} 0\n",
                f64::from(i) / f64::from(n),
                f64::from(j) / f64::from(n)
            ));
        }
    }
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i + 1;
            obj.push_str(&format!(
                "f {a} {} {}\nf {a} {} {}\n",
                a + 1,
                a + n + 2,
                a + n + 2,
                a + n + 1
            ));
        }
    }
    obj
}
