//! Exercise 4, simplex noise (`Lab05-4`): Ashima/McEwan 3D simplex noise evaluated per
//! fragment at the object-space position plus `time`, shown as `shade * |snoise|`; it animates
//! with a clock in seconds. Keys: `R/r G/g B/b` ±0.05 on the shade colour (clamped to [0, 1]),
//! `1`-`4` objects, mouse drag rotates, Space pauses the clock.

use glam::Vec3;

use crate::error::Result;
use crate::lab::{FilesTaken, Input, Lab, LabContext, LabEntry, LabInfo};
use crate::mesh::Vertex;
use crate::params::{ParamSpec, Params};
use crate::render::{AnyProgram, Frame, Load, Program, RenderState, Uniforms};
use crate::tess::Object;

use super::glut_stage::{title_000, GlutStage, StageConfig, PARAMS_000};
use super::{noise_time, shade_key, NOISE_PARAMS};

/// Exercise 4.
pub static INFO: LabInfo = LabInfo {
    name: "noise",
    title: "Lab05-4",
    label: "simplex noise",
    lecture: "000 CMP211 Lab05",
    size: (640, 360),
    keys: crate::lab::Keys::text("R/r G/g B/b: shade ±0.05; 1-4: objects; left drag rotates; Space pauses the clock"),
    files: FilesTaken::NONE,
};

/// The objects drawn outside faces first ([`GlutStage::faces`]: same pixels, fewer fragments
/// shaded). Measured (issue 14, `--set faces=mesh` against `outside_first`, 7 alternating
/// pairs): torus 0.73, teapot 0.92; sphere 1.00 and cube 0.95 within the noise, left as GL draws.
const SPLIT: &[Object] = &[Object::Torus, Object::Teapot];

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params,
    new,
};

/// The `NoiseParams` block of `noise_params.glsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct NoiseUniforms {
    /// `shade`: colour of the noise.
    pub shade: [f32; 3],
    /// `time` in seconds.
    pub time: f32,
}
crate::uniform_block!(NoiseUniforms, "NoiseParams", { shade: "shade", time: "time" });

const OWN: &[ParamSpec] = &[ParamSpec::real(
    "shade",
    &[1.0, 1.0, 1.0],
    -1e30,
    1e30,
    "colour of the noise (R/r G/g B/b, keys within 0..1)",
)];

fn params() -> Params {
    let mut p = Params::new(OWN);
    p.extend(NOISE_PARAMS);
    p.extend(PARAMS_000);
    p
}

struct Noise {
    params: Params,
    stage: GlutStage,
    uniforms: Uniforms<NoiseUniforms>,
    program: Program<Vertex>,
}

fn new(cx: &LabContext) -> Result<Box<dyn Lab>> {
    let stage = GlutStage::new(
        cx.gpu,
        "noise",
        StageConfig {
            perspective: (45.0, 1.0, 100.0),
            eye: Vec3::new(0.0, 0.0, 4.0),
        },
    );
    let uniforms = Uniforms::new(
        cx.gpu,
        "noise.params",
        NoiseUniforms {
            shade: [1.0; 3],
            time: 0.0,
        },
    );
    let mut program = Program::new(cx, "noise", "noise.vert", "noise.frag", RenderState::default())?;
    program.bind(cx.gpu, vec![stage.transform.bind(), uniforms.bind()])?;
    Ok(Box::new(Noise {
        params: params(),
        stage,
        uniforms,
        program,
    }))
}

impl Lab for Noise {
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
            Input::Key(c) if shade_key(&mut self.params, c) => true,
            _ => self.stage.input(&mut self.params, input),
        }
    }
    fn programs(&mut self) -> Vec<&mut dyn AnyProgram> {
        vec![&mut self.program]
    }
    fn title(&self) -> String {
        let [r, g, b] = self.params.v3("shade");
        let summary = format!("shade ({r:.2},{g:.2},{b:.2}) time {:.1}", noise_time(&self.params));
        title_000(&INFO, &self.params, &summary, "")
    }
    fn reload(&mut self, cx: &LabContext) -> Result<()> {
        self.program.reload(cx)
    }
    fn animated(&self) -> bool {
        true
    }
    fn render(&mut self, frame: &mut Frame<'_>) -> Result<()> {
        self.uniforms.value = NoiseUniforms {
            shade: self.params.v3("shade"),
            time: noise_time(&self.params),
        };
        self.uniforms.upload(frame.gpu);
        self.program
            .set_faces(frame.gpu, GlutStage::faces(&self.params, SPLIT))?;
        let mesh = self
            .stage
            .prepare(frame.gpu, &self.params, frame.width, frame.height, true, false);
        let mut pass = frame.pass("noise", Load::Clear([0.0; 3]));
        self.program.draw(&mut pass, mesh);
        Ok(())
    }
}
