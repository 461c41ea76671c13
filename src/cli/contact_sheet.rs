//! `lumiere contact-sheet`: every catalogue entry rendered small, in catalogue order
//! (topic by topic), each under its id: the README's picture of what lumiere does.

use super::bitmap_text::{self, for_each_lit_pixel};
use anyhow::{Context, Result};
use lumiere::catalogue::{self, Topic};
use lumiere::{Renderer, load_scene, write_atomically};
use std::path::PathBuf;

/// Render every catalogue entry small and tile them, each under its id, into one PNG.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The PNG written.
    #[arg(short, long)]
    output: PathBuf,
    /// Entries across.
    #[arg(long, default_value_t = 8, value_parser = clap::value_parser!(u32).range(1..=64))]
    columns: u32,
}

/// Each picture fits this box, its entry's aspect kept.
const CELL: (u32, u32) = (160, 120);
/// Two lines of text under each picture.
const LABEL: u32 = 3 + LINE + bitmap_text::HEIGHT as u32;
/// From one line of a label to the next.
const LINE: u32 = bitmap_text::HEIGHT as u32 + 1;
const GAP: u32 = 4;
const BACKGROUND: [u8; 3] = [24, 24, 28];
const INK: [u8; 3] = [225, 225, 230];

struct Picture {
    id: String,
    width: u32,
    height: u32,
    srgb: Vec<u8>,
}

pub fn run(args: Args) -> Result<()> {
    let mut entries = catalogue::entries()?;
    entries.sort_by_key(|e| {
        (
            Topic::ALL.iter().position(|t| *t == e.algorithm.topic),
            e.algorithm.year,
            e.algorithm.id.clone(),
        )
    });
    // One entry at a time, each rendered with every core.
    let pictures: Vec<Picture> = entries
        .iter()
        .map(|entry| {
            let a = &entry.algorithm;
            let scale = f64::min(
                CELL.0 as f64 / a.test_width as f64,
                CELL.1 as f64 / a.test_height as f64,
            );
            let (width, height) = (
                (a.test_width as f64 * scale).round() as u32,
                (a.test_height as f64 * scale).round() as u32,
            );
            let sets = [
                format!("camera.width={width}"),
                format!("camera.height={height}"),
            ];
            let scene = load_scene(&a.id, &sets)?;
            let exposure = scene.render.exposure;
            let image = Renderer::new(scene)
                .render()
                .with_context(|| format!("rendering {}", a.id))?;
            Ok(Picture {
                id: a.id.clone(),
                width,
                height,
                srgb: image.to_srgb8(exposure),
            })
        })
        .collect::<Result<_>>()?;
    let sheet = tile(&pictures, args.columns);
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, sheet.0, sheet.1);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder
        .write_header()
        .and_then(|mut w| w.write_image_data(&sheet.2))
        .context("encoding the contact sheet")?;
    write_atomically(&args.output, &bytes)?;
    eprintln!("{} entries -> {}", pictures.len(), args.output.display());
    Ok(())
}

/// The sheet's width, height and RGB bytes.
fn tile(pictures: &[Picture], columns: u32) -> (u32, u32, Vec<u8>) {
    let rows = (pictures.len() as u32).div_ceil(columns);
    let pitch = (CELL.0 + GAP, CELL.1 + LABEL + GAP);
    let (width, height) = (columns * pitch.0 + GAP, rows * pitch.1 + GAP);
    let mut rgb: Vec<u8> = BACKGROUND.repeat((width * height) as usize);
    let mut put = |x: u32, y: u32, c: [u8; 3]| {
        let i = 3 * (y * width + x) as usize;
        rgb[i..i + 3].copy_from_slice(&c);
    };
    for (i, p) in pictures.iter().enumerate() {
        let (column, row) = (i as u32 % columns, i as u32 / columns);
        let (left, top) = (GAP + column * pitch.0, GAP + row * pitch.1);
        // Centred in its box.
        let (x0, y0) = (left + (CELL.0 - p.width) / 2, top + (CELL.1 - p.height) / 2);
        for y in 0..p.height {
            for x in 0..p.width {
                let j = 3 * (y * p.width + x) as usize;
                put(x0 + x, y0 + y, [p.srgb[j], p.srgb[j + 1], p.srgb[j + 2]]);
            }
        }
        for (line, text) in label_lines(&p.id, CELL.0 as usize / bitmap_text::ADVANCE)
            .iter()
            .enumerate()
        {
            let y_text = top + CELL.1 + 3 + LINE * line as u32;
            for_each_lit_pixel(text, 1, |x, y| {
                if (x as u32) < CELL.0 {
                    put(left + x as u32, y_text + y as u32, INK)
                }
            });
        }
    }
    (width, height, rgb)
}

/// An id in at most two lines of `columns` characters, broken after a hyphen where
/// it can be.
fn label_lines(id: &str, columns: usize) -> Vec<String> {
    if id.len() <= columns {
        return vec![id.to_string()];
    }
    let head = &id[..columns];
    let cut = head.rfind('-').map_or(columns, |i| i + 1);
    let rest: String = id[cut..].chars().take(columns).collect();
    vec![id[..cut].to_string(), rest]
}

#[cfg(test)]
mod tests {
    use super::label_lines;

    #[test]
    fn long_ids_break_after_a_hyphen_into_two_lines() {
        assert_eq!(label_lines("cornell-box", 20), ["cornell-box"]);
        assert_eq!(
            label_lines("cornell-box-ray-cast-soft", 20),
            ["cornell-box-ray-", "cast-soft"]
        );
        assert_eq!(label_lines("abcdefghij", 4), ["abcd", "efgh"]);
    }
}
