//! Vertex data on the GPU. A [`VertexType`] names its attributes as the shaders call them;
//! [`Program`](super::Program) checks them against the reflected vertex inputs.

use std::marker::PhantomData;

use wgpu::util::DeviceExt;

use crate::gpu::Gpu;

/// One attribute of a vertex type.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexAttr {
    /// The GLSL input it feeds (`vertex_position`, `v_coord`, `height`).
    pub name: &'static str,
    /// Its format.
    pub format: wgpu::VertexFormat,
    /// Byte offset in the vertex.
    pub offset: u64,
}

/// A `#[repr(C)]` vertex whose fields feed named shader inputs. Implement it with
/// [`vertex_type!`](crate::vertex_type).
pub trait VertexType: bytemuck::Pod {
    /// The attributes, by GLSL name.
    const ATTRIBUTES: &'static [VertexAttr];
}

/// Implements [`VertexType`]: `vertex_type!(Vertex, { position: "vertex_position" => Float32x3, ... })`.
#[macro_export]
macro_rules! vertex_type {
    ($ty:ty, { $($field:ident : $glsl:literal => $format:ident),* $(,)? }) => {
        impl $crate::render::VertexType for $ty {
            const ATTRIBUTES: &'static [$crate::render::VertexAttr] = &[$($crate::render::VertexAttr {
                name: $glsl,
                format: ::wgpu::VertexFormat::$format,
                offset: ::core::mem::offset_of!($ty, $field) as u64,
            }),*];
        }
    };
}

// GLUT's meshes: gl_Vertex and gl_Normal, as seed 000's shaders name them.
vertex_type!(crate::mesh::Vertex, {
    position: "vertex_position" => Float32x3,
    normal: "vertex_normal" => Float32x3,
});

/// Vertices (and optionally indices) of one type on the GPU.
pub struct GpuMesh<V: VertexType> {
    vertices: wgpu::Buffer,
    indices: Option<wgpu::Buffer>,
    count: u32,
    _vertex: PhantomData<V>,
}

impl<V: VertexType> GpuMesh<V> {
    /// Uploads `vertices`, drawn in order, or through `indices` when given.
    pub fn new(gpu: &Gpu, label: &str, vertices: &[V], indices: Option<&[u32]>) -> Self {
        let vertex_bytes: &[u8] = bytemuck::cast_slice(vertices);
        // wgpu refuses zero-sized vertex buffers: an empty mesh keeps one unused vertex.
        let padding = [0u8; 16];
        let contents = if vertex_bytes.is_empty() {
            &padding[..]
        } else {
            vertex_bytes
        };
        let buffer = gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(&format!("{label}.vertices")),
            contents,
            usage: wgpu::BufferUsages::VERTEX,
        });
        let (indices, count) = match indices {
            Some(idx) if !idx.is_empty() => (
                Some(gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(&format!("{label}.indices")),
                    contents: bytemuck::cast_slice(idx),
                    usage: wgpu::BufferUsages::INDEX,
                })),
                idx.len() as u32,
            ),
            Some(_) => (None, 0),
            None => (None, vertices.len() as u32),
        };
        GpuMesh {
            vertices: buffer,
            indices,
            count,
            _vertex: PhantomData,
        }
    }

    /// Vertices (or indices) drawn.
    pub fn count(&self) -> u32 {
        self.count
    }

    /// Records the draw of `range` of the vertices (or indices).
    pub(crate) fn draw_range(&self, pass: &mut wgpu::RenderPass<'_>, range: std::ops::Range<u32>) {
        pass.set_vertex_buffer(0, self.vertices.slice(..));
        match &self.indices {
            Some(indices) => {
                pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(range, 0, 0..1);
            }
            None => pass.draw(range, 0..1),
        }
    }
}
