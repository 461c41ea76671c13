//! FLIP, the perceptual difference of Andersson, Nilsson, Akenine-Möller, Oskarsson,
//! Åström & Fairchild, "FLIP: A Difference Evaluator for Alternating Images"
//! (HPG 2020), and its high-dynamic-range form, Andersson, Nilsson, Shirley &
//! Akenine-Möller, "Visualizing Errors in Rendered High Dynamic Range Images"
//! (Eurographics 2021); the figure pbrt-v4's `imgtool diff --metric FLIP` and
//! NVIDIA's `flip` tool report.
//!
//! LDR-FLIP, per pixel: both images go to the opponent space YCxCz and are blurred
//! by the contrast sensitivity of the eye at the viewing distance (sums of
//! Gaussians, separable), clamped to the display's gamut, taken to CIELab with
//! Hunt's adjustment, and their HyAB distance is compressed to [0, 1]. Edges and
//! points (first and second derivatives of a Gaussian on the luminance) that one
//! image has and the other lacks raise that colour error: `E = ΔC^(1 − ΔF)`.
//! HDR-FLIP exposes both images over a range of exposures found from the
//! reference, tone-maps each (ACES), and keeps each pixel's largest LDR-FLIP.
//!
//! Arithmetic is single precision in the order of NVIDIA's implementation, so the
//! two agree to rounding (tests/suite/image_io/flip.rs compares them); borders repeat
//! the edge pixel as theirs do.

use super::super::Image;
use crate::error::{Error, Result};
use glam::Vec3;
use rayon::prelude::*;
use std::f32::consts::PI;

/// Pixels per degree of visual angle of FLIP's default viewing: a 0.7 m wide,
/// 3840-pixel monitor seen from 0.7 m (67.0206).
pub fn default_pixels_per_degree() -> f32 {
    pixels_per_degree(0.7, 3840.0, 0.7)
}

/// Pixels per degree of a monitor `width_m` metres and `width_px` pixels wide,
/// seen from `distance_m` metres.
pub fn pixels_per_degree(distance_m: f32, width_px: f32, width_m: f32) -> f32 {
    distance_m * (width_px / width_m) * (PI / 180.0)
}

/// The dynamic range FLIP assumes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FlipRange {
    /// The images as displayed: linear values clamped to [0, 1].
    Ldr,
    /// Linear radiance, exposed from `start` to `stop` stops (found from the
    /// reference when `None`) in `exposures` steps (at least one a stop when
    /// `None`), each tone-mapped by ACES.
    Hdr {
        /// First exposure, in stops.
        start: Option<f32>,
        /// Last exposure, in stops.
        stop: Option<f32>,
        /// Number of exposures (2 or more).
        exposures: Option<u32>,
    },
}

/// FLIP's error map and the figures drawn from it.
#[derive(Clone, Debug, PartialEq)]
pub struct Flip {
    /// Per-pixel error, 0 (indistinguishable) to 1, row-major.
    pub map: Vec<f32>,
    /// The map's mean: the single figure FLIP's authors recommend.
    pub mean: f64,
    /// HDR-FLIP: the exposures used (first, last, count).
    pub exposures: Option<(f32, f32, u32)>,
}

impl Flip {
    /// The `p`-th percentile of the error map (`p` in [0, 100]), the nearest rank.
    pub fn percentile(&self, p: f64) -> f32 {
        let mut sorted = self.map.clone();
        sorted.sort_by(f32::total_cmp);
        let rank = ((p / 100.0) * sorted.len() as f64).ceil() as usize;
        sorted[rank.clamp(1, sorted.len()) - 1]
    }
}

/// FLIP of `test` against `reference` (linear images of the same size), at
/// `ppd` pixels per degree.
pub fn flip(reference: &Image, test: &Image, range: FlipRange, ppd: f32) -> Result<Flip> {
    super::same_size(reference, test)?;
    if !(ppd.is_finite() && ppd > 0.0) {
        return Err(Error::invalid(
            "pixels-per-degree",
            format!("{ppd}: must be a positive number"),
        ));
    }
    let (w, h) = (reference.width as usize, reference.height as usize);
    match range {
        FlipRange::Ldr => {
            let clamp = |i: &Image| i.pixels.iter().map(|p| clamp01(*p)).collect::<Vec<_>>();
            let map = ldr_flip(&clamp(reference), &clamp(test), w, h, ppd);
            Ok(Flip {
                mean: mean(&map),
                map,
                exposures: None,
            })
        }
        FlipRange::Hdr {
            start,
            stop,
            exposures,
        } => {
            let (found_start, found_stop) = match (start, stop) {
                (Some(a), Some(b)) => (a, b),
                _ => exposure_range(&reference.pixels)?,
            };
            let (start, stop) = (start.unwrap_or(found_start), stop.unwrap_or(found_stop));
            if !(start.is_finite() && stop.is_finite()) || start > stop {
                return Err(Error::invalid(
                    "flip exposures",
                    format!(
                        "from {start} to {stop}: the first must be finite and not above the last"
                    ),
                ));
            }
            let count = exposures.unwrap_or_else(|| ((stop - start).ceil() as u32).max(2));
            if count < 2 {
                return Err(Error::invalid(
                    "flip exposures",
                    format!("{count}: HDR-FLIP needs at least 2 exposures"),
                ));
            }
            let step = (stop - start) / (count - 1) as f32;
            let mut map = vec![0.0f32; w * h];
            for i in 0..count {
                let exposure = start + i as f32 * step;
                let shown = |img: &Image| -> Vec<Vec3> {
                    let m = 2f32.powf(exposure);
                    img.pixels.iter().map(|p| clamp01(aces(*p * m))).collect()
                };
                let level = ldr_flip(&shown(reference), &shown(test), w, h, ppd);
                for (kept, e) in map.iter_mut().zip(level) {
                    if e > *kept {
                        *kept = e;
                    }
                }
            }
            Ok(Flip {
                mean: mean(&map),
                map,
                exposures: Some((start, stop, count)),
            })
        }
    }
}

fn mean(map: &[f32]) -> f64 {
    map.iter().map(|&e| e as f64).sum::<f64>() / map.len().max(1) as f64
}

fn clamp01(p: Vec3) -> Vec3 {
    p.clamp(Vec3::ZERO, Vec3::ONE)
}

/// ACES's filmic curve as FLIP fits it (Narkowicz's fit with the 0.6 pre-exposure
/// folded into its coefficients): `(T0 c² + T1 c + T2) / (T3 c² + T4 c + T5)`.
const ACES: [f32; 6] = [
    0.6 * 0.6 * 2.51,
    0.6 * 0.03,
    0.0,
    0.6 * 0.6 * 2.43,
    0.6 * 0.59,
    0.14,
];

/// The ACES curve, per channel.
fn aces(c: Vec3) -> Vec3 {
    let t = ACES;
    (c * c * t[0] + c * t[1] + t[2]) / (c * c * t[3] + c * t[4] + t[5])
}

/// HDR-FLIP's exposures from the reference: the first brings its brightest pixel,
/// the last its median one, to 0.85 after tone mapping.
fn exposure_range(pixels: &[Vec3]) -> Result<(f32, f32)> {
    // x where aces(x) = 0.85: the larger root of (T0 − tT3) x² + (T1 − tT4) x + (T2 − tT5).
    let t = 0.85f32;
    let [t0, t1, t2, t3, t4, t5] = ACES;
    let (a, b, c) = (t0 - t * t3, t1 - t * t4, t2 - t * t5);
    let half = -0.5 * (b / a);
    let x_max = half + (half * half - c / a).sqrt();
    let mut luminances: Vec<f32> = pixels.iter().map(|p| luminance(*p)).collect();
    let y_max = luminances.iter().copied().fold(-1e30f32, f32::max);
    let middle = luminances.len() / 2;
    let (_, &mut y_median, _) = luminances.select_nth_unstable_by(middle, f32::total_cmp);
    if !(y_median > 0.0 && y_max.is_finite()) {
        return Err(Error::invalid(
            "flip exposures",
            format!(
                "the reference's median luminance is {y_median}: HDR-FLIP cannot find its exposures; give them"
            ),
        ));
    }
    Ok(((x_max / y_max).log2(), (x_max / y_median).log2()))
}

fn luminance(p: Vec3) -> f32 {
    0.2126 * p.x + 0.7152 * p.y + 0.0722 * p.z
}

// Colour spaces (D65), with the constants of NVIDIA's implementation, written with
// its nine digits (more than an f32 holds) so they read as theirs do.
#[allow(clippy::excessive_precision)]
const WHITE: Vec3 = Vec3::new(0.950428545, 1.0, 1.088900371);
#[allow(clippy::excessive_precision)]
const INVERSE_WHITE: Vec3 = Vec3::new(1.052156925, 1.0, 0.918357670);

fn rgb_to_xyz(c: Vec3) -> Vec3 {
    Vec3::new(
        (10135552.0 / 24577794.0) * c.x
            + (8788810.0 / 24577794.0) * c.y
            + (4435075.0 / 24577794.0) * c.z,
        (2613072.0 / 12288897.0) * c.x
            + (8788810.0 / 12288897.0) * c.y
            + (887015.0 / 12288897.0) * c.z,
        (1425312.0 / 73733382.0) * c.x
            + (8788810.0 / 73733382.0) * c.y
            + (70074185.0 / 73733382.0) * c.z,
    )
}

#[allow(clippy::excessive_precision)]
fn xyz_to_rgb(c: Vec3) -> Vec3 {
    Vec3::new(
        3.241003275 * c.x + -1.537398934 * c.y + -0.498615861 * c.z,
        -0.969224334 * c.x + 1.875930071 * c.y + 0.041554224 * c.z,
        0.055639423 * c.x + -0.204011202 * c.y + 1.057148933 * c.z,
    )
}

fn xyz_to_ycxcz(c: Vec3) -> Vec3 {
    let c = c * INVERSE_WHITE;
    Vec3::new(116.0 * c.y - 16.0, 500.0 * (c.x - c.y), 200.0 * (c.y - c.z))
}

fn ycxcz_to_xyz(c: Vec3) -> Vec3 {
    let y = (c.x + 16.0) / 116.0;
    Vec3::new(y + c.y / 500.0, y, y - c.z / 200.0) * WHITE
}

fn xyz_to_lab(c: Vec3) -> Vec3 {
    let delta = 6.0f32 / 29.0;
    let delta_cube = delta * delta * delta;
    let slope = 1.0 / (3.0 * delta * delta);
    let f = |v: f32| {
        if v > delta_cube {
            v.powf(1.0 / 3.0)
        } else {
            slope * v + 4.0 / 29.0
        }
    };
    let c = c * INVERSE_WHITE;
    let (x, y, z) = (f(c.x), f(c.y), f(c.z));
    Vec3::new(116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z))
}

/// Hunt's adjustment: chroma scaled by lightness, so dark colours differ less.
fn hunt(lab: Vec3) -> Vec3 {
    Vec3::new(lab.x, 0.01 * lab.x * lab.y, 0.01 * lab.x * lab.z)
}

/// HyAB: city-block lightness plus Euclidean chroma distance.
fn hyab(a: Vec3, b: Vec3) -> f32 {
    (a.x - b.x).abs() + ((a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z)).sqrt()
}

const QC: f32 = 0.7;
const PC: f32 = 0.4;
const PT: f32 = 0.95;
const W: f32 = 0.082;
const QF: f32 = 0.5;

/// The contrast sensitivity functions as sums of Gaussians a·sqrt(π/b)·exp(−π²x²/b)
/// (achromatic, red-green, blue-yellow; only blue-yellow has a second term).
const A1: [f32; 3] = [1.0, 1.0, 34.1];
const B1: [f32; 3] = [0.0047, 0.0053, 0.04];
const A2: [f32; 3] = [0.0, 0.0, 13.5];
const B2: [f32; 3] = [1.0e-5, 1.0e-5, 0.025];

/// The spatial filters, one row each, normalised: achromatic and red-green sum to
/// one; blue-yellow's two Gaussians are applied as square roots in each direction
/// (so their separable product is the sum of two Gaussians), their joint weight
/// one.
struct SpatialFilters {
    y: Vec<f32>,
    cx: Vec<f32>,
    cz1: Vec<f32>,
    cz2: Vec<f32>,
}

fn spatial_filters(ppd: f32) -> SpatialFilters {
    let largest_b = B1.iter().chain(&B2).copied().fold(0.0f32, f32::max);
    let radius = (3.0 * (largest_b / (2.0 * PI * PI)).sqrt() * ppd).ceil() as i32;
    let dx = 1.0 / ppd;
    let gauss = |x2: f32, a: f32, b: f32| a * (PI / b).sqrt() * (-PI * PI * x2 / b).exp();
    let gauss_root =
        |x2: f32, a: f32, b: f32| (a * (PI / b).sqrt()).sqrt() * (-PI * PI * x2 / b).exp();
    let mut f = SpatialFilters {
        y: Vec::new(),
        cx: Vec::new(),
        cz1: Vec::new(),
        cz2: Vec::new(),
    };
    for i in -radius..=radius {
        let x = i as f32 * dx;
        let x2 = x * x;
        f.y.push(gauss(x2, A1[0], B1[0]));
        f.cx.push(gauss(x2, A1[1], B1[1]));
        f.cz1.push(gauss_root(x2, A1[2], B1[2]));
        f.cz2.push(gauss_root(x2, A2[2], B2[2]));
    }
    let sum = |v: &[f32]| v.iter().sum::<f32>();
    let (sy, scx, s1, s2) = (sum(&f.y), sum(&f.cx), sum(&f.cz1), sum(&f.cz2));
    let cz_norm = 1.0 / (s1 * s1 + s2 * s2).sqrt();
    f.y.iter_mut().for_each(|v| *v *= 1.0 / sy);
    f.cx.iter_mut().for_each(|v| *v *= 1.0 / scx);
    f.cz1.iter_mut().for_each(|v| *v *= cz_norm);
    f.cz2.iter_mut().for_each(|v| *v *= cz_norm);
    f
}

/// The feature filters, one row each: a Gaussian of deviation `0.5 w ppd` summing
/// to one, and its first and second derivatives whose positive and negative
/// weights each sum to one.
struct FeatureFilters {
    gauss: Vec<f32>,
    first: Vec<f32>,
    second: Vec<f32>,
}

fn feature_filters(ppd: f32) -> FeatureFilters {
    let sigma = 0.5 * W * ppd;
    let radius = (3.0 * sigma).ceil() as i32;
    let mut f = FeatureFilters {
        gauss: Vec::new(),
        first: Vec::new(),
        second: Vec::new(),
    };
    let (mut g_sum, mut d_pos, mut d_neg, mut dd_pos, mut dd_neg) =
        (0.0f32, 0.0f32, 0.0f32, 0.0f32, 0.0f32);
    for i in -radius..=radius {
        let x = i as f32;
        let g = (-(x * x) / (2.0 * sigma * sigma)).exp();
        let d = -x * g;
        let dd = (x * x / (sigma * sigma) - 1.0) * g;
        g_sum += g;
        if d > 0.0 {
            d_pos += d
        } else {
            d_neg -= d
        }
        if dd > 0.0 {
            dd_pos += dd
        } else {
            dd_neg -= dd
        }
        f.gauss.push(g);
        f.first.push(d);
        f.second.push(dd);
    }
    f.gauss.iter_mut().for_each(|v| *v /= g_sum);
    f.first
        .iter_mut()
        .for_each(|v| *v /= if *v > 0.0 { d_pos } else { d_neg });
    f.second
        .iter_mut()
        .for_each(|v| *v /= if *v > 0.0 { dd_pos } else { dd_neg });
    f
}

/// LDR-FLIP's error map of two linear images with values in [0, 1].
fn ldr_flip(reference: &[Vec3], test: &[Vec3], w: usize, h: usize, ppd: f32) -> Vec<f32> {
    let to_opponent = |image: &[Vec3]| -> Vec<Vec3> {
        image
            .par_iter()
            .map(|&p| xyz_to_ycxcz(rgb_to_xyz(p)))
            .collect()
    };
    let (reference, test) = (to_opponent(reference), to_opponent(test));
    let colour = colour_difference(&reference, &test, w, h, ppd);
    let feature = feature_difference(&reference, &test, w, h, ppd);
    colour
        .into_par_iter()
        .zip(feature)
        .map(|(c, f)| c.powf(1.0 - f))
        .collect()
}

/// The filtered colour difference, compressed to [0, 1].
fn colour_difference(reference: &[Vec3], test: &[Vec3], w: usize, h: usize, ppd: f32) -> Vec<f32> {
    let f = spatial_filters(ppd);
    let radius = (f.y.len() / 2) as isize;
    let green = hunt(xyz_to_lab(rgb_to_xyz(Vec3::Y)));
    let blue = hunt(xyz_to_lab(rgb_to_xyz(Vec3::Z)));
    let c_max = hyab(green, blue).powf(QC);
    let knee = PC * c_max;
    // Rows: (Y, Cx) through their filters, Cz through each of its two, kept apart.
    let horizontal = |image: &[Vec3]| -> Vec<[f32; 4]> {
        (0..w * h)
            .into_par_iter()
            .map(|k| {
                let (x, y) = ((k % w) as isize, k / w);
                let mut s = [0.0f32; 4];
                for i in -radius..=radius {
                    let xx = (x + i).clamp(0, w as isize - 1) as usize;
                    let p = image[y * w + xx];
                    let j = (i + radius) as usize;
                    s[0] += f.y[j] * p.x;
                    s[1] += f.cx[j] * p.y;
                    s[2] += f.cz1[j] * p.z;
                    s[3] += f.cz2[j] * p.z;
                }
                s
            })
            .collect()
    };
    let (rh, th) = (horizontal(reference), horizontal(test));
    (0..w * h)
        .into_par_iter()
        .map(|k| {
            let (x, y) = (k % w, (k / w) as isize);
            let mut r = [0.0f32; 4];
            let mut t = [0.0f32; 4];
            for i in -radius..=radius {
                let yy = (y + i).clamp(0, h as isize - 1) as usize;
                let j = (i + radius) as usize;
                let weights = [f.y[j], f.cx[j], f.cz1[j], f.cz2[j]];
                for c in 0..4 {
                    r[c] += weights[c] * rh[yy * w + x][c];
                    t[c] += weights[c] * th[yy * w + x][c];
                }
            }
            let lab = |s: [f32; 4]| {
                let rgb = xyz_to_rgb(ycxcz_to_xyz(Vec3::new(s[0], s[1], s[2] + s[3])));
                hunt(xyz_to_lab(rgb_to_xyz(clamp01(rgb))))
            };
            let d = hyab(lab(r), lab(t)).powf(QC);
            if d < knee {
                d * (PT / knee)
            } else {
                PT + ((d - knee) / (c_max - knee)) * (1.0 - PT)
            }
        })
        .collect()
}

/// The difference of edges and points on the luminance, in [0, 1].
fn feature_difference(reference: &[Vec3], test: &[Vec3], w: usize, h: usize, ppd: f32) -> Vec<f32> {
    let f = feature_filters(ppd);
    let radius = (f.gauss.len() / 2) as isize;
    // Lightness in [0, 1]; per pixel: x-derivative, second x-derivative, Gaussian.
    let horizontal = |image: &[Vec3]| -> Vec<[f32; 3]> {
        (0..w * h)
            .into_par_iter()
            .map(|k| {
                let (x, y) = ((k % w) as isize, k / w);
                let mut s = [0.0f32; 3];
                for i in -radius..=radius {
                    let xx = (x + i).clamp(0, w as isize - 1) as usize;
                    let v = image[y * w + xx].x * (1.0 / 116.0) + 16.0 / 116.0;
                    let j = (i + radius) as usize;
                    s[0] += f.first[j] * v;
                    s[1] += f.second[j] * v;
                    s[2] += f.gauss[j] * v;
                }
                s
            })
            .collect()
    };
    let (rh, th) = (horizontal(reference), horizontal(test));
    let features = |rows: &[[f32; 3]], x: usize, y: isize| -> (f32, f32) {
        let (mut dx, mut ddx, mut dy, mut ddy) = (0.0f32, 0.0f32, 0.0f32, 0.0f32);
        for i in -radius..=radius {
            let yy = (y + i).clamp(0, h as isize - 1) as usize;
            let j = (i + radius) as usize;
            let s = rows[yy * w + x];
            dx += f.gauss[j] * s[0];
            ddx += f.gauss[j] * s[1];
            dy += f.first[j] * s[2];
            ddy += f.second[j] * s[2];
        }
        ((dx * dx + dy * dy).sqrt(), (ddx * ddx + ddy * ddy).sqrt())
    };
    (0..w * h)
        .into_par_iter()
        .map(|k| {
            let (x, y) = (k % w, (k / w) as isize);
            let (edge_r, point_r) = features(&rh, x, y);
            let (edge_t, point_t) = features(&th, x, y);
            let d = (edge_r - edge_t).abs().max((point_r - point_t).abs());
            ((1.0 / 2f32.sqrt()) * d).powf(QF)
        })
        .collect()
}
