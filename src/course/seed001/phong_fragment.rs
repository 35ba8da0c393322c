//! Seed 001 `phong_fragment` (SPEC §1.8): the course's modified Phong (Blinn) lighting; N, L and E are interpolated and the lighting is computed per fragment: the highlight is round.
//! See [`crate::course::seed001::modified_phong`] for the light, the keys and `compare` (both halves side by side).

use crate::lab::Recipe;

use crate::course::seed001::modified_phong::{self, Shading};

/// Seed 001, §1.8.
pub static RECIPE: Recipe = Recipe::new(
    super::info(
        lab_name!(),
        "ref001",
        "modified Phong, per fragment",
        modified_phong::KEYS,
    ),
    modified_phong::PARAMS,
    |cx, _| modified_phong::build(cx, "phong_fragment", Shading::Fragment),
);
