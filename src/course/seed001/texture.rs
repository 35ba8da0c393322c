//! Seed 001 `texture` (SPEC §1.9): texture mapping with a sampler, the course's snippet made
//! whole: the uvgrid image (SPEC §0.1) on freeglut's teapot through its own texture
//! coordinates (each patch gets the same (u/7, v/7) table, so the grid repeats per patch and is
//! mirrored on the reflected patches). `GL_REPEAT`, `GL_LINEAR`/`GL_LINEAR`, no mipmaps, unit 0.
//!
//! Keys: left drag rotates.

use glam::Vec3;

use crate::course::common::FaceOrder;
use crate::images;
use crate::lab::{Keys, Material, MaterialScene, Recipe, ShaderPair};
use crate::mesh::glut::teapot_texcoords;
use crate::mesh::tess::Object;
use crate::mesh::Mesh;
use crate::render::{sampler, Bind, SamplerDesc, Texture, ViewOrdered};

use crate::course::seed001::geometry::{OrderedGeometry, UstcCamera, FACES, ROTATION};

/// Seed 001, §1.9: no uniform block besides the Transform; the image and its sampler are the
/// lab's own bindings.
pub static RECIPE: Recipe = Recipe::new(
    super::info(
        lab_name!(),
        "ref001",
        "texture mapping",
        Keys::text("left drag rotates"),
    ),
    &[ROTATION, FACES],
    |cx, p| {
        let image = images::uvgrid();
        let texture = Texture::new(cx.gpu, "texture.uvgrid", image.width, image.height, 1, &[image.rgba]);
        let sampler = sampler(cx.gpu, "texture.sampler", &SamplerDesc::default());
        let (vertices, indices) = textured_teapot();
        let positions = vertices.iter().map(|v| v.position).collect();
        let geometry = OrderedGeometry {
            camera: UstcCamera::new(cx.gpu, cx.name, Vec3::new(0.0, 0.0, 4.0)),
            mesh: ViewOrdered::new(cx.gpu, "texture.teapot", &vertices, Some(indices), positions),
            outside: Object::Teapot.outside_winding(),
            auto: FaceOrder::FacingFirst,
        };
        let own = vec![
            Bind::texture("myTexture", &texture),
            Bind::sampler("myTextureSampler", &sampler),
        ];
        MaterialScene::build_with(cx, p, geometry, &MATERIAL, own)
    },
);

static MATERIAL: Material = Material::new(&[ShaderPair::new("texture.vert", "texture.frag")]);

/// A GLUT vertex with freeglut's solid-teapot texture coordinates.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct TexturedVertex {
    /// `gl_Vertex`.
    pub position: [f32; 3],
    /// `gl_Normal`.
    pub normal: [f32; 3],
    /// `gl_MultiTexCoord0` s, t.
    pub st: [f32; 2],
}
crate::vertex_type!(TexturedVertex, {
    position: "vertex_position" => Float32x3,
    normal: "vertex_normal" => Float32x3,
    st: "vertex_texcoord" => Float32x2,
});

/// `glutSolidTeapot(1)` with its texture coordinates, and its triangles.
pub fn textured_teapot() -> (Vec<TexturedVertex>, Vec<u32>) {
    let mesh = Mesh::teapot(1.0, Mesh::TEAPOT_DEFAULT_GRID);
    let st = teapot_texcoords(Mesh::TEAPOT_DEFAULT_GRID);
    let vertices = mesh
        .vertices
        .iter()
        .zip(st)
        .map(|(v, st)| TexturedVertex {
            position: v.position,
            normal: v.normal,
            st,
        })
        .collect();
    (vertices, mesh.indices)
}
