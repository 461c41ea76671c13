//! The integrators' registry: every integrator is listed once; the scene file
//! chooses each by the name it declares; each reads exactly the scene keys it
//! declares (the others are refused before any work, naming the key) and makes
//! exactly the buffers it declares; its role is the way it makes its frame.

use crate::support::error_line;
use lumiere::render::integrators::{INTEGRATORS, Integrator, Role, declaration, declares_buffer};
use lumiere::{Renderer, Scene, load_scene};

/// Each integrator's position in the registry, written out so that a new one
/// fails to compile here until the test knows it.
fn listed_at(integrator: Integrator) -> usize {
    match integrator {
        Integrator::Direct => 0,
        Integrator::Radiosity => 1,
        Integrator::TwoPass => 2,
        Integrator::RushmeierTorrance => 3,
        Integrator::RayTracing => 4,
        Integrator::PathTracing => 5,
        Integrator::PhotonMap => 6,
    }
}

/// Every scene key an integrator may read, with a valid value to set it to (as
/// `--set` writes it), apart from the registry.
const KEYS: [(&str, &str); 19] = [
    ("radiosity", "radiosity.solver=\"gathering\""),
    ("global.depth", "global.depth=3"),
    ("global.samples", "global.samples=2"),
    ("global.photons", "global.photons=1000"),
    ("global.caustic_photons", "global.caustic_photons=1000"),
    ("global.nearest", "global.nearest=10"),
    ("global.caustic_nearest", "global.caustic_nearest=10"),
    (
        "global.precomputed_irradiance",
        "global.precomputed_irradiance=true",
    ),
    ("global.threshold", "global.threshold=0.01"),
    ("global.subdivisions", "global.subdivisions=1"),
    ("global.contrast", "global.contrast=0.1"),
    ("global.weights", "global.weights=\"fresnel\""),
    ("global.window_depth", "global.window_depth=1"),
    ("global.frustum_resolution", "global.frustum_resolution=4"),
    (
        "global.mechanisms",
        "global.mechanisms=[\"diffuse-diffuse\"]",
    ),
    ("global.exact_direct", "global.exact_direct=true"),
    ("global.analytic_spheres", "global.analytic_spheres=false"),
    ("global.ambient", "global.ambient=[0.1, 0.1, 0.1]"),
    ("global.final_gather", "global.final_gather={rays=16}"),
];

/// The keys each method's paper reads, written out here: Whitted's tracer its ray
/// tree, antialiasing, weights, spheres and ambient term; the two-pass methods the
/// radiosity solution, the ray tree of pass 2, mirror windows, the reflection
/// frustum, the mechanisms, exact direct light and the final gather; Kajiya's path
/// tracer its paths' depth, their number and the spheres; Jensen's photon map
/// those, its two maps' photons and estimates, its final gather, and Christensen's
/// precomputed irradiance.
fn papers_keys(integrator: Integrator) -> Vec<&'static str> {
    let two_pass = vec![
        "radiosity",
        "global.depth",
        "global.threshold",
        "global.window_depth",
        "global.frustum_resolution",
        "global.mechanisms",
        "global.exact_direct",
        "global.final_gather",
    ];
    match integrator {
        Integrator::Direct => vec![],
        Integrator::Radiosity => vec!["radiosity"],
        Integrator::TwoPass | Integrator::RushmeierTorrance => two_pass,
        Integrator::RayTracing => vec![
            "global.depth",
            "global.threshold",
            "global.subdivisions",
            "global.contrast",
            "global.weights",
            "global.analytic_spheres",
            "global.ambient",
        ],
        Integrator::PathTracing => {
            vec!["global.depth", "global.samples", "global.analytic_spheres"]
        }
        Integrator::PhotonMap => vec![
            "global.depth",
            "global.samples",
            "global.analytic_spheres",
            "global.photons",
            "global.caustic_photons",
            "global.nearest",
            "global.caustic_nearest",
            "global.precomputed_irradiance",
            "global.final_gather",
        ],
    }
}

/// A catalogue entry each integrator renders, at 8 × 6 pixels, with `sets`.
fn entry(integrator: Integrator, sets: &[&str]) -> lumiere::Result<Scene> {
    let id = match integrator {
        Integrator::Direct => "cornell-box-point",
        Integrator::Radiosity => "radiosity-gathering",
        Integrator::TwoPass => "two-pass-final-gather",
        Integrator::RushmeierTorrance => "rushmeier-torrance",
        Integrator::RayTracing => "ray-tracing",
        Integrator::PathTracing => "path-tracing",
        Integrator::PhotonMap => "photon-map",
    };
    let mut all = vec!["camera.width=8".to_string(), "camera.height=6".to_string()];
    all.extend(sets.iter().map(|s| s.to_string()));
    load_scene(id, &all)
}

#[test]
fn the_registry_lists_every_integrator_once_and_the_scene_file_chooses_it_by_name() {
    for (at, &integrator) in INTEGRATORS.iter().enumerate() {
        assert_eq!(listed_at(integrator), at);
        let declared = declaration(integrator);
        assert_eq!(declared.integrator, integrator);
        assert_eq!(integrator.name(), declared.name);
        // Its entry, and the scene this test renders it with, choose it.
        let shown = load_scene(declared.entry, &[]).unwrap();
        assert_eq!(Integrator::of(&shown), integrator, "{}", declared.entry);
        assert_eq!(Integrator::of(&entry(integrator, &[]).unwrap()), integrator);
        assert_eq!(Renderer::new(shown).integrator(), integrator);
    }
    // The methods `[global] method` chooses: by their declared names, each its own.
    let base = entry(Integrator::RushmeierTorrance, &[]).unwrap();
    let mut chosen = 0;
    for integrator in INTEGRATORS {
        let declared = declaration(integrator);
        let Some(method) = declared.global_method else {
            continue;
        };
        assert_eq!(method.name(), declared.name);
        let mut scene = base.clone();
        scene.global.as_mut().unwrap().method = method;
        assert_eq!(Integrator::of(&scene), integrator, "{}", declared.name);
        chosen += 1;
    }
    assert_eq!(
        chosen, 5,
        "ray tracing, the two two-pass methods, path tracing and the photon map"
    );
}

#[test]
fn each_integrator_declares_the_keys_its_paper_reads() {
    for integrator in INTEGRATORS {
        let mut declared = declaration(integrator).keys.to_vec();
        let mut expected = papers_keys(integrator);
        declared.sort();
        expected.sort();
        assert_eq!(declared, expected, "{}", integrator.name());
        for key in declared {
            assert!(
                KEYS.iter().any(|(k, _)| *k == key),
                "{key} is not a known key"
            );
        }
    }
}

/// Whether a scene of `integrator` with `set` is accepted before any work: it
/// loads, and the renderer's check passes.
fn accepted(integrator: Integrator, set: &[&str]) -> Result<(), String> {
    let scene = entry(integrator, set).map_err(|e| error_line(&e))?;
    Renderer::new(scene).check().map_err(|e| error_line(&e))
}

#[test]
fn each_integrator_chosen_by_global_method_accepts_exactly_the_keys_it_declares() {
    for integrator in [
        Integrator::TwoPass,
        Integrator::RushmeierTorrance,
        Integrator::RayTracing,
        Integrator::PathTracing,
        Integrator::PhotonMap,
    ] {
        let declared = declaration(integrator);
        accepted(integrator, &[]).unwrap();
        for (key, set) in KEYS {
            // The final gather reads a solution beside the exact direct light.
            let mut sets = vec![set];
            if key == "global.final_gather" && declared.keys.contains(&"global.exact_direct") {
                sets.push("global.exact_direct=true");
            }
            let outcome = accepted(integrator, &sets);
            if declared.keys.contains(&key) {
                outcome.unwrap_or_else(|e| panic!("{} refused {key}: {e}", declared.name));
            } else {
                let error = outcome.expect_err(&format!("{} accepted {key}", declared.name));
                assert!(error.contains(key), "{}: {error}", declared.name);
            }
        }
    }
    // Ray tracing reads no radiosity solution: a [radiosity] table is refused.
    let error = accepted(Integrator::RayTracing, &["radiosity.solver=\"gathering\""]).unwrap_err();
    assert!(
        error.contains("[radiosity] is read by radiosity, two-pass, rushmeier-torrance"),
        "{error}"
    );
}

/// Every buffer any integrator declares.
fn declared_by_some(name: &str) -> bool {
    INTEGRATORS
        .iter()
        .any(|&i| declares_buffer(declaration(i), name))
}

#[test]
fn each_integrator_makes_exactly_the_buffers_it_declares_in_its_role() {
    for integrator in INTEGRATORS {
        let declared = declaration(integrator);
        // Rushmeier & Torrance's box with the final gather, whose cache's records
        // are a buffer.
        let sets: &[&str] = match integrator {
            Integrator::RushmeierTorrance => {
                &["global.exact_direct=true", "global.final_gather={rays=16}"]
            }
            _ => &[],
        };
        let renderer = Renderer::new(entry(integrator, sets).unwrap());
        let available: Vec<String> = renderer
            .available_buffers()
            .unwrap()
            .into_iter()
            .map(|b| b.name)
            .collect();
        // An integrator's buffers among those the frame offers: its own, all of them.
        let own: Vec<&String> = available.iter().filter(|n| declared_by_some(n)).collect();
        for name in &own {
            assert!(declares_buffer(declared, name), "{}: {name}", declared.name);
        }
        for pattern in declared.buffers {
            assert!(
                own.iter().any(|n| declares_buffer(declared, n)
                    && (n.as_str() == *pattern || pattern.ends_with('*'))),
                "{} declares {pattern} but does not offer it: {available:?}",
                declared.name
            );
        }
        // Its own frame makes them all, the image too.
        let frame = renderer.render_with_buffers(&available).unwrap();
        assert_eq!(frame.buffers.len(), available.len(), "{}", declared.name);
        assert!(frame.image.pixels.iter().all(|p| p.is_finite()));
        // A frame made by the integrator itself offers nothing but its own buffers.
        if declared.role == Role::OwnFrame {
            assert_eq!(own.len(), available.len(), "{available:?}");
        }
    }
}
