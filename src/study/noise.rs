//! The course's Ashima/McEwan simplex noise on the CPU, in f32, line for line as
//! `shaders_glsl/noise.glsl` (GLSL `mod(x, y)` is `x - y * floor(x / y)`). Used to measure
//! displacement cracks and to check the noise's time period without a GPU.

use glam::{Vec2, Vec3, Vec4};

fn mod289(x: Vec4) -> Vec4 {
    x - 289.0 * (x / 289.0).floor()
}

fn permute(x: Vec4) -> Vec4 {
    mod289(((x * 34.0) + 1.0) * x)
}

fn taylor_inv_sqrt(r: Vec4) -> Vec4 {
    1.792_842_9 - 0.853_734_7 * r
}

fn step(edge: Vec3, x: Vec3) -> Vec3 {
    Vec3::select(x.cmplt(edge), Vec3::ZERO, Vec3::ONE)
}

fn step4(edge: Vec4, x: Vec4) -> Vec4 {
    Vec4::select(x.cmplt(edge), Vec4::ZERO, Vec4::ONE)
}

/// `snoise(v)`: 3D simplex noise in about [-1, 1].
pub fn snoise(v: Vec3) -> f32 {
    let c = Vec2::new(1.0 / 6.0, 1.0 / 3.0);
    let d = Vec4::new(0.0, 0.5, 1.0, 2.0);

    let mut i = (v + v.dot(Vec3::splat(c.y))).floor();
    let x0 = v - i + i.dot(Vec3::splat(c.x));
    let g = step(Vec3::new(x0.y, x0.z, x0.x), x0);
    let l = 1.0 - g;
    let lzxy = Vec3::new(l.z, l.x, l.y);
    let i1 = g.min(lzxy);
    let i2 = g.max(lzxy);
    let x1 = x0 - i1 + 1.0 * c.x;
    let x2 = x0 - i2 + 2.0 * c.x;
    let x3 = x0 - 1.0 + 3.0 * c.x;

    i = i - 289.0 * (i / 289.0).floor();
    let p = permute(
        permute(permute(i.z + Vec4::new(0.0, i1.z, i2.z, 1.0)) + i.y + Vec4::new(0.0, i1.y, i2.y, 1.0))
            + i.x
            + Vec4::new(0.0, i1.x, i2.x, 1.0),
    );

    let nn = 1.0 / 7.0;
    let ns = nn * Vec3::new(d.w, d.y, d.z) - Vec3::new(d.x, d.z, d.x);
    let j = p - 49.0 * (p * ns.z * ns.z).floor();
    let xx = (j * ns.z).floor();
    let yy = (j - 7.0 * xx).floor();
    let x = xx * ns.x + ns.y;
    let y = yy * ns.x + ns.y;
    let h = 1.0 - x.abs() - y.abs();
    let b0 = Vec4::new(x.x, x.y, y.x, y.y);
    let b1 = Vec4::new(x.z, x.w, y.z, y.w);
    let s0 = b0.floor() * 2.0 + 1.0;
    let s1 = b1.floor() * 2.0 + 1.0;
    let sh = -step4(h, Vec4::ZERO);
    let a0 = Vec4::new(b0.x, b0.z, b0.y, b0.w) + Vec4::new(s0.x, s0.z, s0.y, s0.w) * Vec4::new(sh.x, sh.x, sh.y, sh.y);
    let a1 = Vec4::new(b1.x, b1.z, b1.y, b1.w) + Vec4::new(s1.x, s1.z, s1.y, s1.w) * Vec4::new(sh.z, sh.z, sh.w, sh.w);
    let mut p0 = Vec3::new(a0.x, a0.y, h.x);
    let mut p1 = Vec3::new(a0.z, a0.w, h.y);
    let mut p2 = Vec3::new(a1.x, a1.y, h.z);
    let mut p3 = Vec3::new(a1.z, a1.w, h.w);

    let norm = taylor_inv_sqrt(Vec4::new(p0.dot(p0), p1.dot(p1), p2.dot(p2), p3.dot(p3)));
    p0 *= norm.x;
    p1 *= norm.y;
    p2 *= norm.z;
    p3 *= norm.w;

    let m = (0.6 - Vec4::new(x0.dot(x0), x1.dot(x1), x2.dot(x2), x3.dot(x3))).max(Vec4::ZERO);
    let m = m * m * m * m;
    42.0 * m.dot(Vec4::new(p0.dot(x0), p1.dot(x1), p2.dot(x2), p3.dot(x3)))
}

/// Exercise 5's vertex displacement on the CPU: the displaced position of a vertex.
pub fn displace(position: Vec3, normal: Vec3, time: f32, displacement: f32) -> Vec3 {
    let n = snoise(position.normalize_or_zero() * 2.0 + time);
    position + normal * n * displacement.clamp(0.0, 1.0)
}

/// The widest crack a displaced mesh opens: the largest distance between displaced copies of
/// vertices that share a position (GLUT splits normals at the cube's edges and the teapot's seams).
pub fn max_crack(mesh: &crate::mesh::Mesh, time: f32, displacement: f32) -> f32 {
    let mut by_position: std::collections::HashMap<[u32; 3], Vec<Vec3>> = std::collections::HashMap::new();
    for v in &mesh.vertices {
        let moved = displace(Vec3::from(v.position), Vec3::from(v.normal), time, displacement);
        by_position.entry(v.position.map(f32::to_bits)).or_default().push(moved);
    }
    by_position
        .values()
        .flat_map(|copies| {
            copies
                .iter()
                .flat_map(move |a| copies.iter().map(move |b| a.distance(*b)))
        })
        .fold(0.0, f32::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn noise_is_bounded_and_varies() {
        let values: Vec<f32> = (0..1000)
            .map(|i| snoise(Vec3::new(i as f32 * 0.173, i as f32 * 0.071, 0.3)))
            .collect();
        assert!(values.iter().all(|v| v.abs() <= 1.0));
        let mean = values.iter().sum::<f32>() / values.len() as f32;
        assert!(mean.abs() < 0.1);
        assert!(values.iter().any(|v| *v > 0.5) && values.iter().any(|v| *v < -0.5));
    }

    #[test]
    fn noise_period_along_the_diagonal_is_144_5() {
        // Shifting by t along (1,1,1) moves the skewed lattice by 2t: it repeats at 289 / 2.
        for k in [0.3f32, 1.7, -2.2] {
            let p = Vec3::new(k, 0.5 * k, -0.25);
            let a = snoise(p);
            let b = snoise(p + 144.5);
            assert!((a - b).abs() < 2e-3, "{a} vs {b}");
            // ... and not at nearby shifts.
            assert!((snoise(p + 72.25) - a).abs() > 1e-3 || (snoise(p + 100.0) - a).abs() > 1e-3);
        }
    }
}
