//! Meshes on the CPU, no GPU code: the general types ([`Mesh`], [`Vertex`]: bounds, triangle
//! count, welding shared positions), GLUT's solids bit for bit ([`glut`]) and their tessellation
//! levels ([`tess`]), Wavefront OBJ models ([`obj`]), the lectures' hand-made meshes
//! ([`shapes`]) and seed 002's twisted square, exactly ([`twist`]).

pub mod glut;
pub mod obj;
pub mod shapes;
pub mod tess;
pub mod twist;

use bytemuck::{Pod, Zeroable};
use std::collections::HashMap;

/// One vertex: object-space position and normal, as freeglut passes them to GL.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct Vertex {
    /// Object-space position (`glVertexPointer`).
    pub position: [f32; 3],
    /// Object-space normal (`glNormalPointer`), as freeglut computes it.
    pub normal: [f32; 3],
}

/// An indexed triangle list.
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    /// The vertex array, in freeglut's order.
    pub vertices: Vec<Vertex>,
    /// Three indices per triangle, in the order GL rasterises them (see the
    /// module docs; the teapot's triangles are clockwise, see [`Mesh::teapot`]).
    pub indices: Vec<u32>,
}

impl Mesh {
    /// Number of triangles (`indices.len() / 3`).
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// Axis-aligned bounds (min, max) of the positions.
    ///
    /// An empty mesh gives `([0.0; 3], [0.0; 3])`; NaN coordinates are ignored.
    pub fn bounds(&self) -> ([f32; 3], [f32; 3]) {
        if self.vertices.is_empty() {
            return ([0.0; 3], [0.0; 3]);
        }
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        for v in &self.vertices {
            for k in 0..3 {
                lo[k] = lo[k].min(v.position[k]);
                hi[k] = hi[k].max(v.position[k]);
            }
        }
        for k in 0..3 {
            if lo[k] > hi[k] {
                lo[k] = 0.0;
                hi[k] = 0.0;
            }
        }
        (lo, hi)
    }

    /// A copy with vertices that share a position welded into one, normals
    /// averaged and renormalised; used for crack-free displacement.
    ///
    /// * "Share a position" means: within `eps = 1e-6 * (largest finite
    ///   |coordinate|)` (Euclidean), i.e. a few float ulps. An exact match is
    ///   not enough: freeglut's teapot evaluates some shared patch edges from
    ///   the same control points listed in opposite order (the bottom patch's
    ///   last row is the body's last row reversed), so the two copies of such
    ///   an edge differ by 1-2 ulps and an exact weld would leave cracks.
    ///   Distinct vertices of these meshes are orders of magnitude further
    ///   apart. Clustering is greedy: a vertex joins the first earlier
    ///   representative within `eps`, else it becomes a representative.
    /// * The welded normal is the plain (unweighted) average of the normals of
    ///   the vertices merged into it, renormalised. If that sum is (nearly)
    ///   zero or not finite, the representative's own normal is kept.
    /// * The representative (first occurrence) keeps its position; vertices
    ///   keep the order of their first occurrence; every triangle is kept (so
    ///   `triangle_count` is unchanged), even ones whose corners collapse.
    /// * Linear time: finite positions are hashed into a grid of `eps` cells, so a vertex is
    ///   compared only with the representatives of its 27 neighbouring cells; a position with
    ///   an infinite coordinate welds only with an equal one (hashed by its bits) and one with a
    ///   NaN never welds. (A plain bitwise key for all positions would miss the teapot's 1-2 ulp
    ///   seams: 1890 instead of 1621 vertices at grid 8, and cracks.) Vertices whose 27 cells
    ///   hold no other position (`isolated_leaders`, nearly all of a fine mesh) skip the grid:
    ///   27 hash probes each into a table of millions of cells are slow and large for a fine
    ///   mesh (figures: `docs/speed.md`, "Large meshes, models and pictures").
    pub fn welded(&self) -> Mesh {
        let max_abs = self
            .vertices
            .iter()
            .flat_map(|v| v.position)
            .filter(|c| c.is_finite())
            .fold(0.0f64, |m, c| m.max(f64::from(c).abs()));
        let eps = (max_abs * 1e-6).max(f64::from(f32::MIN_POSITIVE));
        let cell_of = |p: [f32; 3]| p.map(|c| (f64::from(c) / eps).floor() as i64);
        let leaders = isolated_leaders(&self.vertices, cell_of);

        let mut grid: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
        // Positions with an infinite coordinate weld only with an equal position (their
        // distance is NaN or infinite), and a NaN coordinate never welds; they stay out of the
        // grid, where they would all share the cells of ±i64::MAX or 0 and be compared with one
        // another (quadratic). Keyed by bits, with -0 as +0 because -0 == 0.
        let mut exact: HashMap<[u32; 3], u32> = HashMap::new();
        let mut remap: Vec<u32> = Vec::with_capacity(self.vertices.len());
        // At most one per input vertex; reserved, since doubling a vector of millions copies it
        // and briefly holds both.
        let mut vertices: Vec<Vertex> = Vec::with_capacity(self.vertices.len());
        let mut sums: Vec<[f64; 3]> = Vec::with_capacity(self.vertices.len());
        for (i, v) in self.vertices.iter().enumerate() {
            let leader = leaders[i];
            if leader != SEARCH && leader as usize != i {
                // A repeat of an isolated position: it joins what its first occurrence joined.
                let id = remap[leader as usize];
                for (acc, &c) in sums[id as usize].iter_mut().zip(&v.normal) {
                    *acc += f64::from(c);
                }
                remap.push(id);
                continue;
            }
            if !v.position.iter().all(|c| c.is_finite()) {
                let new_id = vertices.len() as u32;
                let id = if v.position.iter().any(|c| c.is_nan()) {
                    new_id
                } else {
                    *exact.entry(bits(v.position)).or_insert(new_id)
                };
                if id == new_id {
                    vertices.push(*v);
                    sums.push([0.0; 3]);
                }
                for (acc, &c) in sums[id as usize].iter_mut().zip(&v.normal) {
                    *acc += f64::from(c);
                }
                remap.push(id);
                continue;
            }
            let cell = cell_of(v.position);
            let mut found = None;
            // An isolated first occurrence has nothing to find, and no later search can reach
            // it (whatever lies within its 27 cells is at its own position, so is isolated too).
            'search: for dx in -1i64..=1 {
                if leader != SEARCH {
                    break;
                }
                for dy in -1i64..=1 {
                    for dz in -1i64..=1 {
                        let key = [
                            cell[0].saturating_add(dx),
                            cell[1].saturating_add(dy),
                            cell[2].saturating_add(dz),
                        ];
                        let Some(ids) = grid.get(&key) else { continue };
                        for &id in ids {
                            let q = vertices[id as usize].position;
                            let d2: f64 = (0..3)
                                .map(|k| {
                                    let d = f64::from(v.position[k]) - f64::from(q[k]);
                                    d * d
                                })
                                .sum();
                            if d2 <= eps * eps || v.position == q {
                                found = Some(id);
                                break 'search;
                            }
                        }
                    }
                }
            }
            let id = match found {
                Some(id) => id,
                None => {
                    let id = vertices.len() as u32;
                    vertices.push(*v);
                    sums.push([0.0; 3]);
                    if leader == SEARCH {
                        grid.entry(cell).or_default().push(id);
                    }
                    id
                }
            };
            for (acc, &c) in sums[id as usize].iter_mut().zip(&v.normal) {
                *acc += f64::from(c);
            }
            remap.push(id);
        }
        for (v, s) in vertices.iter_mut().zip(&sums) {
            let len = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
            if len.is_finite() && len > 1e-12 {
                v.normal = [(s[0] / len) as f32, (s[1] / len) as f32, (s[2] / len) as f32];
            }
        }
        let indices = self
            .indices
            .iter()
            .map(|&i| remap.get(i as usize).copied().unwrap_or(i))
            .collect();
        Mesh { vertices, indices }
    }
}

/// A position's bits with -0 as +0, so that equal finite positions (`==`) get equal keys.
fn bits(p: [f32; 3]) -> [u32; 3] {
    p.map(|c| if c == 0.0 { 0 } else { c.to_bits() })
}

/// In `isolated_leaders`' answer: this vertex needs the grid search.
const SEARCH: u32 = u32::MAX;

/// For each vertex, [`SEARCH`] unless its position is finite and every finite vertex in its 27
/// grid cells (its own and the 26 around it) is at exactly that position; then the index of
/// the first of those. Such a vertex is decided without the grid: the first becomes a new
/// vertex, the others join it (the grid search would find nothing else).
///
/// Sorting the cells makes this one pass over memory in order, where probing a hash table of
/// millions of cells 27 times per vertex missed the cache at nearly every probe.
fn isolated_leaders(vertices: &[Vertex], cell_of: impl Fn([f32; 3]) -> [i64; 3]) -> Vec<u32> {
    let mut leaders = vec![SEARCH; vertices.len()];
    // A cell packs into 21 bits per axis, x highest, so that the packed keys sort like the
    // cells and a neighbour is the key plus a constant. `welded`'s cells lie within ±1e6 + 1
    // (eps is at least 1e-6 of the largest coordinate); anything else, or an index past u32,
    // leaves every vertex to the search.
    const BITS: u32 = 21;
    const BIAS: i64 = 1 << (BITS - 1);
    let fits = |c: i64| (-BIAS + 1..BIAS - 1).contains(&c);
    let pack = |c: [i64; 3]| c.iter().fold(0u64, |key, &a| (key << BITS) | (a + BIAS) as u64);
    if vertices.len() >= SEARCH as usize {
        return leaders;
    }
    let mut keys: Vec<(u64, u32)> = Vec::with_capacity(vertices.len());
    for (i, v) in vertices.iter().enumerate() {
        if v.position.iter().all(|c| c.is_finite()) {
            let cell = cell_of(v.position);
            if !cell.iter().all(|&c| fits(c)) {
                return leaders;
            }
            keys.push((pack(cell), i as u32));
        }
    }
    // By cell, and within a cell by index, so a run's first entry is its first occurrence.
    keys.sort_unstable();

    // The occupied cells, and whether any of the 26 around each is occupied too. For each of
    // the 9 columns (dx, dy) the neighbours' keys are this key plus a fixed offset, and the
    // keys rise, so one cursor per column only moves forward.
    let mut cells: Vec<u64> = keys.iter().map(|&(k, _)| k).collect();
    cells.dedup();
    let mut offsets = [0i64; 9];
    for (o, (dx, dy)) in offsets
        .iter_mut()
        .zip((-1i64..=1).flat_map(|dx| (-1i64..=1).map(move |dy| (dx, dy))))
    {
        *o = (dx << (2 * BITS)) + (dy << BITS);
    }
    let mut cursors = [0usize; 9];
    let mut crowded = vec![false; cells.len()];
    for (j, &key) in cells.iter().enumerate() {
        for (cursor, &offset) in cursors.iter_mut().zip(&offsets) {
            // `fits` keeps key + offset ± 1 inside the packing: no wrap, no borrow.
            let lo = (key as i64 + offset - 1) as u64;
            let hi = lo + 2;
            while *cursor < cells.len() && cells[*cursor] < lo {
                *cursor += 1;
            }
            let mut c = *cursor;
            while c < cells.len() && cells[c] <= hi {
                if c != j {
                    crowded[j] = true;
                    break;
                }
                c += 1;
            }
        }
    }

    // Each run of one cell: isolated if its cell is not crowded and it holds one position.
    let mut j = 0;
    let mut start = 0;
    while start < keys.len() {
        let (key, first) = keys[start];
        let mut end = start + 1;
        while end < keys.len() && keys[end].0 == key {
            end += 1;
        }
        // (A run of one, nearly every run, reads no position: those reads miss the cache.)
        let alone = !crowded[j] && {
            let position = || bits(vertices[first as usize].position);
            keys[start + 1..end]
                .iter()
                .all(|&(_, i)| bits(vertices[i as usize].position) == position())
        };
        if alone {
            for &(_, i) in &keys[start..end] {
                leaders[i as usize] = first;
            }
        }
        j += 1;
        start = end;
    }
    leaders
}

/// The least `n` in `lo + 1 ..= hi` for which `ok(n)` holds, given `ok(lo)` false (or `lo` not
/// a candidate) and `ok(hi)` true, by bisection: the automatic grids and tessellation levels
/// search for the coarsest one within an error budget this way.
pub(crate) fn least_passing(mut lo: u32, mut hi: u32, ok: impl Fn(u32) -> bool) -> u32 {
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if ok(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::glut::tests::{check_indices, check_unit_normals, len, sub};
    use crate::mesh::tess::{self, Object};

    #[test]
    fn welded_cube() {
        let m = Mesh::cube(1.5);
        let w = m.welded();
        assert_eq!(w.vertices.len(), 8);
        assert_eq!(w.triangle_count(), 12);
        check_indices(&w);
        let k = 1.0 / 3.0f32.sqrt();
        for v in &w.vertices {
            for c in 0..3 {
                assert!((v.normal[c] - v.position[c].signum() * k).abs() < 1e-6);
            }
        }
    }

    #[test]
    fn welded_other_shapes() {
        // sphere and torus have no duplicated positions
        let s = Mesh::sphere(1.0, 24, 24);
        assert_eq!(s.welded().vertices.len(), s.vertices.len());
        let t = Mesh::torus(0.5, 1.0, 24, 24);
        assert_eq!(t.welded().vertices.len(), t.vertices.len());
        // the teapot's patch seams weld exactly: no two welded vertices are
        // closer than 1e-6 (so displacement cannot open cracks)
        let m = Mesh::teapot(1.0, 8);
        let w = m.welded();
        assert_eq!(w.triangle_count(), m.triangle_count());
        check_indices(&w);
        assert!(w.vertices.len() < m.vertices.len());
        check_unit_normals(&w, 1e-5);
        for (i, a) in w.vertices.iter().enumerate() {
            for b in &w.vertices[i + 1..] {
                assert!(len(sub(a.position, b.position)) > 1e-6, "{a:?} {b:?}");
            }
        }
    }

    /// `welded()` as it was before non-finite positions got their own exact-match table (a
    /// verbatim copy), the yardstick for "the same output as before".
    fn welded_reference(mesh: &Mesh) -> Mesh {
        let max_abs = mesh
            .vertices
            .iter()
            .flat_map(|v| v.position)
            .filter(|c| c.is_finite())
            .fold(0.0f64, |m, c| m.max(f64::from(c).abs()));
        let eps = (max_abs * 1e-6).max(f64::from(f32::MIN_POSITIVE));
        let cell_of = |p: [f32; 3]| p.map(|c| (f64::from(c) / eps).floor() as i64);
        let mut grid: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
        let mut remap = Vec::with_capacity(mesh.vertices.len());
        let mut vertices: Vec<Vertex> = Vec::new();
        let mut sums: Vec<[f64; 3]> = Vec::new();
        for v in &mesh.vertices {
            let cell = cell_of(v.position);
            let mut found = None;
            'search: for dx in -1i64..=1 {
                for dy in -1i64..=1 {
                    for dz in -1i64..=1 {
                        let key = [
                            cell[0].saturating_add(dx),
                            cell[1].saturating_add(dy),
                            cell[2].saturating_add(dz),
                        ];
                        let Some(ids) = grid.get(&key) else { continue };
                        for &id in ids {
                            let q = vertices[id as usize].position;
                            let d2: f64 = (0..3)
                                .map(|k| {
                                    let d = f64::from(v.position[k]) - f64::from(q[k]);
                                    d * d
                                })
                                .sum();
                            if d2 <= eps * eps || v.position == q {
                                found = Some(id);
                                break 'search;
                            }
                        }
                    }
                }
            }
            let id = match found {
                Some(id) => id,
                None => {
                    let id = vertices.len() as u32;
                    vertices.push(*v);
                    sums.push([0.0; 3]);
                    grid.entry(cell).or_default().push(id);
                    id
                }
            };
            for (acc, &c) in sums[id as usize].iter_mut().zip(&v.normal) {
                *acc += f64::from(c);
            }
            remap.push(id);
        }
        for (v, s) in vertices.iter_mut().zip(&sums) {
            let len = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
            if len.is_finite() && len > 1e-12 {
                v.normal = [(s[0] / len) as f32, (s[1] / len) as f32, (s[2] / len) as f32];
            }
        }
        let indices = mesh
            .indices
            .iter()
            .map(|&i| remap.get(i as usize).copied().unwrap_or(i))
            .collect();
        Mesh { vertices, indices }
    }

    /// Bit for bit: positions, normals (as bits, so NaN compares) and indices.
    fn assert_same_mesh(name: &str, a: &Mesh, b: &Mesh) {
        let bits = |m: &Mesh| -> Vec<[u32; 6]> {
            m.vertices
                .iter()
                .map(|v| {
                    let [x, y, z] = v.position.map(f32::to_bits);
                    let [nx, ny, nz] = v.normal.map(f32::to_bits);
                    [x, y, z, nx, ny, nz]
                })
                .collect()
        };
        assert_eq!(bits(a), bits(b), "{name}: vertices differ");
        assert_eq!(a.indices, b.indices, "{name}: indices differ");
    }

    #[test]
    fn welded_matches_the_reference_on_the_glut_objects() {
        for (name, mesh) in [
            ("cube", Mesh::cube(1.5)),
            ("sphere", Mesh::sphere(1.0, 24, 24)),
            ("torus", Mesh::torus(0.5, 1.0, 24, 24)),
            ("teapot", Mesh::teapot(1.0, Mesh::TEAPOT_DEFAULT_GRID)),
            ("teapot 3", Mesh::teapot(1.0, 3)),
            ("sphere 5x4", Mesh::sphere(0.5, 5, 4)),
        ] {
            assert_same_mesh(name, &mesh.welded(), &welded_reference(&mesh));
        }
        // Non-finite and signed-zero positions: NaN never welds, equal infinities and +0/-0 do.
        let n = [0.0, 0.0, 1.0];
        let odd = Mesh {
            vertices: [
                [f32::NAN, 0.0, 0.0],
                [f32::NAN, 0.0, 0.0],
                [f32::INFINITY, 1.0, 0.0],
                [f32::INFINITY, 1.0, -0.0],
                [f32::INFINITY, 1.0 + 1e-7, 0.0],
                [f32::NEG_INFINITY, f32::NAN, 2.0],
                [0.0, -0.0, 0.0],
                [-0.0, 0.0, 0.0],
                [1.0, 2.0, 3.0],
                [1.0, 2.0, 3.0 + 1e-7],
            ]
            .map(|position| Vertex { position, normal: n })
            .to_vec(),
            indices: vec![0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 3, 2],
        };
        assert_same_mesh("non-finite", &odd.welded(), &welded_reference(&odd));
    }

    #[test]
    fn welded_level_512_sphere_keeps_every_vertex() {
        // 512 * 511 + 2 distinct positions: nothing to weld, every index kept.
        let s = Mesh::sphere(1.0, 512, 512);
        let w = s.welded();
        assert_eq!(w.vertices.len(), 512 * 511 + 2);
        assert_eq!(w.indices, s.indices);
        check_indices(&w);
    }

    #[test]
    fn welded_many_non_finite_positions() {
        // NaN positions must not all land in one grid cell and be compared with every earlier
        // one there (quadratic; figures in docs/speed.md). Each stays its own vertex.
        let count = 300_000;
        let m = Mesh {
            vertices: (0..count)
                .map(|i| Vertex {
                    position: [f32::NAN, f32::NAN, if i % 2 == 0 { f32::NAN } else { 0.0 }],
                    normal: [0.0, 0.0, 1.0],
                })
                .collect(),
            indices: (0..count as u32).collect(),
        };
        let w = m.welded();
        assert_eq!(w.vertices.len(), count);
        assert_eq!(w.indices, m.indices);
    }

    /// `welded()` as it was before isolated vertices skipped the grid (a verbatim copy of that
    /// version): the yardstick for "bit for bit as before" on every input below.
    fn welded_grid_reference(mesh: &Mesh) -> Mesh {
        let max_abs = mesh
            .vertices
            .iter()
            .flat_map(|v| v.position)
            .filter(|c| c.is_finite())
            .fold(0.0f64, |m, c| m.max(f64::from(c).abs()));
        let eps = (max_abs * 1e-6).max(f64::from(f32::MIN_POSITIVE));
        let cell_of = |p: [f32; 3]| p.map(|c| (f64::from(c) / eps).floor() as i64);

        let mut grid: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
        let mut exact: HashMap<[u32; 3], u32> = HashMap::new();
        let bits = |p: [f32; 3]| p.map(|c| if c == 0.0 { 0 } else { c.to_bits() });
        let mut remap = Vec::with_capacity(mesh.vertices.len());
        let mut vertices: Vec<Vertex> = Vec::new();
        let mut sums: Vec<[f64; 3]> = Vec::new();
        for v in &mesh.vertices {
            if !v.position.iter().all(|c| c.is_finite()) {
                let new_id = vertices.len() as u32;
                let id = if v.position.iter().any(|c| c.is_nan()) {
                    new_id
                } else {
                    *exact.entry(bits(v.position)).or_insert(new_id)
                };
                if id == new_id {
                    vertices.push(*v);
                    sums.push([0.0; 3]);
                }
                for (acc, &c) in sums[id as usize].iter_mut().zip(&v.normal) {
                    *acc += f64::from(c);
                }
                remap.push(id);
                continue;
            }
            let cell = cell_of(v.position);
            let mut found = None;
            'search: for dx in -1i64..=1 {
                for dy in -1i64..=1 {
                    for dz in -1i64..=1 {
                        let key = [
                            cell[0].saturating_add(dx),
                            cell[1].saturating_add(dy),
                            cell[2].saturating_add(dz),
                        ];
                        let Some(ids) = grid.get(&key) else { continue };
                        for &id in ids {
                            let q = vertices[id as usize].position;
                            let d2: f64 = (0..3)
                                .map(|k| {
                                    let d = f64::from(v.position[k]) - f64::from(q[k]);
                                    d * d
                                })
                                .sum();
                            if d2 <= eps * eps || v.position == q {
                                found = Some(id);
                                break 'search;
                            }
                        }
                    }
                }
            }
            let id = match found {
                Some(id) => id,
                None => {
                    let id = vertices.len() as u32;
                    vertices.push(*v);
                    sums.push([0.0; 3]);
                    grid.entry(cell).or_default().push(id);
                    id
                }
            };
            for (acc, &c) in sums[id as usize].iter_mut().zip(&v.normal) {
                *acc += f64::from(c);
            }
            remap.push(id);
        }
        for (v, s) in vertices.iter_mut().zip(&sums) {
            let len = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
            if len.is_finite() && len > 1e-12 {
                v.normal = [(s[0] / len) as f32, (s[1] / len) as f32, (s[2] / len) as f32];
            }
        }
        let indices = mesh
            .indices
            .iter()
            .map(|&i| remap.get(i as usize).copied().unwrap_or(i))
            .collect();
        Mesh { vertices, indices }
    }

    /// A small deterministic generator (xorshift), so the point clouds below need no crate.
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0
        }
        /// Uniform in [-1, 1).
        fn unit(&mut self) -> f32 {
            (self.next() >> 40) as f32 / (1u64 << 23) as f32 - 1.0
        }
    }

    /// A triangle soup over `positions`, every vertex used, with varied unit-ish normals.
    fn soup(positions: Vec<[f32; 3]>, rng: &mut Rng) -> Mesh {
        let vertices: Vec<Vertex> = positions
            .into_iter()
            .map(|position| Vertex {
                position,
                normal: [rng.unit(), rng.unit(), rng.unit()],
            })
            .collect();
        let n = vertices.len() as u32;
        let indices = (0..n - n % 3).chain([0, n, n + 7]).collect();
        Mesh { vertices, indices }
    }

    #[test]
    fn welded_matches_the_grid_reference_on_every_object_and_level() {
        for level in [3, 4, 7, 10, 24, 61] {
            for object in Object::ALL {
                let mesh = tess::mesh(object, level);
                let name = format!("{} {level}", object.name());
                assert_same_mesh(&name, &mesh.welded(), &welded_grid_reference(&mesh));
            }
        }
        // Scaled, mirrored, flattened and collapsed copies: the grid's `eps` follows the
        // largest coordinate, so these move the seams to other cells and cell edges.
        for size in [0.0, 1e-30, 1e-7, 0.37, -1.0, 3.0e5, 1e30] {
            for mesh in [
                Mesh::teapot(size, 10),
                Mesh::sphere(size, 7, 5),
                Mesh::torus(size, size * 2.0, 9, 4),
            ] {
                let name = format!("size {size}, {} vertices", mesh.vertices.len());
                assert_same_mesh(&name, &mesh.welded(), &welded_grid_reference(&mesh));
            }
        }
    }

    #[test]
    fn welded_matches_the_grid_reference_on_clusters_and_odd_values() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        // Points a fraction of `eps` to a few `eps` apart (eps = 1e-6 here, the largest
        // coordinate being 1): chains of near neighbours, where the greedy order and the
        // first-cell-found tie-break decide the result; some exact repeats and signed zeros.
        let mut positions = vec![[1.0, 0.0, 0.0], [-1.0, -1.0, -1.0]];
        for spread in [0.2e-6, 1e-6, 3e-6, 30e-6] {
            for _ in 0..3000 {
                let p = [
                    0.25 + spread * rng.unit(),
                    -0.5 + spread * rng.unit(),
                    spread * rng.unit(),
                ];
                positions.push(p);
                if rng.next().is_multiple_of(5) {
                    let k = (rng.next() % positions.len() as u64) as usize;
                    positions.push(positions[k]);
                }
            }
        }
        for _ in 0..200 {
            let z = |r: &mut Rng| if r.next().is_multiple_of(2) { 0.0 } else { -0.0 };
            positions.push([z(&mut rng), z(&mut rng), 1e-6 * rng.unit()]);
        }
        // Values on cell edges: exact multiples of eps, and their neighbours one ulp away.
        for k in -20..20 {
            let c = k as f32 * 1e-6;
            for p in [
                c,
                f32::from_bits(c.to_bits() + 1),
                f32::from_bits(c.to_bits().wrapping_sub(1)),
            ] {
                positions.push([p, 0.5, p]);
            }
        }
        let mesh = soup(positions.clone(), &mut rng);
        assert_same_mesh("clusters", &mesh.welded(), &welded_grid_reference(&mesh));

        // The same with non-finite positions mixed in (their own exact-match path).
        let odd = [
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            -0.0,
            f32::MAX,
            f32::MIN,
            1e-45,
        ];
        for k in 0..positions.len() / 7 {
            let i = (rng.next() % positions.len() as u64) as usize;
            positions[i][k % 3] = odd[k % odd.len()];
        }
        let mesh = soup(positions, &mut rng);
        assert_same_mesh("non-finite", &mesh.welded(), &welded_grid_reference(&mesh));

        // Degenerate meshes: empty, one vertex, all at one point, only non-finite.
        let one = |position| Vertex {
            position,
            normal: [0.0, 0.0, 0.0],
        };
        for mesh in [
            Mesh::default(),
            Mesh {
                vertices: vec![one([0.5; 3])],
                indices: vec![0, 0, 0],
            },
            Mesh {
                vertices: vec![one([0.0; 3]); 1000],
                indices: (0..999).collect(),
            },
            Mesh {
                vertices: vec![one([f32::NAN; 3]); 10],
                indices: vec![9, 3, 1],
            },
            Mesh {
                vertices: vec![one([f32::INFINITY; 3]); 10],
                indices: vec![9, 3, 1],
            },
        ] {
            assert_same_mesh("degenerate", &mesh.welded(), &welded_grid_reference(&mesh));
        }
    }

    /// FNV-1a over a mesh's bits: vertex positions and normals, then indices.
    fn mesh_hash(m: &Mesh) -> u64 {
        let words = m.vertices.iter().flat_map(|v| v.position.into_iter().chain(v.normal));
        let words = words.map(f32::to_bits).chain(m.indices.iter().copied());
        words.fold(0xcbf2_9ce4_8422_2325, |h, w| {
            w.to_le_bytes()
                .iter()
                .fold(h, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3))
        })
    }

    #[test]
    fn welded_level_512_is_what_it_was() {
        // Hashes of the level-512 welds the grid-only version made (too slow to run as a
        // reference in a test; docs/speed.md), and their vertex counts.
        for (object, vertices, hash) in [
            (Object::Sphere, 261_634, 0x65cd_7539_acb8_cc48),
            (Object::Torus, 262_144, 0xf364_ac96_c374_a922),
            (Object::Teapot, 8_359_925, 0xb5e0_0070_bd3c_b1d3),
        ] {
            let w = tess::mesh(object, 512).welded();
            assert_eq!((w.vertices.len(), mesh_hash(&w)), (vertices, hash), "{object:?}");
        }
    }

    // ----------------------------------------------------------- clamping
}
