//! A course's own GLSL 1.10 shaders through `legacy`: seed 000's ten files (lab 4 and 5 with the
//! one-parenthesis mend they need) against the original's reference images, every object; the
//! GLSL 1.10 shaders of SPEC §1.6-1.8 and §2.1, 2.3 against SPEC's references; the command
//! line (files, `--texture NAME=FILE`, usage errors) and live reload.

mod common;

use std::path::{Path, PathBuf};

use common::gpu;
use image::RgbImage;
use shaderlab::lab::{BuildContext, Lab, UserFiles};
use shaderlab::metrics::psnr;
use shaderlab::offscreen::{to_rgb, COLOR_FORMAT};
use shaderlab::shader::ShaderSource;

const OBJECTS: [&str; 4] = ["cube", "sphere", "torus", "teapot"];

fn fixture(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/course").join(path)
}

/// Seed 000's files: the course's, with lab 4 and 5 mended where the course prints an extra `)`.
fn course(lab: u32) -> Vec<PathBuf> {
    let pick = |name: String| {
        if name == "lab4.frag" || name == "lab5.vert" {
            fixture(&format!("seed000-mended/{name}"))
        } else {
            fixture(&format!("seed000/{name}"))
        }
    };
    vec![pick(format!("lab{lab}.vert")), pick(format!("lab{lab}.frag"))]
}

/// The legacy lab on `files`, with `--set`-style assignments applied.
fn legacy(files: Vec<PathBuf>, set: &[(&str, &str)]) -> Box<dyn Lab> {
    legacy_with(
        UserFiles {
            inputs: files,
            ..UserFiles::default()
        },
        set,
    )
}

fn legacy_with(files: UserFiles, set: &[(&str, &str)]) -> Box<dyn Lab> {
    let source = ShaderSource::Embedded;
    let cx = BuildContext::new(gpu(), &source, COLOR_FORMAT, &files);
    let mut lab = (shaderlab::course::LEGACY.new)(&cx).unwrap_or_else(|e| panic!("legacy builds: {e}"));
    for (k, v) in set {
        lab.params_mut()
            .set_str(k, v)
            .unwrap_or_else(|e| panic!("--set {k}={v}: {e}"));
    }
    lab
}

fn render(lab: &mut dyn Lab, w: u32, h: u32) -> RgbImage {
    to_rgb(&shaderlab::shell::screenshot(gpu(), lab, w, h).expect("screenshot"))
}

fn reference(path: &Path) -> RgbImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgb8()
}

/// A reference image kept in the repository (`tests/reference/`, copied from the original
/// programs' renders): the tests read nothing outside the repository.
fn in_tests(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests").join(rel)
}

/// labref.c's uniforms and state per exercise (lab 3: camera (0,0,5), clear (0.05,0.1,0.2)).
fn labref_state(lab: u32) -> Vec<(&'static str, &'static str)> {
    shaderlab::course::legacy::course_state(lab).to_vec()
}

#[test]
fn seed000_course_shaders_render_the_originals_images() {
    let mut worst = f64::INFINITY;
    for lab in 1..=5 {
        let mut state = labref_state(lab);
        let mut app = legacy(course(lab), &state);
        for object in OBJECTS {
            state.push(("object", object));
            app.params_mut().set_str("object", object).unwrap();
            let image = render(app.as_mut(), 640, 360);
            let path = in_tests(&format!("reference/lab{lab}_{object}_x0_y0_t0.png"));
            let db = psnr(&image, &reference(&path)).expect("same size");
            println!("lab{lab} {object}: {db:.1} dB");
            if db < 40.0 {
                image.save(format!("/tmp/legacy_lab{lab}_{object}.png")).ok();
            }
            assert!(db >= 40.0, "lab{lab} {object}: {db:.1} dB (image in /tmp)");
            worst = worst.min(db);
        }
    }
    println!("worst {worst:.1} dB");
}

/// SPEC §1's frame and GL light and material for seed 001's built-in-state shaders.
const SEED001: &[(&str, &str)] = &[
    ("object", "teapot"),
    ("near", "0.1"),
    ("gl_LightSource[0].position", "2,2,2,1"),
    ("gl_LightSource[0].ambient", "0.2,0.2,0.2,1"),
    ("gl_LightSource[0].diffuse", "1,1,1,1"),
    ("gl_LightSource[0].specular", "1,1,1,1"),
    ("gl_FrontMaterial.ambient", "0.2,0.3,0.8,1"),
    ("gl_FrontMaterial.diffuse", "0.2,0.3,0.8,1"),
    ("gl_FrontMaterial.specular", "1,1,1,1"),
    ("gl_FrontMaterial.shininess", "40"),
];

fn seed_reference(name: &str) -> RgbImage {
    reference(&in_tests(&format!("reference/seeds/{name}.png")))
}

#[test]
fn seed001_builtin_state_shaders_render_specs_references() {
    for (name, vert, frag) in [
        ("phong_vertex", "seed001/phong_vertex.vert", "seed001/pass.frag"),
        (
            "phong_fragment",
            "seed001/phong_fragment.vert",
            "seed001/phong_fragment.frag",
        ),
        ("toon", "seed001/toon.vert", "seed001/pass.frag"),
        // The teapot's texture coordinates and the default picture (SPEC's uvgrid, REPEAT,
        // LINEAR, no mipmaps: what §1.9 pins).
        ("texture", "seed001/texture.vert", "seed001/texture.frag"),
    ] {
        let mut app = legacy(vec![fixture(vert), fixture(frag)], &[]);
        // The toon shader reads no material: only the parameters its shaders declare.
        for (k, v) in SEED001 {
            if app.params().has(k) {
                app.params_mut().set_str(k, v).unwrap();
            }
        }
        let image = render(app.as_mut(), 512, 512);
        let db = psnr(&image, &seed_reference(&format!("001_{name}_default"))).expect("same size");
        println!("001 {name}: {db:.1} dB");
        if db < 40.0 {
            image.save(format!("/tmp/legacy_001_{name}.png")).ok();
        }
        assert!(db >= 40.0, "001 {name}: {db:.1} dB");
    }
}

#[test]
fn seed002_shaders_render_specs_references() {
    let cases: [(&str, &[(&str, &str)]); 2] = [
        (
            "twist",
            &[("object", "grid"), ("twisting", "4.25"), ("color", "0.5,9,0.5")],
        ),
        (
            "normal_world",
            &[
                ("object", "teapot"),
                ("fovy", "60"),
                ("near", "0.1"),
                ("camera", "0,0,5"),
            ],
        ),
    ];
    for (name, set) in cases {
        let files = vec![
            fixture(&format!("seed002/{name}.vert")),
            fixture(&format!("seed002/{name}.frag")),
        ];
        let mut app = legacy(files, set);
        let image = render(app.as_mut(), 512, 512);
        let db = psnr(&image, &seed_reference(&format!("002_{name}_default"))).expect("same size");
        println!("002 {name}: {db:.1} dB");
        if db < 40.0 {
            image.save(format!("/tmp/legacy_002_{name}.png")).ok();
        }
        assert!(db >= 40.0, "002 {name}: {db:.1} dB");
    }
}

fn run(args: &[&str]) -> (i32, String, String) {
    let out = std::process::Command::new(common::example("legacy"))
        .args(args)
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("run legacy");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("shaderlab-legacy-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn command_line_runs_a_course_pair_with_its_uniforms() {
    let dir = scratch("cli");
    let png = dir.join("lab3.png");
    let [vert, frag] = [&course(3)[0], &course(3)[1]].map(|p| p.display().to_string());
    let mut args: Vec<String> = vec![vert.clone(), frag.clone()];
    for (k, v) in labref_state(3) {
        match k {
            "camera" => args.extend(["--camera".into(), v.into()]),
            "clear" => args.extend(["--clear".into(), v.into()]),
            _ => args.extend(["--set".into(), format!("{k}={v}")]),
        }
    }
    args.extend([
        "--object".into(),
        "torus".into(),
        "--screenshot".into(),
        png.display().to_string(),
    ]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (code, out, err) = run(&args);
    assert_eq!(code, 0, "{out}{err}");
    let image = image::open(&png).unwrap().to_rgb8();
    let db = psnr(&image, &reference(&in_tests("reference/lab3_torus_x0_y0_t0.png"))).unwrap();
    assert!(db >= 40.0, "{db:.1} dB");

    // --help lists the shaders' uniforms by name.
    let (code, out, _) = run(&[&vert, &frag, "--help"]);
    assert_eq!(code, 0);
    for name in ["lightPosition", "shininess", "camera", "clear", "uniform vec3"] {
        assert!(out.contains(name), "--help lists {name}:\n{out}");
    }
    // An unknown name is a usage error that lists the valid ones.
    let (code, _, err) = run(&[&vert, &frag, "--set", "lightPos=1,2,3", "--screenshot", "x.png"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("unknown parameter `lightPos`") && err.contains("lightPosition"),
        "{err}"
    );
    // One file, or three, is a usage error.
    let (code, _, err) = run(&[&vert, "--screenshot", "x.png"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("VERT FRAG"), "{err}");
    // The course's own lab 4 has an extra `)`: the error points at the user's file.
    let lab4 = fixture("seed000/lab4.frag").display().to_string();
    let lab4v = fixture("seed000/lab4.vert").display().to_string();
    let (code, _, err) = run(&[&lab4v, &lab4, "--screenshot", "x.png"]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("seed000/lab4.frag:34:46: unexpected `)`"), "{err}");
    assert!(
        err.contains("34 |         + i.x + vec4(0.0, i1.x, i2.x, 1.0 ) ));"),
        "{err}"
    );
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn labs_that_take_no_files_reject_them() {
    let out = std::process::Command::new(common::example("noise"))
        .args(["a.vert", "a.frag", "--screenshot", "x.png"])
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("unexpected argument `a.vert`: this lab takes no files"),
        "{err}"
    );
}

const TEXTURE_VS: &str = "varying vec2 uv;\nvoid main() { uv = gl_MultiTexCoord0.st; gl_Position = ftransform(); }\n";
const TEXTURE_FS: &str =
    "uniform sampler2D picture;\nvarying vec2 uv;\nvoid main() { gl_FragColor = texture2D(picture, vec2(0.45, 0.45)); }\n";

#[test]
fn textures_come_from_named_files_or_the_default_picture() {
    let dir = scratch("texture");
    let (vert, frag) = (dir.join("t.vert"), dir.join("t.frag"));
    std::fs::write(&vert, TEXTURE_VS).unwrap();
    std::fs::write(&frag, TEXTURE_FS).unwrap();
    let png = dir.join("orange.png");
    image::RgbImage::from_pixel(4, 4, image::Rgb([255, 128, 0]))
        .save(&png)
        .unwrap();
    let centre = |image: &RgbImage| *image.get_pixel(320, 180);
    // Default: SPEC's uvgrid, whose centre is the dark disc.
    let mut lab = legacy(vec![vert.clone(), frag.clone()], &[("object", "cube")]);
    assert_eq!(centre(&render(lab.as_mut(), 640, 360)).0, [16, 16, 16]);
    // --texture picture=orange.png
    let mut files = UserFiles {
        inputs: vec![vert.clone(), frag.clone()],
        ..UserFiles::default()
    };
    files.load_named_textures(&[("picture".into(), png.clone())]).unwrap();
    let mut lab = legacy_with(files, &[("object", "cube")]);
    assert_eq!(centre(&render(lab.as_mut(), 640, 360)).0, [255, 128, 0]);
    // On the command line, and a name the shaders do not have.
    let out = dir.join("out.png");
    let (v, f, p, o) = (
        vert.display().to_string(),
        frag.display().to_string(),
        png.display().to_string(),
        out.display().to_string(),
    );
    let (code, _, err) = run(&[&v, &f, "--texture", &format!("picture={p}"), "--screenshot", &o]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        image::open(&out).unwrap().to_rgb8().get_pixel(320, 180).0,
        [255, 128, 0]
    );
    let (code, _, err) = run(&[&v, &f, "--texture", &format!("pic={p}"), "--screenshot", &o]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("no sampler `pic` (they have: picture)"), "{err}");
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn live_reload_keeps_the_last_good_pipeline_and_values() {
    let dir = scratch("reload");
    let (vert, frag) = (dir.join("r.vert"), dir.join("r.frag"));
    std::fs::write(&vert, "void main() { gl_Position = ftransform(); }\n").unwrap();
    std::fs::write(
        &frag,
        "uniform vec3 tint;\nvoid main() { gl_FragColor = vec4(tint, 1.0); }\n",
    )
    .unwrap();
    let mut lab = legacy(
        vec![vert.clone(), frag.clone()],
        &[("object", "sphere"), ("tint", "1,0,0")],
    );
    assert_eq!(render(lab.as_mut(), 640, 360).get_pixel(320, 180).0, [255, 0, 0]);
    let source = ShaderSource::Embedded;
    let files = UserFiles {
        inputs: vec![vert.clone(), frag.clone()],
        ..UserFiles::default()
    };
    let cx = BuildContext::new(gpu(), &source, COLOR_FORMAT, &files);
    // An edit that adds a uniform: `tint` keeps its value, `gain` appears with GL's 0.
    std::fs::write(
        &frag,
        "uniform vec3 tint;\nuniform float gain;\nvoid main() { gl_FragColor = vec4(tint * (1.0 - gain), 1.0); }\n",
    )
    .unwrap();
    lab.reload(&cx).expect("reload");
    assert!(lab.params().has("gain"));
    assert_eq!(render(lab.as_mut(), 640, 360).get_pixel(320, 180).0, [255, 0, 0]);
    lab.params_mut().set_str("gain", "0.5").unwrap();
    assert_eq!(render(lab.as_mut(), 640, 360).get_pixel(320, 180).0, [128, 0, 0]);
    // A broken edit: the error names the file and line; the last good pipeline still draws.
    std::fs::write(
        &frag,
        "uniform vec3 tint;\nvoid main() {\n  gl_FragColor = vec4(tint, 1.0) * undefined_thing;\n}\n",
    )
    .unwrap();
    let e = lab.reload(&cx).unwrap_err().to_string();
    assert!(e.contains("r.frag:3:") && e.contains("undefined_thing"), "{e}");
    assert_eq!(render(lab.as_mut(), 640, 360).get_pixel(320, 180).0, [128, 0, 0]);
    // Issue 17: hostile saves (a 10,000-term sum overflowed the stack and killed the window,
    // doubling macros froze it) are errors too, and the last good pipeline still draws.
    let macros: String = (0..40).map(|i| format!("#define A{} (A{i}+A{i})\n", i + 1)).collect();
    for (text, phrase) in [
        (
            format!(
                "void main() {{\n  gl_FragColor = vec4({});\n}}\n",
                vec!["0.1"; 10_000].join(" + ")
            ),
            "r.frag:2:",
        ),
        (
            format!("#define A0 1.0\n{macros}void main() {{ gl_FragColor = vec4(A40); }}\n"),
            "r.frag:42:",
        ),
    ] {
        std::fs::write(&frag, text).unwrap();
        let e = lab.reload(&cx).unwrap_err().to_string();
        assert!(e.contains(phrase), "{e}");
        assert_eq!(render(lab.as_mut(), 640, 360).get_pixel(320, 180).0, [128, 0, 0]);
    }
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn time_runs_when_the_shaders_declare_it() {
    let lab = legacy(course(4), &[]);
    assert!(lab.animated(), "lab 4 declares uniform float time");
    let lab = legacy(course(3), &[]);
    assert!(!lab.animated());
    // Without files: the built-in GLSL 1.10 pair, lit by GL's light 0.
    let mut lab = legacy(Vec::new(), &[("object", "sphere")]);
    let image = render(lab.as_mut(), 640, 360);
    assert!(image.get_pixel(320, 180).0[0] > 100, "{:?}", image.get_pixel(320, 180));
    assert!(lab.params().has("gl_LightSource[0].position"));
}

/// The hand port at `state`, and `legacy` on the same GLSL 1.10 files at the equivalent state.
fn versus_hand_port(
    entry: &shaderlab::LabEntry,
    files: [&str; 2],
    port_state: &[(&str, &str)],
    legacy_state: &[(&str, &str)],
) -> f64 {
    let mut port = common::lab(entry);
    for (k, v) in port_state {
        port.lab
            .params_mut()
            .set_str(k, v)
            .unwrap_or_else(|e| panic!("{}: {k}={v}: {e}", entry.info.name));
    }
    let expected = port.rgb(512, 512);
    let mut app = legacy(vec![fixture(files[0]), fixture(files[1])], &[]);
    for (k, v) in legacy_state {
        if app.params().has(k) {
            app.params_mut().set_str(k, v).unwrap();
        }
    }
    let image = render(app.as_mut(), 512, 512);
    psnr(&image, &expected).expect("same size")
}

/// A named state: the hand port's assignments and legacy's extra ones.
type State = (
    &'static str,
    &'static [(&'static str, &'static str)],
    Vec<(&'static str, &'static str)>,
);

#[test]
fn builtin_state_shaders_match_their_hand_ports() {
    use shaderlab::course;
    let mut worst = f64::INFINITY;
    let light = |x: &'static str| -> (&'static str, &'static str) { ("gl_LightSource[0].position", x) };
    let states: [State; 4] = [
        ("default", &[], vec![]),
        (
            "rotated",
            &[("xangle", "30"), ("yangle", "45")],
            vec![("xangle", "30"), ("yangle", "45")],
        ),
        ("sphere", &[("object", "sphere")], vec![("object", "sphere")]),
        (
            "shiny",
            &[("shininess", "120"), ("lx", "-2")],
            vec![("gl_FrontMaterial.shininess", "120"), light("-2,2,2,1")],
        ),
    ];
    for (entry, files) in [
        (course::PHONG_VERTEX, ["seed001/phong_vertex.vert", "seed001/pass.frag"]),
        (
            course::PHONG_FRAGMENT,
            ["seed001/phong_fragment.vert", "seed001/phong_fragment.frag"],
        ),
        (course::TOON, ["seed001/toon.vert", "seed001/pass.frag"]),
    ] {
        for (state, port, extra) in &states {
            if entry.info.name == "toon" && *state == "shiny" {
                continue;
            }
            let mut set: Vec<(&str, &str)> = SEED001.to_vec();
            set.extend(extra.iter().copied());
            let db = versus_hand_port(entry, files, port, &set);
            println!("{} {state}: {db:.1} dB against the hand port", entry.info.name);
            assert!(db >= 60.0, "{} {state}: {db:.1} dB", entry.info.name);
            worst = worst.min(db);
        }
    }
    for (state, twisting) in [("default", "4.25"), ("none", "0"), ("neg", "-2"), ("strong", "8")] {
        let db = versus_hand_port(
            course::TWIST,
            ["seed002/twist.vert", "seed002/twist.frag"],
            &[("twisting", twisting)],
            &[("object", "grid"), ("twisting", twisting), ("color", "0.5,9,0.5")],
        );
        println!("twist {state}: {db:.1} dB against the hand port");
        assert!(db >= 60.0, "twist {state}: {db:.1} dB");
        worst = worst.min(db);
    }
    // normal_world turns Rz·Ry·Rx, the legacy geometry Rx·Ry·Rz: states about one axis.
    for (state, port, angles) in [("default", vec![], "0,0,0"), ("below", vec![("rx", "-70")], "-70,0,0")] {
        let [x, y, z]: [&str; 3] = angles.split(',').collect::<Vec<_>>().try_into().unwrap();
        let db = versus_hand_port(
            course::NORMAL_WORLD,
            ["seed002/normal_world.vert", "seed002/normal_world.frag"],
            &port,
            &[
                ("object", "teapot"),
                ("fovy", "60"),
                ("near", "0.1"),
                ("camera", "0,0,5"),
                ("xangle", x),
                ("yangle", y),
                ("zangle", z),
            ],
        );
        println!("normal_world {state}: {db:.1} dB against the hand port");
        assert!(db >= 60.0, "normal_world {state}: {db:.1} dB");
        worst = worst.min(db);
    }
    println!("worst {worst:.1} dB");
}

#[test]
fn seed001_envmap_samples_the_default_cube_faces() {
    // §1.10 state `sphere`: the model matrix is the identity, the eye (0,0,4); the cube map is
    // SPEC's six faces (the default picture of a samplerCube).
    let mut app = legacy(
        vec![fixture("seed001/envmap.vert"), fixture("seed001/envmap.frag")],
        &[
            ("object", "sphere"),
            ("near", "0.1"),
            ("modelMatrix", "1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1"),
            ("eyeWorld", "0,0,4"),
        ],
    );
    let image = render(app.as_mut(), 512, 512);
    let db = psnr(&image, &seed_reference("001_envmap_sphere")).expect("same size");
    println!("001 envmap sphere: {db:.1} dB");
    if db < 40.0 {
        image.save("/tmp/legacy_001_envmap.png").ok();
    }
    assert!(db >= 40.0, "001 envmap: {db:.1} dB");
}

#[test]
fn seed002_double_vision_translates_its_sampler_named_texture() {
    // §2.2 names its sampler `texture`, a built-in function from GLSL 1.30 on (SPEC §6.2 #3):
    // the translation renames it, `--texture texture=FILE` still names it as the user does.
    let t = shaderlab::legacy::Translation::from_files(
        &fixture("seed002/double_vision.vert"),
        &fixture("seed002/double_vision.frag"),
    )
    .expect("translates");
    let (_, fs) = t.compile().expect("naga accepts it");
    assert_eq!(t.samplers[0].name, "texture");
    assert_eq!(t.samplers[0].glsl, "sl_texture");
    assert!(t
        .fragment
        .output
        .text
        .contains("texture(sampler2D(sl_texture, sl_texture_sampler), left_tex_coord)"));
    assert!(fs.to_wgsl().expect("WGSL").contains("sl_texture"));
    let names: Vec<&str> = t.params(&|_| false).iter().map(|p| p.name).collect();
    assert_eq!(names, ["left_separation", "right_separation"]);
}

#[test]
fn command_line_refuses_what_gl_refuses_and_says_what_it_draws() {
    let dir = scratch("refusals");
    let vert = dir.join("a.vert");
    let frag = dir.join("a.frag");
    std::fs::write(
        &vert,
        "void main() { gl_Position = ftransform(); gl_FrontColor = gl_LightSource[0].diffuse; }\n",
    )
    .unwrap();
    std::fs::write(&frag, "void main() { gl_FragColor = gl_Color; }\n").unwrap();
    let (vert, frag) = (vert.display().to_string(), frag.display().to_string());
    let png = dir.join("x.png").display().to_string();
    // near >= far, and a cutoff GL refuses (0..90 or 180), are usage errors before any GPU work.
    let (code, _, err) = run(&[
        &vert,
        &frag,
        "--set",
        "near=200",
        "--set",
        "far=100",
        "--screenshot",
        &png,
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("`near` (200) must be less than `far` (100)"), "{err}");
    let (code, _, err) = run(&[
        &vert,
        &frag,
        "--set",
        "gl_LightSource[0].spotCutoff=90.5",
        "--screenshot",
        &png,
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("90.5 is outside 0..90 or 180"), "{err}");
    // The documented lower bound of `near` is taken (an f32 parse put it below the bound).
    let (code, _, err) = run(&[
        &vert,
        &frag,
        "--set",
        "near=0.0001",
        "--set",
        "gl_LightSource[0].spotCutoff=180",
        "--screenshot",
        &png,
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("no VERT FRAG"), "{err}");
    // One array past the block is refused by name while it is read (before its default is
    // allocated); arrays that only add up past the device's limit are named together before a
    // pipeline is made.
    let big = dir.join("big.frag");
    std::fs::write(
        &big,
        "uniform float a[100000];\nvoid main() { gl_FragColor = vec4(a[3]); }\n",
    )
    .unwrap();
    let (code, _, err) = run(&[&vert, &big.display().to_string(), "--screenshot", &png]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("big.frag:1:15: uniform `a` (float[100000]) takes 1600000 bytes"),
        "{err}"
    );
    let sum = dir.join("sum.frag");
    std::fs::write(
        &sum,
        "uniform float a[1000];\nuniform float b[100];\nvoid main() { gl_FragColor = vec4(a[3] + b[2]); }\n",
    )
    .unwrap();
    let (code, _, err) = run(&[&vert, &sum.display().to_string(), "--screenshot", &png]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("sum.frag:1:15: the uniforms need 17600 bytes"), "{err}");
    assert!(
        !err.contains("bind_group") && !err.contains("Validation Error"),
        "{err}"
    );
    // --help abbreviates the 1000 zeros of an array's default.
    let (code, out, _) = run(&[&vert, &sum.display().to_string(), "--help"]);
    assert_eq!(code, 0);
    assert!(
        out.contains("(1000 numbers)") && out.len() < 20_000,
        "{} bytes",
        out.len()
    );
    // A uniform named like a lab parameter is `uniform.NAME`, settable, and stderr says so.
    let near = dir.join("near.frag");
    std::fs::write(
        &near,
        "uniform float near;\nvoid main() { gl_FragColor = vec4(near); }\n",
    )
    .unwrap();
    let near = near.display().to_string();
    let (code, out, _) = run(&[&vert, &near, "--help"]);
    assert_eq!(code, 0);
    assert!(
        out.contains("uniform.near") && out.contains("`near` is the lab's own parameter"),
        "{out}"
    );
    let (code, _, err) = run(&[&vert, &near, "--set", "uniform.near=0.5", "--screenshot", &png]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("the shaders' uniform `near` is the parameter `uniform.near`"),
        "{err}"
    );
    // Without files the built-in pair is drawn, and stderr says so.
    let (code, _, err) = run(&["--screenshot", &png]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("no VERT FRAG given: drawing the built-in GLSL 1.10 pair"),
        "{err}"
    );
    std::fs::remove_dir_all(dir).ok();
}
