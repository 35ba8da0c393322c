//! The part `bump` and `normmap` (seed 001 §1.11–1.12) share: one quad facing the eye with a
//! tangent at every vertex (`attribute vec4 objTangent`), the tangent-space vertex shader that
//! turns the light into the frame (T, B = N × T, N), the egg-crate normal map (SPEC §0.1,
//! `GL_REPEAT`, `GL_LINEAR`, no mipmaps, unit 0), GL's light block with the bump light and
//! material, the light keys and the rotation. Each lab brings its look (its fragment shader)
//! and `normmap` its normalization cube map on unit 1.

use glam::{Mat4, Vec3, Vec4};

use crate::error::Result;
use crate::gpu::Gpu;
use crate::images;
use crate::lab::{BuildContext, Geometry, Input, Keys, Material, MaterialScene, Scene};
use crate::mesh::shapes::{bump_quad, needs_clipping, BumpVertex, QUAD_SPLIT_CLIPPED, QUAD_SPLIT_UNCLIPPED};
use crate::params::{ParamSpec, Params};
use crate::render::{sampler, Bind, GpuMesh, SamplerDesc, Texture};

use crate::course::seed001::geometry::{UstcCamera, ROTATION};
use crate::course::seed001::gl_light::{Lit, BUMP, BUMP_KEYS};

/// The keys of `bump` and `normmap`.
pub const KEYS: Keys = Keys::rows(&BUMP_KEYS, "left drag rotates");

/// The parameters of `bump` and `normmap`.
pub const PARAMS: &[&[ParamSpec]] = &[ROTATION, BUMP.params];

// gl_Vertex, gl_Normal, the objTangent attribute and gl_MultiTexCoord0.
crate::vertex_type!(BumpVertex, {
    position: "vertex_position" => Float32x3,
    normal: "vertex_normal" => Float32x3,
    tangent: "objTangent" => Float32x4,
    st: "vertex_texcoord" => Float32x2,
});

/// The quad on the shared geometry: its four corners twice, with each of Mesa's `GL_QUADS`
/// splits as indices (the unclipped one, then the clipped one).
struct Quad {
    camera: UstcCamera,
    splits: [GpuMesh<BumpVertex>; 2],
}

/// Whether Mesa splits the quad the clipped way for this `mvp`: the per-vertex light vectors
/// differ a lot over the quad, so interpolating them over the other diagonal shows (seen
/// obliquely, 37.8 dB against the original instead of 89).
fn clipped(mvp: &[[f32; 4]; 4]) -> bool {
    let mvp = Mat4::from_cols_array_2d(mvp);
    needs_clipping(bump_quad().map(|v| mvp * Vec4::from((Vec3::from(v.position), 1.0))))
}

impl Geometry for Quad {
    type Vertex = BumpVertex;
    fn input(&mut self, p: &mut Params, input: Input) -> bool {
        self.camera.input(p, input)
    }
    fn binds(&self) -> Vec<Bind> {
        vec![self.camera.transform.bind()]
    }
    fn prepare(&mut self, gpu: &Gpu, p: &Params, width: u32, height: u32) -> &GpuMesh<BumpVertex> {
        self.camera.upload(gpu, p, width, height);
        &self.splits[usize::from(clipped(&self.camera.transform.value.mvp))]
    }
}

/// Builds the bump scene `name` drawn by `look`, with `extra` bindings (texture unit 1 of
/// `normmap`).
pub fn build(
    cx: &BuildContext,
    name: &str,
    p: &Params,
    look: &'static Material,
    extra: Vec<Bind>,
) -> Result<Box<dyn Scene>> {
    let map = images::bump_normal_map();
    let normal_map = Texture::new(
        cx.gpu,
        &format!("{name}.normal_map"),
        map.width,
        map.height,
        1,
        &[map.rgba],
    );
    // GL_REPEAT, GL_LINEAR/GL_LINEAR, no mipmaps.
    let sampler = sampler(cx.gpu, &format!("{name}.sampler"), &SamplerDesc::default());
    let mut own = vec![
        Bind::texture("texMap", &normal_map),
        Bind::sampler("texMapSampler", &sampler),
    ];
    own.extend(extra);
    let corners = bump_quad();
    let split = |indices: &[u32]| GpuMesh::new(cx.gpu, &format!("{name}.quad"), &corners, Some(indices));
    let quad = Quad {
        camera: UstcCamera::new(cx.gpu, name, Vec3::new(0.0, 0.0, 4.0)),
        splits: [split(&QUAD_SPLIT_UNCLIPPED), split(&QUAD_SPLIT_CLIPPED)],
    };
    MaterialScene::build_with(cx, p, Lit::new(cx.gpu, name, &BUMP, quad), look, own)
}
