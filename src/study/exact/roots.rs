//! Real roots of polynomials on an interval (the torus intersection is a quartic): Sturm-free
//! bracketing by the roots of the derivative, then safeguarded Newton.

/// `c[0] + c[1] x + c[2] x² + ...` by Horner's rule.
pub(super) fn poly_eval(c: &[f64], x: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &ci| acc * x + ci)
}

/// The real roots in `[a, b]` of the polynomial `c` (ascending coefficients, degree at most 4,
/// nonzero leading coefficient), sorted, into `out`; returns how many. Between consecutive
/// roots of the derivative (found the same way) the polynomial is monotonic, so a sign change
/// there brackets exactly one root. With `first_only`, stops at the smallest. A root where the
/// polynomial only touches zero counts only if it evaluates to exactly zero.
pub(super) fn real_roots(c: &[f64], a: f64, b: f64, first_only: bool, out: &mut [f64; 4]) -> usize {
    let n = c.len() - 1;
    if n == 0 {
        return 0;
    }
    if n == 1 {
        let x = -c[0] / c[1];
        if x >= a && x <= b {
            out[0] = x;
            return 1;
        }
        return 0;
    }
    let mut dc = [0.0; 4];
    for i in 0..n {
        dc[i] = (i + 1) as f64 * c[i + 1];
    }
    let dc = &dc[..n];
    let mut crit = [0.0; 4];
    let m = real_roots(dc, a, b, false, &mut crit);
    let mut count = 0;
    let mut x0 = a;
    let mut f0 = poly_eval(c, a);
    if f0 == 0.0 {
        out[0] = a;
        count = 1;
        if first_only {
            return 1;
        }
    }
    let ends = crit[..m].iter().map(|&x| (x, true)).chain(std::iter::once((b, false)));
    for (x1, critical) in ends {
        if x1 <= x0 && critical {
            continue;
        }
        let f1 = poly_eval(c, x1);
        let root = if f1 == 0.0 {
            Some(x1)
        } else if f0 != 0.0 && (f0 < 0.0) != (f1 < 0.0) {
            Some(refine_root(c, dc, x0, x1, f0))
        } else {
            None
        };
        if let Some(x) = root {
            if count < out.len() && (count == 0 || x > out[count - 1]) {
                out[count] = x;
                count += 1;
                if first_only {
                    return count;
                }
            }
        }
        x0 = x1;
        f0 = f1;
    }
    count
}

/// The root of `c` (derivative `dc`) in `[lo, hi]`, where `c(lo)` has the sign of `flo` and
/// `c(hi)` the other: Newton's method kept inside the shrinking bracket, bisecting whenever a
/// Newton step would leave it or shrink it too slowly (`rtsafe`).
pub(super) fn refine_root(c: &[f64], dc: &[f64], mut lo: f64, mut hi: f64, flo: f64) -> f64 {
    let negative_lo = flo < 0.0;
    let mut x = 0.5 * (lo + hi);
    let mut step_old = hi - lo;
    let mut step = step_old;
    let mut f = poly_eval(c, x);
    let mut df = poly_eval(dc, x);
    for _ in 0..200 {
        if f == 0.0 {
            return x;
        }
        if (f < 0.0) == negative_lo {
            lo = x;
        } else {
            hi = x;
        }
        let newton_outside = ((x - hi) * df - f) * ((x - lo) * df - f) > 0.0;
        if newton_outside || (2.0 * f).abs() > (step_old * df).abs() || df == 0.0 {
            step_old = step;
            step = 0.5 * (hi - lo);
            let next = lo + step;
            if next <= lo || next >= hi {
                return next;
            }
            x = next;
        } else {
            step_old = step;
            step = f / df;
            let next = x - step;
            if next == x {
                return x;
            }
            x = next;
        }
        if step.abs() <= f64::EPSILON * x.abs().max(f64::MIN_POSITIVE) {
            return x;
        }
        f = poly_eval(c, x);
        df = poly_eval(dc, x);
    }
    x
}
