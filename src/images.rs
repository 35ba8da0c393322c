//! The procedural textures of SPEC §0.1, their mipmaps, and image files.
//!
//! Every image is RGBA8 with alpha 255. Texel (i, j): i = column (s direction), j = row; row
//! j = 0 is the first row in [`Image::rgba`] and the first row uploaded, which GL samples at
//! t ≈ 0 and wgpu at v ≈ 0: a port uploads these bytes as they are, no flip. Cube maps have
//! 6 layers, concatenated in the order +X, −X, +Y, −Y, +Z, −Z (wgpu's cube layer order).

use crate::error::{Error, Result};
use std::path::Path;

/// An RGBA8 image with one or more layers (6 for a cube map), rows first-uploaded first.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Image {
    /// Texels per row.
    pub width: u32,
    /// Rows per layer.
    pub height: u32,
    /// Layers (1 for a 2D texture, 6 for a cube map in the order +X, −X, +Y, −Y, +Z, −Z).
    pub layers: u32,
    /// `width * height * layers * 4` bytes: layer by layer, row j = 0 first, RGBA per texel.
    pub rgba: Vec<u8>,
}

impl Image {
    /// Builds an image from `texel(layer, i, j) -> [r, g, b, a]`, i = column, j = row.
    pub fn from_fn(width: u32, height: u32, layers: u32, mut texel: impl FnMut(u32, u32, u32) -> [u8; 4]) -> Image {
        let mut rgba = Vec::with_capacity(width as usize * height as usize * layers as usize * 4);
        for layer in 0..layers {
            for j in 0..height {
                for i in 0..width {
                    rgba.extend_from_slice(&texel(layer, i, j));
                }
            }
        }
        Image {
            width,
            height,
            layers,
            rgba,
        }
    }

    /// The texel at column `i`, row `j` of `layer`, or `None` outside the image.
    pub fn texel(&self, layer: u32, i: u32, j: u32) -> Option<[u8; 4]> {
        if layer >= self.layers || i >= self.width || j >= self.height {
            return None;
        }
        let at = self.offset(layer, i, j);
        self.rgba.get(at..at + 4).map(|t| [t[0], t[1], t[2], t[3]])
    }

    /// The bytes of one layer (`width * height * 4`), or an empty slice if there is no such layer.
    pub fn layer(&self, layer: u32) -> &[u8] {
        let size = self.width as usize * self.height as usize * 4;
        let start = layer as usize * size;
        self.rgba.get(start..start + size).unwrap_or(&[])
    }

    fn offset(&self, layer: u32, i: u32, j: u32) -> usize {
        (((layer as usize * self.height as usize) + j as usize) * self.width as usize + i as usize) * 4
    }
}

/// `round(x)` of SPEC §0.1: floor(x + 0.5) in double, as a byte.
fn round_byte(x: f64) -> u8 {
    (x + 0.5).floor().clamp(0.0, 255.0) as u8
}

/// A unit vector in [−1, 1]³ stored as round(255·(0.5·n + 0.5)) per channel, alpha 255.
fn encode_unit(n: [f64; 3]) -> [u8; 4] {
    [
        round_byte(255.0 * (0.5 * n[0] + 0.5)),
        round_byte(255.0 * (0.5 * n[1] + 0.5)),
        round_byte(255.0 * (0.5 * n[2] + 0.5)),
        255,
    ]
}

fn normalize64(v: [f64; 3]) -> [f64; 3] {
    let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    [v[0] / len, v[1] / len, v[2] / len]
}

/// SPEC §0.1.1 **uvgrid**, 256×256: white grid lines every 32 texels, a dark (16,16,16) disc of
/// radius 40 in the middle, elsewhere (i, j, 96). Used by 001 `texture`, 002 `double_vision`
/// and 004's "BMP" texture.
pub fn uvgrid() -> Image {
    Image::from_fn(256, 256, 1, |_, i, j| {
        if i % 32 == 0 || j % 32 == 0 {
            return [255, 255, 255, 255];
        }
        let (x, y) = (f64::from(i) + 0.5 - 128.0, f64::from(j) + 0.5 - 128.0);
        if x * x + y * y < 40.0 * 40.0 {
            [16, 16, 16, 255]
        } else {
            [i as u8, j as u8, 96, 255]
        }
    })
}

/// SPEC §0.1.2 **checker**, the course's `createTexureChecker()` (004), 256×256: 8-texel
/// squares, `c = ((row & 8) == 0) ^ ((col & 8) == 0)` (the course's `i` is the row), so texel
/// (0,0) is black. Stored as 0 or 255.
pub fn checker() -> Image {
    Image::from_fn(256, 256, 1, |_, col, row| {
        let c = ((row & 8) == 0) ^ ((col & 8) == 0);
        let v = if c { 255 } else { 0 };
        [v, v, v, 255]
    })
}

/// The base colours of [`cube_faces`], in face order +X, −X, +Y, −Y, +Z, −Z.
pub const CUBE_FACE_COLORS: [[u8; 3]; 6] = [
    [230, 60, 60],
    [60, 230, 230],
    [60, 230, 60],
    [230, 60, 230],
    [60, 60, 230],
    [230, 230, 60],
];

/// SPEC §0.1.3 **cube faces** (001 `envmap`), 6 × 128×128 in face order +X, −X, +Y, −Y, +Z, −Z:
/// white lines every 16 texels, the quadrant i < 64, j < 64 at half the base colour (integer
/// division; it shows each face's orientation), elsewhere the base colour
/// ([`CUBE_FACE_COLORS`]).
pub fn cube_faces() -> Image {
    Image::from_fn(128, 128, 6, |face, i, j| {
        let base = CUBE_FACE_COLORS[face as usize];
        if i % 16 == 0 || j % 16 == 0 {
            [255, 255, 255, 255]
        } else if i < 64 && j < 64 {
            [base[0] / 2, base[1] / 2, base[2] / 2, 255]
        } else {
            [base[0], base[1], base[2], 255]
        }
    })
}

/// SPEC §0.1.4 **bump normal map** (001 `bump`, `normmap`), 256×256: the normals of the
/// egg-crate height field sin(a u)·sin(a v), a = 2π·4/256, u = i + 0.5, v = j + 0.5,
/// n = normalize(−0.8·cos(a u)·sin(a v), −0.8·sin(a u)·cos(a v), 1), stored as
/// round(255·(0.5·n + 0.5)); all in double.
pub fn bump_normal_map() -> Image {
    let a = 2.0 * std::f64::consts::PI * 4.0 / 256.0;
    Image::from_fn(256, 256, 1, |_, i, j| {
        let (u, v) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
        let n = [
            -0.8 * (a * u).cos() * (a * v).sin(),
            -0.8 * (a * u).sin() * (a * v).cos(),
            1.0,
        ];
        encode_unit(normalize64(n))
    })
}

/// SPEC §0.1.5 **normalization cube map** (001 `normmap`; SPEC uses `size` = 32), 6 × size²
/// in face order +X, −X, +Y, −Y, +Z, −Z: texel (i, j) of face f holds the unit direction the GL
/// cube-map table assigns to sc = 2(i+0.5)/size − 1, tc = 2(j+0.5)/size − 1, stored as
/// round(255·(0.5·d/|d| + 0.5)). `size` 0 gives an empty image.
pub fn normalization_cube(size: u32) -> Image {
    let s = f64::from(size);
    Image::from_fn(size, size, 6, |face, i, j| {
        let sc = 2.0 * (f64::from(i) + 0.5) / s - 1.0;
        let tc = 2.0 * (f64::from(j) + 0.5) / s - 1.0;
        let d = match face {
            0 => [1.0, -tc, -sc],
            1 => [-1.0, -tc, sc],
            2 => [sc, 1.0, tc],
            3 => [sc, -1.0, -tc],
            4 => [sc, -tc, 1.0],
            _ => [-sc, -tc, -1.0],
        };
        encode_unit(normalize64(d))
    })
}

/// The mipmap chain of `level0` as `glGenerateMipmap`'s box filter builds it, level 0 (a copy)
/// first, down to 1×1: each level is max(1, size/2) per axis, and each texel of it is
/// (a + b + c + d + 2) / 4 (integer, per channel, alpha too) of the 2×2 block at (2i, 2j) of
/// the level above, source coordinates clamped to that level (odd or 1-texel sizes). Every
/// layer is filtered on its own. Deterministic; an empty image gives just the copy.
pub fn mip_chain(level0: &Image) -> Vec<Image> {
    let mut chain = vec![level0.clone()];
    if level0.width == 0 || level0.height == 0 || level0.rgba.len() != level0.offset(level0.layers, 0, 0) {
        return chain;
    }
    loop {
        let src = &chain[chain.len() - 1];
        if src.width == 1 && src.height == 1 {
            break;
        }
        let (w, h) = ((src.width / 2).max(1), (src.height / 2).max(1));
        let next = Image::from_fn(w, h, src.layers, |layer, i, j| {
            let (x0, x1) = ((2 * i).min(src.width - 1), (2 * i + 1).min(src.width - 1));
            let (y0, y1) = ((2 * j).min(src.height - 1), (2 * j + 1).min(src.height - 1));
            let at = |x, y| src.offset(layer, x, y);
            let (a, b, c, d) = (at(x0, y0), at(x1, y0), at(x0, y1), at(x1, y1));
            let mut out = [0u8; 4];
            for (k, o) in out.iter_mut().enumerate() {
                let sum = u32::from(src.rgba[a + k])
                    + u32::from(src.rgba[b + k])
                    + u32::from(src.rgba[c + k])
                    + u32::from(src.rgba[d + k]);
                *o = ((sum + 2) / 4) as u8;
            }
            out
        });
        chain.push(next);
    }
    chain
}

/// How many RGBA8 copies of a picture are alive at once on its way to the GPU, at the most: the
/// decoder's, the RGBA copy, a flipped copy, the mipmaps, the upload and the driver's texture
/// (the measured peak stays under it; figures: `docs/speed.md`, "Large meshes, models and
/// pictures").
const PICTURE_COPIES: u64 = 7;

/// The largest picture file read (64 MiB); a full 8192×8192 RGBA PNG without any compression
/// is 256 MiB, but real pictures of that size compress far below this.
pub const MAX_IMAGE_FILE_BYTES: u64 = 64 << 20;

/// The widest and tallest picture taken (16384 texels a side): wgpu's default
/// `max_texture_dimension_2d`, which every device offers. A device with a smaller limit is
/// checked when the texture is made ([`crate::render::check_texture_size`]).
pub const MAX_IMAGE_SIDE: u32 = 16384;

/// The most texels a picture may have (64 Mi, e.g. 8192×8192: 256 MiB as RGBA8, and about a
/// third more with its mipmaps), so that a small file claiming a huge size in its header (a
/// decompression bomb) is refused before anything is decoded or allocated.
pub const MAX_IMAGE_PIXELS: u64 = 64 << 20;

/// The most memory the decoder may allocate for one picture (its own buffers; the RGBA8 copy
/// is bounded by [`MAX_IMAGE_PIXELS`]).
const MAX_DECODE_ALLOC: u64 = 512 << 20;

/// Reads a PNG or BMP file (format guessed from its content) as a one-layer RGBA8 [`Image`].
///
/// The file must be a regular file of at most [`MAX_IMAGE_FILE_BYTES`]
/// ([`crate::fsutil::read_user_file`]); its size is read from its header and checked against
/// [`MAX_IMAGE_SIDE`] and [`MAX_IMAGE_PIXELS`] before anything is decoded.
///
/// Rows come in the decoder's order, the picture's top row first (a BMP's bottom-up storage is
/// undone by the decoder); a port that wants GL's "first row uploaded = t ≈ 0" for a picture
/// file decides itself whether to flip. Errors name the file and say in plain words what is
/// wrong ([`Error::Io`]): missing, unreadable, too large a file, not a PNG or BMP, too many
/// pixels, damaged or cut short.
pub fn load_image(path: &Path) -> Result<Image> {
    let bytes = crate::fsutil::read_user_file(path, MAX_IMAGE_FILE_BYTES, "pictures")?;
    decode_image(path, &bytes)
}

fn bad_picture(path: &Path, message: String) -> Error {
    Error::Io {
        path: path.to_path_buf(),
        source: std::io::Error::new(std::io::ErrorKind::InvalidData, message),
    }
}

/// The size a PNG's or BMP's header claims, read without a decoder: (width, height), or `None`
/// if the header is too short to say. A BMP's negative height (rows stored top down) counts
/// as its absolute value; a negative width stays negative (the decoder refuses it). Read by
/// hand because `image`'s PNG decoder reads on to the first IDAT chunk before it reports a
/// size, so a damaged or truncated file would hide the size it claims.
fn header_size(format: image::ImageFormat, bytes: &[u8]) -> Option<(i64, i64)> {
    let be = |at: usize| Some(u32::from_be_bytes(bytes.get(at..at + 4)?.try_into().ok()?));
    let le32 = |at: usize| Some(i32::from_le_bytes(bytes.get(at..at + 4)?.try_into().ok()?));
    let le16 = |at: usize| Some(u16::from_le_bytes(bytes.get(at..at + 2)?.try_into().ok()?));
    match format {
        // Signature (8), IHDR length (4) and type (4), then width and height.
        image::ImageFormat::Png if bytes.get(12..16) == Some(b"IHDR") => Some((i64::from(be(16)?), i64::from(be(20)?))),
        // File header (14), then the info header: its size, then width and height, 16-bit in
        // the old 12-byte BITMAPCOREHEADER, 32-bit signed in the others.
        image::ImageFormat::Bmp => match le32(14)? {
            12 => Some((i64::from(le16(18)?), i64::from(le16(20)?))),
            _ => Some((i64::from(le32(18)?), i64::from(le32(22)?).abs())),
        },
        _ => None,
    }
}

/// Refuses a picture whose size is empty or beyond [`MAX_IMAGE_SIDE`] or [`MAX_IMAGE_PIXELS`].
fn check_size(path: &Path, name: &str, (width, height): (i64, i64)) -> Result<()> {
    if width <= 0 || height <= 0 {
        return Err(bad_picture(
            path,
            format!("the {name} header says {width}x{height} pixels; a picture needs at least 1x1"),
        ));
    }
    let side = i64::from(MAX_IMAGE_SIDE);
    if width > side || height > side {
        return Err(bad_picture(
            path,
            format!("the picture is {width}x{height} pixels; textures are limited to {MAX_IMAGE_SIDE} pixels a side"),
        ));
    }
    let pixels = (width * height) as u64;
    if pixels > MAX_IMAGE_PIXELS {
        return Err(bad_picture(
            path,
            format!(
                "the picture is {width}x{height} pixels ({pixels} pixels); pictures are limited to {MAX_IMAGE_PIXELS} pixels ({} as RGBA, e.g. 8192x8192)",
                crate::fsutil::human_bytes(MAX_IMAGE_PIXELS * 4)
            ),
        ));
    }
    Ok(())
}

/// What went wrong while decoding, in plain words (`size` once the header has been read).
fn decode_error(path: &Path, name: &str, size: Option<(u32, u32)>, e: image::ImageError) -> Error {
    use image::error::{ImageError as E, LimitErrorKind};
    let of = size.map(|(w, h)| format!(" ({w}x{h} pixels)")).unwrap_or_default();
    let message = match e {
        E::IoError(io) if io.kind() == std::io::ErrorKind::UnexpectedEof => {
            format!("the {name} file{of} ends early: it is cut short or damaged")
        }
        E::IoError(io) => format!("reading the {name} file{of}: {io}"),
        E::Limits(limit) => match limit.kind() {
            LimitErrorKind::InsufficientMemory => format!(
                "decoding the {name} file{of} would need more than {} of memory",
                crate::fsutil::human_bytes(MAX_DECODE_ALLOC)
            ),
            _ => format!(
                "the {name} file{of} is too large: textures are limited to {MAX_IMAGE_SIDE} pixels a side and {MAX_IMAGE_PIXELS} pixels"
            ),
        },
        E::Unsupported(u) => format!("a {name} file{of} of a kind that cannot be read: {u}"),
        E::Decoding(d) => {
            // The decoder's own words, without its "Format error decoding Png:" preamble.
            let why = std::error::Error::source(&d).map_or_else(|| d.to_string(), |s| s.to_string());
            format!("not a valid {name} file{of}: {why}")
        }
        e => format!("not a valid {name} file{of}: {e}"),
    };
    bad_picture(path, message)
}

/// Decodes the bytes of a PNG or BMP file as [`load_image`] does (a picture compiled into the
/// program, e.g. `assets/uvgrid.bmp`); `path` names it in errors and, when the content says
/// nothing, its extension gives the format.
pub fn decode_image(path: &Path, bytes: &[u8]) -> Result<Image> {
    use image::ImageDecoder;
    let mut reader = image::ImageReader::new(std::io::Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })?;
    let from_content = reader.format().is_some();
    if !from_content {
        if let Ok(format) = image::ImageFormat::from_path(path) {
            reader.set_format(format);
        }
    }
    let not_a_picture = || {
        bad_picture(
            path,
            "not a PNG or BMP picture (its first bytes are neither's signature)".into(),
        )
    };
    let format = match reader.format() {
        Some(f @ (image::ImageFormat::Png | image::ImageFormat::Bmp)) => f,
        _ => return Err(not_a_picture()),
    };
    let name = if format == image::ImageFormat::Png {
        "PNG"
    } else {
        "BMP"
    };
    // Refuse from the header, before a decoder allocates anything for the picture.
    let header = header_size(format, bytes);
    if let Some(size) = header {
        check_size(path, name, size)?;
    }
    // Checked above: positive and at most MAX_IMAGE_SIDE.
    let header = header.map(|(w, h)| (w as u32, h as u32));
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_IMAGE_SIDE);
    limits.max_image_height = Some(MAX_IMAGE_SIDE);
    limits.max_alloc = Some(MAX_DECODE_ALLOC);
    reader.limits(limits);
    let decoder = reader.into_decoder().map_err(|e| match e {
        // Only the name said PNG or BMP, and the decoder does not recognise the content either.
        image::ImageError::Decoding(_) if !from_content => not_a_picture(),
        e => decode_error(path, name, header, e),
    })?;
    let (width, height) = decoder.dimensions();
    // The decoder's own reading of the header decides (also where the quick look above could not).
    check_size(path, name, (i64::from(width), i64::from(height)))?;
    crate::memory::check(
        &format!("{} ({width}×{height} pixels)", path.display()),
        u64::from(width) * u64::from(height) * 4 * PICTURE_COPIES,
    )?;
    let decoded =
        image::DynamicImage::from_decoder(decoder).map_err(|e| decode_error(path, name, Some((width, height)), e))?;
    let rgba = decoded.to_rgba8();
    Ok(Image {
        width: rgba.width(),
        height: rgba.height(),
        layers: 1,
        rgba: rgba.into_raw(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rgb(image: &Image, layer: u32, i: u32, j: u32) -> [u8; 3] {
        let t = image.texel(layer, i, j).expect("texel inside the image");
        assert_eq!(t[3], 255, "alpha at ({i},{j})");
        [t[0], t[1], t[2]]
    }

    fn decode(image: &Image, layer: u32, i: u32, j: u32) -> [f64; 3] {
        rgb(image, layer, i, j).map(|c| f64::from(c) / 255.0 * 2.0 - 1.0)
    }

    #[test]
    fn uvgrid_texels() {
        let g = uvgrid();
        assert_eq!(
            (g.width, g.height, g.layers, g.rgba.len()),
            (256, 256, 1, 256 * 256 * 4)
        );
        assert_eq!(rgb(&g, 0, 0, 5), [255, 255, 255]);
        assert_eq!(rgb(&g, 0, 5, 64), [255, 255, 255]);
        // (128,128) lies on the grid lines (128 = 4·32); just off them the disc shows.
        assert_eq!(rgb(&g, 0, 128, 128), [255, 255, 255]);
        assert_eq!(rgb(&g, 0, 127, 127), [16, 16, 16]);
        assert_eq!(rgb(&g, 0, 130, 129), [16, 16, 16]);
        assert_eq!(rgb(&g, 0, 40, 70), [40, 70, 96]);
        // i is the column: texel (i, j) sits at byte (j * 256 + i) * 4.
        assert_eq!(&g.rgba[(70 * 256 + 40) * 4..][..4], &[40, 70, 96, 255]);
        assert_eq!(rgb(&g, 0, 255, 1), [255, 1, 96]);
        // disc edge: (168.5-128)² + (128.5-128)² = 1640.5 ≥ 1600, (167.5-128)² + 0.25 < 1600
        assert_eq!(rgb(&g, 0, 168, 129), [168, 129, 96]);
        assert_eq!(rgb(&g, 0, 167, 129), [16, 16, 16]);
    }

    #[test]
    fn checker_texels() {
        let c = checker();
        assert_eq!((c.width, c.height, c.layers), (256, 256, 1));
        assert_eq!(rgb(&c, 0, 0, 0), [0, 0, 0]);
        assert_eq!(rgb(&c, 0, 8, 0), [255, 255, 255]); // row 0, column 8
        assert_eq!(rgb(&c, 0, 0, 8), [255, 255, 255]); // row 8, column 0
        assert_eq!(rgb(&c, 0, 8, 8), [0, 0, 0]);
        assert_eq!(rgb(&c, 0, 7, 7), [0, 0, 0]);
        assert_eq!(rgb(&c, 0, 255, 0), [255, 255, 255]);
        assert!(c
            .rgba
            .chunks(4)
            .all(|t| (t[0] == 0 || t[0] == 255) && t[0] == t[1] && t[1] == t[2]));
    }

    #[test]
    fn cube_face_texels() {
        let c = cube_faces();
        assert_eq!(
            (c.width, c.height, c.layers, c.rgba.len()),
            (128, 128, 6, 6 * 128 * 128 * 4)
        );
        assert_eq!(rgb(&c, 0, 1, 1), [115, 30, 30]);
        assert_eq!(rgb(&c, 0, 0, 1), [255, 255, 255]);
        assert_eq!(rgb(&c, 0, 17, 64), [255, 255, 255]);
        assert_eq!(rgb(&c, 0, 65, 1), [230, 60, 60]);
        for (face, base) in CUBE_FACE_COLORS.iter().enumerate() {
            assert_eq!(rgb(&c, face as u32, 100, 100), *base);
            assert_eq!(rgb(&c, face as u32, 63, 63), base.map(|b| b / 2));
        }
        assert_eq!(rgb(&c, 5, 1, 1), [115, 115, 30]);
        // layer 1 starts right after layer 0
        assert_eq!(&c.layer(1)[..4], &[255, 255, 255, 255]);
        assert_eq!(&c.layer(1)[(128 + 1) * 4..][..4], &[30, 115, 115, 255]);
    }

    #[test]
    fn bump_map_texels() {
        let b = bump_normal_map();
        assert_eq!((b.width, b.height, b.layers), (256, 256, 1));
        for &(i, j) in &[
            (0, 0),
            (15, 15),
            (16, 16),
            (100, 37),
            (127, 128),
            (128, 128),
            (255, 255),
        ] {
            let n = decode(&b, 0, i, j);
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            assert!((len - 1.0).abs() < 0.01, "({i},{j}) {n:?}");
            assert!(n[2] > 0.75, "tilt at most atan 0.8: ({i},{j}) {n:?}");
        }
        // Exact value at texel (0,0): u = v = 0.5, a·u = π/64.
        let a = std::f64::consts::PI / 64.0;
        let (x, y) = (-0.8 * a.cos() * a.sin(), -0.8 * a.sin() * a.cos());
        let len = (x * x + y * y + 1.0f64).sqrt();
        let expect = [x / len, y / len, 1.0 / len].map(|c| (255.0 * (0.5 * c + 0.5) + 0.5).floor() as u8);
        assert_eq!(rgb(&b, 0, 0, 0), expect);
        assert_eq!(expect, [123, 123, 255]);
        // On the diagonal i = j the tilt is symmetric: equal x and y.
        let d = rgb(&b, 0, 40, 40);
        assert_eq!(d[0], d[1]);
    }

    #[test]
    fn normalization_cube_texels() {
        let n = normalization_cube(32);
        assert_eq!(
            (n.width, n.height, n.layers, n.rgba.len()),
            (32, 32, 6, 6 * 32 * 32 * 4)
        );
        let centre = rgb(&n, 0, 16, 16);
        assert_eq!(centre[0], 255);
        assert!(
            centre[1].abs_diff(128) <= 4 && centre[2].abs_diff(128) <= 4,
            "{centre:?}"
        );
        // The +X face at (i, j) = (0, 0): d = (1, -tc, -sc) with sc = tc = -31/32.
        let s = 31.0 / 32.0;
        let len = (1.0f64 + 2.0 * s * s).sqrt();
        let want = [1.0 / len, s / len, s / len].map(|c| (255.0 * (0.5 * c + 0.5) + 0.5).floor() as u8);
        assert_eq!(rgb(&n, 0, 0, 0), want);
        // Each face's centre points along its axis.
        let axes = [
            [1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
        ];
        for (face, axis) in axes.iter().enumerate() {
            let d = decode(&n, face as u32, 16, 16);
            let dot: f64 = d.iter().zip(axis).map(|(a, b)| a * b).sum();
            assert!(dot > 0.99, "face {face}: {d:?}");
        }
        for layer in 0..6 {
            for (i, j) in [(0, 0), (31, 0), (5, 27), (31, 31)] {
                let d = decode(&n, layer, i, j);
                let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                assert!((len - 1.0).abs() < 0.01, "{layer} ({i},{j}) {d:?}");
            }
        }
        assert!(normalization_cube(0).rgba.is_empty());
    }

    #[test]
    fn mip_chain_sizes_and_rounding() {
        let chain = mip_chain(&checker());
        let sizes: Vec<(u32, u32)> = chain.iter().map(|m| (m.width, m.height)).collect();
        assert_eq!(sizes, (0..9).map(|k| (256 >> k, 256 >> k)).collect::<Vec<_>>());
        assert_eq!(chain[0], checker());
        // 8-texel squares stay exact down to level 3 (32×32, one texel per square), then blend to grey.
        assert_eq!(rgb(&chain[3], 0, 0, 0), [0, 0, 0]);
        assert_eq!(rgb(&chain[3], 0, 1, 0), [255, 255, 255]);
        assert_eq!(rgb(&chain[4], 0, 0, 0), [128, 128, 128]);
        assert_eq!(rgb(&chain[8], 0, 0, 0), [128, 128, 128]);

        // 2×2 black/white checker: (0 + 255 + 255 + 0 + 2) / 4 = 128 (127.5 rounds up).
        let tiny = Image::from_fn(2, 2, 1, |_, i, j| {
            if (i + j) % 2 == 0 {
                [0, 0, 0, 255]
            } else {
                [255, 255, 255, 255]
            }
        });
        let chain = mip_chain(&tiny);
        assert_eq!(chain.len(), 2);
        assert_eq!(chain[1].rgba, vec![128, 128, 128, 255]);

        // Odd and non-square sizes: 5×2 → 2×1 → 1×1, layers kept apart, coordinates clamped.
        let odd = Image::from_fn(5, 2, 2, |layer, i, _| [(i * 10) as u8, layer as u8 * 100, 0, 255]);
        let chain = mip_chain(&odd);
        let sizes: Vec<(u32, u32, u32)> = chain.iter().map(|m| (m.width, m.height, m.layers)).collect();
        assert_eq!(sizes, vec![(5, 2, 2), (2, 1, 2), (1, 1, 2)]);
        assert_eq!(chain[1].texel(0, 0, 0), Some([5, 0, 0, 255])); // (0+10+0+10+2)/4 = 5
        assert_eq!(chain[1].texel(0, 1, 0), Some([25, 0, 0, 255])); // (20+30+20+30+2)/4 = 25
        assert_eq!(chain[1].texel(1, 1, 0), Some([25, 100, 0, 255]));
        assert_eq!(chain[2].texel(0, 0, 0), Some([15, 0, 0, 255])); // (5+25+5+25+2)/4 = 15
        assert_eq!(mip_chain(&odd), chain, "deterministic");

        // A 1×1 image is its own chain; an empty or inconsistent one is only copied.
        assert_eq!(mip_chain(&Image::from_fn(1, 1, 1, |_, _, _| [1, 2, 3, 4])).len(), 1);
        let broken = Image {
            width: 4,
            height: 4,
            layers: 1,
            rgba: vec![0; 3],
        };
        assert_eq!(mip_chain(&broken), vec![broken.clone()]);
    }

    /// A PNG of `width`x`height` (grey, colour type 0; RGB, 2) whose IHDR says so but which has
    /// no pixel data: what a decompression bomb looks like before its data.
    fn png_header(width: u32, height: u32, colour: u8) -> Vec<u8> {
        fn chunk(kind: &[u8; 4], data: &[u8]) -> Vec<u8> {
            let mut c = (data.len() as u32).to_be_bytes().to_vec();
            c.extend_from_slice(kind);
            c.extend_from_slice(data);
            c.extend_from_slice(&crc32(&c[4..]).to_be_bytes());
            c
        }
        // PNG's CRC-32 (ISO 3309), bit by bit.
        fn crc32(bytes: &[u8]) -> u32 {
            let mut crc = !0u32;
            for &b in bytes {
                crc ^= u32::from(b);
                for _ in 0..8 {
                    crc = if crc & 1 == 1 {
                        (crc >> 1) ^ 0xEDB8_8320
                    } else {
                        crc >> 1
                    };
                }
            }
            !crc
        }
        let mut ihdr = width.to_be_bytes().to_vec();
        ihdr.extend_from_slice(&height.to_be_bytes());
        ihdr.extend_from_slice(&[8, colour, 0, 0, 0]);
        let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
        png.extend(chunk(b"IHDR", &ihdr));
        png.extend(chunk(b"IEND", &[]));
        png
    }

    /// A 24-bit BMP of `width`x`height` with `pixels` as its data.
    fn bmp(width: i32, height: i32, pixels: &[u8]) -> Vec<u8> {
        let mut b = b"BM".to_vec();
        b.extend_from_slice(&(54 + pixels.len() as u32).to_le_bytes());
        b.extend_from_slice(&[0; 4]);
        b.extend_from_slice(&54u32.to_le_bytes());
        b.extend_from_slice(&40u32.to_le_bytes());
        b.extend_from_slice(&width.to_le_bytes());
        b.extend_from_slice(&height.to_le_bytes());
        b.extend_from_slice(&1u16.to_le_bytes());
        b.extend_from_slice(&24u16.to_le_bytes());
        b.extend_from_slice(&[0; 24]);
        b.extend_from_slice(pixels);
        b
    }

    fn decode_err(name: &str, bytes: &[u8]) -> String {
        decode_image(Path::new(name), bytes).unwrap_err().to_string()
    }

    #[test]
    fn picture_sizes_are_refused_from_the_header() {
        // 22600² grey: 510 MB decoded, 2 GB as RGBA; refused before any decoding.
        assert_eq!(
            decode_err("bomb.png", &png_header(22600, 22600, 0)),
            "bomb.png: the picture is 22600x22600 pixels; textures are limited to 16384 pixels a side"
        );
        assert_eq!(
            decode_err("wide.png", &png_header(16385, 1, 0)),
            "wide.png: the picture is 16385x1 pixels; textures are limited to 16384 pixels a side"
        );
        // 13000² RGB: within the side limit, but 676 MB as RGBA.
        assert_eq!(
            decode_err("big.png", &png_header(13000, 13000, 2)),
            "big.png: the picture is 13000x13000 pixels (169000000 pixels); pictures are limited to \
             67108864 pixels (256 MiB as RGBA, e.g. 8192x8192)"
        );
        assert_eq!(
            decode_err("zero.bmp", &bmp(0, 2, &[])),
            "zero.bmp: the BMP header says 0x2 pixels; a picture needs at least 1x1"
        );
        assert_eq!(
            decode_err("huge.bmp", &bmp(20000, -20000, &[])),
            "huge.bmp: the picture is 20000x20000 pixels; textures are limited to 16384 pixels a side"
        );
    }

    #[test]
    fn damaged_pictures_are_described_in_plain_words() {
        // 4x2, 24-bit: rows of 12 bytes; cut after 6 of its 24 bytes of pixels.
        let whole = bmp(4, 2, &[64; 24]);
        let image = decode_image(Path::new("ok.bmp"), &whole).unwrap();
        assert_eq!((image.width, image.height), (4, 2));
        assert_eq!(
            decode_err("cut.bmp", &whole[..60]),
            "cut.bmp: the BMP file (4x2 pixels) ends early: it is cut short or damaged"
        );
        assert_eq!(
            decode_err("junk.png", b"not a picture"),
            "junk.png: not a PNG or BMP picture (its first bytes are neither's signature)"
        );
        // A header and no pixel data at all.
        let err = decode_err("empty.png", &png_header(4, 4, 2));
        assert!(
            err.starts_with("empty.png: not a valid PNG file (4x4 pixels): "),
            "{err}"
        );
    }

    #[test]
    fn picture_files_have_a_size_cap() {
        let dir = crate::fsutil::ScratchDir::new("images-cap");
        let big = dir.join("big.png");
        std::fs::File::create(&big)
            .unwrap()
            .set_len(MAX_IMAGE_FILE_BYTES + 1)
            .unwrap();
        let err = load_image(&big).unwrap_err().to_string();
        assert!(
            err.ends_with("big.png: 67108865 bytes (64.0 MiB); pictures are limited to 67108864 bytes (64 MiB)"),
            "{err}"
        );
    }

    #[test]
    fn load_image_png_bmp_and_errors() {
        let dir = std::env::temp_dir().join(format!("shaderlab-images-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let picture = image::RgbImage::from_fn(3, 2, |x, y| image::Rgb([x as u8 * 50, y as u8 * 100, 7]));
        for ext in ["png", "bmp"] {
            let path = dir.join(format!("p.{ext}"));
            picture.save(&path).unwrap();
            let loaded = load_image(&path).unwrap();
            assert_eq!((loaded.width, loaded.height, loaded.layers), (3, 2, 1));
            assert_eq!(loaded.texel(0, 2, 1), Some([100, 100, 7, 255]), "{ext}");
            assert_eq!(loaded.texel(0, 0, 0), Some([0, 0, 7, 255]), "{ext}");
        }
        let missing = dir.join("missing.png");
        let err = load_image(&missing).unwrap_err();
        assert!(
            matches!(err, Error::Io { .. }) && err.to_string().contains("missing.png"),
            "{err}"
        );
        let junk = dir.join("junk.png");
        std::fs::write(&junk, b"not an image at all").unwrap();
        let err = load_image(&junk).unwrap_err();
        assert!(
            matches!(err, Error::Io { .. }) && err.to_string().contains("junk.png: not a PNG or BMP picture"),
            "{err}"
        );
        std::fs::remove_dir_all(&dir).ok();
    }
}
