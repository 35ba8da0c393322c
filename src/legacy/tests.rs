//! Unit tests of the translation, construct by construct, and of error positions.

use super::*;

fn src(path: &str, text: &str) -> LegacySource {
    LegacySource::new(path, text)
}

fn fixture(dir: &str, name: &str) -> LegacySource {
    let path = format!("{}/assets/course/{dir}/{name}", env!("CARGO_MANIFEST_DIR"));
    LegacySource::read(std::path::Path::new(&path)).expect("fixture")
}

/// Seed 000's shaders: the course's files, lab 4 and 5 with their one-parenthesis mend.
fn course(lab: u32) -> (LegacySource, LegacySource) {
    let pick = |name: String| {
        if name == "lab4.frag" || name == "lab5.vert" {
            fixture("seed000-mended", &name)
        } else {
            fixture("seed000", &name)
        }
    };
    (pick(format!("lab{lab}.vert")), pick(format!("lab{lab}.frag")))
}

#[test]
fn course_shaders_translate_and_validate() {
    for lab in 1..=5 {
        let (v, f) = course(lab);
        let t = translate(&v, &f).unwrap_or_else(|e| panic!("lab{lab}: {e}"));
        t.compile()
            .unwrap_or_else(|e| panic!("lab{lab}: {e}\n{}\n{}", t.vertex.output.text, t.fragment.output.text));
    }
}

#[test]
fn course_parenthesis_errors_point_at_the_course_line() {
    let (v, _) = course(4);
    let e = translate(&v, &fixture("seed000", "lab4.frag")).unwrap_err();
    let Error::Shader {
        file,
        line,
        column,
        message,
    } = e
    else {
        panic!("{e:?}")
    };
    assert!(file.ends_with("seed000/lab4.frag"), "{file}");
    assert_eq!((line, column), (34, 46), "{message}");
    assert!(message.contains("unexpected `)`"), "{message}");
}

const PASS_VS: &str = "void main() { gl_Position = ftransform(); }\n";
const PASS_FS: &str = "void main() { gl_FragColor = vec4(1.0); }\n";

/// Translates and compiles a pair; panics with both texts on failure.
fn ok(vs: &str, fs: &str) -> Translation {
    let t = translate(&src("t.vert", vs), &src("t.frag", fs)).unwrap_or_else(|e| panic!("translate: {e}"));
    if let Err(e) = t.compile() {
        panic!(
            "compile: {e}\n{}\n-----\n{}",
            t.vertex.output.text, t.fragment.output.text
        );
    }
    t
}

/// The error of a pair (translation or naga), as (file, line, column, message).
fn err(vs: &str, fs: &str) -> (String, u32, u32, String) {
    let e = match translate(&src("t.vert", vs), &src("t.frag", fs)) {
        Err(e) => e,
        Ok(t) => t
            .compile()
            .err()
            .unwrap_or_else(|| panic!("no error:\n{}\n{}", t.vertex.output.text, t.fragment.output.text)),
    };
    match e {
        Error::Shader {
            file,
            line,
            column,
            message,
        } => (file, line, column, message),
        e => panic!("not a shader error: {e:?}"),
    }
}

#[test]
fn versions_110_120_and_none_are_taken_others_refused() {
    for v in ["", "#version 110\n", "#version 120\n"] {
        ok(&format!("{v}{PASS_VS}"), &format!("{v}{PASS_FS}"));
    }
    let (file, line, col, m) = err(&format!("// a comment\n#version 330\n{PASS_VS}"), PASS_FS);
    assert_eq!((file.as_str(), line, col), ("t.vert", 2, 1), "{m}");
    assert!(m.contains("#version 330") && m.contains("1.10"), "{m}");
}

#[test]
fn varyings_get_locations_matched_by_name() {
    let t = ok(
        "varying vec3 a, b;\nvarying float c;\nvoid main() { a = vec3(1.0); b = a; c = 1.0; gl_Position = ftransform(); }\n",
        "varying float c;\nvarying vec3 b;\nvoid main() { gl_FragColor = vec4(b, c); }\n",
    );
    let v = &t.vertex.output.text;
    assert!(
        v.contains("layout(location = 0) out vec3 a;layout(location = 1) out vec3 b;"),
        "{v}"
    );
    assert!(v.contains("layout(location = 2) out float c;"), "{v}");
    let f = &t.fragment.output.text;
    assert!(
        f.contains("layout(location = 2) in float c;") && f.contains("layout(location = 1) in vec3 b;"),
        "{f}"
    );
    // A varying the vertex shader does not write is GL's link error, at the declaration.
    let (file, line, col, m) = err(
        PASS_VS,
        "varying vec3 nope;\nvoid main() { gl_FragColor = vec4(nope, 1.0); }\n",
    );
    assert_eq!((file.as_str(), line, col), ("t.frag", 1, 14), "{m}");
    assert!(m.contains("not declared by the vertex shader"), "{m}");
    let (_, line, _, m) = err(
        &("varying vec3 n;\n".to_owned() + PASS_VS),
        "\nvarying vec4 n;\nvoid main() { gl_FragColor = n; }\n",
    );
    assert_eq!(line, 2, "{m}");
    assert!(m.contains("vec4 here but vec3 at t.vert:1:14"), "{m}");
}

#[test]
fn mesh_inputs_and_current_attributes() {
    let t = ok(
        "attribute float height;\nvarying vec4 c;\nvoid main() {\n  c = gl_MultiTexCoord0 + gl_MultiTexCoord3 + vec4(gl_Normal, height);\n  gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex;\n}\n",
        "varying vec4 c;\nvoid main() { gl_FragColor = c; }\n",
    );
    let v = &t.vertex.output.text;
    for decl in [
        "layout(location = 0) in vec3 sl_Vertex;",
        "layout(location = 1) in vec3 gl_Normal;",
        "layout(location = 2) in vec2 sl_MultiTexCoord0;",
        "const vec4 gl_MultiTexCoord3 = vec4(0.0, 0.0, 0.0, 1.0);",
        "gl_Vertex = vec4(sl_Vertex, 1.0);",
    ] {
        assert!(v.contains(decl), "{decl}:\n{v}");
    }
    assert!(t.texcoords);
    // A generic attribute is GL's current value: a uniform, (0, 0, 0, 1) by default.
    let h = t.uniforms.iter().find(|u| u.name == "height").unwrap();
    assert!(h.attribute && h.default == vec![0.0]);
    let (_, line, _, m) = err(PASS_VS, "attribute vec4 a;\nvoid main() { gl_FragColor = a; }\n");
    assert!(line == 1 && m.contains("`attribute` is for vertex shaders"), "{m}");
}

#[test]
fn matrices_and_ftransform_are_state_members() {
    let t = ok(
        "varying vec3 n;\nvoid main() {\n  n = gl_NormalMatrix * gl_Normal + (gl_ModelViewMatrixInverse * gl_ProjectionMatrixTranspose * gl_ModelViewProjectionMatrixInverseTranspose * gl_Vertex).xyz;\n  gl_Position = ftransform();\n}\n",
        "varying vec3 n;\nvoid main() { gl_FragColor = vec4(n, gl_DepthRange.far); }\n",
    );
    assert_eq!(
        t.state,
        vec![
            "gl_ModelViewProjectionMatrix",
            "gl_ModelViewMatrixInverse",
            "gl_ProjectionMatrixTranspose",
            "gl_ModelViewProjectionMatrixInverseTranspose",
            "gl_NormalMatrix",
            "gl_DepthRange"
        ]
    );
    let v = &t.vertex.output.text;
    assert!(
        v.contains("vec4 ftransform() { return gl_ModelViewProjectionMatrix * gl_Vertex; }"),
        "{v}"
    );
    // wgpu's depth range, once, after the shader's main.
    assert!(
        v.contains("sl_main();\n    gl_Position.z = (gl_Position.z + gl_Position.w) * 0.5;"),
        "{v}"
    );
}

#[test]
fn lighting_state_is_one_block_with_gl_names() {
    let t = ok(
        "varying vec4 c;\nvoid main() {\n  c = gl_FrontLightModelProduct.sceneColor + gl_FrontLightProduct[1].diffuse + gl_LightModel.ambient + gl_FrontMaterial.diffuse * gl_LightSource[0].halfVector * gl_LightSource[1].spotCosCutoff;\n  gl_Position = ftransform();\n}\n",
        "varying vec4 c;\nvoid main() { gl_FragColor = c; }\n",
    );
    assert_eq!(t.lights, 2);
    let names: Vec<&str> = t.params(&|_| false).iter().map(|p| p.name).collect();
    for n in [
        "gl_LightSource[1].position",
        "gl_LightModel.ambient",
        "gl_FrontMaterial.shininess",
    ] {
        assert!(names.contains(&n), "{n} in {names:?}");
    }
    assert!(!names.contains(&"gl_LightSource[2].position"));
    // A variable index needs all of GL's 8 lights.
    let t = ok(
        "uniform int k;\nvarying vec4 c;\nvoid main() { c = gl_LightSource[k].diffuse; gl_Position = ftransform(); }\n",
        "varying vec4 c;\nvoid main() { gl_FragColor = c; }\n",
    );
    assert_eq!(t.lights, 8);
}

#[test]
fn colours_texcoords_and_fragdata_cross_the_stages() {
    let t = ok(
        "void main() { gl_FrontColor = gl_Color * 0.5; gl_TexCoord[0] = gl_MultiTexCoord0; gl_TexCoord[2] = vec4(1.0); gl_Position = ftransform(); }\n",
        "void main() { gl_FragData[0] = gl_Color + gl_TexCoord[0] + gl_TexCoord[2]; }\n",
    );
    let (v, f) = (&t.vertex.output.text, &t.fragment.output.text);
    assert!(v.contains("layout(location = 0) out vec4 gl_FrontColor;"), "{v}");
    assert!(
        v.contains("layout(location = 1) out vec4 sl_TexCoord0;")
            && v.contains("layout(location = 2) out vec4 sl_TexCoord2;"),
        "{v}"
    );
    assert!(v.contains("gl_FrontColor = clamp(gl_FrontColor, 0.0, 1.0);"), "{v}");
    assert!(
        f.contains("layout(location = 0) in vec4 gl_Color;") && f.contains("gl_TexCoord[2] = sl_TexCoord2;"),
        "{f}"
    );
    assert!(f.contains("sl_FragData0 = gl_FragData[0];"), "{f}");
    assert!(t.state.contains(&"gl_Color"));
    // A variable index passes all eight.
    let t = ok(
        "uniform int k;\nvoid main() { gl_TexCoord[k] = vec4(1.0); gl_Position = ftransform(); }\n",
        "void main() { gl_FragColor = gl_TexCoord[1]; }\n",
    );
    assert!(t.vertex.output.text.contains("sl_TexCoord7"));
    let (_, line, col, m) = err(PASS_VS, "void main() {\n  gl_FragData[1] = vec4(1.0);\n}\n");
    assert_eq!((line, col), (2, 3), "{m}");
    assert!(m.contains("multiple render targets"), "{m}");
}

#[test]
fn loose_uniforms_of_every_type_share_one_block() {
    let t = ok(
        "uniform float f;\nuniform int i;\nuniform bool b;\nuniform bvec2 bv;\nuniform vec2 v2;\nuniform ivec3 iv;\nuniform mat2 m2;\nuniform mat3 m3;\nuniform mat4 m4;\nuniform mat2x3 m23;\nuniform mat3x2 m32;\nvarying vec4 c;\nvoid main() {\n  c = vec4(f + float(i) + (b ? 1.0 : 0.0) + (bv.y ? 1.0 : 0.0) + v2.x + float(iv.z) + m2[1][0] + m3[2][2] + m4[3][3] + m23[1][2] + m32[2][1]);\n  gl_Position = ftransform();\n}\n",
        "uniform float w[4];\nuniform vec2 p[3];\nuniform vec3 q[2];\nuniform bool flags[2];\nuniform int n[3];\nuniform mat4 ms[2];\nuniform float f;\nvarying vec4 c;\nvoid main() { gl_FragColor = c + w[3] + p[2].y + q[1].x + (flags[1] ? 1.0 : 0.0) + float(n[2]) + ms[1][3][3] + f; }\n",
    );
    let names: Vec<&str> = t.uniforms.iter().map(|u| u.name.as_str()).collect();
    assert_eq!(
        names,
        ["f", "i", "b", "bv", "v2", "iv", "m2", "m3", "m4", "m23", "m32", "w", "p", "q", "flags", "n", "ms"]
    );
    let enc = |n: &str| t.uniforms.iter().find(|u| u.name == n).unwrap().encoding;
    assert_eq!(enc("f"), Encoding::Plain);
    assert_eq!(enc("b"), Encoding::Bool);
    assert_eq!(enc("m2"), Encoding::Columns);
    assert_eq!(enc("m32"), Encoding::Columns);
    assert_eq!(enc("w"), Encoding::Padded);
    assert_eq!(enc("p"), Encoding::Padded);
    assert_eq!(enc("q"), Encoding::Plain);
    assert_eq!(enc("flags"), Encoding::Padded);
    // Both stages declare the same block.
    let block = |text: &str| {
        text[text.find("uniform sl_Uniforms").unwrap()..]
            .split("};")
            .next()
            .unwrap()
            .to_owned()
    };
    assert_eq!(block(&t.vertex.output.text), block(&t.fragment.output.text));
    // Values land where naga lays them out.
    let (vs, _) = t.compile().unwrap();
    let values: Vec<Vec<f64>> = t
        .uniforms
        .iter()
        .map(|u| (0..u.components()).map(|k| k as f64 + 1.0).collect())
        .collect();
    let bytes = block_bytes(&vs, UNIFORM_BLOCK, &mut uniform_lookup(&t.uniforms, &values)).unwrap();
    let layout = vs.uniform_block(UNIFORM_BLOCK).unwrap();
    let f32_at = |at: usize| f32::from_ne_bytes(bytes[at..at + 4].try_into().unwrap());
    let i32_at = |at: usize| i32::from_ne_bytes(bytes[at..at + 4].try_into().unwrap());
    let off = |m: &str| layout.member(m).unwrap_or_else(|| panic!("{m}")).offset;
    assert_eq!(f32_at(off("f")), 1.0);
    assert_eq!(i32_at(off("i")), 1);
    assert_eq!(i32_at(off("sl_u_bv") + 4), 2);
    // float w[4]: one vec4 per element, value in .x.
    assert_eq!((f32_at(off("sl_u_w")), f32_at(off("sl_u_w") + 16 * 3)), (1.0, 4.0));
    // mat2: columns (1, 2) and (3, 4), one vec4 each.
    assert_eq!((f32_at(off("sl_u_m2") + 4), f32_at(off("sl_u_m2") + 16)), (2.0, 3.0));
    // mat3: std140 columns of 16 bytes.
    assert_eq!(f32_at(off("m3") + 32 + 8), 9.0);
    let params = t.params(&|n| n == "f");
    assert!(
        params.iter().any(|p| p.name == "uniform.f"),
        "a taken name gets `uniform.`"
    );
    assert_eq!(params.iter().find(|p| p.name == "ms").unwrap().default.len(), 32);
}

#[test]
fn uniform_initializers_are_defaults() {
    let t = ok(
        "#version 120\nuniform vec3 c = vec3(0.5, 1.0, -2.0);\nuniform float k = 3.0;\nuniform mat2 m = mat2(2.0);\nvarying vec3 o;\nvoid main() { o = c * k * m[0][0]; gl_Position = ftransform(); }\n",
        "#version 120\nvarying vec3 o;\nvoid main() { gl_FragColor = vec4(o, 1.0); }\n",
    );
    let d = |n: &str| t.uniforms.iter().find(|u| u.name == n).unwrap().default.clone();
    assert_eq!(d("c"), vec![0.5, 1.0, -2.0]);
    assert_eq!(d("k"), vec![3.0]);
    assert_eq!(d("m"), vec![2.0, 0.0, 0.0, 2.0]);
    let (_, line, col, m) = err(
        &("#version 120\nuniform float k = sin(1.0);\n".to_owned() + PASS_VS),
        PASS_FS,
    );
    assert_eq!((line, col), (2, 19), "{m}");
}

#[test]
fn uniforms_must_agree_across_stages() {
    let (file, line, col, m) = err(
        &("uniform vec3 shade;\n".to_owned() + PASS_VS),
        "uniform float shade;\nvoid main() { gl_FragColor = vec4(shade); }\n",
    );
    assert_eq!((file.as_str(), line, col), ("t.frag", 1, 15), "{m}");
    assert!(m.contains("float here but vec3 at t.vert:1:14"), "{m}");
}

#[test]
fn samplers_become_textures_with_samplers() {
    let t = ok(
        "uniform sampler2D heights;\nvarying vec2 uv;\nvoid main() { uv = gl_MultiTexCoord0.st; vec4 p = gl_Vertex; p.y += texture2DLod(heights, uv, 0.0).r; gl_Position = gl_ModelViewProjectionMatrix * p; }\n",
        "uniform sampler2D texture;\nuniform samplerCube env;\nuniform sampler2D heights;\nvarying vec2 uv;\nvoid main() { gl_FragColor = texture2D(texture, uv) + textureCube(env, vec3(uv, 1.0)) + texture2DProj(heights, vec3(uv, 1.0)); }\n",
    );
    let names: Vec<(&str, &str, u32)> = t
        .samplers
        .iter()
        .map(|s| (s.name.as_str(), s.glsl.as_str(), s.binding))
        .collect();
    assert_eq!(
        names,
        [
            ("heights", "heights", 2),
            ("texture", "sl_texture", 4),
            ("env", "env", 6)
        ]
    );
    let f = &t.fragment.output.text;
    assert!(
        f.contains("texture(sampler2D(sl_texture, sl_texture_sampler), uv)"),
        "{f}"
    );
    assert!(
        f.contains("texture(samplerCube(env, env_sampler), vec3(uv, 1.0))"),
        "{f}"
    );
    assert!(
        f.contains("textureProj(sampler2D(heights, heights_sampler), vec3(uv, 1.0))"),
        "{f}"
    );
    assert!(f.contains("layout(set = 0, binding = 6) uniform textureCube env; layout(set = 0, binding = 7) uniform sampler env_sampler;"), "{f}");
    assert!(t
        .vertex
        .output
        .text
        .contains("textureLod(sampler2D(heights, heights_sampler), uv, 0.0)"));
    // A lookup of the wrong kind, at the sampler.
    let (_, line, col, m) = err(
        PASS_VS,
        "uniform sampler2D t;\nvoid main() {\n  gl_FragColor = textureCube(t, vec3(1.0));\n}\n",
    );
    assert_eq!((line, col), (3, 30), "{m}");
    assert!(m.contains("is a sampler2D, this lookup takes a samplerCube"), "{m}");
}

#[test]
fn unsupported_constructs_are_named_where_they_are() {
    let cases: &[(&str, &str, u32, u32, &str)] = &[
        ("void main() {\n  gl_Position = ftransform();\n  gl_ClipVertex = gl_ModelViewMatrix * gl_Vertex;\n}\n", PASS_FS, 3, 3, "gl_ClipVertex"),
        (PASS_VS, "void main() {\n  gl_FragColor = mix(vec4(1.0), gl_Fog.color, 0.5);\n}\n", 2, 33, "fog"),
        (PASS_VS, "uniform sampler3D vol;\nvoid main() { gl_FragColor = texture3D(vol, vec3(0.0)); }\n", 1, 19, "sampler3D"),
        (PASS_VS, "uniform sampler2D s;\nvec4 f(sampler2D t) { return texture2D(t, vec2(0.0)); }\nvoid main() { gl_FragColor = f(s); }\n", 2, 8, "sampler2D function parameter"),
        (PASS_VS, "void main() { gl_FragColor = gl_TextureMatrix[0][0]; }\n", 1, 30, "texture matrices"),
        ("void main() { gl_Position = ftransform(); gl_FrontSecondaryColor = vec4(1.0); }\n", PASS_FS, 1, 43, "secondary colour"),
        (PASS_VS, "void main() { gl_FragColor = shadow2D(s, vec3(0.0)); }\n", 1, 30, "shadow"),
        (PASS_VS, "void main() { gl_FragColor = gl_Normal.xyzz; }\n", 1, 30, "vertex shader built-in"),
    ];
    for (vs, fs, line, col, what) in cases {
        let (_, l, c, m) = err(vs, fs);
        assert_eq!((l, c), (*line, *col), "{what}: {m}");
        assert!(m.contains(what), "{what}: {m}");
    }
}

#[test]
fn naga_errors_point_at_the_users_line_and_column() {
    // A type error naga finds in the translated text, reported in the user's file: line 4
    // of t.frag, where `v` is used, even though the translation moved declarations around.
    let (file, line, col, m) = err(
        PASS_VS,
        "uniform vec3 lightPosition;\nuniform float Ka;\nvoid main() {\n    vec3 v = vec4(lightPosition, Ka);\n    gl_FragColor = vec4(v, 1.0);\n}\n",
    );
    assert_eq!((file.as_str(), line), ("t.frag", 4), "{m}");
    assert!((5..=14).contains(&col), "column {col}: {m}");
    assert!(
        m.contains(" 4 |     vec3 v = vec4(lightPosition, Ka);"),
        "the user's own line is shown: {m}"
    );
    // An unknown name in the vertex shader, after the generated prologue.
    let (file, line, col, m) = err(
        "varying vec3 n;\nvoid main() {\n  n = nrmal;\n  gl_Position = ftransform();\n}\n",
        "varying vec3 n;\nvoid main() { gl_FragColor = vec4(n, 1.0); }\n",
    );
    assert_eq!((file.as_str(), line, col), ("t.vert", 3, 7), "{m}");
    // A syntax error, from glsl-lang's parse of the original text.
    let (file, line, col, m) = err("void main() {\n  gl_Position = ftransform()\n}\n", PASS_FS);
    assert_eq!((file.as_str(), line), ("t.vert", 3), "{m}");
    assert_eq!(col, 1, "{m}");
}

#[test]
fn names_glsl_450_reserves_are_renamed() {
    let t = ok(
        "float round(float x) { return floor(x + 0.5); }\nvarying float r;\nvoid main() { r = round(1.4); gl_Position = ftransform(); }\n",
        "varying float r;\nvoid main() { gl_FragColor = vec4(r); }\n",
    );
    assert!(
        t.vertex.output.text.contains("float sl_round(float x)") && t.vertex.output.text.contains("r = sl_round(1.4)")
    );
}

#[test]
fn naga_internals_reach_the_user_as_sentences_at_the_users_place() {
    let proj = "uniform sampler2D s;\nvoid main() {\n  gl_FragColor = texture2DProj(s, vec3(0.5, 0.5, 0.0));\n}\n";
    let cases: &[(&str, &str, &str, u32, u32, &str)] = &[
        (PASS_VS, "void main() {\n  float x = 1.0;\n  gl_FragColor = vec4(----x);\n}\n", "t.frag", 3, 25, "only a variable"),
        (PASS_VS, "#error not ported yet\nvoid main() { gl_FragColor = vec4(1.0); }\n", "t.frag", 1, 2, "`#error`: not ported yet"),
        (PASS_VS, "#if 1\nvoid main() { gl_FragColor = vec4(1.0); }\n", "t.frag", 1, 2, "no matching `#endif`"),
        (PASS_VS, "float f(float x) {\n  return x > 0.0 ? f(x - 1.0) : 0.0;\n}\nvoid main() { gl_FragColor = vec4(f(1.0)); }\n", "t.frag", 2, 20, "`f` calls itself"),
        (PASS_VS, "float g(float x);\nfloat f(float x) { return g(x); }\nfloat g(float x) { return f(x); }\nvoid main() { gl_FragColor = vec4(f(1.0)); }\n", "t.frag", 2, 27, "recursion (f → g → f)"),
        (PASS_VS, "void main(float x) {\n  gl_FragColor = vec4(1.0);\n}\n", "t.frag", 1, 1, "`main` takes no parameters"),
        ("void main() {\n  gl_Position = ftransform();\n  if (gl_Position.x > 0.0) discard;\n}\n", PASS_FS, "t.vert", 3, 28, "`discard` is only allowed in a fragment shader"),
        (PASS_VS, "void main() {\n  float a[5];\n  a[0] = 1.0;\n  gl_FragColor = vec4(a[7]);\n}\n", "t.frag", 4, 24, "constant index 7 is out of bounds"),
        (PASS_VS, proj, "t.frag", 3, 18, "division by zero"),
    ];
    for (vs, fs, file, line, col, what) in cases {
        let (f, l, c, m) = err(vs, fs);
        assert_eq!((f.as_str(), l, c), (*file, *line, *col), "{what}: {m}");
        assert!(m.contains(what), "{what}: {m}");
        for internal in [
            "HirExpr",
            "ErrorDirective",
            "UnfinishedBlock",
            "Unknown function",
            "Expression [",
            "not visited",
            "Float literal",
            "Expected end of file",
        ] {
            assert!(!m.contains(internal), "{what}: {m}");
        }
    }
    // `void main(void)` is still a `main` without parameters.
    ok(PASS_VS, "void main(void) { gl_FragColor = vec4(1.0); }\n");
}

#[test]
fn limits_are_checked_with_the_uniforms_and_varyings_named() {
    let t = ok(
        PASS_VS,
        "uniform float a[100];\nuniform vec4 b;\nvoid main() { gl_FragColor = vec4(a[3]) + b; }\n",
    );
    let (vs, fs) = t.compile().unwrap();
    assert!(t.check_limits(&vs, &fs, 16384, 16).is_ok());
    let e = t.check_limits(&vs, &fs, 1024, 16).unwrap_err();
    let Error::Shader {
        file, line, message, ..
    } = e
    else {
        panic!("{e:?}")
    };
    assert_eq!((file.as_str(), line), ("t.frag", 1), "{message}");
    assert!(
        message.contains("need 1616 bytes") && message.contains("limit of 1024 bytes"),
        "{message}"
    );
    assert!(message.contains("`a` float[100] 1600 bytes (t.frag:1)"), "{message}");
    assert!(message.contains("`b` vec4 16 bytes (t.frag:2)"), "{message}");

    let vary = "varying vec4 p;\nvarying vec4 q;\nvarying vec4 r;\n";
    let t = ok(
        &format!("{vary}void main() {{ p = q = r = vec4(1.0); gl_FrontColor = p; gl_Position = ftransform(); }}\n"),
        &format!("{vary}void main() {{ gl_FragColor = p + q + r + gl_Color; }}\n"),
    );
    let (vs, fs) = t.compile().unwrap();
    assert!(t.check_limits(&vs, &fs, 16384, 4).is_ok());
    let e = t.check_limits(&vs, &fs, 16384, 3).unwrap_err();
    let Error::Shader {
        file, line, message, ..
    } = e
    else {
        panic!("{e:?}")
    };
    assert_eq!(
        (file.as_str(), line),
        ("t.vert", 3),
        "the first varying past the limit: {message}"
    );
    assert!(
        message.contains("passes 4 values")
            && message.contains("p, q, r, gl_FrontColor")
            && message.contains("at most 3"),
        "{message}"
    );
}

#[test]
fn int_uniforms_are_exact_over_the_whole_range() {
    let t = ok(
        PASS_VS,
        "uniform int k;\nvoid main() { gl_FragColor = vec4(float(k)); }\n",
    );
    let (vs, _) = t.compile().unwrap();
    let mut params = crate::params::Params::new(&t.params(&|_| false));
    for v in ["16777217", "2147483647", "-2147483648"] {
        params.set_str("k", v).unwrap();
        let values = vec![params.get("k").unwrap().to_vec()];
        let bytes = block_bytes(&vs, UNIFORM_BLOCK, &mut uniform_lookup(&t.uniforms, &values)).unwrap();
        let got = i32::from_ne_bytes(bytes[0..4].try_into().unwrap());
        assert_eq!(got.to_string(), v);
    }
}

#[test]
fn uniforms_named_like_lab_parameters_are_renamed_and_say_why() {
    let t = ok(
        PASS_VS,
        "uniform float near;\nuniform float kept;\nvoid main() { gl_FragColor = vec4(near + kept); }\n",
    );
    let params = t.params(&|n| n == "near");
    let names: Vec<&str> = params.iter().map(|p| p.name).collect();
    assert_eq!(names, ["uniform.near", "kept"]);
    assert!(
        params[0]
            .help
            .contains("`near` is the lab's own parameter, so this one is `uniform.near`"),
        "{}",
        params[0].help
    );
}

#[test]
fn point_size_is_accepted_by_the_runner_and_by_wgsl_output() {
    let t = ok(
        "void main() { gl_Position = ftransform(); gl_PointSize = 2.0; }\n",
        PASS_FS,
    );
    let (vs, _) = t.compile().unwrap();
    // glsl2wgsl --legacy writes WGSL, which has no point size: it used to fail here.
    vs.to_wgsl().unwrap_or_else(|e| panic!("{e}"));
}

/// Issue 17: hostile shaders are errors at their file and line, not a stack overflow (the
/// nesting), gigabytes (macros) or a driver crash (calls): `shader::guard` runs before
/// glsl-lang's parser.
#[test]
fn hostile_shaders_are_errors_at_their_line() {
    let deep =
        |body: String| format!("void main() {{\n    float x = 1.0;\n    {body}\n    gl_FragColor = vec4(x);\n}}\n");
    let macros: String = (0..40).map(|i| format!("#define A{} (A{i}+A{i})\n", i + 1)).collect();
    let chain: String = (0..40)
        .map(|i| format!("float f{}(float x) {{ return f{i}(x) + f{i}(x); }}\n", i + 1))
        .collect();
    for (text, line, phrase) in [
        (
            deep(format!("x = {};", vec!["x"; 10_000].join(" + "))),
            3,
            "nests too deeply",
        ),
        (
            deep(format!("x = {}x{};", "(".repeat(10_000), ")".repeat(10_000))),
            3,
            "nests too deeply",
        ),
        (
            deep(format!("{}x = 2.0;{}", "{".repeat(10_000), "}".repeat(10_000))),
            3,
            "nests too deeply",
        ),
        (
            deep(format!("{}x = 2.0;", "if (x > 0.0) ".repeat(5000))),
            3,
            "nests too deeply",
        ),
        (
            format!("#define A0 1.0\n{macros}void main() {{ gl_FragColor = vec4(A40); }}\n"),
            42,
            "`A40`: the shader's macro expansions pass 262144 tokens",
        ),
        (
            format!("float f0(float x) {{ return x; }}\n{chain}void main() {{ gl_FragColor = vec4(f40(0.5)); }}\n"),
            14,
            "with its macros expanded and its calls inlined",
        ),
    ] {
        let Some(e) = translate(&src("t.vert", PASS_VS), &src("t.frag", &text)).err() else {
            panic!("accepted: {}", &text[..200])
        };
        let Error::Shader {
            file,
            line: at,
            message,
            ..
        } = &e
        else {
            panic!("{e:?}")
        };
        assert_eq!((file.as_str(), *at), ("t.frag", line), "{message}");
        assert!(message.contains(phrase), "{message}");
    }
    // Just under the bound, every stage (glsl-lang, the translation, naga) copes on a test
    // thread's 2 MiB stack (checked in a release build).
    let limit = crate::shader::guard::MAX_DEPTH - 10;
    ok(
        PASS_VS,
        &deep(format!("x = {}x{};", "(".repeat(limit), ")".repeat(limit))),
    );
    ok(PASS_VS, &deep(format!("x = {};", vec!["x"; limit].join(" + "))));
    ok(
        PASS_VS,
        &deep(format!("{}x = 2.0;{}", "{".repeat(limit), "}".repeat(limit))),
    );
    ok(PASS_VS, &deep(format!("{}x = 2.0;", "if (x > 0.0) ".repeat(limit))));
    ok(
        PASS_VS,
        &deep(format!(
            "{} {{ x = 2.0; }}",
            "if (x > 0.0) { x = 1.0; } else ".repeat(limit / 2)
        )),
    );
}

/// CPU seconds this thread has used: the work a test times, which other threads and a busy
/// machine do not inflate as they do the wall clock.
fn thread_cpu_seconds() -> f64 {
    #[cfg(target_os = "linux")]
    {
        // SAFETY: a zeroed timespec for clock_gettime to fill.
        let mut t: libc::timespec = unsafe { std::mem::zeroed() };
        // SAFETY: as above; the clock is this thread's.
        let done = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) };
        assert_eq!(done, 0, "clock_gettime: {}", std::io::Error::last_os_error());
        t.tv_sec as f64 + t.tv_nsec as f64 / 1e9
    }
    #[cfg(not(target_os = "linux"))]
    {
        static START: std::sync::OnceLock<std::time::Instant> = std::sync::OnceLock::new();
        START.get_or_init(std::time::Instant::now).elapsed().as_secs_f64()
    }
}

/// The line map is linear in the file's length (one line index per file), not quadratic
/// (issue 17; figures in docs/speed.md): a file four times as long takes at most eight times
/// the CPU (a quadratic map, sixteen), timed on this thread in one run.
#[test]
fn long_files_translate_in_linear_time() {
    let comments = |n: usize| "// a comment line of a long file\n".repeat(n) + PASS_FS;
    let functions = |n: usize| {
        (0..n)
            .map(|i| format!("float g{i}() {{ return 1.0; }}\n"))
            .collect::<String>()
            + PASS_FS
    };
    let cpu = |fs: &str| {
        let start = thread_cpu_seconds();
        let t = ok(PASS_VS, fs);
        assert_eq!(
            t.fragment.compile().unwrap().source.line_map.len(),
            t.fragment.output.text.lines().count()
        );
        thread_cpu_seconds() - start
    };
    for (what, short, long) in [
        ("comment lines", comments(8_000), comments(32_000)),
        ("functions", functions(2_500), functions(10_000)),
    ] {
        // The shorter one twice: the first run warms what is made once.
        cpu(&short);
        let (a, b) = (cpu(&short), cpu(&long));
        eprintln!("{what}: {a:.3} s of CPU, 4x as many {b:.3} s ({:.1}x)", b / a);
        assert!(
            b < 8.0 * a,
            "{what}: 4x as many took {:.1}x the CPU ({a:.3} s, {b:.3} s)",
            b / a
        );
    }
}

/// `uniform float a[1000]` is read from the block element by element, not copied whole into
/// a private array on every invocation (issue 17: lavapipe's compiler took far too long; figures
/// in docs/speed.md).
#[test]
fn uniform_arrays_are_read_in_place() {
    let t = ok(
        PASS_VS,
        "uniform float a[1000];\nuniform bool b[2];\nuniform vec2 texture[2];\n\
         float at(int i) { return a[i]; }\n\
         void main() { gl_FragColor = vec4(at(1) + a[int(a[0])], b[1] ? 1.0 : 0.0, texture[1]); }\n",
    );
    let text = &t.fragment.output.text;
    assert!(!text.contains("for (int i"), "{text}");
    for read in [
        "sl_u_a[i].x",
        "sl_u_a[int(sl_u_a[0].x)].x",
        "(sl_u_b[1].x != 0)",
        "sl_u_sl_texture[1].xy",
    ] {
        assert!(text.contains(read), "{read}:\n{text}");
    }
    // An array used whole (or redeclared, or named by a macro) keeps its private copy.
    let t = ok(
        PASS_VS,
        "uniform float w[3];\nfloat sum(float v[3]) { return v[0] + v[1] + v[2]; }\n\
         void main() { gl_FragColor = vec4(sum(w)); }\n",
    );
    assert!(t
        .fragment
        .output
        .text
        .contains("for (int i = 0; i < 3; i++) { w[i] = sl_u_w[i].x; }"));
}

/// Issue 17: a uniform array larger than a uniform block is refused by name, before its
/// default values are allocated.
#[test]
fn uniform_arrays_beyond_the_block_are_refused_by_name() {
    for (decl, phrase) in [
        (
            "uniform float a[100000];",
            "uniform `a` (float[100000]) takes 1600000 bytes",
        ),
        (
            "uniform mat4 a[2000000000];",
            "uniform `a` (mat4[2000000000]) takes 128000000000 bytes",
        ),
    ] {
        let Some(e) = translate(&src("t.vert", PASS_VS), &src("t.frag", &format!("{decl}\n{PASS_FS}"))).err() else {
            panic!("accepted: {decl}")
        };
        let message = e.to_string();
        assert!(message.contains("t.frag:1:") && message.contains(phrase), "{message}");
        assert!(message.contains("the limit is 16384 bytes"), "{message}");
    }
    ok(PASS_VS, &format!("uniform float a[1024];\n{PASS_FS}"));
}
