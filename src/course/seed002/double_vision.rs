//! Seed 002 (Lecture 12) `double_vision`, SPEC §2.2: two reads of one texture, shifted by
//! `left_separation` and `right_separation`, averaged. One textured triangle given in clip
//! space (the slide sets no matrices, so projection and modelview are identity): (−0.8, 0.8)
//! st (0,0), (0.8, 0.8) st (1,0), (0, −0.8) st (0.5,1) — apex down, the image's first row at
//! the top. Texture: the procedural uvgrid (SPEC §0.1), REPEAT, LINEAR/LINEAR, no mipmaps.
//! Depth test off.
//!
//! Course quirks (SPEC §6.2): the sampler is called `texture`, a built-in function from
//! GLSL 1.30 on — renamed `tex` here (#3); the slide shows no texture set-up, and GL's default
//! minification filter would make the texture incomplete (black) — REPEAT and LINEAR/LINEAR are
//! pinned (#5); `glUniform1f` on the sampler is a GL error that leaves it on unit 0 (#2): a
//! wgpu binding has no units, the one texture is what it reads.
//!
//! The `DoubleVision` block's `left_separation` = (left_x, left_y) and `right_separation` =
//! (right_x, right_y) come from the hook.
//!
//! Keys: `[`/`]` separation ∓/±0.02 (left_x steps by ∓/±0.02, right_x the opposite way: one key
//! moving two parameters, which a key row does not express, so the geometry takes it).

use crate::gpu::Gpu;
use crate::images::uvgrid;
use crate::lab::{Geometry, Input, Keys, Material, MaterialScene, Recipe, ShaderPair};
use crate::mesh::shapes::{double_vision_triangle, TexVertex2};
use crate::params::{ParamSpec, Params};
use crate::render::{sampler, Bind, Derived, GpuMesh, RenderState, SamplerDesc, Texture};

crate::vertex_type!(TexVertex2, {
    position: "vertex_position" => Float32x2,
    st: "vertex_st" => Float32x2,
});

/// `double_vision`.
pub static RECIPE: Recipe = Recipe::new(
    super::info(
        lab_name!(),
        "ref002",
        "double vision",
        Keys::text("[/]: separation ∓/±0.02 (left_x = +sep, right_x = -sep)"),
    ),
    &[&[
        ParamSpec::real(
            "left_x",
            &[0.1],
            -100.0,
            100.0,
            "left_separation.s (] adds 0.02, [ subtracts)",
        ),
        ParamSpec::real(
            "right_x",
            &[-0.1],
            -100.0,
            100.0,
            "right_separation.s (] subtracts 0.02, [ adds)",
        ),
        ParamSpec::real("left_y", &[0.0], -100.0, 100.0, "left_separation.t"),
        ParamSpec::real("right_y", &[0.0], -100.0, 100.0, "right_separation.t"),
    ]],
    |cx, p| {
        let image = uvgrid();
        let texture = Texture::new(cx.gpu, "uvgrid", image.width, image.height, 1, &[image.rgba]);
        let sampler = sampler(cx.gpu, "double_vision.sampler", &SamplerDesc::default());
        let triangle = GpuMesh::new(cx.gpu, "double_vision.triangle", &double_vision_triangle(), None);
        let own = vec![Bind::texture("tex", &texture), Bind::sampler("tex_sampler", &sampler)];
        MaterialScene::build_with(cx, p, Triangle(triangle), &MATERIAL, own)
    },
);

static MATERIAL: Material =
    Material::new(&[ShaderPair::new("double_vision.vert", "double_vision.frag").state(RenderState::GL.no_depth())])
        .derive(|p: &Params, c: &mut Derived| {
            c.set("left_separation", &[p.f("left_x"), p.f("left_y")]);
            c.set("right_separation", &[p.f("right_x"), p.f("right_y")]);
        });

/// The separation step of keys `[` and `]`.
const STEP: f64 = 0.02;

/// The triangle in clip space, and the separation keys.
struct Triangle(GpuMesh<TexVertex2>);

impl Geometry for Triangle {
    type Vertex = TexVertex2;
    fn input(&mut self, p: &mut Params, input: Input) -> bool {
        let delta = match input {
            Input::Key(']') => STEP,
            Input::Key('[') => -STEP,
            _ => return false,
        };
        p.step("left_x", delta);
        p.step("right_x", -delta);
        true
    }
    fn prepare(&mut self, _gpu: &Gpu, _p: &Params, _width: u32, _height: u32) -> &GpuMesh<TexVertex2> {
        &self.0
    }
}
