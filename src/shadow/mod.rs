//! Shadows: every method answers, for one light, how much of it reaches each visible
//! sample (0 shadowed, 1 lit, between for partial), so shading never needs to know
//! how shadows are made and methods can be compared sample by sample.

/// The visibility terms of one render: per light, per sample of the visible-surface
/// buffer. A light without a buffer is wholly visible everywhere.
#[derive(Clone, Debug, Default)]
pub struct Visibility {
    pub per_light: Vec<Option<Vec<f32>>>,
}

impl Visibility {
    /// Every light fully visible at every sample (no shadows).
    pub fn none() -> Visibility {
        Visibility::default()
    }

    /// Visibility of light `light` at sample `k`.
    pub fn of(&self, light: usize, k: usize) -> f32 {
        match self.per_light.get(light) {
            Some(Some(buffer)) => buffer[k],
            _ => 1.0,
        }
    }

    /// Mean visibility of all lights at sample `k` (for modes that shade per vertex
    /// or per polygon and so cannot weigh lights one by one).
    pub fn mean(&self, k: usize) -> f32 {
        let count = self.per_light.len();
        if count == 0 {
            return 1.0;
        }
        (0..count).map(|l| self.of(l, k)).sum::<f32>() / count as f32
    }
}
