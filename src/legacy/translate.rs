//! The translation proper: parse both stages with glsl-lang, find every GLSL 1.10 construct
//! on the syntax tree, and rewrite the user's text in place (declarations, `main`, texture
//! lookups, clashing names) with a generated prologue (GL's built-in state, the loose uniforms
//! as one block, the mesh inputs, the varyings with matched locations) and a generated `main`
//! that feeds and collects GL's built-in variables around the user's own `main`.

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::ops::Range;

use glsl_lang::ast;
use glsl_lang::parse::DefaultParse;
use glsl_lang::visitor::{Host, Visit, Visitor};
use naga::ShaderStage;

use super::builtins::{classify, texture_function, Builtin, SamplerDim, CLASHES, MAX_TEXTURE_COORDS, STATE, STRUCTS};
use super::map::{apply, Edit, File, LegacySource, Origin, Output};
use super::names;
use crate::error::{Error, Result};

/// A scalar kind of GLSL 1.10.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scalar {
    /// `float`
    Float,
    /// `int`
    Int,
    /// `bool`
    Bool,
}

/// A non-opaque GLSL 1.10/1.20 type: scalar, vector (`cols` 1) or matrix (`cols` x `rows`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Ty {
    /// Component kind.
    pub scalar: Scalar,
    /// Columns (1 for scalars and vectors).
    pub cols: u8,
    /// Rows (the vector size; 1 for scalars).
    pub rows: u8,
}

impl Ty {
    /// The GLSL name (`vec3`, `mat2x3`, `bvec2`).
    pub fn glsl(self) -> String {
        let prefix = match self.scalar {
            Scalar::Float => "",
            Scalar::Int => "i",
            Scalar::Bool => "b",
        };
        match (self.cols, self.rows) {
            (1, 1) => match self.scalar {
                Scalar::Float => "float".into(),
                Scalar::Int => "int".into(),
                Scalar::Bool => "bool".into(),
            },
            (1, n) => format!("{prefix}vec{n}"),
            (c, r) if c == r => format!("mat{c}"),
            (c, r) => format!("mat{c}x{r}"),
        }
    }

    /// Number of components.
    pub fn components(self) -> usize {
        self.cols as usize * self.rows as usize
    }

    fn is_matrix(self) -> bool {
        self.cols > 1
    }
}

/// How a loose uniform is held in the uniform block (GLSL 450 in naga's std140 cannot hold
/// every GLSL 1.10 type as it is).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Encoding {
    /// As declared, under its own name.
    Plain,
    /// An array of float, int, bool, vec2, ivec2 or bvec2: one vec4/ivec4 per element, copied
    /// into a private array of the user's name at the start of `main`.
    Padded,
    /// bool or bvecN: an int or ivecN, converted into a private of the user's name.
    Bool,
    /// mat2, mat3x2 or mat4x2: one vec4 per column (`.xy`), rebuilt into a private matrix.
    Columns,
}

/// One loose uniform (or generic vertex attribute) of the program, merged over both stages.
#[derive(Clone, Debug, PartialEq)]
pub struct Uniform {
    /// The name in the user's source.
    pub name: String,
    /// Its name in GLSL 450 (`sl_NAME` when it clashes with a GLSL 450 built-in).
    pub glsl: String,
    /// Its type.
    pub ty: Ty,
    /// Its array length, if it is an array.
    pub array: Option<u32>,
    /// Its value before any `--set`: the initializer of GLSL 1.20, GL's 0 otherwise, and
    /// (0, 0, 0, 1) for a generic vertex attribute.
    pub default: Vec<f64>,
    /// How the block holds it.
    pub encoding: Encoding,
    /// Declared as `attribute` (a generic vertex attribute GL would read as a constant).
    pub attribute: bool,
    /// The first declaration: (vertex file?, byte range).
    pub declared: (bool, Range<usize>),
}

impl Uniform {
    /// The member of the uniform block that holds it.
    pub fn member(&self) -> String {
        match self.encoding {
            Encoding::Plain => self.glsl.clone(),
            _ => names::encoded(&self.glsl),
        }
    }

    /// Number of values it takes (`--set name=...`).
    pub fn components(&self) -> usize {
        self.ty.components() * self.array.unwrap_or(1) as usize
    }

    fn array_suffix(&self) -> String {
        self.array.map(|n| format!("[{n}]")).unwrap_or_default()
    }

    /// Its declaration inside the uniform block.
    fn block_decl(&self) -> String {
        let n = self.array.map(|n| format!("[{n}]")).unwrap_or_default();
        match self.encoding {
            Encoding::Plain => format!("{} {}{n};", self.ty.glsl(), self.glsl),
            Encoding::Padded => {
                let v = if self.ty.scalar == Scalar::Float {
                    "vec4"
                } else {
                    "ivec4"
                };
                format!("{v} {}{n};", self.member())
            }
            Encoding::Bool => {
                let t = Ty {
                    scalar: Scalar::Int,
                    ..self.ty
                };
                format!("{} {};", t.glsl(), self.member())
            }
            Encoding::Columns => format!("vec4 {}[{}];", self.member(), self.ty.cols),
        }
    }

    /// The private variable of the user's name, for the encodings that need one.
    fn private_decl(&self) -> Option<String> {
        (self.encoding != Encoding::Plain).then(|| format!("{} {}{};", self.ty.glsl(), self.glsl, self.array_suffix()))
    }

    /// An element `m[i]` of a padded array read in place, as GLSL 1.10 reads `name[i]`: the
    /// text before `m` and after `]`.
    fn element_read(&self) -> (String, String) {
        let swizzle = match self.ty.rows {
            1 => ".x",
            2 => ".xy",
            3 => ".xyz",
            _ => "",
        };
        match (self.ty.scalar, self.ty.rows) {
            (Scalar::Bool, 1) => ("(".into(), ".x != 0)".into()),
            (Scalar::Bool, n) => ("notEqual(".into(), format!("{swizzle}, ivec{n}(0))")),
            _ => (String::new(), swizzle.into()),
        }
    }

    /// Statements of the generated `main` that fill the private variable.
    fn private_init(&self) -> Option<String> {
        let (g, m) = (&self.glsl, self.member());
        let swizzle = match self.ty.rows {
            1 => ".x",
            2 => ".xy",
            3 => ".xyz",
            _ => "",
        };
        Some(match self.encoding {
            Encoding::Plain => return None,
            Encoding::Padded => {
                let n = self.array.unwrap_or(1);
                let value = match self.ty.scalar {
                    Scalar::Bool if self.ty.rows == 1 => format!("{m}[i].x != 0"),
                    Scalar::Bool => format!("notEqual({m}[i]{swizzle}, ivec{}(0))", self.ty.rows),
                    _ => format!("{m}[i]{swizzle}"),
                };
                format!("for (int i = 0; i < {n}; i++) {{ {g}[i] = {value}; }}")
            }
            Encoding::Bool if self.ty.rows == 1 => format!("{g} = {m} != 0;"),
            Encoding::Bool => format!("{g} = notEqual({m}, ivec{}(0));", self.ty.rows),
            Encoding::Columns => {
                let cols: Vec<String> = (0..self.ty.cols).map(|c| format!("{m}[{c}].xy")).collect();
                format!("{g} = {}({});", self.ty.glsl(), cols.join(", "))
            }
        })
    }
}

/// A `uniform sampler2D`/`samplerCube`: a texture and a sampler in GLSL 450.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Sampler {
    /// The name in the user's source (what `--texture NAME=FILE` names).
    pub name: String,
    /// The texture's name in GLSL 450.
    pub glsl: String,
    /// The sampler's name in GLSL 450.
    pub sampler: String,
    /// 2D or cube.
    pub dim: SamplerDim,
    /// The texture's binding (the sampler's is the next one).
    pub binding: u32,
}

/// A stage's translation.
#[derive(Clone, Debug)]
pub struct Translated {
    /// The user's file.
    pub source: LegacySource,
    /// The other stage's file (some generated declarations stand for it).
    pub other: LegacySource,
    /// The stage.
    pub stage: ShaderStage,
    /// GLSL 450 with its map back to the files.
    pub output: Output,
}

impl Translated {
    /// The user's line that a place of the generated text comes from ("" for generated text).
    pub fn source_line_at(&self, offset: usize) -> String {
        match self.output.locate(offset) {
            Some(origin) => {
                let file = match origin.file {
                    File::This => &self.source,
                    File::Other => &self.other,
                };
                file.line_col(origin.offset).2.to_owned()
            }
            None => String::new(),
        }
    }

    /// An error at a place of the generated text, reported in the user's file.
    pub fn error_at(&self, offset: usize, len: usize, message: &str) -> Error {
        match self.output.locate(offset) {
            Some(origin) => {
                let file = match origin.file {
                    File::This => &self.source,
                    File::Other => &self.other,
                };
                let len = if origin.len > 1 { origin.len } else { len };
                file.error(origin.offset..origin.offset + len, message)
            }
            None => self.source.error(0..1, message),
        }
    }
}

/// Both stages translated, and what the program needs from the CPU.
#[derive(Clone, Debug)]
pub struct Translation {
    /// The vertex shader.
    pub vertex: Translated,
    /// The fragment shader.
    pub fragment: Translated,
    /// The loose uniforms (block `sl_Uniforms`, binding 1), vertex stage's first.
    pub uniforms: Vec<Uniform>,
    /// What the vertex shader passes to the fragment shader, by location: the user's
    /// varyings (with their declaration in the vertex file), then `gl_FrontColor` and each
    /// `gl_TexCoord[i]` used (all 8 for a variable index).
    pub varyings: Vec<(String, Option<Range<usize>>)>,
    /// The samplers (bindings 2 and up).
    pub samplers: Vec<Sampler>,
    /// The members of the built-in state block (`sl_GlState`, binding 0) the shaders use.
    pub state: Vec<&'static str>,
    /// Whether the vertex shader reads `gl_MultiTexCoord0`.
    pub texcoords: bool,
    /// How many of GL's lights the shaders index (`gl_LightSource[i]`, `gl_FrontLightProduct[i]`:
    /// the highest constant index + 1, all 8 for a variable index).
    pub lights: usize,
}

/// The binding of the built-in state block.
pub const STATE_BINDING: u32 = 0;
/// The binding of the loose uniforms' block.
pub const UNIFORM_BINDING: u32 = 1;
/// The name of the built-in state block.
pub const STATE_BLOCK: &str = "sl_GlState";
/// The name of the loose uniforms' block.
pub const UNIFORM_BLOCK: &str = "sl_Uniforms";
/// The largest uniform array, in bytes of the uniform block: wgpu's guaranteed
/// `max_uniform_buffer_binding_size`.
pub const MAX_UNIFORM_BLOCK_BYTES: u64 = 16384;

fn span_of<T: ast::NodeContent>(node: &ast::Node<T>) -> Option<Range<usize>> {
    node.span.map(|s| {
        let r = s.range();
        u32::from(r.start()) as usize..u32::from(r.end()) as usize
    })
}

fn span0<T: ast::NodeContent>(node: &ast::Node<T>) -> Range<usize> {
    span_of(node).unwrap_or(0..0)
}

/// A declared variable of interest (attribute, varying, uniform).
#[derive(Clone, Debug)]
struct Declarator {
    name: String,
    range: Range<usize>,
    ty: DeclTy,
    array: Option<u32>,
    init: Option<Vec<f64>>,
}

#[derive(Clone, Debug, PartialEq)]
enum DeclTy {
    Value(Ty),
    Sampler(SamplerDim),
    Other(String),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Storage {
    Attribute,
    Varying,
    Uniform,
}

#[derive(Clone, Debug)]
struct GlobalDecl {
    storage: Storage,
    range: Range<usize>,
    /// `centroid`, `invariant` kept for varyings.
    extra: String,
    declarators: Vec<Declarator>,
}

/// What one stage contains.
struct Analysis<'a> {
    stage: ShaderStage,
    source: &'a LegacySource,
    edits: Vec<Edit>,
    globals: Vec<GlobalDecl>,
    builtins: BTreeMap<&'static str, Range<usize>>,
    texcoords: BTreeSet<u32>,
    texcoord_any: bool,
    lights: BTreeSet<u32>,
    lights_any: bool,
    fragdata: bool,
    fragcolor: bool,
    ftransform: Option<Range<usize>>,
    main: Option<Range<usize>>,
    /// (sampler name, range of the argument) of each texture lookup, checked after the
    /// declarations are known.
    lookups: Vec<(String, Range<usize>, SamplerDim)>,
    handled: BTreeSet<usize>,
    /// The function whose body is being visited, the functions defined, and each call of a
    /// user function (caller, callee, range): GLSL forbids recursion, which naga reports as
    /// "Unknown function", so cycles are found here.
    function: Option<String>,
    functions: BTreeSet<String>,
    calls: Vec<(String, String, Range<usize>)>,
    /// Each `NAME[...]`: the name, its range and the end of the whole expression (an array
    /// uniform held padded is read in place there, not copied whole on every invocation).
    element_reads: Vec<(String, Range<usize>, usize)>,
    /// The starts of the names of `element_reads`.
    element_bases: BTreeSet<usize>,
    /// Names that cannot be read in place: used whole, declared again, or named by a macro.
    not_in_place: BTreeSet<String>,
    /// How many times each name is declared.
    declared: BTreeMap<String, usize>,
    error: Option<Error>,
}

impl Analysis<'_> {
    fn fail(&mut self, range: Range<usize>, message: &str) {
        if self.error.is_none() {
            self.error = Some(self.source.error(range, message));
        }
    }

    fn text(&self, range: &Range<usize>) -> &str {
        self.source.text.get(range.clone()).unwrap_or("")
    }

    fn edit(&mut self, range: Range<usize>, text: impl Into<String>) {
        self.edits.push(Edit {
            range,
            text: text.into(),
        });
    }

    fn use_builtin(&mut self, name: &str, range: Range<usize>) {
        let Some(builtin) = classify(name, self.stage) else {
            return;
        };
        let key = match &builtin {
            Builtin::State(m) => m.name,
            _ => STATE
                .iter()
                .map(|m| m.name)
                .find(|n| *n == name)
                .unwrap_or_else(|| leak_builtin_name(name)),
        };
        self.builtins.entry(key).or_insert(range.clone());
        match builtin {
            Builtin::Unsupported(why) => self.fail(range, &format!("`{name}`: {why}")),
            Builtin::WrongStage(why) => {
                let stage = match self.stage {
                    ShaderStage::Vertex => "vertex",
                    _ => "fragment",
                };
                self.fail(range, &format!("`{name}` {why}; this is a {stage} shader"))
            }
            Builtin::Constant(value) => self.edit(range, value),
            // wgpu draws points one pixel wide and has no point-size output in WGSL: the
            // shader's writes go to a private variable, so the runner and `glsl2wgsl --legacy`
            // accept the same shaders (the runner draws triangles, where GL ignores it too).
            Builtin::Native if name == "gl_PointSize" => self.edit(range, names::builtin(name)),
            Builtin::TexCoord if !self.handled.contains(&range.start) => self.texcoord_any = true,
            Builtin::State(m)
                if matches!(m.name, "gl_LightSource" | "gl_FrontLightProduct")
                    && !self.handled.contains(&range.start) =>
            {
                self.lights_any = true
            }
            Builtin::FragData if !self.handled.contains(&range.start) => self.fail(
                range,
                "`gl_FragData` must be indexed with 0 (multiple render targets are not supported)",
            ),
            Builtin::FragData => self.fragdata = true,
            Builtin::FragColor => self.fragcolor = true,
            _ => {}
        }
    }
}

/// Names of GL built-ins outside the state table, kept as 'static keys.
fn leak_builtin_name(name: &str) -> &'static str {
    const NAMES: &[&str] = &[
        "gl_Vertex",
        "gl_Normal",
        "gl_MultiTexCoord0",
        "gl_MultiTexCoord1",
        "gl_MultiTexCoord2",
        "gl_MultiTexCoord3",
        "gl_MultiTexCoord4",
        "gl_MultiTexCoord5",
        "gl_MultiTexCoord6",
        "gl_MultiTexCoord7",
        "gl_FrontColor",
        "gl_Color",
        "gl_TexCoord",
        "gl_FragColor",
        "gl_FragData",
        "gl_PointSize",
    ];
    NAMES.iter().copied().find(|n| *n == name).unwrap_or("gl_other")
}

impl Visitor for Analysis<'_> {
    fn visit_expr(&mut self, expr: &ast::Expr) -> Visit {
        match &expr.content {
            ast::ExprData::Variable(ident) => {
                let name = ident.0.as_str();
                let range = span0(ident);
                if !self.element_bases.contains(&range.start) {
                    self.not_in_place.insert(name.to_owned());
                }
                if name.starts_with("gl_") {
                    self.use_builtin(name, range);
                }
            }
            ast::ExprData::Bracket(array, index) => {
                if let ast::ExprData::Variable(ident) = &array.content {
                    let name = ident.0.as_str();
                    if let Some(whole) = span_of(expr) {
                        let range = span0(ident);
                        self.element_bases.insert(range.start);
                        self.element_reads.push((name.to_owned(), range, whole.end));
                    }
                    if name == "gl_LightSource" || name == "gl_FrontLightProduct" {
                        if let ast::ExprData::IntConst(k) = &index.content {
                            if (*k as usize) < super::builtins::MAX_LIGHTS {
                                self.lights.insert(*k as u32);
                                self.handled.insert(span0(ident).start);
                            }
                        }
                    }
                    if name == "gl_TexCoord" || name == "gl_FragData" {
                        let range = span0(ident);
                        match (&index.content, name) {
                            (ast::ExprData::IntConst(k), "gl_TexCoord") if (*k as u32) < MAX_TEXTURE_COORDS => {
                                self.texcoords.insert(*k as u32);
                                self.handled.insert(range.start);
                            }
                            (ast::ExprData::IntConst(0), "gl_FragData") => {
                                self.handled.insert(range.start);
                            }
                            _ => {}
                        }
                    }
                }
            }
            ast::ExprData::FunCall(fun, args) => {
                if let Some(ident) = fun.as_ident() {
                    let name = ident.0.as_str();
                    let range = span0(ident);
                    if let Some(caller) = &self.function {
                        self.calls.push((caller.clone(), name.to_owned(), range.clone()));
                    }
                    if name == "ftransform" {
                        if self.stage != ShaderStage::Vertex {
                            self.fail(
                                range.clone(),
                                "`ftransform()` is a vertex shader function; this is a fragment shader",
                            );
                        }
                        self.ftransform.get_or_insert(range);
                    } else if let Some(lookup) = texture_function(name) {
                        match lookup {
                            Err(why) => self.fail(range, &format!("`{name}`: {why}")),
                            Ok((new_name, dim)) => {
                                self.edit(range.clone(), new_name);
                                match args.first().map(|a| (&a.content, span0(a))) {
                                    Some((ast::ExprData::Variable(s), arg)) => {
                                        self.handled.insert(arg.start);
                                        self.lookups.push((s.0.to_string(), arg, dim));
                                    }
                                    Some((_, arg)) => self.fail(
                                        arg,
                                        &format!(
                                            "the first argument of `{name}` must be a uniform {}",
                                            dim.legacy_name()
                                        ),
                                    ),
                                    None => self.fail(range, &format!("`{name}` needs a sampler and coordinates")),
                                }
                            }
                        }
                    }
                }
            }
            _ => {}
        }
        Visit::Children
    }

    fn visit_identifier(&mut self, ident: &ast::Identifier) -> Visit {
        let name = ident.0.as_str();
        if CLASHES.contains(&name) {
            let range = span0(ident);
            if !self.handled.contains(&range.start) {
                self.edit(range, names::reserved(name));
            }
        }
        Visit::Children
    }

    fn visit_jump_statement(&mut self, jump: &ast::JumpStatement) -> Visit {
        if matches!(jump.content, ast::JumpStatementData::Discard) && self.stage == ShaderStage::Vertex {
            self.fail(
                span0(jump),
                "`discard` is only allowed in a fragment shader; this is a vertex shader",
            );
        }
        Visit::Children
    }

    fn visit_function_definition(&mut self, def: &ast::FunctionDefinition) -> Visit {
        let name = def.prototype.name.0.as_str();
        self.function = Some(name.to_owned());
        self.functions.insert(name.to_owned());
        if name == "main" {
            // `void main(void)` is allowed; anything else is an error naga reports as
            // "Unknown function 'main'".
            let takes_some = def.prototype.parameters.iter().any(|p| {
                !matches!(&p.content, ast::FunctionParameterDeclarationData::Unnamed(_, t)
                    if matches!(t.ty.content, ast::TypeSpecifierNonArrayData::Void))
            });
            if takes_some {
                self.fail(
                    span0(&def.prototype),
                    "`main` takes no parameters: write `void main()` (values come in as uniforms, attributes or varyings)",
                );
            }
            let range = span0(&def.prototype.name);
            self.edit(range.clone(), names::MAIN);
            self.main = Some(range);
        }
        Visit::Children
    }

    fn visit_single_declaration(&mut self, d: &ast::SingleDeclaration) -> Visit {
        if let Some(name) = &d.name {
            *self.declared.entry(name.0.to_string()).or_default() += 1;
        }
        Visit::Children
    }

    fn visit_single_declaration_no_type(&mut self, d: &ast::SingleDeclarationNoType) -> Visit {
        *self.declared.entry(d.ident.ident.0.to_string()).or_default() += 1;
        Visit::Children
    }

    fn visit_function_parameter_declarator(&mut self, d: &ast::FunctionParameterDeclarator) -> Visit {
        *self.declared.entry(d.ident.ident.0.to_string()).or_default() += 1;
        Visit::Children
    }

    fn visit_function_parameter_declaration(&mut self, param: &ast::FunctionParameterDeclaration) -> Visit {
        let ty = match &param.content {
            ast::FunctionParameterDeclarationData::Named(_, d) => &d.ty,
            ast::FunctionParameterDeclarationData::Unnamed(_, t) => t,
        };
        if let DeclTy::Sampler(dim) = decl_ty(&ty.ty.content, "") {
            self.fail(
                span0(param),
                &format!(
                    "a {} function parameter is not supported: sample the uniform in the function that uses it",
                    dim.legacy_name()
                ),
            );
        }
        Visit::Children
    }

    fn visit_preprocessor(&mut self, pp: &ast::Preprocessor) -> Visit {
        // Macros are expanded by naga after the translation: find the built-ins they use.
        if let ast::PreprocessorData::Define(define) = &pp.content {
            let body = match &define.content {
                ast::PreprocessorDefineData::ObjectLike { value, .. } => value,
                ast::PreprocessorDefineData::FunctionLike { value, .. } => value,
            };
            let range = span0(pp);
            for word in body.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_')) {
                self.not_in_place.insert(word.to_owned());
                if word.starts_with("gl_") {
                    if let Some(Builtin::State(_)) = classify(word, self.stage) {
                        self.use_builtin(word, range.clone());
                    } else if classify(word, self.stage).is_some_and(|b| b != Builtin::Native) {
                        self.fail(
                            range.clone(),
                            &format!("`{word}` inside a #define is not supported: use it in the code"),
                        );
                    }
                }
            }
        }
        Visit::Children
    }
}

fn decl_ty(t: &ast::TypeSpecifierNonArrayData, text: &str) -> DeclTy {
    use ast::TypeSpecifierNonArrayData as T;
    let v = |scalar, cols, rows| DeclTy::Value(Ty { scalar, cols, rows });
    match t {
        T::Float => v(Scalar::Float, 1, 1),
        T::Int => v(Scalar::Int, 1, 1),
        T::Bool => v(Scalar::Bool, 1, 1),
        T::Vec2 => v(Scalar::Float, 1, 2),
        T::Vec3 => v(Scalar::Float, 1, 3),
        T::Vec4 => v(Scalar::Float, 1, 4),
        T::IVec2 => v(Scalar::Int, 1, 2),
        T::IVec3 => v(Scalar::Int, 1, 3),
        T::IVec4 => v(Scalar::Int, 1, 4),
        T::BVec2 => v(Scalar::Bool, 1, 2),
        T::BVec3 => v(Scalar::Bool, 1, 3),
        T::BVec4 => v(Scalar::Bool, 1, 4),
        T::Mat2 | T::Mat22 => v(Scalar::Float, 2, 2),
        T::Mat3 | T::Mat33 => v(Scalar::Float, 3, 3),
        T::Mat4 | T::Mat44 => v(Scalar::Float, 4, 4),
        T::Mat23 => v(Scalar::Float, 2, 3),
        T::Mat24 => v(Scalar::Float, 2, 4),
        T::Mat32 => v(Scalar::Float, 3, 2),
        T::Mat34 => v(Scalar::Float, 3, 4),
        T::Mat42 => v(Scalar::Float, 4, 2),
        T::Mat43 => v(Scalar::Float, 4, 3),
        T::Sampler2D => DeclTy::Sampler(SamplerDim::D2),
        T::SamplerCube => DeclTy::Sampler(SamplerDim::Cube),
        _ => DeclTy::Other(text.to_owned()),
    }
}

/// The number of an array specifier (`[4]`), or an error message.
fn array_len(spec: &ast::ArraySpecifier) -> std::result::Result<u32, &'static str> {
    match spec.dimensions.as_slice() {
        [dim] => match &dim.content {
            ast::ArraySpecifierDimensionData::ExplicitlySized(e) => match &e.content {
                ast::ExprData::IntConst(n) if *n > 0 => Ok(*n as u32),
                _ => Err("the array size must be a number"),
            },
            ast::ArraySpecifierDimensionData::Unsized => Err("an unsized array cannot be a uniform or varying"),
        },
        _ => Err("arrays of arrays are not GLSL 1.10"),
    }
}

/// The values of a constant initializer (`1.0`, `vec3(1.0, 0.5, 0.0)`, `-2`), flattened.
fn const_values(expr: &ast::Expr) -> Option<Vec<f64>> {
    Some(match &expr.content {
        ast::ExprData::FloatConst(v) => vec![f64::from(*v)],
        ast::ExprData::DoubleConst(v) => vec![*v],
        ast::ExprData::IntConst(v) => vec![f64::from(*v)],
        ast::ExprData::UIntConst(v) => vec![f64::from(*v)],
        ast::ExprData::BoolConst(v) => vec![if *v { 1.0 } else { 0.0 }],
        ast::ExprData::Unary(op, e) if op.content == ast::UnaryOpData::Minus => {
            const_values(e)?.into_iter().map(|v| -v).collect()
        }
        ast::ExprData::Unary(op, e) if op.content == ast::UnaryOpData::Add => const_values(e)?,
        ast::ExprData::FunCall(fun, args) => {
            let ast::FunIdentifierData::TypeSpecifier(t) = &fun.content else {
                return None;
            };
            if t.array_specifier.is_some() {
                return None;
            }
            let DeclTy::Value(ty) = decl_ty(&t.ty.content, "") else {
                return None;
            };
            let mut values = Vec::new();
            for a in args {
                values.extend(const_values(a)?);
            }
            let n = ty.components();
            if values.len() == 1 && n > 1 {
                // vec3(1.0): every component; mat3(1.0): the diagonal.
                let v = values[0];
                if ty.is_matrix() {
                    (0..n)
                        .map(|i| {
                            if i % ty.rows as usize == i / ty.rows as usize {
                                v
                            } else {
                                0.0
                            }
                        })
                        .collect()
                } else {
                    vec![v; n]
                }
            } else if values.len() >= n {
                values.truncate(n);
                values
            } else {
                return None;
            }
        }
        _ => return None,
    })
}

fn analyse<'a>(source: &'a LegacySource, stage: ShaderStage) -> Result<Analysis<'a>> {
    // Before glsl-lang's parser, the visitor below and naga: nesting, macro and call-graph
    // bounds (see `shader::guard`); the generated code around the user's adds little depth.
    crate::shader::guard::check(&source.text).map_err(|e| source.error(e.range, &e.message))?;
    let tu = ast::TranslationUnit::parse(source.text.as_str()).map_err(|e| {
        let pos = e.pos();
        let start = u32::from(pos.start()) as usize;
        let end = (u32::from(pos.end()) as usize).max(start + 1);
        source.error(start..end, &e.inner().to_string())
    })?;
    let mut a = Analysis {
        stage,
        source,
        edits: Vec::new(),
        globals: Vec::new(),
        builtins: BTreeMap::new(),
        texcoords: BTreeSet::new(),
        texcoord_any: false,
        lights: BTreeSet::new(),
        lights_any: false,
        fragdata: false,
        fragcolor: false,
        ftransform: None,
        main: None,
        lookups: Vec::new(),
        handled: BTreeSet::new(),
        function: None,
        functions: BTreeSet::new(),
        calls: Vec::new(),
        element_reads: Vec::new(),
        element_bases: BTreeSet::new(),
        not_in_place: BTreeSet::new(),
        declared: BTreeMap::new(),
        error: None,
    };
    for external in &tu.0 {
        let range = span0(external);
        match &external.content {
            ast::ExternalDeclarationData::Preprocessor(pp) => match &pp.content {
                ast::PreprocessorData::Version(v) => {
                    if !matches!(v.version, 100 | 110 | 120) {
                        a.fail(
                            range.clone(),
                            &format!(
                                "`#version {}`: the legacy translation takes GLSL 1.10 and 1.20 (no #version, \
                                 #version 110 or #version 120); run GLSL 3.30+ shaders as they are",
                                v.version
                            ),
                        );
                    }
                    a.edit(range, format!("// #version {} (translated to 450)", v.version));
                }
                ast::PreprocessorData::Include(_) => {
                    a.fail(range, "#include is not GLSL 1.10");
                }
                _ => {}
            },
            ast::ExternalDeclarationData::Declaration(decl) => match &decl.content {
                ast::DeclarationData::InitDeclaratorList(list) => {
                    if let Some(global) = global_decl(&mut a, list, range.clone()) {
                        a.globals.push(global);
                    }
                }
                ast::DeclarationData::Block(_) => {
                    a.fail(range, "interface blocks are GLSL 1.40 and later, not GLSL 1.10/1.20");
                }
                _ => {}
            },
            ast::ExternalDeclarationData::FunctionDefinition(_) => {}
        }
    }
    tu.visit(&mut a);
    if let Some((range, message)) = recursion(&a.functions, &a.calls) {
        a.fail(range, &message);
    }
    let again: Vec<String> = a
        .declared
        .iter()
        .filter(|(_, n)| **n > 1)
        .map(|(k, _)| k.clone())
        .collect();
    a.not_in_place.extend(again);
    if a.main.is_none() {
        a.fail(0..0, "no `void main()` in this shader");
    }
    if a.fragdata && a.fragcolor {
        let range = a.builtins.get("gl_FragData").cloned().unwrap_or(0..0);
        a.fail(range, "a shader writes gl_FragColor or gl_FragData, not both");
    }
    match a.error.take() {
        Some(e) => Err(e),
        None => Ok(a),
    }
}

/// The first call that closes a cycle of user functions, with a message naming the cycle.
fn recursion(functions: &BTreeSet<String>, calls: &[(String, String, Range<usize>)]) -> Option<(Range<usize>, String)> {
    for (caller, callee, range) in calls {
        if !functions.contains(callee) {
            continue;
        }
        // Breadth-first from the callee back to the caller, keeping each name's parent.
        let mut parent: BTreeMap<&str, &str> = BTreeMap::new();
        let mut queue = std::collections::VecDeque::from([callee.as_str()]);
        let mut seen = BTreeSet::from([callee.as_str()]);
        while let Some(f) = queue.pop_front() {
            if f == caller {
                let mut chain = vec![f];
                let mut at = f;
                while let Some(p) = parent.get(at) {
                    chain.push(p);
                    at = p;
                }
                chain.reverse();
                let path = std::iter::once(caller.as_str())
                    .chain(chain)
                    .collect::<Vec<_>>()
                    .join(" → ");
                let message = if caller == callee {
                    format!("`{caller}` calls itself: GLSL does not allow recursion; rewrite it as a loop")
                } else {
                    format!("recursion ({path}): GLSL does not allow a function to call itself, directly or through others; rewrite it as a loop")
                };
                return Some((range.clone(), message));
            }
            for (from, to, _) in calls.iter().filter(|(from, _, _)| from == f) {
                if seen.insert(to.as_str()) {
                    parent.insert(to.as_str(), from.as_str());
                    queue.push_back(to.as_str());
                }
            }
        }
    }
    None
}

/// An attribute, varying or uniform declaration at global scope.
fn global_decl(a: &mut Analysis, list: &ast::InitDeclaratorList, range: Range<usize>) -> Option<GlobalDecl> {
    let head = &list.head;
    let qualifier = head.ty.qualifier.as_ref()?;
    let mut storage = None;
    let mut extra = Vec::new();
    for q in &qualifier.qualifiers {
        match &q.content {
            ast::TypeQualifierSpecData::Storage(s) => match &s.content {
                ast::StorageQualifierData::Attribute => storage = Some(Storage::Attribute),
                ast::StorageQualifierData::Varying => storage = Some(Storage::Varying),
                ast::StorageQualifierData::Uniform => storage = Some(Storage::Uniform),
                ast::StorageQualifierData::Centroid => extra.push("centroid"),
                ast::StorageQualifierData::In | ast::StorageQualifierData::Out => {
                    let span = span0(q);
                    a.fail(
                        span,
                        "`in`/`out` globals are GLSL 1.30+: a GLSL 1.10 shader uses `attribute` and `varying`",
                    );
                }
                _ => {}
            },
            ast::TypeQualifierSpecData::Invariant => extra.push("invariant"),
            ast::TypeQualifierSpecData::Layout(_) => {
                let span = span0(q);
                a.fail(span, "layout qualifiers are not GLSL 1.10/1.20");
            }
            _ => {}
        }
    }
    let storage = storage?;
    if storage == Storage::Attribute && a.stage != ShaderStage::Vertex {
        a.fail(
            range.clone(),
            "`attribute` is for vertex shaders; this is a fragment shader",
        );
    }
    let ty_spec = &head.ty.ty;
    let ty_text = a.text(&span0(ty_spec)).to_owned();
    let ty = decl_ty(&ty_spec.ty.content, &ty_text);
    let type_array = ty_spec.array_specifier.as_ref();
    let mut declarators = Vec::new();
    let mut push = |a: &mut Analysis,
                    ident: &ast::Identifier,
                    array: Option<&ast::ArraySpecifier>,
                    init: Option<&ast::Initializer>| {
        let name = ident.0.to_string();
        let span = span0(ident);
        let array = match array.or(type_array).map(array_len) {
            None => None,
            Some(Ok(n)) => Some(n),
            Some(Err(why)) => {
                a.fail(span.clone(), &format!("`{name}`: {why}"));
                None
            }
        };
        let init = match init.map(|i| &i.content) {
            None => None,
            Some(ast::InitializerData::Simple(e)) => match const_values(e) {
                Some(v) => Some(v),
                None => {
                    a.fail(
                        span0(e),
                        "a uniform initializer must be a constant: a number or a constructor of numbers",
                    );
                    None
                }
            },
            Some(ast::InitializerData::List(_)) => {
                a.fail(span.clone(), "initializer lists are not GLSL 1.10/1.20");
                None
            }
        };
        declarators.push(Declarator {
            name,
            range: span,
            ty: ty.clone(),
            array,
            init,
        });
    };
    if let Some(name) = &head.name {
        push(a, name, head.array_specifier.as_ref(), head.initializer.as_ref());
    }
    for tail in &list.tail {
        push(
            a,
            &tail.ident.ident,
            tail.ident.array_spec.as_ref(),
            tail.initializer.as_ref(),
        );
    }
    for d in &declarators {
        let what = match storage {
            Storage::Attribute => "an attribute",
            Storage::Varying => "a varying",
            Storage::Uniform => "a uniform",
        };
        match (&d.ty, storage) {
            (DeclTy::Other(t), _) => a.fail(
                d.range.clone(),
                &format!("`{}`: {what} of type `{t}` is not supported (float, int, bool, vectors, matrices, arrays of them, sampler2D and samplerCube are)", d.name),
            ),
            (DeclTy::Sampler(_), Storage::Uniform) if d.array.is_some() => {
                a.fail(d.range.clone(), &format!("`{}`: arrays of samplers are not supported", d.name))
            }
            (DeclTy::Sampler(_), Storage::Attribute | Storage::Varying) => {
                a.fail(d.range.clone(), &format!("`{}`: a sampler cannot be {what}", d.name))
            }
            (DeclTy::Value(t), Storage::Varying) if t.is_matrix() || d.array.is_some() || t.scalar != Scalar::Float => a.fail(
                d.range.clone(),
                &format!("`{}`: varyings of matrix, array or non-float types are not supported (use float or vecN)", d.name),
            ),
            (DeclTy::Value(t), _) if t.is_matrix() && t.rows == 2 && d.array.is_some() => a.fail(
                d.range.clone(),
                &format!("`{}`: arrays of {} are not supported", d.name, t.glsl()),
            ),
            _ => {}
        }
    }
    Some(GlobalDecl {
        storage,
        range,
        extra: extra.iter().map(|e| format!("{e} ")).collect(),
        declarators,
    })
}

fn encoding(ty: Ty, array: Option<u32>) -> Encoding {
    if array.is_some() && !ty.is_matrix() && (ty.rows <= 2 || ty.scalar == Scalar::Bool) {
        Encoding::Padded
    } else if ty.scalar == Scalar::Bool {
        Encoding::Bool
    } else if ty.is_matrix() && ty.rows == 2 {
        Encoding::Columns
    } else {
        Encoding::Plain
    }
}

fn glsl_name(name: &str) -> String {
    if CLASHES.contains(&name) {
        names::reserved(name)
    } else {
        name.to_owned()
    }
}

/// Translates a vertex and a fragment shader of GLSL 1.10/1.20 into GLSL 450.
pub fn translate(vertex: &LegacySource, fragment: &LegacySource) -> Result<Translation> {
    let vs = analyse(vertex, ShaderStage::Vertex)?;
    let fs = analyse(fragment, ShaderStage::Fragment)?;

    // Loose uniforms and attributes, merged by name.
    let mut uniforms: Vec<Uniform> = Vec::new();
    let mut samplers: Vec<Sampler> = Vec::new();
    // Where each name is in `uniforms` and `samplers`: a shader may declare thousands.
    let mut uniform_at: HashMap<String, usize> = HashMap::new();
    let mut sampler_at: HashMap<String, usize> = HashMap::new();
    for (a, is_vertex) in [(&vs, true), (&fs, false)] {
        for g in a.globals.iter().filter(|g| g.storage != Storage::Varying) {
            for d in &g.declarators {
                match &d.ty {
                    DeclTy::Value(ty) => {
                        // std140 gives each array element (each matrix column) 16 bytes; wgpu
                        // guarantees uniform blocks of 16 KiB (GL 2.0's own minimum is 512
                        // vertex uniform components, 2 KiB). Checked before the defaults of a
                        // `float a[2000000000]` are allocated.
                        if let Some(len) = d.array {
                            let bytes = len as u64 * 16 * ty.cols as u64;
                            if bytes > MAX_UNIFORM_BLOCK_BYTES {
                                return Err(a.source.error(
                                    d.range.clone(),
                                    &format!(
                                        "uniform `{}` ({}[{len}]) takes {bytes} bytes of the uniform block (16 \
                                         per element{}); the limit is {MAX_UNIFORM_BLOCK_BYTES} bytes, {} elements",
                                        d.name,
                                        ty.glsl(),
                                        if ty.cols > 1 { " column" } else { "" },
                                        MAX_UNIFORM_BLOCK_BYTES / (16 * ty.cols as u64)
                                    ),
                                ));
                            }
                        }
                        let n = ty.components() * d.array.unwrap_or(1) as usize;
                        let default = match &d.init {
                            Some(v) if v.len() == n => v.clone(),
                            Some(v) => {
                                return Err(a.source.error(
                                    d.range.clone(),
                                    &format!("`{}` takes {n} value(s) but its initializer gives {}", d.name, v.len()),
                                ))
                            }
                            None if g.storage == Storage::Attribute => {
                                (0..n).map(|i| if i % 4 == 3 { 1.0 } else { 0.0 }).collect()
                            }
                            None => vec![0.0; n],
                        };
                        if let Some(u) = uniform_at.get(&d.name).map(|&i| &uniforms[i]) {
                            if u.ty != *ty || u.array != d.array {
                                let other = if u.declared.0 { vertex } else { fragment };
                                let (line, col, _) = other.line_col(u.declared.1.start);
                                return Err(a.source.error(
                                    d.range.clone(),
                                    &format!(
                                        "uniform `{}` is {}{} here but {}{} at {}:{line}:{col}",
                                        d.name,
                                        ty.glsl(),
                                        d.array.map(|n| format!("[{n}]")).unwrap_or_default(),
                                        u.ty.glsl(),
                                        u.array_suffix(),
                                        other.path
                                    ),
                                ));
                            }
                            continue;
                        }
                        uniform_at.insert(d.name.clone(), uniforms.len());
                        uniforms.push(Uniform {
                            name: d.name.clone(),
                            glsl: glsl_name(&d.name),
                            ty: *ty,
                            array: d.array,
                            default,
                            encoding: encoding(*ty, d.array),
                            attribute: g.storage == Storage::Attribute,
                            declared: (is_vertex, d.range.clone()),
                        });
                    }
                    DeclTy::Sampler(dim) => {
                        if let Some(s) = sampler_at.get(&d.name).map(|&i| &samplers[i]) {
                            if s.dim != *dim {
                                return Err(a.source.error(
                                    d.range.clone(),
                                    &format!(
                                        "`{}` is a {} here but a {} in the other shader",
                                        d.name,
                                        dim.legacy_name(),
                                        s.dim.legacy_name()
                                    ),
                                ));
                            }
                            continue;
                        }
                        let glsl = glsl_name(&d.name);
                        sampler_at.insert(d.name.clone(), samplers.len());
                        samplers.push(Sampler {
                            name: d.name.clone(),
                            sampler: format!("{glsl}_sampler"),
                            glsl,
                            dim: *dim,
                            binding: 2 + 2 * samplers.len() as u32,
                        });
                    }
                    DeclTy::Other(_) => {}
                }
            }
        }
        if let Some(u) = uniforms.iter().find(|u| sampler_at.contains_key(&u.name)) {
            let file = if u.declared.0 { vertex } else { fragment };
            return Err(file.error(
                u.declared.1.clone(),
                &format!("`{}` is a sampler in the other shader", u.name),
            ));
        }
    }
    // Texture lookups name a sampler uniform of the right dimension.
    for a in [&vs, &fs] {
        for (name, range, dim) in &a.lookups {
            match sampler_at.get(name).map(|&i| &samplers[i]) {
                Some(s) if s.dim == *dim => {}
                Some(s) => {
                    return Err(a.source.error(
                        range.clone(),
                        &format!(
                            "`{name}` is a {}, this lookup takes a {}",
                            s.dim.legacy_name(),
                            dim.legacy_name()
                        ),
                    ))
                }
                None => {
                    return Err(a.source.error(
                        range.clone(),
                        &format!("`{name}` is not a uniform {} of this program", dim.legacy_name()),
                    ))
                }
            }
        }
    }

    // Varyings: locations by the vertex shader's order; the fragment shader's must exist there.
    let mut varyings: Vec<(String, Ty, Range<usize>)> = Vec::new();
    let mut varying_at: HashMap<String, usize> = HashMap::new();
    for g in vs.globals.iter().filter(|g| g.storage == Storage::Varying) {
        for d in &g.declarators {
            if let DeclTy::Value(t) = d.ty {
                if !varying_at.contains_key(&d.name) {
                    varying_at.insert(d.name.clone(), varyings.len());
                    varyings.push((d.name.clone(), t, d.range.clone()));
                }
            }
        }
    }
    for g in fs.globals.iter().filter(|g| g.storage == Storage::Varying) {
        for d in &g.declarators {
            if let DeclTy::Value(t) = d.ty {
                match varying_at.get(&d.name).map(|&i| &varyings[i]) {
                    None => {
                        return Err(fs.source.error(
                            d.range.clone(),
                            &format!(
                                "varying `{}` is not declared by the vertex shader {}",
                                d.name, vertex.path
                            ),
                        ))
                    }
                    Some(v) if v.1 != t => {
                        let (line, col, _) = vertex.line_col(v.2.start);
                        return Err(fs.source.error(
                            d.range.clone(),
                            &format!(
                                "varying `{}` is {} here but {} at {}:{line}:{col}",
                                d.name,
                                t.glsl(),
                                v.1.glsl(),
                                vertex.path
                            ),
                        ));
                    }
                    _ => {}
                }
            }
        }
    }

    // Built-in varyings after the user's.
    let mut next_location = varyings.len() as u32;
    let front_color = fs.builtins.contains_key("gl_Color") || vs.builtins.contains_key("gl_FrontColor");
    let color_location = front_color.then(|| {
        next_location += 1;
        next_location - 1
    });
    let texcoords: Vec<u32> = if vs.texcoord_any || fs.texcoord_any {
        (0..MAX_TEXTURE_COORDS).collect()
    } else {
        vs.texcoords.union(&fs.texcoords).copied().collect()
    };
    let texcoord_locations: Vec<(u32, u32)> = texcoords
        .iter()
        .map(|k| {
            next_location += 1;
            (*k, next_location - 1)
        })
        .collect();

    // The state block: what either stage uses (the current colour feeds gl_FrontColor).
    let mut state: BTreeSet<&'static str> = BTreeSet::new();
    for a in [&vs, &fs] {
        for name in a.builtins.keys() {
            if STATE.iter().any(|m| m.name == *name) && !(name == &"gl_Color" && a.stage == ShaderStage::Fragment) {
                state.insert(name);
            }
        }
    }
    if vs.ftransform.is_some() {
        state.insert("gl_ModelViewProjectionMatrix");
    }
    if front_color {
        state.insert("gl_Color");
    }
    let state: Vec<&'static str> = STATE.iter().map(|m| m.name).filter(|n| state.contains(n)).collect();

    let ctx = Context {
        uniforms: &uniforms,
        samplers: &samplers,
        uniform_at: &uniform_at,
        sampler_at: &sampler_at,
        varying_at: &varying_at,
        state: &state,
        color_location,
        texcoords: &texcoord_locations,
    };
    let vertex_out = generate(&vs, &ctx);
    let fragment_out = generate(&fs, &ctx);
    let texcoords = vs.builtins.contains_key("gl_MultiTexCoord0");
    let lights = if vs.lights_any || fs.lights_any {
        super::builtins::MAX_LIGHTS
    } else {
        vs.lights.union(&fs.lights).max().map_or(0, |k| *k as usize + 1)
    };
    // What each location carries, for the limit check before a pipeline is made.
    let locations: Vec<(String, Option<Range<usize>>)> = varyings
        .iter()
        .map(|(name, _, range)| (name.clone(), Some(range.clone())))
        .chain(color_location.map(|_| ("gl_FrontColor".to_owned(), None)))
        .chain(
            texcoord_locations
                .iter()
                .map(|(k, _)| (format!("gl_TexCoord[{k}]"), None)),
        )
        .collect();
    Ok(Translation {
        varyings: locations,
        vertex: Translated {
            source: vertex.clone(),
            other: fragment.clone(),
            stage: ShaderStage::Vertex,
            output: vertex_out,
        },
        fragment: Translated {
            source: fragment.clone(),
            other: vertex.clone(),
            stage: ShaderStage::Fragment,
            output: fragment_out,
        },
        uniforms,
        samplers,
        state,
        texcoords,
        lights,
    })
}

struct Context<'a> {
    uniforms: &'a [Uniform],
    samplers: &'a [Sampler],
    uniform_at: &'a HashMap<String, usize>,
    sampler_at: &'a HashMap<String, usize>,
    varying_at: &'a HashMap<String, usize>,
    state: &'a [&'static str],
    color_location: Option<u32>,
    texcoords: &'a [(u32, u32)],
}

fn generate(a: &Analysis, ctx: &Context) -> Output {
    let vertex = a.stage == ShaderStage::Vertex;
    let this_file = |declared_in_vertex: bool| {
        if declared_in_vertex == vertex {
            File::This
        } else {
            File::Other
        }
    };
    let main = a.main.clone().unwrap_or(0..0);
    let at_main = Origin::this(main.clone());
    let first_use = |name: &str| a.builtins.get(name).map(|r| Origin::this(r.clone())).unwrap_or(at_main);
    let mut out = Output::default();
    out.generated(
        "#version 450\n// Translated by shaderlab from GLSL 1.10: GL's built-in state and the loose uniforms are blocks.\n",
        Origin::this(0..0),
    );

    // GL's state.
    if !ctx.state.is_empty() {
        let members: Vec<&super::builtins::StateMember> = ctx
            .state
            .iter()
            .filter_map(|n| STATE.iter().find(|m| m.name == *n))
            .collect();
        let mut structs: Vec<&str> = Vec::new();
        for m in &members {
            for s in m.structs {
                if !structs.contains(s) {
                    structs.push(s);
                }
            }
        }
        for (name, decl) in STRUCTS {
            if structs.contains(name) {
                out.generated(&format!("{decl}\n"), first_use(name));
            }
        }
        out.generated(
            &format!("layout(std140, set = 0, binding = {STATE_BINDING}) uniform {STATE_BLOCK} {{\n"),
            at_main,
        );
        for m in members {
            out.generated(&format!("    {}\n", m.decl), first_use(m.name));
        }
        out.generated("};\n", at_main);
    }

    // The loose uniforms, the same block in both stages.
    if !ctx.uniforms.is_empty() {
        out.generated(
            &format!("layout(std140, set = 0, binding = {UNIFORM_BINDING}) uniform {UNIFORM_BLOCK} {{\n"),
            at_main,
        );
        for u in ctx.uniforms {
            let origin = Origin {
                file: this_file(u.declared.0),
                offset: u.declared.1.start,
                len: u.declared.1.len(),
            };
            out.generated(&format!("    {}\n", u.block_decl()), origin);
        }
        out.generated("};\n", at_main);
    }

    // Inputs and outputs of GL's built-ins.
    let mut init = Vec::new();
    let mut finish = Vec::new();
    if vertex {
        if a.builtins.contains_key("gl_Vertex") || a.ftransform.is_some() {
            out.generated(
                &format!(
                    "layout(location = 0) in vec3 {};\nvec4 gl_Vertex;\n",
                    names::builtin("gl_Vertex")
                ),
                a.builtins
                    .get("gl_Vertex")
                    .or(a.ftransform.as_ref())
                    .map_or(at_main, |r| Origin::this(r.clone())),
            );
            init.push(format!("gl_Vertex = vec4({}, 1.0);", names::builtin("gl_Vertex")));
        }
        if a.builtins.contains_key("gl_Normal") {
            out.generated("layout(location = 1) in vec3 gl_Normal;\n", first_use("gl_Normal"));
        }
        if a.builtins.contains_key("gl_PointSize") {
            out.generated(
                &format!(
                    "float {}; // gl_PointSize: wgpu draws points one pixel wide\n",
                    names::builtin("gl_PointSize")
                ),
                first_use("gl_PointSize"),
            );
        }
        if a.builtins.contains_key("gl_MultiTexCoord0") {
            out.generated(
                &format!(
                    "layout(location = 2) in vec2 {};\nvec4 gl_MultiTexCoord0;\n",
                    names::builtin("gl_MultiTexCoord0")
                ),
                first_use("gl_MultiTexCoord0"),
            );
            init.push(format!(
                "gl_MultiTexCoord0 = vec4({}, 0.0, 1.0);",
                names::builtin("gl_MultiTexCoord0")
            ));
        }
        for k in 1..8 {
            let name = format!("gl_MultiTexCoord{k}");
            if a.builtins.contains_key(name.as_str()) {
                out.generated(
                    &format!("const vec4 {name} = vec4(0.0, 0.0, 0.0, 1.0);\n"),
                    first_use(&name),
                );
            }
        }
        if let Some(loc) = ctx.color_location {
            out.generated(
                &format!("layout(location = {loc}) out vec4 gl_FrontColor;\n"),
                first_use("gl_FrontColor"),
            );
            // GL leaves it undefined when the shader writes none; the current colour is what
            // fixed-function GL would give.
            init.push("gl_FrontColor = gl_Color;".to_owned());
            // GL_CLAMP_VERTEX_COLOR is on by default: colours are clamped per vertex, before
            // they are interpolated.
            finish.push("gl_FrontColor = clamp(gl_FrontColor, 0.0, 1.0);".to_owned());
        }
    } else if let Some(loc) = ctx.color_location {
        out.generated(
            &format!("layout(location = {loc}) in vec4 gl_Color;\n"),
            first_use("gl_Color"),
        );
    }
    if !ctx.texcoords.is_empty() {
        out.generated(
            &format!("vec4 gl_TexCoord[{MAX_TEXTURE_COORDS}];\n"),
            first_use("gl_TexCoord"),
        );
        for (k, loc) in ctx.texcoords {
            let dir = if vertex { "out" } else { "in" };
            let varying = names::builtin(&format!("gl_TexCoord{k}"));
            out.generated(
                &format!("layout(location = {loc}) {dir} vec4 {varying};\n"),
                first_use("gl_TexCoord"),
            );
            if vertex {
                init.push(format!("gl_TexCoord[{k}] = vec4(0.0, 0.0, 0.0, 1.0);"));
                finish.push(format!("{varying} = gl_TexCoord[{k}];"));
            } else {
                init.push(format!("gl_TexCoord[{k}] = {varying};"));
            }
        }
    }
    if !vertex {
        if a.fragdata {
            out.generated(
                &format!(
                    "layout(location = 0) out vec4 {};\nvec4 gl_FragData[1];\n",
                    names::builtin("gl_FragData0")
                ),
                first_use("gl_FragData"),
            );
            finish.push(format!("{} = gl_FragData[0];", names::builtin("gl_FragData0")));
        } else {
            out.generated(
                "layout(location = 0) out vec4 gl_FragColor;\n",
                first_use("gl_FragColor"),
            );
        }
    }
    if let Some(r) = &a.ftransform {
        out.generated(
            "vec4 ftransform() { return gl_ModelViewProjectionMatrix * gl_Vertex; }\n",
            Origin::this(r.clone()),
        );
    }

    // The user's declarations, rewritten where they stand.
    let mut edits = a.edits.clone();
    let mut privates = Vec::new();
    let mut in_place: Vec<&Uniform> = Vec::new();
    for g in &a.globals {
        let mut text = String::new();
        for d in &g.declarators {
            match g.storage {
                Storage::Varying => {
                    let Some(&loc) = ctx.varying_at.get(&d.name) else {
                        continue;
                    };
                    let DeclTy::Value(t) = d.ty else { continue };
                    let dir = if vertex { "out" } else { "in" };
                    text.push_str(&format!(
                        "layout(location = {loc}) {}{dir} {} {};",
                        g.extra,
                        t.glsl(),
                        d.name
                    ));
                }
                Storage::Uniform | Storage::Attribute => {
                    if let Some(s) = ctx.sampler_at.get(&d.name).map(|&i| &ctx.samplers[i]) {
                        text.push_str(&format!(
                            "layout(set = 0, binding = {}) uniform {} {}; layout(set = 0, binding = {}) uniform sampler {};",
                            s.binding,
                            s.dim.texture_type(),
                            s.glsl,
                            s.binding + 1,
                            s.sampler
                        ));
                    } else if let Some(u) = ctx.uniform_at.get(&d.name).map(|&i| &ctx.uniforms[i]) {
                        if u.encoding == Encoding::Padded && !a.not_in_place.contains(&u.name) {
                            in_place.push(u);
                            continue;
                        }
                        if let Some(p) = u.private_decl() {
                            text.push_str(&p);
                        }
                        if let Some(i) = u.private_init() {
                            privates.push(i);
                        }
                    }
                }
            }
        }
        edits.push(Edit {
            range: g.range.clone(),
            text,
        });
    }
    // Padded arrays read in place: `a[i]` becomes `sl_u_a[i].x`, not a copy of the whole array
    // into a private one on every invocation, which the driver compiles slowly (figures:
    // docs/speed.md, "Shader limits").
    if !in_place.is_empty() {
        let mut names = BTreeSet::new();
        let mut reads = Vec::new();
        for (name, range, end) in &a.element_reads {
            let Some(u) = in_place.iter().find(|u| &u.name == name) else {
                continue;
            };
            let (prefix, suffix) = u.element_read();
            names.insert((range.start, range.end));
            reads.push(Edit {
                range: range.clone(),
                text: format!("{prefix}{}", u.member()),
            });
            reads.push(Edit {
                range: *end..*end,
                text: suffix,
            });
        }
        // The name's own edit (a name GLSL 450 reserves, renamed) gives way to these.
        edits.retain(|e| !names.contains(&(e.range.start, e.range.end)));
        edits.extend(reads);
    }
    // Lookups take the texture and its sampler.
    for (name, range, dim) in &a.lookups {
        if let Some(s) = ctx.sampler_at.get(name).map(|&i| &ctx.samplers[i]) {
            edits.push(Edit {
                range: range.clone(),
                text: format!("{}({}, {})", dim.legacy_name(), s.glsl, s.sampler),
            });
        }
    }
    out.generated("\n", at_main);
    apply(&mut out, &a.source.text, &edits);
    if !out.text.ends_with('\n') {
        out.generated("\n", at_main);
    }

    // GL's built-ins around the user's main.
    let mut body = String::from("\n// GL's built-in inputs and outputs around the shader's own main.\nvoid main() {\n");
    for line in init.iter().chain(&privates) {
        body.push_str(&format!("    {line}\n"));
    }
    body.push_str(&format!("    {}();\n", names::MAIN));
    for line in &finish {
        body.push_str(&format!("    {line}\n"));
    }
    if vertex {
        // GL's clip-space depth is -w..w, wgpu's 0..w: the one place it is converted.
        body.push_str("    gl_Position.z = (gl_Position.z + gl_Position.w) * 0.5;\n");
    }
    body.push_str("}\n");
    out.generated(&body, at_main);
    out
}
