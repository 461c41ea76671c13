//! The method families a scene lets the viewer switch between: the global method
//! (Whitted, the two-pass methods), the radiosity solver (gathering, shooting),
//! a medium's single scattering (light volumes, ray marching), the shadow method,
//! the texture filter and the environment maps' layout. Each option is a list of
//! `key=value` overrides, checked on the scene before it is offered: an option the
//! renderer would refuse is not in the list.

use crate::catalogue;
use crate::error::Result;
use crate::render::Renderer;
use crate::render::integrators::{INTEGRATORS, Integrator, Role, declaration, direct_lights};
use crate::scene::{EnvironmentSource, Scene};
use crate::settings::{Filter, MediumMethod, ShadowMethod, Solver};
use crate::shadow;
use crate::texture::environment::Layout;

/// One family: its options and which the scene chose.
#[derive(Clone, Debug)]
pub struct Family {
    /// Its name in messages: `global`, `solver`, `shadows`, `filter`, `environment`.
    pub name: &'static str,
    /// What the page calls it.
    pub label: &'static str,
    pub options: Vec<Choice>,
}

/// One option of a family.
#[derive(Clone, Debug)]
pub struct Choice {
    /// Its name, as the scene file spells it.
    pub name: String,
    /// The paper it follows ("" where none).
    pub paper: String,
    /// The overrides that choose it.
    pub sets: Vec<String>,
}

/// Loads the scene with extra overrides (the session's source and its overrides).
pub type Load<'a> = dyn Fn(&[String]) -> Result<Scene> + 'a;

/// The families `scene` offers, the one the number keys switch first, each with
/// at least two options; and the option of each that the scene chose.
pub fn families(scene: &Scene, load: &Load) -> (Vec<Family>, Vec<usize>) {
    let mut found: Vec<(Family, usize)> = Vec::new();
    found.extend(global(scene, load));
    found.extend(solver(scene));
    found.extend(medium(scene, load));
    found.extend(shadows(scene));
    found.extend(filter(scene));
    found.extend(environment(scene));
    found
        .into_iter()
        .filter(|(f, _)| f.options.len() > 1)
        .unzip()
}

fn paper(entry: &str) -> String {
    catalogue::entry(entry)
        .map(|e| e.algorithm.authors)
        .unwrap_or_default()
}

fn set(key: &str, value: &str) -> String {
    format!("{key}=\"{value}\"")
}

/// Whitted's ray tracing and the two-pass methods, where the scene has `[global]`.
fn global(scene: &Scene, load: &Load) -> Option<(Family, usize)> {
    let current = scene.global.as_ref()?.method;
    let methods = INTEGRATORS.iter().filter_map(|&i| {
        let declared = declaration(i);
        declared.global_method.map(|m| (m, declared.role))
    });
    let candidates = methods.map(|(method, role)| {
        let mut sets = vec![set("global.method", method.name())];
        if role == Role::OwnFrame && scene.shadows.method != ShadowMethod::None {
            // A frame made by rays casts its own shadow rays (Whitted's).
            sets.push(set("shadows.method", "none"));
        }
        let choice = Choice {
            name: method.name().into(),
            paper: paper(method.name()),
            sets,
        };
        (method, choice)
    });
    let (options, chosen) = accepted(current, candidates, load);
    Some((
        Family {
            name: "global",
            label: "Global method",
            options,
        },
        chosen,
    ))
}

/// The candidates the renderer accepts once loaded (the scene's own always), and
/// where the scene's own is among them.
fn accepted<M: PartialEq>(
    current: M,
    candidates: impl IntoIterator<Item = (M, Choice)>,
    load: &Load,
) -> (Vec<Choice>, usize) {
    let mut options = Vec::new();
    let mut chosen = 0;
    for (method, choice) in candidates {
        if method == current {
            chosen = options.len();
        } else if !load(&choice.sets).is_ok_and(|s| Renderer::new(s).check().is_ok()) {
            continue;
        }
        options.push(choice);
    }
    (options, chosen)
}

/// Gathering and shooting, on a plain radiosity scene.
fn solver(scene: &Scene) -> Option<(Family, usize)> {
    let radiosity = scene.radiosity.as_ref()?;
    if scene.global.is_some() {
        // The first pass through mirrors gathers (the two-pass papers' solve).
        return None;
    }
    let mut options = vec![Choice {
        name: "gathering".into(),
        paper: paper("radiosity-gathering"),
        sets: vec![set("radiosity.solver", "gathering")],
    }];
    if radiosity.subdivision.is_none() {
        options.push(Choice {
            name: "shooting".into(),
            paper: paper("radiosity-shooting"),
            sets: vec![set("radiosity.solver", "shooting")],
        });
    }
    let chosen = match radiosity.solver {
        Solver::Gathering => 0,
        Solver::Shooting => options.len() - 1,
    };
    Some((
        Family {
            name: "solver",
            label: "Radiosity solver",
            options,
        },
        chosen,
    ))
}

/// Max's light volumes and the ray-marched reference, in a scene with a medium.
fn medium(scene: &Scene, load: &Load) -> Option<(Family, usize)> {
    let current = scene.medium.as_ref()?.method;
    let candidates = [
        (
            MediumMethod::LightVolumes,
            "light-volumes",
            paper("light-volumes-cornell"),
        ),
        (
            MediumMethod::RayMarching,
            "ray-marching",
            "the reference".into(),
        ),
    ]
    .map(|(method, name, paper)| {
        let sets = vec![set("medium.method", name)];
        let choice = Choice {
            name: name.into(),
            paper,
            sets,
        };
        (method, choice)
    });
    let (options, chosen) = accepted(current, candidates, load);
    Some((
        Family {
            name: "medium",
            label: "Single scattering",
            options,
        },
        chosen,
    ))
}

/// Every shadow method that can shadow the lights the frame lights directly.
fn shadows(scene: &Scene) -> Option<(Family, usize)> {
    let own_frame = declaration(Integrator::of(scene)).role == Role::OwnFrame;
    let direct = direct_lights(scene);
    if own_frame || !direct.contains(&true) {
        return None;
    }
    let mut options = Vec::new();
    let mut chosen = 0;
    for method in shadow::METHODS {
        let mut candidate = scene.clone();
        candidate.shadows.method = method;
        if Renderer::new(candidate).check().is_err() {
            continue;
        }
        if method == scene.shadows.method {
            chosen = options.len();
        }
        options.push(Choice {
            name: method.name().into(),
            paper: match shadow::method(method).entry {
                Some(entry) => paper(entry),
                None => "no shadows".into(),
            },
            sets: vec![set("shadows.method", method.name())],
        });
    }
    Some((
        Family {
            name: "shadows",
            label: "Shadow method",
            options,
        },
        chosen,
    ))
}

/// The texture filters, forced on every texture.
fn filter(scene: &Scene) -> Option<(Family, usize)> {
    let first = scene.textures.first()?;
    let filters = [
        (Filter::Nearest, ""),
        (Filter::Bilinear, ""),
        (Filter::MipNearest, "Williams 1983"),
        (Filter::Trilinear, "Williams 1983"),
        (Filter::SummedArea, "Crow 1984"),
    ];
    let chosen = filters.iter().position(|f| f.0 == first.filter)?;
    let options = filters
        .iter()
        .map(|(f, paper)| Choice {
            name: f.name().into(),
            paper: (*paper).into(),
            sets: scene
                .textures
                .iter()
                .map(|t| set(&format!("textures.{}.filter", t.name), f.name()))
                .collect(),
        })
        .collect();
    Some((
        Family {
            name: "filter",
            label: "Texture filter",
            options,
        },
        chosen,
    ))
}

/// The layouts of the scene's environment maps when all are procedural (an
/// image's layout is its file's; a captured map is a cube).
fn environment(scene: &Scene) -> Option<(Family, usize)> {
    let maps: Vec<_> = scene
        .environments
        .iter()
        .map(|e| match &e.source {
            EnvironmentSource::Map(map) if e.procedural => Some((e.name.clone(), map.layout())),
            EnvironmentSource::Map(_) | EnvironmentSource::Capture(_) => None,
        })
        .collect::<Option<_>>()?;
    let current = maps.first()?.1;
    let layouts = [
        (Layout::LatLong, "Blinn & Newell 1976"),
        (Layout::Sphere, "Miller & Hoffman 1984"),
        (Layout::Cube, "Greene 1986"),
    ];
    let chosen = layouts.iter().position(|l| l.0 == current)?;
    let options = layouts
        .into_iter()
        .map(|(layout, paper)| Choice {
            name: layout.name().into(),
            paper: paper.into(),
            sets: maps
                .iter()
                .map(|(name, _)| set(&format!("environments.{name}.layout"), layout.name()))
                .collect(),
        })
        .collect();
    Some((
        Family {
            name: "environment",
            label: "Environment layout",
            options,
        },
        chosen,
    ))
}
