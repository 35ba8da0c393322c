//! Seed 001 `toon` (SPEC §1.6): the course's non-photorealistic shading. Per vertex, yellow
//! where the light meets the surface within 60° (`dot(L, N) > 0.5`), red elsewhere, black where
//! the surface is seen edge on (`|dot(E, N)| < 0.1`); the colours blend across triangles, and
//! the black silhouette appears only at vertices that fall in the band (course behaviour).
//! Light (2, 2, 2) in eye space.
//!
//! Keys: light keys (`←→↑↓`, PageUp/PageDown; `h`/`H` shininess, unused here); `1`-`4` objects;
//! left drag rotates.

use glam::Vec3;

use crate::error::Result;
use crate::lab::{FilesTaken, Input, Lab, LabContext, LabEntry, LabInfo};
use crate::mesh::Vertex;
use crate::params::Params;
use crate::render::{Frame, Load, Program, RenderState};

use crate::labs::seed001::gl_light::{GlLight, COURSE};
use crate::labs::seed001::stage::{Solids, UstcStage, OBJECT, ROTATION};

/// Seed 001, §1.6.
pub static INFO: LabInfo = LabInfo {
    name: "toon",
    title: "ref001",
    label: "toon shading",
    lecture: "001 USTC GLSL (III)",
    size: (512, 512),
    keys: crate::lab::Keys::text(
        "←/→ ↑/↓ PageUp/PageDown: light ±0.25; h/H: shininess ∓5; 1-4: objects; left drag rotates",
    ),
    files: FilesTaken::NONE,
};

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params,
    new,
};

fn params() -> Params {
    let mut p = Params::new(OBJECT);
    p.extend(ROTATION);
    p.extend(COURSE.params);
    p
}

struct Toon {
    params: Params,
    stage: UstcStage,
    light: GlLight,
    program: Program<Vertex>,
    solids: Solids,
}

fn new(cx: &LabContext) -> Result<Box<dyn Lab>> {
    let stage = UstcStage::new(cx.gpu, "toon", Vec3::new(0.0, 0.0, 4.0));
    let light = GlLight::new(cx.gpu, "toon", &COURSE);
    let mut program = Program::new(cx, "toon", "toon.vert", "pass_color.frag", RenderState::default())?;
    program.bind(cx.gpu, vec![stage.transform.bind(), light.uniforms.bind()])?;
    Ok(Box::new(Toon {
        params: params(),
        stage,
        light,
        program,
        solids: Solids::default(),
    }))
}

impl Lab for Toon {
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
        self.light.input(&mut self.params, input) || self.stage.input(&mut self.params, input)
    }
    fn reload(&mut self, cx: &LabContext) -> Result<()> {
        self.program.reload(cx)
    }
    fn render(&mut self, frame: &mut Frame<'_>) -> Result<()> {
        let gpu = frame.gpu;
        self.light.upload(gpu, &self.params);
        self.stage.upload(gpu, &self.params, frame.width, frame.height);
        let mesh = self.solids.get(gpu, UstcStage::object(&self.params));
        let mut pass = frame.pass("toon", Load::Clear([0.0; 3]));
        self.program.draw(&mut pass, mesh);
        Ok(())
    }
}
