//! Seed 002 (Lecture 12, P. Khungurn) `twist`, SPEC §2.1: 2D twisting. The course's 100×100
//! `GL_QUADS` grid over [−0.5, 0.5]² ([`twist_grid`], float loop) is given in clip space — no
//! matrices, no camera — and the vertex shader turns each vertex by
//! `twisting · length(gl_Vertex.xy)` radians. Depth test off (2D, nothing overlaps).
//!
//! Course quirk kept (SPEC §6.2 #4): `color` = (0.5, 9.0, 0.5); the 9.0 clamps to 1 in the
//! UNORM framebuffer, so the shape is (128, 255, 128).
//!
//! Keys: `+`/`-` twisting ±0.25.

use crate::error::Result;
use crate::geometry::shapes::twist_grid;
use crate::lab::{FilesTaken, Input, Lab, LabContext, LabEntry, LabInfo};
use crate::params::{ParamSpec, Params};
use crate::render::{Frame, GpuMesh, Load, Program, RenderState, Uniforms};

/// `twist`.
pub static INFO: LabInfo = LabInfo {
    name: "twist",
    title: "ref002",
    label: "2D twisting",
    lecture: "002 Lecture 12",
    size: (512, 512),
    keys: "+/-: twisting ±0.25",
    files: FilesTaken::NONE,
};

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params,
    new,
};

/// One vertex of the grid: `glVertex2f(x, y)`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct TwistVertex {
    /// Clip-space x, y.
    pub position: [f32; 2],
}
crate::vertex_type!(TwistVertex, { position: "vertex_position" => Float32x2 });

/// The `Twist` block of `twist_params.glsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct TwistUniforms {
    /// `color`.
    pub color: [f32; 3],
    /// `twisting`, radians per unit of distance from the centre.
    pub twisting: f32,
}
crate::uniform_block!(TwistUniforms, "Twist", { color: "color", twisting: "twisting" });

const PARAMS: &[ParamSpec] = &[
    ParamSpec::real(
        "twisting",
        &[4.25],
        -1000.0,
        1000.0,
        "radians of turn per unit of radius (+/-)",
    ),
    ParamSpec::real(
        "color",
        &[0.5, 9.0, 0.5],
        -100.0,
        100.0,
        "uniform colour (course: 9.0 clamps to 1 in the framebuffer)",
    ),
];

fn params() -> Params {
    Params::new(PARAMS)
}

struct Twist {
    params: Params,
    uniforms: Uniforms<TwistUniforms>,
    program: Program<TwistVertex>,
    grid: GpuMesh<TwistVertex>,
}

fn uniforms_of(p: &Params) -> TwistUniforms {
    TwistUniforms {
        color: p.v3("color"),
        twisting: p.f("twisting"),
    }
}

fn new(cx: &LabContext) -> Result<Box<dyn Lab>> {
    let params = params();
    let uniforms = Uniforms::new(cx.gpu, "twist.params", uniforms_of(&params));
    let mut program = Program::new(
        cx,
        "twist",
        "twist.vert",
        "twist.frag",
        RenderState::default().no_depth(),
    )?;
    program.bind(cx.gpu, vec![uniforms.bind()])?;
    let vertices: Vec<TwistVertex> = twist_grid()
        .into_iter()
        .map(|position| TwistVertex { position })
        .collect();
    let grid = GpuMesh::new(cx.gpu, "twist.grid", &vertices, None);
    Ok(Box::new(Twist {
        params,
        uniforms,
        program,
        grid,
    }))
}

impl Lab for Twist {
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
            Input::Key('+') => self.params.step("twisting", 0.25),
            Input::Key('-') => self.params.step("twisting", -0.25),
            _ => return false,
        }
        true
    }
    fn reload(&mut self, cx: &LabContext) -> Result<()> {
        self.program.reload(cx)
    }
    fn render(&mut self, frame: &mut Frame<'_>) -> Result<()> {
        self.uniforms.value = uniforms_of(&self.params);
        self.uniforms.upload(frame.gpu);
        let mut pass = frame.pass("twist", Load::Clear([0.0; 3]));
        self.program.draw(&mut pass, &self.grid);
        Ok(())
    }
}
