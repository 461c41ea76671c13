//! The sampled soft-shadow methods against the exact one: Brotman & Badler's
//! soft shadow volumes and ray casting's stratified light samples converge to
//! Nishita & Nakamae's exact penumbra on the Cornell box; jittered hexagonal cells
//! converge to the exact visible share of a spherical light's disc. Brotman & Badler
//! with one point at the light's centre is Crow's shadow volumes bit for bit, its
//! count is an integer in [0, n]; regular cells give at most N + 1 levels (bands),
//! jittered ones do not, and on average their estimate is the uncovered share of the
//! disc behind a straight edge.

use crate::support;

use glam::{DVec2, DVec3, Vec3};
use lumiere::geometry::central_projection::onto_plane;
use lumiere::geometry::disc::area_inside;
use lumiere::geometry::sampling::Stream;
use lumiere::raster::{LightVisibility, View, Visibility, VisibleSurface};
use lumiere::render::visible_surface;
use lumiere::scene::{Light, SphereLight};
use lumiere::settings::{CellSampling, ShadowSettings};
use lumiere::shading::FrameShading;
use lumiere::shadow::jittered_soft_shadows::JitteredSoftShadows;
use lumiere::shadow::shadow_volumes::ShadowVolumes;
use lumiere::shadow::soft_shadow_volumes::SoftShadowVolumes;
use lumiere::shadow::{self, LightShadows, SceneOccluders, ShadowMethod};
use lumiere::{Scene, load_scene};
use std::f64::consts::PI;
use std::sync::Arc;

fn scene_with(id: &str, sets: &[String]) -> Scene {
    load_scene(id, sets).unwrap_or_else(|e| panic!("{}", support::error_line(&e)))
}

/// Light 0's shadows by `settings` on the whole frame: visibility and counts.
fn shadows_of(
    scene: &Scene,
    view: &View,
    surface: &VisibleSurface,
    settings: &ShadowSettings,
) -> (LightVisibility, Option<Vec<i32>>) {
    let band = shadow::light_band(scene, view, surface, settings, 0)
        .unwrap()
        .expect("shadowed");
    (band.visibility, band.counts)
}

/// Per sample radiance with light 0 weighed by `visibility`.
fn shade(scene: &Scene, view: &View, surface: &VisibleSurface, v: LightVisibility) -> Vec<Vec3> {
    let shading = FrameShading::new(scene, view, vec![true]);
    let visibility = Visibility {
        per_light: vec![Some(v)],
    };
    shading.shade_band(surface, &visibility, &[])
}

/// RMSE between two radiance images over the mean of the reference.
fn relative_rmse(found: &[Vec3], reference: &[Vec3]) -> f64 {
    let n = found.len() as f64 * 3.0;
    let sum: f64 = found
        .iter()
        .zip(reference)
        .map(|(a, b)| (*a - *b).length_squared() as f64)
        .sum();
    let mean: f64 = reference
        .iter()
        .map(|r| (r.x + r.y + r.z) as f64)
        .sum::<f64>()
        / n;
    (sum / n).sqrt() / mean
}

/// The Cornell box at 128 x 128 (the lamp's own pixels left out of the error: they
/// are emission, the same in every method).
fn cornell() -> (Scene, View, VisibleSurface) {
    let scene = scene_with(
        "cornell-box",
        &["camera.width=128".into(), "camera.height=128".into()],
    );
    let (view, surface) = visible_surface(&scene);
    (scene, view, surface)
}

/// Soft shadow volumes with n points and ray casting with √n × √n samples against
/// umbra-penumbra, n = 4, 16, 64, 256: their relative RMSEs, each asserted falling
/// and under 2% at 256.
fn converge_to_the_exact_penumbra(scene: &Scene, view: &View, surface: &VisibleSurface) {
    let settings = |method, points, samples| ShadowSettings {
        method,
        light_points: points,
        light_samples: samples,
        ..scene.shadows.clone()
    };
    let exact = shadows_of(
        scene,
        view,
        surface,
        &settings(ShadowMethod::UmbraPenumbra, 1, 1),
    )
    .0;
    let reference = shade(scene, view, surface, exact);
    let mut table = Vec::new();
    for (points, samples) in [(4, 2), (16, 4), (64, 8), (256, 16)] {
        let volumes = settings(ShadowMethod::SoftShadowVolumes, points, 1);
        let (v, counts) = shadows_of(scene, view, surface, &volumes);
        let soft = relative_rmse(&shade(scene, view, surface, v), &reference);
        // The paper's count: an integer number of hidden points, 0 to n.
        let counts = counts.expect("the blocked count");
        assert!(counts.iter().all(|&c| (0..=points as i32).contains(&c)));
        let cast = settings(ShadowMethod::RayCast, 1, samples);
        let (v, _) = shadows_of(scene, view, surface, &cast);
        let sampled = relative_rmse(&shade(scene, view, surface, v), &reference);
        table.push((points, soft, sampled));
    }
    eprintln!("n, relative RMSE of soft shadow volumes, of ray casting: {table:?}");
    for w in table.windows(2) {
        assert!(
            w[1].1 < w[0].1,
            "soft shadow volumes do not converge: {table:?}"
        );
        assert!(w[1].2 < w[0].2, "ray casting does not converge: {table:?}");
    }
    let (_, soft, sampled) = table[3];
    assert!(soft < 0.02 && sampled < 0.02, "{table:?}");
}

#[test]
fn soft_shadow_volumes_and_ray_casting_converge_to_the_exact_penumbra() {
    let (scene, view, surface) = cornell();
    converge_to_the_exact_penumbra(&scene, &view, &surface);
}

/// The same under the L-shaped light of `umbra-penumbra-concave`: points and samples
/// spread over the L's triangles, the exact visible part over its convex pieces. (Soft
/// shadow volumes counted the L's own polygon as an occluder of its points: the
/// quads its edges swept lay in its plane and, the L being concave, overlapped, so
/// the floor came out streaked and dark.)
#[test]
fn under_a_concave_light_too() {
    let scene = scene_with(
        "umbra-penumbra-concave",
        &["camera.width=128".into(), "camera.height=96".into()],
    );
    let (view, surface) = visible_surface(&scene);
    converge_to_the_exact_penumbra(&scene, &view, &surface);
}

/// With one point at the light's centre, Brotman & Badler's count is Crow's: the
/// same visibility bit for bit wherever the light shines (in front of it, and above
/// the sample's horizon; elsewhere the soft count gives nothing, where Crow's says
/// unshadowed), counts of 0 and 1.
#[test]
fn one_point_at_the_centre_is_shadow_volumes() {
    let (scene, view, surface) = cornell();
    let Light::Polygon(l) = &scene.lights[0] else {
        panic!("the quad light");
    };
    let soft = SoftShadowVolumes::at_points(&scene, &scene.lights[0], &[l.centre]);
    let crow = ShadowVolumes::new(&scene, l.centre);
    let a = soft.frame(&scene, &view).band(&surface);
    let b = crow.frame(&scene, &view).band(&surface);
    let (LightVisibility::Fraction(f), LightVisibility::Fraction(g)) =
        (&a.visibility, &b.visibility)
    else {
        panic!("fractions");
    };
    let blocked = a.counts.unwrap();
    let mut unlit = 0;
    for (k, sample) in surface.samples.iter().enumerate() {
        if sample.is_empty() {
            continue;
        }
        let mut n = scene.polygons[sample.polygon as usize].normal;
        if n.dot(view.eye - sample.position) < 0.0 {
            n = -n;
        }
        let to_light = l.centre - sample.position;
        if n.dot(to_light) > 0.0 && l.normal.dot(-to_light) > 0.0 {
            assert_eq!(f[k], g[k], "sample {k}");
            let c = blocked[k];
            assert!(
                (f[k] == 0.0 && c == 1) || (f[k] == 1.0 && c == 0),
                "sample {k}"
            );
        } else {
            assert_eq!(f[k], 0.0, "sample {k}: the light cannot shine there");
            unlit += 1;
        }
    }
    assert!(unlit > 0, "the ceiling, behind the light, is seen");
    let dark = f.iter().filter(|&&v| v == 0.0).count() - unlit;
    assert!(dark > 2000, "{dark} shadowed samples");
}

/// A sphere light over a floor, a square plate between them.
fn sphere_scene_text() -> String {
    support::camera([0.0, 3.0, 5.0], [0.0, 0.0, 0.0], 35.0, 96, 72)
        + r#"[shadows]
method = "jittered-soft-shadows"

[materials.grey]
diffuse = [0.5, 0.5, 0.5]

[[lights]]
type = "sphere"
centre = [0.2, 3.0, 0.0]
radius = 0.5
radiance = [5.0, 5.0, 5.0]

[[objects]]
shape = "quad"
name = "floor"
material = "grey"
transform = [{ scale = 10.0 }]

[[objects]]
shape = "quad"
name = "plate"
material = "grey"
transform = [{ scale = 0.8 }, { translate = [0.0, 1.2, 0.0] }]
"#
}

fn sphere_scene(sets: &[String]) -> Scene {
    support::scene_from_text(&sphere_scene_text(), sets)
}

/// The exact visible share of the sphere's outline disc from `x`: the disc less the
/// plate projected from x onto the disc's plane (one convex plate, so one hole).
fn exact_disc_share(scene: &Scene, x: DVec3) -> f64 {
    let Light::Sphere(l) = &scene.lights[0] else {
        panic!("a sphere light");
    };
    let to_x = x - l.centre;
    let d = to_x.length();
    let axis = to_x / d;
    let centre = l.centre + axis * (l.radius * l.radius / d);
    let radius = l.radius * (1.0 - (l.radius / d).powi(2)).sqrt();
    let plate = scene
        .objects
        .iter()
        .position(|o| o.name == "plate")
        .unwrap();
    let (u, v) = axis.any_orthonormal_pair();
    let mut hidden = 0.0;
    for p in scene.polygons.iter().filter(|p| p.object == plate) {
        let corners: Vec<DVec3> = p.positions().collect();
        if let Some(shadow) = onto_plane(&corners, x, centre, axis) {
            let flat: Vec<DVec2> = shadow
                .iter()
                .map(|&q| DVec2::new((q - centre).dot(u), (q - centre).dot(v)))
                .collect();
            hidden += area_inside(&flat, DVec2::ZERO, radius).abs();
        }
    }
    1.0 - hidden / (PI * radius * radius)
}

#[test]
fn jittered_cells_converge_to_the_exact_share_of_the_disc() {
    let base = sphere_scene(&[]);
    let (view, surface) = visible_surface(&base);
    let exact: Vec<f32> = surface
        .samples
        .iter()
        .map(|s| {
            if s.is_empty() {
                0.0
            } else {
                exact_disc_share(&base, s.position) as f32
            }
        })
        .collect();
    let reference = shade(&base, &view, &surface, LightVisibility::Fraction(exact));
    let mut table = Vec::new();
    // 7, 19, 61 and 271 cells.
    for rings in [1, 2, 4, 9] {
        let settings = ShadowSettings {
            rings,
            ..base.shadows.clone()
        };
        let (v, _) = shadows_of(&base, &view, &surface, &settings);
        table.push((
            rings,
            relative_rmse(&shade(&base, &view, &surface, v), &reference),
        ));
    }
    eprintln!("rings, relative RMSE against the exact disc share: {table:?}");
    for w in table.windows(2) {
        assert!(w[1].1 < w[0].1, "{table:?}");
    }
    assert!(table[3].1 < 0.02, "{table:?}");
}

/// Regular cells: the same points for every pixel, so the visible fraction steps
/// only where an occluder's outline crosses one of them (by about one cell's share)
/// and between steps follows the cells' slowly varying irradiance weights, in
/// contiguous bands: neighbouring penumbra samples mostly differ by far less than a
/// cell's share. Jittered cells: each pixel its own points, so neighbours mostly
/// differ by a cell's share or so (noise).
#[test]
fn regular_cells_band_and_jittered_ones_do_not() {
    let Light::Sphere(l) = &sphere_scene(&[]).lights[0] else {
        panic!("a sphere light");
    };
    let occluders = Arc::new(SceneOccluders::owned(Vec::new()));
    let cells =
        JitteredSoftShadows::new(occluders, l.clone(), 0, 3, CellSampling::Regular, 0).rays();
    let smooth_pairs = |sampling: &str| {
        let scene = sphere_scene(&[
            format!("shadows.sampling={sampling}"),
            "shadows.rings=3".into(),
        ]);
        let (view, surface) = visible_surface(&scene);
        let (v, _) = shadows_of(&scene, &view, &surface, &scene.shadows);
        let LightVisibility::Fraction(f) = v else {
            panic!("a fraction");
        };
        // Horizontal neighbours inside the penumbra within a tenth of a cell's share.
        let width = surface.width as usize;
        let partial = |v: f32| v > 0.0 && v < 1.0;
        let (mut pairs, mut smooth) = (0, 0);
        for k in 0..f.len() - 1 {
            if (k + 1) % width != 0 && partial(f[k]) && partial(f[k + 1]) {
                pairs += 1;
                smooth += ((f[k] - f[k + 1]).abs() < 0.1 / cells as f32) as usize;
            }
        }
        (smooth as f64 / pairs as f64, pairs)
    };
    let (banded, pairs) = smooth_pairs("regular");
    let (noisy, _) = smooth_pairs("jittered");
    eprintln!(
        "{cells} cells: neighbours within a tenth of a cell's share: {banded:.3} regular, {noisy:.3} jittered ({pairs} pairs)"
    );
    assert!(pairs > 300, "{pairs}");
    assert!(
        banded > 0.3 && banded > 2.5 * noisy,
        "{banded} regular, {noisy} jittered"
    );
}

/// Behind a straight edge (a half-plane plate whose edge cuts the disc at distance a
/// from its centre), the jittered estimate averaged over seeds is the uncovered
/// share of the light's irradiance (a quadrature over the sphere's cap, beside the
/// disc's closed-form uncovered area); regular cells are off by their quantisation.
#[test]
fn averaged_over_seeds_jitter_is_unbiased_behind_a_straight_edge() {
    // Light: unit sphere at height 10 above the origin; the receiving point at the
    // origin; a plate at height 5 covering x > 0.15, so its edge cuts the (nearly
    // central) outline disc at a = 0.3 (projected from the origin, doubled).
    let light = SphereLight {
        centre: DVec3::new(0.0, 10.0, 0.0),
        radius: 1.0,
        radiance: Vec3::ONE,
        name: None,
    };
    let plate = lumiere::scene::Polygon {
        vertices: [
            DVec3::new(0.15, 5.0, -50.0),
            DVec3::new(0.15, 5.0, 50.0),
            DVec3::new(50.0, 5.0, 50.0),
            DVec3::new(50.0, 5.0, -50.0),
        ]
        .map(support::vertex)
        .to_vec(),
        normal: DVec3::Y,
        material: 0,
        object: 0,
    };
    let occluders = Arc::new(SceneOccluders::owned(vec![plate]));
    let x = DVec3::ZERO;
    // The outline disc: centre at 10 − 1/10, radius √(1 − 1/100); the edge's
    // projection onto its plane from x lies at 0.15 × 9.9/5.
    // The uncovered share of the disc's area, which the course's equal-area weights
    // estimate: the share of the irradiance differs from it by 5e-4 here.
    let r = (1.0f64 - 0.01).sqrt();
    let a = 0.15 * 9.9 / 5.0;
    let segment = r * r * (a / r).acos() - a * (r * r - a * a).sqrt();
    let area_share = 1.0 - segment / (PI * r * r);
    let plate_hides = |w: DVec3| w.y > 0.0 && 5.0 / w.y * w.x > 0.15;
    let (seen, whole) = cap_quadrature(x, DVec3::Y, &light, plate_hides, 2000, 8000);
    let exact = seen / whole;
    eprintln!("area share {area_share}, irradiance share {exact}");
    let jittered = JitteredSoftShadows::new(
        occluders.clone(),
        light.clone(),
        0,
        2,
        CellSampling::Jittered,
        0,
    );
    let seeds = 40_000;
    let values: Vec<f64> = (0..seeds)
        .map(|seed| jittered.fraction(x, DVec3::Y, u32::MAX, &mut Stream::new(seed, 0)))
        .collect();
    let mean = values.iter().sum::<f64>() / seeds as f64;
    let variance = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (seeds - 1) as f64;
    let standard_error = (variance / seeds as f64).sqrt();
    eprintln!("exact {exact}, jittered mean {mean} ± {standard_error}");
    assert!(
        (mean - exact).abs() < 4.0 * standard_error + 1e-6,
        "jittered {mean} ± {standard_error}, exact {exact}"
    );
    let regular = JitteredSoftShadows::new(occluders, light, 0, 2, CellSampling::Regular, 0);
    let banded = regular.fraction(x, DVec3::Y, u32::MAX, &mut Stream::new(0, 0));
    eprintln!("regular {banded}");
    // Regular cells are biased: their quantisation is many standard errors off.
    assert!(
        (banded - exact).abs() > 6.0 * standard_error,
        "regular {banded}"
    );
}

/// The light a sphere sends to `x` (normal `n`), by a midpoint rule over the
/// directions of its cap (polar angle φ from the axis to the centre, `rings` × `arcs`
/// cells of solid angle sin φ dφ dψ): (cosine-weighted solid angle of the directions
/// above the horizon that `hides` lets through, that of all above the horizon).
fn cap_quadrature(
    x: DVec3,
    n: DVec3,
    light: &SphereLight,
    hides: impl Fn(DVec3) -> bool,
    rings: usize,
    arcs: usize,
) -> (f64, f64) {
    let to_centre = light.centre - x;
    let distance = to_centre.length();
    let axis = to_centre / distance;
    let (t1, t2) = axis.any_orthonormal_pair();
    let half_angle = (light.radius / distance).asin();
    let (d_phi, d_psi) = (half_angle / rings as f64, 2.0 * PI / arcs as f64);
    let (mut seen, mut whole) = (0.0, 0.0);
    for i in 0..rings {
        let phi = (i as f64 + 0.5) * d_phi;
        for j in 0..arcs {
            let psi = (j as f64 + 0.5) * d_psi;
            let w = axis * phi.cos() + (t1 * psi.cos() + t2 * psi.sin()) * phi.sin();
            let cos = n.dot(w);
            if cos <= 0.0 {
                continue;
            }
            let weight = cos * phi.sin() * d_phi * d_psi;
            whole += weight;
            if !hides(w) {
                seen += weight;
            }
        }
    }
    (seen, whole)
}

fn plate_occluder(corners: [DVec3; 4]) -> lumiere::scene::Polygon {
    let normal = (corners[1] - corners[0])
        .cross(corners[2] - corners[0])
        .normalize();
    lumiere::scene::Polygon {
        vertices: corners.map(support::vertex).to_vec(),
        normal,
        material: 0,
        object: 0,
    }
}

/// A unit sphere close to the receiving point (at 1.5, or beside it across its
/// horizon): the jittered cells' share is the share of the irradiance the
/// occluder lets through, measured over the cap's directions, not of the disc's
/// area (off by 0.03 near, and by 0.43 across the horizon, where the half of the
/// disc below it counted as lit), and the unshadowed irradiance of the light model
/// is the cap's above the horizon.
#[test]
fn a_near_sphere_and_one_across_the_horizon_give_their_irradiance_share() {
    let x = DVec3::ZERO;
    let n = DVec3::Y;
    let cases = [
        (
            // A plate at height 0.25 over x > 0.05, under a sphere at 1.5.
            DVec3::new(0.0, 1.5, 0.0),
            [
                DVec3::new(0.05, 0.25, -50.0),
                DVec3::new(0.05, 0.25, 50.0),
                DVec3::new(50.0, 0.25, 50.0),
                DVec3::new(50.0, 0.25, -50.0),
            ],
        ),
        (
            // A sphere whose centre is 8.5° above the horizon and whose cap reaches
            // 21° below it; a wall at x = 0.9 above height 0.15 hides its top.
            DVec3::new(2.0, 0.3, 0.0),
            [
                DVec3::new(0.9, 0.15, -50.0),
                DVec3::new(0.9, 50.0, -50.0),
                DVec3::new(0.9, 50.0, 50.0),
                DVec3::new(0.9, 0.15, 50.0),
            ],
        ),
    ];
    for (centre, corners) in cases {
        let light = SphereLight {
            centre,
            radius: 1.0,
            radiance: Vec3::ONE,
            name: None,
        };
        let occluder = plate_occluder(corners);
        let (a, b, c) = (corners[0], corners[1], corners[2]);
        let hides = |w: DVec3| {
            // The ray x + t w meets the occluder's plane inside its rectangle.
            let t = occluder.normal.dot(a - x) / occluder.normal.dot(w);
            let hit = x + w * t;
            let (u, v) = (b - a, c - b);
            t > 0.0
                && (0.0..=u.length_squared()).contains(&(hit - a).dot(u))
                && (0.0..=v.length_squared()).contains(&(hit - b).dot(v))
        };
        let (seen, whole) = cap_quadrature(x, n, &light, hides, 1000, 4000);
        let exact = seen / whole;
        let model = lumiere::shading::sphere_form_factor::projected_solid_angle(x, n, centre, 1.0);
        assert!(
            (model - whole).abs() < 1e-4 * whole,
            "sphere at {centre}: the light model's {model}, the cap's {whole}"
        );
        let occluders = Arc::new(SceneOccluders::owned(vec![occluder.clone()]));
        let jittered = JitteredSoftShadows::new(occluders, light, 0, 24, CellSampling::Jittered, 0);
        let mean = (0..64)
            .map(|seed| jittered.fraction(x, n, u32::MAX, &mut Stream::new(seed, 0)))
            .sum::<f64>()
            / 64.0;
        eprintln!("sphere at {centre}: jittered {mean}, exact {exact}");
        assert!(
            (mean - exact).abs() < 2e-3,
            "sphere at {centre}: jittered {mean}, exact share {exact}"
        );
    }
}

/// The shading variant's weights: each point of the light counts by its own
/// contribution to the sample, cos θ_sample cos θ_light / d². Two points of a lamp at
/// height 2, a plate at height 1 over 0.2 < x < 0.8 hiding the right one from part of
/// the floor: there the visibility is w_left / (w_left + w_right), the weights
/// written out here.
#[test]
fn each_point_counts_by_its_own_contribution() {
    let text = support::camera([0.0, 4.0, 3.0], [0.3, 0.0, 0.0], 50.0, 64, 64)
        + "[materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\n[materials.lamp]\nemission = [1.0, 1.0, 1.0]\n\
        [[objects]]\nshape = \"polygon\"\nname = \"floor\"\nmaterial = \"grey\"\nvertices = [[-3.0, 0.0, -3.0], [-3.0, 0.0, 3.0], [3.0, 0.0, 3.0], [3.0, 0.0, -3.0]]\n\
        [[objects]]\nshape = \"polygon\"\nname = \"plate\"\nmaterial = \"grey\"\nvertices = [[0.2, 1.0, -3.0], [0.8, 1.0, -3.0], [0.8, 1.0, 3.0], [0.2, 1.0, 3.0]]\n\
        [[objects]]\nshape = \"polygon\"\nname = \"lamp\"\nmaterial = \"lamp\"\nvertices = [[-1.0, 2.0, -0.5], [1.0, 2.0, -0.5], [1.0, 2.0, 0.5], [-1.0, 2.0, 0.5]]\n";
    let scene = support::scene_from_text(&text, &[]);
    let (view, surface) = visible_surface(&scene);
    let points = [DVec3::new(-0.5, 2.0, 0.0), DVec3::new(0.5, 2.0, 0.0)];
    let soft = SoftShadowVolumes::at_points(&scene, &scene.lights[0], &points);
    let band = soft.frame(&scene, &view).band(&surface);
    let LightVisibility::Fraction(f) = &band.visibility else {
        panic!("a fraction");
    };
    // Whether the plate lies on the segment from x to p (it is the plane y = 1).
    let hidden = |x: DVec3, p: DVec3| {
        let hit = x + (p - x) * ((1.0 - x.y) / (p.y - x.y));
        (0.2..=0.8).contains(&hit.x) && hit.z.abs() <= 3.0
    };
    let weight = |x: DVec3, p: DVec3| {
        let d = p - x;
        d.y * d.y / d.length_squared().powi(2)
    };
    let mut checked = 0;
    for (k, s) in surface.samples.iter().enumerate() {
        if s.is_empty() || s.position.y.abs() > 1e-9 {
            continue; // the floor's samples only
        }
        let x = s.position;
        let (left, right) = (hidden(x, points[0]), hidden(x, points[1]));
        if left || !right {
            continue;
        }
        let expected = weight(x, points[0]) / (weight(x, points[0]) + weight(x, points[1]));
        assert!(
            (f[k] as f64 - expected).abs() < 1e-5,
            "at {x}: {}, expected {expected}",
            f[k]
        );
        checked += 1;
    }
    assert!(
        checked > 50,
        "{checked} samples with the right point hidden"
    );
}
