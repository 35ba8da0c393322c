//! Seed 001 `toon` (SPEC §1.6): the course's non-photorealistic shading. Per vertex, yellow
//! where the light meets the surface within 60° (`dot(L, N) > 0.5`), red elsewhere, black where
//! the surface is seen edge on (`|dot(E, N)| < 0.1`); the colours blend across triangles, and
//! the black silhouette appears only at vertices that fall in the band (course behaviour).
//! Light (2, 2, 2) in eye space.
//!
//! Keys: light keys (`←→↑↓`, PageUp/PageDown; `h`/`H` shininess, unused here); `1`-`4` objects;
//! left drag rotates.

use glam::Vec3;

use crate::lab::{Keys, Material, MaterialScene, Recipe, ShaderPair};

use crate::course::seed001::geometry::{torus_facing_first, SolidGeometry, OBJECT, ROTATION, TESS};
use crate::course::seed001::gl_light::{Lit, COURSE, COURSE_KEYS};

/// Seed 001, §1.6: the Transform and GlLight blocks come from the geometry.
pub static RECIPE: Recipe = Recipe::new(
    super::info(
        lab_name!(),
        "ref001",
        "toon shading",
        Keys::rows(&COURSE_KEYS, "1-4: objects; left drag rotates"),
    ),
    &[OBJECT, ROTATION, COURSE.params, TESS],
    |cx, p| {
        let mut geometry = SolidGeometry::new(cx.gpu, cx.name, Vec3::new(0.0, 0.0, 4.0));
        geometry.auto = torus_facing_first;
        MaterialScene::build(cx, p, Lit::new(cx.gpu, cx.name, &COURSE, geometry), &MATERIAL)
    },
);

static MATERIAL: Material = Material::new(&[ShaderPair::new("toon.vert", "pass_color.frag")]);
