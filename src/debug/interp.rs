//! An interpreter of naga's IR: the module a pipeline was built from, run on the CPU for a
//! group of lanes in lockstep — the four pixels of a 2×2 quad, so that `dFdx`, `dFdy`, `fwidth`
//! and a texture's implicit level of detail are computed from the neighbours as the GPU does,
//! or every vertex of a mesh at once.
//!
//! Written here because no kept crate does it: naga itself validates and translates but does
//! not execute, and `naga-rust-back` compiles WGSL to Rust ahead of time, without textures or
//! derivatives, which a debugger needs at run time on any module a user edits.
//!
//! Lanes follow the GPU's SIMD model: expressions are computed for every lane (a lane switched
//! off by a branch keeps computing, as a helper invocation does, so its neighbours' derivatives
//! exist), while stores, returns, `discard` and the trace honour each lane's own control flow
//! (an active mask per statement). Loops end where llvmpipe's loop limiter ends them
//! ([`LOOP_PASSES`]), and a step budget bounds the rest of the work, so a loop too heavy to
//! follow is an error at its line instead of a hang. An operation the interpreter does not
//! implement is an error naming it, never a silently wrong value.

// Lanes are indexed across several masks and values at once.
#![allow(clippy::needless_range_loop)]

use std::rc::Rc;

use naga::{BinaryOperator as B, Expression as E, Handle, Module, Span, Statement as S, TypeInner};

use super::error::Failure;
use super::math::nan_clamp;
use super::value::{self, Bits, Comp, Kind, Offset, Ptr, Root, Val};

/// What a lookup's level of detail is, per lane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Lod {
    /// From the coordinate's derivatives across the quad, with a bias (0 for `texture`).
    Implicit {
        /// d/dx and d/dy of the coordinate from the quad's top-left pixel (one per quad).
        coarse: ([f32; 3], [f32; 3]),
        /// d/dx and d/dy of the coordinate at this pixel (its row's and column's).
        fine: ([f32; 3], [f32; 3]),
        /// `texture(s, uv, bias)`'s bias.
        bias: f32,
    },
    /// An explicit level (`textureLod`; 0 for a lookup outside a fragment shader).
    Level(f32),
}

/// What a shader reads from outside itself: textures through samplers.
pub trait Host {
    /// The texture `image` read through `sampler` at `coord` (2 or 3 of its components
    /// used), as the GPU filters it.
    fn sample(
        &self,
        image: Handle<naga::GlobalVariable>,
        sampler: Handle<naga::GlobalVariable>,
        coord: [f32; 3],
        lod: Lod,
    ) -> Result<[f32; 4], String>;
    /// Texel `coord` of level `level` of `image` (`texelFetch`).
    fn fetch(&self, image: Handle<naga::GlobalVariable>, coord: [i32; 3], level: i32) -> Result<[f32; 4], String>;
    /// The size of level `level` of `image` (`textureSize`).
    fn size(&self, image: Handle<naga::GlobalVariable>, level: i32) -> Result<[u32; 2], String>;
    /// The bytes of the uniform buffer bound to `global`, which a uniform block is then read
    /// from as the GPU addresses it; `None` reads the block from the run's `uniforms`.
    fn buffer(&self, global: Handle<naga::GlobalVariable>) -> Option<std::sync::Arc<Vec<u8>>> {
        let _ = global;
        None
    }
}

/// What a step of the trace is.
#[derive(Clone, Debug, PartialEq)]
pub enum StepKind {
    /// A variable (or part of one) was assigned.
    Assign(String),
    /// An `if` chose: the value is 1 for its first branch, 0 for `else`.
    Branch,
    /// A loop began an iteration: the value is its number, from 0.
    Iteration,
    /// A function was called (its name).
    Call(String),
    /// `discard`.
    Discard,
}

/// One step of the trace: where, what, and the value for each traced lane (`None` where that
/// lane did not take the step).
#[derive(Clone, Debug)]
pub struct Step {
    /// The statement's span in the module's source.
    pub span: Span,
    /// The function it ran in.
    pub function: Option<String>,
    /// What happened.
    pub kind: StepKind,
    /// The kinds of the value's components.
    pub kinds: Vec<Kind>,
    /// Per traced lane, the value's components (numbers; bools as 0/1): at most
    /// [`MAX_COMPONENTS`] of them.
    pub values: Vec<Option<Vec<f64>>>,
    /// The value's components past those kept (an array's elements after its first ones).
    pub more: usize,
}

/// What a run recorded for its traced lanes: the steps kept, in order, and the steps left out
/// between the first [`HEAD_STEPS`] and the last [`TAIL_STEPS`], counted by statement.
#[derive(Clone, Debug, Default)]
pub struct Trace {
    /// The steps kept: the first ones, then the last ones.
    pub steps: Vec<Step>,
    /// Steps left out, by the span of the statement that took them: how many (one per traced
    /// lane that took it).
    pub dropped: Vec<(Span, usize)>,
}

impl Trace {
    /// How many steps were left out (one per traced lane).
    pub fn dropped_total(&self) -> usize {
        self.dropped.iter().map(|(_, n)| n).sum()
    }
}

type Res<T> = std::result::Result<T, Failure>;

fn fail<T>(span: Span, message: impl Into<String>) -> Res<T> {
    Err(Failure {
        message: message.into(),
        span,
    })
}

/// How much work a run may do: lane-evaluations of expressions (one per lane an expression is
/// computed for, one for a value shared by all lanes).
pub const DEFAULT_BUDGET: u64 = 10_000_000;

/// The name shown for a variable the compiler made (a `?:`'s result, a copy).
pub const TEMPORARY: &str = "(temporary)";

/// The budget per lane of a run over many lanes (a generous vertex shader's evaluations).
pub const PER_LANE_BUDGET: u64 = 2_000;

/// The steps a trace keeps from its start, counted per traced lane (a vertex step at three
/// corners counts three). With [`TAIL_STEPS`] this bounds what a trace holds and writes, however
/// long the shader runs: a long loop keeps its first iterations and what the shader did last.
pub const HEAD_STEPS: usize = 3_000;

/// The steps a trace keeps from its end, counted as [`HEAD_STEPS`]; those between the two are
/// counted by line, not kept.
pub const TAIL_STEPS: usize = 1_000;

/// The components of one value a step keeps: a `mat4` whole, an array's first 16 elements of
/// `float` (the rest counted in [`Step::more`]).
pub const MAX_COMPONENTS: usize = 16;

/// The loop passes llvmpipe runs in one shader invocation, all loops together, before it ends
/// each loop at its next pass's end (`LP_MAX_TGSI_LOOP_ITERATIONS`, a counter set once per
/// invocation and decremented at the end of every pass of every loop).
pub const LOOP_PASSES: i64 = 65_535;

/// A function being run: its locals and the values of its expressions.
struct Frame<'m> {
    function: &'m naga::Function,
    info: &'m naga::valid::FunctionInfo,
    locals: Vec<Vec<Comp>>,
    exprs: Vec<Option<Rc<Val>>>,
    args: Vec<Val>,
    /// Lanes that returned, and what they returned.
    returned: Vec<bool>,
    result: Option<Vec<Comp>>,
}

/// Where a `break` goes: out of the innermost loop or switch; lanes that broke are collected
/// here until the construct ends.
struct Breakable {
    broke: Vec<bool>,
    continued: Vec<bool>,
    is_loop: bool,
}

/// A run of one entry point over a group of lanes.
pub struct Run<'m> {
    module: &'m Module,
    info: &'m naga::valid::ModuleInfo,
    lanes: usize,
    /// The lanes are a 2×2 quad (0: top left, 1: top right, 2: bottom left, 3: bottom right).
    quad: bool,
    host: &'m dyn Host,
    globals: Vec<Option<Vec<Comp>>>,
    /// The bound bytes of each uniform block the host has them for.
    buffers: Vec<Option<std::sync::Arc<Vec<u8>>>>,
    frames: Vec<Frame<'m>>,
    breakables: Vec<Breakable>,
    /// Lanes that executed `discard`.
    pub killed: Vec<bool>,
    /// The span of the statement running (for an expression naga gave no span).
    at: Span,
    /// Work done so far and the most allowed.
    work: u64,
    budget: u64,
    /// The lanes whose steps are recorded.
    traced: Vec<usize>,
    /// Loop passes each lane has left before llvmpipe's limiter ends its loops
    /// ([`LOOP_PASSES`]): shared by a quad (llvmpipe counts passes of the SIMD group, which
    /// runs both sides of every branch, a loop no lane enters for one pass), one per lane
    /// otherwise (each vertex taken as a group of its own).
    limiter: Vec<i64>,
    /// The loops each function holds, nested ones and those of the functions it calls.
    loops_in: std::cell::RefCell<Vec<Option<i64>>>,
    /// Where the run met a value GLSL leaves undefined, or a loop the GPU's limiter ended, and
    /// what it gave there (once each).
    pub undefined: Vec<(Span, String)>,
    /// The first steps (up to [`HEAD_STEPS`] lane-steps), then the last ones (up to
    /// [`TAIL_STEPS`]), and the lane-steps each holds.
    head: Vec<Step>,
    tail: std::collections::VecDeque<Step>,
    head_lanes: usize,
    tail_lanes: usize,
    /// Lane-steps left out between the two, by statement.
    dropped: Vec<(Span, usize)>,
}

fn lanes_of(mask: &[bool]) -> bool {
    mask.iter().any(|&m| m)
}

impl<'m> Run<'m> {
    /// A run of `module` over `lanes` lanes (a quad when `quad`), recording the steps of the
    /// `traced` lanes. Uniform globals take their values from `uniforms` (by global handle);
    /// private ones start at their initialiser or zero.
    pub fn new(
        module: &'m Module,
        info: &'m naga::valid::ModuleInfo,
        lanes: usize,
        quad: bool,
        host: &'m dyn Host,
        uniforms: &[(Handle<naga::GlobalVariable>, Vec<Comp>)],
        traced: Vec<usize>,
    ) -> Res<Run<'m>> {
        let mut globals = Vec::with_capacity(module.global_variables.len());
        for (h, var) in module.global_variables.iter() {
            let inner = &module.types[var.ty].inner;
            let value = match var.space {
                naga::AddressSpace::Handle => None,
                _ => {
                    if let Some((_, v)) = uniforms.iter().find(|(g, _)| *g == h) {
                        Some(v.clone())
                    } else if let Some(init) = var.init {
                        Some(const_eval(module, init)?)
                    } else {
                        Some(value::zero(module, inner).ok_or_else(|| Failure {
                            message: format!(
                                "the global `{}` has a type the debugger does not hold",
                                var.name.as_deref().unwrap_or("?")
                            ),
                            span: module.global_variables.get_span(h),
                        })?)
                    }
                }
            };
            globals.push(value);
        }
        let buffers = module
            .global_variables
            .iter()
            .map(|(h, var)| {
                (var.space == naga::AddressSpace::Uniform)
                    .then(|| host.buffer(h))
                    .flatten()
            })
            .collect();
        Ok(Run {
            module,
            info,
            lanes,
            quad,
            host,
            globals,
            buffers,
            frames: Vec::new(),
            breakables: Vec::new(),
            killed: vec![false; lanes],
            at: Span::UNDEFINED,
            work: 0,
            // A vertex shader over a whole mesh does work in proportion to its vertices.
            budget: DEFAULT_BUDGET.max(lanes as u64 * PER_LANE_BUDGET),
            traced,
            limiter: vec![LOOP_PASSES; lanes],
            loops_in: std::cell::RefCell::new(vec![None; module.functions.len()]),
            undefined: Vec::new(),
            head: Vec::new(),
            tail: std::collections::VecDeque::new(),
            head_lanes: 0,
            tail_lanes: 0,
            dropped: Vec::new(),
        })
    }

    /// The offsets of an element: `at(offset, index)` for one offset and index, else per lane.
    fn indexed(&self, offset: &Offset, index: &Bits, at: impl Fn(usize, u32) -> usize) -> Offset {
        match (offset, index) {
            (Offset::Fixed(o), Bits::One(i)) => Offset::Fixed(at(*o, *i)),
            (offset, bits) => Offset::Each(
                (0..self.lanes)
                    .map(|lane| {
                        let o = match offset {
                            Offset::Fixed(o) => *o,
                            Offset::Each(v) => v[lane],
                        };
                        at(o, bits.at(lane))
                    })
                    .collect(),
            ),
        }
    }

    /// With another budget of work.
    pub fn budget(mut self, budget: u64) -> Self {
        self.budget = budget;
        self
    }

    /// Runs entry point `index` with `args` (one value per argument, components per lane) and
    /// returns its result's components.
    pub fn entry(&mut self, index: usize, args: Vec<Vec<Comp>>) -> Res<Vec<Comp>> {
        let ep = &self.module.entry_points[index];
        let info = self.info.get_entry_point(index);
        let args = args.into_iter().map(Val::Data).collect();
        let mask = vec![true; self.lanes];
        self.call(&ep.function, info, args, &mask, Span::UNDEFINED)
    }

    fn call(
        &mut self,
        function: &'m naga::Function,
        info: &'m naga::valid::FunctionInfo,
        args: Vec<Val>,
        mask: &[bool],
        span: Span,
    ) -> Res<Vec<Comp>> {
        if self.frames.len() > 64 {
            return fail(span, "calls nest deeper than 64");
        }
        let mut frame = Frame {
            function,
            info,
            locals: Vec::with_capacity(function.local_variables.len()),
            exprs: vec![None; function.expressions.len()],
            args,
            returned: vec![false; self.lanes],
            result: None,
        };
        for (h, local) in function.local_variables.iter() {
            let inner = &self.module.types[local.ty].inner;
            let zero = value::zero(self.module, inner).ok_or_else(|| Failure {
                message: format!(
                    "the local `{}` has a type the debugger does not hold",
                    local.name.as_deref().unwrap_or("?")
                ),
                span: function.local_variables.get_span(h),
            })?;
            frame.locals.push(zero);
        }
        self.frames.push(frame);
        // Initialisers are constant expressions of the function's arena.
        let depth = self.frames.len() - 1;
        for (h, local) in function.local_variables.iter() {
            if let Some(init) = local.init {
                let v = self.data(init)?;
                self.frames[depth].locals[h.index()] = v.clone();
                let name = local.name.clone().unwrap_or_else(|| TEMPORARY.into());
                self.step(function.local_variables.get_span(h), StepKind::Assign(name), &v, mask);
            }
        }
        let mut active = mask.to_vec();
        let result = self.block(&function.body, &mut active);
        let frame = self.frames.pop().expect("pushed above");
        result?;
        Ok(frame.result.unwrap_or_default())
    }

    fn frame(&self) -> &Frame<'m> {
        self.frames.last().expect("a frame runs")
    }

    fn charge(&mut self, n: usize, span: Span) -> Res<()> {
        self.work += n as u64;
        if self.work > self.budget {
            return fail(
                span,
                format!(
                    "stopped after {} evaluations (the debugger's budget): a loop that does not end, or one too long to follow",
                    self.budget
                ),
            );
        }
        Ok(())
    }

    /// Notes that the statement at `span` met what GLSL leaves undefined (or the GPU ends).
    fn undefined(&mut self, span: Span, what: impl Into<String>) {
        let what = what.into();
        let span = if span == Span::UNDEFINED { self.at } else { span };
        if self.undefined.len() < 32 && !self.undefined.iter().any(|(s, w)| *s == span && *w == what) {
            self.undefined.push((span, what));
        }
    }

    /// How many loops `block` holds, nested ones and those of the functions it calls: the
    /// passes llvmpipe runs through it when no lane of the group takes it (one each).
    fn loops(&self, block: &'m naga::Block) -> i64 {
        block.iter().map(|s| self.loops_of(s)).sum()
    }

    fn loops_of(&self, statement: &'m naga::Statement) -> i64 {
        match statement {
            S::Block(b) => self.loops(b),
            S::If { accept, reject, .. } => self.loops(accept) + self.loops(reject),
            S::Switch { cases, .. } => cases.iter().map(|c| self.loops(&c.body)).sum(),
            S::Loop { body, continuing, .. } => 1 + self.loops(body) + self.loops(continuing),
            S::Call { function, .. } => {
                if let Some(n) = self.loops_in.borrow()[function.index()] {
                    return n;
                }
                // GLSL has no recursion; a cycle counts as nothing rather than looping here.
                self.loops_in.borrow_mut()[function.index()] = Some(0);
                let n = self.loops(&self.module.functions[*function].body);
                self.loops_in.borrow_mut()[function.index()] = Some(n);
                n
            }
            _ => 0,
        }
    }

    /// Lanes `who` spend `passes` of llvmpipe's loop limiter (every lane, in a quad).
    fn spend(&mut self, passes: i64, who: &[bool]) {
        for i in 0..self.lanes {
            if self.quad || who[i] {
                self.limiter[i] -= passes;
            }
        }
    }

    fn step(&mut self, span: Span, kind: StepKind, comps: &[Comp], mask: &[bool]) {
        let lanes = self.traced.iter().filter(|&&l| mask[l]).count();
        if lanes == 0 {
            return;
        }
        let kept = &comps[..comps.len().min(MAX_COMPONENTS)];
        let values = self
            .traced
            .iter()
            .map(|&l| mask[l].then(|| value::numbers(kept, l)))
            .collect();
        let step = Step {
            span,
            function: self.frames.last().and_then(|f| f.function.name.clone()),
            kind,
            kinds: kept.iter().map(|c| c.kind).collect(),
            values,
            more: comps.len() - kept.len(),
        };
        if self.tail.is_empty() && self.head_lanes + lanes <= HEAD_STEPS {
            self.head_lanes += lanes;
            self.head.push(step);
            return;
        }
        self.tail_lanes += lanes;
        self.tail.push_back(step);
        while self.tail_lanes > TAIL_STEPS {
            let Some(old) = self.tail.pop_front() else { break };
            let n = old.values.iter().filter(|v| v.is_some()).count();
            self.tail_lanes -= n;
            match self.dropped.iter_mut().find(|(s, _)| *s == old.span) {
                Some((_, count)) => *count += n,
                None => self.dropped.push((old.span, n)),
            }
        }
    }

    /// The steps recorded so far (the run's trace is left empty).
    pub fn take_trace(&mut self) -> Trace {
        let mut steps = std::mem::take(&mut self.head);
        steps.extend(self.tail.drain(..));
        self.head_lanes = 0;
        self.tail_lanes = 0;
        Trace {
            steps,
            dropped: std::mem::take(&mut self.dropped),
        }
    }

    // ----- statements -----

    fn block(&mut self, block: &'m naga::Block, active: &mut Vec<bool>) -> Res<()> {
        let statements: Vec<(&naga::Statement, &Span)> = block.span_iter().collect();
        for (k, &(statement, span)) in statements.iter().enumerate() {
            if !lanes_of(active) {
                // The GPU runs the rest with no lane active: each loop in it for one pass.
                let rest: i64 = statements[k..].iter().map(|(s, _)| self.loops_of(s)).sum();
                if rest > 0 {
                    self.spend(rest, &vec![true; self.lanes]);
                }
                break;
            }
            // An `Emit` computes what the next statement uses: its line is that statement's.
            let mut span = *span;
            if span == Span::UNDEFINED && matches!(statement, S::Emit(_)) {
                if let Some((_, next)) = statements[k + 1..].iter().find(|(_, s)| **s != Span::UNDEFINED) {
                    span = **next;
                }
            }
            self.statement(statement, span, active)?;
        }
        Ok(())
    }

    fn statement(&mut self, statement: &'m naga::Statement, span: Span, active: &mut Vec<bool>) -> Res<()> {
        if span != Span::UNDEFINED {
            self.at = span;
        }
        match statement {
            S::Emit(range) => {
                for h in range.clone() {
                    let v = self.eval(h)?;
                    let depth = self.frames.len() - 1;
                    self.frames[depth].exprs[h.index()] = Some(Rc::new(v));
                }
            }
            S::Block(inner) => self.block(inner, active)?,
            S::If {
                condition,
                accept,
                reject,
            } => {
                let cond = self.data(*condition)?;
                let c = &cond[0];
                let mut yes: Vec<bool> = (0..self.lanes).map(|i| active[i] && c.bits.at(i) != 0).collect();
                let mut no: Vec<bool> = (0..self.lanes).map(|i| active[i] && c.bits.at(i) == 0).collect();
                self.step(span, StepKind::Branch, &cond, active);
                self.block(accept, &mut yes)?;
                self.block(reject, &mut no)?;
                for i in 0..self.lanes {
                    active[i] = yes[i] || no[i];
                }
            }
            S::Switch { selector, cases } => {
                let sel = self.data(*selector)?;
                let s = &sel[0];
                self.breakables.push(Breakable {
                    broke: vec![false; self.lanes],
                    continued: vec![false; self.lanes],
                    is_loop: false,
                });
                // A lane enters at the first case matching it (or default) and falls through.
                let mut running = vec![false; self.lanes];
                let matches = |case: &naga::SwitchCase, bits: u32| match case.value {
                    naga::SwitchValue::I32(v) => bits as i32 == v,
                    naga::SwitchValue::U32(v) => bits == v,
                    naga::SwitchValue::Default => false,
                };
                let matched_any: Vec<bool> = (0..self.lanes)
                    .map(|i| cases.iter().any(|c| matches(c, s.bits.at(i))))
                    .collect();
                let mut result = Ok(());
                for case in cases {
                    for i in 0..self.lanes {
                        let enters = match case.value {
                            naga::SwitchValue::Default => !matched_any[i],
                            _ => matches(case, s.bits.at(i)),
                        };
                        if active[i] && enters {
                            running[i] = true;
                        }
                    }
                    let mut here = running.clone();
                    result = self.block(&case.body, &mut here);
                    if result.is_err() {
                        break;
                    }
                    if case.fall_through {
                        running = here;
                    } else {
                        running = vec![false; self.lanes];
                    }
                }
                let b = self.breakables.pop().expect("pushed above");
                result?;
                // Lanes that continued inside the switch continue the enclosing loop.
                if let Some(outer) = self.breakables.iter_mut().rev().find(|b| b.is_loop) {
                    for i in 0..self.lanes {
                        if b.continued[i] {
                            outer.continued[i] = true;
                            active[i] = false;
                        }
                    }
                }
                for i in 0..self.lanes {
                    if self.frame().returned[i] || self.killed[i] {
                        active[i] = false;
                    }
                }
            }
            S::Loop {
                body,
                continuing,
                break_if,
            } => {
                let mut running = active.clone();
                self.breakables.push(Breakable {
                    broke: vec![false; self.lanes],
                    continued: vec![false; self.lanes],
                    is_loop: true,
                });
                // A lane of its own group that does not enter runs the loop for one pass.
                if !self.quad {
                    let outside: Vec<bool> = active.iter().map(|a| !a).collect();
                    let n = self.loops_of(statement);
                    self.spend(n, &outside);
                }
                let mut iteration = 0u64;
                let result = loop {
                    if !lanes_of(&running) {
                        break Ok(());
                    }
                    let in_pass = running.clone();
                    let it = [Comp::new(Kind::U32, Bits::One(iteration as u32))];
                    self.step(span, StepKind::Iteration, &it, &running);
                    if let Err(e) = self.charge(1, span) {
                        break Err(e);
                    }
                    let mut here = running.clone();
                    if let Err(e) = self.block(body, &mut here) {
                        break Err(e);
                    }
                    // Lanes that continued run the continuing block with the others.
                    let b = self.breakables.last_mut().expect("pushed above");
                    for i in 0..self.lanes {
                        if b.continued[i] {
                            here[i] = true;
                            b.continued[i] = false;
                        }
                    }
                    if let Err(e) = self.block(continuing, &mut here) {
                        break Err(e);
                    }
                    if let Some(cond) = break_if {
                        match self.data(*cond) {
                            Ok(c) => {
                                let b = self.breakables.last_mut().expect("pushed above");
                                for i in 0..self.lanes {
                                    if here[i] && c[0].bits.at(i) != 0 {
                                        here[i] = false;
                                        b.broke[i] = true;
                                    }
                                }
                            }
                            Err(e) => break Err(e),
                        }
                    }
                    // llvmpipe's limiter: a pass spent, the loop ended for a group out of them.
                    self.spend(1, &in_pass);
                    let stopped: Vec<bool> = (0..self.lanes).map(|i| here[i] && self.limiter[i] <= 0).collect();
                    if lanes_of(&stopped) {
                        let b = self.breakables.last_mut().expect("pushed above");
                        for i in 0..self.lanes {
                            if stopped[i] {
                                here[i] = false;
                                b.broke[i] = true;
                            }
                        }
                        self.undefined(
                            span,
                            format!(
                                "llvmpipe ends every loop once the shader's loops have made {LOOP_PASSES} passes in all (its loop limiter), and this one was ended there (a loop of a few iterations the driver unrolls makes no passes on the GPU but counts here)"
                            ),
                        );
                    }
                    running = here;
                    iteration += 1;
                };
                let b = self.breakables.pop().expect("pushed above");
                result?;
                for i in 0..self.lanes {
                    active[i] = active[i] && b.broke[i] && !self.frame().returned[i] && !self.killed[i];
                }
            }
            S::Break | S::Continue => {
                let breaks = matches!(statement, S::Break);
                let Some(b) = self.breakables.last_mut() else {
                    return fail(
                        span,
                        if breaks {
                            "`break` outside a loop or switch"
                        } else {
                            "`continue` outside a loop"
                        },
                    );
                };
                // The active lanes leave the block, marked as broken out or continuing.
                let marks = if breaks { &mut b.broke } else { &mut b.continued };
                for i in 0..self.lanes {
                    if active[i] {
                        marks[i] = true;
                        active[i] = false;
                    }
                }
            }
            S::Return { value } => {
                if let Some(v) = value {
                    let v = self.data(*v)?;
                    let depth = self.frames.len() - 1;
                    let frame = &mut self.frames[depth];
                    frame.result = Some(match frame.result.take() {
                        None => v,
                        Some(old) => old
                            .iter()
                            .zip(&v)
                            .map(|(o, n)| Comp::new(n.kind, o.bits.blend(&n.bits, active)))
                            .collect(),
                    });
                }
                let depth = self.frames.len() - 1;
                for i in 0..self.lanes {
                    if active[i] {
                        self.frames[depth].returned[i] = true;
                        active[i] = false;
                    }
                }
            }
            S::Kill => {
                self.step(span, StepKind::Discard, &[], active);
                for i in 0..self.lanes {
                    if active[i] {
                        self.killed[i] = true;
                        active[i] = false;
                    }
                }
            }
            S::Store { pointer, value } => {
                let Val::Ptr(ptr) = self.get(*pointer)?.as_ref().clone() else {
                    return fail(span, "a store through something that is not a pointer");
                };
                let v = self.data(*value)?;
                self.store(&ptr, &v, active, span)?;
                self.step(span, StepKind::Assign(ptr.name.clone()), &v, active);
            }
            S::Call {
                function,
                arguments,
                result,
            } => {
                let f = &self.module.functions[*function];
                let mut args = Vec::with_capacity(arguments.len());
                for a in arguments {
                    args.push(self.get(*a)?.as_ref().clone());
                }
                let name = f.name.clone().unwrap_or_else(|| "function".into());
                self.step(span, StepKind::Call(name), &[], active);
                let info = &self.info[*function];
                let r = self.call(f, info, args, active, span)?;
                if let Some(h) = result {
                    let depth = self.frames.len() - 1;
                    self.frames[depth].exprs[h.index()] = Some(Rc::new(Val::Data(r)));
                }
            }
            S::ControlBarrier(_) | S::MemoryBarrier(_) => {}
            other => {
                return fail(span, format!("the debugger does not run {}", statement_name(other)));
            }
        }
        Ok(())
    }

    fn store(&mut self, ptr: &Ptr, v: &[Comp], active: &[bool], span: Span) -> Res<()> {
        let storage = match ptr.root {
            Root::Local(depth, h) => &mut self.frames[depth].locals[h.index()],
            Root::Global(h) => match &mut self.globals[h.index()] {
                Some(s) => s,
                None => return fail(span, "a store to a texture or sampler"),
            },
            Root::Buffer(_) => return fail(span, "a store to a uniform"),
        };
        if v.len() != ptr.len {
            return fail(span, "a store of the wrong size");
        }
        match &ptr.offset {
            Offset::Fixed(o) => {
                for (k, c) in v.iter().enumerate() {
                    let Some(slot) = storage.get_mut(o + k) else {
                        return fail(span, "a store past the end of a variable");
                    };
                    slot.bits = slot.bits.blend(&c.bits, active);
                    slot.kind = c.kind;
                }
            }
            Offset::Each(offsets) => {
                for (lane, &o) in offsets.iter().enumerate() {
                    if !active[lane] {
                        continue;
                    }
                    for (k, c) in v.iter().enumerate() {
                        let Some(slot) = storage.get_mut(o + k) else {
                            return fail(span, "a store past the end of a variable");
                        };
                        let mut each: Vec<u32> = (0..self.lanes).map(|i| slot.bits.at(i)).collect();
                        each[lane] = c.bits.at(lane);
                        slot.bits = Bits::Each(each);
                    }
                }
            }
        }
        Ok(())
    }

    /// The value `ptr` points to, of type `ty`.
    fn load(&self, ptr: &Ptr, ty: Option<&TypeInner>, span: Span) -> Res<Vec<Comp>> {
        let storage = match ptr.root {
            Root::Local(depth, h) => &self.frames[depth].locals[h.index()],
            Root::Global(h) => match &self.globals[h.index()] {
                Some(s) => s,
                None => return fail(span, "a load from a texture or sampler"),
            },
            Root::Buffer(h) => {
                let (Some(bytes), Some(ty)) = (&self.buffers[h.index()], ty) else {
                    return fail(span, "a load from a uniform the debugger cannot read");
                };
                return self.load_bytes(bytes, ty, &ptr.offset, span);
            }
        };
        match &ptr.offset {
            Offset::Fixed(o) => storage
                .get(*o..*o + ptr.len)
                .map(<[Comp]>::to_vec)
                .ok_or_else(|| Failure {
                    message: "a load past the end of a variable".into(),
                    span,
                }),
            Offset::Each(offsets) => (0..ptr.len)
                .map(|k| {
                    let kind = storage.get(offsets[0] + k).map_or(Kind::F32, |c| c.kind);
                    let bits = offsets
                        .iter()
                        .enumerate()
                        .map(|(lane, &o)| storage.get(o + k).map_or(0, |c| c.bits.at(lane)))
                        .collect();
                    Ok(Comp::new(kind, Bits::Each(bits)))
                })
                .collect(),
        }
    }

    /// A value of type `ty` read from a uniform buffer's `bytes` at each lane's byte offset.
    fn load_bytes(&self, bytes: &[u8], ty: &TypeInner, offset: &Offset, span: Span) -> Res<Vec<Comp>> {
        let read = |at: usize| -> Res<Vec<Comp>> {
            let mut out = Vec::new();
            value::read_bytes(self.module, ty, bytes, at as u32, &mut out).ok_or_else(|| Failure {
                message: "a uniform of a type the debugger does not hold".into(),
                span,
            })?;
            Ok(out)
        };
        match offset {
            Offset::Fixed(at) => read(*at),
            Offset::Each(each) => {
                let lanes: Vec<Vec<Comp>> = each.iter().map(|&at| read(at)).collect::<Res<_>>()?;
                let first = lanes.first().cloned().unwrap_or_default();
                Ok((0..first.len())
                    .map(|k| {
                        Comp::new(
                            first[k].kind,
                            Bits::Each(lanes.iter().map(|l| l[k].bits.at(0)).collect()),
                        )
                    })
                    .collect())
            }
        }
    }

    // ----- expressions -----

    fn get(&mut self, h: Handle<naga::Expression>) -> Res<Rc<Val>> {
        if let Some(v) = &self.frame().exprs[h.index()] {
            return Ok(v.clone());
        }
        let v = Rc::new(self.eval(h)?);
        let depth = self.frames.len() - 1;
        self.frames[depth].exprs[h.index()] = Some(v.clone());
        Ok(v)
    }

    fn data(&mut self, h: Handle<naga::Expression>) -> Res<Vec<Comp>> {
        match self.get(h)?.as_ref() {
            Val::Data(d) => Ok(d.clone()),
            _ => fail(self.span(h), "a value was expected here"),
        }
    }

    fn span(&self, h: Handle<naga::Expression>) -> Span {
        self.frame().function.expressions.get_span(h)
    }

    fn ty(&self, h: Handle<naga::Expression>) -> &'m TypeInner {
        let info: &'m naga::valid::FunctionInfo = self.frame().info;
        info[h].ty.inner_with(&self.module.types)
    }

    fn eval(&mut self, h: Handle<naga::Expression>) -> Res<Val> {
        let function: &'m naga::Function = self.frame().function;
        let span = function.expressions.get_span(h);
        let expr = &function.expressions[h];
        let at = self.at;
        let v = self.eval_expr(h, expr, span).map_err(|mut f| {
            if f.span == Span::UNDEFINED {
                f.span = at;
            }
            f
        })?;
        if let Val::Data(d) = &v {
            let n = d.iter().map(|c| c.bits.len()).max().unwrap_or(1);
            self.charge(n, span)?;
        }
        Ok(v)
    }

    /// Evaluates `expr` (expression `h`): the match picks its family, each family has its own
    /// function.
    fn eval_expr(&mut self, h: Handle<naga::Expression>, expr: &'m naga::Expression, span: Span) -> Res<Val> {
        match expr {
            E::Literal(_)
            | E::Constant(_)
            | E::ZeroValue(_)
            | E::Compose { .. }
            | E::Splat { .. }
            | E::Swizzle { .. } => self.construct(expr, span),
            E::FunctionArgument(_) | E::GlobalVariable(_) | E::LocalVariable(_) | E::Load { .. } => {
                self.variable(expr, span)
            }
            E::AccessIndex { base, index } => self.access_index(*base, *index, span),
            E::Access { base, index } => self.access(*base, *index, span),
            E::Unary { .. } | E::Binary { .. } | E::Select { .. } | E::Relational { .. } | E::As { .. } => {
                self.arithmetic(expr, span)
            }
            E::Math {
                fun,
                arg,
                arg1,
                arg2,
                arg3: _,
            } => self.built_in(*fun, *arg, *arg1, *arg2, span),
            E::Derivative { .. } | E::ImageSample { .. } | E::ImageLoad { .. } | E::ImageQuery { .. } => {
                self.image(h, expr, span)
            }
            E::CallResult(_) => fail(span, "a call's result used before the call"),
            other => unsupported(other, span),
        }
    }

    /// Literals, constants and values built from others: `vec3(a, b, c)`, `vec4(x)`, `v.zyx`.
    fn construct(&mut self, expr: &'m naga::Expression, span: Span) -> Res<Val> {
        let module = self.module;
        Ok(match expr {
            E::Literal(l) => Val::Data(vec![literal(*l, span)?]),
            E::Constant(c) => Val::Data(const_eval(module, module.constants[*c].init)?),
            E::ZeroValue(ty) => Val::Data(value::zero(module, &module.types[*ty].inner).ok_or_else(|| Failure {
                message: "a zero value of a type the debugger does not hold".into(),
                span,
            })?),
            E::Compose { components, .. } => {
                let mut out = Vec::new();
                for c in components {
                    out.extend(self.data(*c)?);
                }
                Val::Data(out)
            }
            E::Splat { size, value } => {
                let v = self.data(*value)?;
                Val::Data(vec![v[0].clone(); *size as usize])
            }
            E::Swizzle { size, vector, pattern } => {
                let v = self.data(*vector)?;
                Val::Data(
                    pattern[..*size as usize]
                        .iter()
                        .map(|c| v[*c as usize].clone())
                        .collect(),
                )
            }
            other => return unsupported(other, span),
        })
    }

    /// A function's argument, a variable (a pointer to it, or the texture or sampler it is),
    /// and a load through a pointer.
    fn variable(&mut self, expr: &'m naga::Expression, span: Span) -> Res<Val> {
        let module = self.module;
        Ok(match expr {
            E::FunctionArgument(i) => self.frame().args[*i as usize].clone(),
            E::GlobalVariable(g) => {
                let var = &module.global_variables[*g];
                match &module.types[var.ty].inner {
                    TypeInner::Image { .. } => Val::Image(*g),
                    TypeInner::Sampler { .. } => Val::Sampler(*g),
                    inner => Val::Ptr(Ptr {
                        root: if self.buffers[g.index()].is_some() {
                            Root::Buffer(*g)
                        } else {
                            Root::Global(*g)
                        },
                        offset: Offset::Fixed(0),
                        len: value::count(module, inner),
                        name: var.name.clone().unwrap_or_else(|| format!("global{}", g.index())),
                    }),
                }
            }
            E::LocalVariable(l) => {
                let local = &self.frame().function.local_variables[*l];
                Val::Ptr(Ptr {
                    root: Root::Local(self.frames.len() - 1, *l),
                    offset: Offset::Fixed(0),
                    len: value::count(module, &module.types[local.ty].inner),
                    name: local.name.clone().unwrap_or_else(|| TEMPORARY.into()),
                })
            }
            E::Load { pointer } => {
                let p = self.get(*pointer)?;
                match p.as_ref() {
                    Val::Ptr(ptr) => {
                        let ty = pointee(module, self.ty(*pointer));
                        Val::Data(self.load(ptr, ty.as_ref(), span)?)
                    }
                    // Loading a texture or sampler handle yields itself.
                    other => other.clone(),
                }
            }
            other => return unsupported(other, span),
        })
    }

    /// `base.member` or `base[constant]`: a part of a value, or a pointer to a part.
    fn access_index(&mut self, base: Handle<naga::Expression>, index: u32, span: Span) -> Res<Val> {
        let module = self.module;
        let b = self.get(base)?;
        let base_ty = self.ty(base);
        Ok(match b.as_ref() {
            Val::Ptr(ptr) => {
                let pointee = pointee(module, base_ty).ok_or_else(|| Failure {
                    message: "an access through a pointer of unknown type".into(),
                    span,
                })?;
                let (mut at, len, _) = value::part(module, &pointee, index as usize).ok_or_else(|| Failure {
                    message: "an access the debugger cannot follow".into(),
                    span,
                })?;
                if let Root::Buffer(_) = ptr.root {
                    at = value::byte_part(module, &pointee, index)
                        .ok_or_else(|| Failure {
                            message: "an access the debugger cannot follow".into(),
                            span,
                        })?
                        .0 as usize;
                }
                let members = match &pointee {
                    TypeInner::Struct { members, .. } => Some(members.as_slice()),
                    _ => None,
                };
                Val::Ptr(Ptr {
                    root: ptr.root,
                    offset: match &ptr.offset {
                        Offset::Fixed(o) => Offset::Fixed(advance(ptr.root, *o, at)),
                        Offset::Each(v) => Offset::Each(v.iter().map(|&o| advance(ptr.root, o, at)).collect()),
                    },
                    len,
                    name: format!("{}{}", ptr.name, value::part_name(&pointee, index as usize, members)),
                })
            }
            Val::Data(d) => {
                let (at, len, _) = value::part(module, base_ty, index as usize).ok_or_else(|| Failure {
                    message: "an access the debugger cannot follow".into(),
                    span,
                })?;
                Val::Data(d[at..at + len].to_vec())
            }
            _ => return fail(span, "an access into a texture or sampler"),
        })
    }

    /// `base[index]` with an index computed per lane: an element of a value, or a pointer to
    /// one, restricted or wrapped as the GPU does.
    fn access(&mut self, base: Handle<naga::Expression>, index: Handle<naga::Expression>, span: Span) -> Res<Val> {
        let module = self.module;
        let b = self.get(base)?;
        let idx = self.data(index)?;
        let base_ty = self.ty(base);
        let idx = &idx[0];
        let signed = idx.kind == Kind::I32;
        // wgpu's Vulkan backend has naga restrict an index into a variable or a value
        // (`BoundsCheckPolicy::Restrict`): `min(index, n − 1)` compared as unsigned, so
        // a negative index reads the last element.
        let clamp = |bits: u32, n: usize| -> usize { (bits as usize).min(n.saturating_sub(1)) };
        let n = match b.as_ref() {
            Val::Ptr(_) => pointee(module, base_ty).as_ref().and_then(value::elements),
            _ => value::elements(base_ty),
        };
        if let Some(n) = n {
            if (0..idx.bits.len()).any(|l| idx.bits.at(l) as usize >= n) {
                self.undefined(
                    span,
                    "GLSL leaves an index out of range undefined (a variable's is restricted to its last element, a uniform block's reads the buffer's bytes there or zero past its end)",
                );
            }
        }
        Ok(match b.as_ref() {
            Val::Ptr(ptr) if matches!(ptr.root, Root::Buffer(_)) => {
                // Into a uniform buffer naga leaves the index as it is and the driver's
                // robust buffer access reads zero past the buffer's end (wgpu's
                // `buffer` policy is `Unchecked` where `robustBufferAccess2` is
                // supported, as on lavapipe): the address wraps at 32 bits.
                let pointee = pointee(module, base_ty).ok_or_else(|| Failure {
                    message: "an access through a pointer of unknown type".into(),
                    span,
                })?;
                let (stride, elem) = value::byte_part(module, &pointee, 1).ok_or_else(|| Failure {
                    message: "a dynamic index into something that is not an array, matrix or vector".into(),
                    span,
                })?;
                let at = |o: usize, i: u32| (o as u32).wrapping_add(i.wrapping_mul(stride)) as usize;
                let offset = self.indexed(&ptr.offset, &idx.bits, at);
                let name = match &idx.bits {
                    Bits::One(i) if signed => format!("{}[{}]", ptr.name, *i as i32),
                    Bits::One(i) => format!("{}[{i}]", ptr.name),
                    Bits::Each(_) => format!("{}[i]", ptr.name),
                };
                Val::Ptr(Ptr {
                    root: ptr.root,
                    offset,
                    len: value::count(module, &elem),
                    name,
                })
            }
            Val::Ptr(ptr) => {
                let pointee = pointee(module, base_ty).ok_or_else(|| Failure {
                    message: "an access through a pointer of unknown type".into(),
                    span,
                })?;
                let n = value::elements(&pointee).ok_or_else(|| Failure {
                    message: "a dynamic index into something that is not an array, matrix or vector".into(),
                    span,
                })?;
                let (_, len, _) = value::part(module, &pointee, 0).ok_or_else(|| Failure {
                    message: "an access the debugger cannot follow".into(),
                    span,
                })?;
                let offset = self.indexed(&ptr.offset, &idx.bits, |o, i| o + clamp(i, n) * len);
                let name = match &idx.bits {
                    Bits::One(i) => format!("{}[{}]", ptr.name, clamp(*i, n)),
                    Bits::Each(_) => format!("{}[i]", ptr.name),
                };
                Val::Ptr(Ptr {
                    root: ptr.root,
                    offset,
                    len,
                    name,
                })
            }
            Val::Data(d) => {
                let n = value::elements(base_ty).ok_or_else(|| Failure {
                    message: "a dynamic index into something that is not an array, matrix or vector".into(),
                    span,
                })?;
                let (_, len, _) = value::part(module, base_ty, 0).ok_or_else(|| Failure {
                    message: "an access the debugger cannot follow".into(),
                    span,
                })?;
                match &idx.bits {
                    Bits::One(i) => {
                        let at = clamp(*i, n) * len;
                        Val::Data(d[at..at + len].to_vec())
                    }
                    Bits::Each(_) => Val::Data(
                        (0..len)
                            .map(|k| {
                                let kind = d[k].kind;
                                let bits = (0..self.lanes)
                                    .map(|lane| d[clamp(idx.bits.at(lane), n) * len + k].bits.at(lane))
                                    .collect();
                                Comp::new(kind, Bits::Each(bits))
                            })
                            .collect(),
                    ),
                }
            }
            _ => return fail(span, "an index into a texture or sampler"),
        })
    }

    /// Operators, `?:`, the relational built-ins (`all`, `any`, `isnan`, `isinf`) and
    /// conversions, with what GLSL leaves undefined (a division by zero, a float out of an
    /// int's range) noted.
    fn arithmetic(&mut self, expr: &'m naga::Expression, span: Span) -> Res<Val> {
        Ok(match expr {
            E::Unary { op, expr } => {
                let v = self.data(*expr)?;
                Val::Data(
                    v.iter()
                        .map(|c| match (op, c.kind) {
                            (naga::UnaryOperator::Negate, Kind::F32) => {
                                Comp::new(c.kind, c.bits.map(|b| (-f32::from_bits(b)).to_bits()))
                            }
                            (naga::UnaryOperator::Negate, _) => {
                                Comp::new(c.kind, c.bits.map(|b| (b as i32).wrapping_neg() as u32))
                            }
                            (naga::UnaryOperator::LogicalNot, _) => {
                                Comp::new(c.kind, c.bits.map(|b| u32::from(b == 0)))
                            }
                            (naga::UnaryOperator::BitwiseNot, Kind::Bool) => {
                                Comp::new(c.kind, c.bits.map(|b| u32::from(b == 0)))
                            }
                            (naga::UnaryOperator::BitwiseNot, _) => Comp::new(c.kind, c.bits.map(|b| !b)),
                        })
                        .collect(),
                )
            }
            E::Binary { op, left, right } => {
                let a = self.data(*left)?;
                let b = self.data(*right)?;
                let (ta, tb) = (self.ty(*left), self.ty(*right));
                let by_zero = matches!(op, B::Divide | B::Modulo)
                    && b.iter().any(|c| {
                        let mask = if c.kind == Kind::F32 { 0x7fff_ffff } else { u32::MAX };
                        (0..c.bits.len()).any(|l| c.bits.at(l) & mask == 0)
                    });
                if by_zero {
                    self.undefined(span, "GLSL leaves a division by zero undefined (mod(x, 0) is one)");
                }
                Val::Data(binary(*op, &a, ta, &b, tb, span)?)
            }
            E::Select {
                condition,
                accept,
                reject,
            } => {
                let c = self.data(*condition)?;
                let a = self.data(*accept)?;
                let r = self.data(*reject)?;
                Val::Data(
                    a.iter()
                        .zip(&r)
                        .enumerate()
                        .map(|(k, (x, y))| {
                            let cond = if c.len() == 1 { &c[0] } else { &c[k] };
                            Comp::new(
                                x.kind,
                                cond.bits.zip3(&x.bits, &y.bits, |c, x, y| if c != 0 { x } else { y }),
                            )
                        })
                        .collect(),
                )
            }
            E::Relational { fun, argument } => {
                let v = self.data(*argument)?;
                use naga::RelationalFunction as R;
                Val::Data(match fun {
                    R::All | R::Any => {
                        let all = matches!(fun, R::All);
                        let mut acc = v[0].bits.clone();
                        for c in &v[1..] {
                            acc = acc.zip(&c.bits, |x, y| {
                                if all {
                                    u32::from(x != 0 && y != 0)
                                } else {
                                    u32::from(x != 0 || y != 0)
                                }
                            });
                        }
                        vec![Comp::new(Kind::Bool, acc)]
                    }
                    R::IsNan => v
                        .iter()
                        .map(|c| Comp::new(Kind::Bool, c.bits.map(|b| u32::from(f32::from_bits(b).is_nan()))))
                        .collect(),
                    R::IsInf => v
                        .iter()
                        .map(|c| Comp::new(Kind::Bool, c.bits.map(|b| u32::from(f32::from_bits(b).is_infinite()))))
                        .collect(),
                })
            }
            E::As { expr, kind, convert } => {
                let v = self.data(*expr)?;
                let out: Vec<Comp> = v
                    .iter()
                    .map(|c| cast(c, *kind, convert.is_some(), span))
                    .collect::<Res<_>>()?;
                if convert.is_some() && v.iter().any(|c| c.kind == Kind::F32) {
                    let to = match kind {
                        naga::ScalarKind::Sint => Some(("int", -2_147_483_648.0f64, 2_147_483_648.0)),
                        naga::ScalarKind::Uint => Some(("uint", -1.0, 4_294_967_296.0)),
                        _ => None,
                    };
                    if let Some((name, below, above)) = to {
                        let outside = v.iter().any(|c| {
                            (0..c.bits.len()).any(|l| {
                                let x = f64::from(c.f(l));
                                x.is_nan() || x <= below || x >= above
                            })
                        });
                        if outside {
                            self.undefined(
                                span,
                                format!("GLSL leaves {name}(x) undefined for NaN and for x beyond {name}'s range"),
                            );
                        }
                    }
                }
                Val::Data(out)
            }
            other => return unsupported(other, span),
        })
    }

    /// A built-in function of GLSL's (naga's `MathFunction`, run by [`super::math::math`]),
    /// with what GLSL leaves undefined on its arguments noted.
    fn built_in(
        &mut self,
        fun: naga::MathFunction,
        arg: Handle<naga::Expression>,
        arg1: Option<Handle<naga::Expression>>,
        arg2: Option<Handle<naga::Expression>>,
        span: Span,
    ) -> Res<Val> {
        let a = self.data(arg)?;
        let b = arg1.map(|h| self.data(h)).transpose()?;
        let c = arg2.map(|h| self.data(h)).transpose()?;
        let ty = self.ty(arg);
        let mut undefined = Vec::new();
        let v = super::math::math(fun, &a, b.as_deref(), c.as_deref(), ty, span, &mut undefined)?;
        for what in undefined {
            self.undefined(span, format!("GLSL leaves {what} undefined"));
        }
        Ok(Val::Data(v))
    }

    /// Derivatives across the quad and the texture operations: lookups, `texelFetch` and
    /// `textureSize`.
    fn image(&mut self, h: Handle<naga::Expression>, expr: &'m naga::Expression, span: Span) -> Res<Val> {
        Ok(match expr {
            E::Derivative { axis, ctrl: _, expr } => {
                // llvmpipe computes `dFdx`, `dFdxFine` and `dFdxCoarse` alike: each pixel's
                // own row and column (GLSL lets a coarse derivative be the fine one).
                let v = self.data(*expr)?;
                Val::Data(v.iter().map(|c| self.derivative(c, *axis, false)).collect())
            }
            E::ImageSample {
                image,
                sampler,
                gather,
                coordinate,
                array_index,
                offset,
                level,
                depth_ref,
                clamp_to_edge: _,
            } => {
                if gather.is_some() {
                    return fail(span, "the debugger does not run textureGather");
                }
                if depth_ref.is_some() {
                    return fail(span, "the debugger does not run shadow (depth comparison) lookups");
                }
                if array_index.is_some() {
                    return fail(span, "the debugger does not run lookups into texture arrays");
                }
                if offset.is_some() {
                    return fail(span, "the debugger does not run lookups with a texel offset");
                }
                self.sample(*image, *sampler, *coordinate, level, span)?
            }
            E::ImageLoad {
                image,
                coordinate,
                array_index,
                sample,
                level,
            } => {
                if array_index.is_some() || sample.is_some() {
                    return fail(
                        span,
                        "the debugger does not run texelFetch on arrays or multisampled textures",
                    );
                }
                let Val::Image(img) = self.get(*image)?.as_ref().clone() else {
                    return fail(span, "a texelFetch whose texture the debugger cannot tell");
                };
                let coord = self.data(*coordinate)?;
                let level = level.map(|l| self.data(l)).transpose()?;
                let mut out: Vec<Vec<u32>> = (0..4).map(|_| Vec::with_capacity(self.lanes)).collect();
                for lane in 0..self.lanes {
                    let c = [0, 1, 2].map(|k| coord.get(k).map_or(0, |c| c.bits.at(lane) as i32));
                    let l = level.as_ref().map_or(0, |l| l[0].bits.at(lane) as i32);
                    let rgba = self.host.fetch(img, c, l).map_err(|m| Failure { message: m, span })?;
                    for k in 0..4 {
                        out[k].push(rgba[k].to_bits());
                    }
                }
                Val::Data(out.into_iter().map(|b| Comp::new(Kind::F32, Bits::Each(b))).collect())
            }
            E::ImageQuery { image, query } => {
                let Val::Image(img) = self.get(*image)?.as_ref().clone() else {
                    return fail(span, "a textureSize whose texture the debugger cannot tell");
                };
                match query {
                    naga::ImageQuery::Size { level } => {
                        let level = match level {
                            Some(l) => self.data(*l)?[0].bits.at(0) as i32,
                            None => 0,
                        };
                        let size = self.host.size(img, level).map_err(|m| Failure { message: m, span })?;
                        if size == [0, 0] {
                            self.undefined(
                                span,
                                "GLSL leaves textureSize of a level the texture does not have undefined",
                            );
                        }
                        let kind = match self.ty(h) {
                            TypeInner::Vector { scalar, .. } => Kind::of(*scalar).unwrap_or(Kind::U32),
                            _ => Kind::U32,
                        };
                        Val::Data(size.iter().map(|&s| Comp::new(kind, Bits::One(s))).collect())
                    }
                    _ => return fail(span, "the debugger does not run textureQueryLevels or array queries"),
                }
            }
            other => return unsupported(other, span),
        })
    }

    /// A lookup of `image` through `sampler` at `coordinate`, at the level of detail `level`
    /// gives (implicit ones from the quad's derivatives), filtered by the host.
    fn sample(
        &mut self,
        image: Handle<naga::Expression>,
        sampler: Handle<naga::Expression>,
        coordinate: Handle<naga::Expression>,
        level: &'m naga::SampleLevel,
        span: Span,
    ) -> Res<Val> {
        let (Val::Image(img), Val::Sampler(smp)) =
            (self.get(image)?.as_ref().clone(), self.get(sampler)?.as_ref().clone())
        else {
            return fail(span, "a lookup whose texture or sampler the debugger cannot tell");
        };
        let coord = self.data(coordinate)?;
        let lods: Vec<Lod> = match level {
            naga::SampleLevel::Zero => vec![Lod::Level(0.0); self.lanes],
            naga::SampleLevel::Exact(l) => {
                let l = self.data(*l)?;
                (0..self.lanes).map(|i| Lod::Level(l[0].f(i))).collect()
            }
            naga::SampleLevel::Auto | naga::SampleLevel::Bias(_) => {
                let bias = match level {
                    naga::SampleLevel::Bias(b) => Some(self.data(*b)?),
                    _ => None,
                };
                if !self.quad {
                    vec![Lod::Level(0.0); self.lanes]
                } else {
                    use naga::DerivativeAxis as Ax;
                    let d =
                        |axis, quad| -> Vec<Comp> { coord.iter().map(|c| self.derivative(c, axis, quad)).collect() };
                    let (cx, cy) = (d(Ax::X, true), d(Ax::Y, true));
                    let (fx, fy) = (d(Ax::X, false), d(Ax::Y, false));
                    (0..self.lanes)
                        .map(|i| Lod::Implicit {
                            coarse: (vec3(&cx, i), vec3(&cy, i)),
                            fine: (vec3(&fx, i), vec3(&fy, i)),
                            bias: bias.as_ref().map_or(0.0, |b| b[0].f(i)),
                        })
                        .collect()
                }
            }
            naga::SampleLevel::Gradient { x, y } => {
                let (dx, dy) = (self.data(*x)?, self.data(*y)?);
                (0..self.lanes)
                    .map(|i| Lod::Implicit {
                        coarse: (vec3(&dx, i), vec3(&dy, i)),
                        fine: (vec3(&dx, i), vec3(&dy, i)),
                        bias: 0.0,
                    })
                    .collect()
            }
        };
        let mut out: Vec<Vec<u32>> = (0..4).map(|_| Vec::with_capacity(self.lanes)).collect();
        for (lane, lod) in lods.iter().enumerate() {
            let rgba = self
                .host
                .sample(img, smp, vec3(&coord, lane), *lod)
                .map_err(|m| Failure { message: m, span })?;
            for k in 0..4 {
                out[k].push(rgba[k].to_bits());
            }
        }
        Ok(Val::Data(
            out.into_iter().map(|b| Comp::new(Kind::F32, Bits::Each(b))).collect(),
        ))
    }

    /// d/dx or d/dy of `c` across the quad: at each pixel from its own row and column, or
    /// with `quad` from the quad's top-left pixel's (the one a texture's level of detail uses).
    fn derivative(&self, c: &Comp, axis: naga::DerivativeAxis, quad: bool) -> Comp {
        use naga::DerivativeAxis as A;
        if !self.quad || c.kind != Kind::F32 {
            return Comp::new(Kind::F32, Bits::One(0f32.to_bits()));
        }
        if let Bits::One(_) = c.bits {
            return Comp::new(Kind::F32, Bits::One(0f32.to_bits()));
        }
        let v = |i: usize| c.f(i);
        let dx = |i: usize| if quad { v(1) - v(0) } else { v(i | 1) - v(i & !1) };
        let dy = |i: usize| if quad { v(2) - v(0) } else { v(i | 2) - v(i & !2) };
        let out: Vec<f32> = (0..4)
            .map(|i| match axis {
                A::X => dx(i),
                A::Y => dy(i),
                A::Width => dx(i).abs() + dy(i).abs(),
            })
            .collect();
        Comp::f32s(out)
    }
}

/// Offset `o` of a pointer into `root` moved on by `at` (bytes into a buffer wrap at 32 bits).
fn advance(root: Root, o: usize, at: usize) -> usize {
    match root {
        Root::Buffer(_) => (o as u32).wrapping_add(at as u32) as usize,
        _ => o + at,
    }
}

fn vec3(comps: &[Comp], lane: usize) -> [f32; 3] {
    [0, 1, 2].map(|k| comps.get(k).map_or(0.0, |c| c.f(lane)))
}

/// The type a pointer points at.
pub(crate) fn pointee(module: &Module, ty: &TypeInner) -> Option<TypeInner> {
    match ty {
        TypeInner::Pointer { base, .. } => Some(module.types[*base].inner.clone()),
        TypeInner::ValuePointer { size, scalar, .. } => Some(match size {
            Some(size) => TypeInner::Vector {
                size: *size,
                scalar: *scalar,
            },
            None => TypeInner::Scalar(*scalar),
        }),
        _ => None,
    }
}

fn literal(l: naga::Literal, span: Span) -> Res<Comp> {
    use naga::Literal as L;
    Ok(match l {
        L::F32(v) => Comp::new(Kind::F32, Bits::One(v.to_bits())),
        L::I32(v) => Comp::new(Kind::I32, Bits::One(v as u32)),
        L::U32(v) => Comp::new(Kind::U32, Bits::One(v)),
        L::Bool(v) => Comp::new(Kind::Bool, Bits::One(u32::from(v))),
        L::AbstractInt(v) => Comp::new(Kind::I32, Bits::One(v as i32 as u32)),
        L::AbstractFloat(v) => Comp::new(Kind::F32, Bits::One((v as f32).to_bits())),
        other => {
            return fail(
                span,
                format!("the debugger does not hold {other:?} (only 32-bit numbers and bools)"),
            )
        }
    })
}

/// Evaluates a constant expression of the module's global arena.
pub fn const_eval(module: &Module, h: Handle<naga::Expression>) -> Res<Vec<Comp>> {
    let span = module.global_expressions.get_span(h);
    Ok(match &module.global_expressions[h] {
        E::Literal(l) => vec![literal(*l, span)?],
        E::Constant(c) => const_eval(module, module.constants[*c].init)?,
        E::ZeroValue(ty) => value::zero(module, &module.types[*ty].inner).ok_or_else(|| Failure {
            message: "a constant of a type the debugger does not hold".into(),
            span,
        })?,
        E::Compose { components, .. } => {
            let mut out = Vec::new();
            for c in components {
                out.extend(const_eval(module, *c)?);
            }
            out
        }
        E::Splat { size, value } => vec![const_eval(module, *value)?[0].clone(); *size as usize],
        other => {
            return fail(
                span,
                format!("the debugger does not evaluate the constant {}", expression_name(other)),
            )
        }
    })
}

fn cast(c: &Comp, kind: naga::ScalarKind, convert: bool, span: Span) -> Res<Comp> {
    use naga::ScalarKind as SK;
    let to = match kind {
        SK::Float => Kind::F32,
        SK::Sint => Kind::I32,
        SK::Uint => Kind::U32,
        SK::Bool => Kind::Bool,
        _ => return fail(span, "a conversion to a kind the debugger does not hold"),
    };
    if !convert {
        return Ok(Comp::new(to, c.bits.clone()));
    }
    let from = c.kind;
    // naga clamps a float to the integers it can hold before converting (WGSL's rule), as
    // min(max(x, lo), hi) in which a NaN x gives lo.
    let bits = c.bits.map(|b| match (from, to) {
        (a, b2) if a == b2 => b,
        (Kind::F32, Kind::I32) => (nan_clamp(f32::from_bits(b), -2_147_483_648.0, 2_147_483_520.0) as i32) as u32,
        (Kind::F32, Kind::U32) => nan_clamp(f32::from_bits(b), 0.0, 4_294_967_040.0) as u32,
        (Kind::F32, Kind::Bool) => u32::from(f32::from_bits(b) != 0.0),
        (Kind::I32, Kind::F32) => (b as i32 as f32).to_bits(),
        (Kind::U32, Kind::F32) => (b as f32).to_bits(),
        (Kind::Bool, Kind::F32) => {
            if b != 0 {
                1f32.to_bits()
            } else {
                0
            }
        }
        (Kind::I32 | Kind::U32, Kind::Bool) => u32::from(b != 0),
        (Kind::Bool, _) => u32::from(b != 0),
        _ => b, // i32 <-> u32: the same bits
    });
    Ok(Comp::new(to, bits))
}

/// The shape of a numeric type: rows × columns (a scalar is 1×1, a vector n×1).
fn shape(ty: &TypeInner) -> (usize, usize) {
    match ty {
        TypeInner::Vector { size, .. } => (*size as usize, 1),
        TypeInner::Matrix { columns, rows, .. } => (*rows as usize, *columns as usize),
        _ => (1, 1),
    }
}

fn binary(op: B, a: &[Comp], ta: &TypeInner, b: &[Comp], tb: &TypeInner, span: Span) -> Res<Vec<Comp>> {
    let mat = |t: &TypeInner| matches!(t, TypeInner::Matrix { .. });
    if op == B::Multiply && (mat(ta) || mat(tb)) && !(a.len() == 1 || b.len() == 1) {
        let (ra, ca) = shape(ta);
        let (rb, cb) = shape(tb);
        let (rows, inner, cols, a_col_major) = if mat(ta) && mat(tb) {
            (ra, ca, cb, true)
        } else if mat(ta) {
            (ra, ca, 1, true) // matrix × column vector
        } else {
            (1, rb, cb, false) // row vector × matrix
        };
        let _ = a_col_major;
        // out[c][r] = Σ_k A[k][r] · B[c][k] (A's column k, B's column c).
        let a_at = |r: usize, k: usize| -> &Comp {
            if mat(ta) {
                &a[k * ra + r]
            } else {
                &a[k] // a row vector: its k-th component
            }
        };
        let b_at = |k: usize, c: usize| -> &Comp {
            if mat(tb) {
                &b[c * rb + k]
            } else {
                &b[k]
            }
        };
        let mut out = Vec::with_capacity(rows * cols);
        for c in 0..cols {
            for r in 0..rows {
                let mut acc = a_at(r, 0).bits.zip(&b_at(0, c).bits, fmul);
                for k in 1..inner {
                    let p = a_at(r, k).bits.zip(&b_at(k, c).bits, fmul);
                    acc = acc.zip(&p, fadd);
                }
                out.push(Comp::new(Kind::F32, acc));
            }
        }
        return Ok(out);
    }
    // Component by component, a scalar operand applied to every component.
    let n = a.len().max(b.len());
    if !(a.len() == n || a.len() == 1) || !(b.len() == n || b.len() == 1) {
        return fail(
            span,
            format!("operands of {op:?} with {} and {} components", a.len(), b.len()),
        );
    }
    let mut out = Vec::with_capacity(n);
    for k in 0..n {
        let x = if a.len() == 1 { &a[0] } else { &a[k] };
        let y = if b.len() == 1 { &b[0] } else { &b[k] };
        out.push(scalar_binary(op, x, y, span)?);
    }
    // `==` and `!=` of vectors are component-wise in naga's IR (all()/any() fold them).
    Ok(out)
}

#[inline]
fn fmul(x: u32, y: u32) -> u32 {
    (f32::from_bits(x) * f32::from_bits(y)).to_bits()
}

#[inline]
fn fadd(x: u32, y: u32) -> u32 {
    (f32::from_bits(x) + f32::from_bits(y)).to_bits()
}

fn scalar_binary(op: B, x: &Comp, y: &Comp, span: Span) -> Res<Comp> {
    let kind = x.kind;
    let f = |g: fn(f32, f32) -> f32| {
        x.bits
            .zip(&y.bits, move |a, b| g(f32::from_bits(a), f32::from_bits(b)).to_bits())
    };
    let fc = |g: fn(f32, f32) -> bool| {
        x.bits
            .zip(&y.bits, move |a, b| u32::from(g(f32::from_bits(a), f32::from_bits(b))))
    };
    let i = |g: fn(i32, i32) -> i32| x.bits.zip(&y.bits, move |a, b| g(a as i32, b as i32) as u32);
    let ic = |g: fn(i32, i32) -> bool| x.bits.zip(&y.bits, move |a, b| u32::from(g(a as i32, b as i32)));
    let u = |g: fn(u32, u32) -> u32| x.bits.zip(&y.bits, g);
    let uc = |g: fn(u32, u32) -> bool| x.bits.zip(&y.bits, move |a, b| u32::from(g(a, b)));
    let cmp = |bits: Bits| Ok(Comp::new(Kind::Bool, bits));
    match (kind, op) {
        (Kind::F32, B::Add) => Ok(Comp::new(kind, f(|a, b| a + b))),
        (Kind::F32, B::Subtract) => Ok(Comp::new(kind, f(|a, b| a - b))),
        (Kind::F32, B::Multiply) => Ok(Comp::new(kind, f(|a, b| a * b))),
        (Kind::F32, B::Divide) => Ok(Comp::new(kind, f(|a, b| a / b))),
        (Kind::F32, B::Modulo) => Ok(Comp::new(kind, f(|a, b| a % b))),
        (Kind::F32, B::Equal) => cmp(fc(|a, b| a == b)),
        (Kind::F32, B::NotEqual) => cmp(fc(|a, b| a != b)),
        (Kind::F32, B::Less) => cmp(fc(|a, b| a < b)),
        (Kind::F32, B::LessEqual) => cmp(fc(|a, b| a <= b)),
        (Kind::F32, B::Greater) => cmp(fc(|a, b| a > b)),
        (Kind::F32, B::GreaterEqual) => cmp(fc(|a, b| a >= b)),
        (Kind::I32, B::Add) => Ok(Comp::new(kind, i(i32::wrapping_add))),
        (Kind::I32, B::Subtract) => Ok(Comp::new(kind, i(i32::wrapping_sub))),
        (Kind::I32, B::Multiply) => Ok(Comp::new(kind, i(i32::wrapping_mul))),
        // WGSL's rule, which naga's backends implement: x / 0 is x, MIN / -1 is MIN.
        (Kind::I32, B::Divide) => Ok(Comp::new(kind, i(|a, b| if b == 0 { a } else { a.wrapping_div(b) }))),
        (Kind::I32, B::Modulo) => Ok(Comp::new(kind, i(|a, b| if b == 0 { 0 } else { a.wrapping_rem(b) }))),
        (Kind::I32, B::Equal) => cmp(ic(|a, b| a == b)),
        (Kind::I32, B::NotEqual) => cmp(ic(|a, b| a != b)),
        (Kind::I32, B::Less) => cmp(ic(|a, b| a < b)),
        (Kind::I32, B::LessEqual) => cmp(ic(|a, b| a <= b)),
        (Kind::I32, B::Greater) => cmp(ic(|a, b| a > b)),
        (Kind::I32, B::GreaterEqual) => cmp(ic(|a, b| a >= b)),
        (Kind::I32, B::ShiftRight) => Ok(Comp::new(kind, i(|a, b| a >> (b as u32 & 31)))),
        (Kind::U32, B::Add) => Ok(Comp::new(kind, u(u32::wrapping_add))),
        (Kind::U32, B::Subtract) => Ok(Comp::new(kind, u(u32::wrapping_sub))),
        (Kind::U32, B::Multiply) => Ok(Comp::new(kind, u(u32::wrapping_mul))),
        (Kind::U32, B::Divide) => Ok(Comp::new(kind, u(|a, b| a.checked_div(b).unwrap_or(a)))),
        (Kind::U32, B::Modulo) => Ok(Comp::new(kind, u(|a, b| if b == 0 { 0 } else { a % b }))),
        (Kind::U32 | Kind::Bool, B::Equal) => cmp(uc(|a, b| a == b)),
        (Kind::U32 | Kind::Bool, B::NotEqual) => cmp(uc(|a, b| a != b)),
        (Kind::U32, B::Less) => cmp(uc(|a, b| a < b)),
        (Kind::U32, B::LessEqual) => cmp(uc(|a, b| a <= b)),
        (Kind::U32, B::Greater) => cmp(uc(|a, b| a > b)),
        (Kind::U32, B::GreaterEqual) => cmp(uc(|a, b| a >= b)),
        (Kind::U32, B::ShiftRight) => Ok(Comp::new(kind, u(|a, b| a >> (b & 31)))),
        (Kind::I32 | Kind::U32, B::ShiftLeft) => Ok(Comp::new(kind, u(|a, b| a << (b & 31)))),
        (Kind::I32 | Kind::U32 | Kind::Bool, B::And) => Ok(Comp::new(kind, u(|a, b| a & b))),
        (Kind::I32 | Kind::U32 | Kind::Bool, B::InclusiveOr) => Ok(Comp::new(kind, u(|a, b| a | b))),
        (Kind::I32 | Kind::U32 | Kind::Bool, B::ExclusiveOr) => Ok(Comp::new(kind, u(|a, b| a ^ b))),
        (Kind::Bool, B::LogicalAnd) => Ok(Comp::new(kind, u(|a, b| u32::from(a != 0 && b != 0)))),
        (Kind::Bool, B::LogicalOr) => Ok(Comp::new(kind, u(|a, b| u32::from(a != 0 || b != 0)))),
        _ => fail(span, format!("the debugger does not run {op:?} on {kind:?} values")),
    }
}

fn statement_name(s: &naga::Statement) -> &'static str {
    match s {
        S::ImageStore { .. } => "imageStore",
        S::Atomic { .. } | S::ImageAtomic { .. } => "atomic operations",
        S::WorkGroupUniformLoad { .. } => "workgroup loads",
        S::RayQuery { .. } | S::RayPipelineFunction(_) => "ray queries",
        S::SubgroupBallot { .. } | S::SubgroupGather { .. } | S::SubgroupCollectiveOperation { .. } => {
            "subgroup operations"
        }
        _ => "this statement",
    }
}

/// The failure for an expression the debugger does not run, naming it.
fn unsupported<T>(e: &naga::Expression, span: Span) -> Res<T> {
    fail(span, format!("the debugger does not run {}", expression_name(e)))
}

fn expression_name(e: &naga::Expression) -> String {
    match e {
        E::Override(_) => "pipeline-overridable constants".into(),
        E::AtomicResult { .. } => "atomic operations".into(),
        E::ArrayLength(_) => "runtime-sized arrays (.length())".into(),
        E::SubgroupBallotResult | E::SubgroupOperationResult { .. } => "subgroup operations".into(),
        other => format!("{other:?}")
            .split([' ', '(', '{'])
            .next()
            .unwrap_or("this")
            .to_owned(),
    }
}
