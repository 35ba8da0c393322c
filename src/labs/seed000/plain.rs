//! A GLUT stage drawn by one program with no uniforms of its own: exercises 1 and 2 of seed 000,
//! which differ only in their shaders.

use crate::error::Result;
use crate::lab::{Input, Lab, LabContext, LabInfo};
use crate::mesh::Vertex;
use crate::params::Params;
use crate::render::{AnyProgram, Frame, Load, Program, RenderState};
use crate::tess::Object;

use crate::labs::seed000::stage::{title_000, GlutStage, StageConfig, PARAMS_000};
use glam::Vec3;

/// What distinguishes one such exercise.
pub struct Plain {
    /// Name and title.
    pub info: &'static LabInfo,
    /// Vertex shader file.
    pub vert: &'static str,
    /// Fragment shader file.
    pub frag: &'static str,
    /// The objects drawn outside faces first (measured faster; same pixels), see
    /// [`GlutStage::faces`].
    pub split: &'static [Object],
}

/// The stage's parameters.
pub fn params() -> Params {
    Params::new(PARAMS_000)
}

struct PlainLab {
    info: &'static LabInfo,
    split: &'static [Object],
    params: Params,
    stage: GlutStage,
    program: Program<Vertex>,
}

/// Builds the exercise.
pub fn new(cx: &LabContext, plain: &Plain) -> Result<Box<dyn Lab>> {
    let name = plain.info.name;
    let stage = GlutStage::new(
        cx.gpu,
        name,
        StageConfig {
            perspective: (45.0, 1.0, 100.0),
            eye: Vec3::new(0.0, 0.0, 4.0),
        },
    );
    let mut program = Program::new(cx, name, plain.vert, plain.frag, RenderState::default())?;
    program.bind(cx.gpu, vec![stage.transform.bind()])?;
    Ok(Box::new(PlainLab {
        info: plain.info,
        split: plain.split,
        params: params(),
        stage,
        program,
    }))
}

impl Lab for PlainLab {
    fn info(&self) -> &'static LabInfo {
        self.info
    }
    fn params(&self) -> &Params {
        &self.params
    }
    fn params_mut(&mut self) -> &mut Params {
        &mut self.params
    }
    fn input(&mut self, input: Input) -> bool {
        self.stage.input(&mut self.params, input)
    }
    fn programs(&mut self) -> Vec<&mut dyn AnyProgram> {
        vec![&mut self.program]
    }
    fn title(&self) -> String {
        title_000(self.info, &self.params, "drag to rotate, 1-4 objects", "")
    }
    fn reload(&mut self, cx: &LabContext) -> Result<()> {
        self.program.reload(cx)
    }
    fn render(&mut self, frame: &mut Frame<'_>) -> Result<()> {
        self.program
            .set_faces(frame.gpu, GlutStage::faces(&self.params, self.split))?;
        let mesh = self
            .stage
            .prepare(frame.gpu, &self.params, frame.width, frame.height, true, false);
        let mut pass = frame.pass(self.info.name, Load::Clear([0.0; 3]));
        self.program.draw(&mut pass, mesh);
        Ok(())
    }
}
