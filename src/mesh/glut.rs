//! GLUT-exact meshes: CPU geometry reproducing freeglut 3.4.0's solid shapes.
//!
//! Everything here is a port of what freeglut 3.4.0 (`src/fg_geometry.c`,
//! `src/fg_teapot.c`, `src/fg_teapot_data.h`; tag `v3.4.0`) hands to GL for
//! `glutSolidCube`, `glutSolidSphere`, `glutSolidTorus` and `glutSolidTeapot`:
//! the same vertex positions and normals (same float/double precision
//! choices, same sin/cos tables), the same vertex order, and the same
//! triangles, in the same order, that the GL primitives freeglut issues
//! decompose into.
//!
//! # Which GL primitives freeglut uses
//!
//! In the classic (compatibility profile, fixed-function attribute) path,
//! freeglut 3.4.0 draws solids through `fghDrawGeometrySolid11`, which only
//! ever issues `glDrawArrays(GL_TRIANGLES)`, `glDrawElements(GL_TRIANGLES)`
//! (when the shape is drawn in one part) or one
//! `glDrawElements(GL_TRIANGLE_STRIP)` per part (when there is more than one
//! part). The GL 2.0 attribute path (`fghDrawGeometrySolid20`) and the GL 1.0
//! `glBegin` fallback issue exactly the same primitives. `GL_QUADS` is never
//! used by `fg_geometry.c` or `fg_teapot.c` (only by the menu code), so no
//! quad-splitting convention of the GL driver is involved: every quad is
//! split by freeglut itself, and that split is reproduced here.
//!
//! * Cube: 6 quads pre-split by freeglut (`vert4Decomp = {0,1,2, 0,2,3}`),
//!   drawn as one `GL_TRIANGLES` list: quad `(v0,v1,v2,v3)` becomes
//!   `(v0,v1,v2)`, `(v0,v2,v3)` (diagonal v0-v2).
//! * Sphere: one `GL_TRIANGLE_STRIP` per stack; torus: one
//!   `GL_TRIANGLE_STRIP` per side. Strip triangle `k` uses strip vertices
//!   `(k, k+1, k+2)` for even `k` and `(k+1, k, k+2)` for odd `k` (GL's
//!   convention, which keeps the orientation). Strip triangles with a
//!   repeated index (the sphere's pole strips repeat the pole vertex every
//!   other vertex) have zero area and produce no fragments in GL; they are
//!   dropped. All other triangles are kept in strip order.
//! * Teapot: freeglut builds its own `GL_TRIANGLES` index list per 8x8-vertex
//!   patch grid: cell `(r, c)` with `a = r*n + c` (row = u, column = v) gives
//!   `(a, a+n, a+n+1)` and `(a, a+n+1, a+1)` (diagonal a - a+n+1).
//!
//! # Precision
//!
//! freeglut computes in `float` except where it calls `sin`/`cos`/`sqrt`
//! (double). Here the same operations are done in `f32` in the same order
//! (Rust never contracts `a*b+c` into an FMA, and freeglut's x86-64 builds
//! have no FMA either), with `f64` only where freeglut goes through double.
//!
//! This was checked bit for bit (positions, normals, triangle list and its
//! order) against freeglut 3.4.0's own `fg_geometry.c`/`fg_teapot.c`,
//! compiled with gcc -O2 on x86-64/glibc with stub GL entry points recording
//! the draw calls, for `cube(1.5)`, `sphere(1,24,24)`, `sphere(2.5,7,5)`,
//! `torus(0.5,1,24,24)`, `torus(0.2,3,5,9)`, `teapot(1,8)` and the positions
//! of `teapot(0.7,8)`.

use super::{Mesh, Vertex};

impl Mesh {
    /// freeglut 3.4.0's `GLUT_SOLID_N_SUBDIV`: vertices per patch edge of the
    /// solid teapot (8x8 vertices, 7x7 quads, per Bezier patch).
    pub const TEAPOT_DEFAULT_GRID: u32 = 8;

    /// `glutSolidCube(size)`.
    ///
    /// 24 vertices (4 per face, each face with its own normal), in freeglut's
    /// face order +z, +x, +y, -x, -y, -z; 12 triangles, two per face.
    pub fn cube(size: f32) -> Mesh {
        let mut vertices = Vec::with_capacity(24);
        let mut indices = Vec::with_capacity(36);
        for (face, corners) in CUBE_FACES.iter().enumerate() {
            let base = (face * 4) as u32;
            for &corner in corners {
                let p = CUBE_CORNERS[corner];
                // fghCube: vertices[i] = dSize * cube_verts[i] (float).
                vertices.push(Vertex {
                    position: [size * p[0], size * p[1], size * p[2]],
                    normal: CUBE_NORMALS[face],
                });
            }
            // vert4Decomp = {0,1,2, 0,2,3}
            indices.extend_from_slice(&[base, base + 1, base + 2, base, base + 2, base + 3]);
        }
        Mesh { vertices, indices }
    }

    /// `glutSolidSphere(radius, slices, stacks)`.
    ///
    /// Vertex 0 is the top pole `(0,0,radius)`, then `stacks-1` rings of
    /// `slices` vertices (going from +z to -z; within a ring the angle
    /// decreases, i.e. clockwise seen from +z, as freeglut's `-slices` circle
    /// table gives), then the bottom pole. No seam vertex is duplicated: the
    /// strips wrap around by index.
    ///
    /// Clamping: `slices < 3` is treated as 3 and `stacks < 2` as 2. freeglut
    /// draws nothing for `slices == 0` or `stacks < 2` and a flat (zero
    /// volume) shape for `slices` 1 or 2, so the clamp only changes inputs
    /// for which freeglut's output is empty or degenerate.
    pub fn sphere(radius: f32, slices: u32, stacks: u32) -> Mesh {
        let slices = slices.clamp(3, MAX_COUNT);
        let stacks = stacks.clamp(2, MAX_COUNT);
        let (s, t) = (slices as usize, stacks as usize);

        let (sint1, cost1) = circle_table(-(slices as i64), false);
        let (sint2, cost2) = circle_table(stacks as i64, true);

        let n_vert = s * (t - 1) + 2;
        let mut vertices = Vec::with_capacity(n_vert);
        vertices.push(Vertex {
            position: [0.0, 0.0, radius],
            normal: [0.0, 0.0, 1.0],
        });
        for i in 1..t {
            for j in 0..s {
                let x = cost1[j] * sint2[i];
                let y = sint1[j] * sint2[i];
                let z = cost2[i];
                vertices.push(Vertex {
                    position: [x * radius, y * radius, z * radius],
                    normal: [x, y, z],
                });
            }
        }
        vertices.push(Vertex {
            position: [0.0, 0.0, -radius],
            normal: [0.0, 0.0, -1.0],
        });

        // One strip of (slices+1)*2 indices per stack, as fghSphere builds them.
        let bottom = (n_vert - 1) as u32;
        let mut indices = Vec::with_capacity(6 * s * (t - 1));
        let mut strip = Vec::with_capacity((s + 1) * 2);
        // top stack
        for j in 0..slices {
            strip.extend_from_slice(&[j + 1, 0]);
        }
        strip.extend_from_slice(&[1, 0]);
        push_strip(&mut indices, &strip);
        // middle stacks
        for i in 0..stacks - 2 {
            strip.clear();
            let offset = 1 + i * slices;
            for j in 0..slices {
                strip.extend_from_slice(&[offset + j + slices, offset + j]);
            }
            strip.extend_from_slice(&[offset + slices, offset]);
            push_strip(&mut indices, &strip);
        }
        // bottom stack
        strip.clear();
        let offset = 1 + (stacks - 2) * slices;
        for j in 0..slices {
            strip.extend_from_slice(&[bottom, offset + j]);
        }
        strip.extend_from_slice(&[bottom, offset]);
        push_strip(&mut indices, &strip);

        Mesh { vertices, indices }
    }

    /// `glutSolidTorus(inner_radius, outer_radius, sides, rings)`.
    ///
    /// The torus lies around the z axis; `outer_radius` is the distance from
    /// the origin to the tube's centre circle, `inner_radius` the tube radius.
    /// Vertex `ring * sides + side`; no seam vertex is duplicated.
    ///
    /// Clamping: `sides < 3` and `rings < 3` are treated as 3. freeglut draws
    /// nothing below 2 and a flat (zero volume) shape at 2.
    pub fn torus(inner_radius: f32, outer_radius: f32, sides: u32, rings: u32) -> Mesh {
        let sides = sides.clamp(3, MAX_COUNT);
        let rings = rings.clamp(3, MAX_COUNT);
        let (ns, nr) = (sides as usize, rings as usize);

        let (spsi, cpsi) = circle_table(rings as i64, false);
        let (sphi, cphi) = circle_table(-(sides as i64), false);

        let mut vertices = Vec::with_capacity(ns * nr);
        for j in 0..nr {
            for i in 0..ns {
                let r = outer_radius + cphi[i] * inner_radius;
                vertices.push(Vertex {
                    position: [cpsi[j] * r, spsi[j] * r, sphi[i] * inner_radius],
                    normal: [cpsi[j] * cphi[i], spsi[j] * cphi[i], sphi[i]],
                });
            }
        }

        // One strip of (rings+1)*2 indices per side, as fghTorus builds them.
        let mut indices = Vec::with_capacity(6 * ns * nr);
        let mut strip = Vec::with_capacity((nr + 1) * 2);
        for i in 0..sides {
            strip.clear();
            // ioff = 1, or -i for the last side (wraps to side 0)
            let next = if i == sides - 1 { 0 } else { i + 1 };
            for j in 0..rings {
                let ring = j * sides;
                strip.extend_from_slice(&[ring + i, ring + next]);
            }
            strip.extend_from_slice(&[i, next]);
            push_strip(&mut indices, &strip);
        }

        Mesh { vertices, indices }
    }

    /// `glutSolidTeapot(size)` as freeglut 3.x's `fg_teapot.c` evaluates it,
    /// with `grid` vertices per patch edge (freeglut: [`Self::TEAPOT_DEFAULT_GRID`]).
    ///
    /// * Control points: freeglut's 129 points / 10 input patches (rim, body
    ///   x2, lid x2, bottom, handle x2, spout x2). Each control point
    ///   `(x, y, z)` becomes `(x*s/2, (z-1.575)*s/2, -y*s/2)` with
    ///   `s = size`: scale by `size/2`, shift the data (z in [0, 3.15]) down
    ///   by 1.575 to centre it, and rotate by 270 degrees about x (data z-up
    ///   becomes +Y; data y becomes -Z).
    /// * Patches 0..6 (rim, body, lid, bottom) are emitted 4 times: as is,
    ///   then rotated about Y by 90 (`(x,y,z) -> (z,y,-x)`), 180 and 270
    ///   degrees. Patches 6..10 (handle, spout) are emitted twice: as is, then
    ///   mirrored across the z=0 plane (negated z) with the row order reversed
    ///   to keep the winding. That is 32 patches of `grid*grid` vertices.
    /// * Per patch, vertex `(u, v)` (row u, column v, both `k/(grid-1)`) and
    ///   its normal `normalize(dP/dv x dP/du)` come from the cubic Bernstein
    ///   polynomials and their derivatives, in f32, in freeglut's order.
    /// * Degenerate normals: the bottom patch's first row collapses to one
    ///   point (the derivative along the row is zero, so freeglut's
    ///   normalisation gives NaN) and the lid's first row is nearly
    ///   degenerate. freeglut overwrites the whole first row of the lid patch
    ///   with `(0,1,0)` and of the bottom patch with `(0,-1,0)` (before
    ///   rotating); the same is done here, so no NaN survives.
    /// * Normals are computed from the control points at this `size` (freeglut
    ///   caches the normals of its first call, so this matches a program whose
    ///   first teapot call had this size; for size 1 the scaling is exact).
    ///   For `size == 0` or a non-finite size the normals are computed at size
    ///   1 (freeglut would produce NaN normals at size 0). A negative size
    ///   point-reflects the positions but leaves the normals unchanged, as in
    ///   freeglut.
    ///
    /// * Winding: freeglut's normal is `dP/dv x dP/du`, while its triangles
    ///   run `(u,v) -> (u+1,v) -> (u+1,v+1)`, i.e. along `dP/du x dP/dv`. So
    ///   seen from outside (where the normals point) every teapot triangle is
    ///   clockwise, unlike the cube, sphere and torus. This is kept as is: in
    ///   GL's default state (no culling, one-sided lighting) it is invisible,
    ///   but with back-face culling of CCW-front triangles the outside of the
    ///   teapot is culled and `gl_FrontFacing` is false on it. The only
    ///   triangles with the other orientation are slivers with two corners on
    ///   the collapsed first row of the lid-top and bottom patches.
    ///
    /// Clamping: `grid < 2` is treated as 2 (freeglut's `s/(grid-1)` needs at
    /// least 2 samples per edge).
    pub fn teapot(size: f32, grid: u32) -> Mesh {
        // Keep within u32 indices comfortably (32 * grid^2 vertices).
        let n = grid.clamp(2, 1024) as usize;
        let (bern_0, bern_1) = pregen_bernstein(n);
        let normal_size = if size != 0.0 && size.is_finite() { size } else { 1.0 };

        let n_patches = 6 * 4 + 4 * 2;
        let per_patch = n * n;
        let mut vertices = Vec::with_capacity(n_patches * per_patch);
        for p in 0..TEAPOT_PATCHES.len() {
            let cp = teapot_control_points(p, size);
            let (pos, mut nrm) = eval_bezier_with_norm(&cp, n, &bern_0, &bern_1);
            if normal_size != size {
                let cp_n = teapot_control_points(p, normal_size);
                nrm = eval_bezier_with_norm(&cp_n, n, &bern_0, &bern_1).1;
            }
            // normalFix: p == 3 (lid top) and p == 5 (bottom centre)
            let fix = match p {
                3 => Some([0.0, 1.0, 0.0]),
                5 => Some([0.0, -1.0, 0.0]),
                _ => None,
            };
            if let Some(f) = fix {
                for v in nrm.iter_mut().take(n) {
                    *v = f;
                }
            }
            let base: Vec<Vertex> = pos
                .iter()
                .zip(nrm.iter())
                .map(|(&position, &normal)| Vertex { position, normal })
                .collect();

            if p < 6 {
                // 4 copies: 0, 90, 180, 270 degrees about Y
                let rots: [fn([f32; 3]) -> [f32; 3]; 4] = [
                    |a| a,
                    |a| [a[2], a[1], -a[0]],
                    |a| [-a[0], a[1], -a[2]],
                    |a| [-a[2], a[1], a[0]],
                ];
                for rot in rots {
                    vertices.extend(base.iter().map(|v| Vertex {
                        position: rot(v.position),
                        normal: rot(v.normal),
                    }));
                }
            } else {
                // original, then mirrored (negate z) with rows reversed
                vertices.extend_from_slice(&base);
                for u in 0..n {
                    let row = &base[(n - 1 - u) * n..(n - u) * n];
                    vertices.extend(row.iter().map(|v| Vertex {
                        position: [v.position[0], v.position[1], -v.position[2]],
                        normal: [v.normal[0], v.normal[1], -v.normal[2]],
                    }));
                }
            }
        }

        let n32 = n as u32;
        let mut indices = Vec::with_capacity(n_patches * (n - 1) * (n - 1) * 6);
        for p in 0..n_patches as u32 {
            let idx = n32 * n32 * p;
            for r in 0..n32 - 1 {
                for c in 0..n32 - 1 {
                    let row1 = idx + r * n32 + c;
                    let row2 = row1 + n32;
                    indices.extend_from_slice(&[row1, row2, row2 + 1, row1, row2 + 1, row1 + 1]);
                }
            }
        }

        Mesh { vertices, indices }
    }
}

/// The texture coordinates freeglut 3.4 gives `glutSolidTeapot`, one per vertex of
/// [`Mesh::teapot`]`(size, grid)` in the same order (`grid` clamped the same way).
///
/// freeglut builds the table for the first patch — vertex `u*grid + v` (u = first Bezier
/// parameter, the row) gets (s, t) = (u/(grid-1), v/(grid-1)) in float — and copies it to all
/// 32 patches, including the 8 mirrored handle/spout patches whose rows it reverses (so their
/// texture is mirrored). Only the solid teapot has them; sphere, torus and cube have none.
pub fn teapot_texcoords(grid: u32) -> Vec<[f32; 2]> {
    let n = grid.clamp(2, 1024);
    let last = (n - 1) as f32;
    let patch: Vec<[f32; 2]> = (0..n)
        .flat_map(|u| (0..n).map(move |v| [u as f32 / last, v as f32 / last]))
        .collect();
    let patches = 6 * 4 + 4 * 2;
    let mut out = Vec::with_capacity(patch.len() * patches);
    for _ in 0..patches {
        out.extend_from_slice(&patch);
    }
    out
}

/// Upper clamp for slices/stacks/sides/rings, so index arithmetic stays in u32.
const MAX_COUNT: u32 = 1 << 14;

/// Appends the triangles of one GL_TRIANGLE_STRIP (GL's alternating
/// orientation), skipping triangles with a repeated index (zero area).
fn push_strip(out: &mut Vec<u32>, strip: &[u32]) {
    for k in 0..strip.len().saturating_sub(2) {
        let (a, b, c) = if k % 2 == 0 {
            (strip[k], strip[k + 1], strip[k + 2])
        } else {
            (strip[k + 1], strip[k], strip[k + 2])
        };
        if a != b && b != c && a != c {
            out.extend_from_slice(&[a, b, c]);
        }
    }
}

/// freeglut's `fghCircleTable`: `|n|+1` samples of sin/cos around a circle
/// (half circle if `half`), negative `n` running the other way. The angle
/// step and `angle*i` are float; `sin`/`cos` are evaluated in double and
/// cast to float. The last entry repeats the first (or is exactly
/// `(0,-1)` for a half circle).
fn circle_table(n: i64, half: bool) -> (Vec<f32>, Vec<f32>) {
    let size = n.unsigned_abs() as usize;
    let denom = if n == 0 { 1.0f32 } else { n as f32 };
    let angle: f32 = (if half { 1.0f32 } else { 2.0f32 }) * std::f32::consts::PI / denom;
    let mut sint = vec![0.0f32; size + 1];
    let mut cost = vec![0.0f32; size + 1];
    cost[0] = 1.0;
    for i in 1..size {
        let a = f64::from(angle * i as f32);
        sint[i] = a.sin() as f32;
        cost[i] = a.cos() as f32;
    }
    if half {
        sint[size] = 0.0;
        cost[size] = -1.0;
    } else {
        sint[size] = sint[0];
        cost[size] = cost[0];
    }
    (sint, cost)
}

// ---------------------------------------------------------------- cube data
// fg_geometry.c: cube_v, cube_n, cube_vi (unit cube; scaled by size).

const CUBE_CORNERS: [[f32; 3]; 8] = [
    [0.5, 0.5, 0.5],
    [-0.5, 0.5, 0.5],
    [-0.5, -0.5, 0.5],
    [0.5, -0.5, 0.5],
    [0.5, -0.5, -0.5],
    [0.5, 0.5, -0.5],
    [-0.5, 0.5, -0.5],
    [-0.5, -0.5, -0.5],
];

const CUBE_NORMALS: [[f32; 3]; 6] = [
    [0.0, 0.0, 1.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [-1.0, 0.0, 0.0],
    [0.0, -1.0, 0.0],
    [0.0, 0.0, -1.0],
];

const CUBE_FACES: [[usize; 4]; 6] = [
    [0, 1, 2, 3],
    [0, 3, 4, 5],
    [0, 5, 6, 1],
    [1, 6, 7, 2],
    [7, 4, 3, 2],
    [4, 7, 6, 5],
];

// -------------------------------------------------------------- teapot code

/// Cubic Bernstein polynomial `i` and its derivative at `x`, in f32 with
/// freeglut's operation order (`bernstein3`).
fn bernstein3(i: usize, x: f32) -> (f32, f32) {
    let invx = 1.0f32 - x;
    match i {
        0 => {
            let temp = invx * invx;
            (invx * temp, -3.0 * temp)
        }
        1 => {
            let temp = invx * invx;
            (3.0 * x * temp, 3.0 * temp - 6.0 * x * invx)
        }
        2 => {
            let temp = x * x;
            (3.0 * temp * invx, 6.0 * x * invx - 3.0 * temp)
        }
        3 => {
            let temp = x * x;
            (x * temp, 3.0 * temp)
        }
        _ => (0.0, 0.0),
    }
}

type Bern = Vec<[f32; 4]>;

/// freeglut's `pregenBernstein`: sample `s` at `x = s/(n-1)` (float).
fn pregen_bernstein(n: usize) -> (Bern, Bern) {
    let mut b0 = vec![[0.0f32; 4]; n];
    let mut b1 = vec![[0.0f32; 4]; n];
    let denom = n as f32 - 1.0;
    for s in 0..n {
        let x = s as f32 / denom;
        for i in 0..4 {
            let (r0, r1) = bernstein3(i, x);
            b0[s][i] = r0;
            b1[s][i] = r1;
        }
    }
    (b0, b1)
}

/// The 4x4 control points of input patch `p`, transformed as fghTeaset does:
/// `(x*s/2, (z-1.575)*s/2, -y*s/2)`, all in f32.
fn teapot_control_points(p: usize, scale: f32) -> [[[f32; 3]; 4]; 4] {
    const Z_OFFSET: f32 = 1.575;
    let mut cp = [[[0.0f32; 3]; 4]; 4];
    for (i, &k) in TEAPOT_PATCHES[p].iter().enumerate() {
        let d = TEAPOT_CP[k];
        cp[i / 4][i % 4] = [d[0] * scale / 2.0, (d[2] - Z_OFFSET) * scale / 2.0, -d[1] * scale / 2.0];
    }
    cp
}

/// freeglut's `evalBezierWithNorm` for one patch (before rotation/mirroring
/// and before the normal fix): `n*n` positions and normals, row-major in u.
fn eval_bezier_with_norm(
    cp: &[[[f32; 3]; 4]; 4],
    n: usize,
    bern_0: &[[f32; 4]],
    bern_1: &[[f32; 4]],
) -> (Vec<[f32; 3]>, Vec<[f32; 3]>) {
    let mut verts = Vec::with_capacity(n * n);
    let mut norms = Vec::with_capacity(n * n);
    for u in 0..n {
        for v in 0..n {
            let mut vert = [0.0f32; 3];
            let mut tan1 = [0.0f32; 3];
            let mut tan2 = [0.0f32; 3];
            for i in 0..4 {
                let mut vert_0 = [0.0f32; 3];
                let mut vert_1 = [0.0f32; 3];
                for j in 0..4 {
                    for k in 0..3 {
                        vert_0[k] += bern_0[v][j] * cp[i][j][k];
                        vert_1[k] += bern_1[v][j] * cp[i][j][k];
                    }
                }
                for k in 0..3 {
                    vert[k] += bern_0[u][i] * vert_0[k];
                    tan1[k] += bern_0[u][i] * vert_1[k];
                    tan2[k] += bern_1[u][i] * vert_0[k];
                }
            }
            let mut nrm = [
                tan1[1] * tan2[2] - tan1[2] * tan2[1],
                tan1[2] * tan2[0] - tan1[0] * tan2[2],
                tan1[0] * tan2[1] - tan1[1] * tan2[0],
            ];
            // (GLfloat)sqrt(float sum): double sqrt, cast back to float.
            let sum = nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2];
            let len = f64::from(sum).sqrt() as f32;
            for c in nrm.iter_mut() {
                *c /= len;
            }
            verts.push(vert);
            norms.push(nrm);
        }
    }
    (verts, norms)
}

// -------------------------------------------------------------- teapot data
// Transcribed from freeglut 3.4.0 src/fg_teapot_data.h (patchdata_teapot,
// cpdata_teapot). Data is z-up; y <= 0 quadrant (rotated/mirrored at runtime).

/// Rim, body (2), lid (2), bottom: rotated into all four quadrants;
/// handle (2), spout (2): mirrored across the x-z plane of the data.
const TEAPOT_PATCHES: [[usize; 16]; 10] = [
    [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15], // rim
    [12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26, 27], // body
    [24, 25, 26, 27, 28, 29, 30, 31, 32, 33, 34, 35, 36, 37, 38, 39],
    [40, 41, 42, 40, 43, 44, 45, 46, 47, 47, 47, 47, 48, 49, 50, 51], // lid
    [48, 49, 50, 51, 52, 53, 54, 55, 56, 57, 58, 59, 60, 61, 62, 63],
    [64, 64, 64, 64, 65, 66, 67, 68, 69, 70, 71, 72, 39, 38, 37, 36], // bottom
    [73, 74, 75, 76, 77, 78, 79, 80, 81, 82, 83, 84, 85, 86, 87, 88], // handle
    [85, 86, 87, 88, 89, 90, 91, 92, 93, 94, 95, 96, 97, 98, 99, 100],
    [
        101, 102, 103, 104, 105, 106, 107, 108, 109, 110, 111, 112, 113, 114, 115, 116,
    ], // spout
    [
        113, 114, 115, 116, 117, 118, 119, 120, 121, 122, 123, 124, 125, 126, 127, 128,
    ],
];

const TEAPOT_CP: [[f32; 3]; 129] = [
    [1.40000, 0.00000, 2.40000],
    [1.40000, -0.78400, 2.40000],
    [0.78400, -1.40000, 2.40000],
    [0.00000, -1.40000, 2.40000],
    [1.33750, 0.00000, 2.53125],
    [1.33750, -0.74900, 2.53125],
    [0.74900, -1.33750, 2.53125],
    [0.00000, -1.33750, 2.53125],
    [1.43750, 0.00000, 2.53125],
    [1.43750, -0.80500, 2.53125],
    [0.80500, -1.43750, 2.53125],
    [0.00000, -1.43750, 2.53125],
    [1.50000, 0.00000, 2.40000],
    [1.50000, -0.84000, 2.40000],
    [0.84000, -1.50000, 2.40000],
    [0.00000, -1.50000, 2.40000],
    [1.75000, 0.00000, 1.87500],
    [1.75000, -0.98000, 1.87500],
    [0.98000, -1.75000, 1.87500],
    [0.00000, -1.75000, 1.87500],
    [2.00000, 0.00000, 1.35000],
    [2.00000, -1.12000, 1.35000],
    [1.12000, -2.00000, 1.35000],
    [0.00000, -2.00000, 1.35000],
    [2.00000, 0.00000, 0.90000],
    [2.00000, -1.12000, 0.90000],
    [1.12000, -2.00000, 0.90000],
    [0.00000, -2.00000, 0.90000],
    [2.00000, 0.00000, 0.45000],
    [2.00000, -1.12000, 0.45000],
    [1.12000, -2.00000, 0.45000],
    [0.00000, -2.00000, 0.45000],
    [1.50000, 0.00000, 0.22500],
    [1.50000, -0.84000, 0.22500],
    [0.84000, -1.50000, 0.22500],
    [0.00000, -1.50000, 0.22500],
    [1.50000, 0.00000, 0.15000],
    [1.50000, -0.84000, 0.15000],
    [0.84000, -1.50000, 0.15000],
    [0.00000, -1.50000, 0.15000],
    [0.00000, 0.00000, 3.15000],
    [0.00000, -0.00200, 3.15000],
    [0.00200, 0.00000, 3.15000],
    [0.80000, 0.00000, 3.15000],
    [0.80000, -0.45000, 3.15000],
    [0.45000, -0.80000, 3.15000],
    [0.00000, -0.80000, 3.15000],
    [0.00000, 0.00000, 2.85000],
    [0.20000, 0.00000, 2.70000],
    [0.20000, -0.11200, 2.70000],
    [0.11200, -0.20000, 2.70000],
    [0.00000, -0.20000, 2.70000],
    [0.40000, 0.00000, 2.55000],
    [0.40000, -0.22400, 2.55000],
    [0.22400, -0.40000, 2.55000],
    [0.00000, -0.40000, 2.55000],
    [1.30000, 0.00000, 2.55000],
    [1.30000, -0.72800, 2.55000],
    [0.72800, -1.30000, 2.55000],
    [0.00000, -1.30000, 2.55000],
    [1.30000, 0.00000, 2.40000],
    [1.30000, -0.72800, 2.40000],
    [0.72800, -1.30000, 2.40000],
    [0.00000, -1.30000, 2.40000],
    [0.00000, 0.00000, 0.00000],
    [0.00000, -1.42500, 0.00000],
    [0.79800, -1.42500, 0.00000],
    [1.42500, -0.79800, 0.00000],
    [1.42500, 0.00000, 0.00000],
    [0.00000, -1.50000, 0.07500],
    [0.84000, -1.50000, 0.07500],
    [1.50000, -0.84000, 0.07500],
    [1.50000, 0.00000, 0.07500],
    [-1.60000, 0.00000, 2.02500],
    [-1.60000, -0.30000, 2.02500],
    [-1.50000, -0.30000, 2.25000],
    [-1.50000, 0.00000, 2.25000],
    [-2.30000, 0.00000, 2.02500],
    [-2.30000, -0.30000, 2.02500],
    [-2.50000, -0.30000, 2.25000],
    [-2.50000, 0.00000, 2.25000],
    [-2.70000, 0.00000, 2.02500],
    [-2.70000, -0.30000, 2.02500],
    [-3.00000, -0.30000, 2.25000],
    [-3.00000, 0.00000, 2.25000],
    [-2.70000, 0.00000, 1.80000],
    [-2.70000, -0.30000, 1.80000],
    [-3.00000, -0.30000, 1.80000],
    [-3.00000, 0.00000, 1.80000],
    [-2.70000, 0.00000, 1.57500],
    [-2.70000, -0.30000, 1.57500],
    [-3.00000, -0.30000, 1.35000],
    [-3.00000, 0.00000, 1.35000],
    [-2.50000, 0.00000, 1.12500],
    [-2.50000, -0.30000, 1.12500],
    [-2.65000, -0.30000, 0.93750],
    [-2.65000, 0.00000, 0.93750],
    [-2.00000, 0.00000, 0.90000],
    [-2.00000, -0.30000, 0.90000],
    [-1.90000, -0.30000, 0.60000],
    [-1.90000, 0.00000, 0.60000],
    [1.70000, 0.00000, 1.42500],
    [1.70000, -0.66000, 1.42500],
    [1.70000, -0.66000, 0.60000],
    [1.70000, 0.00000, 0.60000],
    [2.60000, 0.00000, 1.42500],
    [2.60000, -0.66000, 1.42500],
    [3.10000, -0.66000, 0.82500],
    [3.10000, 0.00000, 0.82500],
    [2.30000, 0.00000, 2.10000],
    [2.30000, -0.25000, 2.10000],
    [2.40000, -0.25000, 2.02500],
    [2.40000, 0.00000, 2.02500],
    [2.70000, 0.00000, 2.40000],
    [2.70000, -0.25000, 2.40000],
    [3.30000, -0.25000, 2.40000],
    [3.30000, 0.00000, 2.40000],
    [2.80000, 0.00000, 2.47500],
    [2.80000, -0.25000, 2.47500],
    [3.52500, -0.25000, 2.49375],
    [3.52500, 0.00000, 2.49375],
    [2.90000, 0.00000, 2.47500],
    [2.90000, -0.15000, 2.47500],
    [3.45000, -0.15000, 2.51250],
    [3.45000, 0.00000, 2.51250],
    [2.80000, 0.00000, 2.40000],
    [2.80000, -0.15000, 2.40000],
    [3.20000, -0.15000, 2.40000],
    [3.20000, 0.00000, 2.40000],
];

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    pub(crate) fn sub(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }
    pub(crate) fn cross(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }
    pub(crate) fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }
    pub(crate) fn len(a: [f32; 3]) -> f32 {
        dot(a, a).sqrt()
    }

    pub(crate) fn check_indices(m: &Mesh) {
        assert_eq!(m.indices.len() % 3, 0);
        assert!(m.indices.iter().all(|&i| (i as usize) < m.vertices.len()));
    }

    pub(crate) fn check_unit_normals(m: &Mesh, tol: f32) {
        for (i, v) in m.vertices.iter().enumerate() {
            let l = len(v.normal);
            assert!((l - 1.0).abs() < tol, "vertex {i}: |n| = {l} ({v:?})");
        }
    }

    /// dot(face normal, sum of the corner normals) > 0 for every triangle.
    pub(crate) fn check_outward(m: &Mesh) {
        for (t, tri) in m.indices.chunks_exact(3).enumerate() {
            let [a, b, c] = [0, 1, 2].map(|k| m.vertices[tri[k] as usize]);
            let face = cross(sub(b.position, a.position), sub(c.position, a.position));
            let ns = [0, 1, 2].map(|k| a.normal[k] + b.normal[k] + c.normal[k]);
            assert!(dot(face, ns) > 0.0, "triangle {t} {tri:?} faces inward");
        }
    }

    // ------------------------------------------------------------- counts

    #[test]
    fn cube_counts_and_order() {
        // CUBE_VERT_PER_OBJ = 6 faces * 4 = 24 vertices;
        // CUBE_VERT_PER_OBJ_TRI = 24 + 6*2 = 36 indices = 12 triangles.
        let m = Mesh::cube(1.5);
        assert_eq!(m.vertices.len(), 24);
        assert_eq!(m.triangle_count(), 12);
        check_indices(&m);
        assert_eq!(&m.indices[..12], &[0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7]);
        // first face is +z: cube_v[0..4]
        assert_eq!(m.vertices[0].position, [0.75, 0.75, 0.75]);
        assert_eq!(m.vertices[1].position, [-0.75, 0.75, 0.75]);
        assert_eq!(m.vertices[2].position, [-0.75, -0.75, 0.75]);
        assert_eq!(m.vertices[0].normal, [0.0, 0.0, 1.0]);
        // second face is +x with corners 0,3,4,5
        assert_eq!(m.vertices[5].position, [0.75, -0.75, 0.75]);
        assert_eq!(m.vertices[4].normal, [1.0, 0.0, 0.0]);
    }

    #[test]
    fn sphere_counts_default() {
        // fghGenerateSphere: nVert = slices*(stacks-1) + 2 = 24*23 + 2 = 554.
        // fghSphere draws `stacks` strips of (slices+1)*2 indices, i.e.
        // 2*slices strip triangles each: 2*24*24 = 1152. In the two pole
        // strips every other triangle repeats the pole index (zero area),
        // so slices triangles per pole strip are dropped:
        // 1152 - 2*24 = 1104 = 2*slices*(stacks-1).
        let m = Mesh::sphere(1.0, 24, 24);
        assert_eq!(m.vertices.len(), 554);
        assert_eq!(m.triangle_count(), 1104);
        check_indices(&m);
        // top strip [1,0,2,0,3,0,...]: (1,0,2), (2,0,0) dropped, (2,0,3), ...
        assert_eq!(&m.indices[..6], &[1, 0, 2, 2, 0, 3]);
        // last top-strip triangle closes the ring: (24,0,1)
        assert_eq!(&m.indices[3 * 23..3 * 24], &[24, 0, 1]);
        // first middle strip [25,1,26,2,...]: (25,1,26), (26,1,2)
        assert_eq!(&m.indices[3 * 24..3 * 26], &[25, 1, 26, 26, 1, 2]);
        // bottom strip [553,529,553,530,...]: (553,529,553) dropped,
        // (553,529,530) kept
        let n = m.indices.len();
        assert_eq!(&m.indices[n - 3 * 24..n - 3 * 23], &[553, 529, 530]);
        assert_eq!(&m.indices[n - 3..], &[553, 552, 529]);
    }

    #[test]
    fn torus_counts_default() {
        // fghGenerateTorus: nVert = nSides*nRings = 24*24 = 576.
        // fghTorus draws nSides strips of (nRings+1)*2 indices:
        // 2*nRings triangles each, none degenerate: 2*24*24 = 1152.
        let m = Mesh::torus(0.5, 1.0, 24, 24);
        assert_eq!(m.vertices.len(), 576);
        assert_eq!(m.triangle_count(), 1152);
        check_indices(&m);
        // side 0 strip [0,1,24,25,48,49,...]
        assert_eq!(&m.indices[..9], &[0, 1, 24, 24, 1, 25, 24, 25, 48]);
        // the last side (23) wraps to side 0 (ioff = -i)
        let last = 23 * 48 * 3;
        assert_eq!(&m.indices[last..last + 6], &[23, 0, 47, 47, 0, 24]);
    }

    #[test]
    fn teapot_counts_default() {
        // GLUT_TEAPOT_N_PATCHES = 6*4 + 4*2 = 32 patches;
        // GLUT_SOLID_TEAPOT_N_VERT = 8*8*32 = 2048;
        // GLUT_SOLID_TEAPOT_N_TRI = 7*7*32*2 = 3136.
        assert_eq!(Mesh::TEAPOT_DEFAULT_GRID, 8);
        let m = Mesh::teapot(1.0, Mesh::TEAPOT_DEFAULT_GRID);
        assert_eq!(m.vertices.len(), 2048);
        assert_eq!(m.triangle_count(), 3136);
        check_indices(&m);
        // ABC ACD with B, C one row lower
        assert_eq!(&m.indices[..6], &[0, 8, 9, 0, 9, 1]);
        let m10 = Mesh::teapot(1.0, 10);
        assert_eq!(m10.vertices.len(), 10 * 10 * 32);
        assert_eq!(m10.triangle_count(), 9 * 9 * 32 * 2);
    }

    // ------------------------------------------------------------ normals

    #[test]
    fn normals_unit_length() {
        check_unit_normals(&Mesh::cube(1.5), 0.0 + f32::EPSILON);
        check_unit_normals(&Mesh::sphere(1.0, 24, 24), 1e-6);
        check_unit_normals(&Mesh::sphere(2.5, 7, 5), 1e-6);
        check_unit_normals(&Mesh::torus(0.5, 1.0, 24, 24), 1e-6);
        check_unit_normals(&Mesh::torus(0.2, 3.0, 5, 9), 1e-6);
        // The teapot's normals are all finite and unit: the bottom patch's
        // NaN first row is overwritten by freeglut's normal fix.
        for grid in [2, 3, 8, 10, 17] {
            check_unit_normals(&Mesh::teapot(1.0, grid), 1e-5);
        }
    }

    // ------------------------------------------------------------- sphere

    #[test]
    fn sphere_positions_on_radius() {
        let m = Mesh::sphere(1.0, 24, 24);
        for v in &m.vertices {
            assert!((len(v.position) - 1.0).abs() < 1e-6);
            // radius 1: position = normal * 1, bit for bit
            assert_eq!(v.position, v.normal);
        }
        assert_eq!(m.vertices[0].position, [0.0, 0.0, 1.0]);
        assert_eq!(m.vertices[553].position, [0.0, 0.0, -1.0]);
        let m = Mesh::sphere(2.0, 5, 3);
        for v in &m.vertices {
            assert!((len(v.position) - 2.0).abs() < 2e-6);
        }
    }

    #[test]
    fn sphere_uses_float_circle_table() {
        // freeglut: angle = 2*(float)M_PI/(float)-24 in float, angle*6 in
        // float (= -1.5707964f), cos of that in double, cast to float:
        // -4.3711388e-8, not 0. Stack 1: sin((float)M_PI/24) = 0.1305262f.
        // Vertex 1 + 6 (stack 1, slice 6) has normal x = their float product.
        let m = Mesh::sphere(1.0, 24, 24);
        let expected = -4.371_139e-8_f32 * 0.130_526_2_f32;
        assert_eq!(m.vertices[7].normal[0], expected);
        assert_eq!(m.vertices[7].normal[1], -0.130_526_2_f32);
        // slices run clockwise seen from +z (negative angles)
        assert!(m.vertices[2].position[1] < 0.0);
    }

    // -------------------------------------------------------------- torus

    #[test]
    fn torus_positions_around_tube() {
        for (r, big_r, sides, rings) in [(0.5f32, 1.0f32, 24, 24), (0.25, 2.0, 7, 11)] {
            let m = Mesh::torus(r, big_r, sides, rings);
            for v in &m.vertices {
                let p = v.position;
                let rho = (p[0] * p[0] + p[1] * p[1]).sqrt();
                // closest point on the tube centre circle
                let c = [p[0] / rho * big_r, p[1] / rho * big_r, 0.0];
                let d = sub(p, c);
                assert!((len(d) - r).abs() < 1e-5, "{p:?}");
                // normal points from the centre circle to the vertex
                let nd = [d[0] / r, d[1] / r, d[2] / r];
                assert!(len(sub(nd, v.normal)) < 1e-5);
            }
            // vertex 0: ring 0, side 0: (R + r, 0, 0)
            assert_eq!(m.vertices[0].position, [big_r + r, 0.0, 0.0]);
        }
    }

    // --------------------------------------------------------------- cube

    #[test]
    fn cube_bounds_and_axis_normals() {
        let m = Mesh::cube(1.5);
        assert_eq!(m.bounds(), ([-0.75; 3], [0.75; 3]));
        for v in &m.vertices {
            let n = v.normal;
            assert_eq!(n.iter().filter(|c| c.abs() == 1.0).count(), 1);
            assert_eq!(n.iter().filter(|c| **c == 0.0).count(), 2);
            // the vertex lies on the face its normal names
            assert_eq!(dot(n, v.position), 0.75);
        }
    }

    // ------------------------------------------------------------- teapot

    #[test]
    fn teapot_texcoords_follow_the_patches() {
        for grid in [Mesh::TEAPOT_DEFAULT_GRID, 10, 1] {
            let m = Mesh::teapot(1.0, grid);
            let tc = teapot_texcoords(grid);
            assert_eq!(tc.len(), m.vertices.len(), "grid {grid}");
            assert!(tc
                .iter()
                .all(|c| (0.0..=1.0).contains(&c[0]) && (0.0..=1.0).contains(&c[1])));
        }
        let tc = teapot_texcoords(8);
        // First patch corners: (u, v) = (0,0), (0,7), (7,0), (7,7) at u*8 + v.
        assert_eq!(
            [tc[0], tc[7], tc[56], tc[63]],
            [[0.0, 0.0], [0.0, 1.0], [1.0, 0.0], [1.0, 1.0]]
        );
        assert_eq!(tc[8 + 3], [1.0 / 7.0, 3.0 / 7.0]);
        // Every patch, the mirrored ones (the last 8) included, repeats the first table.
        for p in 1..32 {
            assert_eq!(&tc[p * 64..(p + 1) * 64], &tc[..64], "patch {p}");
        }
    }

    #[test]
    fn teapot_bounds() {
        // Data x in [-3.0 (handle corner cp), ...], z in [0 (bottom), 3.15
        // (lid top)], |y| <= 2.0 (body, reached at patch corners).
        // freeglut: X = x*s/2, Y = (z-1.575)*s/2, Z = -y*s/2 with s = 1:
        //   X min = -1.5 (handle corner), Y = +-0.7875, Z = +-1.0.
        // X max is on the spout lip edge (cps x = 3.3, 3.525, 3.45, 3.2): at
        // grid 8 the largest sample is t = 3/7:
        //   (3.3*64 + 3.525*144 + 3.45*108 + 3.2*27) / 343 / 2 = 1.7169096
        let m = Mesh::teapot(1.0, 8);
        let (lo, hi) = m.bounds();
        let want_lo = [-1.5, -0.7875, -1.0];
        let want_hi = [1.716_909_6, 0.7875, 1.0];
        for k in 0..3 {
            assert!((lo[k] - want_lo[k]).abs() < 1e-5, "min {lo:?}");
            assert!((hi[k] - want_hi[k]).abs() < 1e-5, "max {hi:?}");
        }
        // scale is linear
        let (lo2, hi2) = Mesh::teapot(2.0, 8).bounds();
        for k in 0..3 {
            assert!((lo2[k] - 2.0 * lo[k]).abs() < 1e-5);
            assert!((hi2[k] - 2.0 * hi[k]).abs() < 1e-5);
        }
    }

    #[test]
    fn teapot_mirror_symmetric_about_z0() {
        // The data is symmetric about its y = 0 plane, which becomes Z = 0.
        let m = Mesh::teapot(1.0, 8);
        for v in &m.vertices {
            let p = v.position;
            let n = v.normal;
            let mp = [p[0], p[1], -p[2]];
            let mn = [n[0], n[1], -n[2]];
            let found = m
                .vertices
                .iter()
                .any(|w| len(sub(w.position, mp)) < 1e-5 && len(sub(w.normal, mn)) < 1e-4);
            assert!(found, "no mirror image of {v:?}");
        }
    }

    #[test]
    fn teapot_normal_fix_rows() {
        let g = 8;
        let m = Mesh::teapot(1.0, g);
        let per = (g * g) as usize;
        // input patch 3 (lid) -> output patches 12..16, patch 5 (bottom) -> 20..24
        for copy in 0..4 {
            for c in 0..g as usize {
                assert_eq!(m.vertices[(12 + copy) * per + c].normal, [0.0, 1.0, 0.0]);
                let b = m.vertices[(20 + copy) * per + c];
                assert_eq!(b.normal, [0.0, -1.0, 0.0]);
                assert!((b.position[1] + 0.7875).abs() < 1e-6);
            }
        }
        // the top of the lid is the highest point
        assert!((m.vertices[12 * per].position[1] - 0.7875).abs() < 1e-6);
    }

    #[test]
    fn teapot_winding_is_clockwise_against_normals() {
        // freeglut's normal is dP/dv x dP/du but its triangles run
        // (u,v) -> (u+1,v) -> (u+1,v+1), i.e. along dP/du x dP/dv: seen from
        // the side the (outward) normals point to, every triangle is
        // clockwise. The only exceptions are slivers in the first row of the
        // lid-top and bottom-centre patches (two corners on the collapsed
        // row; |cross| < 1e-4 there).
        let m = Mesh::teapot(1.0, 8);
        let mut clockwise = 0;
        for tri in m.indices.chunks_exact(3) {
            let [a, b, c] = [0, 1, 2].map(|k| m.vertices[tri[k] as usize]);
            let face = cross(sub(b.position, a.position), sub(c.position, a.position));
            if len(face) < 1e-4 {
                continue;
            }
            let ns = [0, 1, 2].map(|k| a.normal[k] + b.normal[k] + c.normal[k]);
            assert!(dot(face, ns) < 0.0, "{tri:?}");
            clockwise += 1;
        }
        assert!(clockwise >= 3136 - 32 * 7, "{clockwise}");
        // normals point outward: on the body's widest ring (data z = 0.9,
        // radius 2) they point away from the Y axis
        // (output patches 4..12 = input patches 1 and 2, the body)
        for v in &m.vertices[4 * 64..12 * 64] {
            let p = v.position;
            if (p[1] - (0.9 - 1.575) / 2.0).abs() < 1e-6 && len([p[0], 0.0, p[2]]) > 0.99 {
                assert!(dot([p[0], 0.0, p[2]], v.normal) > 0.9);
            }
        }
    }

    // ------------------------------------------------------------ winding

    #[test]
    fn outward_winding() {
        check_outward(&Mesh::cube(1.5));
        check_outward(&Mesh::sphere(1.0, 24, 24));
        check_outward(&Mesh::sphere(0.3, 3, 2));
        check_outward(&Mesh::torus(0.5, 1.0, 24, 24));
        check_outward(&Mesh::torus(0.3, 1.0, 3, 3));
    }

    // ------------------------------------------------------------- welded

    #[test]
    fn minimum_counts_clamp() {
        let s = Mesh::sphere(1.0, 0, 0);
        assert_eq!(s.vertices.len(), 3 + 2);
        assert_eq!(s.triangle_count(), 6);
        check_indices(&s);
        let t = Mesh::torus(0.5, 1.0, 0, 1);
        assert_eq!(t.vertices.len(), 9);
        assert_eq!(t.triangle_count(), 18);
        check_indices(&t);
        for g in [0, 1] {
            let p = Mesh::teapot(1.0, g);
            assert_eq!(p.vertices.len(), 4 * 32);
            assert_eq!(p.triangle_count(), 2 * 32);
            check_indices(&p);
        }
        let z = Mesh::teapot(0.0, 8);
        assert!(z.vertices.iter().all(|v| v.normal.iter().all(|c| c.is_finite())));
        assert_eq!(Mesh::default().bounds(), ([0.0; 3], [0.0; 3]));
    }
}
