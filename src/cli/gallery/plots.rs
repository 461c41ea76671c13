//! The gallery's plots: what a method's error does as its one parameter grows,
//! measured here and drawn as SVG (`svg`). Each is computed at a small fixed size,
//! so that it does not depend on the gallery's image size.

use super::svg::{BarChart, LinePlot, Scale, Series};
use super::topics::Plot;
use anyhow::{Context, Result};
use lumiere::Image;
use lumiere::Renderer;
use lumiere::form_factors::{FormFactorMethod, polygon_form_factors};
use lumiere::radiosity_solution;
use lumiere::settings::Solver;
use lumiere::{catalogue, load_scene};
use std::sync::Arc;

/// A drawn plot and what to say about it.
pub struct Drawn {
    pub svg: String,
    /// The figure's caption: what is measured, and against what.
    pub caption: String,
    /// Alt text: what the plot shows, in a sentence.
    pub alt: String,
}

impl Plot {
    /// The plot's file name, without extension.
    pub fn name(self) -> &'static str {
        match self {
            Plot::SoftShadowConvergence => "soft-shadow-convergence",
            Plot::ShadowMapResolution => "shadow-map-resolution",
            Plot::MipFilterError => "mip-filter-error",
            Plot::FormFactorError => "form-factor-error",
            Plot::RadiosityResidual => "radiosity-residual",
        }
    }

    pub fn draw(self) -> Result<Drawn> {
        match self {
            Plot::SoftShadowConvergence => soft_shadow_convergence(),
            Plot::ShadowMapResolution => shadow_map_resolution(),
            Plot::MipFilterError => mip_filter_error(),
            Plot::FormFactorError => form_factor_error(),
            Plot::RadiosityResidual => radiosity_residual(),
        }
    }
}

/// A catalogue scene rendered with some keys changed (solved first if it has
/// radiosity), and its exposure.
fn render(scene: &str, sets: &[String]) -> Result<(Image, f32)> {
    let scene = load_scene(scene, &at_test_size(scene, sets)?)?;
    let exposure = scene.render.exposure;
    let mut renderer = Renderer::new(scene);
    renderer.check()?;
    if let Some(settings) = renderer.scene().radiosity.clone() {
        let scene = renderer.scene().clone();
        let solution = radiosity_solution::solve(&scene, &settings, &mut |_| {})?;
        renderer.set_radiosity_solution(Arc::new(solution));
    }
    Ok((renderer.render()?, exposure))
}

fn rmse(a: &(Image, f32), b: &(Image, f32)) -> Result<f64> {
    Ok(lumiere::compare_images(&a.0, &b.0, a.1)?.rmse)
}

/// `sets` and the entry's test size.
fn at_test_size(id: &str, sets: &[String]) -> Result<Vec<String>> {
    let a = catalogue::entry(id)?.algorithm;
    let mut sets = sets.to_vec();
    sets.push(format!("camera.width={}", a.test_width));
    sets.push(format!("camera.height={}", a.test_height));
    Ok(sets)
}

fn soft_shadow_convergence() -> Result<Drawn> {
    let exact = render("cornell-box", &["shadows.method=\"umbra-penumbra\"".into()])?;
    let mut volumes = Vec::new();
    for n in [1u32, 4, 16, 64, 256] {
        let image = render(
            "cornell-box",
            &[
                "shadows.method=\"soft-shadow-volumes\"".into(),
                format!("shadows.light_points={n}"),
            ],
        )?;
        volumes.push((n as f64, rmse(&exact, &image)?));
    }
    let mut rays = Vec::new();
    for n in [1u32, 2, 4, 8, 16] {
        let image = render(
            "cornell-box",
            &[
                "shadows.method=\"ray-cast\"".into(),
                format!("shadows.light_samples={n}"),
            ],
        )?;
        rays.push(((n * n) as f64, rmse(&exact, &image)?));
    }
    let caption = format!(
        "The Cornell box at 128 × 128, one sample per pixel: RMSE of the displayed image against \
         the exact umbra-penumbra render, as the light samples grow. Soft shadow volumes: {} at 1 \
         point, {} at 256 (their points are the same for every pixel, so the error is banding, not \
         noise). Stratified ray casting: {} at 1 sample, {} at 16 × 16.",
        fmt(volumes[0].1),
        fmt(volumes[volumes.len() - 1].1),
        fmt(rays[0].1),
        fmt(rays[rays.len() - 1].1)
    );
    Ok(Drawn {
        svg: LinePlot {
            title: "Sampled soft shadows converge to the exact one".into(),
            x_label: "light samples per visible point".into(),
            y_label: "RMSE against umbra-penumbra".into(),
            x_scale: Scale::Log,
            y_scale: Scale::Log,
            series: vec![
                Series {
                    name: "soft shadow volumes (n points)".into(),
                    points: volumes,
                },
                Series {
                    name: "ray casting (N × N strata)".into(),
                    points: rays,
                },
            ],
        }
        .svg(),
        caption,
        alt: "Log-log plot: the error of soft shadow volumes and of stratified ray casting falls \
              as the number of light samples grows."
            .into(),
    })
}

/// The share of samples whose visibility of light 0 differs between two renders.
fn visibility(scene: &str, sets: &[String]) -> Result<Vec<f32>> {
    let scene = load_scene(scene, &at_test_size(scene, sets)?)?;
    let renderer = Renderer::new(scene);
    renderer.check()?;
    let rendered = renderer.render_with_buffers(&["visibility-0".into()])?;
    match &rendered.buffers[0].data {
        lumiere::BufferData::Values { data, .. } => Ok(data.clone()),
        _ => anyhow::bail!("visibility-0 is not a buffer of values"),
    }
}

fn shadow_map_resolution() -> Result<Drawn> {
    let scene = "ray-cast-shadows-curved";
    let reference = visibility(scene, &["shadows.method=\"ray-cast\"".into()])?;
    let mut points = Vec::new();
    for resolution in [32u32, 64, 128, 256, 512, 1024, 2048] {
        let map = visibility(
            scene,
            &[
                "shadows.method=\"shadow-map\"".into(),
                format!("shadows.map_resolution={resolution}"),
            ],
        )?;
        let differing = reference
            .iter()
            .zip(&map)
            .filter(|(a, b)| (*a - *b).abs() > 1e-6)
            .count();
        points.push((
            resolution as f64,
            100.0 * differing as f64 / reference.len() as f64,
        ));
    }
    let caption = format!(
        "The curved scene at 128 × 96: the share of samples whose shadow-map visibility differs \
         from ray casting's, as the map's resolution grows: {}% at 32 texels, {}% at 2048. What \
         remains at high resolution is the bias: near contact, the map cannot tell a receiver \
         from its caster.",
        fmt(points[0].1),
        fmt(points[points.len() - 1].1)
    );
    Ok(Drawn {
        svg: LinePlot {
            title: "Shadow-map agreement with ray casting".into(),
            x_label: "map resolution (texels on a side)".into(),
            y_label: "samples that disagree (%)".into(),
            x_scale: Scale::Log,
            y_scale: Scale::Log,
            series: vec![Series {
                name: "Williams's depth test, slope-scaled bias".into(),
                points,
            }],
        }
        .svg(),
        caption,
        alt: "Log-log plot: the share of samples where the shadow map disagrees with ray casting \
              falls as the map's resolution grows."
            .into(),
    })
}

fn mip_filter_error() -> Result<Drawn> {
    let filter = |name: &str| {
        vec![
            format!("textures.point.filter=\"{name}\""),
            format!("textures.trilinear.filter=\"{name}\""),
        ]
    };
    let mut truth_sets = filter("nearest");
    truth_sets.push("render.supersample=16".into());
    let truth = render("mip-mapping", &truth_sets)?;
    let mut bars = Vec::new();
    for name in [
        "nearest",
        "bilinear",
        "mip-nearest",
        "trilinear",
        "summed-area",
    ] {
        let image = render("mip-mapping", &filter(name))?;
        bars.push((name.to_string(), rmse(&truth, &image)?));
    }
    let best = bars
        .iter()
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .expect("five filters");
    let caption = format!(
        "The mip-mapping scene at 192 × 96, one sample per pixel: RMSE of each filter against \
         point sampling at 16 × 16 samples per pixel. The lowest is {} ({}); point sampling and \
         bilinear alias far away, the pyramid and the summed-area table blur where the footprint \
         is long and thin.",
        best.0,
        fmt(best.1)
    );
    Ok(Drawn {
        svg: BarChart {
            title: "Texture filters against supersampled truth".into(),
            y_label: "RMSE".into(),
            bars,
        }
        .svg(),
        caption,
        alt: "Bar chart of the error of five texture filters against a supersampled render.".into(),
    })
}

/// Two unit squares facing each other one unit apart and a third standing at the
/// source's edge: Lambert's formula gives the factors from the source's centre.
const PLATES: &str = r#"
[camera]
eye = [0.0, 0.5, 4.0]
look_at = [0.0, 0.5, 0.0]
fov_y = 40.0
width = 16
height = 16

[materials.grey]
diffuse = [0.5, 0.5, 0.5]

[[objects]]
shape = "polygon"
name = "source"
material = "grey"
vertices = [[-0.5, 0.0, -0.5], [-0.5, 0.0, 0.5], [0.5, 0.0, 0.5], [0.5, 0.0, -0.5]]

[[objects]]
shape = "polygon"
name = "parallel"
material = "grey"
vertices = [[-0.5, 1.0, -0.5], [0.5, 1.0, -0.5], [0.5, 1.0, 0.5], [-0.5, 1.0, 0.5]]

[[objects]]
shape = "polygon"
name = "perpendicular"
material = "grey"
vertices = [[0.5, 0.0, -0.5], [0.5, 0.0, 0.5], [0.5, 1.0, 0.5], [0.5, 1.0, -0.5]]
"#;

fn form_factor_error() -> Result<Drawn> {
    let scene = lumiere::scene_from_toml(PLATES, &[]).context("the plates")?;
    // From the first plate's centre: one element a patch.
    let row = |method, resolution| -> Result<Vec<f64>> {
        let mut matrix = polygon_form_factors(&scene, method, resolution, 1)?;
        Ok(matrix.factors.swap_remove(0))
    };
    let exact = row(FormFactorMethod::Analytic, 0)?;
    anyhow::ensure!(
        exact[1] > 0.0 && exact[2] > 0.0,
        "the plates do not see each other"
    );
    let error = |estimate: &[f64]| {
        (1..3)
            .map(|j| (estimate[j] - exact[j]).abs() / exact[j])
            .fold(0.0, f64::max)
    };
    let resolutions = [4u32, 8, 16, 32, 64, 128, 256, 512];
    let mut series = Vec::new();
    for (name, method) in [
        ("hemi-cube", FormFactorMethod::Hemicube),
        ("Nusselt analog", FormFactorMethod::Nusselt),
    ] {
        let points = resolutions
            .iter()
            .map(|&r| Ok((r as f64, error(&row(method, r)?))))
            .collect::<Result<_>>()?;
        series.push(Series {
            name: name.into(),
            points,
        });
    }
    let at = |s: &Series, r: f64| s.points.iter().find(|p| p.0 == r).map_or(f64::NAN, |p| p.1);
    let caption = format!(
        "Factors from the centre of a unit square to a parallel square one unit above (exact {:.5}) \
         and to a square standing on its edge (exact {:.5}), by Lambert's formula; the larger \
         relative error of the two, as the cells grow finer. Hemi-cube: {} at 8 cells, {} at 512.",
        exact[1],
        exact[2],
        fmt(at(&series[0], 8.0)),
        fmt(at(&series[0], 512.0))
    );
    Ok(Drawn {
        svg: LinePlot {
            title: "Form-factor error against resolution".into(),
            x_label: "cells along the hemi-cube's top face (or the disc)".into(),
            y_label: "relative error".into(),
            x_scale: Scale::Log,
            y_scale: Scale::Log,
            series,
        }
        .svg(),
        caption,
        alt: "Log-log plot: the relative error of hemi-cube and Nusselt form factors falls as \
              their resolution grows."
            .into(),
    })
}

fn radiosity_residual() -> Result<Drawn> {
    // Green: one band is enough to watch convergence.
    const BAND: usize = 1;
    let scene = load_scene("radiosity-gathering", &[])?;
    let settings = scene
        .radiosity
        .clone()
        .context("radiosity-gathering has no [radiosity] table")?;
    let (patches, residuals) =
        radiosity_solution::gathering_residuals(&scene, &settings, BAND, 1e-9)?;
    let gathering: Vec<(f64, f64)> = (1..)
        .zip(residuals)
        .map(|(sweep, r)| (sweep as f64, r))
        .collect();
    let mut shooting_settings = settings.clone();
    shooting_settings.solver = Solver::Shooting;
    shooting_settings.unshot = 1e-3;
    let mut shooting = Vec::new();
    radiosity_solution::solve(&scene, &shooting_settings, &mut |step| {
        shooting.push((step.steps() as f64, step.unshot_fraction()));
    })?;
    let caption = format!(
        "The Cornell box of radiosity-gathering ({} patches): gathering's residual power \
         Σ A|E + ρFB − B| after each Gauss–Seidel sweep, and shooting's unshot power after each \
         step, both as fractions of the emitted power (green band). A sweep updates every patch; a \
         step shoots one: gathering reached {} in {} sweeps, shooting {} in {} steps.",
        patches,
        fmt(gathering.last().map_or(f64::NAN, |p| p.1)),
        gathering.len(),
        fmt(shooting.last().map_or(f64::NAN, |p| p.1)),
        shooting.len()
    );
    Ok(Drawn {
        svg: LinePlot {
            title: "Radiosity: residual per iteration".into(),
            x_label: "iteration (gathering: sweep; shooting: step)".into(),
            y_label: "fraction of the emitted power".into(),
            x_scale: Scale::Log,
            y_scale: Scale::Log,
            series: vec![
                Series {
                    name: "gathering (Gauss–Seidel)".into(),
                    points: gathering,
                },
                Series {
                    name: "progressive shooting".into(),
                    points: shooting,
                },
            ],
        }
        .svg(),
        caption,
        alt: "Log-log plot: gathering's residual and shooting's unshot power fall with each \
              iteration."
            .into(),
    })
}

/// A measured value with three significant digits.
fn fmt(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let digits = (2 - v.abs().log10().floor() as i32).max(0) as usize;
    format!("{v:.digits$}")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The numbers of a drawn plot's caption.
    fn numbers(caption: &str) -> Vec<f64> {
        caption
            .split(|c: char| !(c.is_ascii_digit() || c == '.'))
            .filter_map(|w| w.trim_end_matches('.').parse().ok())
            .collect()
    }

    /// The y pixel of each point of each polyline.
    fn polylines(svg: &str) -> Vec<Vec<f64>> {
        svg.split("points=\"")
            .skip(1)
            .map(|p| {
                let points = p.split('"').next().unwrap();
                points
                    .split(' ')
                    .map(|xy| xy.split(',').nth(1).unwrap().parse().unwrap())
                    .collect()
            })
            .collect()
    }

    #[test]
    fn hemicube_factors_converge_to_lamberts() {
        let drawn = form_factor_error().unwrap();
        let n = numbers(&drawn.caption);
        // The exact factors by Lambert's formula, then the hemi-cube's relative
        // error at 8 cells and at 512.
        assert!(
            (n[0] - 0.23946).abs() < 1e-4 && (n[1] - 0.19014).abs() < 1e-4,
            "{n:?}"
        );
        let (coarse, fine) = (n[2], n[4]);
        assert!(fine < 2e-3 && fine < coarse / 20.0, "{n:?}");
    }

    #[test]
    fn gathering_residual_falls_every_sweep_and_shooting_never_grows() {
        let lines = polylines(&radiosity_residual().unwrap().svg);
        // SVG's y grows downwards: a falling residual is a growing y.
        assert!(lines[0].windows(2).all(|w| w[1] > w[0]), "{:?}", lines[0]);
        assert!(lines[1].windows(2).all(|w| w[1] >= w[0]));
        assert!(lines[0].len() > 5 && lines[1].len() > 100);
    }

    #[test]
    fn sampled_soft_shadows_approach_the_exact_one() {
        let lines = polylines(&soft_shadow_convergence().unwrap().svg);
        for line in &lines {
            // From 1 sample to 256 the error falls by more than ten times: on a
            // log axis of whole decades, more than one decade's height.
            let decade = 292.0 / 3.0;
            assert!(line[line.len() - 1] - line[0] > decade, "{line:?}");
        }
    }
}
