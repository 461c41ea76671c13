//! What the checks share: the binary launcher (`binary`), scene builders, the
//! headless browser (`browser`), FLIP (`flip`) and the peers (`peers`).

mod binary;
pub mod browser;
pub mod flip;
pub mod peers;

pub use binary::*;

use glam::{DVec2, DVec3};
use lumiere::raster::{ScreenPolygon, View};
use lumiere::scene::{Camera, Vertex};

/// A camera at the origin looking down −z: world (x, y, −d) is eye (x, y, d).
pub fn origin_view(width: u32, height: u32) -> View {
    let camera = Camera {
        eye: DVec3::ZERO,
        look_at: DVec3::NEG_Z,
        up: DVec3::Y,
        fov_y: 60.0,
        width,
        height,
        near: 0.01,
    };
    View::new(&camera, width, height)
}

pub fn vertex(p: DVec3) -> Vertex {
    Vertex {
        position: p,
        normal: DVec3::Z,
        uv: DVec2::ZERO,
    }
}

/// The screen polygon of world points seen by `view` (None if out of view).
pub fn screen_polygon(view: &View, id: u32, points: &[DVec3]) -> Option<ScreenPolygon> {
    ScreenPolygon::from_points(view, id, points)
}

/// An error and its causes on one line, joined by ": " (as the command line prints
/// them).
pub fn error_line(e: &dyn std::error::Error) -> String {
    let mut line = e.to_string();
    let mut cause = e.source();
    while let Some(c) = cause {
        line += &format!(": {c}");
        cause = c.source();
    }
    line
}

/// A scene file's `[camera]` table: the eye, the point it looks at, the vertical
/// field of view in degrees and the image's size; a blank line after it.
pub fn camera(eye: [f64; 3], look_at: [f64; 3], fov_y: f64, width: u32, height: u32) -> String {
    format!(
        "[camera]\neye = {eye:?}\nlook_at = {look_at:?}\nfov_y = {fov_y:?}\nwidth = {width}\nheight = {height}\n\n"
    )
}

/// The `[camera]` table of `camera` with `extra` lines (each `key = value`) before its blank line.
pub fn camera_with(
    eye: [f64; 3],
    look_at: [f64; 3],
    fov_y: f64,
    width: u32,
    height: u32,
    extra: &str,
) -> String {
    let mut table = camera(eye, look_at, fov_y, width, height);
    table.pop();
    for line in extra.lines() {
        table += line;
        table.push('\n');
    }
    table.push('\n');
    table
}

/// The scene rendered, or a panic with the library's one-line message.
pub fn render(scene: &lumiere::Scene) -> lumiere::Image {
    lumiere::render(scene).unwrap_or_else(|e| panic!("{}", e.line()))
}

/// Files held in memory, as a scene's directory.
#[allow(unused_imports)]
pub use lumiere::scene::resources::InMemory as Files;

/// A scene written to a temporary file and loaded from it, with `--set` overrides
/// (the path a scene file takes, with its relative paths and messages).
pub fn scene_from_text(text: &str, sets: &[String]) -> lumiere::Scene {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, text).unwrap();
    lumiere::load_scene(path.to_str().unwrap(), sets)
        .unwrap_or_else(|e| panic!("{}", error_line(&e)))
}

/// A scene-file polygon object whose vertices are ordered so that its normal is
/// `facing`.
pub fn polygon(name: &str, material: &str, corners: [DVec3; 4], facing: DVec3) -> String {
    let mut c = corners.to_vec();
    let normal = (c[1] - c[0]).cross(c[2] - c[1]);
    if normal.dot(facing) < 0.0 {
        c.reverse();
    }
    let list: Vec<String> = c
        .iter()
        .map(|p| format!("[{}, {}, {}]", p.x, p.y, p.z))
        .collect();
    format!(
        "[[objects]]\nshape = \"polygon\"\nname = \"{name}\"\nmaterial = \"{material}\"\nvertices = [{}]\n\n",
        list.join(", ")
    )
}

/// The six walls of the unit cube [0, 1]³ as scene-file polygons of `material`,
/// facing in (named low0, high0, low1, …).
pub fn unit_cube_walls(material: &str) -> String {
    let mut text = String::new();
    for axis in 0..3 {
        let corner = |u: f64, v: f64, at: f64| {
            let mut p = [0.0; 3];
            p[(axis + 1) % 3] = u;
            p[(axis + 2) % 3] = v;
            p[axis] = at;
            DVec3::from_array(p)
        };
        let mut inward = DVec3::ZERO;
        inward[axis] = 1.0;
        for (name, at, facing) in [("low", 0.0, inward), ("high", 1.0, -inward)] {
            let corners = [
                corner(0.0, 0.0, at),
                corner(1.0, 0.0, at),
                corner(1.0, 1.0, at),
                corner(0.0, 1.0, at),
            ];
            text += &polygon(&format!("{name}{axis}"), material, corners, facing);
        }
    }
    text
}
