//! Whole-frame views agree with the debugger: a line view's value at a pixel is the value the
//! debugger's trace gives that line's last assignment there (within 1e-3, relative), a pixel
//! where the trace never reaches the line is one where the view says it did not run, and a cost
//! view's count is the debugger's `cost` exactly; across labs, both stages, a course GLSL 1.10
//! file, a branch and loops. Bad probes get their messages.

mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use common::gpu;
use shaderlab::debug::view::{self, Probe, ValueFrame, ViewDrawer, ViewError};
use shaderlab::debug::{Captured, Inspection, Stage};
use shaderlab::lab::{Lab, UserFiles};
use shaderlab::render::DrawLog;
use shaderlab::shader::ShaderSource;

const WIDTH: u32 = 320;
const HEIGHT: u32 = 180;

fn build(name: &str, source: ShaderSource, files: &UserFiles, set: &[(&str, &str)]) -> Box<dyn Lab> {
    common::lab_at(name, &source, files, set)
}

fn lab(name: &str, set: &[(&str, &str)]) -> Box<dyn Lab> {
    build(name, ShaderSource::Embedded, &UserFiles::default(), set)
}

/// A lab drawing with the built-in shaders but for `edits` (file name → text).
fn edited(name: &str, edits: &[(&str, &str)], set: &[(&str, &str)]) -> Box<dyn Lab> {
    let map: BTreeMap<String, String> = edits.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect();
    build(name, ShaderSource::Edited(Arc::new(map)), &UserFiles::default(), set)
}

fn course(lab: u32) -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/course/seed000");
    vec![dir.join(format!("lab{lab}.vert")), dir.join(format!("lab{lab}.frag"))]
}

/// The legacy runner with the course's exercise `n` (GLSL 1.10, translated).
fn legacy(n: u32) -> Box<dyn Lab> {
    let files = UserFiles {
        inputs: course(n),
        ..UserFiles::default()
    };
    build("legacy", ShaderSource::Embedded, &files, &[("object", "teapot")])
}

fn frame(lab: &mut dyn Lab) -> (DrawLog, Captured) {
    view::capture(gpu(), lab, WIDTH, HEIGHT).unwrap_or_else(|e| panic!("capture: {e}"))
}

/// The file (as the lab shows it) whose path ends with `suffix`, and the first line of it
/// holding `needle`.
fn line_of(captured: &Captured, suffix: &str, needle: &str) -> (String, u32) {
    for d in &captured.draws {
        for shader in [&d.vertex, &d.fragment] {
            for (path, text) in &shader.source.files {
                if path.ends_with(suffix) {
                    if let Some(k) = text.lines().position(|l| l.contains(needle)) {
                        return (path.clone(), k as u32 + 1);
                    }
                }
            }
        }
    }
    panic!("no file ending {suffix} holds {needle:?}");
}

fn probe(file: &str, line: u32, name: Option<&str>) -> Probe {
    Probe::Line {
        file: file.to_owned(),
        line,
        name: name.map(str::to_owned),
        stage: None,
    }
}

/// Up to `n` pixels where `pick` holds, spread evenly over them in scan order.
fn spread(frame: &ValueFrame, n: usize, pick: impl Fn(usize) -> bool) -> Vec<(u32, u32)> {
    let all: Vec<usize> = (0..frame.values.len()).filter(|&i| pick(i)).collect();
    if all.is_empty() {
        return Vec::new();
    }
    let step = (all.len() / n).max(1);
    all.iter()
        .skip(step / 2)
        .step_by(step)
        .take(n)
        .map(|&i| (i as u32 % frame.width, i as u32 / frame.width))
        .collect()
}

/// The last value the trace gives `name` at `file:line` in `stage` (the pixel's fragment, or a
/// vertex corner's), if the trace reaches the line.
fn traced(ins: &Inspection, stage: Stage, file: &str, line: u32, name: &str) -> Vec<Vec<f64>> {
    ins.steps
        .iter()
        .filter(|s| s.stage == stage && s.file == file && s.line == line)
        .filter(|s| {
            s.name == name || s.name.starts_with(&format!("{name}.")) || s.name.starts_with(&format!("{name}["))
        })
        .map(|s| s.value.clone())
        .collect()
}

fn close(gpu: f32, cpu: f64) -> bool {
    let (a, b) = (f64::from(gpu), cpu);
    (a - b).abs() <= 1e-3 * b.abs().max(1.0) || (a.is_nan() && b.is_nan())
}

/// Checks a fragment line view of `lab` against the debugger at `n` pixels where it ran (and
/// at pixels drawn where it did not); returns the frame.
fn agrees(label: &str, lab: &mut dyn Lab, suffix: &str, needle: &str, name: Option<&str>, n: usize) -> ValueFrame {
    let (log, captured) = frame(lab);
    let (file, line) = line_of(&captured, suffix, needle);
    let view = view::draw_view(gpu(), &log, &probe(&file, line, name), WIDTH, HEIGHT)
        .unwrap_or_else(|e| panic!("{label}: view of {file}:{line}: {e}"));
    let resolved = view.resolved.clone().expect("a line view");
    // A line assigning only what the compiler made (a `?:`'s result) has no name to choose.
    let name = resolved.site.name.clone().unwrap_or_else(|| "(temporary)".into());
    assert!(!view.vertex, "{label}: {file}:{line} is a fragment line");
    assert!(view.components >= 1, "{label}: the value has components");
    let ran = spread(&view, n, |i| view.ran[i]);
    assert!(
        ran.len() >= n.min(4),
        "{label}: {file}:{line} ran at {} pixels",
        ran.len()
    );
    for &(x, y) in &ran {
        let ins = Inspection::new(label, &captured, x, y).unwrap_or_else(|e| panic!("{label} {x},{y}: {e}"));
        let values = traced(&ins, Stage::Fragment, &file, line, &name);
        let last = values
            .last()
            .unwrap_or_else(|| panic!("{label} {x},{y}: the view ran {file}:{line} but the trace never reaches it"));
        let got = view.values[view.at(x, y)];
        let k = last.len().min(4);
        assert_eq!(k as u32, view.components, "{label} {x},{y}: components of `{name}`");
        for c in 0..k {
            assert!(
                close(got[c], last[c]),
                "{label} pixel {x},{y}: {file}:{line} `{name}` component {c}: view {}, debugger {} (view {:?}, trace {:?})",
                got[c],
                last[c],
                got,
                last
            );
        }
    }
    // Drawn pixels where the view says the line did not run: the trace does not reach it.
    for (x, y) in spread(&view, 4, |i| !view.ran[i] && view.cost[i] > 0) {
        let ins = Inspection::new(label, &captured, x, y).unwrap_or_else(|e| panic!("{label} {x},{y}: {e}"));
        assert!(
            traced(&ins, Stage::Fragment, &file, line, &name).is_empty(),
            "{label} pixel {x},{y}: the view says {file}:{line} did not run, the trace has it"
        );
    }
    view
}

/// Checks a cost view of `lab` against the debugger's `cost` at `n` drawn pixels and a few
/// undrawn ones; returns the costs seen.
fn costs_agree(label: &str, lab: &mut dyn Lab, n: usize) -> Vec<u32> {
    let (log, captured) = frame(lab);
    let view = view::draw_view(gpu(), &log, &Probe::Cost, WIDTH, HEIGHT).unwrap_or_else(|e| panic!("{label}: {e}"));
    let mut pixels = spread(&view, n, |i| view.cost[i] > 0);
    assert!(
        pixels.len() >= n.min(4),
        "{label}: the cost view draws {} pixels",
        pixels.len()
    );
    pixels.extend(spread(&view, 2, |i| view.cost[i] == 0));
    let mut seen = Vec::new();
    for (x, y) in pixels {
        let ins = Inspection::new(label, &captured, x, y).unwrap_or_else(|e| panic!("{label} {x},{y}: {e}"));
        let gpu_cost = view.cost[view.at(x, y)];
        assert_eq!(
            gpu_cost as usize, ins.cost,
            "{label} pixel {x},{y}: the cost view counts {gpu_cost} steps, the debugger {}",
            ins.cost
        );
        let json: serde_json::Value = serde_json::from_str(&ins.json()).expect("the inspection's JSON");
        assert_eq!(
            json["cost"],
            serde_json::json!(ins.cost),
            "{label} {x},{y}: the JSON's cost"
        );
        assert!(
            ins.text()
                .contains(&format!("cost: {} steps of the fragment shader", ins.cost))
                || ins.cost == 0,
            "{label} {x},{y}: the text says the cost"
        );
        seen.push(gpu_cost);
    }
    seen
}

#[test]
fn a_line_view_shows_the_value_the_debugger_traces() {
    // Phong: N·L (the diffuse term) and L, computed through a function of an included file.
    let mut phong = lab("phong", &[("object", "teapot")]);
    let v = agrees("phong", phong.as_mut(), "phong.frag", "max(dot(N, L), 0.0)", None, 8);
    assert_eq!(v.components, 4, "Idiff is a vec4");
    agrees(
        "phong",
        phong.as_mut(),
        "phong.frag",
        "vec3 L = safe_normalize",
        None,
        6,
    );
    // A function called three times (L, E, R): its line shows the last call's value.
    agrees(
        "phong",
        phong.as_mut(),
        "safe_math.glsl",
        "return dot(v, v) > 0.0",
        None,
        6,
    );
    let mut torus = lab("phong", &[("object", "torus"), ("xangle", "30"), ("yangle", "40")]);
    agrees("phong torus", torus.as_mut(), "phong.frag", "vec3 R = ", Some("R"), 6);
    // phong_dir: the scalar N·L, and the colour it adds to.
    let mut dir = lab("phong_dir", &[]);
    let v = agrees("phong_dir", dir.as_mut(), "phong_dir.frag", "float cos_theta", None, 8);
    assert_eq!(v.components, 1, "cos_theta is a float");
    agrees(
        "phong_dir",
        dir.as_mut(),
        "phong_dir.frag",
        "color += light_intensity * material_diffuse",
        None,
        6,
    );
    let mut normal = lab("normal_rgb", &[("object", "sphere")]);
    agrees(
        "normal_rgb",
        normal.as_mut(),
        "normal_rgb.frag",
        "frag_color = vec4(normal",
        None,
        8,
    );
    let mut noise = lab("noise", &[("object", "sphere"), ("time", "2.5")]);
    agrees("noise", noise.as_mut(), "noise.frag", "vec3 v = position", None, 6);
}

#[test]
fn a_line_view_of_a_course_glsl_110_file_uses_the_users_names() {
    let mut lab3 = legacy(3);
    agrees("legacy lab3", lab3.as_mut(), "lab3.frag", "vec3 L = normalize", None, 6);
    let v = agrees("legacy lab3", lab3.as_mut(), "lab3.frag", "gl_FragColor = Ka", None, 6);
    let name = v.resolved.and_then(|r| r.site.name).expect("a name");
    assert_eq!(name, "gl_FragColor", "the user's name, not the translator's");
}

/// A loop whose passes differ from pixel to pixel, in a copy of noise.frag.
const LOOPING_NOISE: &str = "#version 450
#include \"noise_params.glsl\"
#include \"noise.glsl\"

layout(location = 0) in vec3 position;
layout(location = 0) out vec4 frag_color;

void main() {
    vec3 v = position + time;
    float sum = 0.0;
    int n = 1 + int(abs(position.x) * 6.0);
    for (int i = 0; i < n; i++) {
        sum += snoise(v * float(i + 1));
        if (sum > 0.5) {
            sum -= 0.25;
        }
    }
    frag_color = vec4(shade * abs(sum), 1.0);
}
";

#[test]
fn a_line_view_in_a_loop_shows_the_last_value_and_a_branch_not_taken_does_not_run() {
    let mut noise = edited(
        "noise",
        &[("noise.frag", LOOPING_NOISE)],
        &[("object", "sphere"), ("time", "1.5")],
    );
    agrees("looping noise", noise.as_mut(), "noise.frag", "sum += snoise", None, 6);
    let branch = agrees("looping noise", noise.as_mut(), "noise.frag", "sum -= 0.25", None, 6);
    let drawn = branch.cost.iter().filter(|&&c| c > 0).count();
    let ran = branch.ran.iter().filter(|&&r| r).count();
    assert!(
        ran > 0 && ran < drawn,
        "the branch runs at some drawn pixels, not all: {ran} of {drawn}"
    );
    // phong_dir: the specular term is added only where the light reflects towards the eye.
    let mut dir = lab("phong_dir", &[]);
    let v = agrees(
        "phong_dir",
        dir.as_mut(),
        "phong_dir.frag",
        "material_specular * pow",
        None,
        6,
    );
    let drawn = v.cost.iter().filter(|&&c| c > 0).count();
    let ran = v.ran.iter().filter(|&&r| r).count();
    assert!(
        ran > 0 && ran < drawn,
        "the highlight's branch runs at some drawn pixels: {ran} of {drawn}"
    );
    // uniform_arrays: the first band of an if/else chain runs only in the highlight.
    let mut bands = lab("uniform_arrays", &[]);
    let v = agrees(
        "uniform_arrays",
        bands.as_mut(),
        "uniform_arrays.frag",
        "frag_color = colors[2]",
        None,
        4,
    );
    let drawn = v.cost.iter().filter(|&&c| c > 0).count();
    let ran = v.ran.iter().filter(|&&r| r).count();
    assert!(ran < drawn, "the last band is not everywhere: {ran} of {drawn}");
}

#[test]
fn a_vertex_line_view_is_the_value_interpolated_as_a_varying() {
    let mut phong = lab("phong", &[("object", "teapot")]);
    let (log, captured) = frame(phong.as_mut());
    let (file, line) = line_of(&captured, "phong.vert", "v = vec3(modelview * vertex)");
    let view = view::draw_view(gpu(), &log, &probe(&file, line, None), WIDTH, HEIGHT).expect("the view");
    assert!(view.vertex, "a vertex-shader line");
    assert_eq!(view.components, 3);
    let pixels = spread(&view, 8, |i| view.ran[i]);
    assert!(pixels.len() >= 8);
    for (x, y) in pixels {
        let ins = Inspection::new("phong", &captured, x, y).expect("inspection");
        let f = ins.replayed.fragment.as_ref().expect("covered");
        // The vertex shader writes `v` to the varying of the same name: the view at the pixel
        // is that varying as the fragment shader receives it.
        let input = f.inputs.iter().find(|n| n.name == "v").expect("the input v");
        let got = view.values[view.at(x, y)];
        for c in 0..3 {
            assert!(
                close(got[c], input.value[c]),
                "phong pixel {x},{y}: vertex line v component {c}: view {got:?}, interpolated input {:?}",
                input.value
            );
        }
        // And each corner's traced value of the line is that corner's output `v`.
        let steps: Vec<_> = (ins.steps.iter())
            .filter(|s| s.stage == Stage::Vertex && s.file == file && s.line == line && s.name == "v")
            .collect();
        let mut ran: Vec<usize> = steps.iter().filter_map(|s| s.corner).collect();
        ran.sort_unstable();
        assert_eq!(
            ran,
            [0, 1, 2],
            "pixel {x},{y}: the line ran once at each of the three corners"
        );
        for step in steps {
            let k = step.corner.expect("a corner");
            let output = (f.corners[k].outputs.iter())
                .find(|n| n.name == "v")
                .expect("the output v");
            assert!(
                step.value.len() == 3
                    && (0..3).all(|c| (step.value[c] - output.value[c]).abs() <= 1e-5 * output.value[c].abs().max(1.0)),
                "pixel {x},{y} corner {k}: the line's v {:?}, the corner's output v {:?}",
                step.value,
                output.value
            );
        }
    }
}

#[test]
fn a_cost_view_counts_the_steps_the_debugger_counts() {
    let mut phong = lab("phong", &[("object", "teapot")]);
    costs_agree("phong", phong.as_mut(), 8);
    let mut bands = lab("uniform_arrays", &[]);
    costs_agree("uniform_arrays", bands.as_mut(), 8);
    let mut lab3 = legacy(3);
    costs_agree("legacy lab3", lab3.as_mut(), 6);
    // `discard`: where a fragment is discarded, the one behind it (or the clear) shows, with its
    // own cost, in the view as in the debugger.
    let holes = common_text("normal_rgb.frag").replace(
        "frag_color = vec4(normal, 1.0);",
        "if (fract(normal.x * 4.0) > 0.6) {\n        discard;\n    }\n    frag_color = vec4(normal, 1.0);",
    );
    let mut normal = edited("normal_rgb", &[("normal_rgb.frag", &holes)], &[("object", "torus")]);
    costs_agree("normal_rgb with discard", normal.as_mut(), 10);
    let mut noise = edited(
        "noise",
        &[("noise.frag", LOOPING_NOISE)],
        &[("object", "sphere"), ("time", "1.5")],
    );
    let seen = costs_agree("looping noise", noise.as_mut(), 12);
    let (lo, hi) = (
        seen.iter().filter(|&&c| c > 0).min().copied().unwrap_or(0),
        seen.iter().max().copied().unwrap_or(0),
    );
    assert!(hi > lo + 20, "the loop's cost differs from pixel to pixel: {lo}..{hi}");
}

#[test]
fn a_view_drawn_again_builds_nothing_and_draws_the_same() {
    let mut phong = lab("phong", &[("object", "teapot")]);
    let (log, captured) = frame(phong.as_mut());
    let (file, line) = line_of(&captured, "phong.frag", "max(dot(N, L), 0.0)");
    let mut drawer = ViewDrawer::new();
    let p = probe(&file, line, None);
    let a = drawer.draw(gpu(), &log, &p, WIDTH, HEIGHT).expect("first");
    let first = drawer.builds();
    // The teapot: a pipeline and an index buffer for its draw, and the targets, at least.
    assert!(first >= 3, "the first view built {first} things");
    let b = drawer.draw(gpu(), &log, &p, WIDTH, HEIGHT).expect("again");
    assert_eq!(drawer.builds(), first, "the view drawn again built something");
    assert_eq!(a.values, b.values);
    assert_eq!(a.cost, b.cost);
}

/// The error `probe` gets on `lab`'s frame.
fn refused(lab: &mut dyn Lab, probe: &Probe) -> ViewError {
    let (log, _) = frame(lab);
    match view::resolve(&log.draws(), probe) {
        Err(e) => e,
        Ok(r) => panic!("{probe:?} resolved to {r:?}"),
    }
}

#[test]
fn bad_probes_get_clear_messages() {
    let mut phong = lab("phong", &[("object", "teapot")]);
    let (_, captured) = frame(phong.as_mut());
    let (file, comment) = line_of(&captured, "phong.frag", "// The course's lines");
    let e = refused(phong.as_mut(), &probe(&file, comment, None));
    assert!(matches!(e, ViewError::Nothing { .. }), "{e}");
    let said = e.to_string();
    assert!(
        said.contains("assigns nothing") && said.contains("nearest line") && said.contains("13 (L)"),
        "{said}"
    );
    let e = refused(phong.as_mut(), &probe("nowhere.frag", 3, None));
    assert!(matches!(e, ViewError::NotDrawn { .. }), "{e}");
    assert!(e.to_string().contains("phong.frag"), "it lists the files drawn: {e}");
    let (_, l) = line_of(&captured, "phong.frag", "vec3 L = safe_normalize");
    let e = refused(phong.as_mut(), &probe(&file, l, Some("Q")));
    assert!(matches!(e, ViewError::NoSuchName { .. }), "{e}");
    assert!(e.to_string().contains("`L`"), "it lists the names assigned: {e}");
    // A file named by its name alone is the one file of that name.
    let p = probe("phong.frag", l, None);
    let (log, _) = frame(phong.as_mut());
    let r = view::resolve(&log.draws(), &p)
        .expect("phong.frag by its name")
        .expect("a line");
    assert_eq!(r.site.file, file);
    // A view of another size than the frame's.
    let (log, _) = frame(phong.as_mut());
    let e = view::draw_view(gpu(), &log, &Probe::Cost, WIDTH * 2, HEIGHT).expect_err("another size");
    assert!(e.to_string().contains("not at the view's 640x180"), "{e}");
    // A line past the end of the file.
    let e = refused(phong.as_mut(), &probe(&file, 9999, None));
    assert!(matches!(e, ViewError::PastEnd { .. }), "{e}");
    assert!(e.to_string().contains("lines"), "{e}");
}

/// An include used by both of phong's stages, with a line that assigns.
const SHARED: &str = "vec3 twice(vec3 x) {
    vec3 y = x * 2.0;
    return y * 0.5;
}
";

#[test]
fn a_line_of_an_include_both_stages_use_asks_for_the_stage() {
    let vert = common_text("phong.vert").replace(
        "#include \"transform.glsl\"",
        "#include \"transform.glsl\"\n#include \"shared.glsl\"",
    );
    let vert = vert
        .replace("N = normalize(", "N = twice(normalize(")
        .replace("vertex_normal);", "vertex_normal));");
    let frag = common_text("phong.frag").replace(
        "#include \"safe_math.glsl\"",
        "#include \"safe_math.glsl\"\n#include \"shared.glsl\"",
    );
    let frag = frag.replace("vec3 E = safe_normalize(-v);", "vec3 E = twice(safe_normalize(-v));");
    let mut phong = edited(
        "phong",
        &[("phong.vert", &vert), ("phong.frag", &frag), ("shared.glsl", SHARED)],
        &[("object", "sphere")],
    );
    let (log, captured) = frame(phong.as_mut());
    let (file, line) = line_of(&captured, "shared.glsl", "vec3 y = x * 2.0;");
    let e = view::resolve(&log.draws(), &probe(&file, line, None)).expect_err("both stages");
    assert!(matches!(e, ViewError::BothStages { .. }), "{e}");
    assert!(e.to_string().contains("choose the stage"), "{e}");
    for stage in [Stage::Vertex, Stage::Fragment] {
        let p = Probe::Line {
            file: file.clone(),
            line,
            name: None,
            stage: Some(stage),
        };
        let v = view::draw_view(gpu(), &log, &p, WIDTH, HEIGHT).expect("with the stage chosen");
        assert_eq!(v.vertex, stage == Stage::Vertex);
        assert!(v.ran.iter().any(|&r| r), "{stage:?}: the line ran");
    }
}

fn common_text(name: &str) -> String {
    shaderlab::shader::embedded_source(name)
        .expect("an embedded shader")
        .to_owned()
}

#[test]
fn a_probe_is_file_colon_line_or_cost() {
    assert_eq!("cost".parse::<Probe>(), Ok(Probe::Cost));
    assert_eq!("phong.frag:17".parse::<Probe>(), Ok(probe("phong.frag", 17, None)));
    assert_eq!(
        "C:/x/phong.frag:3".parse::<Probe>(),
        Ok(probe("C:/x/phong.frag", 3, None))
    );
    for bad in ["phong.frag", "phong.frag:0", "phong.frag:x", ":3", "phong.frag:-2", ""] {
        let e = bad.parse::<Probe>().expect_err(bad);
        assert!(matches!(e, ViewError::BadProbe { .. }), "{bad}: {e}");
        assert!(e.to_string().contains("expected FILE:LINE"), "{e}");
    }
}

/// Every lab at its defaults: the cost view equals the debugger's cost, the fragment shader's
/// last assignment in its own file shows the traced value, and the vertex shader's first one
/// shows a value between its three corners' (an interpolation is a weighted mean of them).
#[test]
fn every_lab_agrees_with_the_debugger() {
    let mut failures = Vec::new();
    let (mut labs, mut checked) = (0, [0usize; 2]);
    let mut all: Vec<(String, Box<dyn Lab>)> = Vec::new();
    for entry in shaderlab::course::ALL {
        let name = entry.info.name;
        if name == "legacy" {
            continue;
        }
        let set: &[(&str, &str)] = if name == "particles" { &[("time", "2")] } else { &[] };
        all.push((name.to_owned(), lab(name, set)));
    }
    // The course's five GLSL 1.10 pairs (seed 000; exercises 4 and 5 as mended to compile).
    for n in 1..=5 {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/course");
        let pick = |f: String| {
            if f == "lab4.frag" || f == "lab5.vert" {
                dir.join(format!("seed000-mended/{f}"))
            } else {
                dir.join(format!("seed000/{f}"))
            }
        };
        let files = UserFiles {
            inputs: vec![pick(format!("lab{n}.vert")), pick(format!("lab{n}.frag"))],
            ..UserFiles::default()
        };
        let set: &[(&str, &str)] = if n >= 4 {
            &[("object", "teapot"), ("shade", "1,0.8,0.5"), ("time", "1.7")]
        } else {
            &[("object", "teapot")]
        };
        all.push((
            format!("legacy lab{n}"),
            build("legacy", ShaderSource::Embedded, &files, set),
        ));
    }
    for (name, mut lab) in all {
        let name = name.as_str();
        costs_agree(name, lab.as_mut(), 4);
        labs += 1;
        let (log, captured) = frame(lab.as_mut());
        let Some(draw) = captured.draws.first() else { continue };
        let last = |shader: &shaderlab::shader::CompiledShader, first: bool| {
            let mine: Vec<_> = shaderlab::debug::instrument::assignments(shader)
                .into_iter()
                .filter(|a| a.file == shader.path && a.root != "(temporary)")
                .collect();
            if first {
                mine.first().cloned()
            } else {
                mine.last().cloned()
            }
        };
        for (stage, a) in [
            (Stage::Fragment, last(&draw.fragment, false)),
            (Stage::Vertex, last(&draw.vertex, true)),
        ] {
            let Some(a) = a else { continue };
            let p = Probe::Line {
                file: a.file.clone(),
                line: a.line,
                name: Some(a.name.clone()),
                stage: Some(stage),
            };
            let view = match view::draw_view(gpu(), &log, &p, WIDTH, HEIGHT) {
                Ok(v) => v,
                Err(e) => {
                    failures.push(format!("{name} {}:{} `{}`: {e}", a.file, a.line, a.name));
                    continue;
                }
            };
            for (x, y) in spread(&view, 3, |i| view.ran[i]) {
                let ins = Inspection::new(name, &captured, x, y).expect("inspection");
                let got = view.values[view.at(x, y)];
                let values = traced(&ins, stage, &a.file, a.line, &a.name);
                checked[usize::from(stage == Stage::Vertex)] += 1;
                let ok = match stage {
                    Stage::Fragment => values
                        .last()
                        .is_some_and(|v| (0..v.len().min(4)).all(|c| close(got[c], v[c]))),
                    Stage::Vertex => {
                        // The last value at each corner (one for a point): the trace lists
                        // corners in turn.
                        let n = ins.replayed.fragment.as_ref().map_or(3, |f| f.corners.len());
                        let corners: Vec<&Vec<f64>> = values.iter().rev().take(n).collect();
                        corners.len() == n
                            && (0..corners[0].len().min(4)).all(|c| {
                                let lo = corners.iter().map(|v| v[c]).fold(f64::INFINITY, f64::min);
                                let hi = corners.iter().map(|v| v[c]).fold(f64::NEG_INFINITY, f64::max);
                                let slack = 1e-3 * lo.abs().max(hi.abs()).max(1.0);
                                f64::from(got[c]) >= lo - slack && f64::from(got[c]) <= hi + slack
                            })
                    }
                };
                if !ok {
                    failures.push(format!(
                        "{name} pixel {x},{y} {stage:?} {}:{} `{}`: view {got:?}, trace {values:?}",
                        a.file, a.line, a.name
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    eprintln!(
        "{labs} labs; line views checked at {} fragment and {} vertex pixels",
        checked[0], checked[1]
    );
    assert!(
        checked[0] >= 2 * labs && checked[1] >= 2 * labs,
        "most labs' lines were checked: {checked:?} of {labs} labs"
    );
}

#[test]
fn a_line_assigning_two_variables_asks_for_one_and_shows_the_one_named() {
    let two = common_text("normal_rgb.frag").replace(
        "frag_color = vec4(normal, 1.0);",
        "vec3 a = normal; vec3 b = -normal;\n    frag_color = vec4(a + 0.25 * b, 1.0);",
    );
    let mut normal = edited("normal_rgb", &[("normal_rgb.frag", &two)], &[("object", "sphere")]);
    let (log, captured) = frame(normal.as_mut());
    let (file, line) = line_of(&captured, "normal_rgb.frag", "vec3 a = normal;");
    let e = view::resolve(&log.draws(), &probe(&file, line, None)).expect_err("two names");
    assert!(matches!(e, ViewError::Ambiguous { .. }), "{e}");
    assert!(e.to_string().contains("`a`, `b`"), "it lists both: {e}");
    let v = agrees(
        "normal_rgb a and b",
        normal.as_mut(),
        "normal_rgb.frag",
        "vec3 a = normal;",
        Some("b"),
        6,
    );
    let i = v.ran.iter().position(|&r| r).expect("a pixel ran");
    let a = agrees(
        "normal_rgb a and b",
        normal.as_mut(),
        "normal_rgb.frag",
        "vec3 a = normal;",
        Some("a"),
        6,
    );
    assert_eq!(v.values[i][0], -a.values[i][0], "b is -a");
}

/// The lecture's side-by-side (`compare=1`) draws each program in its own viewport: the cost
/// view counts the debugger's steps, a line of the right-hand program's fragment shader runs
/// in the right half only, and the replay stores the GPU's pixel in both halves, each from the
/// draw of its own viewport.
#[test]
fn draws_in_their_own_viewports_are_viewed_and_replayed_there() {
    let mut both = lab("phong_fragment", &[("compare", "1")]);
    costs_agree("phong_fragment compare=1", both.as_mut(), 10);
    let (log, captured) = frame(both.as_mut());
    let (file, line) = line_of(&captured, "phong_fragment.frag", "vec4 diffuse");
    let view = view::draw_view(gpu(), &log, &probe(&file, line, None), WIDTH, HEIGHT).expect("the view");
    let half = WIDTH / 2;
    let (mut right, mut left_drawn) = (0, 0);
    for i in 0..view.values.len() {
        let x = i as u32 % WIDTH;
        if view.ran[i] {
            assert!(
                x >= half,
                "{file}:{line} ran at column {x}, in the left program's viewport"
            );
            right += 1;
        } else if x < half && view.cost[i] > 0 {
            left_drawn += 1;
        }
    }
    assert!(
        right > 1000 && left_drawn > 1000,
        "ran at {right} pixels; the left half drew {left_drawn}"
    );
    agrees(
        "phong_fragment compare=1",
        both.as_mut(),
        "phong_fragment.frag",
        "vec4 diffuse",
        None,
        8,
    );
    let (_, captured) = shaderlab::debug::capture_lab(gpu(), both.as_mut(), WIDTH, HEIGHT, true).expect("a capture");
    for (x, y) in spread(&view, 12, |i| view.cost[i] > 0) {
        let ins = Inspection::new("phong_fragment", &captured, x, y).expect("an inspection");
        assert_eq!(ins.disagreement(), None, "pixel {x},{y}");
        let draw = ins.replayed.fragment.as_ref().map(|f| f.draw);
        assert_eq!(
            draw,
            Some(usize::from(x >= half)),
            "pixel {x},{y}: the draw of its viewport"
        );
    }
}

/// A fragment shader that assigns parts of values: components of a vector (`c.xy`, `c.yx`),
/// array elements (`arr[i]`, `arr[1]`), a component in a switch's case (`c.z`), a matrix.
const PARTS: &str = "#version 450
layout(location = 0) in vec3 normal;
layout(location = 0) out vec4 frag_color;

void main() {
    vec4 c = vec4(0.0, 0.0, 0.0, 1.0);
    c.xy = normal.xy;
    float arr[3];
    int i = int(gl_FragCoord.x) % 3;
    arr[i] = normal.z;
    arr[1] = normal.x;
    mat3 m = mat3(normal, normal.yzx, normal.zxy);
    switch (i) {
        case 0: c.z = arr[0]; break;
        default: c.z = m[1].x; break;
    }
    c.yx = vec2(c.x, c.y) * 0.5;
    frag_color = c;
}
";

/// A line that assigns part of a value shows what it assigns, named as written: the
/// components of `c.xy = …` (2, in the order written, `c.yx` too), `arr[i]` and `arr[1]`, a
/// switch's `c.z`; a matrix is offered as its columns (`m[0]`…), each one a vector. The
/// values are the debugger's at the pixels where the line ran.
#[test]
fn a_line_assigning_part_of_a_value_shows_what_it_assigns_named_as_written() {
    let mut lab = edited("normal_rgb", &[("normal_rgb.frag", PARTS)], &[("object", "sphere")]);
    let (log, captured) = frame(lab.as_mut());
    let at = |needle: &str| line_of(&captured, "normal_rgb.frag", needle);
    let (file, m_line) = at("mat3 m =");
    let e = view::resolve(&log.draws(), &probe(&file, m_line, None)).expect_err("a matrix's columns");
    assert!(
        matches!(&e, ViewError::Ambiguous { choices, .. } if choices == &["m[0]", "m[1]", "m[2]"]),
        "{e}"
    );
    // (needle, name given, the view's name, the trace's names of its components in order)
    let cases: [(&str, Option<&str>, &str, &[&str]); 8] = [
        ("c.xy = normal.xy;", None, "c.xy", &["c.x", "c.y"]),
        ("c.xy = normal.xy;", Some("c"), "c.xy", &["c.x", "c.y"]),
        ("c.yx = vec2", None, "c.yx", &["c.y", "c.x"]),
        ("arr[i] = normal.z;", None, "arr[i]", &[]),
        ("arr[1] = normal.x;", None, "arr[1]", &["arr[1]"]),
        ("case 0: c.z", None, "c.z", &["c.z"]),
        ("default: c.z", None, "c.z", &["c.z"]),
        ("mat3 m =", Some("m[1]"), "m[1]", &["m"]),
    ];
    for (needle, given, name, parts) in cases {
        let (file, line) = at(needle);
        let view = view::draw_view(gpu(), &log, &probe(&file, line, given), WIDTH, HEIGHT)
            .unwrap_or_else(|e| panic!("{needle}: {e}"));
        let resolved = view.resolved.clone().expect("a line view");
        assert_eq!(resolved.site.name.as_deref(), Some(name), "{needle}");
        let want = match name {
            "c.xy" | "c.yx" => 2,
            "m[1]" => 3,
            _ => 1,
        };
        assert_eq!((resolved.components, view.components), (want, want), "{needle}");
        let ran = spread(&view, 6, |i| view.ran[i]);
        assert!(ran.len() >= 4, "{needle}: ran at {} pixels", ran.len());
        for (x, y) in ran {
            let ins = Inspection::new("normal_rgb", &captured, x, y).expect("an inspection");
            let got = view.values[view.at(x, y)];
            let expected: Vec<f64> = match (name, parts) {
                // The element the pixel's own index picks (the trace names it `arr[i]`, or by
                // its value where the quad's pixels agree on it).
                ("arr[i]", _) => traced(&ins, Stage::Fragment, &file, line, "arr")
                    .last()
                    .cloned()
                    .unwrap_or_else(|| panic!("{x},{y}: arr[…] traced")),
                // Column 1 of the matrix: its components 3..6.
                ("m[1]", _) => {
                    let m = traced(&ins, Stage::Fragment, &file, line, "m");
                    m.last().expect("m traced")[3..6].to_vec()
                }
                _ => parts
                    .iter()
                    .map(|p| {
                        let steps: Vec<_> = ins
                            .steps
                            .iter()
                            .filter(|s| s.file == file && s.line == line && s.name == *p)
                            .collect();
                        steps
                            .last()
                            .unwrap_or_else(|| panic!("{needle} {x},{y}: {p} traced"))
                            .value[0]
                    })
                    .collect(),
            };
            assert_eq!(expected.len() as u32, want, "{needle} {x},{y}");
            for (k, e) in expected.iter().enumerate() {
                assert!(
                    close(got[k], *e),
                    "{needle} pixel {x},{y}: `{name}` component {k}: view {:?}, debugger {expected:?}",
                    got
                );
            }
        }
    }
    let e = view::resolve(&log.draws(), &probe(&file, m_line, Some("m[3]"))).expect_err("no such column");
    assert!(matches!(e, ViewError::NoSuchName { .. }), "{e}");
}
