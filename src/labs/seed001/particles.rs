//! Seed 001 `particles` (SPEC §1.5): the course's particle-system vertex shader moves 2000
//! one-pixel points, all starting at (0, −1, 0) with their own initial velocity (`attribute vec3
//! vel`), under gravity: `y = y0 + vy·t + g/(2m)·t²`. With g = −2 and m = 1 they rise about one
//! unit in the first second and fall back after. Seen from (0, 1, 4).
//!
//! Keys: Space pauses the clock; `r` restarts at t = 0; `g`/`G` g ∓0.5; `m`/`M` m ∓0.25
//! (at least 0.25); left drag rotates.

use glam::{Mat4, Vec3};

use crate::error::Result;
use crate::geometry::shapes::{particle_velocities, PARTICLE_COUNT};
use crate::lab::{FilesTaken, Input, Lab, LabContext, LabEntry, LabInfo};
use crate::params::{ParamSpec, Params};
use crate::render::{Frame, GpuMesh, Load, Program, RenderState, Uniforms};

use crate::labs::seed001::immediate::Immediate;
use crate::labs::seed001::stage::{UstcStage, ROTATION};

/// Seed 001, §1.5.
pub static INFO: LabInfo = LabInfo {
    name: "particles",
    title: "ref001",
    label: "particle system",
    lecture: "001 USTC GLSL (III)",
    size: (512, 512),
    keys: crate::lab::Keys::text(
        "Space pauses the clock; r: restart at t = 0; g/G: g ∓0.5; m/M: m ∓0.25 (≥ 0.25); left drag rotates",
    ),
    files: FilesTaken::NONE,
};

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params,
    new,
};

/// The `Particles` block of `particles.vert`: `uniform float g, m, t;`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ParticlesUniforms {
    /// `g`: gravity.
    pub g: f32,
    /// `m`: mass.
    pub m: f32,
    /// `t`: time in seconds.
    pub t: f32,
}
crate::uniform_block!(ParticlesUniforms, "Particles", { g: "g", m: "m", t: "t" });

/// One particle: `glVertexAttrib3fv(vel, …); glVertex3f(0, −1, 0);`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ParticleVertex {
    /// `gl_Vertex`: where it starts.
    pub position: [f32; 3],
    /// The `vel` attribute: its initial velocity.
    pub vel: [f32; 3],
}
crate::vertex_type!(ParticleVertex, {
    position: "vertex_position" => Float32x3,
    vel: "vel" => Float32x3,
});

const OWN: &[ParamSpec] = &[
    ParamSpec::real(
        "time",
        &[0.0],
        -1e9,
        1e9,
        "t in seconds (a clock in a window; Space pauses, r restarts)",
    ),
    ParamSpec::real("g", &[-2.0], -1000.0, 1000.0, "gravity (g G)"),
    ParamSpec::real("m", &[1.0], 0.25, 1000.0, "mass (m M)"),
];

fn params() -> Params {
    let mut p = Params::new(OWN);
    p.extend(ROTATION);
    p
}

/// The 2000 particles as the pinned loop sends them: for each, `glVertexAttrib3fv(vel, v_i)`
/// then `glVertex3f(0, −1, 0)` inside `glBegin(GL_POINTS)`.
pub fn course_points() -> Vec<ParticleVertex> {
    let mut points = Immediate::begin(ParticleVertex {
        position: [0.0; 3],
        vel: [0.0; 3],
    });
    for v in particle_velocities(PARTICLE_COUNT) {
        points.attrib(|p| p.vel = v);
        points.vertex(|p| p.position = [0.0, -1.0, 0.0]);
    }
    points.end()
}

/// Subpixel bits of the rasterizer (llvmpipe/lavapipe: 8, i.e. positions snap to 1/256 pixel).
const SUBPIXEL_BITS: i32 = 8;

/// Makes a 1-pixel point light the pixel GL lights. GL's (non-sprite) points light the pixel
/// `floor(x_w)` of the snapped window position; Vulkan's points are 1×1 squares whose left edge
/// is inside, which lights `ceil(x_w) − 1`: the same except where x_w snaps to a whole number,
/// where Vulkan lights the pixel to the left. Moving every point right by one subpixel makes the
/// two rules agree everywhere. (In y the two conventions already agree: Vulkan's y runs down.)
/// Applied to the projection, so the course's shader stays as written.
pub fn gl_point_rule(projection: Mat4, width: u32) -> Mat4 {
    // One subpixel in clip units: x_ndc spans `width` pixels over 2 units; x_clip = x_ndc · w.
    let subpixel = 2.0 / (width.max(1) as f32 * 2f32.powi(SUBPIXEL_BITS));
    let mut shift = Mat4::IDENTITY;
    shift.w_axis.x = subpixel;
    shift * projection
}

struct Particles {
    params: Params,
    stage: UstcStage,
    uniforms: Uniforms<ParticlesUniforms>,
    program: Program<ParticleVertex>,
    points: GpuMesh<ParticleVertex>,
}

fn uniforms_of(p: &Params) -> ParticlesUniforms {
    ParticlesUniforms {
        g: p.f("g"),
        m: p.f("m"),
        t: p.f("time"),
    }
}

fn new(cx: &LabContext) -> Result<Box<dyn Lab>> {
    let stage = UstcStage::new(cx.gpu, "particles", Vec3::new(0.0, 1.0, 4.0));
    let p = params();
    let uniforms = Uniforms::new(cx.gpu, "particles.params", uniforms_of(&p));
    // GL_POINTS at GL's default point size 1 (the only size WebGPU draws).
    let state = RenderState::default().topology(wgpu::PrimitiveTopology::PointList);
    let mut program = Program::new(cx, "particles", "particles.vert", "particles.frag", state)?;
    program.bind(cx.gpu, vec![stage.transform.bind(), uniforms.bind()])?;
    let points = GpuMesh::new(cx.gpu, "particles.points", &course_points(), None);
    Ok(Box::new(Particles {
        params: p,
        stage,
        uniforms,
        program,
        points,
    }))
}

impl Lab for Particles {
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
            Input::Key('r') => {
                self.params.put("time", &[0.0]);
                return true;
            }
            Input::Key('g') => ("g", -0.5),
            Input::Key('G') => ("g", 0.5),
            Input::Key('m') => ("m", -0.25),
            Input::Key('M') => ("m", 0.25),
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
        let projection = gl_point_rule(UstcStage::projection(frame.width, frame.height), frame.width);
        self.stage.upload_with(frame.gpu, &self.params, projection);
        let mut pass = frame.pass("particles", Load::Clear([0.0; 3]));
        self.program.draw(&mut pass, &self.points);
        Ok(())
    }
}
