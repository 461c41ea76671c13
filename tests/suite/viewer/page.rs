//! The viewer page in headless Chromium, served by `lumiere view --no-open`: it
//! loads without a console error, the canvas shows the engine's frames (pixels
//! read back from the canvas), switching a method, moving the light, dragging the
//! view and splitting it change the pixels they should, and a scene that cannot
//! load shows the command line's one-line message in the page.

use super::server::Server;
use crate::support::browser::Browser;
use serde_json::{Value, json};

/// The canvas's pixels as the page shows them, summed and counted: a digest that
/// changes with any pixel.
const CANVAS: &str = "(() => { const c = document.getElementById('canvas'); \
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data; \
    let h = 0; for (let i = 0; i < d.length; i++) { h = (h * 31 + d[i]) >>> 0; } \
    return [c.width, c.height, h]; })()";

/// The same digest of the last frame the engine sent.
const FRAME: &str = "(() => { const d = lumiere.lastFrame().pixels; \
    let h = 0; for (let i = 0; i < d.length; i++) { h = (h * 31 + d[i]) >>> 0; } \
    const f = lumiere.lastFrame().header; return [f.width, f.height, h]; })()";

fn shown(browser: &mut Browser) -> Value {
    let canvas = browser.evaluate(CANVAS);
    assert_eq!(
        canvas,
        browser.evaluate(FRAME),
        "the canvas shows the last frame"
    );
    canvas
}

pub fn check_page(browser: &mut Browser, url: &str) {
    browser.open(url);
    assert_eq!(
        browser.evaluate("lumiere.ready.then(() => true)"),
        json!(true)
    );
    let first = shown(browser);
    assert_eq!(first[0], 96);
    // Another method: other pixels.
    browser.evaluate("lumiere.choose('shadows', 'none')");
    let unshadowed = shown(browser);
    assert_ne!(first, unshadowed, "switching the method changed nothing");
    browser.evaluate("lumiere.choose('shadows', 'scanline')");
    assert_eq!(
        shown(browser),
        first,
        "back to the first method, the first frame"
    );
    // The light moved: other shadows.
    browser.evaluate("lumiere.moveLight(0, [120, 0, 0])");
    let moved = shown(browser);
    assert_ne!(moved, first, "moving the light changed nothing");
    browser.evaluate("lumiere.moveLight(0, [-120, 0, 0])");
    assert_eq!(shown(browser), first, "the light back, the first frame");
    // Two exact methods split with their difference: black, and no pixel differs.
    browser.evaluate("lumiere.split('shadow-volumes', true)");
    let frame = browser.evaluate("lumiere.lastFrame().header.split.differing");
    assert_eq!(frame.as_f64(), Some(0.0), "{frame}");
    let black = browser
        .evaluate("Array.from(lumiere.lastFrame().pixels).every((v, i) => i % 4 == 3 || v == 0)");
    assert_eq!(
        black,
        json!(true),
        "the difference of two exact methods is black"
    );
    browser.evaluate("lumiere.split(null, false)");
    // A drag across the canvas turns the view.
    let centre = browser.evaluate(
        "(() => { const r = document.getElementById('canvas').getBoundingClientRect(); return [r.x + r.width / 2, r.y + r.height / 2]; })()",
    );
    let (x, y) = (centre[0].as_f64().unwrap(), centre[1].as_f64().unwrap());
    let frames = browser.evaluate("lumiere.frameCount").as_u64().unwrap();
    browser.call("Input.dispatchMouseEvent", json!({"type": "mousePressed", "x": x, "y": y, "button": "left", "buttons": 1, "clickCount": 1}));
    for k in 1..=5 {
        browser.call("Input.dispatchMouseEvent", json!({"type": "mouseMoved", "x": x + 20.0 * k as f64, "y": y, "button": "left", "buttons": 1}));
    }
    browser.call("Input.dispatchMouseEvent", json!({"type": "mouseReleased", "x": x + 100.0, "y": y, "button": "left", "buttons": 0, "clickCount": 1}));
    // Wait for the full frame that follows the drag.
    browser.evaluate(&format!(
        "new Promise(r => {{ const t = setInterval(() => {{ const f = lumiere.lastFrame().header; \
         if (lumiere.frameCount > {frames} && f.quality == 'full' && !lumiere.state().inFlight) {{ clearInterval(t); r(true); }} }}, 50); }})"
    ));
    let turned = shown(browser);
    assert_ne!(turned, first, "dragging did not turn the view");
    let yaw = browser
        .evaluate("lumiere.state().orbit.yaw")
        .as_f64()
        .unwrap();
    assert!(yaw.abs() > 0.1, "yaw {yaw}");
    // The keys of the window: a number chooses the method, s splits with the next,
    // d shows the difference, b the buffers.
    let key = |browser: &mut Browser, key: &str| {
        for kind in ["keyDown", "keyUp"] {
            browser.call(
                "Input.dispatchKeyEvent",
                json!({"type": kind, "key": key, "text": key}),
            );
        }
        browser.evaluate(
            "new Promise(r => { const t = setInterval(() => { \
               if (!lumiere.state().inFlight && !lumiere.state().pending) { clearInterval(t); r(true); } }, 20); })",
        );
    };
    let options = browser.evaluate("lumiere.state().scene.families[0].options.map(o => o.name)");
    key(browser, "2");
    assert_eq!(
        browser.evaluate("lumiere.lastFrame().header.method"),
        options[1]
    );
    key(browser, "s");
    assert_eq!(browser.evaluate("lumiere.state().split"), options[2]);
    key(browser, "d");
    assert_eq!(
        browser.evaluate("lumiere.lastFrame().header.split != null"),
        json!(true)
    );
    key(browser, "s");
    key(browser, "b");
    assert_eq!(
        browser.evaluate("lumiere.lastFrame().header.buffer.name"),
        browser.evaluate("lumiere.lastFrame().header.buffers[0]")
    );
    browser.evaluate("lumiere.buffer(null).then(() => lumiere.split(null, false))");
    // Two fingers moving apart on a touch screen zoom in.
    let distance = browser
        .evaluate("lumiere.state().orbit.distance")
        .as_f64()
        .unwrap();
    browser.call(
        "Emulation.setTouchEmulationEnabled",
        json!({"enabled": true, "maxTouchPoints": 2}),
    );
    let touch = |kind: &str, spread: f64| {
        json!({"type": kind, "touchPoints": if kind == "touchEnd" { json!([]) } else {
            json!([{"x": x - spread, "y": y, "id": 0}, {"x": x + spread, "y": y, "id": 1}]) }})
    };
    browser.call("Input.dispatchTouchEvent", touch("touchStart", 20.0));
    for k in 1..=4 {
        browser.call(
            "Input.dispatchTouchEvent",
            touch("touchMove", 20.0 + 20.0 * k as f64),
        );
    }
    browser.call("Input.dispatchTouchEvent", touch("touchEnd", 0.0));
    let pinched = browser
        .evaluate("lumiere.state().orbit.distance")
        .as_f64()
        .unwrap();
    assert!(
        pinched < 0.7 * distance,
        "a pinch from 40 to 200 px apart: distance {distance} -> {pinched}"
    );
    // A scene of the user's files (an OBJ and its MTL, as a file chooser gives them).
    let opened = browser.evaluate(
        "(() => { const t = s => new TextEncoder().encode(s); \
           return lumiere.openFiles([\
             {name: 'box.obj', bytes: t('mtllib box.mtl\\nv 0 0 0\\nv 1 0 0\\nv 1 1 0\\nv 0 1 0\\nusemtl red\\nf 1 2 3 4\\n')},\
             {name: 'box.mtl', bytes: t('newmtl red\\nKd 0.8 0.1 0.1\\n')}], undefined, ['camera.width=32', 'camera.height=32'])\
           .then(f => { const p = f.pixels, i = (16 * 32 + 16) * 4; return [f.header.width, p[i] > 2 * p[i + 1]]; }, e => String(e)); })()",
    );
    assert_eq!(opened, json!([32, true]), "the OBJ's red quad");
    // A scene that cannot load: the command line's line, in the page.
    let said =
        browser.evaluate("lumiere.open('no-such-entry', []).then(() => 'opened', e => String(e))");
    let banner = browser.evaluate("document.getElementById('error').textContent");
    let said = said.as_str().unwrap();
    assert!(said.contains("no-such-entry"), "{said}");
    assert!(
        banner
            .as_str()
            .unwrap()
            .contains(said.trim_start_matches("Error: ")),
        "{banner}"
    );
    assert!(
        browser.errors().is_empty(),
        "console errors: {:?}",
        browser.errors()
    );
}

#[test]
#[cfg_attr(
    skip_system_tests,
    ignore = "needs Chromium (LUMIERE_SKIP_SYSTEM_TESTS)"
)]
fn the_page_served_natively_shows_and_follows_the_engine() {
    let server = Server::start(&[
        "cornell-box-point",
        "--width",
        "96",
        "--height",
        "96",
        "--shadows",
        "scanline",
    ]);
    let mut browser = Browser::start();
    check_page(&mut browser, &server.url);
}
