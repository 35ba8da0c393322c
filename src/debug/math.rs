//! GLSL's built-in functions (naga's `MathFunction`s) on the interpreter's values, in `f32`
//! as a GPU computes them: one operation at a time, sums left to right. Where GLSL leaves a
//! value undefined (NaN through `max`, `atan(0, 0)`, `pow` of a negative number, ...) the
//! result is the one lavapipe gives — Mesa's SPIR-V translation (its `atan`, `asin`, `asinh`
//! formulas), `fmin`/`fmax` returning the operand that is not NaN — and the caller is told
//! which function met such a value.

use naga::{MathFunction as M, Span, TypeInner};

use super::error::Failure;
use super::value::{Bits, Comp, Kind};

type Res<T> = std::result::Result<T, Failure>;

fn f(c: &Comp, g: impl Fn(f32) -> f32) -> Comp {
    Comp::new(Kind::F32, c.bits.map(|b| g(f32::from_bits(b)).to_bits()))
}

fn f2(a: &Comp, b: &Comp, g: impl Fn(f32, f32) -> f32) -> Comp {
    Comp::new(
        Kind::F32,
        a.bits
            .zip(&b.bits, |x, y| g(f32::from_bits(x), f32::from_bits(y)).to_bits()),
    )
}

fn f3(a: &Comp, b: &Comp, c: &Comp, g: impl Fn(f32, f32, f32) -> f32) -> Comp {
    Comp::new(
        Kind::F32,
        a.bits.zip3(&b.bits, &c.bits, |x, y, z| {
            g(f32::from_bits(x), f32::from_bits(y), f32::from_bits(z)).to_bits()
        }),
    )
}

/// `x` at component `k` of an operand that may be a scalar standing for every component.
fn at(v: &[Comp], k: usize) -> &Comp {
    if v.len() == 1 {
        &v[0]
    } else {
        &v[k]
    }
}

/// Σ a_k b_k, left to right.
fn dot(a: &[Comp], b: &[Comp]) -> Comp {
    let mut acc = f2(&a[0], &b[0], |x, y| x * y);
    for k in 1..a.len() {
        let p = f2(&a[k], &b[k], |x, y| x * y);
        acc = f2(&acc, &p, |x, y| x + y);
    }
    acc
}

/// Whether `test` holds for some lane of a component of `v`.
fn any(v: &[Comp], test: impl Fn(f32) -> bool) -> bool {
    v.iter().any(|c| match &c.bits {
        Bits::One(b) => test(f32::from_bits(*b)),
        Bits::Each(e) => e.iter().any(|b| test(f32::from_bits(*b))),
    })
}

/// Whether `test` holds for some lane of some pair of components of `a` and `b`.
fn any2(a: &[Comp], b: &[Comp], test: impl Fn(f32, f32) -> bool) -> bool {
    let n = a.len().max(b.len());
    (0..n).any(|k| {
        let (x, y) = (at(a, k), at(b, k));
        let lanes = x.bits.len().max(y.bits.len());
        (0..lanes).any(|l| test(x.f(l), y.f(l)))
    })
}

/// `min(max(x, lo), hi)` as Mesa lowers `clamp`: a NaN x gives lo (where `f32::clamp` keeps
/// NaN), a NaN bound gives x.
#[allow(clippy::manual_clamp)]
pub fn nan_clamp(x: f32, lo: f32, hi: f32) -> f32 {
    x.max(lo).min(hi)
}

/// `fsign`: 1, −1, or 0 for zero (and NaN).
fn sign(x: f32) -> f32 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// The natural logarithm as llvmpipe computes it: the positive quiet NaN below 0 and for NaN.
fn ln(x: f32) -> f32 {
    if x < 0.0 || x.is_nan() {
        f32::NAN
    } else {
        x.ln()
    }
}

/// Mesa's `atan` (22.3, `build_atan`): the range reduced to [0, 1], an odd polynomial of
/// degree 11 summed term by term, the reduction undone and the sign put back.
pub fn atan(y: f32) -> f32 {
    let a = y.abs();
    let x = a.min(1.0) / a.max(1.0);
    let x2 = x * x;
    let x3 = x2 * x;
    let x5 = x3 * x2;
    let x7 = x5 * x2;
    let x9 = x7 * x2;
    let x11 = x9 * x2;
    let terms = [
        x * 0.999_979_3,
        x3 * -0.332_675_64,
        x5 * 0.193_892_5,
        x7 * -0.117_350_32,
        x9 * 0.053_681_38,
        x11 * -0.012_132_321,
    ];
    let mut sum = terms[0];
    for t in &terms[1..] {
        sum += t;
    }
    let past_one = if 1.0 < a { 1.0f32 } else { 0.0 };
    let sum = past_one * (sum * -2.0 + std::f32::consts::FRAC_PI_2) + sum;
    sum * sign(y)
}

/// Mesa's `atan2` (`nir_atan2`): on the left half-plane the coordinates turn by π/2, and
/// |x| = |y| counts as tan = 1 (so `atan(0, 0)` is 3π/4, `atan(∞, ∞)` π/4).
pub fn atan2(y: f32, x: f32) -> f32 {
    let flip = 0.0 >= x;
    let (s, t) = if flip { (x.abs(), y) } else { (y, x.abs()) };
    let scale = if t.abs() >= 1e18 { 0.25f32 } else { 1.0 };
    let rcp = 1.0 / (t * scale);
    let tan = if x.abs() == y.abs() {
        1.0
    } else {
        (s * scale).abs() * rcp.abs()
    };
    let arc = (if flip { 1.0f32 } else { 0.0 }) * std::f32::consts::FRAC_PI_2 + atan(tan);
    if y.min(rcp) < 0.0 {
        -arc
    } else {
        arc
    }
}

/// Mesa's `asin` (`build_asin`): π/2 − √(1 − |x|)·(a polynomial), signed, with a rational
/// approximation below |x| = ½ when `piecewise` (`asin`; `acos` is π/2 − the other).
fn asin_of(x: f32, p0: f32, p1: f32, piecewise: bool) -> f32 {
    use std::f32::consts::{FRAC_PI_2, FRAC_PI_4};
    let a = x.abs();
    let p = a * p1 + p0;
    let tail = a * (a * p + (FRAC_PI_4 - 1.0)) + FRAC_PI_2;
    let far = sign(x) * (FRAC_PI_2 - (1.0 - a).sqrt() * tail);
    if piecewise && a < 0.5 {
        let x2 = x * x;
        let p = x2 * (x2 * (x2 * -8.656_363e-3 + -4.274_342_2e-2) + 1.666_658_7e-1);
        let q = x2 * -7.066_296_3e-1 + 1.0;
        return x * (p / q) + x;
    }
    far
}

/// One call: the function, its first argument `a` and the further ones.
struct Call<'a> {
    fun: M,
    a: &'a [Comp],
    b: Option<&'a [Comp]>,
    c: Option<&'a [Comp]>,
    span: Span,
}

impl Call<'_> {
    /// A further argument the function cannot go without.
    fn need(&self, x: Option<&[Comp]>) -> Res<Vec<Comp>> {
        x.map(<[Comp]>::to_vec).ok_or_else(|| Failure {
            message: format!("{} without its arguments", math_name(self.fun)),
            span: self.span,
        })
    }

    /// The kind of the first argument's components.
    fn kind(&self) -> Kind {
        self.a[0].kind
    }

    /// `g` on every component of the first argument.
    fn each(&self, g: &dyn Fn(f32) -> f32) -> Vec<Comp> {
        self.a.iter().map(|c| f(c, g)).collect()
    }

    /// The failure for a function the debugger does not run, naming it.
    fn unsupported(&self) -> Res<Vec<Comp>> {
        Err(Failure {
            message: format!("the debugger does not run {}", math_name(self.fun)),
            span: self.span,
        })
    }
}

/// Runs `fun` on `a` (of type `ty`) and the further arguments; what GLSL leaves undefined
/// on the values met is added to `undefined` (a sentence naming the function). The match picks
/// the function's family, each family has its own function.
pub fn math(
    fun: M,
    a: &[Comp],
    b: Option<&[Comp]>,
    c: Option<&[Comp]>,
    ty: &TypeInner,
    span: Span,
    undefined: &mut Vec<String>,
) -> Res<Vec<Comp>> {
    if a[0].kind == Kind::F32 {
        if let Some(why) = undefined_for(fun, a, b, c) {
            undefined.push(format!("{} {why}", math_name(fun)));
        }
    }
    let call = Call { fun, a, b, c, span };
    match fun {
        M::Abs | M::Sign | M::Min | M::Max | M::Clamp | M::Saturate | M::Step | M::SmoothStep | M::Mix | M::Fma => {
            common(&call)
        }
        M::Ceil | M::Floor | M::Round | M::Fract | M::Trunc | M::Modf | M::Frexp | M::Ldexp => parts(&call),
        M::Cos
        | M::Cosh
        | M::Sin
        | M::Sinh
        | M::Tan
        | M::Tanh
        | M::Acos
        | M::Asin
        | M::Atan
        | M::Asinh
        | M::Acosh
        | M::Atanh
        | M::Atan2
        | M::Radians
        | M::Degrees => trigonometry(&call),
        M::Exp | M::Exp2 | M::Log | M::Log2 | M::Pow | M::Sqrt | M::InverseSqrt => exponential(&call),
        M::Dot | M::Length | M::Distance | M::Normalize | M::Cross | M::Reflect | M::Refract | M::FaceForward => {
            geometric(&call)
        }
        M::Transpose | M::Determinant | M::Inverse | M::Outer => matrix(&call, ty),
        M::CountOneBits
        | M::ReverseBits
        | M::CountTrailingZeros
        | M::CountLeadingZeros
        | M::FirstTrailingBit
        | M::FirstLeadingBit
        | M::ExtractBits => integer(&call),
        M::Pack4x8unorm
        | M::Pack4x8snorm
        | M::Pack2x16unorm
        | M::Pack2x16snorm
        | M::Unpack4x8unorm
        | M::Unpack4x8snorm
        | M::Unpack2x16unorm
        | M::Unpack2x16snorm => packing(&call),
        _ => call.unsupported(),
    }
}

/// What GLSL leaves undefined for the float arguments met, if anything: "of NaN", "at (0, 0)",
/// ...
fn undefined_for(fun: M, a: &[Comp], b: Option<&[Comp]>, c: Option<&[Comp]>) -> Option<String> {
    let nan = |v: Option<&[Comp]>| v.is_some_and(|v| any(v, f32::is_nan));
    match fun {
        M::Min | M::Max | M::Clamp if nan(Some(a)) || nan(b) || nan(c) => Some("of NaN".to_owned()),
        M::Clamp if b.zip(c).is_some_and(|(l, h)| any2(l, h, |l, h| l > h)) => {
            Some("with its minimum above its maximum".to_owned())
        }
        M::Atan2 if b.is_some_and(|x| any2(a, x, |y, x| y == 0.0 && x == 0.0)) => Some("at (0, 0)".to_owned()),
        M::Pow if b.is_some_and(|y| any2(a, y, |x, y| x < 0.0 || (x == 0.0 && y <= 0.0))) => {
            Some("of a negative number, or of 0 to a power ≤ 0".to_owned())
        }
        M::Log | M::Log2 if any(a, |x| x <= 0.0) => Some("of a number ≤ 0".to_owned()),
        M::Sqrt if any(a, |x| x < 0.0) => Some("of a negative number".to_owned()),
        M::InverseSqrt if any(a, |x| x <= 0.0) => Some("of a number ≤ 0".to_owned()),
        M::Asin | M::Acos if any(a, |x| x.abs() > 1.0) => Some("of a number beyond ±1".to_owned()),
        M::Acosh if any(a, |x| x < 1.0) => Some("of a number below 1".to_owned()),
        M::Atanh if any(a, |x| x.abs() >= 1.0) => Some("of a number beyond (−1, 1)".to_owned()),
        M::SmoothStep if b.is_some_and(|e1| any2(a, e1, |e0, e1| e0 >= e1)) => Some("with edge0 ≥ edge1".to_owned()),
        _ => None,
    }
}

/// `abs`, `sign`, `min`, `max`, `clamp`, `step`, `smoothstep`, `mix` and `fma`.
fn common(call: &Call) -> Res<Vec<Comp>> {
    let (fun, a, b, c) = (call.fun, call.a, call.b, call.c);
    let kind = call.kind();
    let float = kind == Kind::F32;
    Ok(match fun {
        M::Abs if float => call.each(&f32::abs),
        M::Abs => a
            .iter()
            .map(|c| {
                Comp::new(
                    kind,
                    c.bits.map(|x| {
                        if kind == Kind::I32 {
                            (x as i32).wrapping_abs() as u32
                        } else {
                            x
                        }
                    }),
                )
            })
            .collect(),
        M::Sign if float => call.each(&sign),
        M::Sign => a
            .iter()
            .map(|c| Comp::new(kind, c.bits.map(|x| (x as i32).signum() as u32)))
            .collect(),
        M::Min | M::Max => {
            let b = call.need(b)?;
            let max = fun == M::Max;
            (0..a.len())
                .map(|k| {
                    let (x, y) = (&a[k], at(&b, k));
                    match kind {
                        // llvmpipe's `fmin`/`fmax` give the operand that is not NaN.
                        Kind::F32 => f2(x, y, |x, y| if max { x.max(y) } else { x.min(y) }),
                        Kind::I32 => Comp::new(
                            kind,
                            x.bits.zip(&y.bits, |p, q| {
                                let (p, q) = (p as i32, q as i32);
                                (if max { p.max(q) } else { p.min(q) }) as u32
                            }),
                        ),
                        _ => Comp::new(kind, x.bits.zip(&y.bits, |p, q| if max { p.max(q) } else { p.min(q) })),
                    }
                })
                .collect()
        }
        M::Clamp => {
            let (lo, hi) = (call.need(b)?, call.need(c)?);
            (0..a.len())
                .map(|k| match kind {
                    // min(max(x, lo), hi), as Mesa lowers it: a NaN x gives lo.
                    Kind::F32 => f3(&a[k], at(&lo, k), at(&hi, k), nan_clamp),
                    Kind::I32 => Comp::new(
                        kind,
                        a[k].bits.zip3(&at(&lo, k).bits, &at(&hi, k).bits, |x, l, h| {
                            (x as i32).max(l as i32).min(h as i32) as u32
                        }),
                    ),
                    _ => Comp::new(
                        kind,
                        a[k].bits
                            .zip3(&at(&lo, k).bits, &at(&hi, k).bits, |x, l, h| x.max(l).min(h)),
                    ),
                })
                .collect()
        }
        M::Saturate => call.each(&|x| nan_clamp(x, 0.0, 1.0)),
        M::Step => {
            // step(edge, x): 0 where x < edge.
            let b = call.need(b)?;
            let n = a.len().max(b.len());
            (0..n)
                .map(|k| f2(at(a, k), at(&b, k), |e, x| if x < e { 0.0 } else { 1.0 }))
                .collect()
        }
        M::SmoothStep => {
            let (b, x) = (call.need(b)?, call.need(c)?);
            let n = a.len().max(b.len()).max(x.len());
            (0..n)
                .map(|k| {
                    // Mesa's order: t·(t·(3 − 2t)), t saturated (a NaN t gives 0).
                    f3(at(a, k), at(&b, k), at(&x, k), |e0, e1, x| {
                        let t = nan_clamp((x - e0) / (e1 - e0), 0.0, 1.0);
                        t * (t * (3.0 - 2.0 * t))
                    })
                })
                .collect()
        }
        M::Mix => {
            let (b, t) = (call.need(b)?, call.need(c)?);
            if t[0].kind == Kind::Bool {
                (0..a.len())
                    .map(|k| {
                        Comp::new(
                            kind,
                            at(&t, k)
                                .bits
                                .zip3(&a[k].bits, &at(&b, k).bits, |t, x, y| if t != 0 { y } else { x }),
                        )
                    })
                    .collect()
            } else {
                // x·(1 − a) + y·a, as GLSL defines it.
                (0..a.len())
                    .map(|k| f3(&a[k], at(&b, k), at(&t, k), |x, y, t| x * (1.0 - t) + y * t))
                    .collect()
            }
        }
        M::Fma => {
            let (b, c) = (call.need(b)?, call.need(c)?);
            // Not fused: a multiply and an add, each rounded (GLSL leaves it open).
            (0..a.len())
                .map(|k| f3(&a[k], at(&b, k), at(&c, k), |x, y, z| x * y + z))
                .collect()
        }
        _ => return call.unsupported(),
    })
}

/// A float's parts: `ceil`, `floor`, `round`, `fract`, `trunc`, `modf`, `frexp` and `ldexp`.
fn parts(call: &Call) -> Res<Vec<Comp>> {
    let a = call.a;
    Ok(match call.fun {
        M::Ceil => call.each(&f32::ceil),
        M::Floor => call.each(&f32::floor),
        // GLSL's roundEven, as SPIR-V's RoundEven and naga's `round`.
        M::Round => call.each(&f32::round_ties_even),
        M::Fract => call.each(&|x| x - x.floor()),
        M::Trunc => call.each(&f32::trunc),
        M::Modf => {
            // A struct: the fractional parts, then the whole parts.
            let mut out: Vec<Comp> = a.iter().map(|c| f(c, |x| x - x.trunc())).collect();
            out.extend(a.iter().map(|c| f(c, f32::trunc)));
            out
        }
        M::Frexp => {
            let mut out: Vec<Comp> = a.iter().map(|c| f(c, |x| frexp(x).0)).collect();
            out.extend(
                a.iter()
                    .map(|c| Comp::new(Kind::I32, c.bits.map(|b| frexp(f32::from_bits(b)).1 as u32))),
            );
            out
        }
        M::Ldexp => {
            let e = call.need(call.b)?;
            (0..a.len())
                .map(|k| {
                    Comp::new(
                        Kind::F32,
                        a[k].bits.zip(&at(&e, k).bits, |x, e| {
                            (f32::from_bits(x) * 2f32.powi(e as i32)).to_bits()
                        }),
                    )
                })
                .collect()
        }
        _ => return call.unsupported(),
    })
}

/// The angle and trigonometry functions, by Mesa's formulas where lavapipe uses them.
fn trigonometry(call: &Call) -> Res<Vec<Comp>> {
    let a = call.a;
    Ok(match call.fun {
        M::Cos => call.each(&f32::cos),
        // Mesa's formulas: ½(eˣ ± e⁻ˣ), tanh over x clamped to ±10, asinh and acosh through
        // log(|x| + √(x² ± 1)) (so asinh(1e30) overflows to ∞), atanh as ½·log((1 + x)/(1 − x)).
        M::Cosh => call.each(&|x| (x.exp() + (-x).exp()) * 0.5),
        M::Sin => call.each(&f32::sin),
        M::Sinh => call.each(&|x| (x.exp() - (-x).exp()) * 0.5),
        M::Tan => call.each(&f32::tan),
        M::Tanh => call.each(&|x| {
            if 0.0 < x.abs() {
                let c = nan_clamp(x, -10.0, 10.0);
                let (p, n) = (c.exp(), (-c).exp());
                (p - n) / (p + n)
            } else {
                x
            }
        }),
        M::Acos => call.each(&|x| std::f32::consts::FRAC_PI_2 - asin_of(x, 0.081_324_63, -0.023_633_18, false)),
        M::Asin => call.each(&|x| asin_of(x, 0.086_566_724, -0.031_029_55, true)),
        M::Atan => call.each(&atan),
        M::Asinh => call.each(&|x| sign(x) * ln(x.abs() + (x * x + 1.0).sqrt())),
        M::Acosh => call.each(&|x| ln(x + (x * x - 1.0).sqrt())),
        // At 1 lavapipe gives NaN where the formula gives ∞ (measured; GLSL leaves it undefined).
        M::Atanh => call.each(&|x| {
            if x == 1.0 {
                f32::NAN
            } else {
                ln((x + 1.0) / (1.0 - x)) * 0.5
            }
        }),
        M::Atan2 => {
            let b = call.need(call.b)?;
            (0..a.len()).map(|k| f2(&a[k], at(&b, k), atan2)).collect()
        }
        M::Radians => call.each(&|x| x * (std::f32::consts::PI / 180.0)),
        M::Degrees => call.each(&|x| x * (180.0 / std::f32::consts::PI)),
        _ => return call.unsupported(),
    })
}

/// `exp`, `exp2`, `log`, `log2`, `pow`, `sqrt` and `inversesqrt`, as llvmpipe gives them
/// outside their domains.
fn exponential(call: &Call) -> Res<Vec<Comp>> {
    let a = call.a;
    Ok(match call.fun {
        M::Exp => call.each(&f32::exp),
        M::Exp2 => call.each(&f32::exp2),
        // llvmpipe's log gives the positive quiet NaN below 0 (and for NaN).
        M::Log => call.each(&ln),
        M::Log2 => call.each(&|x| if x < 0.0 || x.is_nan() { f32::NAN } else { x.log2() }),
        M::Pow => {
            // llvmpipe: 0 for x = 0, else 2^(y·log2 x) (NaN for x < 0).
            let b = call.need(call.b)?;
            (0..a.len())
                .map(|k| {
                    f2(&a[k], at(&b, k), |x, y| {
                        if x == 0.0 {
                            0.0
                        } else if x < 0.0 {
                            f32::NAN
                        } else {
                            x.powf(y)
                        }
                    })
                })
                .collect()
        }
        M::Sqrt => call.each(&f32::sqrt),
        M::InverseSqrt => call.each(&|x| 1.0 / x.sqrt()),
        _ => return call.unsupported(),
    })
}

/// The geometric functions on vectors: `dot`, `length`, `distance`, `normalize`, `cross`,
/// `reflect`, `refract` and `faceforward`, one operation at a time.
fn geometric(call: &Call) -> Res<Vec<Comp>> {
    let (a, b, c) = (call.a, call.b, call.c);
    Ok(match call.fun {
        M::Dot => vec![dot(a, &call.need(b)?)],
        M::Length => {
            let d = dot(a, a);
            vec![f(&d, f32::sqrt)]
        }
        M::Distance => {
            let b = call.need(b)?;
            let diff: Vec<Comp> = (0..a.len()).map(|k| f2(&a[k], &b[k], |x, y| x - y)).collect();
            vec![f(&dot(&diff, &diff), f32::sqrt)]
        }
        M::Normalize => {
            // v / sqrt(dot(v, v)): a division per component.
            let len = f(&dot(a, a), f32::sqrt);
            a.iter().map(|c| f2(c, &len, |x, l| x / l)).collect()
        }
        M::Cross => {
            let b = call.need(b)?;
            let m = |i: usize, j: usize| f2(&a[i], &b[j], |x, y| x * y);
            vec![
                f2(&m(1, 2), &m(2, 1), |x, y| x - y),
                f2(&m(2, 0), &m(0, 2), |x, y| x - y),
                f2(&m(0, 1), &m(1, 0), |x, y| x - y),
            ]
        }
        M::Reflect => {
            // I − 2·dot(N, I)·N.
            let n = call.need(b)?;
            let d = dot(&n, a);
            (0..a.len())
                .map(|k| f3(&a[k], &n[k], &d, |i, n, d| i - 2.0 * d * n))
                .collect()
        }
        M::Refract => {
            let n = call.need(b)?;
            let eta = call.need(c)?;
            let d = dot(&n, a);
            let k = f2(&d, &eta[0], |d, e| 1.0 - e * e * (1.0 - d * d));
            (0..a.len())
                .map(|j| {
                    Comp::new(
                        Kind::F32,
                        bits(
                            (0..lanes(&[&a[j], &n[j], &d, &k, &eta[0]]))
                                .map(|l| {
                                    let (i, nn, dd, kk, e) = (a[j].f(l), n[j].f(l), d.f(l), k.f(l), eta[0].f(l));
                                    let r = if kk < 0.0 {
                                        0.0
                                    } else {
                                        e * i - (e * dd + kk.sqrt()) * nn
                                    };
                                    r.to_bits()
                                })
                                .collect(),
                        ),
                    )
                })
                .collect()
        }
        M::FaceForward => {
            // faceforward(N, I, Nref): N if dot(Nref, I) < 0, else −N.
            let (i, nref) = (call.need(b)?, call.need(c)?);
            let d = dot(&nref, &i);
            a.iter()
                .map(|n| f2(n, &d, |n, d| if d < 0.0 { n } else { -n }))
                .collect()
        }
        _ => return call.unsupported(),
    })
}

/// The matrix functions on `a` of type `ty`: `transpose`, `determinant`, `inverse` and
/// `outerProduct`.
fn matrix(call: &Call, ty: &TypeInner) -> Res<Vec<Comp>> {
    let (fun, a, span) = (call.fun, call.a, call.span);
    Ok(match fun {
        M::Transpose => {
            let (rows, cols) = matrix_shape(ty, fun, span)?;
            let mut out = Vec::with_capacity(a.len());
            for r in 0..rows {
                for c in 0..cols {
                    out.push(a[c * rows + r].clone());
                }
            }
            out
        }
        M::Determinant => {
            let (n, _) = matrix_shape(ty, fun, span)?;
            let lanes = lanes(&a.iter().collect::<Vec<_>>());
            let v: Vec<f32> = (0..lanes)
                .map(|l| {
                    let m: Vec<f64> = a.iter().map(|c| f64::from(c.f(l))).collect();
                    det(&m, n) as f32
                })
                .collect();
            vec![Comp::new(Kind::F32, bits(v.into_iter().map(f32::to_bits).collect()))]
        }
        M::Inverse => {
            let (n, _) = matrix_shape(ty, fun, span)?;
            let lanes = lanes(&a.iter().collect::<Vec<_>>());
            let mut out: Vec<Vec<u32>> = vec![Vec::with_capacity(lanes); n * n];
            for l in 0..lanes {
                let m: Vec<f64> = a.iter().map(|c| f64::from(c.f(l))).collect();
                for (k, v) in inverse(&m, n).into_iter().enumerate() {
                    out[k].push((v as f32).to_bits());
                }
            }
            out.into_iter().map(|b| Comp::new(Kind::F32, bits(b))).collect()
        }
        M::Outer => {
            let b = call.need(call.b)?;
            let mut out = Vec::with_capacity(a.len() * b.len());
            for column in &b {
                for row in a {
                    out.push(f2(row, column, |x, y| x * y));
                }
            }
            out
        }
        _ => return call.unsupported(),
    })
}

/// The integer functions on bits: `bitCount`, `bitfieldReverse`, `findLSB`, `findMSB`,
/// `bitfieldExtract`, and naga's counts of leading and trailing zeros.
fn integer(call: &Call) -> Res<Vec<Comp>> {
    let (a, kind) = (call.a, call.kind());
    Ok(match call.fun {
        M::CountOneBits => a.iter().map(|c| Comp::new(kind, c.bits.map(u32::count_ones))).collect(),
        M::ReverseBits => a
            .iter()
            .map(|c| Comp::new(kind, c.bits.map(u32::reverse_bits)))
            .collect(),
        M::CountTrailingZeros => a
            .iter()
            .map(|c| Comp::new(kind, c.bits.map(u32::trailing_zeros)))
            .collect(),
        M::CountLeadingZeros => a
            .iter()
            .map(|c| Comp::new(kind, c.bits.map(u32::leading_zeros)))
            .collect(),
        M::FirstTrailingBit => a
            .iter()
            .map(|c| Comp::new(kind, c.bits.map(|x| if x == 0 { u32::MAX } else { x.trailing_zeros() })))
            .collect(),
        M::FirstLeadingBit => a
            .iter()
            .map(|c| {
                Comp::new(
                    kind,
                    c.bits.map(|x| {
                        // findMSB: for a negative int, the highest 0 bit.
                        let v = if kind == Kind::I32 && (x as i32) < 0 { !x } else { x };
                        if v == 0 {
                            u32::MAX
                        } else {
                            31 - v.leading_zeros()
                        }
                    }),
                )
            })
            .collect(),
        M::ExtractBits => {
            let (offset, count) = (call.need(call.b)?, call.need(call.c)?);
            let (o, n) = (offset[0].bits.at(0).min(32), count[0].bits.at(0));
            let n = n.min(32 - o);
            a.iter()
                .map(|c| {
                    Comp::new(
                        kind,
                        c.bits.map(|x| {
                            if n == 0 {
                                return 0;
                            }
                            let v = (x >> o) & if n == 32 { u32::MAX } else { (1 << n) - 1 };
                            if kind == Kind::I32 && n < 32 && v >> (n - 1) & 1 == 1 {
                                v | !((1u32 << n) - 1)
                            } else {
                                v
                            }
                        }),
                    )
                })
                .collect()
        }
        _ => return call.unsupported(),
    })
}

/// `packUnorm4x8` and its kin, and their inverses.
fn packing(call: &Call) -> Res<Vec<Comp>> {
    let (fun, a) = (call.fun, call.a);
    Ok(match fun {
        M::Pack4x8unorm | M::Pack4x8snorm | M::Pack2x16unorm | M::Pack2x16snorm => {
            let lanes = lanes(&a.iter().collect::<Vec<_>>());
            let (n, bits) = if matches!(fun, M::Pack4x8unorm | M::Pack4x8snorm) {
                (4, 8)
            } else {
                (2, 16)
            };
            let signed = matches!(fun, M::Pack4x8snorm | M::Pack2x16snorm);
            let max = ((1u32 << (bits - u32::from(signed))) - 1) as f32;
            let v: Vec<u32> = (0..lanes)
                .map(|l| {
                    (0..n).fold(0u32, |acc, k| {
                        let x = a[k].f(l);
                        let q = if signed {
                            (x.clamp(-1.0, 1.0) * max).round() as i32 as u32
                        } else {
                            (x.clamp(0.0, 1.0) * max).round() as u32
                        };
                        acc | ((q & ((1u32 << bits) - 1)) << (k as u32 * bits))
                    })
                })
                .collect();
            vec![Comp::new(Kind::U32, bits_of(v))]
        }
        M::Unpack4x8unorm | M::Unpack4x8snorm | M::Unpack2x16unorm | M::Unpack2x16snorm => {
            let (n, width) = if matches!(fun, M::Unpack4x8unorm | M::Unpack4x8snorm) {
                (4u32, 8u32)
            } else {
                (2, 16)
            };
            let signed = matches!(fun, M::Unpack4x8snorm | M::Unpack2x16snorm);
            let max = ((1u32 << (width - u32::from(signed))) - 1) as f32;
            (0..n)
                .map(|k| {
                    Comp::new(
                        Kind::F32,
                        a[0].bits.map(|x| {
                            let q = (x >> (k * width)) & ((1u32 << width) - 1);
                            let v = if signed {
                                let s = ((q << (32 - width)) as i32) >> (32 - width);
                                (s as f32 / max).max(-1.0)
                            } else {
                                q as f32 / max
                            };
                            v.to_bits()
                        }),
                    )
                })
                .collect()
        }
        _ => return call.unsupported(),
    })
}

/// `x = m · 2^e` with `m` in [0.5, 1) (0 for 0).
fn frexp(x: f32) -> (f32, i32) {
    if x == 0.0 || !x.is_finite() {
        return (x, 0);
    }
    let e = x.abs().log2().floor() as i32 + 1;
    let m = x / 2f32.powi(e);
    // Correct a rounding of log2 near powers of two.
    if m.abs() >= 1.0 {
        (m / 2.0, e + 1)
    } else if m.abs() < 0.5 {
        (m * 2.0, e - 1)
    } else {
        (m, e)
    }
}

fn bits_of(v: Vec<u32>) -> Bits {
    bits(v)
}

/// Per-lane bits, as one value when there is one lane's worth (every input was shared).
fn bits(v: Vec<u32>) -> Bits {
    if v.len() == 1 {
        Bits::One(v[0])
    } else {
        Bits::Each(v)
    }
}

fn lanes(comps: &[&Comp]) -> usize {
    comps.iter().map(|c| c.bits.len()).max().unwrap_or(1)
}

fn matrix_shape(ty: &TypeInner, fun: M, span: Span) -> Res<(usize, usize)> {
    match ty {
        TypeInner::Matrix { columns, rows, .. } => Ok((*rows as usize, *columns as usize)),
        _ => Err(Failure {
            message: format!("{} of something that is not a matrix", math_name(fun)),
            span,
        }),
    }
}

/// The determinant of an n×n column-major matrix (n ≤ 4), by cofactors.
fn det(m: &[f64], n: usize) -> f64 {
    let at = |r: usize, c: usize| m[c * n + r];
    match n {
        1 => m[0],
        2 => at(0, 0) * at(1, 1) - at(0, 1) * at(1, 0),
        _ => {
            let mut sum = 0.0;
            for c in 0..n {
                let mut minor = Vec::with_capacity((n - 1) * (n - 1));
                for cc in 0..n {
                    if cc == c {
                        continue;
                    }
                    for r in 1..n {
                        minor.push(at(r, cc));
                    }
                }
                let sign = if c % 2 == 0 { 1.0 } else { -1.0 };
                sum += sign * at(0, c) * det(&minor, n - 1);
            }
            sum
        }
    }
}

/// The inverse of an n×n column-major matrix, by the adjugate (as GLSL's `inverse`).
fn inverse(m: &[f64], n: usize) -> Vec<f64> {
    let d = det(m, n);
    let at = |r: usize, c: usize| m[c * n + r];
    let mut out = vec![0.0; n * n];
    for r in 0..n {
        for c in 0..n {
            // Cofactor of (r, c), placed at (c, r).
            let mut minor = Vec::with_capacity((n - 1) * (n - 1));
            for cc in 0..n {
                if cc == c {
                    continue;
                }
                for rr in 0..n {
                    if rr == r {
                        continue;
                    }
                    minor.push(at(rr, cc));
                }
            }
            let sign = if (r + c) % 2 == 0 { 1.0 } else { -1.0 };
            let cof = if n == 1 { 1.0 } else { sign * det(&minor, n - 1) };
            out[r * n + c] = cof / d;
        }
    }
    out
}

/// A math function by its GLSL name, for messages.
pub fn math_name(fun: M) -> String {
    let glsl = match fun {
        M::CountOneBits => "bitCount",
        M::ReverseBits => "bitfieldReverse",
        M::ExtractBits => "bitfieldExtract",
        M::InsertBits => "bitfieldInsert",
        M::FirstTrailingBit => "findLSB",
        M::FirstLeadingBit => "findMSB",
        M::QuantizeToF16 => "quantizeToF16",
        M::Pack2x16float => "packHalf2x16",
        M::Unpack2x16float => "unpackHalf2x16",
        M::Saturate => "clamp(x, 0, 1)",
        M::InverseSqrt => "inversesqrt",
        M::Outer => "outerProduct",
        M::Fma => "fma",
        M::SmoothStep => "smoothstep",
        M::Atan2 => "atan(y, x)",
        _ => "",
    };
    if !glsl.is_empty() {
        return format!("`{glsl}`");
    }
    let debug = format!("{fun:?}");
    let mut out = String::new();
    for (i, ch) in debug.chars().enumerate() {
        if i == 0 {
            out.extend(ch.to_lowercase());
        } else {
            out.push(ch);
        }
    }
    format!("`{out}`")
}
