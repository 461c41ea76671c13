//! `lumiere form-factors`: the patch-to-patch form-factor matrix of a scene, each
//! polygon one patch, for teaching and for checking.

use anyhow::Result;
use lumiere::Scene;
use lumiere::form_factors::{FormFactorMethod, MatrixPatch, polygon_form_factors};
use lumiere::load_scene;

/// Print F_ij for every pair of polygons of a scene (rows: from, columns: to).
///
/// Each polygon is one patch. With --elements M every source patch is cut into
/// M x M elements, one estimate at each element's centre, area-averaged into the
/// patch's row (the analytic method integrates over the patch at those points).
#[derive(clap::Args, Debug)]
pub struct Args {
    /// A catalogue id or the path of a .toml scene file.
    scene: String,
    #[arg(long, value_enum, default_value_t = FormFactorMethod::Hemicube)]
    method: FormFactorMethod,
    /// Hemi-cube cells along the top face, or Nusselt grid cells along the disc.
    #[arg(long, default_value_t = 128, value_parser = clap::value_parser!(u32).range(2..=4096))]
    resolution: u32,
    /// Elements along each side of a source patch.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=256))]
    elements: u32,
    /// Print the matrix with patch names and areas as JSON.
    #[arg(long)]
    json: bool,
    /// Override any scene key (as for `render`).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    sets: Vec<String>,
}

pub fn run(args: Args) -> Result<()> {
    let scene = load_scene(&args.scene, &args.sets)?;
    let matrix = polygon_form_factors(&scene, args.method, args.resolution, args.elements)?;
    for warning in scene.warnings.iter().chain(&matrix.warnings) {
        eprintln!("warning: {warning}");
    }
    let names = patch_names(&scene, &matrix.patches);
    if args.json {
        let patches: Vec<_> = matrix
            .patches
            .iter()
            .zip(&names)
            .map(|(p, name)| serde_json::json!({ "name": name, "polygon": p.polygon, "area": p.area }))
            .collect();
        let report = serde_json::json!({
            "method": args.method,
            "resolution": args.resolution,
            "elements": args.elements,
            "patches": patches,
            "factors": matrix.factors,
        });
        outln!("{}", serde_json::to_string_pretty(&report)?)?;
    } else {
        out!("{:<24}{:>12}", "from \\ to", "area")?;
        for name in &names {
            out!(" {:>10.10}", name)?;
        }
        outln!()?;
        for ((row, name), p) in matrix.factors.iter().zip(&names).zip(&matrix.patches) {
            out!("{name:<24.24}{:>12.4}", p.area)?;
            for f in row {
                out!(" {f:>10.6}")?;
            }
            outln!("   sum {:.6}", row.iter().sum::<f64>())?;
        }
    }
    Ok(())
}

/// Each patch's object name, with the polygon's index when its object has several.
fn patch_names(scene: &Scene, patches: &[MatrixPatch]) -> Vec<String> {
    patches
        .iter()
        .map(|p| {
            let object = scene.polygons[p.polygon].object;
            let name = &scene.objects[object].name;
            let siblings: Vec<usize> = (0..scene.polygons.len())
                .filter(|&k| scene.polygons[k].object == object)
                .collect();
            if siblings.len() == 1 {
                name.clone()
            } else {
                let k = siblings.iter().position(|&k| k == p.polygon).unwrap_or(0);
                format!("{name}#{k}")
            }
        })
        .collect()
}
