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
        if dir.exists() && !dir.is_dir() {
            return Err(Error::Io {
                path: dir,
                source: std::io::Error::new(
                    std::io::ErrorKind::InvalidInput,
                    "is not a directory; --shaders takes a folder holding the shader files",
                ),
            });
        }
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

    /// Reads one file: `name` must lie inside the directory (see [`resolve_in_dir`]) and be a
    /// regular file of at most [`MAX_SHADER_BYTES`].
    pub fn read(&self, name: &str) -> Result<String> {
        match self {
            ShaderSource::Embedded => embedded_source(name)
                .map(str::to_owned)
                .ok_or_else(|| Error::ShaderNotFound(self.display_path(name))),
            ShaderSource::Dir(dir) => read_shader_file(&resolve_in_dir(dir, name)?),
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

/// The largest shader file the loader reads (1 MiB); the course's largest is under 4 KiB.
pub const MAX_SHADER_BYTES: u64 = 1 << 20;

fn io_error(path: &Path, kind: std::io::ErrorKind, message: String) -> Error {
    Error::Io {
        path: path.to_owned(),
        source: std::io::Error::new(kind, message),
    }
}

/// The file `name` names inside `dir`, for `--shaders DIR` and `#include`: a relative path
/// (no root, no drive) that stays inside `dir` once symbolic links and `..` are resolved.
/// A missing file is [`Error::ShaderNotFound`]; a name that reaches outside is [`Error::Param`].
pub fn resolve_in_dir(dir: &Path, name: &str) -> Result<PathBuf> {
    use std::path::Component;
    let relative = Path::new(name);
    if name.is_empty() {
        return Err(Error::Param("an empty shader file name".into()));
    }
    if relative
        .components()
        .any(|c| matches!(c, Component::RootDir | Component::Prefix(_)))
    {
        return Err(Error::Param(format!(
            "{name} is an absolute path; shader files and #include must name files inside the \
             shader directory ({})",
            dir.display()
        )));
    }
    let path = dir.join(relative);
    let outside = || {
        Error::Param(format!(
            "{name} lies outside the shader directory ({}); shader files and #include must name \
             files inside it",
            dir.display()
        ))
    };
    let canonical_dir = std::fs::canonicalize(dir).map_err(|source| Error::Io {
        path: dir.to_owned(),
        source,
    })?;
    match std::fs::canonicalize(&path) {
        Ok(canonical) if canonical.starts_with(&canonical_dir) => Ok(canonical),
        Ok(_) => Err(outside()),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            // Missing: still refuse a name that climbs out with `..`, so the message is right.
            let mut depth = 0usize;
            for c in relative.components() {
                match c {
                    Component::ParentDir if depth == 0 => return Err(outside()),
                    Component::ParentDir => depth -= 1,
                    Component::Normal(_) => depth += 1,
                    _ => {}
                }
            }
            Err(Error::ShaderNotFound(path.display().to_string()))
        }
        Err(source) => Err(Error::Io { path, source }),
    }
}

/// Reads a shader file from disk: a regular file (not a device, pipe or directory) of at most
/// [`MAX_SHADER_BYTES`], in UTF-8.
pub fn read_shader_file(path: &Path) -> Result<String> {
    use std::io::Read;
    let not_found = |e: std::io::Error| {
        if e.kind() == std::io::ErrorKind::NotFound {
            Error::ShaderNotFound(path.display().to_string())
        } else {
            Error::Io {
                path: path.to_owned(),
                source: e,
            }
        }
    };
    // Check before opening: opening a FIFO would block.
    let meta = std::fs::metadata(path).map_err(not_found)?;
    if !meta.is_file() {
        let what = if meta.is_dir() {
            "a directory"
        } else {
            "not a regular file"
        };
        return Err(io_error(
            path,
            std::io::ErrorKind::InvalidInput,
            format!("{what}; a shader must be a text file"),
        ));
    }
    let too_big = |size: u64| {
        io_error(
            path,
            std::io::ErrorKind::InvalidData,
            format!(
                "{size} bytes; shader files are limited to {} bytes (1 MiB)",
                MAX_SHADER_BYTES
            ),
        )
    };
    if meta.len() > MAX_SHADER_BYTES {
        return Err(too_big(meta.len()));
    }
    let file = std::fs::File::open(path).map_err(not_found)?;
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    file.take(MAX_SHADER_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|source| Error::Io {
            path: path.to_owned(),
            source,
        })?;
    if bytes.len() as u64 > MAX_SHADER_BYTES {
        return Err(too_big(bytes.len() as u64));
    }
    String::from_utf8(bytes).map_err(|e| {
        io_error(
            path,
            std::io::ErrorKind::InvalidData,
            format!(
                "not UTF-8 text (invalid byte at offset {})",
                e.utf8_error().valid_up_to()
            ),
        )
    })
}

/// Compiles a GLSL file anywhere on disk (the `glsl2wgsl` tool): the stage from its extension,
/// `#include` resolved inside the file's directory (as [`resolve_in_dir`]), then to the
/// snippets built into the binary.
pub fn compile_file(path: &Path) -> Result<CompiledShader> {
    let name = path.display().to_string();
    let stage = stage_of(&name)?;
    let text = read_shader_file(path)?;
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_owned(),
        _ => PathBuf::from("."),
    };
    let display_dir = path.parent().unwrap_or(Path::new(""));
    compile_text(
        &name,
        &text,
        stage,
        &|include: &str| match resolve_in_dir(&dir, include) {
            Ok(file) => Ok((
                display_dir.join(include).display().to_string(),
                read_shader_file(&file)?,
            )),
            Err(Error::ShaderNotFound(local)) => embedded_source(include)
                .map(|t| (format!("shaders_glsl/{include}"), t.to_owned()))
                .ok_or(Error::ShaderNotFound(local)),
            Err(e) => Err(e),
        },
    )
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

/// How deep `#include`s may nest: the main file plus this many levels of snippets.
pub const MAX_INCLUDE_DEPTH: usize = 8;

/// Splices `#include "file"` lines (recursively, each file once). A UTF-8 byte order mark at
/// the start of a file is skipped. Fails on a malformed `#include` line, a file that includes
/// itself (directly or through others), and includes nested deeper than [`MAX_INCLUDE_DEPTH`].
pub fn splice(path: &str, text: &str, resolve: &IncludeResolver) -> Result<Spliced> {
    let mut splicer = Splicer {
        out: Spliced {
            text: String::new(),
            line_map: Vec::new(),
        },
        resolve,
        seen: HashSet::new(),
        stack: Vec::new(),
    };
    let name = Path::new(path)
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    splicer.splice_into(&name, path, text)?;
    Ok(splicer.out)
}

/// An `#include` line, parsed.
#[derive(Debug, PartialEq, Eq)]
enum IncludeLine<'a> {
    /// Not an `#include` directive.
    No,
    /// `#include "name"` or `#include <name>`, with an optional comment after it.
    Name(&'a str),
    /// A malformed `#include`: the 0-based byte column of the problem and what is wrong.
    Bad(usize, String),
}

const INCLUDE_EXAMPLE: &str = "as in #include \"noise.glsl\"";

/// Parses one line as a preprocessor `#include` (`#` and `include` may be apart, as in C).
fn parse_include(line: &str) -> IncludeLine<'_> {
    let start = line.len() - line.trim_start().len();
    let Some(after_hash) = line[start..].strip_prefix('#') else {
        return IncludeLine::No;
    };
    let directive = after_hash.trim_start_matches([' ', '\t']);
    let Some(rest) = directive.strip_prefix("include") else {
        return IncludeLine::No;
    };
    if rest.starts_with(|c: char| c.is_alphanumeric() || c == '_') {
        return IncludeLine::No; // `#includes`, `#include_foo`: another directive
    }
    let at = |s: &str| line.len() - s.len();
    let args = rest.trim_start();
    let close = match args.chars().next() {
        None => return IncludeLine::Bad(start, format!("#include needs a file name, {INCLUDE_EXAMPLE}")),
        Some('"') => '"',
        Some('<') => '>',
        Some(_) => {
            return IncludeLine::Bad(
                at(args),
                format!("#include needs the file name in quotes, {INCLUDE_EXAMPLE}"),
            )
        }
    };
    let Some(len) = args[1..].find(close) else {
        return IncludeLine::Bad(
            at(args),
            format!("the file name of #include lacks its closing `{close}`, {INCLUDE_EXAMPLE}"),
        );
    };
    let name = &args[1..1 + len];
    if name.trim().is_empty() {
        return IncludeLine::Bad(at(args), format!("#include needs a file name, {INCLUDE_EXAMPLE}"));
    }
    // After the name: nothing, a `//` comment, or `/* ... */` comments.
    let mut tail = args[2 + len..].trim_start();
    loop {
        if tail.is_empty() || tail.starts_with("//") {
            return IncludeLine::Name(name);
        }
        if let Some(comment) = tail.strip_prefix("/*") {
            match comment.find("*/") {
                Some(end) => tail = comment[end + 2..].trim_start(),
                None => {
                    return IncludeLine::Bad(at(tail), "a /* comment after #include must end on the same line".into())
                }
            }
            continue;
        }
        return IncludeLine::Bad(
            at(tail),
            format!("unexpected `{}` after #include {:?}", tail.trim_end(), name),
        );
    }
}

struct Splicer<'r, 'a> {
    out: Spliced,
    resolve: &'r IncludeResolver<'a>,
    /// Include names spliced so far (each once).
    seen: HashSet<String>,
    /// The files being spliced, outermost first: (name, display path).
    stack: Vec<(String, String)>,
}

impl Splicer<'_, '_> {
    fn chain(&self, last: &str) -> String {
        let mut names: Vec<&str> = self
            .stack
            .iter()
            .map(|(n, p)| if n.is_empty() { p.as_str() } else { n.as_str() })
            .collect();
        names.push(last);
        names.join(" -> ")
    }

    fn splice_into(&mut self, name: &str, path: &str, text: &str) -> Result<()> {
        self.stack.push((name.to_owned(), path.to_owned()));
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        for (i, line) in text.lines().enumerate() {
            let line_no = i as u32 + 1;
            let fail = |column: usize, msg: String| {
                let column = line[..column.min(line.len())].chars().count() as u32 + 1;
                Error::Shader {
                    file: path.to_owned(),
                    line: line_no,
                    column,
                    message: format_diagnostic(path, line_no, column, &msg, line, 8),
                }
            };
            let hash = line.len() - line.trim_start().len();
            let include = match parse_include(line) {
                IncludeLine::No => {
                    self.out.text.push_str(line);
                    self.out.text.push('\n');
                    self.out.line_map.push((path.to_owned(), line_no));
                    continue;
                }
                IncludeLine::Bad(column, msg) => return Err(fail(column, msg)),
                IncludeLine::Name(include) => include,
            };
            if self.stack.iter().any(|(n, _)| n == include) {
                let itself = self.stack.last().is_some_and(|(n, _)| n == include);
                return Err(fail(hash, self.cycle_message(include, itself)));
            }
            if !self.seen.insert(include.to_owned()) {
                continue; // each snippet once, like an include guard
            }
            let (inc_path, inc_text) =
                (self.resolve)(include).map_err(|e| fail(hash, format!("cannot include {include:?}: {e}")))?;
            if self.stack.iter().any(|(_, p)| *p == inc_path) {
                let itself = self.stack.last().is_some_and(|(_, p)| *p == inc_path);
                return Err(fail(hash, self.cycle_message(include, itself)));
            }
            if self.stack.len() > MAX_INCLUDE_DEPTH {
                return Err(fail(
                    hash,
                    format!(
                        "includes nested deeper than {MAX_INCLUDE_DEPTH}: {}",
                        self.chain(include)
                    ),
                ));
            }
            self.splice_into(include, &inc_path, &inc_text)?;
        }
        self.stack.pop();
        Ok(())
    }

    /// The message for an `#include` of a file that is being spliced already; `itself` when it
    /// is the file that has the `#include` line.
    fn cycle_message(&self, include: &str, itself: bool) -> String {
        if itself {
            format!("{include} includes itself; remove this #include")
        } else {
            format!("#include cycle: {}; remove one of these #includes", self.chain(include))
        }
    }
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
    if text.trim_start_matches('\u{feff}').trim().is_empty() {
        return Err(Error::Shader {
            file: path.to_owned(),
            line: 1,
            column: 1,
            message: format!(
                "{path}: the file is empty; a {} shader needs `#version 450` and a `void main()`",
                stage_name(stage)
            ),
        });
    }
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
            shader_error(path, stage, &source, &spans)
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
            shader_error(path, stage, &source, &[(span, message)])
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

fn stage_name(stage: ShaderStage) -> &'static str {
    match stage {
        ShaderStage::Vertex => "vertex",
        ShaderStage::Fragment => "fragment",
        ShaderStage::Compute => "compute",
        _ => "shader",
    }
}

/// One [`Error::Shader`] for naga's errors; `path` is the main file, named by errors that
/// have no position (naga's "Missing entry point").
fn shader_error(path: &str, stage: ShaderStage, source: &Spliced, spans: &[(naga::Span, String)]) -> Error {
    let mut messages = Vec::new();
    let mut first = None;
    for (span, msg) in spans {
        if span.is_defined() && span.to_range().is_some_and(|r| r.start <= source.text.len()) {
            let loc = span.location(&source.text);
            let (file, line) = source.origin(loc.line_number);
            let src_line = source
                .text
                .lines()
                .nth(loc.line_number as usize - 1)
                .unwrap_or("")
                .to_owned();
            first.get_or_insert((file.clone(), line, loc.line_position));
            messages.push(format_diagnostic(
                &file,
                line,
                loc.line_position,
                msg,
                &src_line,
                loc.length as usize,
            ));
        } else {
            first.get_or_insert((path.to_owned(), 1, 1));
            let msg = if msg == "Missing entry point" {
                format!(
                    "no `void main()` found; a {} shader needs one (naga: {msg})",
                    stage_name(stage)
                )
            } else {
                msg.clone()
            };
            messages.push(format!("{path}: {msg}"));
        }
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

    /// The std140 layout naga gives the uniform block named `block` (type or instance name),
    /// with every member's type.
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
                        .map(|m| {
                            let ty = MemberType::of(module, &module.types[m.ty].inner);
                            MemberLayout {
                                name: m.name.clone().unwrap_or_default(),
                                offset: m.offset as usize,
                                components: ty.map_or(0, |t| t.components()),
                                ty,
                            }
                        })
                        .collect(),
                }),
                _ => None,
            }
        })
    }
}

/// The scalar type of a uniform member (naga's GLSL front end accepts no `bool` in a uniform
/// block: it is not host-shareable; [`ScalarKind::Bool`] is there for completeness).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ScalarKind {
    /// `float`, 4 bytes.
    F32,
    /// `int`, 4 bytes.
    I32,
    /// `uint`, 4 bytes.
    U32,
    /// `bool`, 4 bytes in a buffer (fed by a Rust `u32`, 0 or 1).
    Bool,
    /// `double`, 8 bytes.
    F64,
}

impl ScalarKind {
    /// Bytes of one value.
    pub const fn size(self) -> usize {
        match self {
            ScalarKind::F64 => 8,
            _ => 4,
        }
    }

    fn of(scalar: naga::Scalar) -> Option<Self> {
        use naga::ScalarKind as K;
        match (scalar.kind, scalar.width) {
            (K::Float, 4) => Some(ScalarKind::F32),
            (K::Float, 8) => Some(ScalarKind::F64),
            (K::Sint, 4) => Some(ScalarKind::I32),
            (K::Uint, 4) => Some(ScalarKind::U32),
            (K::Bool, _) => Some(ScalarKind::Bool),
            _ => None,
        }
    }

    /// The GLSL scalar type (`float`, `int`, `uint`, `bool`, `double`).
    pub const fn glsl(self) -> &'static str {
        match self {
            ScalarKind::F32 => "float",
            ScalarKind::I32 => "int",
            ScalarKind::U32 => "uint",
            ScalarKind::Bool => "bool",
            ScalarKind::F64 => "double",
        }
    }

    /// The prefix of GLSL vectors and matrices of this kind (`vec3`, `ivec3`, `dmat4`, ...).
    const fn glsl_prefix(self) -> &'static str {
        match self {
            ScalarKind::F32 => "",
            ScalarKind::I32 => "i",
            ScalarKind::U32 => "u",
            ScalarKind::Bool => "b",
            ScalarKind::F64 => "d",
        }
    }

    /// The Rust type that holds one value (`bool` is a `u32`).
    pub const fn rust(self) -> &'static str {
        match self {
            ScalarKind::F32 => "f32",
            ScalarKind::I32 => "i32",
            ScalarKind::U32 | ScalarKind::Bool => "u32",
            ScalarKind::F64 => "f64",
        }
    }

    /// Whether a Rust field of kind `rust` can feed a member of this kind.
    fn fed_by(self, rust: ScalarKind) -> bool {
        self == rust || (self == ScalarKind::Bool && rust == ScalarKind::U32)
    }
}

/// An array's length and the bytes from one element to the next.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ArrayLayout {
    /// Number of elements.
    pub len: usize,
    /// Bytes between elements (std140: a multiple of 16).
    pub stride: usize,
}

/// The type of a uniform-block member as naga lays it out: a scalar, vector or matrix, or an
/// array of one of those.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MemberType {
    /// The scalar kind.
    pub scalar: ScalarKind,
    /// Components of a vector (1 for a scalar), or rows of a matrix.
    pub rows: usize,
    /// Columns of a matrix; 1 for scalars and vectors.
    pub columns: usize,
    /// Bytes between matrix columns (std140 pads a `vec3` column to 16); 0 unless a matrix.
    pub column_stride: usize,
    /// Length and stride when the member is an array.
    pub array: Option<ArrayLayout>,
}

impl MemberType {
    /// A non-array type, or `None` for one reflection does not describe (structs, nested
    /// arrays, runtime-sized arrays, atomics, ...).
    fn of(module: &naga::Module, inner: &naga::TypeInner) -> Option<MemberType> {
        match inner {
            naga::TypeInner::Array {
                base,
                size: naga::ArraySize::Constant(len),
                stride,
            } => {
                let element = Self::element(&module.types[*base].inner)?;
                Some(MemberType {
                    array: Some(ArrayLayout {
                        len: len.get() as usize,
                        stride: *stride as usize,
                    }),
                    ..element
                })
            }
            inner => Self::element(inner),
        }
    }

    fn element(inner: &naga::TypeInner) -> Option<MemberType> {
        let plain = |scalar: naga::Scalar, rows: usize, columns: usize| {
            let kind = ScalarKind::of(scalar)?;
            // naga's column alignment: a vec2 column aligns to 2 values, vec3 and vec4 to 4;
            // a uniform (std140) block rounds it up to 16 bytes.
            let column_stride = if columns > 1 {
                (if rows == 2 { 2 } else { 4 } * kind.size()).max(16)
            } else {
                0
            };
            Some(MemberType {
                scalar: kind,
                rows,
                columns,
                column_stride,
                array: None,
            })
        };
        match *inner {
            naga::TypeInner::Scalar(scalar) => plain(scalar, 1, 1),
            naga::TypeInner::Vector { size, scalar } => plain(scalar, size as usize, 1),
            naga::TypeInner::Matrix { columns, rows, scalar } => plain(scalar, rows as usize, columns as usize),
            _ => None,
        }
    }

    /// Whether this is a matrix (or an array of them).
    pub fn is_matrix(&self) -> bool {
        self.columns > 1
    }

    /// Values in one element (columns × rows).
    pub fn element_components(&self) -> usize {
        self.columns * self.rows
    }

    /// Array elements (1 for a non-array).
    pub fn elements(&self) -> usize {
        self.array.map_or(1, |a| a.len)
    }

    /// Values in the whole member.
    pub fn components(&self) -> usize {
        self.elements() * self.element_components()
    }

    /// The GLSL name of one element: `float`, `ivec2`, `mat3`, `mat4x3`, `dvec4`.
    pub fn element_glsl(&self) -> String {
        let p = self.scalar.glsl_prefix();
        match (self.columns, self.rows) {
            (1, 1) => self.scalar.glsl().to_owned(),
            (1, n) => format!("{p}vec{n}"),
            (c, r) if c == r => format!("{p}mat{c}"),
            (c, r) => format!("{p}mat{c}x{r}"),
        }
    }

    /// The member declared as in GLSL: `vec4 colors[3]`, `int Ka`.
    pub fn declaration(&self, name: &str) -> String {
        match self.array {
            Some(a) => format!("{} {name}[{}]", self.element_glsl(), a.len),
            None => format!("{} {name}", self.element_glsl()),
        }
    }

    /// (byte offset from the member's start, values there) for each run of tightly packed
    /// values of `elements` (a vector, a matrix column, an array element's column).
    fn runs(&self, elements: std::ops::Range<usize>) -> Vec<(usize, usize)> {
        let stride = self.array.map_or(0, |a| a.stride);
        elements
            .flat_map(|e| (0..self.columns).map(move |c| (e * stride + c * self.column_stride, self.rows)))
            .collect()
    }

    /// The memory form of this type: (is a matrix or array, slots, values per slot, bytes
    /// between slots). A slot is a vector, a matrix column or an array element's column.
    fn slots(&self) -> Option<(bool, usize, usize, usize)> {
        match self.array {
            None if self.is_matrix() => Some((true, self.columns, self.rows, self.column_stride)),
            None => Some((false, 1, self.rows, 0)),
            Some(a) if !self.is_matrix() => Some((true, a.len, self.rows, a.stride)),
            // An array of matrices is its columns back to back when the stride says so.
            Some(a) if a.stride == self.columns * self.column_stride => {
                Some((true, a.len * self.columns, self.rows, self.column_stride))
            }
            Some(_) => None,
        }
    }

    /// The Rust type that feeds this member, e.g. `[[f32; 4]; 3]` for a `mat3` or `vec4[3]`.
    pub fn rust_suggestion(&self) -> String {
        let r = self.scalar.rust();
        match self.slots() {
            Some((false, _, 1, _)) => r.to_owned(),
            Some((false, _, n, _)) => format!("[{r}; {n}]"),
            Some((true, count, _, stride)) => format!("[[{r}; {}]; {count}]", stride / self.scalar.size()),
            None => "(no Rust type: the array stride does not match its matrices)".to_owned(),
        }
    }
}

impl std::fmt::Display for MemberType {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.array {
            Some(a) => write!(f, "{}[{}]", self.element_glsl(), a.len),
            None => f.write_str(&self.element_glsl()),
        }
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
    /// Number of values (1 for float, 3 for vec3, 9 for mat3, 12 for `vec4 colors[3]`);
    /// 0 for a type reflection does not describe.
    pub components: usize,
    /// The member's type; `None` for one reflection does not describe (a struct, a nested
    /// array).
    pub ty: Option<MemberType>,
}

impl MemberLayout {
    /// The member as GLSL declares it (`vec4 colors[3]`), for messages.
    pub fn declaration(&self) -> String {
        match &self.ty {
            Some(ty) => ty.declaration(&self.name),
            None => format!("{} (a struct or nested array)", self.name),
        }
    }
}

impl BlockLayout {
    /// The member called `name`.
    pub fn member(&self, name: &str) -> Option<&MemberLayout> {
        self.members.iter().find(|m| m.name == name)
    }
}

/// The memory form of a Rust field type that feeds a uniform member: a scalar `T`, a vector
/// `[T; W]` or an array of vectors `[[T; W]; N]` (matrix columns or array elements).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RustType {
    /// The scalar type.
    pub scalar: ScalarKind,
    /// Values in the innermost array (1 for a plain scalar).
    pub width: usize,
    /// Whether the innermost type is an array `[T; W]` (not a plain `T`).
    pub vector: bool,
    /// The outer array's length, for `[[T; W]; N]`.
    pub count: Option<usize>,
    /// A `#[repr(C)]` struct laid out as std140 (or an array of them), declared with
    /// [`glsl_struct!`](crate::glsl_struct): it feeds a GLSL struct member, checked by offset
    /// here and member by member where the struct itself is declared.
    pub composite: bool,
}

impl RustType {
    /// Whether a field of this type can feed `member`: the same scalar kind, and the same
    /// memory: a scalar or vector of the same width, or as many vectors as the member has
    /// columns or elements, as far apart as the member's stride, each wide enough for a column
    /// or element (std140's padding included: `[[f32; 4]; 3]` feeds a `mat3`).
    pub fn feeds(&self, member: &MemberType) -> bool {
        let Some((multi, slots, width, stride)) = member.slots() else {
            return false;
        };
        if !member.scalar.fed_by(self.scalar) {
            return false;
        }
        match self.count {
            None => !multi && self.width == width && (self.vector == (width > 1)),
            Some(count) => {
                multi
                    && self.vector
                    && count == slots
                    && self.width * self.scalar.size() == stride
                    && self.width >= width
            }
        }
    }
}

impl std::fmt::Display for RustType {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let inner = if self.composite {
            "(a std140 struct)".to_owned()
        } else if self.vector {
            format!("[{}; {}]", self.scalar.rust(), self.width)
        } else {
            self.scalar.rust().to_owned()
        };
        match self.count {
            Some(n) => write!(f, "[{inner}; {n}]"),
            None => f.write_str(&inner),
        }
    }
}

/// A Rust type that can feed a uniform member, with its memory form; implemented for `f32`,
/// `i32`, `u32`, `f64`, vectors `[T; 2..=4]` and arrays of vectors `[[T; 2..=4]; N]` (matrix
/// columns, std140 `mat3` as `[[f32; 4]; 3]`, arrays of `vec4`, arrays of `float` padded to
/// `[[f32; 4]; N]`).
pub trait GlslType {
    /// The memory form.
    const RUST_TYPE: RustType;
}

macro_rules! glsl_types {
    ($($t:ty => $kind:ident),*) => {$(
        impl GlslType for $t {
            const RUST_TYPE: RustType = RustType { scalar: ScalarKind::$kind, width: 1, vector: false, count: None, composite: false };
        }
        glsl_types!(@vec $t, $kind, 2, 3, 4);
    )*};
    (@vec $t:ty, $kind:ident, $($w:literal),*) => {$(
        impl GlslType for [$t; $w] {
            const RUST_TYPE: RustType = RustType { scalar: ScalarKind::$kind, width: $w, vector: true, count: None, composite: false };
        }
        impl<const N: usize> GlslType for [[$t; $w]; N] {
            const RUST_TYPE: RustType = RustType { scalar: ScalarKind::$kind, width: $w, vector: true, count: Some(N), composite: false };
        }
    )*};
}
glsl_types!(f32 => F32, i32 => I32, u32 => U32, f64 => F64);

/// Declares a `#[repr(C)]` struct that mirrors a GLSL struct inside a uniform block (e.g.
/// `gl_LightSourceParameters`), so that it and arrays of it can be fields of a
/// [`uniform_block!`](crate::uniform_block) struct.
#[macro_export]
macro_rules! glsl_struct {
    ($ty:ty) => {
        impl $crate::shader::GlslType for $ty {
            const RUST_TYPE: $crate::shader::RustType = $crate::shader::RustType {
                scalar: $crate::shader::ScalarKind::F32,
                width: 1,
                vector: false,
                count: None,
                composite: true,
            };
        }
        impl<const N: usize> $crate::shader::GlslType for [$ty; N] {
            const RUST_TYPE: $crate::shader::RustType = $crate::shader::RustType {
                scalar: $crate::shader::ScalarKind::F32,
                width: 1,
                vector: false,
                count: Some(N),
                composite: true,
            };
        }
    };
}

/// The memory form of the field a closure `|s: &S| &s.field` picks (used by
/// [`uniform_block!`](crate::uniform_block); the closure is never called).
pub const fn rust_type_of<S, F: GlslType>(_field: fn(&S) -> &F) -> RustType {
    F::RUST_TYPE
}

/// One field of a Rust uniform struct and the GLSL member it feeds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Field {
    /// The GLSL member's name.
    pub glsl: &'static str,
    /// The Rust field's name.
    pub rust: &'static str,
    /// Byte offset in the Rust struct.
    pub offset: usize,
    /// The Rust field's type.
    pub ty: RustType,
}

/// A Rust struct that feeds one GLSL uniform block. Implement it with [`uniform_block!`](crate::uniform_block).
pub trait UniformBlock: bytemuck::Pod {
    /// The GLSL block name.
    const BLOCK: &'static str;
    /// Every field that feeds a member.
    const FIELDS: &'static [Field];
}

/// Implements [`UniformBlock`] for a `#[repr(C)]` struct: `uniform_block!(PhongUniforms, "PhongParams", { light_position: "lightPosition", ... })`.
/// Each field's type must implement [`GlslType`].
#[macro_export]
macro_rules! uniform_block {
    ($ty:ty, $block:literal, { $($field:ident : $glsl:literal),* $(,)? }) => {
        impl $crate::shader::UniformBlock for $ty {
            const BLOCK: &'static str = $block;
            const FIELDS: &'static [$crate::shader::Field] = &[$($crate::shader::Field {
                glsl: $glsl,
                rust: ::core::stringify!($field),
                offset: ::core::mem::offset_of!($ty, $field),
                ty: $crate::shader::rust_type_of(|s: &$ty| &s.$field),
            }),*];
        }
    };
}

/// Checks a Rust uniform struct against the block naga reflected: the size, and every
/// member's offset and type (scalar kind, vector width, matrix shape, array length and stride).
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
        let Some(field) = T::FIELDS.iter().find(|f| f.glsl == member.name) else {
            problems.push(format!(
                "GLSL block {} member `{}` (offset {}) has no field in struct {rust_name}",
                block.name,
                member.declaration(),
                member.offset
            ));
            continue;
        };
        if field.offset != member.offset {
            problems.push(format!(
                "struct {rust_name} field for `{}` is at offset {} but GLSL block {} puts it at offset {}",
                member.name, field.offset, block.name, member.offset
            ));
        }
        let fits = match &member.ty {
            Some(ty) => !field.ty.composite && field.ty.feeds(ty),
            None => field.ty.composite,
        };
        if !fits {
            let hint = match &member.ty {
                Some(ty) => format!("use {}", ty.rust_suggestion()),
                None => "reflection does not describe that type".to_owned(),
            };
            problems.push(format!(
                "struct {rust_name} field `{}: {}` does not fit GLSL block {} member `{}` ({hint})",
                field.rust,
                field.ty,
                block.name,
                member.declaration()
            ));
        }
    }
    for field in T::FIELDS {
        if block.member(field.glsl).is_none() {
            problems.push(format!(
                "struct {rust_name} field `{}: {}` (offset {}) feeds `{}`, which is not a member of GLSL block {}",
                field.rust, field.ty, field.offset, field.glsl, block.name
            ));
        }
    }
    if problems.is_empty() {
        Ok(())
    } else {
        Err(Error::Layout(problems.join("; ")))
    }
}

/// `name` or `name[index]`.
fn parse_member_name(name: &str) -> Result<(&str, Option<usize>)> {
    let Some(open) = name.find('[') else {
        return Ok((name, None));
    };
    let bad = || Error::Param(format!("`{name}`: expected NAME or NAME[INDEX], e.g. colors[1]"));
    let index = name[open + 1..].strip_suffix(']').ok_or_else(bad)?;
    let index = index.trim().parse::<usize>().map_err(|_| bad())?;
    Ok((&name[..open], Some(index)))
}

/// The member `name` (or `name[i]`) selects: the member and the element range.
fn select<'b>(block: &'b BlockLayout, name: &str) -> Result<(&'b MemberLayout, MemberType, std::ops::Range<usize>)> {
    let (base, index) = parse_member_name(name)?;
    let member = block.member(base).ok_or_else(|| {
        let valid: Vec<&str> = block.members.iter().map(|m| m.name.as_str()).collect();
        Error::Param(format!("unknown parameter `{name}`; valid: {}", valid.join(", ")))
    })?;
    let ty = member.ty.ok_or_else(|| {
        Error::Param(format!(
            "parameter `{base}` is a struct or nested array, which cannot be set by name"
        ))
    })?;
    let elements = match (index, ty.array) {
        (None, _) => 0..ty.elements(),
        (Some(i), Some(a)) if i < a.len => i..i + 1,
        (Some(i), Some(a)) => {
            return Err(Error::Param(format!(
                "`{name}`: index {i} is out of range; `{}` has {} elements (0 to {})",
                member.declaration(),
                a.len,
                a.len - 1
            )))
        }
        (Some(_), None) => {
            return Err(Error::Param(format!(
                "`{name}`: `{}` is not an array",
                member.declaration()
            )))
        }
    };
    Ok((member, ty, elements))
}

/// One value as the bytes of `kind`; integers must be whole and in range, `bool` 0 or 1.
/// `what` names the member in messages.
fn encode(what: &str, kind: ScalarKind, value: f32) -> Result<Vec<u8>> {
    let whole = value.fract() == 0.0;
    let bad = |range: &str| Error::Param(format!("parameter {what} takes {range}; got {value}"));
    Ok(match kind {
        ScalarKind::F32 => value.to_ne_bytes().to_vec(),
        ScalarKind::F64 => f64::from(value).to_ne_bytes().to_vec(),
        ScalarKind::I32 if whole && (-2147483648.0..2147483648.0).contains(&value) => {
            (value as i32).to_ne_bytes().to_vec()
        }
        ScalarKind::I32 => return Err(bad("whole numbers from -2147483648 to 2147483647")),
        ScalarKind::U32 if whole && (0.0..4294967296.0).contains(&value) => (value as u32).to_ne_bytes().to_vec(),
        ScalarKind::U32 => return Err(bad("whole numbers from 0 to 4294967295")),
        ScalarKind::Bool if value == 0.0 || value == 1.0 => (value as u32).to_ne_bytes().to_vec(),
        ScalarKind::Bool => return Err(bad("0 or 1")),
    })
}

fn decode(kind: ScalarKind, bytes: &[u8]) -> f32 {
    let word = |b: &[u8]| [b[0], b[1], b[2], b[3]];
    match kind {
        ScalarKind::F32 => f32::from_ne_bytes(word(bytes)),
        ScalarKind::I32 => i32::from_ne_bytes(word(bytes)) as f32,
        ScalarKind::U32 | ScalarKind::Bool => u32::from_ne_bytes(word(bytes)) as f32,
        ScalarKind::F64 => {
            let mut b = [0; 8];
            b.copy_from_slice(&bytes[..8]);
            f64::from_ne_bytes(b) as f32
        }
    }
}

/// Sets the member `name` of a uniform struct from numbers, by the reflected layout: `colors`
/// sets every element of an array, `colors[1]` one. Integer members take whole numbers.
/// Fails with the list of valid names when `name` is unknown, and on a wrong count.
pub fn set_member<T: UniformBlock>(value: &mut T, block: &BlockLayout, name: &str, values: &[f32]) -> Result<()> {
    let (member, ty, elements) = select(block, name)?;
    let wanted = elements.len() * ty.element_components();
    if values.len() != wanted {
        return Err(Error::Param(format!(
            "parameter `{name}` takes {wanted} number(s), got {} ({})",
            values.len(),
            member.declaration()
        )));
    }
    let size = ty.scalar.size();
    let runs = ty.runs(elements);
    let end = runs
        .iter()
        .map(|(at, n)| member.offset + at + n * size)
        .max()
        .unwrap_or(0);
    let bytes = bytemuck::bytes_of_mut(value);
    if end > bytes.len() {
        return Err(Error::Layout(format!(
            "member `{}` lies outside the Rust struct",
            member.name
        )));
    }
    let what = format!("`{name}` ({})", member.declaration());
    let mut encoded = Vec::with_capacity(values.len() * size);
    for &v in values {
        encoded.extend(encode(&what, ty.scalar, v)?);
    }
    let mut chunks = encoded.chunks(size);
    for (at, n) in runs {
        for k in 0..n {
            let start = member.offset + at + k * size;
            bytes[start..start + size].copy_from_slice(chunks.next().expect("one value per slot"));
        }
    }
    Ok(())
}

/// Reads the member `name` (or `name[index]`) of a uniform struct as numbers.
pub fn get_member<T: UniformBlock>(value: &T, block: &BlockLayout, name: &str) -> Option<Vec<f32>> {
    let (member, ty, elements) = select(block, name).ok()?;
    let bytes = bytemuck::bytes_of(value);
    let size = ty.scalar.size();
    let mut out = Vec::new();
    for (at, n) in ty.runs(elements) {
        for k in 0..n {
            let start = member.offset + at + k * size;
            out.push(decode(ty.scalar, bytes.get(start..start + size)?));
        }
    }
    Some(out)
}

#[cfg(test)]
mod loader_tests {
    use super::*;
    use std::fs;

    /// A copy of the built-in shaders in a fresh directory.
    fn shader_dir(name: &str) -> crate::fsutil::ScratchDir {
        let dir = crate::fsutil::ScratchDir::nested(&format!("loader-{name}"), "shaders");
        for name in embedded_names() {
            fs::write(dir.join(name), embedded_source(name).unwrap()).unwrap();
        }
        dir
    }

    /// `phong.frag` with `line` inserted after `#version`.
    fn phong_with(dir: &Path, line: &str) {
        let text =
            embedded_source("phong.frag")
                .unwrap()
                .replacen("#version 450\n", &format!("#version 450\n{line}\n"), 1);
        fs::write(dir.join("phong.frag"), text).unwrap();
    }

    fn compile_err(dir: &Path, name: &str) -> String {
        let source = ShaderSource::dir(dir).unwrap();
        match source.compile(name) {
            Ok(_) => panic!("{name} compiled"),
            Err(e) => e.to_string(),
        }
    }

    fn compiles(dir: &Path, name: &str) {
        let source = ShaderSource::dir(dir).unwrap();
        if let Err(e) = source.compile(name) {
            panic!("{name}: {e}");
        }
    }

    #[test]
    fn includes_stay_inside_the_shader_directory() {
        let dir = shader_dir("confined");
        for (include, phrase) in [
            ("/dev/zero", "is an absolute path"),
            ("/etc/passwd", "is an absolute path"),
            ("../outside.glsl", "outside the shader directory"),
            ("sub/../../outside.glsl", "outside the shader directory"),
        ] {
            fs::write(dir.parent().unwrap().join("outside.glsl"), "float leaked_secret;\n").unwrap();
            phong_with(&dir, &format!("#include \"{include}\""));
            let err = compile_err(&dir, "phong.frag");
            assert!(err.contains(phrase), "{include}: {err}");
            assert!(err.contains("phong.frag:2:1:"), "{include}: {err}");
            assert!(
                !err.contains("root:") && !err.contains("leaked_secret"),
                "{include}: {err}"
            );
        }
        // A link inside the directory that points outside is outside too.
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink("/dev/zero", dir.join("zero.glsl")).unwrap();
            phong_with(&dir, "#include \"zero.glsl\"");
            let err = compile_err(&dir, "phong.frag");
            assert!(err.contains("outside the shader directory"), "{err}");
        }
        // A subdirectory is fine, as long as it is inside.
        fs::create_dir(dir.join("sub")).unwrap();
        fs::write(dir.join("sub/extra.glsl"), "const float EXTRA = 1.0;\n").unwrap();
        phong_with(&dir, "#include \"sub/extra.glsl\"");
        compiles(&dir, "phong.frag");
        phong_with(&dir, "#include \"sub/../sub/extra.glsl\"");
        compiles(&dir, "phong.frag");
        // Not a regular file.
        fs::create_dir(dir.join("dir.glsl")).unwrap();
        phong_with(&dir, "#include \"dir.glsl\"");
        let err = compile_err(&dir, "phong.frag");
        assert!(err.contains("a directory; a shader must be a text file"), "{err}");
    }

    #[test]
    fn shader_files_have_a_size_limit() {
        let dir = shader_dir("size");
        let big = format!("// {}\n", "x".repeat(MAX_SHADER_BYTES as usize));
        fs::write(dir.join("big.glsl"), &big).unwrap();
        phong_with(&dir, "#include \"big.glsl\"");
        let err = compile_err(&dir, "phong.frag");
        assert!(
            err.contains("shader files are limited to 1048576 bytes (1 MiB)"),
            "{err}"
        );
        let text = embedded_source("phong.frag").unwrap().to_owned() + &big;
        fs::write(dir.join("phong.frag"), text).unwrap();
        let err = compile_err(&dir, "phong.frag");
        assert!(err.contains("phong.frag") && err.contains("limited to"), "{err}");
    }

    #[test]
    fn an_empty_file_is_named_and_called_empty() {
        let dir = shader_dir("empty");
        for text in ["", "\n\n  \n", "\u{feff}"] {
            fs::write(dir.join("phong.frag"), text).unwrap();
            let err = compile_err(&dir, "phong.frag");
            let path = dir.join("phong.frag").display().to_string();
            assert!(
                err.starts_with(&format!("{path}: the file is empty")),
                "{text:?}: {err}"
            );
            assert!(err.contains("void main()"), "{err}");
        }
        fs::write(dir.join("phong.frag"), "#version 450\n// nothing yet\n").unwrap();
        let err = compile_err(&dir, "phong.frag");
        assert!(
            err.contains("phong.frag: no `void main()` found; a fragment shader needs one"),
            "{err}"
        );
        // The main file is named even when its first line is an #include.
        fs::write(dir.join("phong.frag"), "#include \"safe_math.glsl\"\n").unwrap();
        let err = compile_err(&dir, "phong.frag");
        assert!(err.contains("phong.frag: no `void main()`"), "{err}");
    }

    #[test]
    fn a_byte_order_mark_is_skipped() {
        let dir = shader_dir("bom");
        for name in ["phong.frag", "phong_params.glsl"] {
            let text = format!("\u{feff}{}", embedded_source(name).unwrap());
            fs::write(dir.join(name), text).unwrap();
        }
        compiles(&dir, "phong.frag");
    }

    #[test]
    fn include_lines_are_parsed_properly() {
        let dir = shader_dir("parse");
        fs::write(dir.join("extra.glsl"), "const float EXTRA = 1.0;\n").unwrap();
        for ok in [
            "#include \"extra.glsl\" // the extra constant",
            "#include \"extra.glsl\"// no space",
            "  #  include \"extra.glsl\" /* a */ /* b */ // c",
            "#include <extra.glsl>",
        ] {
            phong_with(&dir, ok);
            compiles(&dir, "phong.frag");
        }
        for (bad, phrase, column) in [
            (
                "#include \"extra.glsl\" junk",
                "unexpected `junk` after #include \"extra.glsl\"",
                23,
            ),
            ("#include extra.glsl", "#include needs the file name in quotes", 10),
            ("#include \"extra.glsl", "lacks its closing `\"`", 10),
            ("#include", "#include needs a file name", 1),
            ("#include \"\"", "#include needs a file name", 10),
            ("#include \"extra.glsl\" /* open", "must end on the same line", 23),
        ] {
            phong_with(&dir, bad);
            let err = compile_err(&dir, "phong.frag");
            assert!(err.contains(phrase), "{bad}: {err}");
            assert!(err.contains(&format!("phong.frag:2:{column}:")), "{bad}: {err}");
        }
    }

    #[test]
    fn deep_includes_say_so() {
        let dir = shader_dir("deep");
        // phong.frag -> i1 -> ... -> i8: eight levels are fine.
        for i in 1..=9 {
            fs::write(
                dir.join(format!("i{i}.glsl")),
                format!("#include \"i{}.glsl\"\n", i + 1),
            )
            .unwrap();
        }
        fs::write(dir.join("i8.glsl"), "const float DEEP = 1.0;\n").unwrap();
        phong_with(&dir, "#include \"i1.glsl\"");
        compiles(&dir, "phong.frag");
        // Nine are too many.
        fs::write(dir.join("i8.glsl"), "#include \"i9.glsl\"\n").unwrap();
        fs::write(dir.join("i9.glsl"), "const float DEEP = 1.0;\n").unwrap();
        let err = compile_err(&dir, "phong.frag");
        assert!(err.contains("includes nested deeper than 8"), "{err}");
        assert!(
            err.contains("i8.glsl:1:1:") && err.contains("i7.glsl -> i8.glsl -> i9.glsl"),
            "{err}"
        );
    }

    #[test]
    fn a_file_that_includes_itself_is_named() {
        let dir = shader_dir("self");
        phong_with(&dir, "#include \"phong.frag\"");
        let err = compile_err(&dir, "phong.frag");
        assert!(err.contains("phong.frag:2:1: phong.frag includes itself"), "{err}");
        let dir = shader_dir("self_snippet");
        fs::write(dir.join("loop.glsl"), "// a snippet\n#include \"loop.glsl\"\n").unwrap();
        phong_with(&dir, "#include \"loop.glsl\"");
        let err = compile_err(&dir, "phong.frag");
        assert!(err.contains("loop.glsl:2:1: loop.glsl includes itself"), "{err}");
        let dir = shader_dir("cycle");
        fs::write(dir.join("a.glsl"), "#include \"b.glsl\"\n").unwrap();
        fs::write(dir.join("b.glsl"), "#include \"phong.frag\"\n").unwrap();
        phong_with(&dir, "#include \"a.glsl\"");
        let err = compile_err(&dir, "phong.frag");
        assert!(
            err.contains("#include cycle: phong.frag -> a.glsl -> b.glsl -> phong.frag"),
            "{err}"
        );
        // A snippet included twice (not a cycle) is still spliced once.
        let dir = shader_dir("twice");
        fs::write(
            dir.join("extra.glsl"),
            "#include \"safe_math.glsl\"\nconst float EXTRA = 1.0;\n",
        )
        .unwrap();
        phong_with(&dir, "#include \"extra.glsl\"");
        compiles(&dir, "phong.frag");
    }

    #[test]
    fn compile_file_confines_includes_and_falls_back_to_built_in_snippets() {
        let dir = shader_dir("file");
        let lone = dir.join("lone");
        fs::create_dir(&lone).unwrap();
        fs::write(lone.join("phong.frag"), embedded_source("phong.frag").unwrap()).unwrap();
        let compiled = compile_file(&lone.join("phong.frag")).unwrap();
        assert!(compiled
            .source
            .line_map
            .iter()
            .any(|(f, _)| f == "shaders_glsl/phong_params.glsl"));
        let text = embedded_source("phong.frag").unwrap().replacen(
            "#version 450\n",
            "#version 450\n#include \"/etc/passwd\"\n",
            1,
        );
        fs::write(lone.join("phong.frag"), text).unwrap();
        let err = compile_file(&lone.join("phong.frag")).unwrap_err().to_string();
        assert!(err.contains("is an absolute path"), "{err}");
        let err = compile_file(Path::new("/dev/zero.frag")).unwrap_err().to_string();
        assert!(err.contains("not found"), "{err}");
    }
}

#[cfg(test)]
mod layout_tests {
    use super::*;
    use crate::labs::phong::PhongUniforms;

    fn phong_params_with(edit: impl Fn(&str) -> String) -> BlockLayout {
        let params = edit(embedded_source("phong_params.glsl").unwrap());
        let shader = compile_text(
            "phong.frag",
            embedded_source("phong.frag").unwrap(),
            ShaderStage::Fragment,
            &|name: &str| match name {
                "phong_params.glsl" => Ok((name.to_owned(), params.clone())),
                _ => ShaderSource::Embedded.read(name).map(|t| (name.to_owned(), t)),
            },
        )
        .unwrap_or_else(|e| panic!("{e}"));
        shader.uniform_block("PhongParams").expect("PhongParams")
    }

    #[test]
    fn a_member_of_another_type_is_a_mismatch() {
        let block = phong_params_with(|t| t.replace("float Ka;", "int Ka;"));
        let err = check_layout::<PhongUniforms>("PhongUniforms", &block).expect_err("int Ka must not pass");
        println!("{err}");
        let message = err.to_string();
        for needle in ["PhongUniforms", "`ka: f32`", "`int Ka`", "PhongParams", "use i32"] {
            assert!(message.contains(needle), "lacks {needle:?}: {message}");
        }
        let block = phong_params_with(|t| t.replace("float shininess;", "uint shininess;"));
        let message = check_layout::<PhongUniforms>("PhongUniforms", &block)
            .unwrap_err()
            .to_string();
        assert!(
            message.contains("`shininess: f32`") && message.contains("`uint shininess`"),
            "{message}"
        );
    }

    #[test]
    fn every_lab_block_still_matches() {
        use crate::labs::glut_stage::TransformUniforms;
        use crate::labs::{displacement::DisplacementUniforms, noise::NoiseUniforms};
        let block = |file: &str, name: &str| {
            let shader = ShaderSource::Embedded.compile(file).unwrap();
            shader
                .uniform_block(name)
                .unwrap_or_else(|| panic!("{file} declares {name}"))
        };
        for frag in ["phong.frag", "phong_flat.frag", "phong_blinn.frag"] {
            check_layout::<PhongUniforms>("PhongUniforms", &block(frag, "PhongParams")).unwrap();
        }
        check_layout::<PhongUniforms>("PhongUniforms", &block("phong_gouraud.vert", "PhongParams")).unwrap();
        check_layout::<NoiseUniforms>("NoiseUniforms", &block("noise.frag", "NoiseParams")).unwrap();
        check_layout::<DisplacementUniforms>(
            "DisplacementUniforms",
            &block("displacement.vert", "DisplacementParams"),
        )
        .unwrap();
        for vert in ["position_rgb.vert", "normal_rgb.vert"] {
            check_layout::<TransformUniforms>("TransformUniforms", &block(vert, "Transform")).unwrap();
        }
        // The transform block: two mat4 and a std140 mat3 (three padded columns).
        let vert = ShaderSource::Embedded.compile("phong.vert").unwrap();
        let transform = vert.uniform_block("Transform").unwrap();
        let mat3 = transform.member("normal_matrix").unwrap();
        assert_eq!(mat3.declaration(), "mat3 normal_matrix");
        assert_eq!(mat3.ty.unwrap().column_stride, 16);
        assert_eq!(mat3.components, 9);
        assert_eq!(transform.member("mvp").unwrap().ty.unwrap().to_string(), "mat4");
        check_layout::<TransformUniforms>("TransformUniforms", &transform).unwrap();
    }

    /// A block with arrays, integers and matrices.
    const ARRAYS: &str = "#version 450
layout(std140, set = 0, binding = 1) uniform Arrays {
    vec4 colors[3];
    float t[2];
    mat3 m;
    int count;
    uint flags;
    uvec2 u;
    mat3 ms[2];
    ivec3 iv;
    float last;
};
layout(location = 0) out vec4 c;
void main() {
    c = colors[0] + vec4(t[1] + m[0][0] + float(count) + float(flags) + float(u.x) + ms[1][2][0] + float(iv.y) + last);
}
";

    #[repr(C)]
    #[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
    struct ArraysUniforms {
        colors: [[f32; 4]; 3],
        // naga 30 accepts `float t[2]` in a std140 block and gives it std140's stride of 16
        // (one float per vec4 slot), so the Rust side is an array of padded vec4s.
        t: [[f32; 4]; 2],
        m: [[f32; 4]; 3],
        count: i32,
        flags: u32,
        u: [u32; 2],
        ms: [[f32; 4]; 6],
        iv: [i32; 3],
        last: f32,
    }
    crate::uniform_block!(ArraysUniforms, "Arrays", {
        colors: "colors", t: "t", m: "m", count: "count", flags: "flags", u: "u", ms: "ms", iv: "iv", last: "last",
    });

    fn arrays_block(text: &str) -> BlockLayout {
        let no_includes = |n: &str| Err(Error::ShaderNotFound(n.into()));
        compile_text("arrays.frag", text, ShaderStage::Fragment, &no_includes)
            .unwrap_or_else(|e| panic!("{e}"))
            .uniform_block("Arrays")
            .unwrap()
    }

    #[test]
    fn arrays_integers_and_matrices_are_reflected_and_checked() {
        let block = arrays_block(ARRAYS);
        let decls: Vec<String> = block.members.iter().map(|m| m.declaration()).collect();
        assert_eq!(
            decls,
            [
                "vec4 colors[3]",
                "float t[2]",
                "mat3 m",
                "int count",
                "uint flags",
                "uvec2 u",
                "mat3 ms[2]",
                "ivec3 iv",
                "float last"
            ]
        );
        let t = block.member("t").unwrap().ty.unwrap();
        assert_eq!(
            (t.scalar, t.rows, t.columns, t.array),
            (ScalarKind::F32, 1, 1, Some(ArrayLayout { len: 2, stride: 16 }))
        );
        let ms = block.member("ms").unwrap().ty.unwrap();
        assert_eq!(
            (ms.rows, ms.columns, ms.column_stride, ms.array.unwrap().stride),
            (3, 3, 16, 48)
        );
        assert_eq!(block.member("colors").unwrap().components, 12);
        assert_eq!(block.size, std::mem::size_of::<ArraysUniforms>());
        check_layout::<ArraysUniforms>("ArraysUniforms", &block).unwrap();
        let rust: Vec<String> = ArraysUniforms::FIELDS
            .iter()
            .map(|f| format!("{}: {}", f.rust, f.ty))
            .collect();
        assert_eq!(
            rust[..4],
            [
                "colors: [[f32; 4]; 3]",
                "t: [[f32; 4]; 2]",
                "m: [[f32; 4]; 3]",
                "count: i32"
            ]
        );
    }

    #[test]
    fn array_lengths_strides_and_shapes_must_match() {
        let cases = [
            (
                "vec4 colors[3];",
                "vec4 colors[4];",
                "`colors: [[f32; 4]; 3]` does not fit GLSL block Arrays member `vec4 colors[4]` (use [[f32; 4]; 4])",
            ),
            (
                "mat3 m;",
                "mat4x3 m;",
                "`m: [[f32; 4]; 3]` does not fit GLSL block Arrays member `mat4x3 m` (use [[f32; 4]; 4])",
            ),
            ("mat3 m;", "vec4 m[3];", ""), // the same memory: a mat3 and three vec4s
            (
                "ivec3 iv;",
                "vec3 iv;",
                "`iv: [i32; 3]` does not fit GLSL block Arrays member `vec3 iv` (use [f32; 3])",
            ),
            (
                "uvec2 u;",
                "uvec3 u;",
                "`u: [u32; 2]` does not fit GLSL block Arrays member `uvec3 u` (use [u32; 3])",
            ),
            (
                "uint flags;",
                "int flags;",
                "`flags: u32` does not fit GLSL block Arrays member `int flags` (use i32)",
            ),
        ];
        for (from, to, message) in cases {
            let block = arrays_block(&ARRAYS.replace(from, to));
            let result = check_layout::<ArraysUniforms>("ArraysUniforms", &block);
            match (message, result) {
                ("", Ok(())) => {}
                ("", Err(e)) => panic!("{to}: {e}"),
                (_, Ok(())) => panic!("{to} passed"),
                (m, Err(e)) => assert!(e.to_string().contains(m), "{to}: {e}"),
            }
        }
        // Rust-side mistakes: a packed mat3, a float array as plain floats.
        #[repr(C)]
        #[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
        struct Packed {
            m: [[f32; 3]; 3],
            t: [f32; 2],
            rest: [f32; 53],
        }
        crate::uniform_block!(Packed, "Arrays", { t: "t", m: "m" });
        let err = check_layout::<Packed>("Packed", &arrays_block(ARRAYS))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("`m: [[f32; 3]; 3]` does not fit GLSL block Arrays member `mat3 m` (use [[f32; 4]; 3])"),
            "{err}"
        );
        assert!(
            err.contains("`t: [f32; 2]` does not fit GLSL block Arrays member `float t[2]` (use [[f32; 4]; 2])"),
            "{err}"
        );
        assert!(
            err.contains("member `vec4 colors[3]` (offset 0) has no field in struct Packed"),
            "{err}"
        );
    }

    #[test]
    fn set_and_get_arrays_by_name_and_element() {
        let block = arrays_block(ARRAYS);
        let mut u = ArraysUniforms::default();
        let colors: Vec<f32> = (0..12).map(|i| i as f32).collect();
        set_member(&mut u, &block, "colors", &colors).unwrap();
        assert_eq!(
            u.colors,
            [[0.0, 1.0, 2.0, 3.0], [4.0, 5.0, 6.0, 7.0], [8.0, 9.0, 10.0, 11.0]]
        );
        set_member(&mut u, &block, "colors[1]", &[-1.0, -2.0, -3.0, -4.0]).unwrap();
        assert_eq!(u.colors[1], [-1.0, -2.0, -3.0, -4.0]);
        assert_eq!(get_member(&u, &block, "colors[1]"), Some(vec![-1.0, -2.0, -3.0, -4.0]));
        assert_eq!(get_member(&u, &block, "colors").unwrap().len(), 12);
        // float t[2]: one value per 16-byte slot, the padding untouched.
        set_member(&mut u, &block, "t", &[0.5, 0.25]).unwrap();
        assert_eq!(u.t, [[0.5, 0.0, 0.0, 0.0], [0.25, 0.0, 0.0, 0.0]]);
        set_member(&mut u, &block, "t[1]", &[2.0]).unwrap();
        assert_eq!(get_member(&u, &block, "t"), Some(vec![0.5, 2.0]));
        // mat3: nine values, column by column, into padded columns.
        set_member(&mut u, &block, "m", &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]).unwrap();
        assert_eq!(u.m, [[1.0, 2.0, 3.0, 0.0], [4.0, 5.0, 6.0, 0.0], [7.0, 8.0, 9.0, 0.0]]);
        set_member(&mut u, &block, "ms[1]", &[1.0; 9]).unwrap();
        assert_eq!(u.ms[3..], [[1.0, 1.0, 1.0, 0.0]; 3]);
        assert_eq!(u.ms[..3], [[0.0; 4]; 3]);
        // Integers are stored as integers.
        set_member(&mut u, &block, "count", &[-3.0]).unwrap();
        set_member(&mut u, &block, "u", &[7.0, 4_000_000_000.0]).unwrap();
        assert_eq!((u.count, u.u), (-3, [7, 4_000_000_000]));
        assert_eq!(get_member(&u, &block, "count"), Some(vec![-3.0]));
        let before = u;
        for (name, values, phrase) in [
            (
                "colors",
                &[1.0; 4][..],
                "parameter `colors` takes 12 number(s), got 4 (vec4 colors[3])",
            ),
            (
                "colors[1]",
                &[1.0; 12][..],
                "parameter `colors[1]` takes 4 number(s), got 12",
            ),
            (
                "colors[3]",
                &[1.0; 4][..],
                "index 3 is out of range; `vec4 colors[3]` has 3 elements (0 to 2)",
            ),
            ("count[0]", &[1.0][..], "`int count` is not an array"),
            ("colors[x]", &[1.0; 4][..], "expected NAME or NAME[INDEX]"),
            ("colors[1", &[1.0; 4][..], "expected NAME or NAME[INDEX]"),
            ("count", &[2.5][..], "parameter `count` (int count) takes whole numbers"),
            ("flags", &[-1.0][..], "takes whole numbers from 0 to 4294967295; got -1"),
            (
                "nosuch[1]",
                &[1.0][..],
                "unknown parameter `nosuch[1]`; valid: colors, t, m,",
            ),
        ] {
            let err = set_member(&mut u, &block, name, values).unwrap_err();
            assert!(matches!(err, Error::Param(_)), "{name}: {err:?}");
            assert!(err.to_string().contains(phrase), "{name}: {err}");
        }
        assert_eq!(u, before, "a failed set changed the struct");
        assert_eq!(get_member(&u, &block, "colors[9]"), None);
    }
}
