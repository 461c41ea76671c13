//! Procedural environments, functions of the direction baked into a map at load.
//!
//! - `sky`: a clear sky over a checkered ground plane, the classic surroundings of a
//!   chrome ball. The sky brightens from the zenith to the horizon and around a sun
//!   (up and to the left of a camera looking down −z; a cos⁶⁴ glow); the ground is a plane one unit
//!   below the centre, checkered in unit squares, fading to a haze at the horizon so
//!   that the map carries no detail finer than its texels there.
//! - `directions`: each direction's own unit vector as a colour, (d + 1)/2, so that a
//!   lookup can be read back as the direction it found (for tests and teaching).

use glam::{DVec3, Vec3};

#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ProceduralEnvironment {
    Sky,
    Directions,
}

impl ProceduralEnvironment {
    /// The radiance seen in direction `d`.
    pub fn radiance(self, d: DVec3) -> Vec3 {
        let d = d.normalize();
        match self {
            ProceduralEnvironment::Directions => ((d + DVec3::ONE) / 2.0).as_vec3(),
            ProceduralEnvironment::Sky => sky(d),
        }
    }
}

fn sky(d: DVec3) -> Vec3 {
    let horizon = Vec3::new(0.85, 0.88, 0.92);
    if d.y >= 0.0 {
        let zenith = Vec3::new(0.18, 0.34, 0.75);
        let sun = DVec3::new(-0.45, 0.6, -0.66).normalize();
        let glow = d.dot(sun).max(0.0).powi(64) as f32;
        let height = (d.y.sqrt()) as f32;
        horizon.lerp(zenith, height) + Vec3::new(1.6, 1.4, 1.0) * glow
    } else {
        // The ground plane y = −1 seen from the centre.
        let p = d / -d.y;
        let cell = (p.x.floor() + p.z.floor()).rem_euclid(2.0);
        let ground = if cell < 1.0 {
            Vec3::new(0.62, 0.6, 0.55)
        } else {
            Vec3::new(0.12, 0.13, 0.15)
        };
        // Beyond about 12 units the checks are finer than a texel of a 256 map.
        let haze = (1.0 - (-(p.x * p.x + p.z * p.z).sqrt() / 12.0).exp()) as f32;
        ground.lerp(horizon * 0.8, haze)
    }
}
