//! A textured seed-004 exercise (4.4, 4.5): the vertex shader of 4.2 on the vertex-normal VBO
//! (pinned: the exercise follows "Smooth Suzanne") and a fragment shader sampling texture
//! unit 0, which holds the checker (`tex=0`) or the "BMP" texture (`tex=1`), each with the
//! course's texture parameters; key `t` toggles them.

use crate::error::Result;
use crate::geometry::obj::ObjCorner;
use crate::gpu::Gpu;
use crate::lab::{Input, Lab, LabContext, LabInfo};
use crate::params::{ParamSpec, Params};
use crate::render::{Frame, Load, Program, RenderState};

use crate::labs::seed004::gl_textures::{self, GlTexture, TexParams};
use crate::labs::seed004::stage::{Normals, SuzanneStage, ANGLES};

/// What distinguishes one such exercise.
pub struct Textured {
    /// Name and title.
    pub info: &'static LabInfo,
    /// Fragment shader file.
    pub frag: &'static str,
}

const OWN: &[ParamSpec] = &[ParamSpec::choice(
    "tex",
    &[0.0],
    &["checker", "bmp"],
    "texture: the course's checker or its BMP (uvgrid, or --texture FILE) (t)",
)];

/// The parameters: `tex`, then the stage's.
pub fn params() -> Params {
    let mut p = Params::new(OWN);
    p.extend(ANGLES);
    p
}

struct TexturedSuzanne {
    textured: &'static Textured,
    params: Params,
    stage: SuzanneStage,
    program: Program<ObjCorner>,
    /// Unit 0's two textures, in `tex` order, with their parameters.
    textures: [(GlTexture, TexParams); 2],
    /// The `tex` bound now.
    bound: Option<usize>,
}

/// Builds the exercise.
pub fn new(cx: &LabContext, textured: &'static Textured) -> Result<Box<dyn Lab>> {
    let name = textured.info.name;
    let stage = SuzanneStage::new(cx, name);
    let program = Program::new(
        cx,
        name,
        "suzanne_normal_matrix.vert",
        textured.frag,
        RenderState::default(),
    )?;
    let textures = [
        (gl_textures::checker(cx.gpu)?, TexParams::CHECKER),
        (gl_textures::bmp(cx.gpu, cx.files.texture.as_ref())?, TexParams::BMP),
    ];
    Ok(Box::new(TexturedSuzanne {
        textured,
        params: params(),
        stage,
        program,
        textures,
        bound: None,
    }))
}

impl TexturedSuzanne {
    /// Binds the matrices and the texture chosen by `tex` (glBindTexture on unit 0).
    fn bind(&mut self, gpu: &Gpu) -> Result<()> {
        let tex = self.params.index_of("tex").min(1);
        if self.bound != Some(tex) {
            let (texture, params) = &self.textures[tex];
            let [texture, sampler] = texture.bind(gpu, "tex", "tex_sampler", *params);
            self.program
                .bind(gpu, vec![self.stage.matrices.bind(), texture, sampler])?;
            self.bound = Some(tex);
        }
        Ok(())
    }
}

impl Lab for TexturedSuzanne {
    fn info(&self) -> &'static LabInfo {
        self.textured.info
    }
    fn params(&self) -> &Params {
        &self.params
    }
    fn params_mut(&mut self) -> &mut Params {
        &mut self.params
    }
    fn input(&mut self, input: Input) -> bool {
        match input {
            Input::Key('t') => {
                self.params.cycle("tex");
                true
            }
            _ => self.stage.input(&mut self.params, input),
        }
    }
    fn reload(&mut self, cx: &LabContext) -> Result<()> {
        self.program.reload(cx)
    }
    fn render(&mut self, frame: &mut Frame<'_>) -> Result<()> {
        self.bind(frame.gpu)?;
        self.stage.upload(frame.gpu, &self.params, frame.aspect());
        let mut pass = frame.pass(self.textured.info.name, Load::Clear([0.0; 3]));
        self.program.draw(&mut pass, self.stage.mesh(Normals::Vertex));
        Ok(())
    }
}
