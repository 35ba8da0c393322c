//! Which primitive covers a pixel and what its planes give there, as the reference rasteriser
//! (Mesa's llvmpipe, behind lavapipe) computes them: the viewport transform, positions snapped
//! to 1/256 pixel for coverage with the top-left rule at the pixel centre, winding and culling,
//! depth clipping, and attribute planes set up from the unsnapped positions and evaluated per
//! pixel (perspective-correct through the plane of 1/w) for the four pixels of a 2×2 quad, so
//! the neighbours a derivative reads are interpolated — or extrapolated — as on the GPU.
//! A triangle that leaves the clip volume is first clipped as llvmpipe's draw module clips it
//! (no guard band: against x, y and z, in `f32`, in the same order), and its pieces covered:
//! with coordinates as large as 1e9 the clipper's rounding decides what is drawn.

/// Sub-pixel bits of fixed-point positions (llvmpipe's `FIXED_ORDER`).
pub const SUBPIXEL_BITS: u32 = 8;

pub use crate::render::{Scissor, Viewport};

impl Viewport {
    /// Clip-space position → window position (x right, y down, in pixels), depth and 1/w, in
    /// `f32` as the vertex pipeline's epilogue computes them (scale, then translate by the
    /// viewport's centre).
    pub fn to_window(self, p: [f32; 4]) -> [f32; 4] {
        let oow = 1.0 / p[3];
        let [sx, sy, sz] = self.scale();
        let [tx, ty, tz] = self.translate();
        [
            (p[0] * oow).mul_add(sx, tx),
            (p[1] * oow).mul_add(sy, ty),
            (p[2] * oow).mul_add(sz, tz),
            oow,
        ]
    }

    /// The viewport transform's scale (y flipped: window rows run down).
    fn scale(self) -> [f32; 3] {
        [self.width * 0.5, -self.height * 0.5, self.max_depth - self.min_depth]
    }

    /// Its translation: the viewport's centre and near depth.
    fn translate(self) -> [f32; 3] {
        [self.x + self.width * 0.5, self.y + self.height * 0.5, self.min_depth]
    }

    /// Where the clipper's vertices land: divided, then scaled and translated unfused, as
    /// llvmpipe's clipper interpolates them.
    fn to_window_unfused(self, p: [f32; 4]) -> [f32; 4] {
        let oow = 1.0f32 / p[3];
        let [sx, sy, sz] = self.scale();
        let [tx, ty, tz] = self.translate();
        [p[0] * oow * sx + tx, p[1] * oow * sy + ty, p[2] * oow * sz + tz, oow]
    }
}

/// Whether pixel (x, y) is inside `scissor`.
pub fn scissored(scissor: Scissor, x: u32, y: u32) -> bool {
    let [sx, sy, w, h] = scissor;
    x >= sx && y >= sy && x - sx < w && y - sy < h
}

/// How attribute values are interpolated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interp {
    /// Perspective-correct (GLSL's default).
    Perspective,
    /// Linear in screen space (`noperspective`).
    Linear,
    /// The provoking (first) vertex's value (`flat`).
    Flat,
}

/// A vertex the clipper makes on an edge: `out + t·(in − out)` of two vertices before it
/// (the primitive's three, then those made earlier), as `draw_pipe_clip.c` interpolates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Made {
    /// The vertex outside the plane (or the one the interpolation starts from).
    pub out: usize,
    /// The other one.
    pub inside: usize,
    /// The weight of `inside` in clip space (for perspective-correct values and position).
    pub t: f32,
    /// The weight in screen space (for `noperspective` values).
    pub t_linear: f32,
}

/// A primitive's interpolation at the four pixels of a quad.
#[derive(Clone, Debug, PartialEq)]
pub enum Setup {
    /// Plane equations over the window (llvmpipe's): the three vertices' window x, y in the
    /// rasteriser's order, that order (indices into the primitive's vertices, then the
    /// vertices the clipper made), and each vertex's 1/w; the quad's pixel indices.
    Planes {
        /// Window x and y of the vertices, in setup order.
        xy: [[f32; 2]; 3],
        /// The vertex of each setup vertex.
        order: [usize; 3],
        /// 1/w of each setup vertex.
        oow: [f32; 3],
        /// Window z of each setup vertex.
        z: [f32; 3],
        /// The vertices the clipper made, in order (empty for a triangle not clipped).
        made: Vec<Made>,
    },
    /// A point: every value is the vertex's.
    Point,
}

/// A primitive covering the pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct Cover {
    /// The quad's pixels (0: top left, 1: top right, 2: bottom left, 3: bottom right).
    pub pixels: [(u32, u32); 4],
    /// The lane of the pixel itself.
    pub lane: usize,
    /// Whether the primitive faces the viewer.
    pub front: bool,
    /// Depth at each pixel of the quad (clamped to 0..1), as stored.
    pub depth: [f32; 4],
    /// 1/w at each pixel (`gl_FragCoord.w`).
    pub inv_w: [f32; 4],
    /// How the primitive's values reach the quad.
    pub setup: Setup,
}

/// One attribute's plane: its value at the framebuffer origin's pixel centre and its slopes.
fn plane(xy: &[[f32; 2]; 3], a: [f32; 3]) -> (f32, f32, f32) {
    let [[x0, y0], [x1, y1], [x2, y2]] = *xy;
    let (dx01, dy01, dx20, dy20) = (x0 - x1, y0 - y1, x2 - x0, y2 - y0);
    let ooa = 1.0f32 / (dx01 * dy20 - dy01 * dx20);
    let (dx20o, dy20o, dx01o, dy01o) = (dx20 * ooa, dy20 * ooa, dx01 * ooa, dy01 * ooa);
    let (da01, da20) = (a[0] - a[1], a[2] - a[0]);
    let dadx = da01 * dy20o - da20 * dy01o;
    let dady = da20 * dx01o - da01 * dx20o;
    let a0 = a[0] - (dadx * (x0 - 0.5) + dady * (y0 - 0.5));
    (a0, dadx, dady)
}

fn eval((a0, dadx, dady): (f32, f32, f32), x: u32, y: u32) -> f32 {
    dady.mul_add(y as f32, dadx.mul_add(x as f32, a0))
}

impl Cover {
    /// An attribute whose value at the primitive's vertices is `v`, at the quad's pixels.
    pub fn interpolate(&self, v: [f32; 3], mode: Interp) -> [f32; 4] {
        match (&self.setup, mode) {
            (Setup::Point, _) | (_, Interp::Flat) => [v[0]; 4],
            (
                Setup::Planes {
                    xy, order, oow, made, ..
                },
                Interp::Perspective,
            ) => {
                let all = clipped_values(v, made, false);
                let a = [0, 1, 2].map(|k| all[order[k]] * oow[k]);
                let p = plane(xy, a);
                let w = plane(xy, *oow);
                self.pixels.map(|(x, y)| eval(p, x, y) * (1.0f32 / eval(w, x, y)))
            }
            (Setup::Planes { xy, order, made, .. }, Interp::Linear) => {
                let all = clipped_values(v, made, true);
                let p = plane(xy, [0, 1, 2].map(|k| all[order[k]]));
                self.pixels.map(|(x, y)| eval(p, x, y))
            }
        }
    }
}

/// A value at the primitive's vertices `v`, then at the vertices the clipper made.
fn clipped_values(v: [f32; 3], made: &[Made], linear: bool) -> Vec<f32> {
    let mut all = v.to_vec();
    for m in made {
        let t = if linear { m.t_linear } else { m.t };
        let (out, inside) = (all[m.out], all[m.inside]);
        all.push(out + t * (inside - out));
    }
    all
}

fn quad(x: u32, y: u32) -> ([(u32, u32); 4], usize) {
    let (qx, qy) = (x & !1, y & !1);
    let lane = (x & 1) as usize + 2 * (y & 1) as usize;
    ([(qx, qy), (qx + 1, qy), (qx, qy + 1), (qx + 1, qy + 1)], lane)
}

/// Whether a triangle of winding `ccw` (Vulkan's positive area) is drawn under `cull`, and
/// whether it is front-facing.
fn facing(ccw: bool, front_face: wgpu::FrontFace, cull: Option<wgpu::Face>) -> Option<bool> {
    let front = ccw == (front_face == wgpu::FrontFace::Ccw);
    match cull {
        Some(wgpu::Face::Back) if !front => None,
        Some(wgpu::Face::Front) if front => None,
        _ => Some(front),
    }
}

/// `cvtps2dq((v − 0.5) · 256)`: a window coordinate snapped to the sub-pixel grid, whose
/// integer points are pixel centres.
fn snap(v: f32) -> i64 {
    ((v - 0.5) * (1u32 << SUBPIXEL_BITS) as f32).round_ties_even() as i64
}

/// The clip planes of Vulkan's volume in llvmpipe's order (`draw->plane[0..6]`, z from 0):
/// a vertex is outside plane `i` where `dot(position, plane) < 0`.
const PLANES: [[f32; 4]; 6] = [
    [-1.0, 0.0, 0.0, 1.0],
    [1.0, 0.0, 0.0, 1.0],
    [0.0, -1.0, 0.0, 1.0],
    [0.0, 1.0, 0.0, 1.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, -1.0, 1.0],
];

/// `a · b` in `f32`, left to right, as the clipper's `dot4`.
fn dot4(a: [f32; 4], b: [f32; 4]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]
}

/// The planes `p` lies outside, one bit each.
fn clipmask(p: [f32; 4]) -> u32 {
    (0..6).filter(|&i| dot4(p, PLANES[i]) < 0.0).fold(0, |m, i| m | 1 << i)
}

/// A triangle after clipping.
struct Clipped {
    /// The polygon's vertices: indices into `pos`.
    poly: Vec<usize>,
    /// Clip positions: the triangle's three, then the vertices made.
    pos: Vec<[f32; 4]>,
    /// How each vertex past the third was made.
    made: Vec<Made>,
}

/// A triangle clipped as llvmpipe's `do_clip_tri` clips it (Sutherland–Hodgman, plane by
/// plane in bit order, each new vertex interpolated from the one outside). `None` where a
/// distance is not finite (the clipper drops the triangle).
fn clip(clip: [[f32; 4]; 3], mask: u32) -> Option<Clipped> {
    let mut pos: Vec<[f32; 4]> = clip.to_vec();
    let mut made = Vec::new();
    let mut poly = vec![0, 1, 2];
    let mut mask = mask;
    while mask != 0 && poly.len() >= 3 {
        let plane = PLANES[mask.trailing_zeros() as usize];
        mask &= mask - 1;
        let n = poly.len();
        let mut out = Vec::with_capacity(n + 1);
        let mut prev = poly[0];
        let mut dp_prev = dot4(pos[prev], plane);
        if !dp_prev.is_finite() {
            return None;
        }
        for i in 1..=n {
            let vert = poly[i % n];
            let dp = dot4(pos[vert], plane);
            if !dp.is_finite() {
                return None;
            }
            let different = if dp_prev >= 0.0 {
                out.push(prev);
                dp < 0.0
            } else {
                // Not below 0 (a distance is finite here).
                dp >= 0.0
            };
            if different {
                let denom = dp - dp_prev;
                // Interpolated from the vertex outside, or from the nearer one.
                let (t, from, to) = if dp < 0.0 {
                    if -dp < dp_prev {
                        (dp / denom, vert, prev)
                    } else {
                        (-dp_prev / denom, prev, vert)
                    }
                } else if -dp_prev < dp {
                    (-dp_prev / denom, prev, vert)
                } else {
                    (dp / denom, vert, prev)
                };
                let (o, inn) = (pos[from], pos[to]);
                let p = [0, 1, 2, 3].map(|k| o[k] + t * (inn[k] - o[k]));
                // The screen-space weight, from x (or y where x does not change).
                let mut t_linear = t;
                for k in 0..2 {
                    if inn[k] != o[k] {
                        let (ic, oc, dc) = (inn[k] / inn[3], o[k] / o[3], p[k] / p[3]);
                        t_linear = (dc - oc) / (ic - oc);
                        break;
                    }
                }
                made.push(Made {
                    out: from,
                    inside: to,
                    t,
                    t_linear,
                });
                pos.push(p);
                out.push(pos.len() - 1);
            }
            prev = vert;
            dp_prev = dp;
        }
        poly = out;
    }
    Some(Clipped { poly, pos, made })
}

/// Whether the triangle `clip` (clip-space positions) covers pixel (x, y), and how it
/// interpolates there if so.
pub fn triangle(
    clip_pos: [[f32; 4]; 3],
    vp: Viewport,
    x: u32,
    y: u32,
    front_face: wgpu::FrontFace,
    cull: Option<wgpu::Face>,
) -> Option<Cover> {
    let masks = clip_pos.map(clipmask);
    if masks[0] & masks[1] & masks[2] != 0 {
        return None;
    }
    let any = masks[0] | masks[1] | masks[2];
    if any == 0 {
        if clip_pos.iter().any(|p| p.iter().any(|c| !c.is_finite())) {
            return None;
        }
        let window = clip_pos.map(|p| vp.to_window(p));
        return setup(&window, [0, 1, 2], Vec::new(), x, y, front_face, cull);
    }
    let Clipped { poly, pos, made } = clip(clip_pos, any)?;
    if poly.len() < 3 {
        return None;
    }
    // Window positions: the primitive's vertices as the vertex pipeline computes them, the
    // clipper's as its `interp` does (divide, then scale and translate, unfused).
    let window: Vec<[f32; 4]> = pos
        .iter()
        .enumerate()
        .map(|(i, &p)| {
            if i < 3 {
                vp.to_window(p)
            } else {
                vp.to_window_unfused(p)
            }
        })
        .collect();
    // The polygon as a fan from its first vertex (the provoking one, first).
    for i in 2..poly.len() {
        let tri = [poly[0], poly[i - 1], poly[i]];
        let corners = tri.map(|k| window[k]);
        if let Some(cover) = setup(&corners, tri, made.clone(), x, y, front_face, cull) {
            return Some(cover);
        }
    }
    None
}

/// Coverage of pixel (x, y) by a triangle of window positions `window` (whose vertices are
/// `ids` of the primitive's and the clipper's), and its planes there; depth is clamped to
/// 0..1 as llvmpipe clamps it after clipping.
fn setup(
    window: &[[f32; 4]; 3],
    ids: [usize; 3],
    made: Vec<Made>,
    x: u32,
    y: u32,
    front_face: wgpu::FrontFace,
    cull: Option<wgpu::Face>,
) -> Option<Cover> {
    let fixed = window.map(|w| [snap(w[0]), snap(w[1])]);
    let [f0, f1, f2] = fixed;
    let area = (f0[0] - f1[0]) * (f2[1] - f0[1]) - (f2[0] - f0[0]) * (f0[1] - f1[1]);
    if area == 0 {
        return None;
    }
    let front = facing(area > 0, front_face, cull)?;
    // A clockwise triangle is set up as (v0, v2, v1), keeping the provoking vertex first.
    let order = if area > 0 { [0, 1, 2] } else { [0, 2, 1] };
    let v = order.map(|k| fixed[k]);
    let (px, py) = (i64::from(x) << SUBPIXEL_BITS, i64::from(y) << SUBPIXEL_BITS);
    for i in 0..3 {
        let (a, b) = (v[i], v[(i + 1) % 3]);
        let dcdx = a[1] - b[1];
        let dcdy = a[0] - b[0];
        let mut c = dcdx * a[0] - dcdy * a[1];
        // The top-left rule: left edges and top edges (horizontal, running toward −x) own
        // the pixel centres on them.
        if dcdx < 0 || (dcdx == 0 && dcdy > 0) {
            c += 1;
        }
        if c + dcdy * py - dcdx * px <= 0 {
            return None;
        }
    }
    let (pixels, lane) = quad(x, y);
    let xy = order.map(|k| [window[k][0], window[k][1]]);
    let z = order.map(|k| window[k][2]);
    let oow = order.map(|k| window[k][3]);
    let zp = plane(&xy, z);
    let wp = plane(&xy, oow);
    let depth = pixels.map(|(x, y)| eval(zp, x, y).clamp(0.0, 1.0));
    let inv_w = pixels.map(|(x, y)| eval(wp, x, y));
    Some(Cover {
        pixels,
        lane,
        front,
        depth,
        inv_w,
        setup: Setup::Planes {
            xy,
            order: order.map(|k| ids[k]),
            oow,
            z,
            made,
        },
    })
}

/// Whether a point at `clip` (size 1) covers pixel (x, y): one pixel square around the
/// point, snapped, left and top edges included. A point is dropped only behind the eye or
/// past the near and far planes (points outside the viewport still light the pixels inside).
pub fn point(clip: [f32; 4], vp: Viewport, x: u32, y: u32) -> Option<Cover> {
    let w = clip[3];
    if w.is_nan() || w <= 0.0 || clip.iter().any(|c| !c.is_finite()) || clip[2] < 0.0 || clip[2] > w {
        return None;
    }
    let [sx, sy, z, oow] = vp.to_window(clip);
    let one = 1i64 << SUBPIXEL_BITS;
    let (x0, y0) = (snap(sx) - one / 2, snap(sy) - one / 2);
    let (px, py) = (i64::from(x) * one, i64::from(y) * one);
    if !(x0 <= px && px < x0 + one && y0 <= py && py < y0 + one) {
        return None;
    }
    let (pixels, lane) = quad(x, y);
    Some(Cover {
        pixels,
        lane,
        front: true,
        depth: [z.clamp(0.0, 1.0); 4],
        inv_w: [oow; 4],
        setup: Setup::Point,
    })
}

/// The primitives of `count` vertices in `topology`: each primitive's positions in the
/// vertex sequence (the first is the provoking vertex). A point list's primitives repeat
/// their one vertex.
pub fn primitives(topology: wgpu::PrimitiveTopology, count: usize) -> Option<Vec<[usize; 3]>> {
    use wgpu::PrimitiveTopology as T;
    Some(match topology {
        T::TriangleList => (0..count / 3).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect(),
        // Vulkan: triangle i of a strip is (i, i + 1 + i%2, i + 2 − i%2).
        T::TriangleStrip => (0..count.saturating_sub(2))
            .map(|i| [i, i + 1 + i % 2, i + 2 - i % 2])
            .collect(),
        T::PointList => (0..count).map(|i| [i, i, i]).collect(),
        _ => return None,
    })
}
