//! Issue 33: what every output and every command does with paths that are not regular files,
//! with a closed or full stdout, and with the messages the hostile sweep found unclear. Each
//! command is the installable `shaderlab` (cargo builds it for the integration tests).

mod common;

use std::fs;
use std::os::unix::fs::FileTypeExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn scratch(name: &str) -> PathBuf {
    let dir = common::output_dir().join("outputs").join(name);
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

fn shaderlab(dir: &Path, args: &[&str]) -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_shaderlab"));
    command
        .current_dir(dir)
        .args(args)
        .env_remove("DISPLAY")
        .env_remove("RUST_BACKTRACE");
    command
}

fn run(dir: &Path, args: &[&str]) -> Output {
    let out = shaderlab(dir, args).output().expect("run shaderlab");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("panicked"), "shaderlab {args:?} panicked:\n{err}");
    out
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn mkfifo(path: &Path) {
    let c = std::ffi::CString::new(path.to_str().unwrap()).unwrap();
    // SAFETY: a valid C string.
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
}

fn kind(path: &Path) -> &'static str {
    let t = fs::symlink_metadata(path).unwrap().file_type();
    match () {
        _ if t.is_fifo() => "fifo",
        _ if t.is_char_device() => "char device",
        _ if t.is_symlink() => "link",
        _ if t.is_file() => "file",
        _ => "other",
    }
}

const FRAG: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/shaders_glsl/phong.frag");

/// `-o`, `--screenshot` and `--record` onto a FIFO, a device or a link to one: written into as
/// a stream, never replaced (as root, `-o /dev/full` used to leave a 2,824-byte regular file
/// where the device was); a FIFO nobody reads is an error at once, not a wait; a socket is
/// refused. A regular file still gets the atomic replacement.
#[test]
fn outputs_that_are_not_regular_files_are_never_replaced() {
    let dir = scratch("streams");
    for (name, args) in [
        ("out.wgsl", &["glsl2wgsl", FRAG, "-o", "out.wgsl"][..]),
        ("out.png", &["run", "phong", "--screenshot", "out.png"]),
        ("out.gif", &["record", "wave", "out.gif", "--frames", "2"]),
    ] {
        mkfifo(&dir.join(name));
        let out = run(&dir, args);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {}", stderr(&out));
        assert!(
            stderr(&out).contains(&format!("{name}: a FIFO that nothing reads")),
            "{args:?}: {}",
            stderr(&out)
        );
        assert_eq!(kind(&dir.join(name)), "fifo", "{args:?} replaced the FIFO");
    }
    let fifo = dir.join("out.wgsl");
    // With a reader, the bytes go through the FIFO.
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || fs::read(fifo).unwrap())
    };
    let out = loop {
        let out = run(&dir, &["glsl2wgsl", FRAG, "-o", "out.wgsl"]);
        if out.status.success() || !stderr(&out).contains("nothing reads") {
            break out;
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(String::from_utf8(reader.join().unwrap()).unwrap().contains("fn main"));
    assert_eq!(kind(&fifo), "fifo");

    // A device, directly and through a link: /dev/full says it is full and stays a device.
    std::os::unix::fs::symlink("/dev/full", dir.join("full.png")).unwrap();
    std::os::unix::fs::symlink("/dev/full", dir.join("full.gif")).unwrap();
    for args in [
        &["glsl2wgsl", FRAG, "-o", "/dev/full"][..],
        &["run", "phong", "--screenshot", "full.png", "--size", "32x32"],
        &["record", "wave", "full.gif", "--frames", "2", "--size", "32x32"],
    ] {
        let out = run(&dir, args);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {}", stderr(&out));
        assert!(
            stderr(&out).contains("No space left on device"),
            "{args:?}: {}",
            stderr(&out)
        );
    }
    assert_eq!(kind(Path::new("/dev/full")), "char device");
    assert_eq!(kind(&dir.join("full.png")), "link");
    assert_eq!(kind(&dir.join("full.gif")), "link");
    // /dev/null takes anything, and stays itself.
    let out = run(&dir, &["run", "phong", "--screenshot", "/dev/null", "--size", "32x32"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(kind(Path::new("/dev/null")), "char device");

    // A socket: refused, left alone.
    let _socket = std::os::unix::net::UnixListener::bind(dir.join("s.png")).unwrap();
    let out = run(&dir, &["run", "phong", "--screenshot", "s.png"]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(stderr(&out).contains("s.png: a socket"), "{}", stderr(&out));

    // `-o /dev/stdout` into a pipe: the bytes on stdout (the old code named
    // `/proc/self/fd/pipe:[…]` and failed); a picture there leaves its message on stderr.
    let out = run(&dir, &["glsl2wgsl", FRAG, "-o", "/dev/stdout"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(String::from_utf8_lossy(&out.stdout).contains("fn main"));
    let out = run(
        &dir,
        &["run", "phong", "--screenshot", "/dev/stdout", "--size", "40x30"],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let picture = image::load_from_memory(&out.stdout).expect("a PNG on stdout");
    assert_eq!((picture.width(), picture.height()), (40, 30));
    assert!(stderr(&out).contains("wrote /dev/stdout"), "{}", stderr(&out));

    // A regular file is still replaced whole.
    fs::write(dir.join("x.wgsl"), b"old").unwrap();
    let out = run(&dir, &["glsl2wgsl", FRAG, "-o", "x.wgsl"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(fs::read_to_string(dir.join("x.wgsl")).unwrap().contains("fn main"));
}

/// Every command reports a write error on stdout (closed or full) with one line and status 1,
/// as the labs already did: `--version`, `list`, `glsl2wgsl` (also `--legacy`), a lab's
/// `--help` and `bench` panicked or lost their output and said 0.
#[test]
fn every_command_says_when_stdout_fails() {
    let dir = scratch("stdout");
    let vert = concat!(env!("CARGO_MANIFEST_DIR"), "/src/course/legacy/default.vert");
    let frag = concat!(env!("CARGO_MANIFEST_DIR"), "/src/course/legacy/default.frag");
    for args in [
        &["--version"][..],
        &["list"],
        &["glsl2wgsl", FRAG],
        &["glsl2wgsl", "--legacy", vert, frag],
        &["run", "phong", "--help"],
        &["bench", "--frames", "1", "--only", "twist"],
    ] {
        let full = fs::OpenOptions::new().write(true).open("/dev/full").unwrap();
        let out = shaderlab(&dir, args).stdout(full).output().unwrap();
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{args:?} > /dev/full: {err}");
        assert!(err.contains("<stdout>: No space left on device"), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
    }
    // A reader that goes away: `bench | head -c 1` writes after the pipe closed.
    let mut child = shaderlab(&dir, &["bench", "--frames", "1", "--only", "suzanne"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("<stdout>: Broken pipe"), "{err}");
}

/// The sweep's unclear messages, each now saying what is wrong in the user's own terms.
#[test]
fn messages_say_what_is_wrong_in_the_users_terms() {
    let dir = scratch("messages");
    let cases: &[(&[&str], i32, &str)] = &[
        (
            &["run", "phong_fragment", "--tess", "auto"],
            2,
            "`--tess auto`: phong_fragment has no automatic level; give one from 0 to 512",
        ),
        (
            &["run", "wave", "--set", "time=1e308"],
            2,
            "parameter `time`: 1e308 is outside -1000000000..1000000000",
        ),
        (
            &["record", "wave", "--frames", "5"],
            2,
            "shaderlab record: where to? Usage: shaderlab record NAME OUT --frames N",
        ),
        (
            &["legacy", "a.vert", "b.frag", "extra.frag"],
            2,
            "Usage: shaderlab legacy [OPTIONS]",
        ),
        (
            &["run", "twist", "--set", "twisting=10000.0001"],
            2,
            "parameter `twisting`: 10000.0001 is outside -10000..10000",
        ),
        (
            &["run", "phong", "--screenshot", "x.png", "--frames", "3"],
            2,
            "`--frames` is for recordings",
        ),
        (
            &["record", "phong", "p.gif", "--frames", "2", "--from", "1"],
            2,
            "phong has no `time` parameter",
        ),
    ];
    for (args, code, phrase) in cases {
        let out = run(&dir, args);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(*code), "{args:?}: {err}");
        assert!(err.contains(phrase), "{args:?}: wanted `{phrase}` in:\n{err}");
        assert!(!err.contains("legacy legacy"), "{args:?}: {err}");
        assert!(err.len() < 2000, "{args:?}: {} bytes of message", err.len());
    }
    // The bound itself, as printed, is taken.
    let out = run(
        &dir,
        &[
            "run",
            "twist",
            "--set",
            "twisting=10000",
            "--screenshot",
            "t.png",
            "--size",
            "16x16",
        ],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    // An OBJ index too long for any integer is out of range, not "not an integer".
    fs::write(
        dir.join("big.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n",
    )
    .unwrap();
    let out = run(
        &dir,
        &["run", "suzanne_phong", "--model", "big.obj", "--screenshot", "m.png"],
    );
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(
        stderr(&out)
            .contains("big.obj:4: face corner `99999999999999999999`: v index 99999999999999999999 is out of range"),
        "{}",
        stderr(&out)
    );
    // A file called ffmpeg on PATH that cannot run is named as such.
    let bin = dir.join("bin");
    fs::create_dir(&bin).unwrap();
    fs::write(bin.join("ffmpeg"), "#!/bin/sh\n").unwrap();
    let path = format!("{}:{}", bin.display(), std::env::var("PATH").unwrap_or_default());
    let out = shaderlab(&dir, &["record", "wave", "old.mp4", "--frames", "2"])
        .env("PATH", path)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("bin/ffmpeg is on PATH but is not executable"),
        "{}",
        stderr(&out)
    );
}

/// A tiny OBJ: one triangle.
const TRIANGLE_OBJ: &str = "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n";

/// An output that is, or leads to, one of the run's own inputs is refused, whichever
/// output writes it and whatever path leads there (the same name, a symbolic link, a hard link,
/// a file an input `#include`s), with status 2 and a message naming the input, and the input
/// keeps its bytes. `--screenshot` used to write over the `--texture` picture and, through a
/// link, the `--model` OBJ; `record` over the texture; `glsl2wgsl -o` over an included file.
#[test]
fn no_output_replaces_one_of_the_runs_inputs() {
    let dir = scratch("inputs");
    let picture = |name: &str| {
        image::RgbImage::from_pixel(8, 8, image::Rgb([200, 40, 40]))
            .save_with_format(dir.join(name), image::ImageFormat::Png)
            .unwrap();
    };
    picture("tex.png");
    // A PNG under a .gif name: a picture is known by its content, so it is a texture and a
    // name `record` writes a GIF to.
    picture("tex.gif");
    fs::hard_link(dir.join("tex.png"), dir.join("hard.png")).unwrap();
    fs::write(dir.join("model.obj"), TRIANGLE_OBJ).unwrap();
    std::os::unix::fs::symlink("model.obj", dir.join("model-link.png")).unwrap();
    common::copy_shaders(&dir.join("shaders"));
    std::os::unix::fs::symlink("shaders/phong.frag", dir.join("shader-link.png")).unwrap();
    fs::write(
        dir.join("main.frag"),
        "#version 450\n#include \"tint.glsl\"\nlayout(location = 0) out vec4 colour;\nvoid main() { colour = tint(); }\n",
    )
    .unwrap();
    fs::write(
        dir.join("tint.glsl"),
        "vec4 tint() { return vec4(1.0, 0.5, 0.25, 1.0); }\n",
    )
    .unwrap();
    let legacy = concat!(env!("CARGO_MANIFEST_DIR"), "/src/course/legacy");
    for name in ["default.vert", "default.frag"] {
        fs::copy(format!("{legacy}/{name}"), dir.join(name)).unwrap();
    }
    std::os::unix::fs::symlink("default.vert", dir.join("vert-link.png")).unwrap();

    let small = ["--size", "32x32"];
    let cases: &[(&[&str], &str, &str)] = &[
        (
            &[
                "run",
                "suzanne_texture",
                "--texture",
                "tex.png",
                "--screenshot",
                "tex.png",
            ],
            "tex.png",
            "tex.png: would replace tex.png, one of the pictures this run reads",
        ),
        (
            &[
                "run",
                "suzanne_texture",
                "--texture",
                "tex.png",
                "--screenshot",
                "hard.png",
            ],
            "hard.png",
            "hard.png: would replace tex.png, one of the pictures this run reads",
        ),
        (
            &[
                "run",
                "suzanne_phong",
                "--model",
                "model.obj",
                "--screenshot",
                "model-link.png",
            ],
            "model.obj",
            "model-link.png: would replace model.obj, one of the OBJ models this run reads",
        ),
        (
            &[
                "record",
                "suzanne_texture",
                "tex.gif",
                "--texture",
                "tex.gif",
                "--frames",
                "2",
            ],
            "tex.gif",
            "tex.gif: would replace tex.gif, one of the pictures this run reads",
        ),
        (
            &["glsl2wgsl", "main.frag", "-o", "tint.glsl"],
            "tint.glsl",
            "/tint.glsl, one of the shader files this run reads",
        ),
        (
            &[
                "run",
                "phong",
                "--shaders",
                "shaders",
                "--screenshot",
                "shader-link.png",
            ],
            "shaders/phong.frag",
            "/shaders/phong.frag, one of the shader files this run reads",
        ),
        (
            &[
                "legacy",
                "default.vert",
                "default.frag",
                "--screenshot",
                "vert-link.png",
            ],
            "default.vert",
            "vert-link.png: would replace default.vert, one of the shader files this run reads",
        ),
    ];
    for (args, input, phrase) in cases {
        let args: Vec<&str> = if args[0] == "glsl2wgsl" {
            args.to_vec()
        } else {
            args.iter().chain(&small).copied().collect()
        };
        let before = fs::read(dir.join(input)).unwrap();
        let originals: Vec<Vec<u8>> = ["tex.png", "model.obj", "tint.glsl", "default.vert"]
            .iter()
            .map(|n| fs::read(dir.join(n)).unwrap())
            .collect();
        let out = run(&dir, &args);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(phrase), "{args:?}: wanted `{phrase}` in:\n{err}");
        assert!(err.contains("an output never replaces an input"), "{args:?}: {err}");
        assert_eq!(fs::read(dir.join(input)).unwrap(), before, "{args:?} changed {input}");
        for (n, bytes) in ["tex.png", "model.obj", "tint.glsl", "default.vert"]
            .iter()
            .zip(&originals)
        {
            assert_eq!(&fs::read(dir.join(n)).unwrap(), bytes, "{args:?} changed {n}");
        }
        assert!(
            !fs::read_dir(&dir)
                .unwrap()
                .any(|e| e.unwrap().file_name().to_string_lossy().starts_with(".sl-")),
            "{args:?} left a temporary file"
        );
    }
    // The same runs with an output of their own write it.
    for args in [
        &[
            "run",
            "suzanne_texture",
            "--texture",
            "tex.png",
            "--screenshot",
            "shot.png",
            "--size",
            "32x32",
        ][..],
        &["glsl2wgsl", "main.frag", "-o", "main.wgsl"],
    ] {
        let out = run(&dir, args);
        assert!(out.status.success(), "{args:?}: {}", stderr(&out));
    }
    assert!(fs::read_to_string(dir.join("main.wgsl")).unwrap().contains("fn tint"));
}

/// `shaderlab debug --help` prints the command's help (not "which lab?"), its errors name the
/// flag the user typed (`--pixel`, not `--debug`), and `+5,+6` is not a pixel.
#[test]
fn the_debug_command_has_help_and_names_the_flag_typed() {
    let dir = scratch("debug_command");
    for help in ["--help", "-h"] {
        let out = run(&dir, &["debug", help]);
        assert!(out.status.success(), "{help}: {}", stderr(&out));
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(
            text.contains("Usage: shaderlab debug NAME --pixel X,Y [--json]"),
            "{text}"
        );
        assert!(text.contains("phong"), "the labs are listed: {text}");
    }
    for verb in ["run", "record"] {
        let out = run(&dir, &[verb, "--help"]);
        assert!(out.status.success(), "{verb}: {}", stderr(&out));
        assert!(String::from_utf8_lossy(&out.stdout).contains(&format!("Usage: shaderlab {verb} NAME")));
    }
    let out = run(&dir, &["debug", "phong", "--help"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("--pixel <X,Y>") && !text.contains("--debug"), "{text}");

    let cases: &[(&[&str], &str)] = &[
        (&["debug", "phong", "--pixel", "5"], "'--pixel <X,Y>'"),
        (&["debug", "phong", "--pixel", "+5,+6"], "`+5,+6`: expected X,Y"),
        (&["debug", "phong", "--pixel", "5,-6"], "`5,-6`: expected X,Y"),
        (&["debug", "phong", "--pixel=+5,6"], "`+5,6`: expected X,Y"),
        (
            &["debug", "phong", "--pixel", "1,1", "--pixel", "2,2"],
            "'--pixel <X,Y>'",
        ),
        (
            &["debug", "phong", "--pixel", "3,3", "--record", "x.gif", "--frames", "2"],
            "'--pixel <X,Y>'",
        ),
        (
            &["debug", "phong", "--pixel", "700,5"],
            "--pixel 700,5: the pixel is outside the 640x360 picture",
        ),
        (&["run", "phong", "--debug", "+5,+6"], "`+5,+6`: expected X,Y"),
        (
            &["run", "phong", "--debug", "700,5"],
            "--debug 700,5: the pixel is outside the 640x360 picture",
        ),
    ];
    for (args, phrase) in cases {
        let out = run(&dir, args);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(phrase), "{args:?}: wanted `{phrase}` in:\n{err}");
        if args[0] == "debug" {
            assert!(!err.contains("--debug"), "{args:?} names a flag not typed: {err}");
        }
    }
    let out = run(
        &dir,
        &["debug", "phong", "--pixel", "05,6", "--json", "--size", "16x16"],
    );
    assert!(out.status.success(), "{}", stderr(&out));
}

/// A run that fails leaves no folder it made: `glsl2wgsl --all` into a folder that
/// did not exist, with a shader that does not compile, used to leave the folder, empty (as
/// `tradeoff` did on a full disk).
#[test]
fn a_failed_run_leaves_no_new_folder() {
    let dir = scratch("new_folder");
    let src = dir.join("src");
    fs::create_dir(&src).unwrap();
    fs::copy(FRAG, src.join("a.frag")).unwrap();
    fs::write(src.join("b.frag"), "#version 450\nvoid main() { this is not glsl }\n").unwrap();
    let out = run(&dir, &["glsl2wgsl", "--all", "src", "out/wgsl"]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(stderr(&out).contains("b.frag:2"), "{}", stderr(&out));
    assert!(!dir.join("out").exists(), "a failed run left a folder");
    fs::remove_file(src.join("b.frag")).unwrap();
    let out = run(&dir, &["glsl2wgsl", "--all", "src", "out/wgsl"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(dir.join("out/wgsl/a.frag.wgsl").is_file());
}
