//! A typed uniform block: a `#[repr(C)]` struct, its buffer, and the check of the struct
//! against the block naga reflected, run when it is bound to a [`Program`](super::Program).

use crate::gpu::Gpu;
use crate::shader::UniformBlock;

use super::program::{Bind, Resource};

/// A uniform block's CPU value and its GPU buffer.
pub struct Uniforms<U: UniformBlock> {
    /// The value uploaded by [`Uniforms::upload`].
    pub value: U,
    /// What the buffer holds (the value last written to it).
    uploaded: U,
    buffer: wgpu::Buffer,
}

impl<U: UniformBlock> Uniforms<U> {
    /// A buffer for `value`, labelled `label`.
    pub fn new(gpu: &Gpu, label: &str, value: U) -> Self {
        let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: std::mem::size_of::<U>().max(16) as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        gpu.queue.write_buffer(&buffer, 0, bytemuck::bytes_of(&value));
        Uniforms {
            value,
            uploaded: value,
            buffer,
        }
    }

    /// Makes the buffer hold the value (before the pass that reads it). Labs call it every
    /// frame, as the originals call `glUniform*`; like GL drivers, which skip a uniform update
    /// that changes nothing, it writes only bytes that differ from what the buffer holds: each
    /// `write_buffer` costs a staging buffer, a copy and its clean-up.
    pub fn upload(&mut self, gpu: &Gpu) {
        if bytemuck::bytes_of(&self.value) == bytemuck::bytes_of(&self.uploaded) {
            return;
        }
        gpu.queue.write_buffer(&self.buffer, 0, bytemuck::bytes_of(&self.value));
        self.uploaded = self.value;
    }

    /// The binding of this block, by its GLSL block name, with the layout check.
    pub fn bind(&self) -> Bind {
        Bind {
            name: U::BLOCK.to_owned(),
            resource: Resource::Buffer {
                buffer: self.buffer.clone(),
                rust_name: std::any::type_name::<U>(),
                check: crate::shader::check_layout::<U>,
            },
        }
    }

    /// The buffer.
    pub fn buffer(&self) -> &wgpu::Buffer {
        &self.buffer
    }
}
