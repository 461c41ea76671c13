//! `lumiere bench --radiosity-elements N,…`: radiosity solve times on a catalogue
//! radiosity scene as the element count grows.

use super::timing::median;
use anyhow::{Result, bail};
use lumiere::Scene;
use lumiere::load_scene;
use lumiere::radiosity_solution::{self, SolverTrial};
use lumiere::settings::Division;

/// Times, for each wanted element count, shooting to the scene's unshot fraction and
/// gathering (its form factors and its solve apart).
pub fn run(scene_name: &str, counts: &[usize], runs: usize) -> Result<()> {
    let base = load_scene(scene_name, &[])?;
    if base.radiosity.is_none() {
        bail!("{scene_name} has no [radiosity] table to time");
    }
    outln!(
        "{:<22} {:>9} {:>8} {:>6} {:>13} {:>17} {:>12}",
        "radiosity scene",
        "elements",
        "patches",
        "steps",
        "shooting (s)",
        "gathering FF (s)",
        "GS solve (s)"
    )?;
    for &count in counts {
        let scene = with_element_count(&base, count)?;
        let settings = scene.radiosity.as_ref().expect("checked above");
        let trial = SolverTrial::prepare(&scene, settings)?;
        let (patches, elements) = trial.size();
        let mut steps = 0;
        let shooting = median(runs, || steps = trial.shoot());
        let (form_factor_time, solve_time) = trial.gather()?;
        outln!(
            "{:<22} {:>9} {:>8} {:>6} {:>13.2} {:>17.2} {:>12.4}",
            scene_name,
            elements,
            patches,
            steps,
            shooting.as_secs_f64(),
            form_factor_time.as_secs_f64(),
            solve_time.as_secs_f64()
        )?;
    }
    Ok(())
}

/// The scene with the element size that gives the element count nearest `count`
/// (bisection on the size: the count falls as the size grows, in whole grid steps).
fn with_element_count(base: &Scene, count: usize) -> Result<Scene> {
    let mut scene = base.clone();
    let mut count_at = |size: f64| -> Result<(usize, Scene)> {
        let settings = scene.radiosity.as_mut().expect("checked by the caller");
        settings.elements = Division::Size(size);
        let n = radiosity_solution::meshed_element_count(
            &scene,
            scene.radiosity.as_ref().expect("set"),
        )?;
        Ok((n, scene.clone()))
    };
    let (mut small, mut large) = (1.0_f64, 1000.0_f64);
    let mut best = count_at(large)?;
    for _ in 0..30 {
        let size = (small * large).sqrt();
        let (n, s) = count_at(size)?;
        if n.abs_diff(count) < best.0.abs_diff(count) {
            best = (n, s);
        }
        if n > count {
            small = size
        } else {
            large = size
        }
    }
    Ok(best.1)
}
