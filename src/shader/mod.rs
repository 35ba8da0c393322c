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

pub mod guard;
mod layout;
mod mend;

pub use layout::*;

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
    /// Texts edited in memory (the web page's editor), by file name, over the built-in copies:
    /// a file not edited reads as [`ShaderSource::Embedded`].
    Edited(std::sync::Arc<std::collections::BTreeMap<String, String>>),
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
    ///
    /// The path is fixed when the library is compiled, on purpose: an example run from a checkout
    /// reloads that checkout's files. After the checkout is moved or renamed, the next build
    /// re-runs `build.rs`, whose embedded list then names the new paths, so the library is
    /// recompiled and this names the new folder; a binary left from before the move finds no
    /// folder here and runs on its embedded shaders (no live reload) instead of failing.
    pub fn source_tree() -> Option<Self> {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders_glsl");
        dir.is_dir().then_some(ShaderSource::Dir(dir))
    }

    /// The path shown in messages for `name`.
    pub fn display_path(&self, name: &str) -> String {
        match self {
            ShaderSource::Embedded | ShaderSource::Edited(_) => format!("shaders_glsl/{name}"),
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
            ShaderSource::Edited(texts) => match texts.get(name) {
                Some(text) => Ok(text.clone()),
                None => ShaderSource::Embedded.read(name),
            },
        }
    }

    /// The edited text of `name`, if this source holds one ([`ShaderSource::Edited`]).
    pub fn edited(&self, name: &str) -> Option<&str> {
        match self {
            ShaderSource::Edited(texts) => texts.get(name).map(String::as_str),
            _ => None,
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
/// [`MAX_SHADER_BYTES`] ([`crate::fsutil::read_user_file`]'s rule for every user file), in UTF-8.
pub fn read_shader_file(path: &Path) -> Result<String> {
    let bytes = crate::fsutil::read_user_file(path, MAX_SHADER_BYTES, "shader files").map_err(|e| match e {
        Error::Io { source, .. } if source.kind() == std::io::ErrorKind::NotFound => {
            Error::ShaderNotFound(path.display().to_string())
        }
        e => e,
    })?;
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
    /// Each file as its author wrote it: display path and text (the main file first), for
    /// showing a line next to what it computed.
    pub files: Vec<(String, String)>,
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
            files: Vec::new(),
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
        self.out.files.push((path.to_owned(), text.to_owned()));
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

/// How many characters of a long source line a snippet shows on each side of the caret.
const SNIPPET_CONTEXT: usize = 100;
/// How many carets at most: a construct longer than this is marked by its start.
const SNIPPET_CARETS: usize = 100;

/// Formats `path:line:column: message`, the source line and a caret under the column. A long
/// line is cut to `SNIPPET_CONTEXT` characters on each side of the caret, with `…` where text
/// is left out: a 2 MB minified line would otherwise print 4 MB (the line and its padding).
pub fn format_diagnostic(path: &str, line: u32, column: u32, message: &str, source_line: &str, len: usize) -> String {
    let chars: Vec<char> = source_line.chars().collect();
    let at = (column.saturating_sub(1) as usize).min(chars.len());
    let len = len.clamp(1, chars.len().saturating_sub(at).clamp(1, SNIPPET_CARETS));
    let start = at.saturating_sub(SNIPPET_CONTEXT);
    let end = (at + len + SNIPPET_CONTEXT).min(chars.len());
    let (open, close) = (
        if start > 0 { "…" } else { "" },
        if end < chars.len() { "…" } else { "" },
    );
    let shown: String = chars[start..end].iter().collect();
    let caret_pad: String = std::iter::repeat_n(" ", open.chars().count())
        .chain(chars[start..at].iter().map(|&c| if c == '\t' { "\t" } else { " " }))
        .collect();
    format!(
        "{path}:{line}:{column}: {message}\n {line:>4} | {open}{shown}{close}\n      | {caret_pad}{}",
        "^".repeat(len)
    )
}

/// naga's message for a shader error in words a student understands: naga's GLSL front end
/// prints some errors as Rust debug text (`ErrorDirective`, `UnfinishedBlock`,
/// `HirExpr { kind: PrePostfix … }`) or in IR terms (`Expression [8] is invalid: Accessing
/// index 7 is out of [3] bounds`). `line` is the source line the error points at (for the text
/// of an `#error`). Messages not recognised are kept as naga wrote them.
pub fn plain_message(message: &str, line: &str) -> String {
    // Validation errors are chains "Function [0] 'main' is invalid: Expression [8] is
    // invalid: …": the last link says what is wrong.
    let last = message.rsplit(": ").next().unwrap_or(message);
    let pp = |what: &str| -> Option<&str> {
        Some(match what {
            "ErrorDirective" => "",
            "UnfinishedBlock" => "this `#if`/`#ifdef`/`#ifndef` has no matching `#endif`",
            "ElifOutsideOfBlock" => "`#elif` without an `#if` before it",
            "ElseOutsideOfBlock" => "`#else` without an `#if` before it",
            "EndifOutsideOfBlock" => "`#endif` without an `#if` before it",
            "ElifAfterElse" => "`#elif` after `#else`",
            "MoreThanOneElse" => "a second `#else` for the same `#if`",
            "UnknownDirective" => "unknown preprocessor directive (GLSL has #define, #undef, #if, #ifdef, #ifndef, #elif, #else, #endif, #error, #pragma, #extension, #version, #line)",
            "DefineRedefined" => "this macro is already #defined differently: #undef it first",
            "DuplicateParameter" => "a macro parameter named twice",
            "TooFewDefineArguments" => "too few arguments for this macro",
            "TooManyDefineArguments" => "too many arguments for this macro",
            "RecursionLimitReached" => "macros expand into each other too deeply",
            "DivisionByZero" => "division by zero in a preprocessor expression",
            "RemainderByZero" => "remainder (%) by zero in a preprocessor expression",
            "IntegerOverflow" => "an integer constant too large for 32 bits",
            "FloatParsingError" => "a number that cannot be read",
            "UnexpectedCharacter" => "a character that GLSL does not use here",
            "UnexpectedHash" => "a `#` that starts no directive",
            "UnexpectedNewLine" => "this directive ends too early",
            "UnexpectedEndOfInput" => "the file ends in the middle of a construct",
            "LineOverflow" => "a #line number too large",
            "MacroNotDefined" => "this macro is not defined",
            _ => return None,
        })
    };
    let word = message.split(['(', ' ']).next().unwrap_or(message);
    if message == "ErrorDirective" {
        let text = line.split_once("#error").map_or("", |(_, t)| t.trim());
        let text: String = text.chars().take(200).collect();
        return if text.is_empty() {
            "the shader stops here with `#error`".to_owned()
        } else {
            format!("the shader stops here with `#error`: {text}")
        };
    }
    if word == message || message.starts_with("UnexpectedToken(") {
        if let Some(plain) = pp(word) {
            return plain.to_owned();
        }
        if word == "UnexpectedToken" {
            return "unexpected text in a preprocessor directive".to_owned();
        }
    }
    if message.ends_with("cannot be in the left hand side") {
        return "only a variable (or an element or field of one) can be assigned or changed with `++`/`--`; \
                this is a value (`----x` applies `--` to the value of `--x`: write `x -= 2.0`)"
            .to_owned();
    }
    if let Some(name) = message
        .strip_prefix("Unknown function '")
        .and_then(|r| r.strip_suffix('\''))
        .or_else(|| message.strip_prefix("Unknown variable: "))
        .filter(|name| NAGA_LACKS.contains(name))
    {
        return format!(
            "`{name}` is GLSL, but naga 30 (the compiler that turns shaderlab's GLSL into the GPU's shaders) \
             does not implement it, so no command can run this shader: write it with the built-ins naga has \
             (docs/debugger.md lists those it lacks)"
        );
    }
    if let Some(name) = message
        .strip_prefix("Unknown function '")
        .and_then(|r| r.strip_suffix('\''))
    {
        return format!(
            "unknown function `{name}` for these arguments: no built-in and no function defined above this call takes them \
             (GLSL needs a function declared before it is called, with matching argument types)"
        );
    }
    if let Some(rest) = last.strip_prefix("Accessing index ") {
        let index = rest.split(' ').next().unwrap_or("?");
        return format!("constant index {index} is out of bounds: indices start at 0 and must be below the array's, vector's or matrix's size");
    }
    if last == "Float literal is infinite" || last == "Float literal is NaN" {
        return "a constant expression is infinite or not a number: a division by zero (such as a projective \
                texture lookup with q = 0), or a number too large for a float"
            .to_owned();
    }
    if last == "Uses operations forbidden at this stage" || last.starts_with("Expression not visited") {
        return "an operation this stage cannot use: `discard` and derivatives (dFdx, dFdy, fwidth) are for fragment shaders"
            .to_owned();
    }
    message.to_owned()
}

/// GLSL built-ins naga 30's GLSL front end does not implement: it calls them unknown.
const NAGA_LACKS: [&str; 20] = [
    "frexp",
    "modf",
    "uaddCarry",
    "usubBorrow",
    "umulExtended",
    "imulExtended",
    "matrixCompMult",
    "textureQueryLod",
    "textureSamples",
    "textureGather",
    "textureGatherOffset",
    "interpolateAtCentroid",
    "interpolateAtSample",
    "interpolateAtOffset",
    "packDouble2x32",
    "unpackDouble2x32",
    "anyInvocation",
    "allInvocations",
    "gl_HelperInvocation",
    "gl_SampleMaskIn",
];

/// Keeps only the `#error` of a list of naga's messages when there is one: naga goes on
/// parsing the directive's text as code ("Expected end of file, found Identifier").
pub fn error_directive_first<T>(found: &mut Vec<T>, message: impl Fn(&T) -> &str) {
    if found.iter().any(|f| message(f) == "ErrorDirective") {
        found.retain(|f| message(f) == "ErrorDirective");
        found.truncate(1);
    }
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
    /// Translated from a course's GLSL 1.10 ([`crate::legacy`]): its `main` is the
    /// translator's (the user's is `sl_main`), and `sl_` prefixes the names it renamed; the
    /// debugger shows neither.
    pub translated: bool,
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
    // Before naga's recursive parser: nesting, macro and call-graph bounds (see `guard`).
    guard::check(&source.text).map_err(|e| {
        let span = naga::Span::new(e.range.start as u32, e.range.end as u32);
        shader_error(path, stage, &source, &[(span, e.message)])
    })?;
    let mut frontend = naga::front::glsl::Frontend::default();
    let mut module = frontend
        .parse(&naga::front::glsl::Options::from(stage), &source.text)
        .map_err(|errors| {
            let mut spans: Vec<(naga::Span, String)> = errors
                .errors
                .iter()
                .map(|e| parse_error_span(&source.text, e))
                .collect();
            error_directive_first(&mut spans, |(_, m)| m);
            shader_error(path, stage, &source, &spans)
        })?;
    let info = finish_module(&mut module, stage).map_err(|unfinished| {
        let (span, message) = unfinished.located();
        shader_error(path, stage, &source, &[(span, message)])
    })?;
    Ok(CompiledShader {
        path: path.to_owned(),
        stage,
        source,
        module,
        info,
        translated: false,
    })
}

/// Why [`finish_module`] refused a module.
pub(crate) enum Unfinished {
    /// naga's validator refused it.
    Invalid(Box<naga::WithSpan<naga::valid::ValidationError>>),
    /// A back end of naga panicked on it (a bug in naga): the panic's message. Natively only:
    /// the browser's back ends are the browser's.
    #[cfg_attr(target_arch = "wasm32", allow(dead_code))]
    BackEnd(String),
}

impl Unfinished {
    /// Where to point (the innermost span naga names; none for a back end's panic) and what to say.
    pub(crate) fn located(&self) -> (naga::Span, String) {
        match self {
            Unfinished::Invalid(err) => {
                let mut message = err.as_inner().to_string();
                let mut source: &dyn std::error::Error = err.as_inner();
                while let Some(next) = source.source() {
                    message.push_str(": ");
                    message.push_str(&next.to_string());
                    source = next;
                }
                // naga lists the outermost span first (the whole function) and the offending
                // expression last: point at the innermost one.
                let span = err.spans().last().map(|(s, _)| *s).unwrap_or_default();
                (span, message)
            }
            Unfinished::BackEnd(panic) => (
                naga::Span::default(),
                format!(
                    "naga cannot translate this shader for the GPU: its SPIR-V writer failed ({panic}); \
                     this is a bug in naga, not in the shader: rewriting the line it trips on (often a \
                     call) differently avoids it"
                ),
            ),
        }
    }
}

/// Makes a parsed module ready for every back end: [`mend`]'s rewrites around naga's bugs, then
/// validation, then (natively, where wgpu translates to SPIR-V) a trial translation with its
/// panics contained, so that a bug in naga's writer is a message here and not a crash when
/// wgpu builds the pipeline.
pub(crate) fn finish_module(
    module: &mut naga::Module,
    stage: ShaderStage,
) -> std::result::Result<ModuleInfo, Unfinished> {
    mend::spill_partial_pointers(module);
    let info = Validator::new(ValidationFlags::all(), Capabilities::all())
        .validate(module)
        .map_err(|e| Unfinished::Invalid(Box::new(e)))?;
    try_spirv(module, &info, stage)?;
    if has_loop(module) {
        LOOPS.store(true, std::sync::atomic::Ordering::Relaxed);
    }
    Ok(info)
}

/// Set once a shader with a loop has been compiled in this process.
static LOOPS: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Whether any shader compiled in this process has a loop (`for`, `while`, `do`): a frame that
/// never ends without one is a shader too large for the driver, not one that never ends.
pub fn loops_compiled() -> bool {
    LOOPS.load(std::sync::atomic::Ordering::Relaxed)
}

fn has_loop(module: &naga::Module) -> bool {
    fn block(b: &naga::Block) -> bool {
        b.iter().any(|s| match s {
            naga::Statement::Loop { .. } => true,
            naga::Statement::Block(b) => block(b),
            naga::Statement::If { accept, reject, .. } => block(accept) || block(reject),
            naga::Statement::Switch { cases, .. } => cases.iter().any(|c| block(&c.body)),
            _ => false,
        })
    }
    module.functions.iter().any(|(_, f)| block(&f.body)) || module.entry_points.iter().any(|e| block(&e.function.body))
}

/// Translates `module` to SPIR-V once, natively, with the writer's panics contained. An error
/// (not a panic) is the writer's refusal of something the device may still take with other
/// options: wgpu's own translation reports it with the pipeline.
fn try_spirv(module: &naga::Module, info: &ModuleInfo, stage: ShaderStage) -> std::result::Result<(), Unfinished> {
    #[cfg(not(target_arch = "wasm32"))]
    {
        let pipeline = naga::back::spv::PipelineOptions {
            shader_stage: stage,
            entry_point: "main".into(),
        };
        let options = naga::back::spv::Options::default();
        let _refusal_or_words =
            crate::panics::contained(|| naga::back::spv::write_vec(module, info, &options, Some(&pipeline)))
                .map_err(|panic| Unfinished::BackEnd(panic.to_string()))?;
    }
    #[cfg(target_arch = "wasm32")]
    let _ = (module, info, stage);
    Ok(())
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
                &plain_message(msg, &src_line),
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
                plain_message(msg, "")
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

#[cfg(test)]
mod loader_tests {
    use super::*;
    use std::fs;

    /// Issue 17: nesting past `guard::MAX_DEPTH` (here in an `#include`d snippet) is an
    /// error at the snippet's line, before naga's recursive parser overflows its stack.
    #[test]
    fn deep_nesting_is_an_error_at_the_included_line() {
        let snippet = format!(
            "// deep.glsl\nfloat deep(float x) {{ return {}x{}; }}\n",
            "(".repeat(5000),
            ")".repeat(5000)
        );
        let main = "#version 450\n#include \"deep.glsl\"\nlayout(location = 0) out vec4 c;\nvoid main() { c = vec4(deep(1.0)); }\n";
        let Err(e) = compile_text("main.frag", main, ShaderStage::Fragment, &|_: &str| {
            Ok(("deep.glsl".to_owned(), snippet.clone()))
        }) else {
            panic!("accepted")
        };
        let Error::Shader {
            file, line, message, ..
        } = &e
        else {
            panic!("{e:?}")
        };
        assert_eq!((file.as_str(), *line), ("deep.glsl", 2), "{message}");
        assert!(message.contains("nests too deeply"), "{message}");
        // Just under the limit naga parses and validates it, and writes WGSL.
        let ok = format!(
            "float deep(float x) {{ return {}x{}; }}\n",
            "(".repeat(guard::MAX_DEPTH - 10),
            ")".repeat(guard::MAX_DEPTH - 10)
        );
        let shader = compile_text("main.frag", main, ShaderStage::Fragment, &|_: &str| {
            Ok(("deep.glsl".to_owned(), ok.clone()))
        })
        .unwrap_or_else(|e| panic!("{e}"));
        shader.to_wgsl().unwrap();
    }

    /// Issue 23: a moved checkout once embedded no file at all. Every file of the checkout's
    /// `shaders_glsl/` is embedded with its current text (that every shader name quoted in
    /// `src/course/` is among them, `build.rs` checks: the build fails otherwise).
    #[test]
    fn every_shader_file_is_embedded_with_its_current_text() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let mut on_disk: Vec<String> = fs::read_dir(root.join("shaders_glsl"))
            .expect("shaders_glsl/")
            .map(|e| e.expect("entry").file_name().into_string().expect("UTF-8 name"))
            .collect();
        on_disk.sort();
        let embedded: Vec<&str> = embedded_names().collect();
        assert_eq!(embedded, on_disk, "the embedded list is the folder's files");
        for name in &on_disk {
            let text = fs::read_to_string(root.join("shaders_glsl").join(name)).expect("shader text");
            assert_eq!(
                embedded_source(name),
                Some(text.as_str()),
                "{name}: embedded text is stale"
            );
        }
    }

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
        assert!(err.contains("a directory; shader files must be regular files"), "{err}");
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

    #[test]
    fn long_lines_are_cut_around_the_caret() {
        // A 2 MB line printed whole made 4 MB of stderr (the line and the caret's padding).
        let line = format!("{}BAD{}", "a".repeat(1_000_000), "b".repeat(1_000_000));
        let d = format_diagnostic("x.frag", 1, 1_000_001, "here", &line, 3);
        assert!(d.len() < 600, "{} bytes", d.len());
        let lines: Vec<&str> = d.lines().collect();
        assert!(lines[1].contains("…") && lines[1].ends_with('…'), "{d}");
        // The caret stays under the construct.
        let at = lines[1].chars().position(|c| c == 'B').unwrap();
        let caret = lines[2].chars().position(|c| c == '^').unwrap();
        assert_eq!(at, caret, "{d}");
        assert!(lines[2].ends_with("^^^"), "{d}");
        // A short line is shown whole, without marks.
        let d = format_diagnostic("x.frag", 2, 5, "here", "int x = 1;", 1);
        assert!(d.ends_with("   2 | int x = 1;\n      |     ^"), "{d}");
    }

    #[test]
    fn a_panic_of_naga_s_writer_is_a_message_and_the_rewrite_avoids_it() {
        // naga 30's SPIR-V writer panics on an `out` argument that is a vector's component, as
        // its GLSL front end passes it.
        let text = "#version 450\nlayout(location = 0) out vec4 o;\nvoid h(out float x) { x = 0.5; }\n\
                    void main() { vec4 c = vec4(0.0); h(c.y); o = c; }\n";
        let parse = || {
            naga::front::glsl::Frontend::default()
                .parse(&naga::front::glsl::Options::from(ShaderStage::Fragment), text)
                .expect("parses")
        };
        let validate = |module: &naga::Module| {
            Validator::new(ValidationFlags::all(), Capabilities::all())
                .validate(module)
                .expect("valid")
        };
        let raw = parse();
        match try_spirv(&raw, &validate(&raw), ShaderStage::Fragment) {
            Err(Unfinished::BackEnd(panic)) => assert!(panic.contains("not cached"), "{panic}"),
            _ => panic!("naga's writer no longer panics here: the rewrite may be unneeded"),
        }
        let (_, message) = Unfinished::BackEnd("x".into()).located();
        assert!(message.contains("bug in naga"), "{message}");
        let mut mended = parse();
        assert_eq!(mend::spill_partial_pointers(&mut mended), 1);
        assert!(finish_module(&mut mended, ShaderStage::Fragment).is_ok());
    }

    #[test]
    fn naga_internals_become_sentences() {
        let cases = [
            ("ErrorDirective", "#error not done yet", "`#error`: not done yet"),
            ("UnfinishedBlock", "#if 1", "no matching `#endif`"),
            (
                "HirExpr { kind: PrePostfix { op: Subtract, postfix: false, expr: [1] }, meta: Span { start: 310, end: 312 } } cannot be in the left hand side",
                "",
                "only a variable",
            ),
            ("Unknown function 'f'", "", "unknown function `f`"),
            ("Unknown function 'frexp'", "", "`frexp` is GLSL, but naga 30"),
            ("Unknown variable: gl_HelperInvocation", "", "`gl_HelperInvocation` is GLSL, but naga 30"),
            (
                "Function [0] 'main' is invalid: Expression [8] is invalid: Accessing index 7 is out of [5] bounds",
                "",
                "constant index 7 is out of bounds",
            ),
            ("Float literal is infinite", "", "division by zero"),
            (
                "Entry point main at Vertex is invalid: Uses operations forbidden at this stage",
                "",
                "`discard`",
            ),
        ];
        for (naga, line, plain) in cases {
            let m = plain_message(naga, line);
            assert!(m.contains(plain), "{naga} → {m}");
            for internal in ["HirExpr", "ErrorDirective", "UnfinishedBlock", "Expression [", "Span {"] {
                assert!(!m.contains(internal), "{naga} → {m}");
            }
        }
        assert_eq!(plain_message("something else", ""), "something else");
    }

    #[test]
    fn the_glsl_450_loader_says_error_directives_in_words() {
        let dir = shader_dir("error_directive");
        phong_with(&dir, "#error not ported yet");
        let e = compile_err(&dir, "phong.frag");
        assert!(e.contains("the shader stops here with `#error`: not ported yet"), "{e}");
        assert!(
            !e.contains("ErrorDirective") && !e.contains("Expected end of file"),
            "{e}"
        );
    }
}
