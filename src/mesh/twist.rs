//! The exact picture of seed 002's `twist` and how far the course's per-vertex method is from
//! it. The vertex shader turns each grid vertex q by `twisting · |q|` radians; a turn keeps
//! the radius, so the map is inverted exactly per pixel: p lies in the twisted square when
//! `rotate(p, −twisting · |p|)` lies in [−0.5, 0.5]². The GPU draws straight edges between
//! twisted vertices instead of the spiral arcs they stand for, and the error of a grid is how
//! far those chords leave the arcs ([`grid_error_px`]).

/// Half the side of the course's square ([−0.5, 0.5]²).
const HALF: f64 = 0.5;

/// The finest grid `auto` uses (quads per side: 6·400² = 960,000 vertices).
pub const MAX_GRID: u32 = 400;

/// The course's grid: 100 × 100 quads (60,000 vertices).
pub const COURSE_GRID: u32 = 100;

/// The edge error `auto` allows, in pixels (as seed 000's `--tess auto` allows its silhouette).
pub const DEFAULT_BUDGET_PX: f64 = 0.5;

/// `q` turned by `angle` radians about the origin.
fn rotate([x, y]: [f64; 2], angle: f64) -> [f64; 2] {
    let (s, c) = angle.sin_cos();
    [c * x - s * y, s * x + c * y]
}

/// Where the vertex shader sends grid point `q` (in f64).
pub fn twist(q: [f64; 2], twisting: f64) -> [f64; 2] {
    rotate(q, twisting * q[0].hypot(q[1]))
}

/// Whether clip-space point `p` is inside the exactly twisted square.
pub fn inside(p: [f64; 2], twisting: f64) -> bool {
    let [x, y] = rotate(p, -twisting * p[0].hypot(p[1]));
    x.abs() <= HALF && y.abs() <= HALF
}

/// The exact picture sampled at pixel centres, as the rasterizer samples (row 0 on top):
/// `true` where the twisted square covers the pixel's centre.
pub fn exact_mask(twisting: f64, width: u32, height: u32) -> Vec<bool> {
    let mut mask = Vec::with_capacity((width * height) as usize);
    for j in 0..height {
        for i in 0..width {
            let x = 2.0 * (i as f64 + 0.5) / width as f64 - 1.0;
            let y = 1.0 - 2.0 * (j as f64 + 0.5) / height as f64;
            mask.push(inside([x, y], twisting));
        }
    }
    mask
}

/// Clip space to pixels (x right, y down).
fn to_px([x, y]: [f64; 2], width: u32, height: u32) -> [f64; 2] {
    [(x + 1.0) * 0.5 * width as f64, (1.0 - y) * 0.5 * height as f64]
}

/// Distance from `p` to the segment `a`–`b`.
fn to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
}

/// How far, in pixels of a `width` × `height` picture, the straight edges of an `n` × `n`
/// grid (every edge of every triangle: the sides, the rows, the columns and the diagonals the
/// quads are split along) stray at most from the spiral arcs they stand for, each sampled at a
/// quarter, half and three quarters of its length. The outline alone is not enough: where
/// neighbouring vertices turn by very different angles the inner triangles shear, fold over
/// and cover the gaps between the spiral's arms; an edge that follows its arc within a pixel
/// cannot fold (the twist keeps areas and orientation, so only curvature folds a triangle).
pub fn grid_error_px(n: u32, twisting: f64, width: u32, height: u32) -> f64 {
    let n = n.max(1);
    let size = 2.0 * HALF / n as f64;
    let at = |i: u32, j: u32| [-HALF + i as f64 * size, -HALF + j as f64 * size];
    // Along an edge the radius changes by at most its length, so the turn by at most
    // |twisting| · length: past half a radian three samples cannot speak for the arc, and the
    // grid is too coarse whatever they say.
    if twisting.abs() * size * std::f64::consts::SQRT_2 > 0.5 {
        return f64::INFINITY;
    }
    let sagitta = |a: [f64; 2], b: [f64; 2]| {
        let (ta, tb) = (
            to_px(twist(a, twisting), width, height),
            to_px(twist(b, twisting), width, height),
        );
        [0.25, 0.5, 0.75]
            .iter()
            .map(|&s| {
                let p = [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])];
                to_segment(to_px(twist(p, twisting), width, height), ta, tb)
            })
            .fold(0.0f64, f64::max)
    };
    let mut worst = 0.0f64;
    for i in 0..=n {
        for j in 0..=n {
            let here = at(i, j);
            if i < n {
                worst = worst.max(sagitta(here, at(i + 1, j)));
            }
            if j < n {
                worst = worst.max(sagitta(here, at(i, j + 1)));
            }
            if i < n && j < n {
                worst = worst.max(sagitta(here, at(i + 1, j + 1)));
            }
        }
    }
    worst
}

/// The coarsest grid (quads per side, at most [`MAX_GRID`]) whose edges all follow their arcs
/// within `budget_px` in a `width` × `height` picture ([`grid_error_px`]): `grid=auto`. The error falls
/// as 1/n² (a chord's sagitta), so doubling finds a grid within budget and halving the gap
/// narrows it to the coarsest.
pub fn auto_grid(twisting: f64, width: u32, height: u32, budget_px: f64) -> u32 {
    let ok = |n: u32| grid_error_px(n, twisting, width, height) <= budget_px;
    let mut hi = 1;
    while !ok(hi) {
        if hi >= MAX_GRID {
            return MAX_GRID;
        }
        hi = (hi * 2).min(MAX_GRID);
    }
    super::least_passing(hi / 2, hi, ok) // ok(hi / 2) is false (or hi / 2 is 0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn without_twisting_the_square_is_exact_at_any_grid() {
        assert!(inside([0.49, -0.49], 0.0) && !inside([0.51, 0.0], 0.0));
        assert!(grid_error_px(1, 0.0, 640, 480) < 1e-9);
        assert_eq!(auto_grid(0.0, 640, 480, DEFAULT_BUDGET_PX), 1);
    }

    #[test]
    fn the_inverse_undoes_the_twist() {
        for &t in &[4.25, -13.0, 1e4] {
            for &q in &[[0.3, -0.2], [0.49, 0.49], [-0.1, 0.45]] {
                assert!(inside(twist(q, t), t), "{q:?} at {t}");
            }
            // A point just outside the square stays outside once twisted.
            assert!(!inside(twist([0.52, 0.1], t), t));
        }
    }

    #[test]
    fn the_grid_error_falls_as_one_over_n_squared() {
        let e = |n| grid_error_px(n, 4.25, 640, 480);
        assert!(e(10) > e(20) && e(20) > e(40));
        let ratio = e(20) / e(40);
        assert!(
            (3.5..4.5).contains(&ratio),
            "error ratio when the grid doubles: {ratio}"
        );
    }

    #[test]
    fn auto_picks_the_coarsest_grid_within_budget() {
        for &t in &[1.0, 4.25, 20.0] {
            let n = auto_grid(t, 640, 480, DEFAULT_BUDGET_PX);
            assert!(grid_error_px(n, t, 640, 480) <= DEFAULT_BUDGET_PX);
            assert!(
                n == 1 || grid_error_px(n - 1, t, 640, 480) > DEFAULT_BUDGET_PX,
                "{t}: {n}"
            );
        }
        // The course's default needs far fewer than the course's 100 quads per side.
        assert!(auto_grid(4.25, 640, 480, DEFAULT_BUDGET_PX) < COURSE_GRID / 2);
        // Past what any grid up to MAX_GRID can follow, auto stays at the finest.
        assert_eq!(auto_grid(1e4, 640, 480, DEFAULT_BUDGET_PX), MAX_GRID);
    }
}
