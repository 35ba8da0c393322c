//! Exercise 1, position → RGB (`Lab05-1`): each vertex's colour is `normalize(gl_Vertex.zyxw)
//! + 0.5` — a 4-component normalize with w = 1 — so the object shows its position as colour,
//! z as red, y as green, x as blue; values above 1 clamp. Keys: `1`-`4` objects, mouse drag rotates.

use crate::course::common::FaceOrder;
use crate::lab::{Material, MaterialScene, Recipe, ShaderPair};
use crate::mesh::tess::Object;

use crate::course::seed000::geometry::{Solid, PARAMS_000};
use crate::course::seed000::GEOMETRY_KEYS;

/// The face order of `faces=auto`: the torus and the teapot facing the eye first, which draws
/// the same pixels and shades fewer fragments; the others in mesh order, where no order measured
/// faster (figures: `docs/speed.md`, "Face orders").
const AUTO: &[(Object, FaceOrder)] = &[
    (Object::Torus, FaceOrder::FacingFirst),
    (Object::Teapot, FaceOrder::FacingFirst),
];

/// Exercise 1: seed 000's GLUT solid drawn by one shader pair with no uniforms of its own.
pub static RECIPE: Recipe = Recipe::new(
    super::info(lab_name!(), "Lab05-1", "position to RGB", GEOMETRY_KEYS),
    &[PARAMS_000],
    |cx, p| MaterialScene::build(cx, p, Solid::new(cx.gpu, cx.name, AUTO), &MATERIAL),
);

static MATERIAL: Material = Material::new(&[ShaderPair::new("position_rgb.vert", "position_rgb.frag")]);
