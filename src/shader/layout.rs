//! The std140 side of the uniform interface: the layout naga reflects for a block
//! ([`BlockLayout`], [`MemberLayout`], [`MemberType`]), the Rust side ([`UniformBlock`],
//! [`uniform_block!`](crate::uniform_block), [`GlslType`]), the typed check between them, and
//! setting members by GLSL name (`--set colors[1]=…`).

use crate::error::{Error, Result};

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
    pub(crate) fn of(module: &naga::Module, inner: &naga::TypeInner) -> Option<MemberType> {
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
    set_member_bytes(bytemuck::bytes_of_mut(value), block, name, values)
}

/// [`set_member`] on the bytes of a block laid out as `block` (a
/// [`ParamBlock`](crate::render::ParamBlock), which has no Rust struct).
pub fn set_member_bytes(bytes: &mut [u8], block: &BlockLayout, name: &str, values: &[f32]) -> Result<()> {
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
    if end > bytes.len() {
        return Err(Error::Layout(format!(
            "member `{}` lies outside the block's bytes",
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
mod layout_tests {
    use super::*;
    use crate::shader::{compile_text, embedded_source, ShaderSource};
    use naga::ShaderStage;

    /// `PhongParams` as a Rust struct (the lab fills it by name now, with no struct).
    #[repr(C)]
    #[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
    struct PhongUniforms {
        light_position: [f32; 3],
        ka: f32,
        ambient_color: [f32; 3],
        kd: f32,
        diffuse_color: [f32; 3],
        ks: f32,
        specular_color: [f32; 3],
        shininess: f32,
    }
    crate::uniform_block!(PhongUniforms, "PhongParams", {
        light_position: "lightPosition",
        ka: "Ka",
        ambient_color: "ambientColor",
        kd: "Kd",
        diffuse_color: "diffuseColor",
        ks: "Ks",
        specular_color: "specularColor",
        shininess: "shininess",
    });

    /// Every member of `block` is fed by the lab's parameter of that name, with as many values
    /// (what [`ParamBlock`](crate::render::ParamBlock) checks when the lab is built).
    fn fed_by_params(block: &BlockLayout, lab: &crate::lab::LabEntry) {
        let params = (lab.params)();
        for member in &block.members {
            let value = params
                .get(&member.name)
                .unwrap_or_else(|| panic!("{}: no parameter feeds `{}`", lab.info.name, member.declaration()));
            assert_eq!(
                value.len(),
                member.components,
                "{}: `{}`",
                lab.info.name,
                member.declaration()
            );
        }
    }

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
        use crate::course::common::TransformUniforms;
        use crate::course::{DISPLACEMENT, PHONG};
        let block = |file: &str, name: &str| {
            let shader = ShaderSource::Embedded.compile(file).unwrap();
            shader
                .uniform_block(name)
                .unwrap_or_else(|| panic!("{file} declares {name}"))
        };
        // Phong's and displacement's blocks are filled by name: every member has its parameter
        // (displacement's `time` is the clock wrapped by the lab's hook).
        for frag in ["phong.frag", "phong_flat.frag", "phong_blinn.frag"] {
            let params = block(frag, "PhongParams");
            check_layout::<PhongUniforms>("PhongUniforms", &params).unwrap();
            fed_by_params(&params, PHONG);
        }
        let params = block("phong_gouraud.vert", "PhongParams");
        check_layout::<PhongUniforms>("PhongUniforms", &params).unwrap();
        fed_by_params(&params, PHONG);
        fed_by_params(&block("displacement.vert", "DisplacementParams"), DISPLACEMENT);
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
