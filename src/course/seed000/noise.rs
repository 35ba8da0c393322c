//! Exercise 4, simplex noise (`Lab05-4`): Ashima/McEwan 3D simplex noise evaluated per
//! fragment at the object-space position plus `time`, shown as `shade * |snoise|`; it animates
//! with a clock in seconds. Keys: `R/r G/g B/b` ±0.05 on the shade colour (clamped to [0, 1]),
//! `1`-`4` objects, mouse drag rotates, Space pauses the clock.

use crate::course::common::FaceOrder;
use crate::lab::{Keys, LabInfo, Material, MaterialScene, Recipe, ShaderPair};
use crate::mesh::tess::Object;
use crate::params::{ParamSpec, Params};
use crate::render::Derived;

use crate::course::seed000::geometry::{title_000, Solid, PARAMS_000};
use crate::course::seed000::{noise_time, NOISE_PARAMS, SHADE_KEYS};

/// The face order by object ([`GlutGeometry::face_order`](super::geometry::GlutGeometry::face_order)):
/// the torus and the teapot facing the eye first, which draws the same pixels and shades fewer fragments;
/// the other objects in mesh order, where no order measured faster (figures: `docs/speed.md`,
/// "Face orders").
const AUTO: &[(Object, FaceOrder)] = &[
    (Object::Torus, FaceOrder::FacingFirst),
    (Object::Teapot, FaceOrder::FacingFirst),
];

/// Exercise 4: the `NoiseParams` block's `shade` is a parameter, its `time` the wrapped clock.
pub static RECIPE: Recipe = Recipe::new(
    super::info(
        lab_name!(),
        "Lab05-4",
        "simplex noise",
        Keys::rows(SHADE_KEYS, "1-4: objects; left drag rotates; Space pauses the clock"),
    ),
    &[
        &[ParamSpec::real(
            "shade",
            &[1.0, 1.0, 1.0],
            -1e30,
            1e30,
            "colour of the noise (R/r G/g B/b, keys within 0..1)",
        )],
        NOISE_PARAMS,
        PARAMS_000,
    ],
    |cx, p| MaterialScene::build(cx, p, Solid::new(cx.gpu, cx.name, AUTO).titled(title), &MATERIAL),
)
.animated();

static MATERIAL: Material = Material::new(&[ShaderPair::new("noise.vert", "noise.frag")])
    .derive(|p: &Params, c: &mut Derived| c.set("time", &[noise_time(p)]));

/// The original's title: its state summary.
fn title(info: &LabInfo, p: &Params) -> String {
    let [r, g, b] = p.v3("shade");
    title_000(
        info,
        p,
        &format!("shade ({r:.2},{g:.2},{b:.2}) time {:.1}", noise_time(p)),
        "",
    )
}
