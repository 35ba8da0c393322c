//! Pictures of a frame's values, on plain slices (no GPU): a line view's values per pixel
//! ([`values`]), a cost view's counts ([`cost`]), a diff's per-pixel distance ([`difference`]),
//! each with a legend strip drawn under it, and the values as a NumPy array ([`write_npy`]).
//!
//! A scalar goes through a perceptual sequential map (viridis) over its range, or a diverging
//! one (blue, grey at 0, red) over `-m..m` when its values change sign; a vector's first three
//! components are red, green and blue over the range the legend states. NaN is magenta and
//! either infinity cyan, each counted; a pixel where a fragment ran but the line did not is a
//! dim checker, and one where no fragment ran at all is black.
//!
//! The legend's text is drawn with a 3×5 bitmap font of the few characters it needs (digits,
//! signs and the legend's words), written here: the crates that carry a font bring far more
//! glyphs than a legend needs and a build step to every build.

use std::io::Write;
use std::path::Path;

use image::{Rgba, RgbaImage};

use crate::error::Result;

/// NaN's colour.
pub const NAN_COLOUR: [u8; 3] = [255, 0, 255];
/// The colour of +∞ and −∞.
pub const INFINITE_COLOUR: [u8; 3] = [0, 255, 255];
/// Where no fragment ran.
pub const BACKGROUND: [u8; 3] = [0, 0, 0];
/// The two squares of the checker that marks a pixel where a fragment ran and the line did not.
pub const NOT_RUN: [[u8; 3]; 2] = [[56, 56, 56], [88, 88, 88]];
/// The legend strip's height in pixels, under the picture.
pub const LEGEND_HEIGHT: u32 = 16;
/// The legend strip's grey (each of red, green and blue).
pub const LEGEND_GREY: u8 = 24;

/// Viridis at nine evenly spaced stops (matplotlib's), interpolated linearly between them.
pub(crate) const VIRIDIS: [[u8; 3]; 9] = [
    [68, 1, 84],
    [71, 45, 123],
    [59, 82, 139],
    [44, 114, 142],
    [33, 145, 140],
    [40, 174, 128],
    [94, 201, 98],
    [173, 220, 48],
    [253, 231, 37],
];

/// A diverging map (Moreland's cool–warm): blue at −1, light grey at 0, red at +1.
pub(crate) const DIVERGING: [[u8; 3]; 5] = [
    [59, 76, 192],
    [141, 176, 254],
    [221, 221, 221],
    [244, 154, 123],
    [180, 4, 38],
];

fn ramp(stops: &[[u8; 3]], t: f64) -> [u8; 3] {
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let f = t * (stops.len() - 1) as f64;
    let k = (f.floor() as usize).min(stops.len() - 2);
    let u = f - k as f64;
    std::array::from_fn(|c| {
        let (a, b) = (f64::from(stops[k][c]), f64::from(stops[k + 1][c]));
        (a + (b - a) * u).round() as u8
    })
}

/// The sequential map at `t` in 0..1 (clamped): dark purple at 0, yellow at 1.
pub fn sequential(t: f64) -> [u8; 3] {
    ramp(&VIRIDIS, t)
}

/// The diverging map at `t` in −1..1 (clamped): blue at −1, grey at 0, red at 1.
pub fn diverging(t: f64) -> [u8; 3] {
    ramp(&DIVERGING, (t + 1.0) / 2.0)
}

/// How a view's values became colours: the map and its range, and what was counted.
#[derive(Clone, Debug, PartialEq)]
pub struct Legend {
    /// The map.
    pub scale: Scale,
    /// The range's low end (the colour bar's left).
    pub min: f64,
    /// Its high end.
    pub max: f64,
    /// Pixels with a NaN (in any component).
    pub nan: usize,
    /// Pixels with +∞ (and no NaN).
    pub pos_inf: usize,
    /// Pixels with −∞ (and no NaN or +∞).
    pub neg_inf: usize,
    /// Pixels where a fragment ran and the line did not.
    pub not_run: usize,
    /// Pixels where no fragment ran.
    pub background: usize,
}

/// Which map a picture used.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    /// A scalar through the sequential map over `min..max`.
    Sequential,
    /// A scalar that changes sign through the diverging map over `min..max` (`min = -max`).
    Diverging,
    /// A vector's first three components as red, green, blue over `min..max`.
    Rgb,
}

impl Legend {
    /// The legend in words: `viridis 0 … 1; NaN 3; +inf 0; -inf 0; line not run 120`.
    pub fn text(&self) -> String {
        let map = match self.scale {
            Scale::Sequential => "sequential (viridis)",
            Scale::Diverging => "diverging (blue < 0 < red)",
            Scale::Rgb => "x, y, z as red, green, blue",
        };
        format!(
            "{map} over {} … {}; NaN {} (magenta), ±inf {} (cyan: +{} −{}), line not run {} (checker), no fragment {} (black)",
            short(self.min),
            short(self.max),
            self.nan,
            self.pos_inf + self.neg_inf,
            self.pos_inf,
            self.neg_inf,
            self.not_run,
            self.background
        )
    }
}

/// A number in a legend: at most 4 significant digits.
pub fn short(v: f64) -> String {
    if !v.is_finite() {
        return if v.is_nan() {
            "nan".into()
        } else if v > 0.0 {
            "inf".into()
        } else {
            "-inf".into()
        };
    }
    let a = v.abs();
    if a != 0.0 && !(1e-3..1e5).contains(&a) {
        return format!("{v:.2e}");
    }
    super::report::num(v)
}

fn special(v: &[f32]) -> Option<(usize, [u8; 3])> {
    if v.iter().any(|x| x.is_nan()) {
        Some((0, NAN_COLOUR))
    } else if v.contains(&f32::INFINITY) {
        Some((1, INFINITE_COLOUR))
    } else if v.contains(&f32::NEG_INFINITY) {
        Some((2, INFINITE_COLOUR))
    } else {
        None
    }
}

fn checker(x: u32, y: u32) -> [u8; 3] {
    NOT_RUN[((x / 4 + y / 4) % 2) as usize]
}

/// The picture of a value frame of `width` × `height` (row-major, top row first): `values`
/// with `components` (1–4) meaningful components each, `ran` where the line ran, `drawn`
/// where a fragment ran at all; with its legend strip under it.
pub fn values(
    width: u32,
    height: u32,
    components: usize,
    values: &[[f32; 4]],
    ran: &[bool],
    drawn: &[bool],
) -> (RgbaImage, Legend) {
    let n = (width as usize) * (height as usize);
    let comps = components.clamp(1, 4);
    let shown = comps.min(3);
    let at = |k: usize| -> Option<&[f32]> {
        (k < values.len() && ran.get(k) == Some(&true) && drawn.get(k) == Some(&true)).then(|| &values[k][..comps])
    };
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for k in 0..n {
        if let Some(v) = at(k).filter(|v| special(v).is_none()) {
            for x in &v[..shown] {
                lo = lo.min(f64::from(*x));
                hi = hi.max(f64::from(*x));
            }
        }
    }
    let mut legend = Legend::new(comps, lo, hi);
    let (scale, min, max) = (legend.scale, legend.min, legend.max);
    let span = if max > min { max - min } else { 1.0 };
    let mut image = RgbaImage::new(width, height + LEGEND_HEIGHT);
    for y in 0..height {
        for x in 0..width {
            let k = (y * width + x) as usize;
            let colour = if drawn.get(k) != Some(&true) {
                legend.background += 1;
                BACKGROUND
            } else if let Some(v) = at(k) {
                match special(v) {
                    Some((which, c)) => {
                        *[&mut legend.nan, &mut legend.pos_inf, &mut legend.neg_inf][which] += 1;
                        c
                    }
                    None => match scale {
                        Scale::Sequential => sequential((f64::from(v[0]) - min) / span),
                        Scale::Diverging => diverging(f64::from(v[0]) / max.max(f64::MIN_POSITIVE)),
                        Scale::Rgb => std::array::from_fn(|c| {
                            v.get(c).filter(|_| c < shown).map_or(0, |x| {
                                (((f64::from(*x) - min) / span).clamp(0.0, 1.0) * 255.0).round() as u8
                            })
                        }),
                    },
                }
            } else {
                legend.not_run += 1;
                checker(x, y)
            };
            image.put_pixel(x, y, rgba(colour));
        }
    }
    legend.draw(&mut image, height);
    (image, legend)
}

impl Legend {
    /// The map and range for values of `components` components whose finite shown components
    /// span `lo..=hi` (`lo > hi`: none), with nothing counted yet: a vector is RGB (over 0..1
    /// where it fits, otherwise its range), a scalar that changes sign diverges around 0 over
    /// `-m..m`, any other scalar is sequential over its range.
    pub fn new(components: usize, lo: f64, hi: f64) -> Legend {
        let (lo, hi) = if lo > hi { (0.0, 1.0) } else { (lo, hi) };
        let scale = if components > 1 {
            Scale::Rgb
        } else if lo < 0.0 && hi > 0.0 {
            Scale::Diverging
        } else {
            Scale::Sequential
        };
        let (min, max) = match scale {
            Scale::Diverging => {
                let m = lo.abs().max(hi.abs());
                (-m, m)
            }
            // A vector within 0..1 (a colour, a normal's absolute value) is shown as it is.
            Scale::Rgb if lo >= 0.0 && hi <= 1.0 => (0.0, 1.0),
            _ => (lo, hi),
        };
        Legend {
            scale,
            min,
            max,
            nan: 0,
            pos_inf: 0,
            neg_inf: 0,
            not_run: 0,
            background: 0,
        }
    }

    /// Draws the legend strip into `image` from row `top` down: the range's ends around the
    /// colour bar, then the counts.
    pub fn draw(&self, image: &mut RgbaImage, top: u32) {
        let bar: Box<dyn Fn(f64) -> [u8; 3]> = match self.scale {
            Scale::Sequential => Box::new(sequential),
            Scale::Diverging => Box::new(|t| diverging(2.0 * t - 1.0)),
            Scale::Rgb => Box::new(|t| {
                let g = (t * 255.0).round() as u8;
                [g, g, g]
            }),
        };
        let words = format!(
            "nan {} inf {} not run {}",
            self.nan,
            self.pos_inf + self.neg_inf,
            self.not_run
        );
        draw_legend(image, top, &short(self.min), &short(self.max), &*bar, &words);
    }
}

/// The legend strip alone, `width` pixels wide: what [`values`] draws under its picture.
pub fn strip(width: u32, legend: &Legend) -> RgbaImage {
    let mut image = RgbaImage::new(width.max(1), LEGEND_HEIGHT);
    legend.draw(&mut image, 0);
    image
}

/// A cost view's legend strip alone, `width` pixels wide, for counts up to `max`: what
/// [`cost`] draws under its picture.
pub fn cost_strip(width: u32, max: u32) -> RgbaImage {
    let mut image = RgbaImage::new(width.max(1), LEGEND_HEIGHT);
    draw_cost_legend(&mut image, 0, max);
    image
}

fn draw_cost_legend(image: &mut RgbaImage, top: u32, max: u32) {
    draw_legend(image, top, "0", &max.to_string(), &sequential, "statements run");
}

/// The picture of a cost view: each pixel's count of statements run through the sequential
/// map over `0..max`, black where no fragment ran (`drawn` false); with its legend.
pub fn cost(width: u32, height: u32, cost: &[u32], drawn: &[bool]) -> (RgbaImage, u32) {
    let n = (width as usize) * (height as usize);
    let max = (0..n)
        .filter(|&k| drawn.get(k) == Some(&true))
        .filter_map(|k| cost.get(k).copied())
        .max()
        .unwrap_or(0);
    let mut image = RgbaImage::new(width, height + LEGEND_HEIGHT);
    for y in 0..height {
        for x in 0..width {
            let k = (y * width + x) as usize;
            let colour = match (drawn.get(k), cost.get(k)) {
                (Some(true), Some(&c)) => sequential(f64::from(c) / f64::from(max.max(1))),
                _ => BACKGROUND,
            };
            image.put_pixel(x, y, rgba(colour));
        }
    }
    draw_cost_legend(&mut image, height, max);
    (image, max)
}

/// The picture of a diff: the reference's picture in dim grey, each pixel that differs in
/// the sequential map by its largest channel difference over `1..=max`; with its legend.
/// Returns the picture and that largest difference (0 where the two are the same).
pub fn difference(mine: &RgbaImage, reference: &RgbaImage) -> (RgbaImage, u8) {
    let (width, height) = reference.dimensions();
    let off = |x: u32, y: u32| -> u8 {
        let (a, b) = (mine.get_pixel(x, y).0, reference.get_pixel(x, y).0);
        (0..4).map(|c| a[c].abs_diff(b[c])).max().unwrap_or(0)
    };
    let mut max = 0;
    for y in 0..height.min(mine.height()) {
        for x in 0..width.min(mine.width()) {
            max = max.max(off(x, y));
        }
    }
    let mut image = RgbaImage::new(width, height + LEGEND_HEIGHT);
    for y in 0..height {
        for x in 0..width {
            let d = if x < mine.width() && y < mine.height() {
                off(x, y)
            } else {
                0
            };
            let colour = if d > 0 {
                sequential(0.25 + 0.75 * f64::from(d - 1) / f64::from(max.max(2) - 1))
            } else {
                let p = reference.get_pixel(x, y).0;
                let grey = (0.299 * f64::from(p[0]) + 0.587 * f64::from(p[1]) + 0.114 * f64::from(p[2])) * 0.35;
                let g = grey.round() as u8;
                [g, g, g]
            };
            image.put_pixel(x, y, rgba(colour));
        }
    }
    draw_legend(
        &mut image,
        height,
        "1",
        &max.max(1).to_string(),
        &|t| sequential(0.25 + 0.75 * t),
        "/255 apart",
    );
    (image, max)
}

fn rgba(c: [u8; 3]) -> Rgba<u8> {
    Rgba([c[0], c[1], c[2], 255])
}

/// Draws the legend strip at row `top`: `low`, the colour bar, `high`, then `words`.
fn draw_legend(image: &mut RgbaImage, top: u32, low: &str, high: &str, bar: &dyn Fn(f64) -> [u8; 3], words: &str) {
    let width = image.width();
    for y in top..image.height() {
        for x in 0..width {
            image.put_pixel(x, y, Rgba([LEGEND_GREY, LEGEND_GREY, LEGEND_GREY, 255]));
        }
    }
    let text_y = top + (LEGEND_HEIGHT - 10) / 2;
    let mut x = 4;
    x = draw_text(image, x, text_y, low) + 4;
    let bar_width = (width / 3).clamp(16, 256);
    for k in 0..bar_width {
        let c = bar(f64::from(k) / f64::from(bar_width.max(2) - 1));
        for y in top + 3..top + LEGEND_HEIGHT - 3 {
            if x + k < width {
                image.put_pixel(x + k, y, rgba(c));
            }
        }
    }
    x += bar_width + 4;
    x = draw_text(image, x, text_y, high) + 12;
    draw_text(image, x, text_y, words);
}

/// The 3×5 glyphs of the legend's characters: five rows of three bits, the top row first.
fn glyph(c: char) -> [u8; 5] {
    match c.to_ascii_lowercase() {
        '0' => [7, 5, 5, 5, 7],
        '1' => [2, 6, 2, 2, 7],
        '2' => [7, 1, 7, 4, 7],
        '3' => [7, 1, 7, 1, 7],
        '4' => [5, 5, 7, 1, 1],
        '5' => [7, 4, 7, 1, 7],
        '6' => [7, 4, 7, 5, 7],
        '7' => [7, 1, 1, 2, 2],
        '8' => [7, 5, 7, 5, 7],
        '9' => [7, 5, 7, 1, 7],
        '.' => [0, 0, 0, 0, 2],
        '-' => [0, 0, 7, 0, 0],
        '+' => [0, 2, 7, 2, 0],
        '/' => [1, 1, 2, 4, 4],
        ' ' => [0, 0, 0, 0, 0],
        'a' => [2, 5, 7, 5, 5],
        'e' => [7, 4, 6, 4, 7],
        'f' => [7, 4, 6, 4, 4],
        'i' => [7, 2, 2, 2, 7],
        'm' => [5, 7, 7, 5, 5],
        'n' => [6, 5, 5, 5, 5],
        'o' => [2, 5, 5, 5, 2],
        'p' => [6, 5, 6, 4, 4],
        'r' => [6, 5, 6, 5, 5],
        's' => [3, 4, 2, 1, 6],
        't' => [7, 2, 2, 2, 2],
        'u' => [5, 5, 5, 5, 7],
        _ => [7, 5, 5, 5, 7],
    }
}

/// Draws `text` at (x, y) at twice the glyphs' size in light grey; returns the x after it.
fn draw_text(image: &mut RgbaImage, mut x: u32, y: u32, text: &str) -> u32 {
    for c in text.chars() {
        let g = glyph(c);
        for (row, bits) in g.iter().enumerate() {
            for col in 0..3u32 {
                if bits & (4 >> col) == 0 {
                    continue;
                }
                for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    let (px, py) = (x + 2 * col + dx, y + 2 * row as u32 + dy);
                    if px < image.width() && py < image.height() {
                        image.put_pixel(px, py, Rgba([230, 230, 230, 255]));
                    }
                }
            }
        }
        x += 8;
    }
    x
}

/// The NPY (version 1.0) header of a little-endian float32 array of `shape`, C order:
/// magic, version, header length, the dictionary padded with spaces to a multiple of 64 bytes
/// in all, ending in a newline.
pub fn npy_header(shape: &[usize]) -> Vec<u8> {
    let dims: Vec<String> = shape.iter().map(usize::to_string).collect();
    let shape = if dims.len() == 1 {
        format!("({},)", dims[0])
    } else {
        format!("({})", dims.join(", "))
    };
    let mut dict = format!("{{'descr': '<f4', 'fortran_order': False, 'shape': {shape}, }}");
    let unpadded = 10 + dict.len() + 1;
    dict.push_str(&" ".repeat((64 - unpadded % 64) % 64));
    dict.push('\n');
    let mut out = Vec::with_capacity(10 + dict.len());
    out.extend_from_slice(b"\x93NUMPY\x01\x00");
    out.extend_from_slice(&(dict.len() as u16).to_le_bytes());
    out.extend_from_slice(dict.as_bytes());
    out
}

/// Writes a value frame as a NumPy array of height × width × `components` float32 (little
/// endian), NaN where the line did not run, to `path` through the crate's safe output (a
/// temporary file renamed into place, never over one of the run's inputs).
pub fn write_npy(
    path: &Path,
    width: u32,
    height: u32,
    components: usize,
    values: &[[f32; 4]],
    ran: &[bool],
) -> Result<()> {
    let comps = components.clamp(1, 4);
    let n = (width as usize) * (height as usize);
    crate::fsutil::write_atomic(path, |out: &mut dyn Write| {
        let mut out = std::io::BufWriter::new(out);
        out.write_all(&npy_header(&[height as usize, width as usize, comps]))?;
        for k in 0..n {
            let v = values.get(k).filter(|_| ran.get(k) == Some(&true));
            for c in 0..comps {
                let x = v.map_or(f32::NAN, |v| v[c]);
                out.write_all(&x.to_le_bytes())?;
            }
        }
        out.flush()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_maps_end_where_they_should_and_diverge_around_grey() {
        assert_eq!(sequential(0.0), VIRIDIS[0]);
        assert_eq!(sequential(1.0), VIRIDIS[8]);
        assert_eq!(sequential(-3.0), VIRIDIS[0]);
        assert_eq!(sequential(7.0), VIRIDIS[8]);
        assert_eq!(diverging(0.0), [221, 221, 221]);
        assert_eq!(diverging(-1.0), [59, 76, 192]);
        assert_eq!(diverging(1.0), [180, 4, 38]);
        // Lightness rises along the sequential map.
        let light = |c: [u8; 3]| 0.299 * f64::from(c[0]) + 0.587 * f64::from(c[1]) + 0.114 * f64::from(c[2]);
        let mut last = -1.0;
        for k in 0..=20 {
            let l = light(sequential(f64::from(k) / 20.0));
            assert!(l > last, "step {k}: {l} after {last}");
            last = l;
        }
    }

    #[test]
    fn a_value_that_changes_sign_is_diverging_with_grey_at_zero() {
        let v = [
            [-2.0, 0., 0., 0.],
            [0.0, 0., 0., 0.],
            [1.0, 0., 0., 0.],
            [0.5, 0., 0., 0.],
        ];
        let (image, legend) = values(2, 2, 1, &v, &[true; 4], &[true; 4]);
        assert_eq!(legend.scale, Scale::Diverging);
        assert_eq!((legend.min, legend.max), (-2.0, 2.0));
        assert_eq!(image.get_pixel(1, 0).0, [221, 221, 221, 255]);
        assert_eq!(image.get_pixel(0, 0).0, [59, 76, 192, 255]);
        assert_eq!(image.height(), 2 + LEGEND_HEIGHT);
        // A value that keeps its sign is sequential over its own range.
        let v = [[1.0, 0., 0., 0.], [3.0, 0., 0., 0.]];
        let (image, legend) = values(2, 1, 1, &v, &[true; 2], &[true; 2]);
        assert_eq!((legend.scale, legend.min, legend.max), (Scale::Sequential, 1.0, 3.0));
        assert_eq!(&image.get_pixel(0, 0).0[..3], &VIRIDIS[0]);
        assert_eq!(&image.get_pixel(1, 0).0[..3], &VIRIDIS[8]);
    }

    #[test]
    fn nan_infinity_not_run_and_background_have_colours_of_their_own_and_are_counted() {
        let v = [
            [f32::NAN, 0., 0., 0.],
            [f32::INFINITY, 0., 0., 0.],
            [f32::NEG_INFINITY, 0., 0., 0.],
            [0.5, 0., 0., 0.],
            [0.7, 0., 0., 0.],
            [0.9, 0., 0., 0.],
        ];
        let ran = [true, true, true, false, true, true];
        let drawn = [true, true, true, true, true, false];
        let (image, legend) = values(6, 1, 1, &v, &ran, &drawn);
        assert_eq!(&image.get_pixel(0, 0).0[..3], &NAN_COLOUR);
        assert_eq!(&image.get_pixel(1, 0).0[..3], &INFINITE_COLOUR);
        assert_eq!(&image.get_pixel(2, 0).0[..3], &INFINITE_COLOUR);
        assert!(NOT_RUN.iter().any(|c| &image.get_pixel(3, 0).0[..3] == c));
        assert_eq!(&image.get_pixel(5, 0).0[..3], &BACKGROUND);
        assert_eq!(
            (
                legend.nan,
                legend.pos_inf,
                legend.neg_inf,
                legend.not_run,
                legend.background
            ),
            (1, 1, 1, 1, 1)
        );
        // The range leaves out what is not a number, what did not run and what was not drawn.
        assert_eq!((legend.min, legend.max), (f64::from(0.7f32), f64::from(0.7f32)));
        assert!(legend.text().contains("NaN 1"), "{}", legend.text());
    }

    #[test]
    fn a_vector_is_rgb_over_its_stated_range() {
        let v = [[1.0, 0.0, 0.5, 9.0], [0.0, 1.0, 0.0, 9.0]];
        let (image, legend) = values(2, 1, 3, &v, &[true; 2], &[true; 2]);
        assert_eq!((legend.scale, legend.min, legend.max), (Scale::Rgb, 0.0, 1.0));
        assert_eq!(image.get_pixel(0, 0).0, [255, 0, 128, 255]);
        let v = [[-1.0, 1.0, 0.0, 0.0]];
        let (image, legend) = values(1, 1, 3, &v, &[true], &[true]);
        assert_eq!((legend.min, legend.max), (-1.0, 1.0));
        assert_eq!(image.get_pixel(0, 0).0, [0, 255, 128, 255]);
    }

    #[test]
    fn cost_and_difference_pictures_scale_to_their_largest() {
        let (image, max) = cost(3, 1, &[0, 5, 10], &[false, true, true]);
        assert_eq!(max, 10);
        assert_eq!(&image.get_pixel(0, 0).0[..3], &BACKGROUND);
        assert_eq!(&image.get_pixel(2, 0).0[..3], &VIRIDIS[8]);
        let a = RgbaImage::from_pixel(2, 1, Rgba([100, 100, 100, 255]));
        let mut b = a.clone();
        b.put_pixel(1, 0, Rgba([100, 140, 100, 255]));
        let (image, max) = difference(&b, &a);
        assert_eq!(max, 40);
        assert_eq!(&image.get_pixel(1, 0).0[..3], &VIRIDIS[8]);
        assert_eq!(image.get_pixel(0, 0).0, [35, 35, 35, 255]);
    }

    #[test]
    fn the_npy_header_reads_back_as_numpy_reads_it() {
        let header = npy_header(&[360, 640, 3]);
        assert_eq!(&header[..8], b"\x93NUMPY\x01\x00");
        let len = u16::from_le_bytes([header[8], header[9]]) as usize;
        assert_eq!(header.len(), 10 + len);
        assert_eq!(header.len() % 64, 0);
        let dict = std::str::from_utf8(&header[10..]).expect("ASCII");
        assert!(dict.ends_with('\n'));
        assert_eq!(
            dict.trim_end(),
            "{'descr': '<f4', 'fortran_order': False, 'shape': (360, 640, 3), }"
        );
        let dir = std::env::temp_dir().join(format!("shaderlab-npy-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a folder");
        let path = dir.join("v.npy");
        let v = [[1.5, -2.0, 0., 0.], [7.0, 8.0, 0., 0.]];
        write_npy(&path, 2, 1, 2, &v, &[true, false]).expect("written");
        let bytes = std::fs::read(&path).expect("read back");
        let _ = std::fs::remove_dir_all(&dir);
        let head = npy_header(&[1, 2, 2]);
        assert_eq!(&bytes[..head.len()], &head[..]);
        let data: Vec<f32> = bytes[head.len()..]
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect();
        assert_eq!(data.len(), 4);
        assert_eq!(&data[..2], &[1.5, -2.0]);
        assert!(data[2].is_nan() && data[3].is_nan());
    }
}
