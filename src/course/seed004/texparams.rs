//! Seed 004 §4.6, texture parameters (pinned scene for the slides' settings): a floor quad
//! y = −1 running 18 units away from the eye at (0, 0.5, 3), textured with the course's
//! checker (or `--texture FILE`) repeated 2 × 9 times, drawn with the shaders of 4.4. Its
//! parameters are GL's: `wrap_s`, `wrap_t` (REPEAT or CLAMP_TO_EDGE: the edge texels stretch
//! outside 0..1), `min` (mipmapped filters average the far squares to grey, NEAREST and LINEAR
//! shimmer in moiré) and `mag` (NEAREST keeps the near squares sharp, LINEAR blurs their
//! edges).
//!
//! Keys: `w` wrap_s, `W` wrap_t, `m` min, `M` mag (each cycles).

use glam::{Mat4, Vec3};

use crate::camera::glm;
use crate::error::Result;
use crate::gpu::Gpu;
use crate::lab::{BuildContext, FilesTaken, Geometry, Key::C, KeyRow, Keys, Recipe, Scene, ShaderPair};
use crate::mesh::obj::ObjCorner;
use crate::mesh::shapes;
use crate::params::{ParamSpec, Params};
use crate::render::{Bind, GpuMesh, Uniforms};

use crate::course::seed004::geometry::SuzanneMatrices;
use crate::course::seed004::gl_textures::{
    self, GlTexture, MinFilter, Sampled, TexParams, MAG_FILTERS, MIN_FILTERS, WRAPS,
};
use crate::course::seed004::info;

/// Seed 004 §4.6.
pub static RECIPE: Recipe = Recipe::new(
    info(
        "texparams",
        "texture parameters",
        Keys::rows(
            &[
                KeyRow::cycle(&[C('w')], "wrap_s"),
                KeyRow::cycle(&[C('W')], "wrap_t"),
                KeyRow::cycle(&[C('m')], "min"),
                KeyRow::cycle(&[C('M')], "mag"),
            ],
            "",
        ),
        FilesTaken {
            texture: true,
            ..FilesTaken::NONE
        },
    ),
    &[&[
        ParamSpec::choice(
            "wrap_s",
            &[0.0],
            WRAPS,
            "GL_TEXTURE_WRAP_S: 0 REPEAT, 1 CLAMP_TO_EDGE (w)",
        ),
        ParamSpec::choice(
            "wrap_t",
            &[0.0],
            WRAPS,
            "GL_TEXTURE_WRAP_T: 0 REPEAT, 1 CLAMP_TO_EDGE (W)",
        ),
        ParamSpec::choice(
            "min",
            &[0.0],
            MIN_FILTERS,
            "GL_TEXTURE_MIN_FILTER: 0 LINEAR_MIPMAP_NEAREST, 1 NEAREST, 2 LINEAR, 3 LINEAR_MIPMAP_LINEAR (m)",
        ),
        ParamSpec::choice(
            "mag",
            &[0.0],
            MAG_FILTERS,
            "GL_TEXTURE_MAG_FILTER: 0 NEAREST, 1 LINEAR (M)",
        ),
        ParamSpec::int(
            "aniso",
            &[1.0],
            1.0,
            16.0,
            "port: anisotropic filtering, samples (1 off; above 1 trilinear + anisotropic, min and mag ignored)",
        ),
    ]],
    build,
);

/// V = `lookAt((0, 0.5, 3), (0, −1, −3), (0, 1, 0))`; M = identity.
pub fn view() -> Mat4 {
    glm::look_at(Vec3::new(0.0, 0.5, 3.0), Vec3::new(0.0, -1.0, -3.0), Vec3::Y)
}

/// The texture parameters the state asks for.
pub fn tex_params(p: &Params) -> TexParams {
    TexParams {
        clamp: [p.index_of("wrap_s") == 1, p.index_of("wrap_t") == 1],
        min: MinFilter::from_index(p.index_of("min")),
        mag_linear: p.index_of("mag") == 1,
        anisotropy: if p.has("aniso") { p.f64("aniso") as u16 } else { 1 },
    }
}

/// The floor seen through [`view`], with the Matrices block of the model's shaders.
struct Floor {
    matrices: Uniforms<SuzanneMatrices>,
    mesh: GpuMesh<ObjCorner>,
}

impl Geometry for Floor {
    type Vertex = ObjCorner;
    fn binds(&self) -> Vec<Bind> {
        vec![self.matrices.bind()]
    }
    fn prepare(&mut self, gpu: &Gpu, _p: &Params, width: u32, height: u32) -> &GpuMesh<ObjCorner> {
        let aspect = width as f32 / height.max(1) as f32;
        self.matrices.value = SuzanneMatrices::new(Mat4::IDENTITY, view(), aspect);
        self.matrices.upload(gpu);
        &self.mesh
    }
}

/// The floor drawn by the shaders of 4.4, sampling the checker (or `--texture`) with the
/// parameters' texture parameters.
fn build(cx: &BuildContext, _p: &Params) -> Result<Box<dyn Scene>> {
    let texture = match &cx.files.texture {
        Some(file) => GlTexture::new(
            cx.gpu,
            "texparams.user",
            &gl_textures::bottom_row_first(&file.data),
            &file.path,
        )?,
        None => gl_textures::checker(cx.gpu)?,
    };
    let matrices = SuzanneMatrices::new(Mat4::IDENTITY, view(), 4.0 / 3.0);
    let floor = Floor {
        matrices: Uniforms::new(cx.gpu, "texparams.matrices", matrices),
        mesh: GpuMesh::new(cx.gpu, "texparams.floor", &shapes::texparams_floor(), None),
    };
    let pair = ShaderPair::new("suzanne_normal_matrix.vert", "suzanne_texture.frag");
    Sampled::build(cx, "texparams", floor, pair, vec![texture], |p| (0, tex_params(p)))
}
