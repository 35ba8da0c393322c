//! A shader's naga module rewritten to write down, as it runs on the GPU, what the debugger's
//! trace would say about it: the value a chosen line assigns (its last assignment) and how many
//! steps the interpreter would record ([`super::interp::StepKind`]), counted at the very
//! statements where the interpreter records them.
//!
//! The rewrite adds private globals (the value as `vec4<f32>`, whether the line ran, its
//! component count, the step count) and statements that fill them; the fragment entry point
//! then returns the value and an info word packing the rest instead of its colours. A vertex
//! shader's value travels to the fragment shader as two extra varyings at a location neither
//! uses.

use naga::{Binding, Expression, Function, Handle, Literal, Module, ScalarKind, Span, Statement, Type, TypeInner};

use super::interp::pointee;
use super::{locate, user_name, value::part_name};
use crate::shader::CompiledShader;

/// An assignment a shader's trace can show: where it is in the user's file, and the name the
/// trace gives it (the user's), with the variable it is part of.
#[derive(Clone, Debug, PartialEq)]
pub struct Assignment {
    /// The file.
    pub file: String,
    /// The 1-based line.
    pub line: u32,
    /// The name as the trace writes it (`L`, `color.x`, `arr[i]`, `(temporary)`).
    pub name: String,
    /// The variable it assigns (part of): `color` for `color.x`.
    pub root: String,
    /// The components of the value a view shows (its first four).
    pub components: u32,
    /// For a store into one component of a vector (`c.x`): the vector's name (`c`) and the
    /// component.
    pub part: Option<(String, u32)>,
    /// For a matrix value: its columns and rows.
    pub matrix: Option<(u32, u32)>,
}

/// One thing a line assigns that a view can show, named as written: a whole value (`N`,
/// `arr[i]`, `c.z`), the components of a vector the line assigns one by one (`c.xy` for
/// `c.xy = …;`, in the order written), or a column of a matrix (`m[1]`).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Target {
    /// The name as the view is labelled and chosen.
    pub name: String,
    /// The variable it is (part of).
    pub root: String,
    /// The components a view shows (at most 4).
    pub components: u32,
    /// What is stored for it.
    pub pick: Pick,
}

/// Which stores of a line make a [`Target`]'s value, and how.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Pick {
    /// The value a store of this name stores.
    Value(String),
    /// These components of the vector of this name, read after each store into one of them.
    Parts(String, Vec<u32>),
    /// This column of the matrix a store of this name stores.
    Column(String, u32),
}

impl Target {
    /// Whether `name` picks it: its name, or its variable's where that is the only thing of
    /// the variable's the line assigns (`given` lists the line's targets).
    pub fn named(&self, name: &str, given: &[Target]) -> bool {
        self.name == name || (self.root == name && given.iter().filter(|t| t.root == name).count() == 1)
    }
}

/// The targets of the assignments `here` (those of one line), in the order the line first
/// assigns them: stores into single components of one vector make one target, a matrix one
/// target per column, any other name one target.
pub fn targets(here: &[&Assignment]) -> Vec<Target> {
    let mut out: Vec<Target> = Vec::new();
    for a in here {
        if let Some((base, part)) = &a.part {
            let letter = ["x", "y", "z", "w"].get(*part as usize).copied().unwrap_or("?");
            if let Some(t) = out
                .iter_mut()
                .find(|t| matches!(&t.pick, Pick::Parts(b, _) if b == base))
            {
                if let Pick::Parts(_, parts) = &mut t.pick {
                    if !parts.contains(part) && parts.len() < 4 {
                        parts.push(*part);
                        t.name.push_str(letter);
                        t.components = parts.len() as u32;
                    }
                }
                continue;
            }
            out.push(Target {
                name: format!("{base}.{letter}"),
                root: a.root.clone(),
                components: 1,
                pick: Pick::Parts(base.clone(), vec![*part]),
            });
            continue;
        }
        let made: Vec<Target> = match a.matrix {
            Some((columns, rows)) => (0..columns)
                .map(|k| Target {
                    name: format!("{}[{k}]", a.name),
                    root: a.root.clone(),
                    components: rows.min(4),
                    pick: Pick::Column(a.name.clone(), k),
                })
                .collect(),
            None => vec![Target {
                name: a.name.clone(),
                root: a.root.clone(),
                components: a.components,
                pick: Pick::Value(a.name.clone()),
            }],
        };
        for t in made {
            match out.iter_mut().find(|o| o.name == t.name) {
                Some(o) => o.components = o.components.max(t.components),
                None => out.push(t),
            }
        }
    }
    out
}

/// What a view probes in one module: the line and the name of the [`Target`] chosen (none
/// where the line assigns only what the compiler made).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Site {
    /// The file.
    pub file: String,
    /// The 1-based line.
    pub line: u32,
    /// The name chosen, if one was.
    pub name: Option<String>,
}

/// One function of a module.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Which {
    Entry(usize),
    Function(Handle<Function>),
}

fn function_of(module: &Module, which: Which) -> &Function {
    match which {
        Which::Entry(i) => &module.entry_points[i].function,
        Which::Function(h) => &module.functions[h],
    }
}

fn function_mut(module: &mut Module, which: Which) -> &mut Function {
    match which {
        Which::Entry(i) => &mut module.entry_points[i].function,
        Which::Function(h) => &mut module.functions[h],
    }
}

fn info_of(shader: &CompiledShader, which: Which) -> &naga::valid::FunctionInfo {
    match which {
        Which::Entry(i) => shader.info.get_entry_point(i),
        Which::Function(h) => &shader.info[h],
    }
}

/// Every function of `shader`'s module whose steps the trace shows (not the translator's own
/// `main`, which calls the user's).
fn functions(shader: &CompiledShader) -> Vec<Which> {
    let module = &shader.module;
    let mut out: Vec<Which> = module.functions.iter().map(|(h, _)| Which::Function(h)).collect();
    out.extend((0..module.entry_points.len()).map(Which::Entry));
    out
}

/// Whether the interpreter's steps in `function` reach the trace (the report leaves out the
/// translator's own `main`).
fn shown(shader: &CompiledShader, function: &Function) -> bool {
    !(shader.translated && function.name.as_deref() == Some("main"))
}

/// The name the interpreter gives a store through `pointer` (whole, and its variable's), as
/// the module spells it.
fn pointer_name(
    module: &Module,
    function: &Function,
    info: &naga::valid::FunctionInfo,
    pointer: Handle<Expression>,
) -> Option<(String, String)> {
    match &function.expressions[pointer] {
        Expression::LocalVariable(l) => {
            let n = function.local_variables[*l]
                .name
                .clone()
                .unwrap_or_else(|| super::interp::TEMPORARY.into());
            Some((n.clone(), n))
        }
        Expression::GlobalVariable(g) => {
            let n = module.global_variables[*g]
                .name
                .clone()
                .unwrap_or_else(|| format!("global{}", g.index()));
            Some((n.clone(), n))
        }
        Expression::AccessIndex { base, index } => {
            let (whole, root) = pointer_name(module, function, info, *base)?;
            let inner = pointee(module, info[*base].ty.inner_with(&module.types))?;
            let members = match &inner {
                TypeInner::Struct { members, .. } => Some(members.as_slice()),
                _ => None,
            };
            Some((format!("{whole}{}", part_name(&inner, *index as usize, members)), root))
        }
        Expression::Access { base, index } => {
            let (whole, root) = pointer_name(module, function, info, *base)?;
            Some((format!("{whole}[{}]", index_name(module, function, *index)), root))
        }
        _ => None,
    }
}

/// An index as written: a number, or the variable it is read from (`i` where it is
/// computed).
fn index_name(module: &Module, function: &Function, index: Handle<Expression>) -> String {
    let literal = |l: &Literal| match *l {
        Literal::I32(v) => Some(v.to_string()),
        Literal::U32(v) => Some(v.to_string()),
        Literal::I64(v) => Some(v.to_string()),
        Literal::U64(v) => Some(v.to_string()),
        Literal::AbstractInt(v) => Some(v.to_string()),
        _ => None,
    };
    let named = match &function.expressions[index] {
        Expression::Literal(l) => literal(l),
        Expression::Constant(c) => match &module.global_expressions[module.constants[*c].init] {
            Expression::Literal(l) => literal(l),
            _ => module.constants[*c].name.clone(),
        },
        Expression::Load { pointer } => match &function.expressions[*pointer] {
            Expression::LocalVariable(l) => function.local_variables[*l].name.clone(),
            Expression::GlobalVariable(g) => module.global_variables[*g].name.clone(),
            _ => None,
        },
        Expression::FunctionArgument(k) => function.arguments.get(*k as usize).and_then(|a| a.name.clone()),
        _ => None,
    };
    named.unwrap_or_else(|| "i".into())
}

/// A store's names as [`Assignment`] gives them: the name, its variable's, and for a store
/// into one component of a vector the vector's name and the component (and the vector's
/// pointer).
struct Stored {
    name: String,
    root: String,
    part: Option<(String, u32, Handle<Expression>)>,
}

fn stored(
    module: &Module,
    function: &Function,
    info: &naga::valid::FunctionInfo,
    pointer: Handle<Expression>,
) -> Option<Stored> {
    let (name, root) = pointer_name(module, function, info, pointer)?;
    let part = match &function.expressions[pointer] {
        Expression::AccessIndex { base, index } => match pointee(module, info[*base].ty.inner_with(&module.types)) {
            Some(TypeInner::Vector { .. }) => {
                pointer_name(module, function, info, *base).map(|(whole, _)| (whole, *index, *base))
            }
            _ => None,
        },
        _ => None,
    };
    Some(Stored { name, root, part })
}

/// A matrix type's columns and rows.
fn matrix(inner: &TypeInner) -> Option<(u32, u32)> {
    match *inner {
        TypeInner::Matrix { columns, rows, .. } => Some((columns as u32, rows as u32)),
        _ => None,
    }
}

/// Every assignment of `shader` the trace can show, in module order.
pub fn assignments(shader: &CompiledShader) -> Vec<Assignment> {
    let mut out = Vec::new();
    let module = &shader.module;
    for which in functions(shader) {
        let function = function_of(module, which);
        if !shown(shader, function) {
            continue;
        }
        let info = info_of(shader, which);
        for (h, local) in function.local_variables.iter() {
            if local.init.is_none() {
                continue;
            }
            if let Some((file, line)) = locate(shader, function.local_variables.get_span(h)) {
                let n = user_name(shader, local.name.as_deref().unwrap_or(super::interp::TEMPORARY));
                let inner = &module.types[local.ty].inner;
                out.push(Assignment {
                    file,
                    line,
                    name: n.clone(),
                    root: n,
                    components: count(&module.types, inner),
                    part: None,
                    matrix: matrix(inner),
                });
            }
        }
        stores(shader, function, info, &function.body, &mut out);
    }
    out
}

fn stores(
    shader: &CompiledShader,
    function: &Function,
    info: &naga::valid::FunctionInfo,
    block: &naga::Block,
    out: &mut Vec<Assignment>,
) {
    for (statement, span) in block.span_iter() {
        match statement {
            Statement::Store { pointer, value } => {
                let Some((file, line)) = locate(shader, *span) else {
                    continue;
                };
                let Some(store) = stored(&shader.module, function, info, *pointer) else {
                    continue;
                };
                let types = &shader.module.types;
                let inner = info[*value].ty.inner_with(types);
                out.push(Assignment {
                    file,
                    line,
                    name: user_name(shader, &store.name),
                    root: user_name(shader, &store.root),
                    components: count(types, inner),
                    part: store.part.map(|(base, k, _)| (user_name(shader, &base), k)),
                    matrix: matrix(inner),
                });
            }
            Statement::Block(b) => stores(shader, function, info, b, out),
            Statement::If { accept, reject, .. } => {
                stores(shader, function, info, accept, out);
                stores(shader, function, info, reject, out);
            }
            Statement::Switch { cases, .. } => {
                for c in cases {
                    stores(shader, function, info, &c.body, out);
                }
            }
            Statement::Loop { body, continuing, .. } => {
                stores(shader, function, info, body, out);
                stores(shader, function, info, continuing, out);
            }
            _ => {}
        }
    }
}

/// The globals the rewrite adds.
#[derive(Clone, Copy)]
struct Globals {
    value: Handle<naga::GlobalVariable>,
    ran: Handle<naga::GlobalVariable>,
    components: Handle<naga::GlobalVariable>,
    cost: Handle<naga::GlobalVariable>,
    vec4f: Handle<Type>,
}

fn scalar_type(module: &mut Module, scalar: naga::Scalar) -> Handle<Type> {
    module.types.insert(
        Type {
            name: None,
            inner: TypeInner::Scalar(scalar),
        },
        Span::UNDEFINED,
    )
}

fn add_globals(module: &mut Module) -> Globals {
    let vec4f = module.types.insert(
        Type {
            name: None,
            inner: TypeInner::Vector {
                size: naga::VectorSize::Quad,
                scalar: naga::Scalar::F32,
            },
        },
        Span::UNDEFINED,
    );
    let f32t = scalar_type(module, naga::Scalar::F32);
    let u32t = scalar_type(module, naga::Scalar::U32);
    let global = |module: &mut Module, name: &str, ty: Handle<Type>| {
        let init = module
            .global_expressions
            .append(Expression::ZeroValue(ty), Span::UNDEFINED);
        module.global_variables.append(
            naga::GlobalVariable {
                name: Some(name.into()),
                space: naga::AddressSpace::Private,
                binding: None,
                ty,
                init: Some(init),
                memory_decorations: Default::default(),
            },
            Span::UNDEFINED,
        )
    };
    Globals {
        value: global(module, "shaderlab_view_value", vec4f),
        ran: global(module, "shaderlab_view_ran", f32t),
        components: global(module, "shaderlab_view_components", f32t),
        cost: global(module, "shaderlab_view_cost", u32t),
        vec4f,
    }
}

/// The rewrite of one function's statements.
struct Rewrite<'a> {
    shader: &'a CompiledShader,
    which: Which,
    /// The function's steps reach the trace.
    shown: bool,
    site: Option<&'a Site>,
    /// The target chosen on the site's line (none: every store of the line).
    target: Option<&'a Target>,
    /// Count steps (the fragment shader's).
    count: bool,
    globals: Globals,
    /// Which probed assignments were found, with their component counts.
    found: Vec<u32>,
}

impl Rewrite<'_> {
    fn original(&self) -> &Function {
        function_of(&self.shader.module, self.which)
    }

    /// Whether a step at `span` reaches the trace.
    fn counted(&self, span: Span) -> bool {
        self.count && self.shown && locate(self.shader, span).is_some()
    }

    /// What to store for a store at `span` of `store` where it is the probed one.
    fn probed(&self, span: Span, store: &Stored) -> Option<Source> {
        let site = self.site?;
        if !self.shown {
            return None;
        }
        let (file, line) = locate(self.shader, span)?;
        if file != site.file || line != site.line {
            return None;
        }
        let name = user_name(self.shader, &store.name);
        match self.target.map(|t| &t.pick) {
            None => Some(Source::Stored),
            Some(Pick::Value(n)) => (*n == name).then_some(Source::Stored),
            Some(Pick::Column(n, k)) => (*n == name).then_some(Source::Column(*k)),
            Some(Pick::Parts(b, parts)) => {
                let (base, k, pointer) = store.part.as_ref()?;
                (user_name(self.shader, base) == *b && parts.contains(k))
                    .then(|| Source::Parts(*pointer, parts.clone()))
            }
        }
    }

    /// `cost += 1`.
    fn increment(&self, exprs: &mut naga::Arena<Expression>, out: &mut naga::Block) {
        let s = Span::UNDEFINED;
        let g = exprs.append(Expression::GlobalVariable(self.globals.cost), s);
        let one = exprs.append(Expression::Literal(Literal::U32(1)), s);
        let start = exprs.len();
        let old = exprs.append(Expression::Load { pointer: g }, s);
        let new = exprs.append(
            Expression::Binary {
                op: naga::BinaryOperator::Add,
                left: old,
                right: one,
            },
            s,
        );
        out.push(Statement::Emit(exprs.range_from(start)), s);
        out.push(Statement::Store { pointer: g, value: new }, s);
    }

    /// Stores the probed value, from the store of `value` (of type `inner`) as `source`
    /// says, as its first four components as `f32`, and `ran = 1`.
    fn capture(
        &mut self,
        inner: &TypeInner,
        value: Handle<Expression>,
        source: Source,
        exprs: &mut naga::Arena<Expression>,
        out: &mut naga::Block,
    ) {
        let s = Span::UNDEFINED;
        let zero = exprs.append(Expression::Literal(Literal::F32(0.0)), s);
        let one = exprs.append(Expression::Literal(Literal::F32(1.0)), s);
        let gv = exprs.append(Expression::GlobalVariable(self.globals.value), s);
        let gr = exprs.append(Expression::GlobalVariable(self.globals.ran), s);
        let gc = exprs.append(Expression::GlobalVariable(self.globals.components), s);
        let start = exprs.len();
        let mut comps = Vec::new();
        let types = &self.shader.module.types;
        match (source, inner) {
            (Source::Column(k), &TypeInner::Matrix { rows, scalar, .. }) => {
                let column = exprs.append(Expression::AccessIndex { base: value, index: k }, s);
                let inner = TypeInner::Vector { size: rows, scalar };
                flatten(types, &inner, column, exprs, zero, one, &mut comps);
            }
            (Source::Parts(pointer, parts), _) => {
                let info = info_of(self.shader, self.which);
                let vector = pointee(&self.shader.module, info[pointer].ty.inner_with(types));
                if let Some(TypeInner::Vector { scalar, .. }) = vector {
                    let loaded = exprs.append(Expression::Load { pointer }, s);
                    for k in parts {
                        let c = exprs.append(Expression::AccessIndex { base: loaded, index: k }, s);
                        flatten(types, &TypeInner::Scalar(scalar), c, exprs, zero, one, &mut comps);
                    }
                }
            }
            _ => flatten(types, inner, value, exprs, zero, one, &mut comps),
        }
        let n = comps.len() as u32;
        self.found.push(n);
        while comps.len() < 4 {
            comps.push(zero);
        }
        let v = exprs.append(
            Expression::Compose {
                ty: self.globals.vec4f,
                components: comps,
            },
            s,
        );
        out.push(Statement::Emit(exprs.range_from(start)), s);
        out.push(Statement::Store { pointer: gv, value: v }, s);
        out.push(
            Statement::Store {
                pointer: gr,
                value: one,
            },
            s,
        );
        let nc = exprs.append(Expression::Literal(Literal::F32(n as f32)), s);
        out.push(Statement::Store { pointer: gc, value: nc }, s);
    }

    fn block(&mut self, block: naga::Block, exprs: &mut naga::Arena<Expression>) -> naga::Block {
        let mut out = naga::Block::with_capacity(block.len());
        for (statement, span) in block.span_into_iter() {
            match statement {
                Statement::Block(b) => {
                    let b = self.block(b, exprs);
                    out.push(Statement::Block(b), span);
                }
                Statement::If {
                    condition,
                    accept,
                    reject,
                } => {
                    if self.counted(span) {
                        self.increment(exprs, &mut out);
                    }
                    let accept = self.block(accept, exprs);
                    let reject = self.block(reject, exprs);
                    out.push(
                        Statement::If {
                            condition,
                            accept,
                            reject,
                        },
                        span,
                    );
                }
                Statement::Switch { selector, cases } => {
                    let cases = cases
                        .into_iter()
                        .map(|c| naga::SwitchCase {
                            body: self.block(c.body, exprs),
                            ..c
                        })
                        .collect();
                    out.push(Statement::Switch { selector, cases }, span);
                }
                Statement::Loop {
                    body,
                    continuing,
                    break_if,
                } => {
                    let mut first = naga::Block::new();
                    if self.counted(span) {
                        self.increment(exprs, &mut first);
                    }
                    first.extend_block(self.block(body, exprs));
                    let continuing = self.block(continuing, exprs);
                    out.push(
                        Statement::Loop {
                            body: first,
                            continuing,
                            break_if,
                        },
                        span,
                    );
                }
                Statement::Call { .. } | Statement::Kill => {
                    if self.counted(span) {
                        self.increment(exprs, &mut out);
                    }
                    out.push(statement, span);
                }
                Statement::Store { pointer, value } => {
                    out.push(statement, span);
                    if self.counted(span) {
                        self.increment(exprs, &mut out);
                    }
                    let original = self.original();
                    let info = info_of(self.shader, self.which);
                    let source = stored(&self.shader.module, original, info, pointer)
                        .and_then(|store| self.probed(span, &store));
                    if let Some(source) = source {
                        let inner = info[value].ty.inner_with(&self.shader.module.types).clone();
                        self.capture(&inner, value, source, exprs, &mut out);
                    }
                }
                other => out.push(other, span),
            }
        }
        out
    }
}

/// How many of a value of type `inner`'s components a view shows: its scalars, at most four.
fn count(types: &naga::UniqueArena<Type>, inner: &TypeInner) -> u32 {
    let n = match *inner {
        TypeInner::Scalar(_) => 1,
        TypeInner::Vector { size, .. } => size as u32,
        TypeInner::Matrix { columns, rows, .. } => columns as u32 * rows as u32,
        TypeInner::Array {
            base,
            size: naga::ArraySize::Constant(n),
            ..
        } => count(types, &types[base].inner).saturating_mul(n.get()),
        TypeInner::Struct { ref members, .. } => members
            .iter()
            .map(|m| count(types, &types[m.ty].inner))
            .fold(0u32, u32::saturating_add),
        _ => 0,
    };
    n.min(4)
}

/// The first four scalar components of `value` (of type `inner`) as `f32` expressions
/// (appended to `exprs`; bools as 0/1), in the order the interpreter lists a value's
/// components.
fn flatten(
    types: &naga::UniqueArena<Type>,
    inner: &TypeInner,
    value: Handle<Expression>,
    exprs: &mut naga::Arena<Expression>,
    zero: Handle<Expression>,
    one: Handle<Expression>,
    out: &mut Vec<Handle<Expression>>,
) {
    let s = Span::UNDEFINED;
    if out.len() >= 4 {
        return;
    }
    let part = |exprs: &mut naga::Arena<Expression>, index: u32, inner: &TypeInner, out: &mut Vec<_>| {
        let e = exprs.append(Expression::AccessIndex { base: value, index }, s);
        flatten(types, inner, e, exprs, zero, one, out);
    };
    match *inner {
        TypeInner::Scalar(scalar) => {
            let e = match scalar.kind {
                ScalarKind::Float if scalar.width == 4 => value,
                ScalarKind::Bool => exprs.append(
                    Expression::Select {
                        condition: value,
                        accept: one,
                        reject: zero,
                    },
                    s,
                ),
                _ => exprs.append(
                    Expression::As {
                        expr: value,
                        kind: ScalarKind::Float,
                        convert: Some(4),
                    },
                    s,
                ),
            };
            out.push(e);
        }
        TypeInner::Vector { size, scalar } => {
            for k in 0..size as u32 {
                part(exprs, k, &TypeInner::Scalar(scalar), out);
            }
        }
        TypeInner::Matrix { columns, rows, scalar } => {
            for k in 0..columns as u32 {
                part(exprs, k, &TypeInner::Vector { size: rows, scalar }, out);
            }
        }
        TypeInner::Array {
            base,
            size: naga::ArraySize::Constant(n),
            ..
        } => {
            let element = types[base].inner.clone();
            for k in 0..n.get().min(4) {
                part(exprs, k, &element, out);
            }
        }
        TypeInner::Struct { ref members, .. } => {
            for (k, m) in members.iter().enumerate() {
                let inner = types[m.ty].inner.clone();
                part(exprs, k as u32, &inner, out);
            }
        }
        _ => {}
    }
    out.truncate(4);
}

/// Where a probed value comes from at a store.
enum Source {
    /// The value stored.
    Stored,
    /// A column of the matrix stored.
    Column(u32),
    /// These components of the vector through this pointer, after the store.
    Parts(Handle<Expression>, Vec<u32>),
}

/// The target `site` names on its line among `shader`'s assignments: the one of its name (or
/// of its variable's, where that has one), the only one where no name is given.
pub fn chosen(shader: &CompiledShader, site: &Site) -> Option<Target> {
    let all = assignments(shader);
    let here: Vec<&Assignment> = all
        .iter()
        .filter(|a| a.file == site.file && a.line == site.line)
        .collect();
    let list = targets(&here);
    match &site.name {
        Some(n) => list
            .iter()
            .find(|t| t.name == *n)
            .or_else(|| list.iter().find(|t| t.named(n, &list)))
            .cloned(),
        None if list.len() == 1 => list.into_iter().next(),
        None => None,
    }
}

/// What [`rewrite`] did: the component counts of the probed assignments it found.
struct Rewritten {
    module: Module,
    globals: Globals,
    found: Vec<u32>,
}

/// `shader`'s module with its steps counted (`count`) and the assignments of `site` stored;
/// only the entry point of `stage` kept.
fn rewrite(shader: &CompiledShader, stage: naga::ShaderStage, site: Option<&Site>, count: bool) -> Option<Rewritten> {
    let mut module = shader.module.clone();
    let ep = module.entry_points.iter().position(|e| e.stage == stage)?;
    let globals = add_globals(&mut module);
    let mut found = Vec::new();
    let target = site.and_then(|site| chosen(shader, site));
    for which in functions(shader) {
        let original = function_of(&shader.module, which);
        let mut rw = Rewrite {
            shader,
            which,
            shown: shown(shader, original),
            site,
            target: target.as_ref(),
            count,
            globals,
            found: Vec::new(),
        };
        let function = function_mut(&mut module, which);
        let mut exprs = std::mem::take(&mut function.expressions);
        let body = std::mem::take(&mut function.body);
        let mut prologue = naga::Block::new();
        // Local initialisers: steps at the function's start, as the interpreter takes them.
        for (h, local) in original.local_variables.iter() {
            if local.init.is_none() {
                continue;
            }
            let span = original.local_variables.get_span(h);
            if rw.counted(span) {
                rw.increment(&mut exprs, &mut prologue);
            }
            let name = local.name.clone().unwrap_or_else(|| super::interp::TEMPORARY.into());
            let store = Stored {
                name: name.clone(),
                root: name,
                part: None,
            };
            if let Some(source) = rw.probed(span, &store) {
                let inner = shader.module.types[local.ty].inner.clone();
                let pointer = exprs.append(Expression::LocalVariable(h), Span::UNDEFINED);
                let start = exprs.len();
                let loaded = exprs.append(Expression::Load { pointer }, Span::UNDEFINED);
                prologue.push(Statement::Emit(exprs.range_from(start)), Span::UNDEFINED);
                rw.capture(&inner, loaded, source, &mut exprs, &mut prologue);
            }
        }
        let mut body = rw.block(body, &mut exprs);
        if !prologue.is_empty() {
            prologue.extend_block(body);
            body = prologue;
        }
        let function = function_mut(&mut module, which);
        function.expressions = exprs;
        function.body = body;
        found.extend(rw.found);
    }
    let keep = module.entry_points.swap_remove(ep);
    module.entry_points = vec![keep];
    Some(Rewritten { module, globals, found })
}

/// An entry-point result struct of `members` (name, type, binding), laid out.
fn io_struct(module: &mut Module, name: &str, members: Vec<Member>) -> Handle<Type> {
    let mut layouter = naga::proc::Layouter::default();
    let _ = layouter.update(module.to_ctx());
    let mut offset = 0u32;
    let mut out = Vec::new();
    let mut align = 1u32;
    for (n, ty, binding) in members {
        let l = layouter[ty];
        let a = l.alignment.round_up(1).max(1);
        align = align.max(a);
        offset = offset.div_ceil(a) * a;
        out.push(naga::StructMember {
            name: Some(n),
            ty,
            binding,
            offset,
        });
        offset += l.size;
    }
    let span = offset.div_ceil(align) * align;
    module.types.insert(
        Type {
            name: Some(name.into()),
            inner: TypeInner::Struct { members: out, span },
        },
        Span::UNDEFINED,
    )
}

fn location(location: u32, flat: bool) -> Binding {
    Binding::Location {
        location,
        interpolation: Some(if flat {
            naga::Interpolation::Flat
        } else {
            naga::Interpolation::Perspective
        }),
        sampling: Some(naga::Sampling::Center),
        blend_src: None,
        per_primitive: false,
    }
}

/// What a `return v` (`None`: a return without a value) becomes: a block ending in a return.
type Returned<'a> = dyn Fn(Option<Handle<Expression>>, &mut naga::Arena<Expression>) -> naga::Block + 'a;

/// An entry-point output: its name, type and binding.
type Member = (String, Handle<Type>, Option<Binding>);

/// Replaces every `return v` of `block` by what `returned(v)` builds (a block ending in a
/// return).
fn returns(block: naga::Block, exprs: &mut naga::Arena<Expression>, returned: &Returned) -> naga::Block {
    let mut out = naga::Block::with_capacity(block.len());
    for (statement, span) in block.span_into_iter() {
        let s = match statement {
            Statement::Return { value } => Statement::Block(returned(value, exprs)),
            Statement::Block(b) => Statement::Block(returns(b, exprs, returned)),
            Statement::If {
                condition,
                accept,
                reject,
            } => Statement::If {
                condition,
                accept: returns(accept, exprs, returned),
                reject: returns(reject, exprs, returned),
            },
            Statement::Switch { selector, cases } => Statement::Switch {
                selector,
                cases: cases
                    .into_iter()
                    .map(|c| naga::SwitchCase {
                        body: returns(c.body, exprs, returned),
                        ..c
                    })
                    .collect(),
            },
            Statement::Loop {
                body,
                continuing,
                break_if,
            } => Statement::Loop {
                body: returns(body, exprs, returned),
                continuing: returns(continuing, exprs, returned),
                break_if,
            },
            other => other,
        };
        out.push(s, span);
    }
    out
}

/// The builtin outputs of an entry point's result (a fragment shader's depth): index in the
/// result struct (`None`: the result itself), type and binding.
fn builtins(module: &Module, result: Option<&naga::FunctionResult>) -> Vec<(Option<u32>, Handle<Type>, Binding)> {
    let Some(result) = result else { return Vec::new() };
    match (&result.binding, &module.types[result.ty].inner) {
        (Some(b @ Binding::BuiltIn(_)), _) => vec![(None, result.ty, b.clone())],
        (None, TypeInner::Struct { members, .. }) => members
            .iter()
            .enumerate()
            .filter_map(|(k, m)| match &m.binding {
                Some(b @ Binding::BuiltIn(_)) => Some((Some(k as u32), m.ty, b.clone())),
                _ => None,
            })
            .collect(),
        _ => Vec::new(),
    }
}

/// The locations an entry point's arguments or result use.
fn locations(module: &Module, function: &Function, result: bool) -> Vec<u32> {
    let mut out = Vec::new();
    let mut take = |ty: Handle<Type>, binding: &Option<Binding>| match (binding, &module.types[ty].inner) {
        (Some(Binding::Location { location, .. }), _) => out.push(*location),
        (None, TypeInner::Struct { members, .. }) => {
            for m in members {
                if let Some(Binding::Location { location, .. }) = &m.binding {
                    out.push(*location);
                }
            }
        }
        _ => {}
    };
    if result {
        if let Some(r) = &function.result {
            take(r.ty, &r.binding);
        }
    } else {
        for a in &function.arguments {
            take(a.ty, &a.binding);
        }
    }
    out
}

/// The first location after those `vertex`'s outputs and `fragment`'s inputs use: where a
/// vertex-shader view's varyings go.
pub fn free_location(vertex: &CompiledShader, fragment: &CompiledShader) -> u32 {
    fn stage_ep(s: &CompiledShader, stage: naga::ShaderStage) -> Option<&naga::EntryPoint> {
        s.module.entry_points.iter().find(|e| e.stage == stage)
    }
    let mut used = Vec::new();
    if let Some(ep) = stage_ep(vertex, naga::ShaderStage::Vertex) {
        used.extend(locations(&vertex.module, &ep.function, true));
    }
    if let Some(ep) = stage_ep(fragment, naga::ShaderStage::Fragment) {
        used.extend(locations(&fragment.module, &ep.function, false));
    }
    used.into_iter().max().map_or(0, |m| m + 1)
}

/// Puts `returned`'s block in place of every `return` of the module's entry point, and also
/// at the end of its body where `falls_off` (an entry point that ends without a `return`);
/// then validates the module.
fn end_with(module: &mut Module, returned: &Returned, falls_off: bool) -> Result<(), String> {
    let function = &mut module.entry_points[0].function;
    let mut exprs = std::mem::take(&mut function.expressions);
    let body = std::mem::take(&mut function.body);
    let mut body = returns(body, &mut exprs, returned);
    if falls_off {
        body.push(Statement::Block(returned(None, &mut exprs)), Span::UNDEFINED);
    }
    function.expressions = exprs;
    function.body = body;
    validate(module)
}

fn validate(module: &Module) -> Result<(), String> {
    let mut validator =
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::all());
    validator
        .validate(module)
        .map(|_| ())
        .map_err(|e| format!("the instrumented shader does not validate: {}", e.emit_to_string("")))
}

/// The bit of a view's info word saying the line ran; the component count sits in the three
/// bits above it and the step count in the bits above those ([`COST_SHIFT`]).
pub const RAN_BIT: u32 = 1;
/// Where the step count starts in a view's info word.
pub const COST_SHIFT: u32 = 4;
/// The largest step count an info word holds (more reads as this).
pub const COST_MAX: u32 = u32::MAX >> COST_SHIFT;

/// `fragment`'s module rewritten to count its steps and return the view's outputs instead of
/// its colours: with `value`, at location 0 the value of `site`'s assignment as `vec4<f32>` (or,
/// with `varying = Some((l, n))`, the value of `n` components arriving at location `l`, and
/// whether it ran at `l + 1`, from a vertex shader rewritten by [`vertex`]); then, at the next
/// location, the info word `steps << COST_SHIFT | components << 1 | ran` as `u32`. Its depth
/// output is kept. Also the component counts of the probed assignments found.
pub fn fragment(
    fragment: &CompiledShader,
    site: Option<&Site>,
    varying: Option<(u32, u32)>,
    value: bool,
) -> Result<(Module, Vec<u32>), String> {
    let Rewritten {
        mut module,
        globals,
        found,
    } = rewrite(fragment, naga::ShaderStage::Fragment, site, true)
        .ok_or_else(|| format!("{} has no fragment entry point", fragment.path))?;
    let kept = builtins(&module, module.entry_points[0].function.result.as_ref());
    let vec4f = globals.vec4f;
    let f32t = scalar_type(&mut module, naga::Scalar::F32);
    let u32t = scalar_type(&mut module, naga::Scalar::U32);
    let output = |l: u32| Binding::Location {
        location: l,
        interpolation: None,
        sampling: None,
        blend_src: None,
        per_primitive: false,
    };
    let mut members = Vec::new();
    if value {
        members.push(("value".to_owned(), vec4f, Some(output(0))));
    }
    members.push(("info".to_owned(), u32t, Some(output(u32::from(value)))));
    for (k, (_, ty, b)) in kept.iter().enumerate() {
        members.push((format!("builtin{k}"), *ty, Some(b.clone())));
    }
    let out_ty = io_struct(&mut module, "ShaderlabViewOutput", members);
    let function = &mut module.entry_points[0].function;
    let had_result = function.result.is_some();
    let (value_arg, ran_arg) = match varying {
        Some((l, _)) => {
            function.arguments.push(naga::FunctionArgument {
                name: Some("shaderlab_view_value".into()),
                ty: vec4f,
                binding: Some(location(l, false)),
            });
            function.arguments.push(naga::FunctionArgument {
                name: Some("shaderlab_view_ran".into()),
                ty: f32t,
                binding: Some(location(l + 1, false)),
            });
            let n = function.arguments.len() as u32;
            (Some(n - 2), Some(n - 1))
        }
        None => (None, None),
    };
    let vertex_components = varying.map(|(_, c)| c);
    function.result = Some(naga::FunctionResult {
        ty: out_ty,
        binding: None,
    });
    let returned = |v: Option<Handle<Expression>>, exprs: &mut naga::Arena<Expression>| {
        let s = Span::UNDEFINED;
        let lit = |exprs: &mut naga::Arena<Expression>, l| exprs.append(Expression::Literal(l), s);
        let gv = exprs.append(Expression::GlobalVariable(globals.value), s);
        let gr = exprs.append(Expression::GlobalVariable(globals.ran), s);
        let gc = exprs.append(Expression::GlobalVariable(globals.components), s);
        let gn = exprs.append(Expression::GlobalVariable(globals.cost), s);
        // A vertex line's `ran` arrives interpolated: it ran where it ran at every corner.
        let threshold = lit(exprs, Literal::F32(if varying.is_some() { 0.999 } else { 0.5 }));
        let vc = lit(exprs, Literal::U32(vertex_components.unwrap_or(0)));
        let one = lit(exprs, Literal::U32(RAN_BIT));
        let zero = lit(exprs, Literal::U32(0));
        let most = lit(exprs, Literal::U32(COST_MAX));
        let shift = lit(exprs, Literal::U32(COST_SHIFT));
        let va = value_arg.map(|a| exprs.append(Expression::FunctionArgument(a), s));
        let ra = ran_arg.map(|a| exprs.append(Expression::FunctionArgument(a), s));
        let start = exprs.len();
        let mut add = |e: Expression| exprs.append(e, s);
        let bin = |op, left, right| Expression::Binary { op, left, right };
        let probed = va.unwrap_or_else(|| add(Expression::Load { pointer: gv }));
        let ran = ra.unwrap_or_else(|| add(Expression::Load { pointer: gr }));
        let ran = add(bin(naga::BinaryOperator::GreaterEqual, ran, threshold));
        let ran = add(Expression::Select {
            condition: ran,
            accept: one,
            reject: zero,
        });
        let components = if varying.is_some() {
            vc
        } else {
            let c = add(Expression::Load { pointer: gc });
            add(Expression::As {
                expr: c,
                kind: ScalarKind::Uint,
                convert: Some(4),
            })
        };
        let cost = add(Expression::Load { pointer: gn });
        let cost = add(Expression::Math {
            fun: naga::MathFunction::Min,
            arg: cost,
            arg1: Some(most),
            arg2: None,
            arg3: None,
        });
        let cost = add(bin(naga::BinaryOperator::ShiftLeft, cost, shift));
        let components = add(bin(naga::BinaryOperator::ShiftLeft, components, one));
        let info = add(bin(naga::BinaryOperator::InclusiveOr, cost, components));
        let info = add(bin(naga::BinaryOperator::InclusiveOr, info, ran));
        let mut parts = if value { vec![probed, info] } else { vec![info] };
        for (k, _, _) in &kept {
            match (k, v) {
                (Some(k), Some(v)) => parts.push(add(Expression::AccessIndex { base: v, index: *k })),
                (None, Some(v)) => parts.push(v),
                _ => {}
            }
        }
        let out = add(Expression::Compose {
            ty: out_ty,
            components: parts,
        });
        let mut block = naga::Block::new();
        block.push(Statement::Emit(exprs.range_from(start)), s);
        block.push(Statement::Return { value: Some(out) }, s);
        block
    };
    // A shader without outputs ends without a `return`.
    end_with(&mut module, &returned, !had_result)?;
    Ok((module, found))
}

/// `vertex`'s module rewritten to pass the value of `site`'s assignment (its first four
/// components as `f32`) and whether it ran to the fragment shader as varyings at locations
/// `at` and `at + 1`. Also the component counts of the probed assignments found.
pub fn vertex(vertex: &CompiledShader, site: Option<&Site>, at: u32) -> Result<(Module, Vec<u32>), String> {
    let Rewritten {
        mut module,
        globals,
        found,
    } = rewrite(vertex, naga::ShaderStage::Vertex, site, false)
        .ok_or_else(|| format!("{} has no vertex entry point", vertex.path))?;
    let vec4f = globals.vec4f;
    let f32t = scalar_type(&mut module, naga::Scalar::F32);
    let function = &module.entry_points[0].function;
    let result = function
        .result
        .clone()
        .ok_or_else(|| format!("{}'s entry point returns nothing", vertex.path))?;
    // The original outputs, each as a member: from the struct, or the result itself.
    let (members, whole): (Vec<Member>, bool) = match (&result.binding, &module.types[result.ty].inner) {
        (None, TypeInner::Struct { members, .. }) => (
            members
                .iter()
                .enumerate()
                .map(|(k, m)| {
                    (
                        m.name.clone().unwrap_or_else(|| format!("member{k}")),
                        m.ty,
                        m.binding.clone(),
                    )
                })
                .collect(),
            false,
        ),
        (b, _) => (vec![("position".to_owned(), result.ty, b.clone())], true),
    };
    let original = members.len() as u32;
    let mut all = members;
    all.push(("shaderlab_view_value".into(), vec4f, Some(location(at, false))));
    all.push(("shaderlab_view_ran".into(), f32t, Some(location(at + 1, false))));
    let out_ty = io_struct(&mut module, "ShaderlabViewVertexOutput", all);
    let function = &mut module.entry_points[0].function;
    function.result = Some(naga::FunctionResult {
        ty: out_ty,
        binding: None,
    });
    let returned = |v: Option<Handle<Expression>>, exprs: &mut naga::Arena<Expression>| {
        let s = Span::UNDEFINED;
        let gv = exprs.append(Expression::GlobalVariable(globals.value), s);
        let gr = exprs.append(Expression::GlobalVariable(globals.ran), s);
        let start = exprs.len();
        let mut parts = Vec::new();
        if let Some(v) = v {
            if whole {
                parts.push(v);
            } else {
                for k in 0..original {
                    parts.push(exprs.append(Expression::AccessIndex { base: v, index: k }, s));
                }
            }
        }
        parts.push(exprs.append(Expression::Load { pointer: gv }, s));
        parts.push(exprs.append(Expression::Load { pointer: gr }, s));
        let out = exprs.append(
            Expression::Compose {
                ty: out_ty,
                components: parts,
            },
            s,
        );
        let mut block = naga::Block::new();
        block.push(Statement::Emit(exprs.range_from(start)), s);
        block.push(Statement::Return { value: Some(out) }, s);
        block
    };
    end_with(&mut module, &returned, false)?;
    Ok((module, found))
}
