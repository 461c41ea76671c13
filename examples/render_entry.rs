//! Renders a catalogue entry to a file: `cargo run --release --example render_entry
//! -- [ID] [OUT.png|OUT.pfm|OUT.exr]` (default: the Cornell box to cornell-box.png).

use lumiere::{Renderer, load_scene, write_image};
use std::path::PathBuf;

fn main() -> Result<(), lumiere::Error> {
    let mut args = std::env::args().skip(1);
    let id = args.next().unwrap_or_else(|| "cornell-box".to_string());
    let output = PathBuf::from(args.next().unwrap_or_else(|| format!("{id}.png")));

    // The entry at 256 x 256, as `lumiere render ID --set camera.width=256 ...` would.
    let sets = ["camera.width=256", "camera.height=256"].map(String::from);
    let scene = load_scene(&id, &sets)?;
    let exposure = scene.render.exposure;
    let renderer = Renderer::new(scene);
    for warning in renderer.warnings() {
        eprintln!("warning: {warning}");
    }
    let image = renderer.render()?;
    // PNG: sRGB after the scene's exposure; PFM and EXR: linear radiance.
    write_image(&image, &output, exposure)?;

    let entry = lumiere::catalogue::entry(&id)?;
    println!(
        "{}: {} ({}) -> {}",
        id,
        entry.algorithm.title,
        entry.algorithm.authors,
        output.display()
    );
    Ok(())
}
