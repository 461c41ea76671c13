//! The shadow methods' registry: every method declares the lights it shadows and
//! renders exactly those (the others are refused before any work, naming the method
//! and the light); its declared name is the one the scene file reads; its declared
//! count buffer is the one its frames give; the registry lists every method.

use lumiere::Error;
use lumiere::LightKind;
use lumiere::Renderer;
use lumiere::settings::ShadowMethod;
use lumiere::shadow::{METHODS, method};

/// One light of each kind, as a scene file writes it.
fn light(kind: LightKind) -> &'static str {
    match kind {
        LightKind::Point => {
            "type = \"point\"\nposition = [0.0, 2.0, 1.0]\nintensity = [5.0, 5.0, 5.0]"
        }
        LightKind::Spot => {
            "type = \"spot\"\nposition = [0.0, 2.0, 0.0]\naxis = [0.0, -1.0, 0.0]\ncone_angle = 30.0\nintensity = [4.0, 4.0, 4.0]"
        }
        LightKind::Distant => {
            "type = \"distant\"\ndirection = [0.3, -1.0, 0.2]\nirradiance = [1.0, 1.0, 1.0]"
        }
        LightKind::Sphere => {
            "type = \"sphere\"\ncentre = [0.5, 1.5, 0.0]\nradius = 0.25\nradiance = [2.0, 2.0, 2.0]"
        }
        LightKind::Polygon => {
            "type = \"area\"\nvertices = [[-0.5, 2.0, 0.5], [0.5, 2.0, 0.5], [0.5, 2.0, -0.5], [-0.5, 2.0, -0.5]]\nradiance = [1.0, 1.0, 1.0]"
        }
    }
}

/// A floor, a box over it and one light of `kind`, shadowed by `name`.
fn scene_text(kind: LightKind, name: &str) -> String {
    format!(
        "{}[shadows]\nmethod = \"{name}\"\n\n\
         [materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\n\n\
         [[lights]]\n{}\n\n\
         [[objects]]\nshape = \"quad\"\nmaterial = \"grey\"\ntransform = [{{ scale = 4.0 }}]\n\n\
         [[objects]]\nshape = \"box\"\nmaterial = \"grey\"\ntransform = [{{ scale = 0.4 }}, {{ translate = [0.0, 0.5, 0.0] }}]\n",
        crate::support::camera([0.0, 1.5, 3.0], [0.0, 0.0, 0.0], 50.0, 24, 18),
        light(kind)
    )
}

fn load(dir: &std::path::Path, kind: LightKind, m: ShadowMethod) -> lumiere::Scene {
    let path = dir.join(format!("{}-{}.toml", m.name(), kind.name()));
    std::fs::write(&path, scene_text(kind, m.name())).unwrap();
    lumiere::load_scene(path.to_str().unwrap(), &[]).unwrap()
}

#[test]
fn the_registry_lists_every_method_once_under_its_scene_file_name() {
    let variants = <ShadowMethod as clap::ValueEnum>::value_variants();
    assert_eq!(METHODS.len(), variants.len());
    for m in variants {
        assert_eq!(METHODS.iter().filter(|n| *n == m).count(), 1, "{m:?}");
        let declared = method(*m);
        assert_eq!(declared.method, *m);
        let cli = clap::ValueEnum::to_possible_value(m).unwrap();
        assert_eq!(declared.name, cli.get_name(), "{m:?}");
    }
    let dir = tempfile::tempdir().unwrap();
    for m in METHODS {
        // The name the method declares is the one the scene file reads.
        assert_eq!(load(dir.path(), LightKind::Point, m).shadows.method, m);
    }
}

/// The lights each method's paper shadows, written out here, apart from the
/// registry: hard shadows from a point (Crow's volumes also from a direction),
/// Nishita & Nakamae and Brotman & Badler for polygons (a point is a polygon's
/// limit), the hexagonal cells for spheres, ray casting for all.
fn papers_lights(m: ShadowMethod) -> Vec<LightKind> {
    use LightKind::*;
    match m {
        ShadowMethod::None | ShadowMethod::RayCast => vec![Point, Spot, Distant, Sphere, Polygon],
        ShadowMethod::Scanline | ShadowMethod::ShadowPolygons | ShadowMethod::ShadowMap => {
            vec![Point, Spot]
        }
        ShadowMethod::ShadowVolumes | ShadowMethod::StencilShadowVolumes => {
            vec![Point, Spot, Distant]
        }
        ShadowMethod::UmbraPenumbra | ShadowMethod::SoftShadowVolumes => {
            vec![Point, Spot, Polygon]
        }
        ShadowMethod::JitteredSoftShadows => vec![Sphere],
    }
}

#[test]
fn each_method_declares_the_lights_its_paper_shadows() {
    for m in METHODS {
        let mut declared = method(m).lights.to_vec();
        let mut expected = papers_lights(m);
        declared.sort_by_key(|k| k.name());
        expected.sort_by_key(|k| k.name());
        assert_eq!(declared, expected, "{}", m.name());
    }
}

#[test]
fn each_method_renders_exactly_the_lights_it_declares() {
    let dir = tempfile::tempdir().unwrap();
    let mut rendered = 0;
    for m in METHODS {
        let declared = method(m);
        for kind in LightKind::ALL {
            let scene = load(dir.path(), kind, m);
            let renderer = Renderer::new(scene);
            let checked = renderer.check();
            let frame = renderer.render();
            if declared.lights.contains(&kind) {
                checked.unwrap_or_else(|e| panic!("{} refused {kind}: {e}", declared.name));
                let image = frame.unwrap_or_else(|e| panic!("{} on {kind}: {e}", declared.name));
                assert!(
                    image.pixels.iter().all(|p| p.is_finite()),
                    "{}",
                    declared.name
                );
                rendered += 1;
            } else {
                for result in [checked, frame.map(|_| ())] {
                    match result {
                        Err(Error::Unsupported(u)) => {
                            assert_eq!(u.method, m);
                            assert_eq!(u.name, declared.name);
                            let line = Error::Unsupported(u).to_string();
                            assert!(line.contains(declared.handles), "{line}");
                            assert!(line.contains(kind.name()), "{line}");
                        }
                        other => panic!("{} on {kind}: {:?}", declared.name, other.err()),
                    }
                }
            }
        }
    }
    // Every method shadows something; none shadows everything but ray casting and none.
    assert!(rendered >= METHODS.len() + 2 * 4, "{rendered}");
}

#[test]
fn a_method_s_frames_give_the_count_buffer_it_declares() {
    let dir = tempfile::tempdir().unwrap();
    for m in METHODS {
        let declared = method(m);
        let Some(kind) = declared.lights.first().copied() else {
            panic!("{} shadows no light", declared.name)
        };
        let renderer = Renderer::new(load(dir.path(), kind, m));
        let names: Vec<String> = renderer
            .available_buffers()
            .unwrap()
            .into_iter()
            .map(|b| b.name)
            .collect();
        let counted: Vec<&String> = names
            .iter()
            .filter(|n| {
                ["shadow-volume-counts-", "umbra-", "blocked-"]
                    .iter()
                    .any(|p| n.starts_with(p))
            })
            .collect();
        match declared.counts {
            Some(counts) => {
                assert_eq!(counted, [&counts.name(0)], "{}", declared.name);
                let frame = renderer.render_with_buffers(&[counts.name(0)]).unwrap();
                assert!(frame.buffer(&counts.name(0)).is_some(), "{}", declared.name);
            }
            None => assert!(counted.is_empty(), "{}: {counted:?}", declared.name),
        }
    }
}
