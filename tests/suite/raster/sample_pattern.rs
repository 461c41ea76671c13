//! Where a pixel's samples lie: the regular grid and the rotated grid (the
//! accumulation buffer's shifted frames), checked by the coverage of an edge.

use lumiere::render::Renderer;
use lumiere::scene_from_toml;

/// An emitting polygon (radiance 1, nothing else lit) over the left of the image,
/// its right edge vertical at x = `edge` in the plane z = 0, seen from z = 1 with a
/// 90° field: an 8 × 4 image puts world x at pixel x 4 + 2x, so the edge crosses
/// pixel 4 at `2 edge` of its width.
fn edge_scene(edge: f64, pattern: &str) -> String {
    format!(
        r#"{}[render]
supersample = 4
sample_pattern = "{pattern}"

[materials.lamp]
diffuse = [0.0, 0.0, 0.0]
emission = [1.0, 1.0, 1.0]

[[objects]]
shape = "polygon"
material = "lamp"
vertices = [[-3.0, -3.0, 0.0], [{edge}, -3.0, 0.0], [{edge}, 3.0, 0.0], [-3.0, 3.0, 0.0]]
"#,
        crate::support::camera([0.0, 0.0, 1.0], [0.0, 0.0, 0.0], 90.0, 8, 4)
    )
}

/// Pixel (4, 1)'s radiance, and its neighbours' on the row.
fn pixels_across_the_edge(edge: f64, pattern: &str) -> [f32; 3] {
    let scene = scene_from_toml(&edge_scene(edge, pattern), &[]).unwrap();
    let image = Renderer::new(scene).render().unwrap();
    let at = |x: usize| image.pixels[8 + x].x;
    [at(3), at(4), at(5)]
}

/// The share of pixel 4 covered is f = (m + ½)/64 for m = 0..63 (never on a sample's
/// column, and between any two of a pattern shifted by a quarter of a cell). The regular 4 × 4 grid has its sample columns at (2j + 1)/8 of the
/// pixel: four levels. The rotated grid has one sample in each of the 16 columns,
/// at (2k + 1)/32: the pixel is k/16 covered where k counts the columns left of the
/// edge, seventeen levels.
#[test]
fn a_vertical_edge_is_seen_at_seventeen_levels_on_the_rotated_grid_and_five_on_the_regular() {
    let mut levels = (Vec::new(), Vec::new());
    for m in 0..64 {
        let f = (m as f64 + 0.5) / 64.0;
        let rotated = pixels_across_the_edge(f / 2.0, "rotated-grid");
        let regular = pixels_across_the_edge(f / 2.0, "regular");
        let columns_left = |count: u32| {
            (0..count)
                .filter(|&k| ((2 * k + 1) as f64) < f * (2 * count) as f64)
                .count()
        };
        let expected_rotated = columns_left(16) as f32 / 16.0;
        let expected_regular = columns_left(4) as f32 / 4.0;
        assert_eq!(
            rotated,
            [1.0, expected_rotated, 0.0],
            "rotated grid, f = {f}"
        );
        assert_eq!(
            regular,
            [1.0, expected_regular, 0.0],
            "regular grid, f = {f}"
        );
        levels.0.push(rotated[1].to_bits());
        levels.1.push(regular[1].to_bits());
    }
    for l in [&mut levels.0, &mut levels.1] {
        l.sort();
        l.dedup();
    }
    assert_eq!(levels.0.len(), 17);
    assert_eq!(levels.1.len(), 5);
}

#[test]
fn the_rotated_grid_gives_the_image_alone() {
    let scene = scene_from_toml(&edge_scene(0.1, "rotated-grid"), &[]).unwrap();
    let error = Renderer::new(scene)
        .render_with_buffers(&["depth".to_string()])
        .err()
        .expect("a buffer on the rotated grid");
    let message = error.to_string();
    assert!(
        message.starts_with("render.sample_pattern:") && message.contains("`depth`"),
        "{message}"
    );
}

#[test]
fn an_unknown_pattern_is_refused_naming_key_and_value() {
    let error =
        scene_from_toml(&edge_scene(0.1, "hexagonal"), &[]).expect_err("an unknown pattern");
    // The line the command line prints: the error and its sources.
    let mut message = error.to_string();
    let mut source = std::error::Error::source(&error);
    while let Some(s) = source {
        message += &format!(": {s}");
        source = s.source();
    }
    assert!(
        message.contains("render.sample_pattern") && message.contains("hexagonal"),
        "{message}"
    );
}
