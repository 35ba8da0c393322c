//! Exercise 2, normal → RGB (`Lab05-2`): `normalize(gl_NormalMatrix * gl_Normal)` in eye space
//! as colour; negative components clamp to 0. Keys: `1`-`4` objects, mouse drag rotates.

use crate::course::common::FaceOrder;
use crate::lab::{Material, MaterialScene, Recipe, ShaderPair};
use crate::mesh::tess::Object;

use crate::course::seed000::geometry::{Solid, PARAMS_000};
use crate::course::seed000::GEOMETRY_KEYS;

/// The face order by object ([`GlutGeometry::face_order`](super::geometry::GlutGeometry::face_order)):
/// the torus and the teapot facing the eye first, which draws the same pixels and shades fewer fragments;
/// the other objects in mesh order, where no order measured faster (figures: `docs/speed.md`,
/// "Face orders").
const AUTO: &[(Object, FaceOrder)] = &[
    (Object::Torus, FaceOrder::FacingFirst),
    (Object::Teapot, FaceOrder::FacingFirst),
];

/// Exercise 2: the geometry and one shader pair, no uniforms of its own.
pub static RECIPE: Recipe = Recipe::new(
    super::info(lab_name!(), "Lab05-2", "normal to RGB", GEOMETRY_KEYS),
    &[PARAMS_000],
    |cx, p| {
        let geometry = Solid::new(cx.gpu, cx.name, AUTO);
        MaterialScene::build(cx, p, geometry, &MATERIAL)
    },
);

static MATERIAL: Material = Material::new(&[ShaderPair::new("normal_rgb.vert", "normal_rgb.frag")]);
