//! GL 2.0's light and material state, which seed 001's shaders read as built-ins
//! (`gl_LightSource[0]`, `gl_FrontMaterial`, `gl_FrontLightProduct[0]`), as ONE uniform block:
//! `GlLight` of `gl_light.glsl`. The values are SPEC §1's pinned `glLightfv`/`glMaterialfv`
//! calls; the products are what GL derives from them. The light position is set while the
//! modelview is the identity, so it is in eye space exactly as given.
//!
//! Rust computes the whole block ([`state`]), so it stays a typed struct; [`Lit`] adds it to a
//! geometry for the runner.
//!
//! Keys (SPEC §1, "light keys", as rows: [`COURSE_KEYS`], [`BUMP_KEYS`]): `←`/`→` x ∓0.25,
//! `↑`/`↓` y ±0.25, `PageUp`/`PageDown` z ±0.25, `h`/`H` shininess −/+5 within [1, 128]
//! (`GL_SHININESS` must be ≤ 128).

use crate::gpu::Gpu;
use crate::lab::{Geometry, Input, Key::C, KeyRow, Keys, DOWN, LEFT, PAGE_DOWN, PAGE_UP, RIGHT, UP};
use crate::params::{ParamSpec, Params};
use crate::render::{Bind, Culling, GpuMesh, Uniforms};

/// `struct LightSourceParameters` of `gl_light.glsl` (the members the course reads).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct LightSourceParameters {
    /// `GL_AMBIENT`.
    pub ambient: [f32; 4],
    /// `GL_DIFFUSE`.
    pub diffuse: [f32; 4],
    /// `GL_SPECULAR`.
    pub specular: [f32; 4],
    /// `GL_POSITION`, eye space.
    pub position: [f32; 4],
}

/// `struct MaterialParameters` (std140: the float after four vec4s rounds the struct to 80 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct MaterialParameters {
    /// `GL_EMISSION`.
    pub emission: [f32; 4],
    /// `GL_AMBIENT`.
    pub ambient: [f32; 4],
    /// `GL_DIFFUSE`.
    pub diffuse: [f32; 4],
    /// `GL_SPECULAR`.
    pub specular: [f32; 4],
    /// `GL_SHININESS`.
    pub shininess: f32,
    /// std140 pads a struct to a multiple of 16 bytes.
    pub _pad: [f32; 3],
}

/// `struct LightProducts`: material × light, component by component.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct LightProducts {
    /// Acm·Acli.
    pub ambient: [f32; 4],
    /// Dcm·Dcli.
    pub diffuse: [f32; 4],
    /// Scm·Scli.
    pub specular: [f32; 4],
}

/// The `GlLight` block of `gl_light.glsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GlLightUniforms {
    /// `LightSource[1]`: `gl_LightSource[0]`.
    pub light_source: [LightSourceParameters; 1],
    /// `FrontMaterial`: `gl_FrontMaterial`.
    pub front_material: MaterialParameters,
    /// `FrontLightProduct[1]`: `gl_FrontLightProduct[0]`.
    pub front_light_product: [LightProducts; 1],
}
crate::glsl_struct!(LightSourceParameters);
crate::glsl_struct!(MaterialParameters);
crate::glsl_struct!(LightProducts);
crate::uniform_block!(GlLightUniforms, "GlLight", {
    light_source: "LightSource",
    front_material: "FrontMaterial",
    front_light_product: "FrontLightProduct",
});

/// GL's products: RGB multiplied, alpha the material's (as Mesa derives `gl_FrontLightProduct`).
fn product(material: [f32; 4], light: [f32; 4]) -> [f32; 4] {
    [
        material[0] * light[0],
        material[1] * light[1],
        material[2] * light[2],
        material[3],
    ]
}

/// One exercise's light and material: the fixed values and the parameters that move it.
#[derive(Clone, Copy, Debug)]
pub struct LightSetup {
    /// Parameters: the three position coordinates first, then (optionally) `shininess`.
    pub params: &'static [ParamSpec],
    /// The keys that move them ([`COURSE_KEYS`], [`BUMP_KEYS`]).
    pub keys: &'static [KeyRow],
    /// `GL_LIGHT0`'s colours (its position comes from the parameters, w = 1).
    pub light: LightSourceParameters,
    /// The front material (its shininess comes from a `shininess` parameter when there is one).
    pub material: MaterialParameters,
}

const BLACK: [f32; 4] = [0.0, 0.0, 0.0, 1.0];
const WHITE: [f32; 4] = [1.0, 1.0, 1.0, 1.0];

/// Range of the light coordinates.
const REACH: f64 = 50.0;

/// Step of the light keys.
const STEP: f64 = 0.25;

/// SPEC §1's light keys: `←`/`→` lx ∓0.25, `↓`/`↑` ly ∓0.25, PageDown/PageUp lz ∓0.25, `h`/`H`
/// shininess ∓5 (within its range [1, 128]).
pub const COURSE_KEYS: [KeyRow; 4] = [
    KeyRow::step(&[LEFT, RIGHT], "lx", STEP),
    KeyRow::step(&[DOWN, UP], "ly", STEP),
    KeyRow::step(&[PAGE_DOWN, PAGE_UP], "lz", STEP),
    KeyRow::step(&[C('h'), C('H')], "shininess", 5.0),
];

/// The bump light's keys: as [`COURSE_KEYS`] on blx, bly, blz (no shininess).
pub const BUMP_KEYS: [KeyRow; 3] = [
    KeyRow::step(&[LEFT, RIGHT], "blx", STEP),
    KeyRow::step(&[DOWN, UP], "bly", STEP),
    KeyRow::step(&[PAGE_DOWN, PAGE_UP], "blz", STEP),
];

/// SPEC §1's light: position (lx, ly, lz, 1) = (2, 2, 2, 1) in eye space, ambient 0.2, diffuse
/// and specular 1; material ambient = diffuse (0.2, 0.3, 0.8), specular 1, shininess 40.
pub const COURSE: LightSetup = LightSetup {
    params: &[
        ParamSpec::real("lx", &[2.0], -REACH, REACH, "light x, eye space (← →)"),
        ParamSpec::real("ly", &[2.0], -REACH, REACH, "light y, eye space (↑ ↓)"),
        ParamSpec::real("lz", &[2.0], -REACH, REACH, "light z, eye space (PageUp PageDown)"),
        ParamSpec::real("shininess", &[40.0], 1.0, 128.0, "GL_SHININESS (h H)"),
    ],
    keys: &COURSE_KEYS,
    light: LightSourceParameters {
        ambient: [0.2, 0.2, 0.2, 1.0],
        diffuse: WHITE,
        specular: WHITE,
        position: [2.0, 2.0, 2.0, 1.0],
    },
    material: MaterialParameters {
        emission: BLACK,
        ambient: [0.2, 0.3, 0.8, 1.0],
        diffuse: [0.2, 0.3, 0.8, 1.0],
        specular: WHITE,
        shininess: 40.0,
        _pad: [0.0; 3],
    },
};

/// SPEC §1.11's light for `bump` and `normmap`: position (blx, bly, blz, 1) = (1.5, 1.5, −2, 1)
/// in eye space, GL_LIGHT0's default colours (diffuse 1); material diffuse (0.9, 0.7, 0.5),
/// ambient and specular (0, 0, 0, 1).
pub const BUMP: LightSetup = LightSetup {
    params: &[
        ParamSpec::real("blx", &[1.5], -REACH, REACH, "light x, eye space (← →)"),
        ParamSpec::real("bly", &[1.5], -REACH, REACH, "light y, eye space (↑ ↓)"),
        ParamSpec::real("blz", &[-2.0], -REACH, REACH, "light z, eye space (PageUp PageDown)"),
    ],
    keys: &BUMP_KEYS,
    light: LightSourceParameters {
        ambient: BLACK,
        diffuse: WHITE,
        specular: WHITE,
        position: [1.5, 1.5, -2.0, 1.0],
    },
    material: MaterialParameters {
        emission: BLACK,
        ambient: BLACK,
        diffuse: [0.9, 0.7, 0.5, 1.0],
        specular: BLACK,
        shininess: 0.0,
        _pad: [0.0; 3],
    },
};

/// The block's value for a setup at the current parameters.
pub fn state(setup: &LightSetup, params: &Params) -> GlLightUniforms {
    let [x, y, z] = [0, 1, 2].map(|i| params.f(setup.params[i].name));
    let light = LightSourceParameters {
        position: [x, y, z, 1.0],
        ..setup.light
    };
    let material = match setup.params.get(3) {
        Some(spec) => MaterialParameters {
            shininess: params.f(spec.name),
            ..setup.material
        },
        None => setup.material,
    };
    GlLightUniforms {
        light_source: [light],
        front_material: material,
        front_light_product: [LightProducts {
            ambient: product(material.ambient, light.ambient),
            diffuse: product(material.diffuse, light.diffuse),
            specular: product(material.specular, light.specular),
        }],
    }
}

/// The light part of an exercise: its setup and its block.
pub struct GlLight {
    setup: &'static LightSetup,
    /// The `GlLight` block.
    pub uniforms: Uniforms<GlLightUniforms>,
}

impl GlLight {
    /// The block for `setup`, at its defaults.
    pub fn new(gpu: &Gpu, label: &str, setup: &'static LightSetup) -> Self {
        let defaults = Params::new(setup.params);
        GlLight {
            setup,
            uniforms: Uniforms::new(gpu, &format!("{label}.gl_light"), state(setup, &defaults)),
        }
    }

    /// The light keys ([`LightSetup::keys`]); false for any other input.
    pub fn input(&self, params: &mut Params, input: Input) -> bool {
        Keys::rows(self.setup.keys, "").apply(params, input)
    }

    /// Writes the block for the current parameters.
    pub fn upload(&mut self, gpu: &Gpu, params: &Params) {
        self.uniforms.value = state(self.setup, params);
        self.uniforms.upload(gpu);
    }
}

/// A [`Geometry`] lit by GL's light: the geometry's blocks plus the `GlLight` block, written for the
/// parameters every frame. The light keys are the lab's key rows ([`LightSetup::keys`]).
pub struct Lit<S: Geometry> {
    /// The geometry.
    pub geometry: S,
    /// The light.
    pub light: GlLight,
}

impl<S: Geometry> Lit<S> {
    /// `geometry` lit by `setup`.
    pub fn new(gpu: &Gpu, label: &str, setup: &'static LightSetup, geometry: S) -> Self {
        Lit {
            light: GlLight::new(gpu, label, setup),
            geometry,
        }
    }
}

impl<S: Geometry> Geometry for Lit<S> {
    type Vertex = S::Vertex;
    fn input(&mut self, p: &mut Params, input: Input) -> bool {
        self.geometry.input(p, input)
    }
    fn binds(&self) -> Vec<Bind> {
        let mut binds = self.geometry.binds();
        binds.push(self.light.uniforms.bind());
        binds
    }
    fn culling(&self, p: &Params) -> Option<Culling> {
        self.geometry.culling(p)
    }
    fn prepare(&mut self, gpu: &Gpu, p: &Params, width: u32, height: u32) -> &GpuMesh<S::Vertex> {
        self.light.upload(gpu, p);
        self.geometry.prepare(gpu, p, width, height)
    }
}
