//! Limits checked on a shader's tokens before any recursive stage sees them.
//!
//! Every stage after the text is recursive over the shader's nesting: glsl-lang's and naga's
//! parsers, the legacy translation's visitor, naga's validator and WGSL writer, and the GPU
//! driver's compiler. A hostile (or generated) shader — a 10,000-term sum, 10,000 nested `(`,
//! `{` or `if` — overflows one of their stacks and aborts the process, which no `Result` can
//! catch. Macros multiply the text (40 nested `#define A1 (A0+A0)` is 2^40 tokens), and calls
//! multiply the code the driver sees (it inlines every call: `f1(x) = f0(x) + f0(x)` forty
//! times is 2^40 copies of `f0`). So one linear pass over the tokens, with object-like and
//! function-like macros expanded as the preprocessor would, bounds all three before the
//! first parser runs:
//! - the nesting depth: open brackets plus, at each open level, the operators and control
//!   keywords (`if`, `else`, `for`, ...) since its last `,` or `;` — an upper bound of the
//!   syntax tree's depth ([`MAX_DEPTH`]);
//! - the number of tokens after macro expansion ([`MAX_EXPANDED_TOKENS`]);
//! - the size of each function with its calls inlined ([`MAX_INLINED_TOKENS`]).
//!
//! The pass itself uses no recursion and memory proportional to the text and the budget.

use std::collections::HashMap;
use std::ops::Range;

/// The deepest nesting accepted (brackets, plus chained operators and control statements). The
/// course's shaders stay under 20; naga and the legacy translation handle this many in a debug
/// build on a 2 MiB thread stack.
pub const MAX_DEPTH: usize = 256;

/// The most tokens a shader's macro expansions may produce, all together. naga's GLSL front
/// end is slower than linear in the tokens, and takes seconds at this many (figures:
/// `docs/speed.md`, "Shader limits").
pub const MAX_EXPANDED_TOKENS: usize = 1 << 18;

/// The most tokens outside function bodies (declarations, constant initializers): naga's
/// handling of global constants is slower than linear (figures: `docs/speed.md`, "Shader
/// limits"). A 4096-entry constant table is under 10,000.
pub const MAX_GLOBAL_TOKENS: usize = 1 << 16;

/// The most tokens a function may have with every call inlined, as the GPU driver compiles it.
/// Mesa's lavapipe takes seconds and hundreds of megabytes at this many, and crashes long
/// before a chain of doubling calls reaches 2^40 (figures: `docs/speed.md`, "Shader limits").
pub const MAX_INLINED_TOKENS: u64 = 1 << 17;

/// A limit the text passes: where (a byte range of the text checked) and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Exceeded {
    /// The place: the token (or the macro use that produced it) at which the limit was passed.
    pub range: Range<usize>,
    /// What is too large, and the limit.
    pub message: String,
}

/// Checks `text` (GLSL source, any version) against [`MAX_DEPTH`], [`MAX_EXPANDED_TOKENS`]
/// and [`MAX_INLINED_TOKENS`].
pub fn check(text: &str) -> Result<(), Exceeded> {
    let mut ex = Expander {
        lexer: Lexer::new(text, 0, text.len(), true),
        macros: HashMap::new(),
        frames: Vec::new(),
        active: HashMap::new(),
        pushback: None,
        expanded: 0,
    };
    let mut depth = Depth::default();
    let mut calls = CallGraph::default();
    while let Some(tok) = ex.next()? {
        depth.push(&tok)?;
        calls.push(&tok, depth.brackets());
    }
    calls.check()
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Ident,
    Number,
    Punct,
}

/// A token, with the place in the checked text it stands for (for a token of a macro's
/// expansion: the outermost macro use).
#[derive(Clone, Copy, Debug)]
struct Tok<'a> {
    text: &'a str,
    kind: Kind,
    site: (usize, usize),
}

enum Lexed<'a> {
    Tok(Tok<'a>),
    /// A preprocessor line after its `#`: (start, end) in the text.
    Directive(usize, usize),
}

struct Lexer<'a> {
    text: &'a str,
    i: usize,
    end: usize,
    line_start: bool,
}

const PUNCT3: &[&str] = &["<<=", ">>="];
const PUNCT2: &[&str] = &[
    "++", "--", "<<", ">>", "<=", ">=", "==", "!=", "&&", "||", "^^", "+=", "-=", "*=", "/=", "%=", "&=", "|=", "^=",
    "##",
];

impl<'a> Lexer<'a> {
    fn new(text: &'a str, start: usize, end: usize, line_start: bool) -> Self {
        Lexer {
            text,
            i: start,
            end,
            line_start,
        }
    }

    fn next(&mut self) -> Option<Lexed<'a>> {
        let b = self.text.as_bytes();
        loop {
            if self.i >= self.end {
                return None;
            }
            let c = b[self.i];
            match c {
                b'\n' => {
                    self.line_start = true;
                    self.i += 1;
                }
                b' ' | b'\t' | b'\r' | 0x0b | 0x0c => self.i += 1,
                b'\\' if b.get(self.i + 1) == Some(&b'\n') => self.i += 2,
                b'/' if b.get(self.i + 1) == Some(&b'/') => {
                    self.i = memchr(b, b'\n', self.i, self.end);
                }
                b'/' if b.get(self.i + 1) == Some(&b'*') => {
                    self.i = self.text[self.i + 2..self.end]
                        .find("*/")
                        .map_or(self.end, |k| self.i + 2 + k + 2);
                }
                b'#' if self.line_start => {
                    // The directive runs to the end of the line, `\`-newline continuing it.
                    let start = self.i + 1;
                    let mut j = start;
                    loop {
                        j = memchr(b, b'\n', j, self.end);
                        if j > start && j < self.end && b[j - 1] == b'\\' {
                            j += 1;
                            continue;
                        }
                        if j > start + 1 && j < self.end && b[j - 1] == b'\r' && b[j - 2] == b'\\' {
                            j += 1;
                            continue;
                        }
                        break;
                    }
                    self.i = j;
                    return Some(Lexed::Directive(start, j));
                }
                _ => {
                    self.line_start = false;
                    let start = self.i;
                    let kind = if c.is_ascii_alphabetic() || c == b'_' || c >= 0x80 {
                        while self.i < self.end
                            && (b[self.i].is_ascii_alphanumeric() || b[self.i] == b'_' || b[self.i] >= 0x80)
                        {
                            self.i += 1;
                        }
                        Kind::Ident
                    } else if c.is_ascii_digit() || (c == b'.' && b.get(self.i + 1).is_some_and(u8::is_ascii_digit)) {
                        while self.i < self.end {
                            let d = b[self.i];
                            let exponent_sign = (d == b'+' || d == b'-')
                                && matches!(b[self.i - 1], b'e' | b'E')
                                && !self.text[start..self.i].starts_with("0x");
                            if d.is_ascii_alphanumeric() || d == b'.' || d == b'_' || exponent_sign {
                                self.i += 1;
                            } else {
                                break;
                            }
                        }
                        Kind::Number
                    } else {
                        let rest = &self.text[start..self.end];
                        let n = if PUNCT3.iter().any(|p| rest.starts_with(p)) {
                            3
                        } else if PUNCT2.iter().any(|p| rest.starts_with(p)) {
                            2
                        } else {
                            rest.chars().next().map_or(1, char::len_utf8)
                        };
                        self.i += n;
                        Kind::Punct
                    };
                    return Some(Lexed::Tok(Tok {
                        text: &self.text[start..self.i],
                        kind,
                        site: (start, self.i),
                    }));
                }
            }
        }
    }
}

/// The index of the first `byte` in `b[from..end]`, or `end`.
fn memchr(b: &[u8], byte: u8, from: usize, end: usize) -> usize {
    b[from..end].iter().position(|&c| c == byte).map_or(end, |k| from + k)
}

struct Macro<'a> {
    /// The parameters of a function-like macro.
    params: Option<Vec<&'a str>>,
    body: Vec<Tok<'a>>,
}

struct Frame<'a> {
    name: &'a str,
    toks: Vec<Tok<'a>>,
    i: usize,
}

/// The token stream with macros expanded (as C's preprocessor does, near enough to count:
/// conditional directives are not evaluated, so every branch's macros are defined in turn).
struct Expander<'a> {
    lexer: Lexer<'a>,
    macros: HashMap<&'a str, Macro<'a>>,
    frames: Vec<Frame<'a>>,
    /// How many frames of each macro are open (a macro is not expanded inside itself).
    active: HashMap<&'a str, usize>,
    pushback: Option<Tok<'a>>,
    /// Tokens produced by expansions so far.
    expanded: usize,
}

impl<'a> Expander<'a> {
    /// The next token before expansion: from the innermost expansion, else from the text.
    fn next_raw(&mut self) -> Option<Tok<'a>> {
        if let Some(t) = self.pushback.take() {
            return Some(t);
        }
        while let Some(frame) = self.frames.last_mut() {
            if let Some(t) = frame.toks.get(frame.i) {
                frame.i += 1;
                return Some(*t);
            }
            if let Some(f) = self.frames.pop() {
                if let Some(n) = self.active.get_mut(f.name) {
                    *n -= 1;
                }
            }
        }
        loop {
            match self.lexer.next()? {
                Lexed::Tok(t) => return Some(t),
                Lexed::Directive(start, end) => self.directive(start, end),
            }
        }
    }

    fn directive(&mut self, start: usize, end: usize) {
        let mut lexer = Lexer::new(self.lexer.text, start, end, false);
        let mut toks = Vec::new();
        while let Some(Lexed::Tok(t)) = lexer.next() {
            toks.push(t);
        }
        match toks.as_slice() {
            [d, name, rest @ ..] if d.text == "define" && name.kind == Kind::Ident => {
                // A function-like macro has its `(` right after the name.
                let function = rest.first().is_some_and(|t| t.text == "(" && t.site.0 == name.site.1);
                let (params, body) = if function {
                    let close = rest.iter().position(|t| t.text == ")").unwrap_or(rest.len());
                    let params = rest[1..close]
                        .iter()
                        .filter(|t| t.kind == Kind::Ident)
                        .map(|t| t.text)
                        .collect();
                    (Some(params), rest.get(close + 1..).unwrap_or(&[]).to_vec())
                } else {
                    (None, rest.to_vec())
                };
                self.macros.insert(name.text, Macro { params, body });
            }
            [d, name, ..] if d.text == "undef" => {
                self.macros.remove(name.text);
            }
            _ => {}
        }
    }

    fn next(&mut self) -> Result<Option<Tok<'a>>, Exceeded> {
        loop {
            let Some(tok) = self.next_raw() else {
                return Ok(None);
            };
            if tok.kind != Kind::Ident || self.active.get(tok.text).is_some_and(|&n| n > 0) {
                return Ok(Some(tok));
            }
            let Some(mac) = self.macros.get(tok.text) else {
                return Ok(Some(tok));
            };
            let mac_is_function = mac.params.is_some();
            let body = match &mac.params {
                None => mac.body.clone(),
                Some(params) => {
                    let params = params.clone();
                    let body = mac.body.clone();
                    let Some(open) = self.next_raw() else {
                        return Ok(Some(tok));
                    };
                    if open.text != "(" {
                        self.pushback = Some(open);
                        return Ok(Some(tok));
                    }
                    // The arguments, unexpanded: their expansion comes on the rescan.
                    let mut args: Vec<Vec<Tok<'a>>> = vec![Vec::new()];
                    let mut level = 0usize;
                    while let Some(t) = self.next_raw() {
                        match t.text {
                            "(" | "[" | "{" => level += 1,
                            ")" | "]" | "}" if level == 0 => break,
                            ")" | "]" | "}" => level -= 1,
                            "," if level == 0 => {
                                args.push(Vec::new());
                                continue;
                            }
                            _ => {}
                        }
                        self.expanded += 1;
                        if self.expanded > MAX_EXPANDED_TOKENS {
                            return Err(self.too_many_tokens(tok));
                        }
                        if let Some(last) = args.last_mut() {
                            last.push(t);
                        }
                    }
                    let mut out = Vec::with_capacity(body.len());
                    for t in body {
                        match params.iter().position(|p| *p == t.text) {
                            Some(k) if t.kind == Kind::Ident => {
                                let arg = args.get(k).map_or(&[][..], Vec::as_slice);
                                self.expanded += arg.len();
                                if self.expanded > MAX_EXPANDED_TOKENS {
                                    return Err(self.too_many_tokens(tok));
                                }
                                out.extend_from_slice(arg);
                            }
                            _ => out.push(t),
                        }
                    }
                    out
                }
            };
            self.expanded += body.len();
            if self.expanded > MAX_EXPANDED_TOKENS {
                return Err(self.too_many_tokens(tok));
            }
            // Every token of an expansion stands for the outermost macro use.
            let site = tok.site;
            let toks = body.into_iter().map(|t| Tok { site, ..t }).collect();
            // Only an object-like macro is kept from expanding inside itself: a function-like
            // one's arguments are expanded on the rescan here, where C expands them before
            // substitution (so `D(D(x))` expands both). A function-like macro that calls itself
            // then runs into the token budget instead of stopping.
            let name = if mac_is_function { "" } else { tok.text };
            *self.active.entry(name).or_default() += 1;
            self.frames.push(Frame { name, toks, i: 0 });
        }
    }
}

impl Expander<'_> {
    /// The error at the macro use (the outermost one, where the user's text names it).
    fn too_many_tokens(&self, tok: Tok) -> Exceeded {
        let name = self.lexer.text.get(tok.site.0..tok.site.1).unwrap_or(tok.text);
        Exceeded {
            range: tok.site.0..tok.site.1,
            message: format!(
                "`{name}`: the shader's macro expansions pass {MAX_EXPANDED_TOKENS} tokens here \
                 (macros within macros multiply); shaderlab refuses expansions this large"
            ),
        }
    }
}

/// The nesting measure of [`MAX_DEPTH`].
#[derive(Default)]
struct Depth {
    /// Per open bracket (and the outermost level at 0): the operators since its last `,`/`;`.
    levels: Vec<usize>,
    top: usize,
    total: usize,
    /// The last token closed a block: a statement ended, unless `else` follows.
    after_block: bool,
}

impl Depth {
    fn brackets(&self) -> usize {
        self.levels.len()
    }

    fn push(&mut self, tok: &Tok) -> Result<(), Exceeded> {
        // `if (a) { } if (b) { }` are two statements, not nested; `if (a) { } else if (b) { }`
        // nests (the `else` holds the second `if`).
        if std::mem::take(&mut self.after_block) && tok.text != "else" {
            self.reset();
        }
        match tok.text {
            "(" | "[" | "{" => {
                self.levels.push(0);
                self.total += 1;
            }
            ")" | "]" | "}" => {
                if let Some(ops) = self.levels.pop() {
                    self.total -= 1 + ops;
                }
                self.after_block = tok.text == "}";
            }
            "," | ";" => self.reset(),
            "if" | "else" | "for" | "while" | "do" | "switch" | "case" | "default" => self.op(),
            _ if tok.kind == Kind::Punct => self.op(),
            _ => {}
        }
        if self.total > MAX_DEPTH {
            return Err(Exceeded {
                range: tok.site.0..tok.site.1,
                message: format!(
                    "the code nests too deeply here (brackets, blocks, `if`s and chained operators \
                     more than {MAX_DEPTH} deep); split the expression or block into smaller ones"
                ),
            });
        }
        Ok(())
    }

    fn reset(&mut self) {
        let ops = self.levels.last_mut().unwrap_or(&mut self.top);
        self.total -= *ops;
        *ops = 0;
    }

    fn op(&mut self) {
        *self.levels.last_mut().unwrap_or(&mut self.top) += 1;
        self.total += 1;
    }
}

struct Function<'a> {
    name: &'a str,
    site: (usize, usize),
    size: u64,
    /// The names it calls, each with the place of the call.
    calls: Vec<(&'a str, (usize, usize))>,
}

/// Functions defined at the outermost level, their sizes and the names they call.
#[derive(Default)]
struct CallGraph<'a> {
    functions: Vec<Function<'a>>,
    /// The last token, if an identifier: a `(` after it is a call (or a definition's).
    last_ident: Option<Tok<'a>>,
    /// A name before a `(` at the outermost level, then whether that `)` has closed.
    candidate: Option<(Tok<'a>, bool)>,
    /// In a function's body.
    inside: bool,
    /// Tokens outside function bodies so far, and the one past [`MAX_GLOBAL_TOKENS`].
    global: usize,
    too_many_global: Option<(usize, usize)>,
}

impl<'a> CallGraph<'a> {
    /// `brackets`: the open brackets after `tok`.
    fn push(&mut self, tok: &Tok<'a>, brackets: usize) {
        if self.inside {
            if let Some(f) = self.functions.last_mut() {
                f.size += 1;
                if tok.text == "(" {
                    if let Some(callee) = self.last_ident {
                        f.calls.push((callee.text, callee.site));
                    }
                }
            }
            if brackets == 0 {
                self.inside = false;
            }
        } else {
            self.global += 1;
            if self.global > MAX_GLOBAL_TOKENS && self.too_many_global.is_none() {
                self.too_many_global = Some(tok.site);
            }
            match (tok.text, brackets, self.candidate) {
                ("(", 1, _) => self.candidate = self.last_ident.map(|t| (t, false)),
                (")", 0, Some((t, false))) => self.candidate = Some((t, true)),
                ("{", 1, Some((t, true))) => {
                    self.functions.push(Function {
                        name: t.text,
                        site: t.site,
                        size: 1,
                        calls: Vec::new(),
                    });
                    self.inside = true;
                    self.candidate = None;
                }
                (_, 0, _) => self.candidate = None,
                _ => {}
            }
        }
        self.last_ident = (tok.kind == Kind::Ident).then_some(*tok);
    }

    /// The first call, in the text's order, whose callee leads back to its caller, with the
    /// cycle named as `legacy`'s translation names it (`recursion (f → g → f)`).
    fn first_cycle(&self, by_name: &HashMap<&str, Vec<usize>>) -> Exceeded {
        for f in &self.functions {
            for (callee, site) in &f.calls {
                // Breadth-first from the callee back to the caller, keeping each name's parent.
                let mut parent: HashMap<&str, &str> = HashMap::new();
                let mut queue = std::collections::VecDeque::from([*callee]);
                let mut seen = std::collections::HashSet::from([*callee]);
                while let Some(at) = queue.pop_front() {
                    if at == f.name {
                        let mut cycle = vec![at];
                        let mut back = at;
                        while let Some(p) = parent.get(back) {
                            cycle.push(p);
                            back = p;
                        }
                        cycle.push(f.name);
                        cycle.reverse();
                        let message = if *callee == f.name {
                            format!("`{callee}` calls itself: GLSL does not allow recursion; rewrite it as a loop")
                        } else {
                            format!(
                                "recursion ({}): GLSL does not allow a function to call itself, directly or \
                                 through others; rewrite it as a loop",
                                cycle.join(" → ")
                            )
                        };
                        return Exceeded {
                            range: site.0..site.1,
                            message,
                        };
                    }
                    for &k in by_name.get(at).into_iter().flatten() {
                        for (next, _) in &self.functions[k].calls {
                            if by_name.contains_key(next) && seen.insert(next) {
                                parent.insert(next, at);
                                queue.push_back(next);
                            }
                        }
                    }
                }
            }
        }
        Exceeded {
            range: 0..0,
            message: "recursion: GLSL does not allow a function to call itself; rewrite it as a loop".into(),
        }
    }

    /// Each function's size with its calls inlined (overloads counted together), without
    /// recursion; a function that calls itself, directly or through others, which GLSL forbids
    /// (and naga reports in words of its own IR), is refused at the call that closes the cycle.
    fn check(&self) -> Result<(), Exceeded> {
        if let Some(site) = self.too_many_global {
            return Err(Exceeded {
                range: site.0..site.1,
                message: format!(
                    "the declarations outside functions pass {MAX_GLOBAL_TOKENS} tokens here (after \
                     macro expansion); shaderlab refuses global initializers this large"
                ),
            });
        }
        let mut by_name: HashMap<&str, Vec<usize>> = HashMap::new();
        for (i, f) in self.functions.iter().enumerate() {
            by_name.entry(f.name).or_default().push(i);
        }
        const NEW: u8 = 0;
        const OPEN: u8 = 1;
        const DONE: u8 = 2;
        let n = self.functions.len();
        let mut state = vec![NEW; n];
        let mut inlined = vec![0u64; n];
        for root in 0..n {
            let mut stack = vec![root];
            while let Some(&i) = stack.last() {
                if state[i] == DONE {
                    stack.pop();
                    continue;
                }
                let callees = self.functions[i]
                    .calls
                    .iter()
                    .flat_map(|(c, _)| by_name.get(c).into_iter().flatten());
                if state[i] == NEW {
                    state[i] = OPEN;
                    // A call of a function open now (on the path from the root to `i`)
                    // closes a cycle.
                    let calls = &self.functions[i].calls;
                    if calls
                        .iter()
                        .any(|(c, _)| by_name.get(c).into_iter().flatten().any(|&j| state[j] == OPEN))
                    {
                        return Err(self.first_cycle(&by_name));
                    }
                    stack.extend(callees.filter(|&&j| state[j] == NEW));
                    continue;
                }
                let size = callees.fold(self.functions[i].size, |sum, &j| {
                    sum.saturating_add(if state[j] == DONE { inlined[j] } else { 1 })
                });
                inlined[i] = size;
                state[i] = DONE;
                stack.pop();
            }
        }
        match (0..n).find(|&i| inlined[i] > MAX_INLINED_TOKENS) {
            Some(i) => {
                let f = &self.functions[i];
                Err(Exceeded {
                    range: f.site.0..f.site.1,
                    message: format!(
                        "`{}` is {} tokens with its macros expanded and its calls inlined (as the GPU \
                         driver compiles it); the limit is {MAX_INLINED_TOKENS}: make fewer calls of \
                         functions that themselves call others many times",
                        f.name, inlined[i]
                    ),
                })
            }
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn nested(open: &str, close: &str, n: usize) -> String {
        format!(
            "void main() {{ float x = 1.0; float y = {}x{}; }}\n",
            open.repeat(n),
            close.repeat(n)
        )
    }

    #[test]
    fn recursion_is_refused_at_the_call_that_closes_it() {
        let text = "float b(float x);\nfloat a(float x) { return x > 1.0 ? b(x - 1.0) : x; }\n\
                    float b(float x) { return a(x * 0.5); }\nvoid main() { float y = a(2.0); }\n";
        let err = check(text).unwrap_err();
        // The first call that closes the cycle, in the text's order: `a`'s call of `b`.
        assert_eq!(&text[err.range.clone()], "b", "{err:?}");
        assert_eq!(text[..err.range.start].lines().count(), 2, "{err:?}");
        assert!(
            err.message.starts_with("recursion (a → b → a): GLSL does not allow"),
            "{}",
            err.message
        );
        let err = check("float f(float x) { return f(x); }\nvoid main() { float y = f(1.0); }\n").unwrap_err();
        assert!(err.message.starts_with("`f` calls itself"), "{}", err.message);
        // Calling the same function twice, or two functions the same one, is no cycle.
        assert_eq!(check("float g(float x) { return x; }\nfloat f(float x) { return g(x) + g(x); }\nfloat h(float x) { return g(x) * f(x); }\nvoid main() { float y = h(1.0); }\n"), Ok(()));
    }

    #[test]
    fn ordinary_shaders_pass() {
        for (name, text) in
            crate::shader::embedded_names().filter_map(|n| Some((n, crate::shader::embedded_source(n)?)))
        {
            assert_eq!(check(text), Ok(()), "{name}");
        }
        assert_eq!(check(&nested("(", ")", 200)), Ok(()));
        // Statements one after another do not nest, however many.
        let ifs = "if (x > 0.0) { x = 1.0; } for (int i = 0; i < 2; i++) { x += 1.0; }\n".repeat(1000);
        assert_eq!(check(&format!("void main() {{ float x = 0.0;\n{ifs}}}\n")), Ok(()));
        let chain: String = (0..10)
            .map(|i| format!("float f{}(float x) {{ return f{i}(x) + f{i}(x); }}\n", i + 1))
            .collect();
        assert_eq!(check(&chain), Ok(()));
        let macros: String = (0..10).map(|i| format!("#define A{} (A{i}+A{i})\n", i + 1)).collect();
        assert_eq!(check(&format!("#define A0 1.0\n{macros}float x = A10;\n")), Ok(()));
    }

    #[test]
    fn deep_nesting_is_refused_at_its_place() {
        let sum = format!("void main() {{\n float x = {}; }}\n", vec!["1.0"; 10_000].join("+"));
        let ifs = format!("void main() {{\n{} x = 1.0; }}\n", "if (x > 0.0) ".repeat(5000));
        let chain = format!("void main() {{\n{} {{ }}\n}}\n", "if (x > 0.0) { } else ".repeat(5000));
        for text in [
            chain,
            nested("(", ")", 10_000),
            nested("{", "}", 10_000),
            nested("[", "]", 300),
            sum,
            ifs,
        ] {
            let e = check(&text).unwrap_err();
            assert!(e.message.contains("nests too deeply"), "{}", e.message);
            assert!(e.range.start > 10 && e.range.start < 4000, "{:?}", e.range);
        }
    }

    #[test]
    fn macro_bombs_are_refused_at_their_use() {
        let macros: String = (0..40).map(|i| format!("#define A{} (A{i}+A{i})\n", i + 1)).collect();
        let text = format!("#define A0 1.0\n{macros}void main() {{ float x = A40; }}\n");
        let e = check(&text).unwrap_err();
        assert!(
            e.message.contains("`A40`: the shader's macro expansions pass"),
            "{}",
            e.message
        );
        assert_eq!(&text[e.range.clone()], "A40");
        // Function-like macros multiply their arguments.
        let text =
            "#define D(x) (x)+(x)\nfloat y = D(D(D(D(D(D(D(D(D(D(D(D(D(D(D(D(D(D(D(D(D(D(1.0))))))))))))))))))))));\n";
        let e = check(text).unwrap_err();
        assert!(
            e.message.contains("macro expansions pass") || e.message.contains("nests"),
            "{}",
            e.message
        );
        // A macro that names itself is not expanded again (as in C).
        assert_eq!(check("#define A A+1\nfloat x = A;\n"), Ok(()));
    }

    #[test]
    fn huge_global_initializers_are_refused() {
        let table = format!("const float t[4096] = float[]({});\n", vec!["1.0"; 4096].join(", "));
        assert_eq!(check(&table), Ok(()));
        let consts: String = (0..10_000)
            .map(|i| format!("const float k{i} = 1.0 + 2.0;\n"))
            .collect();
        let e = check(&consts).unwrap_err();
        assert!(
            e.message.contains("outside functions pass 65536 tokens"),
            "{}",
            e.message
        );
    }

    #[test]
    fn call_chains_are_bounded_by_their_inlined_size() {
        let chain: String = (0..40)
            .map(|i| format!("float f{}(float x) {{ return f{i}(x) + f{i}(x); }}\n", i + 1))
            .collect();
        let text = format!("float f0(float x) {{ return x; }}\n{chain}void main() {{ float y = f40(0.5); }}\n");
        let e = check(&text).unwrap_err();
        assert!(e.message.contains("inlined"), "{}", e.message);
        assert!(text[e.range.clone()].starts_with('f'), "{:?}", &text[e.range.clone()]);
    }

    /// Every shader file of the repository (labs, fixtures, course files) is within the bounds.
    #[test]
    fn every_shader_of_the_repository_passes() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let mut stack = vec![root.join("tests"), root.join("shaders_glsl"), root.join("assets")];
        let mut checked = 0;
        while let Some(dir) = stack.pop() {
            for entry in std::fs::read_dir(&dir).expect("a directory of the repository") {
                let path = entry.expect("an entry").path();
                if path.is_dir() {
                    stack.push(path);
                } else if matches!(
                    path.extension().and_then(|e| e.to_str()),
                    Some("vert" | "frag" | "glsl" | "comp")
                ) {
                    let text = std::fs::read_to_string(&path).expect("a shader's text");
                    assert_eq!(check(&text), Ok(()), "{}", path.display());
                    checked += 1;
                }
            }
        }
        assert!(checked > 50, "{checked} shader files");
    }
}
