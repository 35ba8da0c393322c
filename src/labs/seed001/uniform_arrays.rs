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
use crate::lab::{FilesTaken, Input, Lab, LabContext, LabEntry, LabInfo};
use crate::mesh::Vertex;
use crate::params::{ParamSpec, Params};
use crate::render::{Frame, Load, Program, RenderState, Uniforms};
use crate::shader::CompiledShader;

use crate::labs::seed001::gl_light::{GlLight, COURSE};
use crate::labs::seed001::stage::{Solids, UstcStage, OBJECT, ROTATION};

/// Seed 001, §1.2.
pub static INFO: LabInfo = LabInfo {
    name: "uniform_arrays",
    title: "ref001",
    label: "uniform vectors and arrays",
    lecture: "001 USTC GLSL (III)",
    size: (512, 512),
    keys: crate::lab::Keys::text(
        "e: setter style (whole arrays / element by element; same image); ←/→ ↑/↓ PageUp/PageDown: light ±0.25;\n\
           h/H: shininess ∓5; 1-4: objects; left drag rotates",
    ),
    files: FilesTaken::NONE,
};

/// The list entry.
pub static ENTRY: LabEntry = LabEntry {
    info: &INFO,
    params,
    new,
};

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

const OWN: &[ParamSpec] = &[ParamSpec::choice(
    "mode",
    &[0.0],
    &["arrays", "elements"],
    "setter style: 0 glUniform*v on whole arrays, 1 element by element (e)",
)];

fn params() -> Params {
    let mut p = Params::new(OWN);
    p.extend(OBJECT);
    p.extend(ROTATION);
    p.extend(COURSE.params);
    p
}

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

struct UniformArrays {
    params: Params,
    stage: UstcStage,
    light: GlLight,
    uniforms: Uniforms<UniformArraysUniforms>,
    program: Program<Vertex>,
    solids: Solids,
}

fn new(cx: &LabContext) -> Result<Box<dyn Lab>> {
    let stage = UstcStage::new(cx.gpu, "uniform_arrays", Vec3::new(0.0, 0.0, 4.0));
    let light = GlLight::new(cx.gpu, "uniform_arrays", &COURSE);
    let mut program = Program::new(
        cx,
        "uniform_arrays",
        "uniform_arrays.vert",
        "uniform_arrays.frag",
        RenderState::default(),
    )?;
    let uniforms = Uniforms::new(
        cx.gpu,
        "uniform_arrays.params",
        course_uniforms(program.shaders().1, 0)?,
    );
    program.bind(
        cx.gpu,
        vec![stage.transform.bind(), light.uniforms.bind(), uniforms.bind()],
    )?;
    Ok(Box::new(UniformArrays {
        params: params(),
        stage,
        light,
        uniforms,
        program,
        solids: Solids::default(),
    }))
}

impl Lab for UniformArrays {
    fn info(&self) -> &'static LabInfo {
        &INFO
    }
    fn params(&self) -> &Params {
        &self.params
    }
    fn params_mut(&mut self) -> &mut Params {
        &mut self.params
    }
    fn input(&mut self, input: Input) -> bool {
        match input {
            Input::Key('e') => {
                self.params.cycle("mode");
                true
            }
            _ => self.light.input(&mut self.params, input) || self.stage.input(&mut self.params, input),
        }
    }
    fn reload(&mut self, cx: &LabContext) -> Result<()> {
        self.program.reload(cx)
    }
    fn render(&mut self, frame: &mut Frame<'_>) -> Result<()> {
        let gpu = frame.gpu;
        self.uniforms.value = course_uniforms(self.program.shaders().1, self.params.index_of("mode"))?;
        self.uniforms.upload(gpu);
        self.light.upload(gpu, &self.params);
        self.stage.upload(gpu, &self.params, frame.width, frame.height);
        let mesh = self.solids.get(gpu, UstcStage::object(&self.params));
        let mut pass = frame.pass("uniform_arrays", Load::Clear([0.0; 3]));
        self.program.draw(&mut pass, mesh);
        Ok(())
    }
}
