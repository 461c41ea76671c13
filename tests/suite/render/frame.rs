//! The frame: bands, threads, the renderer's kept work, buffers, per-light weights
//! and the radiosity integrator's lights.

use lumiere::image_io::{BufferData, Image};
use lumiere::raster::NO_POLYGON;
use lumiere::render::{Prepasses, Renderer, visible_surface};
use lumiere::scene::{Light, Scene};
use lumiere::settings::ShadowMethod;
use lumiere::{load_scene, render};

fn scene(id: &str, sets: &[&str]) -> Scene {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    load_scene(id, &sets).unwrap()
}

fn with_bands(scene: &Scene, rows: u32) -> Image {
    let mut scene = scene.clone();
    scene.render.band_rows = rows;
    render(&scene).unwrap()
}

fn on_threads(threads: usize, f: impl FnOnce() -> Image + Send) -> Image {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(f)
}

/// Bit for bit: the image's floats, not their rounding to 8 bits.
fn assert_same(a: &Image, b: &Image, what: &str) {
    assert_eq!((a.width, a.height), (b.width, b.height), "{what}");
    let differing = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .filter(|(p, q)| p.to_array().map(f32::to_bits) != q.to_array().map(f32::to_bits))
        .count();
    assert_eq!(differing, 0, "{what}: {differing} pixels differ");
}

/// Every shadow method (the soft ones included), a soft-shadowed area light, textures, several shading modes
/// and a radiosity solution give the same bytes whether the frame is made in bands
/// of 1, 7 or 64 rows or whole, on one thread or four.
#[test]
fn bands_and_threads_do_not_change_a_single_bit() {
    let small = [
        "camera.width=40",
        "camera.height=30",
        "render.supersample=2",
    ];
    let mut cases: Vec<(String, Scene)> = Vec::new();
    for method in [
        "ray-cast",
        "scanline",
        "shadow-polygons",
        "shadow-map",
        "shadow-volumes",
    ] {
        let set = format!("shadows.method=\"{method}\"");
        let mut sets = small.to_vec();
        sets.push(&set);
        cases.push((method.into(), scene("cornell-box-point", &sets)));
    }
    // Reeves's points: one stream per sample, by its place on the whole grid.
    cases.push(("percentage-closer".into(), scene("shadow-map-pcf", &small)));
    let mut soft = small.to_vec();
    soft.extend(["shadows.method=\"ray-cast\"", "shadows.light_samples=3"]);
    cases.push(("soft".into(), scene("cornell-box", &soft)));
    for (name, id, extra) in [
        ("umbra-penumbra", "umbra-penumbra", "shadows.seed=0"),
        (
            "soft-shadow-volumes",
            "soft-shadow-volumes",
            "shadows.light_points=5",
        ),
        ("jittered", "jittered-soft-shadows", "shadows.rings=2"),
        (
            "regular cells",
            "jittered-soft-shadows-regular",
            "shadows.rings=2",
        ),
    ] {
        let sets = [&small[..], &[extra]].concat();
        cases.push((name.into(), scene(id, &sets)));
    }
    cases.push(("mip-mapping".into(), scene("mip-mapping", &small)));
    cases.push(("shading-modes".into(), scene("shading-modes", &small)));
    cases.push((
        "radiosity".into(),
        scene(
            "radiosity-shooting",
            &[&small[..], &["radiosity.max_steps=20"]].concat(),
        ),
    ));
    for (name, scene) in &cases {
        let whole = with_bands(scene, scene.camera.height);
        for rows in [1, 7, 64, 0] {
            assert_same(
                &whole,
                &with_bands(scene, rows),
                &format!("{name}, bands of {rows}"),
            );
        }
        let one = on_threads(1, || with_bands(scene, 7));
        let four = on_threads(4, || with_bands(scene, 0));
        assert_same(&one, &four, &format!("{name}, 1 and 4 threads"));
    }
}

/// Rendering twice reuses every pre-pass; a new camera reuses them and gives the same
/// bytes as a fresh render from there; a moved light redoes its own shadows only.
#[test]
fn the_renderer_keeps_view_independent_work() {
    let sets = ["camera.width=48", "camera.height=48"];
    for method in [
        "ray-cast",
        "scanline",
        "shadow-polygons",
        "shadow-map",
        "shadow-volumes",
    ] {
        let set = format!("shadows.method=\"{method}\"");
        let base = scene("cornell-box-point", &[&sets[..], &[set.as_str()]].concat());
        let mut renderer = Renderer::new(base.clone());
        assert_eq!(renderer.prepasses(), Prepasses::default(), "{method}");
        let first = renderer.render().unwrap();
        let built = renderer.prepasses();
        assert_eq!(built.light_shadows, 1, "{method}");
        assert_eq!(built.occluders, (method == "ray-cast") as usize, "{method}");
        let again = renderer.render().unwrap();
        assert_same(&first, &again, method);
        assert_eq!(renderer.prepasses(), built, "{method}: rendered twice");

        let mut camera = base.camera.clone();
        camera.eye += glam::DVec3::new(120.0, -40.0, 150.0);
        camera.look_at += glam::DVec3::new(-30.0, 20.0, 0.0);
        renderer.set_camera(camera.clone());
        let moved = renderer.render().unwrap();
        assert_eq!(renderer.prepasses(), built, "{method}: a new camera");
        let mut fresh_scene = base.clone();
        fresh_scene.camera = camera;
        assert_same(&moved, &render(&fresh_scene).unwrap(), method);

        let Light::Point(mut lamp) = base.lights[0].clone() else {
            panic!("a point light")
        };
        lamp.position.x -= 100.0;
        renderer.set_light(0, Light::Point(lamp.clone())).unwrap();
        let relit = renderer.render().unwrap();
        assert_eq!(
            renderer.prepasses().light_shadows,
            2,
            "{method}: a moved light"
        );
        assert_eq!(renderer.prepasses().occluders, built.occluders, "{method}");
        let mut fresh_scene = renderer.scene().clone();
        fresh_scene.lights[0] = Light::Point(lamp);
        assert_same(&relit, &render(&fresh_scene).unwrap(), method);
    }
    // A radiosity solution is solved once, whatever the camera.
    let base = scene(
        "radiosity-shooting",
        &[
            "camera.width=24",
            "camera.height=24",
            "radiosity.max_steps=10",
        ],
    );
    let mut renderer = Renderer::new(base.clone());
    renderer.render().unwrap();
    let mut camera = base.camera.clone();
    camera.eye.x += 50.0;
    renderer.set_camera(camera);
    renderer.render().unwrap();
    assert_eq!(renderer.prepasses().radiosity, 1);

    // A light the solution holds moved: solved again, as a fresh renderer would.
    let base = scene(
        "radiosity-point-light",
        &["camera.width=24", "camera.height=24"],
    );
    let mut renderer = Renderer::new(base.clone());
    renderer.render().unwrap();
    let Light::Point(mut lamp) = base.lights[0].clone() else {
        panic!("a point light")
    };
    lamp.position.y -= 0.1;
    renderer.set_light(0, Light::Point(lamp.clone())).unwrap();
    let relit = renderer.render().unwrap();
    assert_eq!(renderer.prepasses().radiosity, 2, "a moved light");
    let mut fresh_scene = base.clone();
    fresh_scene.lights[0] = Light::Point(lamp);
    assert_same(
        &relit,
        &render(&fresh_scene).unwrap(),
        "radiosity-point-light",
    );
}

/// The buffers are what the passes computed: the polygon ids are the visible-surface
/// buffer's, a light's visibility is the shadow method's, Crow's counts are the
/// volumes', the shadow map's faces are its depth images.
#[test]
fn buffers_hold_what_the_passes_computed() {
    let sets = [
        "camera.width=32",
        "camera.height=24",
        "shadows.method=\"shadow-volumes\"",
    ];
    let scene = scene("cornell-box-point", &sets);
    let renderer = Renderer::new(scene.clone());
    let names: Vec<String> = renderer
        .available_buffers()
        .unwrap()
        .into_iter()
        .map(|b| b.name)
        .collect();
    for name in [
        "polygon",
        "depth",
        "normal",
        "uv",
        "visibility-0",
        "shadow-volume-counts-0",
    ] {
        assert!(names.contains(&name.to_string()), "{name} not in {names:?}");
    }
    let rendered = renderer.render_with_buffers(&names).unwrap();
    let (view, surface) = visible_surface(&scene);
    let buffer = |name: &str| rendered.buffers.iter().find(|b| b.name == name).unwrap();
    let BufferData::Ids(ids) = &buffer("polygon").data else {
        panic!("ids")
    };
    let expected: Vec<u32> = surface.samples.iter().map(|s| s.polygon).collect();
    assert_eq!(ids, &expected);
    assert!(ids.contains(&NO_POLYGON) || ids.iter().all(|&i| i != NO_POLYGON));
    let visibility =
        lumiere::shadow::compute(&scene, &view, &surface, ShadowMethod::ShadowVolumes).unwrap();
    let BufferData::Values { data, channels: 1 } = &buffer("visibility-0").data else {
        panic!("values")
    };
    for (k, s) in surface.samples.iter().enumerate() {
        let expected = if s.is_empty() {
            0.0
        } else {
            visibility.fraction(0, k)
        };
        assert_eq!(data[k], expected, "sample {k}");
    }
    let counts = lumiere::shadow::shadow_volumes::counts(
        &scene,
        &view,
        &surface,
        match &scene.lights[0] {
            Light::Point(l) => l.position,
            _ => unreachable!(),
        },
    );
    assert_eq!(
        buffer("shadow-volume-counts-0").data,
        BufferData::Counts(counts)
    );
    assert_same(
        &rendered.image,
        &render(&scene).unwrap(),
        "the image beside its buffers",
    );
    assert!(
        renderer
            .render_with_buffers(&["no-such".to_string()])
            .is_err()
    );

    let mut map = scene.clone();
    map.shadows.method = ShadowMethod::ShadowMap;
    map.shadows.map_resolution = 64;
    let renderer = Renderer::new(map);
    let faces: Vec<String> = ["px", "nx", "py", "ny", "pz", "nz"]
        .iter()
        .map(|f| format!("shadow-map-0-{f}"))
        .collect();
    let rendered = renderer.render_with_buffers(&faces).unwrap();
    for b in &rendered.buffers {
        assert_eq!((b.width, b.height), (64, 64), "{}", b.name);
        let BufferData::Values { data, .. } = &b.data else {
            panic!("depths")
        };
        // Walls, ceiling and back wall close the light in on four faces; the faces
        // looking down and to the front see out of the box's open front.
        let finite = data.iter().filter(|d| d.is_finite()).count();
        let closed = ["px", "nx", "py", "pz"].iter().any(|f| b.name.ends_with(f));
        assert_eq!(finite == data.len(), closed, "{}: {finite} finite", b.name);
        assert!(finite > data.len() / 3, "{}", b.name);
        assert!(data.iter().all(|d| *d > 0.0), "{}", b.name);
    }
}

/// Flat and Gouraud shading weigh each light by its own visibility: where only one
/// of two lights is shadowed, the other's light is all that is left, and a shadowed
/// light no longer dims an unshadowed one.
#[test]
fn each_light_is_weighed_by_its_own_visibility() {
    for shading in ["flat", "gouraud", "phong"] {
        let set = format!("render.shading=\"{shading}\"");
        let sets = [
            "camera.width=48",
            "camera.height=48",
            "shadows.method=\"ray-cast\"",
            set.as_str(),
        ];
        let mut both = scene("cornell-box-point", &sets);
        let Light::Point(lamp) = both.lights[0].clone() else {
            panic!("a point light")
        };
        let mut second = lamp.clone();
        second.position = glam::DVec3::new(450.0, 300.0, 150.0);
        second.intensity *= 0.5;
        both.lights.push(Light::Point(second.clone()));
        let mut only_second = both.clone();
        only_second.lights = vec![Light::Point(second)];
        let mut only_first = both.clone();
        only_first.lights = vec![Light::Point(lamp)];
        let (a, b, ab) = (
            render(&only_first).unwrap(),
            render(&only_second).unwrap(),
            render(&both).unwrap(),
        );
        // Per pixel, both lights' image is the sum of each light's image.
        let worst = ab
            .pixels
            .iter()
            .zip(a.pixels.iter().zip(&b.pixels))
            .map(|(s, (p, q))| {
                ((*s - (*p + *q)).abs() / (p.max_element() + q.max_element()).max(1e-3))
                    .max_element()
            })
            .fold(0.0f32, f32::max);
        assert!(worst < 1e-4, "{shading}: sum differs by {worst}");
    }
}

/// The radiosity integrator shoots a point light into its solution and adds its
/// direct light, with its shadows, at every sample. Radiosity is linear in its
/// sources: the image lit by the lamp quad and the point light is the image lit by
/// the quad alone plus the image lit by the point light alone (each with every
/// bounce), and the point light's image is more than its direct light (the walls
/// throw it back).
#[test]
fn radiosity_takes_point_lights_and_their_shadows() {
    let sets = [
        "camera.width=32",
        "camera.height=32",
        "radiosity.solver=\"gathering\"",
        "radiosity.tolerance=1e-9",
        "shadows.method=\"ray-cast\"",
    ];
    let base = scene("radiosity-shooting", &sets);
    let lamp = scene(
        "cornell-box-point",
        &["camera.width=32", "camera.height=32"],
    )
    .lights[0]
        .clone();
    let mut with_lamp = base.clone();
    with_lamp.lights.push(lamp.clone());
    let mut lamp_only = with_lamp.clone();
    // The quad: no emission, and no polygon light (which a frame without
    // radiosity would light directly).
    for m in &mut lamp_only.materials {
        m.emission = glam::Vec3::ZERO;
    }
    lamp_only.lights.retain(|l| !matches!(l, Light::Polygon(_)));
    let mut direct_only = lamp_only.clone();
    direct_only.radiosity = None;
    let (quad, both, point, direct) = (
        render(&base).unwrap(),
        render(&with_lamp).unwrap(),
        render(&lamp_only).unwrap(),
        render(&direct_only).unwrap(),
    );
    let (_, surface) = visible_surface(&direct_only);
    let n = direct_only.render.supersample;
    let (mut compared, mut brighter) = (0, 0);
    for (i, (b, (q, p))) in both
        .pixels
        .iter()
        .zip(quad.pixels.iter().zip(&point.pixels))
        .enumerate()
    {
        let (x, y) = (i as u32 % both.width, i as u32 / both.width);
        let sample = surface.at(x * n, y * n);
        // Emitters show their emission; skip them and the sky.
        if sample.is_empty() || base.material_of(sample.polygon as usize).is_emitter() {
            continue;
        }
        let expected = *q + *p;
        assert!(
            (*b - expected).abs().max_element() <= 1e-4 * expected.max_element().max(1.0),
            "pixel {x},{y}: {b} against {expected}"
        );
        let d = direct.pixels[i];
        assert!(
            p.cmpge(d - 1e-6).all(),
            "pixel {x},{y}: the point light's image {p} below its direct light {d}"
        );
        if p.max_element() > 1.1 * d.max_element() + 1e-3 {
            brighter += 1;
        }
        compared += 1;
    }
    assert!(compared > 500);
    assert!(
        brighter > compared / 2,
        "{brighter} of {compared} lit by bounces"
    );
}

fn textured_radiosity() -> String {
    crate::support::camera([0.0, 2.0, 4.0], [0.0, 0.0, 0.0], 45.0, 32, 32)
        + r#"[textures.half]
procedural = "checkerboard"
colors = [[0.5, 0.25, 0.125], [0.5, 0.25, 0.125]]

[materials.floor]
diffuse = [0.8, 0.8, 0.8]
diffuse_texture = "half"

[materials.lamp]
diffuse = [0.0, 0.0, 0.0]
emission = [4.0, 4.0, 4.0]

[[objects]]
shape = "quad"
name = "floor"
material = "floor"
transform = [{ scale = 3.0 }]

[[objects]]
shape = "quad"
name = "lamp"
material = "lamp"
transform = [{ rotate = { axis = [1.0, 0.0, 0.0], degrees = 180.0 } }, { translate = [0.0, 1.5, 0.0] }]

[radiosity]
solver = "gathering"
patch_size = 1.0
"#
}

/// Under radiosity a diffuse texture scales the light a surface reflects: with a
/// constant texture of colour c, the floor shows c times its untextured radiance.
#[test]
fn radiosity_takes_textures() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.toml");
    std::fs::write(&path, textured_radiosity()).unwrap();
    let textured = load_scene(path.to_str().unwrap(), &[]).unwrap();
    let mut plain = textured.clone();
    for m in &mut plain.materials {
        m.diffuse_texture = None;
    }
    let (a, b) = (render(&textured).unwrap(), render(&plain).unwrap());
    let (_, surface) = visible_surface(&textured);
    let floor = textured
        .objects
        .iter()
        .position(|o| o.name == "floor")
        .unwrap();
    let c = glam::Vec3::new(0.5, 0.25, 0.125);
    let mut compared = 0;
    for (k, s) in surface.samples.iter().enumerate() {
        if s.is_empty() || textured.polygons[s.polygon as usize].object != floor {
            continue;
        }
        let expected = b.pixels[k] * c;
        assert!(
            (a.pixels[k] - expected).abs().max_element() <= 1e-5 * expected.max_element(),
            "sample {k}: {} against {expected}",
            a.pixels[k]
        );
        compared += 1;
    }
    assert!(compared > 200, "{compared}");
}

/// A progress watcher is told, band by band, the fraction of the frame done:
/// rising, ending at 1, and the image is the one made without it.
#[test]
fn progress_is_told_band_by_band_up_to_the_whole_frame() {
    let scene = scene("cornell-box-point", &["render.band_rows=8"]);
    let told = std::sync::Arc::new(std::sync::Mutex::new(Vec::new()));
    let mut renderer = Renderer::new(scene.clone());
    let record = told.clone();
    renderer.set_progress(move |done| record.lock().unwrap().push(done));
    let image = renderer.render().unwrap();
    let told = told.lock().unwrap().clone();
    let bands = scene.camera.height.div_ceil(8) as usize;
    assert_eq!(told.len(), bands, "{told:?}");
    assert!(told.windows(2).all(|w| w[0] < w[1]), "{told:?}");
    assert_eq!(*told.last().unwrap(), 1.0);
    assert_same(
        &image,
        &Renderer::new(scene).render().unwrap(),
        "with progress",
    );
}

/// A stop switch set from another thread ends the frame with `Error::Stopped`; the
/// pre-passes built are kept, and once the switch is cleared the next frame renders.
#[test]
fn a_stopped_frame_ends_early_and_keeps_its_prepasses() {
    use std::sync::Arc;
    use std::sync::atomic::{AtomicBool, Ordering};
    let sets = [
        "camera.width=64",
        "camera.height=64",
        "shadows.method=\"shadow-volumes\"",
    ]
    .map(String::from);
    let mut renderer =
        lumiere::Renderer::new(lumiere::load_scene("cornell-box-point", &sets).unwrap());
    let stop = Arc::new(AtomicBool::new(true));
    renderer.set_stop(stop.clone());
    assert!(matches!(renderer.render(), Err(lumiere::Error::Stopped)));
    let built = renderer.prepasses();
    assert_eq!(built.light_shadows, 1);
    stop.store(false, Ordering::Relaxed);
    let image = renderer.render().unwrap();
    assert_eq!((image.width, image.height), (64, 64));
    assert_eq!(
        renderer.prepasses(),
        built,
        "the pre-passes are not built again"
    );
}
