//! The lectures' hand-made meshes as plain vertex data, computed the way the course code (or
//! SPEC's pinned code) computes them: in float where the C code uses float, in double and then
//! rounded where SPEC says so. Quads are split as (v0, v1, v2), (v0, v2, v3) into triangle
//! lists unless a function says otherwise: Mesa's split of a `GL_QUADS` draw none of whose
//! vertices needs clipping (see [`QUAD_SPLIT_CLIPPED`] for the other case). All vertex structs are `#[repr(C)]` and [`Pod`], so
//! a slice of them is a vertex buffer as it is.

use crate::camera::fly::qt_normalize;
use crate::mesh::obj::ObjCorner;
use bytemuck::{Pod, Zeroable};
use glam::{Vec3, Vec4};

/// A 2D vertex with the custom `height` attribute of 001 `height`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct HeightVertex {
    /// `glVertex2f` x, y.
    pub position: [f32; 2],
    /// The `attribute float height`.
    pub height: f32,
}

/// A position with a `glColor3f` colour.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct ColorVertex {
    /// Object-space position.
    pub position: [f32; 3],
    /// RGB colour.
    pub color: [f32; 3],
}

/// One vertex of 001 `morph`: `gl_Vertex` (`vertices_one`) and the `vertices2` attribute
/// (`vertices_two`; w = 1 is added by `glVertexAttrib3fv`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct MorphVertex {
    /// `vertices_one[i]`: the 16-gon.
    pub one: [f32; 3],
    /// `vertices_two[i]`: the 8-pointed star.
    pub two: [f32; 3],
}

/// One vertex of 001 `bump`'s quad.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct BumpVertex {
    /// Object-space position.
    pub position: [f32; 3],
    /// `glNormal3f`: (0, 0, 1).
    pub normal: [f32; 3],
    /// The `objTangent` attribute: (1, 0, 0, 1).
    pub tangent: [f32; 4],
    /// `glTexCoord2f` s, t.
    pub st: [f32; 2],
}

/// A 2D vertex with texture coordinates (002 `double_vision`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct TexVertex2 {
    /// Clip-space x, y (the matrices are identity).
    pub position: [f32; 2],
    /// `glTexCoord2f` s, t.
    pub st: [f32; 2],
}

/// 003's `VertexData`: position, colour, normal; 9 floats, stride 36, attributes 0, 1, 2.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct StripVertex {
    /// `objectPosition`.
    pub position: [f32; 3],
    /// `objectColor`.
    pub color: [f32; 3],
    /// `normal`, from `calculateNormals`.
    pub normal: [f32; 3],
}

/// Mesa's (llvmpipe's) split of a `GL_QUADS` quad into two triangles when no vertex of the
/// draw lies outside the clip volume: diagonal v0–v2.
pub const QUAD_SPLIT_UNCLIPPED: [u32; 6] = [0, 1, 2, 0, 2, 3];

/// Mesa's split when some vertex of the draw lies outside the clip volume (the draw then takes
/// the clipping path, which cuts every quad of it this other way): diagonal v1–v3. Measured on
/// the original `bump` (one quad, per-vertex light vectors far apart, so the diagonal shows):
/// drawn as `GL_QUADS` it is bit-identical to `GL_TRIANGLES` (v0,v1,v2),(v0,v2,v3) in every
/// tried state whose corners are all inside (largest |NDC| 0.75–0.99) and to
/// (v0,v1,v3),(v1,v2,v3) in every one with a corner outside (1.01–1.09); the wrong diagonal
/// costs 32–52 dB.
pub const QUAD_SPLIT_CLIPPED: [u32; 6] = [0, 1, 3, 1, 2, 3];

/// Whether Mesa flags any of these clip-space positions (wgpu's depth convention, as the
/// port's `mvp` gives them) for clipping: outside −w ≤ x, y ≤ w or 0 ≤ z ≤ w. llvmpipe uses no
/// guard band, so a corner just off screen counts.
pub fn needs_clipping(clip: impl IntoIterator<Item = Vec4>) -> bool {
    clip.into_iter()
        .any(|c| !(c.x.abs() <= c.w && c.y.abs() <= c.w && c.z >= 0.0 && c.z <= c.w))
}

/// The split Mesa gives the quads of a `GL_QUADS` draw with these clip-space vertices.
pub fn quad_split(clip: impl IntoIterator<Item = Vec4>) -> [u32; 6] {
    if needs_clipping(clip) {
        QUAD_SPLIT_CLIPPED
    } else {
        QUAD_SPLIT_UNCLIPPED
    }
}

/// Splits quads (4 consecutive vertices each) into triangles (v0, v1, v2), (v0, v2, v3).
fn quads_to_triangles<T: Copy>(quads: &[T]) -> Vec<T> {
    quads
        .chunks_exact(4)
        .flat_map(|q| [q[0], q[1], q[2], q[0], q[2], q[3]])
        .collect()
}

/// A triangle list of quads split (v0,v1,v2),(v0,v2,v3) (what the grids here return) as
/// distinct corners and the indices of the same triangles: each quad's four corners, then
/// corners equal to the bit merged across quads ([`weld_identical`]). Drawn indexed, a corner
/// is shaded once instead of in each triangle that uses it, and the triangles, hence the
/// pixels, are the same.
pub fn indexed_quads<T: bytemuck::Pod>(list: &[T]) -> (Vec<T>, Vec<u32>) {
    let corners: Vec<T> = list.chunks_exact(6).flat_map(|t| [t[0], t[1], t[2], t[5]]).collect();
    let indices: Vec<u32> = (0..corners.len() as u32 / 4)
        .flat_map(|q| [0, 1, 2, 0, 2, 3].map(|i| 4 * q + i))
        .collect();
    weld_identical(&corners, &indices)
}

/// An indexed mesh with vertices whose bytes are equal merged into one (the first keeps its
/// place, in order of first use), the indices following them: the triangles, their order and
/// every value the shaders see stay the same, so the picture does; the vertex shader runs
/// once per distinct vertex. Exact: vertices that differ in any bit stay apart (a grid whose
/// far corners are computed as `x + size` shares only the corners where float agrees).
pub fn weld_identical<T: bytemuck::Pod>(vertices: &[T], indices: &[u32]) -> (Vec<T>, Vec<u32>) {
    let mut seen: std::collections::HashMap<&[u8], u32> = std::collections::HashMap::with_capacity(vertices.len());
    let mut kept = Vec::with_capacity(vertices.len());
    let new_index: Vec<u32> = vertices
        .iter()
        .map(|v| {
            *seen.entry(bytemuck::bytes_of(v)).or_insert_with(|| {
                kept.push(*v);
                kept.len() as u32 - 1
            })
        })
        .collect();
    let indices = indices.iter().map(|&i| new_index[i as usize]).collect();
    (kept, indices)
}

/// SPEC §1.1 (001 `height`): the 4 vertices of the `GL_TRIANGLE_STRIP`, in strip order
/// (draw with a triangle-strip topology): (−1, 1) h 2, (1, 1) h 2, (−1, −1) h −2, (1, −1) h −2.
pub fn height_quad() -> [HeightVertex; 4] {
    [
        HeightVertex {
            position: [-1.0, 1.0],
            height: 2.0,
        },
        HeightVertex {
            position: [1.0, 1.0],
            height: 2.0,
        },
        HeightVertex {
            position: [-1.0, -1.0],
            height: -2.0,
        },
        HeightVertex {
            position: [1.0, -1.0],
            height: -2.0,
        },
    ]
}

/// Cells per side of [`wave_grid`].
pub const WAVE_CELLS: u32 = 40;

/// SPEC §1.3 (001 `wave`): the 40×40-cell mesh over x, z ∈ [−2, 2] in the plane y = 0 as a
/// triangle list, 40·40·6 = 9600 vertices. x_i = (float)(−2 + 0.1·i) in double (i = 0..40),
/// the same for z; cell (i, j) (outer loop i along x, inner j along z) is the quad
/// (x_i,0,z_j), (x_i,0,z_j+1), (x_i+1,0,z_j+1), (x_i+1,0,z_j) split (v0,v1,v2),(v0,v2,v3),
/// coloured (0.1, 0.4, 0.8) if i + j is even, (0.85, 0.9, 1.0) if odd.
pub fn wave_grid() -> Vec<ColorVertex> {
    wave_grid_sub(1)
}

/// [`wave_grid`] with each of the 40×40 checker cells split into `k` × `k` quads of its colour
/// (`wave`'s `subdiv`; at least 1): the same picture on a flat grid, a finer approximation of
/// the waving surface. `k = 1` is the course's grid, vertex for vertex.
pub fn wave_grid_sub(k: u32) -> Vec<ColorVertex> {
    let k = k.max(1);
    let coord = |i: u32| -2.0 + 0.1 * f64::from(i);
    // Sub-vertex a of cell i; the cell's own corners exactly as the course computes them.
    let sub = |i: u32, a: u32| match a {
        0 => coord(i) as f32,
        a if a == k => coord(i + 1) as f32,
        a => (coord(i) + (coord(i + 1) - coord(i)) * f64::from(a) / f64::from(k)) as f32,
    };
    let mut quads = Vec::with_capacity((WAVE_CELLS * WAVE_CELLS * k * k * 4) as usize);
    for i in 0..WAVE_CELLS {
        for j in 0..WAVE_CELLS {
            let color = if (i + j) % 2 == 0 {
                [0.1, 0.4, 0.8]
            } else {
                [0.85, 0.9, 1.0]
            };
            for a in 0..k {
                for b in 0..k {
                    let (x0, x1, z0, z1) = (sub(i, a), sub(i, a + 1), sub(j, b), sub(j, b + 1));
                    for position in [[x0, 0.0, z0], [x0, 0.0, z1], [x1, 0.0, z1], [x1, 0.0, z0]] {
                        quads.push(ColorVertex { position, color });
                    }
                }
            }
        }
    }
    quads_to_triangles(&quads)
}

/// Vertices of [`morph_vertices`] (the course's `#define N 50`).
pub const MORPH_VERTICES: usize = 50;

/// SPEC §1.4 (001 `morph`): all 50 vertices of the course's `GL_TRIANGLES` loop. Vertex i,
/// k = i/3, c = i%3: c = 0 is the origin; c = 1, 2 is rim point m = k + c − 1 at angle
/// a = 2π·m/16, `one` = (cos a, sin a, 0) (a 16-gon), `two` = r·(cos a, sin a, 0) with r = 1 for
/// even m and 0.4 for odd m (an 8-pointed star); computed in double, stored as float.
///
/// GL draws only the first 48 as 16 triangles; the last 2 are kept here as the course sends
/// them, and a port draws `0..48`.
pub fn morph_vertices() -> Vec<MorphVertex> {
    (0..MORPH_VERTICES)
        .map(|i| {
            let (k, c) = (i / 3, i % 3);
            if c == 0 {
                return MorphVertex {
                    one: [0.0; 3],
                    two: [0.0; 3],
                };
            }
            let m = k + c - 1;
            let a = 2.0 * std::f64::consts::PI * m as f64 / 16.0;
            let r = if m % 2 == 0 { 1.0 } else { 0.4 };
            MorphVertex {
                one: [a.cos() as f32, a.sin() as f32, 0.0],
                two: [(r * a.cos()) as f32, (r * a.sin()) as f32, 0.0],
            }
        })
        .collect()
}

/// SPEC §1.5's particle count.
pub const PARTICLE_COUNT: u32 = 2000;

/// SPEC §1.5 (001 `particles`): the initial velocity of particles 0..n (SPEC: n =
/// [`PARTICLE_COUNT`]), in double, stored as float: f1 = frac(i·0.618033988749895),
/// f2 = frac(i·0.754877666246693), a = 2π·f1, r = sqrt((i + 0.5)/n),
/// vel = (r·cos a, 1.8 + 0.4·f2, r·sin a). Every particle starts at (0, −1, 0).
pub fn particle_velocities(n: u32) -> Vec<[f32; 3]> {
    let count = f64::from(n);
    (0..n)
        .map(|i| {
            let i = f64::from(i);
            let frac = |x: f64| x - x.floor();
            let (f1, f2) = (frac(i * 0.618033988749895), frac(i * 0.754877666246693));
            let a = 2.0 * std::f64::consts::PI * f1;
            let r = ((i + 0.5) / count).sqrt();
            [(r * a.cos()) as f32, (1.8 + 0.4 * f2) as f32, (r * a.sin()) as f32]
        })
        .collect()
}

/// SPEC §1.11 (001 `bump`, also `normmap`): the `GL_QUADS` quad (−1.25,−1.25,0) st (0,0);
/// (1.25,−1.25,0) (1,0); (1.25,1.25,0) (1,1); (−1.25,1.25,0) (0,1), normal (0,0,1), tangent
/// (1,0,0,1): the four corners in that order, to be drawn through [`quad_split`]'s indices
/// (the lab picks the split per frame: its per-vertex light vectors make the diagonal show).
pub fn bump_quad() -> [BumpVertex; 4] {
    let corner = |x: f32, y: f32, s: f32, t: f32| BumpVertex {
        position: [x, y, 0.0],
        normal: [0.0, 0.0, 1.0],
        tangent: [1.0, 0.0, 0.0, 1.0],
        st: [s, t],
    };
    [
        corner(-1.25, -1.25, 0.0, 0.0),
        corner(1.25, -1.25, 1.0, 0.0),
        corner(1.25, 1.25, 1.0, 1.0),
        corner(-1.25, 1.25, 0.0, 1.0),
    ]
}

/// Quads per side of [`twist_grid`] (the course's `count`).
pub const TWIST_COUNT: u32 = 100;

/// SPEC §2.1 (002 `twist`): the course's `GL_QUADS` loop in float, `size = 1.0f/count`, for
/// i, j in 0..100 (i outer): x = −0.5f + i·size, y = −0.5f + j·size, quad (x,y), (x+size,y),
/// (x+size,y+size), (x,y+size), split (v0,v1,v2),(v0,v2,v3): 100·100·6 clip-space vertices.
pub fn twist_grid() -> Vec<[f32; 2]> {
    twist_grid_n(TWIST_COUNT)
}

/// [`twist_grid`] with `n` × `n` quads (at least 1) instead of the course's 100: `twist`'s
/// `grid` parameter, built by the same float loop.
pub fn twist_grid_n(n: u32) -> Vec<[f32; 2]> {
    let n = n.max(1);
    let size = 1.0f32 / n as f32;
    let mut quads = Vec::with_capacity((n * n * 4) as usize);
    for i in 0..n {
        for j in 0..n {
            let x = -0.5f32 + i as f32 * size;
            let y = -0.5f32 + j as f32 * size;
            quads.extend_from_slice(&[[x, y], [x + size, y], [x + size, y + size], [x, y + size]]);
        }
    }
    quads_to_triangles(&quads)
}

/// SPEC §2.2 (002 `double_vision`): the one triangle, apex down, in clip space:
/// (−0.8, 0.8) st (0,0); (0.8, 0.8) st (1,0); (0, −0.8) st (0.5, 1).
pub fn double_vision_triangle() -> [TexVertex2; 3] {
    [
        TexVertex2 {
            position: [-0.8, 0.8],
            st: [0.0, 0.0],
        },
        TexVertex2 {
            position: [0.8, 0.8],
            st: [1.0, 0.0],
        },
        TexVertex2 {
            position: [0.0, -0.8],
            st: [0.5, 1.0],
        },
    ]
}

/// SPEC §4.6 (004 `texparams`): the floor y = −1, x ∈ [−2, 2], z ∈ [−16, 2] in seed 004's VBO
/// layout, triangles (A,B,C), (A,C,D): A (−2,−1,2) uv (−0.5,−0.5), B (2,−1,2) (1.5,−0.5),
/// C (2,−1,−16) (1.5,8.5), D (−2,−1,−16) (−0.5,8.5), normal (0,1,0), w = 1.
pub fn texparams_floor() -> [ObjCorner; 6] {
    let corner = |x: f32, z: f32, u: f32, v: f32| ObjCorner {
        position: [x, -1.0, z, 1.0],
        uv: [u, v],
        normal: [0.0, 1.0, 0.0],
    };
    let a = corner(-2.0, 2.0, -0.5, -0.5);
    let b = corner(2.0, 2.0, 1.5, -0.5);
    let c = corner(2.0, -16.0, 1.5, 8.5);
    let d = corner(-2.0, -16.0, -0.5, 8.5);
    [a, b, c, a, c, d]
}

/// SPEC §3's control points P0, P1, P2 (course).
pub const BEZIER_CONTROL: [[f32; 2]; 3] = [[-0.75, -0.45], [0.0, -0.85], [0.75, -0.3]];

/// SPEC §3's pinned `curve(t)`: the quadratic Bézier of [`BEZIER_CONTROL`] in float,
/// u = 1 − t, p = (u·u)·P0 + (2·u·t)·P1 + (t·t)·P2, summed left to right per component.
pub fn bezier_point(t: f32) -> [f32; 2] {
    let u = 1.0 - t;
    let (w0, w1, w2) = (u * u, 2.0 * u * t, t * t);
    let [p0, p1, p2] = BEZIER_CONTROL;
    [
        w0 * p0[0] + w1 * p1[0] + w2 * p2[0],
        w0 * p0[1] + w1 * p1[1] + w2 * p2[1],
    ]
}

/// The parameters of the course loop `for (float t = 0; t <= 1; t += 0.01)`: `t` is float and
/// `t += 0.01` adds a double and rounds back, t ← (float)((double)t + 0.01). 101 values, the
/// last 0.99999934 (never exactly 1).
pub fn bezier_parameters() -> Vec<f32> {
    let mut ts = Vec::with_capacity(101);
    let mut t = 0.0f32;
    while t <= 1.0 {
        ts.push(t);
        t = (f64::from(t) + 0.01) as f32;
    }
    ts
}

/// SPEC §3 (003 `specular_strip`): the 202-vertex `GL_TRIANGLE_STRIP` (draw with a
/// triangle-strip topology). Per [`bezier_parameters`] point p two vertices (p.x, p.y, −0.5) and
/// (p.x, p.y, +0.5), colour (1, 1, 0), with the normals of the course's `calculateNormals`
/// exactly as written:
///
/// ```text
/// for i in 0 .. size-2:   n = cross(P[i+1]-P[i], P[i+2]-P[i+1]); n.normalize();
///                         if n.y < 0 { n.y = -n.y }; n.normalize(); N[i] += n; N[i+1] += n
/// for i in 0 .. size:     N[i].normalize()
/// ```
///
/// in float with Qt 6's `QVector3D::normalize` ([`qt_normalize`]): the last vertex (201) keeps
/// (0, 0, 0), the others come out close to +y.
pub fn bezier_strip() -> Vec<StripVertex> {
    strip_at(bezier_parameters())
}

/// [`bezier_strip`] with `segments` equal steps of t from exactly 0 to exactly 1 (at least 1),
/// the course's normals computed the course's way: `specular_strip`'s `segments` (the course's
/// float loop is `segments=100`, [`bezier_strip`] itself).
pub fn bezier_strip_n(segments: u32) -> Vec<StripVertex> {
    let n = segments.max(1);
    strip_at((0..=n).map(|k| (f64::from(k) / f64::from(n)) as f32).collect())
}

/// The strip through the curve points at parameters `ts`.
fn strip_at(ts: Vec<f32>) -> Vec<StripVertex> {
    let mut vertices: Vec<StripVertex> = ts
        .into_iter()
        .flat_map(|t| {
            let [x, y] = bezier_point(t);
            [-0.5f32, 0.5].map(|z| StripVertex {
                position: [x, y, z],
                color: [1.0, 1.0, 0.0],
                normal: [0.0; 3],
            })
        })
        .collect();
    let mut normals = vec![Vec3::ZERO; vertices.len()];
    let p = |i: usize| Vec3::from_array(vertices[i].position);
    for i in 0..vertices.len().saturating_sub(2) {
        let (v1, v2) = (p(i + 1) - p(i), p(i + 2) - p(i + 1));
        // QVector3D::crossProduct, component by component in float.
        let cross = Vec3::new(
            v1.y * v2.z - v1.z * v2.y,
            v1.z * v2.x - v1.x * v2.z,
            v1.x * v2.y - v1.y * v2.x,
        );
        let mut n = qt_normalize(cross);
        if n.y < 0.0 {
            n.y = -n.y;
        }
        let n = qt_normalize(n);
        normals[i] += n;
        normals[i + 1] += n;
    }
    for (v, n) in vertices.iter_mut().zip(normals) {
        v.normal = qt_normalize(n).to_array();
    }
    vertices
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indexed_quads_draw_the_same_triangles_with_fewer_corners() {
        for list in [twist_grid_n(100), twist_grid_n(7)] {
            let (corners, indices) = indexed_quads(&list);
            // The triangles, corner for corner and bit for bit, in the same order.
            let drawn: Vec<[f32; 2]> = indices.iter().map(|&i| corners[i as usize]).collect();
            assert_eq!(
                bytemuck::cast_slice::<_, u8>(&drawn),
                bytemuck::cast_slice::<_, u8>(&list)
            );
            // No two kept corners are equal, and at least each quad's two shared corners merged.
            let distinct: std::collections::HashSet<[u32; 2]> = corners.iter().map(|c| c.map(f32::to_bits)).collect();
            assert_eq!(distinct.len(), corners.len());
            assert!(corners.len() <= list.len() / 6 * 4, "{} corners", corners.len());
        }
        // The course's 100x100 grid: float shares about a third of the corners across quads.
        assert_eq!(indexed_quads(&twist_grid_n(100)).0.len(), 26_244);
    }

    #[test]
    fn height_quad_strip() {
        let q = height_quad();
        let flat: Vec<[f32; 3]> = q.iter().map(|v| [v.position[0], v.position[1], v.height]).collect();
        assert_eq!(
            flat,
            vec![[-1.0, 1.0, 2.0], [1.0, 1.0, 2.0], [-1.0, -1.0, -2.0], [1.0, -1.0, -2.0]]
        );
        assert_eq!(std::mem::size_of::<HeightVertex>(), 12);
    }

    #[test]
    fn wave_grid_layout() {
        let g = wave_grid();
        assert_eq!(g.len(), 40 * 40 * 6);
        // x_i = (float)(-2 + 0.1 i), computed in double.
        assert_eq!(g[0].position, [-2.0, 0.0, -2.0]);
        assert_eq!(g[1].position, [-2.0, 0.0, (-2.0f64 + 0.1) as f32]);
        assert_eq!(g[2].position, [(-2.0f64 + 0.1) as f32, 0.0, (-2.0f64 + 0.1) as f32]);
        assert_eq!(g[5].position, [(-2.0f64 + 0.1) as f32, 0.0, -2.0]);
        assert_eq!(g[3].position, g[0].position);
        assert_eq!(g[4].position, g[2].position);
        let xs: Vec<f32> = g.iter().map(|v| v.position[0]).collect();
        assert_eq!(xs.iter().cloned().fold(f32::MAX, f32::min), -2.0);
        assert_eq!(xs.iter().cloned().fold(f32::MIN, f32::max), 2.0);
        assert!(g.iter().all(|v| v.position[1] == 0.0));
        // Checker colours: cell (0,0) even, (0,1) odd (the inner loop runs along z).
        assert!(g[..6].iter().all(|v| v.color == [0.1, 0.4, 0.8]));
        assert!(g[6..12].iter().all(|v| v.color == [0.85, 0.9, 1.0]));
        assert_eq!(g[6].position, [-2.0, 0.0, (-2.0f64 + 0.1) as f32]);
        // The cell (1,0) starts after the 40 cells of i = 0.
        assert_eq!(g[40 * 6].position, [(-2.0f64 + 0.1) as f32, 0.0, -2.0]);
        assert_eq!(g[40 * 6].color, [0.85, 0.9, 1.0]);
    }

    #[test]
    fn morph_shapes() {
        let m = morph_vertices();
        assert_eq!(m.len(), 50);
        assert_eq!(
            m[0],
            MorphVertex {
                one: [0.0; 3],
                two: [0.0; 3]
            }
        );
        assert_eq!(m[1].one, [1.0, 0.0, 0.0]); // m = 0
        assert_eq!(m[1].two, [1.0, 0.0, 0.0]);
        let a = 2.0 * std::f64::consts::PI / 16.0; // m = 1: a star's inner point
        assert_eq!(m[2].one, [a.cos() as f32, a.sin() as f32, 0.0]);
        assert_eq!(m[2].two, [(0.4 * a.cos()) as f32, (0.4 * a.sin()) as f32, 0.0]);
        assert_eq!(m[4].one, m[2].one); // triangle 1 starts at rim point 1
        for (i, v) in m.iter().enumerate() {
            let r1 = (v.one[0].powi(2) + v.one[1].powi(2)).sqrt();
            let r2 = (v.two[0].powi(2) + v.two[1].powi(2)).sqrt();
            if i % 3 == 0 {
                assert_eq!((r1, r2), (0.0, 0.0));
            } else {
                let m_index = i / 3 + i % 3 - 1;
                assert!((r1 - 1.0).abs() < 1e-6);
                assert!((r2 - if m_index % 2 == 0 { 1.0 } else { 0.4 }).abs() < 1e-6, "{i}");
            }
        }
        // The two extra vertices: the origin and rim point 16 (= 0).
        assert_eq!(m[48].one, [0.0; 3]);
        assert!((m[49].one[0] - 1.0).abs() < 1e-7 && m[49].one[1].abs() < 1e-7);
    }

    #[test]
    fn particle_velocity_values() {
        let v = particle_velocities(PARTICLE_COUNT);
        assert_eq!(v.len(), 2000);
        // i = 0: f1 = f2 = 0, a = 0, r = sqrt(0.5/2000).
        assert_eq!(v[0], [(0.5f64 / 2000.0).sqrt() as f32, 1.8f64 as f32, 0.0]);
        let i = 7.0f64;
        let (f1, f2) = ((i * 0.618033988749895).fract(), (i * 0.754877666246693).fract());
        let (a, r) = (2.0 * std::f64::consts::PI * f1, ((i + 0.5) / 2000.0).sqrt());
        assert_eq!(
            v[7],
            [(r * a.cos()) as f32, (1.8 + 0.4 * f2) as f32, (r * a.sin()) as f32]
        );
        assert!(v.iter().all(|p| p[1] >= 1.8 && p[1] < 2.2 && p[0].hypot(p[2]) <= 1.0));
        assert!(particle_velocities(0).is_empty());
    }

    #[test]
    fn bump_quad_corners() {
        let q = bump_quad();
        let st: Vec<[f32; 2]> = q.iter().map(|v| v.st).collect();
        assert_eq!(st, vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
        assert_eq!(q[2].position, [1.25, 1.25, 0.0]);
        assert!(q
            .iter()
            .all(|v| v.normal == [0.0, 0.0, 1.0] && v.tangent == [1.0, 0.0, 0.0, 1.0]));
        assert_eq!(std::mem::size_of::<BumpVertex>(), 48);
    }

    #[test]
    fn quad_split_follows_clipping() {
        let inside = [Vec4::new(-0.5, -0.5, 0.5, 1.0), Vec4::new(2.0, -2.0, 3.9, 4.0)];
        assert_eq!(quad_split(inside), QUAD_SPLIT_UNCLIPPED);
        // Each bound on its own: x and y beyond ±w, z before 0 (near) or beyond w (far).
        for outside in [
            Vec4::new(1.01, 0.0, 0.5, 1.0),
            Vec4::new(0.0, -1.01, 0.5, 1.0),
            Vec4::new(0.0, 0.0, -0.01, 1.0),
            Vec4::new(0.0, 0.0, 1.01, 1.0),
            Vec4::new(0.0, 0.0, 0.5, -1.0),
        ] {
            assert!(needs_clipping(inside.into_iter().chain([outside])), "{outside}");
            assert_eq!(quad_split(inside.into_iter().chain([outside])), QUAD_SPLIT_CLIPPED);
        }
        // Both splits are the same quad, counter-clockwise like it, cut along the two diagonals.
        assert_eq!(QUAD_SPLIT_UNCLIPPED, [0, 1, 2, 0, 2, 3]);
        assert_eq!(QUAD_SPLIT_CLIPPED, [0, 1, 3, 1, 2, 3]);
    }

    #[test]
    fn twist_grid_float_loop() {
        let g = twist_grid();
        assert_eq!(g.len(), 100 * 100 * 6);
        let size = 1.0f32 / 100.0;
        assert_eq!(g[0], [-0.5, -0.5]);
        assert_eq!(g[1], [-0.5 + size, -0.5]);
        assert_eq!(g[2], [-0.5 + size, -0.5 + size]);
        assert_eq!(g[5], [-0.5, -0.5 + size]);
        // The last quad: i = j = 99, x = -0.5f + 99·size, in float.
        let x = -0.5f32 + 99.0 * size;
        let last = &g[g.len() - 6..];
        assert_eq!(last[0], [x, x]);
        assert_eq!(last[2], [x + size, x + size]);
        assert!((x + size - 0.5).abs() < 1e-6);
        // j is the inner loop: the second quad is one step up in y.
        assert_eq!(g[6], [-0.5, -0.5 + size]);
    }

    #[test]
    fn fixed_meshes() {
        let t = double_vision_triangle();
        assert_eq!(
            t[2],
            TexVertex2 {
                position: [0.0, -0.8],
                st: [0.5, 1.0]
            }
        );
        let f = texparams_floor();
        assert_eq!(f[0].position, [-2.0, -1.0, 2.0, 1.0]);
        assert_eq!(f[2].uv, [1.5, 8.5]);
        assert_eq!(f[5].position, [-2.0, -1.0, -16.0, 1.0]);
        assert_eq!(f[3], f[0]);
        assert!(f.iter().all(|c| c.normal == [0.0, 1.0, 0.0]));
    }

    #[test]
    fn bezier_parameters_and_points() {
        let ts = bezier_parameters();
        assert_eq!(ts.len(), 101);
        assert_eq!(ts[0], 0.0);
        assert_eq!(ts[10], 0.099999994);
        assert_eq!(ts[50], 0.49999982);
        assert_eq!(ts[100], 0.99999934);
        let last = bezier_point(ts[100]);
        assert!(
            (last[0] - 0.749999).abs() < 1e-6 && (last[1] + 0.300001).abs() < 1e-6,
            "{last:?}"
        );
        assert_eq!(bezier_point(0.0), [-0.75, -0.45]);
        // y dips to about -0.62 in the middle.
        let low = ts.iter().map(|&t| bezier_point(t)[1]).fold(f32::MAX, f32::min);
        assert!((low + 0.62).abs() < 0.01, "{low}");
    }

    #[test]
    fn bezier_strip_normals() {
        let s = bezier_strip();
        assert_eq!(s.len(), 202);
        assert_eq!(std::mem::size_of::<StripVertex>(), 36);
        assert_eq!(s[0].position, [-0.75, -0.45, -0.5]);
        assert_eq!(s[1].position, [-0.75, -0.45, 0.5]);
        assert!(s.iter().all(|v| v.color == [1.0, 1.0, 0.0]));
        assert_eq!(s[201].normal, [0.0, 0.0, 0.0]);
        // Close to +y; the two end vertices (0 and 200) get one triangle's normal each.
        for (i, v) in s[..201].iter().enumerate() {
            let n = Vec3::from_array(v.normal);
            assert!((n.length() - 1.0).abs() < 1e-5, "{i}: {n}");
            assert!(
                n.z == 0.0 && n.y > if i == 0 || i == 200 { 0.8 } else { 0.9999 },
                "{i}: {n}"
            );
        }
        // Vertex 0 gets only triangle 0's normal (−dy, dx, 0)/ℓ, the even-i form.
        let (p0, p2) = (Vec3::from_array(s[0].position), Vec3::from_array(s[2].position));
        let d = p2 - p0;
        let n0 = Vec3::from_array(s[0].normal);
        assert!((n0 - Vec3::new(-d.y, d.x, 0.0).normalize()).length() < 1e-5, "{n0}");
        // Vertex 1 sums triangles 0 and 1: the x parts nearly cancel.
        assert!(s[1].normal[0].abs() < 0.02, "{:?}", s[1].normal);
    }
}
