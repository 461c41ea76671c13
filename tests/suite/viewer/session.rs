//! The viewer's engine through its messages, in this process: what the page sends,
//! what it gets back. Frames must equal what the library renders of the same view,
//! follow the method, the light and the split, and a bad message must get one
//! error and leave the session working.

use lumiere::viewer::Session;
use lumiere::{Renderer, load_scene};
use serde_json::{Value, json};

/// Sends `message` (its `id` set) and returns the replies' headers and payloads.
pub fn ask(session: &mut Session, message: Value) -> Vec<(Value, Vec<u8>)> {
    decoded(&session.handle_text(&message.to_string()))
}

/// The replies to a binary message, decoded as `ask`'s are.
pub fn ask_binary(session: &mut Session, bytes: &[u8]) -> Vec<(Value, Vec<u8>)> {
    decoded(&session.handle_binary(bytes))
}

fn decoded(replies: &[lumiere::viewer::Reply]) -> Vec<(Value, Vec<u8>)> {
    replies
        .iter()
        .map(|r| {
            (
                r.header().expect("a reply has a header"),
                r.payload().to_vec(),
            )
        })
        .collect()
}

/// The one reply of type `kind` among `replies`.
pub fn one(replies: &[(Value, Vec<u8>)], kind: &str) -> (Value, Vec<u8>) {
    let found: Vec<_> = replies.iter().filter(|r| r.0["type"] == kind).collect();
    assert_eq!(found.len(), 1, "one {kind} in {:?}", headers(replies));
    found[0].clone()
}

pub fn headers(replies: &[(Value, Vec<u8>)]) -> Vec<Value> {
    replies.iter().map(|r| r.0.clone()).collect()
}

/// The error message among `replies`.
pub fn error(replies: &[(Value, Vec<u8>)]) -> String {
    let (header, _) = one(replies, "error");
    header["message"].as_str().unwrap().to_string()
}

/// `a` equals `b`, or how many of their values differ (not the values: thousands).
pub fn same<T: PartialEq>(a: &[T], b: &[T], what: &str) {
    let differing = a.iter().zip(b).filter(|(x, y)| x != y).count();
    assert!(
        a.len() == b.len() && differing == 0,
        "{what}: {differing} of {} values differ ({} against {})",
        a.len().min(b.len()),
        a.len(),
        b.len()
    );
}

/// Floats of an export's payload.
pub fn floats(payload: &[u8]) -> Vec<f32> {
    payload
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
        .collect()
}

const BOX: [&str; 2] = ["camera.width=48", "camera.height=40"];

fn opened(scene: &str, sets: &[&str]) -> Session {
    let mut session = Session::new();
    let replies = ask(
        &mut session,
        json!({"type": "open", "id": 1, "scene": scene, "sets": sets}),
    );
    one(&replies, "scene");
    one(&replies, "frame");
    session
}

/// The library's own render of the point-lit box under `method` (`extra` sets).
fn rendered(method: &str, extra: &[String]) -> lumiere::Image {
    let mut sets: Vec<String> = BOX.iter().map(|s| s.to_string()).collect();
    sets.push(format!("shadows.method=\"{method}\""));
    sets.extend_from_slice(extra);
    Renderer::new(load_scene("cornell-box-point", &sets).unwrap())
        .render()
        .unwrap()
}

fn exported(session: &mut Session, what: &str) -> (Value, Vec<f32>) {
    let replies = ask(session, json!({"type": "export", "id": 90, "what": what}));
    let (header, payload) = one(&replies, "export");
    (header, floats(&payload))
}

#[test]
fn frames_are_what_the_library_renders_and_follow_the_method() {
    let mut session = opened("cornell-box-point", &BOX);
    let mut previous: Option<Vec<u8>> = None;
    for method in ["none", "shadow-volumes", "shadow-map"] {
        let replies = ask(
            &mut session,
            json!({"type": "set", "id": 2, "choices": {"shadows": method}}),
        );
        let (header, pixels) = one(&replies, "frame");
        assert_eq!(header["method"], method);
        assert_eq!(
            (header["width"].as_u64(), header["height"].as_u64()),
            (Some(48), Some(40))
        );
        assert_eq!(pixels.len(), 48 * 40 * 4);
        // The RGBA bytes are the PNG output's sRGB bytes.
        let image = rendered(method, &[]);
        let srgb = image.to_srgb8(1.0);
        let rgb: Vec<u8> = pixels.chunks(4).flat_map(|p| p[..3].to_vec()).collect();
        same(&rgb, &srgb, &format!("{method}: the frame's bytes"));
        let (_, values) = exported(&mut session, "image");
        let expected: Vec<f32> = image.pixels.iter().flat_map(|p| p.to_array()).collect();
        same(
            &values,
            &expected,
            &format!("{method}: the exported radiance"),
        );
        if let Some(p) = &previous {
            assert!(p != &pixels, "{method} changed nothing");
        }
        previous = Some(pixels);
    }
}

#[test]
fn a_moved_light_and_a_turned_camera_change_the_frame_as_the_library_does() {
    let mut session = opened("cornell-box-point", &BOX);
    ask(
        &mut session,
        json!({"type": "set", "id": 2, "choices": {"shadows": "shadow-volumes"}}),
    );
    let scene = load_scene("cornell-box-point", &[]).unwrap();
    let lumiere::Light::Point(light) = &scene.lights[0] else {
        panic!("a point light")
    };
    let offset = [60.0, -40.0, 30.0];
    let replies = ask(
        &mut session,
        json!({"type": "set", "id": 3, "lights": [offset]}),
    );
    one(&replies, "frame");
    let moved = light.position + glam::DVec3::from_array(offset);
    let expected = rendered(
        "shadow-volumes",
        &[format!(
            "lights.0.position=[{}, {}, {}]",
            moved.x, moved.y, moved.z
        )],
    );
    let (_, values) = exported(&mut session, "image");
    let expected: Vec<f32> = expected.pixels.iter().flat_map(|p| p.to_array()).collect();
    same(&values, &expected, "the moved light's frame");
    // A quarter turn about the target: the eye goes round, the frame changes.
    let opened = ask(
        &mut session,
        json!({"type": "open", "id": 4, "scene": "cornell-box-point", "sets": BOX}),
    );
    let (scene_reply, _) = one(&opened, "scene");
    let orbit = &scene_reply["orbit"];
    let (_, before) = one(&opened, "frame");
    let replies = ask(
        &mut session,
        json!({"type": "set", "id": 5, "orbit": {"yaw": 0.5, "pitch": orbit["pitch"], "distance": orbit["distance"]}}),
    );
    let (_, after) = one(&replies, "frame");
    assert!(before != after, "the turn changed nothing");
}

#[test]
fn the_split_view_measures_two_methods_and_their_difference() {
    let mut session = opened("cornell-box-point", &BOX);
    // Two exact methods: no pixel differs, the difference is black.
    let replies = ask(
        &mut session,
        json!({"type": "set", "id": 2, "choices": {"shadows": "scanline"}, "split": "shadow-volumes", "difference": true}),
    );
    let (header, pixels) = one(&replies, "frame");
    assert_eq!(header["split"]["differing"], 0.0, "{header}");
    assert!(pixels.chunks(4).all(|p| p[..3] == [0, 0, 0]));
    // Against no shadows the shadows differ.
    let replies = ask(
        &mut session,
        json!({"type": "set", "id": 3, "split": "none", "difference": false}),
    );
    let (header, pixels) = one(&replies, "frame");
    assert!(
        header["split"]["differing"].as_f64().unwrap() > 0.05,
        "{header}"
    );
    // Left half scan-line shadows, right half none.
    let left = rendered("scanline", &[]).to_srgb8(1.0);
    let right = rendered("none", &[]).to_srgb8(1.0);
    for y in 0..40 {
        for x in [3, 20, 30, 44] {
            let i = y * 48 + x;
            let expected = if x < 24 { &left } else { &right };
            assert_eq!(
                pixels[i * 4..i * 4 + 3],
                expected[i * 3..i * 3 + 3],
                "({x}, {y})"
            );
        }
    }
}

#[test]
fn buffers_come_with_a_legend_and_export_unrounded() {
    let mut session = opened("cornell-box-point", &BOX);
    let replies = ask(
        &mut session,
        json!({"type": "set", "id": 2, "choices": {"shadows": "shadow-volumes"}}),
    );
    let (header, _) = one(&replies, "frame");
    let buffers: Vec<&str> = header["buffers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b.as_str().unwrap())
        .collect();
    assert!(
        buffers.contains(&"visibility-0") && buffers.contains(&"depth"),
        "{buffers:?}"
    );
    let replies = ask(
        &mut session,
        json!({"type": "set", "id": 3, "buffer": "depth"}),
    );
    let (header, _) = one(&replies, "frame");
    assert_eq!(header["buffer"]["name"], "depth");
    assert!(
        header["buffer"]["legend"]
            .as_str()
            .unwrap()
            .starts_with("black "),
        "{header}"
    );
    let frame = Renderer::new(
        load_scene(
            "cornell-box-point",
            &[
                BOX[0].into(),
                BOX[1].into(),
                "shadows.method=\"shadow-volumes\"".into(),
            ],
        )
        .unwrap(),
    )
    .render_with_buffers(&["visibility-0".into()])
    .unwrap();
    let lumiere::BufferData::Values { data, .. } = &frame.buffer("visibility-0").unwrap().data
    else {
        panic!("visibility holds values")
    };
    let (header, values) = exported(&mut session, "visibility-0");
    assert_eq!(header["channels"], 1);
    same(&values, data, "the visibility buffer");
    // Back to the image.
    let replies = ask(
        &mut session,
        json!({"type": "set", "id": 4, "buffer": null}),
    );
    assert!(one(&replies, "frame").0["buffer"].is_null());
}

#[test]
fn preview_frames_take_one_sample_a_pixel() {
    let sets = [
        "camera.width=32",
        "camera.height=32",
        "render.supersample=3",
        "shadows.method=\"ray-cast\"",
    ];
    let mut session = opened("cornell-box-point", &sets);
    let replies = ask(
        &mut session,
        json!({"type": "set", "id": 2, "quality": "preview"}),
    );
    let (header, pixels) = one(&replies, "frame");
    assert_eq!(header["quality"], "preview");
    let mut one_sample: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    one_sample.push("render.supersample=1".into());
    let expected = Renderer::new(load_scene("cornell-box-point", &one_sample).unwrap())
        .render()
        .unwrap();
    let rgb: Vec<u8> = pixels.chunks(4).flat_map(|p| p[..3].to_vec()).collect();
    same(&rgb, &expected.to_srgb8(1.0), "the preview frame");
    let replies = ask(
        &mut session,
        json!({"type": "set", "id": 3, "quality": "full"}),
    );
    let (_, full) = one(&replies, "frame");
    assert_ne!(
        full, pixels,
        "nine samples a pixel differ from one at the edges"
    );
}

#[test]
fn shooting_brightens_step_by_step_and_ends_as_render_does() {
    let sets = [
        "camera.width=40",
        "camera.height=40",
        "radiosity.solver=\"shooting\"",
    ];
    let mut session = Session::new();
    let replies = ask(
        &mut session,
        json!({"type": "open", "id": 1, "scene": "radiosity-shooting", "sets": sets}),
    );
    let (scene, _) = one(&replies, "scene");
    assert_eq!(scene["families"][0]["name"], "solver", "{scene}");
    let (first, _) = one(&replies, "frame");
    assert!(first["solving"].as_bool().unwrap());
    let replies = ask(
        &mut session,
        json!({"type": "solve", "id": 2, "action": "pause"}),
    );
    let (paused, _) = one(&replies, "frame");
    assert!(!paused["solving"].as_bool().unwrap(), "{paused}");
    assert!(session.tick().is_empty(), "paused, no step is taken");
    let steps = |h: &Value| -> u64 {
        let status = h["status"].as_str().unwrap();
        status
            .split("step ")
            .nth(1)
            .unwrap()
            .split(',')
            .next()
            .unwrap()
            .parse()
            .unwrap()
    };
    let before = steps(&paused);
    let replies = ask(
        &mut session,
        json!({"type": "solve", "id": 3, "action": "step"}),
    );
    let (stepped, _) = one(&replies, "frame");
    assert_eq!(steps(&stepped), before + 1, "{stepped}");
    ask(
        &mut session,
        json!({"type": "solve", "id": 4, "action": "resume"}),
    );
    let mut last = None;
    while session.busy() {
        last = Some(session.tick());
    }
    let last = last.expect("the solve went on");
    let (end, _) = one(&decoded(&last), "frame");
    assert!(end["status"].as_str().unwrap().ends_with("done"), "{end}");
    let (_, values) = exported(&mut session, "image");
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let expected = Renderer::new(load_scene("radiosity-shooting", &sets).unwrap())
        .render()
        .unwrap();
    let expected: Vec<f32> = expected.pixels.iter().flat_map(|p| p.to_array()).collect();
    let brightest = expected.iter().fold(0f32, |m, v| m.max(*v));
    let worst = values
        .iter()
        .zip(&expected)
        .map(|(a, b)| (a - b).abs())
        .fold(0f32, f32::max);
    assert!(
        worst <= 1e-5 * brightest,
        "the solve's end differs from render by {worst}"
    );
}

#[test]
fn a_bad_message_gets_one_error_and_the_session_goes_on() {
    let mut session = Session::new();
    let cases: Vec<(String, &str)> = vec![
        ("not json".into(), "not JSON"),
        (json!({"id": 1}).to_string(), "no type"),
        (json!({"type": "warp", "id": 2}).to_string(), "`warp`"),
        (
            json!({"type": "set", "id": 3}).to_string(),
            "no scene is open",
        ),
        (
            json!({"type": "export", "id": 4, "what": "image"}).to_string(),
            "no scene is open",
        ),
        (
            json!({"type": "open", "id": 5, "scene": "no-such-entry"}).to_string(),
            "not a catalogue entry",
        ),
        (
            json!({"type": "open", "id": 6, "scene": "/etc/passwd"}).to_string(),
            "not a catalogue entry",
        ),
        (
            json!({"type": "set", "id": 7, "orbit": {"yaw": "left"}}).to_string(),
            "`set`",
        ),
    ];
    for (message, said) in &cases {
        let replies: Vec<_> = decoded(&session.handle_text(message));
        let line = error(&replies);
        assert!(line.contains(said), "{message}: {line}");
        assert!(!line.contains('\n'), "one line: {line}");
    }
    let oversized = " ".repeat(lumiere::viewer::MAX_MESSAGE + 1);
    let line = error(&decoded(&session.handle_text(&oversized)));
    assert!(line.contains("MiB"), "{line}");
    for bytes in [
        &[1u8, 0][..],
        &[200, 0, 0, 0, b'{'][..],
        &[1, 0, 0, 0, b'x'][..],
    ] {
        let replies: Vec<_> = ask_binary(&mut session, bytes);
        assert!(error(&replies).contains("binary message"), "{bytes:?}");
    }
    // The session still opens, and refuses what the scene lacks, in one line each.
    let mut session = opened("cornell-box-point", &BOX);
    let refusals = [
        (
            json!({"type": "set", "id": 8, "choices": {"warp": "x"}}),
            "no family `warp`",
        ),
        (
            json!({"type": "set", "id": 9, "choices": {"shadows": "magic"}}),
            "no option `magic`",
        ),
        (
            json!({"type": "set", "id": 10, "lights": [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]}),
            "1 lights, 2 offsets",
        ),
        (
            json!({"type": "set", "id": 11, "exposure": -1.0}),
            "exposure",
        ),
        (
            json!({"type": "set", "id": 12, "buffer": "no-such-buffer"}),
            "no-such-buffer",
        ),
        (
            json!({"type": "solve", "id": 13, "action": "step"}),
            "no shooting solve",
        ),
        (
            json!({"type": "export", "id": 14, "what": "nothing"}),
            "nothing",
        ),
    ];
    for (message, said) in refusals {
        let replies = ask(&mut session, message.clone());
        let line = error(&replies);
        assert_eq!(replies[0].0["id"], message["id"]);
        assert!(line.contains(said), "{message}: {line}");
        ask(
            &mut session,
            json!({"type": "set", "id": 20, "buffer": null}),
        );
    }
    let replies = ask(
        &mut session,
        json!({"type": "set", "id": 21, "choices": {"shadows": "ray-cast"}}),
    );
    one(&replies, "frame");
}

/// A binary `open-files` message of `files`.
pub fn open_files(main: &str, files: &[(&str, &[u8])], sets: &[&str]) -> Vec<u8> {
    let header = json!({
        "type": "open-files", "id": 1, "main": main, "sets": sets,
        "files": files.iter().map(|(n, b)| json!({"name": n, "size": b.len()})).collect::<Vec<_>>(),
    })
    .to_string();
    let mut bytes = (header.len() as u32).to_le_bytes().to_vec();
    bytes.extend_from_slice(header.as_bytes());
    for (_, b) in files {
        bytes.extend_from_slice(b);
    }
    bytes
}

#[test]
fn scenes_open_from_files_sent_as_bytes() {
    let obj = b"mtllib box.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl red\nf 1 2 3 4\n";
    let mtl = b"newmtl red\nKd 0.8 0.1 0.1\n";
    let mut session = Session::new();
    let message = open_files(
        "model/box.obj",
        &[("model/box.obj", obj), ("model/box.mtl", mtl)],
        &["camera.width=32", "camera.height=32"],
    );
    let replies: Vec<_> = ask_binary(&mut session, &message);
    let (scene, _) = one(&replies, "scene");
    assert_eq!(scene["title"], "model/box.obj");
    let (_, pixels) = one(&replies, "frame");
    // The red quad faces the camera and its light: red in the middle.
    let centre = (16 * 32 + 16) * 4;
    assert!(
        pixels[centre] > 2 * pixels[centre + 1] && pixels[centre] > 20,
        "{:?}",
        &pixels[centre..centre + 4]
    );
    // A TOML scene and the OBJ it names.
    let toml = br#"extends = "cornell-box-point"
[camera]
width = 24
height = 24
[[objects]]
shape = "obj"
name = "extra"
file = "box.obj"
transform = [{ scale = 100.0 }]
"#;
    let message = open_files(
        "scene.toml",
        &[("scene.toml", toml), ("box.obj", obj), ("box.mtl", mtl)],
        &[],
    );
    let replies: Vec<_> = ask_binary(&mut session, &message);
    assert_eq!(one(&replies, "frame").0["width"], 24);
    // A scene naming a file it was not sent: the scene's own one-line error.
    let message = open_files("scene.toml", &[("scene.toml", toml)], &[]);
    let replies: Vec<_> = ask_binary(&mut session, &message);
    assert!(
        error(&replies).contains("box.obj"),
        "{:?}",
        headers(&replies)
    );
    // Sizes that do not add up.
    let mut message = open_files("box.obj", &[("box.obj", obj)], &[]);
    message.pop();
    let replies: Vec<_> = ask_binary(&mut session, &message);
    assert!(
        error(&replies).contains("add up"),
        "{:?}",
        headers(&replies)
    );
}

#[test]
fn every_family_a_scene_offers_is_switched() {
    // Texture filters, environment layouts, global methods: Rushmeier &
    // Torrance's extension of the two-pass method draws a scene without panes as
    // the two-pass method does.
    for (entry, family, other, changes) in [
        ("mip-mapping", "filter", "summed-area", true),
        ("reflection-mapping-lat-long", "environment", "cube", true),
        ("two-pass", "global", "rushmeier-torrance", false),
    ] {
        let mut session = Session::new();
        let sets = ["camera.width=32", "camera.height=24"];
        let replies = ask(
            &mut session,
            json!({"type": "open", "id": 1, "scene": entry, "sets": sets}),
        );
        let (scene, _) = one(&replies, "scene");
        let (_, first) = one(&replies, "frame");
        let families = scene["families"].as_array().unwrap();
        let offered = families
            .iter()
            .find(|f| f["name"] == family)
            .unwrap_or_else(|| panic!("{entry}: {scene}"));
        assert_ne!(offered["chosen"], other);
        let options = offered["options"].as_array().unwrap();
        assert!(options.iter().any(|o| o["name"] == other), "{offered}");
        let replies = ask(
            &mut session,
            json!({"type": "set", "id": 2, "choices": {family: other}}),
        );
        let (header, pixels) = one(&replies, "frame");
        assert_eq!(pixels != first, changes, "{entry}: {family} {other}");
        if family == scene["families"][0]["name"] {
            assert_eq!(header["method"], other);
        }
    }
}

#[test]
fn a_gltf_scene_sent_as_bytes_draws_as_the_library_reads_it_from_disk() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("box.gltf");
    let sets: Vec<String> = BOX.iter().map(|s| s.to_string()).collect();
    let scene = load_scene("cornell-box-point", &sets).unwrap();
    let options = lumiere::export::Options {
        format: lumiere::export::Format::Gltf,
        spp: 1,
        integrator: None,
        area_samples: 1,
    };
    lumiere::export::export(&scene, &options, &path).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    let mut session = Session::new();
    let replies = ask_binary(
        &mut session,
        &open_files("box.gltf", &[("box.gltf", &bytes)], &BOX),
    );
    one(&replies, "scene");
    let (_, values) = exported(&mut session, "image");
    let from_disk = Renderer::new(load_scene(path.to_str().unwrap(), &sets).unwrap())
        .render()
        .unwrap();
    let expected: Vec<f32> = from_disk.pixels.iter().flat_map(|p| p.to_array()).collect();
    same(&values, &expected, "the glTF scene's image");
    assert!(expected.iter().any(|v| *v > 0.0), "the glTF scene is lit");
}

#[test]
fn every_option_offered_renders_and_those_the_renderer_refuses_are_not_offered() {
    // Refused, so not offered: the two-pass method on glass (transmission is
    // Rushmeier & Torrance's), ray tracing where global.window_depth is set (a
    // two-pass setting it would ignore).
    let mut offered_globals = Vec::new();
    for entry in [
        "ray-tracing",
        "ray-tracing-cornell",
        "two-pass",
        "light-volumes-spot",
    ] {
        let mut session = Session::new();
        let sets = ["camera.width=16", "camera.height=12"];
        let replies = ask(
            &mut session,
            json!({"type": "open", "id": 1, "scene": entry, "sets": sets}),
        );
        let (scene, _) = one(&replies, "scene");
        for family in scene["families"].as_array().unwrap() {
            let name = family["name"].as_str().unwrap();
            for option in family["options"].as_array().unwrap() {
                if name == "global" {
                    offered_globals.push(format!("{entry}: {}", option["name"]));
                }
                let replies = ask(
                    &mut session,
                    json!({"type": "set", "id": 2, "choices": {name: option["name"]}}),
                );
                assert!(
                    replies.iter().all(|r| r.0["type"] != "error"),
                    "{entry}: {name} {}: {:?}",
                    option["name"],
                    headers(&replies)
                );
                one(&replies, "frame");
            }
        }
    }
    let offered = |text: &str| offered_globals.iter().any(|o| o == text);
    for (option, expected) in [
        ("ray-tracing-cornell: \"two-pass\"", false),
        ("two-pass: \"ray-tracing\"", false),
        ("two-pass: \"rushmeier-torrance\"", true),
    ] {
        assert_eq!(offered(option), expected, "{option} in {offered_globals:?}");
    }
}
