//! Geometry on the CPU, no GPU code: the general [`mesh`] types, GLUT's solids bit for bit
//! ([`glut`]) and their tessellation levels ([`tess`]), Wavefront OBJ models ([`obj`]), the
//! procedural textures and their mipmaps ([`images`]), the lectures' hand-made meshes
//! ([`shapes`]) and seed 002's twisted square, exactly ([`twist`]).

pub mod glut;
pub mod images;
pub mod mesh;
pub mod obj;
pub mod shapes;
pub mod tess;
pub mod twist;

/// The least `n` in `lo + 1 ..= hi` for which `ok(n)` holds, given `ok(lo)` false (or `lo` not
/// a candidate) and `ok(hi)` true, by bisection: the automatic grids and tessellation levels
/// search for the coarsest one within an error budget this way.
pub(crate) fn least_passing(mut lo: u32, mut hi: u32, ok: impl Fn(u32) -> bool) -> u32 {
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if ok(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}
