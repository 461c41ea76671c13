//! `[[lights]]` entries checked and made into lights: the point, distant, sphere and
//! spot lights (a polygon light is a polygon of the scene, made by the builder).

use super::file::LightFile;
use super::validate;
use super::{DistantLight, Light, PointLight, SphereLight, SpotDistribution, SpotLight};
use crate::error::ensure_valid;
use crate::error::{Error, Result};
use glam::DVec3;

/// The light of a `[[lights]]` entry other than a polygon, seen from `eye` (a
/// sphere light may not enclose it).
pub(super) fn light(light: &LightFile, eye: DVec3) -> Result<Light> {
    match light {
        LightFile::Point {
            name,
            position,
            intensity,
        } => Ok(Light::Point(PointLight {
            position: validate::position("position", *position)?,
            intensity: validate::colour("intensity", *intensity)?,
            name: name.clone(),
        })),
        LightFile::Distant {
            name,
            direction,
            irradiance,
        } => Ok(Light::Distant(DistantLight {
            direction: validate::direction("direction", *direction)?,
            irradiance: validate::colour("irradiance", *irradiance)?,
            name: name.clone(),
        })),
        LightFile::Sphere {
            name,
            centre,
            radius,
            radiance,
        } => {
            ensure_valid!(
                radius.is_finite() && *radius > 0.0,
                "radius",
                "radius must be a positive number, got {radius}"
            );
            let at = validate::position("centre", *centre)?;
            ensure_valid!(
                (eye - at).length() > *radius,
                "radius",
                "the sphere light (radius {radius}) encloses the eye: it would be seen from inside, where it does not shine"
            );
            Ok(Light::Sphere(SphereLight {
                centre: at,
                radius: *radius,
                radiance: validate::colour("radiance", *radiance)?,
                name: name.clone(),
            }))
        }
        LightFile::Spot {
            name,
            position,
            axis,
            cone_angle,
            intensity,
            cosine_power,
            distribution,
        } => {
            ensure_valid!(
                cone_angle.is_finite() && *cone_angle > 0.0 && *cone_angle <= 90.0,
                "cone_angle",
                "cone_angle must be in (0, 90] degrees, got {cone_angle}"
            );
            let distribution = match (cosine_power, distribution) {
                (Some(_), Some(_)) => {
                    return Err(Error::invalid(
                        "distribution",
                        "give `cosine_power` or `distribution`, not both",
                    ));
                }
                (Some(p), None) => {
                    ensure_valid!(
                        p.is_finite() && *p >= 0.0,
                        "cosine_power",
                        "cosine_power must be a non-negative number, got {p}"
                    );
                    SpotDistribution::CosinePower(*p)
                }
                (None, Some(table)) => SpotDistribution::Table(spot_table(table)?),
                (None, None) => SpotDistribution::CosinePower(0.0),
            };
            Ok(Light::Spot(SpotLight {
                position: validate::position("position", *position)?,
                axis: validate::direction("axis", *axis)?,
                cone_angle: cone_angle.to_radians(),
                intensity: validate::colour("intensity", *intensity)?,
                distribution,
                name: name.clone(),
            }))
        }
        LightFile::Polygon { .. } => unreachable!("a polygon light is the builder's"),
    }
}

/// A spot light's (degrees, factor) table: angles increasing from 0 up, factors
/// non-negative; angles turned into radians.
fn spot_table(table: &[[f64; 2]]) -> Result<Vec<(f64, f64)>> {
    ensure_valid!(
        !table.is_empty(),
        "distribution",
        "distribution must hold at least one [angle, factor] pair"
    );
    for (k, &[angle, factor]) in table.iter().enumerate() {
        ensure_valid!(
            angle.is_finite() && (0.0..=90.0).contains(&angle),
            format!("distribution[{k}]"),
            "distribution[{k}]: angle must be between 0 and 90 degrees, got {angle}"
        );
        ensure_valid!(
            factor.is_finite() && factor >= 0.0,
            format!("distribution[{k}]"),
            "distribution[{k}]: factor must be a non-negative number, got {factor}"
        );
        if k > 0 && angle <= table[k - 1][0] {
            return Err(Error::invalid(
                "distribution",
                format!(
                    "distribution angles must increase, got {} then {angle}",
                    table[k - 1][0]
                ),
            ));
        }
    }
    Ok(table
        .iter()
        .map(|&[angle, factor]| (angle.to_radians(), factor))
        .collect())
}
