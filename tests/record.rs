//! `--record`: frames at a fixed time step into a GIF, a PNG sequence or (through ffmpeg) a
//! video; deterministic, atomic, and every bad name or missing tool a clear message.

mod common;

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use common::*;
use image::AnimationDecoder;

fn scratch(name: &str) -> PathBuf {
    let dir = output_dir().join("record").join(name);
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

fn run(lab: &str, dir: &Path, args: &[&str]) -> Output {
    Command::new(example(lab))
        .current_dir(dir)
        .env(
            "XDG_RUNTIME_DIR",
            std::env::var_os("XDG_RUNTIME_DIR").unwrap_or_default(),
        )
        .args(args)
        .output()
        .expect("run the example")
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn a_gif_has_its_frames_moves_with_time_and_is_the_same_twice() {
    let dir = scratch("gif");
    let out = run(
        "wave",
        &dir,
        &["--record", "w.gif", "--frames", "6", "--fps", "25", "--size", "160x120"],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let first = fs::read(dir.join("w.gif")).unwrap();
    let decoder = image::codecs::gif::GifDecoder::new(std::io::Cursor::new(&first)).unwrap();
    let frames = decoder.into_frames().collect_frames().unwrap();
    assert_eq!(frames.len(), 6);
    for f in &frames {
        assert_eq!(f.buffer().dimensions(), (160, 120));
        let (n, d) = f.delay().numer_denom_ms();
        assert_eq!(n / d, 40, "25 fps is 4/100 s");
    }
    assert_ne!(frames[0].buffer(), frames[5].buffer(), "wave moves with time");
    // Frame 5 is the picture at time 5/25 s.
    let still = run(
        "wave",
        &dir,
        &["--set", "time=0.2", "--size", "160x120", "--screenshot", "s.png"],
    );
    assert!(still.status.success(), "{}", stderr(&still));
    let shot = image::open(dir.join("s.png")).unwrap().to_rgba8();
    let differing = shot
        .pixels()
        .zip(frames[5].buffer().pixels())
        .filter(|(a, b)| a != b)
        .count();
    assert!(
        differing < shot.pixels().len() / 50,
        "frame 5 is the picture at t = 0.2 s ({differing} pixels differ after GIF's palette)"
    );
    let again = run(
        "wave",
        &dir,
        &["--record", "w.gif", "--frames", "6", "--fps", "25", "--size", "160x120"],
    );
    assert!(again.status.success(), "{}", stderr(&again));
    assert_eq!(
        fs::read(dir.join("w.gif")).unwrap(),
        first,
        "two runs write the same bytes"
    );
    assert_eq!(common::names_in(&dir), ["s.png", "w.gif"], "no temporary file left");
}

#[test]
fn a_png_sequence_is_named_by_its_pattern_and_never_overwrites() {
    let dir = scratch("pngs");
    let out = run("twist", &dir, &["--record", "f-%03d.png", "--frames", "3"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(common::names_in(&dir), ["f-000.png", "f-001.png", "f-002.png"]);
    let frame = image::open(dir.join("f-001.png")).unwrap();
    assert_eq!((frame.width(), frame.height()), (512, 512));
    let before = fs::read(dir.join("f-000.png")).unwrap();
    let out = run(
        "twist",
        &dir,
        &["--record", "f-%03d.png", "--frames", "3", "--set", "twisting=0"],
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("f-000.png: exists"), "{}", stderr(&out));
    assert_eq!(fs::read(dir.join("f-000.png")).unwrap(), before, "left as it was");
    // A directory takes LAB-0000.png ….
    fs::create_dir(dir.join("sub")).unwrap();
    let out = run("twist", &dir, &["--record", "sub", "--frames", "2"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(common::names_in(&dir.join("sub")), ["twist-0000.png", "twist-0001.png"]);
}

#[test]
fn bad_names_and_missing_tools_are_clear_and_write_nothing() {
    let dir = scratch("bad");
    let cases: &[(&[&str], i32, &str)] = &[
        (&["--record", "a.avi", "--frames", "2"], 2, "expected NAME.gif"),
        (&["--record", "a.gif"], 2, "--frames"),
        (&["--frames", "2"], 2, "--record"),
        (&["--record", "a.gif", "--frames", "0"], 2, "--frames"),
        (
            &["--record", "a.gif", "--frames", "2", "--fps", "0"],
            2,
            "frames per second",
        ),
        (
            &["--record", "a.gif", "--frames", "2", "--screenshot", "a.png"],
            2,
            "cannot be used with",
        ),
        (&["--record", "nowhere/a.gif", "--frames", "2"], 1, "does not exist"),
    ];
    for (args, code, says) in cases {
        let out = run("twist", &dir, args);
        assert_eq!(out.status.code(), Some(*code), "{args:?}: {}", stderr(&out));
        assert!(stderr(&out).contains(says), "{args:?}: {}", stderr(&out));
    }
    // No ffmpeg on PATH: say which package, write nothing.
    let empty = dir.join("empty-path");
    fs::create_dir(&empty).unwrap();
    let out = Command::new(example("twist"))
        .current_dir(&dir)
        .env("PATH", &empty)
        .args(["--record", "a.mp4", "--frames", "2"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(stderr(&out).contains("apt-get install ffmpeg"), "{}", stderr(&out));
    assert_eq!(common::names_in(&dir), ["empty-path"], "nothing written");
}

/// A stand-in `ffmpeg` that copies its input to its output (or fails): what the port pipes
/// in and how it keeps the file whole, without the real encoder.
fn fake_ffmpeg(dir: &Path, body: &str) -> PathBuf {
    use std::os::unix::fs::PermissionsExt;
    let bin = dir.join("bin");
    fs::create_dir_all(&bin).unwrap();
    let script = bin.join("ffmpeg");
    fs::write(&script, format!("#!/bin/sh\n{body}\n")).unwrap();
    fs::set_permissions(&script, fs::Permissions::from_mode(0o755)).unwrap();
    bin
}

#[test]
fn a_video_is_the_frames_piped_through_ffmpeg_and_a_failure_keeps_the_old_file() {
    let dir = scratch("video");
    let path = format!("{}:/usr/bin:/bin", fake_ffmpeg(&dir, "cat").display());
    let out = Command::new(example("twist"))
        .current_dir(&dir)
        .env("PATH", &path)
        .args(["--record", "v.webm", "--frames", "3", "--size", "64x32"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(
        fs::metadata(dir.join("v.webm")).unwrap().len(),
        3 * 64 * 32 * 4,
        "three RGBA frames"
    );
    let bin = fake_ffmpeg(&dir, "echo 'encoder exploded' >&2; exit 3");
    let out = Command::new(example("twist"))
        .current_dir(&dir)
        .env("PATH", format!("{}:/usr/bin:/bin", bin.display()))
        .args(["--record", "v.webm", "--frames", "3", "--size", "64x32"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("encoder exploded"), "{}", stderr(&out));
    assert_eq!(
        fs::metadata(dir.join("v.webm")).unwrap().len(),
        3 * 64 * 32 * 4,
        "the old file stays"
    );
    assert_eq!(common::names_in(&dir), ["bin", "v.webm"], "no temporary file left");
}

#[test]
fn an_interrupted_recording_leaves_no_file() {
    let dir = scratch("interrupted");
    fs::write(dir.join("long.gif"), b"an older recording").unwrap();
    let mut child = Command::new(example("wave"))
        .current_dir(&dir)
        .args(["--record", "long.gif", "--frames", "100000"])
        .spawn()
        .unwrap();
    // Wait until it is writing (its temporary file exists), then interrupt it.
    let started = std::time::Instant::now();
    while !common::names_in(&dir).iter().any(|n| n.ends_with(".tmp")) {
        assert!(started.elapsed().as_secs() < 120, "the recording never started");
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let status = interrupt(&mut child);
    assert!(!status.success());
    assert_eq!(common::names_in(&dir), ["long.gif"], "the temporary file is gone");
    assert_eq!(fs::read(dir.join("long.gif")).unwrap(), b"an older recording");
}

/// Ctrl-C for `child`, and how it ended. Ctrl-C is SIGINT. A shell that starts a job in the
/// background without job control makes it ignore SIGINT, children inherit that, and the
/// recorder leaves an ignored signal alone by design (as under `nohup`): under such a parent,
/// SIGTERM, which the same handler serves, stands in for it.
fn interrupt(child: &mut std::process::Child) -> std::process::ExitStatus {
    let signal = if sigint_ignored() { "-TERM" } else { "-INT" };
    Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .unwrap();
    child.wait().unwrap()
}

/// Whether this process ignores SIGINT (inherited from a background job's shell).
fn sigint_ignored() -> bool {
    // SAFETY: sigaction only reads the current disposition into a zeroed struct.
    unsafe {
        let mut old: libc::sigaction = std::mem::zeroed();
        libc::sigaction(libc::SIGINT, std::ptr::null(), &mut old) == 0 && old.sa_sigaction == libc::SIG_IGN
    }
}

/// Issue 33: two recordings into the same frame pattern both said "wrote 40 frames" and 40
/// files remained, all of the second. Now each sequence is written beside its names and moved
/// in whole at the end, claiming every name exclusively: one recording wins whole, the other
/// fails, naming the frame, and leaves nothing.
#[test]
fn two_recordings_into_one_pattern_never_mix() {
    let dir = scratch("race");
    fs::create_dir(dir.join("seq")).unwrap();
    let start = |lab: &str| {
        Command::new(example(lab))
            .current_dir(&dir)
            .args(["--record", "seq/f-%04d.png", "--frames", "40", "--size", "64x64"])
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap()
    };
    let (wave, phong) = (start("wave"), start("phong"));
    let (wave, phong) = (wave.wait_with_output().unwrap(), phong.wait_with_output().unwrap());
    let ok: Vec<bool> = [&wave, &phong].iter().map(|o| o.status.success()).collect();
    assert_eq!(
        ok.iter().filter(|o| **o).count(),
        1,
        "exactly one recording must win:\nwave: {}\nphong: {}",
        stderr(&wave),
        stderr(&phong)
    );
    let loser = if ok[0] { &phong } else { &wave };
    assert_eq!(loser.status.code(), Some(1));
    assert!(
        stderr(loser).contains(".png: exists; this output never overwrites"),
        "{}",
        stderr(loser)
    );
    let names = common::names_in(&dir.join("seq"));
    assert_eq!(names.len(), 40, "{names:?}");
    assert!(names.iter().all(|n| n.starts_with("f-")), "{names:?}");
    // All 40 from the winner: its own run, again into a fresh folder, gives the same bytes.
    let winner = if ok[0] { "wave" } else { "phong" };
    fs::create_dir(dir.join("again")).unwrap();
    let out = run(
        winner,
        &dir,
        &["--record", "again/f-%04d.png", "--frames", "40", "--size", "64x64"],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    for name in &names {
        assert_eq!(
            fs::read(dir.join("seq").join(name)).unwrap(),
            fs::read(dir.join("again").join(name)).unwrap(),
            "{name} is not {winner}'s"
        );
    }
}

/// Issue 33: a PNG sequence stopped half-way (a signal here) left frames 0…k with nothing to
/// say it was incomplete, and the same command then refused to run because they existed. Now
/// nothing is left, the process ends as the signal asked, and the command runs again.
#[test]
fn a_sequence_stopped_half_way_leaves_nothing() {
    let dir = scratch("sequence_stopped");
    let args = ["--record", "f-%05d.png", "--frames", "100000", "--size", "64x64"];
    let mut child = Command::new(example("wave"))
        .current_dir(&dir)
        .args(args)
        .spawn()
        .unwrap();
    let started = std::time::Instant::now();
    while common::names_in(&dir).iter().filter(|n| n.ends_with(".tmp")).count() < 5 {
        assert!(started.elapsed().as_secs() < 120, "the recording never started");
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let status = interrupt(&mut child);
    use std::os::unix::process::ExitStatusExt;
    assert!(status.signal().is_some(), "ended by the signal: {status:?}");
    assert!(
        common::names_in(&dir).is_empty(),
        "left behind: {:?}",
        common::names_in(&dir)
    );
    let out = run(
        "wave",
        &dir,
        &["--record", "f-%05d.png", "--frames", "3", "--size", "64x64"],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(common::names_in(&dir), ["f-00000.png", "f-00001.png", "f-00002.png"]);
}

/// Issue 33: a recording killed with SIGKILL (no handler can run) left its 3 MB temporary file
/// for ever; the next run that writes into the folder removes it.
#[test]
fn a_killed_recordings_temporary_file_is_swept_by_the_next_run() {
    let dir = scratch("killed");
    let mut child = Command::new(example("wave"))
        .current_dir(&dir)
        .args(["--record", "long.gif", "--frames", "100000"])
        .spawn()
        .unwrap();
    let started = std::time::Instant::now();
    while !common::names_in(&dir).iter().any(|n| n.ends_with(".tmp")) {
        assert!(started.elapsed().as_secs() < 120, "the recording never started");
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let left = common::names_in(&dir);
    assert!(
        left.iter().any(|n| n.starts_with(".sl-") && n.ends_with(".tmp")),
        "{left:?}"
    );
    let out = run("phong", &dir, &["--screenshot", "shot.png", "--size", "32x32"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(common::names_in(&dir), ["shot.png"]);
}

/// Issue 33: every frame's time is checked before the first is drawn: `--from` outside the
/// lab's `time` range (a 309-digit number, naming `time`) failed only at its frame, and
/// `--from` on a lab with no clock, or `--frames` without `--record`, were taken and ignored.
#[test]
fn recording_flags_are_checked_before_anything_is_drawn() {
    let dir = scratch("flags");
    let out = run("wave", &dir, &["--record", "w.gif", "--frames", "5", "--from", "1e308"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("--from 1e308 --fps 25: frame 0 would be at time 1e308, outside the lab's `time` range -1000000000..1000000000"),
        "{}",
        stderr(&out)
    );
    let out = run(
        "wave",
        &dir,
        &[
            "--record",
            "w.gif",
            "--frames",
            "5",
            "--from",
            "999999999.9",
            "--fps",
            "1",
        ],
    );
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("frame 4 would be at time 1000000003.9"),
        "{}",
        stderr(&out)
    );
    let out = run("phong", &dir, &["--record", "p.gif", "--frames", "2", "--from", "3"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("phong has no `time` parameter"),
        "{}",
        stderr(&out)
    );
    let out = run("phong", &dir, &["--screenshot", "p.png", "--frames", "3"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("`--frames` is for recordings"),
        "{}",
        stderr(&out)
    );
    assert!(common::names_in(&dir).is_empty(), "{:?}", common::names_in(&dir));
}
