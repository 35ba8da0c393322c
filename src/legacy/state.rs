//! GL's built-in uniform state: its parameters (GL's defaults, settable by their GLSL names,
//! `--set gl_LightSource[0].position=2,2,2,1`), the values derived from them as GL derives
//! them (Mesa's formulas), and the scene's matrices.

use std::collections::{HashMap, HashSet};
use std::sync::Mutex;

use glam::{Mat3, Mat4, Vec3};

use crate::params::{ParamSpec, Params};

/// A name or default kept for the life of the program (parameter names come from the user's
/// shaders; each distinct one is stored once).
pub fn intern(s: &str) -> &'static str {
    static NAMES: Mutex<Option<HashSet<&'static str>>> = Mutex::new(None);
    let mut names = NAMES.lock().unwrap_or_else(|e| e.into_inner());
    let names = names.get_or_insert_with(HashSet::new);
    if let Some(n) = names.get(s) {
        return n;
    }
    let leaked: &'static str = Box::leak(s.to_owned().into_boxed_str());
    names.insert(leaked);
    leaked
}

/// A default value kept for the life of the program (stored once per distinct value, told
/// apart by their bits).
pub fn intern_values(v: &[f64]) -> &'static [f64] {
    static VALUES: Mutex<Option<HashMap<Vec<u64>, &'static [f64]>>> = Mutex::new(None);
    let mut values = VALUES.lock().unwrap_or_else(|e| e.into_inner());
    let values = values.get_or_insert_with(HashMap::new);
    let key: Vec<u64> = v.iter().map(|x| x.to_bits()).collect();
    values
        .entry(key)
        .or_insert_with(|| Box::leak(v.to_vec().into_boxed_slice()))
}

const BIG: f64 = 1e9;
const BLACK: &[f64] = &[0.0, 0.0, 0.0, 1.0];
const WHITE: &[f64] = &[1.0, 1.0, 1.0, 1.0];

/// The settable fields of `gl_LightSource[i]`, with GL's defaults for light 0 and the others.
const LIGHT_FIELDS: &[(&str, &[f64], &[f64])] = &[
    ("ambient", BLACK, BLACK),
    ("diffuse", WHITE, BLACK),
    ("specular", WHITE, BLACK),
    ("position", &[0.0, 0.0, 1.0, 0.0], &[0.0, 0.0, 1.0, 0.0]),
    ("spotDirection", &[0.0, 0.0, -1.0], &[0.0, 0.0, -1.0]),
    ("spotExponent", &[0.0], &[0.0]),
    ("spotCutoff", &[180.0], &[180.0]),
    ("constantAttenuation", &[1.0], &[1.0]),
    ("linearAttenuation", &[0.0], &[0.0]),
    ("quadraticAttenuation", &[0.0], &[0.0]),
];

/// The settable fields of `gl_FrontMaterial`, with GL's defaults.
const MATERIAL_FIELDS: &[(&str, &[f64])] = &[
    ("emission", BLACK),
    ("ambient", &[0.2, 0.2, 0.2, 1.0]),
    ("diffuse", &[0.8, 0.8, 0.8, 1.0]),
    ("specular", BLACK),
    ("shininess", &[0.0]),
];

fn light_help(field: &str) -> &'static str {
    match field {
        "position" => "GL light position as the shader sees it (eye space; w = 0: a direction)",
        "spotDirection" => "GL spot direction (eye space)",
        "spotExponent" => "GL spot exponent (0..128)",
        "spotCutoff" => "GL spot cutoff in degrees (0..90, or 180: no spot)",
        "constantAttenuation" | "linearAttenuation" | "quadraticAttenuation" => "GL attenuation factor",
        _ => "GL light colour (RGBA)",
    }
}

/// The parameters of GL's state that the shaders use: `used` names the state block's members,
/// `lights` how many lights are indexed.
pub fn params(used: &[&str], lights: usize) -> Vec<ParamSpec> {
    let uses = |n: &str| used.contains(&n);
    let mut out = Vec::new();
    if uses("gl_Color") {
        out.push(ParamSpec::real(
            "gl_Color",
            WHITE,
            -BIG,
            BIG,
            "GL's current colour (glColor), RGBA",
        ));
    }
    let products = uses("gl_FrontLightProduct");
    if uses("gl_LightSource") || products {
        for i in 0..lights {
            for (field, first, other) in LIGHT_FIELDS {
                let (min, max) = match *field {
                    "spotExponent" => (0.0, 128.0),
                    // GL takes 0..90 or exactly 180 (no spot); 90.5 is GL_INVALID_VALUE.
                    "spotCutoff" => (0.0, 90.0),
                    "constantAttenuation" | "linearAttenuation" | "quadraticAttenuation" => (0.0, BIG),
                    _ => (-BIG, BIG),
                };
                let spec = ParamSpec::real(
                    intern(&format!("gl_LightSource[{i}].{field}")),
                    if i == 0 { first } else { other },
                    min,
                    max,
                    light_help(field),
                );
                out.push(if *field == "spotCutoff" {
                    spec.or_exactly(180.0)
                } else {
                    spec
                });
            }
        }
    }
    if uses("gl_LightModel") || uses("gl_FrontLightModelProduct") {
        out.push(ParamSpec::real(
            "gl_LightModel.ambient",
            &[0.2, 0.2, 0.2, 1.0],
            -BIG,
            BIG,
            "GL light model ambient colour (RGBA)",
        ));
    }
    if uses("gl_FrontMaterial") || products || uses("gl_FrontLightModelProduct") {
        for (field, default) in MATERIAL_FIELDS {
            let (min, max, help) = match *field {
                "shininess" => (0.0, 128.0, "GL material shininess (0..128)"),
                _ => (-BIG, BIG, "GL material colour (RGBA)"),
            };
            out.push(ParamSpec::real(
                intern(&format!("gl_FrontMaterial.{field}")),
                default,
                min,
                max,
                help,
            ));
        }
    }
    out
}

/// The matrices of the scene in GL's conventions (depth -1..1: the translation converts
/// `gl_Position` once, so the shader sees GL's own matrices).
#[derive(Clone, Copy, Debug)]
pub struct Scene {
    /// `gl_ModelViewMatrix`.
    pub modelview: Mat4,
    /// `gl_ProjectionMatrix`.
    pub projection: Mat4,
}

fn v4(p: &Params, name: &str, default: [f32; 4]) -> [f32; 4] {
    if p.has(name) {
        p.v4(name)
    } else {
        default
    }
}

fn f1(p: &Params, name: &str, default: f32) -> f32 {
    if p.has(name) {
        p.f(name)
    } else {
        default
    }
}

fn mul3(a: [f32; 4], b: [f32; 4]) -> Vec<f32> {
    vec![a[0] * b[0], a[1] * b[1], a[2] * b[2]]
}

/// The values of the state block's leaves, by their GLSL path (`gl_LightSource[0].halfVector`),
/// for the members the shaders use.
pub fn values(used: &[&str], lights: usize, params: &Params, scene: &Scene) -> HashMap<String, Vec<f32>> {
    let mut out: HashMap<String, Vec<f32>> = HashMap::new();
    let mat4 = |m: Mat4| m.to_cols_array().to_vec();
    let mv = scene.modelview;
    let p = scene.projection;
    let mvp = p * mv;
    for name in used {
        let m = match *name {
            "gl_ModelViewMatrix" => mv,
            "gl_ProjectionMatrix" => p,
            "gl_ModelViewProjectionMatrix" => mvp,
            "gl_ModelViewMatrixInverse" => mv.inverse(),
            "gl_ProjectionMatrixInverse" => p.inverse(),
            "gl_ModelViewProjectionMatrixInverse" => mvp.inverse(),
            "gl_ModelViewMatrixTranspose" => mv.transpose(),
            "gl_ProjectionMatrixTranspose" => p.transpose(),
            "gl_ModelViewProjectionMatrixTranspose" => mvp.transpose(),
            "gl_ModelViewMatrixInverseTranspose" => mv.inverse().transpose(),
            "gl_ProjectionMatrixInverseTranspose" => p.inverse().transpose(),
            "gl_ModelViewProjectionMatrixInverseTranspose" => mvp.inverse().transpose(),
            _ => continue,
        };
        out.insert((*name).to_owned(), mat4(m));
    }
    if used.contains(&"gl_NormalMatrix") {
        let n: Mat3 = crate::camera::normal_matrix(mv);
        out.insert("gl_NormalMatrix".into(), n.to_cols_array().to_vec());
    }
    if used.contains(&"gl_Color") {
        out.insert("gl_Color".into(), v4(params, "gl_Color", [1.0; 4]).to_vec());
    }
    out.insert("gl_DepthRange.near".into(), vec![0.0]);
    out.insert("gl_DepthRange.far".into(), vec![1.0]);
    out.insert("gl_DepthRange.diff".into(), vec![1.0]);

    let material = |field: &str, default: [f32; 4]| v4(params, &format!("gl_FrontMaterial.{field}"), default);
    let m_ambient = material("ambient", [0.2, 0.2, 0.2, 1.0]);
    let m_diffuse = material("diffuse", [0.8, 0.8, 0.8, 1.0]);
    let m_specular = material("specular", [0.0, 0.0, 0.0, 1.0]);
    let m_emission = material("emission", [0.0, 0.0, 0.0, 1.0]);
    let shininess = f1(params, "gl_FrontMaterial.shininess", 0.0);
    for (field, v) in [
        ("ambient", m_ambient),
        ("diffuse", m_diffuse),
        ("specular", m_specular),
        ("emission", m_emission),
    ] {
        out.insert(format!("gl_FrontMaterial.{field}"), v.to_vec());
    }
    out.insert("gl_FrontMaterial.shininess".into(), vec![shininess]);
    let model_ambient = v4(params, "gl_LightModel.ambient", [0.2, 0.2, 0.2, 1.0]);
    out.insert("gl_LightModel.ambient".into(), model_ambient.to_vec());
    // Mesa: sceneColor = emission + ambient * model ambient, alpha = the material's diffuse alpha.
    let mut scene_color = mul3(m_ambient, model_ambient);
    for (c, e) in scene_color.iter_mut().zip(m_emission) {
        *c += e;
    }
    scene_color.push(m_diffuse[3]);
    out.insert("gl_FrontLightModelProduct.sceneColor".into(), scene_color);

    for i in 0..lights.max(1) {
        let key = |field: &str| format!("gl_LightSource[{i}].{field}");
        let white_if_first = if i == 0 { [1.0; 4] } else { [0.0, 0.0, 0.0, 1.0] };
        let ambient = v4(params, &key("ambient"), [0.0, 0.0, 0.0, 1.0]);
        let diffuse = v4(params, &key("diffuse"), white_if_first);
        let specular = v4(params, &key("specular"), white_if_first);
        let position = v4(params, &key("position"), [0.0, 0.0, 1.0, 0.0]);
        let spot = if params.has(&key("spotDirection")) {
            params.v3(&key("spotDirection"))
        } else {
            [0.0, 0.0, -1.0]
        };
        let cutoff = f1(params, &key("spotCutoff"), 180.0);
        // Mesa: halfVector = normalize(normalize(position.xyz) + (0, 0, 1)), w = 1.
        let dir = Vec3::new(position[0], position[1], position[2]).normalize_or_zero();
        let half = (dir + Vec3::Z).normalize_or_zero();
        let cos_cutoff = if cutoff == 180.0 {
            -1.0
        } else {
            (cutoff as f64).to_radians().cos() as f32
        };
        for (field, v) in [
            ("ambient", ambient.to_vec()),
            ("diffuse", diffuse.to_vec()),
            ("specular", specular.to_vec()),
            ("position", position.to_vec()),
            ("halfVector", vec![half.x, half.y, half.z, 1.0]),
            ("spotDirection", spot.to_vec()),
            ("spotExponent", vec![f1(params, &key("spotExponent"), 0.0)]),
            ("spotCutoff", vec![cutoff]),
            ("spotCosCutoff", vec![cos_cutoff]),
            (
                "constantAttenuation",
                vec![f1(params, &key("constantAttenuation"), 1.0)],
            ),
            ("linearAttenuation", vec![f1(params, &key("linearAttenuation"), 0.0)]),
            (
                "quadraticAttenuation",
                vec![f1(params, &key("quadraticAttenuation"), 0.0)],
            ),
        ] {
            out.insert(key(field), v);
        }
        // Mesa: light products are the component-wise products, alpha = the material's.
        for (field, l, m) in [
            ("ambient", ambient, m_ambient),
            ("diffuse", diffuse, m_diffuse),
            ("specular", specular, m_specular),
        ] {
            let mut v = mul3(l, m);
            v.push(m[3]);
            out.insert(format!("gl_FrontLightProduct[{i}].{field}"), v);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn products_follow_mesa() {
        let mut p = Params::new(&params(
            &["gl_LightSource", "gl_FrontLightProduct", "gl_FrontMaterial"],
            1,
        ));
        p.set_str("gl_LightSource[0].ambient", "0.2,0.2,0.2,1").unwrap();
        p.set_str("gl_FrontMaterial.ambient", "0.2,0.3,0.8,1").unwrap();
        p.set_str("gl_LightSource[0].position", "2,2,2,1").unwrap();
        let scene = Scene {
            modelview: Mat4::IDENTITY,
            projection: Mat4::IDENTITY,
        };
        let v = values(&["gl_LightSource"], 1, &p, &scene);
        let amb = &v["gl_FrontLightProduct[0].ambient"];
        assert!((amb[0] - 0.04).abs() < 1e-6 && (amb[1] - 0.06).abs() < 1e-6 && (amb[2] - 0.16).abs() < 1e-6);
        assert_eq!(amb[3], 1.0);
        assert_eq!(v["gl_LightSource[0].spotCosCutoff"], vec![-1.0]);
        let h = &v["gl_LightSource[0].halfVector"];
        let d = 1.0 / 3f32.sqrt();
        let expect = Vec3::new(d, d, d + 1.0).normalize();
        assert!((h[2] - expect.z).abs() < 1e-6 && h[3] == 1.0);
        assert!(p.has("gl_LightSource[0].quadraticAttenuation"));
        assert!(!p.has("gl_LightSource[1].ambient"));
    }
}
