//! The debugger against the GPU where GLSL gets strange: indices out of range, loops the GPU
//! ends, NaN and the values GLSL leaves undefined, coarse derivatives, `textureSize` past the
//! last level, clip coordinates near 1e10. Each case is a lab with one shader's `main`
//! replaced (an edited copy, as the page's editor makes it), drawn by the GPU and replayed by
//! the debugger at the same pixels: the stored bytes must be the same. Most cases write a
//! float's bits as the colour (the low three bytes at an even column, the high byte at the odd
//! one beside it), so that the comparison is of the value itself.

mod common;

use std::collections::BTreeMap;
use std::sync::Arc;

use common::gpu;
use shaderlab::debug::{capture_lab, Inspection};
use shaderlab::lab::{BuildContext, Lab, UserFiles};
use shaderlab::offscreen::COLOR_FORMAT;
use shaderlab::shader::ShaderSource;

/// `lab` with the `main` of `file` (from `void main()` to the end) replaced by `main`.
fn edited(lab: &str, file: &str, main: &str, set: &[(&str, &str)]) -> Box<dyn Lab> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("shaders_glsl")
        .join(file);
    let text = std::fs::read_to_string(&path).expect("the built-in shader");
    let at = text.find("void main()").expect("a main");
    let texts: BTreeMap<String, String> = [(file.to_owned(), format!("{}{main}", &text[..at]))].into();
    let source = ShaderSource::Edited(Arc::new(texts));
    let files = UserFiles::default();
    let cx = BuildContext::new(gpu(), &source, COLOR_FORMAT, &files);
    let entry = shaderlab::course::find(lab).expect("a lab");
    let mut lab = (entry.new)(&cx).unwrap_or_else(|e| panic!("{lab} builds with\n{main}\n{e}"));
    for (k, v) in set {
        lab.params_mut().set_str(k, v).expect("a parameter");
    }
    lab
}

/// The GPU's bytes and the debugger's at `pixels` of `lab` where they differ (by more than
/// `tolerance` in a channel), and the caveats of the inspection at the first pixel.
fn differences(what: &str, mut lab: Box<dyn Lab>, pixels: &[(u32, u32)], tolerance: i32) -> (Vec<String>, Vec<String>) {
    let (w, h) = lab.info().size;
    let (image, captured) = capture_lab(gpu(), lab.as_mut(), w, h, true).unwrap_or_else(|e| panic!("{what}: {e}"));
    let image = image.expect("the picture");
    let mut out = Vec::new();
    let mut caveats = Vec::new();
    for (k, &(x, y)) in pixels.iter().enumerate() {
        let gpu_px = image.get_pixel(x, y).0;
        let i = Inspection::new(what, &captured, x, y).unwrap_or_else(|e| panic!("{what} at {x},{y}: {e}"));
        if k == 0 {
            caveats = i.caveats.clone();
        }
        let cpu = i.replayed.pixel;
        if (0..4).any(|c| (i32::from(cpu[c]) - i32::from(gpu_px[c])).abs() > tolerance) {
            out.push(format!("{what} at {x},{y}: debugger {cpu:?}, GPU {gpu_px:?}"));
        }
    }
    (out, caveats)
}

/// phong's fragment shader computing `body` (which sets `float r`) with `zero`, `one`, `nan`
/// and `inf` made at run time, writing r's bits: the low 24 at even columns, the high 8 at
/// odd ones (or the low 24 everywhere with `low_only`).
fn bits_main(body: &str, low_only: bool) -> String {
    let split = if low_only {
        ""
    } else {
        "    if (mod(floor(gl_FragCoord.x), 2.0) == 1.0) b = b >> 24;\n"
    };
    format!(
        "void main() {{
    float zero = floor(gl_FragCoord.x / 100000.0);
    float one = zero + 1.0;
    float nan = sqrt(zero - 1.0);
    float inf = 1.0 / zero;
    {body}
    uint b = floatBitsToUint(r);
{split}    frag_color = vec4(float(b & 255u), float((b >> 8) & 255u), float((b >> 16) & 255u), 255.0) / 255.0;
}}
"
    )
}

/// Runs `cases` (name, body setting `r`) in phong's fragment shader at the centre pixels;
/// panics listing every difference. Returns each case's caveats.
fn bits_cases(cases: &[(&str, &str)], pixels: &[(u32, u32)], low_only: bool) -> Vec<(String, Vec<String>)> {
    let mut all = Vec::new();
    let mut said = Vec::new();
    for (name, body) in cases {
        let lab = edited("phong", "phong.frag", &bits_main(body, low_only), &[]);
        let (d, caveats) = differences(name, lab, pixels, 0);
        all.extend(d);
        said.push(((*name).to_owned(), caveats));
    }
    assert!(
        all.is_empty(),
        "{} pixels differ in {} cases:\n{}",
        all.len(),
        cases.len(),
        all.join("\n")
    );
    said
}

const CENTRE: [(u32, u32); 2] = [(320, 180), (321, 180)];

#[test]
fn out_of_range_indices_read_what_the_gpu_reads() {
    // Into a variable or a value naga restricts the index as unsigned (a negative one reads
    // the last element); into a uniform buffer it reads the bytes there, zero past the end.
    let cases = [
        "frag_color = vec4(t[zero - 1].xyz, 1.0);",
        "frag_color = vec4(t[zero + 2].xyz, 1.0);",
        "frag_color = colors[zero + 3];",
        "frag_color = colors[zero - 1];",
        "frag_color = colors[zero + 100];",
        "frag_color = colors[uint(zero) + 4294967295u];",
        "frag_color = vec4(specColor[zero + 5], specColor[zero - 1], 0.5, 1.0);",
        "vec4 c[3] = colors; frag_color = c[zero - 1];",
        "vec4 c[3] = colors; frag_color = c[zero + 7];",
        "vec4 c = colors[1]; frag_color = vec4(c[zero - 1], c[zero + 9], c[zero + 1], 1.0);",
        "mat3 m = mat3(colors[0].xyz, colors[1].xyz, colors[2].xyz); frag_color = vec4(m[zero - 1], 1.0);",
        "frag_color = vec4((colors[1] * 0.5)[zero - 1], (colors[2] + 0.1)[zero + 5], 0.0, 1.0);",
    ];
    let mut all = Vec::new();
    for body in cases {
        let main = format!("void main() {{\n    int zero = int(floor(gl_FragCoord.x / 100000.0));\n    {body}\n    frag_color.a = 1.0;\n}}\n");
        let lab = edited("uniform_arrays", "uniform_arrays.frag", &main, &[]);
        let (d, caveats) = differences(body, lab, &CENTRE, 0);
        all.extend(d);
        assert!(
            caveats.iter().any(|c| c.contains("index out of range undefined")),
            "{body}: {caveats:?}"
        );
    }
    assert!(all.is_empty(), "{}", all.join("\n"));
}

#[test]
fn loops_end_where_llvmpipe_ends_them() {
    // llvmpipe counts loop passes, all loops together, and ends every loop past 65,535.
    let cases = [
        ("for", "float k = 0.0; for (int i = 0; i < 100000 + int(zero); i++) { k += 1.0; } float r = k;"),
        ("constant bound", "float k = 0.0; for (int i = 0; i < 100000; i++) { k += 1.0; } float r = k;"),
        ("nested", "float k = 0.0; for (int j = 0; j < 3 + int(zero); j++) { for (int i = 0; i < 30000 + int(zero); i++) { k += 1.0; } } float r = k;"),
        ("two", "float k = 0.0; for (int i = 0; i < 40000 + int(zero); i++) { k += 1.0; } for (int i = 0; i < 40000 + int(zero); i++) { k += 1.0; } float r = k;"),
        ("while", "float k = 0.0; while (k < 1e9 + zero) { k += 1.0; } float r = k;"),
        ("do", "float k = 0.0; do { k += 1.0; } while (k < 1e9 + zero); float r = k;"),
        ("short first", "float k = 0.0; for (int i = 0; i < 3 + int(zero); i++) { k += 1.0; } for (int i = 0; i < 100000 + int(zero); i++) { k += 1.0; } float r = k;"),
        ("not taken", "float k = 0.0; if (zero > 0.5) { for (int i = 0; i < 10 + int(zero); i++) { k += 1.0; } } for (int i = 0; i < 100000 + int(zero); i++) { k += 1.0; } float r = k;"),
    ];
    for (name, caveats) in bits_cases(&cases, &CENTRE, false) {
        assert!(
            caveats.iter().any(|c| c.contains("65535 passes")),
            "{name}: the caveats say the loop was ended: {caveats:?}"
        );
    }
}

#[test]
fn undefined_maths_gives_what_lavapipe_gives_and_says_so() {
    let cases = [
        ("max(NaN, x)", "float r = max(nan, 0.5 * one);"),
        ("max(x, NaN)", "float r = max(0.5 * one, nan);"),
        ("min(NaN, x)", "float r = min(nan, 0.5 * one);"),
        ("clamp(NaN)", "float r = clamp(nan, 0.25 * one, 0.75 * one);"),
        ("clamp(x, NaN, hi)", "float r = clamp(0.5 * one, nan, 0.75 * one);"),
        ("clamp(NaN, 0, 1)", "float r = clamp(nan, 0.0, 1.0);"),
        ("int(NaN)", "float r = intBitsToFloat(int(nan));"),
        ("int(1e20)", "float r = intBitsToFloat(int(1e20 * one));"),
        ("int(-1e20)", "float r = intBitsToFloat(int(-1e20 * one));"),
        ("uint(1e20)", "float r = uintBitsToFloat(uint(1e20 * one));"),
        ("uint(NaN)", "float r = uintBitsToFloat(uint(nan));"),
        ("atan(0, 0)", "float r = atan(zero, zero);"),
        ("atan(∞, ∞)", "float r = atan(inf, inf);"),
        ("atan(y, x)", "float r = atan(0.3 * one, 0.7 * one);"),
        ("atan(x)", "float r = atan(0.3 * one);"),
        ("mod(x, 0)", "float r = mod(1.5 * one, zero);"),
        ("asinh(1e30)", "float r = asinh(1e30 * one);"),
        ("asinh(x)", "float r = asinh(0.7 * one);"),
        ("asin(x)", "float r = asin(0.3 * one);"),
        ("acos(x)", "float r = acos(0.5 * one);"),
        ("acosh(0.5)", "float r = acosh(0.5 * one);"),
        ("atanh(1)", "float r = atanh(one);"),
        ("pow(-2, 2)", "float r = pow(-2.0 * one, 2.0 * one);"),
        ("pow(0, 0)", "float r = pow(zero, zero);"),
        ("log(-1)", "float r = log(-one);"),
        ("smoothstep(NaN)", "float r = smoothstep(0.2 * one, 0.6 * one, nan);"),
        (
            "smoothstep order",
            "float r = smoothstep(0.6 * one, 0.2 * one, 0.3 * one);",
        ),
    ];
    let said = bits_cases(&cases, &CENTRE, false);
    // Where GLSL leaves the value undefined the inspection says so at the line.
    for (name, caveats) in &said {
        let defined = [
            "atan(y, x)",
            "atan(x)",
            "atan(∞, ∞)",
            "asinh(1e30)",
            "asinh(x)",
            "asin(x)",
            "acos(x)",
            "smoothstep(NaN)",
        ]
        .contains(&name.as_str());
        let undefined = caveats
            .iter()
            .filter(|c| c.contains("phong.frag:15") && c.contains("undefined"))
            .count();
        assert_eq!(undefined > 0, !defined, "{name}: {caveats:?}");
    }
}

#[test]
fn coarse_derivatives_are_per_pixel_as_on_llvmpipe() {
    let quad = [(320, 180), (321, 180), (320, 181), (321, 181)];
    let cases = [
        (
            "dFdxCoarse",
            "float w = gl_FragCoord.x * gl_FragCoord.x * gl_FragCoord.y; float r = dFdxCoarse(w);",
        ),
        (
            "dFdyCoarse",
            "float w = gl_FragCoord.y * gl_FragCoord.y * gl_FragCoord.x; float r = dFdyCoarse(w);",
        ),
        (
            "fwidthCoarse",
            "float w = gl_FragCoord.x * gl_FragCoord.x * gl_FragCoord.y; float r = fwidthCoarse(w);",
        ),
    ];
    bits_cases(&cases, &quad, true);
}

#[test]
fn texture_size_past_the_last_level_is_zero() {
    // texparams' texture has levels 0 to 8 (256² mipmapped).
    let mut all = Vec::new();
    for level in ["0", "1", "8", "9", "30", "-1"] {
        let main = format!(
            "void main() {{
    int zero = int(floor(gl_FragCoord.x / 100000.0));
    ivec2 s = textureSize(sampler2D(tex, tex_sampler), zero + {level});
    fColor = vec4(float(s.x & 255), float(s.x >> 8), float(s.y & 255), 255.0) / 255.0;
}}
"
        );
        let lab = edited("texparams", "suzanne_texture.frag", &main, &[]);
        all.extend(differences(&format!("textureSize level {level}"), lab, &[(320, 240)], 0).0);
    }
    assert!(all.is_empty(), "{}", all.join("\n"));
}

#[test]
fn huge_clip_coordinates_are_clipped_as_llvmpipe_clips_them() {
    // Positions scaled by up to 1e12 about the centre: llvmpipe clips each triangle against
    // the volume in f32, and from about 1e9 the clipper's rounding leaves pixels undrawn.
    let mut pixels = Vec::new();
    for y in (168..192).step_by(3) {
        for x in (308..332).step_by(3) {
            pixels.push((x, y));
        }
    }
    let mut all = Vec::new();
    let mut undrawn = 0;
    for scale in ["1e3", "1e8", "1e9", "1e10", "1e12"] {
        let main = format!(
            "void main() {{
    vec4 vertex = vec4(vertex_position, 1.0);
    v = vec3(modelview * vertex);
    N = normalize(normal_matrix * vertex_normal);
    gl_Position = mvp * vertex;
    gl_Position.xy *= {scale};
}}
"
        );
        let mut lab = edited("phong", "phong.vert", &main, &[]);
        let (w, h) = lab.info().size;
        let (image, _) = capture_lab(gpu(), lab.as_mut(), w, h, true).expect("capture");
        let image = image.expect("picture");
        undrawn += pixels
            .iter()
            .filter(|&&(x, y)| image.get_pixel(x, y).0 == [13, 26, 51, 255])
            .count();
        let lab = edited("phong", "phong.vert", &main, &[]);
        all.extend(differences(&format!("xy × {scale}"), lab, &pixels, 2).0);
    }
    assert!(
        undrawn > 20,
        "the GPU leaves pixels undrawn at these scales ({undrawn})"
    );
    assert!(all.is_empty(), "{} differ:\n{}", all.len(), all.join("\n"));
}

#[test]
fn nan_and_the_infinities_stay_apart_in_the_json() {
    let dir = common::output_dir().join("debug_edges_json");
    let _ = std::fs::remove_dir_all(&dir);
    common::copy_shaders(&dir);
    let path = dir.join("phong.frag");
    let text = std::fs::read_to_string(&path).expect("phong.frag");
    let at = text.find("void main()").expect("main");
    let main = "void main() {
    float zero = floor(gl_FragCoord.x / 100000.0);
    float a = sqrt(zero - 1.0);
    float b = 1.0 / zero;
    float c = -1.0 / zero;
    frag_color = vec4(0.5, 0.5, 0.5, 1.0);
}
";
    std::fs::write(&path, format!("{}{main}", &text[..at])).expect("write");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_shaderlab"))
        .args(["debug", "phong", "--pixel", "320,180", "--json", "--shaders"])
        .arg(&dir)
        .output()
        .expect("shaderlab runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let value = |name: &str| {
        v["trace"]
            .as_array()
            .expect("trace")
            .iter()
            .find(|s| s["name"] == name)
            .unwrap_or_else(|| panic!("a step `{name}` in {v}"))["value"]
            .clone()
    };
    assert_eq!(value("a"), "NaN");
    assert_eq!(value("b"), "Infinity");
    assert_eq!(value("c"), "-Infinity");
}

#[test]
fn glsl_naga_does_not_implement_is_named_as_such() {
    let dir = common::output_dir().join("debug_edges_naga_lacks");
    for (name, line) in [
        ("frexp", "int e; float r = frexp(0.5, e);"),
        ("uaddCarry", "uint c; float r = float(uaddCarry(1u, 2u, c));"),
        (
            "matrixCompMult",
            "float r = matrixCompMult(mat2(1.0), mat2(2.0))[0][0];",
        ),
        (
            "textureQueryLod",
            "float r = textureQueryLod(sampler2D(tex, tex_sampler), texcoord).x;",
        ),
        ("gl_HelperInvocation", "float r = gl_HelperInvocation ? 1.0 : 0.0;"),
    ] {
        let _ = std::fs::remove_dir_all(&dir);
        common::copy_shaders(&dir);
        let path = dir.join("suzanne_texture.frag");
        let text = std::fs::read_to_string(&path).expect("suzanne_texture.frag");
        let at = text.find("void main()").expect("main");
        std::fs::write(
            &path,
            format!("{}void main() {{\n    {line}\n    fColor = vec4(r);\n}}\n", &text[..at]),
        )
        .expect("write");
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_shaderlab"))
            .args(["debug", "texparams", "--pixel", "320,240", "--shaders"])
            .arg(&dir)
            .output()
            .expect("shaderlab runs");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{name}: {err}");
        assert!(
            err.contains(&format!("`{name}` is GLSL, but naga 30")) && err.contains("suzanne_texture.frag:10"),
            "{name}: {err}"
        );
    }
}
