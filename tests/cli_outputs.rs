//! What the command's verbs print and write: every `--json` output is exactly one JSON
//! document, `--npy` into a stream (`/dev/stdout` into a file or a pipe, a link to it) takes
//! the array as `--out` does, a line past a file's end says how many lines the file has,
//! `diff legacy VERT FRAG --reference VERT0 FRAG0` compares the two pairs (and `--shaders` is
//! refused for legacy), and `--help` says `any value` for a range no lab declared.

mod common;

use std::path::Path;
use std::process::{Command, Output, Stdio};

const SIZE: &str = "64x36";

fn ok(args: &[&str], out: &Output) -> String {
    assert!(
        out.status.success(),
        "{args:?}: status {:?}: {}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout.clone()).expect("UTF-8")
}

/// The 1-based line of the built-in `file` that holds `needle`.
fn line_of(file: &str, needle: &str) -> u32 {
    let text = shaderlab::shader::embedded_source(file).expect("a built-in shader");
    text.lines().position(|l| l.contains(needle)).expect("the line") as u32 + 1
}

/// The course's lab 3 pair as `NAME.vert` and `NAME.frag` in `dir`, with `edit` applied to the
/// fragment shader; the 1-based line of the diffuse term's assignment.
fn course_pair(dir: &Path, name: &str, edit: impl Fn(&str) -> String) -> u32 {
    let course = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/course/seed000");
    std::fs::copy(course.join("lab3.vert"), dir.join(format!("{name}.vert"))).expect("lab3.vert");
    let text = std::fs::read_to_string(course.join("lab3.frag")).expect("lab3.frag");
    std::fs::write(dir.join(format!("{name}.frag")), edit(&text)).expect("the fragment shader");
    text.lines().position(|l| l.contains("vec4 Idiff =")).expect("the line") as u32 + 1
}

/// The course's lab 3 lit: its uniforms default to 0.
const LIT: &[&str] = &[
    "--set",
    "object=teapot",
    "--set",
    "Kd=1",
    "--set",
    "diffuseColor=1,0.5,0",
];

#[test]
fn every_json_output_is_one_json_document() {
    let dir = common::fresh_dir("cli_outputs_json");
    let copy = dir.join("copy");
    common::copy_shaders(&copy);
    let copy = copy.to_str().expect("utf-8").to_owned();
    course_pair(&dir, "mine", |t| {
        t.replace("max(dot(N, L), 0.0)", "max(dot(N, L), 0.5)")
    });
    course_pair(&dir, "ref", str::to_owned);
    let line = format!("phong.frag:{}", line_of("phong.frag", "max(dot(N, L), 0.0)"));
    let runs: Vec<Vec<&str>> = vec![
        vec!["view", "phong", "--line", &line, "--json"],
        vec!["view", "phong", "--cost", "--json"],
        vec!["view", "phong", "--cost", "--bench", "2", "--json"],
        vec![
            "view", "phong", "--line", &line, "--bench", "2", "--json", "--out", "v.png",
        ],
        vec!["run", "phong", "--line", &line, "--json"],
        vec!["run", "phong", "--cost", "--bench", "2", "--json"],
        vec!["debug", "phong", "--pixel", "32,18", "--json"],
        vec!["run", "phong", "--debug", "32,18", "--json", "--screenshot", "d.png"],
        vec!["diff", "phong", "--shaders", &copy, "--json"],
        vec!["run", "phong", "--diff", &copy, "--json"],
        vec![
            "diff",
            "legacy",
            "mine.vert",
            "mine.frag",
            "--reference",
            "ref.vert",
            "ref.frag",
            "--json",
        ],
    ];
    for run in runs {
        let mut args = run.clone();
        args.extend_from_slice(&["--size", SIZE]);
        if run[1] == "legacy" {
            args.extend_from_slice(LIT);
        }
        let text = ok(&args, &common::shaderlab_in(&dir, &args));
        let v: serde_json::Value =
            serde_json::from_str(&text).unwrap_or_else(|e| panic!("{args:?}: not one JSON document ({e}):\n{text}"));
        assert!(v.is_object(), "{args:?}: {v}");
        if run.contains(&"--bench") {
            let bench = &v["bench"];
            assert_eq!(bench["frames"], 2, "{args:?}: {v}");
            for key in ["ms_per_frame", "plain_ms_per_frame", "ratio", "values_ms_per_frame"] {
                assert!(
                    bench[key].as_f64().is_some_and(|x| x > 0.0 && x.is_finite()),
                    "{args:?}: {key}: {v}"
                );
            }
        }
    }
}

#[test]
fn npy_into_a_stream_takes_the_array_whatever_its_name() {
    let dir = common::fresh_dir("cli_outputs_npy");
    let args = ["view", "phong", "--cost", "--size", SIZE];
    // The array written to a file, for comparison.
    let mut file_args = args.to_vec();
    file_args.extend_from_slice(&["--npy", "c.npy"]);
    ok(&file_args, &common::shaderlab_in(&dir, &file_args));
    let reference = std::fs::read(dir.join("c.npy")).expect("c.npy");
    let (shape, cost) = common::parse_npy(&reference);
    assert_eq!(shape, vec![36, 64, 1]);
    assert!(cost.iter().any(|c| c.is_finite() && *c > 0.0), "the teapot is drawn");
    // /dev/stdout into a file, /dev/stdout into a pipe, a link to /dev/stdout with another name.
    std::os::unix::fs::symlink("/dev/stdout", dir.join("values.dat")).expect("the link");
    for (target, into_file) in [("/dev/stdout", true), ("/dev/stdout", false), ("values.dat", true)] {
        let mut run = args.to_vec();
        run.extend_from_slice(&["--npy", target]);
        let mut command = Command::new(env!("CARGO_BIN_EXE_shaderlab"));
        command.current_dir(&dir).args(&run);
        let bytes = if into_file {
            let path = dir.join("stdout.bin");
            let file = std::fs::File::create(&path).expect("the file stdout goes to");
            let out = command.stdout(Stdio::from(file)).output().expect("shaderlab runs");
            assert!(
                out.status.success(),
                "{run:?} > file: {}",
                String::from_utf8_lossy(&out.stderr)
            );
            std::fs::read(&path).expect("stdout's file")
        } else {
            let out = command.output().expect("shaderlab runs");
            assert!(
                out.status.success(),
                "{run:?} | …: {}",
                String::from_utf8_lossy(&out.stderr)
            );
            out.stdout
        };
        // The stream holds the array alone: the summary went to stderr.
        assert_eq!(bytes, reference, "{run:?} (into a file: {into_file})");
    }
    // A file still needs the .npy name.
    let out = common::shaderlab_in(&dir, &["view", "phong", "--cost", "--npy", "v.txt"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("use a .npy name"));
    assert!(!dir.join("v.txt").exists());
}

#[test]
fn a_line_past_the_end_says_how_many_lines_the_file_has() {
    let dir = common::fresh_dir("cli_outputs_past_end");
    let lines = shaderlab::shader::embedded_source("phong.frag")
        .expect("phong.frag")
        .lines()
        .count();
    for line in [lines + 1, 999] {
        let at = format!("phong.frag:{line}");
        let out = common::shaderlab_in(&dir, &["view", "phong", "--line", &at, "--size", SIZE]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(
            err.contains(&format!("phong.frag:{line} is past the end of the file"))
                && err.contains(&format!("phong.frag has {lines} lines")),
            "{err}"
        );
        assert!(!err.contains("assigns nothing"), "{err}");
    }
    // The user's own file, in legacy: its own count.
    course_pair(&dir, "lab3", str::to_owned);
    let count = std::fs::read_to_string(dir.join("lab3.frag"))
        .expect("lab3.frag")
        .lines()
        .count();
    let at = format!("lab3.frag:{}", count + 1);
    let out = common::shaderlab_in(
        &dir,
        &[
            "view",
            "legacy",
            "lab3.vert",
            "lab3.frag",
            "--line",
            &at,
            "--size",
            SIZE,
        ],
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains(&format!("lab3.frag has {count} lines")), "{err}");
    assert!(!dir.join("legacy-view.png").exists());
}

#[test]
fn diff_legacy_compares_with_the_reference_pair_and_refuses_a_folder() {
    let dir = common::fresh_dir("cli_outputs_legacy");
    let line = course_pair(&dir, "mine", |t| {
        t.replace(
            "vec4 Idiff = vec4(diffuseColor * max(dot(N, L), 0.0), 1.0);",
            "vec4 Idiff = vec4(diffuseColor * max(dot(N, L), 0.0), 1.0) * 0.5;",
        )
    });
    course_pair(&dir, "ref", str::to_owned);
    let mine = std::fs::read_to_string(dir.join("mine.frag")).expect("mine.frag");
    assert!(mine.contains("* 0.5;"), "the planted difference");
    let mut args = vec![
        "diff",
        "legacy",
        "mine.vert",
        "mine.frag",
        "--reference",
        "ref.vert",
        "ref.frag",
        "--size",
        SIZE,
        "--json",
        "--out",
        "d.png",
    ];
    args.extend_from_slice(LIT);
    let v: serde_json::Value =
        serde_json::from_str(&ok(&args, &common::shaderlab_in(&dir, &args))).expect("one JSON object");
    assert!(v["differing"].as_u64().is_some_and(|n| n > 50), "{v}");
    let first = &v["first_divergence"];
    assert_eq!(first["file"], "mine.frag", "the user's own file: {v}");
    assert_eq!(first["line"], line, "{v}");
    assert_eq!(first["name"], "Idiff", "{v}");
    assert_eq!(first["reference_file"], "ref.frag", "{v}");
    // The copy's value is half the reference's where the two depart.
    let (a, b) = (&first["mine"], &first["reference"]);
    for c in 0..4 {
        let (a, b) = (a[c].as_f64().expect("mine"), b[c].as_f64().expect("reference"));
        assert!((a - 0.5 * b).abs() < 1e-4, "{v}");
    }
    assert!(image::open(dir.join("d.png")).is_ok(), "the picture of the difference");
    // The same pair on both sides is identical.
    let mut same = vec![
        "diff",
        "legacy",
        "ref.vert",
        "ref.frag",
        "--reference",
        "ref.vert",
        "ref.frag",
        "--size",
        SIZE,
        "--json",
    ];
    same.extend_from_slice(LIT);
    let v: serde_json::Value =
        serde_json::from_str(&ok(&same, &common::shaderlab_in(&dir, &same))).expect("one JSON object");
    assert_eq!(v["differing"], 0, "{v}");

    // A folder of shaders means nothing to legacy, even an empty one; no pair is a question.
    let empty = dir.join("empty");
    std::fs::create_dir_all(&empty).expect("the empty folder");
    let before = std::fs::read_dir(&dir).expect("the folder").count();
    for (args, says) in [
        (
            vec![
                "diff",
                "legacy",
                "mine.vert",
                "mine.frag",
                "--shaders",
                empty.to_str().expect("utf-8"),
            ],
            "`--shaders` reads a lab's shaders from a folder, and does nothing for legacy",
        ),
        (
            vec!["diff", "legacy", "mine.vert", "mine.frag"],
            "which pair to compare with? name it with --reference VERT0 FRAG0",
        ),
        (
            vec![
                "diff",
                "phong",
                "--shaders",
                empty.to_str().expect("utf-8"),
                "--reference",
                "ref.vert",
                "ref.frag",
            ],
            "`--reference` names the pair",
        ),
        (
            vec!["diff", "legacy", "mine.vert", "mine.frag", "--reference", "ref.vert"],
            "`--reference` needs two files",
        ),
    ] {
        let out = common::shaderlab_in(&dir, &args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(out.stdout.is_empty(), "{args:?}");
    }
    let after = std::fs::read_dir(&dir).expect("the folder").count();
    assert_eq!(before, after, "nothing written");
}

#[test]
fn help_says_any_value_for_a_range_no_lab_declared() {
    let dir = common::fresh_dir("cli_outputs_help");
    let help = ok(
        &["run", "phong", "--help"],
        &common::shaderlab_in(&dir, &["run", "phong", "--help"]),
    );
    assert!(!help.contains("e38"), "{help}");
    let light = help
        .lines()
        .find(|l| l.trim_start().starts_with("lightPosition"))
        .expect("lightPosition's line");
    assert!(light.contains("any value"), "{light}");
    // A declared range still prints as declared.
    let twist = ok(
        &["run", "twist", "--help"],
        &common::shaderlab_in(&dir, &["run", "twist", "--help"]),
    );
    let twisting = twist
        .lines()
        .find(|l| l.trim_start().starts_with("twisting"))
        .expect("twisting's line");
    assert!(twisting.contains("-10000..10000"), "{twisting}");
}
