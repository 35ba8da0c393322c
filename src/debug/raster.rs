//! Which primitive covers a pixel and what its planes give there, as the reference rasteriser
//! (Mesa's llvmpipe, behind lavapipe) computes them: the viewport transform, positions snapped
//! to 1/256 pixel for coverage with the top-left rule at the pixel centre, winding and culling,
//! depth clipping, and attribute planes set up from the unsnapped positions and evaluated per
//! pixel (perspective-correct through the plane of 1/w) for the four pixels of a 2×2 quad, so
//! the neighbours a derivative reads are interpolated — or extrapolated — as on the GPU.
//! Triangles that cross the eye's plane are covered in 2D homogeneous coordinates instead.

/// Sub-pixel bits of fixed-point positions (llvmpipe's `FIXED_ORDER`).
pub const SUBPIXEL_BITS: u32 = 8;

/// The viewport: the target's size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Viewport {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

impl Viewport {
    /// Clip-space position → window position (x right, y down, in pixels), depth and 1/w, in
    /// `f32` as the vertex pipeline's epilogue computes them.
    pub fn to_window(&self, p: [f32; 4]) -> [f32; 4] {
        let oow = 1.0 / p[3];
        let (hw, hh) = (self.width as f32 * 0.5, self.height as f32 * 0.5);
        [
            (p[0] * oow).mul_add(hw, hw),
            (p[1] * oow).mul_add(-hh, hh),
            p[2] * oow,
            oow,
        ]
    }
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

/// A primitive's interpolation at the four pixels of a quad.
#[derive(Clone, Debug, PartialEq)]
pub enum Setup {
    /// Plane equations over the window (llvmpipe's): the three vertices' window x, y in the
    /// rasteriser's order, that order (indices into the primitive's vertices), and each
    /// vertex's 1/w; the quad's pixel indices.
    Planes {
        /// Window x and y of the vertices, in setup order.
        xy: [[f32; 2]; 3],
        /// The primitive's vertex of each setup vertex.
        order: [usize; 3],
        /// 1/w of each setup vertex.
        oow: [f32; 3],
        /// Window z of each setup vertex.
        z: [f32; 3],
    },
    /// Weights computed per pixel: screen-space and perspective-correct, per quad pixel, for
    /// the primitive's vertices (triangles crossing the eye's plane).
    Weights {
        /// Screen-space weights.
        linear: [[f64; 3]; 4],
        /// Perspective-correct weights.
        perspective: [[f64; 3]; 4],
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

impl Cover {
    /// The cover of a triangle whose depth at the pixel passes depth clipping (the near and
    /// far planes), with the quad's depths clamped to 0..1 (which then changes nothing at the
    /// pixel itself); `None` when clipped.
    fn depth_clipped(
        pixels: [(u32, u32); 4],
        lane: usize,
        front: bool,
        depth: [f32; 4],
        inv_w: [f32; 4],
        setup: Setup,
    ) -> Option<Cover> {
        (0.0..=1.0).contains(&depth[lane]).then(|| Cover {
            pixels,
            lane,
            front,
            depth: depth.map(|d| d.clamp(0.0, 1.0)),
            inv_w,
            setup,
        })
    }
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
            (Setup::Planes { xy, order, oow, .. }, Interp::Perspective) => {
                let a = [0, 1, 2].map(|k| v[order[k]] * oow[k]);
                let p = plane(xy, a);
                let w = plane(xy, *oow);
                self.pixels.map(|(x, y)| eval(p, x, y) * (1.0f32 / eval(w, x, y)))
            }
            (Setup::Planes { xy, order, .. }, Interp::Linear) => {
                let p = plane(xy, [0, 1, 2].map(|k| v[order[k]]));
                self.pixels.map(|(x, y)| eval(p, x, y))
            }
            (Setup::Weights { linear, perspective }, mode) => {
                let w = if mode == Interp::Linear { linear } else { perspective };
                let f = |k: usize| f64::from(v[k]);
                [0, 1, 2, 3].map(|i| (w[i][0] * f(0) + w[i][1] * f(1) + w[i][2] * f(2)) as f32)
            }
        }
    }
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

/// Whether the triangle `clip` (clip-space positions) covers pixel (x, y), and how it
/// interpolates there if so.
pub fn triangle(
    clip: [[f32; 4]; 3],
    vp: Viewport,
    x: u32,
    y: u32,
    front_face: wgpu::FrontFace,
    cull: Option<wgpu::Face>,
) -> Option<Cover> {
    let needs_homogeneous = clip
        .iter()
        .any(|p| p[3].is_nan() || p[3] <= 0.0 || p.iter().any(|c| !c.is_finite()));
    let window = clip.map(|p| vp.to_window(p));
    let huge = window.iter().any(|w| w[0].abs() > 1e7 || w[1].abs() > 1e7);
    if needs_homogeneous || huge {
        return homogeneous(clip, vp, x, y, front_face, cull);
    }
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
    let depth = pixels.map(|(x, y)| eval(zp, x, y));
    let inv_w = pixels.map(|(x, y)| eval(wp, x, y));
    Cover::depth_clipped(pixels, lane, front, depth, inv_w, Setup::Planes { xy, order, oow, z })
}

/// Coverage of a triangle that crosses the eye's plane (w ≤ 0) or lies far outside the
/// viewport, without clipping it into pieces: in 2D homogeneous coordinates (Olano and
/// Greer), the pixel's weights `k = M⁻¹ (X, Y, 1)` are all non-negative exactly where it lies
/// inside the clipped triangle.
fn homogeneous(
    clip: [[f32; 4]; 3],
    vp: Viewport,
    x: u32,
    y: u32,
    front_face: wgpu::FrontFace,
    cull: Option<wgpu::Face>,
) -> Option<Cover> {
    let m = clip.map(|p| [f64::from(p[0]), f64::from(p[1]), f64::from(p[3])]);
    let det3 = |a: [f64; 3], b: [f64; 3], c: [f64; 3]| {
        a[0] * (b[1] * c[2] - b[2] * c[1]) - b[0] * (a[1] * c[2] - a[2] * c[1]) + c[0] * (a[1] * b[2] - a[2] * b[1])
    };
    let det = det3(m[0], m[1], m[2]);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let front = facing(det > 0.0, front_face, cull)?;
    let (pixels, lane) = quad(x, y);
    let z = clip.map(|p| f64::from(p[2]));
    let w = clip.map(|p| f64::from(p[3]));
    let weights = |px: u32, py: u32| -> [f64; 3] {
        let p = [
            (f64::from(px) + 0.5) / f64::from(vp.width) * 2.0 - 1.0,
            1.0 - (f64::from(py) + 0.5) / f64::from(vp.height) * 2.0,
            1.0,
        ];
        [
            det3(p, m[1], m[2]) / det,
            det3(m[0], p, m[2]) / det,
            det3(m[0], m[1], p) / det,
        ]
    };
    let k = weights(x, y);
    if k.iter().any(|&v| v < 0.0) || k.iter().sum::<f64>() <= 0.0 {
        return None;
    }
    let mut linear = [[0.0; 3]; 4];
    let mut perspective = [[0.0; 3]; 4];
    let mut depth = [0.0f32; 4];
    let mut inv_w = [0.0f32; 4];
    for (i, &(px, py)) in pixels.iter().enumerate() {
        let k = weights(px, py);
        let sum: f64 = k.iter().sum();
        perspective[i] = [k[0] / sum, k[1] / sum, k[2] / sum];
        depth[i] = (k[0] * z[0] + k[1] * z[1] + k[2] * z[2]) as f32;
        inv_w[i] = sum as f32;
        let l = [0, 1, 2].map(|j| perspective[i][j] / w[j]);
        let ls: f64 = l.iter().sum();
        linear[i] = l.map(|v| v / ls);
    }
    Cover::depth_clipped(
        pixels,
        lane,
        front,
        depth,
        inv_w,
        Setup::Weights { linear, perspective },
    )
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
