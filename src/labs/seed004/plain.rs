//! A seed-004 exercise drawn by one program with no uniforms but the matrices: 4.1, 4.2 and
//! 4.3, which differ only in their shaders and in which normals they draw.

use crate::error::Result;
use crate::geometry::obj::ObjCorner;
use crate::lab::{Input, Lab, LabContext, LabInfo};
use crate::params::Params;
use crate::render::{Frame, Load, Program, RenderState};

use crate::labs::seed004::stage::{Normals, SuzanneStage, ANGLES};

/// What distinguishes one such exercise.
pub struct Plain {
    /// Name and title.
    pub info: &'static LabInfo,
    /// Vertex shader file.
    pub vert: &'static str,
    /// Fragment shader file.
    pub frag: &'static str,
    /// The VBO it draws.
    pub normals: Normals,
}

/// The stage's parameters.
pub fn params() -> Params {
    Params::new(ANGLES)
}

struct PlainSuzanne {
    plain: &'static Plain,
    params: Params,
    stage: SuzanneStage,
    program: Program<ObjCorner>,
}

/// Builds the exercise.
pub fn new(cx: &LabContext, plain: &'static Plain) -> Result<Box<dyn Lab>> {
    let name = plain.info.name;
    let stage = SuzanneStage::new(cx, name);
    let mut program = Program::new(cx, name, plain.vert, plain.frag, RenderState::default())?;
    program.bind(cx.gpu, vec![stage.matrices.bind()])?;
    Ok(Box::new(PlainSuzanne {
        plain,
        params: params(),
        stage,
        program,
    }))
}

impl Lab for PlainSuzanne {
    fn info(&self) -> &'static LabInfo {
        self.plain.info
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
    fn reload(&mut self, cx: &LabContext) -> Result<()> {
        self.program.reload(cx)
    }
    fn render(&mut self, frame: &mut Frame<'_>) -> Result<()> {
        self.stage.upload(frame.gpu, &self.params, frame.aspect());
        let mut pass = frame.pass(self.plain.info.name, Load::Clear([0.0; 3]));
        self.program.draw(&mut pass, self.stage.mesh(self.plain.normals));
        Ok(())
    }
}
