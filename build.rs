//! Embeds every file of `shaders_glsl/` into the library, so an installed example runs anywhere.
//!
//! The checkout is read from the `CARGO_MANIFEST_DIR` of *this run* (`std::env::var`), not from
//! `env!` at the script's compile time: after a checkout is moved or renamed, or when two
//! checkouts share one target directory, cargo re-runs this script without recompiling it, and a
//! compiled-in path would name the old, missing folder (issue 23). A folder that cannot be read, or
//! that lacks a shader file the labs name, fails the build with a message instead of embedding an
//! empty list.
use std::{
    env, fs,
    path::{Path, PathBuf},
    process::exit,
};

fn main() {
    let root = match env::var_os("CARGO_MANIFEST_DIR") {
        Some(root) => PathBuf::from(root),
        None => fail("CARGO_MANIFEST_DIR is not set; run the build through cargo"),
    };
    let dir = root.join("shaders_glsl");
    println!("cargo:rerun-if-changed={}", dir.display());
    let entries = fs::read_dir(&dir).unwrap_or_else(|e| fail(&format!("cannot read {}: {e}", dir.display())));
    let mut names = Vec::new();
    for entry in entries {
        let entry = entry.unwrap_or_else(|e| fail(&format!("cannot list {}: {e}", dir.display())));
        if !entry.path().is_file() {
            continue;
        }
        match entry.file_name().into_string() {
            Ok(name) => names.push(name),
            Err(name) => fail(&format!(
                "{}: a shader file name that is not UTF-8: {name:?}",
                dir.display()
            )),
        }
    }
    names.sort();

    let named = names_used_by_labs(&root.join("src/course"));
    let missing: Vec<&String> = named.iter().filter(|n| !names.contains(n)).collect();
    if !missing.is_empty() {
        fail(&format!(
            "{} lacks shader files the labs name: {}",
            dir.display(),
            missing.iter().map(|s| s.as_str()).collect::<Vec<_>>().join(", ")
        ));
    }

    let mut code = String::from(
        "/// Every shader file of `shaders_glsl/`, by file name.\npub static EMBEDDED: &[(&str, &str)] = &[\n",
    );
    for name in &names {
        let path = dir.join(name);
        println!("cargo:rerun-if-changed={}", path.display());
        code.push_str(&format!(
            "    ({name:?}, include_str!({:?})),\n",
            path.display().to_string()
        ));
    }
    code.push_str("];\n");
    let out = match env::var_os("OUT_DIR") {
        Some(out) => Path::new(&out).join("embedded_shaders.rs"),
        None => fail("OUT_DIR is not set; run the build through cargo"),
    };
    if let Err(e) = fs::write(&out, code) {
        fail(&format!("cannot write {}: {e}", out.display()));
    }
}

/// The shader file names quoted in the labs' sources (`"toon.vert"`, `"phong_params.glsl"`):
/// a plain scan of string literals, enough to catch a folder that is missing or stale.
fn names_used_by_labs(labs: &Path) -> Vec<String> {
    let mut names = Vec::new();
    let mut stack = vec![labs.to_path_buf()];
    while let Some(dir) = stack.pop() {
        println!("cargo:rerun-if-changed={}", dir.display());
        let Ok(entries) = fs::read_dir(&dir) else {
            fail(&format!("cannot read {}", dir.display()))
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let text = fs::read_to_string(&path).unwrap_or_default();
                for suffix in [".vert\"", ".frag\"", ".glsl\""] {
                    for (end, _) in text.match_indices(suffix) {
                        // Walk back over the name's characters to its opening quote.
                        let head = &text[..end];
                        let start = head
                            .rfind(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == '.'))
                            .unwrap_or(0);
                        if head[start..].starts_with('"') && end > start + 1 {
                            let name = format!("{}{}", &head[start + 1..], &suffix[..5]);
                            if !names.contains(&name) {
                                names.push(name);
                            }
                        }
                    }
                }
            }
        }
    }
    names.sort();
    names
}

fn fail(message: &str) -> ! {
    eprintln!("error: shaderlab build: {message}");
    println!("cargo:warning=shaderlab build: {message}");
    exit(1)
}
