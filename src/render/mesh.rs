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
                    // COPY_DST: [`ViewOrdered`] rewrites the order of the same triangles.
                    usage: wgpu::BufferUsages::INDEX | wgpu::BufferUsages::COPY_DST,
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

/// `indices`' triangles reordered for the view `mvp` (object to clip space): first those that
/// face the eye (wound `outside` on screen), then the others, each group in mesh order.
///
/// With `GL_LESS` the nearest fragment wins whatever the order, except at exact depth ties, so
/// this draws the same pixels as mesh order (tests/faces.rs checks it lab by lab), while the
/// faces turned away arrive after the ones in front of them and fail the early depth test
/// instead of being shaded. It is one draw, where [`Faces::OutsideFirst`](super::Faces) draws
/// the mesh twice (its vertices shaded twice). A triangle with a corner at or behind the eye
/// (w ≤ 0) counts as turned away: its order only costs time, never a pixel.
pub fn facing_first(positions: &[[f32; 3]], indices: &[u32], mvp: glam::Mat4, outside: wgpu::FrontFace) -> Vec<u32> {
    let screen: Vec<Option<glam::Vec2>> = positions
        .iter()
        .map(|&p| {
            let c = mvp * glam::Vec3::from_array(p).extend(1.0);
            (c.w > 0.0).then(|| glam::Vec2::new(c.x, c.y) / c.w)
        })
        .collect();
    let faces_eye = |t: &[u32]| match [t[0], t[1], t[2]].map(|i| screen.get(i as usize).copied().flatten()) {
        [Some(a), Some(b), Some(c)] => {
            let area = (b - a).perp_dot(c - a);
            match outside {
                wgpu::FrontFace::Ccw => area > 0.0,
                wgpu::FrontFace::Cw => area < 0.0,
            }
        }
        _ => false,
    };
    let (mut front, mut back) = (Vec::with_capacity(indices.len()), Vec::new());
    for t in indices.chunks_exact(3) {
        if faces_eye(t) {
            front.extend_from_slice(t);
        } else {
            back.extend_from_slice(t);
        }
    }
    front.extend(back);
    front
}

/// A mesh drawn in mesh order or, for a view, with its triangles facing the eye first
/// ([`facing_first`]; the labs' `faces=facing_first`). Mesh order draws the mesh as given,
/// indexed or not, untouched; the view's order is drawn through an indexed copy built on first
/// use, whose index buffer is rewritten only when the view changes: a still picture costs
/// nothing per frame, a turning one a sort on the CPU and one `write_buffer` (5 µs for GLUT's
/// torus, 14 µs for its teapot). A mesh of more than [`SORT_EVERY_FRAME`] triangles is sorted
/// only once the view holds still for a frame, and drawn in its last order meanwhile: any
/// order draws the same pixels but for exact depth ties, and sorting a 512-level torus (half a
/// million triangles) takes 6.6 ms.
pub struct ViewOrdered<V: VertexType> {
    label: String,
    plain: GpuMesh<V>,
    ordered: Option<GpuMesh<V>>,
    vertices: Vec<V>,
    positions: Vec<[f32; 3]>,
    /// Mesh order's triangles (for an unindexed mesh, every vertex in turn).
    indices: Vec<u32>,
    /// The view (bits of the matrix, winding) `ordered` holds the order for.
    ordered_for: Option<([u32; 16], bool)>,
    /// A large mesh's view seen last frame, not sorted for yet.
    pending: Option<([u32; 16], bool)>,
}

/// The most triangles [`ViewOrdered`] sorts in the frame their view changes (about 0.7 ms).
pub const SORT_EVERY_FRAME: usize = 65_536;

impl<V: VertexType> ViewOrdered<V> {
    /// Uploads the mesh as [`GpuMesh::new`] does; `positions` are the vertices' object-space
    /// positions (what the order is computed from), one per vertex.
    pub fn new(gpu: &Gpu, label: &str, vertices: &[V], indices: Option<Vec<u32>>, positions: Vec<[f32; 3]>) -> Self {
        let plain = GpuMesh::new(gpu, label, vertices, indices.as_deref());
        ViewOrdered {
            label: format!("{label}.facing_first"),
            plain,
            ordered: None,
            vertices: vertices.to_vec(),
            indices: indices.unwrap_or_else(|| (0..vertices.len() as u32).collect()),
            positions,
            ordered_for: None,
            pending: None,
        }
    }

    /// The mesh to draw: facing the eye first for `view` (object-to-clip matrix and the
    /// winding of the mesh's outside), or as given for `None`.
    pub fn get(&mut self, gpu: &Gpu, view: Option<(glam::Mat4, wgpu::FrontFace)>) -> &GpuMesh<V> {
        let Some((mvp, outside)) = view else {
            return &self.plain;
        };
        if self.indices.is_empty() {
            return &self.plain;
        }
        let want = Some((mvp.to_cols_array().map(f32::to_bits), outside == wgpu::FrontFace::Ccw));
        let large = self.indices.len() / 3 > SORT_EVERY_FRAME;
        if large && want != self.ordered_for && want != self.pending {
            // The view moves: keep the last order (or mesh order) until it holds still.
            self.pending = want;
            return self.ordered.as_ref().unwrap_or(&self.plain);
        }
        if want != self.ordered_for || self.ordered.is_none() {
            let order = facing_first(&self.positions, &self.indices, mvp, outside);
            match &self.ordered {
                Some(GpuMesh {
                    indices: Some(buffer), ..
                }) => {
                    gpu.queue.write_buffer(buffer, 0, bytemuck::cast_slice(&order));
                }
                _ => self.ordered = Some(GpuMesh::new(gpu, &self.label, &self.vertices, Some(&order))),
            }
            self.ordered_for = want;
        }
        self.ordered.as_ref().unwrap_or(&self.plain)
    }
}

#[cfg(test)]
mod tests {
    use super::facing_first;
    use glam::Mat4;

    /// Four triangles in the z = 0 plane seen through the identity (x right, y up): 0 and 2
    /// counter-clockwise, 1 clockwise, 3 with a corner behind the eye (w < 0).
    fn scene() -> (Vec<[f32; 3]>, Vec<u32>, Mat4) {
        let positions = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 0.0, 5.0],
        ];
        let indices = vec![0, 1, 2, 0, 2, 1, 1, 3, 2, 0, 1, 4];
        // w = 1 - z/4: the fifth vertex (z = 5) is behind the eye.
        let mvp = Mat4::from_cols_array(&[
            1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, -0.25, 0.0, 0.0, 0.0, 1.0,
        ]);
        (positions, indices, mvp)
    }

    #[test]
    fn facing_triangles_come_first_each_group_in_mesh_order() {
        let (positions, indices, mvp) = scene();
        assert_eq!(
            facing_first(&positions, &indices, mvp, wgpu::FrontFace::Ccw),
            [0, 1, 2, 1, 3, 2, 0, 2, 1, 0, 1, 4]
        );
        // The teapot's outside is clockwise: then the clockwise triangle leads.
        assert_eq!(
            facing_first(&positions, &indices, mvp, wgpu::FrontFace::Cw),
            [0, 2, 1, 0, 1, 2, 1, 3, 2, 0, 1, 4]
        );
    }

    #[test]
    fn the_order_is_a_permutation_of_whole_triangles() {
        let (positions, indices, mvp) = scene();
        let order = facing_first(&positions, &indices, mvp.transpose(), wgpu::FrontFace::Ccw);
        let triangles = |v: &[u32]| {
            let mut t: Vec<[u32; 3]> = v.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
            t.sort();
            t
        };
        assert_eq!(triangles(&order), triangles(&indices));
    }
}
