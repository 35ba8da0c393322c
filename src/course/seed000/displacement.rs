//! Exercise 5, displacement (`Lab05-5`): each vertex moves along its normal by simplex noise
//! of its direction (`snoise(normalize(v)*2 + time)`) times `clamp(displacement, 0, 1)`, and is
//! coloured `shade * clamp(noise, 0, 1)`. On GLUT's meshes the shapes look jagged, and the cube
//! and teapot crack open where vertices share a position but not a normal — as in the original.
//! `--set smooth=1` (a port addition) welds shared vertices and averages their normals, which
//! closes the cracks. Keys: `[`/`]` displacement ∓0.01 (clamped to [0, 1]), `R/r G/g B/b` ±0.05
//! on the shade, `1`-`4` objects, mouse drag rotates, Space pauses the clock.

use crate::course::common::FaceOrder;
use crate::lab::{Key::C, KeyRow, Keys, LabInfo, Material, MaterialScene, Recipe, ShaderPair};
use crate::mesh::tess::Object;
use crate::params::{ParamSpec, Params};
use crate::render::Derived;

use crate::course::seed000::geometry::{title_000, Solid, PARAMS_000};
use crate::course::seed000::{noise_time, NOISE_PARAMS, SHADE_KEYS};

/// The face order by object ([`GlutGeometry::face_order`](super::geometry::GlutGeometry::face_order)):
/// the torus facing the eye first, which draws the same pixels and shades fewer fragments;
/// the other objects in mesh order, where no order measured faster (figures: `docs/speed.md`,
/// "Face orders").
const AUTO: &[(Object, FaceOrder)] = &[(Object::Torus, FaceOrder::FacingFirst)];

/// `[`/`]` on the strength, then the shade keys.
const KEYS: &[KeyRow] = &[
    KeyRow::clamped(&[C('['), C(']')], "displacement", 0.01, 0.0, 1.0),
    SHADE_KEYS[0],
    SHADE_KEYS[1],
    SHADE_KEYS[2],
];

/// Exercise 5: the `DisplacementParams` block's `shade` and `displacement` are parameters, its
/// `time` the wrapped clock; `smooth` is the geometry's ([`Solid`]).
pub static RECIPE: Recipe = Recipe::new(
    super::info(
        lab_name!(),
        "Lab05-5",
        "displacement",
        Keys::rows(KEYS, "1-4: objects; left drag rotates; Space pauses the clock"),
    ),
    &[
        &[
            ParamSpec::real(
                "shade",
                &[1.0, 1.0, 1.0],
                -1e30,
                1e30,
                "colour of the noise (R/r G/g B/b, keys within 0..1)",
            ),
            ParamSpec::real(
                "displacement",
                &[0.5],
                -1e30,
                1e30,
                "strength ([ / ], keys within 0..1; the shader clamps)",
            ),
            ParamSpec::flag(
                "smooth",
                &[0.0],
                "port: weld shared vertices and average normals (no cracks)",
            ),
        ],
        NOISE_PARAMS,
        PARAMS_000,
    ],
    |cx, p| {
        let geometry = Solid::new(cx.gpu, cx.name, AUTO).titled(title);
        MaterialScene::build(cx, p, geometry, &MATERIAL)
    },
)
.animated();

static MATERIAL: Material = Material::new(&[ShaderPair::new("displacement.vert", "displacement.frag")])
    .derive(|p: &Params, c: &mut Derived| c.set("time", &[noise_time(p)]));

/// The original's title: its state summary.
fn title(info: &LabInfo, p: &Params) -> String {
    let [r, g, b] = p.v3("shade");
    let summary = format!(
        "displacement {:.2} shade ({r:.2},{g:.2},{b:.2}) time {:.1}",
        p.f("displacement"),
        noise_time(p)
    );
    let smooth = if p.on("smooth") { " | smooth" } else { "" };
    title_000(info, p, &summary, "") + smooth
}
