//! The point light's share of the light model over four samples at once, as lanes
//! of one vector register: the same IEEE-754 operations, in the same order, as
//! `light_model::reflected` does one sample at a time (additions, products,
//! quotients and square roots are correctly rounded in every lane, and nothing is
//! fused), so each lane's result is the scalar one, bit for bit. What the scalar
//! model spends most on, the division by the distance and the square root, is done
//! for four samples in a few instructions.

use glam::DVec3;
use wide::f64x4;

/// Four samples' positions and shading normals (on the eye's side), a lane each.
pub struct Lanes {
    pub position: [f64x4; 3],
    pub normal: [f64x4; 3],
}

impl Lanes {
    /// The lanes of `points` (position, normal).
    pub fn new(points: &[(DVec3, DVec3); 4]) -> Lanes {
        let lane = |f: &dyn Fn(&(DVec3, DVec3)) -> f64| {
            f64x4::new([f(&points[0]), f(&points[1]), f(&points[2]), f(&points[3])])
        };
        Lanes {
            position: [lane(&|p| p.0.x), lane(&|p| p.0.y), lane(&|p| p.0.z)],
            normal: [lane(&|p| p.1.x), lane(&|p| p.1.y), lane(&|p| p.1.z)],
        }
    }

    /// For a point light at `light`, per lane: cos θ / r² where the light is in
    /// front of the point (cos θ > 0 and finite), else `None`, as the scalar
    /// model's `point_contribution` finds them.
    pub fn point_factors(&self, light: DVec3) -> [Option<f64>; 4] {
        let d = [
            f64x4::splat(light.x) - self.position[0],
            f64x4::splat(light.y) - self.position[1],
            f64x4::splat(light.z) - self.position[2],
        ];
        // length_squared: (x·x + y·y) + z·z.
        let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        let length = r2.sqrt();
        let l = [d[0] / length, d[1] / length, d[2] / length];
        let cos = self.normal[0] * l[0] + self.normal[1] * l[1] + self.normal[2] * l[2];
        let factor = (cos / r2).to_array();
        let cos = cos.to_array();
        std::array::from_fn(|i| (cos[i] > 0.0 && cos[i] < f64::INFINITY).then_some(factor[i]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The scalar model's steps, written out.
    fn scalar(light: DVec3, position: DVec3, normal: DVec3) -> Option<f64> {
        let d = light - position;
        let r2 = d.length_squared();
        let l = d / r2.sqrt();
        let cos = normal.dot(l);
        (cos > 0.0 && cos < f64::INFINITY).then_some(cos / r2)
    }

    #[test]
    fn every_lane_is_the_scalar_result_bit_for_bit() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 20.0 - 10.0
        };
        for _ in 0..10_000 {
            let light = DVec3::new(next(), next(), next());
            let points: [(DVec3, DVec3); 4] = std::array::from_fn(|_| {
                let p = DVec3::new(next(), next(), next());
                let n = DVec3::new(next(), next(), next()).normalize();
                (p, n)
            });
            let lanes = Lanes::new(&points);
            let found = lanes.point_factors(light);
            for (i, (p, n)) in points.iter().enumerate() {
                let expected = scalar(light, *p, *n);
                assert_eq!(
                    found[i].map(f64::to_bits),
                    expected.map(f64::to_bits),
                    "lane {i}"
                );
            }
        }
        // The light on the point: no direction, no light.
        let lanes = Lanes::new(&[(DVec3::ONE, DVec3::Y); 4]);
        assert_eq!(lanes.point_factors(DVec3::ONE), [None; 4]);
    }
}
