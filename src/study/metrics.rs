//! Image statistics used by the tests and the speed/accuracy tools: PSNR against a reference,
//! coverage (pixels that differ from the background), mean colour of a region, the brightest
//! spot, and a difference image for people to look at.

use image::{Rgb, RgbImage};

/// Peak signal-to-noise ratio in dB over the RGB channels (8-bit). Identical images give infinity.
/// Images of different sizes give `None`.
pub fn psnr(a: &RgbImage, b: &RgbImage) -> Option<f64> {
    let mse = mse(a, b)?;
    Some(if mse == 0.0 {
        f64::INFINITY
    } else {
        10.0 * (255.0f64 * 255.0 / mse).log10()
    })
}

/// Mean squared error over the RGB channels (8-bit units).
pub fn mse(a: &RgbImage, b: &RgbImage) -> Option<f64> {
    if a.dimensions() != b.dimensions() {
        return None;
    }
    let sum: f64 = a
        .as_raw()
        .iter()
        .zip(b.as_raw())
        .map(|(&x, &y)| {
            let d = x as f64 - y as f64;
            d * d
        })
        .sum();
    Some(sum / a.as_raw().len().max(1) as f64)
}

/// Root-mean-square error over the RGB channels (8-bit units); `None` for different sizes.
pub fn rmse(a: &RgbImage, b: &RgbImage) -> Option<f64> {
    mse(a, b).map(f64::sqrt)
}

/// Pixels where some channel differs by more than `threshold` (8-bit units): what a person
/// sees as a different pixel, where PSNR mixes many small differences with few large ones.
/// `None` for different sizes.
pub fn pixels_off(a: &RgbImage, b: &RgbImage, threshold: u8) -> Option<usize> {
    (a.dimensions() == b.dimensions()).then(|| {
        a.pixels()
            .zip(b.pixels())
            .filter(|(p, q)| p.0.iter().zip(q.0.iter()).any(|(x, y)| x.abs_diff(*y) > threshold))
            .count()
    })
}

/// `image` box-filtered down by `n` on each side (each pixel the rounded mean of its n × n
/// block): a supersampled rendering brought to the size it stands for.
pub fn box_downsample(image: &RgbImage, n: u32) -> RgbImage {
    let n = n.max(1);
    RgbImage::from_fn(image.width() / n, image.height() / n, |x, y| {
        let mut sum = [0u32; 3];
        for j in 0..n {
            for i in 0..n {
                let p = image.get_pixel(x * n + i, y * n + j).0;
                (0..3).for_each(|c| sum[c] += u32::from(p[c]));
            }
        }
        let count = n * n;
        Rgb(sum.map(|s| ((s + count / 2) / count) as u8))
    })
}

/// Largest absolute channel difference.
pub fn max_abs_diff(a: &RgbImage, b: &RgbImage) -> Option<u8> {
    (a.dimensions() == b.dimensions()).then(|| {
        a.as_raw()
            .iter()
            .zip(b.as_raw())
            .map(|(&x, &y)| x.abs_diff(y))
            .max()
            .unwrap_or(0)
    })
}

/// A picture of where two images differ: the absolute difference, amplified 4x.
pub fn diff_image(a: &RgbImage, b: &RgbImage) -> Option<RgbImage> {
    (a.dimensions() == b.dimensions()).then(|| {
        RgbImage::from_fn(a.width(), a.height(), |x, y| {
            let (p, q) = (a.get_pixel(x, y), b.get_pixel(x, y));
            Rgb([0, 1, 2].map(|c| (p[c].abs_diff(q[c]) as u16 * 4).min(255) as u8))
        })
    })
}

/// Pixels whose colour differs from `background` by more than `tolerance` in any channel.
pub fn mask(image: &RgbImage, background: [u8; 3], tolerance: u8) -> Vec<bool> {
    image
        .pixels()
        .map(|p| (0..3).any(|c| p[c].abs_diff(background[c]) > tolerance))
        .collect()
}

/// Fraction of pixels that are not background.
pub fn coverage(image: &RgbImage, background: [u8; 3]) -> f64 {
    let m = mask(image, background, 2);
    m.iter().filter(|&&b| b).count() as f64 / m.len().max(1) as f64
}

/// Bounding box (x0, y0, x1, y1) inclusive of the non-background pixels.
pub fn bounding_box(image: &RgbImage, background: [u8; 3]) -> Option<(u32, u32, u32, u32)> {
    let m = mask(image, background, 2);
    let w = image.width();
    let mut bbox: Option<(u32, u32, u32, u32)> = None;
    for (i, &on) in m.iter().enumerate() {
        if on {
            let (x, y) = (i as u32 % w, i as u32 / w);
            bbox = Some(match bbox {
                None => (x, y, x, y),
                Some((x0, y0, x1, y1)) => (x0.min(x), y0.min(y), x1.max(x), y1.max(y)),
            });
        }
    }
    bbox
}

/// Mean RGB (0..255) of the pixels in the rectangle [x0, x1) x [y0, y1), optionally only those not
/// equal to `background`.
pub fn mean_color(image: &RgbImage, rect: (u32, u32, u32, u32), background: Option<[u8; 3]>) -> [f64; 3] {
    let (x0, y0, x1, y1) = rect;
    let mut sum = [0.0; 3];
    let mut n = 0.0;
    for y in y0..y1.min(image.height()) {
        for x in x0..x1.min(image.width()) {
            let p = image.get_pixel(x, y);
            if let Some(bg) = background {
                if (0..3).all(|c| p[c].abs_diff(bg[c]) <= 2) {
                    continue;
                }
            }
            for c in 0..3 {
                sum[c] += p[c] as f64;
            }
            n += 1.0;
        }
    }
    sum.map(|s| if n > 0.0 { s / n } else { 0.0 })
}

/// Centroid of the brightest pixels (luma within `within` of the maximum): where the highlight is.
pub fn highlight(image: &RgbImage, within: f64) -> (f64, f64) {
    let luma = |p: &Rgb<u8>| 0.299 * p[0] as f64 + 0.587 * p[1] as f64 + 0.114 * p[2] as f64;
    let max = image.pixels().map(luma).fold(0.0f64, f64::max);
    let (mut sx, mut sy, mut n) = (0.0f64, 0.0f64, 0.0f64);
    for (x, y, p) in image.enumerate_pixels() {
        if luma(p) >= max - within {
            sx += x as f64;
            sy += y as f64;
            n += 1.0;
        }
    }
    (sx / n.max(1.0), sy / n.max(1.0))
}

/// Mean and variance of luma (0..1) over the pixels selected by `mask`.
pub fn luma_stats(image: &RgbImage, mask: &[bool]) -> (f64, f64) {
    let values: Vec<f64> = image
        .pixels()
        .zip(mask)
        .filter(|(_, &m)| m)
        .map(|(p, _)| (0.299 * p[0] as f64 + 0.587 * p[1] as f64 + 0.114 * p[2] as f64) / 255.0)
        .collect();
    let n = values.len().max(1) as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n;
    (mean, var)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pixels_off_and_box_downsample() {
        let a = RgbImage::from_fn(4, 4, |x, _| Rgb([if x < 2 { 0 } else { 200 }, 0, 0]));
        let mut b = a.clone();
        b.put_pixel(0, 0, Rgb([26, 0, 0]));
        b.put_pixel(1, 0, Rgb([25, 0, 0]));
        assert_eq!(pixels_off(&a, &b, 25), Some(1));
        assert_eq!(pixels_off(&a, &RgbImage::new(2, 2), 25), None);
        let small = box_downsample(&a, 2);
        assert_eq!(small.dimensions(), (2, 2));
        assert_eq!(small.get_pixel(0, 0).0, [0, 0, 0]);
        assert_eq!(small.get_pixel(1, 1).0, [200, 0, 0]);
        assert_eq!(rmse(&a, &a), Some(0.0));
    }
}
