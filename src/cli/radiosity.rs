//! Rendering a radiosity scene from the command line: a progress bar while shooting,
//! and the course's "observation of intermediate states" (`--frames DIR`): one
//! image every k shooting steps and an animated GIF of the convergence.

use anyhow::{Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use lumiere::Image;
use lumiere::Renderer;
use lumiere::Scene;
use lumiere::radiosity_solution::{self, Solution};
use lumiere::settings::RadiositySettings;
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
pub fn solve(
    renderer: &mut Renderer,
    settings: &RadiositySettings,
    frames: Option<&Frames>,
) -> Result<()> {
    let scene = renderer.scene().clone();
    let scene = &scene;
    let exposure = scene.render.exposure;
    // The frames go to a staging directory and the animation is encoded as they
    // come; both replace an earlier run's only once this run is complete.
    let mut staged = frames
        .map(|f| -> Result<_> {
            let directory = lumiere::StagedDirectory::create(&f.dir).with_context(|| {
                format!("cannot create the frames directory {}", f.dir.display())
            })?;
            let gif = directory.path("convergence.gif");
            let file = std::fs::File::create(&gif)
                .with_context(|| format!("cannot write {}", gif.display()))?;
            let animation =
                lumiere::GifAnimation::new(std::io::BufWriter::new(file), exposure, 200);
            Ok((directory, animation))
        })
        .transpose()?;
    // Hidden when stderr is not a terminal.
    let bar = ProgressBar::new(1000).with_style(
        ProgressStyle::with_template("{spinner} [{elapsed_precise}] {bar:40} {msg}")
            .expect("a valid template"),
    );
    bar.set_message(format!("{:?} radiosity", settings.solver).to_lowercase());
    bar.enable_steady_tick(std::time::Duration::from_millis(100));
    let mut frame_error = Ok(());
    let target = settings.unshot.max(1e-12);
    let solution = radiosity_solution::solve(scene, settings, &mut |step| {
        let fraction = step.unshot_fraction().max(target);
        // Progress on a log scale: from all power unshot to the target fraction.
        bar.set_position((1000.0 * fraction.ln() / target.ln()).clamp(0.0, 1000.0) as u64);
        bar.set_message(format!(
            "step {}, {:.2}% unshot",
            step.steps(),
            100.0 * fraction
        ));
        if let (Some(f), Some((directory, animation))) = (frames, staged.as_mut())
            && step.steps() % f.every.max(1) == 0
            && frame_error.is_ok()
        {
            let snapshot = step.snapshot(String::new());
            let path = directory.path(&format!("step-{:05}.png", step.steps()));
            frame_error = draw(scene, snapshot).and_then(|image| {
                lumiere::write_image(&image, &path, exposure)?;
                Ok(animation.add(&image)?)
            });
        }
    })?;
    frame_error?;
    bar.finish_and_clear();
    for warning in solution.warnings() {
        eprintln!("warning: {warning}");
    }
    eprintln!("{}", solution.summary);
    let solution = Arc::new(solution);
    renderer.set_radiosity_solution(solution.clone());
    if let Some((directory, mut animation)) = staged {
        animation.add(&renderer.render()?)?;
        animation
            .finish()?
            .into_inner()
            .map_err(|e| e.into_error())
            .and_then(|file| file.sync_all())
            .context("cannot write the convergence animation")?;
        directory.publish(is_frame_file)?;
    }
    Ok(())
}

/// The files a run writes into the frames directory.
fn is_frame_file(name: &str) -> bool {
    name == "convergence.gif" || (name.starts_with("step-") && name.ends_with(".png"))
}

/// The image of an intermediate solution.
fn draw(scene: &Scene, solution: Solution) -> Result<Image> {
    let mut renderer = Renderer::new(scene.clone());
    renderer.set_radiosity_solution(Arc::new(solution));
    Ok(renderer.render()?)
}
