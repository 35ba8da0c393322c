//! The package `cargo install shaderlab` builds from: what `cargo package --list` puts in it. It
//! holds what the command needs (sources, shaders, assets, examples, README, licence) and none
//! of what only the repository uses (the tests' reference pictures, the docs and their images,
//! scripts, CI). `.ci/run` builds the packaged crate by itself and runs its command from
//! another folder.

use std::path::Path;
use std::process::Command;

fn listed() -> Vec<String> {
    let out = Command::new(env!("CARGO"))
        .args(["package", "--list", "--allow-dirty", "--offline"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("cargo runs");
    assert!(
        out.status.success(),
        "cargo package --list failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout)
        .expect("UTF-8 paths")
        .lines()
        .map(str::to_owned)
        .collect()
}

#[test]
fn the_package_holds_what_the_command_needs_and_nothing_else() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let files = listed();
    for needed in [
        "Cargo.toml",
        "Cargo.lock",
        "LICENSE",
        "README.md",
        "build.rs",
        "src/main.rs",
        "src/lib.rs",
    ] {
        assert!(files.iter().any(|f| f == needed), "{needed} is not in the package");
    }
    // Every shader build.rs embeds, and every asset the sources include.
    for dir in ["shaders_glsl", "assets"] {
        let mut stack = vec![root.join(dir)];
        while let Some(d) = stack.pop() {
            for entry in std::fs::read_dir(&d).unwrap() {
                let path = entry.unwrap().path();
                if path.is_dir() {
                    stack.push(path);
                    continue;
                }
                let rel = path.strip_prefix(root).unwrap().to_string_lossy().replace('\\', "/");
                assert!(files.contains(&rel), "{rel} is not in the package");
            }
        }
    }
    for left_out in ["tests/", "docs/", "scripts/", ".ci/"] {
        let found: Vec<&String> = files.iter().filter(|f| f.starts_with(left_out)).collect();
        assert!(found.is_empty(), "the package holds {left_out}: {found:?}");
    }
    // Small: what is listed from the checkout (cargo's own generated files aside).
    let bytes: u64 = files
        .iter()
        .filter_map(|f| std::fs::metadata(root.join(f)).ok())
        .map(|m| m.len())
        .sum();
    assert!(bytes < 3_000_000, "the package's files take {bytes} bytes");
}

#[test]
fn the_licence_is_the_one_the_manifest_names() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let manifest = std::fs::read_to_string(root.join("Cargo.toml")).unwrap();
    assert!(manifest.contains("license = \"MIT\""));
    let licence = std::fs::read_to_string(root.join("LICENSE")).unwrap();
    assert!(
        licence.starts_with("MIT License"),
        "{}",
        &licence[..40.min(licence.len())]
    );
}
