//! Methods checked against independent methods and exact values.

use crate::support;

use glam::{DVec3, Vec3};
use lumiere::geometry::lambert_contour::projected_solid_angle;
use lumiere::raster::{NO_POLYGON, ScreenPolygon, rasterize, zbuffer};
use lumiere::render::visible_surface;
use lumiere::scene::{Light, Scene};
use lumiere::{load_scene, render};
use proptest::prelude::*;
use std::f64::consts::PI;
use support::{origin_view, screen_polygon};

fn triangle() -> impl Strategy<Value = [DVec3; 3]> {
    let point =
        (-3.0..3.0f64, -3.0..3.0f64, -9.0..-2.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z));
    [point.clone(), point.clone(), point]
}

/// Distance from (x, y) to the nearest edge of a screen polygon.
fn distance_to_edges(p: &ScreenPolygon, x: f64, y: f64) -> f64 {
    let n = p.vertices.len();
    (0..n)
        .map(|i| {
            let (a, b) = (&p.vertices[i], &p.vertices[(i + 1) % n]);
            let (dx, dy) = (b.x - a.x, b.y - a.y);
            let t = (((x - a.x) * dx + (y - a.y) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
            ((a.x + t * dx - x).powi(2) + (a.y + t * dy - y).powi(2)).sqrt()
        })
        .fold(f64::INFINITY, f64::min)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// Watkins' span decisions equal a per-sample z-buffer on random, overlapping and
    /// interpenetrating triangles, sample for sample. The two compute edge crossings
    /// differently (fixed-point steps, direct evaluation), so a sample may differ only
    /// when its centre lies within 1e-6 pixel of an edge.
    #[test]
    fn scanline_equals_a_zbuffer(triangles in prop::collection::vec(triangle(), 1..14)) {
        let view = origin_view(72, 56);
        let polygons: Vec<ScreenPolygon> = triangles
            .iter()
            .enumerate()
            .filter_map(|(k, t)| screen_polygon(&view, k as u32, t))
            .collect();
        let sweep = rasterize(&polygons, view.width, view.height);
        let reference = zbuffer::visible_ids(&polygons, view.width, view.height);
        for (k, (s, &id)) in sweep.samples.iter().zip(&reference).enumerate() {
            if s.polygon == id {
                continue;
            }
            let (x, y) = ((k as u32 % view.width) as f64 + 0.5, (k as u32 / view.width) as f64 + 0.5);
            let near_edge = [s.polygon, id]
                .iter()
                .filter(|&&p| p != NO_POLYGON)
                .map(|&p| polygons.iter().find(|q| q.id == p).unwrap())
                .any(|q| distance_to_edges(q, x, y) < 1e-6);
            prop_assert!(near_edge, "sample ({x}, {y}): sweep {} but z-buffer {}", s.polygon, id);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Scan-out with invisible surfaces in the edge table: at every sample the piece
    /// shows the polygon the frame's own sweep shows, and lists exactly the invisible
    /// triangles whose footprint covers the sample.
    #[test]
    fn scan_out_shows_what_the_sweep_shows(
        visible in prop::collection::vec(triangle(), 1..10),
        invisible in prop::collection::vec(triangle(), 0..8),
    ) {
        use lumiere::raster::{EdgeTable, covered_samples, scan_out};
        let view = origin_view(64, 48);
        let (w, h) = (view.width, view.height);
        let shown: Vec<ScreenPolygon> = visible
            .iter()
            .enumerate()
            .filter_map(|(k, t)| screen_polygon(&view, k as u32, t))
            .collect();
        let hidden: Vec<ScreenPolygon> = invisible
            .iter()
            .enumerate()
            .filter_map(|(k, t)| screen_polygon(&view, 100 + k as u32, t))
            .collect();
        let sweep = rasterize(&shown, w, h);
        // The invisible triangles covering each sample, as a bit set.
        let mut covering = vec![0u32; (w * h) as usize];
        for (k, p) in hidden.iter().enumerate() {
            for (x, y) in covered_samples(p, w, h) {
                covering[(y * w + x) as usize] |= 1 << k;
            }
        }
        let mut all = shown.clone();
        all.extend(hidden);
        let table = EdgeTable::build(&all, h);
        let found = scan_out(&all, shown.len(), &table, w, 0..h, None, |_| (), |_, row, out| {
            for piece in row.pieces {
                let bits = row
                    .invisible(piece)
                    .iter()
                    .fold(0u32, |bits, &i| bits | 1 << (i as usize - shown.len()));
                for x in piece.first..=piece.last {
                    out[x as usize] = Some((all[piece.visible as usize].id, bits));
                }
            }
        });
        for (k, s) in sweep.samples.iter().enumerate() {
            let expected = (!s.is_empty()).then_some((s.polygon, covering[k]));
            prop_assert_eq!(found[k], expected, "sample {}", k);
        }
    }
}

fn cornell(id: &str, size: u32) -> Scene {
    load_scene(
        id,
        &[
            format!("camera.width={size}"),
            format!("camera.height={size}"),
        ],
    )
    .unwrap()
}

/// Perspective-correct interpolation: every sample's world position is where the
/// ray through the sample centre meets the visible polygon's plane, and its depth is
/// the distance along the view axis.
#[test]
fn interpolated_positions_are_exact_ray_plane_intersections() {
    let scene = cornell("cornell-box", 96);
    let (view, surface) = visible_surface(&scene);
    let mut checked = 0;
    for (k, s) in surface.samples.iter().enumerate() {
        if s.is_empty() {
            continue;
        }
        let polygon = &scene.polygons[s.polygon as usize];
        let (x, y) = (
            (k as u32 % view.width) as f64 + 0.5,
            (k as u32 / view.width) as f64 + 0.5,
        );
        let d = view.ray(x, y);
        let origin = polygon.vertices[0].position;
        let t = (origin - view.eye).dot(polygon.normal) / d.dot(polygon.normal);
        let exact = view.eye + d * t;
        assert!(
            (s.position - exact).length() < 1e-7 * exact.length(),
            "sample {k}: {} vs exact {}",
            s.position,
            exact
        );
        let depth = (exact - view.eye).dot(view.forward);
        assert!((s.depth - depth).abs() < 1e-9 * depth);
        checked += 1;
    }
    assert!(checked > 96 * 96 * 9 / 10);
}

/// E/L by the midpoint rule over an n × n grid of the light quad (an independent
/// method for the irradiance from a Lambertian polygon).
fn quadrature(p: DVec3, n_p: DVec3, quad: &[DVec3], normal: DVec3, n: usize) -> f64 {
    let (o, u, v) = (quad[0], quad[1] - quad[0], quad[3] - quad[0]);
    let d_area = u.cross(v).length() / (n * n) as f64;
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n {
            let q = o + u * ((i as f64 + 0.5) / n as f64) + v * ((j as f64 + 0.5) / n as f64);
            let r = q - p;
            let r2 = r.length_squared();
            let (cos_p, cos_q) = (n_p.dot(r) / r2.sqrt(), -normal.dot(r) / r2.sqrt());
            if cos_p > 0.0 && cos_q > 0.0 {
                sum += cos_p * cos_q / r2 * d_area;
            }
        }
    }
    sum
}

fn area_light(scene: &Scene) -> (Vec<DVec3>, DVec3, Vec3) {
    scene
        .lights
        .iter()
        .find_map(|l| match l {
            Light::Polygon(a) => Some((a.vertices.clone(), a.normal, a.radiance)),
            _ => None,
        })
        .unwrap()
}

/// Lambert's contour formula against quadrature at points of the Cornell box, and
/// against the published value under the lamp (0.0446485 per unit radiance).
#[test]
fn polygon_irradiance_matches_quadrature_and_the_published_value() {
    let scene = cornell("cornell-box", 8);
    let (quad, normal, _) = area_light(&scene);
    let under_lamp = projected_solid_angle(DVec3::new(278.0, 0.0, 279.5), DVec3::Y, &quad);
    assert!((under_lamp - 0.0446485).abs() < 1e-7, "{under_lamp}");
    let points = [
        (DVec3::new(278.0, 0.0, 279.5), DVec3::Y),
        (DVec3::new(100.0, 0.0, 500.0), DVec3::Y),
        (DVec3::new(300.0, 300.0, 559.2), DVec3::NEG_Z),
        (DVec3::new(0.0, 400.0, 100.0), DVec3::X),
        (DVec3::new(200.0, 165.0, 150.0), DVec3::Y),
        (DVec3::new(278.0, 540.0, 280.0), DVec3::Y), // just under the light, grazing
    ];
    for (p, n) in points {
        let exact = projected_solid_angle(p, n, &quad);
        let numeric = quadrature(p, n, &quad, normal, 800);
        assert!(
            (exact - numeric).abs() <= 2e-5 * exact.max(1e-3),
            "at {p}: {exact} vs {numeric}"
        );
    }
}

/// Each floor pixel of the point-lit box has radiance ρ/π · I cos θ / r², computed
/// here by hand; each visible pixel of the light quad shows exactly its radiance.
#[test]
fn pixel_radiance_is_the_light_model_exactly() {
    let scene = cornell("cornell-box-point", 64);
    let (_, surface) = visible_surface(&scene);
    let image = render(&scene).unwrap();
    let Light::Point(lamp) = &scene.lights[0] else {
        panic!("a point light")
    };
    let floor = scene
        .objects
        .iter()
        .position(|o| o.name == "cornell/floor")
        .unwrap();
    let mut checked = 0;
    for (s, pixel) in surface.samples.iter().zip(&image.pixels) {
        if s.is_empty() || scene.polygons[s.polygon as usize].object != floor {
            continue;
        }
        let d = lamp.position - s.position;
        let cos = d.y / d.length();
        let expected = scene.material_of(s.polygon as usize).diffuse / std::f32::consts::PI
            * lamp.intensity
            * (cos / d.length_squared()) as f32;
        assert!((*pixel - expected).abs().max_element() <= 1e-5 * expected.max_element());
        checked += 1;
    }
    assert!(checked > 300, "{checked} floor pixels");

    let scene = cornell("cornell-box", 64);
    let (_, surface) = visible_surface(&scene);
    let image = render(&scene).unwrap();
    let (_, _, radiance) = area_light(&scene);
    let lit: Vec<Vec3> = surface
        .samples
        .iter()
        .zip(&image.pixels)
        .filter(|(s, _)| {
            !s.is_empty() && scene.material_of(s.polygon as usize).emission != Vec3::ZERO
        })
        .map(|(_, p)| *p)
        .collect();
    assert!(!lit.is_empty());
    assert!(lit.iter().all(|p| *p == radiance));
}

/// A glossy floor under a point light, the eye near the mirror direction: each pixel
/// has radiance (ρ/π + k_s (e + 2)/(2π) cosᵉ α) · I cos θ / r² (Phong's lobe,
/// energy-normalised), computed here by hand with α measured from the eye's mirror
/// direction (the light model measures it from the light's).
#[test]
fn specular_pixel_radiance_is_the_normalised_phong_lobe() {
    let (rho, k_s, e, intensity) = (0.3f64, 0.6f64, 20.0f64, 10.0f64);
    let light = DVec3::new(0.3, 2.0, -2.0);
    let scene = support::scene_from_text(
        &format!(
            r#"{}
            [render]
            shading = "phong"
            [shadows]
            method = "none"
            [materials.gloss]
            diffuse = [{rho}, {rho}, {rho}]
            specular = [{k_s}, {k_s}, {k_s}]
            exponent = {e}
            [[lights]]
            type = "point"
            position = [{}, {}, {}]
            intensity = [{intensity}, {intensity}, {intensity}]
            [[objects]]
            shape = "quad"
            material = "gloss"
            transform = [{{ scale = [8.0, 1.0, 8.0] }}]
            "#,
            support::camera([0.0, 1.5, 2.5], [0.0, 0.0, -0.5], 50.0, 64, 64),
            light.x,
            light.y,
            light.z
        ),
        &[],
    );
    let (view, surface) = visible_surface(&scene);
    let image = render(&scene).unwrap();
    // Also kept: the pixel nearest the mirror direction (cos α there, and the two
    // terms) and the largest relative error.
    let (mut checked, mut closest, mut worst) = (0, (0.0f64, 0.0, 0.0), 0.0f64);
    for (s, pixel) in surface.samples.iter().zip(&image.pixels) {
        if s.is_empty() {
            continue;
        }
        let n = DVec3::Y;
        let to_light = light - s.position;
        let r2 = to_light.length_squared();
        let l = to_light / r2.sqrt();
        let v = (view.eye - s.position).normalize();
        let eye_mirror = 2.0 * n.dot(v) * n - v;
        let cos_alpha = eye_mirror.dot(l).max(0.0);
        let diffuse = rho / PI;
        let specular = k_s * (e + 2.0) / (2.0 * PI) * cos_alpha.powf(e);
        let expected = (diffuse + specular) * intensity * n.dot(l) / r2;
        let error = (pixel.x as f64 - expected).abs() / expected;
        assert!(
            error <= 1e-5,
            "{pixel} vs {expected} at {} (cos α = {cos_alpha})",
            s.position
        );
        worst = worst.max(error);
        if cos_alpha > closest.0 {
            closest = (cos_alpha, specular, diffuse);
        }
        checked += 1;
    }
    assert!(checked > 2000, "{checked} floor pixels");
    // The highlight is in view, and there the lobe outweighs the diffuse term.
    let (cos_alpha, specular, diffuse) = closest;
    println!(
        "{checked} floor pixels, worst relative error {worst:.1e}; nearest the mirror \
         direction cos α = {cos_alpha:.6}, specular {specular:.4} vs diffuse {diffuse:.4}"
    );
    assert!(
        cos_alpha > 0.9999,
        "no pixel near the mirror direction: {cos_alpha}"
    );
    assert!(specular > 20.0 * diffuse, "{specular} vs {diffuse}");
}

/// Pixels lit by the quad light: radiance ρ/π · L · Φ with Φ by quadrature (the
/// unoccluded light: the entry's shadows off).
#[test]
fn area_lit_pixels_match_quadrature() {
    let mut scene = cornell("cornell-box", 32);
    scene.shadows.method = lumiere::settings::ShadowMethod::None;
    let (_, surface) = visible_surface(&scene);
    let image = render(&scene).unwrap();
    let (quad, normal, radiance) = area_light(&scene);
    let mut checked = 0;
    for (s, pixel) in surface.samples.iter().zip(&image.pixels).step_by(7) {
        if s.is_empty() || scene.material_of(s.polygon as usize).emission != Vec3::ZERO {
            continue;
        }
        let polygon = &scene.polygons[s.polygon as usize];
        let to_eye = scene.camera.eye - s.position;
        let n = if polygon.normal.dot(to_eye) > 0.0 {
            polygon.normal
        } else {
            -polygon.normal
        };
        let behind_light = (s.position - quad[0]).dot(normal) <= 0.0;
        let phi = if behind_light {
            0.0
        } else {
            quadrature(s.position, n, &quad, normal, 300)
        };
        let expected =
            scene.material_of(s.polygon as usize).diffuse / PI as f32 * radiance * phi as f32;
        assert!(
            (*pixel - expected).abs().max_element() <= 1e-4 * expected.max_element().max(1e-3),
            "{pixel} vs {expected} at {}",
            s.position
        );
        checked += 1;
    }
    assert!(checked > 100, "{checked}");
}

/// A square occluder of side s at height h under a point light at height H over its
/// centre casts a square shadow of side s·H/(H − h) on the ground (similar
/// triangles). Ray casting decides at the sample's own point, so every ground sample
/// is classified exactly, up to 1e-6 of the border.
#[test]
fn ray_cast_shadow_of_a_square_is_the_similar_triangle_square() {
    let (s, h, light_height) = (2.0, 1.0, 4.0);
    let text = format!(
        "{}[shadows]\nmethod = \"ray-cast\"\n[materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\n\
         [[lights]]\ntype = \"point\"\nposition = [0.0, {light_height}, 0.0]\nintensity = [10.0, 10.0, 10.0]\n\
         [[objects]]\nshape = \"quad\"\nname = \"ground\"\nmaterial = \"grey\"\ntransform = [{{ scale = 8.0 }}]\n\
         [[objects]]\nshape = \"quad\"\nname = \"occluder\"\nmaterial = \"grey\"\n\
         transform = [{{ scale = {s} }}, {{ translate = [0.0, {h}, 0.0] }}]\n",
        support::camera([0.0, 12.0, 0.001], [0.0, 0.0, 0.0], 40.0, 160, 160)
    );
    let dir = std::env::temp_dir().join(format!("lumiere-square-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("square.toml");
    std::fs::write(&path, text).unwrap();
    let scene = load_scene(path.to_str().unwrap(), &[]).unwrap();
    let (view, surface) = visible_surface(&scene);
    let visibility =
        lumiere::shadow::compute(&scene, &view, &surface, scene.shadows.method).unwrap();
    let half_shadow = 0.5 * s * light_height / (light_height - h);
    let ground = scene
        .objects
        .iter()
        .position(|o| o.name == "ground")
        .unwrap();
    let (mut checked, mut shadowed) = (0, 0);
    for (k, sample) in surface.samples.iter().enumerate() {
        if sample.is_empty() || scene.polygons[sample.polygon as usize].object != ground {
            continue;
        }
        let inside = sample.position.x.abs().max(sample.position.z.abs());
        if (inside - half_shadow).abs() <= 1e-6 {
            continue;
        }
        let expected = if inside < half_shadow { 0.0 } else { 1.0 };
        assert_eq!(
            visibility.fraction(0, k),
            expected,
            "at {}",
            sample.position
        );
        checked += 1;
        shadowed += (expected == 0.0) as usize;
    }
    std::fs::remove_dir_all(&dir).ok();
    assert!(
        checked > 10_000 && shadowed > 500,
        "{checked} checked, {shadowed} shadowed"
    );
}
