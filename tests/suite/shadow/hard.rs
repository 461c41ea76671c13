//! Hard-shadow methods against Appel's ray casting, the exact reference: the same
//! visibility at every sample except on shadow boundaries (exact methods), or
//! converging to it as resolution grows (shadow maps).

use lumiere::Scene;
use lumiere::load_scene;
use lumiere::raster::VisibleSurface;
use lumiere::render::visible_surface;
use lumiere::settings::ShadowMethod;

/// The first light's visibility per sample of entry `id` at `w × h`, with `sets`.
fn mask(
    id: &str,
    w: u32,
    h: u32,
    method: ShadowMethod,
    sets: &[&str],
) -> (Scene, VisibleSurface, Vec<f32>) {
    let mut all = vec![format!("camera.width={w}"), format!("camera.height={h}")];
    all.extend(sets.iter().map(|s| s.to_string()));
    let scene = load_scene(id, &all).unwrap();
    let (view, surface) = visible_surface(&scene);
    let visibility = lumiere::shadow::compute(&scene, &view, &surface, method).unwrap();
    let values = (0..surface.samples.len())
        .map(|k| visibility.fraction(0, k))
        .collect();
    (scene, surface, values)
}

/// Share of the counted samples where `a` and `b` differ.
fn disagreement(a: &[f32], b: &[f32], counted: impl Fn(usize) -> bool) -> f64 {
    let (mut n, mut differ) = (0usize, 0usize);
    for k in (0..a.len()).filter(|&k| counted(k)) {
        n += 1;
        differ += (a[k] != b[k]) as usize;
    }
    differ as f64 / n as f64
}

const CURVED: &str = "ray-cast-shadows-curved";

/// Williams's maps converge to the exact shadows as the map resolution grows, and at
/// 2048 texels without filtering agree on at least 99% of the samples.
#[test]
fn shadow_maps_converge_to_ray_casting() {
    let (_, _, exact) = mask(CURVED, 256, 192, ShadowMethod::RayCast, &[]);
    let shares: Vec<f64> = [256, 512, 1024, 2048]
        .iter()
        .map(|r| {
            let set = format!("shadows.map_resolution={r}");
            let (_, _, map) = mask(CURVED, 256, 192, ShadowMethod::ShadowMap, &[&set]);
            disagreement(&map, &exact, |_| true)
        })
        .collect();
    assert!(
        shares.windows(2).all(|w| w[1] <= w[0]),
        "not converging: {shares:?}"
    );
    assert!(
        shares[0] > 0.0,
        "a coarse map should differ somewhere: {shares:?}"
    );
    assert!(
        shares[3] <= 0.01,
        "2048 texels: {:.4}% differ",
        100.0 * shares[3]
    );
}

/// On the point-lit Cornell box the lamp hangs 0.1 mm under the fixture and 0.2 mm
/// under the ceiling: seen from the lamp, ceiling and fixture fall in the same texel
/// row at the horizon, which no map resolution or bias separates (the method's
/// limit, shown by the `shadow-map` entry). Everywhere else a 2048-texel map agrees
/// with ray casting on at least 99% of the samples.
#[test]
fn shadow_maps_agree_on_the_cornell_box_away_from_the_grazed_ceiling() {
    let id = "cornell-box-point";
    let (scene, surface, exact) = mask(id, 256, 256, ShadowMethod::RayCast, &[]);
    let (_, _, map) = mask(
        id,
        256,
        256,
        ShadowMethod::ShadowMap,
        &["shadows.map_resolution=2048"],
    );
    let grazed: Vec<usize> = ["cornell/ceiling", "cornell/light"]
        .iter()
        .map(|name| scene.objects.iter().position(|o| o.name == *name).unwrap())
        .collect();
    let counted = |k: usize| {
        let s = &surface.samples[k];
        !s.is_empty() && !grazed.contains(&scene.polygons[s.polygon as usize].object)
    };
    let share = disagreement(&map, &exact, counted);
    assert!(share <= 0.01, "{:.4}% differ", 100.0 * share);
}

/// An exact method gives ray casting's visibility at every sample (as measured on
/// both scenes: not one sample differs).
fn assert_exact(id: &str, w: u32, h: u32, method: ShadowMethod) {
    let (_, _, exact) = mask(id, w, h, ShadowMethod::RayCast, &[]);
    let (_, _, other) = mask(id, w, h, method, &[]);
    let differing: Vec<(usize, usize)> = (0..exact.len())
        .filter(|&k| exact[k] != other[k])
        .map(|k| (k % w as usize, k / w as usize))
        .collect();
    assert!(
        differing.is_empty(),
        "{id} with {method:?}: {} samples differ from ray casting, first at {:?}",
        differing.len(),
        &differing[..differing.len().min(5)]
    );
    assert!(exact.contains(&0.0) && exact.contains(&1.0));
}

#[test]
fn shadow_volumes_agree_with_ray_casting() {
    assert_exact("cornell-box-point", 256, 256, ShadowMethod::ShadowVolumes);
    assert_exact(CURVED, 256, 192, ShadowMethod::ShadowVolumes);
}

#[test]
fn stencil_shadow_volumes_agree_with_ray_casting() {
    assert_exact(
        "cornell-box-point",
        256,
        256,
        ShadowMethod::StencilShadowVolumes,
    );
    assert_exact(CURVED, 256, 192, ShadowMethod::StencilShadowVolumes);
}

/// Crow's counting inside the scan-line pass and Heidmann's count buffer after it
/// find the same count at every sample, on both scenes and with the eye inside a
/// volume (the count then starts above zero).
#[test]
fn crow_and_the_count_buffer_count_alike() {
    let cases: [(&str, &[&str]); 3] = [
        ("cornell-box-point", &[]),
        (CURVED, &[]),
        // The eye in the tall block's shadow (the line from it to the light crosses
        // the block's top), looking across the floor.
        (
            "cornell-box-point",
            &[
                "camera.eye=[480.0, 60.0, 440.0]",
                "camera.look_at=[150.0, 100.0, 100.0]",
            ],
        ),
    ];
    for (id, sets) in cases {
        let mut all = vec![
            "camera.width=160".to_string(),
            "camera.height=120".to_string(),
        ];
        all.extend(sets.iter().map(|s| s.to_string()));
        let scene = load_scene(id, &all).unwrap();
        let (view, surface) = visible_surface(&scene);
        let count = |method| {
            let settings = lumiere::settings::ShadowSettings {
                method,
                ..scene.shadows.clone()
            };
            lumiere::shadow::light_band(&scene, &view, &surface, &settings, 0)
                .unwrap()
                .unwrap()
                .counts
                .unwrap()
        };
        let light = scene.lights[0].position().unwrap();
        let start = lumiere::shadow::shadow_volumes::eye_count_from(
            &scene,
            view.eye,
            lumiere::shadow::shadow_volumes::Source::Point(light),
        );
        assert_eq!(
            start > 0,
            !sets.is_empty(),
            "{id} {sets:?}: eye count {start}"
        );
        let crow = count(ShadowMethod::ShadowVolumes);
        let stencil = count(ShadowMethod::StencilShadowVolumes);
        let differing = (0..crow.len())
            .filter(|&k| !surface.samples[k].is_empty() && crow[k] != stencil[k])
            .count();
        assert_eq!(differing, 0, "{id} {sets:?}");
        assert!(
            crow.iter().any(|&c| c > 0),
            "{id} {sets:?}: no shadow counted"
        );
    }
}

/// The limit shown by `shadow-volumes-open-mesh`: on an open mesh the volumes miss
/// shadow that ray casting finds.
#[test]
fn shadow_volumes_leak_on_an_open_mesh() {
    let id = "shadow-volumes-open-mesh";
    let (_, _, exact) = mask(id, 128, 96, ShadowMethod::RayCast, &[]);
    let (_, _, volumes) = mask(id, 128, 96, ShadowMethod::ShadowVolumes, &[]);
    let leaked = exact
        .iter()
        .zip(&volumes)
        .filter(|(e, v)| **e == 0.0 && **v == 1.0)
        .count();
    assert!(leaked > 200, "only {leaked} samples leak");
    let scene = load_scene(id, &[]).unwrap();
    assert_eq!(
        lumiere::shadow::shadow_volumes::open_objects(&scene),
        ["tube"]
    );
}

/// Crow's volumes need closed meshes: every object of the curved scene is one (the
/// generated spheres and cylinder share their seams and poles bit for bit, and the
/// shipped teapot is closed where Newell's patches are open).
#[test]
fn the_curved_scene_is_made_of_closed_meshes() {
    let scene = load_scene(CURVED, &[]).unwrap();
    assert!(scene.objects.iter().any(|o| o.name.starts_with("teapot")));
    let open = lumiere::shadow::shadow_volumes::open_objects(&scene);
    assert!(open.is_empty(), "open: {open:?}");
}

mod closed_shapes {
    use lumiere::scene::{scene_from_table, tables};
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]
        /// Spheres and capped cylinders of any resolution, under any rotation, scale and
        /// translation, are closed 2-manifolds.
        #[test]
        fn generated_spheres_and_cylinders_are_closed(
            resolution in 4u32..70,
            axis in (-1.0..1.0f64, -1.0..1.0f64, 0.1..1.0f64),
            degrees in -180.0..180.0f64,
            scale in (0.1..3.0f64, 0.1..3.0f64, 0.1..3.0f64),
            offset in (-5.0..5.0f64, -5.0..5.0f64, -5.0..5.0f64),
        ) {
            let transform = format!(
                "[{{ scale = [{}, {}, {}] }}, {{ rotate = {{ axis = [{}, {}, {}], degrees = {degrees} }} }}, {{ translate = [{}, {}, {}] }}]",
                scale.0, scale.1, scale.2, axis.0, axis.1, axis.2, offset.0, offset.1, offset.2
            );
            let text = format!(
                "{}[materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\n\
                 [[objects]]\nshape = \"sphere\"\nname = \"sphere\"\nmaterial = \"grey\"\nresolution = {resolution}\ntransform = {transform}\n\
                 [[objects]]\nshape = \"cylinder\"\nname = \"cylinder\"\nmaterial = \"grey\"\nresolution = {resolution}\ntransform = {transform}\n",
                crate::support::camera([0.0, 0.0, 9.0], [0.0, 0.0, 0.0], 40.0, 8, 8)
            );
            let table = tables::parse(&text, "test scene").unwrap();
            let scene = scene_from_table(table, &lumiere::catalogue::resources())
                .map_err(|e| crate::support::error_line(&e))
                .unwrap();
            let open = lumiere::shadow::shadow_volumes::open_objects(&scene);
            prop_assert!(open.is_empty(), "open: {:?}", open);
        }
    }
}

mod edge_cases {
    use super::*;

    const METHODS: [ShadowMethod; 6] = [
        ShadowMethod::RayCast,
        ShadowMethod::ShadowMap,
        ShadowMethod::ShadowVolumes,
        ShadowMethod::StencilShadowVolumes,
        ShadowMethod::Scanline,
        ShadowMethod::ShadowPolygons,
    ];

    /// A ground quad seen from above, a point light at `light`, and `extra` objects.
    fn scene_with(light: &str, extra: &str) -> String {
        format!(
            "{}[materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\n\
             [[lights]]\ntype = \"point\"\nposition = {light}\nintensity = [10.0, 10.0, 10.0]\n\
             [[objects]]\nshape = \"quad\"\nname = \"ground\"\nmaterial = \"grey\"\ntransform = [{{ scale = 8.0 }}]\n{extra}",
            crate::support::camera([0.0, 9.0, 6.0], [0.0, 0.0, 0.0], 40.0, 96, 72)
        )
    }

    /// Per method, the visibility of the samples of object `name`.
    fn visibility_of(text: &str, name: &str) -> Vec<(ShadowMethod, Vec<f32>)> {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("s.toml");
        std::fs::write(&path, text).unwrap();
        let scene = load_scene(path.to_str().unwrap(), &[]).unwrap();
        let object = scene.objects.iter().position(|o| o.name == name).unwrap();
        let (view, surface) = visible_surface(&scene);
        METHODS
            .iter()
            .map(|&m| {
                let v = lumiere::shadow::compute(&scene, &view, &surface, m).unwrap();
                let values = surface
                    .samples
                    .iter()
                    .enumerate()
                    .filter(|(_, s)| {
                        !s.is_empty() && scene.polygons[s.polygon as usize].object == object
                    })
                    .map(|(k, _)| v.fraction(0, k))
                    .collect();
                (m, values)
            })
            .collect()
    }

    fn lit_share(values: &[f32]) -> f64 {
        values.iter().filter(|&&v| v == 1.0).count() as f64 / values.len() as f64
    }

    /// A light inside a closed box: ray casting, the map, the scan-line shadow
    /// polygons and the light's own hidden-surface pass shadow everything outside;
    /// Crow's silhouette finds no light-facing polygon, so the volumes (counted
    /// either way) shadow nothing (documented in shadow_volumes).
    #[test]
    fn light_inside_a_closed_object() {
        let text = scene_with(
            "[0.0, 1.0, 0.0]",
            "[[objects]]\nshape = \"box\"\nname = \"box\"\nmaterial = \"grey\"\ntransform = [{ translate = [0.0, 1.0, 0.0] }]\n",
        );
        for (method, ground) in visibility_of(&text, "ground") {
            let volumes = [
                ShadowMethod::ShadowVolumes,
                ShadowMethod::StencilShadowVolumes,
            ];
            let expected = if volumes.contains(&method) { 1.0 } else { 0.0 };
            assert_eq!(lit_share(&ground), expected, "{method:?}");
        }
    }

    /// A light in a polygon's plane: the polygon is seen edge-on from the light, is
    /// itself unlit (self-shadow) and casts no shadow.
    #[test]
    fn light_in_a_polygons_plane() {
        let wall = "[[objects]]\nshape = \"polygon\"\nname = \"wall\"\nmaterial = \"grey\"\n\
                    vertices = [[-1.0, 0.5, 0.0], [1.0, 0.5, 0.0], [1.0, 2.0, 0.0], [-1.0, 2.0, 0.0]]\n";
        let text = scene_with("[0.0, 4.0, 0.0]", wall);
        for (method, ground) in visibility_of(&text, "ground") {
            assert_eq!(lit_share(&ground), 1.0, "{method:?}");
        }
        for (method, wall) in visibility_of(&text, "wall") {
            assert!(!wall.is_empty() && lit_share(&wall) == 0.0, "{method:?}");
        }
    }

    /// Appel's self-shadow rule is a setting: with the light under the ground and
    /// the eye above it, every method darkens the ground while the rule holds; off,
    /// each answers on its own, and the methods that look for occluders between
    /// the point and the light find none.
    #[test]
    fn the_self_shadow_rule_is_a_setting() {
        let below = scene_with("[0.0, -2.0, 0.0]", "");
        for (method, ground) in visibility_of(&below, "ground") {
            assert_eq!(lit_share(&ground), 0.0, "{method:?} with the rule");
        }
        let off = format!("{below}[shadows]\nself_shadow = false\n");
        for (method, ground) in visibility_of(&off, "ground") {
            if matches!(method, ShadowMethod::RayCast | ShadowMethod::Scanline) {
                assert_eq!(lit_share(&ground), 1.0, "{method:?} without the rule");
            }
        }
    }

    /// Coincident polygons do not shadow each other.
    #[test]
    fn coincident_polygons() {
        let twin = "[[objects]]\nshape = \"quad\"\nname = \"twin\"\nmaterial = \"grey\"\ntransform = [{ scale = 8.0 }]\n";
        let text = scene_with("[1.0, 3.0, 1.0]", twin);
        for (method, ground) in visibility_of(&text, "ground") {
            assert_eq!(lit_share(&ground), 1.0, "{method:?}");
        }
    }

    /// A polygon whose front faces away from the light: surfaces are two-sided, so
    /// the side the light and the eye both see (its back) is lit, and the polygon
    /// still shadows the ground under it.
    #[test]
    fn polygon_facing_away_from_the_light() {
        // A panel turned upside down (front facing the ground), light and eye above.
        let flipped = "[[objects]]\nshape = \"quad\"\nname = \"panel\"\nmaterial = \"grey\"\n\
                       transform = [{ rotate = { axis = [1.0, 0.0, 0.0], degrees = 180.0 } }, { translate = [0.0, 1.0, 0.0] }]\n";
        let text = scene_with("[0.0, 4.0, 0.0]", flipped);
        let ground = visibility_of(&text, "ground");
        for (method, panel) in visibility_of(&text, "panel") {
            assert_eq!(lit_share(&panel), 1.0, "{method:?}");
        }
        for (method, values) in ground {
            let share = lit_share(&values);
            assert!(share > 0.5 && share < 1.0, "{method:?}: {share}");
        }
    }
}

#[test]
fn scanline_shadows_agree_with_ray_casting() {
    assert_exact("cornell-box-point", 256, 256, ShadowMethod::Scanline);
    assert_exact(CURVED, 256, 192, ShadowMethod::Scanline);
}

/// Bouknight & Kelley's sphere test prunes caster/receiver pairs: it changes the
/// cost, never the image.
#[test]
fn scanline_pruning_changes_nothing() {
    use lumiere::shadow::scanline_shadows::visibility_with;
    let scene = load_scene(
        CURVED,
        &["camera.width=128".into(), "camera.height=96".into()],
    )
    .unwrap();
    let (view, surface) = visible_surface(&scene);
    let light = match &scene.lights[0] {
        lumiere::Light::Point(l) => l.position,
        _ => unreachable!("a point light"),
    };
    let pruned = visibility_with(&scene, &view, &surface, light, true);
    let all_pairs = visibility_with(&scene, &view, &surface, light, false);
    assert_eq!(pruned, all_pairs);
    assert!(pruned.contains(&0.0) && pruned.contains(&1.0));
}

#[test]
fn shadow_polygons_agree_with_ray_casting() {
    assert_exact("cornell-box-point", 256, 256, ShadowMethod::ShadowPolygons);
    assert_exact(CURVED, 256, 192, ShadowMethod::ShadowPolygons);
    // At this size a sample fell on a sphere's pole, where a fan of facet shadows
    // pinches the ground's region: the case that made Weiler-Atherton's retries
    // escalate their perturbation.
    assert_exact(CURVED, 128, 96, ShadowMethod::ShadowPolygons);
}

mod shadow_polygon_areas {
    use lumiere::load_scene;
    use lumiere::shadow::shadow_polygon_areas::receiver_shadows;

    /// The shadow polygons' areas: a square occluder of side s at height h under a
    /// point light at height H over its centre shadows a square of side s·H/(H − h)
    /// on the ground (similar triangles), to a relative 1e-6; lit and shadowed areas
    /// add up to each receiver's area.
    #[test]
    fn a_square_shadows_the_similar_triangle_square() {
        let (s, h, light_height) = (2.0, 1.0, 4.0);
        let text = format!(
            "{}[materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\n\
             [[lights]]\ntype = \"point\"\nposition = [0.0, {light_height}, 0.0]\nintensity = [10.0, 10.0, 10.0]\n\
             [[objects]]\nshape = \"quad\"\nname = \"ground\"\nmaterial = \"grey\"\ntransform = [{{ scale = 7.0 }}]\n\
             [[objects]]\nshape = \"quad\"\nname = \"occluder\"\nmaterial = \"grey\"\n\
             transform = [{{ scale = {s} }}, {{ translate = [0.0, {h}, 0.0] }}]\n",
            crate::support::camera([0.0, 12.0, 0.001], [0.0, 0.0, 0.0], 40.0, 32, 32)
        );
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("square.toml");
        std::fs::write(&path, text).unwrap();
        let scene = load_scene(path.to_str().unwrap(), &[]).unwrap();
        let light = glam::DVec3::new(0.0, light_height, 0.0);
        let receivers = receiver_shadows(&scene, light);
        let ground = receivers.iter().find(|r| r.object == "ground").unwrap();
        // Each report names its own polygon: the one of its object, of its area (the
        // ground 7 x 7, the occluder s x s).
        for r in &receivers {
            let polygon = &scene.polygons[r.polygon];
            assert_eq!(scene.objects[polygon.object].name, r.object);
            let side = if r.object == "ground" { 7.0 } else { s };
            assert!(
                (r.area - side * side).abs() < 1e-9,
                "{}: {}",
                r.object,
                r.area
            );
        }
        let side = s * light_height / (light_height - h);
        let expected = side * side;
        assert!(
            (ground.shadowed_area - expected).abs() <= 1e-6 * expected,
            "shadow {} vs {expected}",
            ground.shadowed_area
        );
        for r in &receivers {
            assert!(
                (r.lit_area + r.shadowed_area - r.area).abs() <= 1e-9 * r.area,
                "{}: {} + {} != {}",
                r.object,
                r.lit_area,
                r.shadowed_area,
                r.area
            );
        }
        let occluder = receivers.iter().find(|r| r.object == "occluder").unwrap();
        assert!((occluder.lit_area - s * s).abs() <= 1e-9 * s * s);
    }

    /// On the point-lit Cornell box, the lamp 0.1 mm under the 130 × 105 mm fixture
    /// and 0.2 mm under the ceiling: the fixture's shadow on the ceiling is the
    /// fixture scaled by 2, 54,600 mm².
    #[test]
    fn the_fixture_shadows_twice_its_size_on_the_ceiling() {
        let scene = load_scene("cornell-box-point", &[]).unwrap();
        let light = glam::DVec3::new(278.0, 548.6, 279.5);
        let receivers = receiver_shadows(&scene, light);
        let ceiling = receivers
            .iter()
            .find(|r| r.object == "cornell/ceiling")
            .unwrap();
        assert!(
            (ceiling.shadowed_area - 54_600.0).abs() <= 1e-6 * 54_600.0,
            "{}",
            ceiling.shadowed_area
        );
        // Lit and shadowed add up within the clipper's documented bound (1e-6 relative
        // once a clip has needed a larger perturbation, as one here does).
        for r in &receivers {
            assert!(
                (r.lit_area + r.shadowed_area - r.area).abs() <= 1e-6 * r.area,
                "{}",
                r.object
            );
        }
    }
}
