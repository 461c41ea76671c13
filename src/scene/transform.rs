//! Object transforms: translate, rotate (axis, degrees), scale, applied in order.

use super::Vertex;
use super::file::{Scale, TransformStep};
use crate::error::{Error, Result};
use glam::{DMat3, DMat4, DVec3};

/// The matrix of a list of steps, the first step applied first.
pub fn matrix(steps: &[TransformStep]) -> Result<DMat4> {
    let mut m = DMat4::IDENTITY;
    for step in steps {
        let s = match step {
            TransformStep::Translate(t) => DMat4::from_translation(DVec3::from(*t)),
            TransformStep::Scale(Scale::Uniform(k)) => DMat4::from_scale(DVec3::splat(*k)),
            TransformStep::Scale(Scale::PerAxis(k)) => DMat4::from_scale(DVec3::from(*k)),
            TransformStep::Rotate { axis, degrees } => {
                let axis = DVec3::from(*axis);
                if axis.length() == 0.0 {
                    return Err(Error::invalid(
                        "transform",
                        "rotate: the axis must be a non-zero vector",
                    ));
                }
                DMat4::from_axis_angle(axis.normalize(), degrees.to_radians())
            }
        };
        m = s * m;
    }
    if !m.is_finite() || m.determinant() == 0.0 {
        return Err(Error::invalid(
            "transform",
            "the transform is degenerate (a zero or non-finite scale)",
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
