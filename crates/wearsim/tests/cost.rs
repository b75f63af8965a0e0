//! The cost estimate (`wearsim::cost`) against the measured time of sliding runs, calibrated just
//! before them: within a factor of three on small grids. Calibration and runs are timed in
//! processor time on one thread, which other work on a shared machine does not inflate as it does
//! the wall clock (on an idle machine the two agree); the estimate is for sizing a Slurm job, not a
//! benchmark. Being a measurement of time, it is not one of the test command's tests: it runs with
//! `cargo test --profile ci -p wearsim --test integration cost:: -- --ignored` (about 30 s of
//! processor time), on a machine of the kind the estimates are for.

use wearsim::config::{RunConfig, SurfacePair, SurfaceSource, Units};
use wearsim::cost::Calibration;
use wearsim::run::SlidingRun;
use wearsim::sliding::SlidingConfig;
use wearsim::surface::pair_seeds;
use wearsim::{Grid, Interrupt, Material, ModulusConvention, SolverOptions, SpectrumParams, Stopping, Surface};

/// Processor time of this process (user + system), in seconds, from /proc/self/stat (Linux; clock
/// ticks of 1/100 s, the kernel's fixed USER_HZ).
fn processor_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").expect("Linux /proc");
    let fields: Vec<&str> = stat[stat.rfind(')').unwrap() + 2..].split_whitespace().collect();
    // utime and stime are fields 14 and 15 of the line, 12 and 13 after the command name.
    let ticks: f64 = fields[11].parse::<f64>().unwrap() + fields[12].parse::<f64>().unwrap();
    ticks / 100.0
}

#[test]
#[ignore = "a timing (about 30 s of processor time): run with --ignored, as the module says"]
fn the_estimate_is_within_a_factor_of_three_of_the_measured_time() {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    pool.install(|| {
        let calibration = Calibration::measure_with(&Interrupt::default(), &processor_seconds).unwrap();
        assert_eq!(calibration.threads, 1);
        let a = calibration.seconds_per_iteration;
        assert!(a.tolerance > 0.0 && a.settled_map > 0.0);
        let material = Material::new(1.0, 0.3, 0.012, vec![0.5e-6], 3.0).unwrap();
        for (n, loads) in [(256, vec![5e-4, 2e-3]), (512, vec![1e-3])] {
            let grid = Grid::square(n, 1.0).unwrap();
            let spectrum = SpectrumParams::paper_roughness(n, 1.0);
            let (a, b) = pair_seeds(3);
            let (top, bottom) = (
                Surface::generate(grid, &spectrum, a).unwrap(),
                Surface::generate(grid, &spectrum, b).unwrap(),
            );
            let sliding = SlidingConfig::new(loads, 0.3, 0.2, 4, 1, Some(n)).unwrap();
            let config = RunConfig::builder(SurfaceSource::Arrays { grid, length: 1.0 }, material.clone())
                .units(Units::Reduced)
                .modulus(ModulusConvention::HalfSpace)
                .solver(SolverOptions::default())
                .connectivity(4)
                .sliding(sliding.clone())
                .stopping(Stopping::SettledMap)
                .model(wearsim::model::WearModel::Sliding)
                .build()
                .unwrap();
            let t = processor_seconds();
            let runs = SlidingRun::with_surfaces(&config, SurfacePair::of_arrays(top, bottom))
                .unwrap()
                .run(|_| {})
                .unwrap()
                .runs;
            let measured = processor_seconds() - t;
            let estimate = calibration.estimate(grid, &sliding, Stopping::SettledMap);
            let steps: usize = runs.iter().map(|r| r.steps.len()).sum();
            let iterations: usize = runs.iter().map(|r| r.total_iterations).sum();
            assert_eq!(estimate.steps, steps);
            let ratio = estimate.seconds / measured;
            println!(
                "{n}²: estimated {:.2} s ({:.0} iterations), measured {measured:.2} s ({iterations} iterations): {ratio:.2}",
                estimate.seconds, estimate.iterations
            );
            assert!((1.0 / 3.0..3.0).contains(&ratio), "{n}²: estimate / measured = {ratio:.2}");
        }
    });
}

/// A 128² run of the paper's roughness, or of another spectrum (H = 0.8, λ_l = 8 px, a fifth of the
/// RMS height: a larger contact fraction, as on the measured maps), at a nominal pressure of 2×10⁻³ E.
fn probe_config(other: bool) -> RunConfig {
    let (hurst, lambda_lower, rms) = if other { (0.8, 8.0, 0.001) } else { (0.7, 16.0, 0.005) };
    let text = format!(
        "units = \"reduced\"\n[surface]\ngrid = 128\nlength = 1.0\nhurst = {hurst}\nlambda_lower = {}\n\
         lambda_upper = 0.25\nrms_height = {rms}\nseed = 3\n[material]\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\n\
         shear_strength = 0.010\nfracture_energies = [0.25e-6]\n[sliding]\nloads = [2e-3]\ndistance = 0.5\n\
         running_in = 0.125\n",
        lambda_lower / 128.0
    );
    RunConfig::from_toml(&text, std::path::Path::new(".")).unwrap()
}

#[test]
fn iterations_measured_on_the_runs_own_surfaces_follow_a_rough_pair_and_match_its_run() {
    // Iterations only: the calibration's constants of time do not enter.
    let runs = |fine: f64| {
        [128, 256, 512].map(|n| wearsim::cost::CalibrationRun {
            n,
            stopping: Stopping::SettledMap,
            steps: 20,
            iterations: 300,
            seconds: 1.0,
            step_iterations: wearsim::cost::StepIterations {
                cold: 20.0,
                coarse: 15.0,
                fine,
            },
        })
    };
    let calibration = Calibration {
        format: 0,
        software: String::new(),
        machine: String::new(),
        threads: 1,
        cores: 1,
        load_average: None,
        measured_at: 0,
        seconds_per_iteration: wearsim::cost::PerRule {
            tolerance: 1e-9,
            settled_map: 1e-9,
        },
        runs: runs(12.0).to_vec(),
    };
    let (mut predicted, mut taken_all) = (Vec::new(), Vec::new());
    for rough in [false, true] {
        let config = probe_config(rough);
        let sliding = config.sliding.clone().unwrap();
        let grid = config.grid().unwrap();
        // The probe slides on the run's own surfaces, which the run then slides on: made once.
        let prepared = SlidingRun::prepare(&config).unwrap();
        let probe = prepared.probe_iterations().unwrap();
        let e = calibration.estimate_measured(grid, &sliding, config.stopping, Some(probe.iterations));
        let run = prepared.run(|_| {}).unwrap();
        if !rough {
            // Probing first leaves the run as it was: every step and result of a run not probed.
            let unprobed = SlidingRun::prepare(&config).unwrap().run(|_| {}).unwrap();
            assert_eq!(run.runs[0].steps, unprobed.runs[0].steps);
            assert_eq!(run.runs[0].results, unprobed.runs[0].results);
        }
        let taken = run.runs[0].total_iterations as f64;
        let ratio = e.iterations / taken;
        eprintln!(
            "rough {rough}: predicted {:.0} iterations (assumed {:.0}), taken {taken:.0}",
            e.iterations, e.assumed_iterations
        );
        assert!(
            (0.5..=2.0).contains(&ratio),
            "rough {rough}: {} predicted, {taken} taken",
            e.iterations
        );
        predicted.push(e.iterations);
        taken_all.push(taken);
    }
    // The other spectrum takes more iterations than the paper's, and the estimate says so where the
    // calibration's assumption cannot.
    assert!(taken_all[1] > 1.2 * taken_all[0], "{taken_all:?}");
    assert!(predicted[1] > 1.2 * predicted[0], "{predicted:?}");
}
