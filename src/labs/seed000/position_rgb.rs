//! Exercise 1, position → RGB (`Lab05-1`): each vertex's colour is `normalize(gl_Vertex.zyxw)
//! + 0.5` — a 4-component normalize with w = 1 — so the object shows its position as colour,
//! z as red, y as green, x as blue; values above 1 clamp. Keys: `1`-`4` objects, mouse drag rotates.

use crate::lab::{Material, MaterialScene, Recipe, ShaderPair};
use crate::labs::common::FaceOrder;
use crate::tess::Object;

use crate::labs::seed000::stage::{Solid, PARAMS_000};
use crate::labs::seed000::STAGE_KEYS;

/// The face order by object ([`GlutGeometry::face_order`]; same pixels, fewer fragments shaded).
/// Measured at the bench view (rotate 30,45,0; 7 alternating pairs, wall time of the new order
/// over the old): issue 14's `outside_first` against mesh order, torus 0.97-0.98, sphere
/// 1.04-1.12, teapot 1.00-1.09, cube 0.99-1.00; issue 22's `facing_first` against the order
/// before it, torus 0.956 (against outside_first), teapot 0.955, sphere 1.032 (mesh order
/// already draws its near half first), cube 0.934 (not used: the cube ties at some views).
const AUTO: &[(Object, FaceOrder)] = &[
    (Object::Torus, FaceOrder::FacingFirst),
    (Object::Teapot, FaceOrder::FacingFirst),
];

/// Exercise 1: the stage and one pass, no uniforms of its own.
pub static RECIPE: Recipe = Recipe::new(
    super::info("position_rgb", "Lab05-1", "position to RGB", STAGE_KEYS),
    &[PARAMS_000],
    |cx, p| {
        let stage = Solid::new(cx.gpu, "position_rgb", AUTO);
        MaterialScene::build(cx, p, stage, &MATERIAL)
    },
);

static MATERIAL: Material = Material::new(&[ShaderPair::new("position_rgb.vert", "position_rgb.frag")]);
