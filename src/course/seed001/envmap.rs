//! Seed 001 `envmap` (SPEC §1.10): a cube-map environment (reflection) map. The course's
//! fragment shader looks up `textureCube(texMap, R)` with the reflection of the view ray about
//! the normal, computed in world space with the model matrix passed as a uniform. The cube map
//! has six coloured faces (SPEC §0.1: +X red, −X cyan, +Y green, −Y magenta, +Z blue, −Z yellow,
//! white grid lines, a darker quadrant showing each face's orientation); `GL_LINEAR`, no
//! mipmaps, `GL_CLAMP_TO_EDGE`, seamless. No skybox is drawn.
//!
//! Keys: `1`-`4` objects; left drag rotates.

use glam::Vec3;

use crate::images;
use crate::lab::{Keys, Material, MaterialScene, Recipe, ShaderPair};
use crate::params::Params;
use crate::render::{sampler, Bind, Derived, SamplerDesc, Texture};

use crate::course::common::FaceOrder;
use crate::course::seed001::geometry::{SolidGeometry, UstcCamera, OBJECT, ROTATION};

/// Seed 001, §1.10: the `EnvMap` block is computed (`env_map`); the cube map and its
/// sampler are the lab's own bindings.
pub static RECIPE: Recipe = Recipe::new(
    super::info(
        lab_name!(),
        "ref001",
        "environment map",
        Keys::text("1-4: objects; left drag rotates"),
    ),
    &[OBJECT, ROTATION],
    |cx, p| {
        let faces = images::cube_faces();
        let cube = Texture::new(cx.gpu, "envmap.cube", faces.width, faces.height, 6, &[faces.rgba]);
        let clamp = wgpu::AddressMode::ClampToEdge;
        let sampler = sampler(
            cx.gpu,
            "envmap.sampler",
            &SamplerDesc {
                wrap: [clamp; 3],
                ..SamplerDesc::default()
            },
        );
        let own = vec![Bind::texture("texMap", &cube), Bind::sampler("texMapSampler", &sampler)];
        let mut geometry = SolidGeometry::new(cx.gpu, cx.name, EYE);
        geometry.auto = |_| FaceOrder::Mesh;
        MaterialScene::build_with(cx, p, geometry, &MATERIAL, own)
    },
);

static MATERIAL: Material = Material::new(&[ShaderPair::new("envmap.vert", "envmap.frag")]).derive(env_map);

/// The eye.
const EYE: Vec3 = Vec3::new(0.0, 0.0, 4.0);

/// The `EnvMap` block of `envmap.vert`: `modelMatrix` = Rx(xangle)·Ry(yangle), `eyeWorld` the
/// eye in world space.
fn env_map(p: &Params, c: &mut Derived) {
    c.set("modelMatrix", &UstcCamera::model(p).to_cols_array());
    c.set("eyeWorld", &EYE.to_array());
}
