//! Seed 002 (Lecture 12) `double_vision`, SPEC §2.2: two reads of one texture, shifted by
//! `left_separation` and `right_separation`, averaged. One textured triangle given in clip
//! space (the slide sets no matrices, so projection and modelview are identity): (−0.8, 0.8)
//! st (0,0), (0.8, 0.8) st (1,0), (0, −0.8) st (0.5,1) — apex down, the image's first row at
//! the top. Texture: the procedural uvgrid (SPEC §0.1), REPEAT, LINEAR/LINEAR, no mipmaps.
//! Depth test off.
//!
//! Course quirks (SPEC §6.2): the sampler is called `texture`, a built-in function from
//! GLSL 1.30 on — renamed `tex` here (#3); the slide shows no texture set-up, and GL's default
//! minification filter would make the texture incomplete (black) — REPEAT and LINEAR/LINEAR are
//! pinned (#5); `glUniform1f` on the sampler is a GL error that leaves it on unit 0 (#2): a
//! wgpu binding has no units, the one texture is what it reads.
//!
//! Keys: `[`/`]` separation ∓/±0.02 (left_x steps by ∓/±0.02, right_x the opposite way).

use crate::error::Result;
use crate::geometry::images::uvgrid;
use crate::geometry::shapes::{double_vision_triangle, TexVertex2};
use crate::lab::{FilesTaken, Input, Lab, LabContext, LabEntry, LabInfo};
use crate::params::{ParamSpec, Params};
use crate::render::{sampler, Bind, Frame, GpuMesh, Load, Program, RenderState, SamplerDesc, Texture, Uniforms};

/// `double_vision`.
pub static INFO: LabInfo = LabInfo {
    name: "double_vision",
    title: "ref002",
    label: "double vision",
    lecture: "002 Lecture 12",
    size: (512, 512),
    keys: crate::lab::Keys::text("[/]: separation ∓/±0.02 (left_x = +sep, right_x = -sep)"),
    files: FilesTaken::NONE,
};

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params,
    new,
};

crate::vertex_type!(TexVertex2, {
    position: "vertex_position" => Float32x2,
    st: "vertex_st" => Float32x2,
});

/// The `DoubleVision` block of `double_vision.frag`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct DoubleVisionUniforms {
    /// `left_separation`.
    pub left_separation: [f32; 2],
    /// `right_separation`.
    pub right_separation: [f32; 2],
}
crate::uniform_block!(DoubleVisionUniforms, "DoubleVision", {
    left_separation: "left_separation",
    right_separation: "right_separation",
});

/// The separation step of keys `[` and `]`.
const STEP: f64 = 0.02;

const PARAMS: &[ParamSpec] = &[
    ParamSpec::real(
        "left_x",
        &[0.1],
        -100.0,
        100.0,
        "left_separation.s (] adds 0.02, [ subtracts)",
    ),
    ParamSpec::real(
        "right_x",
        &[-0.1],
        -100.0,
        100.0,
        "right_separation.s (] subtracts 0.02, [ adds)",
    ),
    ParamSpec::real("left_y", &[0.0], -100.0, 100.0, "left_separation.t"),
    ParamSpec::real("right_y", &[0.0], -100.0, 100.0, "right_separation.t"),
];

fn params() -> Params {
    Params::new(PARAMS)
}

struct DoubleVision {
    params: Params,
    uniforms: Uniforms<DoubleVisionUniforms>,
    program: Program<TexVertex2>,
    triangle: GpuMesh<TexVertex2>,
}

fn uniforms_of(p: &Params) -> DoubleVisionUniforms {
    DoubleVisionUniforms {
        left_separation: [p.f("left_x"), p.f("left_y")],
        right_separation: [p.f("right_x"), p.f("right_y")],
    }
}

fn new(cx: &LabContext) -> Result<Box<dyn Lab>> {
    let params = params();
    let uniforms = Uniforms::new(cx.gpu, "double_vision.params", uniforms_of(&params));
    let image = uvgrid();
    let texture = Texture::new(cx.gpu, "uvgrid", image.width, image.height, 1, &[image.rgba]);
    // REPEAT/REPEAT, LINEAR/LINEAR, no mipmaps (SPEC §2.2, pinned).
    let sampler = sampler(cx.gpu, "double_vision.sampler", &SamplerDesc::default());
    let mut program = Program::new(
        cx,
        "double_vision",
        "double_vision.vert",
        "double_vision.frag",
        RenderState::default().no_depth(),
    )?;
    program.bind(
        cx.gpu,
        vec![
            Bind::texture("tex", &texture),
            Bind::sampler("tex_sampler", &sampler),
            uniforms.bind(),
        ],
    )?;
    let triangle = GpuMesh::new(cx.gpu, "double_vision.triangle", &double_vision_triangle(), None);
    Ok(Box::new(DoubleVision {
        params,
        uniforms,
        program,
        triangle,
    }))
}

impl Lab for DoubleVision {
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
        let delta = match input {
            Input::Key(']') => STEP,
            Input::Key('[') => -STEP,
            _ => return false,
        };
        self.params.step("left_x", delta);
        self.params.step("right_x", -delta);
        true
    }
    fn reload(&mut self, cx: &LabContext) -> Result<()> {
        self.program.reload(cx)
    }
    fn render(&mut self, frame: &mut Frame<'_>) -> Result<()> {
        self.uniforms.value = uniforms_of(&self.params);
        self.uniforms.upload(frame.gpu);
        let mut pass = frame.pass("double_vision", Load::Clear([0.0; 3]));
        self.program.draw(&mut pass, &self.triangle);
        Ok(())
    }
}
