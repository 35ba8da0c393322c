//! Seed 001 `bump` (SPEC §1.11): tangent-space diffuse bump mapping on one quad facing the
//! eye. Each vertex carries a tangent (`attribute vec4 objTangent`); the vertex shader turns
//! the light direction into the tangent frame (T, B = N × T, N), and the fragment shader lights
//! the normal read from a normal map (an egg-crate of 4×4 bumps, SPEC §0.1) with it. The light
//! (blx, bly, blz) = (1.5, 1.5, −2) in eye space sits upper right, 2 units in front of the
//! plane, so the bumps are lit obliquely; diffuse material (0.9, 0.7, 0.5). Normal map:
//! `GL_REPEAT`, `GL_LINEAR`/`GL_LINEAR`, no mipmaps, unit 0.
//!
//! `normmap` (§1.12) is the same lab with a normalization cube map in place of `normalize(L)`.
//!
//! Keys: `←`/`→` blx ∓0.25, `↑`/`↓` bly ±0.25, PageUp/PageDown blz ±0.25; left drag rotates.

use crate::lab::{Material, Recipe, ShaderPair};

use crate::course::seed001::tangent_bump;

/// Seed 001, §1.11.
pub static RECIPE: Recipe = Recipe::new(
    super::info(lab_name!(), "ref001", "bump mapping", tangent_bump::KEYS),
    tangent_bump::PARAMS,
    |cx, p| tangent_bump::build(cx, "bump", p, &MATERIAL, Vec::new()),
);

static MATERIAL: Material = Material::new(&[ShaderPair::new("bump.vert", "bump.frag")]);
