//! Two-part texture mapping: E. A. Bier and K. R. Sloan Jr., "Two-part texture
//! mappings", IEEE Computer Graphics and Applications 6(9):40–53, 1986.
//!
//! The texture is first wrapped onto a simple intermediate surface whose (u, v) is
//! known in closed form (the S-mapping: plane, cylinder, sphere or box), then each
//! object point is sent to a point of that surface (the O-mapping). Everything here
//! works in the intermediate surface's own frame: origin `centre`, z along `axis`, x
//! along `reference`, y = z × x; the frame is given in the object's modelling
//! coordinates, so the texture moves with the object.
//!
//! S-mappings, as the course writes them (u, v ∈ [0, 1] before `repeat`):
//! - plane: orthographic along z, (u, v) = (x / size_u, y / size_v);
//! - cylinder: the point (r cos θ, r sin θ, h z) maps to (θ / 2π, z), θ ∈ [0, 2π);
//! - sphere: θ as for the cylinder and latitude φ = asin(z / r) ∈ [−π/2, π/2],
//!   (u, v) = (θ / 2π, (φ + π/2) / π). (The course writes the point with cos φ on z,
//!   a colatitude, but its (u, v) formula and its range for φ are those of a
//!   latitude; we follow the (u, v) formula.)
//! - box: six planar maps, the face chosen by the dominant axis, each face seen from
//!   outside unmirrored.
//!
//! O-mappings, Bier and Sloan's four: the intermediate-surface normal (the point of the
//! surface whose normal line passes through P: orthographic for the plane, radial for
//! the cylinder and sphere, the dominant face for the box), the object normal (the
//! line from P along N), the object centroid (the ray from the centroid through P),
//! and the reflected ray (the eye ray reflected at P). The last three intersect a
//! surface of definite size: the plane z = 0, a cylinder or sphere of `radius`, a box
//! of side `size`. Where the line misses the surface, we fall back to the
//! intermediate-surface normal (a choice; the paper leaves it open).

use crate::error::Result;
use crate::error::ensure_valid;
use glam::{DVec2, DVec3};
use std::f64::consts::{PI, TAU};

#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum IntermediateSurface {
    Plane,
    Cylinder,
    Sphere,
    Box,
}

/// Bier and Sloan's O-mappings.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Projector {
    /// The intermediate surface's normal line through the point.
    #[default]
    Surface,
    /// The object's normal line.
    Normal,
    /// The ray from the object's centroid through the point.
    Centroid,
    /// The eye ray reflected at the point (view dependent).
    Reflected,
}

/// An orthonormal frame: the intermediate surface's own coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    pub centre: DVec3,
    pub x: DVec3,
    pub y: DVec3,
    pub z: DVec3,
}

impl Frame {
    /// The frame with z along `axis` and x along the part of `reference` orthogonal to
    /// it; an error when the axis is zero or the reference parallel to it.
    pub fn new(centre: DVec3, axis: DVec3, reference: DVec3) -> Result<Frame> {
        ensure_valid!(
            centre.is_finite() && axis.is_finite() && reference.is_finite(),
            "frame",
            "the mapping frame must be finite numbers"
        );
        ensure_valid!(
            axis.length() > 1e-12,
            "axis",
            "the mapping axis is a zero vector"
        );
        let z = axis.normalize();
        let x = reference - z * reference.dot(z);
        ensure_valid!(
            x.length() > 1e-9 * reference.length().max(1e-300),
            "reference",
            "the mapping reference direction is zero or parallel to the axis (a degenerate frame)"
        );
        let x = x.normalize();
        Ok(Frame {
            centre,
            x,
            y: z.cross(x),
            z,
        })
    }

    pub fn to_local(&self, p: DVec3) -> DVec3 {
        let d = p - self.centre;
        DVec3::new(d.dot(self.x), d.dot(self.y), d.dot(self.z))
    }

    pub fn direction_to_local(&self, d: DVec3) -> DVec3 {
        DVec3::new(d.dot(self.x), d.dot(self.y), d.dot(self.z))
    }

    pub fn from_local(&self, l: DVec3) -> DVec3 {
        self.centre + self.direction_from_local(l)
    }

    pub fn direction_from_local(&self, l: DVec3) -> DVec3 {
        self.x * l.x + self.y * l.y + self.z * l.z
    }
}

/// A two-part mapping as a material gives it.
#[derive(Clone, Debug, PartialEq)]
pub struct Mapping {
    pub surface: IntermediateSurface,
    pub projector: Projector,
    pub frame: Frame,
    /// Plane: the size of one texture tile along x and y. Box: the side of the box.
    pub size: DVec2,
    /// Cylinder: the height that v = 1 reaches from the frame's origin.
    pub height: f64,
    /// Cylinder and sphere: the radius the object-normal, centroid and reflected
    /// projectors intersect.
    pub radius: f64,
    /// (u, v) multiplied by this after the S-mapping (tiling with `repeat` wrap).
    pub repeat: DVec2,
}

/// Box faces: outward axis and the in-plane u and v axes (u × v = outward), in the
/// frame's coordinates. The built-in box's faces follow the same table, so a box
/// mapping whose frame is the object's own (axis z, reference x) reproduces the
/// box's own texture coordinates.
pub const BOX_FACES: [(DVec3, DVec3, DVec3); 6] = [
    (DVec3::X, DVec3::NEG_Z, DVec3::Y),
    (DVec3::NEG_X, DVec3::Z, DVec3::Y),
    (DVec3::Y, DVec3::X, DVec3::NEG_Z),
    (DVec3::NEG_Y, DVec3::X, DVec3::Z),
    (DVec3::Z, DVec3::X, DVec3::Y),
    (DVec3::NEG_Z, DVec3::NEG_X, DVec3::Y),
];

/// θ = atan2(y, x) in [0, 2π).
fn angle(l: DVec3) -> f64 {
    let t = l.y.atan2(l.x);
    if t < 0.0 { t + TAU } else { t }
}

/// The box face whose outward axis is nearest `d`.
fn box_face(d: DVec3) -> usize {
    let a = d.abs();
    if a.x >= a.y && a.x >= a.z {
        if d.x >= 0.0 { 0 } else { 1 }
    } else if a.y >= a.z {
        if d.y >= 0.0 { 2 } else { 3 }
    } else if d.z >= 0.0 {
        4
    } else {
        5
    }
}

impl Mapping {
    pub fn check(&self) -> Result<()> {
        ensure_valid!(
            self.size.min_element() > 0.0 && self.size.is_finite(),
            "size",
            "mapping size must be positive"
        );
        ensure_valid!(
            self.height > 0.0 && self.height.is_finite(),
            "height",
            "mapping height must be positive"
        );
        ensure_valid!(
            self.radius > 0.0 && self.radius.is_finite(),
            "radius",
            "mapping radius must be positive"
        );
        ensure_valid!(
            self.repeat.min_element() > 0.0 && self.repeat.is_finite(),
            "repeat",
            "mapping repeat must be positive"
        );
        Ok(())
    }

    /// The S-mapping of a point in the frame's coordinates; `facing` picks the box
    /// face (the direction the point is seen along).
    pub fn s_mapping(&self, l: DVec3, facing: DVec3) -> DVec2 {
        let uv = match self.surface {
            IntermediateSurface::Plane => DVec2::new(l.x / self.size.x, l.y / self.size.y),
            IntermediateSurface::Cylinder => DVec2::new(angle(l) / TAU, l.z / self.height),
            IntermediateSurface::Sphere => {
                let r = l.length();
                let phi = if r > 0.0 {
                    (l.z / r).clamp(-1.0, 1.0).asin()
                } else {
                    0.0
                };
                DVec2::new(angle(l) / TAU, (phi + PI / 2.0) / PI)
            }
            IntermediateSurface::Box => {
                let (_, u, v) = BOX_FACES[box_face(facing)];
                DVec2::new(l.dot(u) / self.size.x + 0.5, l.dot(v) / self.size.y + 0.5)
            }
        };
        uv * self.repeat
    }

    /// (u, v) of object point `p` with object normal `n`; `centroid` is the object's
    /// centroid and `to_eye` the unit direction from `p` to the eye (both used only
    /// by their projectors). All in the object's coordinates.
    pub fn uv(&self, p: DVec3, n: DVec3, centroid: DVec3, to_eye: DVec3) -> DVec2 {
        let f = &self.frame;
        let (l, ln) = (f.to_local(p), f.direction_to_local(n));
        let line = match self.projector {
            Projector::Surface => None,
            Projector::Normal => Some((l, ln, false)),
            Projector::Centroid => Some((f.to_local(centroid), l - f.to_local(centroid), true)),
            Projector::Reflected => {
                let e = f.direction_to_local(to_eye);
                Some((l, 2.0 * e.dot(ln) * ln - e, true))
            }
        };
        let hit = line.and_then(|(o, d, forward)| self.intersect(o, d, forward));
        match hit {
            Some(q) => self.s_mapping(q, q),
            // Intermediate-surface normal: the point itself (the box by its normal).
            None => self.s_mapping(l, if ln == DVec3::ZERO { l } else { ln }),
        }
    }

    /// Where the line o + t d meets the intermediate surface: the first t > 0 when
    /// `forward`, else the t of least magnitude.
    fn intersect(&self, o: DVec3, d: DVec3, forward: bool) -> Option<DVec3> {
        let roots: Vec<f64> = match self.surface {
            IntermediateSurface::Plane => vec![-o.z / d.z],
            IntermediateSurface::Cylinder => quadratic(
                d.x * d.x + d.y * d.y,
                2.0 * (o.x * d.x + o.y * d.y),
                o.x * o.x + o.y * o.y - self.radius * self.radius,
            ),
            IntermediateSurface::Sphere => quadratic(
                d.length_squared(),
                2.0 * o.dot(d),
                o.length_squared() - self.radius * self.radius,
            ),
            IntermediateSurface::Box => {
                let half = DVec3::new(self.size.x, self.size.y, self.size.x) / 2.0;
                let (t0, t1) = ((-half - o) / d, (half - o) / d);
                let (near, far) = (t0.min(t1).max_element(), t0.max(t1).min_element());
                if near <= far { vec![near, far] } else { vec![] }
            }
        };
        let t = roots
            .into_iter()
            .filter(|t| t.is_finite() && (!forward || *t > 0.0))
            .min_by(|a, b| {
                let key = |t: f64| if forward { t } else { t.abs() };
                key(*a).total_cmp(&key(*b))
            })?;
        Some(o + d * t)
    }

    /// The point of the intermediate surface at (u, v), the surface passing through
    /// local point `through` (its radius for a cylinder or sphere): the S-mapping's
    /// inverse. Plane, cylinder and sphere.
    pub fn surface_point(&self, uv: DVec2, through: DVec3) -> DVec3 {
        let uv = uv / self.repeat;
        let theta = uv.x * TAU;
        match self.surface {
            IntermediateSurface::Plane | IntermediateSurface::Box => {
                DVec3::new(uv.x * self.size.x, uv.y * self.size.y, 0.0)
            }
            IntermediateSurface::Cylinder => {
                let r = through.truncate().length();
                DVec3::new(r * theta.cos(), r * theta.sin(), uv.y * self.height)
            }
            IntermediateSurface::Sphere => {
                let r = through.length();
                let phi = uv.y * PI - PI / 2.0;
                r * DVec3::new(theta.cos() * phi.cos(), theta.sin() * phi.cos(), phi.sin())
            }
        }
    }

    /// The tangents ∂O/∂u and ∂O/∂v of the intermediate surface through object point
    /// `p` (object coordinates): the analytic surface derivatives bump mapping needs.
    /// `n` (the object normal) picks the box face.
    pub fn tangents(&self, p: DVec3, n: DVec3) -> [DVec3; 2] {
        let f = &self.frame;
        let l = f.to_local(p);
        let (ru, rv) = (self.repeat.x, self.repeat.y);
        let (du, dv) = match self.surface {
            IntermediateSurface::Plane => {
                (DVec3::X * self.size.x / ru, DVec3::Y * self.size.y / rv)
            }
            IntermediateSurface::Box => {
                let (_, u, v) = BOX_FACES[box_face(f.direction_to_local(n))];
                (u * self.size.x / ru, v * self.size.y / rv)
            }
            IntermediateSurface::Cylinder => {
                let (r, theta) = (l.truncate().length(), angle(l));
                (
                    DVec3::new(-theta.sin(), theta.cos(), 0.0) * (r * TAU / ru),
                    DVec3::Z * (self.height / rv),
                )
            }
            IntermediateSurface::Sphere => {
                let r = l.length();
                let theta = angle(l);
                let phi = if r > 0.0 {
                    (l.z / r).clamp(-1.0, 1.0).asin()
                } else {
                    0.0
                };
                (
                    DVec3::new(-theta.sin() * phi.cos(), theta.cos() * phi.cos(), 0.0)
                        * (r * TAU / ru),
                    DVec3::new(
                        -theta.cos() * phi.sin(),
                        -theta.sin() * phi.sin(),
                        phi.cos(),
                    ) * (r * PI / rv),
                )
            }
        };
        [f.direction_from_local(du), f.direction_from_local(dv)]
    }

    /// Whether u wraps around (cylinder, sphere): per-vertex coordinates then need the
    /// seam fixed.
    pub fn wraps_in_u(&self) -> bool {
        matches!(
            self.surface,
            IntermediateSurface::Cylinder | IntermediateSurface::Sphere
        )
    }

    /// Whether local point `l` lies on the axis, where θ (so u) is undefined: the
    /// sphere's poles, the centre of a cylinder's cap.
    pub fn on_axis(&self, p: DVec3) -> bool {
        let l = self.frame.to_local(p);
        self.wraps_in_u() && l.truncate().length() <= 1e-9 * l.length().max(1e-300)
    }
}

/// Real roots of a t² + b t + c.
fn quadratic(a: f64, b: f64, c: f64) -> Vec<f64> {
    if a == 0.0 {
        return vec![-c / b];
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return vec![];
    }
    let s = disc.sqrt();
    vec![(-b - s) / (2.0 * a), (-b + s) / (2.0 * a)]
}

/// Per-vertex texture coordinates of one polygon under a wrapping mapping, made
/// continuous across the seam: when the u of its vertices spread over more than half a
/// turn, the small ones get one more turn (sampling wraps them back); a vertex on the
/// axis, whose θ is undefined, takes the mean u of the others (the course's pinching
/// at the poles).
pub fn fix_seam(uvs: &mut [DVec2], on_axis: &[bool], period: f64) {
    let off: Vec<usize> = (0..uvs.len()).filter(|&k| !on_axis[k]).collect();
    if off.is_empty() {
        return;
    }
    let (lo, hi) = off
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &k| {
            (lo.min(uvs[k].x), hi.max(uvs[k].x))
        });
    if hi - lo > period / 2.0 {
        for &k in &off {
            if uvs[k].x < lo + period / 2.0 {
                uvs[k].x += period;
            }
        }
    }
    let mean = off.iter().map(|&k| uvs[k].x).sum::<f64>() / off.len() as f64;
    for (k, uv) in uvs.iter_mut().enumerate() {
        if on_axis[k] {
            uv.x = mean;
        }
    }
}
