//! Procedural textures: functions of (u, v) instead of stored images.
//!
//! Checkerboard and grid are what a course draws on floors to show warping and
//! aliasing; value noise is smooth, so it serves as a bump height with analytic
//! derivatives (Blinn's F_u, F_v without finite differences). Each is periodic over
//! the unit square so that `repeat` wrapping tiles it without seams.

use glam::{DVec2, Vec3};

#[derive(Clone, Debug, PartialEq)]
pub enum Procedural {
    /// `cells × cells` squares alternating between `colors[0]` and `colors[1]`,
    /// `colors[0]` in the cell at (0, 0).
    Checkerboard { cells: u32, colors: [Vec3; 2] },
    /// Lines of `colors[0]` (width `line` in cell units, centred on the cell borders)
    /// over `colors[1]`.
    Grid {
        cells: u32,
        line: f64,
        colors: [Vec3; 2],
    },
    /// Value noise on a `cells × cells` lattice with pseudo-random values in [0, 1]
    /// (from `seed`), blended by the quintic smoothstep: C² smooth, so its gradient
    /// is continuous. Shown as a blend of `colors[0]` (0) to `colors[1]` (1).
    Noise {
        cells: u32,
        seed: u32,
        colors: [Vec3; 2],
    },
}

impl Procedural {
    pub fn color(&self, uv: DVec2) -> Vec3 {
        match self {
            Procedural::Checkerboard { cells, colors } => {
                let c = (uv * *cells as f64).floor();
                colors[(c.x + c.y).rem_euclid(2.0) as usize]
            }
            Procedural::Grid {
                cells,
                line,
                colors,
            } => {
                let c = uv * *cells as f64;
                // Distance to the nearest cell border, in cell units.
                let d = (c - c.round()).abs().min_element();
                colors[if d < line / 2.0 { 0 } else { 1 }]
            }
            Procedural::Noise { colors, .. } => {
                let (h, _) = self.height(uv);
                colors[0].lerp(colors[1], h as f32)
            }
        }
    }

    /// The height (the texture's value as a scalar, in [0, 1]) and its gradient
    /// (∂/∂u, ∂/∂v), analytic. The checkerboard and grid are piecewise constant: their
    /// gradient is zero almost everywhere.
    pub fn height(&self, uv: DVec2) -> (f64, DVec2) {
        match self {
            Procedural::Noise { cells, seed, .. } => value_noise(uv, *cells, *seed),
            other @ (Procedural::Checkerboard { .. } | Procedural::Grid { .. }) => {
                let c = other.color(uv);
                (luminance(c), DVec2::ZERO)
            }
        }
    }
}

/// Rec. 709 luminance: how a colour texture is read as a height.
pub fn luminance(c: Vec3) -> f64 {
    (0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z) as f64
}

/// Value noise and its gradient: lattice values blended by s(t) = 6t⁵ − 15t⁴ + 10t³.
fn value_noise(uv: DVec2, cells: u32, seed: u32) -> (f64, DVec2) {
    let n = cells as f64;
    let p = uv * n;
    let (i, j) = (p.x.floor(), p.y.floor());
    let (tx, ty) = (p.x - i, p.y - j);
    let (i, j) = (i as i64, j as i64);
    let lattice = |a: i64, b: i64| {
        lattice_value(
            a.rem_euclid(cells as i64) as u32,
            b.rem_euclid(cells as i64) as u32,
            seed,
        )
    };
    let (v00, v10, v01, v11) = (
        lattice(i, j),
        lattice(i + 1, j),
        lattice(i, j + 1),
        lattice(i + 1, j + 1),
    );
    let (sx, sy) = (smooth(tx), smooth(ty));
    let (dsx, dsy) = (smooth_slope(tx), smooth_slope(ty));
    let bottom = v00 + (v10 - v00) * sx;
    let top = v01 + (v11 - v01) * sx;
    let value = bottom + (top - bottom) * sy;
    let du = ((v10 - v00) + (v11 - v01 - v10 + v00) * sy) * dsx * n;
    let dv = (top - bottom) * dsy * n;
    (value, DVec2::new(du, dv))
}

fn smooth(t: f64) -> f64 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

fn smooth_slope(t: f64) -> f64 {
    30.0 * t * t * (t * (t - 2.0) + 1.0)
}

/// A pseudo-random value in [0, 1] for lattice point (i, j): an integer hash, so the
/// noise is the same on every machine and thread.
fn lattice_value(i: u32, j: u32, seed: u32) -> f64 {
    let mut h = i.wrapping_mul(0x8da6_b343) ^ j.wrapping_mul(0xd816_3841) ^ seed;
    h ^= h >> 15;
    h = h.wrapping_mul(0x2c1b_3c6d);
    h ^= h >> 12;
    h = h.wrapping_mul(0x297a_2d39);
    h ^= h >> 15;
    h as f64 / u32::MAX as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn noise_gradient_matches_finite_differences() {
        let noise = Procedural::Noise {
            cells: 7,
            seed: 3,
            colors: [Vec3::ZERO, Vec3::ONE],
        };
        let h = 1e-6;
        for k in 0..200 {
            let uv = DVec2::new((k as f64 * 0.137).fract(), (k as f64 * 0.291).fract());
            let (_, g) = noise.height(uv);
            let du =
                (noise.height(uv + DVec2::X * h).0 - noise.height(uv - DVec2::X * h).0) / (2.0 * h);
            let dv =
                (noise.height(uv + DVec2::Y * h).0 - noise.height(uv - DVec2::Y * h).0) / (2.0 * h);
            assert!(
                (g.x - du).abs() < 1e-5 && (g.y - dv).abs() < 1e-5,
                "{g} vs {du},{dv}"
            );
        }
    }

    #[test]
    fn noise_tiles_the_unit_square() {
        let noise = Procedural::Noise {
            cells: 5,
            seed: 1,
            colors: [Vec3::ZERO, Vec3::ONE],
        };
        for k in 0..50 {
            let uv = DVec2::new(k as f64 / 50.0, 0.3);
            let a = noise.height(uv).0;
            let b = noise.height(uv + DVec2::new(1.0, -2.0)).0;
            assert!((a - b).abs() < 1e-12);
        }
    }

    #[test]
    fn checkerboard_alternates() {
        let c = Procedural::Checkerboard {
            cells: 4,
            colors: [Vec3::ZERO, Vec3::ONE],
        };
        assert_eq!(c.color(DVec2::new(0.1, 0.1)), Vec3::ZERO);
        assert_eq!(c.color(DVec2::new(0.3, 0.1)), Vec3::ONE);
        assert_eq!(c.color(DVec2::new(0.3, 0.3)), Vec3::ZERO);
    }
}
