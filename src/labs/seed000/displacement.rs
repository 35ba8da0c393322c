//! Exercise 5, displacement (`Lab05-5`): each vertex moves along its normal by simplex noise
//! of its direction (`snoise(normalize(v)*2 + time)`) times `clamp(displacement, 0, 1)`, and is
//! coloured `shade * clamp(noise, 0, 1)`. On GLUT's meshes the shapes look jagged, and the cube
//! and teapot crack open where vertices share a position but not a normal — as in the original.
//! `--set smooth=1` (a port addition) welds shared vertices and averages their normals, which
//! closes the cracks. Keys: `[`/`]` displacement ∓0.01 (clamped to [0, 1]), `R/r G/g B/b` ±0.05
//! on the shade, `1`-`4` objects, mouse drag rotates, Space pauses the clock.

use glam::Vec3;

use crate::error::Result;
use crate::lab::{FilesTaken, Input, Lab, LabContext, LabEntry, LabInfo};
use crate::mesh::Vertex;
use crate::params::{ParamSpec, Params};
use crate::render::{AnyProgram, Frame, Load, Program, RenderState, Uniforms};
use crate::tess::Object;

use crate::labs::seed000::stage::{title_000, GlutStage, StageConfig, PARAMS_000};
use crate::labs::seed000::{noise_time, shade_key, NOISE_PARAMS};

/// Exercise 5.
pub static INFO: LabInfo = LabInfo {
    name: "displacement",
    title: "Lab05-5",
    label: "displacement",
    lecture: "000 CMP211 Lab05",
    size: (640, 360),
    keys: crate::lab::Keys::text(
        "[ / ]: displacement ∓0.01; R/r G/g B/b: shade ±0.05; 1-4: objects; left drag rotates; Space pauses the clock",
    ),
    files: FilesTaken::NONE,
};

/// The objects drawn outside faces first ([`GlutStage::faces`]: same pixels, fewer fragments
/// shaded). Measured (issue 14, `--set faces=mesh` against `outside_first`, 7 alternating
/// pairs): torus 0.93; cube 1.02, sphere 1.02, teapot 1.00: the vertex shader (noise per
/// vertex) is dear, so the second pass over the geometry does not pay there.
const SPLIT: &[Object] = &[Object::Torus];

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params,
    new,
};

/// The `DisplacementParams` block of `displacement_params.glsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct DisplacementUniforms {
    /// `shade`: colour of the noise.
    pub shade: [f32; 3],
    /// `time` in seconds.
    pub time: f32,
    /// `displacement`: strength.
    pub displacement: f32,
    /// std140 rounds the block up to 16 bytes.
    pub _pad: [f32; 3],
}
crate::uniform_block!(DisplacementUniforms, "DisplacementParams", {
    shade: "shade",
    time: "time",
    displacement: "displacement",
});

const OWN: &[ParamSpec] = &[
    ParamSpec::real(
        "shade",
        &[1.0, 1.0, 1.0],
        -1e30,
        1e30,
        "colour of the noise (R/r G/g B/b, keys within 0..1)",
    ),
    ParamSpec::real(
        "displacement",
        &[0.5],
        -1e30,
        1e30,
        "strength ([ / ], keys within 0..1; the shader clamps)",
    ),
    ParamSpec::flag(
        "smooth",
        &[0.0],
        "port: weld shared vertices and average normals (no cracks)",
    ),
];

fn params() -> Params {
    let mut p = Params::new(OWN);
    p.extend(NOISE_PARAMS);
    p.extend(PARAMS_000);
    p
}

struct Displacement {
    params: Params,
    stage: GlutStage,
    uniforms: Uniforms<DisplacementUniforms>,
    program: Program<Vertex>,
}

fn new(cx: &LabContext) -> Result<Box<dyn Lab>> {
    let stage = GlutStage::new(
        cx.gpu,
        "displacement",
        StageConfig {
            perspective: (45.0, 1.0, 100.0),
            eye: Vec3::new(0.0, 0.0, 4.0),
        },
    );
    let uniforms = Uniforms::new(
        cx.gpu,
        "displacement.params",
        DisplacementUniforms {
            shade: [1.0; 3],
            time: 0.0,
            displacement: 0.5,
            _pad: [0.0; 3],
        },
    );
    let mut program = Program::new(
        cx,
        "displacement",
        "displacement.vert",
        "displacement.frag",
        RenderState::default(),
    )?;
    program.bind(cx.gpu, vec![stage.transform.bind(), uniforms.bind()])?;
    Ok(Box::new(Displacement {
        params: params(),
        stage,
        uniforms,
        program,
    }))
}

impl Lab for Displacement {
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
            Input::Key('[') => self.params.step_clamped("displacement", 0, -0.01, 0.0, 1.0),
            Input::Key(']') => self.params.step_clamped("displacement", 0, 0.01, 0.0, 1.0),
            Input::Key(c) if shade_key(&mut self.params, c) => {}
            _ => return self.stage.input(&mut self.params, input),
        }
        true
    }
    fn programs(&mut self) -> Vec<&mut dyn AnyProgram> {
        vec![&mut self.program]
    }
    fn title(&self) -> String {
        let [r, g, b] = self.params.v3("shade");
        let summary = format!(
            "displacement {:.2} shade ({r:.2},{g:.2},{b:.2}) time {:.1}",
            self.params.f("displacement"),
            noise_time(&self.params)
        );
        let smooth = if self.params.on("smooth") { " | smooth" } else { "" };
        let mut title = title_000(&INFO, &self.params, &summary, "");
        title.push_str(smooth);
        title
    }
    fn reload(&mut self, cx: &LabContext) -> Result<()> {
        self.program.reload(cx)
    }
    fn animated(&self) -> bool {
        true
    }
    fn render(&mut self, frame: &mut Frame<'_>) -> Result<()> {
        self.uniforms.value = DisplacementUniforms {
            shade: self.params.v3("shade"),
            time: noise_time(&self.params),
            displacement: self.params.f("displacement"),
            _pad: [0.0; 3],
        };
        self.uniforms.upload(frame.gpu);
        self.program
            .set_faces(frame.gpu, GlutStage::faces(&self.params, SPLIT))?;
        let smooth = self.params.on("smooth");
        let mesh = self
            .stage
            .prepare(frame.gpu, &self.params, frame.width, frame.height, !smooth, smooth);
        let mut pass = frame.pass("displacement", Load::Clear([0.0; 3]));
        self.program.draw(&mut pass, mesh);
        Ok(())
    }
}
