//! The speed/accuracy yardsticks, apart from what the labs need at run time: an exact f64 ray
//! caster and its silhouette metric ([`exact`]), image metrics ([`metrics`]) and the CPU simplex
//! noise ([`noise`]). Tests, the trade-off sweep and the "where methods fail" studies use them;
//! the exact twisted square ([`twist`]) lives with the geometry, as the `twist` lab's
//! `grid=auto` needs it at run time.

pub mod exact;
pub mod metrics;
pub mod noise;
pub use crate::mesh::twist;
