//! Analytic validation of the contact solver: Hertz, Westergaard, the elastic and fully
//! plastic limits, load balance, pixel-wise optimality, converged contact maps, and the PSD of
//! generated surfaces. Small grids so that CI on two cores stays fast.

use std::f64::consts::PI;

use wearsim::surface::pair_seeds;
use wearsim::{
    composite_heights, Boundary, ContactSolver, Error, Generation, SolverOptions, SpectrumParams, Surface, Termination,
};

const E_STAR: f64 = 1.0 / (1.0 - 0.09); // E = 1, ν = 0.3

fn paper_pair(n: usize, seed: u64) -> Vec<f64> {
    let spectrum = SpectrumParams::paper_roughness(n, 1.0);
    let (a, b) = pair_seeds(seed);
    let top = Surface::generate(wearsim::Grid::square(n, 1.0).unwrap(), &spectrum, a).unwrap();
    let bottom = Surface::generate(wearsim::Grid::square(n, 1.0).unwrap(), &spectrum, b).unwrap();
    let mut h = vec![0.0; n * n];
    composite_heights(&top, &bottom, 0, &mut h);
    h
}

fn flow_pressure(shear_strength: f64) -> f64 {
    3.0 * 3f64.sqrt() * shear_strength
}

#[test]
fn hertz_sphere_on_flat() {
    // Paraboloid of radius R on a flat half-space; contact radius a = 0.08 L (41 px).
    let n = 512;
    let radius = 1.0;
    let a_hertz: f64 = 0.08;
    let force = 4.0 * a_hertz.powi(3) * E_STAR / (3.0 * radius);
    let p0 = 3.0 * force / (2.0 * PI * a_hertz * a_hertz);
    let dx = 1.0 / n as f64;
    let h: Vec<f64> = (0..n * n)
        .map(|k| {
            let (x, y) = (
                ((k / n) as f64 - n as f64 / 2.0) * dx,
                ((k % n) as f64 - n as f64 / 2.0) * dx,
            );
            -(x * x + y * y) / (2.0 * radius)
        })
        .collect();
    let mut solver = ContactSolver::new(wearsim::Grid::square(n, 1.0).unwrap(), E_STAR).unwrap();
    let mut p = vec![0.0; n * n];
    let info = solver.solve(&h, force, f64::INFINITY, &mut p).unwrap();
    let a_num = (info.contact_pixels as f64 * dx * dx / PI).sqrt();
    let p_max = p.iter().copied().fold(0.0, f64::max);
    assert!(
        (a_num / a_hertz - 1.0).abs() < 0.015,
        "contact radius {a_num} vs Hertz {a_hertz}"
    );
    assert!((p_max / p0 - 1.0).abs() < 0.015, "peak pressure {p_max} vs Hertz {p0}");
    // Hertz profile p0 √(1 − r²/a²) at half the radius.
    let c = n / 2;
    let k = c * n + c + (a_hertz / 2.0 / dx) as usize;
    let r = (a_hertz / 2.0 / dx).floor() * dx;
    let expected = p0 * (1.0 - r * r / (a_hertz * a_hertz)).sqrt();
    assert!((p[k] / expected - 1.0).abs() < 0.02, "p(a/2) {} vs {expected}", p[k]);
}

/// A paraboloid of radius R pressed into a half-space with a free boundary: the map is the whole
/// surface, no periodic image of the contact pushes back, and Hertz holds to the pixel size.
#[test]
fn hertz_sphere_on_a_free_boundary_half_space() {
    let n = 128;
    let radius = 1.0;
    let a_hertz: f64 = 0.25; // 32 px, half the map across
    let force = 4.0 * a_hertz.powi(3) * E_STAR / (3.0 * radius);
    let p0 = 3.0 * force / (2.0 * PI * a_hertz * a_hertz);
    let dx = 1.0 / n as f64;
    let h: Vec<f64> = (0..n * n)
        .map(|k| {
            let (x, y) = (
                ((k / n) as f64 - n as f64 / 2.0) * dx,
                ((k % n) as f64 - n as f64 / 2.0) * dx,
            );
            -(x * x + y * y) / (2.0 * radius)
        })
        .collect();
    let grid = wearsim::Grid::square(n, 1.0).unwrap();
    let mut solver = ContactSolver::with_boundary(grid, E_STAR, Boundary::Free).unwrap();
    let mut p = vec![0.0; n * n];
    let info = solver.solve(&h, force, f64::INFINITY, &mut p).unwrap();
    let a_num = (info.contact_pixels as f64 * dx * dx / PI).sqrt();
    let p_max = p.iter().copied().fold(0.0, f64::max);
    assert!(
        (a_num / a_hertz - 1.0).abs() < 0.01,
        "contact radius {a_num} vs Hertz {a_hertz}"
    );
    assert!((p_max / p0 - 1.0).abs() < 0.005, "peak pressure {p_max} vs Hertz {p0}");
    // Hertz's approach δ = a²/R: the rigid body's position relative to the undeformed surface far away.
    let delta = a_hertz * a_hertz / radius;
    assert!(
        (info.approach / delta - 1.0).abs() < 0.005,
        "approach {} vs Hertz {delta}",
        info.approach
    );
    // The same problem on the periodic half-space of the same box is visibly off: the images of
    // the contact, one diameter apart, raise the peak pressure by about 2 %.
    let mut periodic = ContactSolver::new(grid, E_STAR).unwrap();
    let mut q = vec![0.0; n * n];
    periodic.solve(&h, force, f64::INFINITY, &mut q).unwrap();
    let p_max_periodic = q.iter().copied().fold(0.0, f64::max);
    assert!(
        p_max_periodic / p0 - 1.0 > 0.015,
        "periodic peak {p_max_periodic} vs Hertz {p0}"
    );
}

#[test]
fn westergaard_sinusoid_in_full_contact() {
    let n = 64;
    let g0 = 0.01;
    let h: Vec<f64> = (0..n * n)
        .map(|k| g0 * (2.0 * PI * (k / n) as f64 / n as f64).cos())
        .collect();
    let p_star = PI * E_STAR * g0 / 1.0; // full-contact pressure amplitude, π E* g / λ
    let mean = 2.0 * p_star;
    let mut solver = ContactSolver::new(wearsim::Grid::square(n, 1.0).unwrap(), E_STAR)
        .unwrap()
        .with_options(SolverOptions::new(1e-12, 20_000).unwrap());
    let mut p = vec![0.0; n * n];
    solver.solve(&h, mean, f64::INFINITY, &mut p).unwrap();
    for (k, &pk) in p.iter().enumerate() {
        let exact = mean + p_star * (2.0 * PI * (k / n) as f64 / n as f64).cos();
        assert!((pk - exact).abs() < 1e-9 * p_star, "pixel {k}: {pk} vs {exact}");
    }
}

#[test]
fn large_flow_pressure_reproduces_the_elastic_solution() {
    let n = 128;
    let h = paper_pair(n, 2);
    let mut solver = ContactSolver::new(wearsim::Grid::square(n, 1.0).unwrap(), E_STAR).unwrap();
    let mut elastic = vec![0.0; n * n];
    solver.solve(&h, 1e-3, f64::INFINITY, &mut elastic).unwrap();
    let p_max = elastic.iter().copied().fold(0.0, f64::max);
    let mut bounded = vec![0.0; n * n];
    let info = solver.solve(&h, 1e-3, 10.0 * p_max, &mut bounded).unwrap();
    assert_eq!(info.plastic_pixels, 0);
    for (a, b) in elastic.iter().zip(&bounded) {
        assert_eq!(*a > 0.0, *b > 0.0, "contact maps differ");
        assert!((a - b).abs() < 1e-6 * p_max);
    }
}

#[test]
fn small_flow_pressure_tends_to_the_fully_plastic_limit() {
    let n = 128;
    let h = paper_pair(n, 3);
    let load = 1e-3;
    let mut solver = ContactSolver::new(wearsim::Grid::square(n, 1.0).unwrap(), E_STAR).unwrap();
    let mut previous_gap = f64::INFINITY;
    for shear_strength in [0.01, 0.003, 0.001] {
        let pm = flow_pressure(shear_strength);
        let mut p = vec![0.0; n * n];
        let info = solver.solve(&h, load, pm, &mut p).unwrap();
        let area = info.contact_pixels as f64 / (n * n) as f64;
        let limit = load / pm;
        let gap = area / limit - 1.0;
        assert!(gap >= 0.0, "area below the plastic limit");
        assert!(
            gap < previous_gap,
            "area does not approach F/p_m: {gap} after {previous_gap}"
        );
        previous_gap = gap;
    }
    assert!(previous_gap < 0.05, "area/(F/p_m) − 1 = {previous_gap}");
}

#[test]
fn load_balance_and_optimality_hold_pixel_by_pixel_on_the_gap_of_both_boundaries() {
    let n = 128;
    let h = paper_pair(n, 4);
    let pm = flow_pressure(0.01);
    let load = 2e-3;
    let h_mean = h.iter().sum::<f64>() / (n * n) as f64;
    let h_std = (h.iter().map(|x| (x - h_mean).powi(2)).sum::<f64>() / (n * n) as f64).sqrt();
    let h_max = h.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    for boundary in [Boundary::Periodic, Boundary::Free] {
        let mut solver =
            ContactSolver::with_boundary(wearsim::Grid::square(n, 1.0).unwrap(), E_STAR, boundary).unwrap();
        let mut p = vec![0.0; n * n];
        let info = solver.solve(&h, load, pm, &mut p).unwrap();
        let mean: f64 = p.iter().sum::<f64>() / (n * n) as f64;
        assert!((mean / load - 1.0).abs() < 1e-13, "mean pressure {mean}");
        assert!(info.plastic_pixels > 0 && info.contact_pixels > info.plastic_pixels);
        let fields = solver.gap_and_displacement(&h, &p, &info).unwrap();
        // The displacement is 𝒦p recomputed, and the gap is 𝒦p − h + (max h − approach).
        let mut u = vec![0.0; n * n];
        solver.apply_influence(&p, &mut u);
        assert_eq!(fields.displacement, u);
        let bound = 1.0001 * info.tolerance * h_std;
        for k in 0..n * n {
            let gap = fields.gap[k];
            assert!((gap - (u[k] - h[k] + h_max - info.approach)).abs() <= 1e-12 * h_std);
            assert!(p[k] >= 0.0 && p[k] <= pm);
            if p[k] == 0.0 {
                assert!(
                    gap >= -bound,
                    "{boundary:?} pixel {k}: non-contact pixel penetrates by {gap}"
                );
            } else if p[k] < pm {
                assert!(gap.abs() <= bound, "{boundary:?} pixel {k}: free pixel with gap {gap}");
            } else {
                assert!(
                    gap <= bound,
                    "{boundary:?} pixel {k}: plastic pixel with open gap {gap}"
                );
            }
        }
        // Not a vacuous check: the plastic pixels interpenetrate by more than the tolerance.
        let deepest = (0..n * n)
            .filter(|&k| p[k] >= pm)
            .map(|k| fields.gap[k])
            .fold(0.0, f64::min);
        assert!(deepest < -100.0 * bound, "{boundary:?}: deepest plastic gap {deepest}");
    }
}

#[test]
fn default_tolerance_gives_converged_contact_maps() {
    let n = 256;
    let h = paper_pair(n, 5);
    let pm = flow_pressure(0.01);
    for load in [2.5e-4, 1e-3, 2.5e-3] {
        let mut solver = ContactSolver::new(wearsim::Grid::square(n, 1.0).unwrap(), E_STAR).unwrap();
        let mut p = vec![0.0; n * n];
        solver.solve(&h, load, pm, &mut p).unwrap();
        let tighter = SolverOptions::new(solver.options().tolerance() / 100.0, 20_000).unwrap();
        let mut solver = solver.with_options(tighter);
        let mut tight = vec![0.0; n * n];
        solver.solve(&h, load, pm, &mut tight).unwrap();
        let changed = p.iter().zip(&tight).filter(|(a, b)| (**a > 0.0) != (**b > 0.0)).count();
        assert_eq!(
            changed, 0,
            "load {load}: {changed} contact pixels change with a 100× tighter tolerance"
        );
    }
}

#[test]
fn warm_start_after_a_slide_converges_to_the_cold_solution() {
    let n = 128;
    let dx = 1.0 / n as f64;
    let spectrum = SpectrumParams {
        hurst: 0.7,
        lambda_lower: 16.0 * dx,
        lambda_upper: 0.5,
        rms_height: 0.005,
        generation: Generation::RandomPhase,
    };
    let top = Surface::generate(wearsim::Grid::square(n, 1.0).unwrap(), &spectrum, 11).unwrap();
    let bottom = Surface::generate(wearsim::Grid::square(n, 1.0).unwrap(), &spectrum, 12).unwrap();
    let pm = flow_pressure(0.01);
    let mut solver = ContactSolver::new(wearsim::Grid::square(n, 1.0).unwrap(), E_STAR).unwrap();
    let mut h = vec![0.0; n * n];
    composite_heights(&top, &bottom, 0, &mut h);
    let mut warm = vec![0.0; n * n];
    solver.solve(&h, 1e-3, pm, &mut warm).unwrap();
    composite_heights(&top, &bottom, 1, &mut h);
    solver.solve(&h, 1e-3, pm, &mut warm).unwrap();
    let mut cold = vec![0.0; n * n];
    solver.solve(&h, 1e-3, pm, &mut cold).unwrap();
    for (a, b) in warm.iter().zip(&cold) {
        assert_eq!(*a > 0.0, *b > 0.0);
        assert!((a - b).abs() < 1e-5 * pm);
    }
}

#[test]
fn fields_kept_in_the_solver_give_the_solution_of_fields_passed_in_bit_for_bit() {
    // A sliding run composes the heights where the solver's fields live and warm-starts from the
    // solver's own pressure; `solve` copies heights and pressure in and out. Same algorithm, same bits.
    let n = 64;
    let grid = wearsim::Grid::square(n, 1.0).unwrap();
    let spectrum = SpectrumParams::paper_roughness(n, 1.0);
    let top = Surface::generate(grid, &spectrum, 21).unwrap();
    let bottom = Surface::generate(grid, &spectrum, 22).unwrap();
    let pm = flow_pressure(0.01);
    let mut kept = ContactSolver::on_device(wearsim::Device::Cpu, grid, E_STAR, Boundary::Periodic).unwrap();
    let mut passed = ContactSolver::new(grid, E_STAR).unwrap();
    let (mut h, mut p) = (vec![0.0; n * n], vec![0.0; n * n]);
    // Composing before any surfaces are bound is an error, not a solve of stale heights.
    let e = kept.compose(0).unwrap_err().to_string();
    assert!(e.contains("bind"), "{e}");
    kept.bind_surfaces(std::sync::Arc::new(top.clone()), std::sync::Arc::new(bottom.clone()))
        .unwrap();
    for offset in 0..3 {
        kept.compose(offset).unwrap();
        let a = kept.solve_in_place(1e-3, pm).unwrap();
        composite_heights(&top, &bottom, offset, &mut h);
        let b = passed.solve(&h, 1e-3, pm, &mut p).unwrap();
        // The kept fields save one convolution per warm step: the displacement of the last solve.
        let saved = if offset > 0 { 1 } else { 0 };
        assert_eq!(a.convolutions + saved, b.convolutions, "offset {offset}");
        let but_convolutions = |i: wearsim::SolveInfo| wearsim::SolveInfo { convolutions: 0, ..i };
        assert_eq!(but_convolutions(a), but_convolutions(b));
        assert_eq!(kept.pressure(), &p[..]);
        let map = kept.contact_map();
        assert!((0..n * n).all(|k| map.contains(k) == (p[k] > 0.0)));
    }
    // A cold start set from outside equals a fresh solve.
    kept.set_pressure(|p| p.fill(0.0));
    let a = kept.solve_in_place(1e-3, pm).unwrap();
    let b = passed.solve(&h, 1e-3, pm, &mut vec![0.0; n * n]).unwrap();
    assert_eq!(a, b);
    // Surfaces of another grid are refused.
    let mut other = ContactSolver::new(wearsim::Grid::square(32, 1.0).unwrap(), E_STAR).unwrap();
    let e = other
        .bind_surfaces(std::sync::Arc::new(top), std::sync::Arc::new(bottom))
        .unwrap_err()
        .to_string();
    assert!(e.contains("32×32"), "{e}");
}

#[test]
fn a_device_this_build_cannot_compute_on_is_refused_with_the_fix() {
    let grid = wearsim::Grid::square(32, 1.0).unwrap();
    let e = ContactSolver::on_device(wearsim::Device::Cuda, grid, E_STAR, Boundary::Periodic)
        .err()
        .expect("no GPU backend in this build")
        .to_string();
    assert!(e.contains("device") && e.contains("\"cpu\""), "{e}");
    let e = "gpu".parse::<wearsim::Device>().unwrap_err().to_string();
    assert!(e.contains("device") && e.contains("cpu"), "{e}");
    assert_eq!("cuda".parse::<wearsim::Device>().unwrap(), wearsim::Device::Cuda);
}

#[test]
fn solution_does_not_depend_on_thread_count() {
    let n = 128;
    let h = paper_pair(n, 6);
    let solve = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| {
                let mut solver = ContactSolver::new(wearsim::Grid::square(n, 1.0).unwrap(), E_STAR).unwrap();
                let mut p = vec![0.0; n * n];
                let info = solver.solve(&h, 1e-3, flow_pressure(0.01), &mut p).unwrap();
                (p, info.iterations)
            })
    };
    assert_eq!(solve(1), solve(2));
}

#[test]
fn infeasible_load_and_non_convergence_are_errors() {
    let n = 64;
    let h = paper_pair(n, 7);
    let pm = flow_pressure(0.01);
    let mut solver = ContactSolver::new(wearsim::Grid::square(n, 1.0).unwrap(), E_STAR).unwrap();
    let mut p = vec![0.0; n * n];
    assert!(matches!(
        solver.solve(&h, pm, pm, &mut p),
        Err(Error::InfeasibleLoad { .. })
    ));
    let mut solver = solver.with_options(SolverOptions::new(1e-14, 1).unwrap());
    let e = solver.solve(&h, 1e-3, pm, &mut vec![0.0; n * n]).unwrap_err();
    assert!(matches!(e, Error::NotConverged { iterations: 1, .. }), "{e}");
    // `run` returns the state at the limit instead, with the reason.
    let info = solver.run(&h, 1e-3, pm, &mut vec![0.0; n * n]).unwrap();
    assert_eq!((info.termination, info.iterations), (Termination::MaxIterations, 1));
}

#[test]
fn a_raised_interrupt_stops_the_solve_and_a_fresh_one_does_not() {
    let n = 64;
    let h = paper_pair(n, 7);
    let pm = flow_pressure(0.01);
    let flag = wearsim::Interrupt::default();
    let mut solver = ContactSolver::new(wearsim::Grid::square(n, 1.0).unwrap(), E_STAR)
        .unwrap()
        .with_interrupt(flag.clone());
    flag.request();
    let e = solver.solve(&h, 1e-3, pm, &mut vec![0.0; n * n]).unwrap_err();
    assert!(matches!(e, Error::Interrupted), "{e}");
    solver.set_interrupt(wearsim::Interrupt::default());
    assert!(solver.solve(&h, 1e-3, pm, &mut vec![0.0; n * n]).is_ok());
}

#[test]
fn generated_psd_follows_the_self_affine_power_law() {
    let n = 256;
    let hurst = 0.7;
    for (generation, slack) in [(Generation::RandomPhase, 0.05), (Generation::FilteredNoise, 0.25)] {
        let spectrum = SpectrumParams {
            hurst,
            lambda_lower: 4.0 / n as f64,
            lambda_upper: 1.0 / 4.0,
            rms_height: 0.005,
            generation,
        };
        let s = Surface::generate(wearsim::Grid::square(n, 1.0).unwrap(), &spectrum, 9).unwrap();
        // Least-squares slope of log C(q) against log q inside the band (q from 6 to 60).
        let pts: Vec<(f64, f64)> = s
            .radial_psd()
            .into_iter()
            .filter(|(q, _)| *q >= 6.0 && *q <= 60.0)
            .map(|(q, c)| (q.ln(), c.ln()))
            .collect();
        let m = pts.len() as f64;
        let (sx, sy) = pts.iter().fold((0.0, 0.0), |(a, b), (x, y)| (a + x, b + y));
        let (mx, my) = (sx / m, sy / m);
        let slope = pts.iter().map(|(x, y)| (x - mx) * (y - my)).sum::<f64>()
            / pts.iter().map(|(x, _)| (x - mx) * (x - mx)).sum::<f64>();
        let expected = -2.0 * (1.0 + hurst);
        assert!(
            (slope - expected).abs() < slack,
            "{generation:?}: slope {slope} vs {expected}"
        );
    }
}
