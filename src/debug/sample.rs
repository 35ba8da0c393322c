//! Texture lookups on the CPU, from the texels the GPU was given and the sampler's GL state:
//! level of detail from the quad's derivatives, magnification or minification filter, nearest
//! or linear within a level, mipmap selection or blending, wrap modes, cube-map faces.

use std::sync::Arc;

use super::interp::Lod;
use crate::render::{SamplerDesc, Texels};

/// What a texture binding shows: its texels and the levels its view takes.
#[derive(Clone, Debug)]
pub struct View {
    /// The texels.
    pub texels: Arc<Texels>,
    /// The first level and the number of levels the view shows.
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

    /// Texel (i, j) of `face` of `level`, as 0..1 floats.
    fn texel(&self, level: u32, face: u32, i: u32, j: u32) -> [f32; 4] {
        let (w, h) = self.level_size(level);
        let Some(data) = self.texels.levels.get(level as usize) else {
            return [0.0, 0.0, 0.0, 1.0];
        };
        let at = ((face * h + j) * w + i) as usize * 4;
        match data.get(at..at + 4) {
            Some(p) => [0, 1, 2, 3].map(|k| f32::from(p[k]) / 255.0),
            None => [0.0, 0.0, 0.0, 1.0],
        }
    }

    /// The size of level `level` of the view (`textureSize`).
    pub fn size(&self, level: i32) -> [u32; 2] {
        let l = self.base + (level.max(0) as u32).min(self.count.saturating_sub(1));
        let (w, h) = self.level_size(l);
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
        self.texel(l, 0, coord[0] as u32, coord[1] as u32)
    }
}

fn wrap(mode: wgpu::AddressMode, i: i64, n: u32) -> u32 {
    let n = i64::from(n);
    (match mode {
        wgpu::AddressMode::Repeat => i.rem_euclid(n),
        wgpu::AddressMode::MirrorRepeat => {
            let period = i.rem_euclid(2 * n);
            if period < n {
                period
            } else {
                2 * n - 1 - period
            }
        }
        _ => i.clamp(0, n - 1),
    }) as u32
}

/// The face and its (s, t) for a cube-map direction (Vulkan's table; ties go to x, then y).
fn cube_face(d: [f32; 3]) -> (u32, f32, f32, f32) {
    let [x, y, z] = d;
    let (ax, ay, az) = (x.abs(), y.abs(), z.abs());
    let (face, sc, tc, ma) = if ax >= ay && ax >= az {
        if x >= 0.0 {
            (0, -z, -y, ax)
        } else {
            (1, z, -y, ax)
        }
    } else if ay >= az {
        if y >= 0.0 {
            (2, x, z, ay)
        } else {
            (3, x, -z, ay)
        }
    } else if z >= 0.0 {
        (4, x, -y, az)
    } else {
        (5, -x, -y, az)
    };
    (face, 0.5 * (sc / ma + 1.0), 0.5 * (tc / ma + 1.0), ma)
}

/// Looks `view` up through `desc` at `coord` with level of detail `lod`.
pub fn sample(view: &View, desc: &SamplerDesc, coord: [f32; 3], lod: Lod) -> [f32; 4] {
    let (face, s, t, ma) = if view.cube {
        cube_face(coord)
    } else {
        (0, coord[0], coord[1], 1.0)
    };
    let (w0, h0) = view.level_size(view.base);
    // λ: from the derivatives in texels (for a cube map, of the face coordinates), or given.
    let lambda = match lod {
        Lod::Level(l) => l,
        Lod::Implicit { dx, dy, bias } => {
            let scale = |d: [f32; 3]| -> (f32, f32) {
                if view.cube {
                    // d(sc/ma)/dx ≈ (dsc·ma − sc·dma)/ma²; half of it in face units.
                    let (_, s1, t1, _) = cube_face([coord[0] + d[0], coord[1] + d[1], coord[2] + d[2]]);
                    let _ = ma;
                    ((s1 - s) * w0 as f32, (t1 - t) * h0 as f32)
                } else {
                    (d[0] * w0 as f32, d[1] * h0 as f32)
                }
            };
            let (ux, vx) = scale(dx);
            let (uy, vy) = scale(dy);
            let rho = (ux * ux + vx * vx).sqrt().max((uy * uy + vy * vy).sqrt());
            rho.log2() + bias
        }
    };
    let max_level = view.count.saturating_sub(1) as f32;
    let magnify = lambda <= 0.0;
    let filter = if magnify { desc.mag } else { desc.min };
    match (magnify, desc.mipmap) {
        (true, _) | (false, None) => filter_level(view, desc, filter, view.base, face, s, t),
        (false, Some(wgpu::MipmapFilterMode::Nearest)) => {
            // Vulkan: level ⌈λ + ½⌉ − 1, clamped to the view's levels.
            let level = ((lambda + 0.5).ceil() - 1.0).clamp(0.0, max_level) as u32;
            filter_level(view, desc, filter, view.base + level, face, s, t)
        }
        (false, Some(wgpu::MipmapFilterMode::Linear)) => {
            let l = lambda.clamp(0.0, max_level);
            let lo = l.floor();
            let frac = l - lo;
            let a = filter_level(view, desc, filter, view.base + lo as u32, face, s, t);
            if frac == 0.0 || lo as u32 + 1 > max_level as u32 {
                return a;
            }
            let b = filter_level(view, desc, filter, view.base + lo as u32 + 1, face, s, t);
            [0, 1, 2, 3].map(|k| a[k] + (b[k] - a[k]) * frac)
        }
    }
}

fn filter_level(view: &View, desc: &SamplerDesc, filter: wgpu::FilterMode, level: u32, face: u32, s: f32, t: f32) -> [f32; 4] {
    let (w, h) = view.level_size(level);
    // A cube map's faces clamp at their edges (filtering across faces is not modelled).
    let (wrap_s, wrap_t) = if view.cube {
        (wgpu::AddressMode::ClampToEdge, wgpu::AddressMode::ClampToEdge)
    } else {
        (desc.wrap[0], desc.wrap[1])
    };
    let u = s * w as f32;
    let v = t * h as f32;
    match filter {
        wgpu::FilterMode::Nearest => {
            let i = wrap(wrap_s, u.floor() as i64, w);
            let j = wrap(wrap_t, v.floor() as i64, h);
            view.texel(level, face, i, j)
        }
        wgpu::FilterMode::Linear => {
            let (u, v) = (u - 0.5, v - 0.5);
            let (i0, j0) = (u.floor(), v.floor());
            let (a, b) = (u - i0, v - j0);
            let (i0, j0) = (i0 as i64, j0 as i64);
            let (i1, j1) = (wrap(wrap_s, i0 + 1, w), wrap(wrap_t, j0 + 1, h));
            let (i0, j0) = (wrap(wrap_s, i0, w), wrap(wrap_t, j0, h));
            let t00 = view.texel(level, face, i0, j0);
            let t10 = view.texel(level, face, i1, j0);
            let t01 = view.texel(level, face, i0, j1);
            let t11 = view.texel(level, face, i1, j1);
            [0, 1, 2, 3].map(|k| {
                let top = t00[k] + (t10[k] - t00[k]) * a;
                let bottom = t01[k] + (t11[k] - t01[k]) * a;
                top + (bottom - top) * b
            })
        }
    }
}
