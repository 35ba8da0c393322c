//! Values of the interpreter: every GLSL value flattened into scalar components (a `vec3` is 3,
//! a `mat4` 16 in column order, a struct its members' in turn), each held for all the lanes
//! run together — one number when every lane has the same (uniforms, constants), one per lane
//! otherwise — so that a uniform subexpression is computed once and a vertex shader runs over
//! a whole mesh in one pass.

use naga::{Handle, Module, ScalarKind, TypeInner};

/// The kind of one scalar component.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// `float`.
    F32,
    /// `int`.
    I32,
    /// `uint`.
    U32,
    /// `bool`.
    Bool,
}

impl Kind {
    /// The kind of a naga scalar; `None` for widths other than 32 bits (and bool).
    pub fn of(scalar: naga::Scalar) -> Option<Kind> {
        match (scalar.kind, scalar.width) {
            (ScalarKind::Float, 4) => Some(Kind::F32),
            (ScalarKind::Sint, 4) => Some(Kind::I32),
            (ScalarKind::Uint, 4) => Some(Kind::U32),
            (ScalarKind::Bool, _) => Some(Kind::Bool),
            _ => None,
        }
    }
}

/// One component's 32 bits (an `f32`'s bits, an `i32`'s, a `u32`, a bool as 0/1), for all
/// lanes at once or one per lane.
#[derive(Clone, Debug, PartialEq)]
pub enum Bits {
    /// The same for every lane.
    One(u32),
    /// One per lane.
    Each(Vec<u32>),
}

impl Bits {
    /// Lane `i`'s bits.
    #[inline]
    pub fn at(&self, i: usize) -> u32 {
        match self {
            Bits::One(v) => *v,
            Bits::Each(v) => v[i],
        }
    }

    /// How many values it holds (1 or the lanes).
    pub fn len(&self) -> usize {
        match self {
            Bits::One(_) => 1,
            Bits::Each(v) => v.len(),
        }
    }

    /// Whether it holds no value (never: kept for clippy's `len` rule).
    pub fn is_empty(&self) -> bool {
        false
    }

    /// `f` of each lane: one value when `self` is one.
    #[inline]
    pub fn map(&self, f: impl Fn(u32) -> u32) -> Bits {
        match self {
            Bits::One(v) => Bits::One(f(*v)),
            Bits::Each(v) => Bits::Each(v.iter().map(|&x| f(x)).collect()),
        }
    }

    /// `f` of each lane of `self` and `other`: one value when both are.
    #[inline]
    pub fn zip(&self, other: &Bits, f: impl Fn(u32, u32) -> u32) -> Bits {
        match (self, other) {
            (Bits::One(a), Bits::One(b)) => Bits::One(f(*a, *b)),
            (Bits::Each(a), Bits::One(b)) => Bits::Each(a.iter().map(|&x| f(x, *b)).collect()),
            (Bits::One(a), Bits::Each(b)) => Bits::Each(b.iter().map(|&y| f(*a, y)).collect()),
            (Bits::Each(a), Bits::Each(b)) => Bits::Each(a.iter().zip(b).map(|(&x, &y)| f(x, y)).collect()),
        }
    }

    /// `f` of each lane of three: one value when all are.
    pub fn zip3(&self, b: &Bits, c: &Bits, f: impl Fn(u32, u32, u32) -> u32) -> Bits {
        if let (Bits::One(x), Bits::One(y), Bits::One(z)) = (self, b, c) {
            return Bits::One(f(*x, *y, *z));
        }
        let n = self.len().max(b.len()).max(c.len());
        Bits::Each((0..n).map(|i| f(self.at(i), b.at(i), c.at(i))).collect())
    }

    /// Per lane: `a` where `take` is set, else `self` (a masked store).
    pub fn blend(&self, new: &Bits, take: &[bool]) -> Bits {
        if take.iter().all(|&t| t) {
            return new.clone();
        }
        if !take.iter().any(|&t| t) {
            return self.clone();
        }
        Bits::Each(
            take.iter()
                .enumerate()
                .map(|(i, &t)| if t { new.at(i) } else { self.at(i) })
                .collect(),
        )
    }
}

/// One scalar component: its kind and its bits.
#[derive(Clone, Debug, PartialEq)]
pub struct Comp {
    /// Its kind.
    pub kind: Kind,
    /// Its bits.
    pub bits: Bits,
}

impl Comp {
    /// A float, the same in every lane.
    pub fn f32(v: f32) -> Comp {
        Comp {
            kind: Kind::F32,
            bits: Bits::One(v.to_bits()),
        }
    }

    /// Floats, one per lane.
    pub fn f32s(v: impl IntoIterator<Item = f32>) -> Comp {
        Comp {
            kind: Kind::F32,
            bits: Bits::Each(v.into_iter().map(f32::to_bits).collect()),
        }
    }

    /// A component of `kind` with `bits`.
    pub fn new(kind: Kind, bits: Bits) -> Comp {
        Comp { kind, bits }
    }

    /// Lane `i` as a float (its bits read as its kind).
    pub fn f(&self, i: usize) -> f32 {
        f32::from_bits(self.bits.at(i))
    }

    /// Lane `i` as a number for people (bool as 0/1).
    pub fn number(&self, i: usize) -> f64 {
        let b = self.bits.at(i);
        match self.kind {
            Kind::F32 => f64::from(f32::from_bits(b)),
            Kind::I32 => f64::from(b as i32),
            Kind::U32 => f64::from(b),
            Kind::Bool => f64::from(b & 1),
        }
    }
}

/// A value: data (flattened components), or what GLSL cannot store (a pointer, a texture or a
/// sampler).
#[derive(Clone, Debug)]
pub enum Val {
    /// Scalar components in order.
    Data(Vec<Comp>),
    /// Where a variable (or part of one) lives.
    Ptr(Ptr),
    /// A texture (its global variable).
    Image(Handle<naga::GlobalVariable>),
    /// A sampler (its global variable).
    Sampler(Handle<naga::GlobalVariable>),
}

/// The variable a pointer points into.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Root {
    /// A local of the call frame at this depth.
    Local(usize, Handle<naga::LocalVariable>),
    /// A global.
    Global(Handle<naga::GlobalVariable>),
    /// A uniform block, read from the bound buffer's bytes: its pointers' offsets are in bytes,
    /// as the GPU addresses it (an index past an array's end reads what lies there).
    Buffer(Handle<naga::GlobalVariable>),
}

/// Where in its variable a pointer starts, in components (in bytes for a [`Root::Buffer`]).
#[derive(Clone, Debug, PartialEq)]
pub enum Offset {
    /// The same in every lane.
    Fixed(usize),
    /// One per lane (a dynamic index that differs between lanes).
    Each(Vec<usize>),
}

/// A pointer: a variable, the first component, how many, and how people name it
/// (`lights[1].position.x`).
#[derive(Clone, Debug)]
pub struct Ptr {
    /// The variable.
    pub root: Root,
    /// The first component.
    pub offset: Offset,
    /// The components it spans.
    pub len: usize,
    /// Its name in the source.
    pub name: String,
}

/// How many scalar components a value of `inner` flattens to.
pub fn count(module: &Module, inner: &TypeInner) -> usize {
    match inner {
        TypeInner::Scalar(_) | TypeInner::Atomic(_) => 1,
        TypeInner::Vector { size, .. } => *size as usize,
        TypeInner::Matrix { columns, rows, .. } => *columns as usize * *rows as usize,
        TypeInner::Array {
            base,
            size: naga::ArraySize::Constant(n),
            ..
        } => n.get() as usize * count(module, &module.types[*base].inner),
        TypeInner::Struct { members, .. } => members.iter().map(|m| count(module, &module.types[m.ty].inner)).sum(),
        _ => 0,
    }
}

/// The kinds of `inner`'s components, in order; `None` for a type the interpreter does not
/// hold (f16, f64, runtime-sized arrays, ...).
pub fn kinds(module: &Module, inner: &TypeInner) -> Option<Vec<Kind>> {
    Some(match inner {
        TypeInner::Scalar(s) | TypeInner::Atomic(s) => vec![Kind::of(*s)?],
        TypeInner::Vector { size, scalar } => vec![Kind::of(*scalar)?; *size as usize],
        TypeInner::Matrix { columns, rows, scalar } => vec![Kind::of(*scalar)?; *columns as usize * *rows as usize],
        TypeInner::Array { base, size, .. } => {
            let naga::ArraySize::Constant(n) = size else {
                return None;
            };
            let one = kinds(module, &module.types[*base].inner)?;
            let mut out = Vec::with_capacity(one.len() * n.get() as usize);
            for _ in 0..n.get() {
                out.extend_from_slice(&one);
            }
            out
        }
        TypeInner::Struct { members, .. } => {
            let mut out = Vec::new();
            for m in members {
                out.extend(kinds(module, &module.types[m.ty].inner)?);
            }
            out
        }
        _ => return None,
    })
}

/// The zero value of a type (`ZeroValue`).
pub fn zero(module: &Module, inner: &TypeInner) -> Option<Vec<Comp>> {
    Some(
        kinds(module, inner)?
            .into_iter()
            .map(|kind| Comp::new(kind, Bits::One(0)))
            .collect(),
    )
}

/// Where element or member `index` of `inner` starts and how many components it has.
pub fn part(module: &Module, inner: &TypeInner, index: usize) -> Option<(usize, usize, TypeInner)> {
    match inner {
        TypeInner::Vector { scalar, .. } => Some((index, 1, TypeInner::Scalar(*scalar))),
        TypeInner::Matrix { rows, scalar, .. } => Some((
            index * *rows as usize,
            *rows as usize,
            TypeInner::Vector {
                size: *rows,
                scalar: *scalar,
            },
        )),
        TypeInner::Array { base, .. } => {
            let elem = module.types[*base].inner.clone();
            let n = count(module, &elem);
            Some((index * n, n, elem))
        }
        TypeInner::Struct { members, .. } => {
            let mut at = 0;
            for (i, m) in members.iter().enumerate() {
                let n = count(module, &module.types[m.ty].inner);
                if i == index {
                    return Some((at, n, module.types[m.ty].inner.clone()));
                }
                at += n;
            }
            None
        }
        _ => None,
    }
}

/// Where element or member `index` of `inner` starts in a uniform block's bytes (naga's
/// std140 layout, as [`read_bytes`] reads it), and its type.
pub fn byte_part(module: &Module, inner: &TypeInner, index: u32) -> Option<(u32, TypeInner)> {
    match inner {
        TypeInner::Vector { scalar, .. } => Some((index.wrapping_mul(4), TypeInner::Scalar(*scalar))),
        TypeInner::Matrix { rows, scalar, .. } => Some((
            index.wrapping_mul(column_stride(*rows)),
            TypeInner::Vector {
                size: *rows,
                scalar: *scalar,
            },
        )),
        TypeInner::Array { base, stride, .. } => Some((index.wrapping_mul(*stride), module.types[*base].inner.clone())),
        TypeInner::Struct { members, .. } => members
            .get(index as usize)
            .map(|m| (m.offset, module.types[m.ty].inner.clone())),
        _ => None,
    }
}

/// The bytes between a matrix's columns in a uniform block: a column is aligned as a vector
/// of `rows`, 8 bytes for two, 16 for three or four.
fn column_stride(rows: naga::VectorSize) -> u32 {
    if rows as usize == 2 {
        8
    } else {
        16
    }
}

/// How many elements a dynamically indexed `inner` has (for clamping the index, as wgpu's
/// bounds-check policy does).
pub fn elements(inner: &TypeInner) -> Option<usize> {
    match inner {
        TypeInner::Vector { size, .. } => Some(*size as usize),
        TypeInner::Matrix { columns, .. } => Some(*columns as usize),
        TypeInner::Array {
            size: naga::ArraySize::Constant(n),
            ..
        } => Some(n.get() as usize),
        _ => None,
    }
}

/// The name of member `index` for a pointer's name (`.x`, `[2]`, `.position`).
pub fn part_name(inner: &TypeInner, index: usize, members: Option<&[naga::StructMember]>) -> String {
    match inner {
        TypeInner::Vector { .. } => format!(".{}", ["x", "y", "z", "w"].get(index).copied().unwrap_or("?")),
        TypeInner::Struct { .. } => match members.and_then(|m| m.get(index)).and_then(|m| m.name.as_deref()) {
            Some(name) => format!(".{name}"),
            None => format!(".{index}"),
        },
        _ => format!("[{index}]"),
    }
}

/// Reads a value of type `inner` laid out as naga laid it out (a uniform block's std140
/// offsets and strides) from `bytes` at byte `offset`. Addresses wrap at 32 bits and a word
/// past the end reads as zero, as the GPU's robust buffer access reads a uniform buffer.
pub fn read_bytes(module: &Module, inner: &TypeInner, bytes: &[u8], offset: u32, out: &mut Vec<Comp>) -> Option<()> {
    let word = |at: u32| -> u32 {
        let at = at as usize;
        bytes
            .get(at..at.saturating_add(4))
            .map_or(0, |b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    };
    match inner {
        TypeInner::Scalar(s) | TypeInner::Atomic(s) => {
            let kind = Kind::of(*s)?;
            let mut v = word(offset);
            if kind == Kind::Bool {
                v = u32::from(v != 0);
            }
            out.push(Comp::new(kind, Bits::One(v)));
        }
        TypeInner::Vector { size, scalar } => {
            let kind = Kind::of(*scalar)?;
            for i in 0..*size as u32 {
                let mut v = word(offset.wrapping_add(4 * i));
                if kind == Kind::Bool {
                    v = u32::from(v != 0);
                }
                out.push(Comp::new(kind, Bits::One(v)));
            }
        }
        TypeInner::Matrix { columns, rows, scalar } => {
            let kind = Kind::of(*scalar)?;
            let stride = column_stride(*rows);
            for c in 0..*columns as u32 {
                for r in 0..*rows as u32 {
                    let at = offset.wrapping_add(c * stride).wrapping_add(4 * r);
                    out.push(Comp::new(kind, Bits::One(word(at))));
                }
            }
        }
        TypeInner::Array { base, size, stride } => {
            let naga::ArraySize::Constant(n) = size else {
                return None;
            };
            for i in 0..n.get() {
                read_bytes(
                    module,
                    &module.types[*base].inner,
                    bytes,
                    offset.wrapping_add(i.wrapping_mul(*stride)),
                    out,
                )?;
            }
        }
        TypeInner::Struct { members, .. } => {
            for m in members {
                read_bytes(
                    module,
                    &module.types[m.ty].inner,
                    bytes,
                    offset.wrapping_add(m.offset),
                    out,
                )?;
            }
        }
        _ => return None,
    }
    Some(())
}

/// The components of lane `lane` as numbers for people (bools as 0/1).
pub fn numbers(comps: &[Comp], lane: usize) -> Vec<f64> {
    comps.iter().map(|c| c.number(lane)).collect()
}
