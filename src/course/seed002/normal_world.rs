//! Seed 002 (Lecture 12) `normal_world`, SPEC §2.3: the normal as colour, `(n + 1) / 2`, in
//! world space. The view is folded into the projection (`gluPerspective(60, 1, 0.1, 100)` then
//! `gluLookAt(0,0,5, …)` on the projection stack, [`crate::course::seed002::geometry`]), so
//! `gl_NormalMatrix` is the model's alone and the colours follow the teapot's own rotation,
//! never the camera. Model: `glRotated(rz, 0,0,1); glRotated(ry, 0,1,0); glRotated(rx, 1,0,0);
//! glutSolidTeapot(1.0)`. Depth test on.
//!
//! Port addition: the parameter `eye` (default the course's (0, 0, 5)) moves the `gluLookAt`
//! eye around the origin, to show that the colours belong to the surface, not to the view.
//!
//! Keys: `x`/`X`, `y`/`Y`, `z`/`Z`: rx, ry, rz ∓/±5°.

use glam::Vec3;

use crate::lab::{Key::C, KeyRow, Keys, Material, MaterialScene, Recipe, ShaderPair};
use crate::params::ParamSpec;

use crate::course::seed002::geometry::{model_zyx, Teapot};

/// Bound on the angles (a held key must not reach float precision trouble).
const TURNS: f64 = 36000.0;

/// `normal_world`: the shaders read the Transform block alone.
pub static RECIPE: Recipe = Recipe::new(
    super::info(
        lab_name!(),
        "ref002",
        "normal as colour, world space",
        Keys::rows(
            &[
                KeyRow::step(&[C('x'), C('X')], "rx", 5.0),
                KeyRow::step(&[C('y'), C('Y')], "ry", 5.0),
                KeyRow::step(&[C('z'), C('Z')], "rz", 5.0),
            ],
            "",
        ),
    ),
    &[&[
        ParamSpec::real(
            "rx",
            &[0.0],
            -TURNS,
            TURNS,
            "glRotated about x, degrees (x/X), turns first",
        ),
        ParamSpec::real("ry", &[0.0], -TURNS, TURNS, "glRotated about y, degrees (y/Y)"),
        ParamSpec::real(
            "rz",
            &[0.0],
            -TURNS,
            TURNS,
            "glRotated about z, degrees (z/Z), turns last",
        ),
        ParamSpec::real(
            "eye",
            &[0.0, 0.0, 5.0],
            -100.0,
            100.0,
            "port study: gluLookAt eye, looking at the origin (colours stay world-space)",
        ),
        crate::course::common::FACES,
    ]],
    |cx, p| {
        let geometry = Teapot::new(
            cx.gpu,
            "normal_world",
            |p| {
                (
                    model_zyx(p.f("rx"), p.f("ry"), p.f("rz")),
                    Vec3::from_array(p.v3("eye")),
                )
            },
            crate::course::common::FaceOrder::Mesh,
        );
        MaterialScene::build(cx, p, geometry, &MATERIAL)
    },
);

static MATERIAL: Material = Material::new(&[ShaderPair::new("normal_world.vert", "normal_world.frag")]);
