//! Rendering a radiosity scene from the command line: a progress bar while shooting,
//! and the course's "observation of intermediate states" (`--frames DIR`): one
//! image every k shooting steps and an animated GIF of the convergence.

use anyhow::{Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use lumiere::output::{self, Image};
use lumiere::radiosity::{self, Settings, Solution};
use lumiere::render::Renderer;
use lumiere::scene::Scene;
use std::path::PathBuf;
use std::sync::Arc;

/// Where and how often to write intermediate images.
pub struct Frames {
    pub dir: PathBuf,
    pub every: usize,
}

/// Solves `scene`'s radiosity, showing progress and writing the intermediate frames
/// asked for; the solution is handed to the renderer, which draws it like any
/// frame.
pub fn solve(renderer: &mut Renderer, settings: &Settings, frames: Option<&Frames>) -> Result<()> {
    let scene = renderer.scene().clone();
    let scene = &scene;
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
            let snapshot = Solution {
                mesh: mesh.clone(),
                elements: shown,
                direct: None,
                display: settings.display,
                summary: String::new(),
            };
            let path = f.dir.join(format!("step-{:05}.png", state.steps));
            frame_error = draw(scene, snapshot).and_then(|image| {
                let saved = output::save(&image, &path, exposure);
                animation.push(image);
                Ok(saved?)
            });
        }
    })?;
    frame_error?;
    bar.finish_and_clear();
    for warning in &solution.mesh.warnings {
        eprintln!("warning: {warning}");
    }
    eprintln!("{}", solution.summary);
    let solution = Arc::new(solution);
    renderer.set_radiosity_solution(solution.clone());
    if let Some(f) = frames {
        animation.push(renderer.render()?);
        let gif = output::encode_gif(&animation, exposure, 200)?;
        output::write_atomically(&f.dir.join("convergence.gif"), &gif)?;
    }
    Ok(())
}

/// The image of an intermediate solution.
fn draw(scene: &Scene, solution: Solution) -> Result<Image> {
    let mut renderer = Renderer::new(scene.clone());
    renderer.set_radiosity_solution(Arc::new(solution));
    Ok(renderer.render()?)
}
