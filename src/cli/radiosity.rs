//! Rendering a radiosity scene from the command line: a progress bar while shooting,
//! and the course's "observation of intermediate states" (`--frames DIR`): one
//! image every k shooting steps and an animated GIF of the convergence.

use anyhow::{Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use lumiere::output::{self, Image};
use lumiere::radiosity::{self, Settings, display};
use lumiere::scene::Scene;
use std::path::{Path, PathBuf};

/// Where and how often to write intermediate images.
pub struct Frames {
    pub dir: PathBuf,
    pub every: usize,
}

/// Solves `scene`'s radiosity and writes the image to `output`.
pub fn render(
    scene: &Scene,
    settings: &Settings,
    out: &Path,
    frames: Option<&Frames>,
) -> Result<()> {
    if let Some(f) = frames {
        std::fs::create_dir_all(&f.dir)
            .with_context(|| format!("cannot create the frames directory {}", f.dir.display()))?;
    }
    // Hidden when stderr is not a terminal.
    let bar = ProgressBar::new(1000).with_style(
        ProgressStyle::with_template("{spinner} [{elapsed_precise}] {bar:40} {msg}")
            .expect("a valid template"),
    );
    bar.set_message(format!("{:?} radiosity", settings.solver).to_lowercase());
    bar.enable_steady_tick(std::time::Duration::from_millis(100));
    let exposure = scene.render.exposure;
    let mut animation: Vec<Image> = Vec::new();
    let mut frame_error = Ok(());
    let target = settings.unshot.max(1e-12);
    let solution = radiosity::solve(scene, settings, &mut |mesh, state| {
        let fraction = state.unshot_fraction(mesh).max(target);
        // Progress on a log scale: from all power unshot to the target fraction.
        bar.set_position((1000.0 * fraction.ln() / target.ln()).clamp(0.0, 1000.0) as u64);
        bar.set_message(format!(
            "step {}, {:.2}% unshot",
            state.steps,
            100.0 * fraction
        ));
        if let Some(f) = frames
            && state.steps % f.every.max(1) == 0
            && frame_error.is_ok()
        {
            let shown = state.displayed(mesh, settings.ambient);
            let image = display::image(scene, mesh, &shown, settings.display);
            let path = f.dir.join(format!("step-{:05}.png", state.steps));
            frame_error = output::save(&image, &path, exposure);
            animation.push(image);
        }
    })?;
    frame_error?;
    bar.finish_and_clear();
    for warning in &solution.mesh.warnings {
        eprintln!("warning: {warning}");
    }
    eprintln!("{}", solution.summary);
    let image = display::image(scene, &solution.mesh, &solution.elements, settings.display);
    if let Some(f) = frames {
        animation.push(image.clone());
        let gif = output::encode_gif(&animation, exposure, 200)?;
        output::write_atomically(&f.dir.join("convergence.gif"), &gif)?;
    }
    output::save(&image, out, exposure)
}
