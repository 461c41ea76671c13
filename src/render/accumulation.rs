//! A frame averaged from several frames, each with its projection shifted by a
//! fraction of a pixel: the accumulation buffer of P. Haeberli & K. Akeley, "The
//! accumulation buffer: hardware support for high-quality rendering", Computer
//! Graphics (SIGGRAPH '90) 24(4):309-318, 1990. Their antialiasing renders the scene
//! once per sample position, the viewing transformation translated by the sample's
//! sub-pixel offset, adds each image into the accumulation buffer and divides by the
//! count.
//!
//! The sample positions are ours to choose (the paper leaves the pattern open and
//! shows several): N² samples on a rotated grid, sample (a, b) at
//! ((aN + b + ½)/N², (bN + a + ½)/N²) of the pixel. It is N-rooks: each of the N²
//! columns and N² rows of sub-pixel cells holds one sample, so an edge near the
//! horizontal or the vertical is seen at N² + 1 levels of coverage where the regular
//! N × N grid gives N + 1.

use super::frame::{Pass, render_pass};
use super::output::Frame;
use super::plan::FramePlan;
use crate::error::Result;
use crate::image_io::Image;
use crate::scene::Scene;
use glam::{DVec2, Vec3};

/// The rotated grid of `n`² samples: each sample's offset from the pixel's centre, in
/// pixels (each coordinate in (−½, ½)), in the order the frames are made.
pub(super) fn rotated_grid(n: u32) -> Vec<DVec2> {
    let cells = f64::from(n * n);
    (0..n)
        .flat_map(|a| (0..n).map(move |b| (a, b)))
        .map(|(a, b)| {
            let x = (f64::from(a * n + b) + 0.5) / cells;
            let y = (f64::from(b * n + a) + 0.5) / cells;
            DVec2::new(x - 0.5, y - 0.5)
        })
        .collect()
}

/// `scene`'s frame with its `render.supersample`² samples a pixel on the rotated
/// grid: one frame of one sample a pixel per sample, averaged in the order made.
pub(super) fn render_rotated_grid(scene: &Scene, plan: &FramePlan) -> Result<Frame> {
    let offsets = rotated_grid(scene.render.supersample);
    // The passes are frames of one sample a pixel, and everything a frame sizes (its
    // view, bands, buffers) reads that from the scene: one copy of the scene a frame.
    let mut single = scene.clone();
    single.render.supersample = 1;
    let mut sum: Vec<[f64; 3]> = Vec::new();
    for (number, &shift) in offsets.iter().enumerate() {
        let pass = Pass {
            shift,
            number,
            of: offsets.len(),
        };
        let frame = render_pass(&single, plan, &[], pass)?;
        sum.resize(frame.image.pixels.len(), [0.0; 3]);
        for (s, p) in sum.iter_mut().zip(&frame.image.pixels) {
            s[0] += f64::from(p.x);
            s[1] += f64::from(p.y);
            s[2] += f64::from(p.z);
        }
    }
    let count = offsets.len() as f64;
    let pixels = sum
        .iter()
        .map(|s| {
            Vec3::new(
                (s[0] / count) as f32,
                (s[1] / count) as f32,
                (s[2] / count) as f32,
            )
        })
        .collect();
    Ok(Frame {
        image: Image {
            width: scene.camera.width,
            height: scene.camera.height,
            pixels,
        },
        buffers: Vec::new(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rotated_grid_puts_one_sample_in_each_column_and_row_of_cells() {
        for n in 1..=16u32 {
            let cells = (n * n) as usize;
            let offsets = rotated_grid(n);
            assert_eq!(offsets.len(), cells);
            let mut columns = vec![0; cells];
            let mut rows = vec![0; cells];
            for o in &offsets {
                assert!(o.x.abs() < 0.5 && o.y.abs() < 0.5, "{o} outside the pixel");
                // The cell a sample lies in, and its centre there.
                let (x, y) = ((o.x + 0.5) * cells as f64, (o.y + 0.5) * cells as f64);
                assert!((x.fract() - 0.5).abs() < 1e-9 && (y.fract() - 0.5).abs() < 1e-9);
                columns[x as usize] += 1;
                rows[y as usize] += 1;
            }
            assert!(columns.iter().chain(&rows).all(|&c| c == 1), "n = {n}");
            // Centred on the pixel: the box filter's mean position is its centre.
            let mean = offsets.iter().sum::<DVec2>() / cells as f64;
            assert!(mean.length() < 1e-12, "n = {n}: mean {mean}");
        }
    }
}
