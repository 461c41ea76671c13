//! The static site's viewer: the library compiled to WebAssembly (built by
//! tools/build-web.sh, which installs its toolchain when missing), served by a
//! plain static server on 127.0.0.1, in headless Chromium. The page behaves as it
//! does against the native server; the exact hard-shadow methods give visibility
//! buffers identical to the native library's and images within 1e-5 of the
//! brightest pixel; every catalogue entry renders in the page.

use super::page::check_page;
use super::server::Server;
use crate::support::browser::{Browser, StaticServer, static_viewer};
use lumiere::{BufferData, Renderer, load_scene};
use serde_json::{Value, json};

#[test]
#[cfg_attr(
    skip_system_tests,
    ignore = "needs Chromium and the WebAssembly toolchain (LUMIERE_SKIP_SYSTEM_TESTS)"
)]
fn the_static_page_shows_and_follows_the_webassembly_engine() {
    let server = StaticServer::start(static_viewer());
    let mut browser = Browser::start();
    let sets = "camera.width%3D96,camera.height%3D96,shadows.method%3D%22scanline%22";
    check_page(
        &mut browser,
        &server.url(&format!("index.html?scene=cornell-box-point&sets={sets}")),
    );
    assert_eq!(browser.evaluate("lumiere.state().engine"), json!("worker"));
}

/// The floats of an export the page asks its engine for.
fn exported(browser: &mut Browser, what: &str) -> Vec<f32> {
    let values = browser.evaluate(&format!(
        "lumiere.send({{type: 'export', what: '{what}'}}).then(rs => {{ \
           const r = rs[rs.length - 1]; if (!r.header) throw new Error(r.message); \
           return Array.from(new Float32Array(r.payload.slice().buffer)); }})"
    ));
    values
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap() as f32)
        .collect()
}

#[test]
#[cfg_attr(
    skip_system_tests,
    ignore = "needs Chromium and the WebAssembly toolchain (LUMIERE_SKIP_SYSTEM_TESTS)"
)]
fn exact_hard_shadows_in_webassembly_equal_the_native_library() {
    let server = StaticServer::start(static_viewer());
    let mut browser = Browser::start();
    let size = ["camera.width=64", "camera.height=64"];
    browser.open(
        &server.url("index.html?scene=cornell-box-point&sets=camera.width%3D64,camera.height%3D64"),
    );
    assert_eq!(
        browser.evaluate("lumiere.ready.then(() => true)"),
        json!(true)
    );
    for method in [
        "ray-cast",
        "scanline",
        "shadow-polygons",
        "shadow-volumes",
        "stencil-shadow-volumes",
    ] {
        browser.evaluate(&format!("lumiere.choose('shadows', '{method}')"));
        let mut sets: Vec<String> = size.iter().map(|s| s.to_string()).collect();
        sets.push(format!("shadows.method=\"{method}\""));
        let native = Renderer::new(load_scene("cornell-box-point", &sets).unwrap())
            .render_with_buffers(&["visibility-0".to_string()])
            .unwrap();
        let BufferData::Values { data, .. } = &native.buffer("visibility-0").unwrap().data else {
            panic!("visibility holds values")
        };
        let visibility = exported(&mut browser, "visibility-0");
        assert!(
            visibility
                .iter()
                .map(|v| v.to_bits())
                .eq(data.iter().map(|v| v.to_bits())),
            "{method}: the visibility buffers differ"
        );
        let image = exported(&mut browser, "image");
        let expected: Vec<f32> = native
            .image
            .pixels
            .iter()
            .flat_map(|p| p.to_array())
            .collect();
        let brightest = expected.iter().fold(0f32, |m, v| m.max(*v));
        let worst = image
            .iter()
            .zip(&expected)
            .map(|(a, b)| (a - b).abs())
            .fold(0f32, f32::max);
        assert_eq!(image.len(), expected.len());
        let differing = image.iter().zip(&expected).filter(|(a, b)| a != b).count();
        eprintln!(
            "{method}: {differing} of {} channels differ from native, by at most {worst}",
            image.len()
        );
        assert!(
            worst <= 1e-5 * brightest,
            "{method}: {worst} off, brightest {brightest}"
        );
    }
    assert!(browser.errors().is_empty(), "{:?}", browser.errors());
}

/// Opens every catalogue entry in the page at 24 x 24: each gives a frame.
fn every_entry_renders(browser: &mut Browser) {
    let ids = lumiere::catalogue::ids();
    assert!(ids.len() >= 60, "{} entries", ids.len());
    for id in ids {
        let said: Value = browser.evaluate(&format!(
            "lumiere.open('{id}', ['camera.width=24', 'camera.height=24']).then(f => [f.header.width, f.header.height], e => String(e))"
        ));
        assert_eq!(said, json!([24, 24]), "{id}");
    }
    assert!(browser.errors().is_empty(), "{:?}", browser.errors());
}

#[test]
#[cfg_attr(
    skip_system_tests,
    ignore = "needs Chromium and the WebAssembly toolchain (LUMIERE_SKIP_SYSTEM_TESTS)"
)]
fn every_catalogue_entry_renders_in_the_static_page() {
    let server = StaticServer::start(static_viewer());
    let mut browser = Browser::start();
    browser.open(
        &server.url("index.html?scene=cornell-box-point&sets=camera.width%3D24,camera.height%3D24"),
    );
    assert_eq!(
        browser.evaluate("lumiere.ready.then(() => true)"),
        json!(true)
    );
    every_entry_renders(&mut browser);
}

#[test]
#[cfg_attr(
    skip_system_tests,
    ignore = "needs Chromium (LUMIERE_SKIP_SYSTEM_TESTS)"
)]
fn every_catalogue_entry_renders_in_the_page_served_natively() {
    let server = Server::start(&["cornell-box-point", "--width", "24", "--height", "24"]);
    let mut browser = Browser::start();
    browser.open(&server.url);
    assert_eq!(
        browser.evaluate("lumiere.ready.then(() => true)"),
        json!(true)
    );
    every_entry_renders(&mut browser);
}
