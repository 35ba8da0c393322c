//! A uniform block with no Rust struct: its bytes are laid out by the block naga reflected and
//! filled by GLSL member name, from the lab's [`Params`] or from values the lab computes each
//! frame ([`Derived`]). A parameter that feeds a uniform is then declared once, as its
//! [`ParamSpec`](crate::params::ParamSpec); a typed struct ([`Uniforms`](super::Uniforms))
//! stays only where Rust computes the whole block (matrices).

use crate::error::{Error, Result};
use crate::gpu::Gpu;
use crate::params::Params;
use crate::shader::{set_member_bytes, BlockLayout};

use super::program::{Bind, Resource};

/// Values a lab computes per frame for members no parameter feeds as is (a wrapped clock,
/// `Ka` = (ka, ka, ka, 1)), by GLSL member name; they win over a parameter of the same name.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Derived {
    values: Vec<(&'static str, Vec<f32>)>,
}

impl Derived {
    /// Sets member `name` to `values`.
    pub fn set(&mut self, name: &'static str, values: &[f32]) {
        match self.values.iter_mut().find(|(n, _)| *n == name) {
            Some((_, v)) => {
                v.clear();
                v.extend_from_slice(values);
            }
            None => self.values.push((name, values.to_vec())),
        }
    }

    /// The values set for `name`.
    pub fn get(&self, name: &str) -> Option<&[f32]> {
        self.values.iter().find(|(n, _)| *n == name).map(|(_, v)| v.as_slice())
    }
}

/// A uniform block filled by member name, and its buffer.
pub struct ParamBlock {
    layout: BlockLayout,
    bytes: Vec<u8>,
    uploaded: Vec<u8>,
    buffer: wgpu::Buffer,
    label: String,
}

impl ParamBlock {
    /// A buffer for `layout`, checking that every member is fed: by a parameter of the same
    /// name with as many values, or by a computed value (`computed` holds the names the lab
    /// computes, with example values).
    pub fn new(gpu: &Gpu, label: &str, layout: &BlockLayout, params: &Params, computed: &Derived) -> Result<Self> {
        let mut block = ParamBlock {
            layout: layout.clone(),
            bytes: vec![0; layout.size.max(16)],
            uploaded: Vec::new(),
            buffer: gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: layout.size.max(16) as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            label: label.to_owned(),
        };
        block.fill(params, computed)?;
        Ok(block)
    }

    /// The GLSL block name.
    pub fn name(&self) -> &str {
        &self.layout.name
    }

    /// Writes every member from `computed` or `params`, by name; fails naming the member no
    /// value feeds, or one whose value has the wrong number of components.
    pub fn fill(&mut self, params: &Params, computed: &Derived) -> Result<()> {
        let mut scratch: Vec<f32> = Vec::new();
        for member in &self.layout.members {
            let values: &[f32] = match (computed.get(&member.name), params.get(&member.name)) {
                (Some(v), _) => v,
                (None, Some(v)) => {
                    scratch.clear();
                    scratch.extend(v.iter().map(|&x| x as f32));
                    &scratch
                }
                (None, None) => {
                    return Err(Error::Layout(format!(
                    "{}: uniform block {} member `{}` has no parameter of that name and no value computed by the lab",
                    self.label,
                    self.layout.name,
                    member.declaration()
                )))
                }
            };
            set_member_bytes(&mut self.bytes, &self.layout, &member.name, values)
                .map_err(|e| Error::Layout(format!("{}: {e}", self.label)))?;
        }
        Ok(())
    }

    /// Makes the buffer hold the bytes, writing only when they changed (as
    /// [`Uniforms::upload`](super::Uniforms::upload) does).
    pub fn upload(&mut self, gpu: &Gpu) {
        if self.bytes != self.uploaded {
            gpu.queue.write_buffer(&self.buffer, 0, &self.bytes);
            self.uploaded.clone_from(&self.bytes);
        }
    }

    /// The binding of this block by its GLSL name; binding checks that the program's block
    /// has the layout this one was made for.
    pub fn bind(&self) -> Bind {
        Bind {
            name: self.layout.name.clone(),
            resource: Resource::Block {
                buffer: self.buffer.clone(),
                layout: self.layout.clone(),
            },
        }
    }
}
