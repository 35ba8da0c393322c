//! A course's own GLSL 1.10/1.20 shaders, unchanged, on wgpu: translated into the GLSL 450
//! that naga accepts, on a real parse ([glsl-lang](https://docs.rs/glsl-lang)), with a source
//! map so that every error points at the user's own file, line and column.
//!
//! What the translation does, construct by construct:
//! - no `#version` (= 110), `#version 110` or `120` → `#version 450`; anything else is an error;
//! - `attribute` → a generic attribute GL would read as a constant (`glVertexAttrib`, default
//!   (0, 0, 0, 1)): a member of the uniform block, settable by name;
//! - `varying` → `layout(location = N) out`/`in`, locations matched by name across the stages;
//! - `gl_Vertex`, `gl_Normal`, `gl_MultiTexCoord0` → the mesh's attributes (`sl_Vertex`,
//!   `gl_Normal`, `sl_MultiTexCoord0`); `gl_MultiTexCoord1..7` → GL's current (0, 0, 0, 1);
//! - GL's built-in uniforms (`gl_ModelViewMatrix` and friends with their inverses and
//!   transposes, `gl_NormalMatrix`, `gl_LightSource[i]`, `gl_LightModel`, `gl_FrontMaterial`,
//!   `gl_FrontLightProduct[i]`, `gl_FrontLightModelProduct`, `gl_DepthRange`, `gl_Color` in a
//!   vertex shader) → members of the block `sl_GlState` (binding 0) with GL's names, filled from
//!   the scene and from parameters of the same names with GL's defaults ([`state`]);
//! - `ftransform()` → a function of the prologue; `gl_Position` is converted from GL's depth
//!   range to wgpu's once, after the shader's `main`;
//! - `gl_FrontColor` → `gl_Color` of the fragment shader, `gl_TexCoord[i]` → one varying per
//!   index used, `gl_FragColor` / `gl_FragData[0]` → the colour output;
//! - loose uniforms of both stages → one std140 block `sl_Uniforms` (binding 1) reflected by
//!   naga; the types naga's std140 cannot hold (bool, arrays of float/vec2, mat2) are held in
//!   another form and copied into a private variable of the user's name;
//! - `uniform sampler2D`/`samplerCube` → a texture and a sampler (bindings 2, 3, ...), with
//!   `texture2D`/`textureCube`/`...Lod`/`...Proj` rewritten;
//! - names that GLSL 450 reserves (`uniform sampler2D texture;`) → `sl_NAME`;
//! - what is not supported (`gl_ClipVertex`, fog, 1D/3D/shadow samplers, ...) is an error
//!   naming the construct.
//!
//! The user's text is kept as it is everywhere else: the translation is a list of edits at the
//! syntax tree's spans, a generated prologue and a generated `main` that calls the user's.

mod builtins;
mod map;
pub mod state;
mod translate;

use std::ops::Range;

use naga::valid::{Capabilities, ValidationFlags, Validator};

pub use builtins::SamplerDim;
pub use map::{LegacySource, Output};
pub use translate::{
    translate, Encoding, Sampler, Scalar, Translated, Translation, Ty, Uniform, STATE_BINDING, STATE_BLOCK,
    UNIFORM_BINDING, UNIFORM_BLOCK,
};

use crate::error::{Error, Result};
use crate::params::ParamSpec;
use crate::shader::{CompiledShader, Spliced};

impl Translated {
    /// Parses and validates the GLSL 450 with naga; errors point at the user's files.
    pub fn compile(&self) -> Result<CompiledShader> {
        let text = &self.output.text;
        let mut frontend = naga::front::glsl::Frontend::default();
        let module = frontend
            .parse(&naga::front::glsl::Options::from(self.stage), text)
            .map_err(|errors| {
                let found: Vec<(Range<usize>, String)> = errors
                    .errors
                    .iter()
                    .map(|e| (e.meta.to_range().unwrap_or(0..0), e.kind.to_string()))
                    .collect();
                self.combine(&found)
            })?;
        let info = Validator::new(ValidationFlags::all(), Capabilities::all())
            .validate(&module)
            .map_err(|err| {
                let mut message = err.as_inner().to_string();
                let mut source: &dyn std::error::Error = err.as_inner();
                while let Some(next) = source.source() {
                    message.push_str(": ");
                    message.push_str(&next.to_string());
                    source = next;
                }
                let span = err.spans().last().and_then(|(s, _)| s.to_range()).unwrap_or(0..0);
                self.combine(&[(span, message)])
            })?;
        // One line index per file: `line_col` for every line would scan the text each time,
        // quadratic in the file's length.
        let (this, other) = (
            map::LineIndex::new(&self.source.text),
            map::LineIndex::new(&self.other.text),
        );
        let line_map = self
            .output
            .line_origins()
            .into_iter()
            .map(|origin| match origin {
                Some(o) => match o.file {
                    map::File::This => (self.source.path.clone(), this.line(o.offset)),
                    map::File::Other => (self.other.path.clone(), other.line(o.offset)),
                },
                None => (self.source.path.clone(), 1),
            })
            .collect();
        Ok(CompiledShader {
            path: self.source.path.clone(),
            stage: self.stage,
            source: Spliced {
                text: text.clone(),
                line_map,
            },
            module,
            info,
        })
    }

    fn combine(&self, found: &[(Range<usize>, String)]) -> Error {
        let errors: Vec<Error> = found
            .iter()
            // The user's `main` is `sl_main` in the translation: name it as the user does.
            .map(|(range, message)| {
                self.error_at(range.start, range.len().max(1), &message.replace("'sl_main'", "'main'"))
            })
            .collect();
        let mut errors = errors.into_iter();
        let Some(first) = errors.next() else {
            return self.source.error(0..1, "naga rejected the translated shader");
        };
        let rest: Vec<String> = errors.map(|e| e.to_string()).collect();
        match first {
            Error::Shader {
                file,
                line,
                column,
                message,
            } if !rest.is_empty() => Error::Shader {
                file,
                line,
                column,
                message: format!("{message}\n{}", rest.join("\n")),
            },
            e => e,
        }
    }
}

impl Translation {
    /// Translates two files.
    pub fn from_files(vertex: &std::path::Path, fragment: &std::path::Path) -> Result<Translation> {
        translate(&LegacySource::read(vertex)?, &LegacySource::read(fragment)?)
    }

    /// Both stages compiled by naga.
    pub fn compile(&self) -> Result<(CompiledShader, CompiledShader)> {
        Ok((self.vertex.compile()?, self.fragment.compile()?))
    }

    /// The parameter name of each loose uniform: its own name, or `uniform.NAME` where the
    /// name is already a parameter (`taken`, e.g. a lab's `object`).
    pub fn param_names(&self, taken: &dyn Fn(&str) -> bool) -> Vec<&'static str> {
        self.uniforms
            .iter()
            .map(|u| {
                if taken(&u.name) {
                    state::intern(&format!("uniform.{}", u.name))
                } else {
                    state::intern(&u.name)
                }
            })
            .collect()
    }

    /// The parameters of the shaders: GL's state they use, then their loose uniforms (named
    /// by [`Translation::param_names`]).
    pub fn params(&self, taken: &dyn Fn(&str) -> bool) -> Vec<ParamSpec> {
        let mut out = state::params(&self.state, self.lights);
        for (u, name) in self.uniforms.iter().zip(self.param_names(taken)) {
            let file = if u.declared.0 {
                &self.vertex.source
            } else {
                &self.fragment.source
            };
            let (line, _, _) = file.line_col(u.declared.1.start);
            let kind = if u.attribute { "attribute" } else { "uniform" };
            let help = state::intern(&format!(
                "{kind} {}{} ({}:{line})",
                u.ty.glsl(),
                u.array.map(|n| format!("[{n}]")).unwrap_or_default(),
                file.path
            ));
            let default = state::intern_values(&u.default);
            out.push(match u.ty.scalar {
                Scalar::Float => ParamSpec::real(name, default, -1e30, 1e30, help),
                Scalar::Int => ParamSpec::int(name, default, -2147483648.0, 2147483647.0, help),
                Scalar::Bool => ParamSpec::int(name, default, 0.0, 1.0, help),
            });
        }
        out
    }
}

/// The uniform block `name` of a compiled shader as raw bytes, each leaf (scalar, vector or
/// matrix, by its GLSL path such as `gl_LightSource[0].position` or `w[2]`) filled by
/// `lookup` in naga's layout; `None` if the shader has no such block.
pub fn block_bytes(
    shader: &CompiledShader,
    name: &str,
    lookup: &mut dyn FnMut(&str) -> Option<Vec<f64>>,
) -> Option<Vec<u8>> {
    let module = &shader.module;
    let var = module
        .global_variables
        .iter()
        .map(|(_, v)| v)
        .find(|v| v.space == naga::AddressSpace::Uniform && module.types[v.ty].name.as_deref() == Some(name))?;
    let naga::TypeInner::Struct { members, span } = &module.types[var.ty].inner else {
        return None;
    };
    let mut bytes = vec![0u8; (*span as usize).next_multiple_of(16)];
    for m in members {
        let path = m.name.clone().unwrap_or_default();
        write_leaf(module, m.ty, m.offset as usize, &path, &mut bytes, lookup);
    }
    Some(bytes)
}

fn write_leaf(
    module: &naga::Module,
    ty: naga::Handle<naga::Type>,
    offset: usize,
    path: &str,
    bytes: &mut [u8],
    lookup: &mut dyn FnMut(&str) -> Option<Vec<f64>>,
) {
    use naga::TypeInner as T;
    let put = |bytes: &mut [u8], at: usize, kind: naga::ScalarKind, v: f64| {
        let word: [u8; 4] = match kind {
            naga::ScalarKind::Sint => (v as i32).to_ne_bytes(),
            naga::ScalarKind::Uint => (v as u32).to_ne_bytes(),
            _ => (v as f32).to_ne_bytes(),
        };
        if let Some(slot) = bytes.get_mut(at..at + 4) {
            slot.copy_from_slice(&word);
        }
    };
    match &module.types[ty].inner {
        T::Struct { members, .. } => {
            for m in members {
                let name = m.name.clone().unwrap_or_default();
                write_leaf(
                    module,
                    m.ty,
                    offset + m.offset as usize,
                    &format!("{path}.{name}"),
                    bytes,
                    lookup,
                );
            }
        }
        T::Array {
            base,
            size: naga::ArraySize::Constant(n),
            stride,
        } => {
            for i in 0..n.get() as usize {
                write_leaf(
                    module,
                    *base,
                    offset + i * *stride as usize,
                    &format!("{path}[{i}]"),
                    bytes,
                    lookup,
                );
            }
        }
        T::Scalar(s) => {
            if let Some(v) = lookup(path) {
                put(bytes, offset, s.kind, v.first().copied().unwrap_or(0.0));
            }
        }
        T::Vector { size, scalar } => {
            if let Some(v) = lookup(path) {
                for (k, x) in v.iter().take(*size as usize).enumerate() {
                    put(bytes, offset + 4 * k, scalar.kind, *x);
                }
            }
        }
        T::Matrix { columns, rows, scalar } => {
            if let Some(v) = lookup(path) {
                let (c, r) = (*columns as usize, *rows as usize);
                let stride = if r == 2 { 8 } else { 16 };
                for col in 0..c {
                    for row in 0..r {
                        if let Some(x) = v.get(col * r + row) {
                            put(bytes, offset + col * stride + 4 * row, scalar.kind, *x);
                        }
                    }
                }
            }
        }
        _ => {}
    }
}

/// The values of the loose uniforms' block leaves from the uniforms' parameter values
/// (`values[i]` for `uniforms[i]`), by the GLSL path [`block_bytes`] asks for.
pub fn uniform_lookup<'a>(
    uniforms: &'a [Uniform],
    values: &'a [Vec<f64>],
) -> impl FnMut(&str) -> Option<Vec<f64>> + 'a {
    move |path: &str| {
        let (member, index) = match path.split_once('[') {
            Some((m, rest)) => (m, rest.trim_end_matches(']').parse::<usize>().ok()),
            None => (path, None),
        };
        let i = uniforms.iter().position(|u| u.member() == member)?;
        let u = &uniforms[i];
        let v = values.get(i)?;
        let element = u.ty.components();
        Some(match (u.encoding, index) {
            (Encoding::Columns, Some(c)) => {
                let r = u.ty.rows as usize;
                v.get(c * r..(c + 1) * r)?.to_vec()
            }
            (_, Some(k)) => v.get(k * element..(k + 1) * element)?.to_vec(),
            (_, None) => v.clone(),
        })
    }
}

#[cfg(test)]
mod tests;
