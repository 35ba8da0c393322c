//! Which primitive covers a pixel, as the rasteriser decides: the viewport transform, vertex
//! positions snapped to the rasteriser's sub-pixel grid, edge functions with the top-left rule
//! at the pixel centre, culling by winding, clipping against the near and far planes, and the
//! barycentric weights (screen-space and perspective-correct) of a 2×2 quad of pixels, so that
//! the neighbours a derivative reads are interpolated — or extrapolated — as the GPU does.

/// Sub-pixel bits of the rasteriser's fixed-point positions (llvmpipe's `FIXED_ORDER`).
pub const SUBPIXEL_BITS: u32 = 8;

/// What the rasteriser computes for one pixel of a primitive.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Screen-space (linear) weights of the three vertices.
    pub linear: [f64; 3],
    /// Perspective-correct weights.
    pub perspective: [f64; 3],
    /// Depth (z/w interpolated), as stored.
    pub depth: f32,
    /// 1/w interpolated (`gl_FragCoord.w`).
    pub inv_w: f32,
}

/// A primitive covering the pixel: its samples for the four pixels of the quad (0: top left,
/// 1: top right, 2: bottom left, 3: bottom right) and whether it faces the viewer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cover {
    /// The quad's samples (helpers extrapolated from the primitive's planes).
    pub quad: [Sample; 4],
    /// The lane of the pixel itself.
    pub lane: usize,
    /// Whether the primitive is front-facing.
    pub front: bool,
}

/// The viewport: the target's size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Viewport {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

impl Viewport {
    /// Clip-space position → window position (x right, y down, in pixels) and depth, computed
    /// in `f32` as the rasteriser does.
    pub fn to_window(&self, p: [f32; 4]) -> [f32; 3] {
        let inv_w = 1.0 / p[3];
        let (hw, hh) = (self.width as f32 * 0.5, self.height as f32 * 0.5);
        [p[0] * inv_w * hw + hw, -(p[1] * inv_w) * hh + hh, p[2] * inv_w]
    }
}

fn quad_lanes(x: u32, y: u32) -> ([(f64, f64); 4], usize) {
    let (qx, qy) = (f64::from(x & !1), f64::from(y & !1));
    let lane = (x & 1) as usize + 2 * (y & 1) as usize;
    (
        [
            (qx + 0.5, qy + 0.5),
            (qx + 1.5, qy + 0.5),
            (qx + 0.5, qy + 1.5),
            (qx + 1.5, qy + 1.5),
        ],
        lane,
    )
}

/// Whether a triangle of winding `ccw` (counter-clockwise seen with y up) is drawn under
/// `cull`, and whether it is front-facing.
fn facing(ccw: bool, front_face: wgpu::FrontFace, cull: Option<wgpu::Face>) -> Option<bool> {
    let front = ccw == (front_face == wgpu::FrontFace::Ccw);
    match cull {
        Some(wgpu::Face::Back) if !front => None,
        Some(wgpu::Face::Front) if front => None,
        _ => Some(front),
    }
}

/// Whether the triangle `clip` (clip-space positions) covers pixel (x, y), and its samples if so.
pub fn triangle(
    clip: [[f32; 4]; 3],
    vp: Viewport,
    x: u32,
    y: u32,
    front_face: wgpu::FrontFace,
    cull: Option<wgpu::Face>,
) -> Option<Cover> {
    let needs_clip = clip.iter().any(|p| !(p[3] > 0.0) || p.iter().any(|c| !c.is_finite()));
    let window = clip.map(|p| vp.to_window(p));
    let huge = window.iter().any(|w| w[0].abs() > 1e7 || w[1].abs() > 1e7);
    if needs_clip || huge {
        return homogeneous(clip, vp, x, y, front_face, cull);
    }
    let one = f64::from(1u32 << SUBPIXEL_BITS);
    let fixed = window.map(|w| [(f64::from(w[0]) * one).round() as i64, (f64::from(w[1]) * one).round() as i64]);
    let [a, b, c] = fixed;
    // Twice the signed area with y down: negative for a triangle counter-clockwise with y up.
    let area = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    if area == 0 {
        return None;
    }
    let front = facing(area < 0, front_face, cull)?;
    let sign = area.signum();
    // Edge i is opposite vertex i; its function is positive inside.
    let edge = |i: usize, p: [i64; 2]| -> i64 {
        let (s, e) = (fixed[(i + 1) % 3], fixed[(i + 2) % 3]);
        sign * ((e[0] - s[0]) * (p[1] - s[1]) - (e[1] - s[1]) * (p[0] - s[0]))
    };
    let top_left = |i: usize| -> bool {
        let (s, e) = (fixed[(i + 1) % 3], fixed[(i + 2) % 3]);
        let n = [-(e[1] - s[1]) * sign, (e[0] - s[0]) * sign];
        n[0] > 0 || (n[0] == 0 && n[1] > 0)
    };
    let half = 1i64 << (SUBPIXEL_BITS - 1);
    let centre = [i64::from(x) * one as i64 + half, i64::from(y) * one as i64 + half];
    for i in 0..3 {
        let e = edge(i, centre);
        if e < 0 || (e == 0 && !top_left(i)) {
            return None;
        }
    }
    let abs_area = (area * sign) as f64;
    let (pixels, lane) = quad_lanes(x, y);
    let z = window.map(|w| f64::from(w[2]));
    let inv_w = clip.map(|p| 1.0 / f64::from(p[3]));
    let quad = pixels.map(|(px, py)| {
        let p = [px * one, py * one];
        let e = |i: usize| -> f64 {
            let (s, t) = (fixed[(i + 1) % 3], fixed[(i + 2) % 3]);
            let (s, t) = ([s[0] as f64, s[1] as f64], [t[0] as f64, t[1] as f64]);
            sign as f64 * ((t[0] - s[0]) * (p[1] - s[1]) - (t[1] - s[1]) * (p[0] - s[0]))
        };
        let linear = [e(0) / abs_area, e(1) / abs_area, e(2) / abs_area];
        sample(linear, z, inv_w)
    });
    let depth = quad[lane].depth;
    if !(0.0..=1.0).contains(&depth) {
        return None; // clipped by the near or far plane
    }
    Some(Cover { quad, lane, front })
}

fn sample(linear: [f64; 3], z: [f64; 3], inv_w: [f64; 3]) -> Sample {
    let q = [linear[0] * inv_w[0], linear[1] * inv_w[1], linear[2] * inv_w[2]];
    let sum = q[0] + q[1] + q[2];
    Sample {
        linear,
        perspective: [q[0] / sum, q[1] / sum, q[2] / sum],
        depth: (linear[0] * z[0] + linear[1] * z[1] + linear[2] * z[2]) as f32,
        inv_w: sum as f32,
    }
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
    let (pixels, lane) = quad_lanes(x, y);
    let z = clip.map(|p| f64::from(p[2]));
    let weights = |px: f64, py: f64| -> [f64; 3] {
        let p = [
            px / f64::from(vp.width) * 2.0 - 1.0,
            1.0 - py / f64::from(vp.height) * 2.0,
            1.0,
        ];
        [
            det3(p, m[1], m[2]) / det,
            det3(m[0], p, m[2]) / det,
            det3(m[0], m[1], p) / det,
        ]
    };
    let k = weights(pixels[lane].0, pixels[lane].1);
    if k.iter().any(|&v| v < 0.0) || k.iter().sum::<f64>() <= 0.0 {
        return None;
    }
    let quad = pixels.map(|(px, py)| {
        let k = weights(px, py);
        let sum: f64 = k.iter().sum();
        let perspective = [k[0] / sum, k[1] / sum, k[2] / sum];
        let depth = k[0] * z[0] + k[1] * z[1] + k[2] * z[2];
        // Screen-space weights: the perspective ones divided by w, renormalised.
        let w = clip.map(|p| f64::from(p[3]));
        let l = [perspective[0] / w[0], perspective[1] / w[1], perspective[2] / w[2]];
        let ls: f64 = l.iter().sum();
        Sample {
            linear: [l[0] / ls, l[1] / ls, l[2] / ls],
            perspective,
            depth: depth as f32,
            inv_w: sum as f32,
        }
    });
    if !(0.0..=1.0).contains(&quad[lane].depth) {
        return None;
    }
    Some(Cover { quad, lane, front })
}

/// Whether a point at `clip` (size 1) covers pixel (x, y): the pixel's centre inside the
/// one-pixel square around the point (left and top edges included).
pub fn point(clip: [f32; 4], vp: Viewport, x: u32, y: u32) -> Option<Cover> {
    let w = clip[3];
    if !(w > 0.0) || clip[0].abs() > w || clip[1].abs() > w || clip[2] < 0.0 || clip[2] > w {
        return None;
    }
    let [sx, sy, depth] = vp.to_window(clip);
    let (cx, cy) = (x as f32 + 0.5, y as f32 + 0.5);
    if !(sx - 0.5 <= cx && cx < sx + 0.5 && sy - 0.5 <= cy && cy < sy + 0.5) {
        return None;
    }
    let (_, lane) = quad_lanes(x, y);
    let s = Sample {
        linear: [1.0, 0.0, 0.0],
        perspective: [1.0, 0.0, 0.0],
        depth,
        inv_w: 1.0 / w,
    };
    Some(Cover {
        quad: [s; 4],
        lane,
        front: true,
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
