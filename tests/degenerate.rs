//! Where methods fail, lectures 001–004 (seed 000's are in `tests/failures.rs`, twist's
//! `twisting` at ±1e4 in `tests/seed002.rs`): the degenerate inputs of each lecture, drawn
//! into a float target (`Rgba32Float`) so that a NaN or an infinity would be seen before the
//! 8-bit framebuffer clamps it. Each case asserts finite output within the range the lab's
//! framebuffer holds, and a picture that still shows something; beside it, what the original
//! does there and what the port chose.

mod common;

use common::lab_with;
use shaderlab::course;
use shaderlab::images::Image;
use shaderlab::lab::{BuildContext, LabEntry, UserFile, UserFiles};
use shaderlab::mesh::obj::parse_obj;
use shaderlab::shader::ShaderSource;

const FLOAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// How a float picture came out.
#[derive(Debug)]
struct Outcome {
    non_finite: usize,
    /// The largest and smallest channel value.
    max: f32,
    min: f32,
    /// Pixels that differ from the top-left pixel (the background, in every lab here).
    drawn: usize,
}

fn outcome(pixels: &[[f32; 4]]) -> Outcome {
    let background = pixels.first().copied().unwrap_or_default();
    let channels = pixels.iter().flat_map(|p| p[..3].iter().copied());
    Outcome {
        non_finite: pixels.iter().filter(|p| p.iter().any(|c| !c.is_finite())).count(),
        max: channels.clone().fold(f32::MIN, f32::max),
        min: channels.fold(f32::MAX, f32::min),
        drawn: pixels.iter().filter(|p| **p != background).count(),
    }
}

/// `entry` at `state` in a float target of its own size (a smaller one for speed).
fn float_render(entry: &LabEntry, state: &[(&str, &str)]) -> Outcome {
    let mut lab = lab_with(entry, &ShaderSource::Embedded, FLOAT);
    common::set_state(lab.lab.as_mut(), state);
    let (w, h) = entry.info.size;
    outcome(&lab.render_f32(w / 2, h / 2).expect("render"))
}

/// The largest channel a lab may write: seed 001's GL lighting adds emission, ambient,
/// diffuse and specular terms of at most 1 each (the course's shaders do not clamp: GL clamps
/// in the fixed-point framebuffer, and so does the port's UNORM one; a float target shows the
/// sum).
const BOUND: f32 = 4.0;

/// Finite, within [0, BOUND], and something drawn.
fn assert_sane(what: &str, o: &Outcome) {
    assert_finite(what, o);
    assert!(o.drawn > 0, "{what}: nothing drawn");
}

/// Finite and within [0, BOUND] (a case where nothing need be drawn).
fn assert_finite(what: &str, o: &Outcome) {
    println!("{what}: {o:?}");
    assert_eq!(o.non_finite, 0, "{what}: NaN or infinity reached the picture");
    assert!(
        o.min >= -1e-6 && o.max <= BOUND,
        "{what}: channels {}..{}",
        o.min,
        o.max
    );
}

/// `time` at 1e6 and 1e9 s in the animated labs of seed 001. The originals keep time as a
/// float of milliseconds or seconds: at 1e6 s a float steps by 0.06 s and at 1e9 s by 64 s, so
/// their animation stutters and then stands. The port keeps `time` in f64 and reduces it before
/// it becomes a float where the shader only takes sin of it (`wave`: modulo 2π, so 1e9 s looks
/// like any other moment); `morph` and `particles` take it as the course does and stay finite.
/// `particles` follow a parabola in t, as the course's do: by t = 1e6 they have fallen out of
/// view (nothing drawn, as in the original), and stay finite.
#[test]
fn huge_times_stay_finite_and_wave_repeats_with_its_period() {
    for entry in [course::WAVE, course::MORPH, course::PARTICLES] {
        for t in ["1e6", "1e9", "-1e9"] {
            let o = float_render(entry, &[("time", t)]);
            let what = format!("{} at time {t}", entry.info.name);
            if entry.info.name == "particles" {
                assert_finite(&what, &o);
            } else {
                assert_sane(&what, &o);
            }
        }
    }
    // The wave's time is reduced modulo 2π in double: t and t + 2π·k draw the same picture.
    let k = 159_154.0 * std::f64::consts::TAU;
    let a = common::render_state(course::WAVE, &[("time", "0.7")]);
    let b = common::render_state(course::WAVE, &[("time", &format!("{}", 0.7 + k))]);
    let db = shaderlab::metrics::psnr(&a, &b).unwrap();
    println!("wave at 0.7 and 0.7 + 2π·159154 s (1.0e6 s): {db:.1} dB");
    assert!(db >= 50.0, "{db:.1} dB");
}

/// Lights on the surface and at the eye. GL's lighting divides by nothing here (no
/// attenuation in these labs) but normalizes L = light − vertex: a light exactly on a vertex
/// makes L zero, `normalize(0)` is undefined in GLSL (NaN on llvmpipe). The port's shaders are
/// the course's; where L can be zero the result must still be finite (a NaN is drawn black by
/// the fixed-point framebuffer in the original, and would poison a float target).
#[test]
fn lights_on_the_surface_and_at_the_eye() {
    let cases: &[(&LabEntry, &[(&str, &str)])] = &[
        // Seed 001: the sphere (radius 1) 4 units in front of the eye, in eye space.
        (
            course::PHONG_FRAGMENT,
            &[("object", "sphere"), ("lx", "0"), ("ly", "0"), ("lz", "-3")],
        ),
        (
            course::PHONG_FRAGMENT,
            &[("object", "sphere"), ("lx", "0"), ("ly", "0"), ("lz", "0")],
        ),
        (
            course::PHONG_VERTEX,
            &[("object", "sphere"), ("lx", "0"), ("ly", "0"), ("lz", "-3")],
        ),
        (
            course::TOON,
            &[("object", "sphere"), ("lx", "0"), ("ly", "0"), ("lz", "0")],
        ),
        (course::BUMP, &[("blx", "0"), ("bly", "0"), ("blz", "0")]),
        (course::NORMMAP, &[("blx", "0"), ("bly", "0"), ("blz", "0")]),
        // Seed 003: the light on the strip's curve and at the report's camera.
        (
            course::SPECULAR_STRIP,
            &[("lightx", "0"), ("lighty", "-0.65"), ("lightz", "0")],
        ),
        // Seed 004: eye-space lights, at the eye.
        (
            course::SUZANNE_PHONG,
            &[("lightx", "0"), ("lighty", "0"), ("lightz", "0")],
        ),
        (
            course::SUZANNE_GOURAUD,
            &[("lightx", "0"), ("lighty", "0"), ("lightz", "0")],
        ),
    ];
    for (entry, state) in cases {
        let o = float_render(entry, state);
        assert_sane(&format!("{} {state:?}", entry.info.name), &o);
    }
}

/// Shininess 0 and 1e6. GL clamps `GL_SHININESS` to [0, 128]; the courses' sliders keep their
/// own ranges. The port's parameters refuse what the lab's range excludes with a message that
/// says the range (so 0 and 1e6 never reach `pow`), and draw the ends of the range.
#[test]
fn shininess_at_and_beyond_the_ends() {
    for (entry, lo, hi) in [
        (course::PHONG_FRAGMENT, "1", "128"),
        (course::SUZANNE_PHONG, "1", "256"),
    ] {
        let mut lab = common::build(entry);
        for bad in ["0", "1e6"] {
            let err = lab.params_mut().set_str("shininess", bad).expect_err("refused");
            println!("{} shininess={bad}: {err}", entry.info.name);
            assert!(err.to_string().contains("shininess"), "{err}");
        }
        for good in [lo, hi] {
            let o = float_render(entry, &[("shininess", good)]);
            assert_sane(&format!("{} shininess {good}", entry.info.name), &o);
        }
    }
}

/// `normalize` of zero vectors: GLUT's sphere poles (normals exact), the Bézier strip's last
/// vertex (the course leaves its normal (0, 0, 0): its fragments interpolate a non-zero normal,
/// so no pixel takes `normalize(0)`), and a zero-area triangle in a user's OBJ (its face normal
/// is the cross product of two parallel edges, zero: the OBJ loader keeps it zero
/// (`normalize_or_zero`), it adds nothing to its corners' smooth normals and covers no pixel).
#[test]
fn zero_vectors_never_reach_the_picture() {
    for entry in [course::PHONG_FRAGMENT, course::PHONG_VERTEX, course::TOON] {
        // Looking down on the sphere's pole.
        let o = float_render(entry, &[("object", "sphere"), ("xangle", "90")]);
        assert_sane(&format!("{} at the pole", entry.info.name), &o);
    }
    let o = float_render(course::SPECULAR_STRIP, &[]);
    assert_sane("specular_strip (its last normal is zero)", &o);

    let obj = "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nv 2 2 0\nv 3 3 0\nv 4 4 0\nf 1 2 3\nf 4 5 6\nf 1 2 2\n";
    let model = parse_obj("degenerate.obj", obj).expect("an OBJ with zero-area faces loads");
    let files = UserFiles {
        model: Some(UserFile {
            path: "degenerate.obj".into(),
            data: model,
        }),
        ..UserFiles::default()
    };
    for entry in [
        course::SUZANNE_SMOOTH,
        course::SUZANNE_PHONG,
        course::SUZANNE_GOURAUD,
        course::SUZANNE_FLAT,
    ] {
        let pixels = render_with_files(entry, &files);
        let o = outcome(&pixels);
        assert_sane(&format!("{} on an OBJ with zero-area triangles", entry.info.name), &o);
    }
}

/// `entry` built with user files, rendered into the float target at half its size.
fn render_with_files(entry: &LabEntry, files: &UserFiles) -> Vec<[f32; 4]> {
    let gpu = common::gpu();
    let cx = BuildContext::new(gpu, &ShaderSource::Embedded, FLOAT, files);
    let mut lab = (entry.new)(&cx).unwrap_or_else(|e| panic!("{}: {e}", entry.info.name));
    let (w, h) = entry.info.size;
    let target = shaderlab::offscreen::Offscreen::with_format(gpu, w / 2, h / 2, FLOAT);
    shaderlab::shell::render_into(gpu, lab.as_mut(), &target).expect("render");
    target.read_f32(gpu).expect("read")
}

/// Tangent frames where the tangent is parallel to the normal: seed 001's bump labs carry a
/// constant tangent (1, 0, 0) on a quad whose normal is (0, 0, 1), so the frame itself never
/// degenerates through a parameter (the original's is the same constant). The nearest case a
/// user reaches is the quad turned towards edge-on (yangle → 90°): the tangent points almost
/// at the eye and the light vector in the frame is almost (0, 0, ±|L|). Nearly edge-on the
/// quad still shows and stays finite; at 90° and 270° it is exactly edge-on and covers no pixel.
#[test]
fn tangent_frames_edge_on() {
    for entry in [course::BUMP, course::NORMMAP] {
        for (yangle, shows) in [("80", true), ("88", true), ("90", false), ("270", false)] {
            let mut lab = lab_with(entry, &ShaderSource::Embedded, FLOAT);
            common::set_state(lab.lab.as_mut(), &[("yangle", yangle)]);
            let (w, h) = entry.info.size;
            let o = outcome(&lab.render_f32(w / 2, h / 2).expect("render"));
            let what = format!("{} yangle {yangle}", entry.info.name);
            if shows {
                assert_sane(&what, &o);
            } else {
                assert_finite(&what, &o);
                assert_eq!(
                    o.drawn, 0,
                    "{what}: the quad is edge-on, yet pixels differ from the background"
                );
            }
        }
    }
}

/// 1×1 and non-power-of-two textures (`--texture FILE`): GL 2.0 and later take any size, and
/// `glGenerateMipmap` makes a 1×1 texture's one level; the port uploads the same and its mip
/// chain halves each side down to 1 (3×5 → 1×2 → 1×1).
#[test]
fn one_texel_and_odd_sized_textures() {
    for (w, h) in [(1, 1), (3, 5), (1, 7)] {
        let image = Image::from_fn(w, h, 1, |i, j, _| {
            if (i + j) % 2 == 0 {
                [255, 200, 0, 255]
            } else {
                [0, 60, 255, 255]
            }
        });
        let files = UserFiles {
            texture: Some(UserFile {
                path: format!("{w}x{h}.png").into(),
                data: image,
            }),
            ..UserFiles::default()
        };
        for entry in [
            course::TEXPARAMS,
            course::SUZANNE_TEXTURE,
            course::SUZANNE_TEXTURE_COLOR,
        ] {
            let o = outcome(&render_with_files(entry, &files));
            assert_sane(&format!("{} with a {w}x{h} texture", entry.info.name), &o);
        }
    }
}

/// A camera inside an object: seed 000's sphere and torus seen from inside (the camera
/// parameter; `legacy`'s sphere from its centre with a near plane that lets the inside show),
/// seed 003's strip with the camera moved onto it. GL clips what lies behind the
/// near plane; from inside a closed mesh the original sees the inner faces unless it culls.
/// The port's picture is finite whatever it shows (from inside the torus' tube it shows
/// nothing, as the original would: all of the tube around the eye lies nearer than
/// `gluPerspective`'s near plane at 1).
#[test]
fn camera_inside_an_object() {
    let cases: &[(&LabEntry, &[(&str, &str)])] = &[
        (course::PHONG, &[("object", "sphere"), ("camera", "0,0,0.3")]),
        (course::PHONG, &[("object", "torus"), ("camera", "0.75,0,0")]),
        (
            course::LEGACY,
            &[("object", "sphere"), ("camera", "0,0,0"), ("near", "0.01")],
        ),
        (course::SPECULAR_STRIP, &[("forward", "6")]),
    ];
    for (entry, state) in cases {
        let o = float_render(entry, state);
        assert_finite(&format!("{} {state:?}", entry.info.name), &o);
    }
}
