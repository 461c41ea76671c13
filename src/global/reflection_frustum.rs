//! The reflection frustum of J. R. Wallace, M. F. Cohen, D. P. Greenberg, "A
//! two-pass solution to the rendering equation", SIGGRAPH '87: how the second pass
//! sees a glossy surface. The light arriving around the mirror direction R is
//! gathered through a small frustum centred on R, a low-resolution image of the
//! scene whose cells are weighted by the specular reflection's lobe and summed.
//!
//! Here the frustum's window is a square at unit distance along R, cut into N × N
//! cells; each cell shows what the nearest surface at its centre shows (the
//! paper's z-buffer image, sampled at cell centres: one ray through each), weighted
//! by the lobe cosⁿγ (γ the angle from R) times the solid angle the cell subtends
//! (its area × cos³γ), the weights normalised to 1 over the window.
//!
//! Choices left open (the paper gives neither the resolution nor the weighting in
//! detail): the lobe is Phong's cosⁿ about R; the window reaches the angle where
//! the lobe falls to 1% of its peak, cos θ_f = 0.01^(1/n), but at most 60° from R
//! (a frustum cannot cover a hemisphere); the frustum turns about R by a random
//! angle per sample, so that the cells' aliasing becomes noise that supersampling
//! averages; cells below the surface's horizon bring nothing, their weight kept in
//! the normalisation (a grazing lobe loses light, as a real one does).

use glam::{DVec2, DVec3};

/// Where the lobe has fallen to this share of its peak, the window ends.
const LOBE_EDGE: f64 = 0.01;
/// The window's widest half-angle from R.
const WIDEST: f64 = std::f64::consts::PI / 3.0;

/// The cells of one frustum, for one lobe exponent and resolution.
#[derive(Clone, Debug)]
pub struct ReflectionFrustum {
    /// Each cell's centre on the window (unit distance along R, in the window's
    /// own axes) and its normalised weight.
    cells: Vec<(DVec2, f64)>,
}

impl ReflectionFrustum {
    /// The half-angle from R at which the window of lobe `exponent` ends.
    pub fn half_angle(exponent: f64) -> f64 {
        LOBE_EDGE.powf(1.0 / exponent).acos().min(WIDEST)
    }

    /// The frustum of lobe cosⁿ (n = `exponent`) with `resolution` cells a side.
    pub fn new(exponent: f64, resolution: u32) -> ReflectionFrustum {
        let half = Self::half_angle(exponent).tan();
        let n = resolution as f64;
        let side = 2.0 * half / n;
        let mut cells = Vec::with_capacity((resolution * resolution) as usize);
        for j in 0..resolution {
            for i in 0..resolution {
                let at = DVec2::new(
                    -half + (i as f64 + 0.5) * side,
                    -half + (j as f64 + 0.5) * side,
                );
                let cos = 1.0 / (1.0 + at.length_squared()).sqrt();
                cells.push((at, cos.powf(exponent) * cos.powi(3) * side * side));
            }
        }
        let total: f64 = cells.iter().map(|c| c.1).sum();
        for c in &mut cells {
            c.1 /= total;
        }
        ReflectionFrustum { cells }
    }

    /// Each cell's unit direction and weight, the frustum centred on unit `mirror`
    /// and turned about it by `turn` radians.
    pub fn rays(&self, mirror: DVec3, turn: f64) -> impl Iterator<Item = (DVec3, f64)> + '_ {
        let (a, b) = mirror.any_orthonormal_pair();
        let (sin, cos) = turn.sin_cos();
        let (u, v) = (a * cos + b * sin, b * cos - a * sin);
        self.cells
            .iter()
            .map(move |&(at, weight)| ((mirror + u * at.x + v * at.y).normalize(), weight))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_sum_to_one_and_peak_at_the_centre() {
        let f = ReflectionFrustum::new(50.0, 9);
        let total: f64 = f.cells.iter().map(|c| c.1).sum();
        assert!((total - 1.0).abs() < 1e-12);
        let centre = f.cells[4 * 9 + 4].1;
        assert!(f.cells.iter().all(|c| c.1 <= centre));
    }

    #[test]
    fn rays_surround_the_mirror_direction_whatever_the_turn() {
        let f = ReflectionFrustum::new(200.0, 8);
        let r = DVec3::new(0.3, 0.8, -0.2).normalize();
        let edge = ReflectionFrustum::half_angle(200.0);
        for turn in [0.0, 1.0, 4.0] {
            let mean: DVec3 = f.rays(r, turn).map(|(d, w)| d * w).sum();
            assert!(mean.normalize().dot(r) > 1.0 - 1e-12);
            for (d, _) in f.rays(r, turn) {
                // Inside the cone through the window's corners.
                assert!(d.dot(r) >= (edge.tan() * 2f64.sqrt()).atan().cos() - 1e-12);
            }
        }
    }
}
