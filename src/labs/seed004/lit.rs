//! The shading models of seed 004 (4.7 flat, 4.8 Gouraud, 4.9 Phong): one light in eye space,
//! ambient + diffuse + specular (R·V) with white light, clamped. Flat runs the Gouraud shaders
//! with `flat` interpolation on the face-normal VBO (each triangle lit at its first vertex);
//! Gouraud and Phong draw the vertex-normal VBO. Each exercise starts with its own model; keys
//! `1`/`2`/`3` switch between the three, as in the course's program.
//!
//! Keys: `a`/`A` ka ∓/±0.05; `r`/`R`, `g`/`G`, `b`/`B` Kd channels ∓/±0.05; `s`/`S` ks ∓/±0.05
//! (all within [0, 1]); `h`/`H` shininess ∓/±4 within [1, 256]; ←/→ lightx ∓/±0.25, ↑/↓ lighty
//! ±/∓0.25, PageUp/PageDown lightz ±/∓0.25; `1`/`2`/`3` flat/Gouraud/Phong; left drag rotates.

use crate::error::Result;
use crate::geometry::obj::ObjCorner;
use crate::lab::{Input, Lab, LabContext, LabInfo, Special};
use crate::params::{ParamSpec, Params};
use crate::render::{Frame, Load, Program, RenderState, Uniforms};

use crate::labs::seed004::stage::{Normals, SuzanneStage, ANGLES};

/// The `Light` block of `suzanne_light.glsl` (std140: `lightpos` and `shininess` share 16 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct SuzanneLight {
    /// `Ka` = (ka, ka, ka, 1).
    pub ka: [f32; 4],
    /// `Kd` = (kdr, kdg, kdb, 1).
    pub kd: [f32; 4],
    /// `Ks` = (ks, ks, ks, 1).
    pub ks: [f32; 4],
    /// `lightpos`, eye space.
    pub lightpos: [f32; 3],
    /// `shininess`.
    pub shininess: f32,
}
crate::uniform_block!(SuzanneLight, "Light", {
    ka: "Ka",
    kd: "Kd",
    ks: "Ks",
    lightpos: "lightpos",
    shininess: "shininess",
});

impl SuzanneLight {
    /// The block for the current parameters.
    pub fn of(p: &Params) -> Self {
        let (ka, ks) = (p.f("ka"), p.f("ks"));
        SuzanneLight {
            ka: [ka, ka, ka, 1.0],
            kd: [p.f("kdr"), p.f("kdg"), p.f("kdb"), 1.0],
            ks: [ks, ks, ks, 1.0],
            lightpos: [p.f("lightx"), p.f("lighty"), p.f("lightz")],
            shininess: p.f("shininess"),
        }
    }
}

/// The shading models in key order (`1`, `2`, `3`): name, shaders, VBO.
pub const MODELS: [(&str, &str, &str, Normals); 3] = [
    ("flat", "suzanne_flat.vert", "suzanne_flat.frag", Normals::Face),
    (
        "gouraud",
        "suzanne_gouraud.vert",
        "suzanne_gouraud.frag",
        Normals::Vertex,
    ),
    ("phong", "suzanne_phong.vert", "suzanne_phong.frag", Normals::Vertex),
];

/// Names of [`MODELS`], for the `shading` choice.
pub const SHADINGS: &[&str] = &["flat", "gouraud", "phong"];

/// The keys, for `--help`.
pub const KEYS: &str = "a/A: ka -/+0.05; r/R g/G b/B: Kd channels -/+0.05; s/S: ks -/+0.05; h/H: shininess -/+4;\n\
                        Left/Right: light x -/+0.25; Up/Down: light y +/-0.25; PageUp/PageDown: light z +/-0.25;\n\
                        1/2/3: flat/Gouraud/Phong; left drag rotates (0.5 degrees per pixel)";

/// Bound on the light's coordinates.
const REACH: f64 = 50.0;

/// The lighting parameters (SPEC §4.7's pinned defaults).
pub const LIGHT: &[ParamSpec] = &[
    ParamSpec::real("ka", &[0.2], 0.0, 1.0, "ambient Ka = (ka, ka, ka, 1) (a/A)"),
    ParamSpec::real("kdr", &[0.8], 0.0, 1.0, "diffuse Kd red (r/R)"),
    ParamSpec::real("kdg", &[0.5], 0.0, 1.0, "diffuse Kd green (g/G)"),
    ParamSpec::real("kdb", &[0.2], 0.0, 1.0, "diffuse Kd blue (b/B)"),
    ParamSpec::real("ks", &[0.8], 0.0, 1.0, "specular Ks = (ks, ks, ks, 1) (s/S)"),
    ParamSpec::real("shininess", &[32.0], 1.0, 256.0, "specular exponent (h/H)"),
    ParamSpec::real("lightx", &[2.0], -REACH, REACH, "light x, eye space (←/→)"),
    ParamSpec::real("lighty", &[2.0], -REACH, REACH, "light y, eye space (↑/↓)"),
    ParamSpec::real("lightz", &[2.0], -REACH, REACH, "light z, eye space (PageUp/PageDown)"),
];

/// The parameters of an exercise whose `shading` spec gives its own model as the default.
pub fn params(shading: &'static [ParamSpec]) -> Params {
    let mut p = Params::new(LIGHT);
    p.extend(ANGLES);
    p.extend(shading);
    p
}

/// What distinguishes one shading exercise.
pub struct Lit {
    /// Name and title.
    pub info: &'static LabInfo,
    /// Its parameters (the `shading` default is its own model).
    pub params: fn() -> Params,
}

struct LitSuzanne {
    lit: &'static Lit,
    params: Params,
    stage: SuzanneStage,
    light: Uniforms<SuzanneLight>,
    programs: Vec<Program<ObjCorner>>,
}

/// Builds the exercise with all three models (keys switch between them without a pause).
pub fn new(cx: &LabContext, lit: &'static Lit) -> Result<Box<dyn Lab>> {
    let name = lit.info.name;
    let stage = SuzanneStage::new(cx, name);
    let params = (lit.params)();
    let light = Uniforms::new(cx.gpu, &format!("{name}.light"), SuzanneLight::of(&params));
    let programs = MODELS
        .iter()
        .map(|(model, vert, frag, _)| {
            let mut program = Program::new(cx, &format!("{name}.{model}"), vert, frag, RenderState::default())?;
            program.bind(cx.gpu, vec![stage.matrices.bind(), light.bind()])?;
            Ok(program)
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(Box::new(LitSuzanne {
        lit,
        params,
        stage,
        light,
        programs,
    }))
}

impl Lab for LitSuzanne {
    fn info(&self) -> &'static LabInfo {
        self.lit.info
    }
    fn params(&self) -> &Params {
        &self.params
    }
    fn params_mut(&mut self) -> &mut Params {
        &mut self.params
    }
    fn input(&mut self, input: Input) -> bool {
        let p = &mut self.params;
        let (name, delta) = match input {
            Input::Key(c @ '1'..='3') => {
                p.put("shading", &[f64::from(c as u8 - b'1')]);
                return true;
            }
            Input::Key('a') => ("ka", -0.05),
            Input::Key('A') => ("ka", 0.05),
            Input::Key('r') => ("kdr", -0.05),
            Input::Key('R') => ("kdr", 0.05),
            Input::Key('g') => ("kdg", -0.05),
            Input::Key('G') => ("kdg", 0.05),
            Input::Key('b') => ("kdb", -0.05),
            Input::Key('B') => ("kdb", 0.05),
            Input::Key('s') => ("ks", -0.05),
            Input::Key('S') => ("ks", 0.05),
            Input::Key('h') => ("shininess", -4.0),
            Input::Key('H') => ("shininess", 4.0),
            Input::Special(Special::Left) => ("lightx", -0.25),
            Input::Special(Special::Right) => ("lightx", 0.25),
            Input::Special(Special::Up) => ("lighty", 0.25),
            Input::Special(Special::Down) => ("lighty", -0.25),
            Input::Special(Special::PageUp) => ("lightz", 0.25),
            Input::Special(Special::PageDown) => ("lightz", -0.25),
            _ => return self.stage.input(p, input),
        };
        p.step(name, delta);
        true
    }
    fn reload(&mut self, cx: &LabContext) -> Result<()> {
        for program in &mut self.programs {
            program.reload(cx)?;
        }
        Ok(())
    }
    fn render(&mut self, frame: &mut Frame<'_>) -> Result<()> {
        let model = self.params.index_of("shading").min(MODELS.len() - 1);
        let (_, _, _, normals) = MODELS[model];
        self.stage.upload(frame.gpu, &self.params, frame.aspect());
        self.light.value = SuzanneLight::of(&self.params);
        self.light.upload(frame.gpu);
        let mut pass = frame.pass(self.lit.info.name, Load::Clear([0.0; 3]));
        self.programs[model].draw(&mut pass, self.stage.mesh(normals));
        Ok(())
    }
}
