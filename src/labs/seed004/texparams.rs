//! Seed 004 §4.6, texture parameters (pinned scene for the slides' settings): a floor quad
//! y = −1 running 18 units away from the eye at (0, 0.5, 3), textured with the course's
//! checker (or `--texture FILE`) repeated 2 × 9 times, drawn with the shaders of 4.4. Its
//! parameters are GL's: `wrap_s`, `wrap_t` (REPEAT or CLAMP_TO_EDGE: the edge texels stretch
//! outside 0..1), `min` (mipmapped filters average the far squares to grey, NEAREST and LINEAR
//! shimmer in moiré) and `mag` (NEAREST keeps the near squares sharp, LINEAR blurs their
//! edges).
//!
//! Keys: `w` wrap_s, `W` wrap_t, `m` min, `M` mag (each cycles).

use glam::{Mat4, Vec3};

use crate::camera::glm;
use crate::error::Result;
use crate::geometry::obj::ObjCorner;
use crate::geometry::shapes;
use crate::lab::{FilesTaken, Input, Lab, LabContext, LabEntry, LabInfo};
use crate::params::{ParamSpec, Params};
use crate::render::{Frame, GpuMesh, Load, Program, RenderState, Uniforms};

use crate::labs::seed004::gl_textures::{self, GlTexture, MinFilter, TexParams, MAG_FILTERS, MIN_FILTERS, WRAPS};
use crate::labs::seed004::stage::SuzanneMatrices;

/// Seed 004 §4.6.
pub static INFO: LabInfo = LabInfo {
    name: "texparams",
    title: "OpenGL III",
    label: "texture parameters",
    lecture: "004 OpenGL III – Basic Shaders",
    size: (640, 480),
    keys: crate::lab::Keys::text("w: wrap_s; W: wrap_t; m: min filter; M: mag filter (each cycles)"),
    files: FilesTaken {
        texture: true,
        ..FilesTaken::NONE
    },
};

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params,
    new,
};

const OWN: &[ParamSpec] = &[
    ParamSpec::choice(
        "wrap_s",
        &[0.0],
        WRAPS,
        "GL_TEXTURE_WRAP_S: 0 REPEAT, 1 CLAMP_TO_EDGE (w)",
    ),
    ParamSpec::choice(
        "wrap_t",
        &[0.0],
        WRAPS,
        "GL_TEXTURE_WRAP_T: 0 REPEAT, 1 CLAMP_TO_EDGE (W)",
    ),
    ParamSpec::choice(
        "min",
        &[0.0],
        MIN_FILTERS,
        "GL_TEXTURE_MIN_FILTER: 0 LINEAR_MIPMAP_NEAREST, 1 NEAREST, 2 LINEAR, 3 LINEAR_MIPMAP_LINEAR (m)",
    ),
    ParamSpec::choice(
        "mag",
        &[0.0],
        MAG_FILTERS,
        "GL_TEXTURE_MAG_FILTER: 0 NEAREST, 1 LINEAR (M)",
    ),
];

fn params() -> Params {
    Params::new(OWN)
}

/// V = `lookAt((0, 0.5, 3), (0, −1, −3), (0, 1, 0))`; M = identity.
pub fn view() -> Mat4 {
    glm::look_at(Vec3::new(0.0, 0.5, 3.0), Vec3::new(0.0, -1.0, -3.0), Vec3::Y)
}

/// The texture parameters the state asks for.
pub fn tex_params(p: &Params) -> TexParams {
    TexParams {
        clamp: [p.index_of("wrap_s") == 1, p.index_of("wrap_t") == 1],
        min: MinFilter::from_index(p.index_of("min")),
        mag_linear: p.index_of("mag") == 1,
    }
}

struct TexParamsLab {
    params: Params,
    matrices: Uniforms<SuzanneMatrices>,
    floor: GpuMesh<ObjCorner>,
    texture: GlTexture,
    program: Program<ObjCorner>,
    /// The texture parameters bound now.
    bound: Option<TexParams>,
}

fn new(cx: &LabContext) -> Result<Box<dyn Lab>> {
    let texture = match &cx.files.texture {
        Some(file) => GlTexture::new(
            cx.gpu,
            "texparams.user",
            &gl_textures::bottom_row_first(&file.data),
            &file.path,
        )?,
        None => gl_textures::checker(cx.gpu)?,
    };
    let program = Program::new(
        cx,
        "texparams",
        "suzanne_normal_matrix.vert",
        "suzanne_texture.frag",
        RenderState::default(),
    )?;
    let matrices = SuzanneMatrices::new(Mat4::IDENTITY, view(), 4.0 / 3.0);
    Ok(Box::new(TexParamsLab {
        params: params(),
        matrices: Uniforms::new(cx.gpu, "texparams.matrices", matrices),
        floor: GpuMesh::new(cx.gpu, "texparams.floor", &shapes::texparams_floor(), None),
        texture,
        program,
        bound: None,
    }))
}

impl Lab for TexParamsLab {
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
        let name = match input {
            Input::Key('w') => "wrap_s",
            Input::Key('W') => "wrap_t",
            Input::Key('m') => "min",
            Input::Key('M') => "mag",
            _ => return false,
        };
        self.params.cycle(name);
        true
    }
    fn reload(&mut self, cx: &LabContext) -> Result<()> {
        self.program.reload(cx)
    }
    fn render(&mut self, frame: &mut Frame<'_>) -> Result<()> {
        let gpu = frame.gpu;
        let want = tex_params(&self.params);
        if self.bound != Some(want) {
            let [texture, sampler] = self.texture.bind(gpu, "tex", "tex_sampler", want);
            self.program.bind(gpu, vec![self.matrices.bind(), texture, sampler])?;
            self.bound = Some(want);
        }
        self.matrices.value = SuzanneMatrices::new(Mat4::IDENTITY, view(), frame.aspect());
        self.matrices.upload(gpu);
        let mut pass = frame.pass("texparams", Load::Clear([0.0; 3]));
        self.program.draw(&mut pass, &self.floor);
        Ok(())
    }
}
