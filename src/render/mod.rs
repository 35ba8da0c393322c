//! The wgpu layer every lab is composed from: [`Program`] (a pipeline whose bind-group layout
//! comes from naga's reflection, bound by GLSL name), [`Uniforms`] (a typed uniform block),
//! [`GpuMesh`] and [`VertexType`] (vertex data whose attributes are checked against the
//! shader's inputs), [`Texture`] and samplers, and [`Frame`] (where one frame is recorded).
//! Nothing here knows a lab or winit.

mod frame;
mod mesh;
mod program;
mod texture;
mod uniforms;

pub use frame::{Frame, Load};
pub use mesh::{GpuMesh, VertexAttr, VertexType};
pub use program::{
    reflect_bindings, reflect_inputs, AnyProgram, Bind, BindingInfo, BindingKind, Program, RenderState, Resource, VertexInput,
};
pub use texture::{sampler, SamplerDesc, Texture};
pub use uniforms::Uniforms;
