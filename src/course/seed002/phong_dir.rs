//! Seed 002 (Lecture 12) `phong_dir`, SPEC §2.4: Phong shading with a directional light
//! (direction (1,1,1) toward the light, world space), an emission term and the eye at (0,0,5),
//! on `glutSolidTeapot(1.0)` turned by `glRotated(rx, 1,0,0)`; the view is folded into the
//! projection as in `normal_world` ([`crate::course::seed002::geometry`]), so normals and positions
//! are in world space. Depth test on.
//!
//! Course bug kept (SPEC §6.2 #1): the vertex shader computes `position =
//! (gl_ModelViewMatrix * gl_Position).xyz` — the *clip-space* position (GL's, depth −w..w)
//! turned by the model — so the highlight sits where that puts it. `fixpos=1` (key `p`)
//! renders the intent, `(gl_ModelViewMatrix * gl_Vertex).xyz`. The slide stops after the
//! rotation: `glUseProgram` first and the teapot are pinned (#6).
//!
//! The `PhongDir` block (`phong_dir_params.glsl`): `fixpos` is its parameter; the course's
//! material, light and eye and the GL-depth `mvp_gl` (what the bug multiplies) come from the
//! hook.
//!
//! Keys: ↑/↓ rx ±5°; `p` toggles fixpos.

use glam::Mat4;

use crate::lab::{Key::C, KeyRow, Keys, Material, MaterialScene, Recipe, ShaderPair, DOWN, UP};
use crate::params::{ParamSpec, Params};
use crate::render::Derived;

use crate::course::common::FaceOrder;
use crate::course::seed002::geometry::{self, Teapot};

/// `phong_dir`.
pub static RECIPE: Recipe = Recipe::new(
    super::info(
        lab_name!(),
        "ref002",
        "Phong, directional light",
        Keys::rows(
            &[
                KeyRow::step(&[DOWN, UP], "rx", 5.0),
                KeyRow::toggle(&[C('p'), C('P')], "fixpos"),
            ],
            "",
        ),
    ),
    &[&[
        ParamSpec::real("rx", &[0.0], -36000.0, 36000.0, "glRotated about x, degrees (Up/Down)"),
        ParamSpec::flag(
            "fixpos",
            &[0.0],
            "0: position from gl_Position (course bug), 1: from gl_Vertex (p)",
        ),
        crate::course::common::FACES,
    ]],
    |cx, p| {
        let geometry = Teapot::new(
            cx.gpu,
            "phong_dir",
            |p| (model_rx(p.f("rx")), geometry::EYE),
            FaceOrder::FacingFirst,
        );
        MaterialScene::build(cx, p, geometry, &MATERIAL)
    },
);

static MATERIAL: Material = Material::new(&[ShaderPair::new("phong_dir.vert", "phong_dir.frag")]).derive(course);

/// The course's values (SPEC §2.4), and `gl_ModelViewProjectionMatrix` in GL's depth
/// convention for the model.
fn course(p: &Params, c: &mut Derived) {
    c.set("material_ambient", &[0.1, 0.1, 0.1]);
    c.set("material_shininess", &[100.0]);
    c.set("material_diffuse", &[0.5, 0.5, 0.8]);
    c.set("material_specular", &[1.0, 1.0, 1.0]);
    c.set("material_emission", &[0.0, 0.0, 0.0]);
    c.set("light_ambient", &[1.0, 1.0, 1.0]);
    c.set("light_intensity", &[1.0, 1.0, 1.0]);
    c.set("light_direction", &[1.0, 1.0, 1.0]);
    c.set("eye", &geometry::EYE.to_array());
    let mvp_gl = geometry::projection_stack_gl(geometry::EYE) * model_rx(p.f("rx"));
    c.set("mvp_gl", &mvp_gl.to_cols_array());
}

/// The modelview: `glRotated(rx, 1,0,0)` (float, as Mesa's glRotated).
fn model_rx(rx: f32) -> Mat4 {
    geometry::model_zyx(rx, 0.0, 0.0)
}
