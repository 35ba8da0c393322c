//! Shader loading: GLSL 450 files, `#include` splicing, naga parsing and validation,
//! diagnostics as `path:line:column`, WGSL output and uniform-block reflection.
//!
//! naga's GLSL front end accepts only `#version 440+` with Vulkan semantics: every uniform
//! block needs `layout(set, binding)`, every in/out a `layout(location)`, there is no
//! `gl_FragColor` and no `#include`. This module is the one place that knows that. Shared
//! snippets (`transform.glsl`, `noise.glsl`) are spliced in here, line by line, and a line map
//! turns naga's positions in the spliced text back into the file the user edited.

use std::borrow::Cow;
use std::collections::HashSet;
use std::path::{Path, PathBuf};

use naga::valid::{Capabilities, ModuleInfo, ValidationFlags, Validator};
use naga::ShaderStage;

use crate::error::{Error, Result};

mod embedded {
    include!(concat!(env!("OUT_DIR"), "/embedded_shaders.rs"));
}

/// Names of every shader file built into the binary (the contents of `shaders_glsl/`).
pub fn embedded_names() -> impl Iterator<Item = &'static str> {
    embedded::EMBEDDED.iter().map(|(name, _)| *name)
}

/// The text of a shader built into the binary.
pub fn embedded_source(name: &str) -> Option<&'static str> {
    embedded::EMBEDDED.iter().find(|(n, _)| *n == name).map(|(_, s)| *s)
}

/// Where shader files come from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ShaderSource {
    /// The copies of `shaders_glsl/` built into the binary.
    Embedded,
    /// A directory on disk with the same file names (`--shaders DIR`, live reload).
    Dir(PathBuf),
}

impl ShaderSource {
    /// A directory source; fails if `dir` is not a readable directory.
    pub fn dir(dir: impl Into<PathBuf>) -> Result<Self> {
        let dir = dir.into();
        if !dir.is_dir() {
            return Err(Error::Io {
                path: dir,
                source: std::io::Error::new(std::io::ErrorKind::NotFound, "shader directory not found"),
            });
        }
        Ok(ShaderSource::Dir(dir))
    }

    /// `shaders_glsl/` of the source tree, when running from a checkout (for live reload).
    pub fn source_tree() -> Option<Self> {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders_glsl");
        dir.is_dir().then_some(ShaderSource::Dir(dir))
    }

    /// The path shown in messages for `name`.
    pub fn display_path(&self, name: &str) -> String {
        match self {
            ShaderSource::Embedded => format!("shaders_glsl/{name}"),
            ShaderSource::Dir(dir) => dir.join(name).display().to_string(),
        }
    }

    /// Reads one file.
    pub fn read(&self, name: &str) -> Result<String> {
        match self {
            ShaderSource::Embedded => embedded_source(name)
                .map(str::to_owned)
                .ok_or_else(|| Error::ShaderNotFound(self.display_path(name))),
            ShaderSource::Dir(dir) => {
                let path = dir.join(name);
                std::fs::read_to_string(&path).map_err(|source| {
                    if source.kind() == std::io::ErrorKind::NotFound {
                        Error::ShaderNotFound(path.display().to_string())
                    } else {
                        Error::Io { path, source }
                    }
                })
            }
        }
    }

    /// Reads, splices and compiles `name` (stage from its extension).
    pub fn compile(&self, name: &str) -> Result<CompiledShader> {
        let stage = stage_of(name)?;
        let text = self.read(name)?;
        let path = self.display_path(name);
        compile_text(&path, &text, stage, &|include: &str| {
            self.read(include).map(|t| (self.display_path(include), t))
        })
    }
}

/// The shader stage named by a file's extension: `.vert`, `.frag` or `.comp`.
pub fn stage_of(name: &str) -> Result<ShaderStage> {
    match Path::new(name).extension().and_then(|e| e.to_str()) {
        Some("vert") => Ok(ShaderStage::Vertex),
        Some("frag") => Ok(ShaderStage::Fragment),
        Some("comp") => Ok(ShaderStage::Compute),
        _ => Err(Error::Param(format!(
            "{name}: cannot tell the shader stage; use the extension .vert, .frag or .comp"
        ))),
    }
}

/// Text after splicing, with where each of its lines came from.
#[derive(Clone, Debug)]
pub struct Spliced {
    /// The text naga sees.
    pub text: String,
    /// For each line of `text` (0-based), the file (display path) and its 1-based line.
    pub line_map: Vec<(String, u32)>,
}

impl Spliced {
    /// Maps a 1-based line of the spliced text to (file, 1-based line).
    pub fn origin(&self, line: u32) -> (String, u32) {
        self.line_map
            .get(line.saturating_sub(1) as usize)
            .cloned()
            .unwrap_or_else(|| (self.line_map.first().map(|l| l.0.clone()).unwrap_or_default(), line))
    }
}

/// Resolves an `#include "name"` to (display path, text).
pub type IncludeResolver<'a> = dyn Fn(&str) -> Result<(String, String)> + 'a;

/// Splices `#include "file"` lines (recursively, each file once).
pub fn splice(path: &str, text: &str, resolve: &IncludeResolver) -> Result<Spliced> {
    let mut out = Spliced {
        text: String::new(),
        line_map: Vec::new(),
    };
    let mut seen = HashSet::new();
    splice_into(&mut out, path, text, resolve, &mut seen, 0)?;
    Ok(out)
}

fn splice_into(
    out: &mut Spliced,
    path: &str,
    text: &str,
    resolve: &IncludeResolver,
    seen: &mut HashSet<String>,
    depth: usize,
) -> Result<()> {
    for (i, line) in text.lines().enumerate() {
        let line_no = i as u32 + 1;
        let trimmed = line.trim_start();
        if let Some(rest) = trimmed.strip_prefix("#include") {
            let column = (line.len() - trimmed.len()) as u32 + 1;
            let name = rest.trim().trim_matches(|c| c == '"' || c == '<' || c == '>');
            let fail = |msg: String| Error::Shader {
                file: path.to_owned(),
                line: line_no,
                column,
                message: format_diagnostic(path, line_no, column, &msg, line, 8),
            };
            if name.is_empty() || depth > 8 {
                return Err(fail("#include needs a file name, as in #include \"noise.glsl\"".into()));
            }
            if !seen.insert(name.to_owned()) {
                continue; // each snippet once, like an include guard
            }
            let (inc_path, inc_text) = resolve(name).map_err(|e| fail(format!("cannot include {name:?}: {e}")))?;
            splice_into(out, &inc_path, &inc_text, resolve, seen, depth + 1)?;
        } else {
            out.text.push_str(line);
            out.text.push('\n');
            out.line_map.push((path.to_owned(), line_no));
        }
    }
    Ok(())
}

/// Formats `path:line:column: message`, the source line and a caret under the column.
pub fn format_diagnostic(path: &str, line: u32, column: u32, message: &str, source_line: &str, len: usize) -> String {
    let caret_pad: String = source_line
        .chars()
        .take(column.saturating_sub(1) as usize)
        .map(|c| if c == '\t' { '\t' } else { ' ' })
        .collect();
    let len = len.clamp(1, source_line.len().saturating_sub(column as usize - 1).max(1));
    format!(
        "{path}:{line}:{column}: {message}\n {line:>4} | {source_line}\n      | {caret_pad}{}",
        "^".repeat(len)
    )
}

/// A parsed and validated shader.
#[derive(Debug)]
pub struct CompiledShader {
    /// Display path of the main file.
    pub path: String,
    /// Its stage.
    pub stage: ShaderStage,
    /// The spliced source naga parsed.
    pub source: Spliced,
    /// naga's IR.
    pub module: naga::Module,
    /// Validation results (needed for WGSL output).
    pub info: ModuleInfo,
}

/// Splices, parses and validates GLSL text.
pub fn compile_text(path: &str, text: &str, stage: ShaderStage, resolve: &IncludeResolver) -> Result<CompiledShader> {
    let source = splice(path, text, resolve)?;
    let mut frontend = naga::front::glsl::Frontend::default();
    let module = frontend
        .parse(&naga::front::glsl::Options::from(stage), &source.text)
        .map_err(|errors| {
            let spans: Vec<(naga::Span, String)> = errors
                .errors
                .iter()
                .map(|e| parse_error_span(&source.text, e))
                .collect();
            shader_error(&source, &spans)
        })?;
    let info = Validator::new(ValidationFlags::all(), Capabilities::all())
        .validate(&module)
        .map_err(|err| {
            let mut message = err.as_inner().to_string();
            let mut source_err: &dyn std::error::Error = err.as_inner();
            while let Some(next) = source_err.source() {
                message.push_str(": ");
                message.push_str(&next.to_string());
                source_err = next;
            }
            // naga lists the outermost span first (the whole function) and the offending
            // expression last: point at the innermost one.
            let span = err.spans().last().map(|(s, _)| *s).unwrap_or_default();
            shader_error(&source, &[(span, message)])
        })?;
    Ok(CompiledShader {
        path: path.to_owned(),
        stage,
        source,
        module,
        info,
    })
}

/// naga reports a missing `;` at the next token, often on the next line; point at the end of
/// the line that lacks it instead, as C compilers do.
fn parse_error_span(text: &str, error: &naga::front::glsl::Error) -> (naga::Span, String) {
    use naga::front::glsl::{ErrorKind, ExpectedToken, TokenValue};
    let message = error.kind.to_string();
    let wants_semicolon = matches!(&error.kind, ErrorKind::InvalidToken(_, expected)
        if expected.contains(&ExpectedToken::Token(TokenValue::Semicolon)));
    let start = error.meta.to_range().map(|r| r.start).filter(|&s| s <= text.len());
    if let (true, Some(start)) = (wants_semicolon, start) {
        let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
        if text[line_start..start].trim().is_empty() {
            // The offending token starts its line: find the end of the previous code line.
            let mut end = line_start;
            while end > 0 {
                let prev_start = text[..end - 1].rfind('\n').map_or(0, |i| i + 1);
                let line = &text[prev_start..end - 1];
                let code = line.split("//").next().unwrap_or("").trim_end();
                if !code.trim().is_empty() {
                    let at = (prev_start + code.len()) as u32;
                    let next = error.meta.to_range().and_then(|r| text.get(r)).unwrap_or("").trim();
                    let message = format!("expected `;` at the end of this line, before `{next}`");
                    return (naga::Span::new(at, at), message);
                }
                end = prev_start;
            }
        }
    }
    (error.meta, message)
}

fn shader_error(source: &Spliced, spans: &[(naga::Span, String)]) -> Error {
    let mut messages = Vec::new();
    let mut first = None;
    for (span, msg) in spans {
        let (file, line, column, src_line, len) =
            if span.is_defined() && span.to_range().is_some_and(|r| r.start <= source.text.len()) {
                let loc = span.location(&source.text);
                let (file, line) = source.origin(loc.line_number);
                let src_line = source
                    .text
                    .lines()
                    .nth(loc.line_number as usize - 1)
                    .unwrap_or("")
                    .to_owned();
                (file, line, loc.line_position, src_line, loc.length as usize)
            } else {
                let (file, _) = source.origin(1);
                (file, 1, 1, String::new(), 1)
            };
        first.get_or_insert((file.clone(), line, column));
        messages.push(format_diagnostic(&file, line, column, msg, &src_line, len));
    }
    let (file, line, column) = first.unwrap_or_default();
    Error::Shader {
        file,
        line,
        column,
        message: messages.join("\n"),
    }
}

impl CompiledShader {
    /// The shader as WGSL text.
    pub fn to_wgsl(&self) -> Result<String> {
        naga::back::wgsl::write_string(&self.module, &self.info, naga::back::wgsl::WriterFlags::EXPLICIT_TYPES)
            .map_err(|e| Error::Param(format!("{}: WGSL output failed: {e}", self.path)))
    }

    /// Creates a wgpu shader module from the validated IR.
    pub fn create_module(&self, device: &wgpu::Device, label: &str) -> wgpu::ShaderModule {
        device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(label),
            source: wgpu::ShaderSource::Naga(Cow::Owned(self.module.clone())),
        })
    }

    /// The std140 layout naga gives the uniform block named `block` (type or instance name).
    pub fn uniform_block(&self, block: &str) -> Option<BlockLayout> {
        let module = &self.module;
        module.global_variables.iter().find_map(|(_, var)| {
            if var.space != naga::AddressSpace::Uniform {
                return None;
            }
            let ty = &module.types[var.ty];
            let matches = ty.name.as_deref() == Some(block) || var.name.as_deref() == Some(block);
            match &ty.inner {
                naga::TypeInner::Struct { members, span } if matches => Some(BlockLayout {
                    name: block.to_owned(),
                    size: *span as usize,
                    binding: var.binding.as_ref().map(|b| b.binding),
                    members: members
                        .iter()
                        .map(|m| MemberLayout {
                            name: m.name.clone().unwrap_or_default(),
                            offset: m.offset as usize,
                            components: components_of(&module.types[m.ty].inner),
                        })
                        .collect(),
                }),
                _ => None,
            }
        })
    }
}

fn components_of(inner: &naga::TypeInner) -> usize {
    match inner {
        naga::TypeInner::Scalar(_) => 1,
        naga::TypeInner::Vector { size, .. } => *size as usize,
        naga::TypeInner::Matrix { columns, rows, .. } => *columns as usize * *rows as usize,
        _ => 0,
    }
}

/// A uniform block as naga lays it out.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BlockLayout {
    /// Block name.
    pub name: String,
    /// Size in bytes.
    pub size: usize,
    /// `layout(binding = N)`.
    pub binding: Option<u32>,
    /// Members in order.
    pub members: Vec<MemberLayout>,
}

/// One member of a uniform block.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MemberLayout {
    /// GLSL name.
    pub name: String,
    /// Byte offset.
    pub offset: usize,
    /// Number of f32 components (1 for float, 3 for vec3, 16 for mat4).
    pub components: usize,
}

impl BlockLayout {
    /// The member called `name`.
    pub fn member(&self, name: &str) -> Option<&MemberLayout> {
        self.members.iter().find(|m| m.name == name)
    }
}

/// A Rust struct that feeds one GLSL uniform block. Implement it with [`uniform_block!`](crate::uniform_block).
pub trait UniformBlock: bytemuck::Pod {
    /// The GLSL block name.
    const BLOCK: &'static str;
    /// (GLSL member name, byte offset in the Rust struct) for every member.
    const FIELDS: &'static [(&'static str, usize)];
}

/// Implements [`UniformBlock`] for a `#[repr(C)]` struct: `uniform_block!(PhongUniforms, "PhongParams", { light_position: "lightPosition", ... })`.
#[macro_export]
macro_rules! uniform_block {
    ($ty:ty, $block:literal, { $($field:ident : $glsl:literal),* $(,)? }) => {
        impl $crate::shader::UniformBlock for $ty {
            const BLOCK: &'static str = $block;
            const FIELDS: &'static [(&'static str, usize)] = &[$(($glsl, ::core::mem::offset_of!($ty, $field))),*];
        }
    };
}

/// Checks a Rust uniform struct against the block naga reflected: size and every member offset.
pub fn check_layout<T: UniformBlock>(rust_name: &str, block: &BlockLayout) -> Result<()> {
    let rust_size = std::mem::size_of::<T>();
    let mut problems = Vec::new();
    if rust_size != block.size {
        problems.push(format!(
            "struct {rust_name} is {rust_size} bytes but GLSL block {} is {} bytes",
            block.name, block.size
        ));
    }
    for member in &block.members {
        match T::FIELDS.iter().find(|(n, _)| *n == member.name) {
            None => problems.push(format!(
                "GLSL block {} member `{}` (offset {}) has no field in struct {rust_name}",
                block.name, member.name, member.offset
            )),
            Some((_, off)) if *off != member.offset => problems.push(format!(
                "struct {rust_name} field for `{}` is at offset {off} but GLSL block {} puts it at offset {}",
                member.name, block.name, member.offset
            )),
            _ => {}
        }
    }
    for (name, off) in T::FIELDS {
        if block.member(name).is_none() {
            problems.push(format!(
                "struct {rust_name} field `{name}` (offset {off}) is not a member of GLSL block {}",
                block.name
            ));
        }
    }
    if problems.is_empty() {
        Ok(())
    } else {
        Err(Error::Layout(problems.join("; ")))
    }
}

/// Sets the member `name` of a uniform struct from f32 values, by the reflected layout.
/// Fails with the list of valid names when `name` is unknown, and on a wrong component count.
pub fn set_member<T: UniformBlock>(value: &mut T, block: &BlockLayout, name: &str, values: &[f32]) -> Result<()> {
    let member = block.member(name).ok_or_else(|| {
        let valid: Vec<&str> = block.members.iter().map(|m| m.name.as_str()).collect();
        Error::Param(format!("unknown parameter `{name}`; valid: {}", valid.join(", ")))
    })?;
    if values.len() != member.components {
        return Err(Error::Param(format!(
            "parameter `{name}` takes {} number(s), got {}",
            member.components,
            values.len()
        )));
    }
    let bytes = bytemuck::bytes_of_mut(value);
    let end = member.offset + 4 * values.len();
    if end > bytes.len() {
        return Err(Error::Layout(format!("member `{name}` lies outside the Rust struct")));
    }
    bytes[member.offset..end].copy_from_slice(bytemuck::cast_slice(values));
    Ok(())
}

/// Reads the member `name` of a uniform struct as f32 values.
pub fn get_member<T: UniformBlock>(value: &T, block: &BlockLayout, name: &str) -> Option<Vec<f32>> {
    let member = block.member(name)?;
    let bytes = bytemuck::bytes_of(value);
    let slice = bytes.get(member.offset..member.offset + 4 * member.components)?;
    Some(
        slice
            .chunks_exact(4)
            .map(|c| f32::from_ne_bytes([c[0], c[1], c[2], c[3]]))
            .collect(),
    )
}
