//! Seed 001 `envmap` (SPEC §1.10): a cube-map environment (reflection) map. The course's
//! fragment shader looks up `textureCube(texMap, R)` with the reflection of the view ray about
//! the normal, computed in world space with the model matrix passed as a uniform. The cube map
//! has six coloured faces (SPEC §0.1: +X red, −X cyan, +Y green, −Y magenta, +Z blue, −Z yellow,
//! white grid lines, a darker quadrant showing each face's orientation); `GL_LINEAR`, no
//! mipmaps, `GL_CLAMP_TO_EDGE`, seamless. No skybox is drawn.
//!
//! Keys: `1`-`4` objects; left drag rotates.

use glam::Vec3;

use crate::error::Result;
use crate::geometry::images;
use crate::lab::{FilesTaken, Input, Lab, LabContext, LabEntry, LabInfo};
use crate::mesh::Vertex;
use crate::params::Params;
use crate::render::{sampler, Bind, Frame, Load, Program, RenderState, SamplerDesc, Texture, Uniforms};

use crate::labs::seed001::stage::{Solids, UstcStage, OBJECT, ROTATION};

/// Seed 001, §1.10.
pub static INFO: LabInfo = LabInfo {
    name: "envmap",
    title: "ref001",
    label: "environment map",
    lecture: "001 USTC GLSL (III)",
    size: (512, 512),
    keys: crate::lab::Keys::text("1-4: objects; left drag rotates"),
    files: FilesTaken::NONE,
};

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params,
    new,
};

/// The `EnvMap` block of `envmap.vert`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct EnvMapUniforms {
    /// `modelMatrix`: Rx(xangle)·Ry(yangle).
    pub model_matrix: [[f32; 4]; 4],
    /// `eyeWorld`: the eye in world space.
    pub eye_world: [f32; 3],
    /// std140 rounds the block up to 16 bytes.
    pub _pad: f32,
}
crate::uniform_block!(EnvMapUniforms, "EnvMap", {
    model_matrix: "modelMatrix",
    eye_world: "eyeWorld",
});

/// The eye.
const EYE: Vec3 = Vec3::new(0.0, 0.0, 4.0);

fn params() -> Params {
    let mut p = Params::new(OBJECT);
    p.extend(ROTATION);
    p
}

struct EnvMap {
    params: Params,
    stage: UstcStage,
    uniforms: Uniforms<EnvMapUniforms>,
    program: Program<Vertex>,
    solids: Solids,
}

fn uniforms_of(p: &Params) -> EnvMapUniforms {
    EnvMapUniforms {
        model_matrix: UstcStage::model(p).to_cols_array_2d(),
        eye_world: EYE.to_array(),
        _pad: 0.0,
    }
}

fn new(cx: &LabContext) -> Result<Box<dyn Lab>> {
    let stage = UstcStage::new(cx.gpu, "envmap", EYE);
    let p = params();
    let uniforms = Uniforms::new(cx.gpu, "envmap.params", uniforms_of(&p));
    let faces = images::cube_faces();
    let cube = Texture::new(cx.gpu, "envmap.cube", faces.width, faces.height, 6, &[faces.rgba]);
    let clamp = wgpu::AddressMode::ClampToEdge;
    let sampler = sampler(
        cx.gpu,
        "envmap.sampler",
        &SamplerDesc {
            wrap: [clamp; 3],
            ..SamplerDesc::default()
        },
    );
    let mut program = Program::new(cx, "envmap", "envmap.vert", "envmap.frag", RenderState::default())?;
    program.bind(
        cx.gpu,
        vec![
            stage.transform.bind(),
            uniforms.bind(),
            Bind::texture("texMap", &cube),
            Bind::sampler("texMapSampler", &sampler),
        ],
    )?;
    Ok(Box::new(EnvMap {
        params: p,
        stage,
        uniforms,
        program,
        solids: Solids::default(),
    }))
}

impl Lab for EnvMap {
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
        self.stage.input(&mut self.params, input)
    }
    fn reload(&mut self, cx: &LabContext) -> Result<()> {
        self.program.reload(cx)
    }
    fn render(&mut self, frame: &mut Frame<'_>) -> Result<()> {
        let gpu = frame.gpu;
        self.uniforms.value = uniforms_of(&self.params);
        self.uniforms.upload(gpu);
        self.stage.upload(gpu, &self.params, frame.width, frame.height);
        let mesh = self.solids.get(gpu, UstcStage::object(&self.params));
        let mut pass = frame.pass("envmap", Load::Clear([0.0; 3]));
        self.program.draw(&mut pass, mesh);
        Ok(())
    }
}
