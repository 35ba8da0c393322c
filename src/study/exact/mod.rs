//! An exact CPU reference renderer in f64: the yardstick of the speed/accuracy study.
//!
//! [`ExactScene::render`] ray-casts the *exact* surfaces the lab's meshes approximate — the unit
//! sphere of `glutSolidSphere(1, ..)` and the torus of `glutSolidTorus(0.5, 1, ..)` (tube radius
//! 0.5 around a ring of radius 1 that lies in the object's x-y plane, so the tube circles the z
//! axis, as freeglut's `fghTorus` builds it) — with no mesh at all, and shades every pixel with
//! the formula of `phong.frag` evaluated in f64 at the exact hit point and the exact unit normal.
//!
//! The camera is the Phong exercise's, in ideal f64 arithmetic:
//!
//! * projection `gluPerspective(45, w/h, 1, 100)` (a height of 0 counts as 1, as in
//!   [`crate::camera::lab_projection`]); hits nearer than the near plane or beyond the far plane
//!   are clipped, as the GPU clips them, and the next surface behind is shown (the lab does not
//!   cull faces);
//! * view `gluLookAt(camera.x, 0, camera.z, camera.x, 0, camera.z - 1, 0, 1, 0)`: the original
//!   uses only the x and z of `camera`, so `camera[1]` is ignored;
//! * model `glRotatef(X,1,0,0)·glRotatef(Y,0,1,0)·glRotatef(Z,0,0,1)`, angles in degrees.
//!
//! Pixel `(i, j)` (row `j` counted from the top, as in an image) is sampled once at its centre
//! `(i + 0.5, j + 0.5)` in window coordinates: the ray leaves the eye (the eye-space origin)
//! through that point of the near plane, with GL's y axis up, so row 0 is the top of the view.
//! A pixel whose ray misses is the clear colour `(0.05, 0.1, 0.2)`. Colours are clamped to
//! [0, 1] and quantised as a GPU writes `unorm8`: `(c * 255).round()`.
//!
//! Only the object is drawn: the Phong exercise's light marker (a small white sphere at the
//! light, behind the camera with the default light) is not part of the reference.
//!
//! Besides the image, the module measures renderings against the reference:
//! [`silhouette_error`] (how far, in pixels, wrongly covered or uncovered pixels lie from the
//! exact silhouette) and [`image_error`] (RMSE, maximum error and PSNR).

mod kdtree;
mod roots;
mod vec3;

use image::RgbImage;

use kdtree::{kd_build, kd_nearest};
use roots::real_roots;
use vec3::*;

/// `gluPerspective`'s vertical field of view, degrees.
const FOVY_DEGREES: f64 = 45.0;
/// Near clipping distance.
const NEAR: f64 = 1.0;
/// Far clipping distance.
const FAR: f64 = 100.0;
/// The Phong exercise's clear colour.
const CLEAR: [f64; 3] = [0.05, 0.1, 0.2];
/// `glutSolidSphere(1, ..)`.
const SPHERE_RADIUS: f64 = 1.0;
/// `glutSolidTorus(0.5, 1, ..)`: the tube radius (freeglut's `innerRadius`).
const TORUS_TUBE: f64 = 0.5;
/// `glutSolidTorus(0.5, 1, ..)`: the ring radius, origin to tube centre (`outerRadius`).
const TORUS_RING: f64 = 1.0;

/// The exact surface drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Shape {
    /// The unit sphere at the origin (`glutSolidSphere(1, ..)`).
    Sphere,
    /// The torus of `glutSolidTorus(0.5, 1, ..)`: tube radius 0.5, ring radius 1, the ring in the
    /// object's x-y plane (around the z axis).
    Torus,
}

/// The specular term.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Specular {
    /// `phong.frag`: `pow(max(R·E, 0), shininess)` with `R = normalize(-reflect(L, N))`.
    Phong,
    /// Blinn-Phong: `pow(max(N·H, 0), shininess)` with `H = normalize(L + E)`.
    Blinn,
}

/// Everything the reference renderer needs: the object, its rotation, the camera and the
/// parameters of `phong.frag`, all in f64.
#[derive(Clone, Debug, PartialEq)]
pub struct ExactScene {
    /// The object.
    pub shape: Shape,
    /// `xAngle`, `yAngle`, `zAngle` in degrees (`glRotatef` about x, then y, then z).
    pub angles: [f64; 3],
    /// The eye position; only x and z are used (the original's `gluLookAt` has eye y = 0).
    pub camera: [f64; 3],
    /// `lightPosition`, in eye space.
    pub light_position: [f64; 3],
    /// `Ka`.
    pub ka: f64,
    /// `Kd`.
    pub kd: f64,
    /// `Ks`.
    pub ks: f64,
    /// `shininess`.
    pub shininess: f64,
    /// `ambientColor`.
    pub ambient_color: [f64; 3],
    /// `diffuseColor`.
    pub diffuse_color: [f64; 3],
    /// `specularColor`.
    pub specular_color: [f64; 3],
    /// Phong (as `phong.frag`) or Blinn-Phong specular.
    pub specular: Specular,
}

impl Default for ExactScene {
    /// The Phong exercise's defaults (the `phong` lab's parameter defaults) with
    /// the sphere, no rotation and the camera at (0, 0, 5).
    fn default() -> Self {
        ExactScene {
            shape: Shape::Sphere,
            angles: [0.0; 3],
            camera: [0.0, 0.0, 5.0],
            light_position: [0.0, 1.0, 1.0],
            ka: 0.1,
            kd: 1.0,
            ks: 1.0,
            shininess: 32.0,
            ambient_color: [0.1, 0.1, 0.1],
            diffuse_color: [1.0, 0.5, 0.0],
            specular_color: [1.0, 1.0, 1.0],
            specular: Specular::Phong,
        }
    }
}

/// A ray's first visible intersection with the exact surface, in eye space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// The hit point `v` (eye space; the eye is at the origin, looking down -z).
    pub point: [f64; 3],
    /// The exact outward unit normal `N` there (eye space).
    pub normal: [f64; 3],
}

impl ExactScene {
    /// The ground truth: the scene rendered `width` x `height`, one exact sample per pixel
    /// centre, quantised to 8 bits per channel.
    pub fn render(&self, width: u32, height: u32) -> RgbImage {
        let tracer = Tracer::new(self, width, height);
        let background = CLEAR.map(quantise);
        let rows = par_map(height as usize, |j| {
            let mut row = Vec::with_capacity(width as usize * 3);
            for i in 0..width {
                let rgb = match tracer.trace(i as f64 + 0.5, j as f64 + 0.5) {
                    Some(hit) => self.shade(&hit).map(quantise),
                    None => background,
                };
                row.extend_from_slice(&rgb);
            }
            row
        });
        RgbImage::from_raw(width, height, rows.concat()).expect("the rows fill the image")
    }

    /// Which pixel centres hit the exact surface (row-major, top row first).
    pub fn coverage_mask(&self, width: u32, height: u32) -> Vec<bool> {
        let tracer = Tracer::new(self, width, height);
        par_map(height as usize, |j| {
            (0..width)
                .map(|i| tracer.covers(i as f64 + 0.5, j as f64 + 0.5))
                .collect::<Vec<_>>()
        })
        .concat()
    }

    /// The exact eye-space hit point and normal seen at window position `(px, py)` of a
    /// `width` x `height` view, in pixels from the top-left corner (pixel `(i, j)`'s centre is
    /// `(i + 0.5, j + 0.5)`); `None` where the ray misses or every hit is clipped.
    pub fn hit(&self, width: u32, height: u32, px: f64, py: f64) -> Option<Hit> {
        Tracer::new(self, width, height).trace(px, py)
    }

    /// The colour of `phong.frag` at a hit, before clamping (linear, 0..1 and beyond).
    fn shade(&self, hit: &Hit) -> [f64; 3] {
        let n = hit.normal;
        let v = hit.point;
        let l = normalize(sub(self.light_position, v));
        let e = normalize(scale(v, -1.0));
        let n_dot_l = dot(n, l);
        let base = match self.specular {
            Specular::Phong => {
                // -reflect(L, N) = 2 (N·L) N - L
                let r = normalize(sub(scale(n, 2.0 * n_dot_l), l));
                dot(r, e)
            }
            Specular::Blinn => dot(n, normalize(add(l, e))),
        };
        // A NaN (degenerate half vector) counts as no highlight.
        let base = if base.is_nan() { 0.0 } else { base.max(0.0) };
        let spec = base.powf(self.shininess);
        let diff = n_dot_l.max(0.0);
        std::array::from_fn(|c| {
            self.ka * self.ambient_color[c]
                + self.kd * self.diffuse_color[c] * diff
                + self.ks * self.specular_color[c] * spec
        })
    }
}

/// `c` clamped to [0, 1] and stored as `unorm8`, as a GPU rounds it.
fn quantise(c: f64) -> u8 {
    (c.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// How far a rendered coverage mask is from the exact one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SilhouetteError {
    /// The largest distance, in pixels, from a differing pixel's centre to the exact silhouette
    /// (0 when no pixel differs; infinite when pixels differ but the exact view has no
    /// silhouette at all).
    pub max_px: f64,
    /// The mean of those distances over the differing pixels (0 when none differ).
    pub mean_px: f64,
    /// How many pixels have a coverage different from the exact one.
    pub differing: usize,
}

/// Silhouette error in pixels between a rendered coverage mask (row-major, top row first, as
/// [`ExactScene::coverage_mask`] and [`crate::study::metrics::mask`] give it) and the exact one: for
/// every pixel whose coverage differs, the distance from its centre to the exact silhouette;
/// the maximum, the mean and the number of differing pixels.
///
/// The exact silhouette is located where the exact coverage changes: between pixel centres of
/// different coverage (including one ring of centres just outside the image), each such cell
/// of the centre lattice is resampled on an 8x8 sub-grid and every crossing on the sub-grid is
/// bisected to 3e-5 pixel. Distances are to the nearest of those crossing points, which
/// overestimates the distance to the curve by at most about 0.01 pixel at distances of a
/// quarter pixel and more (at most 1/16 pixel right at the curve). Features thinner than an
/// eighth of a pixel that fall between samples are not seen.
///
/// A mask that is not `width * height` long is an [`Error::Param`](crate::error::Error::Param).
pub fn silhouette_error(
    exact: &ExactScene,
    rendered_mask: &[bool],
    width: u32,
    height: u32,
) -> crate::error::Result<SilhouetteError> {
    let (w, h) = (width as usize, height as usize);
    if rendered_mask.len() != w * h {
        return Err(crate::error::Error::Param(format!(
            "the mask has {} entries, not {width} x {height}",
            rendered_mask.len()
        )));
    }
    let tracer = Tracer::new(exact, width, height);

    // Exact coverage at the pixel centres and one ring around: grid (gi, gj) is the centre of
    // pixel (gi - 1, gj - 1), at window position (gi - 0.5, gj - 0.5).
    let (gw, gh) = (w + 2, h + 2);
    let grid = par_map(gh, |gj| {
        (0..gw)
            .map(|gi| tracer.covers(gi as f64 - 0.5, gj as f64 - 0.5))
            .collect::<Vec<_>>()
    })
    .concat();
    let exact_at = |x: usize, y: usize| grid[(y + 1) * gw + x + 1];

    let differing: Vec<(usize, usize)> = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .filter(|&(x, y)| exact_at(x, y) != rendered_mask[y * w + x])
        .collect();
    if differing.is_empty() {
        return Ok(SilhouetteError {
            max_px: 0.0,
            mean_px: 0.0,
            differing: 0,
        });
    }

    // Cells of the centre lattice whose corners disagree hold the silhouette.
    let mixed: Vec<(usize, usize)> = (0..gh - 1)
        .flat_map(|cj| (0..gw - 1).map(move |ci| (ci, cj)))
        .filter(|&(ci, cj)| {
            let c = grid[cj * gw + ci];
            grid[cj * gw + ci + 1] != c || grid[(cj + 1) * gw + ci] != c || grid[(cj + 1) * gw + ci + 1] != c
        })
        .collect();
    let mut points: Vec<[f64; 2]> = par_map(mixed.len(), |k| {
        let (ci, cj) = mixed[k];
        silhouette_points(&tracer, ci as f64 - 0.5, cj as f64 - 0.5)
    })
    .concat();
    if points.is_empty() {
        return Ok(SilhouetteError {
            max_px: f64::INFINITY,
            mean_px: f64::INFINITY,
            differing: differing.len(),
        });
    }
    kd_build(&mut points, 0);

    let distances = par_map(differing.len(), |k| {
        let (x, y) = differing[k];
        let q = [x as f64 + 0.5, y as f64 + 0.5];
        let mut best = f64::INFINITY;
        kd_nearest(&points, 0, q, &mut best);
        best.sqrt()
    });
    let max_px = distances.iter().copied().fold(0.0, f64::max);
    let mean_px = distances.iter().sum::<f64>() / distances.len() as f64;
    Ok(SilhouetteError {
        max_px,
        mean_px,
        differing: differing.len(),
    })
}

/// Sub-samples per pixel, per axis, when locating the silhouette.
const SUB: usize = 8;

/// Points of the exact silhouette inside the lattice cell `[x0, x0+1] x [y0, y0+1]` (window
/// coordinates): every crossing of the coverage on the edges of an 8x8 sub-grid, bisected.
fn silhouette_points(tracer: &Tracer, x0: f64, y0: f64) -> Vec<[f64; 2]> {
    let step = 1.0 / SUB as f64;
    let n = SUB + 1;
    let pos = |a: usize| a as f64 * step;
    let mut cover = vec![false; n * n];
    for b in 0..n {
        for a in 0..n {
            cover[b * n + a] = tracer.covers(x0 + pos(a), y0 + pos(b));
        }
    }
    // Bisects the segment from p (coverage cp) to q (a different coverage).
    let bisect = |mut p: [f64; 2], mut q: [f64; 2], cp: bool| {
        for _ in 0..12 {
            let m = [0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])];
            if tracer.covers(m[0], m[1]) == cp {
                p = m;
            } else {
                q = m;
            }
        }
        [0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])]
    };
    let mut points = Vec::new();
    for b in 0..n {
        for a in 0..n {
            let c = cover[b * n + a];
            let p = [x0 + pos(a), y0 + pos(b)];
            if a + 1 < n && cover[b * n + a + 1] != c {
                points.push(bisect(p, [x0 + pos(a + 1), p[1]], c));
            }
            if b + 1 < n && cover[(b + 1) * n + a] != c {
                points.push(bisect(p, [p[0], y0 + pos(b + 1)], c));
            }
        }
    }
    points
}

/// Accuracy of an image against the exact one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageError {
    /// Root mean squared error over all pixels and the R, G, B channels, in 0..255 units.
    pub rmse: f64,
    /// The largest absolute difference of any channel of any pixel.
    pub max: u8,
    /// Peak signal-to-noise ratio in dB, `20 log10(255 / rmse)`; infinite for identical images.
    pub psnr: f64,
}

/// Accuracy of `rendered` against `exact`: RMSE (0..255 units over RGB), the maximum per-pixel
/// error (max over channels) and PSNR, as [`crate::study::metrics`] computes them.
/// Images of different sizes are an [`Error::Param`](crate::error::Error::Param).
pub fn image_error(exact: &RgbImage, rendered: &RgbImage) -> crate::error::Result<ImageError> {
    let size_error = || {
        crate::error::Error::Param(format!(
            "cannot compare a {:?} image with a {:?} one",
            exact.dimensions(),
            rendered.dimensions()
        ))
    };
    let mse = crate::study::metrics::mse(exact, rendered).ok_or_else(size_error)?;
    Ok(ImageError {
        rmse: mse.sqrt(),
        max: crate::study::metrics::max_abs_diff(exact, rendered).ok_or_else(size_error)?,
        psnr: crate::study::metrics::psnr(exact, rendered).ok_or_else(size_error)?,
    })
}

/// The exact silhouette radius in pixels of a sphere of radius `radius` whose centre lies on
/// the view axis at `distance` from the eye, in a view `height` pixels high with the lab's
/// projection (`fovy` 45°): `r_px = (h/2) · cot(fovy/2) · r / sqrt(d² - r²)` (the tangent cone
/// of half-angle `asin(r/d)` on the image plane). For tests and adaptive tessellation.
pub fn projected_sphere_radius_px(radius: f64, distance: f64, height: u32) -> f64 {
    let cot = 1.0 / (FOVY_DEGREES / 2.0).to_radians().tan();
    height as f64 / 2.0 * cot * radius / (distance * distance - radius * radius).sqrt()
}

// ------------------------------------------------------------------------------- ray casting

/// A scene prepared for one view size: the rays of window positions and the intersections.
struct Tracer {
    shape: Shape,
    /// Object to eye rotation (row-major): `eye = rotation · object + (-camera.x, 0, -camera.z)`.
    rotation: [[f64; 3]; 3],
    /// The eye in object space.
    origin: [f64; 3],
    /// Near-plane half extents over the near distance: `tan(fovy/2) · aspect` and `tan(fovy/2)`.
    half: [f64; 2],
    /// View size in pixels (height at least 1).
    size: [f64; 2],
}

impl Tracer {
    fn new(scene: &ExactScene, width: u32, height: u32) -> Tracer {
        let height = height.max(1);
        let tan = (FOVY_DEGREES / 2.0).to_radians().tan();
        let aspect = width as f64 / height as f64;
        let rotation = lab_rotation(scene.angles);
        // The eye sits at (camera.x, 0, camera.z) in the world; in object space it is R^T of that.
        let origin = mul_transposed(&rotation, [scene.camera[0], 0.0, scene.camera[2]]);
        Tracer {
            shape: scene.shape,
            rotation,
            origin,
            half: [tan * aspect, tan],
            size: [width as f64, height as f64],
        }
    }

    /// The eye-space ray through window position `(px, py)`, scaled so that its z is -1 (its
    /// parameter is then the eye depth).
    fn ray(&self, px: f64, py: f64) -> [f64; 3] {
        let [w, h] = self.size;
        // (2 px - w) / w is exactly antisymmetric about the centre, so mirrored pixels mirror.
        let ndc_x = (2.0 * px - w) / w;
        let ndc_y = (h - 2.0 * py) / h;
        [ndc_x * self.half[0], ndc_y * self.half[1], -1.0]
    }

    /// Distance along the unit ray (object space) to the first hit within the depth range.
    fn distance(&self, px: f64, py: f64) -> Option<(f64, [f64; 3], [f64; 3])> {
        let eye = self.ray(px, py);
        let len = norm(eye);
        let unit = scale(eye, 1.0 / len);
        let d = mul_transposed(&self.rotation, unit);
        // depth = distance / len: keep depths in [NEAR, FAR].
        let (lo, hi) = (NEAR * len, FAR * len);
        let o = self.origin;
        let t = match self.shape {
            Shape::Sphere => sphere_first_hit(o, d, SPHERE_RADIUS, lo, hi),
            Shape::Torus => torus_first_hit(o, d, lo, hi),
        }?;
        Some((t, unit, d))
    }

    fn covers(&self, px: f64, py: f64) -> bool {
        self.distance(px, py).is_some()
    }

    fn trace(&self, px: f64, py: f64) -> Option<Hit> {
        let (t, unit, d) = self.distance(px, py)?;
        let p = add(self.origin, scale(d, t));
        let n = match self.shape {
            Shape::Sphere => normalize(p),
            Shape::Torus => torus_normal(p),
        };
        Some(Hit {
            point: scale(unit, t),
            normal: normalize(mul(&self.rotation, n)),
        })
    }
}

/// The lab rotation `glRotatef(X,1,0,0)·glRotatef(Y,0,1,0)·glRotatef(Z,0,0,1)` in f64, row-major.
fn lab_rotation(angles: [f64; 3]) -> [[f64; 3]; 3] {
    let [x, y, z] = angles.map(|a| (a * std::f64::consts::PI / 180.0).sin_cos());
    let rx = [[1.0, 0.0, 0.0], [0.0, x.1, -x.0], [0.0, x.0, x.1]];
    let ry = [[y.1, 0.0, y.0], [0.0, 1.0, 0.0], [-y.0, 0.0, y.1]];
    let rz = [[z.1, -z.0, 0.0], [z.0, z.1, 0.0], [0.0, 0.0, 1.0]];
    mat_mul(&mat_mul(&rx, &ry), &rz)
}

/// The smallest root in `[lo, hi]` of `|o + t d|² = r²` (`d` a unit vector).
fn sphere_roots(o: [f64; 3], d: [f64; 3], r: f64) -> Option<(f64, f64)> {
    let b = dot(o, d);
    // r² - (distance from the centre to the line)²: no cancellation between b² and |o|².
    let perp = sub(o, scale(d, b));
    let disc = r * r - dot(perp, perp);
    if disc < 0.0 {
        return None;
    }
    let s = disc.sqrt();
    Some((-b - s, -b + s))
}

fn sphere_first_hit(o: [f64; 3], d: [f64; 3], r: f64, lo: f64, hi: f64) -> Option<f64> {
    let (t0, t1) = sphere_roots(o, d, r)?;
    [t0, t1].into_iter().find(|&t| t >= lo && t <= hi)
}

/// The first hit in `[lo, hi]` of the unit ray `o + t d` with the torus
/// `(sqrt(x² + y²) - R)² + z² = r²`: the quartic
/// `(|p|² + R² - r²)² - 4 R² (x² + y²) = 0`, written about the entry into the bounding sphere
/// (radius R + r) so its coefficients stay small, and solved by isolating its real roots between
/// the roots of its derivatives (each bracket refined by safeguarded Newton to f64 precision).
fn torus_first_hit(o: [f64; 3], d: [f64; 3], lo: f64, hi: f64) -> Option<f64> {
    let (big, small) = (TORUS_RING, TORUS_TUBE);
    let (t0, t1) = sphere_roots(o, d, big + small)?;
    let (lo, hi) = (lo.max(t0), hi.min(t1));
    if lo > hi {
        return None;
    }
    let o = add(o, scale(d, lo));
    let b = dot(o, d);
    let k = dot(o, o) + big * big - small * small;
    let r4 = 4.0 * big * big;
    let quartic = [
        k * k - r4 * (o[0] * o[0] + o[1] * o[1]),
        4.0 * b * k - 2.0 * r4 * (o[0] * d[0] + o[1] * d[1]),
        4.0 * b * b + 2.0 * k - r4 * (d[0] * d[0] + d[1] * d[1]),
        4.0 * b,
        1.0,
    ];
    let mut roots = [0.0; 4];
    let n = real_roots(&quartic, 0.0, hi - lo, true, &mut roots);
    (n > 0).then(|| lo + roots[0])
}

/// The outward unit normal of the torus at `p` (on its surface): from the nearest point of the
/// tube's centre circle to `p`.
fn torus_normal(p: [f64; 3]) -> [f64; 3] {
    let rho = (p[0] * p[0] + p[1] * p[1]).sqrt();
    let centre = [p[0] / rho * TORUS_RING, p[1] / rho * TORUS_RING, 0.0];
    normalize(sub(p, centre))
}

// ----------------------------------------------------------------------------- small helpers

/// `f(0), f(1), ..., f(n-1)`, computed on all cores (scoped threads taking small blocks of
/// indices in turn), in order.
fn par_map<T: Send, F: Fn(usize) -> T + Sync>(n: usize, f: F) -> Vec<T> {
    use std::sync::atomic::{AtomicUsize, Ordering};
    let threads = std::thread::available_parallelism().map_or(1, |t| t.get()).min(n);
    if threads <= 1 {
        return (0..n).map(f).collect();
    }
    let block = (n / (threads * 8)).clamp(1, 64);
    let next = AtomicUsize::new(0);
    let parts: Vec<Vec<(usize, T)>> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..threads)
            .map(|_| {
                s.spawn(|| {
                    let mut done = Vec::new();
                    loop {
                        let start = next.fetch_add(block, Ordering::Relaxed);
                        if start >= n {
                            break done;
                        }
                        for i in start..(start + block).min(n) {
                            done.push((i, f(i)));
                        }
                    }
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
            .collect()
    });
    let mut slots: Vec<Option<T>> = (0..n).map(|_| None).collect();
    for (i, value) in parts.into_iter().flatten() {
        slots[i] = Some(value);
    }
    slots.into_iter().map(|v| v.expect("every index computed")).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::Rgb;

    const W: u32 = 640;
    const H: u32 = 360;

    fn torus() -> ExactScene {
        ExactScene {
            shape: Shape::Torus,
            ..ExactScene::default()
        }
    }

    fn count(mask: &[bool]) -> usize {
        mask.iter().filter(|&&b| b).count()
    }

    /// Window position of an eye-space point.
    fn project(p: [f64; 3], w: u32, h: u32) -> (f64, f64) {
        let tan = (22.5f64).to_radians().tan();
        let aspect = w as f64 / h as f64;
        let ndc_x = p[0] / -p[2] / (tan * aspect);
        let ndc_y = p[1] / -p[2] / tan;
        ((ndc_x + 1.0) * w as f64 / 2.0, (1.0 - ndc_y) * h as f64 / 2.0)
    }

    #[test]
    fn defaults_are_the_phong_exercise() {
        // Test-only: the yardstick must describe the phong lab's defaults.
        let p = (crate::course::PHONG.params)();
        let s = ExactScene::default();
        let close = |a: &[f64], b: &[f32]| a.iter().zip(b).all(|(x, y)| (x - *y as f64).abs() < 1e-6);
        assert!(close(&s.light_position, &p.v3("lightPosition")));
        assert!(close(
            &[s.ka, s.kd, s.ks, s.shininess],
            &[p.f("Ka"), p.f("Kd"), p.f("Ks"), p.f("shininess")]
        ));
        assert!(close(&s.ambient_color, &p.v3("ambientColor")));
        assert!(close(&s.diffuse_color, &p.v3("diffuseColor")));
        assert!(close(&s.specular_color, &p.v3("specularColor")));
        assert!(close(&s.camera, &p.v3("camera")));
        assert!(close(&CLEAR, &[0.05, 0.1, 0.2]));
    }

    #[test]
    fn rotation_matches_the_lab_matrices() {
        for angles in [
            [0.0, 0.0, 0.0],
            [90.0, 0.0, 0.0],
            [30.0, -45.0, 120.0],
            [10.0, 200.0, -70.0],
        ] {
            let ours = lab_rotation(angles);
            let lab =
                crate::camera::lab_rotation(glam::Vec3::new(angles[0] as f32, angles[1] as f32, angles[2] as f32));
            for (i, row) in ours.iter().enumerate() {
                for (j, value) in row.iter().enumerate() {
                    // glam is column-major: element (row i, column j) is col(j)[i].
                    assert!((value - lab.col(j)[i] as f64).abs() < 1e-6, "{angles:?} ({i},{j})");
                }
            }
        }
    }

    #[test]
    fn sphere_silhouette_has_the_projected_radius() {
        let mask = ExactScene::default().coverage_mask(W, H);
        let expected = projected_sphere_radius_px(1.0, 5.0, H);
        assert!((expected - 88.70).abs() < 0.01, "{expected}");
        // Centre row / column: covered runs from the first to the last covered pixel.
        let run = |cells: Vec<bool>| {
            let first = cells.iter().position(|&b| b).unwrap() as f64;
            let last = cells.iter().rposition(|&b| b).unwrap() as f64;
            assert_eq!(
                cells.iter().filter(|&&b| b).count() as f64,
                last - first + 1.0,
                "one run"
            );
            ((last + 1.0 - first) / 2.0, (first + last + 1.0) / 2.0)
        };
        for row in [179, 180] {
            let (radius, centre) = run((0..W).map(|x| mask[(row * W + x) as usize]).collect());
            assert!(
                (radius - expected).abs() <= 1.0,
                "row {row}: radius {radius} vs {expected}"
            );
            assert!((centre - 320.0).abs() <= 0.5, "row {row}: centre {centre}");
        }
        for col in [319, 320] {
            let (radius, centre) = run((0..H).map(|y| mask[(y * W + col) as usize]).collect());
            assert!(
                (radius - expected).abs() <= 1.0,
                "column {col}: radius {radius} vs {expected}"
            );
            assert!((centre - 180.0).abs() <= 0.5, "column {col}: centre {centre}");
        }
        // The area agrees too (a disc of the projected radius, to within the edge pixels).
        let area = std::f64::consts::PI * expected * expected;
        assert!(
            (count(&mask) as f64 - area).abs() < 2.0 * std::f64::consts::PI * expected,
            "{}",
            count(&mask)
        );
    }

    #[test]
    fn hits_lie_on_the_surfaces() {
        for scene in [
            ExactScene::default(),
            torus(),
            ExactScene {
                angles: [35.0, -20.0, 75.0],
                ..torus()
            },
        ] {
            let mut hits = 0;
            for j in (0..H).step_by(7) {
                for i in (0..W).step_by(5) {
                    let Some(hit) = scene.hit(W, H, i as f64 + 0.5, j as f64 + 0.5) else {
                        continue;
                    };
                    hits += 1;
                    assert!((norm(hit.normal) - 1.0).abs() < 1e-12);
                    // Back to object space: eye = R obj - camera.
                    let r = lab_rotation(scene.angles);
                    let p = mul_transposed(&r, add(hit.point, [0.0, 0.0, 5.0]));
                    let n = mul_transposed(&r, hit.normal);
                    match scene.shape {
                        Shape::Sphere => {
                            assert!((norm(p) - 1.0).abs() < 1e-12);
                            assert!(norm(sub(n, p)) < 1e-12);
                        }
                        Shape::Torus => {
                            let rho = (p[0] * p[0] + p[1] * p[1]).sqrt();
                            assert!((((rho - 1.0).powi(2) + p[2] * p[2]).sqrt() - 0.5).abs() < 1e-12);
                            // the normal is the gradient direction of the implicit function
                            let k = dot(p, p) + 1.0 - 0.25;
                            let g =
                                normalize([4.0 * k * p[0] - 8.0 * p[0], 4.0 * k * p[1] - 8.0 * p[1], 4.0 * k * p[2]]);
                            assert!(norm(sub(g, n)) < 1e-9);
                        }
                    }
                    // The normal faces the eye (the first hit from outside is a front face).
                    assert!(dot(hit.normal, hit.point) < 0.0);
                    // The point is on the pixel's ray.
                    let (x, y) = project(hit.point, W, H);
                    assert!((x - (i as f64 + 0.5)).abs() < 1e-9 && (y - (j as f64 + 0.5)).abs() < 1e-9);
                }
            }
            assert!(hits > 100, "{scene:?}");
        }
    }

    #[test]
    fn torus_first_hit_matches_dense_marching() {
        // Brute force: the first sign change of the implicit function along the ray, sampled
        // finely, must agree with the root finder (which must not skip the near tube).
        let scene = ExactScene {
            angles: [60.0, 25.0, 10.0],
            ..torus()
        };
        let tracer = Tracer::new(&scene, W, H);
        let f = |p: [f64; 3]| (dot(p, p) + 0.75).powi(2) - 4.0 * (p[0] * p[0] + p[1] * p[1]);
        let mut checked = 0;
        for j in (0..H).step_by(11) {
            for i in (0..W).step_by(13) {
                let eye = tracer.ray(i as f64 + 0.5, j as f64 + 0.5);
                let d = mul_transposed(&tracer.rotation, normalize(eye));
                let steps = 20_000;
                let (t0, t1) = (3.0, 7.0);
                let mut prev = f(add(tracer.origin, scale(d, t0)));
                let mut brute = None;
                for s in 1..=steps {
                    let t = t0 + (t1 - t0) * s as f64 / steps as f64;
                    let v = f(add(tracer.origin, scale(d, t)));
                    if (v < 0.0) != (prev < 0.0) {
                        brute = Some(t);
                        break;
                    }
                    prev = v;
                }
                let ours = tracer.distance(i as f64 + 0.5, j as f64 + 0.5).map(|h| h.0);
                match (brute, ours) {
                    (Some(b), Some(o)) => {
                        assert!((b - o).abs() <= 2e-4, "({i},{j}): {b} vs {o}");
                        checked += 1;
                    }
                    (None, None) => {}
                    // A grazing ray may dip into the tube between two samples.
                    (None, Some(o)) => {
                        let p = add(tracer.origin, scale(d, o));
                        let n = torus_normal(p);
                        assert!(dot(n, d).abs() < 0.05, "({i},{j}): missed by marching at {o}");
                    }
                    (Some(b), None) => panic!("({i},{j}): marching hits at {b}, the solver misses"),
                }
            }
        }
        assert!(checked > 50);
    }

    #[test]
    fn highlight_is_where_the_reflection_points_at_the_eye() {
        // The Phong highlight R·E = 1 lies where N bisects L and E. By symmetry (light, eye and
        // centre all have x = 0) the point is n = (0, sin θ, cos θ) from the centre (0, 0, -5).
        let light = [0.0, 1.0, 1.0];
        let point = |theta: f64| add([0.0, 0.0, -5.0], [0.0, theta.sin(), theta.cos()]);
        let misfit = |theta: f64| {
            let p = point(theta);
            let h = add(normalize(sub(light, p)), normalize(scale(p, -1.0)));
            theta.sin() * h[2] - theta.cos() * h[1] // (n x h).x
        };
        let (mut lo, mut hi) = (0.0f64, std::f64::consts::FRAC_PI_4);
        assert!(misfit(lo) < 0.0 && misfit(hi) > 0.0);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if misfit(mid) < 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let (hx, hy) = project(point(lo), W, H);
        assert!((hx - 320.0).abs() < 1e-9 && hy < 175.0, "({hx}, {hy})");

        let image = ExactScene::default().render(W, H);
        let (bx, by) = crate::study::metrics::highlight(&image, 0.0);
        let (bx, by) = (bx + 0.5, by + 0.5); // pixel index to pixel centre
        assert!(
            ((bx - hx).powi(2) + (by - hy).powi(2)).sqrt() <= 2.0,
            "brightest ({bx}, {by}), analytic ({hx}, {hy})"
        );
        assert_eq!(*image.get_pixel(bx as u32, by as u32), Rgb([255, 255, 255]));
        // And the exact shading there is the full highlight.
        let hit = ExactScene::default().hit(W, H, hx, hy).unwrap();
        let colour = ExactScene::default().shade(&hit);
        assert!((colour[2] - (0.01 + 1.0)).abs() < 1e-9, "{colour:?}");
    }

    #[test]
    fn background_and_shading_values() {
        let scene = ExactScene::default();
        let image = scene.render(W, H);
        assert_eq!(*image.get_pixel(0, 0), Rgb([13, 26, 51]));
        // The centre of the sphere faces the eye: N = (0,0,1), v = (0,0,-4).
        let hit = scene.hit(W, H, 320.0, 180.0).unwrap();
        assert!(norm(sub(hit.point, [0.0, 0.0, -4.0])) < 1e-12);
        assert!(norm(sub(hit.normal, [0.0, 0.0, 1.0])) < 1e-12);
        let l = normalize([0.0, 1.0, 5.0]);
        let diff = l[2];
        let r = sub(scale([0.0, 0.0, 1.0], 2.0 * diff), l);
        let spec = r[2].powf(32.0);
        let expected = [0.01 + diff + spec, 0.01 + 0.5 * diff + spec, 0.01 + spec];
        let got = scene.shade(&hit);
        for c in 0..3 {
            assert!((got[c] - expected[c]).abs() < 1e-12, "{got:?} vs {expected:?}");
        }
    }

    #[test]
    fn torus_has_a_hole_and_is_symmetric() {
        let mask = torus().coverage_mask(W, H);
        let at = |x: u32, y: u32| mask[(y * W + x) as usize];
        assert!(!at(320, 180) && !at(319, 179), "the hole");
        // The ring: object (±1, 0, 0.5) is eye (±1, 0, -4.5), about 96.6 px from the centre.
        let ring = 1.0 / 4.5 * projected_sphere_radius_px(1.0, 5.0, H) * 24f64.sqrt();
        assert!((ring - 96.57).abs() < 0.01);
        assert!(at(416, 180) && at(223, 180) && at(320, 84) && at(320, 276));
        // Outer edge: (±1.5, 0, 0) at depth 5 → 130 px; nothing beyond.
        assert!(!at(320 + 135, 180) && !at(320 - 136, 180));
        for y in 0..H {
            for x in 0..W / 2 {
                assert_eq!(at(x, y), at(W - 1 - x, y), "({x},{y})");
            }
        }
        for y in 0..H / 2 {
            for x in 0..W {
                assert_eq!(at(x, y), at(x, H - 1 - y), "({x},{y})");
            }
        }
    }

    #[test]
    fn torus_edge_on_covers_much_less() {
        let face = torus().coverage_mask(W, H);
        let edge = ExactScene {
            angles: [90.0, 0.0, 0.0],
            ..torus()
        }
        .coverage_mask(W, H);
        let (nf, ne) = (count(&face), count(&edge));
        assert!((ne as f64) < 0.6 * nf as f64, "edge-on {ne} vs face-on {nf}");
        // Edge-on the ring lies in the x-z plane: the centre is covered (the near side of the
        // ring), and the band is as tall as the tube's near side (radius 0.5 at depth 4: ±54.7 px).
        assert!(edge[(180 * W + 320) as usize]);
        let rows: Vec<u32> = (0..H).filter(|&y| (0..W).any(|x| edge[(y * W + x) as usize])).collect();
        let height = rows.len() as f64;
        let tube = 2.0 * projected_sphere_radius_px(0.5, 4.0, H);
        assert!((height - tube).abs() <= 2.0, "band {height} px, tube {tube} px");
    }

    #[test]
    fn blinn_highlight_is_wider() {
        let highlight_pixels = |specular| {
            let image = ExactScene {
                specular,
                ..ExactScene::default()
            }
            .render(W, H);
            // Blue is ambient 0.01 + specular only (the diffuse colour has no blue).
            image.pixels().filter(|p| p[2] > 128).count()
        };
        let (phong, blinn) = (highlight_pixels(Specular::Phong), highlight_pixels(Specular::Blinn));
        assert!(phong > 10, "{phong}");
        assert!(blinn as f64 > 2.0 * phong as f64, "Blinn {blinn} vs Phong {phong}");
    }

    #[test]
    fn silhouette_error_of_exact_and_dilated_masks() {
        for scene in [ExactScene::default(), torus()] {
            let exact = scene.coverage_mask(W, H);
            let zero = silhouette_error(&scene, &exact, W, H).expect("sizes match");
            assert_eq!(
                zero,
                SilhouetteError {
                    max_px: 0.0,
                    mean_px: 0.0,
                    differing: 0
                }
            );

            // Dilate by one pixel (4-neighbourhood).
            let at =
                |x: i64, y: i64| x >= 0 && y >= 0 && x < W as i64 && y < H as i64 && exact[(y * W as i64 + x) as usize];
            let dilated: Vec<bool> = (0..(W * H) as i64)
                .map(|k| {
                    let (x, y) = (k % W as i64, k / W as i64);
                    at(x, y) || at(x - 1, y) || at(x + 1, y) || at(x, y - 1) || at(x, y + 1)
                })
                .collect();
            let added = count(&dilated) - count(&exact);
            let e = silhouette_error(&scene, &dilated, W, H).expect("sizes match");
            assert_eq!(e.differing, added);
            assert!(e.max_px <= 1.0 + 1e-3 && e.max_px > 0.8, "{e:?}");
            assert!(e.mean_px > 0.3 && e.mean_px < 0.7, "{e:?}");

            // Eroding instead: the removed pixels are inside, also within a pixel.
            let eroded: Vec<bool> = (0..(W * H) as i64)
                .map(|k| {
                    let (x, y) = (k % W as i64, k / W as i64);
                    at(x, y) && at(x - 1, y) && at(x + 1, y) && at(x, y - 1) && at(x, y + 1)
                })
                .collect();
            let e = silhouette_error(&scene, &eroded, W, H).expect("sizes match");
            assert_eq!(e.differing, count(&exact) - count(&eroded));
            assert!(e.max_px <= 1.0 + 1e-3 && e.mean_px > 0.3 && e.mean_px < 0.7, "{e:?}");
        }
    }

    #[test]
    fn silhouette_error_far_off() {
        // A sphere mask shifted 10 pixels right: the worst pixels are about 10 px off.
        let scene = ExactScene::default();
        let exact = scene.coverage_mask(W, H);
        let shifted: Vec<bool> = (0..(W * H) as usize)
            .map(|k| k % W as usize >= 10 && exact[k - 10])
            .collect();
        let e = silhouette_error(&scene, &shifted, W, H).expect("sizes match");
        assert!(e.max_px > 9.0 && e.max_px <= 10.01, "{e:?}");
        // An empty mask: the deepest pixel is the centre, one radius in.
        let empty = vec![false; (W * H) as usize];
        let e = silhouette_error(&scene, &empty, W, H).expect("sizes match");
        assert_eq!(e.differing, count(&exact));
        let r = projected_sphere_radius_px(1.0, 5.0, H);
        assert!((e.max_px - r).abs() < 1.0, "{e:?} vs {r}");
    }

    #[test]
    fn image_error_measures() {
        let image = ExactScene::default().render(64, 36);
        let same = image_error(&image, &image).expect("sizes match");
        assert_eq!(same.rmse, 0.0);
        assert_eq!(same.max, 0);
        assert!(same.psnr.is_infinite() && same.psnr > 0.0);
        let mut other = image.clone();
        other.get_pixel_mut(3, 4)[1] = other.get_pixel(3, 4)[1].wrapping_add(30);
        let e = image_error(&image, &other).expect("sizes match");
        assert_eq!(e.max, 30);
        let rmse = (900.0f64 / (64.0 * 36.0 * 3.0)).sqrt();
        assert!((e.rmse - rmse).abs() < 1e-12);
        assert!((e.psnr - 20.0 * (255.0 / rmse).log10()).abs() < 1e-9);
    }

    #[test]
    fn quartic_roots() {
        // (x-1)(x-2)(x-3)(x-4) = x⁴ - 10x³ + 35x² - 50x + 24
        let c = [24.0, -50.0, 35.0, -10.0, 1.0];
        let mut out = [0.0; 4];
        assert_eq!(real_roots(&c, 0.0, 10.0, false, &mut out), 4);
        for (k, r) in out.iter().enumerate() {
            assert!((r - (k + 1) as f64).abs() < 1e-14, "{out:?}");
        }
        assert_eq!(real_roots(&c, 2.5, 10.0, true, &mut out), 1);
        assert!((out[0] - 3.0).abs() < 1e-14);
        // x⁴ + 1 has none.
        assert_eq!(real_roots(&[1.0, 0.0, 0.0, 0.0, 1.0], -5.0, 5.0, false, &mut out), 0);
    }

    #[test]
    fn close_to_the_original_program() {
        // tests/reference holds the original C/GLUT program's images (Mesa llvmpipe, 24x24
        // meshes). The exact reference differs from them only by the tessellation: silhouettes
        // within the polygons' sagitta (r (1 - cos(pi/24)): 0.76 px for the sphere, 1.13 px for
        // the torus's outer edge) plus rasterisation, and shading close to it. Blinn-Phong is
        // further away: the lab's formula is Phong's.
        for (shape, name, min_psnr, max_px) in
            [(Shape::Sphere, "sphere", 40.0, 1.0), (Shape::Torus, "torus", 33.0, 1.5)]
        {
            let path = format!(
                "{}/tests/reference/lab3_{name}_x0_y0_t0.png",
                env!("CARGO_MANIFEST_DIR")
            );
            let original = image::open(&path).expect("reference image").to_rgb8();
            let scene = ExactScene {
                shape,
                ..ExactScene::default()
            };
            let phong = image_error(&scene.render(W, H), &original).expect("sizes match");
            let blinn = image_error(
                &ExactScene {
                    specular: Specular::Blinn,
                    ..scene.clone()
                }
                .render(W, H),
                &original,
            )
            .expect("sizes match");
            assert!(phong.psnr >= min_psnr, "{name}: {phong:?}");
            assert!(
                blinn.psnr < phong.psnr - 5.0,
                "{name}: Blinn {blinn:?}, Phong {phong:?}"
            );
            let background = *original.get_pixel(0, 0);
            assert_eq!(background.0, CLEAR.map(quantise));
            let mask = crate::study::metrics::mask(&original, background.0, 0);
            let e = silhouette_error(&scene, &mask, W, H).expect("sizes match");
            assert!(e.max_px <= max_px && e.mean_px < 0.6, "{name}: {e:?}");
        }
    }

    /// Set in the child that [`timing_640x360`] runs to do the timed work alone.
    const TIMING_CHILD: &str = "SHADERLAB_EXACT_TIMING_CHILD";

    /// The render and the silhouette search of both scenes at 640x360, checked.
    fn timed_work() {
        for scene in [ExactScene::default(), torus()] {
            let image = scene.render(W, H);
            let mask = crate::study::metrics::mask(&image, CLEAR.map(quantise), 0);
            assert_eq!(mask, scene.coverage_mask(W, H));
            // A mask one pixel too wide, so that the silhouette is located and searched.
            let wide: Vec<bool> = (0..mask.len())
                .map(|k| mask[k] || (k % W as usize > 0 && mask[k - 1]))
                .collect();
            let e = silhouette_error(&scene, &wide, W, H).expect("sizes match");
            eprintln!("{:?}: silhouette_error {e:?}", scene.shape);
        }
    }

    /// Not a benchmark: a guard that the reference stays usable (generous for debug builds).
    /// The work runs in a child of its own (this test alone, in this test binary), whose CPU
    /// seconds over all its threads are the measure: the tests beside it in this process, and a
    /// busy machine, would inflate the process's own and the wall clock.
    #[test]
    fn timing_640x360() {
        if std::env::var_os(TIMING_CHILD).is_some() {
            timed_work();
            return;
        }
        let exe = std::env::current_exe().expect("the test binary");
        let mut child = std::process::Command::new(exe)
            .args(["--exact", "study::exact::tests::timing_640x360", "--test-threads", "1"])
            .env(TIMING_CHILD, "1")
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .expect("the test binary runs");
        let read = |mut pipe: Box<dyn std::io::Read + Send>| {
            std::thread::spawn(move || {
                let mut text = String::new();
                let _ = pipe.read_to_string(&mut text);
                text
            })
        };
        let stdout = read(Box::new(child.stdout.take().expect("piped")));
        let stderr = read(Box::new(child.stderr.take().expect("piped")));
        let (success, cpu) = child_cpu(child);
        let (stdout, stderr) = (stdout.join().expect("stdout"), stderr.join().expect("stderr"));
        assert!(
            success && stdout.contains("1 passed"),
            "the timed child:\n{stdout}\n{stderr}"
        );
        eprintln!("{stderr}render and silhouette search of both scenes: {cpu:.1} s of CPU");
        assert!(cpu < 20.0, "{cpu:.1} s of CPU");
    }

    /// Waits for `child`: whether it succeeded, and the CPU seconds (user + system, all its
    /// threads) it used.
    #[cfg(target_os = "linux")]
    #[allow(clippy::zombie_processes)] // waited for with wait4, which clippy does not see
    fn child_cpu(child: std::process::Child) -> (bool, f64) {
        let mut status = 0;
        // SAFETY: a zeroed rusage for wait4 to fill; the pid is this test's unwaited child.
        let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
        let pid = child.id() as libc::pid_t;
        // SAFETY: as above.
        let waited = unsafe { libc::wait4(pid, &mut status, 0, &mut usage) };
        assert_eq!(waited, pid, "wait4: {}", std::io::Error::last_os_error());
        let seconds = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 / 1e6;
        (
            libc::WIFEXITED(status) && libc::WEXITSTATUS(status) == 0,
            seconds(usage.ru_utime) + seconds(usage.ru_stime),
        )
    }

    /// Elsewhere, the wall clock stands in for the CPU.
    #[cfg(not(target_os = "linux"))]
    fn child_cpu(mut child: std::process::Child) -> (bool, f64) {
        let start = std::time::Instant::now();
        let status = child.wait().expect("wait");
        (status.success(), start.elapsed().as_secs_f64())
    }
}
