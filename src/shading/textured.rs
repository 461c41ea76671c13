//! Textures in the shading pass. Per sample of a textured polygon: the texture
//! coordinates (as the scan-line pass interpolated them, or the material's mapping
//! evaluated at the visible point when the projection function is known), the
//! filtered colours that scale the material's reflectances, and Blinn's perturbed
//! normal from the bump map and the surface's derivatives O_u, O_v.
//!
//! Where O_u and O_v come from: the material's mapping (the analytic intermediate
//! surface through the point), else a built-in sphere's or cylinder's own analytic
//! parameterisation, else the mesh's texture coordinates (P_u and P_v solved per
//! polygon as Blinn does per triangle, averaged into per-vertex frames and
//! interpolated across each polygon), with N the interpolated shading normal. All are carried by the object's transform, so the
//! wrinkles move with the object.

use crate::geometry::polygon::area;
use crate::raster::{Sample, VisibleSurface};
use crate::scene::{Polygon, Reflectance, Scene};
use crate::texture::Interpolation;
use crate::texture::bump::perturb;
use glam::{DMat3, DVec2, DVec3};
use std::cell::LazyCell;
use std::collections::HashMap;

/// The reflectance and unit shading normal (not yet turned towards the eye) at
/// sample `k`, textures and bump applied.
pub fn textured_point(
    scene: &Scene,
    eye: DVec3,
    surface: &VisibleSurface,
    k: usize,
    polygon_tangents: &[Option<Vec<[DVec3; 2]>>],
) -> (Reflectance, DVec3) {
    let s = &surface.samples[k];
    let polygon = &scene.polygons[s.polygon as usize];
    let material = &scene.materials[polygon.material];
    let frame = &scene.objects[polygon.object].frame;
    let normal = s.normal.as_dvec3();
    // Only the exact mapping and bump frames need the point in modelling coordinates.
    let local = LazyCell::new(|| Local::of(s, normal, eye, frame));
    let uv = match &material.mapping {
        Some(m) if material.interpolation == Interpolation::Exact => {
            m.uv(local.point, local.normal, frame.centroid, local.to_eye)
        }
        _ => s.uv,
    };
    let footprint = surface.uv_derivatives(k);
    let texture = |t: Option<usize>| t.map(|t| scene.textures[t].color(uv, footprint));
    let mut reflectance = material.reflectance();
    if let Some(c) = texture(material.diffuse_texture) {
        reflectance.diffuse *= c;
    }
    if let Some(c) = texture(material.specular_texture) {
        reflectance.specular *= c;
    }
    let normal = match material.bump {
        Some(bump) => {
            let (_, gradient) = scene.textures[bump.texture].height(uv);
            let tangents = surface_tangents(scene, polygon, &local, polygon_tangents, s);
            perturb(normal, tangents, gradient * bump.height)
        }
        None => normal,
    };
    (reflectance, normal)
}

/// A sample's point, normal and eye direction in its object's modelling coordinates.
struct Local {
    point: DVec3,
    normal: DVec3,
    to_eye: DVec3,
}

impl Local {
    fn of(s: &Sample, normal: DVec3, eye: DVec3, frame: &crate::scene::ObjectFrame) -> Local {
        let point = frame.to_object.transform_point3(s.position);
        Local {
            point,
            normal: frame.normal_to_object(normal).normalize_or_zero(),
            to_eye: (frame.to_object.transform_point3(eye) - point).normalize_or_zero(),
        }
    }
}

/// O_u and O_v at the sample, in world coordinates.
fn surface_tangents(
    scene: &Scene,
    polygon: &Polygon,
    local: &Local,
    polygon_tangents: &[Option<Vec<[DVec3; 2]>>],
    s: &Sample,
) -> [DVec3; 2] {
    let frame = &scene.objects[polygon.object].frame;
    let material = &scene.materials[polygon.material];
    let analytic = material.mapping.as_ref().or_else(|| {
        // A built-in shape's own parameterisation covers its curved sides, not the
        // flat caps of a cylinder (whose normal runs along the axis).
        frame.own_mapping.as_ref().filter(|m| {
            let n = frame.normal_to_object(polygon.normal).normalize_or_zero();
            n.dot(m.frame.z).abs() < 0.999
        })
    });
    match analytic {
        Some(m) => {
            let to_world = DMat3::from_mat4(frame.to_world);
            m.tangents(local.point, local.normal).map(|t| to_world * t)
        }
        None => match &polygon_tangents[s.polygon as usize] {
            Some(values) => interpolate(polygon, values, s.position),
            None => [DVec3::ZERO; 2],
        },
    }
}

/// Per polygon with a bump-mapped material, O_u and O_v at each of its vertices
/// (`None` for the others): the per-vertex frames of a mesh parameterised by its
/// texture coordinates. Each polygon's P_u and P_v are solved from its vertices, then
/// averaged, weighted by area, over the polygons sharing a vertex (same position,
/// normal and texture coordinates: smooth meshes share, creases and seams do not).
pub fn polygon_tangents(scene: &Scene) -> Vec<Option<Vec<[DVec3; 2]>>> {
    type Key = (usize, [u64; 3], [u64; 3], [u64; 2]);
    let key = |p: &Polygon, v: &crate::scene::Vertex| -> Key {
        (
            p.object,
            v.position.to_array().map(f64::to_bits),
            v.normal.to_array().map(f64::to_bits),
            v.uv.to_array().map(f64::to_bits),
        )
    };
    let bumped = |p: &Polygon| scene.materials[p.material].bump.is_some();
    // Per vertex key: area-weighted sums of P_u and P_v, and the total weight.
    let mut sums: HashMap<Key, (DVec3, DVec3, f64)> = HashMap::new();
    for p in scene.polygons.iter().filter(|p| bumped(p)) {
        let weight = area(&p.positions().collect::<Vec<_>>());
        let [t_u, t_v] = tangents_from_uv(p);
        for v in &p.vertices {
            let sum = sums.entry(key(p, v)).or_default();
            sum.0 += t_u * weight;
            sum.1 += t_v * weight;
            sum.2 += weight;
        }
    }
    scene
        .polygons
        .iter()
        .map(|p| {
            bumped(p).then(|| {
                p.vertices
                    .iter()
                    .map(|v| {
                        let (a, b, w) = sums[&key(p, v)];
                        [a / w, b / w]
                    })
                    .collect()
            })
        })
        .collect()
}

/// Vertex values interpolated at `point` of a planar polygon: barycentric in the fan
/// triangle (v0, vk, vk+1) that holds the point best.
fn interpolate(p: &Polygon, values: &[[DVec3; 2]], point: DVec3) -> [DVec3; 2] {
    let v = &p.vertices;
    let mut best = (f64::NEG_INFINITY, values[0]);
    for k in 1..v.len() - 1 {
        let (a, b, c) = (v[0].position, v[k].position, v[k + 1].position);
        let n = (b - a).cross(c - a);
        let n2 = n.length_squared();
        if n2 == 0.0 {
            continue;
        }
        let wb = (point - a).cross(c - a).dot(n) / n2;
        let wc = (b - a).cross(point - a).dot(n) / n2;
        let wa = 1.0 - wb - wc;
        let inside = wa.min(wb).min(wc);
        if inside > best.0 {
            let mix = |i: usize| values[0][i] * wa + values[k][i] * wb + values[k + 1][i] * wc;
            best = (inside, [mix(0), mix(1)]);
        }
    }
    best.1
}

/// Solves P_i − P_0 = P_u (u_i − u_0) + P_v (v_i − v_0) on the polygon's best-shaped
/// fan triangle (exact for a planar polygon with affine texture coordinates).
fn tangents_from_uv(p: &Polygon) -> [DVec3; 2] {
    let v = &p.vertices;
    let mut best = (0.0, [DVec3::ZERO; 2]);
    for k in 1..v.len() - 1 {
        let (e1, e2) = (
            v[k].position - v[0].position,
            v[k + 1].position - v[0].position,
        );
        let (d1, d2): (DVec2, DVec2) = (v[k].uv - v[0].uv, v[k + 1].uv - v[0].uv);
        let det = d1.x * d2.y - d2.x * d1.y;
        if det.abs() > best.0 {
            let p_u = (e1 * d2.y - e2 * d1.y) / det;
            let p_v = (e2 * d1.x - e1 * d2.x) / det;
            best = (det.abs(), [p_u, p_v]);
        }
    }
    best.1
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Vertex;

    fn polygon(points: &[(f64, f64)]) -> Polygon {
        Polygon {
            vertices: points
                .iter()
                .map(|&(x, z)| Vertex {
                    position: DVec3::new(x, 0.0, z),
                    normal: DVec3::Y,
                    // An affine parameterisation: u along x (scaled), v along −z.
                    uv: DVec2::new(x / 2.0, -z / 3.0),
                })
                .collect(),
            normal: DVec3::Y,
            material: 0,
            object: 0,
        }
    }

    #[test]
    fn an_affine_parameterisation_gives_its_exact_tangents_everywhere() {
        let p = polygon(&[(0.0, 0.0), (1.0, 0.0), (1.5, -1.0), (0.2, -1.3)]);
        let t = tangents_from_uv(&p);
        assert!((t[0] - DVec3::new(2.0, 0.0, 0.0)).length() < 1e-12);
        assert!((t[1] - DVec3::new(0.0, 0.0, -3.0)).length() < 1e-12);
        let values = vec![t; 4];
        let inside = interpolate(&p, &values, DVec3::new(0.7, 0.0, -0.6));
        assert!((inside[0] - t[0]).length() < 1e-12 && (inside[1] - t[1]).length() < 1e-12);
    }

    #[test]
    fn interpolation_reproduces_vertex_values() {
        let p = polygon(&[(0.0, 0.0), (1.0, 0.0), (1.0, -1.0), (0.0, -1.0)]);
        let values: Vec<[DVec3; 2]> = (0..4)
            .map(|k| [DVec3::X * k as f64, DVec3::Z * (k * k) as f64])
            .collect();
        for (k, v) in p.vertices.iter().enumerate() {
            let got = interpolate(&p, &values, v.position);
            assert!((got[0] - values[k][0]).length() < 1e-12);
            assert!((got[1] - values[k][1]).length() < 1e-12);
        }
    }
}
