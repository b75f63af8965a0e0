//! Every figure drawn from a small hand-made study (jobs expanded from a study file, results made
//! up): each entry of the registry writes its files, intervals and per-area rates are what the
//! axes show, and Kim's band is drawn only for Kim's ceramics.

use super::*;
use wearsim::output::{JobResult, Provenance, StepRow, JOB_FORMAT};
use wearsim::sliding::WearResult;

const REDUCED: &str = r#"
units = "reduced"
[surface]
grid = 64
length = 0.5
hurst = 0.7
lambda_lower = 0.0625
lambda_upper = 0.125
rms_height = 0.005
seed = [1, 2, 3]
[material]
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = [0.008, 0.012]
fracture_energies = [0.5e-6, 1e-6]
[sliding]
loads = [2.5e-4, 5e-4]
distance = 0.5
running_in = 0.25
"#;

const KIM: &str = r#"
units = "si"
[surface]
grid = 64
length = 50e-6
hurst = 0.7
lambda_lower = 6.25e-6
lambda_upper = 25e-6
seed = [1, 2]
[[materials]]
name = "SiC"
youngs_modulus = 392e9
poisson_ratio = 0.16
shear_strength = 4.80e9
fracture_energies = [45.00]
surface = { rms_height = 5.0e-6 }
[[materials]]
name = "Al2O3"
youngs_modulus = 343e9
poisson_ratio = 0.25
shear_strength = 3.37e9
fracture_energies = [46.65]
surface = { rms_height = 20.0e-6 }
[sliding]
loads = [0.3125, 0.625]
distance = 0.5
running_in = 0.25
"#;

/// Made-up results of one job: W growing with the load and the seed, a few steps of series.
fn result_of(job: &Job) -> JobResult {
    let inputs = job.inputs();
    let (load, seed) = (job.load(), inputs.seed.unwrap_or(1) as f64);
    let energies = &job.run.material.fracture_energies;
    let scale = inputs.length * inputs.length;
    let results: Vec<WearResult> = energies
        .iter()
        .enumerate()
        .map(|(e, &g)| {
            let w = scale * 1e-4 * (load / 2.5e-4 * scale.recip()).powf(1.2) * (1.0 + 0.1 * seed) / (1 + e) as f64;
            WearResult {
                fracture_energy: g,
                critical_diameter: inputs.length * 0.02 * (1 + e) as f64,
                wear_rate: Some(w),
                wear_rate_r2: Some(0.95),
                wear_volume_intercept: Some(w * 0.1),
                fit_window_start: 0.25 * inputs.length,
                wear_coefficient: Some(0.05 * (1.0 + 0.1 * seed)),
                particle_rate: Some(100.0 / (1 + e) as f64),
                wear_rate_estimate: Some(0.9 * w),
                particles_in_fit: 10 + 5 * e,
                initial_volume: 20.0 * w,
                static_wear_coefficient_mean: 0.5,
                static_wear_rate_mean: 5.0 * w,
                junctions_mean: 30.0,
                critical_junctions_mean: 3.0,
                memory_decay_length: Some(0.05 * inputs.length * seed),
                memory_decay_r2: Some(0.9),
                memory_fit_initial_junctions: Some(20.0),
                running_in_decay_lengths: Some(5.0 / seed),
                ..WearResult::default()
            }
        })
        .collect();
    let steps = (0..6)
        .map(|k| StepRow {
            s: k as f64 * 0.1 * inputs.length,
            junctions: 30,
            wrapping_junctions: 0,
            contact_area: 0.1,
            initial_junctions: 20usize >> k,
            n_critical: vec![3; energies.len()],
            n_formed: vec![2 + k; energies.len()],
            volume: results
                .iter()
                .map(|w| w.initial_volume + w.wear_rate.unwrap_or(0.0) * k as f64)
                .collect(),
            static_wear_coefficient: vec![0.5; energies.len()],
        })
        .collect();
    JobResult {
        format: JOB_FORMAT,
        provenance: Provenance::current(),
        index: job.index,
        material: job.material.clone(),
        inputs,
        load,
        flow_pressure: 3.0 * 3f64.sqrt() * job.run.material.shear_strength,
        effective_modulus: 1.0,
        results,
        steps,
        total_iterations: 0,
        seconds: 1.0,
        warnings: Vec::new(),
        estimates: Vec::new(),
    }
}

fn study(text: &str) -> Data {
    let study = wearsim::study::expand(text, Path::new(".")).expect("the test study expands");
    let results: Vec<JobResult> = study.jobs.iter().map(result_of).collect();
    Data::new(study.jobs, results).unwrap()
}

/// The files a figure wrote, by stem.
fn drawn(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".png"))
        .map(|n| n.trim_end_matches(".png").to_string())
        .collect();
    names.sort();
    names
}

#[test]
fn every_figure_of_the_registry_draws_its_files() {
    let data = study(REDUCED);
    for figure in &FIGURES {
        let dir = tempfile::tempdir().unwrap();
        draw(&data, None, Some(&[figure.name.to_string()]), dir.path(), dir.path()).unwrap();
        let names = drawn(dir.path());
        assert!(!names.is_empty(), "{} drew nothing", figure.name);
        for n in &names {
            let png = std::fs::metadata(dir.path().join(format!("{n}.png"))).unwrap().len();
            let svg = std::fs::read_to_string(dir.path().join(format!("{n}.svg"))).unwrap();
            assert!(png > 2000 && svg.len() > 1000, "{}: {n}", figure.name);
        }
    }
}

#[test]
fn rates_are_per_unit_area_with_intervals_and_kims_band_only_for_kims_ceramics() {
    let data = study(REDUCED);
    // A box of 0.5 × 0.5 L: W divided by its area 0.25; the bars are the 95 % interval of the mean
    // of the three pairs (1.1, 1.2, 1.3 times a base: mean 1.2, sd 0.1, t(2) = 4.303).
    let c = &data.curves[0];
    let (per_area, plain) = (c.stats("wear_rate", true), c.stats("wear_rate", false));
    assert!((per_area[0].1 - plain[0].1 / 0.25).abs() < 1e-15 * plain[0].1.abs().max(1.0));
    let half = 4.302_652_7 * 0.1 / 3f64.sqrt() / 1.2 * plain[0].1;
    assert!(
        (plain[0].3 - plain[0].1 - half).abs() < 1e-6 * plain[0].1,
        "{:?}",
        plain[0]
    );
    let dir = tempfile::tempdir().unwrap();
    draw(
        &data,
        None,
        Some(&["fig4".into(), "fig6".into()]),
        dir.path(),
        dir.path(),
    )
    .unwrap();
    let svg = |name: &str| std::fs::read_to_string(dir.path().join(format!("{name}.svg"))).unwrap();
    assert!(svg("fig4_sliding_wear").contains("95 % confidence interval"));
    assert!(svg("fig4_sliding_wear").contains("per unit nominal area"));
    assert!(!svg("fig6_kim_comparison").contains("rolling experiments"));
    // Kim's ceramics: the band, and appendix F with the paper's fits beside them.
    let kim = study(KIM);
    let dir = tempfile::tempdir().unwrap();
    draw(
        &kim,
        None,
        Some(&["fig6".into(), "appF".into()]),
        dir.path(),
        dir.path(),
    )
    .unwrap();
    let svg = |name: &str| std::fs::read_to_string(dir.path().join(format!("{name}.svg"))).unwrap();
    assert!(svg("fig6_kim_comparison").contains("rolling experiments"));
    assert!(svg("appF_contact_severity").contains("fit to their experiments"));
}

#[test]
fn the_memory_figure_shows_every_pair_of_the_setting() {
    let data = study(REDUCED);
    let (job, _) = series_job(&data, Some(0)).unwrap();
    let pairs = data.pairs_of(job);
    assert_eq!(pairs.len(), 3);
    assert!(pairs
        .iter()
        .all(|(j, _)| j.material == job.material && j.load() == job.load()));
    let seeds: Vec<Option<u64>> = pairs.iter().map(|(j, _)| j.inputs().seed).collect();
    assert_eq!(seeds, [Some(1), Some(2), Some(3)]);
}
