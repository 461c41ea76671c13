//! Moves a light through a `Renderer` and writes the frames: the renderer keeps its
//! view-independent work between frames and makes again only what a change
//! invalidates (here, the moved light's shadow map).
//!
//! `cargo run --release --example moving_light -- [DIR]` (default: moving-light/).

use lumiere::settings::ShadowMethod;
use lumiere::{Light, Renderer, load_scene, write_image};
use std::path::PathBuf;

const FRAMES: usize = 8;

fn main() -> lumiere::Result<()> {
    let dir = PathBuf::from(std::env::args().nth(1).unwrap_or("moving-light".into()));
    std::fs::create_dir_all(&dir).map_err(|e| lumiere::Error::Io {
        op: lumiere::FileOp::Write,
        path: dir.clone(),
        source: e,
    })?;

    // Williams's shadow map on the point-lit Cornell box, at 160 x 160.
    let sets = [
        "camera.width=160",
        "camera.height=160",
        "shadows.method=shadow-map",
    ];
    let scene = load_scene("cornell-box-point", &sets.map(String::from))?;
    assert_eq!(scene.shadows.method, ShadowMethod::ShadowMap);
    let exposure = scene.render.exposure;
    let Light::Point(start) = scene.lights[0].clone() else {
        panic!("the point-lit box's first light is a point light");
    };
    let mut renderer = Renderer::new(scene);

    for frame in 0..FRAMES {
        // A circle of radius 0.15 under the ceiling, around the light's first place.
        let angle = std::f64::consts::TAU * frame as f64 / FRAMES as f64;
        let mut light = start.clone();
        light.position += 0.15 * lumiere::glam::DVec3::new(angle.cos(), 0.0, angle.sin());
        renderer.set_light(0, Light::Point(light))?;
        let image = renderer.render()?;
        let path = dir.join(format!("frame-{frame:02}.png"));
        write_image(&image, &path, exposure)?;
        let built = renderer.prepasses();
        // One shadow map a light position: the camera's frames reuse it.
        println!(
            "{}: {} shadow maps made so far",
            path.display(),
            built.light_shadows
        );
    }
    Ok(())
}
