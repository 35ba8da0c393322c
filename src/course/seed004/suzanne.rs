//! The exercises on the model ([`Model`]), three families, each a recipe builder and a scene
//! builder that an exercise calls with its name and its shaders or shading model:
//!
//! - normals as colour (4.1–4.3, [`colour`], [`draw`]): one shader pair, no uniforms but the matrices;
//! - textured (4.4, 4.5, [`textured`], [`sample`]): the vertex shader of 4.2 on the
//!   vertex-normal VBO (pinned: the exercises follow "Smooth Suzanne") and a fragment shader
//!   sampling unit 0, which holds the checker (`tex=0`) or the "BMP" texture (`tex=1`), each
//!   with the course's texture parameters; key `t` toggles them;
//! - lit (4.7 flat, 4.8 Gouraud, 4.9 Phong, [`lit`], [`shade`]): one light in eye space,
//!   ambient + diffuse + specular (R·V) with white light, clamped. Flat runs the Gouraud
//!   shaders with `flat` interpolation on the face-normal VBO (each triangle lit at its first
//!   vertex); Gouraud and Phong draw the vertex-normal VBO. Each exercise starts with its own
//!   model; keys `1`/`2`/`3` switch between the three, as in the course's program. The `Light`
//!   block (`suzanne_light.glsl`) is filled by name: `shininess` is its parameter, `Ka` =
//!   (ka, ka, ka, 1), `Kd` = (kdr, kdg, kdb, 1), `Ks` = (ks, ks, ks, 1) and `lightpos` =
//!   (lightx, lighty, lightz) are computed ([`light`]).

use crate::error::Result;
use crate::lab::{
    BuildContext, FilesTaken, Key::C, KeyRow, Keys, Material, MaterialScene, Recipe, Scene, ShaderPair, DOWN, LEFT,
    PAGE_DOWN, PAGE_UP, RIGHT, UP,
};
use crate::params::{ParamSpec, Params};
use crate::render::Derived;

use super::geometry::{Model, Normals, ANGLES};
use super::gl_textures::{self, Sampled, TexParams};
use super::info;
use crate::course::common::FaceOrder;

/// How a recipe builds its scene.
type Build = fn(&BuildContext, &Params) -> Result<Box<dyn Scene>>;

/// The mouse of every exercise on the model.
const DRAG: &str = "left drag rotates (0.5° per pixel)";

/// The files an exercise on the model draws: `--model`, and `--texture` if it samples one.
const fn files(texture: bool) -> FilesTaken {
    FilesTaken {
        model: true,
        texture,
        ..FilesTaken::NONE
    }
}

/// A normals-as-colour exercise: the rotation is its only parameter.
pub const fn colour(name: &'static str, label: &'static str, build: Build) -> Recipe {
    Recipe::new(info(name, label, Keys::text(DRAG), files(false)), &[ANGLES], build)
}

/// The model drawn by `look` with the normals `normals` picks.
pub fn draw(
    cx: &BuildContext,
    p: &Params,
    name: &str,
    look: &'static Material,
    normals: fn(&Params) -> Normals,
) -> Result<Box<dyn Scene>> {
    MaterialScene::build(cx, p, Model::new(cx, name, normals)?, look)
}

/// A textured exercise's parameters: `tex`, then the rotation.
const TEXTURED_PARAMS: &[&[ParamSpec]] = &[
    &[ParamSpec::choice(
        "tex",
        &[0.0],
        &["checker", "bmp"],
        "texture: the course's checker or its BMP (uvgrid, or --texture FILE) (t)",
    )],
    ANGLES,
];

/// A textured exercise.
pub const fn textured(name: &'static str, label: &'static str, build: Build) -> Recipe {
    Recipe::new(
        info(name, label, Keys::rows(TEXTURED_KEYS, DRAG), files(true)),
        TEXTURED_PARAMS,
        build,
    )
}

/// Key `t` toggles the texture.
const TEXTURED_KEYS: &[KeyRow] = &[KeyRow::cycle(&[C('t')], "tex")];

/// The model's vertex-normal VBO drawn by the vertex shader of 4.2 and `frag`, sampling the
/// texture `tex` chooses with its own parameters, in `auto`'s face order by default.
pub fn sample(
    cx: &BuildContext,
    name: &str,
    frag: &'static str,
    auto: fn(&Params) -> FaceOrder,
) -> Result<Box<dyn Scene>> {
    let textures = vec![
        gl_textures::checker(cx.gpu)?,
        gl_textures::bmp(cx.gpu, cx.files.texture.as_ref())?,
    ];
    let mut model = Model::new(cx, name, |_| Normals::Vertex)?;
    model.auto = auto;
    Sampled::build(
        cx,
        name,
        model,
        ShaderPair::new("suzanne_normal_matrix.vert", frag),
        textures,
        |p| {
            let tex = p.index_of("tex").min(1);
            (tex, [TexParams::CHECKER, TexParams::BMP][tex])
        },
    )
}

/// The shading models, in key order (`1`, `2`, `3`) and `shading` order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shading {
    /// The Gouraud shaders with `flat` interpolation on the face-normal VBO.
    Flat,
    /// Lit per vertex on the vertex-normal VBO.
    Gouraud,
    /// Lit per fragment on the vertex-normal VBO.
    Phong,
}

/// Bound on the light's coordinates.
const REACH: f64 = 50.0;

/// The lighting parameters (SPEC §4.7's pinned defaults).
pub const LIGHT: &[ParamSpec] = &[
    ParamSpec::real("ka", &[0.2], 0.0, 1.0, "ambient Ka = (ka, ka, ka, 1) (a/A)"),
    ParamSpec::real("kdr", &[0.8], 0.0, 1.0, "diffuse Kd red (r/R)"),
    ParamSpec::real("kdg", &[0.5], 0.0, 1.0, "diffuse Kd green (g/G)"),
    ParamSpec::real("kdb", &[0.2], 0.0, 1.0, "diffuse Kd blue (b/B)"),
    ParamSpec::real("ks", &[0.8], 0.0, 1.0, "specular Ks = (ks, ks, ks, 1) (s/S)"),
    ParamSpec::real("shininess", &[32.0], 1.0, 256.0, "specular exponent (h/H)"),
    ParamSpec::real("lightx", &[2.0], -REACH, REACH, "light x, eye space (←/→)"),
    ParamSpec::real("lighty", &[2.0], -REACH, REACH, "light y, eye space (↑/↓)"),
    ParamSpec::real("lightz", &[2.0], -REACH, REACH, "light z, eye space (PageUp/PageDown)"),
];

/// The `shading` choice starting at `default`.
const fn shading(default: &'static [f64]) -> ParamSpec {
    ParamSpec::choice(
        "shading",
        default,
        &["flat", "gouraud", "phong"],
        "shading model (1/2/3)",
    )
}

/// A lit exercise's parameters, by its [`Shading`]: the light, the rotation, `shading`.
const LIT_PARAMS: [&[&[ParamSpec]]; 3] = [
    &[LIGHT, ANGLES, &[shading(&[0.0])]],
    &[LIGHT, ANGLES, &[shading(&[1.0])]],
    &[LIGHT, ANGLES, &[shading(&[2.0])]],
];

/// The lit exercises' keys: coefficients within their ranges ([0, 1], shininess [1, 256]),
/// the light within ±50.
const LIT_KEYS: &[KeyRow] = &[
    KeyRow::step(&[C('a'), C('A')], "ka", 0.05),
    KeyRow::step(&[C('r'), C('R')], "kdr", 0.05),
    KeyRow::step(&[C('g'), C('G')], "kdg", 0.05),
    KeyRow::step(&[C('b'), C('B')], "kdb", 0.05),
    KeyRow::step(&[C('s'), C('S')], "ks", 0.05),
    KeyRow::step(&[C('h'), C('H')], "shininess", 4.0),
    KeyRow::step(&[LEFT, RIGHT], "lightx", 0.25),
    KeyRow::step(&[DOWN, UP], "lighty", 0.25),
    KeyRow::step(&[PAGE_DOWN, PAGE_UP], "lightz", 0.25),
    KeyRow::pick(&[C('1'), C('2'), C('3')], "shading"),
];

/// A lit exercise starting with the model `start`.
pub const fn lit(name: &'static str, label: &'static str, start: Shading, build: Build) -> Recipe {
    Recipe::new(
        info(name, label, Keys::rows(LIT_KEYS, DRAG), files(false)),
        LIT_PARAMS[start as usize],
        build,
    )
}

/// The three models' shader pairs, `shading` picking one (keys switch without a pause).
static LIT: Material = Material::new(&[
    ShaderPair::new("suzanne_flat.vert", "suzanne_flat.frag").named("flat"),
    ShaderPair::new("suzanne_gouraud.vert", "suzanne_gouraud.frag").named("gouraud"),
    ShaderPair::new("suzanne_phong.vert", "suzanne_phong.frag").named("phong"),
])
.chosen_by("shading")
.derive(light);

/// The `Light` block's members that are not parameters as they stand.
pub fn light(p: &Params, c: &mut Derived) {
    let (ka, ks) = (p.f("ka"), p.f("ks"));
    c.set("Ka", &[ka, ka, ka, 1.0]);
    c.set("Kd", &[p.f("kdr"), p.f("kdg"), p.f("kdb"), 1.0]);
    c.set("Ks", &[ks, ks, ks, 1.0]);
    c.set("lightpos", &[p.f("lightx"), p.f("lighty"), p.f("lightz")]);
}

/// The model lit by the model `shading` picks, on its VBO (flat: the face normals).
pub fn shade(cx: &BuildContext, p: &Params, name: &str) -> Result<Box<dyn Scene>> {
    let normals = |p: &Params| {
        if p.index_of("shading") == Shading::Flat as usize {
            Normals::Face
        } else {
            Normals::Vertex
        }
    };
    // Gouraud and per-pixel Phong draw facing the eye first (flat keeps mesh order on the
    // face-normal VBO, see `Model::auto`): 1000 random views of each byte-identical to mesh
    // order.
    let mut model = Model::new(cx, name, normals)?;
    model.auto = |_| FaceOrder::FacingFirst;
    MaterialScene::build(cx, p, model, &LIT)
}
