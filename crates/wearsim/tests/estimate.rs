//! The static estimate (`wearsim::estimate`): against a sliding run it was not calibrated on, on a
//! small grid; independent of the thread count; as a study job, marked and collected.

use std::path::Path;

use wearsim::config::RunConfig;
use wearsim::estimate::{Sampling, CALIBRATION};
use wearsim::model::WearModel;
use wearsim::run::SlidingRun;
use wearsim::study::{expand, run_job};
use wearsim::Interrupt;

/// A 512² box of side L/8 at the paper's pixel size (Δx = L/4096, d* = 23.6 px for 𝒢 = 0.25×10⁻⁶ E L),
/// a surface pair (seed 7) and λ_u = L/32 that the calibration (L/4 boxes, λ_u = L/16, seeds 1–3) never saw.
const HELD_OUT: &str = "units = \"reduced\"\n[surface]\ngrid = 512\nlength = 0.125\nhurst = 0.7\n\
    lambda_lower = 0.00390625\nlambda_upper = 0.03125\nrms_height = 0.005\nseed = 7\n\
    [material]\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.010\n\
    fracture_energies = [0.25e-6]\n[sliding]\nloads = [2.34375e-5, 3.90625e-5]\n";

#[test]
fn the_sliding_run_falls_in_the_estimates_interval_on_a_held_out_small_grid() {
    let config = RunConfig::from_toml(HELD_OUT, Path::new(".")).unwrap();
    let estimate = SlidingRun::prepare(&config)
        .unwrap()
        .estimate(Sampling::Auto, &CALIBRATION, |_, _| {})
        .unwrap();
    let slid = SlidingRun::prepare(&config).unwrap().run(|_| {}).unwrap();
    for (e, s) in estimate.loads.iter().zip(&slid.runs) {
        let (e, s) = (&e.results[0], &s.results[0]);
        assert!(s.particles_in_fit >= 10, "the sliding run forms particles: {s:?}");
        let (w, lo, hi) = (
            s.wear_rate.unwrap(),
            e.wear_rate_low.unwrap(),
            e.wear_rate_high.unwrap(),
        );
        assert!(
            lo <= w && w <= hi,
            "sliding W = {w:e} outside the estimate's [{lo:e}, {hi:e}]"
        );
        let error = e.wear_rate.unwrap() / w - 1.0;
        assert!(error.abs() <= 0.5, "estimate/sliding − 1 = {error:.2}");
        let rate_error = e.particle_rate.unwrap() / s.particle_rate.unwrap() - 1.0;
        assert!(
            rate_error.abs() <= 0.5,
            "dN*₊/ds: estimate/sliding − 1 = {rate_error:.2}"
        );
        // k is W times p_m/F_N in both.
        let k_ratio = e.wear_coefficient.unwrap() / s.wear_coefficient.unwrap();
        assert!((k_ratio - (1.0 + error)).abs() < 1e-9);
        // Static N* against the sliding run's mean N*.
        let n_ratio = e.critical_junctions_mean / s.critical_junctions_mean;
        assert!((0.6..1.6).contains(&n_ratio), "N* static/sliding = {n_ratio:.2}");
    }
}

#[test]
fn an_estimate_does_not_depend_on_the_thread_count() {
    let config = RunConfig::from_toml(
        &HELD_OUT.replace("grid = 512", "grid = 256").replace("0.125", "0.0625"),
        Path::new("."),
    )
    .unwrap();
    let on = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| {
            SlidingRun::prepare(&config)
                .unwrap()
                .estimate(Sampling::Fixed(6), &CALIBRATION, |_, _| {})
                .unwrap()
                .loads
        })
    };
    let (one, two) = (on(1), on(2));
    assert_eq!(one, two);
    assert_eq!(one[0].samples.len(), 6);
    assert!(one[0].results[0].critical_junctions_mean > 0.0);
}

#[test]
fn an_estimate_job_is_marked_and_its_results_fill_the_tables() {
    let study = expand(
        &HELD_OUT
            .replace("grid = 512", "grid = 128")
            .replace("0.125", "0.03125")
            .replace(
                "loads = [2.34375e-5, 3.90625e-5]",
                "loads = [1.5e-6, 2.4e-6]\nmodel = \"estimate\"\nestimate_samples = 4",
            ),
        Path::new("."),
    )
    .unwrap();
    assert_eq!(study.jobs.len(), 2);
    let job = &study.jobs[1];
    assert_eq!(job.run.model, WearModel::Estimate);
    let r = run_job(job, &Interrupt::default()).unwrap();
    assert_eq!(r.inputs.model, Some(WearModel::Estimate));
    assert_eq!(r.inputs.estimate_samples, Some(4));
    assert!(r.steps.is_empty(), "an estimate takes no sliding step");
    assert_eq!(r.estimates.len(), 1);
    assert_eq!(r.results[0].wear_rate, r.estimates[0].wear_rate);
    assert_eq!(r.results[0].particle_rate, r.estimates[0].particle_rate);
    assert_eq!(r.results[0].particles_in_fit, 0, "an estimate counts no particle");
    // The job file round-trips with its estimates; a sliding job's file has none.
    let back = wearsim::output::JobResult::from_json(&r.to_json()).unwrap();
    assert_eq!(back, r);
    // Its file is checked as an estimate's: an interval that does not hold its value, or sliding
    // steps, are refused as edited or damaged.
    assert_eq!(wearsim::study::store::out_of_range(&r, job), None);
    let mut edited = r.clone();
    if let Some(w) = edited.estimates[0].wear_rate {
        edited.estimates[0].wear_rate_low = Some(2.0 * w);
        let why = wearsim::study::store::out_of_range(&edited, job).expect("refused");
        assert!(why.contains("estimates[0].wear_rate"), "{why}");
    }
    let rows = wearsim::output::TidyRow::of_job(&r);
    let table = wearsim::output::Table::of(&rows);
    let model = table.column("sliding.model").expect("the tidy table names the model");
    assert_eq!(table.rows[0][model].text(), "estimate");
}

#[test]
fn a_bad_model_or_sample_count_is_named() {
    let bad = |extra: &str| {
        RunConfig::from_toml(&format!("{HELD_OUT}{extra}"), Path::new("."))
            .unwrap_err()
            .to_string()
    };
    let e = bad("model = \"static\"\n");
    assert!(e.contains("model") && e.contains("estimate"), "{e}");
    let e = bad("estimate_samples = 0\n");
    assert!(e.contains("estimate_samples") && e.contains("16"), "{e}");
}

/// A 64² box at a load near the flow pressure: the whole box is in contact, one junction around the
/// torus (as in the sliding test of full contact).
fn full_contact_run() -> String {
    let pm_fraction = 0.999 * 3.0 * 3f64.sqrt() * 0.010; // p_m = 3√3 τ̃, τ̃ = 0.010 E
    let area = 0.015625_f64 * 0.015625;
    HELD_OUT
        .replace("grid = 512", "grid = 64")
        .replace("length = 0.125", "length = 0.015625")
        .replace("lambda_upper = 0.03125", "lambda_upper = 0.0078125")
        .replace(
            "loads = [2.34375e-5, 3.90625e-5]",
            &format!("loads = [{:e}, {:e}]", 1.5e-3 * area, pm_fraction * area),
        )
}

#[test]
fn the_estimate_flags_a_junction_around_the_box_as_the_sliding_model_does() {
    let config = RunConfig::from_toml(&full_contact_run(), Path::new(".")).unwrap();
    let estimate = SlidingRun::prepare(&config)
        .unwrap()
        .estimate(Sampling::Fixed(2), &CALIBRATION, |_, _| {})
        .unwrap();
    let slid = SlidingRun::prepare(&config).unwrap().run(|_| {}).unwrap();
    let (light, full) = (&estimate.loads[0], &estimate.loads[1]);
    assert!(light.samples.iter().all(|s| s.wrapping_junctions == 0));
    assert!(!light.warnings.iter().any(|w| w.contains("wraps the periodic box")));
    assert!(
        full.samples.iter().all(|s| s.wrapping_junctions == 1),
        "{:?}",
        full.samples
    );
    // The same rule and the same words as the sliding run's, naming where it met it.
    let said = |warnings: &[String]| {
        warnings
            .iter()
            .find(|w| w.contains("wraps the periodic box"))
            .cloned()
            .unwrap_or_default()
    };
    let (estimated, slid_warning) = (said(&full.warnings), said(&slid.runs[1].warnings));
    assert!(estimated.contains("in 2 of 2 static maps"), "{estimated}");
    assert!(slid_warning.contains("steps (the first at s = "), "{slid_warning}");
    let tail = |w: &str| w.split(" a junction wraps").nth(1).unwrap_or("").to_string();
    assert_eq!(tail(&estimated), tail(&slid_warning), "one warning for both models");
    assert!(estimate.warnings.contains(&estimated));
    // It is counted as a critical junction by both, as the sliding model counts it.
    assert_eq!(
        full.results[0].critical_junctions_mean,
        slid.runs[1].results[0].critical_junctions_mean
    );
}

#[test]
fn automatic_sampling_keeps_its_promise_or_says_it_could_not() {
    // A 128² box at the paper's pixel size: few critical junctions per map, so the Poisson floor of
    // the sampling error (1/√n over the junctions counted) is what decides when to stop.
    let config = RunConfig::from_toml(
        &HELD_OUT
            .replace("grid = 512", "grid = 128")
            .replace("length = 0.125", "length = 0.03125")
            .replace("lambda_upper = 0.03125", "lambda_upper = 0.0078125")
            .replace(
                "fracture_energies = [0.25e-6]",
                "fracture_energies = [0.05e-6, 0.25e-6]",
            )
            .replace("loads = [2.34375e-5, 3.90625e-5]", "loads = [1.5e-6, 2.4e-6]"),
        Path::new("."),
    )
    .unwrap();
    let estimate = SlidingRun::prepare(&config)
        .unwrap()
        .estimate(Sampling::Auto, &CALIBRATION, |_, _| {})
        .unwrap();
    let target = wearsim::estimate::TARGET_SAMPLING_ERROR;
    let worst = estimate
        .loads
        .iter()
        .flat_map(|l| &l.results)
        .filter(|r| r.critical_junctions_mean >= wearsim::estimate::RESOLVED_CRITICAL_JUNCTIONS)
        .filter_map(|r| r.critical_junctions_sampling_error)
        .fold(0.0, f64::max);
    let warned = estimate
        .warnings
        .iter()
        .any(|w| w.contains("sampling error of N* is still"));
    assert!(worst > 0.0, "the box has resolved settings");
    if worst > target {
        assert_eq!(estimate.samples, wearsim::estimate::MAX_SAMPLES);
        assert!(
            warned,
            "{worst} over the target without a warning: {:?}",
            estimate.warnings
        );
    } else {
        assert!(!warned);
    }
}
