//! Vertex data on the GPU. A [`VertexType`] names its attributes as the shaders call them;
//! [`Program`](super::Program) checks them against the reflected vertex inputs.

use std::marker::PhantomData;
use std::sync::Arc;

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
pub trait VertexType: bytemuck::Pod + Send + Sync {
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

/// Checks, before anything is made, that `what` fits where it goes: its largest buffer
/// (`buffer_bytes`) within the device's largest, and on a CPU adapter (lavapipe, whose GPU
/// memory is the machine's own) everything it takes (`total_bytes`, CPU copies included) within
/// the memory the machine has available now. A model too large is then one clear message
/// instead of a driver's out-of-memory error after a minute of work.
pub fn check_fits(gpu: &Gpu, what: &str, buffer_bytes: u64, total_bytes: u64) -> crate::error::Result<()> {
    use crate::fsutil::human_bytes;
    let max = gpu.device.limits().max_buffer_size;
    if buffer_bytes > max {
        return Err(crate::error::Error::Limit(format!(
            "{what} needs a vertex buffer of {} ({buffer_bytes} bytes); this GPU takes at most {} in one buffer",
            human_bytes(buffer_bytes),
            human_bytes(max)
        )));
    }
    if gpu.adapter.get_info().device_type == wgpu::DeviceType::Cpu {
        crate::memory::check(
            &format!("{what}, drawn on this CPU adapter (whose GPU memory is the machine's),"),
            total_bytes,
        )?;
    }
    Ok(())
}

/// Triangles above which a mesh is large: an automatic choice (`auto`) never draws more, and a
/// mesh a user asks for beyond it is announced with its cost before it is drawn (on a software
/// rasteriser each frame of such a mesh takes seconds, and memory climbs by the gigabyte;
/// figures: `docs/speed.md`, "Large meshes, models and pictures").
pub const LARGE_MESH_TRIANGLES: u64 = 1_000_000;

/// Prints `message` on stderr once per process (a window draws the same state many times).
pub fn note_once(message: String) {
    static SAID: std::sync::Mutex<Vec<String>> = std::sync::Mutex::new(Vec::new());
    let Ok(mut said) = SAID.lock() else { return };
    if !said.contains(&message) {
        eprintln!("{message}");
        said.push(message);
    }
}

/// An index buffer holding `indices`.
fn index_buffer(gpu: &Gpu, label: &str, indices: &[u32]) -> wgpu::Buffer {
    gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(&format!("{label}.indices")),
        contents: bytemuck::cast_slice(indices),
        // COPY_DST: [`ViewOrdered`] rewrites the order of the same triangles.
        usage: wgpu::BufferUsages::INDEX | wgpu::BufferUsages::COPY_DST,
    })
}

/// Vertices (and optionally indices) of one type on the GPU.
pub struct GpuMesh<V: VertexType> {
    vertices: wgpu::Buffer,
    indices: Option<wgpu::Buffer>,
    /// What `indices` holds, kept on the CPU for the debugger: WebGL2 cannot copy out of an
    /// index buffer (a buffer bound as `ELEMENT_ARRAY_BUFFER` is bound as nothing else).
    index_data: Option<Arc<Vec<u32>>>,
    count: u32,
    _vertex: PhantomData<V>,
}

impl<V: VertexType> GpuMesh<V> {
    /// Uploads `vertices`, drawn in order, or through `indices` when given.
    pub fn new(gpu: &Gpu, label: &str, vertices: &[V], indices: Option<&[u32]>) -> Self {
        let vertex_bytes: &[u8] = bytemuck::cast_slice(vertices);
        let triangles = indices.map_or(vertices.len(), <[u32]>::len) as u64 / 3;
        if triangles > LARGE_MESH_TRIANGLES {
            let bytes = vertex_bytes.len() as u64 + indices.map_or(0, |i| 4 * i.len() as u64);
            note_once(format!(
                "{label}: {triangles} triangles ({} of vertex data), more than the {LARGE_MESH_TRIANGLES} an automatic \
                 choice draws: expect seconds a frame and memory by the gigabyte on a CPU adapter",
                crate::fsutil::human_bytes(bytes)
            ));
        }
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
            // COPY_SRC: the debugger reads the vertices back.
            usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_SRC,
        });
        let index_data = indices.filter(|i| !i.is_empty()).map(|i| Arc::new(i.to_vec()));
        let (indices, count) = match indices {
            Some(idx) if !idx.is_empty() => (Some(index_buffer(gpu, label, idx)), idx.len() as u32),
            Some(_) => (None, 0),
            None => (None, vertices.len() as u32),
        };
        GpuMesh {
            vertices: buffer,
            indices,
            index_data,
            count,
            _vertex: PhantomData,
        }
    }

    /// The same vertices drawn through `indices`: the vertex buffer is shared, not copied.
    pub fn reindexed(&self, gpu: &Gpu, label: &str, indices: Vec<u32>) -> Self {
        GpuMesh {
            vertices: self.vertices.clone(),
            indices: Some(index_buffer(gpu, label, &indices)),
            count: indices.len() as u32,
            index_data: Some(Arc::new(indices)),
            _vertex: PhantomData,
        }
    }

    /// Writes `order` (as many indices as the mesh has) over the indices of a mesh made by
    /// [`GpuMesh::reindexed`] (nothing for a mesh without an index buffer).
    fn rewrite_indices(&mut self, gpu: &Gpu, order: Vec<u32>) {
        if let Some(buffer) = &self.indices {
            gpu.queue.write_buffer(buffer, 0, bytemuck::cast_slice(&order));
            self.index_data = Some(Arc::new(order));
        }
    }

    /// Vertices (or indices) drawn.
    pub fn count(&self) -> u32 {
        self.count
    }

    /// The vertex buffer.
    pub(crate) fn vertex_buffer(&self) -> &wgpu::Buffer {
        &self.vertices
    }

    /// The indices (as uploaded last), if indexed.
    pub(crate) fn index_data(&self) -> Option<&Arc<Vec<u32>>> {
        self.index_data.as_ref()
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
/// face the eye (wound `outside` on screen) and those `guard` keeps with them, then the
/// others, each group in mesh order.
///
/// With `GL_LESS` the nearest fragment wins whatever the order, except at exact depth ties, so
/// this draws the same pixels as mesh order but at ties, while the faces turned away arrive
/// after the ones in front of them and fail the early depth test instead of being shaded. It
/// is one draw, where [`Culling::OutsideFirst`](super::Culling) draws the mesh twice (its vertices
/// shaded twice). A triangle with a corner at or behind the eye (w ≤ 0) counts as turned away.
/// Ties are what [`TieGuard`] is for: without one (`None`) a tie at the silhouette or where the
/// surface passes through itself can settle differently from mesh order (1 px in a few views of
/// 1000 on seed 001's teapot).
pub fn facing_first(
    positions: &[[f32; 3]],
    indices: &[u32],
    mvp: glam::Mat4,
    outside: wgpu::FrontFace,
    guard: Option<&TieGuard>,
) -> Vec<u32> {
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
    let mut first: Vec<bool> = indices.chunks_exact(3).map(faces_eye).collect();
    if let Some(guard) = guard {
        guard.keep_with_facing(&mut first);
    }
    let (mut front, mut back) = (Vec::with_capacity(indices.len()), Vec::new());
    for (t, first) in indices.chunks_exact(3).zip(first) {
        if first {
            front.extend_from_slice(t);
        } else {
            back.extend_from_slice(t);
        }
    }
    front.extend(back);
    front
}

/// Which triangles [`facing_first`] keeps in mesh order among the facing ones, so that no depth
/// tie settles otherwise than in mesh order: built once per mesh.
///
/// Two triangles tie only where their depths are equal at a pixel: where they meet (a shared
/// corner or edge, at the silhouette) or where the surface passes through itself (the teapot's
/// spout and handle through its body). Found on seed 001's teapot, whose near plane at 0.1 makes
/// depths coarse: a turned-away triangle of the body inside the spout drawn after the spout
/// left 1 px of the body's colour, and at the spout's tip an edge shared by a facing and a
/// turned-away triangle settled 1 px one shade of blue apart. So the guard keeps with the
/// facing triangles every triangle that shares an edge with one of them (corners within `eps`
/// of each other are one: patches repeat their seams) and every triangle that crosses, or comes
/// within `eps` of, a triangle it shares no corner with; `eps` is 10⁻⁴ of the mesh's diagonal.
/// The rest of the turned-away triangles, most of them, still go last. (Sharing a corner, not
/// an edge, kept more and measured no safer: 1000 random views of each reordered seed-001 and
/// seed-004 lab byte-identical to mesh order either way.)
pub struct TieGuard {
    /// The triangles that share an edge with each triangle (corners within `eps` of each
    /// other are one): triangle t's are `neighbours[start[t]..start[t + 1]]`.
    neighbours: Vec<u32>,
    /// Where each triangle's neighbours start in `neighbours`, and their end.
    start: Vec<u32>,
    /// Per triangle: it crosses or nearly touches a triangle it shares no corner with.
    crossing: Vec<bool>,
}

/// The most grid cells one triangle may span in [`TieGuard::new`], and the most in all per
/// triangle on average (which bound its memory); a mesh past either is kept in mesh order
/// untested.
const GUARD_CELLS_PER_TRIANGLE: u64 = 4096;
const GUARD_CELLS_ON_AVERAGE: u64 = 64;
/// The most triangles one edge joins before they are kept in mesh order untested.
const GUARD_EDGE_LIMIT: usize = 16;
/// The most triangles one grid cell holds before its triangles are kept untested.
const GUARD_CELL_LIMIT: usize = 512;

impl TieGuard {
    /// Finds the mesh's edges and the triangles that cross another, once per mesh (built with
    /// a mesh's first order; a large mesh sorts only once its view holds still; figures:
    /// `docs/speed.md`, "Ordering the triangles").
    pub fn new(positions: &[[f32; 3]], indices: &[u32]) -> Self {
        use glam::{IVec3, Vec3};
        let points: Vec<Vec3> = positions.iter().map(|&p| Vec3::from_array(p)).collect();
        let (lo, hi) = points
            .iter()
            .filter(|p| p.is_finite())
            .fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(l, h), p| {
                (l.min(*p), h.max(*p))
            });
        let diagonal = if lo.cmple(hi).all() { (hi - lo).length() } else { 0.0 };
        let eps = (diagonal * 1e-4).max(f32::MIN_POSITIVE);
        let corner = weld(&points, eps);
        let tris: Vec<[Vec3; 3]> = indices
            .chunks_exact(3)
            .map(|t| [0, 1, 2].map(|k| points.get(t[k] as usize).copied().unwrap_or(Vec3::NAN)))
            .collect();
        let corners_of = |t: usize| [0, 1, 2].map(|k| corner.get(indices[3 * t + k] as usize).copied());
        let mut crossing = vec![false; tris.len()];
        // Each triangle's box, grown by eps.
        let boxes: Vec<(Vec3, Vec3)> = tris
            .iter()
            .map(|[a, b, c]| (a.min(*b).min(*c) - eps, a.max(*b).max(*c) + eps))
            .collect();

        // A uniform grid of cells about twice a typical triangle's size (its median extent),
        // at most 128 to a side; each triangle listed in every cell its box touches, and each
        // pair tested in the first cell both touch.
        let mut extents: Vec<f32> = boxes
            .iter()
            .map(|(l, h)| (*h - *l).max_element())
            .filter(|e| e.is_finite())
            .collect();
        let median = if extents.is_empty() {
            0.0
        } else {
            let mid = extents.len() / 2;
            *extents.select_nth_unstable_by(mid, f32::total_cmp).1
        };
        let cell = (2.0 * median).max(diagonal / 128.0).max(eps);
        // Cells from -1 to at most 130 along each axis (a box grown by eps reaches one cell
        // out): shifted by one, a key of 8 bits per axis.
        let cell_of = |p: Vec3| {
            ((p - lo) / cell)
                .floor()
                .as_ivec3()
                .clamp(IVec3::splat(-1), IVec3::splat(254))
        };
        let cells: Vec<(IVec3, IVec3)> = boxes.iter().map(|&(l, h)| (cell_of(l), cell_of(h))).collect();
        let span = |(l, h): (IVec3, IVec3)| {
            let d = (h - l + 1).max(IVec3::ZERO).as_i64vec3();
            (d.x * d.y * d.z) as u64
        };
        let key = |c: IVec3| {
            let c = (c + 1).as_uvec3();
            (c.z << 16) | (c.y << 8) | c.x
        };
        // A triangle that is not finite, or too large to list, could cross any other: then the
        // guard keeps every triangle in mesh order (bad input costs speed, never a pixel).
        let total: u64 = cells.iter().map(|&c| span(c)).sum();
        let listable = boxes.iter().all(|(l, h)| l.is_finite() && h.is_finite())
            && cells.iter().all(|&c| span(c) <= GUARD_CELLS_PER_TRIANGLE)
            && total <= GUARD_CELLS_ON_AVERAGE * tris.len() as u64 + GUARD_CELLS_PER_TRIANGLE;
        if !listable {
            crossing.fill(true);
        }
        let mut listed: Vec<u64> = Vec::with_capacity(if listable { total as usize } else { 0 });
        for (t, &(l, h)) in cells.iter().enumerate().filter(|_| listable) {
            for z in l.z..=h.z {
                for y in l.y..=h.y {
                    for x in l.x..=h.x {
                        listed.push(((key(IVec3::new(x, y, z)) as u64) << 32) | t as u64);
                    }
                }
            }
        }
        listed.sort_unstable();
        for list in listed.chunk_by(|a, b| a >> 32 == b >> 32) {
            if list.len() > GUARD_CELL_LIMIT {
                for &e in list {
                    crossing[e as u32 as usize] = true;
                }
                continue;
            }
            let here = (list[0] >> 32) as u32;
            for (n, &i) in list.iter().enumerate() {
                let i = i as u32 as usize;
                for &j in &list[n + 1..] {
                    let j = j as u32 as usize;
                    let ((li, hi), (lj, hj)) = (boxes[i], boxes[j]);
                    // Boxes apart, or this pair's first common cell is another one.
                    if li.cmpgt(hj).any() || lj.cmpgt(hi).any() || key(cells[i].0.max(cells[j].0)) != here {
                        continue;
                    }
                    if (crossing[i] && crossing[j]) || corners_of(i).iter().any(|c| corners_of(j).contains(c)) {
                        continue;
                    }
                    if near(&tris[i], &tris[j], eps) {
                        crossing[i] = true;
                        crossing[j] = true;
                    }
                }
            }
        }
        let (neighbours, start) = edge_neighbours(tris.len(), corners_of, &mut crossing);
        TieGuard {
            neighbours,
            start,
            crossing,
        }
    }

    /// Marks in `first` (the facing triangles) every triangle that could tie with one of them.
    fn keep_with_facing(&self, first: &mut [bool]) {
        let facing = first.to_vec();
        for (t, f) in first.iter_mut().enumerate() {
            let (a, b) = (self.start[t] as usize, self.start[t + 1] as usize);
            *f = *f || self.crossing[t] || self.neighbours[a..b].iter().any(|&u| facing[u as usize]);
        }
    }
}

/// Each triangle's neighbours across its edges, as [`TieGuard::neighbours`] and
/// [`TieGuard::start`] hold them; `corners_of` gives a triangle's corners (`None`: an index out
/// of range, which joins nothing). An edge whose two corners are one joins nothing either; an
/// edge of more than [`GUARD_EDGE_LIMIT`] triangles (a degenerate fan) marks them all in
/// `crossing` instead, which bounds the lists.
fn edge_neighbours(
    tris: usize,
    corners_of: impl Fn(usize) -> [Option<u32>; 3],
    crossing: &mut [bool],
) -> (Vec<u32>, Vec<u32>) {
    // (edge, triangle) sorted by edge: the triangles of one edge are neighbours.
    let mut edges: Vec<(u64, u32)> = Vec::with_capacity(3 * tris);
    for t in 0..tris {
        let c = corners_of(t);
        for (a, b) in [(c[0], c[1]), (c[1], c[2]), (c[2], c[0])] {
            if let (Some(a), Some(b)) = (a, b) {
                if a != b {
                    edges.push((((a.min(b) as u64) << 32) | a.max(b) as u64, t as u32));
                }
            }
        }
    }
    edges.sort_unstable();
    let mut pairs: Vec<(u32, u32)> = Vec::new();
    for group in edges.chunk_by(|x, y| x.0 == y.0) {
        if group.len() > GUARD_EDGE_LIMIT {
            for &(_, t) in group {
                crossing[t as usize] = true;
            }
            continue;
        }
        for (n, &(_, i)) in group.iter().enumerate() {
            for &(_, j) in &group[n + 1..] {
                if i != j {
                    pairs.extend([(i, j), (j, i)]);
                }
            }
        }
    }
    pairs.sort_unstable();
    pairs.dedup();
    let mut start = Vec::with_capacity(tris + 1);
    let mut k = 0;
    for t in 0..tris as u32 {
        start.push(k as u32);
        while k < pairs.len() && pairs[k].0 == t {
            k += 1;
        }
    }
    start.push(pairs.len() as u32);
    (pairs.into_iter().map(|(_, j)| j).collect(), start)
}

/// Gives vertices within `eps` of each other one corner number (the first such vertex's), by
/// a grid of cells of 4·eps: a point near a cell's face also looks in the neighbour across it.
fn weld(points: &[glam::Vec3], eps: f32) -> Vec<u32> {
    let size = 4.0 * eps;
    let mut cells: std::collections::HashMap<glam::I64Vec3, Vec<(glam::Vec3, u32)>> = std::collections::HashMap::new();
    let mut corner = Vec::with_capacity(points.len());
    let mut corners = 0u32;
    for &p in points {
        if !p.is_finite() {
            corner.push(corners);
            corners += 1;
            continue;
        }
        let q = p / size;
        let home = q.floor().as_i64vec3();
        let f = q - q.floor();
        let side = |x: f32| -> &'static [i64] {
            if x < 0.25 {
                &[0, -1]
            } else if x > 0.75 {
                &[0, 1]
            } else {
                &[0]
            }
        };
        let mut found = None;
        'look: for &dz in side(f.z) {
            for &dy in side(f.y) {
                for &dx in side(f.x) {
                    if let Some(list) = cells.get(&(home + glam::I64Vec3::new(dx, dy, dz))) {
                        if let Some(&(_, c)) = list.iter().find(|(o, _)| o.distance(p) <= eps) {
                            found = Some(c);
                            break 'look;
                        }
                    }
                }
            }
        }
        let c = found.unwrap_or_else(|| {
            corners += 1;
            corners - 1
        });
        cells.entry(home).or_default().push((p, c));
        corner.push(c);
    }
    corner
}

/// Whether no axis separates the triangles by more than `eps`: the separating-axis test over
/// both normals, the nine cross products of their edges and each edge's normal in its plane.
fn near(a: &[glam::Vec3; 3], b: &[glam::Vec3; 3], eps: f32) -> bool {
    let ea = [a[1] - a[0], a[2] - a[1], a[0] - a[2]];
    let eb = [b[1] - b[0], b[2] - b[1], b[0] - b[2]];
    let (na, nb) = (ea[0].cross(ea[1]), eb[0].cross(eb[1]));
    // An axis from nearly parallel vectors is all rounding: it separates nothing.
    let separates = |axis: glam::Vec3, from: f32| {
        let len = axis.length();
        if len.partial_cmp(&(1e-4 * from)) != Some(std::cmp::Ordering::Greater) {
            return false;
        }
        let pa = a.map(|p| p.dot(axis));
        let pb = b.map(|p| p.dot(axis));
        let (mina, maxa) = (pa[0].min(pa[1]).min(pa[2]), pa[0].max(pa[1]).max(pa[2]));
        let (minb, maxb) = (pb[0].min(pb[1]).min(pb[2]), pb[0].max(pb[1]).max(pb[2]));
        mina > maxb + eps * len || minb > maxa + eps * len
    };
    let l = |v: glam::Vec3| v.length();
    if separates(na, l(ea[0]) * l(ea[1])) || separates(nb, l(eb[0]) * l(eb[1])) {
        return false;
    }
    for x in ea {
        if separates(na.cross(x), l(na) * l(x)) {
            return false;
        }
        for y in eb {
            if separates(x.cross(y), l(x) * l(y)) {
                return false;
            }
        }
    }
    !eb.iter().any(|&y| separates(nb.cross(y), l(nb) * l(y)))
}

/// A mesh drawn in mesh order or, for a view, with its triangles facing the eye first
/// ([`facing_first`]; the labs' `faces=facing_first`). Mesh order draws the mesh as given,
/// indexed or not, untouched; the view's order is drawn through an indexed copy built on first
/// use, whose index buffer is rewritten only when the view changes: a still picture costs
/// nothing per frame, a turning one a sort on the CPU and one `write_buffer`. A mesh of more
/// than [`SORT_EVERY_FRAME`] triangles is sorted only once the view holds still for a frame,
/// and drawn in its last order meanwhile: any order draws the same pixels but for exact depth
/// ties, and sorting a mesh that large in every frame of a turn would slow the turn (figures:
/// `docs/speed.md`, "Ordering the triangles").
pub struct ViewOrdered<V: VertexType> {
    label: String,
    plain: GpuMesh<V>,
    ordered: Option<GpuMesh<V>>,
    positions: Vec<[f32; 3]>,
    /// Mesh order's triangles (for an unindexed mesh, every vertex in turn); for an indexed
    /// mesh, the plain mesh's own copy.
    indices: Arc<Vec<u32>>,
    /// The view (bits of the matrix, winding) `ordered` holds the order for.
    ordered_for: Option<([u32; 16], bool)>,
    /// A large mesh's view seen last frame, not sorted for yet.
    pending: Option<([u32; 16], bool)>,
    /// The mesh's [`TieGuard`], built with its first order; `None` for an unguarded mesh.
    guard: Option<std::cell::OnceCell<TieGuard>>,
}

/// The most triangles [`ViewOrdered`] sorts in the frame their view changes (figures:
/// `docs/speed.md`, "Ordering the triangles").
pub const SORT_EVERY_FRAME: usize = 65_536;

impl<V: VertexType> ViewOrdered<V> {
    /// Uploads the mesh as [`GpuMesh::new`] does; `positions` are the vertices' object-space
    /// positions (what the order is computed from), one per vertex.
    pub fn new(gpu: &Gpu, label: &str, vertices: &[V], indices: Option<Vec<u32>>, positions: Vec<[f32; 3]>) -> Self {
        let plain = GpuMesh::new(gpu, label, vertices, indices.as_deref());
        // An indexed mesh's order is the plain mesh's own copy of its indices.
        let indices = match indices {
            Some(_) => plain.index_data().cloned().unwrap_or_default(),
            None => Arc::new((0..vertices.len() as u32).collect()),
        };
        ViewOrdered {
            label: format!("{label}.facing_first"),
            plain,
            ordered: None,
            indices,
            positions,
            ordered_for: None,
            pending: None,
            guard: Some(std::cell::OnceCell::new()),
        }
    }

    /// Orders without a [`TieGuard`]: the facing triangles alone first. For meshes seen only
    /// where depth is fine enough that no tie showed (seed 000's camera, its near plane at 1:
    /// 1000 random views of each reordered solid byte-identical to mesh order, and 200 more in
    /// tests/faces.rs), where the guard would only keep turned-away triangles shaded.
    pub fn unguarded(mut self) -> Self {
        self.guard = None;
        self
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
            let guard = self
                .guard
                .as_ref()
                .map(|g| g.get_or_init(|| TieGuard::new(&self.positions, &self.indices)));
            let order = facing_first(&self.positions, &self.indices, mvp, outside, guard);
            match &mut self.ordered {
                Some(mesh) if mesh.indices.is_some() => {
                    mesh.rewrite_indices(gpu, order);
                }
                _ => self.ordered = Some(self.plain.reindexed(gpu, &self.label, order)),
            }
            self.ordered_for = want;
        }
        self.ordered.as_ref().unwrap_or(&self.plain)
    }
}

#[cfg(test)]
mod tests {
    use super::{facing_first, TieGuard};
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
            facing_first(&positions, &indices, mvp, wgpu::FrontFace::Ccw, None),
            [0, 1, 2, 1, 3, 2, 0, 2, 1, 0, 1, 4]
        );
        // The teapot's outside is clockwise: then the clockwise triangle leads.
        assert_eq!(
            facing_first(&positions, &indices, mvp, wgpu::FrontFace::Cw, None),
            [0, 2, 1, 0, 1, 2, 1, 3, 2, 0, 1, 4]
        );
    }

    #[test]
    fn the_order_is_a_permutation_of_whole_triangles() {
        let (positions, indices, mvp) = scene();
        let order = facing_first(&positions, &indices, mvp.transpose(), wgpu::FrontFace::Ccw, None);
        let triangles = |v: &[u32]| {
            let mut t: Vec<[u32; 3]> = v.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
            t.sort();
            t
        };
        assert_eq!(triangles(&order), triangles(&indices));
    }

    /// A UV sphere of `rings` × `segments` quads, its seam and poles repeated as separate
    /// vertices the way patch meshes repeat theirs, wound counter-clockwise from outside.
    fn sphere(rings: u32, segments: u32) -> (Vec<[f32; 3]>, Vec<u32>) {
        let mut positions = Vec::new();
        for r in 0..=rings {
            let theta = std::f32::consts::PI * r as f32 / rings as f32;
            // The poles exactly on the axis, so that their triangles are exactly degenerate.
            let (sin, cos) = match r {
                0 => (0.0, 1.0),
                r if r == rings => (0.0, -1.0),
                _ => theta.sin_cos(),
            };
            for s in 0..=segments {
                let phi = std::f32::consts::TAU * s as f32 / segments as f32;
                positions.push([sin * phi.cos(), cos, -sin * phi.sin()]);
            }
        }
        let at = |r: u32, s: u32| r * (segments + 1) + s;
        let mut indices = Vec::new();
        for r in 0..rings {
            for s in 0..segments {
                indices.extend([at(r, s), at(r + 1, s), at(r + 1, s + 1)]);
                indices.extend([at(r, s), at(r + 1, s + 1), at(r, s + 1)]);
            }
        }
        (positions, indices)
    }

    #[test]
    fn a_closed_surface_that_does_not_cross_itself_pins_nothing_and_welds_its_seams() {
        let (positions, indices) = sphere(16, 32);
        let guard = TieGuard::new(&positions, &indices);
        assert!(guard.crossing.iter().all(|c| !c), "a sphere does not cross itself");
        // Away from the poles every triangle has three neighbours, across the seam too.
        for t in 2 * 32..2 * 32 * 15 {
            let n = guard.start[t + 1] - guard.start[t];
            assert_eq!(n, 3, "triangle {t}: {n} neighbours");
        }
        // Seen along -z, the facing half (normals towards +z) plus the turned-away triangles
        // with an edge on the silhouette lead; the rest of the back half goes last.
        let centre_z = |t: &[u32]| t.iter().map(|&i| positions[i as usize][2]).sum::<f32>() / 3.0;
        let normal_z = |t: &[u32]| {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| glam::Vec3::from_array(positions[i as usize]));
            (b - a).cross(c - a).z
        };
        let facing: Vec<bool> = indices.chunks_exact(3).map(|t| normal_z(t) > 0.0).collect();
        let mut first = facing.clone();
        guard.keep_with_facing(&mut first);
        let (before, after) = (
            facing.iter().filter(|&&f| f).count(),
            first.iter().filter(|&&f| f).count(),
        );
        let tris = indices.len() / 3;
        assert!(
            before > tris / 3 && before < tris / 2,
            "{before} of {tris} face the eye"
        );
        assert!(after > before, "the silhouette's turned-away triangles lead too");
        assert!(
            after - before < (tris - before) / 2,
            "{after} of {tris} lead: most turned-away ones still go last"
        );
        for ((t, f), kept) in indices.chunks_exact(3).zip(&facing).zip(&first) {
            if kept & !f {
                assert!(centre_z(t) > -0.2, "only triangles at the silhouette are kept: {t:?}");
            }
        }
        let order = facing_first(
            &positions,
            &indices,
            Mat4::from_scale(glam::Vec3::splat(0.5)),
            wgpu::FrontFace::Ccw,
            Some(&guard),
        );
        let leading: Vec<&[u32]> = indices
            .chunks_exact(3)
            .zip(&first)
            .filter(|(_, &k)| k)
            .map(|(t, _)| t)
            .collect();
        assert_eq!(order[..3 * after].chunks_exact(3).collect::<Vec<_>>(), leading);
    }

    #[test]
    fn a_triangle_through_another_is_kept_in_mesh_order_and_a_neighbour_too() {
        // Seen through the identity: `through` (clockwise, turned away) stands through
        // `facing` (counter-clockwise, in z = 0) with no corner shared; `neighbour`
        // (clockwise) shares an edge with `facing`, `corner` (clockwise) only a corner; `far`
        // (clockwise) touches nothing.
        let positions = vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 2.0, 0.0],
            [0.3, 0.3, -1.0],
            [0.3, 0.8, 1.0],
            [0.8, 0.3, 0.0],
            [-1.0, 0.0, 0.0],
            [1.0, -1.0, 0.0],
            [5.0, 5.0, 0.0],
            [6.0, 5.0, 0.0],
            [5.0, 6.0, 0.0],
            [-1.0, -1.0, 0.0],
        ];
        let (facing, through, neighbour) = ([0, 1, 2], [3, 4, 5], [0, 1, 7]);
        let (corner, far) = ([0, 11, 6], [8, 10, 9]);
        let indices: Vec<u32> = [through, neighbour, corner, far, facing].concat();
        let guard = TieGuard::new(&positions, &indices);
        assert_eq!(guard.crossing, [true, false, false, false, true]);
        let ccw = |guard| facing_first(&positions, &indices, Mat4::IDENTITY, wgpu::FrontFace::Ccw, guard);
        assert_eq!(ccw(None), [facing, through, neighbour, corner, far].concat());
        assert_eq!(ccw(Some(&guard)), [through, neighbour, facing, corner, far].concat());
        // Seen from the other side the other four face the eye and `facing`, which crosses
        // `through`, stays with them: mesh order.
        let cw = facing_first(&positions, &indices, Mat4::IDENTITY, wgpu::FrontFace::Cw, Some(&guard));
        assert_eq!(cw, indices);
    }

    #[test]
    fn a_mesh_with_a_point_at_infinity_or_nan_keeps_mesh_order() {
        let positions = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [f32::NAN, 0.0, 0.0],
            [f32::INFINITY, 1.0, 1.0],
            [3.0, 3.0, 3.0],
        ];
        let indices = vec![0, 2, 1, 3, 4, 5, 0, 1, 2];
        let guard = TieGuard::new(&positions, &indices);
        assert!(guard.crossing.iter().all(|&c| c));
        let order = facing_first(&positions, &indices, Mat4::IDENTITY, wgpu::FrontFace::Ccw, Some(&guard));
        assert_eq!(order, indices);
    }

    #[test]
    fn a_huge_triangle_beside_tiny_ones_keeps_mesh_order_instead_of_listing_millions_of_cells() {
        let (mut positions, mut indices) = sphere(8, 8);
        let n = positions.len() as u32;
        positions.extend([[-1e30, -1e30, -1e30], [1e30, -1e30, 1e30], [0.0, 1e30, 0.0]]);
        indices.extend([n, n + 1, n + 2]);
        let guard = TieGuard::new(&positions, &indices);
        assert!(guard.crossing.iter().all(|&c| c));
    }

    #[test]
    fn an_edge_of_many_triangles_keeps_them_in_mesh_order_instead_of_pairing_them_all() {
        // 40 triangles around one edge (a fan of fins on the z axis), and one beside them.
        let mut positions = vec![[0.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
        let mut indices = Vec::new();
        for k in 0..40 {
            let a = std::f32::consts::TAU * k as f32 / 40.0;
            positions.push([a.cos(), a.sin(), 0.5]);
            indices.extend([0, 1, k + 2]);
        }
        positions.extend([[5.0, 5.0, 0.0], [6.0, 5.0, 0.0], [5.0, 6.0, 0.0]]);
        indices.extend([42, 43, 44]);
        let guard = TieGuard::new(&positions, &indices);
        assert!(guard.crossing[..40].iter().all(|&c| c));
        assert!(!guard.crossing[40]);
        assert!(guard.neighbours.is_empty());
    }
}
