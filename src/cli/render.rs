//! `lumiere render`: one image of a catalogue entry or a scene file.

use anyhow::{Context, Result, bail};
use lumiere::Renderer;
use lumiere::StagedDirectory;
use lumiere::settings::{FormFactorMethod, SamplePattern, ShadowMethod, Solver};
use lumiere::{ImageFormat, catalogue, load_scene, write_atomically, write_image};
use std::path::PathBuf;

/// Render a catalogue entry (by id) or a scene file (.toml) to PNG, PFM or EXR.
///
/// PNG is 8-bit sRGB after the scene's exposure; PFM and EXR are linear radiance
/// (32-bit float).
#[derive(clap::Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    /// A catalogue id (see `lumiere list`) or the path of a .toml scene file.
    scene: String,
    /// Output image: .png (sRGB), .pfm or .exr (linear radiance); `-` writes the
    /// PNG to standard output.
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    size: super::ImageSize,
    /// N x N samples per pixel, averaged (box filter), on the grid `--sample-pattern`
    /// names.
    #[arg(long)]
    supersample: Option<u32>,
    /// Where a pixel's samples lie, overriding the scene's `[render] sample_pattern`:
    /// `regular` (the default) or `rotated-grid` (N² frames shifted, averaged).
    #[arg(long, value_enum)]
    sample_pattern: Option<SamplePattern>,
    /// Shadow method, overriding the scene's `[shadows] method`.
    #[arg(long, value_enum)]
    shadows: Option<ShadowMethod>,
    /// Write an intermediate buffer instead of the image, at the sample grid's size:
    /// `--aov list -o -` names those this scene's frame makes (polygon ids, depth,
    /// normals, each light's visibility, shadow-map faces, shadow-volume counts, mip
    /// levels, hemi-cube item buffers…; `-o FILE` writes the list there); `--aov all -o
    /// DIR` writes them all into DIR.
    /// Ids and counts are colour-mapped (PNG) or their numbers (PFM, EXR); values are
    /// linear. `shadow` is `visibility-0`.
    #[arg(long, value_name = "NAME|list|all")]
    aov: Option<String>,
    /// Radiosity: the element whose hemi-cube item buffers `--aov hemicube-*` shows.
    #[arg(long, value_name = "E", default_value_t = 0)]
    hemicube_element: usize,
    /// Render a catalogue entry at its golden-image test size.
    #[arg(long)]
    test_size: bool,
    /// Light the scene by radiosity with this solver (overrides `[radiosity] solver`).
    #[arg(long, value_enum)]
    radiosity: Option<Solver>,
    /// Radiosity form factors (overrides `[radiosity] form_factors`).
    #[arg(long, value_enum)]
    form_factors: Option<FormFactorMethod>,
    /// Hemi-cube cells along the top face (or Nusselt grid cells along the disc).
    #[arg(long)]
    hemicube_resolution: Option<u32>,
    /// Longest patch side, in scene units.
    #[arg(long)]
    patch_size: Option<f64>,
    /// Longest element side, in scene units.
    #[arg(long)]
    element_size: Option<f64>,
    /// Gathering: adaptive subdivision of elements differing from a neighbour by
    /// more than this fraction of the largest reflected radiosity.
    #[arg(long, value_name = "FRACTION")]
    subdivide: Option<f64>,
    /// Gathering: rounds of adaptive subdivision (default 2).
    #[arg(long, value_name = "N")]
    subdivision_levels: Option<u32>,
    /// Shooting: stop after this many steps.
    #[arg(long)]
    steps: Option<usize>,
    /// Shooting: display with the ambient term.
    #[arg(long)]
    ambient: bool,
    /// Shooting: write an image every `--frame-every` steps into DIR, and
    /// DIR/convergence.gif.
    #[arg(long, value_name = "DIR")]
    frames: Option<PathBuf>,
    #[arg(long, default_value_t = 1, requires = "frames", value_parser = super::at_least_one)]
    frame_every: usize,
    /// After the image, one line on standard error: its size, the time taken and
    /// samples per second.
    #[arg(long)]
    summary: bool,
    /// Override any scene key, e.g. --set camera.width=64 --set render.shading=flat
    /// (array elements by index: --set objects.0.material=red). Repeatable.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    sets: Vec<String>,
}

pub fn run(args: Args) -> Result<()> {
    let started = std::time::Instant::now();
    // Fail on a bad output name before any work is done.
    let aov = args.aov.as_deref();
    match aov {
        Some("all") if args.output.as_os_str() == "-" => {
            bail!("--aov all writes a directory of images: give -o DIR, not -")
        }
        Some("all" | "list") => {}
        None if args.output.as_os_str() == "-" => {
            if std::io::IsTerminal::is_terminal(&std::io::stdout()) {
                bail!(
                    "-o - writes the image (PNG) to standard output, which is a terminal: pipe it into a program, or give a file"
                );
            }
        }
        _ => {
            ImageFormat::of(&args.output)?;
        }
    }
    let mut sets = Vec::new();
    if args.test_size {
        let path = std::path::Path::new(&args.scene);
        if args.scene.ends_with(".toml") || path.exists() {
            bail!(
                "--test-size: {} is a scene file; the test size is a catalogue entry's (its golden image's)",
                args.scene
            );
        }
        let a = catalogue::entry(&args.scene)?.algorithm;
        sets.push(format!("camera.width={}", a.test_width));
        sets.push(format!("camera.height={}", a.test_height));
    }
    sets.extend(args.sets.iter().cloned());
    sets.extend(args.size.sets());
    if let Some(n) = args.supersample {
        sets.push(format!("render.supersample={n}"));
    }
    if let Some(pattern) = args.sample_pattern {
        sets.push(format!("render.sample_pattern=\"{}\"", name(&pattern)));
    }
    if let Some(method) = args.shadows {
        sets.push(format!("shadows.method=\"{}\"", name(&method)));
    }
    sets.extend(radiosity_sets(&args));
    let scene = load_scene(&args.scene, &sets)?;
    let exposure = scene.render.exposure;
    let radiosity = scene.radiosity.clone();
    if let Some(settings) = &radiosity
        && settings.solver == Solver::Gathering
    {
        refuse_shooting_options(&args)?;
    }
    let mut renderer = Renderer::new(scene);
    renderer.check()?;
    renderer.set_hemicube_element(args.hemicube_element);
    for warning in renderer.warnings() {
        eprintln!("warning: {}", super::one_line(&warning));
    }
    let scene = renderer.scene();
    if !scene.polygons.is_empty() && !renderer.sees_a_polygon() {
        eprintln!(
            "warning: no polygon lies in front of the camera within its field of view (and beyond camera.near = {}): the image shows the background only",
            scene.camera.near
        );
    }
    if let Some(settings) = &radiosity {
        refuse_missing_element(&args, renderer.scene(), settings)?;
        let frames = args.frames.map(|dir| super::radiosity::Frames {
            dir,
            every: args.frame_every,
        });
        super::radiosity::solve(&mut renderer, settings, frames.as_ref())?;
    } else if args.frames.is_some() {
        bail!("--frames shows radiosity shooting steps: the scene has no [radiosity] table");
    }
    match aov {
        None => {
            // Drawn only on a terminal, and only once a frame has run a while.
            let bar = indicatif::ProgressBar::new(1000).with_style(
                indicatif::ProgressStyle::with_template(
                    "{spinner} [{elapsed_precise}] {bar:40} {percent}% rendering",
                )
                .expect("a valid template"),
            );
            let shown = bar.clone();
            let begun = std::time::Instant::now();
            renderer.set_progress(move |done| {
                if begun.elapsed().as_secs_f64() > 2.0 {
                    shown.set_position((done * 1000.0) as u64);
                }
            });
            let image = renderer.render();
            bar.finish_and_clear();
            let image = image?;
            if args.summary {
                let seconds = started.elapsed().as_secs_f64();
                let c = &renderer.scene().camera;
                let samples = c.width as u64
                    * c.height as u64
                    * (renderer.scene().render.supersample as u64).pow(2);
                eprintln!(
                    "rendered {} at {} x {} in {seconds:.2} s: {samples} samples, {:.0} samples/s",
                    args.scene,
                    c.width,
                    c.height,
                    samples as f64 / seconds.max(1e-9)
                );
            }
            let unbounded = image.pixels.iter().filter(|p| !p.is_finite()).count();
            if unbounded > 0 {
                eprintln!(
                    "warning: {unbounded} pixels have infinite or undefined radiance (a point light on a surface?); PNG shows them white, PFM and EXR keep them"
                );
            }
            if args.output.as_os_str() == "-" {
                let png = lumiere::encode_image(&image, ImageFormat::Png, exposure)?;
                std::io::Write::write_all(&mut std::io::stdout(), &png)
                    .context("writing standard output")?;
                return Ok(());
            }
            Ok(write_image(&image, &args.output, exposure)?)
        }
        // To standard output with `-o -`, else written (whole or not at all) to the file.
        Some("list") => {
            let list: String = renderer
                .available_buffers()?
                .iter()
                .map(|info| format!("{:<28} {}\n", info.name, info.description))
                .collect();
            if args.output.as_os_str() == "-" {
                out!("{list}")?;
            } else {
                write_atomically(&args.output, list.as_bytes())?;
            }
            Ok(())
        }
        Some("all") => {
            let names: Vec<String> = renderer
                .available_buffers()?
                .into_iter()
                .map(|b| b.name)
                .collect();
            let rendered = renderer.render_with_buffers(&names)?;
            let dir = &args.output;
            // All the buffers or none: an earlier run's stay until every one is written.
            let staged = StagedDirectory::create(dir)
                .with_context(|| format!("cannot create the directory {}", dir.display()))?;
            let mut files = Vec::new();
            for buffer in &rendered.buffers {
                let format = buffer.natural_format();
                let file = format!("{}.{}", buffer.name, format.extension());
                write_image(&buffer.to_image(format), &staged.path(&file), 1.0)?;
                files.push(file);
            }
            Ok(staged.publish(|name| files.iter().any(|f| f == name))?)
        }
        Some(name) => {
            let name = if name == "shadow" {
                "visibility-0"
            } else {
                name
            };
            let rendered = renderer.render_with_buffers(&[name.to_string()])?;
            let buffer = &rendered.buffers[0];
            let format = ImageFormat::of(&args.output)?;
            Ok(write_image(&buffer.to_image(format), &args.output, 1.0)?)
        }
    }
}

/// `--steps`, `--ambient` and `--frames` are the shooting solver's: gathering solves
/// the whole system at once, has no steps to stop after or show, and no ambient term.
fn refuse_shooting_options(args: &Args) -> Result<()> {
    let given: Vec<&str> = [
        (args.steps.is_some(), "--steps"),
        (args.ambient, "--ambient"),
        (args.frames.is_some(), "--frames"),
    ]
    .into_iter()
    .filter_map(|(given, name)| given.then_some(name))
    .collect();
    if !given.is_empty() {
        bail!(
            "{} belong{} to the shooting solver (--radiosity shooting); this scene is solved by gathering",
            given.join(", "),
            if given.len() == 1 { "s" } else { "" }
        );
    }
    Ok(())
}

/// An option's value as the scene file spells it.
fn name(value: &impl clap::ValueEnum) -> String {
    let value = value.to_possible_value().expect("no skipped variants");
    value.get_name().to_string()
}

/// The radiosity options as scene-key overrides.
fn radiosity_sets(args: &Args) -> Vec<String> {
    let mut sets = Vec::new();
    if let Some(s) = args.radiosity {
        sets.push(format!("radiosity.solver=\"{}\"", name(&s)));
    }
    if let Some(m) = args.form_factors {
        sets.push(format!("radiosity.form_factors=\"{}\"", name(&m)));
    }
    if let Some(r) = args.hemicube_resolution {
        sets.push(format!("radiosity.resolution={r}"));
    }
    if let Some(p) = args.patch_size {
        sets.push(format!("radiosity.patch_size={p:?}"));
    }
    if let Some(e) = args.element_size {
        sets.push(format!("radiosity.element_size={e:?}"));
    }
    if let Some(t) = args.subdivide {
        sets.push(format!("radiosity.subdivide={t:?}"));
    }
    if let Some(n) = args.subdivision_levels {
        sets.push(format!("radiosity.subdivision_levels={n}"));
    }
    if let Some(n) = args.steps {
        sets.push(format!("radiosity.max_steps={n}"));
    }
    if args.ambient {
        sets.push("radiosity.ambient=true".to_string());
    }
    sets
}

/// `--hemicube-element E` past every element the mesh can have (those it is cut
/// into, each cut in four by every round of adaptive subdivision), refused before
/// the solve rather than after it.
fn refuse_missing_element(
    args: &Args,
    scene: &lumiere::Scene,
    settings: &lumiere::settings::RadiositySettings,
) -> Result<()> {
    if args.hemicube_element == 0 {
        return Ok(());
    }
    let elements = lumiere::radiosity_solution::element_count(scene, settings);
    let levels = settings.subdivision.map_or(0, |s| s.levels);
    let most = elements.saturating_mul(4u64.saturating_pow(levels));
    if args.hemicube_element as u64 >= most {
        bail!(
            "--hemicube-element {}: the mesh has {} elements{}, numbered from 0",
            args.hemicube_element,
            elements,
            if levels > 0 {
                format!(" (at most {most} after {levels} rounds of subdivision)")
            } else {
                String::new()
            }
        );
    }
    Ok(())
}
