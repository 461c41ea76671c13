//! glTF 2.0 and OBJ: scenes exported, read back and rendered; a hand-written glTF
//! read with its transforms, camera, lights and material checked by hand.
//!
//! The exported glTF is checked here by the `gltf` crate's own validation (what
//! `load_scene` runs) and by its counts. The Khronos glTF-Validator is a
//! JavaScript package, not part of the Rust tool chain these tests need; run by
//! hand (`npm install gltf-validator`, `validateBytes`), it finds no error and no
//! warning in the exports of cornell-box, cornell-box-point, light-volumes-spot,
//! ray-tracing, reflection-mapping and two-pass.

use crate::support::render;
use base64::Engine as _;
use lumiere::export::{self, Format, Options};
use lumiere::glam::{DVec3, Vec3};
use lumiere::{Image, Light, Scene, SpotDistribution, load_scene, scene_from_toml};

fn sets(list: &[&str]) -> Vec<String> {
    list.iter().map(|s| s.to_string()).collect()
}

/// The point-lit Cornell box at 48 x 48, Crow's shadow volumes.
const BOX: [&str; 3] = [
    "camera.width=48",
    "camera.height=48",
    "shadows.method=\"shadow-volumes\"",
];

/// light-volumes-spot without what glTF cannot carry: its fog, and the cos⁸ fall-off
/// of its spot (a uniform cone is what glTF's sharp-edged spot holds).
fn spot_scene(overrides: &[String]) -> Scene {
    let mut table = lumiere::catalogue::entry("light-volumes-spot")
        .unwrap()
        .scene;
    table.remove("medium");
    table.remove("algorithm");
    let lights = table.get_mut("lights").unwrap().as_array_mut().unwrap();
    lights[0].as_table_mut().unwrap().remove("cosine_power");
    scene_from_toml(&toml::to_string(&table).unwrap(), overrides).unwrap()
}

/// glTF holds no render settings: the entry's shadow method is set again.
const SPOT: [&str; 3] = [
    "camera.width=64",
    "camera.height=48",
    "shadows.method=\"shadow-volumes\"",
];

/// The largest difference between two images' pixels, over the brightest pixel of
/// the first.
fn largest_relative_difference(a: &Image, b: &Image) -> f32 {
    assert_eq!((a.width, a.height), (b.width, b.height));
    let brightest = a.pixels.iter().map(|p| p.max_element()).fold(0.0, f32::max);
    assert!(brightest > 0.0);
    a.pixels
        .iter()
        .zip(&b.pixels)
        .map(|(p, q)| (*p - *q).abs().max_element())
        .fold(0.0, f32::max)
        / brightest
}

/// Exported to glTF and read back, a scene renders as it did. Not byte for byte:
/// glTF stores positions, normals, the camera's rotation, light colours and
/// intensities as 32-bit floats (lumiere keeps 64-bit positions), so vertices move
/// by up to half an f32 ulp (3e-5 at the box's 550 mm) and intensities by one part
/// in 1e7 (the 683 lm/W there and back). Those shift a pixel's radiance by about
/// a millionth of the image's brightest; an edge moved by a pixel, a light off by
/// a unit conversion or a render setting lost would differ by a large fraction
/// of it.
#[test]
fn a_scene_read_back_from_its_gltf_renders_the_same() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&str, Scene, Vec<String>); 2] = [
        (
            "box.gltf",
            load_scene("cornell-box-point", &sets(&BOX)).unwrap(),
            sets(&BOX),
        ),
        ("spot.gltf", spot_scene(&sets(&SPOT)), sets(&SPOT)),
    ];
    for (name, scene, overrides) in cases {
        let path = dir.path().join(name);
        let left_out = export::export(&scene, &Options::new(Format::Gltf), &path).unwrap();
        assert!(left_out.is_empty(), "{name}: {left_out:?}");
        let read = load_scene(path.to_str().unwrap(), &overrides).unwrap();
        assert_eq!(read.lights.len(), scene.lights.len(), "{name}");
        assert!(
            !read.warnings.iter().any(|w| w.starts_with("gltf:")),
            "{name}: {:?}",
            read.warnings
        );
        let (before, after) = (render(&scene), render(&read));
        let difference = largest_relative_difference(&before, &after);
        // Measured: 6.1e-7 (box) and 4.8e-7 (spot), the f32 rounding of the
        // intensities; no edge moved.
        assert!(difference < 1e-5, "{name}: {difference}");
    }
}

/// The glTF written is one the `gltf` crate validates, with one mesh per material,
/// one punctual light per point, spot or distant light, one camera, and the 683
/// lm/W conversion.
#[test]
fn the_exported_gltf_is_valid_and_holds_the_scene() {
    let dir = tempfile::tempdir().unwrap();
    for (scene, meshes, lights) in [
        (load_scene("cornell-box-point", &[]).unwrap(), 4, 1),
        (spot_scene(&[]), 2, 1),
        // The quad light: an emissive mesh, no punctual light.
        (load_scene("cornell-box", &[]).unwrap(), 4, 0),
    ] {
        let path = dir.path().join("s.gltf");
        export::export(&scene, &Options::new(Format::Gltf), &path).unwrap();
        let gltf = gltf::Gltf::from_slice(&std::fs::read(&path).unwrap()).unwrap();
        let materials: std::collections::HashSet<usize> =
            scene.polygons.iter().map(|p| p.material).collect();
        assert_eq!(materials.len(), meshes);
        assert_eq!(gltf.meshes().count(), meshes);
        assert_eq!(gltf.cameras().count(), 1);
        let punctual: Vec<_> = gltf.lights().map(|l| l.collect()).unwrap_or_default();
        assert_eq!(punctual.len(), lights);
        if let (Some(light), Some(Light::Point(point))) = (punctual.first(), scene.lights.first()) {
            let candela = Vec3::from(light.color()) * light.intensity();
            let expected = point.intensity * 683.0;
            assert!(
                ((candela - expected).abs() / expected).max_element() < 1e-6,
                "{candela} cd for {} W/sr",
                point.intensity
            );
        }
        let triangles: usize = gltf
            .meshes()
            .flat_map(|m| m.primitives())
            .map(|p| p.indices().unwrap().count() / 3)
            .sum();
        let expected: usize = scene.polygons.iter().map(|p| p.vertices.len() - 2).sum();
        assert_eq!(triangles, expected);
    }
}

/// The OBJ export read back by lumiere's own OBJ loader: as many vertices and
/// faces as the scene's polygons; its JSON sidecar holds the camera and lights.
#[test]
fn the_obj_export_reads_back_with_its_sidecar() {
    let dir = tempfile::tempdir().unwrap();
    let scene = spot_scene(&[]);
    let path = dir.path().join("scene.obj");
    export::export(&scene, &Options::new(Format::Obj), &path).unwrap();
    for file in ["scene.obj", "scene.mtl", "scene.json"] {
        assert!(dir.path().join(file).is_file(), "{file}");
    }
    let text = std::fs::read_to_string(&path).unwrap();
    let count = |prefix: &str| text.lines().filter(|l| l.starts_with(prefix)).count();
    let vertices: usize = scene.polygons.iter().map(|p| p.vertices.len()).sum();
    assert_eq!((count("v "), count("f ")), (vertices, scene.polygons.len()));
    // The OBJ through the loader, its MTL's materials, as a scene file names it.
    let toml = crate::support::camera([0.0, 2.2, 7.5], [0.0, 1.4, 0.0], 42.0, 8, 6)
        + "[[objects]]\nshape = \"obj\"\nfile = \"scene.obj\"\nsmooth = true\n";
    std::fs::write(dir.path().join("read.toml"), toml).unwrap();
    let read = load_scene(dir.path().join("read.toml").to_str().unwrap(), &[]).unwrap();
    assert_eq!(read.polygons.len(), scene.polygons.len());
    let read_vertices: usize = read.polygons.iter().map(|p| p.vertices.len()).sum();
    assert_eq!(read_vertices, vertices);
    for (a, b) in scene.polygons.iter().zip(&read.polygons) {
        assert_eq!(
            scene.materials[a.material].diffuse,
            read.materials[b.material].diffuse
        );
        for (u, v) in a.vertices.iter().zip(&b.vertices) {
            assert_eq!(u.position, v.position);
        }
    }

    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("scene.json")).unwrap()).unwrap();
    let camera = &json["camera"];
    let c = &scene.camera;
    let vector = |v: &serde_json::Value| {
        DVec3::new(
            v[0].as_f64().unwrap(),
            v[1].as_f64().unwrap(),
            v[2].as_f64().unwrap(),
        )
    };
    assert_eq!(vector(&camera["eye"]), c.eye);
    assert_eq!(vector(&camera["look_at"]), c.look_at);
    assert_eq!(vector(&camera["up"]), c.up);
    assert_eq!(camera["fov_y_degrees"].as_f64().unwrap(), c.fov_y);
    assert_eq!(
        (camera["width"].as_u64(), camera["height"].as_u64()),
        (Some(c.width as u64), Some(c.height as u64))
    );
    let lights = json["lights"].as_array().unwrap();
    assert_eq!(lights.len(), scene.lights.len());
    let Light::Spot(spot) = &scene.lights[0] else {
        panic!("light-volumes-spot's light is a spot")
    };
    assert_eq!(lights[0]["kind"], "spot");
    assert_eq!(vector(&lights[0]["position"]), spot.position);
    assert_eq!(vector(&lights[0]["axis"]), spot.axis);
    assert_eq!(
        lights[0]["intensity"][0].as_f64().unwrap() as f32,
        spot.intensity.x
    );
    assert_eq!(lights[0]["distribution"]["cosine_power"], 0.0);
    assert!(
        json["units"]["length"]
            .as_str()
            .unwrap()
            .contains("scene units")
    );
    assert_eq!(
        json["materials"].as_array().unwrap().len(),
        scene.materials.len()
    );
}

/// A glTF written by hand: one triangle placed by two nodes (one turned, scaled and
/// moved; one stretched along x, to tell the inverse transpose from the matrix
/// itself), a camera, a point and a spot light, a coloured material, and what
/// lumiere leaves out (a metallic material with a normal map, lines, a second
/// camera), each named once.
fn hand_written() -> String {
    let floats: [f32; 18] = [
        0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, // positions
        0.6, 0.0, 0.8, 0.6, 0.0, 0.8, 0.6, 0.0, 0.8, // normals, not the face's
    ];
    let bytes: Vec<u8> = floats.iter().flat_map(|f| f.to_le_bytes()).collect();
    let uri = base64::engine::general_purpose::STANDARD.encode(&bytes);
    let half = std::f64::consts::FRAC_1_SQRT_2;
    format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {{"KHR_lights_punctual": {{"lights": [
    {{"type": "point", "name": "bulb", "color": [1.0, 0.5, 0.25], "intensity": 2732.0}},
    {{"type": "spot", "color": [1.0, 1.0, 1.0], "intensity": 683.0,
      "spot": {{"innerConeAngle": 0.2, "outerConeAngle": 0.5}}}}
  ]}}}},
  "scene": 0,
  "scenes": [{{"nodes": [0, 1, 2, 3, 4, 5]}}],
  "nodes": [
    {{"name": "turned", "mesh": 0, "translation": [1.0, 2.0, 3.0],
      "rotation": [0.0, 0.0, {half}, {half}], "scale": [2.0, 2.0, 2.0]}},
    {{"name": "stretched", "mesh": 0, "scale": [2.0, 1.0, 1.0], "translation": [0.0, 0.0, -1.0]}},
    {{"camera": 0, "translation": [0.0, 0.0, 10.0]}},
    {{"extensions": {{"KHR_lights_punctual": {{"light": 0}}}}, "translation": [0.0, 5.0, 0.0]}},
    {{"extensions": {{"KHR_lights_punctual": {{"light": 1}}}}, "translation": [0.0, 0.0, 5.0]}},
    {{"camera": 1, "mesh": 1}}
  ],
  "cameras": [
    {{"type": "perspective", "perspective": {{"yfov": 0.5, "aspectRatio": 1.5, "znear": 0.1}}}},
    {{"type": "perspective", "name": "spare", "perspective": {{"yfov": 1.0, "znear": 0.1}}}}
  ],
  "meshes": [
    {{"primitives": [{{"attributes": {{"POSITION": 0, "NORMAL": 1}}, "material": 0}}]}},
    {{"primitives": [
      {{"attributes": {{"POSITION": 0}}, "material": 0, "mode": 1}},
      {{"attributes": {{"POSITION": 0}}, "material": 1}}
    ]}}
  ],
  "materials": [
    {{"name": "terracotta", "pbrMetallicRoughness": {{"baseColorFactor": [0.8, 0.3, 0.2, 1.0],
      "metallicFactor": 0.0, "roughnessFactor": 1.0}}}},
    {{"name": "chrome", "pbrMetallicRoughness": {{"metallicFactor": 1.0, "roughnessFactor": 0.5}},
      "normalTexture": {{"index": 0}}}}
  ],
  "textures": [{{"source": 0}}],
  "images": [{{"uri": "bumps.png"}}],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
      "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0]}},
    {{"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"}}
  ],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 36}},
    {{"buffer": 0, "byteOffset": 36, "byteLength": 36}}
  ],
  "buffers": [{{"byteLength": 72, "uri": "data:application/octet-stream;base64,{uri}"}}]
}}"#
    )
}

#[test]
fn a_hand_written_gltf_is_placed_lit_and_seen_as_computed_by_hand() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("hand.gltf");
    std::fs::write(&path, hand_written()).unwrap();
    let scene = load_scene(path.to_str().unwrap(), &[]).unwrap();

    // Node "turned": p → (1, 2, 3) + R_z(90°)(2 p); R_z(90°) takes (x, y) to (−y, x).
    // Node "stretched": p → (2x, y, z − 1).
    let placed: Vec<Vec<DVec3>> = scene
        .polygons
        .iter()
        .map(|p| p.positions().collect())
        .collect();
    let close = |a: DVec3, b: DVec3| (a - b).length() < 1e-6;
    let expected = [
        [
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(1.0, 4.0, 3.0),
            DVec3::new(-1.0, 2.0, 3.0),
        ],
        [
            DVec3::new(0.0, 0.0, -1.0),
            DVec3::new(2.0, 0.0, -1.0),
            DVec3::new(0.0, 1.0, -1.0),
        ],
    ];
    // The third: chrome's triangle, untransformed.
    assert_eq!(placed.len(), 3, "{placed:?}");
    for (got, want) in placed.iter().zip(&expected) {
        assert!(
            got.iter().zip(want).all(|(a, b)| close(*a, *b)),
            "{got:?} != {want:?}"
        );
    }
    // Normals by the inverse transpose: (0.6, 0, 0.8) under diag(2, 1, 1) becomes
    // (0.3, 0, 0.8) normalised; the matrix itself would give (1.2, 0, 0.8).
    let stretched = DVec3::new(0.3, 0.0, 0.8).normalize();
    assert!(
        scene.polygons[1]
            .vertices
            .iter()
            .all(|v| close(v.normal, stretched)),
        "{:?}",
        scene.polygons[1].vertices
    );
    // Turned by R_z(90°) (uniform scale): (0.6, 0, 0.8) → (0, 0.6, 0.8).
    assert!(
        scene.polygons[0]
            .vertices
            .iter()
            .all(|v| close(v.normal, DVec3::new(0.0, 0.6, 0.8)))
    );
    let material = scene.material_of(0);
    assert_eq!(material.diffuse, Vec3::new(0.8, 0.3, 0.2));

    // The camera: at (0, 0, 10) looking down −z, yfov 0.5 rad, 512 wide at 1.5.
    let c = &scene.camera;
    assert!(close(c.eye, DVec3::new(0.0, 0.0, 10.0)));
    assert!(close((c.look_at - c.eye).normalize(), DVec3::NEG_Z));
    assert!(close(c.up, DVec3::Y));
    assert!((c.fov_y - 0.5f64.to_degrees()).abs() < 1e-5);
    assert_eq!((c.width, c.height, c.near), (512, 341, 0.1f32 as f64));

    // The point light: colour × candela / 683 W/sr, (1, 0.5, 0.25) × 2732 / 683.
    let Light::Point(bulb) = &scene.lights[0] else {
        panic!("{:?}", scene.lights[0])
    };
    assert!(close(bulb.position, DVec3::new(0.0, 5.0, 0.0)));
    assert_eq!(bulb.intensity, Vec3::new(4.0, 2.0, 1.0));
    // The spot: 1 W/sr down −z; glTF's smooth edge from 0.2 to 0.5 rad, its
    // ((cos θ − cos 0.5) / (cos 0.2 − cos 0.5))², tabulated.
    let Light::Spot(spot) = &scene.lights[1] else {
        panic!("{:?}", scene.lights[1])
    };
    assert_eq!(spot.intensity, Vec3::ONE);
    assert!(close(spot.axis, DVec3::NEG_Z));
    assert!((spot.cone_angle - 0.5).abs() < 1e-6);
    assert!(matches!(spot.distribution, SpotDistribution::Table(_)));
    let edge = |theta: f64| {
        (((theta.cos() - 0.5f64.cos()) / (0.2f64.cos() - 0.5f64.cos())).clamp(0.0, 1.0)).powi(2)
    };
    for theta in [0.0, 0.1, 0.2, 0.3, 0.35, 0.45, 0.5, 0.6] {
        let (got, want) = (spot.factor(theta), edge(theta));
        assert!((got - want).abs() < 2e-3, "f({theta}) = {got}, not {want}");
    }

    // What is left out, one line each.
    let warnings: Vec<&String> = scene
        .warnings
        .iter()
        .filter(|w| w.starts_with("gltf: "))
        .collect();
    for fragment in [
        "material `chrome`: metallic 1 and roughness 0.5 are left out",
        "material `chrome`: its normal texture is left out",
        "primitive 0: Lines are not triangles, left out",
        "camera `spare` left out",
    ] {
        assert_eq!(
            warnings.iter().filter(|w| w.contains(fragment)).count(),
            1,
            "`{fragment}` not once in {warnings:?}"
        );
    }
    assert_eq!(warnings.len(), 4, "{warnings:?}");
    assert!(warnings.iter().all(|w| !w.contains('\n')));
}

/// The defaults a glTF scene gets give way to overrides, as a scene file's do.
#[test]
fn overrides_set_a_gltf_scenes_render_settings() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("hand.gltf");
    std::fs::write(&path, hand_written()).unwrap();
    let spec = path.to_str().unwrap();
    let scene = load_scene(
        spec,
        &sets(&["camera.width=20", "shadows.method=\"ray-cast\""]),
    )
    .unwrap();
    assert_eq!((scene.camera.width, scene.camera.height), (20, 341));
    assert_eq!(
        scene.shadows.method,
        lumiere::settings::ShadowMethod::RayCast
    );
    let image = render(&load_scene(spec, &sets(&["camera.width=16", "camera.height=12"])).unwrap());
    assert_eq!((image.width, image.height), (16, 12));
}
