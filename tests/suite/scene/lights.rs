//! What a light answers of its geometry (src/scene/lights.rs), which the shadow
//! methods, the media and the tracer ask instead of its kind: how it reaches the
//! scene, the polygon it is, its cone, where it moves, its polygon renumbered.

use glam::{DVec3, Vec3};
use lumiere::{Light, LightKind, Reach, load_scene};

/// One light of each kind in a scene: a floor, and the light.
fn light(kind: LightKind) -> Light {
    let text = match kind {
        LightKind::Point => {
            "type = \"point\"\nposition = [0.0, 2.0, 1.0]\nintensity = [5.0, 4.0, 3.0]"
        }
        LightKind::Spot => {
            "type = \"spot\"\nposition = [0.0, 2.0, 0.0]\naxis = [0.0, -1.0, 0.0]\ncone_angle = 30.0\nintensity = [4.0, 4.0, 4.0]"
        }
        LightKind::Distant => {
            "type = \"distant\"\ndirection = [0.0, -1.0, 0.0]\nirradiance = [1.0, 2.0, 3.0]"
        }
        LightKind::Sphere => {
            "type = \"sphere\"\ncentre = [0.5, 1.5, 0.0]\nradius = 0.25\nradiance = [2.0, 2.0, 2.0]"
        }
        LightKind::Polygon => {
            "type = \"area\"\nvertices = [[-0.5, 2.0, 0.5], [0.5, 2.0, 0.5], [0.5, 2.0, -0.5], [-0.5, 2.0, -0.5]]\nradiance = [1.0, 1.0, 1.0]"
        }
    };
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("light.toml");
    let scene = format!(
        "{}\n[materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\n\n[[lights]]\n{text}\n\n[[objects]]\nshape = \"quad\"\nmaterial = \"grey\"\ntransform = [{{ scale = 4.0 }}]\n",
        crate::support::camera([0.0, 1.5, 3.0], [0.0; 3], 50.0, 8, 6)
    );
    std::fs::write(&path, scene).unwrap();
    let mut scene = load_scene(path.to_str().unwrap(), &[]).unwrap();
    scene.lights.remove(0)
}

#[test]
fn each_kind_reaches_the_scene_as_its_geometry_says() {
    for kind in LightKind::ALL {
        let l = light(kind);
        let reach = l.reach();
        match kind {
            LightKind::Point => assert_eq!(
                reach,
                Reach::Point {
                    at: DVec3::new(0.0, 2.0, 1.0),
                    intensity: Vec3::new(5.0, 4.0, 3.0)
                }
            ),
            LightKind::Spot => {
                assert!(matches!(reach, Reach::Point { at, .. } if at == DVec3::new(0.0, 2.0, 0.0)))
            }
            LightKind::Distant => assert_eq!(
                reach,
                Reach::Direction {
                    direction: DVec3::new(0.0, -1.0, 0.0),
                    irradiance: Vec3::new(1.0, 2.0, 3.0)
                }
            ),
            LightKind::Sphere => assert_eq!(
                reach,
                Reach::Extended {
                    radiance: Vec3::splat(2.0)
                }
            ),
            LightKind::Polygon => assert_eq!(
                reach,
                Reach::Extended {
                    radiance: Vec3::ONE
                }
            ),
        }
        // The position is the point it reaches from, and nothing else has one.
        match reach {
            Reach::Point { at, .. } => assert_eq!(l.position(), Some(at)),
            Reach::Direction { .. } | Reach::Extended { .. } => assert_eq!(l.position(), None),
        }
        // Only a polygon light is a polygon of the scene: the floor is polygon 0.
        assert_eq!(
            l.emitter_polygon().is_some(),
            kind == LightKind::Polygon,
            "{kind}"
        );
    }
}

#[test]
fn a_spot_sends_its_cone_and_the_others_all_their_intensity() {
    let spot = light(LightKind::Spot);
    // On the axis, everything; 30° off it, at the cone's edge, less; beyond, none.
    assert_eq!(spot.cone_factor(DVec3::new(0.0, 0.0, 0.0)), 1.0);
    let outside = DVec3::new(2.0, 1.9, 0.0);
    assert_eq!(spot.cone_factor(outside), 0.0);
    for kind in [
        LightKind::Point,
        LightKind::Distant,
        LightKind::Sphere,
        LightKind::Polygon,
    ] {
        assert_eq!(light(kind).cone_factor(outside), 1.0, "{kind}");
    }
}

#[test]
fn lights_that_sit_somewhere_move_and_polygon_lights_follow_their_polygon() {
    let offset = DVec3::new(0.25, -0.5, 1.0);
    for kind in LightKind::ALL {
        let l = light(kind);
        match l.moved(offset) {
            Some(moved) => {
                assert!(matches!(
                    kind,
                    LightKind::Point | LightKind::Spot | LightKind::Sphere
                ));
                let place = |l: &Light| match l {
                    Light::Sphere(s) => s.centre,
                    other => other.position().unwrap(),
                };
                assert!(
                    (place(&moved) - place(&l) - offset).length() < 1e-12,
                    "{kind}"
                );
            }
            None => assert!(matches!(kind, LightKind::Distant | LightKind::Polygon)),
        }
    }
    let area = light(LightKind::Polygon);
    let polygon = area.emitter_polygon().unwrap();
    let mut map = vec![None; polygon + 1];
    assert!(area.renumbered(&map).is_none(), "left out with its polygon");
    map[polygon] = Some(7);
    assert_eq!(area.renumbered(&map).unwrap().emitter_polygon(), Some(7));
    let point = light(LightKind::Point);
    assert_eq!(point.renumbered(&[]).unwrap().position(), point.position());
}
