//! Object transforms: translate, rotate (axis, degrees), scale, applied in order.

use super::Vertex;
use super::file::{Scale, TransformStep};
use crate::error::{Error, Result};
use glam::{DMat3, DMat4, DVec3};

/// The matrix of a list of steps, the first step applied first.
pub fn matrix(steps: &[TransformStep]) -> Result<DMat4> {
    let mut m = DMat4::IDENTITY;
    for (i, step) in steps.iter().enumerate() {
        let key = |what: &str| format!("transform[{i}].{what}");
        let s = match step {
            TransformStep::Translate(t) => {
                DMat4::from_translation(super::validate::vec3(&key("translate"), *t)?)
            }
            TransformStep::Scale(scale) => {
                let k = match scale {
                    Scale::Uniform(k) => DVec3::splat(*k),
                    Scale::PerAxis(k) => DVec3::from(*k),
                };
                if !k.is_finite() || k.cmpeq(DVec3::ZERO).any() {
                    return Err(Error::invalid(
                        key("scale"),
                        format!(
                            "{}: a scale must be finite and not zero on any axis, got {:?}",
                            key("scale"),
                            k.to_array()
                        ),
                    ));
                }
                DMat4::from_scale(k)
            }
            TransformStep::Rotate { axis, degrees } => {
                let axis = super::validate::direction(&key("rotate.axis"), *axis)?;
                if !degrees.is_finite() {
                    return Err(Error::invalid(
                        key("rotate.degrees"),
                        format!(
                            "{} must be a finite number, got {degrees}",
                            key("rotate.degrees")
                        ),
                    ));
                }
                DMat4::from_axis_angle(axis, degrees.to_radians())
            }
        };
        m = s * m;
    }
    if !m.is_finite() || m.determinant() == 0.0 {
        return Err(Error::invalid(
            "transform",
            "transform: its steps together leave floating point (scales whose product overflows or vanishes)",
        ));
    }
    Ok(m)
}

/// Applies `m` to a polygon's vertices: positions by `m`, normals by its inverse
/// transpose. A mirroring transform reverses the vertex order so the polygon keeps
/// facing the way its normals say.
pub fn apply(m: &DMat4, vertices: &mut [Vertex]) {
    let normal_matrix = DMat3::from_mat4(*m).inverse().transpose();
    for v in vertices.iter_mut() {
        v.position = m.transform_point3(v.position);
        v.normal = (normal_matrix * v.normal).normalize_or_zero();
    }
    if m.determinant() < 0.0 {
        vertices.reverse();
    }
}
