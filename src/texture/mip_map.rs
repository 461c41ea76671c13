//! Mip-mapping: L. Williams, "Pyramidal parametrics", Computer Graphics (SIGGRAPH '83)
//! 17(3):1–11, 1983.
//!
//! The texture is pre-filtered once at every power-of-two reduction: level 0 is the
//! image, and each texel of level k + 1 is the mean of the 2 × 2 block of level k
//! below it (a box filter), down to a single texel. At a pixel, the footprint of the
//! pixel in the texture, d texels across, selects the level λ = log₂ d; trilinear
//! lookup blends bilinear lookups in the two levels that bracket λ. Constant cost per
//! lookup, whatever the minification.
//!
//! Choices the paper leaves open, or that we make:
//! - Williams assumes a 2ⁿ × 2ⁿ image. Other sizes are resampled at load (bilinear, in
//!   linear values) up to the next power of two along each side, so that every level
//!   is an exact 2 × 2 box reduction of the one below and keeps its mean. Sides need not
//!   be equal: once one side reaches 1, texels are averaged in pairs along the other.
//! - The footprint size is d = max(|(∂u/∂x, ∂v/∂x)|, |(∂u/∂y, ∂v/∂y)|) in texels of
//!   level 0, the derivatives being those of the screen-to-texture map at the sample
//!   (the longer of the pixel's two sides in the texture).
//! - Williams stored R, G and B in three quadrants of one square with the smaller
//!   levels in the fourth; a vector of RGB levels is the same data laid out for code.

use super::texels::{Texels, Wrap};
use glam::{DVec2, Vec3};

#[derive(Clone, Debug)]
pub struct Pyramid {
    /// Level 0 (power-of-two sides) first, a 1 × 1 level last.
    pub levels: Vec<Texels>,
}

impl Pyramid {
    pub fn build(image: &Texels) -> Pyramid {
        let base = if image.width.is_power_of_two() && image.height.is_power_of_two() {
            image.clone()
        } else {
            resample(
                image,
                image.width.next_power_of_two(),
                image.height.next_power_of_two(),
            )
        };
        let mut levels = vec![base];
        loop {
            let last = levels.last().expect("level 0 exists");
            if last.width == 1 && last.height == 1 {
                break;
            }
            let next = reduce(last);
            levels.push(next);
        }
        Pyramid { levels }
    }

    /// λ = log₂ d for a footprint given by the screen derivatives of (u, v), clamped to
    /// the pyramid; 0 where the texture is magnified (d < 1).
    pub fn level(&self, derivatives: [DVec2; 2]) -> f64 {
        let base = &self.levels[0];
        let size = DVec2::new(base.width as f64, base.height as f64);
        let d = (derivatives[0] * size)
            .length()
            .max((derivatives[1] * size).length());
        if d.is_nan() || d <= 1.0 {
            return 0.0;
        }
        d.log2().min((self.levels.len() - 1) as f64)
    }

    /// Bilinear lookup in the level nearest λ.
    pub fn nearest_level(&self, uv: DVec2, lambda: f64, wrap: Wrap) -> Vec3 {
        let k = (lambda.round() as usize).min(self.levels.len() - 1);
        self.levels[k].bilinear(uv, wrap)
    }

    /// Bilinear lookups in levels ⌊λ⌋ and ⌊λ⌋ + 1, blended linearly by the fraction.
    pub fn trilinear(&self, uv: DVec2, lambda: f64, wrap: Wrap) -> Vec3 {
        self.trilinear_wrapped(uv, lambda, [wrap, wrap])
    }

    /// `trilinear` with a wrap mode per axis (columns, rows).
    pub fn trilinear_wrapped(&self, uv: DVec2, lambda: f64, wrap: [Wrap; 2]) -> Vec3 {
        let l0 = (lambda.floor() as usize).min(self.levels.len() - 1);
        let l1 = (l0 + 1).min(self.levels.len() - 1);
        let f = (lambda - l0 as f64).clamp(0.0, 1.0) as f32;
        let a = self.levels[l0].bilinear_wrapped(uv, wrap);
        if f == 0.0 || l1 == l0 {
            return a;
        }
        a.lerp(self.levels[l1].bilinear_wrapped(uv, wrap), f)
    }
}

/// The next level: each texel the mean of a 2 × 2 block (or of a pair, when one side
/// is already 1).
pub(crate) fn reduce(level: &Texels) -> Texels {
    let (w, h) = ((level.width / 2).max(1), (level.height / 2).max(1));
    let (sx, sy) = (level.width / w, level.height / h);
    let weight = 1.0 / (sx * sy) as f32;
    let mut texels = Vec::with_capacity((w * h) as usize);
    for j in 0..h {
        for i in 0..w {
            let mut sum = Vec3::ZERO;
            for dj in 0..sy {
                for di in 0..sx {
                    let (x, y) = (i * sx + di, j * sy + dj);
                    sum += level.texels[(y * level.width + x) as usize];
                }
            }
            texels.push(sum * weight);
        }
    }
    Texels {
        width: w,
        height: h,
        texels,
    }
}

/// Bilinear resampling to `width × height`, texel centres mapped onto texel centres'
/// positions in (u, v) (clamped at the borders).
pub(crate) fn resample(image: &Texels, width: u32, height: u32) -> Texels {
    Texels::generate(width, height, |uv| image.bilinear(uv, Wrap::Clamp))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_level_k_texel_is_the_mean_of_its_base_block() {
        let image = Texels::generate(8, 4, |uv| {
            Vec3::new((uv.x * 7.0).sin() as f32, uv.y as f32, 0.5)
        });
        let p = Pyramid::build(&image);
        assert_eq!(p.levels.len(), 4); // 8×4, 4×2, 2×1, 1×1
        let l2 = &p.levels[2];
        // Texel (1, 0) of level 2 covers base columns 4..8, rows 0..4.
        let mut sum = Vec3::ZERO;
        for y in 0..4 {
            for x in 4..8 {
                sum += image.texels[y * 8 + x];
            }
        }
        assert!((l2.texels[1] - sum / 16.0).abs().max_element() < 1e-6);
    }

    #[test]
    fn level_selection() {
        let p = Pyramid::build(&Texels::generate(64, 64, |_| Vec3::ONE));
        let one_texel = [DVec2::new(1.0 / 64.0, 0.0), DVec2::new(0.0, 1.0 / 64.0)];
        assert_eq!(p.level(one_texel), 0.0);
        let four = [DVec2::new(4.0 / 64.0, 0.0), DVec2::new(0.0, 1.0 / 64.0)];
        assert!((p.level(four) - 2.0).abs() < 1e-12);
        let huge = [DVec2::new(100.0, 0.0), DVec2::ZERO];
        assert_eq!(p.level(huge), 6.0);
    }
}
