//! Tessellation levels, and choosing the smallest one a view needs.
//!
//! A level is one number per object: slices = stacks for the sphere, sides = rings for the
//! torus, vertices per patch edge for the teapot (the cube has none). [`deviation`] measures how
//! far a level's triangles stray from the exact surface, in object units; projected to pixels
//! at the distance of the silhouette it predicts the silhouette error, and [`choose_level`] picks
//! the smallest level that keeps it under a budget (default half a pixel).

use std::collections::HashMap;
use std::sync::{Mutex, OnceLock};

use crate::mesh::Mesh;

/// The four objects of keys `1`..`4`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Object {
    /// `glutSolidCube(1.5)`
    Cube,
    /// `glutSolidSphere(1, 24, 24)`
    Sphere,
    /// `glutSolidTorus(0.5, 1, 24, 24)`
    Torus,
    /// `glutSolidTeapot(1)`, the default
    Teapot,
}

impl Object {
    /// All objects, in key order.
    pub const ALL: [Object; 4] = [Object::Cube, Object::Sphere, Object::Torus, Object::Teapot];

    /// Lower-case name used on the command line and in file names.
    pub fn name(self) -> &'static str {
        match self {
            Object::Cube => "cube",
            Object::Sphere => "sphere",
            Object::Torus => "torus",
            Object::Teapot => "teapot",
        }
    }

    /// Parses a command-line name.
    pub fn from_name(name: &str) -> Option<Object> {
        Object::ALL.into_iter().find(|o| o.name() == name)
    }

    /// The mesh the original draws for this object.
    pub fn mesh(self) -> Mesh {
        mesh(self, glut_level(self))
    }

    /// How the object's outside faces are wound seen from outside: GLUT's cube, sphere and
    /// torus counter-clockwise, its teapot clockwise (see [`Mesh::teapot`]).
    pub fn outside_winding(self) -> wgpu::FrontFace {
        match self {
            Object::Teapot => wgpu::FrontFace::Cw,
            _ => wgpu::FrontFace::Ccw,
        }
    }
}

/// Smallest level offered.
pub const MIN_LEVEL: u32 = 3;
/// Largest level offered (a 512x512 sphere is half a million triangles).
pub const MAX_LEVEL: u32 = 512;
/// The default error budget of `--tess auto`: half a pixel of silhouette error.
pub const DEFAULT_BUDGET_PX: f64 = 0.5;

/// GLUT's own level for an object (what the original draws).
pub fn glut_level(object: Object) -> u32 {
    match object {
        Object::Cube => 0,
        Object::Sphere | Object::Torus => 24,
        Object::Teapot => Mesh::TEAPOT_DEFAULT_GRID,
    }
}

/// The object's mesh at a level (the cube ignores it).
pub fn mesh(object: Object, level: u32) -> Mesh {
    match object {
        Object::Cube => Mesh::cube(1.5),
        Object::Sphere => Mesh::sphere(1.0, level, level),
        Object::Torus => Mesh::torus(0.5, 1.0, level, level),
        Object::Teapot => Mesh::teapot(1.0, level),
    }
}

/// Radius of the object's bounding sphere about the origin.
pub fn bounding_radius(object: Object) -> f64 {
    match object {
        Object::Cube => 0.75 * 3f64.sqrt(),
        Object::Sphere => 1.0,
        Object::Torus => 1.5,
        Object::Teapot => 1.72,
    }
}

/// Largest distance (object units) between a level's triangles and the exact surface.
/// Sphere and torus: the exact distance at sample points of every triangle. Teapot: the distance
/// between the coarse grid's quads and the exact patch points at their parameter midpoints (taken
/// from the grid of level 2n-1, which contains them). Cached per (object, level).
pub fn deviation(object: Object, level: u32) -> f64 {
    static CACHE: OnceLock<Mutex<HashMap<(Object, u32), f64>>> = OnceLock::new();
    let cache = CACHE.get_or_init(|| Mutex::new(HashMap::new()));
    if let Some(d) = cache.lock().ok().and_then(|c| c.get(&(object, level)).copied()) {
        return d;
    }
    let d = match object {
        Object::Cube => 0.0,
        Object::Sphere => surface_deviation(&mesh(object, level), |p| (1.0 - len(p)).abs()),
        Object::Torus => surface_deviation(&mesh(object, level), |p| {
            let ring = (p[0] * p[0] + p[1] * p[1]).sqrt() - 1.0;
            ((ring * ring + p[2] * p[2]).sqrt() - 0.5).abs()
        }),
        Object::Teapot => teapot_deviation(level),
    };
    if let Ok(mut c) = cache.lock() {
        c.insert((object, level), d);
    }
    d
}

fn len(p: [f64; 3]) -> f64 {
    (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt()
}

fn surface_deviation(mesh: &Mesh, distance: impl Fn([f64; 3]) -> f64) -> f64 {
    let pos = |i: u32| mesh.vertices[i as usize].position.map(f64::from);
    let mut worst = 0.0f64;
    for tri in mesh.indices.chunks_exact(3) {
        let (a, b, c) = (pos(tri[0]), pos(tri[1]), pos(tri[2]));
        // A 5x5 barycentric grid covers the edge midpoints, the centroid and the deepest point well.
        for i in 0..=4 {
            for j in 0..=(4 - i) {
                let (u, v) = (i as f64 / 4.0, j as f64 / 4.0);
                let w = 1.0 - u - v;
                let p = [0, 1, 2].map(|k| u * a[k] + v * b[k] + w * c[k]);
                worst = worst.max(distance(p));
            }
        }
    }
    worst
}

fn teapot_deviation(level: u32) -> f64 {
    let n = level.clamp(2, 1024) as usize;
    let m = 2 * n - 1;
    let (coarse, fine) = (Mesh::teapot(1.0, n as u32), Mesh::teapot(1.0, m as u32));
    let patches = coarse.vertices.len() / (n * n);
    let c = |p: usize, i: usize, j: usize| coarse.vertices[p * n * n + i * n + j].position.map(f64::from);
    let f = |p: usize, i: usize, j: usize| fine.vertices[p * m * m + i * m + j].position.map(f64::from);
    let dist = |a: [f64; 3], b: [f64; 3]| len([a[0] - b[0], a[1] - b[1], a[2] - b[2]]);
    let mid = |a: [f64; 3], b: [f64; 3]| [0, 1, 2].map(|k| (a[k] + b[k]) / 2.0);
    let mut worst = 0.0f64;
    for p in 0..patches {
        for i in 0..n - 1 {
            for j in 0..n - 1 {
                // Quad (i, j)..(i+1, j+1) is split along (i, j)-(i+1, j+1): its midpoint lies on that diagonal.
                worst = worst.max(dist(mid(c(p, i, j), c(p, i + 1, j + 1)), f(p, 2 * i + 1, 2 * j + 1)));
                worst = worst.max(dist(mid(c(p, i, j), c(p, i + 1, j)), f(p, 2 * i + 1, 2 * j)));
                worst = worst.max(dist(mid(c(p, i, j), c(p, i, j + 1)), f(p, 2 * i, 2 * j + 1)));
            }
        }
    }
    worst
}

/// Pixels per object unit at the object's silhouette, for the lab's projection
/// (`gluPerspective(45, w/h, 1, 100)`, `height` rows) with the object centre `distance` away.
pub fn pixels_per_unit(object: Object, distance: f64, height: u32) -> f64 {
    let focal = height.max(1) as f64 / 2.0 / (22.5f64).to_radians().tan();
    let r = bounding_radius(object);
    // The silhouette lies about sqrt(D^2 - R^2) from the eye; never nearer than the near plane.
    let d = (distance * distance - r * r).max(1.0).sqrt();
    focal / d
}

/// Predicted silhouette error in pixels of `level` at `distance`.
pub fn silhouette_error_px(object: Object, level: u32, distance: f64, height: u32) -> f64 {
    deviation(object, level) * pixels_per_unit(object, distance, height)
}

/// The smallest level whose predicted silhouette error is within `budget_px` (deviation falls
/// as the level grows, so a binary search finds it). The cube has only one level.
pub fn choose_level(object: Object, distance: f64, height: u32, budget_px: f64) -> u32 {
    if object == Object::Cube {
        return 0;
    }
    let fits = |level: u32| silhouette_error_px(object, level, distance, height) <= budget_px;
    let max = if object == Object::Teapot { 64 } else { MAX_LEVEL };
    if fits(MIN_LEVEL) {
        return MIN_LEVEL;
    }
    if !fits(max) {
        return max;
    }
    super::least_passing(MIN_LEVEL, max, fits) // fits(MIN_LEVEL) false, fits(max) true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sphere_deviation_matches_geometry() {
        // The deepest point of an inscribed quad-ish triangle is about r(1 - cos(pi/n)).
        for n in [6u32, 12, 24, 48] {
            let d = deviation(Object::Sphere, n);
            let chord = 1.0 - (std::f64::consts::PI / n as f64).cos();
            assert!(d > 0.5 * chord && d < 1.5 * chord, "n={n}: {d} vs {chord}");
        }
    }

    #[test]
    fn deviation_falls_with_level() {
        for object in [Object::Sphere, Object::Torus, Object::Teapot] {
            let (a, b, c) = (deviation(object, 6), deviation(object, 12), deviation(object, 24));
            assert!(a > b && b > c && c > 0.0, "{object:?}: {a} {b} {c}");
            // Second-order convergence: doubling the level divides the error by about 4.
            assert!(a / c > 8.0, "{object:?}: {a} / {c}");
        }
    }

    #[test]
    fn farther_objects_need_fewer_triangles() {
        let near = choose_level(Object::Sphere, 3.0, 360, 0.5);
        let far = choose_level(Object::Sphere, 20.0, 360, 0.5);
        assert!(near > far, "near {near} far {far}");
        let big = choose_level(Object::Torus, 5.0, 1080, 0.5);
        let small = choose_level(Object::Torus, 5.0, 360, 0.5);
        assert!(big > small);
        assert_eq!(choose_level(Object::Cube, 5.0, 360, 0.5), 0);
    }

    #[test]
    fn chosen_level_is_the_smallest_that_fits() {
        for (object, d) in [(Object::Sphere, 5.0), (Object::Torus, 6.0), (Object::Teapot, 4.0)] {
            let level = choose_level(object, d, 360, 0.5);
            assert!(silhouette_error_px(object, level, d, 360) <= 0.5);
            assert!(
                silhouette_error_px(object, level - 1, d, 360) > 0.5,
                "{object:?} {level}"
            );
        }
    }
}
