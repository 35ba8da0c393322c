//! The installable `shaderlab` command: `cargo install --path .` puts it in `ROOT/bin`, and it
//! lists the labs, runs one, records one, and refuses what it does not know.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::output_dir;

/// `cargo install --path . --root DIR`, reusing this build's target directory.
fn installed() -> PathBuf {
    let root = output_dir().join("install-root");
    let _ = std::fs::remove_dir_all(&root);
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let status = Command::new(cargo)
        .args(["install", "--quiet", "--offline", "--locked", "--path"])
        .arg(manifest)
        .arg("--root")
        .arg(&root)
        .arg("--target-dir")
        .arg(manifest.join("target"))
        .status()
        .expect("run cargo install");
    assert!(status.success(), "cargo install failed ({status})");
    let bin = root.join("bin/shaderlab");
    assert!(bin.is_file(), "{} is missing", bin.display());
    bin
}

#[test]
fn the_installed_command_lists_runs_and_refuses() {
    let bin = installed();
    let dir = output_dir().join("command");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let run = |args: &[&str]| Command::new(&bin).current_dir(&dir).args(args).output().unwrap();

    let list = run(&["list"]);
    assert!(list.status.success());
    let text = String::from_utf8_lossy(&list.stdout);
    for entry in shaderlab::course::ALL {
        assert!(
            text.lines()
                .any(|l| l.split_whitespace().next() == Some(entry.info.name)),
            "{} is not listed:\n{text}",
            entry.info.name
        );
        assert!(
            text.lines().any(|l| l == entry.info.lecture),
            "{} has no heading",
            entry.info.lecture
        );
    }

    let shot = run(&["run", "twist", "--set", "twisting=2", "--screenshot", "t.png"]);
    assert!(shot.status.success(), "{}", String::from_utf8_lossy(&shot.stderr));
    let picture = image::open(dir.join("t.png")).unwrap().to_rgb8();
    let reference = common::render_state(shaderlab::course::TWIST, &[("twisting", "2")]);
    assert_eq!(picture, reference, "the command draws what the lab draws");

    let rec = run(&["record", "twist", "r.gif", "--frames", "2"]);
    assert!(rec.status.success(), "{}", String::from_utf8_lossy(&rec.stderr));
    assert!(dir.join("r.gif").is_file());

    let help = run(&["run", "phong", "--help"]);
    assert!(help.status.success());
    assert!(String::from_utf8_lossy(&help.stdout).contains("PARAMETERS"));

    for (args, says) in [
        (&["run", "nope"][..], "no lab called `nope`"),
        (&["frobnicate"][..], "unknown command"),
        (&["record", "twist"][..], "where to?"),
    ] {
        let out = run(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(String::from_utf8_lossy(&out.stderr).contains(says), "{args:?}");
    }
}
