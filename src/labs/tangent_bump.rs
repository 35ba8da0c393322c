//! The part `bump` and `normmap` (seed 001 §1.11–1.12) share: one quad facing the eye with a
//! tangent at every vertex (`attribute vec4 objTangent`), the tangent-space vertex shader that
//! turns the light into the frame (T, B = N × T, N), the egg-crate normal map (SPEC §0.1,
//! `GL_REPEAT`, `GL_LINEAR`, no mipmaps, unit 0), GL's light block with the bump light and
//! material, the light keys and the rotation. Each lab brings its fragment shader (and
//! `normmap` its normalization cube map on unit 1).

use glam::Vec3;

use crate::error::Result;
use crate::geometry::images;
use crate::geometry::shapes::{bump_quad, BumpVertex};
use crate::lab::{Input, Lab, LabContext, LabInfo};
use crate::params::Params;
use crate::render::{sampler, Bind, Frame, GpuMesh, Load, Program, RenderState, SamplerDesc, Texture};

use super::gl_light::{GlLight, BUMP};
use super::ustc_stage::{UstcStage, ROTATION};

/// The keys of `bump` and `normmap`.
pub const KEYS: &str = "←/→: light x ∓0.25; ↑/↓: light y ±0.25; PageUp/PageDown: light z ±0.25; left drag rotates";

// gl_Vertex, gl_Normal, the objTangent attribute and gl_MultiTexCoord0.
crate::vertex_type!(BumpVertex, {
    position: "vertex_position" => Float32x3,
    normal: "vertex_normal" => Float32x3,
    tangent: "objTangent" => Float32x4,
    st: "vertex_texcoord" => Float32x2,
});

/// The parameters of `bump` and `normmap`.
pub fn params() -> Params {
    let mut p = Params::new(ROTATION);
    p.extend(BUMP.params);
    p
}

struct BumpLab {
    info: &'static LabInfo,
    params: Params,
    stage: UstcStage,
    light: GlLight,
    program: Program<BumpVertex>,
    quad: GpuMesh<BumpVertex>,
}

/// Builds the bump lab with fragment shader `frag`, and `extra` bindings (texture unit 1 of
/// `normmap`).
pub(super) fn build(
    cx: &LabContext,
    info: &'static LabInfo,
    frag: &str,
    extra: Option<Vec<Bind>>,
) -> Result<Box<dyn Lab>> {
    let stage = UstcStage::new(cx.gpu, info.name, Vec3::new(0.0, 0.0, 4.0));
    let light = GlLight::new(cx.gpu, info.name, &BUMP);
    let map = images::bump_normal_map();
    let normal_map = Texture::new(
        cx.gpu,
        &format!("{}.normal_map", info.name),
        map.width,
        map.height,
        1,
        &[map.rgba],
    );
    // GL_REPEAT, GL_LINEAR/GL_LINEAR, no mipmaps.
    let sampler = sampler(cx.gpu, &format!("{}.sampler", info.name), &SamplerDesc::default());
    let mut program = Program::new(cx, info.name, "bump.vert", frag, RenderState::default())?;
    let mut bindings = vec![
        stage.transform.bind(),
        light.uniforms.bind(),
        Bind::texture("texMap", &normal_map),
        Bind::sampler("texMapSampler", &sampler),
    ];
    bindings.extend(extra.unwrap_or_default());
    program.bind(cx.gpu, bindings)?;
    let quad = GpuMesh::new(cx.gpu, &format!("{}.quad", info.name), &bump_quad(), None);
    Ok(Box::new(BumpLab {
        info,
        params: params(),
        stage,
        light,
        program,
        quad,
    }))
}

impl Lab for BumpLab {
    fn info(&self) -> &'static LabInfo {
        self.info
    }
    fn params(&self) -> &Params {
        &self.params
    }
    fn params_mut(&mut self) -> &mut Params {
        &mut self.params
    }
    fn input(&mut self, input: Input) -> bool {
        self.light.input(&mut self.params, input) || self.stage.input(&mut self.params, input)
    }
    fn reload(&mut self, cx: &LabContext) -> Result<()> {
        self.program.reload(cx)
    }
    fn render(&mut self, frame: &mut Frame<'_>) -> Result<()> {
        let gpu = frame.gpu;
        self.light.upload(gpu, &self.params);
        self.stage.upload(gpu, &self.params, frame.width, frame.height);
        let mut pass = frame.pass(self.info.name, Load::Clear([0.0; 3]));
        self.program.draw(&mut pass, &self.quad);
        Ok(())
    }
}
