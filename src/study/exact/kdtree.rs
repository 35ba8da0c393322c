//! An implicit 2-d tree over silhouette points, for nearest-point distances.

/// Arranges `points` as an implicit 2-d tree: the median (on x at even depths, y at odd) in the
/// middle, the smaller half before it, the larger after.
pub(super) fn kd_build(points: &mut [[f64; 2]], depth: usize) {
    if points.len() <= 1 {
        return;
    }
    let axis = depth % 2;
    let mid = points.len() / 2;
    points.select_nth_unstable_by(mid, |a, b| a[axis].total_cmp(&b[axis]));
    let (left, right) = points.split_at_mut(mid);
    kd_build(left, depth + 1);
    kd_build(&mut right[1..], depth + 1);
}

/// Lowers `best` (a squared distance) to the squared distance from `q` to the nearest point of
/// a tree built by [`kd_build`] if that is nearer.
pub(super) fn kd_nearest(points: &[[f64; 2]], depth: usize, q: [f64; 2], best: &mut f64) {
    if points.is_empty() {
        return;
    }
    let mid = points.len() / 2;
    let p = points[mid];
    let d2 = (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2);
    if d2 < *best {
        *best = d2;
    }
    let axis = depth % 2;
    let diff = q[axis] - p[axis];
    let (near, far) = if diff < 0.0 {
        (&points[..mid], &points[mid + 1..])
    } else {
        (&points[mid + 1..], &points[..mid])
    };
    kd_nearest(near, depth + 1, q, best);
    if diff * diff < *best {
        kd_nearest(far, depth + 1, q, best);
    }
}
