//! Seed 002 (Lecture 12) `phong_dir`, SPEC §2.4: Phong shading with a directional light
//! (direction (1,1,1) toward the light, world space), an emission term and the eye at (0,0,5),
//! on `glutSolidTeapot(1.0)` turned by `glRotated(rx, 1,0,0)`; the view is folded into the
//! projection as in `normal_world` ([`crate::labs::seed002::stage`]), so normals and positions
//! are in world space. Depth test on.
//!
//! Course bug kept (SPEC §6.2 #1): the vertex shader computes `position =
//! (gl_ModelViewMatrix * gl_Position).xyz` — the *clip-space* position (GL's, depth −w..w)
//! turned by the model — so the highlight sits where that puts it. `fixpos=1` (key `p`)
//! renders the intent, `(gl_ModelViewMatrix * gl_Vertex).xyz`. The slide stops after the
//! rotation: `glUseProgram` first and the teapot are pinned (#6).
//!
//! Keys: ↑/↓ rx ±5°; `p` toggles fixpos.

use glam::Mat4;

use crate::error::Result;
use crate::lab::{FilesTaken, Input, Lab, LabContext, LabEntry, LabInfo, Special};
use crate::mesh::Vertex;
use crate::params::{ParamSpec, Params};
use crate::render::{Frame, GpuMesh, Load, Program, RenderState, Uniforms};

use crate::labs::common::TransformUniforms;
use crate::labs::seed002::stage;

/// `phong_dir`.
pub static INFO: LabInfo = LabInfo {
    name: "phong_dir",
    title: "ref002",
    label: "Phong, directional light",
    lecture: "002 Lecture 12",
    size: (512, 512),
    keys: crate::lab::Keys::text("Up/Down: rx ±5°; p: fixpos (course bug / gl_Vertex)"),
    files: FilesTaken::NONE,
};

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params,
    new,
};

/// The `PhongDir` block of `phong_dir_params.glsl` (std140: each vec3 takes 16 bytes unless a
/// scalar shares them).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct PhongDirUniforms {
    /// `material_ambient`.
    pub material_ambient: [f32; 3],
    /// `material_shininess`.
    pub material_shininess: f32,
    /// `material_diffuse`.
    pub material_diffuse: [f32; 3],
    /// `fixpos`: 0 = the course's `gl_Position`, 1 = `gl_Vertex`.
    pub fixpos: i32,
    /// `material_specular`.
    pub material_specular: [f32; 3],
    /// std140 padding.
    pub _pad0: f32,
    /// `material_emission`.
    pub material_emission: [f32; 3],
    /// std140 padding.
    pub _pad1: f32,
    /// `light_ambient`.
    pub light_ambient: [f32; 3],
    /// std140 padding.
    pub _pad2: f32,
    /// `light_intensity`.
    pub light_intensity: [f32; 3],
    /// std140 padding.
    pub _pad3: f32,
    /// `light_direction`, world space, toward the light.
    pub light_direction: [f32; 3],
    /// std140 padding.
    pub _pad4: f32,
    /// `eye`.
    pub eye: [f32; 3],
    /// std140 padding.
    pub _pad5: f32,
    /// `gl_ModelViewProjectionMatrix` in GL's depth convention (what the bug multiplies).
    pub mvp_gl: [[f32; 4]; 4],
}
crate::uniform_block!(PhongDirUniforms, "PhongDir", {
    material_ambient: "material_ambient",
    material_shininess: "material_shininess",
    material_diffuse: "material_diffuse",
    fixpos: "fixpos",
    material_specular: "material_specular",
    material_emission: "material_emission",
    light_ambient: "light_ambient",
    light_intensity: "light_intensity",
    light_direction: "light_direction",
    eye: "eye",
    mvp_gl: "mvp_gl",
});

impl PhongDirUniforms {
    /// The course's values (SPEC §2.4) with a model matrix and the fix switch.
    pub fn course(model: Mat4, fixpos: bool) -> Self {
        PhongDirUniforms {
            material_ambient: [0.1, 0.1, 0.1],
            material_shininess: 100.0,
            material_diffuse: [0.5, 0.5, 0.8],
            fixpos: i32::from(fixpos),
            material_specular: [1.0, 1.0, 1.0],
            _pad0: 0.0,
            material_emission: [0.0, 0.0, 0.0],
            _pad1: 0.0,
            light_ambient: [1.0, 1.0, 1.0],
            _pad2: 0.0,
            light_intensity: [1.0, 1.0, 1.0],
            _pad3: 0.0,
            light_direction: [1.0, 1.0, 1.0],
            _pad4: 0.0,
            eye: stage::EYE.to_array(),
            _pad5: 0.0,
            mvp_gl: (stage::projection_stack_gl(stage::EYE) * model).to_cols_array_2d(),
        }
    }
}

const PARAMS: &[ParamSpec] = &[
    ParamSpec::real("rx", &[0.0], -36000.0, 36000.0, "glRotated about x, degrees (Up/Down)"),
    ParamSpec::flag(
        "fixpos",
        &[0.0],
        "0: position from gl_Position (course bug), 1: from gl_Vertex (p)",
    ),
];

fn params() -> Params {
    Params::new(PARAMS)
}

struct PhongDir {
    params: Params,
    transform: Uniforms<TransformUniforms>,
    uniforms: Uniforms<PhongDirUniforms>,
    program: Program<Vertex>,
    teapot: GpuMesh<Vertex>,
}

fn new(cx: &LabContext) -> Result<Box<dyn Lab>> {
    let transform = Uniforms::new(
        cx.gpu,
        "phong_dir.transform",
        TransformUniforms::new(Mat4::IDENTITY, stage::projection_stack(stage::EYE)),
    );
    let uniforms = Uniforms::new(
        cx.gpu,
        "phong_dir.params",
        PhongDirUniforms::course(Mat4::IDENTITY, false),
    );
    let mut program = Program::new(
        cx,
        "phong_dir",
        "phong_dir.vert",
        "phong_dir.frag",
        RenderState::default(),
    )?;
    program.bind(cx.gpu, vec![transform.bind(), uniforms.bind()])?;
    Ok(Box::new(PhongDir {
        params: params(),
        transform,
        uniforms,
        program,
        teapot: stage::teapot(cx.gpu, "phong_dir.teapot"),
    }))
}

impl Lab for PhongDir {
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
            Input::Special(Special::Up) => self.params.step("rx", 5.0),
            Input::Special(Special::Down) => self.params.step("rx", -5.0),
            Input::Key('p' | 'P') => self.params.toggle("fixpos"),
            _ => return false,
        }
        true
    }
    fn reload(&mut self, cx: &LabContext) -> Result<()> {
        self.program.reload(cx)
    }
    fn render(&mut self, frame: &mut Frame<'_>) -> Result<()> {
        let model = model_rx(self.params.f("rx"));
        self.transform.value = TransformUniforms::new(model, stage::projection_stack(stage::EYE));
        self.transform.upload(frame.gpu);
        self.uniforms.value = PhongDirUniforms::course(model, self.params.on("fixpos"));
        self.uniforms.upload(frame.gpu);
        let mut pass = frame.pass("phong_dir", Load::Clear([0.0; 3]));
        self.program.draw(&mut pass, &self.teapot);
        Ok(())
    }
}

/// The modelview: `glRotated(rx, 1,0,0)` (float, as Mesa's glRotated).
fn model_rx(rx: f32) -> Mat4 {
    stage::model_zyx(rx, 0.0, 0.0)
}
