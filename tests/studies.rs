//! The references of the speed/accuracy studies (`examples/tradeoff/`), tested on their own:
//! a converged reference must be what finer and finer drawings approach, and a supersampled
//! one must change little when sampled finer still. (The exact twisted square is tested in
//! `src/study/twist.rs`, seed 000's ray caster in `src/study/exact/`, the wave's and the
//! strip's references in `tests/seed001.rs` and `tests/seed003.rs`.)

mod common;

use image::RgbImage;
use shaderlab::course;
use shaderlab::metrics::box_downsample;
use shaderlab::offscreen::to_rgb;

fn rmse(a: &RgbImage, b: &RgbImage) -> f64 {
    shaderlab::metrics::rmse(a, b).expect("same size")
}

/// The `lighting` study's reference (the per-fragment program on a 256-level mesh): the
/// per-fragment picture approaches it as the mesh refines, level after level.
#[test]
fn lighting_reference_is_what_finer_meshes_approach() {
    let at = |tess: &str| common::render_state(course::PHONG_FRAGMENT, &[("object", "sphere"), ("tess", tess)]);
    let reference = at("256");
    let errors: Vec<f64> = ["8", "24", "96", "192"]
        .iter()
        .map(|t| rmse(&at(t), &reference))
        .collect();
    println!("phong_fragment sphere RMSE against level 256 at levels 8, 24, 96, 192: {errors:.2?}");
    // Measured: 14.83, 3.74, 1.02, 0.04.
    assert!(errors.windows(2).all(|w| w[1] < w[0]), "{errors:?}");
    assert!(errors[3] < 0.15 * errors[1], "{errors:?}");
}

/// The `suzanne` study's reference (per-pixel Phong drawn 4 × 4 larger, box-filtered down)
/// changes little when sampled 8 × 8: the study's errors (RMSE 1.9 and up) are not the
/// reference's own.
#[test]
fn suzanne_supersampled_reference_is_converged() {
    let gpu = common::gpu();
    let mut lab = common::build(course::SUZANNE_PHONG);
    common::set_state(lab.as_mut(), &[("yangle", "40"), ("shading", "phong")]);
    let four = box_downsample(
        &to_rgb(&shaderlab::shell::screenshot(gpu, lab.as_mut(), 2560, 1920).unwrap()),
        4,
    );
    let eight = box_downsample(
        &to_rgb(&shaderlab::shell::screenshot(gpu, lab.as_mut(), 5120, 3840).unwrap()),
        8,
    );
    let e = rmse(&four, &eight);
    println!("4x4 against 8x8 supersampling: RMSE {e:.3}"); // measured 0.275
    assert!(e < 0.8, "RMSE {e:.3}");
}

/// `docs/studies.md` quotes each study's lesson from `docs/tradeoff/index.md` (the run's own
/// words): after a new run, `scripts/sync-lessons` copies them; until then this fails, naming
/// the study.
#[test]
fn the_lessons_quoted_match_the_index() {
    let root = env!("CARGO_MANIFEST_DIR");
    let index = std::fs::read_to_string(format!("{root}/docs/tradeoff/index.md")).unwrap();
    let readme = std::fs::read_to_string(format!("{root}/docs/studies.md")).unwrap();
    let mut studies = 0;
    for section in index.split("\n## ").skip(1) {
        let lines: Vec<&str> = section.lines().collect();
        let title = lines[0].trim();
        let image = lines
            .iter()
            .position(|l| l.starts_with("!["))
            .expect("a chart under each heading");
        let lesson = lines[image + 1..]
            .iter()
            .find(|l| !l.trim().is_empty())
            .expect("a lesson under each chart");
        // docs/studies.md's copy sits under a bold heading of the same title.
        let at = readme
            .find(&format!("**{title}**"))
            .unwrap_or_else(|| panic!("docs/studies.md has no heading **{title}**"));
        let next = readme[at + 2..].find("\n**").map_or(readme.len(), |n| at + 2 + n);
        assert!(
            readme[at..next].lines().any(|l| l == *lesson),
            "docs/studies.md's lesson for \"{title}\" is not the index's; run scripts/sync-lessons"
        );
        studies += 1;
    }
    assert_eq!(studies, 8, "docs/tradeoff/index.md should hold the eight studies");
    // docs/studies.md dates the run it shows: the index's date must appear in that paragraph.
    let date = index
        .lines()
        .find(|l| l.starts_with("Data:"))
        .and_then(|l| l.rsplit('(').next())
        .and_then(|s| s.get(..10))
        .expect("a Data line ending in its date");
    let shown = readme
        .find("`docs/tradeoff/` holds the run shown here")
        .expect("docs/studies.md's paragraph on the run");
    assert!(
        readme[shown..shown + 200].contains(date),
        "docs/studies.md's run date is not the index's {date}"
    );
}

/// Issue 33: `tradeoff` interrupted half-way left a study's CSV new and its SVG, notes and the
/// index old; now every file of a run is kept until all its studies are done and moved in
/// together, so an interrupted run leaves the folder exactly as it was. An output folder that
/// cannot be written is said at once, in one line, before any sweep.
#[test]
fn an_interrupted_or_impossible_tradeoff_run_changes_nothing() {
    use std::process::{Command, Stdio};
    let dir = common::output_dir().join("studies_interrupted");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let old: Vec<(String, &[u8])> = ["twist.csv", "twist.svg", "twist.md", "index.md"]
        .iter()
        .map(|n| (n.to_string(), &b"an older run"[..]))
        .collect();
    for (name, bytes) in &old {
        std::fs::write(dir.join(name), bytes).unwrap();
    }
    let mut child = Command::new(common::example("tradeoff"))
        .args(["--study", "twist", "--quick", "--frames", "2", "--out"])
        .arg(&dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Its first measured configuration printed, it is half-way through: stop it.
    let mut err = std::io::BufReader::new(child.stderr.take().unwrap());
    let mut line = String::new();
    std::io::BufRead::read_line(&mut err, &mut line).unwrap();
    assert!(line.starts_with("twist "), "{line}");
    Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    let status = child.wait().unwrap();
    use std::os::unix::process::ExitStatusExt;
    assert_eq!(status.signal(), Some(libc::SIGTERM), "{status:?}");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["index.md", "twist.csv", "twist.md", "twist.svg"]);
    for (name, bytes) in &old {
        assert_eq!(std::fs::read(dir.join(name)).unwrap(), *bytes, "{name} changed");
    }
    // An --out under a file: one line, before the GPU is opened or a sweep run.
    let out = Command::new(common::example("tradeoff"))
        .args(["--study", "twist", "--out"])
        .arg(dir.join("index.md").join("sub"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with("tradeoff: error: ") && err.contains("Not a directory"),
        "{err}"
    );
    assert!(!err.contains("Caused by") && !err.contains("backtrace"), "{err}");
}

/// `tradeoff` on a full disk leaves what was there before, never a new, empty output folder
/// (the folder is made only when the files are moved in, and removed again if that fails). The disk is made full for the one process by a file size
/// limit (`RLIMIT_FSIZE`: a write past 4 KiB fails, as on a full disk, with `SIGXFSZ`
/// ignored), which needs no root and no mount.
#[test]
fn a_tradeoff_run_that_cannot_write_leaves_no_new_folder() {
    use std::os::unix::process::CommandExt;
    use std::process::Command;
    let dir = common::output_dir().join("studies_full_disk");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let mut command = Command::new(common::example("tradeoff"));
    command
        .args(["--study", "bezier", "--quick", "--frames", "1", "--out"])
        .arg(dir.join("new/sub"))
        .env("MESA_SHADER_CACHE_DISABLE", "true");
    // SAFETY: only async-signal-safe calls (signal, setrlimit) between fork and exec.
    unsafe {
        command.pre_exec(|| {
            libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
            let limit = libc::rlimit {
                rlim_cur: 4096,
                rlim_max: 4096,
            };
            if libc::setrlimit(libc::RLIMIT_FSIZE, &limit) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
    let out = command.output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("bezier.svg: File too large"), "{err}");
    let left: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()).collect();
    assert!(left.is_empty(), "a failed run left {left:?}");
}
