//! Built-in shapes, in object space before the object's transform:
//! quad (unit square in the xz plane, facing +y), box (unit cube), sphere (unit
//! radius) and cylinder (unit radius, y from −0.5 to 0.5), all centred on the origin.
//! Faces run counter-clockwise seen from outside.

use super::Vertex;
use crate::texture::mapping::{BOX_FACES, Frame, IntermediateSurface, Mapping, Projector};
use glam::{DVec2, DVec3};
use std::f64::consts::{PI, TAU};

/// A shape's polygons as vertex lists.
pub type Faces = Vec<Vec<Vertex>>;

fn flat_face(corners: &[DVec3], uvs: &[DVec2]) -> Vec<Vertex> {
    let normal = crate::geometry::polygon::newell_normal(corners).normalize();
    corners
        .iter()
        .zip(uvs)
        .map(|(&position, &uv)| Vertex {
            position,
            normal,
            uv,
        })
        .collect()
}

const UNIT_UV: [DVec2; 4] = [
    DVec2::new(0.0, 0.0),
    DVec2::new(1.0, 0.0),
    DVec2::new(1.0, 1.0),
    DVec2::new(0.0, 1.0),
];

pub fn quad() -> Faces {
    let c = [
        DVec3::new(-0.5, 0.0, 0.5),
        DVec3::new(0.5, 0.0, 0.5),
        DVec3::new(0.5, 0.0, -0.5),
        DVec3::new(-0.5, 0.0, -0.5),
    ];
    vec![flat_face(&c, &UNIT_UV)]
}

pub fn polygon(corners: &[DVec3]) -> Faces {
    let uvs: Vec<DVec2> = corners.iter().map(|p| DVec2::new(p.x, p.z)).collect();
    vec![flat_face(corners, &uvs)]
}

pub fn cube() -> Faces {
    // Each face: an outward axis and two in-plane axes (u, v) with u × v = outward.
    BOX_FACES
        .iter()
        .map(|&(n, u, v)| {
            let c = [
                0.5 * (n - u - v),
                0.5 * (n + u - v),
                0.5 * (n + u + v),
                0.5 * (n - u + v),
            ];
            flat_face(&c, &UNIT_UV)
        })
        .collect()
}

/// A UV sphere: `resolution` segments around y, `resolution / 2` rings; quads between
/// rings and triangles at the poles. Vertex normals point radially; with `smooth`
/// false the faces get their flat normals instead.
pub fn sphere(resolution: u32, smooth: bool) -> Faces {
    let segments = resolution as usize;
    let rings = (resolution as usize / 2).max(2);
    let point = |i: usize, j: usize| {
        let (u, v) = (i as f64 / segments as f64, j as f64 / rings as f64);
        // The seam and the poles are computed once, so that neighbouring faces share
        // their corners bit for bit (sin 2π and sin π are not zero in floating point)
        // and the sphere is a closed mesh.
        let phi = (i % segments) as f64 / segments as f64 * TAU;
        let theta = v * PI;
        let position = if j == 0 || j == rings {
            DVec3::new(0.0, theta.cos().signum(), 0.0)
        } else {
            DVec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                -theta.sin() * phi.sin(),
            )
        };
        Vertex {
            position,
            normal: position,
            uv: DVec2::new(u, 1.0 - v),
        }
    };
    let mut faces = Vec::new();
    for j in 0..rings {
        for i in 0..segments {
            // Quads between rings; at the poles the two pole corners coincide, so the
            // face is the triangle without the repeated one.
            let face = if j == 0 {
                vec![point(i, j), point(i, j + 1), point(i + 1, j + 1)]
            } else if j + 1 == rings {
                vec![point(i, j), point(i, j + 1), point(i + 1, j)]
            } else {
                vec![
                    point(i, j),
                    point(i, j + 1),
                    point(i + 1, j + 1),
                    point(i + 1, j),
                ]
            };
            faces.push(finish(face, smooth));
        }
    }
    faces
}

/// The spherical mapping the sphere's own texture coordinates follow: axis y, θ = 0
/// along x (so `material.mapping` with these values reproduces them).
pub fn sphere_mapping() -> Mapping {
    own_mapping(IntermediateSurface::Sphere, DVec3::ZERO)
}

/// The cylindrical mapping of the cylinder's sides: axis y from its base at y = −0.5,
/// height 1.
pub fn cylinder_mapping() -> Mapping {
    own_mapping(IntermediateSurface::Cylinder, DVec3::new(0.0, -0.5, 0.0))
}

fn own_mapping(surface: IntermediateSurface, centre: DVec3) -> Mapping {
    Mapping {
        surface,
        projector: Projector::Surface,
        frame: Frame::new(centre, DVec3::Y, DVec3::X).expect("a valid frame"),
        size: DVec2::ONE,
        height: 1.0,
        radius: 1.0,
        repeat: DVec2::ONE,
    }
}

/// A cylinder of `resolution` side quads, optionally closed by two polygons.
pub fn cylinder(resolution: u32, caps: bool, smooth: bool) -> Faces {
    let n = resolution as usize;
    let rim = |i: usize, y: f64| {
        let u = i as f64 / n as f64;
        // The seam is computed once, so that the last quad shares the first one's edge.
        let phi = (i % n) as f64 / n as f64 * TAU;
        let radial = DVec3::new(phi.cos(), 0.0, -phi.sin());
        Vertex {
            position: radial + DVec3::new(0.0, y, 0.0),
            normal: radial,
            uv: DVec2::new(u, y + 0.5),
        }
    };
    let mut faces: Faces = (0..n)
        .map(|i| {
            let face = vec![rim(i, -0.5), rim(i + 1, -0.5), rim(i + 1, 0.5), rim(i, 0.5)];
            finish(face, smooth)
        })
        .collect();
    if caps {
        let disc = |y: f64, up: bool| {
            let mut c: Vec<DVec3> = (0..n).map(|i| rim(i, y).position).collect();
            if !up {
                c.reverse();
            }
            let uvs: Vec<DVec2> = c.iter().map(|p| DVec2::new(p.x, p.z) * 0.5 + 0.5).collect();
            flat_face(&c, &uvs)
        };
        faces.push(disc(0.5, true));
        faces.push(disc(-0.5, false));
    }
    faces
}

fn finish(face: Vec<Vertex>, smooth: bool) -> Vec<Vertex> {
    if smooth {
        return face;
    }
    let corners: Vec<DVec3> = face.iter().map(|v| v.position).collect();
    let uvs: Vec<DVec2> = face.iter().map(|v| v.uv).collect();
    flat_face(&corners, &uvs)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::polygon::newell_normal;

    fn outward(faces: &Faces) -> bool {
        faces.iter().all(|f| {
            let c: Vec<DVec3> = f.iter().map(|v| v.position).collect();
            let centre = c.iter().copied().sum::<DVec3>() / c.len() as f64;
            newell_normal(&c).dot(centre) > 0.0
        })
    }

    #[test]
    fn closed_shapes_face_outwards() {
        assert!(outward(&cube()));
        assert!(outward(&sphere(12, true)));
        assert!(outward(&cylinder(10, true, true)));
    }

    #[test]
    fn cube_area_is_six() {
        let a: f64 = cube()
            .iter()
            .map(|f| {
                crate::geometry::polygon::area(&f.iter().map(|v| v.position).collect::<Vec<_>>())
            })
            .sum();
        assert!((a - 6.0).abs() < 1e-12);
    }

    #[test]
    fn quad_faces_up() {
        let q = quad();
        assert_eq!(q[0][0].normal, DVec3::Y);
    }
}
