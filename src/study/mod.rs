//! The speed/accuracy yardsticks, apart from what the labs need at run time: an exact f64 ray
//! caster and its silhouette metric ([`exact`]), image metrics ([`metrics`]) and the CPU simplex
//! noise ([`noise`]). Tests, the trade-off sweep and the "where methods fail" studies use them;
//! [`twist`] (the exact twisted square and the error of a grid) also gives `twist` its
//! `grid=auto`.

pub mod exact;
pub mod metrics;
pub mod noise;
pub mod twist;
