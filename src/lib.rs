//! # shaderlab
//!
//! Classic OpenGL/GLSL shader lectures ported to wgpu, starting with the five exercises of
//! CMP211 Lab05 ("Shader programming", OpenGL 2.0 / GLSL 1.10 / GLUT): position → RGB,
//! normal → RGB, Phong, simplex noise and displacement, on GLUT-exact cube, sphere, torus and
//! teapot meshes, rendered like the original in a window or offscreen.
//!
//! Layers, each using only those below it (no module reaches up, and there are no import
//! circles):
//! - [`shell`]: the window and the browser page, each turning its events into calls on one
//!   [`shell::session::Session`] (which draws each frame) and presenting what it drew; the
//!   command line; `--screenshot`, `--bench`, `--record` and the tools, which build the lab as
//!   the session does ([`shell::session::Sources`]) and draw it with the same checked render,
//!   without a clock, input or inspector. It drives any [`Lab`] through its [`LabEntry`] and
//!   never names an exercise.
//! - [`course`]: the course, one module per lab, and [`course::ALL`], the one list of labs.
//! - [`debug`]: the GLSL debugger, why a pixel has its colour: a frame's draws read back and
//!   replayed on the CPU for one pixel, naga's IR of its shaders interpreted (`shaderlab
//!   debug`, F2 in a window and the page's Inspect); whole-frame views of a line's value or the
//!   cost, drawn by instrumented shaders and coloured on the GPU (`shaderlab view`, F3, a
//!   clicked line); `diff`, where a copy of the shaders departs.
//! - [`lab`]: the contract a lab fulfils ([`Lab`], [`lab::Input`]) and the runner of labs
//!   described as data ([`lab::Recipe`]: a [`lab::Geometry`] drawn with a [`lab::Material`]).
//! - [`legacy`]: a course's own GLSL 1.10/1.20 shaders translated to GLSL 450 (source-mapped).
//! - [`render`]: programs reflected from their shaders, uniform blocks, meshes, textures, frames.
//! - Foundations: [`shader`] (GLSL loading, diagnostics, reflection), [`offscreen`] and [`gpu`]
//!   (targets and the device), [`camera`] (GLU matrices), [`mesh`] (meshes on the CPU: GLUT's
//!   solids and their levels, [`tess`], OBJ models), [`images`] (pictures and procedural
//!   textures), [`params`] (named, ranged values), [`user_files`],
//!   [`fsutil`] (files in and out, never lost), [`memory`] (what the process may still take),
//!   [`panics`] (dependencies' panics contained), [`error`] (the typed errors).
//! - [`study`]: the speed/accuracy yardsticks of the tests and studies, which nothing above
//!   uses: [`exact`], [`metrics`], [`noise`].
//!
//! Everything that needs no GPU can be used directly, e.g. GLUT's meshes and the tessellation
//! level `--tess auto` would pick:
//!
//! ```
//! use shaderlab::mesh::Mesh;
//! use shaderlab::{tess, Object};
//!
//! // glutSolidSphere(1, 24, 24): 24 * 23 + 2 vertices, the pole triangles of zero area dropped.
//! let sphere = Mesh::sphere(1.0, 24, 24);
//! assert_eq!((sphere.vertices.len(), sphere.triangle_count()), (554, 1104));
//! // At 5 units in a 360-row window GLUT's 24 slices leave about 0.9 px of silhouette error;
//! // half a pixel needs more.
//! let level = tess::choose_level(Object::Sphere, 5.0, 360, tess::DEFAULT_BUDGET_PX);
//! assert!(level > 24 && tess::silhouette_error_px(Object::Sphere, level, 5.0, 360) <= 0.5);
//! ```
#![warn(missing_docs)]

pub mod camera;
pub mod course;
pub mod debug;
pub mod error;
pub mod fsutil;
pub mod gpu;
pub mod images;
pub mod lab;
pub mod legacy;
pub mod memory;
pub mod mesh;
pub mod offscreen;
pub mod panics;
pub mod params;
pub mod render;
pub mod shader;
pub mod shell;
pub mod study;
pub mod user_files;

pub use error::{Error, Result};
pub use gpu::Gpu;
pub use lab::{Lab, LabEntry};
pub use mesh::tess;
pub use mesh::tess::Object;
pub use study::{exact, metrics, noise};

#[cfg(test)]
mod tests {
    use std::path::Path;

    /// The names this file re-exports at the crate's root (`pub use a::{b, c};`, `pub use a::b;`).
    fn root_re_exports(lib: &str) -> Vec<String> {
        let mut names = Vec::new();
        for line in lib.lines().filter_map(|l| l.strip_prefix("pub use ")) {
            let line = line.trim_end_matches(';');
            let list = match line.split_once("::{") {
                Some((_, list)) => list.trim_end_matches('}').to_owned(),
                None => line.rsplit("::").next().unwrap_or(line).to_owned(),
            };
            names.extend(list.split(',').map(|n| n.trim().to_owned()).filter(|n| !n.is_empty()));
        }
        names
    }

    /// The places in `text` that name `crate::NAME` for one of `names` (not `$crate::`, which a
    /// macro expands where the crate's user wrote it, nor a longer path ending in `crate`).
    fn through_the_root(text: &str, names: &[String]) -> Vec<String> {
        let mut found = Vec::new();
        for (at, _) in text.match_indices("crate::") {
            let before = text[..at].chars().next_back();
            if before.is_some_and(|c| c.is_alphanumeric() || matches!(c, '_' | ':' | '$')) {
                continue;
            }
            let rest = &text[at + "crate::".len()..];
            let ident: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            if names.contains(&ident) {
                let line = text[..at].matches('\n').count() + 1;
                found.push(format!("{line}: crate::{ident}"));
            }
        }
        found
    }

    /// The text files of the crate, its tests, examples and docs (`.rs`, `.md`, shaders), by path
    /// from the crate's root, this file left out (it names what it looks for).
    fn texts() -> Vec<(String, String)> {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let mut found = vec![(
            "README.md".to_owned(),
            std::fs::read_to_string(root.join("README.md")).unwrap(),
        )];
        let mut dirs: Vec<_> = ["src", "tests", "examples", "docs", "shaders_glsl"]
            .iter()
            .map(|d| root.join(d))
            .collect();
        while let Some(dir) = dirs.pop() {
            for entry in std::fs::read_dir(&dir).unwrap() {
                let path = entry.unwrap().path();
                let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
                if path.is_dir() {
                    dirs.push(path);
                } else if ["rs", "md", "glsl", "vert", "frag"].contains(&ext) && path != root.join("src/lib.rs") {
                    let name = path.strip_prefix(root).unwrap().display().to_string();
                    found.push((name, std::fs::read_to_string(&path).unwrap()));
                }
            }
        }
        found
    }

    /// Whether `text` holds `word` as a whole word (not inside a longer identifier).
    fn has_word(text: &str, word: &str) -> bool {
        let ident = |c: Option<char>| c.is_some_and(|c| c.is_alphanumeric() || c == '_');
        text.match_indices(word)
            .any(|(at, _)| !ident(text[..at].chars().next_back()) && !ident(text[at + word.len()..].chars().next()))
    }

    /// One name per idea: the course is `course` (a lab is one of its modules), CPU meshes are
    /// `mesh` and pictures `images` (a lab's camera, matrices and mesh are its geometry, the
    /// trait `lab::Geometry`), which shader pairs a material draws is its `PairChoice`, a draw the
    /// debugger captured is a `CapturedDraw`, F10 makes a recording, and a `BuildContext` has a
    /// name. The names these ideas had before are nowhere.
    #[test]
    fn one_name_per_idea() {
        assert!(has_word("a stage.", "stage") && !has_word("max_inter_stage_x", "stage"));
        // Written in two halves, so that the renaming script (renames.sh) leaves them.
        let retired = [
            ("crate::", "labs"),
            ("shaderlab::", "labs"),
            ("src/", "labs/"),
            ("crate::", "geometry"),
            ("shaderlab::", "geometry"),
            ("src/", "geometry/"),
            ("stage", ".rs"),
            ("Stage", "Config"),
            ("STAGE", "_KEYS"),
            ("with_", "lab"),
            ("cx.", "lab"),
            ("window/", "capture.rs"),
            ("capture::", "Capture"),
            ("Draw::", "ChosenBy"),
            ("capture::", "Draw"),
            ("material.", "passes"),
            ("MATERIAL.", "passes"),
        ]
        .map(|(a, b)| format!("{a}{b}"));
        let mut found = Vec::new();
        for (file, text) in texts() {
            for name in &retired {
                if text.contains(name.as_str()) {
                    found.push(format!("{file}: {name}"));
                }
            }
            // Inside the course "stage" meant a lab's geometry: the word is kept out of it.
            if file.starts_with("src/course/") && (has_word(&text, "stage") || has_word(&text, "stages")) {
                found.push(format!("{file}: stage"));
            }
        }
        assert!(found.is_empty(), "retired names:\n{}", found.join("\n"));
    }

    /// The layer list above and the README's "How it is built" name every module of the crate.
    #[test]
    fn the_layer_lists_name_every_module() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let lib = std::fs::read_to_string(root.join("src/lib.rs")).unwrap();
        let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
        let doc: String = lib.lines().filter_map(|l| l.strip_prefix("//!")).collect();
        let tree = readme
            .split("## How it is built")
            .nth(1)
            .and_then(|rest| rest.split("```").nth(1))
            .expect("README: a tree under \"How it is built\"");
        let modules: Vec<&str> = lib
            .lines()
            .filter_map(|l| l.strip_prefix("pub mod ")?.strip_suffix(';'))
            .collect();
        assert!(modules.len() > 10, "{modules:?}");
        for module in modules {
            assert!(
                doc.contains(&format!("[`{module}`]")),
                "lib.rs's layers leave out `{module}`"
            );
        }
        // Every entry of src/ (the binary's main.rs, a module's folder and its face beside
        // it) is named in the tree.
        for entry in std::fs::read_dir(root.join("src")).unwrap() {
            let entry = entry.unwrap();
            let name = entry.file_name().to_string_lossy().into_owned();
            let word = if entry.path().is_dir() {
                format!("{name}/")
            } else {
                name
            };
            assert!(
                tree.split_whitespace().any(|w| w == word),
                "README's \"How it is built\" leaves out src/{word}"
            );
        }
    }

    /// The crate's root re-exports are for its users: inside the crate every module names an
    /// item by the module that defines it (`crate::mesh::tess`, `crate::error::Error`),
    /// so that no lower layer depends on the root, which holds every layer.
    #[test]
    fn inside_the_crate_items_are_named_by_their_modules_not_the_root() {
        let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
        let names = root_re_exports(&std::fs::read_to_string(src.join("lib.rs")).unwrap());
        for name in ["tess", "Error", "metrics", "Object"] {
            assert!(names.iter().any(|n| n == name), "{name} in {names:?}");
        }
        let sample = "use crate::tess::Object;\nfn f() -> crate::Result<()> { $crate::tess; crate::mesh::tess }";
        assert_eq!(through_the_root(sample, &names), ["1: crate::tess", "2: crate::Result"]);

        let mut found = Vec::new();
        let mut dirs = vec![src.clone()];
        while let Some(dir) = dirs.pop() {
            for entry in std::fs::read_dir(&dir).unwrap() {
                let path = entry.unwrap().path();
                if path.is_dir() {
                    dirs.push(path);
                } else if path.extension().is_some_and(|e| e == "rs") && path != src.join("lib.rs") {
                    let text = std::fs::read_to_string(&path).unwrap();
                    let file = path.strip_prefix(&src).unwrap().display().to_string();
                    found.extend(
                        through_the_root(&text, &names)
                            .into_iter()
                            .map(|f| format!("src/{file}:{f}")),
                    );
                }
            }
        }
        found.sort();
        assert!(
            found.is_empty(),
            "named through the crate's root re-exports:\n{}",
            found.join("\n")
        );
    }
}
