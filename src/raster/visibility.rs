//! What a shadow method hands to shading: for one light, how much of it each visible
//! sample of a band receives. Point lights and sampled methods give a fraction (0
//! shadowed, 1 lit, between for partial); exact methods under an extended light give
//! the visible part of the emitter, a polygon with holes, from which shading takes
//! the exact irradiance (Lambert's contour formula on what remains). Shading never
//! needs to know how shadows were made, and methods compare sample by sample.

use glam::DVec3;

/// The part of a polygonal emitter a point sees: contours on the emitter's plane,
/// each with its sign (+1 an outer contour, −1 a hole).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct VisiblePart {
    pub contours: Vec<(Vec<DVec3>, f64)>,
}

/// One light's visibility over the samples of a band.
#[derive(Clone, Debug, PartialEq)]
pub enum LightVisibility {
    /// The fraction of the light each sample receives.
    Fraction(Vec<f32>),
    /// The visible part of the emitter at each sample (`None`: all of it).
    Emitter(Vec<Option<VisiblePart>>),
}

impl LightVisibility {
    /// The fraction at sample `k` (for an exact part, 1 where the whole emitter is
    /// seen and 0 where none of it is; partial parts have no single fraction and
    /// count as ½ in buffers).
    pub fn fraction(&self, k: usize) -> f32 {
        match self {
            LightVisibility::Fraction(f) => f[k],
            LightVisibility::Emitter(parts) => match &parts[k] {
                None => 1.0,
                Some(p) if p.contours.is_empty() => 0.0,
                Some(_) => 0.5,
            },
        }
    }
}

/// Every light's visibility over a band: `None` for a light nothing shadows.
#[derive(Clone, Debug, Default)]
pub struct Visibility {
    pub per_light: Vec<Option<LightVisibility>>,
}

impl Visibility {
    /// Every light fully visible at every sample (no shadows).
    pub fn none() -> Visibility {
        Visibility::default()
    }

    /// Light `light`'s visibility, `None` when unshadowed.
    pub fn of(&self, light: usize) -> Option<&LightVisibility> {
        self.per_light.get(light).and_then(Option::as_ref)
    }

    /// The fraction of light `light` reaching sample `k` (1 when unshadowed).
    pub fn fraction(&self, light: usize, k: usize) -> f32 {
        self.of(light).map_or(1.0, |v| v.fraction(k))
    }
}

/// The lit parts of each sample's viewing ray for one light: intervals of distance
/// from the eye, [near, far] in scene units, outside every shadow volume.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LitIntervals {
    /// Sample k's intervals are `spans[start[k]..start[k + 1]]`, ascending.
    pub start: Vec<u32>,
    pub spans: Vec<[f64; 2]>,
}

impl LitIntervals {
    /// Sample `k`'s lit intervals.
    pub fn of(&self, k: usize) -> &[[f64; 2]] {
        &self.spans[self.start[k] as usize..self.start[k + 1] as usize]
    }

    /// The number of samples.
    pub fn len(&self) -> usize {
        self.start.len().saturating_sub(1)
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}
