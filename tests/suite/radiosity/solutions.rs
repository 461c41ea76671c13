//! Radiosity against exact values: form factors against Lambert's point-to-polygon
//! formula and the closed-form patch-to-patch factors of the radiative-transfer
//! catalogues (derived below), the delta form-factor table against its exact face
//! totals, the solvers against the furnace and an exactly solved cube, and the two
//! solvers against each other.

use glam::{DVec3, Vec3};
use lumiere::Renderer;
use lumiere::geometry::lambert_contour::form_factor;
use lumiere::radiosity::form_factors::patch_factors;
use lumiere::radiosity::gathering::{gather, gauss_seidel};
use lumiere::radiosity::hemicube::Hemicube;
use lumiere::radiosity::receivers::Receivers;
use lumiere::radiosity::shooting::Shooting;
use lumiere::radiosity::{
    Display, Division, Estimator, FormFactorMethod, Mesh, Settings, Solver, Stop, solve,
};
use lumiere::scene::tables;
use lumiere::scene::{Camera, Scene, scene_from_table};
use std::f64::consts::PI;

// ---------------------------------------------------------------------------
// Closed forms (Siegel & Howell's catalogue, configurations C-11 and C-14),
// written from the integrals they solve.

/// Two directly opposed parallel rectangles a × b at distance c.
fn parallel_rectangles(a: f64, b: f64, c: f64) -> f64 {
    let (x, y) = (a / c, b / c);
    let (x2, y2) = (x * x, y * y);
    2.0 / (PI * x * y)
        * (0.5 * ((1.0 + x2) * (1.0 + y2) / (1.0 + x2 + y2)).ln()
            + x * (1.0 + y2).sqrt() * (x / (1.0 + y2).sqrt()).atan()
            + y * (1.0 + x2).sqrt() * (y / (1.0 + x2).sqrt()).atan()
            - x * x.atan()
            - y * y.atan())
}

/// From a rectangle of width w to a perpendicular one of height h sharing its
/// edge of length l.
fn perpendicular_rectangles(l: f64, w: f64, h: f64) -> f64 {
    let (hh, ww) = (h / l, w / l);
    let (h2, w2) = (hh * hh, ww * ww);
    let s = (h2 + w2).sqrt();
    let log = ((1.0 + w2) * (1.0 + h2) / (1.0 + w2 + h2)).ln()
        + w2 * (w2 * (1.0 + w2 + h2) / ((1.0 + w2) * (w2 + h2))).ln()
        + h2 * (h2 * (1.0 + h2 + w2) / ((1.0 + h2) * (h2 + w2))).ln();
    (ww * (1.0 / ww).atan() + hh * (1.0 / hh).atan() - s * (1.0 / s).atan() + 0.25 * log)
        / (PI * ww)
}

#[test]
fn the_closed_forms_give_the_published_unit_square_values() {
    // The catalogue values for unit squares (a check of the transcription).
    assert!((parallel_rectangles(1.0, 1.0, 1.0) - 0.1998249).abs() < 1e-7);
    assert!((perpendicular_rectangles(1.0, 1.0, 1.0) - 0.2000438).abs() < 1e-7);
}

// ---------------------------------------------------------------------------
// Scenes

/// The corners turned, if need be, so that their normal is `normal`.
fn facing(mut corners: Vec<DVec3>, normal: DVec3) -> Vec<DVec3> {
    let n = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
    if n.dot(normal) < 0.0 {
        corners.reverse();
    }
    corners
}

/// A scene of polygons, each with (reflectance, emitted radiance).
fn scene_of(polygons: &[(Vec<DVec3>, f64, f64)]) -> Scene {
    let mut text = crate::support::camera([0.5, 0.5, -3.0], [0.5, 0.5, 0.5], 60.0, 32, 32);
    for (k, (_, rho, emission)) in polygons.iter().enumerate() {
        text += &format!(
            "[materials.m{k}]\ndiffuse = [{rho}, {rho}, {rho}]\nemission = [{emission}, {emission}, {emission}]\n"
        );
    }
    for (k, (corners, _, _)) in polygons.iter().enumerate() {
        let vertices: Vec<[f64; 3]> = corners.iter().map(|c| c.to_array()).collect();
        text += &format!(
            "[[objects]]\nshape = \"polygon\"\nname = \"p{k}\"\nmaterial = \"m{k}\"\nvertices = {vertices:?}\n"
        );
    }
    let table = tables::parse(&text, "test scene").unwrap();
    scene_from_table(table, &lumiere::catalogue::resources()).unwrap()
}

/// Source a × b in y = 0 facing up, receiver directly above at height c facing down.
fn parallel_pair(a: f64, b: f64, c: f64) -> Scene {
    let square = |y: f64| {
        vec![
            DVec3::new(0.0, y, 0.0),
            DVec3::new(a, y, 0.0),
            DVec3::new(a, y, b),
            DVec3::new(0.0, y, b),
        ]
    };
    scene_of(&[
        (facing(square(0.0), DVec3::Y), 0.5, 0.0),
        (facing(square(c), DVec3::NEG_Y), 0.5, 0.0),
    ])
}

/// Source l × w in y = 0 (z from 0 to w) facing up, receiver l × h in z = 0 (y from
/// 0 to h) facing +z: they share the edge along x.
fn perpendicular_pair(l: f64, w: f64, h: f64) -> Scene {
    let floor = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(l, 0.0, 0.0),
        DVec3::new(l, 0.0, w),
        DVec3::new(0.0, 0.0, w),
    ];
    let wall = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(l, 0.0, 0.0),
        DVec3::new(l, h, 0.0),
        DVec3::new(0.0, h, 0.0),
    ];
    scene_of(&[
        (facing(floor, DVec3::Y), 0.5, 0.0),
        (facing(wall, DVec3::Z), 0.5, 0.0),
    ])
}

/// The unit cube seen from inside: six faces facing in, with reflectance `rho` and
/// the given emission per face (top first, then bottom, then the four sides).
fn closed_cube(rho: f64, emission: [f64; 6]) -> Scene {
    closed_box(DVec3::ONE, rho, emission)
}

/// The box [0, size] seen from inside, with reflectance `rho` and the given
/// emission per face (in `closed_box_faces`' order).
fn closed_box(size: DVec3, rho: f64, emission: [f64; 6]) -> Scene {
    let polygons: Vec<_> = closed_box_faces(size)
        .into_iter()
        .zip(emission)
        .map(|(corners, e)| (corners, rho, e))
        .collect();
    scene_of(&polygons)
}

/// The faces of the box [0, size], facing in, in `closed_cube`'s order: y = size.y
/// (top), y = 0, x = 0, x = size.x, z = 0, z = size.z.
fn closed_box_faces(size: DVec3) -> Vec<Vec<DVec3>> {
    let c = |x: f64, y: f64, z: f64| DVec3::new(x, y, z) * size;
    let faces = [
        (
            vec![c(0., 1., 0.), c(1., 1., 0.), c(1., 1., 1.), c(0., 1., 1.)],
            DVec3::NEG_Y,
        ),
        (
            vec![c(0., 0., 0.), c(1., 0., 0.), c(1., 0., 1.), c(0., 0., 1.)],
            DVec3::Y,
        ),
        (
            vec![c(0., 0., 0.), c(0., 1., 0.), c(0., 1., 1.), c(0., 0., 1.)],
            DVec3::X,
        ),
        (
            vec![c(1., 0., 0.), c(1., 1., 0.), c(1., 1., 1.), c(1., 0., 1.)],
            DVec3::NEG_X,
        ),
        (
            vec![c(0., 0., 0.), c(1., 0., 0.), c(1., 1., 0.), c(0., 1., 0.)],
            DVec3::Z,
        ),
        (
            vec![c(0., 0., 1.), c(1., 0., 1.), c(1., 1., 1.), c(0., 1., 1.)],
            DVec3::NEG_Z,
        ),
    ];
    faces
        .into_iter()
        .map(|(corners, n)| facing(corners, n))
        .collect()
}

/// F from patch 0 to patch 1 (each polygon one patch), averaged over m × m
/// elements of patch 0.
fn patch_to_patch(scene: &Scene, method: FormFactorMethod, resolution: u32, m: u32) -> f64 {
    let mesh = Mesh::build(scene, Division::Whole, Division::Count(m)).unwrap();
    let estimator = Estimator::new(method, resolution, scene);
    patch_factors(&mesh, &estimator.element_to_patch(&mesh))[0][1]
}

/// The estimate at the centre of polygon 0 of its factor to polygon 1, and Lambert's
/// exact point-to-polygon value.
fn point_to_patch(scene: &Scene, method: FormFactorMethod, resolution: u32) -> (f64, f64) {
    let mesh = Mesh::build(scene, Division::Whole, Division::Whole).unwrap();
    let source = &mesh.patches[0];
    let estimator = Estimator::new(method, resolution, scene);
    let estimate = estimator.factors(
        source.centre,
        source.normal,
        &Receivers::patches(&mesh),
        &|j| j == 0,
    )[1];
    let exact = form_factor(source.centre, source.normal, &mesh.patches[1].corners);
    (estimate, exact)
}

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

// ---------------------------------------------------------------------------
// The delta form-factor table

#[test]
fn the_delta_table_sums_to_one_within_order_one_over_r_squared() {
    let mut previous = f64::INFINITY;
    for r in [8, 16, 32, 64, 128, 256] {
        let (top, side) = Hemicube::new(r).face_sums();
        let error = (top + 4.0 * side - 1.0).abs();
        // O(1/R²): the error times R² stays bounded, and each doubling divides the
        // error by about four.
        // Measured: error × R² = 0.542 from R = 8 on.
        assert!(error * (r * r) as f64 <= 0.55, "R = {r}: error {error:e}");
        assert!(
            error < previous / 3.0,
            "R = {r}: {error:e} after {previous:e}"
        );
        previous = error;
    }
}

#[test]
fn the_top_face_total_is_lamberts_factor_of_the_face() {
    // The top face is a 2 × 2 square at height 1 over the point: its exact factor
    // by Lambert's formula (0.5541264), and each side takes a quarter of the rest.
    let square = [
        DVec3::new(-1.0, -1.0, 1.0),
        DVec3::new(1.0, -1.0, 1.0),
        DVec3::new(1.0, 1.0, 1.0),
        DVec3::new(-1.0, 1.0, 1.0),
    ];
    let exact_top = form_factor(DVec3::ZERO, DVec3::Z, &square);
    assert!((exact_top - 0.5541264).abs() < 1e-7);
    let (top, side) = Hemicube::new(512).face_sums();
    assert!((top - exact_top).abs() < 1e-5, "{top} against {exact_top}");
    assert!((side - (1.0 - exact_top) / 4.0).abs() < 1e-5, "{side}");
}

// ---------------------------------------------------------------------------
// Form factors against exact values

#[test]
fn a_point_estimate_converges_to_lamberts_point_to_patch_factor() {
    for (name, scene) in [
        ("parallel", parallel_pair(1.0, 1.0, 1.0)),
        ("perpendicular", perpendicular_pair(1.0, 1.0, 1.0)),
    ] {
        for method in [FormFactorMethod::Hemicube, FormFactorMethod::Nusselt] {
            let errors: Vec<f64> = [32, 128, 512]
                .iter()
                .map(|&r| {
                    let (estimate, exact) = point_to_patch(&scene, method, r);
                    relative(estimate, exact)
                })
                .collect();
            assert!(errors[2] < 0.01, "{name} {method:?}: {errors:?}");
            assert!(errors[2] < errors[0], "{name} {method:?}: {errors:?}");
        }
        let (analytic, exact) = point_to_patch(&scene, FormFactorMethod::Analytic, 1);
        assert!(relative(analytic, exact) < 1e-12, "{name}");
    }
}

#[test]
fn element_averaged_factors_converge_to_the_closed_form_patch_to_patch_factors() {
    let cases = [
        (
            "parallel 1 x 1 at 1",
            parallel_pair(1.0, 1.0, 1.0),
            parallel_rectangles(1.0, 1.0, 1.0),
        ),
        (
            "parallel 2 x 1 at 0.5",
            parallel_pair(2.0, 1.0, 0.5),
            parallel_rectangles(2.0, 1.0, 0.5),
        ),
        (
            "parallel 1 x 3 at 2",
            parallel_pair(1.0, 3.0, 2.0),
            parallel_rectangles(1.0, 3.0, 2.0),
        ),
        (
            "perpendicular 1, 1, 1",
            perpendicular_pair(1.0, 1.0, 1.0),
            perpendicular_rectangles(1.0, 1.0, 1.0),
        ),
        (
            "perpendicular 1, 2, 0.5",
            perpendicular_pair(1.0, 2.0, 0.5),
            perpendicular_rectangles(1.0, 2.0, 0.5),
        ),
        (
            "perpendicular 2, 1, 3",
            perpendicular_pair(2.0, 1.0, 3.0),
            perpendicular_rectangles(2.0, 1.0, 3.0),
        ),
    ];
    for (name, scene, exact) in &cases {
        let hemicube = patch_to_patch(scene, FormFactorMethod::Hemicube, 256, 16);
        let nusselt = patch_to_patch(scene, FormFactorMethod::Nusselt, 256, 16);
        let analytic = patch_to_patch(scene, FormFactorMethod::Analytic, 1, 16);
        let one_element = patch_to_patch(scene, FormFactorMethod::Analytic, 1, 1);
        assert!(
            relative(hemicube, *exact) < 0.01,
            "{name}: hemicube {hemicube} against {exact}"
        );
        assert!(
            relative(nusselt, *exact) < 0.01,
            "{name}: nusselt {nusselt} against {exact}"
        );
        assert!(
            relative(analytic, *exact) < 0.01,
            "{name}: analytic {analytic} against {exact}"
        );
        // One element is the centre approximation: refining must help.
        assert!(
            relative(analytic, *exact) < relative(one_element, *exact),
            "{name}"
        );
    }
}

#[test]
fn closed_box_factors_are_reciprocal_close_to_one_per_row_and_zero_on_the_diagonal() {
    let scene = closed_cube(0.5, [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    let mesh = Mesh::build(&scene, Division::Whole, Division::Count(8)).unwrap();
    for method in [
        FormFactorMethod::Hemicube,
        FormFactorMethod::Nusselt,
        FormFactorMethod::Analytic,
    ] {
        let estimator = Estimator::new(method, 128, &scene);
        let f = patch_factors(&mesh, &estimator.element_to_patch(&mesh));
        for (i, row) in f.iter().enumerate() {
            assert_eq!(row[i], 0.0, "{method:?}");
            let sum: f64 = row.iter().sum();
            assert!((sum - 1.0).abs() < 0.01, "{method:?} row {i} sums to {sum}");
            for (j, f_ij) in row.iter().enumerate() {
                let (a, b) = (mesh.patches[i].area * f_ij, mesh.patches[j].area * f[j][i]);
                assert!(
                    (a - b).abs() <= 0.01 * a.max(b),
                    "{method:?} A{i} F{i}{j} = {a}, A{j} F{j}{i} = {b}"
                );
            }
        }
    }
}

// ---------------------------------------------------------------------------
// Solvers

fn settings(solver: Solver, method: FormFactorMethod, elements: u32) -> Settings {
    Settings {
        solver,
        form_factors: method,
        resolution: 128,
        patches: Division::Whole,
        elements: Division::Count(elements),
        tolerance: 1e-9,
        unshot: 1e-6,
        max_steps: 100_000,
        ambient: false,
        display: Display::Gouraud,
        memory_budget: 1 << 30,
        subdivision: None,
    }
}

#[test]
fn the_furnace_converges_to_e_over_one_minus_rho_with_both_solvers() {
    let (rho, e) = (0.5, 1.0);
    let scene = closed_cube(rho, [e; 6]);
    // Emission in the file is radiance; radiosity is π times it.
    let expected = PI * e / (1.0 - rho);
    let gathered = solve(
        &scene,
        &settings(Solver::Gathering, FormFactorMethod::Hemicube, 4),
        &mut |_, _| {},
    )
    .unwrap();
    for b in &gathered.elements {
        assert!(
            relative(b.x as f64, expected) < 0.01,
            "gathering: {b} against {expected}"
        );
    }
    // Shooting: 8 × 8 patches per face, each its own element.
    let mut s = settings(Solver::Shooting, FormFactorMethod::Hemicube, 1);
    s.patches = Division::Count(8);
    s.unshot = 1e-4;
    let shot = solve(&scene, &s, &mut |_, _| {}).unwrap();
    let mesh = &shot.mesh;
    let total: f64 = shot
        .elements
        .iter()
        .zip(&mesh.elements)
        .map(|(b, e)| b.x as f64 * e.area)
        .sum();
    assert!(
        relative(total, expected * 6.0) < 2e-3,
        "shooting: total {total}"
    );
    // Two patches or more from the cube's edges every element is within 1%. Near
    // an edge, a shooter's factor to an element across the crease is taken from
    // the shooter's centre, which sees a neighbour 5% smaller than the neighbour
    // sees the shooter (point-to-patch 0.190 against 0.200 for adjacent squares):
    // the patch-centre approximation, the method's own limit, darkens the
    // elements along an edge by about 1% and brightens the next row by about 1%
    // (measured at resolution 128 and 512 alike).
    let from_edge = |c: DVec3| {
        c.to_array()
            .into_iter()
            .filter(|&x| x > 1e-9 && x < 1.0 - 1e-9)
            .map(|x| x.min(1.0 - x))
            .fold(f64::INFINITY, f64::min)
    };
    let mut inner = 0;
    for (b, element) in shot.elements.iter().zip(&mesh.elements) {
        let error = relative(b.x as f64, expected);
        if from_edge(element.centre) > 0.25 {
            inner += 1;
            assert!(
                error < 0.01,
                "shooting: {b} against {expected} at {}",
                element.centre
            );
        } else {
            assert!(
                error < 0.02,
                "shooting, near an edge: {b} against {expected}"
            );
        }
    }
    assert_eq!(inner, 6 * 16);
}

#[test]
fn the_cube_lit_from_its_top_matches_its_exact_solution() {
    // One patch per face, ρ = 0.5, the top emitting. By symmetry three unknowns:
    // T = E + ρ (F_o B + 4 F_a S), B = ρ (F_o T + 4 F_a S),
    // S = ρ (F_a T + F_a B + F_o S + 2 F_a S); solved here by Cramer's rule with the
    // closed-form factors (adjacent F_a, opposite F_o).
    let (fa, fo) = (
        perpendicular_rectangles(1.0, 1.0, 1.0),
        parallel_rectangles(1.0, 1.0, 1.0),
    );
    let (rho, e) = (0.5, PI);
    let m = [
        [1.0, -rho * fo, -4.0 * rho * fa],
        [-rho * fo, 1.0, -4.0 * rho * fa],
        [-rho * fa, -rho * fa, 1.0 - rho * (fo + 2.0 * fa)],
    ];
    let det = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let rhs = [e, 0.0, 0.0];
    let solve3 = |k: usize| {
        let mut mk = m;
        for r in 0..3 {
            mk[r][k] = rhs[r];
        }
        det(mk) / det(m)
    };
    let (top, bottom, side) = (solve3(0), solve3(1), solve3(2));
    assert!((top / PI - 1.0909091).abs() < 1e-6 && (bottom / PI - 0.1817458).abs() < 1e-6);
    // The energy invariant: Σ A B = Σ A E / (1 − ρ).
    assert!((top + bottom + 4.0 * side - 2.0 * PI).abs() < 1e-9);

    let scene = closed_cube(rho, [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    let mesh = Mesh::build(&scene, Division::Whole, Division::Count(16)).unwrap();
    let estimator = Estimator::new(FormFactorMethod::Analytic, 1, &scene);
    let g = gather(&mesh, &estimator, 1e-12, 1 << 30).unwrap();
    let expected = [top, bottom, side, side, side, side];
    for (p, want) in g.patches.iter().zip(expected) {
        assert!(relative(p.x, want) < 1e-3, "{} against {want}", p.x);
    }
}

#[test]
fn elements_average_back_to_their_patch_and_one_element_per_patch_is_the_patch_method() {
    let scene = closed_cube(0.6, [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    let mesh = Mesh::build(&scene, Division::Count(2), Division::Count(3)).unwrap();
    let estimator = Estimator::new(FormFactorMethod::Hemicube, 64, &scene);
    let g = gather(&mesh, &estimator, 1e-12, 1 << 30).unwrap();
    for (i, patch) in mesh.patches.iter().enumerate() {
        // Σ_q A_iq B_iq / A_i = E_i + ρ_i Σ_j F_ij B_j exactly (steps 3 and 5).
        let mean: DVec3 = patch
            .elements
            .clone()
            .map(|e| g.elements[e] * mesh.elements[e].area)
            .sum::<DVec3>()
            / patch.area;
        let gathered: DVec3 = g.patch_factors[i]
            .iter()
            .zip(&g.patches)
            .map(|(f, b)| *b * *f)
            .sum();
        let one_step = patch.emission.as_dvec3() + patch.reflectance.as_dvec3() * gathered;
        assert!((mean - one_step).abs().max_element() <= 1e-12 * one_step.max_element().max(1.0));
    }
    let whole = Mesh::build(&scene, Division::Count(2), Division::Whole).unwrap();
    let plain = gather(&whole, &estimator, 1e-12, 1 << 30).unwrap();
    for (e, p) in plain.elements.iter().zip(&plain.patches) {
        assert!((*e - *p).abs().max_element() < 1e-9 * p.max_element().max(1.0));
    }
}

#[test]
fn gathering_refuses_a_matrix_over_its_memory_budget_and_suggests_shooting() {
    let scene = closed_cube(0.5, [1.0; 6]);
    let mesh = Mesh::build(&scene, Division::Count(8), Division::Count(2)).unwrap();
    let estimator = Estimator::new(FormFactorMethod::Hemicube, 16, &scene);
    let error = gather(&mesh, &estimator, 1e-6, 1000)
        .err()
        .unwrap()
        .to_string();
    assert!(error.contains("shooting"), "{error}");
}

#[test]
fn shooting_conserves_power_with_the_ambient_term_and_grows_monotonically_without() {
    let rho = 0.5;
    let scene = closed_cube(rho, [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    let mesh = Mesh::build(&scene, Division::Count(2), Division::Count(2)).unwrap();
    let estimator = Estimator::new(FormFactorMethod::Hemicube, 128, &scene);
    let converged = mesh.emitted_power().x as f64 / (1.0 - rho);
    let total = |b: &[Vec3]| -> f64 {
        b.iter()
            .zip(&mesh.elements)
            .map(|(b, e)| b.x as f64 * e.area)
            .sum()
    };
    let mut state = Shooting::start(&mesh);
    let mut previous = total(&state.displayed(&mesh, false));
    assert!(relative(total(&state.displayed(&mesh, true)), converged) < 0.01);
    let stop = Stop {
        unshot: 1e-4,
        max_steps: 200,
    };
    let mut steps = 0;
    state.run(&mesh, &estimator, stop, &mut |s| {
        steps += 1;
        let with = total(&s.displayed(&mesh, true));
        let without = total(&s.displayed(&mesh, false));
        assert!(
            relative(with, converged) < 0.01,
            "step {}: {with} against {converged}",
            s.steps
        );
        assert!(
            without >= previous,
            "step {}: {without} after {previous}",
            s.steps
        );
        previous = without;
    });
    assert!(steps > 20);
    assert!(relative(previous, converged) < 0.01);
}

#[test]
fn shooting_converges_to_the_gauss_seidel_solution_of_its_own_factors_on_the_cornell_box() {
    // Shooting from patch i uses i's hemi-cube row F_ij and hands element j the
    // reciprocal F'_ji = F_ij A_i / A_j; Gauss–Seidel on F' must reach the same
    // radiosities. (Gauss–Seidel on each element's own hemi-cube differs by the
    // hemi-cube's non-reciprocity: 1.7% in L1 on this mesh.)
    let sets = [
        "radiosity.patch_size=140.0".to_string(),
        "radiosity.element_size=140.0".to_string(),
    ];
    let scene = lumiere::load_scene("radiosity-shooting", &sets).unwrap();
    let mut s = scene.radiosity.clone().unwrap();
    s.unshot = 1e-5;
    s.ambient = false;
    let shot = solve(&scene, &s, &mut |_, _| {}).unwrap();
    let mesh = &shot.mesh;
    assert_eq!(mesh.patches.len(), mesh.elements.len());
    let estimator = Estimator::new(s.form_factors, s.resolution, &scene);
    let receivers = Receivers::elements(mesh);
    let n = mesh.patches.len();
    let mut reciprocal = vec![vec![0.0; n]; n];
    for (i, p) in mesh.patches.iter().enumerate() {
        let row = estimator.factors(p.centre, p.normal, &receivers, &|j| j == i);
        for (j, f) in row.into_iter().enumerate() {
            reciprocal[j][i] = f * p.area / mesh.patches[j].area;
        }
    }
    for k in 0..3 {
        let emission: Vec<f64> = mesh.patches.iter().map(|p| p.emission[k] as f64).collect();
        let rho: Vec<f64> = mesh
            .patches
            .iter()
            .map(|p| p.reflectance[k] as f64)
            .collect();
        let (b, _) = gauss_seidel(&reciprocal, &emission, &rho, 1e-9);
        let difference: f64 = shot
            .elements
            .iter()
            .zip(&b)
            .zip(&mesh.patches)
            .map(|((a, b), p)| (a[k] as f64 - b).abs() * p.area)
            .sum();
        let size: f64 = b.iter().zip(&mesh.patches).map(|(b, p)| b * p.area).sum();
        assert!(
            difference / size < 0.005,
            "band {k}: relative difference {}",
            difference / size
        );
    }
}

// ---------------------------------------------------------------------------
// Properties of the geometric core

mod properties {
    use super::*;
    use proptest::prelude::*;

    /// A convex planar quad (a square with jittered corners) in a random frame.
    fn quad(jitter: [f64; 8], normal: DVec3, origin: DVec3, size: f64) -> Vec<DVec3> {
        let (t, b) = normal.any_orthonormal_pair();
        let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
        square
            .iter()
            .enumerate()
            .map(|(k, &(x, y))| {
                let (x, y) = (x + 0.2 * jitter[2 * k], y + 0.2 * jitter[2 * k + 1]);
                origin + (t * x + b * y) * size
            })
            .collect()
    }

    fn normal_strategy() -> impl Strategy<Value = DVec3> {
        (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64)
            .prop_filter("not zero", |(x, y, z)| x * x + y * y + z * z > 0.01)
            .prop_map(|(x, y, z)| DVec3::new(x, y, z).normalize())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        #[test]
        fn meshing_keeps_area_orientation_and_shares_grid_vertices(
            jitter in prop::array::uniform8(-1.0..1.0f64),
            normal in normal_strategy(),
            size in 0.5..3.0f64,
            patch in 0.2..2.0f64,
            element in 0.05..1.0f64,
            triangle in any::<bool>(),
        ) {
            let mut corners = quad(jitter, normal, DVec3::new(0.3, -0.2, 0.1), size);
            if triangle {
                corners.pop();
            }
            let scene = scene_of(&[(corners.clone(), 0.5, 0.0)]);
            let polygon_area = lumiere::geometry::polygon::area(&corners);
            let mesh = Mesh::build(&scene, Division::Size(patch), Division::Size(element)).unwrap();
            let patch_sum: f64 = mesh.patches.iter().map(|p| p.area).sum();
            let element_sum: f64 = mesh.elements.iter().map(|e| e.area).sum();
            prop_assert!(relative(patch_sum, polygon_area) < 1e-9);
            prop_assert!(relative(element_sum, polygon_area) < 1e-9);
            let mut next = 0;
            for (i, p) in mesh.patches.iter().enumerate() {
                prop_assert_eq!(p.elements.start, next);
                next = p.elements.end;
                let p_area = lumiere::geometry::polygon::area(&p.corners);
                prop_assert!(relative(p_area, p.area) < 1e-9);
                for e in p.elements.clone() {
                    prop_assert_eq!(mesh.elements[e].patch, i);
                    let c = mesh.element_corners(e);
                    let n = lumiere::geometry::polygon::newell_normal(&c);
                    prop_assert!(n.normalize().dot(scene.polygons[0].normal) > 1.0 - 1e-9);
                }
            }
            prop_assert_eq!(next, mesh.elements.len());
            // One grid of points per polygon: a triangle cut n per side has
            // (n + 1)(n + 2)/2 of them, a quad cut nu × nv has (nu + 1)(nv + 1).
            let users = mesh.vertex_elements();
            prop_assert!(users.iter().all(|u| !u.is_empty()));
            if triangle {
                let n = (mesh.elements.len() as f64).sqrt().round() as usize;
                prop_assert_eq!(n * n, mesh.elements.len());
                prop_assert_eq!(mesh.vertices.len(), (n + 1) * (n + 2) / 2);
            } else {
                let m = mesh.elements.len();
                let grid = (1..=m)
                    .filter(|nu| m.is_multiple_of(*nu))
                    .any(|nu| (nu + 1) * (m / nu + 1) == mesh.vertices.len());
                prop_assert!(grid, "{} elements, {} vertices", m, mesh.vertices.len());
            }
        }

        #[test]
        fn a_hemicube_estimate_agrees_with_lambert_for_any_polygon_above_the_point(
            jitter in prop::array::uniform8(-1.0..1.0f64),
            normal in normal_strategy(),
            height in 0.5..2.0f64,
            offset in (-1.0..1.0f64, -1.0..1.0f64),
            tilt in normal_strategy(),
        ) {
            // A receiver above the point's tangent plane, facing it more or less.
            let (t, b) = normal.any_orthonormal_pair();
            let centre = normal * height + (t * offset.0 + b * offset.1);
            let facing_normal = (-normal + tilt * 0.5).normalize();
            prop_assume!(facing_normal.dot(-centre) > 0.1);
            let receiver = quad(jitter, facing_normal, centre - facing_normal.any_orthonormal_pair().0 * 0.5, 1.0);
            prop_assume!(receiver.iter().all(|v| v.dot(normal) > 0.05));
            let source = quad([0.0; 8], normal, -(t + b) * 0.05, 0.1);
            let scene = scene_of(&[(source, 0.5, 0.0), (facing(receiver.clone(), facing_normal), 0.5, 0.0)]);
            let mesh = Mesh::build(&scene, Division::Whole, Division::Whole).unwrap();
            let exact = form_factor(mesh.patches[0].centre, normal, &mesh.patches[1].corners);
            let estimate = Estimator::new(FormFactorMethod::Hemicube, 256, &scene).factors(
                mesh.patches[0].centre, normal, &Receivers::patches(&mesh), &|j| j == 0,
            )[1];
            // Cells are all or nothing: the error is at most the cells along the
            // receiver's outline, a few thousandths at R = 256.
            prop_assert!((estimate - exact).abs() < 0.02 * exact + 2e-3, "{} against {}", estimate, exact);
        }
    }
}

#[test]
fn gathering_and_shooting_converge_to_each_other_as_patches_shrink() {
    // Shooting takes each factor at the shooter's centre, gathering at the
    // receiver's: two different point samplings of the same patch-to-patch
    // factors, which meet as the patches shrink (and the hemi-cube keeps up).
    let scene = closed_cube(0.5, [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    let mut differences = Vec::new();
    for (n, r) in [(2, 64), (4, 128), (8, 256)] {
        let mut s = settings(Solver::Shooting, FormFactorMethod::Hemicube, 1);
        s.patches = Division::Count(n);
        s.resolution = r;
        s.unshot = 1e-5;
        let shot = solve(&scene, &s, &mut |_, _| {}).unwrap();
        s.solver = Solver::Gathering;
        let gathered = solve(&scene, &s, &mut |_, _| {}).unwrap();
        let (mut d, mut t) = (0.0, 0.0);
        for ((a, b), e) in shot
            .elements
            .iter()
            .zip(&gathered.elements)
            .zip(&shot.mesh.elements)
        {
            d += (a.x - b.x).abs() as f64 * e.area;
            t += b.x as f64 * e.area;
        }
        differences.push(d / t);
    }
    eprintln!("{differences:?}");
    assert!(
        differences.windows(2).all(|w| w[1] < w[0]),
        "{differences:?}"
    );
}

// ---------------------------------------------------------------------------
// The furnace through the renderer, and enclosures of unequal patches
//
// These sit beside two known limits, which they do not loosen: shooting's
// patch-centre approximation leaves the furnace's elements along the cube's edges
// up to 2% off (the furnace test above), and on the Cornell box gathering and
// shooting differ by 0.87% (area-weighted L1) with 35 mm patches at hemi-cube
// resolution 512, because each samples the factors at a different
// patch's centre. The checks below are exact wherever the method is: analytic
// factors from a point inside a closed box sum to exactly one, so gathering
// holds the furnace to rounding and shooting conserves power to rounding. Where
// a large patch borders a small one across an edge, shooting's patch-centre error
// grows to 7.7% (measured below; the same with hemi-cube factors): a third limit,
// of the method, not loosened into the other tests.

/// `scene` solved once with `settings` and drawn by the renderer from each
/// (eye, look_at) inside the box with a 100° field of view: every pixel sees the
/// inside of some face, and the frames cross the edges and corners where faces meet.
fn rendered_from_inside(
    scene: &Scene,
    settings: &Settings,
    views: &[(DVec3, DVec3)],
) -> Vec<lumiere::Image> {
    let mut scene = scene.clone();
    scene.radiosity = Some(settings.clone());
    let mut renderer = Renderer::new(scene.clone());
    views
        .iter()
        .map(|&(eye, look_at)| {
            renderer.set_camera(Camera {
                eye,
                look_at,
                up: DVec3::Y,
                fov_y: 100.0,
                width: 40,
                height: 30,
                near: 0.01,
            });
            renderer.render().unwrap()
        })
        .collect()
}

/// The largest relative error of any pixel's three bands against `expected`.
fn worst_pixel(image: &lumiere::Image, expected: f64) -> f64 {
    image
        .pixels
        .iter()
        .flat_map(|p| p.to_array())
        .map(|v| relative(v as f64, expected))
        .fold(0.0, f64::max)
}

#[test]
fn the_rendered_furnace_shows_the_radiance_e_over_one_minus_rho_at_every_pixel() {
    // The furnace of `the_furnace_converges_...` drawn from inside: radiosity
    // E/(1 − ρ) is radiance E/(1 − ρ)/π = e/(1 − ρ) for the file's emitted radiance
    // e, the same at every pixel, on every face, across every edge.
    let (rho, e) = (0.5, 1.0);
    let scene = closed_cube(rho, [e; 6]);
    let radiance = e / (1.0 - rho);
    let mut analytic = settings(Solver::Gathering, FormFactorMethod::Analytic, 2);
    analytic.patches = Division::Count(2);
    let mut flat = analytic.clone();
    flat.display = Display::Flat;
    // The furnace test's own gathering settings (hemi-cube, resolution 128).
    let hemicube = settings(Solver::Gathering, FormFactorMethod::Hemicube, 4);
    // Its shooting settings: 8 × 8 patches per face, each its own element.
    let mut shooting = settings(Solver::Shooting, FormFactorMethod::Hemicube, 1);
    shooting.patches = Division::Count(8);
    shooting.unshot = 1e-4;
    // Measured worst pixels: analytic gathering 0 (Gouraud and flat: every pixel
    // exactly 2.0; the bound leaves f32 rounding), hemi-cube gathering 3.3e-5 (the
    // delta table's sum at resolution 128), shooting 1.8e-2 (its patch-centre limit
    // along the cube's edges, where the furnace test allows its elements 2%).
    let cases = [
        ("analytic gathering, Gouraud", analytic, 1e-6),
        ("analytic gathering, flat", flat, 1e-6),
        ("hemi-cube gathering", hemicube, 5e-5),
        ("hemi-cube shooting", shooting, 0.02),
    ];
    let views = [
        (DVec3::new(0.5, 0.5, 0.9), DVec3::new(0.5, 0.5, 0.0)),
        (DVec3::new(0.8, 0.7, 0.85), DVec3::new(0.1, 0.2, 0.0)),
    ];
    for (name, s, tolerance) in &cases {
        for (image, (eye, _)) in rendered_from_inside(&scene, s, &views).iter().zip(views) {
            assert_eq!(image.pixels.len(), 40 * 30);
            let worst = worst_pixel(image, radiance);
            eprintln!("{name} from {eye}: worst pixel {worst:.2e}");
            assert!(
                worst < *tolerance,
                "{name} from {eye}: a pixel {worst:e} from {radiance}"
            );
        }
    }
}

/// A 1.5 × 1 × 0.5 box: its faces have areas 0.75 (top, bottom), 0.5 (x = 0 and
/// x = 1.5) and 1.5 (z = 0 and z = 0.5), so cut n × n their patches differ in area
/// up to threefold, and shooting's reciprocity A_i/A_j matters.
const BOX: DVec3 = DVec3::new(1.5, 1.0, 0.5);

/// The axis each face of `closed_box` is normal to, in its order.
const FACE_AXIS: [usize; 6] = [1, 1, 0, 0, 2, 2];

/// The largest patch area over the smallest.
fn area_ratio(mesh: &Mesh) -> f64 {
    let areas = mesh.patches.iter().map(|p| p.area);
    areas.clone().fold(0.0, f64::max) / areas.fold(f64::INFINITY, f64::min)
}

/// The furnace of `closed_cube` (ρ, emitted radiance 1 everywhere) with its top
/// and its walls x = 0 and z = 0 each made of four square polygons: cut n × n like
/// the others, their patches have a quarter of the others' area, and the three meet
/// at a corner, so small patches border small and large ones along the edges.
fn tiled_furnace(rho: f64) -> Scene {
    let tiled = [true, false, true, false, true, false];
    let mut polygons = Vec::new();
    for (corners, tiled) in closed_box_faces(DVec3::ONE).into_iter().zip(tiled) {
        if !tiled {
            polygons.push((corners, rho, 1.0));
            continue;
        }
        let at = |u: f64, v: f64| {
            corners[0] * (1.0 - u) * (1.0 - v)
                + corners[1] * u * (1.0 - v)
                + corners[2] * u * v
                + corners[3] * (1.0 - u) * v
        };
        for (u, v) in [(0.0, 0.0), (0.5, 0.0), (0.5, 0.5), (0.0, 0.5)] {
            let quarter = vec![
                at(u, v),
                at(u + 0.5, v),
                at(u + 0.5, v + 0.5),
                at(u, v + 0.5),
            ];
            polygons.push((quarter, rho, 1.0));
        }
    }
    scene_of(&polygons)
}

#[test]
fn the_furnace_holds_in_a_cube_of_unequal_patches_with_both_solvers() {
    // Uniform E and ρ in any closed enclosure: B = E/(1 − ρ) exactly, whatever the
    // patches' areas (every row of the exact factors sums to one).
    let rho = 0.5;
    let scene = tiled_furnace(rho);
    let expected = PI / (1.0 - rho);
    // Gathering, 4 × 4 patches per polygon: every element's factors from its centre
    // sum to one (analytic: exactly; hemi-cube: the delta table's sum), so every
    // element holds the furnace. Measured worst element: analytic 2.8e-8 (2 × 2
    // elements per patch; rounding), hemi-cube 3.3e-5 (resolution 128).
    for (method, elements, tolerance) in [
        (FormFactorMethod::Analytic, 2, 1e-6),
        (FormFactorMethod::Hemicube, 1, 5e-5),
    ] {
        let mut s = settings(Solver::Gathering, method, elements);
        s.patches = Division::Count(4);
        let gathered = solve(&scene, &s, &mut |_, _| {}).unwrap();
        assert!(relative(area_ratio(&gathered.mesh), 4.0) < 1e-9);
        let worst = gathered
            .elements
            .iter()
            .map(|b| relative(b.x as f64, expected))
            .fold(0.0, f64::max);
        eprintln!("gathering {method:?}: worst element {worst:.2e}");
        assert!(worst < tolerance, "gathering {method:?}: {worst:e}");
    }
    // Shooting, the same patches each its own element, analytic factors (what
    // remains is the patch-centre approximation alone). Every shot hands on
    // exactly ρ times the power it sends, so the total is exact to the unshot
    // fraction. Each element is off by the approximation: across an edge between
    // a large and a small patch the small one, seen from the large one's distant
    // centre, gets too little and the large one too much (measured 7.7% at worst,
    // against 2% in the cube of equal patches; the method's limit, which does not
    // shrink as the patches do). Measured: total 5.7e-6, worst element 7.7e-2,
    // area-weighted mean error 1.6e-2.
    let mut s = settings(Solver::Shooting, FormFactorMethod::Analytic, 1);
    s.patches = Division::Count(4);
    s.unshot = 1e-5;
    let shot = solve(&scene, &s, &mut |_, _| {}).unwrap();
    let mesh = &shot.mesh;
    assert_eq!(mesh.patches.len(), mesh.elements.len());
    assert!(relative(area_ratio(mesh), 4.0) < 1e-9);
    let area: f64 = mesh.elements.iter().map(|e| e.area).sum();
    let (mut total, mut mean, mut worst) = (0.0, 0.0, 0.0f64);
    for (b, e) in shot.elements.iter().zip(&mesh.elements) {
        let error = relative(b.x as f64, expected);
        total += b.x as f64 * e.area;
        mean += error * e.area / area;
        worst = worst.max(error);
    }
    let total_error = relative(total, expected * area);
    eprintln!("shooting: total {total_error:.2e}, worst {worst:.2e}, mean {mean:.2e}");
    assert!(
        total_error < 2e-5,
        "shooting: total {total} off by {total_error:e}"
    );
    assert!(worst < 0.08, "shooting: worst element {worst:e}");
    assert!(mean < 0.02, "shooting: mean error {mean:e}");
}

/// The exact patch-to-patch factors between the faces of the box [0, size], in
/// `closed_box`'s order, from the closed forms: opposite faces are parallel
/// rectangles, adjacent ones perpendicular rectangles sharing an edge.
fn box_factors(size: DVec3) -> [[f64; 6]; 6] {
    let d = size.to_array();
    let mut f = [[0.0; 6]; 6];
    for (i, row) in f.iter_mut().enumerate() {
        for (j, f_ij) in row.iter_mut().enumerate() {
            let (k, m) = (FACE_AXIS[i], FACE_AXIS[j]);
            *f_ij = if i == j {
                0.0
            } else if k == m {
                let (u, v) = ((k + 1) % 3, (k + 2) % 3);
                parallel_rectangles(d[u], d[v], d[k])
            } else {
                // Face i spans axes m and t, face j axes k and t: they share the
                // edge along t.
                let t = 3 - k - m;
                perpendicular_rectangles(d[t], d[m], d[k])
            };
        }
    }
    f
}

/// The area of face `i` of the box [0, size].
fn face_area(size: DVec3, i: usize) -> f64 {
    let d = size.to_array();
    (0..3)
        .filter(|&k| k != FACE_AXIS[i])
        .map(|k| d[k])
        .product()
}

/// x solving m x = b, by Gaussian elimination with partial pivoting.
fn solve_dense<const N: usize>(mut m: [[f64; N]; N], mut b: [f64; N]) -> [f64; N] {
    for k in 0..N {
        let pivot = (k..N)
            .max_by(|&i, &j| m[i][k].abs().total_cmp(&m[j][k].abs()))
            .unwrap();
        m.swap(k, pivot);
        b.swap(k, pivot);
        for i in k + 1..N {
            let factor = m[i][k] / m[k][k];
            let row_k = m[k];
            for (x, y) in m[i].iter_mut().zip(row_k).skip(k) {
                *x -= factor * y;
            }
            b[i] -= factor * b[k];
        }
    }
    let mut x = [0.0; N];
    for k in (0..N).rev() {
        let known: f64 = (k + 1..N).map(|j| m[k][j] * x[j]).sum();
        x[k] = (b[k] - known) / m[k][k];
    }
    x
}

/// The exact one-patch-per-face solution of the box lit from its wall x = 0 (ρ = 0.5,
/// radiosity emission π): radiosity per face, and the areas.
fn box_lit_from_one_wall() -> ([f64; 6], [f64; 6]) {
    let (rho, e) = (0.5, PI);
    let f = box_factors(BOX);
    let mut m = [[0.0; 6]; 6];
    for (i, row) in m.iter_mut().enumerate() {
        for (j, m_ij) in row.iter_mut().enumerate() {
            *m_ij = f64::from(u8::from(i == j)) - rho * f[i][j];
        }
    }
    let mut emission = [0.0; 6];
    emission[2] = e;
    let areas = std::array::from_fn(|i| face_area(BOX, i));
    (solve_dense(m, emission), areas)
}

#[test]
fn the_box_of_unequal_faces_lit_from_one_wall_matches_its_exact_solution() {
    // The closed forms in the box: reciprocal, and rows summing to one.
    let f = box_factors(BOX);
    for (i, row) in f.iter().enumerate() {
        let sum: f64 = row.iter().sum();
        assert!((sum - 1.0).abs() < 1e-12, "row {i} sums to {sum}");
        for (j, f_ij) in row.iter().enumerate() {
            let (a, b) = (face_area(BOX, i) * f_ij, face_area(BOX, j) * f[j][i]);
            assert!(
                (a - b).abs() < 1e-12,
                "A{i} F{i}{j} = {a}, A{j} F{j}{i} = {b}"
            );
        }
    }
    let (exact, areas) = box_lit_from_one_wall();
    // Not uniform: the lit wall, the wall facing it, the four others in two pairs.
    assert!(exact[2] > exact[3] && exact[0] != exact[4] && exact[3] > 0.0);
    assert!(relative(exact[0], exact[1]) < 1e-12 && relative(exact[4], exact[5]) < 1e-12);
    // Σ A B = Σ A E/(1 − ρ).
    let total: f64 = exact.iter().zip(areas).map(|(b, a)| b * a).sum();
    assert!(relative(total, areas[2] * PI / 0.5) < 1e-12);

    // Gathering, one patch per face: the patch factors averaged over m × m
    // elements approach the exact ones, and the radiosities with them. Measured
    // worst patch: 4.2e-3 with 16 × 16 elements, 1.2e-3 with 32 × 32.
    let scene = closed_box(BOX, 0.5, [0.0, 0.0, 1.0, 0.0, 0.0, 0.0]);
    let estimator = Estimator::new(FormFactorMethod::Analytic, 1, &scene);
    let errors: Vec<f64> = [16, 32]
        .into_iter()
        .map(|m| {
            let mesh = Mesh::build(&scene, Division::Whole, Division::Count(m)).unwrap();
            let g = gather(&mesh, &estimator, 1e-12, 1 << 30).unwrap();
            g.patches
                .iter()
                .zip(exact)
                .map(|(p, want)| relative(p.x, want))
                .fold(0.0, f64::max)
        })
        .collect();
    eprintln!("gathering: worst patch {errors:?} against {exact:?}");
    assert!(errors[1] < 1.5e-3, "gathering: {errors:?}");
    assert!(errors[1] < errors[0] / 3.0, "gathering: {errors:?}");
}

#[test]
fn shooting_in_a_box_of_unequal_patches_keeps_its_power_and_reaches_its_own_fixed_point() {
    // The box lit from one wall, 3 × 3 patches per face of 2 × 2 elements, analytic
    // factors (every shooter's factors sum to exactly one in the closed box).
    let rho = 0.5;
    let scene = closed_box(BOX, rho, [0.0, 0.0, 1.0, 0.0, 0.0, 0.0]);
    let mesh = Mesh::build(&scene, Division::Count(3), Division::Count(2)).unwrap();
    assert!(relative(area_ratio(&mesh), 3.0) < 1e-9);
    let estimator = Estimator::new(FormFactorMethod::Analytic, 1, &scene);
    let converged = mesh.emitted_power().x as f64 / (1.0 - rho);
    let total = |b: &[Vec3]| -> f64 {
        b.iter()
            .zip(&mesh.elements)
            .map(|(b, e)| b.x as f64 * e.area)
            .sum()
    };
    // Each shot hands element e of patch j the radiosity ρ ΔB_i F_ie A_i/A_e, so
    // the power it sends, ΔB_i A_i, arrives whole times ρ: the displayed total with
    // the ambient term, Σ A B + ρ/(1 − ρ) Σ A ΔB, is Σ A E/(1 − ρ) at every step.
    // Measured: 7.7e-7 at worst (rounding in f32).
    let mut state = Shooting::start(&mesh);
    let mut worst = 0.0f64;
    let stop = Stop {
        unshot: 1e-7,
        max_steps: 100_000,
    };
    state.run(&mesh, &estimator, stop, &mut |s| {
        worst = worst.max(relative(total(&s.displayed(&mesh, true)), converged));
    });
    eprintln!(
        "shooting: {} steps, worst displayed total {worst:.2e}",
        state.steps
    );
    assert!(state.steps > 100);
    assert!(worst < 2e-6, "displayed total off by {worst:e}");

    // Converged, shooting solves B_e = E_e + ρ Σ_j F_je (A_j/A_e) B_j, with F_je the
    // factor from patch j's centre to element e and B_j the area-weighted mean of
    // j's elements: patch by patch, F'_ij = (A_j/A_i) Σ_{e in i} F_je, then one
    // gathering step to the elements. Solved here by Gauss–Seidel on F'.
    let receivers = Receivers::elements(&mesh);
    let n = mesh.patches.len();
    let mut to_elements = vec![vec![0.0; mesh.elements.len()]; n];
    for (j, p) in mesh.patches.iter().enumerate() {
        to_elements[j] =
            estimator.factors(p.centre, p.normal, &receivers, &|e| receivers.patch[e] == j);
    }
    let mut reciprocal = vec![vec![0.0; n]; n];
    for (i, p) in mesh.patches.iter().enumerate() {
        for (j, q) in mesh.patches.iter().enumerate() {
            let seen: f64 = p.elements.clone().map(|e| to_elements[j][e]).sum();
            reciprocal[i][j] = seen * q.area / p.area;
        }
    }
    let emission: Vec<f64> = mesh.patches.iter().map(|p| p.emission.x as f64).collect();
    let reflectance = vec![rho; n];
    let (patches, _) = gauss_seidel(&reciprocal, &emission, &reflectance, 1e-12);
    let mut worst = 0.0f64;
    for (e, (b, element)) in state.elements.iter().zip(&mesh.elements).enumerate() {
        let gathered: f64 = (0..n)
            .map(|j| to_elements[j][e] * mesh.patches[j].area / element.area * patches[j])
            .sum();
        let want = emission[element.patch] + rho * gathered;
        worst = worst.max(relative(b.x as f64, want));
    }
    // Measured: 2.4e-6, the unshot remainder (1e-7 of the power) and f32 rounding.
    eprintln!("shooting against its fixed point: worst element {worst:.2e}");
    assert!(
        worst < 5e-6,
        "shooting against its own fixed point: {worst:e}"
    );
    let without = total(&state.displayed(&mesh, false));
    assert!(relative(without, converged) < 1e-6);
}

/// `max_steps` is the number of shots taken, no more: stopped by it, shooting has
/// taken exactly that many steps, each observed once, and it can be resumed.
#[test]
fn shooting_stops_after_exactly_max_steps() {
    let scene = closed_cube(0.5, [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    let mesh = Mesh::build(&scene, Division::Count(2), Division::Count(2)).unwrap();
    let estimator = Estimator::new(FormFactorMethod::Hemicube, 32, &scene);
    let mut state = Shooting::start(&mesh);
    let mut observed = 0;
    let stop = |max_steps| Stop {
        unshot: 0.0,
        max_steps,
    };
    state.run(&mesh, &estimator, stop(5), &mut |_| observed += 1);
    assert_eq!((state.steps, observed), (5, 5));
    state.run(&mesh, &estimator, stop(7), &mut |_| observed += 1);
    assert_eq!((state.steps, observed), (7, 7));
}

/// Gathering keeps each element's direct part, ρ Σ_j F_ej E_j over the emitters, for
/// a second pass that draws the direct light itself: in a cube of reflectance 0.5
/// lit by its top face (radiance 1, radiosity π), every element's direct part is
/// 0.5 π F with F Lambert's point-to-polygon factor from its centre to the top face
/// (the hemi-cube's estimate at 256: within 1%).
#[test]
fn gathering_keeps_the_direct_part_of_each_element() {
    let scene = closed_cube(0.5, [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    let mut s = settings(Solver::Gathering, FormFactorMethod::Hemicube, 2);
    s.resolution = 256;
    let solution = solve(&scene, &s, &mut |_, _| {}).unwrap();
    let direct = solution
        .direct
        .as_ref()
        .expect("gathering keeps the direct part");
    let top: Vec<DVec3> = closed_box_faces(DVec3::ONE)[0].clone();
    let mut lit = 0;
    for (e, d) in solution.mesh.elements.iter().zip(direct) {
        let normal = solution.mesh.patches[e.patch].normal;
        // The lamp's own elements get nothing from it (Lambert's formula is not
        // meant for points in the polygon's plane).
        let on_lamp = (e.centre.y - 1.0).abs() < 1e-12;
        let expected = if on_lamp {
            0.0
        } else {
            0.5 * PI * form_factor(e.centre, normal, &top)
        };
        let found = d.x as f64;
        assert!(
            (found - expected).abs() <= 0.01 * expected + 1e-9,
            "element at {}: {found} against {expected}",
            e.centre
        );
        lit += usize::from(expected > 0.0);
    }
    assert_eq!(lit, 20, "the five faces below the lamp, four elements each");
}

/// Counted on the disc, the Nusselt analog hands every cell inside it to exactly one
/// wall of a closed box: from a point of its floor the factors sum to 1 to
/// rounding, at any resolution (each is cells over cells inside the disc). (The
/// point is chosen so that no cell's ray runs exactly into an edge of the box: such
/// a ray meets neither wall and its cell is lost, 1 in 37 from the middle of the
/// floor at resolution 7.)
#[test]
fn the_nusselt_counts_from_inside_a_closed_box_sum_to_one() {
    use lumiere::radiosity::nusselt::Nusselt;
    let scene = closed_cube(0.5, [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    let mesh = Mesh::build(&scene, Division::Whole, Division::Whole).unwrap();
    let receivers = Receivers::patches(&mesh);
    let floor = (0..mesh.patches.len())
        .find(|&p| mesh.patches[p].normal == DVec3::Y)
        .unwrap();
    for resolution in [7, 32, 101] {
        let factors = Nusselt { resolution }.factors(
            DVec3::new(0.3719, 0.0, 0.6133),
            DVec3::Y,
            &receivers,
            &|r| r == floor,
        );
        let sum: f64 = factors.iter().sum();
        assert!((sum - 1.0).abs() < 1e-12, "resolution {resolution}: {sum}");
    }
}
