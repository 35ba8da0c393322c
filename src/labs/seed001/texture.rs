//! Seed 001 `texture` (SPEC §1.9): texture mapping with a sampler, the course's snippet made
//! whole: the uvgrid image (SPEC §0.1) on freeglut's teapot through its own texture
//! coordinates (each patch gets the same (u/7, v/7) table, so the grid repeats per patch and is
//! mirrored on the reflected patches). `GL_REPEAT`, `GL_LINEAR`/`GL_LINEAR`, no mipmaps, unit 0.
//!
//! Keys: left drag rotates.

use glam::Vec3;

use crate::error::Result;
use crate::geometry::glut::teapot_texcoords;
use crate::geometry::images;
use crate::lab::{FilesTaken, Input, Lab, LabContext, LabEntry, LabInfo};
use crate::mesh::Mesh;
use crate::params::Params;
use crate::render::{sampler, Bind, Frame, GpuMesh, Load, Program, RenderState, SamplerDesc, Texture};

use crate::labs::seed001::stage::{UstcStage, ROTATION};

/// Seed 001, §1.9.
pub static INFO: LabInfo = LabInfo {
    name: "texture",
    title: "ref001",
    label: "texture mapping",
    lecture: "001 USTC GLSL (III)",
    size: (512, 512),
    keys: crate::lab::Keys::text("left drag rotates"),
    files: FilesTaken::NONE,
};

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params,
    new,
};

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

fn params() -> Params {
    Params::new(ROTATION)
}

struct TextureLab {
    params: Params,
    stage: UstcStage,
    program: Program<TexturedVertex>,
    teapot: GpuMesh<TexturedVertex>,
}

fn new(cx: &LabContext) -> Result<Box<dyn Lab>> {
    let stage = UstcStage::new(cx.gpu, "texture", Vec3::new(0.0, 0.0, 4.0));
    let image = images::uvgrid();
    let texture = Texture::new(cx.gpu, "texture.uvgrid", image.width, image.height, 1, &[image.rgba]);
    // GL_REPEAT on s and t, GL_LINEAR for both filters, no mipmaps.
    let sampler = sampler(cx.gpu, "texture.sampler", &SamplerDesc::default());
    let mut program = Program::new(cx, "texture", "texture.vert", "texture.frag", RenderState::default())?;
    program.bind(
        cx.gpu,
        vec![
            stage.transform.bind(),
            Bind::texture("myTexture", &texture),
            Bind::sampler("myTextureSampler", &sampler),
        ],
    )?;
    let (vertices, indices) = textured_teapot();
    let teapot = GpuMesh::new(cx.gpu, "texture.teapot", &vertices, Some(&indices));
    Ok(Box::new(TextureLab {
        params: params(),
        stage,
        program,
        teapot,
    }))
}

impl Lab for TextureLab {
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
        self.stage.upload(frame.gpu, &self.params, frame.width, frame.height);
        let mut pass = frame.pass("texture", Load::Clear([0.0; 3]));
        self.program.draw(&mut pass, &self.teapot);
        Ok(())
    }
}
