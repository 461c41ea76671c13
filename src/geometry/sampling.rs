//! Deterministic random numbers and stratified sample sets, for methods that sample
//! lights (soft shadows by ray casting: R. L. Cook, T. Porter, L. Carpenter,
//! "Distributed ray tracing", SIGGRAPH '84).
//!
//! There is no global generator: every stream is made from an explicit seed and a
//! stream index (a pixel, a light, a frame), so output never depends on the order in
//! which threads draw numbers. The generator is SplitMix64 (G. L. Steele, D. Lea,
//! C. H. Flood, "Fast splittable pseudorandom number generators", OOPSLA 2014): a
//! 64-bit counter stepped by the golden-ratio increment, each value passed through
//! a bijective mixing function.

use glam::{DVec2, DVec3};
use std::f64::consts::TAU;

/// The golden-ratio increment of SplitMix64 (2⁶⁴/φ, odd).
const GOLDEN_GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;

/// The largest double below 1.
const BELOW_ONE: f64 = 1.0 - f64::EPSILON / 2.0;

/// SplitMix64's finaliser (Stafford's "Mix13" variant of MurmurHash3's).
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// One stream of pseudo-random numbers.
#[derive(Clone, Debug)]
pub struct Stream {
    state: u64,
}

impl Stream {
    /// Stream `index` of generator `seed`. Streams of one seed start at states
    /// scattered by the mixing function, so neighbouring indices are unrelated.
    pub fn new(seed: u64, index: u64) -> Stream {
        Stream {
            state: mix(seed ^ mix(index.wrapping_add(GOLDEN_GAMMA))),
        }
    }

    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(GOLDEN_GAMMA);
        mix(self.state)
    }

    /// Uniform in [0, 1): the top 53 bits as a fraction.
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// A stratified (jittered) set of n × n points in [0, 1)²: one uniform point in
    /// each cell of an n × n grid, cells in row order (x fastest).
    pub fn jittered(&mut self, n: usize) -> Vec<DVec2> {
        let size = n as f64;
        let mut points = Vec::with_capacity(n * n);
        for j in 0..n {
            for i in 0..n {
                let x = ((i as f64 + self.next_f64()) / size).min(BELOW_ONE);
                let y = ((j as f64 + self.next_f64()) / size).min(BELOW_ONE);
                points.push(DVec2::new(x, y));
            }
        }
        points
    }
}

/// A direction about unit `normal` with density cos θ / π (Malley's method: a
/// uniform point on the unit disc lifted to the hemisphere), for u, v in [0, 1).
pub fn cosine_weighted(normal: DVec3, u: f64, v: f64) -> DVec3 {
    let r = u.sqrt();
    let phi = TAU * v;
    let (t, b) = normal.any_orthonormal_pair();
    let z = (1.0 - u).max(0.0).sqrt();
    (t * (r * phi.cos()) + b * (r * phi.sin()) + normal * z).normalize()
}

/// A direction about unit `axis` with density (e + 1)/(2π) cosᵉ α, α from the
/// axis, for u, v in [0, 1).
pub fn phong_lobe(axis: DVec3, e: f64, u: f64, v: f64) -> DVec3 {
    let cos = (1.0 - u).powf(1.0 / (e + 1.0));
    around(axis, cos, v)
}

/// A direction uniform over the cone of half-angle α about unit `axis` (density
/// 1 / (2π (1 − cos α))), for u, v in [0, 1); α = π gives the whole sphere.
pub fn uniform_cone(axis: DVec3, cos_alpha: f64, u: f64, v: f64) -> DVec3 {
    around(axis, 1.0 - u * (1.0 - cos_alpha), v)
}

/// The direction at cos θ from unit `axis`, at azimuth 2π v about it.
fn around(axis: DVec3, cos: f64, v: f64) -> DVec3 {
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    let phi = TAU * v;
    let (t, b) = axis.any_orthonormal_pair();
    (t * (sin * phi.cos()) + b * (sin * phi.sin()) + axis * cos).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streams_are_deterministic_and_distinct() {
        let a: Vec<u64> = (0..4).map(|_| Stream::new(7, 3).next_u64()).collect();
        assert!(a.windows(2).all(|w| w[0] == w[1]));
        let mut s = Stream::new(7, 3);
        let mut t = Stream::new(7, 4);
        let mut u = Stream::new(8, 3);
        let (x, y, z) = (s.next_u64(), t.next_u64(), u.next_u64());
        assert!(x != y && x != z && y != z);
    }

    #[test]
    fn uniform_numbers_lie_in_the_unit_interval_with_the_right_mean() {
        let mut s = Stream::new(1, 0);
        let n = 100_000;
        let values: Vec<f64> = (0..n).map(|_| s.next_f64()).collect();
        assert!(values.iter().all(|&x| (0.0..1.0).contains(&x)));
        let mean = values.iter().sum::<f64>() / n as f64;
        let var = values.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n as f64;
        assert!((mean - 0.5).abs() < 0.005, "{mean}");
        assert!((var - 1.0 / 12.0).abs() < 0.002, "{var}");
    }

    #[test]
    fn a_jittered_set_has_one_point_per_cell() {
        for n in [1, 2, 3, 7, 16, 64] {
            let points = Stream::new(42, n as u64).jittered(n);
            assert_eq!(points.len(), n * n);
            let mut seen = vec![0; n * n];
            for p in &points {
                assert!(
                    (0.0..1.0).contains(&p.x) && (0.0..1.0).contains(&p.y),
                    "{p}"
                );
                let (i, j) = ((p.x * n as f64) as usize, (p.y * n as f64) as usize);
                seen[j * n + i] += 1;
            }
            assert!(seen.iter().all(|&c| c == 1), "n = {n}");
        }
    }
}
