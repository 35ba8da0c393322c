//! Exercise 2, normal → RGB (`Lab05-2`): `normalize(gl_NormalMatrix * gl_Normal)` in eye space
//! as colour; negative components clamp to 0. Keys: `1`-`4` objects, mouse drag rotates.

use crate::lab::{Material, MaterialScene, Recipe, ShaderPair};
use crate::labs::common::FaceOrder;
use crate::tess::Object;

use crate::labs::seed000::stage::{Solid, PARAMS_000};
use crate::labs::seed000::STAGE_KEYS;

/// The face order by object ([`GlutGeometry::face_order`]; same pixels, fewer fragments shaded).
/// Measured at the bench view (rotate 30,45,0; 7 alternating pairs, wall time of the new order
/// over the old): issue 14's `outside_first` against mesh order, torus 0.97-0.98, sphere
/// 1.04-1.12, teapot 1.00-1.09, cube 0.99-1.00; issue 22's `facing_first`, torus 0.946 (against
/// outside_first), teapot 0.973; sphere and cube stay in mesh order (see position_rgb).
const AUTO: &[(Object, FaceOrder)] = &[
    (Object::Torus, FaceOrder::FacingFirst),
    (Object::Teapot, FaceOrder::FacingFirst),
];

/// Exercise 2: the stage and one pass, no uniforms of its own.
pub static RECIPE: Recipe = Recipe::new(
    super::info("normal_rgb", "Lab05-2", "normal to RGB", STAGE_KEYS),
    &[PARAMS_000],
    |cx, p| {
        let stage = Solid::new(cx.gpu, "normal_rgb", AUTO);
        MaterialScene::build(cx, p, stage, &MATERIAL)
    },
);

static MATERIAL: Material = Material::new(&[ShaderPair::new("normal_rgb.vert", "normal_rgb.frag")]);
