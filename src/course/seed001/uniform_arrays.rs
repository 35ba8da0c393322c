//! Seed 001 `uniform_arrays` (SPEC §1.2): the course's uniform vectors and arrays
//! (`specIntensity` 0.98, `specColor`, `t[2]` = {0.5, 0.25}, `colors[3]`) drive a banded "toon"
//! teapot: `specColor` where the light meets the surface head on, then `colors[0..3]` by the
//! thresholds `t`.
//!
//! The course sets the uniforms two ways, both here as `mode`, through GL-style locations
//! looked up by name in the block naga reflected (`"t"`, `"t[1]"`, `"colors[2]"`, each array
//! element in its std140 slot): 0 whole arrays (`glUniform1f`, `glUniform4fv(loc, 1, sc)`,
//! `glUniform1fv(loc, 2, t)`, `glUniform4fv(loc, 3, colors)`), 1 element by element
//! (`glUniform4f` for specColor, `"t[0]"`, `"t[1]"`, `"colors[k]"`). Same bytes, same image.
//!
//! Keys: `e` toggles the setter style; light keys (`←→↑↓`, PageUp/PageDown, `h`/`H`);
//! `1`-`4` objects; left drag rotates.

use bytemuck::Zeroable;
use glam::Vec3;

use crate::error::{Error, Result};
use crate::gpu::Gpu;
use crate::lab::{Geometry, Input, Key::C, KeyRow, Keys, Material, MaterialScene, Recipe, ShaderPair};
use crate::mesh::Vertex;
use crate::params::{ParamSpec, Params};
use crate::render::{Bind, GpuMesh, Uniforms};
use crate::shader::CompiledShader;

use crate::course::seed001::geometry::{SolidGeometry, OBJECT, ROTATION};
use crate::course::seed001::gl_light::{Lit, COURSE, COURSE_KEYS};

/// Seed 001, §1.2: both blocks are the geometry's (`Course`): the `UniformArrays` block as the
/// course's setters leave it for `mode`, and the GL light state.
pub static RECIPE: Recipe = Recipe::new(
    super::info(
        lab_name!(),
        "ref001",
        "uniform vectors and arrays",
        Keys::rows(
            &[
                KeyRow::cycle(&[C('e')], "mode"),
                COURSE_KEYS[0],
                COURSE_KEYS[1],
                COURSE_KEYS[2],
                COURSE_KEYS[3],
            ],
            "1-4: objects; left drag rotates",
        ),
    ),
    &[
        &[ParamSpec::choice(
            "mode",
            &[0.0],
            &["arrays", "elements"],
            "setter style: 0 glUniform*v on whole arrays, 1 element by element (e)",
        )],
        OBJECT,
        ROTATION,
        COURSE.params,
    ],
    |cx, p| {
        let shader = cx.source.compile(MATERIAL.pairs[0].frag)?;
        let modes = [course_uniforms(&shader, 0)?, course_uniforms(&shader, 1)?];
        let solid = SolidGeometry::new(cx.gpu, cx.name, Vec3::new(0.0, 0.0, 4.0));
        let geometry = Course {
            lit: Lit::new(cx.gpu, cx.name, &COURSE, solid),
            block: Uniforms::new(cx.gpu, "uniform_arrays.params", modes[0]),
            modes,
        };
        MaterialScene::build(cx, p, geometry, &MATERIAL)
    },
);

static MATERIAL: Material = Material::new(&[ShaderPair::new("uniform_arrays.vert", "uniform_arrays.frag")]);

/// The `UniformArrays` block of `uniform_arrays.frag` (std140: a float, then 16-byte slots).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct UniformArraysUniforms {
    /// `specIntensity`.
    pub spec_intensity: f32,
    /// std140 aligns the vec4 after it to 16 bytes.
    pub _pad: [f32; 3],
    /// `specColor`.
    pub spec_color: [f32; 4],
    /// `float t[2]`: each element in the x of its own 16-byte slot.
    pub t: [[f32; 4]; 2],
    /// `colors[3]`.
    pub colors: [[f32; 4]; 3],
}
crate::uniform_block!(UniformArraysUniforms, "UniformArrays", {
    spec_intensity: "specIntensity",
    spec_color: "specColor",
    t: "t",
    colors: "colors",
});

/// The block's name in the shader.
const BLOCK: &str = "UniformArrays";

// The course's values.
const SPEC_INTENSITY: f32 = 0.98;
const SC: [f32; 4] = [0.8, 0.8, 0.8, 1.0];
const THRESHOLD: [f32; 2] = [0.5, 0.25];
const COLORS: [f32; 12] = [0.4, 0.4, 0.8, 1.0, 0.2, 0.2, 0.4, 1.0, 0.1, 0.1, 0.1, 1.0];

/// A uniform location as `glGetUniformLocation` returns it: where a member (or an element of
/// an array member) starts, and the elements from there on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Location {
    /// Byte offset in the block.
    pub offset: usize,
    /// Bytes from one array element to the next (0 for a non-array).
    pub stride: usize,
    /// Elements from this location to the end of the array (1 for a non-array).
    pub elements: usize,
    /// Float components of one element.
    pub components: usize,
}

/// `glGetUniformLocation(p, name)` for a member of `block` in `shader`: `"specColor"`, `"t"` (the
/// first element), `"t[1]"`. Offsets and array strides are naga's std140 layout.
pub fn location(shader: &CompiledShader, block: &str, name: &str) -> Result<Location> {
    let module = &shader.module;
    let unknown = || Error::Param(format!("{}: no uniform `{name}` in block {block}", shader.path));
    let (member, index) = match name.split_once('[') {
        Some((m, rest)) => {
            let k = rest
                .strip_suffix(']')
                .and_then(|k| k.parse::<usize>().ok())
                .ok_or_else(unknown)?;
            (m, Some(k))
        }
        None => (name, None),
    };
    let members = module
        .global_variables
        .iter()
        .filter(|(_, v)| v.space == naga::AddressSpace::Uniform)
        .find_map(|(_, v)| match &module.types[v.ty] {
            naga::Type {
                name: Some(n),
                inner: naga::TypeInner::Struct { members, .. },
            } if n == block => Some(members),
            _ => None,
        })
        .ok_or_else(unknown)?;
    let m = members
        .iter()
        .find(|m| m.name.as_deref() == Some(member))
        .ok_or_else(unknown)?;
    let components = |inner: &naga::TypeInner| match inner {
        naga::TypeInner::Scalar(_) => Some(1),
        naga::TypeInner::Vector { size, .. } => Some(*size as usize),
        _ => None,
    };
    let offset = m.offset as usize;
    match (&module.types[m.ty].inner, index) {
        (
            naga::TypeInner::Array {
                base,
                size: naga::ArraySize::Constant(n),
                stride,
            },
            k,
        ) => {
            let k = k.unwrap_or(0);
            let n = n.get() as usize;
            if k >= n {
                return Err(unknown());
            }
            Ok(Location {
                offset: offset + k * *stride as usize,
                stride: *stride as usize,
                elements: n - k,
                components: components(&module.types[*base].inner).ok_or_else(unknown)?,
            })
        }
        (inner, None) => Ok(Location {
            offset,
            stride: 0,
            elements: 1,
            components: components(inner).ok_or_else(unknown)?,
        }),
        _ => Err(unknown()),
    }
}

/// `glUniform{size}fv(location, count, values)` into a block's bytes: `count = values.len() /
/// size` elements from `location` on, each in the first `size` floats of its slot.
pub fn uniform_fv(bytes: &mut [u8], at: Location, size: usize, values: &[f32]) -> Result<()> {
    let count = values.len() / size.max(1);
    if size == 0 || size > at.components || values.len() != count * size || count > at.elements {
        return Err(Error::Param(format!(
            "glUniform{size}fv with {} values does not fit a location of {} element(s) of {} component(s)",
            values.len(),
            at.elements,
            at.components
        )));
    }
    for (k, element) in values.chunks_exact(size).enumerate() {
        let start = at.offset + k * at.stride;
        let end = start + 4 * size;
        let slot = bytes
            .get_mut(start..end)
            .ok_or_else(|| Error::Layout(format!("uniform element at byte {start} lies outside the block")))?;
        slot.copy_from_slice(bytemuck::cast_slice(element));
    }
    Ok(())
}

/// The block as the course's two listings leave it (`mode` 0 or 1), starting from GL's initial
/// uniform values (all zero).
pub fn course_uniforms(shader: &CompiledShader, mode: usize) -> Result<UniformArraysUniforms> {
    let mut value = UniformArraysUniforms::zeroed();
    let bytes = bytemuck::bytes_of_mut(&mut value);
    let loc = |name: &str| location(shader, BLOCK, name);
    uniform_fv(bytes, loc("specIntensity")?, 1, &[SPEC_INTENSITY])?; // glUniform1f(loc1, specIntensity)
    if mode == 0 {
        uniform_fv(bytes, loc("specColor")?, 4, &SC)?; // glUniform4fv(loc2, 1, sc)
        uniform_fv(bytes, loc("t")?, 1, &THRESHOLD)?; // glUniform1fv(loc3, 2, threshold)
        uniform_fv(bytes, loc("colors")?, 4, &COLORS)?; // glUniform4fv(loc4, 3, colors)
    } else {
        uniform_fv(bytes, loc("specColor")?, 4, &[SC[0], SC[1], SC[2], SC[3]])?; // glUniform4f
        uniform_fv(bytes, loc("t[0]")?, 1, &[THRESHOLD[0]])?; // glUniform1f(loct0, threshold[0])
        uniform_fv(bytes, loc("t[1]")?, 1, &[THRESHOLD[1]])?; // glUniform1f(loct1, threshold[1])
        for k in 0..3 {
            uniform_fv(bytes, loc(&format!("colors[{k}]"))?, 4, &COLORS[4 * k..4 * k + 4])?;
        }
    }
    Ok(value)
}

/// GLUT's solid with the GL light state and the `UniformArrays` block of the current `mode`
/// (each computed once, by [`course_uniforms`] on the fragment shader).
struct Course {
    lit: Lit<SolidGeometry>,
    block: Uniforms<UniformArraysUniforms>,
    modes: [UniformArraysUniforms; 2],
}

impl Geometry for Course {
    type Vertex = Vertex;
    fn input(&mut self, p: &mut Params, input: Input) -> bool {
        self.lit.input(p, input)
    }
    fn binds(&self) -> Vec<Bind> {
        let mut binds = self.lit.binds();
        binds.push(self.block.bind());
        binds
    }
    fn prepare(&mut self, gpu: &Gpu, p: &Params, width: u32, height: u32) -> &GpuMesh<Vertex> {
        self.block.value = self.modes[p.index_of("mode").min(1)];
        self.block.upload(gpu);
        self.lit.prepare(gpu, p, width, height)
    }
}
