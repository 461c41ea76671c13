//! A scene's frame on the sample grid: its view and its polygons on the screen.

use super::{ScreenPolygon, ToPrepare, View, prepare};
use crate::scene::Scene;

/// The view of the scene's sample grid (pixels × supersample along each axis).
pub fn sample_view(scene: &Scene) -> View {
    let n = scene.render.supersample;
    View::new(
        &scene.camera,
        scene.camera.width * n,
        scene.camera.height * n,
    )
}

/// The scene's polygons on `view`'s screen, without vertex colours (passes that need
/// only coverage and depth: shadow maps, benchmarks).
pub fn screen_polygons(scene: &Scene, view: &View) -> Vec<ScreenPolygon> {
    prepare(
        view,
        scene.polygons.iter().enumerate().map(|(id, p)| ToPrepare {
            id: id as u32,
            element: id as u32,
            vertices: &p.vertices,
            colors: &[],
            affine_uv: false,
        }),
    )
}
