//! Exercise 3, Phong per-pixel lighting (`Lab05-3`): an orange object lit by one point light
//! given in eye space, `Ka*ambient + Kd*diffuse*max(N·L,0) + Ks*specular*pow(max(R·E,0), shininess)`
//! with `R = normalize(-reflect(L, N))`, on a dark blue background. The light is drawn as a small
//! white sphere (visible once it is in front of the camera).
//!
//! Keys: `W/A/S/D` move the camera by 0.1 (and the eye-space light the opposite way, so it stays
//! put in the world); `X/Y/Z` +0.1 and `x/y/z` -0.1 on the light; `<`/`>` Ka ∓0.05; `[`/`]` Kd
//! ∓0.05; `{`/`}` Ks ∓0.05; `H`/`h` shininess ±1 within [6, 200]; `R/G/B` +0.01 and `r/g/b`
//! -0.01 on the diffuse colour; `m` cycles the shading model (flat, Gouraud, Phong, Blinn-Phong;
//! a port addition, the original has Phong only; a model whose shader is broken is skipped with
//! its error shown). Coefficients and colours clamp to [0, 1]; the light and camera coordinates
//! to [-50, 50].

use std::collections::HashMap;

use glam::{Mat4, Vec3};

use crate::course::common::FaceOrder;
use crate::error::{Error, Result};
use crate::lab::{BuildContext, Input, Key::C, KeyRow, Keys, Lab, LabEntry, LabInfo};
use crate::mesh::tess::Object;
use crate::mesh::{Mesh, Vertex};
use crate::params::{ParamSpec, Params};
use crate::render::{AnyProgram, Derived, Frame, GpuMesh, Load, ParamBlock, Program, RenderState, Uniforms};
use crate::shader::ShaderSource;

use crate::course::common::TransformUniforms;
use crate::course::seed000::geometry::{title_000, GeometryConfig, GlutGeometry, PARAMS_000};

/// Exercise 3.
pub static INFO: LabInfo = super::info(
    lab_name!(),
    "Lab05-3",
    "Phong",
    Keys::rows(
        KEYS,
        "W/A/S/D: camera ±0.1 (light stays put); 1-4: objects; left drag rotates",
    ),
);

/// The face order by object ([`GlutGeometry::face_order`](super::geometry::GlutGeometry::face_order)):
/// the torus and the teapot facing the eye first, which draws the same pixels and shades fewer fragments;
/// the other objects in mesh order, where no order measured faster (figures: `docs/speed.md`,
/// "Face orders").
const AUTO: &[(Object, FaceOrder)] = &[
    (Object::Torus, FaceOrder::FacingFirst),
    (Object::Teapot, FaceOrder::FacingFirst),
];

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params,
    new,
};

/// Bound on light and camera coordinates.
const REACH: f64 = 50.0;

/// The keys on one parameter each (W/A/S/D move two: [`Phong::walk`]). Coefficients and
/// colours within [0, 1], shininess within [6, 200], the light within ±50.
const KEYS: &[KeyRow] = &[
    KeyRow::channel(&[C('x'), C('X')], "lightPosition", 0, 0.1, -REACH, REACH),
    KeyRow::channel(&[C('y'), C('Y')], "lightPosition", 1, 0.1, -REACH, REACH),
    KeyRow::channel(&[C('z'), C('Z')], "lightPosition", 2, 0.1, -REACH, REACH),
    KeyRow::clamped(&[C('<'), C('>')], "Ka", 0.05, 0.0, 1.0),
    KeyRow::clamped(&[C('['), C(']')], "Kd", 0.05, 0.0, 1.0),
    KeyRow::clamped(&[C('{'), C('}')], "Ks", 0.05, 0.0, 1.0),
    KeyRow::clamped(&[C('h'), C('H')], "shininess", 1.0, 6.0, 200.0),
    KeyRow::channel(&[C('r'), C('R')], "diffuseColor", 0, 0.01, 0.0, 1.0),
    KeyRow::channel(&[C('g'), C('G')], "diffuseColor", 1, 0.01, 0.0, 1.0),
    KeyRow::channel(&[C('b'), C('B')], "diffuseColor", 2, 0.01, 0.0, 1.0),
    KeyRow::cycle(&[C('m')], "shading"),
];

/// The shading models, in the order key `m` cycles through them, with their shader files.
const MODELS: [(&str, &str, &str); 4] = [
    ("flat", "phong.vert", "phong_flat.frag"),
    ("gouraud", "phong_gouraud.vert", "phong_gouraud.frag"),
    ("phong", "phong.vert", "phong.frag"),
    ("blinn", "phong.vert", "phong_blinn.frag"),
];
const PHONG: usize = 2;

/// `--set` takes any finite value, as the original's uniforms do (the "where methods fail"
/// studies set values far outside what the keys reach); the keys clamp.
const ANY: f64 = f32::MAX as f64;

const OWN: &[ParamSpec] = &[
    ParamSpec::real(
        "lightPosition",
        &[0.0, 1.0, 1.0],
        -ANY,
        ANY,
        "light, eye space (X/Y/Z x/y/z, ±50)",
    ),
    ParamSpec::real("Ka", &[0.1], -ANY, ANY, "ambient coefficient (< >, keys within 0..1)"),
    ParamSpec::real("ambientColor", &[0.1, 0.1, 0.1], -ANY, ANY, "ambient colour"),
    ParamSpec::real("Kd", &[1.0], -ANY, ANY, "diffuse coefficient ([ ], keys within 0..1)"),
    ParamSpec::real(
        "diffuseColor",
        &[1.0, 0.5, 0.0],
        -ANY,
        ANY,
        "diffuse colour (R/G/B r/g/b, keys within 0..1)",
    ),
    ParamSpec::real("Ks", &[1.0], -ANY, ANY, "specular coefficient ({ }, keys within 0..1)"),
    ParamSpec::real("specularColor", &[1.0, 1.0, 1.0], -ANY, ANY, "specular colour"),
    ParamSpec::real(
        "shininess",
        &[32.0],
        -ANY,
        ANY,
        "specular exponent (H/h, keys within 6..200)",
    ),
    ParamSpec::real(
        "camera",
        &[0.0, 0.0, 5.0],
        -ANY,
        ANY,
        "eye position; the view looks down -z (W/A/S/D, ±50)",
    ),
    ParamSpec::choice(
        "shading",
        &[PHONG as f64],
        &["flat", "gouraud", "phong", "blinn"],
        "port: shading model (m)",
    ),
];

fn params() -> Params {
    let mut p = Params::new(OWN);
    p.extend(PARAMS_000);
    p
}

struct Phong {
    params: Params,
    geometry: GlutGeometry,
    /// The `PhongParams` block, filled by name from the parameters.
    uniforms: ParamBlock,
    models: HashMap<usize, Program<Vertex>>,
    /// The model drawn last (the fallback while a chosen one does not build).
    drawn: usize,
    /// Whether the model was chosen by key `m`, which skips broken models.
    cycling: bool,
    error: Option<Error>,
    /// Where the models' shaders come from (updated by live reload).
    source: ShaderSource,
    format: wgpu::TextureFormat,
    marker: Program<Vertex>,
    marker_transform: Uniforms<TransformUniforms>,
    marker_mesh: GpuMesh<Vertex>,
}

fn program_of(cx: &BuildContext, model: usize) -> Result<Program<Vertex>> {
    let (name, vert, frag) = MODELS[model];
    Program::new(cx, &format!("phong.{name}"), vert, frag, RenderState::default())
}

fn build_model(
    cx: &BuildContext,
    geometry: &GlutGeometry,
    uniforms: &ParamBlock,
    model: usize,
) -> Result<Program<Vertex>> {
    let mut program = program_of(cx, model)?;
    program.bind(cx.gpu, vec![geometry.transform.bind(), uniforms.bind()])?;
    Ok(program)
}

fn new(cx: &BuildContext) -> Result<Box<dyn Lab>> {
    let geometry = GlutGeometry::new(
        cx.gpu,
        "phong",
        GeometryConfig {
            perspective: (45.0, 1.0, 100.0),
            eye: Vec3::new(0.0, 0.0, 5.0),
        },
    );
    let p = params();
    // Every member of `PhongParams` is the parameter of its name.
    let mut model = program_of(cx, PHONG)?;
    let layout = model
        .block("PhongParams")
        .ok_or_else(|| Error::Binding(format!("{} declares no PhongParams block", MODELS[PHONG].2)))?;
    let uniforms = ParamBlock::new(cx.gpu, "phong.params", layout, &p, &Derived::default())?;
    model.bind(cx.gpu, vec![geometry.transform.bind(), uniforms.bind()])?;
    let marker_transform = Uniforms::new(
        cx.gpu,
        "light_marker.transform",
        TransformUniforms::new(Mat4::IDENTITY, Mat4::IDENTITY),
    );
    let mut marker = Program::new(
        cx,
        "light_marker",
        "light_marker.vert",
        "light_marker.frag",
        RenderState::default(),
    )?;
    marker.bind(cx.gpu, vec![marker_transform.bind()])?;
    let sphere = Mesh::sphere(0.05, 4, 4);
    let marker_mesh = GpuMesh::new(cx.gpu, "mesh.light_marker", &sphere.vertices, Some(&sphere.indices));
    Ok(Box::new(Phong {
        params: p,
        geometry,
        uniforms,
        models: HashMap::from([(PHONG, model)]),
        drawn: PHONG,
        cycling: false,
        error: None,
        source: cx.source.clone(),
        format: cx.format,
        marker,
        marker_transform,
        marker_mesh,
    }))
}

impl Phong {
    /// Moves the camera by (dx, dz) and the eye-space light the opposite way.
    fn walk(&mut self, dx: f64, dz: f64) {
        let p = &mut self.params;
        p.step_clamped("camera", 0, dx, -REACH, REACH);
        p.step_clamped("camera", 2, dz, -REACH, REACH);
        p.step_clamped("lightPosition", 0, -dx, -REACH, REACH);
        p.step_clamped("lightPosition", 2, -dz, -REACH, REACH);
    }

    /// Builds the chosen model if needed. A model that does not build is skipped when key `m`
    /// chose it, and otherwise falls back to the model drawn last; the error is kept for the
    /// window to show.
    fn ensure_model(&mut self, cx: &BuildContext) {
        for _ in 0..MODELS.len() {
            let want = self.params.index_of("shading");
            if self.models.contains_key(&want) {
                break;
            }
            match build_model(cx, &self.geometry, &self.uniforms, want) {
                Ok(program) => {
                    self.models.insert(want, program);
                    break;
                }
                Err(e) => {
                    self.error = Some(e);
                    if self.cycling {
                        self.params.cycle("shading");
                    } else {
                        self.params.set_unchecked("shading", &[self.drawn as f64]);
                        break;
                    }
                }
            }
        }
        if !self.models.contains_key(&self.params.index_of("shading")) {
            self.params.set_unchecked("shading", &[self.drawn as f64]);
        }
        self.cycling = false;
    }
}

impl Lab for Phong {
    fn info(&self) -> &'static LabInfo {
        &INFO
    }
    fn params(&self) -> &Params {
        &self.params
    }
    fn params_mut(&mut self) -> &mut Params {
        &mut self.params
    }
    fn input(&mut self, input: Input) -> bool {
        match input {
            Input::Key('a' | 'A') => self.walk(-0.1, 0.0),
            Input::Key('d' | 'D') => self.walk(0.1, 0.0),
            Input::Key('w' | 'W') => self.walk(0.0, -0.1),
            Input::Key('s' | 'S') => self.walk(0.0, 0.1),
            _ if INFO.keys.apply(&mut self.params, input) => {
                // Key `m` skips models that do not build ([`Phong::ensure_model`]).
                if input == Input::Key('m') {
                    self.cycling = true;
                }
            }
            _ => return self.geometry.input(&mut self.params, input),
        }
        true
    }
    fn title(&self) -> String {
        let p = &self.params;
        // Keys step in f32, so +0.1 then -0.1 can leave -0.00000001: show it as 0.0, not -0.0.
        let [lx, ly, lz] = p.v3("lightPosition").map(|c| if c.abs() < 0.05 { 0.0 } else { c });
        let [r, g, b] = p.v3("diffuseColor");
        let summary = format!(
            "light ({lx:.1},{ly:.1},{lz:.1}) Ka {:.2} Kd {:.2} Ks {:.2} shininess {:.0} diffuse ({r:.2},{g:.2},{b:.2})",
            p.f("Ka"),
            p.f("Kd"),
            p.f("Ks"),
            p.f("shininess")
        );
        title_000(&INFO, p, &summary, &format!(" | shading {} (m)", p.text("shading")))
    }
    fn reload(&mut self, cx: &BuildContext) -> Result<()> {
        self.source = cx.source.clone();
        for program in self.models.values_mut() {
            program.reload(cx)?;
        }
        self.marker.reload(cx)
    }
    fn programs(&mut self) -> Vec<&mut dyn AnyProgram> {
        let mut out: Vec<&mut dyn AnyProgram> = Vec::new();
        for program in self.models.values_mut() {
            out.push(program);
        }
        out.push(&mut self.marker);
        out
    }
    fn take_error(&mut self) -> Option<Error> {
        self.error.take()
    }
    fn render(&mut self, frame: &mut Frame<'_>) -> Result<()> {
        let gpu = frame.gpu;
        if self.models.contains_key(&self.params.index_of("shading")) {
            self.cycling = false;
        } else {
            // Only when a model is still to be built (the context borrows the source).
            let source = self.source.clone();
            self.ensure_model(&BuildContext::new(gpu, &source, self.format, &crate::lab::NO_FILES));
        }
        self.drawn = self.params.index_of("shading");
        self.uniforms.fill(&self.params, &Derived::default())?;
        self.uniforms.upload(gpu);
        // The original's gluLookAt uses camera.x and camera.z only.
        let [x, _, z] = self.params.v3("camera");
        self.geometry.eye = Vec3::new(x, 0.0, z);
        let faithful = self.drawn == PHONG;
        let faces = GlutGeometry::culling(&self.params, AUTO);
        let order = GlutGeometry::face_order(&self.params, AUTO);
        if let Some(program) = self.models.get_mut(&self.drawn) {
            program.set_culling(gpu, faces)?;
        }
        // Drawn with the modelview reset: glLoadIdentity(); glTranslatef(light).
        let light = Vec3::from_array(self.params.v3("lightPosition"));
        self.marker_transform.value = TransformUniforms::new(
            Mat4::from_translation(light),
            self.geometry.projection(frame.width, frame.height),
        );
        self.marker_transform.upload(gpu);
        let mesh = self
            .geometry
            .prepare(gpu, &self.params, frame.width, frame.height, faithful, false, order);
        let mut pass = frame.pass("phong", Load::Clear([0.05, 0.1, 0.2]));
        self.marker.draw(&mut pass, &self.marker_mesh);
        self.models[&self.drawn].draw(&mut pass, mesh);
        Ok(())
    }
}
