//! Seed 001 `wave` (SPEC §1.3): the course's wave-motion vertex shader lifts a flat checkered
//! 40×40 grid by `h·sin(time + xs·x) + h·sin(time + zs·z)`; the crests travel with time (in
//! seconds: the course's idle callback sends milliseconds, which would flicker, §6.1). Seen
//! from (0, 3.5, 6.5).
//!
//! Keys: Space pauses the clock; `h`/`H` h ∓0.02; `x`/`X` xs ∓0.5; `z`/`Z` zs ∓0.5; left drag
//! rotates.

use std::f64::consts::TAU;

use glam::Vec3;

use crate::error::Result;
use crate::geometry::shapes::{wave_grid, ColorVertex};
use crate::lab::{FilesTaken, Input, Lab, LabContext, LabEntry, LabInfo};
use crate::params::{ParamSpec, Params};
use crate::render::{Frame, GpuMesh, Load, Program, RenderState, Uniforms};

use crate::labs::seed001::stage::{UstcStage, ROTATION};

/// Seed 001, §1.3.
pub static INFO: LabInfo = LabInfo {
    name: "wave",
    title: "ref001",
    label: "wave motion",
    lecture: "001 USTC GLSL (III)",
    size: (512, 512),
    keys: crate::lab::Keys::text("Space pauses the clock; h/H: h ∓0.02; x/X: xs ∓0.5; z/Z: zs ∓0.5; left drag rotates"),
    files: FilesTaken::NONE,
};

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params,
    new,
};

/// The `Wave` block of `wave.vert`: the course's four loose float uniforms.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct WaveUniforms {
    /// `time`, seconds.
    pub time: f32,
    /// `xs`: frequency along x.
    pub xs: f32,
    /// `zs`: frequency along z.
    pub zs: f32,
    /// `h`: height scale.
    pub h: f32,
}
crate::uniform_block!(WaveUniforms, "Wave", { time: "time", xs: "xs", zs: "zs", h: "h" });

// gl_Vertex and glColor3f's colour.
crate::vertex_type!(ColorVertex, {
    position: "vertex_position" => Float32x3,
    color: "vertex_color" => Float32x3,
});

const OWN: &[ParamSpec] = &[
    ParamSpec::real("time", &[0.0], -1e9, 1e9, "seconds (a clock in a window; Space pauses)"),
    ParamSpec::real("h", &[0.1], -10.0, 10.0, "height scale (h H)"),
    ParamSpec::real("xs", &[3.0], -100.0, 100.0, "frequency along x (x X)"),
    ParamSpec::real("zs", &[2.0], -100.0, 100.0, "frequency along z (z Z)"),
];

fn params() -> Params {
    let mut p = Params::new(OWN);
    p.extend(ROTATION);
    p
}

/// The block for the current parameters. `time` only enters through `sin(time + …)`, so it is
/// wrapped by 2π in double before it becomes a float: the same value below 2π, and no lost
/// precision in a window left running for hours.
pub fn uniforms_of(p: &Params) -> WaveUniforms {
    WaveUniforms {
        time: p.f64("time").rem_euclid(TAU) as f32,
        xs: p.f("xs"),
        zs: p.f("zs"),
        h: p.f("h"),
    }
}

struct Wave {
    params: Params,
    stage: UstcStage,
    uniforms: Uniforms<WaveUniforms>,
    program: Program<ColorVertex>,
    grid: GpuMesh<ColorVertex>,
}

fn new(cx: &LabContext) -> Result<Box<dyn Lab>> {
    let stage = UstcStage::new(cx.gpu, "wave", Vec3::new(0.0, 3.5, 6.5));
    let p = params();
    let uniforms = Uniforms::new(cx.gpu, "wave.params", uniforms_of(&p));
    let mut program = Program::new(cx, "wave", "wave.vert", "pass_color.frag", RenderState::default())?;
    program.bind(cx.gpu, vec![stage.transform.bind(), uniforms.bind()])?;
    let grid = GpuMesh::new(cx.gpu, "wave.grid", &wave_grid(), None);
    Ok(Box::new(Wave {
        params: p,
        stage,
        uniforms,
        program,
        grid,
    }))
}

impl Lab for Wave {
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
        let (name, delta) = match input {
            Input::Key('h') => ("h", -0.02),
            Input::Key('H') => ("h", 0.02),
            Input::Key('x') => ("xs", -0.5),
            Input::Key('X') => ("xs", 0.5),
            Input::Key('z') => ("zs", -0.5),
            Input::Key('Z') => ("zs", 0.5),
            _ => return self.stage.input(&mut self.params, input),
        };
        self.params.step(name, delta);
        true
    }
    fn reload(&mut self, cx: &LabContext) -> Result<()> {
        self.program.reload(cx)
    }
    fn animated(&self) -> bool {
        true
    }
    fn render(&mut self, frame: &mut Frame<'_>) -> Result<()> {
        self.uniforms.value = uniforms_of(&self.params);
        self.uniforms.upload(frame.gpu);
        self.stage.upload(frame.gpu, &self.params, frame.width, frame.height);
        let mut pass = frame.pass("wave", Load::Clear([0.0; 3]));
        self.program.draw(&mut pass, &self.grid);
        Ok(())
    }
}
