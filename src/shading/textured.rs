//! Textures in the shading pass. Per sample of a textured polygon: the texture
//! coordinates (as the scan-line pass interpolated them, or the material's mapping
//! evaluated at the visible point when the projection function is known), the
//! filtered colours that scale the material's reflectances, and Blinn's perturbed
//! normal from the bump map and the surface's derivatives O_u, O_v.
//!
//! Where O_u and O_v come from: the material's mapping (the analytic intermediate
//! surface through the point), else a built-in sphere's or cylinder's own analytic
//! parameterisation, else the polygon's texture coordinates (P_u and P_v solved from
//! its vertices, constant over the polygon as Blinn does per triangle), with N the
//! interpolated shading normal. All are carried by the object's transform, so the
//! wrinkles move with the object.

use crate::raster::{Sample, VisibleSurface};
use crate::scene::{Material, Polygon, Reflectance, Scene};
use crate::texture::Interpolation;
use crate::texture::bump::perturb;
use glam::{DMat3, DVec2, DVec3};

/// The reflectance and unit shading normal (not yet turned towards the eye) at
/// sample `k`, textures and bump applied.
pub fn textured_point(
    scene: &Scene,
    eye: DVec3,
    surface: &VisibleSurface,
    k: usize,
    polygon_tangents: &[Option<[DVec3; 2]>],
) -> (Reflectance, DVec3) {
    let s = &surface.samples[k];
    let polygon = &scene.polygons[s.polygon as usize];
    let material = &scene.materials[polygon.material];
    let frame = &scene.objects[polygon.object].frame;
    let normal = s.normal.as_dvec3();
    let local = Local::of(s, normal, eye, frame);
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
    polygon_tangents: &[Option<[DVec3; 2]>],
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
        None => polygon_tangents[s.polygon as usize].unwrap_or([DVec3::ZERO; 2]),
    }
}

/// Per polygon with a bump-mapped material, P_u and P_v from its vertices' texture
/// coordinates (`None` for the others).
pub fn polygon_tangents(scene: &Scene) -> Vec<Option<[DVec3; 2]>> {
    scene
        .polygons
        .iter()
        .map(|p| {
            let m: &Material = &scene.materials[p.material];
            m.bump.map(|_| tangents_from_uv(p))
        })
        .collect()
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
