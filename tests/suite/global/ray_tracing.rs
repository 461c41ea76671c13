//! Whitted's recursive ray tracing proved right: his direction formulas against
//! Snell's law and the mirror law, hits against the surfaces' own equations, a glass
//! slab's sideways shift against its closed form, a mirror sphere's image of a
//! corner against the reflection point solved independently, shadows against the
//! scan-line pass's ray-cast shadows, and the adaptive antialiasing against a densely
//! supersampled image.

use crate::support;

use glam::{DMat3, DVec3, Vec3};
use lumiere::BufferData;
use lumiere::Renderer;
use lumiere::Scene;
use lumiere::global::TracedScene;
use lumiere::global::traced_scene::{Leaving, SurfaceHit};
use lumiere::global::whitted::{Whitted, reflected_direction, refracted_direction};
use lumiere::raster::View;
use lumiere::settings::GlobalSettings;
use lumiere::shading::optics;
use proptest::prelude::*;
use support::{camera, error_line, scene_from_text};

/// `[global]` settings of the ray tracer, from the lines of a scene file's section
/// (validated as a scene file's are).
fn global(lines: &str) -> GlobalSettings {
    let text = format!("method = \"ray-tracing\"\n{lines}");
    let file: lumiere::scene::file::GlobalFile = toml::from_str(&text).unwrap();
    lumiere::scene::global_settings::from_file(&file)
        .unwrap_or_else(|e| panic!("{}", error_line(&e)))
}

fn object_index(scene: &Scene, name: &str) -> usize {
    scene
        .objects
        .iter()
        .position(|o| o.name == name)
        .unwrap_or_else(|| panic!("no object {name}"))
}

/// Whitted's normal on the side the ray comes from, as `shade` takes it.
fn incident_side(hit: &SurfaceHit, direction: DVec3) -> (DVec3, bool) {
    let front = direction.dot(hit.geometric_normal) < 0.0;
    (if front { hit.normal } else { -hit.normal }, front)
}

// ---------------------------------------------------------------------------------
// 1. Whitted's direction identities.
// ---------------------------------------------------------------------------------

fn unit_vector() -> impl Strategy<Value = DVec3> {
    (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64).prop_filter_map(
        "inside the unit ball",
        |(x, y, z)| {
            let v = DVec3::new(x, y, z);
            (v.length() > 0.1 && v.length() <= 1.0).then(|| v.normalize())
        },
    )
}

/// An incident direction (unit, travelling towards the surface: V·N < 0) and the
/// unit normal, at least 0.06° away from grazing.
fn incidence() -> impl Strategy<Value = (DVec3, DVec3)> {
    (unit_vector(), unit_vector()).prop_filter_map("not grazing", |(v, n)| {
        let v = if v.dot(n) > 0.0 { -v } else { v };
        (v.dot(n) < -1e-3).then_some((v, n))
    })
}

/// The unit vector normal to the plane of V and N, where they span one.
fn plane_normal(v: DVec3, n: DVec3) -> Option<DVec3> {
    let axis = v.cross(n);
    (axis.length() > 1e-3).then(|| axis.normalize())
}

/// The component of `a` along the surface (perpendicular to unit `n`).
fn tangential(a: DVec3, n: DVec3) -> DVec3 {
    a - a.dot(n) * n
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(4000))]

    /// R = V' + 2N: unit, on the incident side, at the angle to N that V makes (cos
    /// θ_r = −V·N), in the plane of V and N, with V's tangential component kept; the
    /// same as the textbook mirror direction; and independent of |V| (V' divides it
    /// out).
    #[test]
    fn the_reflected_direction_obeys_the_mirror_law(
        (v, n) in incidence(),
        length in 0.01..100.0f64,
    ) {
        let r = reflected_direction(v * length, n);
        prop_assert!((r.length() - 1.0).abs() <= 1e-12, "|R| = {}", r.length());
        // Equal angles with N (on either side of it).
        prop_assert!((r.dot(n) + v.dot(n)).abs() <= 1e-12, "R·N {} vs −V·N {}", r.dot(n), -v.dot(n));
        if let Some(axis) = plane_normal(v, n) {
            prop_assert!(r.dot(axis).abs() <= 1e-12, "out of the plane by {}", r.dot(axis));
        }
        prop_assert!((tangential(r, n) - tangential(v, n)).length() <= 1e-12);
        prop_assert!((r - optics::reflect(-v, n)).length() <= 1e-12);
    }

    /// P = k_f (N + V') − N with k_n = n₂/n₁: where it exists, n₁ sin θ₁ = n₂ sin θ₂,
    /// P in the plane of V and N, on the far side, bent the same way round as V goes
    /// (its tangential part along V's), and the same direction as the textbook
    /// vector form in `optics::refract`; it exists exactly when sin θ₁ < n₂/n₁
    /// (checked outside the last 1e-3 under the critical angle, which the next test
    /// probes).
    #[test]
    fn the_refracted_direction_obeys_snells_law(
        (v, n) in incidence(),
        k_n in 0.2..5.0f64,
        length in 0.01..100.0f64,
    ) {
        let sin1 = v.cross(n).length();
        let p = refracted_direction(v * length, n, k_n);
        let reference = optics::refract(v, n, 1.0 / k_n);
        if sin1 >= k_n * (1.0 + 1e-9) {
            prop_assert!(p.is_none(), "sin θ₁ {sin1} > k_n {k_n}: {p:?}");
            prop_assert!(reference.is_none());
        } else if sin1 <= k_n * (1.0 - 1e-3) {
            let p = p.expect("a transmitted ray below the critical angle");
            let reference = reference.unwrap();
            prop_assert!((p.length() - 1.0).abs() <= 1e-12);
            let sin2 = p.cross(n).length();
            // n₁ = 1, n₂ = k_n.
            prop_assert!((sin1 - k_n * sin2).abs() <= 1e-12, "{sin1} vs {}", k_n * sin2);
            prop_assert!(p.dot(n) < 0.0, "P does not cross the surface");
            if let Some(axis) = plane_normal(v, n) {
                prop_assert!(p.dot(axis).abs() <= 1e-12, "out of the plane by {}", p.dot(axis));
                prop_assert!(tangential(p, n).dot(tangential(v, n)) > 0.0);
            }
            prop_assert!((p - reference).length() <= 1e-12, "{p} vs {reference}");
        }
    }
}

/// Total internal reflection begins exactly at θ_c = asin(n₂/n₁): 1e-10 rad below it
/// a transmitted ray exists and grazes the surface (θ₂ within 1e-4 rad of 90°);
/// 1e-10 rad above it there is none. Over indices from water to diamond and
/// beyond, and normals and planes of incidence all round.
#[test]
fn total_internal_reflection_begins_at_the_critical_angle() {
    let mut cases = 0;
    for n1 in [1.1, 1.33, 1.5, 1.9, 2.42, 4.0] {
        // Leaving the denser medium into vacuum, and into a less dense one.
        for n2 in [1.0, 1.05] {
            let k_n: f64 = n2 / n1;
            let critical = k_n.asin();
            for a in 0..7 {
                let n = DVec3::new(
                    (a as f64 * 0.9).cos() * 0.6,
                    (a as f64 * 1.7).sin(),
                    0.3 + 0.1 * a as f64,
                )
                .normalize();
                let t0 = n.any_orthonormal_vector();
                let t1 = n.cross(t0);
                for b in 0..9 {
                    let phi = b as f64 * 0.77;
                    let t = t0 * phi.cos() + t1 * phi.sin();
                    let v = |theta: f64| t * theta.sin() - n * theta.cos();
                    let below = refracted_direction(v(critical - 1e-10), n, k_n);
                    let above = refracted_direction(v(critical + 1e-10), n, k_n);
                    let p = below.unwrap_or_else(|| {
                        panic!(
                            "n1 {n1} n2 {n2}: no transmitted ray 1e-10 rad below the critical angle"
                        )
                    });
                    assert!(p.dot(n).abs() < 1e-4, "not grazing: P·N = {}", p.dot(n));
                    assert!(
                        above.is_none(),
                        "n1 {n1} n2 {n2}: a transmitted ray 1e-10 rad above the critical angle"
                    );
                    // Entering the denser medium, no angle reflects totally.
                    assert!(refracted_direction(v(critical + 1e-10), n, 1.0 / k_n).is_some());
                    cases += 1;
                }
            }
        }
    }
    assert_eq!(cases, 6 * 2 * 7 * 9);
}

// ---------------------------------------------------------------------------------
// 2. Hits satisfy the surface equations.
// ---------------------------------------------------------------------------------

/// A small deterministic generator (xorshift), for reproducible rays.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
    fn unit(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            if v.length() > 0.1 && v.length() <= 1.0 {
                return v.normalize();
            }
        }
    }
}

/// An ellipsoid as the scene file makes it: the unit sphere scaled by `axes`,
/// rotated by `degrees` about `axis`, moved to `centre`; its equation
/// f(p) = |S⁻¹ Rᵀ (p − c)|² = 1, written here from the parameters alone.
struct Ellipsoid {
    axes: DVec3,
    rotation: DMat3,
    centre: DVec3,
}

impl Ellipsoid {
    fn new(axes: [f64; 3], axis: [f64; 3], degrees: f64, centre: [f64; 3]) -> Ellipsoid {
        Ellipsoid {
            axes: DVec3::from(axes),
            rotation: DMat3::from_axis_angle(DVec3::from(axis).normalize(), degrees.to_radians()),
            centre: DVec3::from(centre),
        }
    }

    fn transform(&self, axis: [f64; 3], degrees: f64) -> String {
        format!(
            "[{{ scale = {:?} }}, {{ rotate = {{ axis = {axis:?}, degrees = {degrees} }} }}, {{ translate = {:?} }}]",
            self.axes.to_array(),
            self.centre.to_array()
        )
    }

    /// Unit-sphere coordinates of p.
    fn local(&self, p: DVec3) -> DVec3 {
        (self.rotation.transpose() * (p - self.centre)) / self.axes
    }

    fn f(&self, p: DVec3) -> f64 {
        self.local(p).length_squared()
    }

    /// ∇f / 2: the outward normal's direction.
    fn gradient(&self, p: DVec3) -> DVec3 {
        self.rotation * (self.local(p) / self.axes)
    }

    /// The roots of f(o + t d) = 1, in order.
    fn roots(&self, o: DVec3, d: DVec3) -> Option<(f64, f64)> {
        let lo = self.local(o);
        let ld = (self.rotation.transpose() * d) / self.axes;
        let (a, b, c) = (
            ld.length_squared(),
            2.0 * lo.dot(ld),
            lo.length_squared() - 1.0,
        );
        let disc = b * b - 4.0 * a * c;
        (disc > 0.0).then(|| {
            let q = -0.5 * (b + disc.sqrt().copysign(b));
            let (t0, t1) = (q / a, c / q);
            (t0.min(t1), t0.max(t1))
        })
    }
}

/// The scene of one built-in sphere under `transform`, alone.
fn one_sphere(transform: &str) -> Scene {
    let text = format!(
        "{}[materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\n\
         [[objects]]\nshape = \"sphere\"\nname = \"ball\"\nmaterial = \"grey\"\nresolution = 12\ntransform = {transform}\n",
        camera([0.0, 0.0, 9.0], [0.0, 0.0, 0.0], 40.0, 8, 8)
    );
    scene_from_text(&text, &[])
}

/// Checks every quadric hit of many rays (from outside, from inside and from the
/// surface itself) against the ellipsoid's equation; returns the hits checked.
fn check_quadric(e: &Ellipsoid, scene: &Scene, rng: &mut Rng) -> usize {
    let traced = TracedScene::new(scene, true);
    let ball = object_index(scene, "ball");
    let size = e.axes.max_element();
    let mut checked = 0;
    let check = |hit: &SurfaceHit, origin: DVec3, direction: DVec3, what: &str| {
        let p = hit.position;
        assert_eq!(hit.polygon, None, "{what}: not the quadric");
        assert_eq!(hit.object, ball);
        let f = e.f(p);
        assert!((f - 1.0).abs() <= 1e-12, "{what}: f(p) − 1 = {:e}", f - 1.0);
        assert!(
            (origin + direction * hit.t - p).length() <= 1e-12 * (origin.length() + size),
            "{what}: not on the ray"
        );
        assert!(
            (hit.normal.length() - 1.0).abs() <= 1e-12,
            "{what}: |N| = {}",
            hit.normal.length()
        );
        let g = e.gradient(p).normalize();
        assert!(
            hit.normal.cross(g).length() <= 1e-12,
            "{what}: N not along ∇f"
        );
        assert!(hit.normal.dot(g) > 0.0, "{what}: N points inwards");
        assert_eq!(hit.geometric_normal, hit.normal);
    };
    for _ in 0..400 {
        // From outside, at points around the ellipsoid: the nearer root.
        let origin = e.centre + rng.unit() * (4.0 * size);
        let aim = e.centre + rng.unit() * (1.2 * size * rng.next());
        let d = (aim - origin).normalize();
        let hit = traced.closest(origin, d, f64::INFINITY, Leaving::Eye);
        match e.roots(origin, d) {
            Some((t0, t1)) if t1 - t0 > 1e-6 * size => {
                let hit = hit.expect("the ray meets the ellipsoid");
                check(&hit, origin, d, "outside");
                assert!((hit.t - t0).abs() <= 1e-12 * t0, "t {} vs {t0}", hit.t);
                assert!(hit.normal.dot(d) < 0.0);
                checked += 1;
                // From the surface, into it: the far side, never the point left.
                let inward = (-hit.normal + rng.unit() * 0.9).normalize();
                if inward.dot(hit.normal) < -0.05 {
                    let far = traced
                        .closest(hit.position, inward, f64::INFINITY, hit.leaving())
                        .expect("the far side");
                    check(&far, hit.position, inward, "from the surface, inwards");
                    assert!(far.t > 1e-3 * size, "met the point it left: t = {}", far.t);
                    assert!(far.normal.dot(inward) > 0.0);
                    checked += 1;
                }
                // From the surface, outwards: nothing else in the scene.
                let outward = (hit.normal + rng.unit() * 0.9).normalize();
                if outward.dot(hit.normal) > 0.05 {
                    assert_eq!(
                        traced.closest(hit.position, outward, f64::INFINITY, hit.leaving()),
                        None
                    );
                    // A shadow ray outwards is clear; one through the body is blocked.
                    let far = hit.position + outward * (3.0 * size);
                    assert!(!traced.blocked(hit.position, far, hit.leaving(), None));
                    let through = hit.position - hit.normal * (3.0 * size);
                    assert!(traced.blocked(hit.position, through, hit.leaving(), None));
                }
            }
            Some(_) => {}
            None => assert_eq!(hit, None, "a hit where the ellipsoid is missed"),
        }
        // From inside: every ray meets it, from within, outward normal.
        let inside = e.centre + e.rotation * (e.axes * rng.unit() * 0.8 * rng.next());
        let d = rng.unit();
        let hit = traced
            .closest(inside, d, f64::INFINITY, Leaving::Eye)
            .expect("a ray from inside meets the ellipsoid");
        check(&hit, inside, d, "inside");
        assert!(hit.normal.dot(d) > 0.0);
        let (_, t1) = e.roots(inside, d).unwrap();
        assert!((hit.t - t1).abs() <= 1e-12 * (t1 + size));
        checked += 1;
    }
    checked
}

/// Hits on an analytic sphere (radius 0.7, off the origin) and on a non-uniformly
/// scaled, rotated one (an ellipsoid) satisfy the quadric's equation to 1e-12, with
/// unit outward normals along its gradient, at the nearer root from outside and the
/// far one from inside or from the surface itself; polygon hits lie in the
/// polygon's plane, within it, with its normal.
#[test]
fn hits_satisfy_the_surface_equations() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let sphere = Ellipsoid::new([0.7; 3], [0.0, 1.0, 0.0], 0.0, [1.0, 0.5, -2.0]);
    let scene = one_sphere(&sphere.transform([0.0, 1.0, 0.0], 0.0));
    let n_sphere = check_quadric(&sphere, &scene, &mut rng);
    let (axis, degrees) = ([0.3, 1.0, 0.2], 35.0);
    let egg = Ellipsoid::new([1.5, 0.6, 0.9], axis, degrees, [-1.2, 0.3, -1.0]);
    let scene = one_sphere(&egg.transform(axis, degrees));
    let n_egg = check_quadric(&egg, &scene, &mut rng);
    assert!(n_sphere > 500 && n_egg > 500, "{n_sphere} {n_egg} hits");

    // A tilted square tile 3 across.
    let (axis, degrees, centre) = ([1.0, 0.2, 0.0], 50.0f64, DVec3::new(0.2, -1.0, -1.0));
    let text = format!(
        "{}[materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\n\
         [[objects]]\nshape = \"quad\"\nname = \"tile\"\nmaterial = \"grey\"\n\
         transform = [{{ scale = 3.0 }}, {{ rotate = {{ axis = {axis:?}, degrees = {degrees} }} }}, {{ translate = {:?} }}]\n",
        camera([0.0, 0.0, 9.0], [0.0, 0.0, 0.0], 40.0, 8, 8),
        centre.to_array()
    );
    let scene = scene_from_text(&text, &[]);
    let traced = TracedScene::new(&scene, true);
    let rotation = DMat3::from_axis_angle(DVec3::from(axis).normalize(), degrees.to_radians());
    let normal = rotation * DVec3::Y;
    let (u, w) = (rotation * DVec3::X, rotation * DVec3::Z);
    let mut hits = 0;
    for _ in 0..2000 {
        let origin = centre + rng.unit() * 6.0;
        let aim = centre + u * rng.range(-2.0, 2.0) + w * rng.range(-2.0, 2.0);
        let d = (aim - origin).normalize();
        let (a, b) = ((aim - centre).dot(u), (aim - centre).dot(w));
        let hit = traced.closest(origin, d, f64::INFINITY, Leaving::Eye);
        // Clear of the edges by 1e-9: inside or outside for certain.
        if a.abs().max(b.abs()) < 1.5 - 1e-9 {
            let hit = hit.expect("a hit inside the tile");
            let p = hit.position;
            let polygon = hit.polygon.expect("the tile's polygon") as usize;
            assert!(
                (p - centre).dot(normal).abs() <= 1e-12 * 8.0,
                "off the plane by {}",
                (p - centre).dot(normal)
            );
            assert!((scene.polygons[polygon].normal - normal).length() <= 1e-12);
            assert_eq!(hit.geometric_normal, scene.polygons[polygon].normal);
            assert!((p - aim).length() <= 1e-12 * 8.0, "{p} vs {aim}");
            assert!((origin + d * hit.t - p).length() <= 1e-12 * 8.0);
            hits += 1;
        } else if a.abs().max(b.abs()) > 1.5 + 1e-9 {
            assert_eq!(hit, None);
        }
    }
    assert!(hits > 1000, "{hits} hits");

    // The ellipsoid cut by a floor through its centre: whichever the ray meets
    // first, quadric or polygon, is the hit (against both closed forms).
    let text = format!(
        "{}[materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\n\
         [[objects]]\nshape = \"sphere\"\nname = \"ball\"\nmaterial = \"grey\"\nresolution = 12\ntransform = {}\n\
         [[objects]]\nshape = \"quad\"\nname = \"floor\"\nmaterial = \"grey\"\n\
         transform = [{{ scale = 8.0 }}, {{ translate = [0.0, {}, 0.0] }}]\n",
        camera([0.0, 0.0, 9.0], [0.0, 0.0, 0.0], 40.0, 8, 8),
        egg.transform([0.3, 1.0, 0.2], 35.0),
        egg.centre.y
    );
    let scene = scene_from_text(&text, &[]);
    let traced = TracedScene::new(&scene, true);
    let floor = object_index(&scene, "floor");
    let (mut on_ball, mut on_floor) = (0, 0);
    for _ in 0..2000 {
        let origin = egg.centre + rng.unit() * 5.0;
        let aim = egg.centre + rng.unit() * 1.6;
        let d = (aim - origin).normalize();
        let t_plane = (egg.centre.y - origin.y) / d.y;
        let p = origin + d * t_plane;
        let in_floor = t_plane > 0.0 && (p.x.abs().max(p.z.abs()) < 4.0 - 1e-9);
        let t_ball = egg.roots(origin, d).map(|(t0, _)| t0).filter(|&t| t > 0.0);
        let hit = traced.closest(origin, d, f64::INFINITY, Leaving::Eye);
        let expected = match (in_floor.then_some(t_plane), t_ball) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
        match (hit, expected) {
            (Some(hit), Some(t)) => {
                assert!((hit.t - t).abs() <= 1e-9 * t, "t {} vs {t}", hit.t);
                if hit.object == floor {
                    on_floor += 1;
                } else {
                    on_ball += 1;
                }
            }
            (None, None) => {}
            (hit, t) => panic!("{hit:?} where {t:?} was expected"),
        }
    }
    assert!(on_ball > 300 && on_floor > 300, "{on_ball} {on_floor}");
}

// ---------------------------------------------------------------------------------
// 3. A glass slab with parallel faces.
// ---------------------------------------------------------------------------------

/// A glass slab (index 1.5) `thickness` thick, faces at y = ±thickness/2, 40 wide;
/// under it, at y = −`depth`, an emitting square whose edge runs along x = `edge`
/// (it covers x > edge); the backdrop black.
fn slab(thickness: f64, depth: f64, edge: f64) -> Scene {
    let text = format!(
        "{}[render]\nbackground = [0.0, 0.0, 0.0]\n\
         [materials.glass]\ndiffuse = [0.0, 0.0, 0.0]\ntransmittance = [0.9, 0.9, 0.9]\nior = 1.5\n\
         [materials.lamp]\ndiffuse = [0.0, 0.0, 0.0]\nemission = [1.0, 1.0, 1.0]\n\
         [[objects]]\nshape = \"box\"\nname = \"slab\"\nmaterial = \"glass\"\ntransform = [{{ scale = [40.0, {thickness}, 40.0] }}]\n\
         [[objects]]\nshape = \"quad\"\nname = \"target\"\nmaterial = \"lamp\"\n\
         transform = [{{ scale = 30.0 }}, {{ translate = [{}, {}, 0.0] }}]\n\
         [global]\nmethod = \"ray-tracing\"\n",
        camera([0.0, 5.0, 5.0], [0.0, 0.0, 0.0], 40.0, 8, 8),
        edge + 15.0,
        -depth
    );
    scene_from_text(&text, &[])
}

/// A ray through the slab, followed as Whitted's `shade` follows it (normals on the
/// incident side; k_n = 1.5 entering, 1/1.5 leaving), leaves along its own
/// direction, shifted sideways by d·sin(θ₁ − θ₂)/cos θ₂, to 1e-9; inside it obeys
/// Snell's law. Then Whitted's tracer itself, eye rays through the slab onto an
/// emitting square below: the square's edge is seen where the shifted rays put it
/// (found by bisection to 1e-12, against the closed form to 1e-9), not where
/// straight rays would.
#[test]
fn a_glass_slab_shifts_rays_sideways_and_keeps_their_direction() {
    let (thickness, depth, edge) = (0.5, 2.0, 0.3);
    let scene = slab(thickness, depth, edge);
    let traced = TracedScene::new(&scene, true);
    let glass = &scene.materials[scene.polygons[0].material];
    assert_eq!(glass.ior, Some(1.5));
    let top = thickness / 2.0;
    let mut followed = 0;
    for degrees in [0.0f64, 5.0, 20.0, 35.0, 50.0, 65.0, 80.0, 88.0] {
        let theta1 = degrees.to_radians();
        let theta2 = (theta1.sin() / 1.5).asin();
        let shift = thickness * (theta1 - theta2).sin() / theta2.cos();
        for azimuth in [0.0f64, 1.1, 2.5, 4.0] {
            let d = DVec3::new(
                theta1.sin() * azimuth.cos(),
                -theta1.cos(),
                theta1.sin() * azimuth.sin(),
            );
            let origin = DVec3::new(0.3, top, -0.2) - d * 3.0;
            let enter = traced
                .closest(origin, d, f64::INFINITY, Leaving::Eye)
                .expect("the slab's top");
            let (n, front) = incident_side(&enter, d);
            assert!(front && (n - DVec3::Y).length() < 1e-12);
            assert!((enter.position.y - top).abs() <= 1e-12);
            let inside = refracted_direction(d, n, 1.5).expect("no total reflection entering");
            assert!((inside.cross(n).length() * 1.5 - theta1.sin()).abs() <= 1e-12);
            let leave = traced
                .closest(enter.position, inside, f64::INFINITY, enter.leaving())
                .expect("the slab's bottom");
            let (n, front) = incident_side(&leave, inside);
            assert!(
                !front && (n - DVec3::Y).length() < 1e-12,
                "bottom face seen from inside"
            );
            assert!((leave.position.y + top).abs() <= 1e-12);
            let out = refracted_direction(inside, n, 1.0 / 1.5).expect("leaving below θ_c");
            assert!(
                (out - d).length() <= 1e-9,
                "{degrees}°: leaves along {out}, came along {d}"
            );
            // Distance of the exit point from the incident ray's line.
            let off = (leave.position - origin).cross(d).length();
            assert!(
                (off - shift).abs() <= 1e-9,
                "{degrees}°: shifted by {off}, expected {shift}"
            );
            followed += 1;
        }
    }
    assert_eq!(followed, 32);

    // The tracer: rays from (s, 3, 0) at θ₁ in the x-y plane land at
    // x = s + tan θ₁ (3 + depth − d) + tan θ₂ d; the square's edge appears at the s
    // that puts the landing on x = edge.
    let settings = global("depth = 4\nsubdivisions = 0");
    let tracer = Whitted::new(&scene, &traced, &settings, None);
    let seen = 0.9f32 * 0.9; // through two faces of transmittance 0.9
    for degrees in [10.0f64, 30.0, 45.0, 60.0, 75.0] {
        let theta1 = degrees.to_radians();
        let theta2 = (theta1.sin() / 1.5).asin();
        let d = DVec3::new(theta1.sin(), -theta1.cos(), 0.0);
        let height = 3.0;
        let radiance = |s: f64| tracer.trace(DVec3::new(s, height, 0.0), d, 0).radiance;
        let straight = edge - theta1.tan() * (height + depth);
        let expected = straight + (theta1.tan() - theta2.tan()) * thickness;
        let (mut lo, mut hi) = (expected - 0.5, expected + 0.5);
        assert_eq!(
            radiance(lo),
            Vec3::ZERO,
            "{degrees}°: the square seen left of its edge"
        );
        let lit = radiance(hi);
        assert!(
            (lit - Vec3::splat(seen)).abs().max_element() <= 1e-6,
            "{degrees}°: {lit}"
        );
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if radiance(mid) == Vec3::ZERO {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        assert!(
            (lo - expected).abs() <= 1e-9,
            "{degrees}°: edge seen from s = {lo}, expected {expected} (straight rays: {straight})"
        );
        assert!((expected - straight).abs() > 0.02);
    }
}

// ---------------------------------------------------------------------------------
// 4. A corner seen in a mirror sphere.
// ---------------------------------------------------------------------------------

const BALL_CENTRE: DVec3 = DVec3::new(0.0, 0.0, 0.0);
const BALL_RADIUS: f64 = 0.8;
const EYE: DVec3 = DVec3::new(0.3, 0.6, 5.0);
/// The corner where four emitting squares meet, on a wall behind the eye facing
/// the ball (out of the camera's sight: seen only in the mirror).
const CORNER: DVec3 = DVec3::new(0.9, 1.1, 7.0);
/// The four squares' emission, red, green, blue and black: a pixel's colour gives
/// the share of each it sees.
const QUADRANTS: [[f64; 3]; 4] = [
    [0.8, 0.0, 0.0],
    [0.0, 0.8, 0.0],
    [0.0, 0.0, 0.8],
    [0.0, 0.0, 0.0],
];

fn mirror_ball(width: u32, height: u32) -> Scene {
    let mut text = camera(EYE.to_array(), [0.0, 0.0, 0.0], 22.0, width, height);
    text += "[render]\nbackground = [0.0, 0.0, 0.0]\n\
             [materials.mirror]\ndiffuse = [0.0, 0.0, 0.0]\nmirror = [1.0, 1.0, 1.0]\n\
             [global]\nmethod = \"ray-tracing\"\n\
             [[objects]]\nshape = \"sphere\"\nname = \"ball\"\nmaterial = \"mirror\"\nresolution = 16\n";
    text += &format!("transform = [{{ scale = {BALL_RADIUS} }}]\n");
    let (x, y, z) = (CORNER.x, CORNER.y, CORNER.z);
    // Quadrants around the corner in the plane z = CORNER.z, facing −z: seen from
    // −z, counter-clockwise.
    let spans = [
        ((x, x + 20.0), (y, y + 20.0)),
        ((x - 20.0, x), (y, y + 20.0)),
        ((x - 20.0, x), (y - 20.0, y)),
        ((x, x + 20.0), (y - 20.0, y)),
    ];
    for (q, ((x0, x1), (y0, y1))) in spans.iter().enumerate() {
        text += &format!(
            "[materials.q{q}]\ndiffuse = [0.0, 0.0, 0.0]\nemission = {:?}\n\
             [[objects]]\nshape = \"polygon\"\nname = \"q{q}\"\nmaterial = \"q{q}\"\n\
             vertices = [[{x1}, {y0}, {z}], [{x0}, {y0}, {z}], [{x0}, {y1}, {z}], [{x1}, {y1}, {z}]]\n",
            QUADRANTS[q]
        );
    }
    scene_from_text(&text, &[])
}

/// The point S of the ball where a ray from the eye reflects to the corner: in the
/// plane of eye, centre and corner, S = C + r(cos φ u + sin φ w) with u towards the
/// eye, and the normal at S makes equal angles with the directions to eye and
/// corner; bisection on φ between the eye's and the corner's directions.
fn reflection_point() -> DVec3 {
    let (c, r) = (BALL_CENTRE, BALL_RADIUS);
    let u = (EYE - c).normalize();
    let q = CORNER - c;
    let w = (q - q.dot(u) * u).normalize();
    let at = |phi: f64| c + r * (phi.cos() * u + phi.sin() * w);
    let g = |phi: f64| {
        let s = at(phi);
        let n = (s - c) / r;
        (EYE - s).normalize().dot(n) - (CORNER - s).normalize().dot(n)
    };
    let (mut lo, mut hi) = (0.0, q.dot(w).atan2(q.dot(u)));
    assert!(g(lo) > 0.0 && g(hi) < 0.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if g(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let s = at(0.5 * (lo + hi));
    let n = (s - c) / r;
    assert!(
        n.dot(EYE - s) > 0.0 && n.dot(CORNER - s) > 0.0,
        "S seen from both"
    );
    s
}

/// Which quadrant's colour a radiance is (the mirror reflects all of it), if any.
fn quadrant(radiance: Vec3) -> Option<usize> {
    QUADRANTS
        .iter()
        .position(|q| (radiance - DVec3::from(*q).as_vec3()).abs().max_element() <= 1e-6)
}

/// The corner's image in a mirror sphere is where the reflection point, solved
/// independently, projects. At ray level: the eye ray through that screen point
/// meets the ball at S (1e-9), and its reflection (R = V' + 2N) meets the wall at
/// the corner (1e-9). At image level: rays on a circle of 0.05 pixel around it
/// see all four squares; the render shows all four colours only in pixels within a
/// pixel of it, and in one at least.
#[test]
fn a_corner_seen_in_a_mirror_ball_appears_where_the_reflection_point_projects() {
    let (width, height) = (48, 48);
    let scene = mirror_ball(width, height);
    let traced = TracedScene::new(&scene, true);
    let view = View::new(&scene.camera, width, height);
    let s = reflection_point();
    let (x, y) = view.project(view.to_eye(s));
    assert!(
        x > 4.0 && y > 4.0 && x < width as f64 - 4.0 && y < height as f64 - 4.0,
        "({x}, {y})"
    );

    // Ray level.
    let (origin, direction) = view.ray_through(x, y);
    let direction = direction.normalize();
    let hit = traced
        .closest(origin, direction, f64::INFINITY, Leaving::Eye)
        .expect("the ball");
    assert_eq!(hit.object, object_index(&scene, "ball"));
    assert!(
        (hit.position - s).length() <= 1e-9,
        "{} from S",
        (hit.position - s).length()
    );
    let (n, _) = incident_side(&hit, direction);
    let r = reflected_direction(direction, n);
    let to_wall = (CORNER.z - hit.position.z) / r.z;
    let landing = hit.position + r * to_wall;
    assert!(
        to_wall > 0.0 && (landing - CORNER).length() <= 1e-9,
        "lands {} from the corner",
        (landing - CORNER).length()
    );
    let wall = traced
        .closest(hit.position, r, f64::INFINITY, hit.leaving())
        .expect("the wall");
    assert!((wall.position - CORNER).length() <= 1e-9);

    // Around the predicted point, all four squares.
    let settings = global("depth = 3\nsubdivisions = 3\ncontrast = 0.02");
    let tracer = Whitted::new(&scene, &traced, &settings, None);
    let mut seen = [0; 4];
    for k in 0..720 {
        let a = k as f64 * std::f64::consts::TAU / 720.0;
        let radiance = tracer
            .through(&view, x + 0.05 * a.cos(), y + 0.05 * a.sin(), 0)
            .radiance;
        let q = quadrant(radiance).unwrap_or_else(|| panic!("{radiance}: no square's colour"));
        seen[q] += 1;
    }
    assert!(
        seen.iter().all(|&n| n > 0),
        "squares seen around the point: {seen:?}"
    );

    // The render.
    let (image, _) = tracer.render(&view);
    let mut corner_pixels = Vec::new();
    for j in 0..height {
        for i in 0..width {
            let p = image.pixels[(j * width + i) as usize] / 0.8;
            let shares = [p.x, p.y, p.z, 1.0 - p.x - p.y - p.z];
            if shares.iter().all(|&f| f > 0.01) {
                corner_pixels.push((i, j));
            }
        }
    }
    assert!(!corner_pixels.is_empty(), "no pixel shows all four squares");
    for &(i, j) in &corner_pixels {
        assert!(
            (i as f64 + 0.5 - x).abs() <= 1.0 && (j as f64 + 0.5 - y).abs() <= 1.0,
            "pixel ({i}, {j}) shows all four squares, predicted ({x:.3}, {y:.3})"
        );
    }
    eprintln!("corner image predicted at ({x:.4}, {y:.4}); four-colour pixels {corner_pixels:?}");
}

// ---------------------------------------------------------------------------------
// 5. Whitted's shadows are ray-cast shadows.
// ---------------------------------------------------------------------------------

/// On the point-lit Cornell box (diffuse only, flat normals), eye rays through the
/// pixel centres traced by Whitted give, wherever they meet the polygon the
/// scan-line pass sees there, the radiance of the scan-line pass shadowed by ray
/// casting (relative 1e-4); the pixels where the two see different polygons are
/// few and each on a polygon edge of the scan-line image.
#[test]
fn whitted_shadows_equal_ray_cast_shadows() {
    let (w, h) = (64u32, 64u32);
    let sets: Vec<String> = [
        format!("camera.width={w}"),
        format!("camera.height={h}"),
        "shadows.method=\"ray-cast\"".to_string(),
        "render.supersample=1".to_string(),
    ]
    .to_vec();
    let scene = lumiere::load_scene("cornell-box-point", &sets).unwrap();
    assert!(scene.global.is_none());
    assert!(scene.materials.iter().all(|m| !m.is_specular()));
    let rendered = Renderer::new(scene.clone())
        .render_with_buffers(&["polygon".to_string()])
        .unwrap();
    let ids = match &rendered.buffers[0].data {
        BufferData::Ids(ids) => ids.clone(),
        other => panic!("polygon buffer: {other:?}"),
    };
    let traced = TracedScene::new(&scene, true);
    let settings = global("depth = 5\nsubdivisions = 0");
    let tracer = Whitted::new(&scene, &traced, &settings, None);
    let view = View::new(&scene.camera, w, h);
    let (mut agreeing, mut shadowed, mut other_polygon, mut different) =
        (0, 0, Vec::new(), Vec::new());
    let mut worst = 0.0f32;
    for j in 0..h {
        for i in 0..w {
            let k = (j * w + i) as usize;
            let (cx, cy) = (i as f64 + 0.5, j as f64 + 0.5);
            let (origin, direction) = view.ray_through(cx, cy);
            let hit = traced.closest(origin, direction.normalize(), f64::INFINITY, Leaving::Eye);
            let polygon = hit.and_then(|h| h.polygon);
            let scan = (ids[k] != lumiere::NO_ID).then_some(ids[k]);
            if polygon != scan {
                other_polygon.push((i, j));
                continue;
            }
            let traced_radiance = tracer.through(&view, cx, cy, k as u64).radiance;
            let scanned = rendered.image.pixels[k];
            let scale = traced_radiance.max_element().max(scanned.max_element());
            let difference = (traced_radiance - scanned).abs().max_element();
            if difference <= 1e-4 * scale + 1e-9 {
                agreeing += 1;
                if scale > 0.0 {
                    worst = worst.max(difference / scale);
                }
                shadowed += (scale == 0.0) as usize;
            } else {
                different.push((i, j, traced_radiance, scanned));
            }
        }
    }
    eprintln!(
        "Cornell box {w}x{h}: {agreeing} pixels agree ({shadowed} in shadow; largest relative difference {worst:e}), {} see another polygon, {} differ",
        other_polygon.len(),
        different.len()
    );
    assert!(
        different.is_empty(),
        "radiance differs on the same polygon: {different:?}"
    );
    assert!(
        shadowed > 100,
        "only {shadowed} shadowed pixels: the test needs shadows"
    );
    assert!(
        other_polygon.len() <= 24,
        "{} pixels see another polygon",
        other_polygon.len()
    );
    let id = |i: i64, j: i64| ids[(j * w as i64 + i) as usize];
    for &(i, j) in &other_polygon {
        let (i, j) = (i as i64, j as i64);
        let on_edge = (-1..=1)
            .flat_map(|dj| (-1..=1).map(move |di| (i + di, j + dj)))
            .any(|(a, b)| a >= 0 && b >= 0 && a < w as i64 && b < h as i64 && id(a, b) != id(i, j));
        assert!(
            on_edge,
            "pixel ({i}, {j}) sees another polygon away from any edge"
        );
    }
}

/// The same for an analytic sphere, against the closed forms: a diffuse ball over
/// a floor under a point light. Where an eye ray meets the ball, Whitted gives
/// ρ/π · I cos θ / r² wherever cos θ > 0 (a convex body never shadows its own lit
/// side: the shadow ray leaves the surface it starts on) and 0 elsewhere; on the
/// floor, the same where the segment to the light misses the sphere (solved here)
/// and 0 where it meets it.
#[test]
fn whitted_shadows_of_an_analytic_sphere_are_its_ray_cast_shadows() {
    let (w, h) = (48u32, 48u32);
    let (centre, radius) = (DVec3::new(0.0, 1.2, 0.0), 0.8);
    let light = DVec3::new(1.5, 5.0, 1.0);
    let intensity = 60.0f32;
    let text = format!(
        "{}[materials.floor]\ndiffuse = [0.6, 0.6, 0.6]\n[materials.ball]\ndiffuse = [0.7, 0.7, 0.7]\n\
         [[lights]]\ntype = \"point\"\nposition = {:?}\nintensity = [{intensity}, {intensity}, {intensity}]\n\
         [[objects]]\nshape = \"quad\"\nname = \"floor\"\nmaterial = \"floor\"\ntransform = [{{ scale = 10.0 }}]\n\
         [[objects]]\nshape = \"sphere\"\nname = \"ball\"\nmaterial = \"ball\"\nresolution = 16\n\
         transform = [{{ scale = {radius} }}, {{ translate = {:?} }}]\n",
        camera([0.0, 3.0, 6.0], [0.0, 0.8, 0.0], 40.0, w, h),
        light.to_array(),
        centre.to_array()
    );
    let scene = scene_from_text(&text, &[]);
    let traced = TracedScene::new(&scene, true);
    let settings = global("depth = 2\nsubdivisions = 0");
    let tracer = Whitted::new(&scene, &traced, &settings, None);
    let view = View::new(&scene.camera, w, h);
    let ball = object_index(&scene, "ball");
    // Whether the segment from p to the light meets the sphere (None: too near
    // tangent to say).
    let segment_meets_ball = |p: DVec3| {
        let d = light - p;
        let o = p - centre;
        let (a, b, c) = (
            d.length_squared(),
            2.0 * o.dot(d),
            o.length_squared() - radius * radius,
        );
        let disc = b * b - 4.0 * a * c;
        if disc.abs() < 1e-6 * a {
            return None;
        }
        if disc < 0.0 {
            return Some(false);
        }
        let t = (-b - disc.sqrt()) / (2.0 * a);
        Some(t > 0.0 && t < 1.0)
    };
    let (mut lit_ball, mut dark_ball, mut lit_floor, mut shadowed_floor) = (0, 0, 0, 0);
    for j in 0..h {
        for i in 0..w {
            let (cx, cy) = (i as f64 + 0.5, j as f64 + 0.5);
            let (origin, direction) = view.ray_through(cx, cy);
            let Some(hit) =
                traced.closest(origin, direction.normalize(), f64::INFINITY, Leaving::Eye)
            else {
                continue;
            };
            let p = hit.position;
            let to_light = light - p;
            let cos = hit.normal.dot(to_light.normalize());
            let on_ball = hit.object == ball;
            let lit = if on_ball {
                if cos.abs() < 1e-6 {
                    continue;
                }
                cos > 0.0
            } else {
                match segment_meets_ball(p) {
                    Some(blocked) => !blocked,
                    None => continue,
                }
            };
            let rho = if on_ball { 0.7 } else { 0.6 };
            let expected = if lit {
                rho / std::f32::consts::PI * intensity * (cos / to_light.length_squared()) as f32
            } else {
                0.0
            };
            let got = tracer.through(&view, cx, cy, 0).radiance;
            assert!(
                (got - Vec3::splat(expected)).abs().max_element() <= 1e-5 * expected + 1e-9,
                "pixel ({i}, {j}) on the {}: {got} vs {expected}",
                if on_ball { "ball" } else { "floor" }
            );
            match (on_ball, lit) {
                (true, true) => lit_ball += 1,
                (true, false) => dark_ball += 1,
                (false, true) => lit_floor += 1,
                (false, false) => shadowed_floor += 1,
            }
        }
    }
    eprintln!(
        "analytic ball: {lit_ball} lit and {dark_ball} unlit ball pixels, {lit_floor} lit and {shadowed_floor} shadowed floor pixels"
    );
    assert!(lit_ball > 100 && dark_ball > 20 && lit_floor > 200 && shadowed_floor > 50);
}

// ---------------------------------------------------------------------------------
// 6. Whitted's adaptive antialiasing.
// ---------------------------------------------------------------------------------

/// Coloured shapes at odd angles over a grey floor, lit by a distant point light
/// (smooth gradients, and the shapes' shadows): edges, and flat regions.
fn edges_scene(width: u32, height: u32) -> Scene {
    let mut text = camera([0.0, 7.0, 3.0], [0.2, 0.5, 0.5], 22.0, width, height);
    text += "[render]\nbackground = [0.05, 0.05, 0.1]\n\
             [materials.floor]\ndiffuse = [0.5, 0.5, 0.5]\n\
             [materials.red]\ndiffuse = [0.9, 0.2, 0.1]\n\
             [materials.blue]\ndiffuse = [0.1, 0.3, 0.8]\n\
             [[lights]]\ntype = \"point\"\nposition = [15.0, 40.0, 10.0]\nintensity = [7000.0, 7000.0, 7000.0]\n\
             [[objects]]\nshape = \"quad\"\nname = \"floor\"\nmaterial = \"floor\"\ntransform = [{ scale = 8.0 }]\n\
             [[objects]]\nshape = \"quad\"\nname = \"panel\"\nmaterial = \"red\"\n\
             transform = [{ scale = [1.6, 1.0, 0.9] }, { rotate = { axis = [1.0, 0.0, 0.0], degrees = 80.0 } }, { rotate = { axis = [0.0, 0.0, 1.0], degrees = 23.0 } }, { translate = [-0.7, 1.0, 0.5] }]\n\
             [[objects]]\nshape = \"polygon\"\nname = \"sliver\"\nmaterial = \"blue\"\n\
             vertices = [[0.4, 0.3, 1.0], [1.9, 0.5, 1.2], [0.9, 1.8, 0.6]]\n";
    scene_from_text(&text, &[])
}

fn rms(a: &[Vec3], b: &[Vec3]) -> f64 {
    let sum: f64 = a
        .iter()
        .zip(b)
        .map(|(x, y)| (*x - *y).length_squared() as f64)
        .sum();
    (sum / a.len() as f64).sqrt()
}

/// Whitted's subdivision written out from its description, on eye rays alone: a
/// square whose four corners (top-left, top-right, bottom-left, bottom-right) differ
/// by more than `contrast` in a displayed channel (exposure applied, clamped to
/// [0, 1]) is split into four, its five new points traced (edge midpoints and
/// centre), down to `levels`; a square's value is the mean of its corners, a split
/// square's the mean of its quarters'. Gives the value and the rays traced inside
/// (the new points; the corners are counted by the caller).
#[allow(clippy::too_many_arguments)]
fn subdivided(
    ray: &dyn Fn(f64, f64) -> Vec3,
    (x, y, size): (f64, f64, f64),
    c: [Vec3; 4],
    level: u32,
    levels: u32,
    contrast: f64,
    exposure: f32,
) -> (Vec3, u32) {
    let shown = c.map(|v| (v * exposure).clamp(Vec3::ZERO, Vec3::ONE));
    let low = shown[1..].iter().fold(shown[0], |a, b| a.min(*b));
    let high = shown[1..].iter().fold(shown[0], |a, b| a.max(*b));
    if level == levels || ((high - low).max_element() as f64) <= contrast {
        return ((c[0] + c[1] + c[2] + c[3]) / 4.0, 0);
    }
    let h = size / 2.0;
    let top = ray(x + h, y);
    let left = ray(x, y + h);
    let centre = ray(x + h, y + h);
    let right = ray(x + size, y + h);
    let bottom = ray(x + h, y + size);
    let quarters = [
        ((x, y), [c[0], top, left, centre]),
        ((x + h, y), [top, c[1], centre, right]),
        ((x, y + h), [left, centre, c[2], bottom]),
        ((x + h, y + h), [centre, right, bottom, c[3]]),
    ];
    let (mut total, mut rays) = (Vec3::ZERO, 5);
    for ((qx, qy), corners) in quarters {
        let (v, r) = subdivided(
            ray,
            (qx, qy, h),
            corners,
            level + 1,
            levels,
            contrast,
            exposure,
        );
        total += v;
        rays += r;
    }
    (total / 4.0, rays)
}

/// With no subdivision each pixel is the mean of the rays through its four corners
/// (exactly). At every level from 0 to 3 the render is Whitted's subdivision as
/// written out above (`subdivided`): the same pixels, to 1e-6, and the same rays
/// per pixel (1 for the corners' share, 5 per split square). As the levels grow the
/// image approaches the mean of 16 × 16 rays per pixel, the error falling at each
/// level; a pixel without edges (its 17 × 17 rays within the contrast) is never
/// split.
#[test]
fn adaptive_subdivision_converges_to_the_supersampled_image() {
    let (w, h) = (40u32, 30u32);
    let scene = edges_scene(w, h);
    let traced = TracedScene::new(&scene, true);
    let view = View::new(&scene.camera, w, h);
    let contrast = 0.01;
    let at = |settings: &GlobalSettings, x: f64, y: f64| {
        Whitted::new(&scene, &traced, settings, None)
            .through(&view, x, y, 0)
            .radiance
    };
    let base = global(&format!(
        "depth = 2\nsubdivisions = 0\ncontrast = {contrast}"
    ));

    // Level 0: the corners' mean.
    let (image, rays) = Whitted::new(&scene, &traced, &base, None).render(&view);
    for j in 0..h {
        for i in 0..w {
            let (x, y) = (i as f64, j as f64);
            let mean = (at(&base, x, y)
                + at(&base, x + 1.0, y)
                + at(&base, x, y + 1.0)
                + at(&base, x + 1.0, y + 1.0))
                / 4.0;
            let k = (j * w + i) as usize;
            assert!(
                (image.pixels[k] - mean).abs().max_element() <= 1e-6,
                "pixel ({i}, {j}): {} vs {mean}: {} {} {} {}",
                image.pixels[k],
                at(&base, x, y),
                at(&base, x + 1.0, y),
                at(&base, x, y + 1.0),
                at(&base, x + 1.0, y + 1.0)
            );
            assert_eq!(rays[k], 1);
        }
    }

    // The reference, and which pixels hold no edge.
    let n = 16;
    let mut reference = Vec::with_capacity((w * h) as usize);
    let mut flat = Vec::with_capacity((w * h) as usize);
    for j in 0..h {
        for i in 0..w {
            let mut sum = Vec3::ZERO;
            for b in 0..n {
                for a in 0..n {
                    let x = i as f64 + (a as f64 + 0.5) / n as f64;
                    let y = j as f64 + (b as f64 + 0.5) / n as f64;
                    sum += at(&base, x, y);
                }
            }
            reference.push(sum / (n * n) as f32);
            let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
            for b in 0..=n {
                for a in 0..=n {
                    let v = at(
                        &base,
                        i as f64 + a as f64 / n as f64,
                        j as f64 + b as f64 / n as f64,
                    );
                    lo = lo.min(v);
                    hi = hi.max(v);
                }
            }
            flat.push(((hi - lo).max_element() as f64) < contrast);
        }
    }
    let n_flat = flat.iter().filter(|f| **f).count();
    assert!(
        n_flat > 300 && n_flat < (w * h) as usize - 100,
        "{n_flat} flat pixels"
    );

    let mut errors = Vec::new();
    for levels in 0..=3u32 {
        let settings = global(&format!(
            "depth = 2\nsubdivisions = {levels}\ncontrast = {contrast}"
        ));
        let (image, rays) = Whitted::new(&scene, &traced, &settings, None).render(&view);
        errors.push(rms(&image.pixels, &reference));
        let ray = |x: f64, y: f64| at(&base, x, y);
        let exposure = scene.render.exposure;
        for j in 0..h {
            for i in 0..w {
                let (x, y) = (i as f64, j as f64);
                let corners = [
                    ray(x, y),
                    ray(x + 1.0, y),
                    ray(x, y + 1.0),
                    ray(x + 1.0, y + 1.0),
                ];
                let (value, inside) =
                    subdivided(&ray, (x, y, 1.0), corners, 0, levels, contrast, exposure);
                let k = (j * w + i) as usize;
                assert!(
                    (image.pixels[k] - value).abs().max_element() <= 1e-6,
                    "level {levels}, pixel ({i}, {j}): {} vs Whitted's {value}",
                    image.pixels[k]
                );
                assert_eq!(rays[k], 1 + inside, "level {levels}, pixel ({i}, {j})");
            }
        }
        let most = 1 + 5 * (0..levels).map(|l| 4u32.pow(l)).sum::<u32>();
        let mut split = 0;
        for k in 0..(w * h) as usize {
            assert_eq!(rays[k] % 5, 1, "pixel {k}: {} rays", rays[k]);
            assert!(rays[k] <= most);
            if flat[k] {
                assert_eq!(
                    rays[k], 1,
                    "level {levels}: a pixel without edges was split"
                );
            }
            split += (rays[k] > 1) as usize;
        }
        if levels > 0 {
            assert!(split > 50, "level {levels}: only {split} pixels split");
        }
    }
    eprintln!("rms error against 16x16 rays per pixel, levels 0-3: {errors:?}");
    // Measured: 0.0570, 0.0240, 0.0102, 0.0059 (the 16 x 16 reference is itself
    // about 0.0006 from a 64 x 64 one). What level 3 leaves is mostly features no
    // square's four corners see: the narrow tip of a shadow, a polygon's corner
    // inside a square (Whitted's "small object could be missed").
    assert!(
        errors.windows(2).all(|e| e[1] < e[0]),
        "not converging: {errors:?}"
    );
    assert!(errors[1] < 0.6 * errors[0], "{errors:?}");
    assert!(
        errors[3] < 0.008 && errors[3] < 0.15 * errors[0],
        "{errors:?}"
    );
}

/// Where the corners differ is decided in displayed values, exposure applied and
/// clamped to [0, 1], against the contrast: an emitting panel 0.1 brighter than the
/// backdrop splits the pixels along its edges under a contrast of 0.095 and none
/// under 0.105; panel and backdrop both above 1 (clamped alike) split nothing, until
/// an exposure of 0.5 shows them 0.25 apart.
#[test]
fn subdivision_follows_the_displayed_contrast() {
    let split = |background: f32, panel: f32, exposure: f32, contrast: f64| {
        let mut text = camera([0.0, 0.0, 5.0], [0.0, 0.0, 0.0], 30.0, 24, 24);
        text += &format!(
            "[render]\nbackground = [{background}, {background}, {background}]\nexposure = {exposure}\n\
             [materials.panel]\ndiffuse = [0.0, 0.0, 0.0]\nemission = [{panel}, {background}, {background}]\n\
             [[objects]]\nshape = \"quad\"\nname = \"panel\"\nmaterial = \"panel\"\n\
             transform = [{{ scale = 1.2 }}, {{ rotate = {{ axis = [1.0, 0.0, 0.0], degrees = 90.0 }} }}, {{ rotate = {{ axis = [0.0, 0.0, 1.0], degrees = 17.0 }} }}]\n"
        );
        let scene = scene_from_text(&text, &[]);
        let traced = TracedScene::new(&scene, true);
        let view = View::new(&scene.camera, 24, 24);
        let settings = global(&format!(
            "depth = 0\nsubdivisions = 2\ncontrast = {contrast}"
        ));
        let (image, rays) = Whitted::new(&scene, &traced, &settings, None).render(&view);
        // The panel is in view, facing the eye.
        assert!(image.pixels.iter().any(|p| (p.x - panel).abs() < 1e-6));
        rays.iter().filter(|&&r| r > 1).count()
    };
    let edge = split(0.3, 0.4, 1.0, 0.095);
    assert!(edge > 20, "{edge} pixels split along the panel's edges");
    assert_eq!(split(0.3, 0.4, 1.0, 0.105), 0);
    assert_eq!(
        split(1.5, 2.5, 1.0, 0.05),
        0,
        "values above 1 are shown as 1"
    );
    assert!(split(1.5, 2.5, 0.5, 0.2) > 20);
    assert_eq!(split(1.5, 2.5, 0.5, 0.3), 0);
}

// ---------------------------------------------------------------------------------
// 7. Bad input on the command line.
// ---------------------------------------------------------------------------------

/// A bad `[global]` key or a glass of index 0: one error line naming the key,
/// a non-zero exit, no image written.
#[test]
fn bad_ray_tracing_settings_are_one_error_line_naming_the_key() {
    let scene = |global: &str, ior: &str| {
        format!(
            "{}[materials.glass]\ndiffuse = [0.0, 0.0, 0.0]\ntransmittance = [0.9, 0.9, 0.9]\nior = {ior}\n\
             [[lights]]\ntype = \"point\"\nposition = [0.0, 2.0, 2.0]\nintensity = [5.0, 5.0, 5.0]\n\
             [[objects]]\nshape = \"sphere\"\nmaterial = \"glass\"\n\
             [global]\n{global}\n",
            camera([0.0, 1.0, 3.0], [0.0, 0.0, 0.0], 40.0, 16, 12)
        )
    };
    let ok = "method = \"ray-tracing\"";
    for (text, sets, fragment) in [
        (
            scene("method = \"ray-tracing\"\ndepth = 17", "1.5"),
            vec![],
            "global.depth must be at most 16",
        ),
        (
            scene(ok, "1.5"),
            vec!["--set", "global.depth=100"],
            "global.depth must be at most 16",
        ),
        (
            scene(ok, "0.0"),
            vec![],
            "materials.glass.ior must be a positive number",
        ),
        (
            scene("method = \"metropolis\"", "1.5"),
            vec![],
            "global.method: unknown variant `metropolis`",
        ),
    ] {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("s.toml"), &text).unwrap();
        let mut args = vec!["render", "s.toml", "-o", "out.png"];
        args.extend(sets);
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_lumiere"))
            .args(&args)
            .current_dir(dir.path())
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{fragment}: should fail");
        assert!(!stderr.contains("panicked"), "{stderr}");
        let lines: Vec<&str> = stderr.lines().collect();
        assert_eq!(lines.len(), 1, "one line expected: {stderr}");
        assert!(
            lines[0].starts_with("error: ") && lines[0].contains(fragment),
            "`{fragment}` not in {}",
            lines[0]
        );
        assert!(!dir.path().join("out.png").exists());
    }
    // The same scene, valid, renders.
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("s.toml"), scene(ok, "1.5")).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_lumiere"))
        .args(["render", "s.toml", "-o", "out.png"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Whitted's guard for small objects: a glowing sphere a fifth of a pixel across,
/// centred between the four corner rays of a pixel, is met by none of them; the
/// pixel is split because its bounding sphere projects onto it, until a ray meets
/// it. Without the guard the pixel is the background, as its neighbours are.
#[test]
fn a_small_sphere_between_the_corners_is_found_by_its_bounding_sphere() {
    // 16 x 16 pixels over a 40° field from 10 away: a pixel is
    // 20 tan 20° / 16 ≈ 0.455 wide at the ball, whose diameter 0.09 is a fifth of
    // that. The eye is moved by half a pixel so the ball projects onto the centre of
    // pixel (8, 8), between its corners.
    let half = 0.5 * 20.0 * 20f64.to_radians().tan() / 16.0;
    let text = format!(
        "{}[materials.glow]\nemission = [1.0, 1.0, 1.0]\n\
         [[objects]]\nshape = \"sphere\"\nname = \"ball\"\nmaterial = \"glow\"\nresolution = 12\n\
         transform = [{{ scale = 0.045 }}]\n",
        support::camera([-half, half, 10.0], [-half, half, 0.0], 40.0, 16, 16)
    );
    let scene = scene_from_text(&text, &[]);
    let view = View::new(&scene.camera, 16, 16);
    let (x, y) = view.project(view.to_eye(DVec3::ZERO));
    assert!((x - 8.5).abs() < 1e-9 && (y - 8.5).abs() < 1e-9, "{x} {y}");
    let traced = TracedScene::new(&scene, true);
    let settings = global("depth = 1\nsubdivisions = 3\ncontrast = 0.1");
    let tracer = Whitted::new(&scene, &traced, &settings, None);
    for (i, j) in [(8, 8), (9, 8), (8, 9), (9, 9)] {
        let t = tracer.through(&view, i as f64, j as f64, 0);
        assert_eq!(t.object, None, "corner ({i}, {j}) meets the ball");
    }
    let (image, rays) = tracer.render(&view);
    let pixel = |i: u32, j: u32| image.pixels[(j * 16 + i) as usize];
    assert!(pixel(8, 8).x > 0.0, "the ball's pixel: {}", pixel(8, 8));
    assert!(rays[8 * 16 + 8] > 1, "the ball's pixel was not split");
    for (i, j) in [(7, 8), (9, 8), (8, 7), (8, 9)] {
        assert_eq!(pixel(i, j), Vec3::ZERO, "pixel ({i}, {j})");
    }
}

/// The depth limit counts reflections: between two parallel glowing mirrors
/// (emission 1, k_s = 0.5) the eye ray sees 1 + 0.5 + … + 0.5^D at depth D, every
/// reflected ray met by the other mirror.
#[test]
fn between_two_glowing_mirrors_the_depth_limit_counts_the_reflections() {
    let mut text = camera([0.0, 0.0, 5.0], [0.0, 0.0, 0.0], 20.0, 8, 8);
    text += "[global]\nmethod = \"ray-tracing\"\n[materials.glowing_mirror]\nemission = [1.0, 1.0, 1.0]\nmirror = [0.5, 0.5, 0.5]\n";
    for (name, order) in [
        (
            "near",
            "[-9.0, -9.0, 0.0], [9.0, -9.0, 0.0], [9.0, 9.0, 0.0], [-9.0, 9.0, 0.0]",
        ),
        (
            "far",
            "[-9.0, -9.0, 10.0], [-9.0, 9.0, 10.0], [9.0, 9.0, 10.0], [9.0, -9.0, 10.0]",
        ),
    ] {
        text += &format!(
            "[[objects]]\nshape = \"polygon\"\nname = \"{name}\"\nmaterial = \"glowing_mirror\"\nvertices = [{order}]\n"
        );
    }
    let scene = scene_from_text(&text, &[]);
    let view = View::new(&scene.camera, 8, 8);
    let traced = TracedScene::new(&scene, true);
    for depth in 0..5 {
        let settings = global(&format!("depth = {depth}\nthreshold = 0.0"));
        let tracer = Whitted::new(&scene, &traced, &settings, None);
        let seen = tracer.through(&view, 4.5, 4.5, 0);
        let expected: f64 = (0..=depth).map(|i| 0.5f64.powi(i)).sum();
        assert!(
            (seen.radiance.x as f64 - expected).abs() < 1e-6,
            "depth {depth}: {} against {expected}",
            seen.radiance
        );
        assert_eq!(seen.rays, depth as u32 + 1, "depth {depth}");
    }
}

/// Textures where rays land: a quad under a 2 × 2 checkerboard, seen slanting, shows
/// the same check at every pixel centre to the ray tracer as to the scan-line
/// renderer (their uv conventions agree; a v flipped at ray hits swaps every check).
#[test]
fn textures_at_ray_hits_follow_the_scan_line_renderers_uv() {
    let text = |method: &str| {
        format!(
            "{}{method}[textures.check]\nprocedural = \"checkerboard\"\ncells = 2\ncolors = [[1.0, 1.0, 1.0], [0.1, 0.1, 0.1]]\nfilter = \"nearest\"\n\
             [materials.card]\ndiffuse = [0.8, 0.8, 0.8]\ndiffuse_texture = \"check\"\n\
             [[lights]]\ntype = \"distant\"\ndirection = [0.0, -1.0, -1.0]\nirradiance = [1.0, 1.0, 1.0]\n\
             [[objects]]\nshape = \"quad\"\nname = \"card\"\nmaterial = \"card\"\n\
             transform = [{{ scale = 3.0 }}, {{ rotate = {{ axis = [0.0, 1.0, 0.0], degrees = 30.0 }} }}]\n",
            camera([0.3, 2.5, 2.0], [0.0, 0.0, 0.0], 40.0, 24, 24)
        )
    };
    let scene = scene_from_text(&text(""), &[]);
    let scan = lumiere::render(&scene).unwrap();
    let traced_scene = scene_from_text(&text("[global]\nmethod = \"ray-tracing\"\n"), &[]);
    let view = View::new(&traced_scene.camera, 24, 24);
    let traced = TracedScene::new(&traced_scene, true);
    let settings = global("depth = 1");
    let tracer = Whitted::new(&traced_scene, &traced, &settings, None);
    let (mut bright, mut dark) = (0, 0);
    for j in 0..24u32 {
        for i in 0..24u32 {
            let a = scan.pixels[(j * 24 + i) as usize].x;
            let b = tracer
                .through(&view, i as f64 + 0.5, j as f64 + 0.5, 0)
                .radiance
                .x;
            // Each check's colour, where the scan-line renderer shows one (not on
            // the quad's edge or the background).
            if a > 0.002 {
                assert!(
                    (a - b).abs() <= 0.02 * a,
                    "pixel ({i}, {j}): {b} traced, {a} scan-line"
                );
                if a > 0.05 { bright += 1 } else { dark += 1 }
            }
        }
    }
    assert!(
        bright > 40 && dark > 40,
        "{bright} bright, {dark} dark pixels"
    );
}
