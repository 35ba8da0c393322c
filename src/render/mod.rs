//! The wgpu layer every lab is composed from: [`Program`] (a pipeline whose bind-group layout
//! comes from naga's reflection, bound by GLSL name), [`Uniforms`] (a typed uniform block),
//! [`GpuMesh`] and [`VertexType`] (vertex data whose attributes are checked against the
//! shader's inputs), [`Texture`] and samplers, and [`Frame`] (where one frame is recorded).
//! Nothing here knows a lab or winit.

use crate::gpu::Gpu;
use crate::shader::ShaderSource;

/// What programs, textures and labs are built with: the device, where shader files come from,
/// the colour format drawn into, the user's files, and the name that what is built is labelled
/// with (set by [`crate::lab::Runner`] to the lab's name from its registration).
/// Made by [`BuildContext::new`] only, so a new field has one place to get its default.
#[derive(Clone, Copy)]
#[non_exhaustive]
pub struct BuildContext<'a> {
    /// The device.
    pub gpu: &'a Gpu,
    /// Where shader files come from.
    pub source: &'a ShaderSource,
    /// The colour format of the targets it will draw into.
    pub format: wgpu::TextureFormat,
    /// Files the user named for the lab to draw instead of its built-in data.
    pub files: &'a crate::user_files::UserFiles,
    /// The name that the labels of what is built and the messages about it begin with (the
    /// lab's name, `phong`; empty outside a lab).
    pub name: &'static str,
}

impl<'a> BuildContext<'a> {
    /// What to build with on `gpu`, from `source`, drawing in `format`, with the user's `files`;
    /// its name is empty until [`BuildContext::named`] gives one.
    pub fn new(
        gpu: &'a Gpu,
        source: &'a ShaderSource,
        format: wgpu::TextureFormat,
        files: &'a crate::user_files::UserFiles,
    ) -> Self {
        BuildContext {
            gpu,
            source,
            format,
            files,
            name: "",
        }
    }

    /// The same, named `name`: the labels of what it builds and the messages about it begin
    /// with `name` (a lab's name).
    pub fn named(self, name: &'static str) -> Self {
        BuildContext { name, ..self }
    }
}

mod frame;
mod log;
mod mesh;
mod param_block;
mod program;
mod texture;
mod uniforms;

pub use frame::{Frame, Load, Pass};
pub use log::{DrawCall, DrawLog, DrawSetup, Scissor, Texels, Viewport};
pub use mesh::{
    check_fits, facing_first, note_once, GpuMesh, TieGuard, VertexAttr, VertexType, ViewOrdered, LARGE_MESH_TRIANGLES,
    SORT_EVERY_FRAME,
};
pub use param_block::{Derived, ParamBlock};
pub use program::{
    depth_state, reflect_bindings, reflect_inputs, AnyProgram, Bind, BindingInfo, BindingKind, Culling, Program,
    RenderState, Resource, VertexInput,
};
pub use texture::{check_texture_size, sampler, Sampler, SamplerDesc, Texture};
pub use uniforms::Uniforms;
