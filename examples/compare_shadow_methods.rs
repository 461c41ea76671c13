//! Builds a scene in code (a floor and a ring of posts under a point light) and
//! compares two shadow methods sample by sample: Crow's shadow volumes, counted in
//! the scan-line pass, against Appel's shadow rays. Both are exact, so their
//! visibility buffers agree everywhere but where a sample lies on a shadow's edge.
//!
//! `cargo run --release --example compare_shadow_methods -- [OUT.png]`

use lumiere::settings::ShadowMethod;
use lumiere::{BufferData, Renderer, compare_images, scene_from_toml};
use std::fmt::Write as _;

/// The scene file's text: the posts are made by a loop, as any generated scene is.
fn ring_of_posts(posts: usize) -> String {
    let mut toml = String::from(
        r#"
[camera]
eye = [0.0, 4.0, 7.0]
look_at = [0.0, 0.3, 0.0]
up = [0.0, 1.0, 0.0]
fov_y = 45.0
width = 192
height = 144

[materials.floor]
diffuse = [0.7, 0.7, 0.7]

[materials.post]
diffuse = [0.6, 0.3, 0.2]

[[lights]]
type = "point"
position = [0.5, 3.0, 0.5]
intensity = [30.0, 30.0, 30.0]

[[objects]]
shape = "quad"
name = "floor"
material = "floor"
transform = [{ scale = 10.0 }]
"#,
    );
    for i in 0..posts {
        let angle = std::f64::consts::TAU * i as f64 / posts as f64;
        let (x, z) = (1.8 * angle.cos(), 1.8 * angle.sin());
        let _ = write!(
            toml,
            r#"
[[objects]]
shape = "box"
name = "post {i}"
material = "post"
transform = [{{ scale = [0.25, 1.2, 0.25] }}, {{ translate = [{x}, 0.6, {z}] }}]
"#
        );
    }
    toml
}

/// The light's visibility at every pixel of a frame under `method`.
fn visibility(renderer: &mut Renderer, method: ShadowMethod) -> lumiere::Result<Vec<f32>> {
    let mut shadows = renderer.scene().shadows.clone();
    shadows.method = method;
    renderer.set_shadows(shadows);
    let frame = renderer.render_with_buffers(&["visibility-0".to_string()])?;
    match &frame.buffer("visibility-0").expect("asked for").data {
        BufferData::Values { data, .. } => Ok(data.clone()),
        other => panic!("visibility is a fraction per pixel, not {other:?}"),
    }
}

fn main() -> lumiere::Result<()> {
    let scene = scene_from_toml(&ring_of_posts(8), &[])?;
    let mut renderer = Renderer::new(scene);

    let crow = visibility(&mut renderer, ShadowMethod::ShadowVolumes)?;
    let crow_image = renderer.render()?;
    let appel = visibility(&mut renderer, ShadowMethod::RayCast)?;
    let appel_image = renderer.render()?;
    if let Some(path) = std::env::args().nth(1) {
        lumiere::write_image(&appel_image, std::path::Path::new(&path), 1.0)?;
    }

    let differing = crow
        .iter()
        .zip(&appel)
        .filter(|(a, b)| (*a - *b).abs() > 1e-6)
        .count();
    let shadowed = appel.iter().filter(|v| **v < 0.5).count();
    let images = compare_images(&crow_image, &appel_image, 1.0)?;
    println!(
        "shadow volumes against ray casting: {differing} of {} pixels differ in visibility \
         ({shadowed} in shadow); images: RMSE {:.2e}, largest difference {}/255",
        crow.len(),
        images.rmse,
        images.max_difference
    );
    Ok(())
}
