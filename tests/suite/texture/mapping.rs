//! Texture mapping, mip-mapping and bump mapping proved against exact references:
//! mapping round trips, per-pixel interpolation against the exact inverse mapping,
//! pyramid invariants, filtering error against a supersampled reference, and Blinn's
//! normals against the normals of the truly displaced surface.

use glam::{DVec2, DVec3, Vec3};
use lumiere::geometry::sampling::Stream;
use lumiere::raster::View;
use lumiere::render::visible_surface;
use lumiere::scene::resources::Directory;
use lumiere::scene::{Scene, scene_from_table, tables};
use lumiere::texture::bump::perturb;
use lumiere::texture::mapping::{Frame, IntermediateSurface, Mapping, Projector};
use lumiere::texture::mip_map::Pyramid;
use lumiere::texture::{Filter, Texels, Texture, Wrap};
use lumiere::{Image, catalogue, load_scene, render};
use proptest::prelude::*;
use std::f64::consts::{PI, TAU};
use std::sync::Arc;

fn mapping(surface: IntermediateSurface, frame: Frame, height: f64) -> Mapping {
    Mapping {
        surface,
        projector: Projector::Surface,
        frame,
        size: DVec2::ONE,
        height,
        radius: 1.0,
        repeat: DVec2::ONE,
    }
}

fn vec3() -> impl Strategy<Value = DVec3> {
    (-3.0..3.0f64, -3.0..3.0f64, -3.0..3.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

fn frame() -> impl Strategy<Value = Frame> {
    (vec3(), vec3(), vec3()).prop_filter_map("a non-degenerate frame", |(c, a, r)| {
        if a.length() < 0.1 || a.normalize().cross(r).length() < 0.1 {
            return None;
        }
        Frame::new(c, a, r).ok()
    })
}

proptest! {
    /// Cylinder: a point (r cos θ, r sin θ, h z) maps to (θ/2π, z) in [0, 1]², and the
    /// inverse mapping (on the cylinder through the point) gives the point back.
    #[test]
    fn cylindrical_round_trip(
        f in frame(), theta in 0.01..TAU - 0.01, z in 0.0..1.0f64,
        r in 0.1..4.0f64, h in 0.2..5.0f64,
    ) {
        let m = mapping(IntermediateSurface::Cylinder, f, h);
        let local = DVec3::new(r * theta.cos(), r * theta.sin(), z * h);
        let p = f.from_local(local);
        let uv = m.uv(p, f.direction_from_local(local.with_z(0.0)), DVec3::ZERO, DVec3::Z);
        prop_assert!((0.0..=1.0).contains(&uv.x) && (0.0..=1.0).contains(&uv.y), "{uv}");
        prop_assert!((uv.x - theta / TAU).abs() < 1e-12 && (uv.y - z).abs() < 1e-12);
        let back = f.from_local(m.surface_point(uv, local));
        prop_assert!((back - p).length() < 1e-9 * (1.0 + p.length()), "{back} vs {p}");
    }

    /// Sphere: latitude φ maps to v = (φ + π/2)/π (the equator to 0.5), and back.
    #[test]
    fn spherical_round_trip(
        f in frame(), theta in 0.01..TAU - 0.01, phi in -1.55..1.55f64, r in 0.1..4.0f64,
    ) {
        let m = mapping(IntermediateSurface::Sphere, f, 1.0);
        let local = r * DVec3::new(theta.cos() * phi.cos(), theta.sin() * phi.cos(), phi.sin());
        let p = f.from_local(local);
        let uv = m.uv(p, f.direction_from_local(local / r), DVec3::ZERO, DVec3::Z);
        prop_assert!((0.0..=1.0).contains(&uv.x) && (0.0..=1.0).contains(&uv.y), "{uv}");
        prop_assert!((uv.x - theta / TAU).abs() < 1e-12);
        prop_assert!((uv.y - (phi + PI / 2.0) / PI).abs() < 1e-12);
        let back = f.from_local(m.surface_point(uv, local));
        prop_assert!((back - p).length() < 1e-9 * (1.0 + p.length()), "{back} vs {p}");
    }
}

#[test]
fn the_equator_maps_to_the_middle_row() {
    let f = Frame::new(DVec3::ZERO, DVec3::Y, DVec3::X).unwrap();
    let m = mapping(IntermediateSurface::Sphere, f, 1.0);
    for k in 0..16 {
        let a = k as f64 / 16.0 * TAU;
        let p = DVec3::new(a.cos(), 0.0, -a.sin()) * 2.5;
        assert!((m.uv(p, p, DVec3::ZERO, DVec3::Z).y - 0.5).abs() < 1e-15);
    }
}

fn scene_from(text: &str) -> Scene {
    let table = tables::parse(text, "test scene").unwrap();
    scene_from_table(table, &Directory(".".into())).unwrap()
}

/// A textured quad whose coordinates come from a planar mapping stored at its
/// vertices, seen by `eye`, interpolated as `interpolation` says.
fn textured_quad(eye: [f64; 3], look_at: [f64; 3], up: [f64; 3], interpolation: &str) -> Scene {
    scene_from(&format!(
        r#"{}
        [textures.t]
        procedural = "checkerboard"
        [materials.m]
        diffuse = [0.5, 0.5, 0.5]
        diffuse_texture = "t"
        interpolation = "{interpolation}"
        mapping = {{ surface = "plane", axis = [0.0, 1.0, 0.0], reference = [1.0, 0.0, 0.2], size = [0.3, 0.7] }}
        [[objects]]
        shape = "quad"
        material = "m"
        transform = [{{ scale = [3.0, 1.0, 12.0] }}, {{ rotate = {{ axis = [0.0, 1.0, 0.0], degrees = 20.0 }} }}, {{ translate = [0.0, 0.0, -4.0] }}]
        "#,
        crate::support::camera_with(eye, look_at, 50.0, 160, 120, &format!("up = {up:?}"))
    ))
}

/// The largest difference between interpolated (u, v) and the exact inverse mapping
/// (the pixel's ray met with the quad's plane, then the mapping), and where it is.
fn interpolation_error(scene: &Scene) -> (f64, (u32, u32), usize) {
    let (view, surface): (View, _) = visible_surface(scene);
    let material = &scene.materials[0];
    let mapping = material.mapping.as_ref().unwrap();
    let frame = &scene.objects[0].frame;
    let polygon = &scene.polygons[0];
    let origin = polygon.vertices[0].position;
    let (mut worst, mut at, mut covered) = (0.0f64, (0, 0), 0);
    for y in 0..view.height {
        for x in 0..view.width {
            let s = surface.at(x, y);
            if s.is_empty() {
                continue;
            }
            covered += 1;
            let d = view.ray(x as f64 + 0.5, y as f64 + 0.5);
            let t = (origin - view.eye).dot(polygon.normal) / d.dot(polygon.normal);
            let p = frame.to_object.transform_point3(view.eye + d * t);
            let exact = mapping.uv(p, DVec3::Y, DVec3::ZERO, DVec3::Y);
            let e = (exact - s.uv).abs().max_element();
            if e > worst {
                (worst, at) = (e, (x, y));
            }
        }
    }
    (worst, at, covered)
}

#[test]
fn perspective_correct_coordinates_are_exact_and_affine_ones_are_not() {
    const Y: [f64; 3] = [0.0, 1.0, 0.0];
    let (eye, look) = ([0.5, 1.5, 4.0], [0.0, 0.0, -6.0]);
    let (error, _, covered) = interpolation_error(&textured_quad(eye, look, Y, "perspective"));
    assert!(covered > 4000, "the quad covers {covered} pixels");
    assert!(error < 1e-4, "perspective-correct (u, v) off by {error}");

    // Affine interpolation departs from the exact map, most where depth varies most
    // along the spans, far from the vertices: tens of checks' worth here.
    let (error, (x, y), _) = interpolation_error(&textured_quad(eye, look, Y, "affine"));
    println!("affine interpolation departs by {error:.3} in (u, v) at pixel ({x}, {y})");
    assert!(error > 0.5, "affine error only {error}");

    // Facing the camera squarely, affine interpolation is exact too.
    let front = textured_quad(
        [0.0, 15.0, -4.0],
        [0.0, 0.0, -4.0],
        [0.0, 0.0, -1.0],
        "affine",
    );
    let (error, _, covered) = interpolation_error(&front);
    assert!(covered > 1000, "the quad covers {covered} pixels");
    assert!(error < 1e-6, "fronto-parallel affine error {error}");
}

/// The footprint the filters read, [∂(u, v)/∂x, ∂(u, v)/∂y] at each pixel centre, is
/// the derivative of the exact screen-to-texture map (central differences of the
/// ray–plane intersection and the mapping). The camera is rolled so that depth
/// varies along the rows as well as down the columns.
#[test]
fn footprints_are_the_screen_derivatives_of_the_exact_map() {
    let scene = textured_quad(
        [0.5, 1.5, 4.0],
        [0.0, 0.0, -6.0],
        [0.4, 1.0, 0.0],
        "perspective",
    );
    let (view, surface) = visible_surface(&scene);
    let mapping = scene.materials[0].mapping.as_ref().unwrap();
    let frame = &scene.objects[0].frame;
    let polygon = &scene.polygons[0];
    let origin = polygon.vertices[0].position;
    let exact = |x: f64, y: f64| {
        let d = view.ray(x, y);
        let t = (origin - view.eye).dot(polygon.normal) / d.dot(polygon.normal);
        let p = frame.to_object.transform_point3(view.eye + d * t);
        mapping.uv(p, DVec3::Y, DVec3::ZERO, DVec3::Y)
    };
    let h = 1e-3;
    let (mut worst, mut checked) = (0.0f64, 0);
    for k in 0..surface.samples.len() {
        if surface.samples[k].is_empty() {
            continue;
        }
        let (x, y) = surface.position_of(k);
        let (x, y) = (x as f64 + 0.5, y as f64 + 0.5);
        let numeric = [
            (exact(x + h, y) - exact(x - h, y)) / (2.0 * h),
            (exact(x, y + h) - exact(x, y - h)) / (2.0 * h),
        ];
        for (got, want) in surface.uv_derivatives(k).iter().zip(numeric) {
            let e = (*got - want).length() / want.length();
            assert!(e < 1e-6, "pixel ({x}, {y}): {got} vs {want}");
            worst = worst.max(e);
        }
        checked += 1;
    }
    println!("{checked} pixels: derivatives within {worst:.1e} of the exact map's");
    assert!(checked > 4000, "{checked} pixels");
}

#[test]
fn exact_mode_evaluates_the_mapping_at_each_point() {
    // On a sphere, a spherical mapping interpolated from the vertices is only
    // approximately the mapping; evaluated per sample it is exact. The two agree to
    // the tessellation's order, and exact differs from interpolated.
    let text = |mode: &str| {
        format!(
            r#"{}
            [textures.t]
            procedural = "grid"
            [materials.m]
            diffuse = [0.5, 0.5, 0.5]
            diffuse_texture = "t"
            interpolation = "{mode}"
            mapping = {{ surface = "sphere" }}
            [[lights]]
            type = "point"
            position = [2.0, 3.0, 4.0]
            intensity = [30.0, 30.0, 30.0]
            [[objects]]
            shape = "sphere"
            resolution = 24
            material = "m"
            "#,
            crate::support::camera([0.0, 0.5, 4.0], [0.0, 0.0, 0.0], 40.0, 96, 96)
        )
    };
    let exact = render(&scene_from(&text("exact"))).unwrap();
    let interpolated = render(&scene_from(&text("perspective"))).unwrap();
    let differing = exact
        .pixels
        .iter()
        .zip(&interpolated.pixels)
        .filter(|(a, b)| (**a - **b).abs().max_element() > 1e-3)
        .count();
    assert!(
        differing > 0,
        "exact and interpolated renders are identical"
    );
    assert!(
        differing < exact.pixels.len() / 10,
        "{differing} pixels differ: more than grid lines shifting by a fraction of a cell"
    );
}

fn hashed_image(width: u32, height: u32) -> Texels {
    Texels::generate(width, height, |uv| {
        let h = ((uv.x * 12.9898 + uv.y * 78.233).sin() * 43_758.545)
            .fract()
            .abs() as f32;
        Vec3::new(h, 1.0 - h, (h * 3.0).fract())
    })
}

#[test]
fn every_pyramid_level_keeps_the_mean() {
    for (w, h) in [(64, 64), (128, 16), (360, 180), (5, 3), (1, 7)] {
        let pyramid = Pyramid::build(&hashed_image(w, h));
        let base = &pyramid.levels[0];
        assert!(base.width.is_power_of_two() && base.height.is_power_of_two());
        let top = pyramid.levels.last().unwrap();
        assert_eq!((top.width, top.height), (1, 1));
        let mean = base.mean();
        for (k, level) in pyramid.levels.iter().enumerate() {
            let d = (level.mean() - mean).abs().max_element();
            assert!(d < 1e-6, "{w}x{h} level {k}: mean off by {d}");
        }
    }
}

#[test]
fn a_constant_texture_stays_constant_at_every_level_and_filter() {
    let c = Vec3::new(0.25, 0.5, 0.75);
    let texels = Texels::generate(48, 20, |_| c);
    for level in Pyramid::build(&texels).levels {
        assert!(
            level
                .texels
                .iter()
                .all(|t| (*t - c).abs().max_element() < 1e-6)
        );
    }
    for filter in [
        Filter::Nearest,
        Filter::Bilinear,
        Filter::MipNearest,
        Filter::Trilinear,
        Filter::SummedArea,
    ] {
        for wrap in [Wrap::Repeat, Wrap::Clamp] {
            let t = Texture::new("c", texels.clone(), None, wrap, filter);
            for k in 0..50 {
                let uv = DVec2::new(k as f64 * 0.731 - 7.0, k as f64 * 0.377 - 3.0);
                let size = (k as f64 * 0.3).exp2() / 48.0;
                let footprint = [DVec2::new(size, size * 0.3), DVec2::new(-0.2 * size, size)];
                let got = t.color(uv, footprint);
                assert!(
                    (got - c).abs().max_element() < 1e-5,
                    "{filter:?} {wrap:?} at {uv}: {got}"
                );
            }
        }
    }
}

fn rmse(a: &Image, b: &Image) -> f64 {
    let sum: f64 = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .map(|(p, q)| (*p - *q).as_dvec3().length_squared())
        .sum();
    (sum / a.pixels.len() as f64).sqrt()
}

/// The mip-mapping entry with both halves sampled by `filter`, at 192 × 96.
fn horizon(filter: &str, supersample: u32) -> Image {
    let overrides: Vec<String> = [
        format!("textures.point.filter=\"{filter}\""),
        format!("textures.trilinear.filter=\"{filter}\""),
        "camera.width=192".into(),
        "camera.height=96".into(),
        format!("render.supersample={supersample}"),
    ]
    .into();
    render(&load_scene("mip-mapping", &overrides).unwrap()).unwrap()
}

#[test]
fn trilinear_mip_mapping_is_three_times_closer_to_the_filtered_image() {
    let reference = horizon("nearest", 16);
    let point = rmse(&horizon("nearest", 1), &reference);
    let trilinear = rmse(&horizon("trilinear", 1), &reference);
    let summed = rmse(&horizon("summed-area", 1), &reference);
    println!(
        "RMSE against 16x16 supersampling: point {point:.4}, trilinear {trilinear:.4}, summed-area {summed:.4}"
    );
    assert!(
        trilinear * 3.0 <= point,
        "trilinear {trilinear} is not 3x below point sampling {point}"
    );
    assert!(summed < point, "summed-area {summed} vs point {point}");
}

/// Texels with detail at every scale: six octaves of white noise in [0, 1], octave k
/// constant over blocks of 2^k × 2^k texels, each octave shifted by its own offset
/// (so that most do not line up with the pyramid's 2^k grid). Whatever a pixel's
/// footprint, averaging over too much or too little of it shows.
fn octave_noise(side: u32) -> Texels {
    let octaves = 6;
    let mut texels = vec![0.0f64; (side * side) as usize];
    for k in 0..octaves {
        let (block, offset) = (1u32 << k, (7 * k + 3) % side);
        let cells = side / block;
        let mut stream = Stream::new(41, k as u64);
        let values: Vec<f64> = (0..cells * cells).map(|_| stream.next_f64()).collect();
        for j in 0..side {
            for i in 0..side {
                let (a, b) = ((i + offset) % side / block, (j + 2 * offset) % side / block);
                texels[(j * side + i) as usize] +=
                    values[(b * cells + a) as usize] / octaves as f64;
            }
        }
    }
    Texels {
        width: side,
        height: side,
        texels: texels.into_iter().map(|t| Vec3::splat(t as f32)).collect(),
    }
}

/// Where the textured plane is seen from.
#[derive(Clone, Copy, Debug)]
enum PlaneView {
    /// Low over the plane: footprints from half a texel under the eye to some 35
    /// texels near the far edge, elongated up to 12:1 along the receding axis.
    Grazing,
    /// From high above, looking steeply down: footprints of 0.9 to 3.8 texels, at most
    /// 2:1, where the finest levels (and the blend between them) matter most.
    Steep,
}

/// A plane carrying `texels` (grey, one tile per 5.12 units, turned 30° against the
/// view) under a distant light of irradiance π from straight above, so that each
/// pixel's radiance is the filtered texture value itself.
fn filtered_plane(texels: &Texels, filter: Filter, view: PlaneView) -> (Scene, Image) {
    let (eye, look_at) = match view {
        PlaneView::Grazing => ([0.0, 1.0, 0.5], [0.0, 0.0, -3.0]),
        PlaneView::Steep => ([0.0, 4.0, 0.0], [0.0, 0.0, -3.0]),
    };
    let mut scene = scene_from(&format!(
        r#"{}
        [shadows]
        method = "none"
        [textures.t]
        procedural = "checkerboard"
        [materials.m]
        diffuse = [1.0, 1.0, 1.0]
        diffuse_texture = "t"
        mapping = {{ surface = "plane", axis = [0.0, 1.0, 0.0], reference = [1.0, 0.0, 0.0], size = [0.512, 0.512] }}
        [[lights]]
        type = "distant"
        direction = [0.0, -1.0, 0.0]
        irradiance = [{PI}, {PI}, {PI}]
        [[objects]]
        shape = "quad"
        material = "m"
        transform = [{{ scale = [10.0, 1.0, 10.0] }}, {{ rotate = {{ axis = [0.0, 1.0, 0.0], degrees = 30.0 }} }}, {{ translate = [0.0, 0.0, -5.5] }}]
        "#,
        crate::support::camera(eye, look_at, 50.0, 128, 96)
    ));
    scene.textures[0] = Arc::new(Texture::new(
        "octave noise",
        texels.clone(),
        None,
        Wrap::Repeat,
        filter,
    ));
    let image = render(&scene).unwrap();
    (scene, image)
}

/// Per pixel showing the plane, the exact box filter: the mean of the texture (its
/// texels as a piecewise-constant function) over the pixel's footprint, by brute
/// force: a grid of sub-pixel points, at least four per texel the footprint spans
/// along each screen axis, each carried onto the plane by its own ray and through the
/// mapping. `None` where the pixel centre misses the plane.
fn box_filtered_footprints(scene: &Scene, texels: &Texels) -> Vec<Option<f64>> {
    let (view, surface) = visible_surface(scene);
    let mapping = scene.materials[0].mapping.as_ref().unwrap();
    let frame = &scene.objects[0].frame;
    let polygon = &scene.polygons[0];
    let origin = polygon.vertices[0].position;
    let texel_size = DVec2::new(texels.width as f64, texels.height as f64);
    (0..surface.samples.len())
        .map(|k| {
            if surface.samples[k].is_empty() {
                return None;
            }
            let (x, y) = surface.position_of(k);
            let [dx, dy] = surface.uv_derivatives(k);
            let count = |d: DVec2| (4.0 * (d * texel_size).length()).ceil().clamp(4.0, 256.0);
            let (nx, ny) = (count(dx), count(dy));
            let mut sum = 0.0;
            for j in 0..ny as u32 {
                for i in 0..nx as u32 {
                    let d = view.ray(
                        x as f64 + (i as f64 + 0.5) / nx,
                        y as f64 + (j as f64 + 0.5) / ny,
                    );
                    let t = (origin - view.eye).dot(polygon.normal) / d.dot(polygon.normal);
                    let p = frame.to_object.transform_point3(view.eye + d * t);
                    let uv = mapping.uv(p, DVec3::Y, DVec3::ZERO, DVec3::Y);
                    sum += texels.nearest(uv, Wrap::Repeat).x as f64;
                }
            }
            Some(sum / (nx * ny))
        })
        .collect()
}

/// The RMSE of `filter`'s rendering of the plane against the exact box filter.
fn footprint_rmse(filter: Filter, view: PlaneView) -> f64 {
    let texels = octave_noise(128);
    let (scene, image) = filtered_plane(&texels, filter, view);
    let reference = box_filtered_footprints(&scene, &texels);
    let errors: Vec<f64> = reference
        .iter()
        .zip(&image.pixels)
        .filter_map(|(r, p)| r.map(|r| p.x as f64 - r))
        .collect();
    assert!(
        errors.len() > 8000,
        "{} pixels show the plane",
        errors.len()
    );
    (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt()
}

/// `filter`'s RMSE against the box filter is within 15% of the value measured (both
/// ways: filtering too much and too little fail alike), from each view.
fn assert_rmse_near(filter: Filter, measured: [(PlaneView, f64); 2]) {
    for (view, measured) in measured {
        let rmse = footprint_rmse(filter, view);
        println!(
            "{filter:?}, {view:?} view: RMSE {rmse:.4} against the box filter (measured {measured})"
        );
        assert!(
            (rmse - measured).abs() <= 0.15 * measured,
            "{filter:?}, {view:?} view: RMSE {rmse:.4} against the box filter, not within 15% of {measured}"
        );
    }
}

/// Williams's trilinear lookup against the box filter over the footprint, measured
/// at 0.0278 (grazing) and 0.0178 (steep). Mutations and what they gave: blend weight
/// reversed 0.0309 (+11%) grazing, 0.0241 (+35%) steep; level one too fine 0.0208
/// (−25%: less blur where the square footprint over-blurs) grazing; one too coarse
/// 0.0433 (+56%) grazing; the footprint's shorter side taken for its size instead of
/// the longer 0.0304 (+9%) grazing, 0.0107 (−40%) steep.
#[test]
fn trilinear_mip_mapping_tracks_the_box_filtered_footprint() {
    assert_rmse_near(
        Filter::Trilinear,
        [(PlaneView::Grazing, 0.0278), (PlaneView::Steep, 0.0178)],
    );
}

/// The nearest level alone, measured at 0.0292 (grazing) and 0.0213 (steep).
/// Mutations: the level below λ instead of the nearest 0.0236 (−19%) grazing; level
/// one too coarse 0.0440 (+51%) grazing; the footprint's shorter side 0.0314 (+8%)
/// grazing, 0.0140 (−34%) steep.
#[test]
fn nearest_level_mip_mapping_tracks_the_box_filtered_footprint() {
    assert_rmse_near(
        Filter::MipNearest,
        [(PlaneView::Grazing, 0.0292), (PlaneView::Steep, 0.0213)],
    );
}

/// Crow's summed-area table over the footprint's bounding box, measured at 0.0180
/// (grazing) and 0.0144 (steep). Mutations: the box twice too large 0.0360 (+100%)
/// grazing; half too small 0.0218 (+21%) grazing.
#[test]
fn summed_area_table_tracks_the_box_filtered_footprint() {
    assert_rmse_near(
        Filter::SummedArea,
        [(PlaneView::Grazing, 0.0180), (PlaneView::Steep, 0.0144)],
    );
}

/// Point sampling ignores the footprint: measured at 0.0518 (grazing) and 0.0470
/// (steep), two to three times further from the box filter than the pre-filtered
/// lookups.
#[test]
fn point_sampling_is_far_from_the_box_filtered_footprint() {
    assert_rmse_near(
        Filter::Nearest,
        [(PlaneView::Grazing, 0.0518), (PlaneView::Steep, 0.0470)],
    );
}

/// A smooth height with exact derivatives: B(u, v) = a sin(k u + c) cos(l v).
#[derive(Clone, Copy, Debug)]
struct Height {
    a: f64,
    k: f64,
    l: f64,
    c: f64,
}

impl Height {
    fn at(&self, uv: DVec2) -> f64 {
        self.a * (self.k * uv.x + self.c).sin() * (self.l * uv.y).cos()
    }
    fn gradient(&self, uv: DVec2) -> DVec2 {
        let (s, co) = (
            (self.k * uv.x + self.c).sin(),
            (self.k * uv.x + self.c).cos(),
        );
        DVec2::new(
            self.a * self.k * co * (self.l * uv.y).cos(),
            -self.a * self.l * s * (self.l * uv.y).sin(),
        )
    }
}

/// The unit normal of O + B N/|N| by central differences of the displaced surface.
fn displaced_normal(surface: impl Fn(DVec2) -> (DVec3, DVec3), b: Height, uv: DVec2) -> DVec3 {
    let displaced = |uv: DVec2| {
        let (p, n) = surface(uv);
        p + n * b.at(uv)
    };
    let h = 1e-6;
    let du = (displaced(uv + DVec2::X * h) - displaced(uv - DVec2::X * h)) / (2.0 * h);
    let dv = (displaced(uv + DVec2::Y * h) - displaced(uv - DVec2::Y * h)) / (2.0 * h);
    du.cross(dv).normalize()
}

fn height() -> impl Strategy<Value = Height> {
    (1.0..8.0f64, 1.0..8.0f64, 0.0..TAU).prop_map(|(k, l, c)| Height { a: 1.0, k, l, c })
}

proptest! {
    /// On a plane (any frame, any scale of its parameterisation) Blinn's normal is the
    /// displaced surface's normal: the dropped term B (N/|N|)_u is zero.
    #[test]
    fn bumped_plane_normals_are_the_displaced_normals(
        f in frame(), size in (0.2..3.0f64, 0.2..3.0f64), b in height(),
        amplitude in 1e-4..0.05f64, uv in (0.0..1.0f64, 0.0..1.0f64),
    ) {
        let m = Mapping { size: DVec2::new(size.0, size.1), ..mapping(IntermediateSurface::Plane, f, 1.0) };
        let b = Height { a: amplitude, ..b };
        let uv = DVec2::new(uv.0, uv.1);
        let surface = |uv: DVec2| (f.from_local(m.surface_point(uv, DVec3::ZERO)), f.z);
        let p = surface(uv).0;
        let bumped = perturb(f.z, m.tangents(p, f.z), b.gradient(uv));
        let exact = displaced_normal(surface, b, uv);
        prop_assert!(bumped.angle_between(exact) < 1e-6, "{bumped} vs {exact}");
    }

    /// On a sphere the dropped term B (N/|N|)_u is parallel to N, so Blinn's normal
    /// matches the displaced surface's to first order: the angle between them is
    /// second order in the amplitude, a small fraction of the tilt itself.
    #[test]
    fn bumped_sphere_normals_match_the_displaced_normals_to_first_order(
        f in frame(), r in 0.3..3.0f64, b in height(),
        amplitude in 1e-4..1e-2f64, uv in (0.05..0.95f64, 0.15..0.85f64),
    ) {
        let m = mapping(IntermediateSurface::Sphere, f, 1.0);
        let b = Height { a: amplitude * r, ..b };
        let uv = DVec2::new(uv.0, uv.1);
        let through = DVec3::X * r;
        let surface = |uv: DVec2| {
            let l = m.surface_point(uv, through);
            (f.from_local(l), f.direction_from_local(l / r))
        };
        let (p, n) = surface(uv);
        let bumped = perturb(n, m.tangents(p, n), b.gradient(uv));
        let exact = displaced_normal(surface, b, uv);
        let tilt = n.angle_between(exact);
        let error = bumped.angle_between(exact);
        prop_assert!(error <= 4.0 * amplitude * tilt + 1e-7, "error {error}, tilt {tilt}");
    }
}

/// The bump-mapping entry's scene table at a small size.
fn bump_table() -> toml::Table {
    let mut table = catalogue::entry("bump-mapping").unwrap().scene;
    tables::set(&mut table, "camera.width=120").unwrap();
    tables::set(&mut table, "camera.height=90").unwrap();
    table
}

fn render_table(table: toml::Table) -> Image {
    render(&scene_from_table(table, &catalogue::resources()).unwrap()).unwrap()
}

#[test]
fn a_zero_height_bump_map_changes_nothing() {
    let mut flat = bump_table();
    tables::set(&mut flat, "materials.sphere.bump_height=0.0").unwrap();
    tables::set(&mut flat, "materials.floor.bump_height=0.0").unwrap();
    let mut plain = bump_table();
    for m in ["sphere", "floor"] {
        let material = plain["materials"][m].as_table().unwrap().clone();
        let mut material = material;
        material.remove("bump_texture");
        material.remove("bump_height");
        plain["materials"].as_table_mut().unwrap()[m] = material.into();
    }
    let (a, b) = (render_table(flat), render_table(plain));
    assert!(a.pixels == b.pixels, "a zero bump height changed the image");
    // And a non-zero one does change it (the comparison can fail).
    assert!(render_table(bump_table()).pixels != b.pixels);
}

#[test]
fn bumps_move_with_their_object() {
    // Rotate and translate everything (objects, light, camera) by one rigid motion:
    // wrinkles attached to the surfaces give the same picture; wrinkles fixed in
    // world space would not.
    let axis = DVec3::new(0.3, 1.0, -0.2).normalize();
    let degrees = 37.0f64;
    let shift = DVec3::new(1.5, -0.5, 2.0);
    let motion = glam::DMat4::from_translation(shift)
        * glam::DMat4::from_axis_angle(axis, degrees.to_radians());
    let mut moved = bump_table();
    let point = |key: &str, t: &toml::Table| -> DVec3 {
        let a = t[key].as_array().unwrap();
        DVec3::new(
            a[0].as_float().unwrap(),
            a[1].as_float().unwrap(),
            a[2].as_float().unwrap(),
        )
    };
    let set = |table: &mut toml::Table, key: &str, v: DVec3| {
        tables::set(table, &format!("{key}=[{}, {}, {}]", v.x, v.y, v.z)).unwrap();
    };
    let camera = moved["camera"].as_table().unwrap().clone();
    set(
        &mut moved,
        "camera.eye",
        motion.transform_point3(point("eye", &camera)),
    );
    set(
        &mut moved,
        "camera.look_at",
        motion.transform_point3(point("look_at", &camera)),
    );
    set(&mut moved, "camera.up", motion.transform_vector3(DVec3::Y));
    let light = moved["lights"][0].as_table().unwrap().clone();
    set(
        &mut moved,
        "lights.0.position",
        motion.transform_point3(point("position", &light)),
    );
    for k in 0..2 {
        let extra = format!(
            "objects.{k}.transform=[{}, {{ rotate = {{ axis = [{}, {}, {}], degrees = {degrees} }} }}, {{ translate = [{}, {}, {}] }}]",
            moved["objects"][k]["transform"]
                .as_array()
                .unwrap()
                .iter()
                .map(|s| s.to_string())
                .collect::<Vec<_>>()
                .join(", "),
            axis.x,
            axis.y,
            axis.z,
            shift.x,
            shift.y,
            shift.z
        );
        tables::set(&mut moved, &extra).unwrap();
    }
    let (before, after) = (render_table(bump_table()), render_table(moved));
    let differing = before
        .pixels
        .iter()
        .zip(&after.pixels)
        .filter(|(a, b)| (**a - **b).abs().max_element() > 1e-3 * a.max_element().max(1e-3))
        .count();
    // Only samples exactly on a polygon edge may fall the other way.
    assert!(
        differing * 1000 < before.pixels.len(),
        "{differing} of {} pixels changed",
        before.pixels.len()
    );
}

#[test]
fn the_box_mapping_reproduces_the_boxs_own_coordinates() {
    let scene = |mapping: &str| {
        scene_from(&format!(
            r#"{}
            [textures.t]
            procedural = "grid"
            [materials.m]
            diffuse = [0.5, 0.5, 0.5]
            diffuse_texture = "t"
            {mapping}
            [[objects]]
            shape = "box"
            material = "m"
            transform = [{{ rotate = {{ axis = [1.0, 2.0, 3.0], degrees = 40.0 }} }}]
            "#,
            crate::support::camera([2.0, 3.0, 4.0], [0.0, 0.0, 0.0], 40.0, 8, 8)
        ))
    };
    let own = scene("");
    let mapped = scene(
        "mapping = { surface = \"box\", axis = [0.0, 0.0, 1.0], reference = [1.0, 0.0, 0.0] }",
    );
    for (a, b) in own.polygons.iter().zip(&mapped.polygons) {
        for (u, v) in a.vertices.iter().zip(&b.vertices) {
            assert!((u.uv - v.uv).length() < 1e-12, "{} vs {}", u.uv, v.uv);
        }
    }
}

/// At a pole, where θ is undefined, a vertex takes the mean u of the polygon's other
/// vertices: between their least and greatest u, never outside (the course's pinching).
#[test]
fn a_pole_vertex_takes_the_mean_u_of_the_others() {
    use lumiere::texture::mapping::fix_seam;
    for (others, expected) in [
        (vec![0.5, 0.55], 0.525),
        (vec![0.2, 0.3, 0.4], 0.3),
        // Across the seam: 0.95 and 0.05 are a tenth of a turn apart.
        (vec![0.95, 0.05], 1.0),
    ] {
        let mut uvs: Vec<DVec2> = std::iter::once(DVec2::new(0.0, 1.0))
            .chain(others.iter().map(|&u| DVec2::new(u, 0.9)))
            .collect();
        let mut on_axis = vec![false; uvs.len()];
        on_axis[0] = true;
        fix_seam(&mut uvs, &on_axis, 1.0);
        assert!(
            (uvs[0].x - expected).abs() < 1e-12,
            "others {others:?}: the pole's u {}, expected {expected}",
            uvs[0].x
        );
    }
}

/// The procedural sky brightens from the zenith towards the horizon (its documented
/// gradient): straight up it is the deep blue, just above the horizon nearly white.
#[test]
fn the_sky_is_blue_overhead_and_pale_at_the_horizon() {
    use lumiere::texture::environment::sky::ProceduralEnvironment;
    // Away from the sun (up and to the left of −z): towards +x.
    let up = ProceduralEnvironment::Sky.radiance(DVec3::Y);
    let low = ProceduralEnvironment::Sky.radiance(DVec3::new(1.0, 1e-4, 0.0));
    assert!(up.z > 2.0 * up.x, "overhead {up}: blue");
    assert!(low.min_element() > 0.8, "at the horizon {low}: pale");
    assert!(low.x > 3.0 * up.x, "{low} against {up}");
}

/// An 8-bit texel is its byte over 255, decoded from sRGB: 0 is black, 255 is
/// exactly 1, and 128 the sRGB curve's value at 128/255 (the standard's piecewise
/// formula, written out here).
#[test]
fn eight_bit_texels_are_their_bytes_over_255_decoded_from_srgb() {
    let image = image::RgbImage::from_fn(3, 1, |x, _| image::Rgb([[0u8, 128, 255][x as usize]; 3]));
    let mut bytes = Vec::new();
    image
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .unwrap();
    let texels = Texels::decode(&bytes).unwrap();
    let c = 128.0f64 / 255.0;
    let decoded = ((c + 0.055) / 1.055).powf(2.4);
    let expected = [0.0, decoded, 1.0];
    for (i, e) in expected.iter().enumerate() {
        let got = texels.at(i as i64, 0, Wrap::Clamp);
        assert!(
            (got.x as f64 - e).abs() < 1e-6,
            "byte {}: {got}, expected {e}",
            [0, 128, 255][i]
        );
    }
}

/// The procedural sky's sun glows as a cos⁶⁴ lobe (its documented shape): at the
/// sun's elevation, a direction turned θ away in azimuth has the same sky gradient,
/// and exceeds a direction far from the sun by (1.6, 1.4, 1.0) cos⁶⁴ of its angle to
/// the sun.
#[test]
fn the_suns_glow_is_a_cos64_lobe() {
    use lumiere::texture::environment::sky::ProceduralEnvironment;
    let sun = DVec3::new(-0.45, 0.6, -0.66).normalize();
    let turn = |degrees: f64| {
        let (s, c) = degrees.to_radians().sin_cos();
        DVec3::new(sun.x * c - sun.z * s, sun.y, sun.x * s + sun.z * c)
    };
    let far = ProceduralEnvironment::Sky.radiance(turn(180.0));
    for degrees in [0.0, 5.0, 10.0, 15.0] {
        let d = turn(degrees);
        let glow = ProceduralEnvironment::Sky.radiance(d) - far;
        let expected = 1.6 * d.dot(sun).powi(64);
        assert!(
            (glow.x as f64 - expected).abs() < 1e-5,
            "{degrees}° from the sun: {glow}, expected red {expected}"
        );
    }
}

/// Bump height is the displacement's scale: a floor 2 × 2 (∂P/∂u and ∂P/∂v of
/// length 2) bumped by h F(u, v) with F a value noise is shaded as the displaced
/// surface y = h F, whose slopes are h F_u / 2 and h F_v / 2, so under a light
/// straight above each sample's radiance is the flat floor's times
/// 1/√(1 + (h F_u/2)² + (h F_v/2)²) (F's gradient from the texture).
#[test]
fn the_bump_height_scales_the_displacement() {
    let h = 0.05;
    let text = format!(
        "{}[render]\nshading = \"phong\"\n\
         [textures.bumps]\nprocedural = \"noise\"\ncells = 4\nseed = 5\n\
         [materials.floor]\ndiffuse = [0.5, 0.5, 0.5]\nbump_texture = \"bumps\"\nbump_height = {h}\n\
         [[lights]]\ntype = \"distant\"\ndirection = [0.0, -1.0, 0.0]\nirradiance = [1.0, 1.0, 1.0]\n\
         [[objects]]\nshape = \"quad\"\nname = \"floor\"\nmaterial = \"floor\"\ntransform = [{{ scale = 2.0 }}]\n",
        crate::support::camera([0.0, 3.0, 0.001], [0.0, 0.0, 0.0], 30.0, 48, 48)
    );
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bumps.toml");
    std::fs::write(&path, text).unwrap();
    let scene = load_scene(path.to_str().unwrap(), &[]).unwrap();
    let frame = lumiere::Renderer::new(scene.clone())
        .render_with_buffers(&["uv".to_string(), "polygon".to_string()])
        .unwrap();
    let lumiere::BufferData::Values { data: uv, channels } = &frame.buffer("uv").unwrap().data
    else {
        panic!("uv values")
    };
    let lumiere::BufferData::Ids(ids) = &frame.buffer("polygon").unwrap().data else {
        panic!("ids")
    };
    let image = render(&scene).unwrap();
    let flat = 0.5 / PI as f32;
    let (mut checked, mut tilted) = (0, 0);
    for (k, pixel) in image.pixels.iter().enumerate() {
        if ids[k] == u32::MAX {
            continue;
        }
        let at = DVec2::new(uv[k * channels] as f64, uv[k * channels + 1] as f64);
        let (_, g) = scene.textures[0].height(at);
        let slope = g * h / 2.0;
        let expected = flat as f64 / (1.0 + slope.length_squared()).sqrt();
        assert!(
            (pixel.x as f64 - expected).abs() < 1e-5,
            "sample {k} at uv {at}: {} against {expected}",
            pixel.x
        );
        checked += 1;
        tilted += usize::from(expected < 0.999 * flat as f64);
    }
    assert!(
        checked > 1000 && tilted > 500,
        "{checked} samples, {tilted} tilted"
    );
}
