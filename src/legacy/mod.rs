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
pub mod names;
pub mod state;
mod translate;

use std::ops::Range;

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
        let mut module = frontend
            .parse(&naga::front::glsl::Options::from(self.stage), text)
            .map_err(|errors| {
                let mut found: Vec<(Range<usize>, String)> = errors
                    .errors
                    .iter()
                    .map(|e| (e.meta.to_range().unwrap_or(0..0), e.kind.to_string()))
                    .collect();
                crate::shader::error_directive_first(&mut found, |(_, m)| m);
                self.combine(&found)
            })?;
        let info = crate::shader::finish_module(&mut module, self.stage).map_err(|unfinished| {
            let (span, message) = unfinished.located();
            self.combine(&[(span.to_range().unwrap_or(0..0), message)])
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
                files: vec![
                    (self.source.path.clone(), self.source.text.clone()),
                    (self.other.path.clone(), self.other.text.clone()),
                ],
            },
            module,
            info,
            translated: true,
        })
    }

    /// An error naga gives no place for. naga folds constants with no span: a projective
    /// lookup with q = 0 (`texture2DProj(s, vec3(0.5, 0.5, 0.0))`) is "Float literal is
    /// infinite" at nowhere; point at the first projective lookup if there is one, else name
    /// the file without a (wrong) line.
    fn spanless(&self, message: &str) -> Error {
        let plain = crate::shader::plain_message(message, "");
        let text = &self.source.text;
        if message.contains("Float literal is") {
            if let Some(at) = text.find("Proj(") {
                let start = text[..at]
                    .rfind(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                    .map_or(0, |i| i + 1);
                return self.source.error(start..at + 4, &plain);
            }
        }
        Error::Shader {
            file: self.source.path.clone(),
            line: 1,
            column: 1,
            message: format!("{}: {plain}", self.source.path),
        }
    }

    fn combine(&self, found: &[(Range<usize>, String)]) -> Error {
        let errors: Vec<Error> = found
            .iter()
            // The user's `main` is `sl_main` in the translation: name it as the user does.
            .map(|(range, message)| {
                if *range == (0..0) {
                    return self.spanless(message);
                }
                let line = self.source_line_at(range.start);
                let message =
                    crate::shader::plain_message(&message.replace(&format!("'{}'", names::MAIN), "'main'"), &line);
                self.error_at(range.start, range.len().max(1), &message)
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
        // Line numbers for every uniform from one index per file (not a scan of the text each).
        let lines = [
            map::LineIndex::new(&self.fragment.source.text),
            map::LineIndex::new(&self.vertex.source.text),
        ];
        for (u, name) in self.uniforms.iter().zip(self.param_names(taken)) {
            let file = if u.declared.0 {
                &self.vertex.source
            } else {
                &self.fragment.source
            };
            let line = lines[usize::from(u.declared.0)].line(u.declared.1.start);
            let kind = if u.attribute { "attribute" } else { "uniform" };
            // A uniform named like one of the lab's parameters keeps both settable: the
            // lab's keeps its name (documented, used by keys and shorthands such as
            // `--camera`), the shader's is `uniform.NAME`, and its help line says why.
            let renamed = if name != u.name {
                format!("; `{}` is the lab's own parameter, so this one is `{name}`", u.name)
            } else {
                String::new()
            };
            let help = state::intern(&format!(
                "{kind} {}{} ({}:{line}){renamed}",
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

impl Translation {
    /// Checks what the shaders need against the device's limits before any buffer or pipeline
    /// is made: wgpu would otherwise report them as validation errors about `legacy.bind_group`
    /// or `legacy.pipeline`. `max_block` is the largest uniform binding in bytes,
    /// `max_varyings` the inter-stage variables; `vs` and `fs` the compiled stages.
    pub fn check_limits(
        &self,
        vs: &CompiledShader,
        fs: &CompiledShader,
        max_block: u64,
        max_varyings: u32,
    ) -> Result<()> {
        if let Some(sizes) = member_sizes(vs, UNIFORM_BLOCK) {
            let total: u64 = sizes.iter().map(|(_, size)| size).sum();
            if total > max_block {
                // Name the uniforms, largest first, with their sizes in the block.
                let size_of: std::collections::HashMap<&str, u64> =
                    sizes.iter().map(|(m, s)| (m.as_str(), *s)).collect();
                let mut by_size: Vec<(&Uniform, u64)> = self
                    .uniforms
                    .iter()
                    .filter_map(|u| size_of.get(u.member().as_str()).map(|s| (u, *s)))
                    .collect();
                by_size.sort_by_key(|u| std::cmp::Reverse(u.1));
                let list: Vec<String> = by_size
                    .iter()
                    .take(5)
                    .map(|(u, size)| {
                        let file = if u.declared.0 {
                            &self.vertex.source
                        } else {
                            &self.fragment.source
                        };
                        format!(
                            "`{}` {}{} {size} bytes ({}:{})",
                            u.name,
                            u.ty.glsl(),
                            u.array.map(|n| format!("[{n}]")).unwrap_or_default(),
                            file.path,
                            file.line_col(u.declared.1.start).0
                        )
                    })
                    .collect();
                let more = by_size.len().saturating_sub(5);
                let message = format!(
                    "the uniforms need {total} bytes, more than this GPU's limit of {max_block} bytes for one uniform block: {}{}; \
                     each element of a float or vec2 array takes 16 bytes (std140): use fewer or smaller arrays, or pack floats into vec4s",
                    list.join(", "),
                    if more > 0 { format!(" and {more} more") } else { String::new() }
                );
                return Err(match by_size.first() {
                    Some((u, _)) => {
                        let file = if u.declared.0 {
                            &self.vertex.source
                        } else {
                            &self.fragment.source
                        };
                        file.error(u.declared.1.clone(), &message)
                    }
                    None => self.vertex.source.error(0..0, &message),
                });
            }
        }
        // The fragment shader's built-in inputs other than the position (gl_FrontFacing)
        // take inter-stage variables too.
        let builtins = fragment_builtin_inputs(fs);
        let limit = max_varyings.saturating_sub(builtins) as usize;
        if self.varyings.len() > limit {
            let names: Vec<&str> = self.varyings.iter().map(|(n, _)| n.as_str()).take(16).collect();
            let more = self.varyings.len().saturating_sub(16);
            let message = format!(
                "the vertex shader passes {} values to the fragment shader ({}{}); this GPU takes at most {limit}{}: \
                 pack several floats into one vec4 varying (gl_FrontColor and each gl_TexCoord[i] count, a variable gl_TexCoord index counts all 8)",
                self.varyings.len(),
                names.join(", "),
                if more > 0 { format!(", and {more} more") } else { String::new() },
                if builtins > 0 { format!(" ({max_varyings} less {builtins} for the fragment built-ins read)") } else { String::new() }
            );
            let first_over = self.varyings.iter().skip(limit).find_map(|(_, r)| r.clone());
            let range = first_over.or_else(|| self.varyings.iter().rev().find_map(|(_, r)| r.clone()));
            return Err(match range {
                Some(r) => self.vertex.source.error(r, &message),
                None => self.vertex.source.error(0..0, &message),
            });
        }
        Ok(())
    }
}

/// The members and size of the uniform block whose struct type is called `name`.
fn uniform_block<'a>(shader: &'a CompiledShader, name: &str) -> Option<(&'a [naga::StructMember], &'a u32)> {
    let module = &shader.module;
    let var = module
        .global_variables
        .iter()
        .map(|(_, v)| v)
        .find(|v| v.space == naga::AddressSpace::Uniform && module.types[v.ty].name.as_deref() == Some(name))?;
    match &module.types[var.ty].inner {
        naga::TypeInner::Struct { members, span } => Some((members, span)),
        _ => None,
    }
}

/// Each member of the uniform block `name` with its size in bytes (up to the next member).
fn member_sizes(shader: &CompiledShader, name: &str) -> Option<Vec<(String, u64)>> {
    let (members, span) = uniform_block(shader, name)?;
    Some(
        members
            .iter()
            .enumerate()
            .map(|(i, m)| {
                let end = members.get(i + 1).map_or(*span, |n| n.offset);
                (m.name.clone().unwrap_or_default(), u64::from(end - m.offset))
            })
            .collect(),
    )
}

/// How many built-in inputs other than the position the fragment entry point reads.
fn fragment_builtin_inputs(fs: &CompiledShader) -> u32 {
    let module = &fs.module;
    let count = |b: &Option<naga::Binding>| matches!(b, Some(naga::Binding::BuiltIn(bi)) if !matches!(bi, naga::BuiltIn::Position { .. }));
    module
        .entry_points
        .iter()
        .flat_map(|ep| &ep.function.arguments)
        .map(|arg| match &module.types[arg.ty].inner {
            naga::TypeInner::Struct { members, .. } => members.iter().filter(|m| count(&m.binding)).count() as u32,
            _ => u32::from(count(&arg.binding)),
        })
        .sum()
}

/// The uniform block `name` of a compiled shader as raw bytes, each leaf (scalar, vector or
/// matrix, by its GLSL path such as `gl_LightSource[0].position` or `w[2]`) filled by
/// `lookup` in naga's layout; `None` if the shader has no such block.
pub fn block_bytes(
    shader: &CompiledShader,
    name: &str,
    lookup: &mut dyn FnMut(&str) -> Option<Vec<f64>>,
) -> Option<Vec<u8>> {
    let (members, span) = uniform_block(shader, name)?;
    let mut bytes = vec![0u8; (*span as usize).next_multiple_of(16)];
    for m in members {
        let path = m.name.clone().unwrap_or_default();
        write_leaf(&shader.module, m.ty, m.offset as usize, &path, &mut bytes, lookup);
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
