//! Telling noise from bias in sampled output: a per-pixel test of a candidate
//! against a reference's per-pixel mean and variance over independent renders.
//!
//! - One candidate render: a Z-test, as Mitsuba 3's render tests do against their
//!   references at thousands of samples: under the hypothesis that the candidate
//!   samples what the reference does, `x − m` has variance `v (1 + 1/N)` (one
//!   render's, plus the mean's). With `v` estimated from the N renders the
//!   standardised difference is Student's t with N − 1 degrees of freedom (a
//!   prediction interval), which becomes the normal as N grows; that is the
//!   distribution used, so a small N does not raise the false-positive rate.
//! - A candidate's own mean and variance over M renders: Welch's t-test, as Jung,
//!   Hanika & Dachsbacher ("Detecting Bias in Monte Carlo Renderers using Welch's
//!   t-test", JCGT 2020) use it, with the Welch–Satterthwaite degrees of freedom.
//!
//! A pixel's three channels are one test at a Šidák-corrected level
//! (`1 − (1 − p_min)^3`), so `alpha` is each pixel's false-positive rate; the
//! image passes when the share of accepted pixels reaches `level`. A pixel with no
//! noise in either (variance 0: lit wholly, in full shadow) is accepted when the
//! values agree to a relative 1e-6, so a bias there is always found.

use super::super::Image;
use super::same_size;
use crate::error::{Error, Result};
use statrs::distribution::{ContinuousCDF, StudentsT};

/// Per-pixel moments of `renders` independent renders.
#[derive(Clone, Debug, PartialEq)]
pub struct Moments {
    /// Their mean.
    pub mean: Image,
    /// The unbiased variance of one render about that mean.
    pub variance: Image,
    /// How many renders (2 or more).
    pub renders: u32,
}

impl Moments {
    /// The moments of `renders`, accumulated in double precision.
    pub fn of(renders: &[Image]) -> Result<Moments> {
        let first = renders
            .first()
            .ok_or_else(|| Error::invalid("renders", "moments need at least two renders"))?;
        let mut sum = MomentsSum::new(first.width, first.height);
        for r in renders {
            sum.add(r)?;
        }
        sum.finish()
    }
}

/// Moments gathered one render at a time (Welford's update, in double precision),
/// so thousands of renders need the memory of two images, not of thousands.
pub struct MomentsSum {
    width: u32,
    height: u32,
    count: u32,
    mean: Vec<[f64; 3]>,
    squares: Vec<[f64; 3]>,
}

impl MomentsSum {
    /// No renders yet, of `width × height` pixels.
    pub fn new(width: u32, height: u32) -> MomentsSum {
        let n = width as usize * height as usize;
        MomentsSum {
            width,
            height,
            count: 0,
            mean: vec![[0.0; 3]; n],
            squares: vec![[0.0; 3]; n],
        }
    }

    /// Adds one render.
    pub fn add(&mut self, render: &Image) -> Result<()> {
        if (render.width, render.height) != (self.width, self.height) {
            return Err(Error::SizeMismatch {
                first: (self.width, self.height),
                second: (render.width, render.height),
            });
        }
        self.count += 1;
        let n = self.count as f64;
        for ((m, s), p) in self
            .mean
            .iter_mut()
            .zip(&mut self.squares)
            .zip(&render.pixels)
        {
            for c in 0..3 {
                let x = p[c] as f64;
                let delta = x - m[c];
                m[c] += delta / n;
                s[c] += delta * (x - m[c]);
            }
        }
        Ok(())
    }

    /// The mean and the unbiased variance of one render.
    pub fn finish(self) -> Result<Moments> {
        if self.count < 2 {
            return Err(Error::invalid(
                "renders",
                "moments need at least two renders",
            ));
        }
        let n = self.count as f64;
        let image = |pixels: Vec<glam::Vec3>| Image {
            width: self.width,
            height: self.height,
            pixels,
        };
        let mean = self
            .mean
            .iter()
            .map(|m| glam::Vec3::new(m[0] as f32, m[1] as f32, m[2] as f32))
            .collect();
        let variance = self
            .squares
            .iter()
            .map(|s| {
                let v = |c: usize| (s[c] / (n - 1.0)) as f32;
                glam::Vec3::new(v(0), v(1), v(2))
            })
            .collect();
        Ok(Moments {
            mean: image(mean),
            variance: image(variance),
            renders: self.count,
        })
    }
}

/// What a candidate is tested as.
pub enum Candidate<'a> {
    /// One render (Z-test).
    Render(&'a Image),
    /// Moments over its own renders (Welch's t-test).
    Moments(&'a Moments),
}

/// The outcome of the per-pixel test.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct StatisticalTest {
    /// `"z"` or `"welch"`.
    pub test: &'static str,
    /// Each pixel's false-positive rate.
    pub alpha: f64,
    /// The share of accepted pixels the image needs.
    pub level: f64,
    /// Pixels tested.
    pub pixels: u64,
    /// Pixels rejected.
    pub rejected: u64,
    /// Pixels with noise in the reference or the candidate (variance above 0).
    pub noisy: u64,
    /// The share of pixels accepted.
    pub accepted_share: f64,
    /// Whether the accepted share reaches the level.
    pub passed: bool,
}

/// Tests `candidate` against `reference` pixel by pixel (see the module's account).
pub fn statistical_test(
    reference: &Moments,
    candidate: Candidate,
    alpha: f64,
    level: f64,
) -> Result<StatisticalTest> {
    if !(alpha > 0.0 && alpha < 1.0) {
        return Err(Error::invalid(
            "alpha",
            format!("{alpha}: must lie strictly between 0 and 1"),
        ));
    }
    if !(0.0..=1.0).contains(&level) {
        return Err(Error::invalid(
            "level",
            format!("{level}: must be a share between 0 and 1"),
        ));
    }
    if reference.renders < 2 {
        return Err(Error::invalid(
            "renders",
            "a reference's variance needs at least two renders",
        ));
    }
    same_size(&reference.mean, &reference.variance)?;
    let n = reference.renders as f64;
    let (test, candidate_mean) = match &candidate {
        Candidate::Render(image) => ("z", *image),
        Candidate::Moments(m) => {
            if m.renders < 2 {
                return Err(Error::invalid(
                    "renders",
                    "a candidate's variance needs at least two renders",
                ));
            }
            same_size(&m.mean, &m.variance)?;
            ("welch", &m.mean)
        }
    };
    same_size(&reference.mean, candidate_mean)?;
    let prediction = student(n - 1.0)?;
    let mut outcome = StatisticalTest {
        test,
        alpha,
        level,
        pixels: reference.mean.pixels.len() as u64,
        rejected: 0,
        noisy: 0,
        accepted_share: 0.0,
        passed: false,
    };
    for k in 0..reference.mean.pixels.len() {
        let mut smallest_p = 1.0f64;
        let mut noisy = false;
        for c in 0..3 {
            let m = reference.mean.pixels[k][c] as f64;
            let v = reference.variance.pixels[k][c].max(0.0) as f64;
            let x = candidate_mean.pixels[k][c] as f64;
            let p = match &candidate {
                Candidate::Render(_) => {
                    let s = v * (1.0 + 1.0 / n);
                    if s > 0.0 {
                        two_sided(&prediction, (x - m).abs() / s.sqrt())
                    } else {
                        noiseless(m, x)
                    }
                }
                Candidate::Moments(cm) => {
                    let big_m = cm.renders as f64;
                    let vc = cm.variance.pixels[k][c].max(0.0) as f64;
                    let (a, b) = (vc / big_m, v / n);
                    if a + b > 0.0 {
                        let t = (x - m).abs() / (a + b).sqrt();
                        let dof = (a + b).powi(2) / (a * a / (big_m - 1.0) + b * b / (n - 1.0));
                        two_sided(&student(dof)?, t)
                    } else {
                        noiseless(m, x)
                    }
                }
            };
            noisy |= v > 0.0
                || matches!(&candidate, Candidate::Moments(cm) if cm.variance.pixels[k][c] > 0.0);
            smallest_p = smallest_p.min(if p.is_nan() { 0.0 } else { p });
        }
        let pixel_p = 1.0 - (1.0 - smallest_p).powi(3);
        outcome.rejected += u64::from(pixel_p < alpha);
        outcome.noisy += u64::from(noisy);
    }
    outcome.accepted_share = 1.0 - outcome.rejected as f64 / outcome.pixels.max(1) as f64;
    outcome.passed = outcome.accepted_share >= level;
    Ok(outcome)
}

fn student(dof: f64) -> Result<StudentsT> {
    StudentsT::new(0.0, 1.0, dof)
        .map_err(|e| Error::invalid("degrees of freedom", format!("{dof}: {e}")))
}

/// The probability of a standardised difference at least `t` either way.
fn two_sided(distribution: &StudentsT, t: f64) -> f64 {
    2.0 * distribution.sf(t)
}

/// The p-value of a pixel without noise: 1 if the values agree to a relative 1e-6
/// (the rounding of a mean stored as 32-bit floats), else 0.
fn noiseless(m: f64, x: f64) -> f64 {
    if (x - m).abs() <= 1e-6 * m.abs().max(x.abs()) {
        1.0
    } else {
        0.0
    }
}
