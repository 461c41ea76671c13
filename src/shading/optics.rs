//! Mirror reflection, Snell's refraction and Schlick's Fresnel approximation: the
//! directions and weights environment mapping (and ray tracing) reads.

use glam::DVec3;

/// The mirror direction of `to_eye` (unit, from the surface to the eye) about the unit
/// normal `n`: R = 2(N·V)N − V. Unit, and N·R = N·V.
pub fn reflect(to_eye: DVec3, n: DVec3) -> DVec3 {
    2.0 * n.dot(to_eye) * n - to_eye
}

/// The refracted direction of the incident direction `incident` (unit, travelling
/// towards the surface) through the unit normal `n` on the incident side, for
/// η = η₁/η₂ (incident over transmitted index): with c = −N·I and
/// k = 1 − η²(1 − c²), T = ηI + (ηc − √k)N; `None` when k < 0 (total internal
/// reflection).
pub fn refract(incident: DVec3, n: DVec3, eta: f64) -> Option<DVec3> {
    let c = -n.dot(incident);
    let k = 1.0 - eta * eta * (1.0 - c * c);
    (k >= 0.0).then(|| eta * incident + (eta * c - k.sqrt()) * n)
}

/// Schlick's approximation to the Fresnel reflectance of unpolarised light between
/// indices η₁ (incident side) and η₂: F₀ + (1 − F₀)(1 − cos θ)⁵ with
/// F₀ = ((η₁ − η₂)/(η₁ + η₂))², θ the angle on the less dense side (the transmitted
/// one when leaving a denser medium); 1 beyond the critical angle. Equal indices are
/// no interface at all: 0 (where the formula would still give (1 − cos θ)⁵).
pub fn schlick(cos_incident: f64, eta1: f64, eta2: f64) -> f64 {
    if eta1 == eta2 {
        return 0.0;
    }
    let f0 = ((eta1 - eta2) / (eta1 + eta2)).powi(2);
    let cos = if eta1 > eta2 {
        let sin2 = (eta1 / eta2).powi(2) * (1.0 - cos_incident * cos_incident);
        if sin2 > 1.0 {
            return 1.0;
        }
        (1.0 - sin2).sqrt()
    } else {
        cos_incident
    };
    f0 + (1.0 - f0) * (1.0 - cos.clamp(0.0, 1.0)).powi(5)
}

/// Fresnel's reflectance of unpolarised light at a smooth interface from index η₁
/// to η₂, the mean of the s and p polarisations' (the exact formulas): for cos θ₁
/// on the incident side, sin θ₂ = (η₁/η₂) sin θ₁, r_s = (η₁ cos θ₁ − η₂ cos θ₂) /
/// (η₁ cos θ₁ + η₂ cos θ₂), r_p = (η₂ cos θ₁ − η₁ cos θ₂) / (η₂ cos θ₁ + η₁ cos θ₂),
/// F = (r_s² + r_p²)/2; 1 beyond the critical angle, 0 between equal indices.
pub fn fresnel(cos_incident: f64, eta1: f64, eta2: f64) -> f64 {
    if eta1 == eta2 {
        return 0.0;
    }
    let cos1 = cos_incident.clamp(0.0, 1.0);
    let sin2 = (eta1 / eta2).powi(2) * (1.0 - cos1 * cos1);
    if sin2 >= 1.0 {
        return 1.0;
    }
    let cos2 = (1.0 - sin2).sqrt();
    let rs = (eta1 * cos1 - eta2 * cos2) / (eta1 * cos1 + eta2 * cos2);
    let rp = (eta2 * cos1 - eta1 * cos2) / (eta2 * cos1 + eta1 * cos2);
    0.5 * (rs * rs + rp * rp)
}
