//! The repository stands alone (issue 17.1): nothing the build, the tests or CI run reads
//! outside the checkout. CI runs with the team's shared folder beside the clone, so a test that
//! quietly read its reference images would pass there and fail for every user who cloned the
//! repository; this scan fails instead. Benchmark scripts under `scripts/` may call the original
//! programs kept in that folder, and say so in their header; they are not scanned.

use std::fs;
use std::path::{Path, PathBuf};

/// Every Rust and shell file under the paths that the build, the tests and CI run.
fn files() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut out = vec![root.join("build.rs"), root.join("Cargo.toml")];
    let mut stack: Vec<PathBuf> = ["src", "tests", "examples", ".ci"]
        .iter()
        .map(|d| root.join(d))
        .collect();
    while let Some(dir) = stack.pop() {
        for entry in fs::read_dir(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
            let path = entry.expect("directory entry").path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_none_or(|e| e == "rs" || e == "sh" || e == "toml") {
                out.push(path);
            }
        }
    }
    out
}

#[test]
fn nothing_the_build_tests_or_ci_run_reads_outside_the_repository() {
    let files = files();
    assert!(files.len() > 50, "the scan sees the tree ({} files)", files.len());
    let mut offenders = Vec::new();
    for path in &files {
        let Ok(text) = fs::read_to_string(path) else { continue };
        for (n, line) in text.lines().enumerate() {
            let code = line.trim_start();
            if code.starts_with("//") || code.starts_with('#') {
                continue;
            }
            // A path that climbs out of the checkout, or names the team's folder beside it.
            // (Spelled in pieces so that this line does not match itself.)
            let outside = [concat!("..", "/shared"), concat!("/wo", "rk/")]
                .iter()
                .any(|p| code.contains(p));
            if outside {
                offenders.push(format!("{}:{}: {}", path.display(), n + 1, code));
            }
        }
    }
    assert!(
        offenders.is_empty(),
        "reads outside the repository:\n{}",
        offenders.join("\n")
    );
}

#[test]
fn every_reference_image_the_tests_name_is_in_the_repository() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let seeds = root.join("tests/reference/seeds");
    let count = fs::read_dir(&seeds)
        .unwrap_or_else(|e| panic!("{}: {e}", seeds.display()))
        .filter(|e| {
            e.as_ref()
                .is_ok_and(|e| e.path().extension().is_some_and(|x| x == "png"))
        })
        .count();
    assert!(
        count >= 27,
        "the 27 images of the original programs of 001-004 are kept ({count} found)"
    );
    for name in [
        "001_bump_oblique.png",
        "003_specular_strip_default.png",
        "004_texparams_default.png",
    ] {
        assert!(seeds.join(name).is_file(), "{name} is in tests/reference/seeds");
    }
}
