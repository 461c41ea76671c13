//! Radiosity: diffuse interreflection solved once for the whole scene, then drawn
//! from the camera.
//!
//! - `mesh`: polygons cut into patches and elements (substructuring);
//! - form factors from a point by `hemicube`, `nusselt` or `analytic`
//!   (`form_factors` puts them behind one interface);
//! - solvers: `gathering` (the matrix, Gauss–Seidel) and `shooting` (progressive
//!   refinement, with the ambient term);
//! - `display`: vertex radiosities, Gouraud or flat, radiance B/π.

pub mod analytic;
pub mod display;
pub mod extended;
pub mod form_factors;
pub mod gathering;
pub mod hemicube;
pub mod light_sources;
pub mod mesh;
pub mod nusselt;
pub mod receivers;
pub mod shooting;
pub mod subdivision;
pub mod windows;

use crate::error::{Error, Result};
use crate::scene::Scene;
pub use crate::settings::{Division, RadiositySettings as Settings, Solver, Subdivision};
pub use display::Display;
pub use form_factors::{Estimator, FormFactorMethod};
use glam::Vec3;
pub use mesh::Mesh;
pub use shooting::{Shooting, Stop};

/// A solved scene: its mesh and the radiosity to display for every element.
pub struct Solution {
    /// The patches and elements the scene was cut into.
    pub mesh: Mesh,
    /// Each element's radiosity as drawn (the ambient term added where asked).
    pub elements: Vec<Vec3>,
    /// The part of each element's radiosity that came straight from the emitters
    /// (ρ_e Σ_j F_ej E_j), for a second pass that computes direct light itself;
    /// `None` after adaptive subdivision, which does not keep it.
    pub direct: Option<Vec<Vec3>>,
    /// How the elements are drawn.
    pub display: Display,
    /// What the solve did, for the terminal: steps or sweeps, unshot fraction.
    pub summary: String,
}

/// Meshes `scene` and checks it can be solved: every reflectance below 1 (checked
/// by the mesher), something emitting.
pub fn mesh(scene: &Scene, settings: &Settings) -> Result<Mesh> {
    if settings.subdivision.is_some() && settings.solver != Solver::Gathering {
        return Err(Error::Radiosity(
            "adaptive subdivision refines a gathering solution (Cohen et al. 1986): use the gathering solver, or leave `subdivide` out".into(),
        ));
    }
    if settings.solver == Solver::Gathering {
        // The stored factors dominate gathering's memory: refused first, with the
        // suggestion to shoot instead.
        let counts = Mesh::count(scene, settings.patches, settings.elements);
        let needed = gathering::matrix_bytes_for(counts.elements, counts.patches);
        if needed > settings.memory_budget {
            return Err(Error::Memory {
                elements: usize::try_from(counts.elements).unwrap_or(usize::MAX),
                patches: usize::try_from(counts.patches).unwrap_or(usize::MAX),
                needed,
                budget: settings.memory_budget,
            });
        }
    }
    let hemicubes = hemicube_bytes(settings);
    if hemicubes > settings.memory_budget {
        return Err(Error::OverBudget(Box::new(crate::error::OverBudget {
            key: "radiosity.resolution".into(),
            value: settings.resolution.to_string(),
            what: format!(
                "the hemi-cube's delta form-factor tables and the item buffers of {} hemi-cubes at once",
                rayon::current_num_threads()
            ),
            needed: hemicubes,
            budget: settings.memory_budget,
            budget_key: "radiosity.max_memory_mb".into(),
            suggestion: "use a lower resolution, or raise radiosity.max_memory_mb".into(),
        })));
    }
    if settings.subdivision.is_some() && light_sources::any(scene) {
        return Err(Error::Radiosity(
            "adaptive subdivision refines a solution lit by emitting polygons: leave `subdivide` out, or light the scene with polygon lights only".into(),
        ));
    }
    let mut mesh = Mesh::build_within(
        scene,
        settings.patches,
        settings.elements,
        settings.memory_budget,
        hemicubes,
    )?;
    light_sources::shine(scene, &mut mesh);
    if mesh.source_power().max_element() <= 0.0 {
        return Err(Error::Radiosity(
            "nothing lights the mesh: the scene has no emitting surface (a material with `emission`), and no light reaches a polygon's front: radiosity has no light to distribute".into(),
        ));
    }
    Ok(mesh)
}

impl Solution {
    /// What meshing the scene left out, one sentence each.
    pub fn warnings(&self) -> &[String] {
        &self.mesh.warnings
    }

    /// The solution without its direct part: what each element received after
    /// more than one bounce (its emission kept), for a second pass that adds the
    /// direct light itself. `None` if the solver did not keep the direct part.
    pub fn indirect(&self) -> Option<Solution> {
        let direct = self.direct.as_ref()?;
        Some(Solution {
            mesh: self.mesh.clone(),
            elements: self
                .elements
                .iter()
                .zip(direct)
                .map(|(b, d)| (*b - *d).max(Vec3::ZERO))
                .collect(),
            direct: None,
            display: self.display,
            summary: format!("{}; drawn without its direct part", self.summary),
        })
    }

    /// The solution without what the point, spot, distant and sphere lights gave
    /// the elements directly, for a display that adds those lights' direct light
    /// itself, exactly and shadowed, at every sample (their light stays in the
    /// interreflection). `None` if they gave nothing.
    pub fn without_light_sources(&self) -> Option<Solution> {
        if self.mesh.elements.iter().all(|e| e.received == Vec3::ZERO) {
            return None;
        }
        Some(Solution {
            mesh: self.mesh.clone(),
            elements: self
                .elements
                .iter()
                .zip(&self.mesh.elements)
                .map(|(b, e)| (*b - e.received).max(Vec3::ZERO))
                .collect(),
            direct: self.direct.clone(),
            display: self.display,
            summary: self.summary.clone(),
        })
    }
}

/// Per element, ρ_e Σ_j F_ej E_j over the emitting patches j, from its gathering row,
/// and what the element received from the lights shot into the solution.
fn direct_from_rows(mesh: &Mesh, rows: &[Vec<f32>]) -> Vec<Vec3> {
    let emitters: Vec<usize> = (0..mesh.patches.len())
        .filter(|&j| mesh.patches[j].emission.max_element() > 0.0)
        .collect();
    mesh.elements
        .iter()
        .zip(rows)
        .map(|(e, row)| {
            let gathered: Vec3 = emitters
                .iter()
                .map(|&j| mesh.patches[j].emission * row[j])
                .sum();
            mesh.patches[e.patch].reflectance * gathered + e.received
        })
        .collect()
}

/// The first pass's extension, when the scene's `[global]` method has one and the
/// scene has something for it to do (a mirror, a pane, a translucent panel, or a
/// mechanism left out); `None` gives plain radiosity, bit for bit.
pub fn extension(scene: &Scene) -> Option<extended::Extension> {
    use crate::settings::{GlobalMethod, Mechanisms};
    let g = scene.global.as_ref()?;
    let follow = match g.method {
        GlobalMethod::RayTracing | GlobalMethod::PathTracing | GlobalMethod::PhotonMap => {
            return None;
        }
        GlobalMethod::TwoPass => windows::Follow {
            mirrors: true,
            panes: false,
        },
        GlobalMethod::RushmeierTorrance => windows::Follow {
            mirrors: true,
            panes: true,
        },
    };
    let something = scene.materials.iter().any(|m| {
        m.mirror.max_element() > 0.0
            || m.transmittance.max_element() > 0.0
            || m.translucence.max_element() > 0.0
    });
    (something || g.mechanisms != Mechanisms::ALL).then_some(extended::Extension {
        follow,
        window_depth: g.window_depth,
        mechanisms: g.mechanisms,
    })
}

/// Memory the hemi-cube method holds, estimated: its delta form-factor tables (R² +
/// 4 × R²/2 of f64) once, and per thread one hemi-cube's item buffers (R² +
/// 4 × R²/2 of u32). Other methods hold no buffers of this size.
pub fn hemicube_bytes(settings: &Settings) -> u64 {
    if settings.form_factors != FormFactorMethod::Hemicube {
        return 0;
    }
    let r = settings.resolution as u64;
    let cells = 3 * r * r;
    let threads = rayon::current_num_threads() as u64;
    cells
        .saturating_mul(8)
        .saturating_add(cells.saturating_mul(4).saturating_mul(threads))
}

/// Solves `scene`'s radiosity with `settings`. `observe` sees the shooting solver
/// after each step (it is not called when gathering).
pub fn solve(
    scene: &Scene,
    settings: &Settings,
    observe: &mut dyn FnMut(&Mesh, &Shooting),
) -> Result<Solution> {
    let mesh = mesh(scene, settings)?;
    let estimator = Estimator::new(settings.form_factors, settings.resolution, scene);
    let extension = extension(scene);
    if extension.is_some() {
        if settings.solver != Solver::Gathering {
            return Err(Error::Radiosity(
                "the first pass through mirrors, panes and translucent panels gathers, as Wallace et al. and Rushmeier & Torrance solved it: set radiosity.solver = \"gathering\"".into(),
            ));
        }
        if settings.subdivision.is_some() {
            return Err(Error::Radiosity(
                "adaptive subdivision refines plain radiosity; leave `subdivide` out of a two-pass scene".into(),
            ));
        }
    }
    match settings.solver {
        Solver::Gathering => {
            let g = match extension {
                Some(extension) => extended::gather(
                    scene,
                    &mesh,
                    &estimator,
                    extension,
                    settings.tolerance,
                    settings.memory_budget,
                )?,
                None => gathering::gather(
                    &mesh,
                    &estimator,
                    settings.tolerance,
                    settings.memory_budget,
                )?,
            };
            let mut summary = format!(
                "gathering: {} patches, {} elements, Gauss-Seidel sweeps (r, g, b) {:?}",
                mesh.patches.len(),
                mesh.elements.len(),
                g.sweeps
            );
            let direct = direct_from_rows(&mesh, &g.element_factors);
            let (mesh, elements, direct) = match settings.subdivision {
                None => (mesh, g.elements, Some(direct)),
                Some(s) => {
                    let r = subdivision::refine(
                        mesh,
                        g.elements,
                        &g.patches,
                        &estimator,
                        s,
                        settings.memory_budget,
                    )?;
                    summary += &format!(
                        "; adaptive subdivision cut {:?} elements, {} in the end",
                        r.cut,
                        r.mesh.elements.len()
                    );
                    (r.mesh, r.elements, None)
                }
            };
            Ok(Solution {
                display: settings.display,
                elements: elements.iter().map(|b| b.as_vec3()).collect(),
                direct,
                mesh,
                summary,
            })
        }
        Solver::Shooting => {
            let mut state = Shooting::start(&mesh);
            let stop = Stop {
                unshot: settings.unshot,
                max_steps: settings.max_steps,
            };
            state.run(&mesh, &estimator, stop, &mut |s| observe(&mesh, s));
            let summary = format!(
                "shooting: {} patches, {} elements, {} steps, {:.3}% of the emitted power unshot",
                mesh.patches.len(),
                mesh.elements.len(),
                state.steps,
                100.0 * state.unshot_fraction(&mesh)
            );
            Ok(Solution {
                display: settings.display,
                elements: state.displayed(&mesh, settings.ambient),
                direct: Some(state.direct.clone()),
                mesh,
                summary,
            })
        }
    }
}
