//! The part `bump` and `normmap` (seed 001 §1.11–1.12) share: one quad facing the eye with a
//! tangent at every vertex (`attribute vec4 objTangent`), the tangent-space vertex shader that
//! turns the light into the frame (T, B = N × T, N), the egg-crate normal map (SPEC §0.1,
//! `GL_REPEAT`, `GL_LINEAR`, no mipmaps, unit 0), GL's light block with the bump light and
//! material, the light keys and the rotation. Each lab brings its fragment shader (and
//! `normmap` its normalization cube map on unit 1).

use glam::{Mat4, Vec3, Vec4};

use crate::error::Result;
use crate::geometry::images;
use crate::geometry::shapes::{bump_quad, needs_clipping, BumpVertex, QUAD_SPLIT_CLIPPED, QUAD_SPLIT_UNCLIPPED};
use crate::lab::{Input, Lab, LabContext, LabInfo};
use crate::params::Params;
use crate::render::{sampler, Bind, Frame, GpuMesh, Load, Program, RenderState, SamplerDesc, Texture};

use crate::labs::seed001::gl_light::{GlLight, BUMP};
use crate::labs::seed001::stage::{UstcStage, ROTATION};

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
    /// The four corners with both of Mesa's `GL_QUADS` splits as indices: 0..6 the unclipped
    /// one, 6..12 the clipped one.
    quad: GpuMesh<BumpVertex>,
}

/// Which half of the quad's indices Mesa's split is for this `mvp`: the per-vertex light
/// vectors differ a lot over the quad, so interpolating them over the other diagonal shows
/// (seen obliquely, 37.8 dB against the original instead of 89).
fn split_range(mvp: &[[f32; 4]; 4]) -> std::ops::Range<u32> {
    let mvp = Mat4::from_cols_array_2d(mvp);
    let corners = bump_quad().map(|v| mvp * Vec4::from((Vec3::from(v.position), 1.0)));
    if needs_clipping(corners) {
        6..12
    } else {
        0..6
    }
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
    let indices: Vec<u32> = QUAD_SPLIT_UNCLIPPED
        .iter()
        .chain(&QUAD_SPLIT_CLIPPED)
        .copied()
        .collect();
    let quad = GpuMesh::new(cx.gpu, &format!("{}.quad", info.name), &bump_quad(), Some(&indices));
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
        let range = split_range(&self.stage.transform.value.mvp);
        self.program.draw_range(&mut pass, &self.quad, range);
        Ok(())
    }
}
