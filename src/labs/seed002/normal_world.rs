//! Seed 002 (Lecture 12) `normal_world`, SPEC §2.3: the normal as colour, `(n + 1) / 2`, in
//! world space. The view is folded into the projection (`gluPerspective(60, 1, 0.1, 100)` then
//! `gluLookAt(0,0,5, …)` on the projection stack, [`crate::labs::seed002::stage`]), so
//! `gl_NormalMatrix` is the model's alone and the colours follow the teapot's own rotation,
//! never the camera. Model: `glRotated(rz, 0,0,1); glRotated(ry, 0,1,0); glRotated(rx, 1,0,0);
//! glutSolidTeapot(1.0)`. Depth test on.
//!
//! Port addition: the parameter `eye` (default the course's (0, 0, 5)) moves the `gluLookAt`
//! eye around the origin, to show that the colours belong to the surface, not to the view.
//!
//! Keys: `x`/`X`, `y`/`Y`, `z`/`Z`: rx, ry, rz ∓/±5°.

use crate::error::Result;
use crate::lab::{FilesTaken, Input, Lab, LabContext, LabEntry, LabInfo};
use crate::mesh::Vertex;
use crate::params::{ParamSpec, Params};
use crate::render::{Frame, GpuMesh, Load, Program, RenderState, Uniforms};

use crate::labs::common::TransformUniforms;
use crate::labs::seed002::stage;

/// `normal_world`.
pub static INFO: LabInfo = LabInfo {
    name: "normal_world",
    title: "ref002",
    label: "normal as colour, world space",
    lecture: "002 Lecture 12",
    size: (512, 512),
    keys: crate::lab::Keys::text("x/X y/Y z/Z: rotate about x, y, z ∓/±5°"),
    files: FilesTaken::NONE,
};

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params,
    new,
};

/// Bound on the angles (a held key must not reach float precision trouble).
const TURNS: f64 = 36000.0;

const PARAMS: &[ParamSpec] = &[
    ParamSpec::real(
        "rx",
        &[0.0],
        -TURNS,
        TURNS,
        "glRotated about x, degrees (x/X), turns first",
    ),
    ParamSpec::real("ry", &[0.0], -TURNS, TURNS, "glRotated about y, degrees (y/Y)"),
    ParamSpec::real(
        "rz",
        &[0.0],
        -TURNS,
        TURNS,
        "glRotated about z, degrees (z/Z), turns last",
    ),
    ParamSpec::real(
        "eye",
        &[0.0, 0.0, 5.0],
        -100.0,
        100.0,
        "port study: gluLookAt eye, looking at the origin (colours stay world-space)",
    ),
];

fn params() -> Params {
    Params::new(PARAMS)
}

struct NormalWorld {
    params: Params,
    transform: Uniforms<TransformUniforms>,
    program: Program<Vertex>,
    teapot: GpuMesh<Vertex>,
}

fn new(cx: &LabContext) -> Result<Box<dyn Lab>> {
    let transform = Uniforms::new(
        cx.gpu,
        "normal_world.transform",
        TransformUniforms::new(glam::Mat4::IDENTITY, stage::projection_stack(stage::EYE)),
    );
    let mut program = Program::new(
        cx,
        "normal_world",
        "normal_world.vert",
        "normal_world.frag",
        RenderState::default(),
    )?;
    program.bind(cx.gpu, vec![transform.bind()])?;
    Ok(Box::new(NormalWorld {
        params: params(),
        transform,
        program,
        teapot: stage::teapot(cx.gpu, "normal_world.teapot"),
    }))
}

impl Lab for NormalWorld {
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
        let Input::Key(c) = input else {
            return false;
        };
        let name = match c.to_ascii_lowercase() {
            'x' => "rx",
            'y' => "ry",
            'z' => "rz",
            _ => return false,
        };
        self.params.step(name, if c.is_ascii_uppercase() { 5.0 } else { -5.0 });
        true
    }
    fn reload(&mut self, cx: &LabContext) -> Result<()> {
        self.program.reload(cx)
    }
    fn render(&mut self, frame: &mut Frame<'_>) -> Result<()> {
        let p = &self.params;
        let model = stage::model_zyx(p.f("rx"), p.f("ry"), p.f("rz"));
        let eye = glam::Vec3::from_array(p.v3("eye"));
        self.transform.value = TransformUniforms::new(model, stage::projection_stack(eye));
        self.transform.upload(frame.gpu);
        let mut pass = frame.pass("normal_world", Load::Clear([0.0; 3]));
        self.program.draw(&mut pass, &self.teapot);
        Ok(())
    }
}
