//! What the one runner promises for every lab of `course::ALL`: each lab hands out its programs
//! and draws the same picture through naga's WGSL translation of them (the GLSL-versus-WGSL
//! round trip); each key row names a parameter the lab has; a uniform block member that no
//! parameter or computed value feeds is an error that names it.

mod common;

use common::*;
use shaderlab::course;
use shaderlab::metrics::psnr;
use shaderlab::shader::ShaderSource;

#[test]
fn every_lab_draws_the_same_picture_through_wgsl() {
    let gpu = gpu();
    let mut report = Vec::new();
    for entry in course::ALL {
        let name = entry.info.name;
        let mut glsl = build(entry);
        let mut wgsl = build(entry);
        let programs = wgsl.programs();
        assert!(!programs.is_empty(), "{name} hands out no programs");
        let count = programs.len();
        for program in programs {
            let (vs, fs) = program.shaders();
            let (vs, fs) = (
                vs.to_wgsl().unwrap_or_else(|e| panic!("{name}: {e}")),
                fs.to_wgsl().unwrap_or_else(|e| panic!("{name}: {e}")),
            );
            program
                .use_wgsl(gpu, &vs, &fs)
                .unwrap_or_else(|e| panic!("{name}: the WGSL pipeline does not build: {e}"));
        }
        let a = shot(glsl.as_mut());
        let b = shot(wgsl.as_mut());
        let first = *b.get_pixel(0, 0);
        assert!(
            b.pixels().any(|p| *p != first),
            "{name}: the WGSL pipeline drew nothing (one colour)"
        );
        match psnr(&a, &b) {
            None => panic!("{name}: images differ in size"),
            Some(db) if a != b && db < 60.0 => {
                let _ = a.save(output_dir().join(format!("{name}.glsl.png")));
                let _ = b.save(output_dir().join(format!("{name}.wgsl.png")));
                panic!("{name}: the WGSL picture differs from the GLSL one: {db:.2} dB < 60");
            }
            Some(db) => report.push(format!(
                "{name}: {count} program(s), {}",
                if a == b {
                    "identical".to_owned()
                } else {
                    format!("{db:.1} dB")
                }
            )),
        }
    }
    println!("{}", report.join("\n"));
}

#[test]
fn every_key_row_names_a_parameter_of_its_lab() {
    for entry in course::ALL {
        let params = (entry.params)();
        for name in entry.info.keys.params() {
            assert!(
                params.has(name),
                "{}: a key row names `{name}`, which it lacks",
                entry.info.name
            );
        }
        assert!(!entry.info.keys.help().is_empty(), "{}: no keys help", entry.info.name);
    }
}

#[test]
fn a_block_member_without_a_parameter_is_named() {
    let dir = output_dir().join("recipes-unfed-member");
    let _ = std::fs::remove_dir_all(&dir);
    copy_shaders(&dir);
    let file = dir.join("twist_params.glsl");
    let text = std::fs::read_to_string(&file).unwrap();
    let edited = text.replace("float twisting;", "float twisting;\n    float spin;");
    assert_ne!(text, edited, "twist_params.glsl has `float twisting;`");
    std::fs::write(&file, edited).unwrap();
    let source = ShaderSource::Dir(dir.clone());
    let cx = shaderlab::lab::BuildContext::new(
        gpu(),
        &source,
        shaderlab::offscreen::COLOR_FORMAT,
        &shaderlab::lab::NO_FILES,
    );
    let err = match (course::TWIST.new)(&cx) {
        Ok(_) => panic!("twist built with a block member no parameter feeds"),
        Err(e) => e.to_string(),
    };
    assert!(
        err.contains("`float spin`") && err.contains("Twist") && err.contains("no parameter"),
        "{err}"
    );
}

#[test]
fn a_reload_that_changes_a_block_keeps_the_last_good_pipeline() {
    let dir = output_dir().join("recipes-block-reload");
    let _ = std::fs::remove_dir_all(&dir);
    copy_shaders(&dir);
    let source = ShaderSource::Dir(dir.clone());
    let cx = shaderlab::lab::BuildContext::new(
        gpu(),
        &source,
        shaderlab::offscreen::COLOR_FORMAT,
        &shaderlab::lab::NO_FILES,
    );
    let mut lab = (course::TWIST.new)(&cx).expect("twist builds");
    let before = shot(lab.as_mut());
    let file = dir.join("twist_params.glsl");
    let text = std::fs::read_to_string(&file).unwrap();
    // The same members in another order: the block the lab fills no longer matches.
    let swapped = text.replace(
        "    vec3 color;       // uniform vec3 color (course: (0.5, 9.0, 0.5); 9.0 clamps to 1)\n    float twisting;",
        "    float twisting;\n    vec3 color;",
    );
    assert_ne!(text, swapped, "twist_params.glsl declares color then twisting");
    std::fs::write(&file, swapped).unwrap();
    let err = lab.reload(&cx).expect_err("a changed block").to_string();
    assert!(err.contains("Twist") && err.contains("changed its members"), "{err}");
    assert_eq!(shot(lab.as_mut()), before, "the last good pipeline still draws");
}

/// `cargo run --example NAME` works for every lab: each lab of the one list has its example
/// (which names no lab: `lab_example!()` finds the one registered under the example's name),
/// and every other example is one of the tools.
#[test]
fn every_lab_has_its_example_and_every_example_is_a_lab_or_a_tool() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    for entry in course::ALL {
        let name = entry.info.name;
        let text = std::fs::read_to_string(dir.join(format!("{name}.rs")))
            .unwrap_or_else(|e| panic!("examples/{name}.rs: {e}"));
        assert!(
            text.contains("shaderlab::lab_example!();"),
            "examples/{name}.rs does not call shaderlab::lab_example!()"
        );
        assert!(course::find(name).is_some_and(|e| std::ptr::eq(e, *entry)));
    }
    for file in std::fs::read_dir(&dir).unwrap() {
        let path = file.unwrap().path();
        let stem = path.file_stem().unwrap().to_string_lossy().into_owned();
        assert!(
            course::find(&stem).is_some() || ["bench", "glsl2wgsl", "labs", "tradeoff", "web"].contains(&stem.as_str()),
            "examples/{stem}.rs is neither a lab nor a tool"
        );
    }
}

#[test]
fn a_texture_the_lab_does_not_provide_is_named() {
    let dir = output_dir().join("recipes-missing-texture");
    let _ = std::fs::remove_dir_all(&dir);
    copy_shaders(&dir);
    let file = dir.join("twist.frag");
    let text = std::fs::read_to_string(&file).unwrap();
    let edited = text.replacen(
        "void main()",
        "layout(set = 0, binding = 7) uniform texture2D extra;\nvoid main()",
        1,
    );
    assert_ne!(text, edited, "twist.frag has a main");
    std::fs::write(&file, edited).unwrap();
    let source = ShaderSource::Dir(dir.clone());
    let cx = shaderlab::lab::BuildContext::new(
        gpu(),
        &source,
        shaderlab::offscreen::COLOR_FORMAT,
        &shaderlab::lab::NO_FILES,
    );
    let err = match (course::TWIST.new)(&cx) {
        Ok(_) => panic!("twist built without the texture its shader declares"),
        Err(e) => e.to_string(),
    };
    assert!(err.contains("`extra`") && err.contains("does not provide"), "{err}");
}

/// "Adding an exercise" (docs/adding-an-exercise.md) shows exercise 1's file as it is: a copy that drifted from
/// the code would teach a newcomer something false.
#[test]
fn the_readmes_example_lab_is_the_real_file() {
    let root = env!("CARGO_MANIFEST_DIR");
    let readme = std::fs::read_to_string(format!("{root}/docs/adding-an-exercise.md")).unwrap();
    let file = std::fs::read_to_string(format!("{root}/src/course/seed000/position_rgb.rs")).unwrap();
    let code = &file[file.find("\nuse ").expect("the file's first use") + 1..];
    let shown = readme
        .split("```rust\n")
        .nth(1)
        .and_then(|rest| rest.split("\n```").next())
        .expect("a rust block in docs/adding-an-exercise.md");
    assert_eq!(
        shown.trim_end(),
        code.trim_end(),
        "docs/adding-an-exercise.md's copy of position_rgb.rs differs from the file"
    );
    // And what it names exists.
    for name in [
        "Recipe::new",
        "MaterialScene::build",
        "Material::new",
        "ShaderPair::new",
        "lab_name!()",
    ] {
        assert!(code.contains(name), "{name}");
    }
    assert!(std::path::Path::new(&format!("{root}/examples/position_rgb.rs")).is_file());
}
