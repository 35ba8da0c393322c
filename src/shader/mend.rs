//! Rewrites of naga's IR that keep valid GLSL away from bugs in naga's back ends.
//!
//! naga's GLSL front end passes an `out` or `inout` argument that is part of a local variable
//! (a vector's component `h(c.y)`, an array's element `g(a[1])`, a matrix's column `h(m[1])`)
//! as a pointer into that variable. naga's SPIR-V writer caches only whole variables as call
//! arguments and panics on such a pointer ("Expression [N] is not cached"), and WGSL has no
//! pointer to a component at all. GLSL's own rule is copy-in, copy-out: [`spill_partial_pointers`]
//! writes exactly that, through a new local of the parameter's type, so that every back end sees
//! a whole variable. No crate does this; naga's own spill covers other address spaces only.

use naga::{Block, Expression, Handle, LocalVariable, Module, Span, Statement};

/// Passes every call argument that points into part of a variable through a new local
/// variable: stored from the part before the call, stored back into it after. Returns how many
/// arguments it rewrote (0: the module is unchanged).
pub fn spill_partial_pointers(module: &mut Module) -> usize {
    // The pointee type of each function's pointer parameters, by function and argument index.
    let pointees: Vec<Vec<Option<Handle<naga::Type>>>> = module
        .functions
        .iter()
        .map(|(_, f)| {
            f.arguments
                .iter()
                .map(|a| match module.types[a.ty].inner {
                    naga::TypeInner::Pointer { base, .. } => Some(base),
                    _ => None,
                })
                .collect()
        })
        .collect();
    let mut rewritten = 0;
    let mut mend = |f: &mut naga::Function| {
        let body = std::mem::take(&mut f.body);
        f.body = spill_block(body, f, &pointees, &mut rewritten);
    };
    for (_, f) in module.functions.iter_mut() {
        mend(f);
    }
    for ep in module.entry_points.iter_mut() {
        mend(&mut ep.function);
    }
    rewritten
}

fn spill_block(
    block: Block,
    f: &mut naga::Function,
    pointees: &[Vec<Option<Handle<naga::Type>>>],
    rewritten: &mut usize,
) -> Block {
    let mut out = Block::with_capacity(block.len());
    for (statement, span) in block.span_into_iter() {
        let statement = match statement {
            Statement::Block(b) => Statement::Block(spill_block(b, f, pointees, rewritten)),
            Statement::If {
                condition,
                accept,
                reject,
            } => Statement::If {
                condition,
                accept: spill_block(accept, f, pointees, rewritten),
                reject: spill_block(reject, f, pointees, rewritten),
            },
            Statement::Switch { selector, cases } => Statement::Switch {
                selector,
                cases: cases
                    .into_iter()
                    .map(|mut case| {
                        case.body = spill_block(std::mem::take(&mut case.body), f, pointees, rewritten);
                        case
                    })
                    .collect(),
            },
            Statement::Loop {
                body,
                continuing,
                break_if,
            } => Statement::Loop {
                body: spill_block(body, f, pointees, rewritten),
                continuing: spill_block(continuing, f, pointees, rewritten),
                break_if,
            },
            Statement::Call {
                function,
                mut arguments,
                result,
            } => {
                let mut after = Vec::new();
                for (i, arg) in arguments.iter_mut().enumerate() {
                    let partial = matches!(
                        f.expressions[*arg],
                        Expression::Access { .. } | Expression::AccessIndex { .. }
                    );
                    let Some(Some(ty)) = pointees[function.index()].get(i) else {
                        continue;
                    };
                    if !partial {
                        continue;
                    }
                    let part = *arg;
                    let local = f.local_variables.append(
                        LocalVariable {
                            name: None,
                            ty: *ty,
                            init: None,
                        },
                        span,
                    );
                    let spill = f.expressions.append(Expression::LocalVariable(local), span);
                    // Copy in (an `out` parameter starts undefined, so a copy is as good).
                    let value = emit(f, &mut out, Expression::Load { pointer: part }, span);
                    out.push(Statement::Store { pointer: spill, value }, span);
                    *arg = spill;
                    after.push((part, spill));
                    *rewritten += 1;
                }
                out.push(
                    Statement::Call {
                        function,
                        arguments,
                        result,
                    },
                    span,
                );
                // Copy out, in argument order, as GLSL writes back.
                for (part, spill) in after {
                    let value = emit(f, &mut out, Expression::Load { pointer: spill }, span);
                    out.push(Statement::Store { pointer: part, value }, span);
                }
                continue;
            }
            other => other,
        };
        out.push(statement, span);
    }
    out
}

/// Appends `expression` to `f` and emits it at the end of `out`.
fn emit(f: &mut naga::Function, out: &mut Block, expression: Expression, span: Span) -> Handle<Expression> {
    let handle = f.expressions.append(expression, span);
    out.push(Statement::Emit(naga::Range::new_from_bounds(handle, handle)), span);
    handle
}
