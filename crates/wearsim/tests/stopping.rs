//! The settled-map stopping rule of sliding solves (`contact` module documentation): a solve that
//! stops once its contact map is settled must leave the map {p > 0} of the solve to the default
//! tolerance, pixel for pixel, at every offset of a slide, and so a sliding run must give the same
//! wear results with fewer iterations.

use std::sync::Arc;

use wearsim::config::{RunConfig, SurfacePair, SurfaceSource, Units};
use wearsim::run::SlidingRun;
use wearsim::sliding::SlidingConfig;
use wearsim::surface::pair_seeds;
use wearsim::{
    ContactSolver, Grid, Material, ModulusConvention, SolverOptions, SpectrumParams, Stopping, Surface, Termination,
};

const E_STAR: f64 = 1.0 / (1.0 - 0.3 * 0.3);

/// The paper's roughness (λ_l = 16 px, h_rms = 0.005 L) on an n² grid of side 1.
fn pair(n: usize, seed: u64) -> (Surface, Surface) {
    let grid = Grid::square(n, 1.0).unwrap();
    let spectrum = SpectrumParams::paper_roughness(n, 1.0);
    let (a, b) = pair_seeds(seed);
    (
        Surface::generate(grid, &spectrum, a).unwrap(),
        Surface::generate(grid, &spectrum, b).unwrap(),
    )
}

/// Slides `top` over `bottom` one pixel at a time for `offsets` steps, each solve warm-started from
/// the previous one as in a sliding run, with two solvers: one to the default tolerance, one that
/// stops at a settled map. Returns (offsets whose maps differ, iterations of each, settled solves).
fn slide_both(
    top: &Surface,
    bottom: &Surface,
    mean_pressure: f64,
    pm: f64,
    offsets: usize,
) -> (Vec<String>, [usize; 2], usize) {
    let grid = top.grid();
    let tight = SolverOptions::default();
    let mut solvers = [
        ContactSolver::new(grid, E_STAR).unwrap().with_options(tight),
        ContactSolver::new(grid, E_STAR)
            .unwrap()
            .with_options(tight.with_stopping(Stopping::SettledMap)),
    ];
    for solver in &mut solvers {
        solver
            .bind_surfaces(Arc::new(top.clone()), Arc::new(bottom.clone()))
            .unwrap();
    }
    let (mut differ, mut iterations, mut settled) = (Vec::new(), [0, 0], 0);
    for offset in 0..offsets {
        let mut infos = Vec::new();
        for solver in &mut solvers {
            solver.compose(offset).unwrap();
            infos.push(solver.solve_in_place(mean_pressure, pm).unwrap());
        }
        for (i, info) in infos.iter().enumerate() {
            iterations[i] += info.iterations;
        }
        assert_eq!(infos[0].termination, Termination::Converged);
        settled += usize::from(infos[1].termination == Termination::Settled);
        let reference: Vec<bool> = solvers[0].pressure().iter().map(|&p| p > 0.0).collect();
        let flipped = solvers[1]
            .pressure()
            .iter()
            .zip(&reference)
            .filter(|(&p, &r)| (p > 0.0) != r)
            .count();
        if flipped > 0 {
            differ.push(format!(
                "offset {offset}: {flipped} px (residual {:.2e} after {} iterations)",
                infos[1].residual, infos[1].iterations
            ));
        }
    }
    (differ, iterations, settled)
}

#[test]
fn a_settled_map_is_the_tight_map_at_every_offset() {
    let pm = 3.0 * 3f64.sqrt() * 0.010;
    let mut wrong = Vec::new();
    let (mut all, mut settled, mut iterations) = (0, 0, [0, 0]);
    for (n, seeds) in [(64, [1, 2, 3]), (128, [4, 5, 6])] {
        for seed in seeds {
            let (top, bottom) = pair(n, seed);
            // Nominal pressures from a few isolated spots to a contact near a quarter of the box.
            for mean_pressure in [2.5e-4, 1e-3, 4e-3] {
                let (differ, its, s) = slide_both(&top, &bottom, mean_pressure, pm, n / 2);
                wrong.extend(
                    differ
                        .into_iter()
                        .map(|d| format!("{n}², seed {seed}, p {mean_pressure}: {d}")),
                );
                all += n / 2;
                settled += s;
                iterations[0] += its[0];
                iterations[1] += its[1];
            }
        }
    }
    println!(
        "{settled} of {all} solves settled; iterations {} settled, {} tight",
        iterations[1], iterations[0]
    );
    assert!(
        wrong.is_empty(),
        "settled maps that are not the tight map:\n{}",
        wrong.join("\n")
    );
    // Not a vacuous comparison: most solves stopped early, on far fewer iterations.
    assert!(
        settled * 2 > all,
        "only {settled} of {all} solves stopped at a settled map"
    );
    let ratio = iterations[1] as f64 / iterations[0] as f64;
    assert!(
        ratio < 0.85,
        "settled-map solves took {ratio:.2} of the iterations of tight ones"
    );
}

#[test]
fn a_sliding_run_gives_the_same_wear_results_with_either_rule() {
    let n = 128;
    let (top, bottom) = pair(n, 7);
    let material = Material::new(1.0, 0.3, 0.010, vec![0.25e-6, 0.5e-6], 3.0).unwrap();
    let sliding = SlidingConfig::new(vec![1e-3, 3e-3], 0.5, 0.25, 4, 1, Some(n)).unwrap();
    let run = |stopping| {
        let config = RunConfig::builder(
            SurfaceSource::Arrays {
                grid: top.grid(),
                length: top.length(),
            },
            material.clone(),
        )
        .units(Units::Reduced)
        .modulus(ModulusConvention::HalfSpace)
        .solver(SolverOptions::default())
        .connectivity(4)
        .sliding(sliding.clone())
        .stopping(stopping)
        .model(wearsim::model::WearModel::Sliding)
        .build()
        .unwrap();
        SlidingRun::with_surfaces(&config, SurfacePair::of_arrays(top.clone(), bottom.clone()))
            .unwrap()
            .run(|_| {})
            .unwrap()
            .runs
    };
    let (tight, settled) = (run(Stopping::Tolerance), run(Stopping::SettledMap));
    for (a, b) in tight.iter().zip(&settled) {
        // Everything but the solver's own counts is the same, bit for bit.
        assert_eq!(a.results, b.results, "load {}", a.load);
        for (x, y) in a.steps.iter().zip(&b.steps) {
            let (mut x, mut y) = (x.clone(), y.clone());
            (x.iterations, x.residual, y.iterations, y.residual) = (0, 0.0, 0, 0.0);
            assert_eq!(x, y, "load {}, offset {}", a.load, x.offset);
        }
        assert!(
            b.total_iterations * 10 < a.total_iterations * 9,
            "load {}: {} iterations settled, {} tight",
            a.load,
            b.total_iterations,
            a.total_iterations
        );
    }
}
