//! Ray casting under an extended light (Cook, Porter & Carpenter 1984) converges to
//! the exact penumbra as the light samples grow: a square light over a square
//! occluder, both parallel to the floor, whose visible part of the light is known
//! exactly at every floor point (the light minus the occluder projected from the
//! point onto the light's plane, a rectangle), and whose irradiance is Lambert's
//! contour formula on it.

use glam::DVec3;
use lumiere::geometry::lambert_contour::projected_solid_angle;
use lumiere::render::visible_surface;
use lumiere::settings::ShadowMethod;

fn scene_text() -> String {
    crate::support::camera([0.3, 1.2, 5.0], [0.0, 0.0, 0.0], 30.0, 64, 64)
        + r#"[materials.grey]
diffuse = [0.5, 0.5, 0.5]

[[lights]]
type = "polygon"
vertices = [[-0.5, 2.0, -0.5], [0.5, 2.0, -0.5], [0.5, 2.0, 0.5], [-0.5, 2.0, 0.5]]
radiance = [1.0, 1.0, 1.0]

[[objects]]
shape = "quad"
name = "floor"
material = "grey"
transform = [{ scale = 6.0 }]

[[objects]]
shape = "quad"
name = "occluder"
material = "grey"
transform = [{ scale = 0.6 }, { translate = [0.0, 1.0, 0.0] }]
"#
}

const LIGHT_HALF: f64 = 0.5;
const OCCLUDER_HALF: f64 = 0.3;
const LIGHT_Y: f64 = 2.0;
const OCCLUDER_Y: f64 = 1.0;

fn square(x0: f64, x1: f64, z0: f64, z1: f64) -> Vec<DVec3> {
    vec![
        DVec3::new(x0, LIGHT_Y, z0),
        DVec3::new(x1, LIGHT_Y, z0),
        DVec3::new(x1, LIGHT_Y, z1),
        DVec3::new(x0, LIGHT_Y, z1),
    ]
}

fn light() -> Vec<DVec3> {
    square(-LIGHT_HALF, LIGHT_HALF, -LIGHT_HALF, LIGHT_HALF)
}

/// The part of the light the occluder hides from floor point `p`: the occluder
/// seen from p on the light's plane (scaled about p), cut to the light.
fn hidden(p: DVec3) -> Option<Vec<DVec3>> {
    let k = (LIGHT_Y - p.y) / (OCCLUDER_Y - p.y);
    let project = |o: f64, q: f64| q + (o - q) * k;
    let (x0, x1) = (
        project(-OCCLUDER_HALF, p.x).max(-LIGHT_HALF),
        project(OCCLUDER_HALF, p.x).min(LIGHT_HALF),
    );
    let (z0, z1) = (
        project(-OCCLUDER_HALF, p.z).max(-LIGHT_HALF),
        project(OCCLUDER_HALF, p.z).min(LIGHT_HALF),
    );
    (x0 < x1 && z0 < z1).then(|| square(x0, x1, z0, z1))
}

/// The exact share of the light's irradiance reaching floor point `p`.
fn exact_share(p: DVec3) -> f64 {
    let n = DVec3::Y;
    let whole = projected_solid_angle(p, n, &light());
    let hidden = hidden(p).map_or(0.0, |h| projected_solid_angle(p, n, &h));
    (whole - hidden) / whole
}

/// The scene with `samples` × `samples` light samples, and its floor's object index.
fn soft_scene(samples: u32) -> (lumiere::Scene, usize) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("soft.toml");
    std::fs::write(&path, scene_text()).unwrap();
    let sets = [format!("shadows.light_samples={samples}")];
    let scene = lumiere::load_scene(path.to_str().unwrap(), &sets).unwrap();
    let floor = scene
        .objects
        .iter()
        .position(|o| o.name == "floor")
        .unwrap();
    (scene, floor)
}

/// RMS error of the ray-cast share against the exact one over the penumbra, and
/// the largest error in the umbra and in full light.
fn errors(samples: u32) -> (f64, f64, usize) {
    let (scene, floor) = soft_scene(samples);
    let (view, surface) = visible_surface(&scene);
    let visibility =
        lumiere::shadow::compute(&scene, &view, &surface, ShadowMethod::RayCast).unwrap();
    let (mut sum, mut count, mut outside) = (0.0, 0, 0.0f64);
    for (k, s) in surface.samples.iter().enumerate() {
        if s.is_empty() || scene.polygons[s.polygon as usize].object != floor {
            continue;
        }
        let exact = exact_share(s.position);
        let found = visibility.fraction(0, k) as f64;
        if !(1e-9..=1.0 - 1e-9).contains(&exact) {
            outside = outside.max((found - exact).abs());
        } else {
            sum += (found - exact).powi(2);
            count += 1;
        }
    }
    ((sum / count as f64).sqrt(), outside, count)
}

#[test]
fn the_sampled_penumbra_converges_to_the_exact_one() {
    let mut previous = f64::INFINITY;
    let mut table = Vec::new();
    for n in [1, 2, 4, 8, 16] {
        let (rms, outside, count) = errors(n);
        table.push((n, rms));
        assert!(count > 300, "{count} penumbra samples");
        // Umbra and full light: every sample ray agrees.
        assert!(outside < 1e-6, "n = {n}: {outside} outside the penumbra");
        assert!(
            rms < previous,
            "n = {n}: {rms} after {previous} ({table:?})"
        );
        previous = rms;
    }
    let (_, at_16) = table[4];
    assert!(at_16 < 0.01, "{table:?}");
    // Stratified sampling: the error falls faster than 1/N (N × N samples: 1/N²
    // would be Monte Carlo's 1/sqrt(samples)).
    let (_, at_2) = table[1];
    assert!(at_16 < at_2 / 8.0, "{table:?}");
}

/// An exact method's answer, the visible part of the emitter (the light with the
/// occluder's projection as a hole), gives shading the exact irradiance: the
/// unshadowed radiance times the visible share of Lambert's contour integral.
#[test]
fn the_visible_part_of_an_emitter_shades_exactly() {
    use lumiere::raster::{LightVisibility, Visibility, VisiblePart};
    use lumiere::shading::FrameShading;
    let (scene, floor) = soft_scene(4);
    let (view, surface) = visible_surface(&scene);
    let on_floor = |k: usize| {
        let s = &surface.samples[k];
        !s.is_empty() && scene.polygons[s.polygon as usize].object == floor
    };
    let parts = (0..surface.samples.len())
        .map(|k| {
            if !on_floor(k) {
                return None;
            }
            let p = surface.samples[k].position;
            let mut contours = vec![(light(), 1.0)];
            contours.extend(hidden(p).map(|h| (h, -1.0)));
            Some(VisiblePart { contours })
        })
        .collect();
    let exact = Visibility {
        per_light: vec![Some(LightVisibility::Emitter(parts))],
    };
    let shading = FrameShading::new(&scene, &view, vec![true]);
    let shadowed = shading.shade_band(&surface, &exact, &[]);
    let unshadowed = shading.shade_band(&surface, &Visibility::none(), &[]);
    let mut penumbra = 0;
    for k in (0..surface.samples.len()).filter(|&k| on_floor(k)) {
        let share = exact_share(surface.samples[k].position) as f32;
        let expected = unshadowed[k] * share;
        assert!(
            (shadowed[k] - expected).abs().max_element() <= 1e-5 * unshadowed[k].max_element(),
            "sample {k}: {} against {expected}",
            shadowed[k]
        );
        penumbra += (share > 0.0 && share < 1.0) as usize;
    }
    assert!(penumbra > 300, "{penumbra}");
}

/// Soft shadow volumes under a polygon light: a point that no point of the light
/// shines on (a ceiling above a lamp that emits downwards: every point's weight is
/// zero) gets nothing from it, not the unweighted fraction of points it can see
/// (which called it fully lit).
#[test]
fn a_point_the_light_cannot_shine_on_gets_nothing() {
    use lumiere::image_io::BufferData;
    use lumiere::render::Renderer;
    let text = crate::support::camera([0.0, 1.0, 4.0], [0.0, 2.5, 0.0], 60.0, 24, 24)
        + "[shadows]\nmethod = \"soft-shadow-volumes\"\nlight_points = 4\n\
        [materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\n[materials.lamp]\nemission = [5.0, 5.0, 5.0]\n\
        [[objects]]\nshape = \"polygon\"\nname = \"floor\"\nmaterial = \"grey\"\nvertices = [[-3.0, 0.0, -3.0], [-3.0, 0.0, 3.0], [3.0, 0.0, 3.0], [3.0, 0.0, -3.0]]\n\
        [[objects]]\nshape = \"polygon\"\nname = \"ceiling\"\nmaterial = \"grey\"\nvertices = [[-3.0, 3.0, -3.0], [3.0, 3.0, -3.0], [3.0, 3.0, 3.0], [-3.0, 3.0, 3.0]]\n\
        [[objects]]\nshape = \"polygon\"\nname = \"lamp\"\nmaterial = \"lamp\"\nvertices = [[-0.3, 2.0, -0.3], [0.3, 2.0, -0.3], [0.3, 2.0, 0.3], [-0.3, 2.0, 0.3]]\n";
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("s.toml");
    std::fs::write(&path, text).unwrap();
    let scene = lumiere::load_scene(path.to_str().unwrap(), &[]).unwrap();
    let ceiling = scene
        .polygons
        .iter()
        .position(|p| scene.objects[p.object].name == "ceiling")
        .unwrap() as u32;
    let floor = scene
        .polygons
        .iter()
        .position(|p| scene.objects[p.object].name == "floor")
        .unwrap() as u32;
    let wanted = ["polygon".to_string(), "visibility-0".to_string()];
    let frame = Renderer::new(scene).render_with_buffers(&wanted).unwrap();
    let BufferData::Ids(ids) = &frame.buffer("polygon").unwrap().data else {
        panic!("ids")
    };
    let BufferData::Values { data, channels } = &frame.buffer("visibility-0").unwrap().data else {
        panic!("values")
    };
    let at = |polygon: u32| -> Vec<f32> {
        ids.iter()
            .enumerate()
            .filter(|&(_, &id)| id == polygon)
            .map(|(k, _)| data[k * channels])
            .collect()
    };
    let (above, below) = (at(ceiling), at(floor));
    assert!(!above.is_empty() && !below.is_empty());
    assert!(above.iter().all(|&v| v == 0.0), "ceiling: {above:?}");
    // The floor below, in the open, sees the whole light.
    assert!(below.iter().all(|&v| v == 1.0), "floor: {below:?}");
}
