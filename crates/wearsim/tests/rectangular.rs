//! Rectangular grids (Nx × Ny square pixels, sliding along x) against the square case: a periodic
//! problem repeated twice along one side is the same problem, so its contact solution is the
//! original tiled, its junctions and particles twice as many, its wear volume twice as large and its
//! wear coefficient the same. A wrong wavenumber along y, a labeller or a schedule mixing up the two
//! sides all break these identities. A square grid given as `grid = [N, N]` is the square run.

use std::path::Path;

use wearsim::config::{RunConfig, SurfacePair, SurfaceSource, Units};
use wearsim::junctions::JunctionLabeller;
use wearsim::run::SlidingRun;
use wearsim::sliding::LoadRun;
use wearsim::sliding::SlidingConfig;
use wearsim::surface::pair_seeds;
use wearsim::{
    composite_heights, ContactSolver, Generation, Grid, Material, ModulusConvention, SpectrumParams, Surface,
};

const E_STAR: f64 = 1.0 / (1.0 - 0.09);

fn pair(grid: Grid, seed: u64) -> (Surface, Surface) {
    let spectrum = SpectrumParams {
        hurst: 0.7,
        lambda_lower: 4.0 * grid.pixel_size(),
        lambda_upper: 0.25,
        rms_height: 0.005,
        generation: Generation::RandomPhase,
    };
    let (a, b) = pair_seeds(seed);
    (
        Surface::generate(grid, &spectrum, a).unwrap(),
        Surface::generate(grid, &spectrum, b).unwrap(),
    )
}

/// The surface repeated `rx` times along x and `ry` times along y.
fn tiled(s: &Surface, rx: usize, ry: usize) -> Surface {
    let (nx, ny) = (s.nx(), s.ny());
    let h = s.heights();
    let mut out = Vec::with_capacity(nx * ny * rx * ry);
    for i in 0..nx * rx {
        for _ in 0..ry {
            out.extend_from_slice(&h[(i % nx) * ny..(i % nx + 1) * ny]);
        }
    }
    let grid = Grid::new(nx * rx, ny * ry, s.length() * rx as f64).unwrap();
    Surface::new("tiled", grid, out).unwrap()
}

/// Pressure (solved to a tight tolerance) and junction count of the contact at `offset`.
fn contact(top: &Surface, bottom: &Surface, mean_pressure: f64, offset: usize) -> (Vec<f64>, usize) {
    let grid = top.grid();
    let material = Material::new(1.0, 0.3, 0.01, vec![], 3.0).unwrap();
    let mut solver = ContactSolver::new(grid, E_STAR)
        .unwrap()
        .with_options(wearsim::SolverOptions::new(1e-12, 20_000).unwrap());
    let mut h = vec![0.0; grid.pixels()];
    composite_heights(top, bottom, offset, &mut h);
    let mut p = vec![0.0; grid.pixels()];
    solver
        .solve(&h, mean_pressure, material.flow_pressure(), &mut p)
        .unwrap();
    let mut labeller = JunctionLabeller::new(grid.nx(), grid.ny(), 4);
    let count = labeller.label(|k| p[k] > 0.0);
    (p, count)
}

#[test]
fn a_problem_repeated_along_y_or_x_has_the_tiled_contact_solution() {
    let grid = Grid::new(64, 32, 1.0).unwrap();
    let (top, bottom) = pair(grid, 3);
    let (p, count) = contact(&top, &bottom, 1e-3, 5);
    assert!(count > 5);
    let pm = Material::new(1.0, 0.3, 0.01, vec![], 3.0).unwrap().flow_pressure();
    for (rx, ry) in [(1, 2), (2, 1)] {
        let (pt, count_t) = contact(&tiled(&top, rx, ry), &tiled(&bottom, rx, ry), 1e-3, 5);
        let (nx, ny) = (64 * rx, 32 * ry);
        let mut worst: f64 = 0.0;
        let mut flipped = 0;
        for i in 0..nx {
            for j in 0..ny {
                let (a, b) = (pt[i * ny + j], p[(i % 64) * 32 + j % 32]);
                worst = worst.max((a - b).abs());
                flipped += usize::from((a > 0.0) != (b > 0.0));
            }
        }
        assert!(worst < 1e-8 * pm, "tiled {rx}×{ry}: pressures differ by {worst:e}");
        assert_eq!(flipped, 0, "tiled {rx}×{ry}: contact pixels differ");
        // No junction percolates across the box here, so every junction appears twice.
        assert_eq!(count_t, 2 * count, "tiled {rx}×{ry}");
    }
}

fn slide(top: &Surface, bottom: &Surface, loads: Vec<f64>) -> Vec<LoadRun> {
    let material = Material::new(1.0, 0.3, 0.01, vec![0.05e-6, 0.1e-6], 3.0).unwrap();
    let sliding = SlidingConfig::new(loads, 0.5, 0.25, 4, 1, None).unwrap();
    let config = RunConfig::builder(
        SurfaceSource::Arrays {
            grid: top.grid(),
            length: top.length(),
        },
        material,
    )
    .units(Units::Reduced)
    .modulus(ModulusConvention::HalfSpace)
    .solver(wearsim::SolverOptions::new(1e-12, 20_000).unwrap())
    .connectivity(4)
    .sliding(sliding)
    .stopping(wearsim::contact::SLIDING_STOPPING)
    .model(wearsim::model::WearModel::Sliding)
    .build()
    .unwrap();
    slide_config(&config, SurfacePair::of_arrays(top.clone(), bottom.clone()))
}

/// A run through the one way in.
fn slide_config(config: &RunConfig, pair: SurfacePair) -> Vec<LoadRun> {
    SlidingRun::with_surfaces(config, pair)
        .unwrap()
        .run(|_| {})
        .unwrap()
        .runs
}

#[test]
fn sliding_a_problem_repeated_across_the_sliding_direction_doubles_the_wear_and_keeps_k() {
    // 64 × 32 pixels over 1 × 0.5, and the same pair twice along y (64 × 64 over 1 × 1) at twice the
    // load: the same mean pressure.
    let (top, bottom) = pair(Grid::new(64, 32, 1.0).unwrap(), 7);
    let small = slide(&top, &bottom, vec![1e-3]);
    let large = slide(&tiled(&top, 1, 2), &tiled(&bottom, 1, 2), vec![2e-3]);
    assert_eq!(small[0].steps.len(), large[0].steps.len());
    let mut particles = 0;
    for (a, b) in small[0].steps.iter().zip(&large[0].steps) {
        assert_eq!((a.offset, a.s), (b.offset, b.s));
        assert_eq!(2 * a.junctions, b.junctions, "s = {}", a.s);
        assert!((a.contact_area - b.contact_area).abs() < 1e-12);
        for (wa, wb) in a.wear.iter().zip(&b.wear) {
            assert_eq!(2 * wa.n_formed, wb.n_formed);
            assert!((2.0 * wa.volume - wb.volume).abs() <= 1e-12 * wb.volume.max(1e-300));
            particles = particles.max(wa.n_formed);
        }
    }
    assert!(particles > 3, "the test needs particles: {particles}");
    for (ra, rb) in small[0].results.iter().zip(&large[0].results) {
        let (ka, kb) = (ra.wear_coefficient.unwrap(), rb.wear_coefficient.unwrap());
        assert!((ka - kb).abs() <= 1e-9 * ka, "k {ka} vs {kb}");
        assert!((2.0 * ra.wear_rate.unwrap() - rb.wear_rate.unwrap()).abs() <= 1e-9 * rb.wear_rate.unwrap());
    }
}

const RUN: &str = r#"
[surface]
grid = GRID
length = LENGTH
lambda_lower = 0.0625
lambda_upper = 0.25
rms_height = 0.005
seed = 4
[material]
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = 0.01
fracture_energies = [0.1e-6]
[sliding]
loads = [1e-3]
"#;

fn run_file(grid: &str, length: &str) -> RunConfig {
    RunConfig::from_toml(&RUN.replace("GRID", grid).replace("LENGTH", length), Path::new(".")).unwrap()
}

#[test]
fn a_square_grid_written_as_two_sides_is_the_square_run() {
    let runs: Vec<Vec<LoadRun>> = [("64", "1.0"), ("[64, 64]", "1.0"), ("[64, 64]", "[1.0, 1.0]")]
        .iter()
        .map(|(g, l)| {
            let config = run_file(g, l);
            slide_config(&config, config.surface_pair().unwrap())
        })
        .collect();
    for other in &runs[1..] {
        assert_eq!(other[0].steps, runs[0][0].steps);
        assert_eq!(other[0].results, runs[0][0].results);
    }
    // The three spellings of a rectangle agree, and its sides are checked.
    let a = run_file("[64, 32]", "1.0").grid().unwrap();
    assert_eq!(a, run_file("[64, 32]", "[1.0, 0.5]").grid().unwrap());
    assert_eq!(a, run_file("64", "[1.0, 0.5]").grid().unwrap());
    assert_eq!((a.nx(), a.ny(), a.length_y()), (64, 32, 0.5));
    let bad = RunConfig::from_toml(
        &RUN.replace("GRID", "[64, 32]").replace("LENGTH", "[1.0, 1.0]"),
        Path::new("."),
    );
    assert!(bad.unwrap_err().to_string().contains("square"));
    let bad = RunConfig::from_toml(
        &RUN.replace("GRID", "64").replace("LENGTH", "[1.0, 0.3]"),
        Path::new("."),
    );
    assert!(bad.unwrap_err().to_string().contains("whole number"));
    let bad = RunConfig::from_toml(
        &RUN.replace("GRID", "[64, 32, 16]").replace("LENGTH", "1.0"),
        Path::new("."),
    );
    assert!(bad.unwrap_err().to_string().contains("[along x, along y]"));
}
