//! Texture lookups on the CPU, from the texels the GPU was given and the sampler's GL state,
//! computed the way the reference rasteriser (Mesa's llvmpipe, behind lavapipe) computes them:
//! one level of detail per 2×2 quad from the top-left pixel's derivatives, the exact
//! `floor(log2 ρ + ½)` for nearest-mipmap selection and its piecewise-linear `log2` otherwise,
//! 8-bit fixed-point weights for RGBA8 2D textures under repeat or clamp-to-edge, float
//! weights with seamless edges for cube maps, and an elliptical weighted average for
//! anisotropic samplers. The Vulkan rules leave some of this to the
//! implementation; where another GPU differs, it differs by a texel-edge tie or a rounding.
//! `docs/debugger.md` lists the sources.

use std::sync::Arc;

use super::interp::Lod;
use crate::render::{SamplerDesc, Texels};

/// What a texture binding shows: its texels and the levels its view takes.
#[derive(Clone, Debug)]
pub struct View {
    /// The texels.
    pub texels: Arc<Texels>,
    /// The first level the view shows.
    pub base: u32,
    /// Levels shown.
    pub count: u32,
    /// A cube map (six faces).
    pub cube: bool,
}

impl View {
    fn level_size(&self, level: u32) -> (u32, u32) {
        (
            (self.texels.width >> level).max(1),
            (self.texels.height >> level).max(1),
        )
    }

    /// Texel (i, j) of `face` of `level` as bytes.
    fn texel(&self, level: u32, face: u32, i: u32, j: u32) -> [u8; 4] {
        let (w, h) = self.level_size(level);
        let Some(data) = self.texels.levels.get(level as usize) else {
            return [0, 0, 0, 255];
        };
        let at = ((face * h + j) * w + i) as usize * 4;
        match data.get(at..at + 4) {
            Some(p) => [p[0], p[1], p[2], p[3]],
            None => [0, 0, 0, 255],
        }
    }

    /// The size of level `level` of the view (`textureSize`); zero for a level the view does
    /// not have, as llvmpipe answers (GLSL leaves it undefined).
    pub fn size(&self, level: i32) -> [u32; 2] {
        if level < 0 || level as u32 >= self.count {
            return [0, 0];
        }
        let (w, h) = self.level_size(self.base + level as u32);
        [w, h]
    }

    /// Texel `coord` of level `level` (`texelFetch`); out of range reads zero, as wgpu's
    /// robust access does.
    pub fn fetch(&self, coord: [i32; 3], level: i32) -> [f32; 4] {
        if level < 0 || level as u32 >= self.count {
            return [0.0; 4];
        }
        let l = self.base + level as u32;
        let (w, h) = self.level_size(l);
        if coord[0] < 0 || coord[1] < 0 || coord[0] as u32 >= w || coord[1] as u32 >= h {
            return [0.0; 4];
        }
        unorm(self.texel(l, 0, coord[0] as u32, coord[1] as u32))
    }
}

/// 8-bit channels as floats: `v · (1/255)`, one rounding.
fn unorm(t: [u8; 4]) -> [f32; 4] {
    t.map(|v| f32::from(v) * (1.0f32 / 255.0))
}

/// `a + ((w·(b − a) + 128) >> 8)`: the 8-bit lerp of the fixed-point path (w in 0..=255).
fn lerp8(a: i32, b: i32, w: i32) -> i32 {
    a + ((w * (b - a) + 128) >> 8)
}

/// log2 of `x` as a piecewise-linear function of its bits: exponent plus mantissa − 1.
fn fast_log2(x: f32) -> f32 {
    let bits = x.to_bits();
    let exponent = ((bits >> 23) & 0xff) as i32 - 127;
    let mantissa = f32::from_bits((bits & 0x007f_ffff) | 0x3f80_0000);
    exponent as f32 + (mantissa - 1.0)
}

/// `cvtps2dq`: round half to even.
fn iround(x: f32) -> i32 {
    x.round_ties_even() as i32
}

/// The level of detail as the sampler uses it: the integer level (relative to the view's
/// first), the blend toward the next level (0–1), and whether it minifies.
struct Level {
    ipart: i32,
    fpart: f32,
    minify: bool,
}

fn mip_mode(view: &View, desc: &SamplerDesc) -> Option<wgpu::MipmapFilterMode> {
    // Without GL's mipmap filter wgpu's sampler selects the nearest level; a view of one level
    // has no mipmapping at all.
    (view.count > 1).then(|| desc.mipmap.unwrap_or(wgpu::MipmapFilterMode::Nearest))
}

fn level_of(rho2: Option<f32>, explicit: Option<f32>, bias: f32, mip: Option<wgpu::MipmapFilterMode>) -> Level {
    use wgpu::MipmapFilterMode as Mip;
    if let (Some(rho2), None, true, false) = (rho2, explicit, bias == 0.0, mip == Some(Mip::Linear)) {
        // No bias, nearest or no mipmapping: the exact floor(log2 ρ + ½) from ρ²'s exponent.
        let exponent = ((rho2.to_bits() >> 23) & 0xff) as i32;
        return Level {
            ipart: (exponent - 126) >> 1,
            fpart: 0.0,
            minify: rho2 > 1.0,
        };
    }
    let lod = match explicit {
        Some(l) => l + bias,
        None => 0.5f32 * fast_log2(rho2.unwrap_or(1.0)) + bias,
    };
    let minify = lod > 0.0;
    match mip {
        Some(Mip::Linear) => Level {
            ipart: lod.floor() as i32,
            fpart: lod - lod.floor(),
            minify,
        },
        _ => Level {
            ipart: iround(lod),
            fpart: 0.0,
            minify,
        },
    }
}

/// The levels to read and the 8-bit weight of the second: (l0, l1, weight 0..=255, float fpart).
fn levels(view: &View, mip: Option<wgpu::MipmapFilterMode>, level: &Level) -> (u32, u32, f32) {
    let (first, last) = (view.base as i32, (view.base + view.count - 1) as i32);
    if !level.minify {
        return (first as u32, first as u32, 0.0);
    }
    match mip {
        None => (first as u32, first as u32, 0.0),
        Some(wgpu::MipmapFilterMode::Nearest) => {
            let l = (first + level.ipart).clamp(first, last) as u32;
            (l, l, 0.0)
        }
        Some(wgpu::MipmapFilterMode::Linear) => {
            let l0 = first + level.ipart;
            if l0 < first {
                (first as u32, first as u32, 0.0)
            } else if l0 >= last {
                (last as u32, last as u32, 0.0)
            } else {
                (l0 as u32, l0 as u32 + 1, level.fpart)
            }
        }
    }
}

/// Looks `view` up through `desc` at `coord` with level of detail `lod`.
pub fn sample(view: &View, desc: &SamplerDesc, coord: [f32; 3], lod: Lod) -> [f32; 4] {
    if view.cube {
        return sample_cube(view, desc, coord, lod);
    }
    if desc.anisotropy > 1 {
        return sample_aniso(view, desc, coord, lod);
    }
    let mip = mip_mode(view, desc);
    let (w0, h0) = view.level_size(view.base);
    let level = match lod {
        Lod::Level(l) => level_of(None, Some(l), 0.0, mip),
        Lod::Implicit { coarse, bias, .. } => {
            let (dx, dy) = coarse;
            let (sx, tx) = (dx[0] * w0 as f32, dx[1] * h0 as f32);
            let (sy, ty) = (dy[0] * w0 as f32, dy[1] * h0 as f32);
            let rho2 = (sx * sx + tx * tx).max(sy * sy + ty * ty);
            level_of(Some(rho2), None, bias, mip)
        }
    };
    let filter = if level.minify { desc.min } else { desc.mag };
    let (l0, l1, fpart) = levels(view, mip, &level);
    let fixed = desc
        .wrap
        .iter()
        .take(2)
        .all(|w| matches!(w, wgpu::AddressMode::Repeat | wgpu::AddressMode::ClampToEdge));
    if fixed {
        // The 8-bit fixed-point path.
        let a = filter8(view, desc, filter, l0, coord[0], coord[1]);
        let wl = (fpart * 256.0) as i32;
        let c = if l1 != l0 && wl > 0 {
            let b = filter8(view, desc, filter, l1, coord[0], coord[1]);
            [0, 1, 2, 3].map(|k| lerp8(a[k], b[k], wl))
        } else {
            a
        };
        return c.map(|v| f32::from(v as u8) * (1.0f32 / 255.0));
    }
    let a = filter_float(view, desc.wrap, filter, l0, 0, coord[0], coord[1]);
    if l1 != l0 && fpart > 0.0 {
        let b = filter_float(view, desc.wrap, filter, l1, 0, coord[0], coord[1]);
        return [0, 1, 2, 3].map(|k| fpart.mul_add(b[k] - a[k], a[k]));
    }
    a
}

fn wrap_nearest(mode: wgpu::AddressMode, u: f32, size: u32) -> u32 {
    let n = size as i64;
    let pot = size.is_power_of_two();
    match mode {
        wgpu::AddressMode::Repeat if pot => ((u * size as f32).floor() as i64 & (n - 1)) as u32,
        wgpu::AddressMode::Repeat => {
            let f = u - u.floor();
            ((f * size as f32) as i64).clamp(0, n - 1) as u32
        }
        wgpu::AddressMode::MirrorRepeat => {
            let i = (u * size as f32).floor() as i64;
            let p = i.rem_euclid(2 * n);
            (if p < n { p } else { 2 * n - 1 - p }) as u32
        }
        _ => ((u * size as f32).floor() as i64).clamp(0, n - 1) as u32,
    }
}

/// The two texels and the 8-bit weight of linear filtering along one axis (fixed point).
fn wrap_linear8(mode: wgpu::AddressMode, u: f32, size: u32) -> (u32, u32, i32) {
    let n = size as i32;
    if mode == wgpu::AddressMode::Repeat && !size.is_power_of_two() {
        let f = (u - u.floor()) * (size as f32 * 256.0);
        let s = iround(f) - 128;
        let w = s & 255;
        let mut i0 = s >> 8;
        if i0 < 0 {
            i0 = n - 1;
        }
        let i0 = i0.min(n - 1);
        let i1 = if i0 == n - 1 { 0 } else { i0 + 1 };
        return (i0 as u32, i1 as u32, w);
    }
    let s = iround(u * (size << 8) as f32) - 128;
    let (i0, w) = (s >> 8, s & 255);
    match mode {
        wgpu::AddressMode::Repeat => {
            let i0 = i0 & (n - 1);
            let i1 = if i0 == n - 1 { 0 } else { i0 + 1 };
            (i0 as u32, i1 as u32, w)
        }
        _ => {
            let c0 = i0.clamp(0, n - 1);
            let c1 = if (0..=n - 2).contains(&i0) { i0 + 1 } else { c0 };
            (c0 as u32, c1 as u32, w)
        }
    }
}

fn filter8(view: &View, desc: &SamplerDesc, filter: wgpu::FilterMode, level: u32, u: f32, v: f32) -> [i32; 4] {
    let (w, h) = view.level_size(level);
    let wide = |t: [u8; 4]| t.map(i32::from);
    match filter {
        wgpu::FilterMode::Nearest => {
            let i = wrap_nearest(desc.wrap[0], u, w);
            let j = wrap_nearest(desc.wrap[1], v, h);
            wide(view.texel(level, 0, i, j))
        }
        wgpu::FilterMode::Linear => {
            let (i0, i1, ws) = wrap_linear8(desc.wrap[0], u, w);
            let (j0, j1, wt) = wrap_linear8(desc.wrap[1], v, h);
            let t00 = wide(view.texel(level, 0, i0, j0));
            let t10 = wide(view.texel(level, 0, i1, j0));
            let t01 = wide(view.texel(level, 0, i0, j1));
            let t11 = wide(view.texel(level, 0, i1, j1));
            [0, 1, 2, 3].map(|k| lerp8(lerp8(t00[k], t10[k], ws), lerp8(t01[k], t11[k], ws), wt))
        }
    }
}

/// Float linear filtering (mirror or border wrap): texel indices and weights.
fn wrap_linear_float(mode: wgpu::AddressMode, u: f32, size: u32) -> (u32, u32, f32) {
    let n = size as i64;
    match mode {
        wgpu::AddressMode::Repeat => {
            let c = u * size as f32 - 0.5;
            let i0 = c.floor();
            let w = c - i0;
            let i0 = (i0 as i64).rem_euclid(n);
            (i0 as u32, ((i0 + 1) % n) as u32, w)
        }
        wgpu::AddressMode::MirrorRepeat => {
            let c = u * size as f32 - 0.5;
            let i0 = c.floor();
            let w = c - i0;
            let m = |i: i64| {
                let p = i.rem_euclid(2 * n);
                (if p < n { p } else { 2 * n - 1 - p }) as u32
            };
            (m(i0 as i64), m(i0 as i64 + 1), w)
        }
        _ => {
            let c = ((u * size as f32).min(size as f32) - 0.5).max(0.0);
            let i0 = c.floor();
            let w = c - i0;
            let i0 = i0 as i64;
            (i0.min(n - 1) as u32, (i0 + 1).min(n - 1) as u32, w)
        }
    }
}

fn filter_float(
    view: &View,
    wrap: [wgpu::AddressMode; 3],
    filter: wgpu::FilterMode,
    level: u32,
    face: u32,
    u: f32,
    v: f32,
) -> [f32; 4] {
    let (w, h) = view.level_size(level);
    match filter {
        wgpu::FilterMode::Nearest => {
            let i = wrap_nearest(wrap[0], u, w);
            let j = wrap_nearest(wrap[1], v, h);
            unorm(view.texel(level, face, i, j))
        }
        wgpu::FilterMode::Linear => {
            let (i0, i1, ws) = wrap_linear_float(wrap[0], u, w);
            let (j0, j1, wt) = wrap_linear_float(wrap[1], v, h);
            let t = |i, j| unorm(view.texel(level, face, i, j));
            let (t00, t10, t01, t11) = (t(i0, j0), t(i1, j0), t(i0, j1), t(i1, j1));
            [0, 1, 2, 3].map(|k| {
                let top = ws.mul_add(t10[k] - t00[k], t00[k]);
                let bottom = ws.mul_add(t11[k] - t01[k], t01[k]);
                wt.mul_add(bottom - top, top)
            })
        }
    }
}

/// The face of a cube-map direction, its major axis value and the face's (sc, tc) axes as
/// (component, sign) pairs. Ties go to z, then y.
fn cube_face(d: [f32; 3]) -> (u32, usize, (usize, f32), (usize, f32)) {
    let [ax, ay, az] = d.map(f32::abs);
    let neg = |v: f32| v.is_sign_negative();
    if az >= ax.max(ay) {
        if neg(d[2]) {
            (5, 2, (0, -1.0), (1, -1.0))
        } else {
            (4, 2, (0, 1.0), (1, -1.0))
        }
    } else if ax > ay {
        if neg(d[0]) {
            (1, 0, (2, 1.0), (1, -1.0))
        } else {
            (0, 0, (2, -1.0), (1, -1.0))
        }
    } else if neg(d[1]) {
        (3, 1, (0, 1.0), (2, -1.0))
    } else {
        (2, 1, (0, 1.0), (2, 1.0))
    }
}

/// Face coordinates (s, t) of a direction on `face`'s axes.
fn face_st(d: [f32; 3], major: usize, sc: (usize, f32), tc: (usize, f32)) -> (f32, f32) {
    let k = 0.5f32 / d[major].abs();
    (sc.1 * d[sc.0] * k + 0.5, tc.1 * d[tc.0] * k + 0.5)
}

fn sample_cube(view: &View, desc: &SamplerDesc, d: [f32; 3], lod: Lod) -> [f32; 4] {
    let (face, major, sc, tc) = cube_face(d);
    let (s, t) = face_st(d, major, sc, tc);
    let mip = mip_mode(view, desc);
    let (size, _) = view.level_size(view.base);
    let level = match lod {
        Lod::Level(l) => level_of(None, Some(l), 0.0, mip),
        Lod::Implicit { fine, bias, .. } => {
            // Per pixel, from its own derivatives carried onto the face.
            let ma = d[major] * if d[major].is_sign_negative() { -1.0 } else { 1.0 };
            let ima = 1.0f32 / ma;
            let face_d = |dd: [f32; 3]| -> (f32, f32) {
                let dma = dd[major] * if d[major].is_sign_negative() { -1.0 } else { 1.0 };
                let (scv, tcv) = (sc.1 * d[sc.0], tc.1 * d[tc.0]);
                let (dsc, dtc) = (sc.1 * dd[sc.0], tc.1 * dd[tc.0]);
                (
                    (dsc - (dma * ima) * scv) * (0.5 * ima) * size as f32,
                    (dtc - (dma * ima) * tcv) * (0.5 * ima) * size as f32,
                )
            };
            let (sx, tx) = face_d(fine.0);
            let (sy, ty) = face_d(fine.1);
            let rho2 = (sx * sx + tx * tx).max(sy * sy + ty * ty);
            level_of(Some(rho2), None, bias, mip)
        }
    };
    let filter = if level.minify { desc.min } else { desc.mag };
    let (l0, l1, fpart) = levels(view, mip, &level);
    let one = |l: u32| match filter {
        wgpu::FilterMode::Nearest => {
            let clamp = [wgpu::AddressMode::ClampToEdge; 3];
            filter_float(view, clamp, filter, l, face, s, t)
        }
        wgpu::FilterMode::Linear => seamless(view, l, face, major, sc, tc, s, t),
    };
    let a = one(l0);
    if l1 != l0 && fpart > 0.0 {
        let b = one(l1);
        return [0, 1, 2, 3].map(|k| fpart.mul_add(b[k] - a[k], a[k]));
    }
    a
}

/// Linear filtering on a cube face whose texels past an edge come from the neighbouring face
/// (the missing fourth texel at a corner gives a third of its weight to each of the others).
#[allow(clippy::too_many_arguments)]
fn seamless(
    view: &View,
    level: u32,
    face: u32,
    major: usize,
    sc: (usize, f32),
    tc: (usize, f32),
    s: f32,
    t: f32,
) -> [f32; 4] {
    let (size, _) = view.level_size(level);
    let n = size as f32;
    let cs = s.max(0.0) * n - 0.5;
    let ct = t.max(0.0) * n - 0.5;
    let (i0, j0) = (cs.floor(), ct.floor());
    let (ws, wt) = (cs - i0, ct - j0);
    let (i0, j0) = (i0 as i64, j0 as i64);
    let positive = [0u32, 2, 4].contains(&face);
    // The direction through the centre of texel (i, j) of this face, possibly past its edge.
    let texel = |i: i64, j: i64| -> Option<[f32; 4]> {
        let inside = |k: i64| (0..size as i64).contains(&k);
        if inside(i) && inside(j) {
            return Some(unorm(view.texel(level, face, i as u32, j as u32)));
        }
        if !inside(i) && !inside(j) {
            return None; // a corner: no texel
        }
        let fs = (i as f32 + 0.5) / n * 2.0 - 1.0;
        let ft = (j as f32 + 0.5) / n * 2.0 - 1.0;
        let mut dir = [0.0f32; 3];
        dir[major] = if positive { 1.0 } else { -1.0 };
        dir[sc.0] += sc.1 * fs;
        dir[tc.0] += tc.1 * ft;
        // Past the edge the direction leaves the face's square; the neighbour's texel is the
        // one it lands in (clamped onto the face it selects).
        let (f2, m2, s2, t2) = cube_face(dir);
        let (u, v) = face_st(dir, m2, s2, t2);
        let ii = ((u * n).floor() as i64).clamp(0, size as i64 - 1) as u32;
        let jj = ((v * n).floor() as i64).clamp(0, size as i64 - 1) as u32;
        Some(unorm(view.texel(level, f2, ii, jj)))
    };
    let taps = [
        (texel(i0, j0), (1.0 - ws) * (1.0 - wt)),
        (texel(i0 + 1, j0), ws * (1.0 - wt)),
        (texel(i0, j0 + 1), (1.0 - ws) * wt),
        (texel(i0 + 1, j0 + 1), ws * wt),
    ];
    if taps.iter().all(|(t, _)| t.is_some()) {
        let t = taps.map(|(t, _)| t.unwrap_or_default());
        return [0, 1, 2, 3].map(|k| {
            let top = ws.mul_add(t[1][k] - t[0][k], t[0][k]);
            let bottom = ws.mul_add(t[3][k] - t[2][k], t[2][k]);
            wt.mul_add(bottom - top, top)
        });
    }
    let missing: f32 = taps.iter().filter(|(t, _)| t.is_none()).map(|(_, w)| *w).sum();
    let mut out = [0.0f32; 4];
    for (t, w) in taps.iter() {
        if let Some(t) = t {
            let w = w + missing / 3.0;
            for k in 0..4 {
                out[k] += w * t[k];
            }
        }
    }
    out
}

/// `cvttps2dq`: truncation, with the "integer indefinite" `i32::MIN` for NaN and out of range.
fn itrunc(x: f32) -> i32 {
    // NaN is outside every range.
    if (-2_147_483_648.0..2_147_483_648.0).contains(&x) {
        x as i32
    } else {
        i32::MIN
    }
}

/// The anisotropic filter's weights: `expf(−2 r²)` for r² = i / 1023, printed to six decimals
/// (Mesa's `aniso_filter_table`, which was generated that way).
fn aniso_weights() -> &'static [f32; 1024] {
    static TABLE: std::sync::OnceLock<[f32; 1024]> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        std::array::from_fn(|i| {
            let w = (-2.0f32 * (i as f32 / 1023.0)).exp();
            format!("{w:.6}").parse().unwrap_or(w)
        })
    })
}

/// Anisotropic filtering as llvmpipe does it (`lp_build_sample_aniso`, Mesa 22.3): an
/// elliptical weighted average (Heckbert's EWA) of the nearest texels of one level, weighted
/// by a Gaussian of the pixel's footprint, the level chosen from the footprint's *shorter*
/// axis and truncated. Float arithmetic in the order llvmpipe's code does it (no fused
/// operations), so that the stored byte is the GPU's.
fn sample_aniso(view: &View, desc: &SamplerDesc, coord: [f32; 3], lod: Lod) -> [f32; 4] {
    let (w0, h0) = view.level_size(0);
    let (fw, fh) = (w0 as f32, h0 as f32);
    // Derivatives of (s, t) across the quad: (ds/dx, ds/dy, dt/dx, dt/dy).
    let (dx, dy, explicit, bias) = match lod {
        Lod::Implicit { coarse, bias, .. } => (coarse.0, coarse.1, None, bias),
        Lod::Level(l) => ([0.0; 3], [0.0; 3], Some(l), 0.0),
    };
    let d = [dx[0], dy[0], dx[1], dy[1]];
    let lod = match explicit {
        Some(l) => l,
        None => {
            // lp_build_pmin: the squared length of the shorter axis (its clamp by the
            // anisotropy compares the shorter axis with itself, so it never applies).
            let base = [fw, fw, fh, fh];
            let sq: [f32; 4] = std::array::from_fn(|k| {
                let v = d[k] * base[k];
                v * v
            });
            let (px2, py2) = (sq[0] + sq[2], sq[1] + sq[3]);
            let pmin2 = px2.min(py2);
            0.5f32 * fast_log2(pmin2) + bias
        }
    };
    let (first, last) = (view.base as i32, (view.base + view.count - 1) as i32);
    let level = (first.saturating_add(itrunc(lod))).clamp(first, last) as u32;
    let scaling = 1.0f32 / (1u32 << level.min(31)) as f32;
    let (lw, lh) = view.level_size(level);
    let (dim_w, dim_h) = (lw as f32, lh as f32);
    let base = [fw, fw, fh, fh];
    let e: [f32; 4] = std::array::from_fn(|k| d[k] * base[k] * scaling);
    // The ellipse A·u² + B·u·v + C·v² = F.
    let a = (e[2] * e[2] + e[3] * e[3]) + 1.0;
    let b = (e[0] * e[2] + e[1] * e[3]) * -2.0;
    let c = (e[0] * e[0] + e[1] * e[1]) + 1.0;
    let f = a * c - (b * b) / 4.0;
    let det = (0.0 - b * b) + (a * c) * 4.0;
    let box_u = (2.0 / det) * ((det * c) * f).sqrt();
    let box_v = (2.0 / det) * ((a * det) * f).sqrt();
    let scale = 1023.0 / f;
    let (a, b, c) = (a * scale, b * scale, c * scale);
    let ddq = a * 2.0;
    let tex_u = coord[0] * (fw * scaling) + -0.5;
    let tex_v = coord[1] * (fh * scaling) + -0.5;
    let u0 = itrunc((tex_u - box_u).floor());
    let u1 = itrunc((tex_u + box_u).ceil());
    let v0 = itrunc((tex_v - box_v).floor());
    let v1 = itrunc((tex_v + box_v).ceil());
    let big_u = u0 as f32 - tex_u;
    let dq_base = (big_u * 2.0 + 1.0) * a;
    let q_base = (big_u * big_u) * a;
    let table = aniso_weights();
    let mut color = [0.0f32; 4];
    let mut den = 0.0f32;
    // Bounded like the GPU's loop (a degenerate footprint spans the texture at most).
    let span = |lo: i32, hi: i32| (hi as i64 - lo as i64).clamp(-1, 1 << 14);
    let (nu, nv) = (span(u0, u1), span(v0, v1));
    for j in 0..=nv {
        let v = (v0 as i64 + j) as i32;
        let big_v = v as f32 - tex_v;
        let mut dq = big_v * b + dq_base;
        let mut q = (c * big_v + b * big_u) * big_v + q_base;
        for i in 0..=nu {
            let u = (u0 as i64 + i) as i32;
            let qi = itrunc(q);
            if qi <= 0x3ff {
                let weight = table[(qi.max(0) & 0x3ff) as usize];
                if weight != 0.0 {
                    let s = u as f32 / dim_w;
                    let t = v as f32 / dim_h;
                    let x = wrap_nearest(desc.wrap[0], s, lw);
                    let y = wrap_nearest(desc.wrap[1], t, lh);
                    let texel = unorm(view.texel(level, 0, x, y));
                    for k in 0..4 {
                        color[k] += texel[k] * weight;
                    }
                    den += weight;
                }
            }
            q += dq;
            dq += ddq;
        }
    }
    if den == 0.0 {
        return filter_float(view, desc.wrap, wgpu::FilterMode::Linear, level, 0, coord[0], coord[1]);
    }
    color.map(|v| v / den)
}
