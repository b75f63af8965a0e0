//! The same dimensionless problem stated at any length and stress scale within
//! `check::SCALE_RANGE` gives the dimensionless results scaled (wear volumes of 1e-240 m³ and
//! 1e240 m³ alike), and scales outside it are refused with the range, not answered with W = 0,
//! R² = NaN or a solver that "did not converge".

use std::path::Path;

use wearsim::config::RunConfig;
use wearsim::run::SlidingRun;

/// A 64² run of the paper's roughness at box side `l` (m) and Young's modulus `e` (Pa).
fn run_file(l: f64, e: f64) -> String {
    format!(
        "units = \"si\"\n[surface]\ngrid = 64\nlength = {l:e}\nhurst = 0.7\nlambda_lower = {:e}\nlambda_upper = {:e}\n\
         rms_height = {:e}\nseed = 1\n[material]\nyoungs_modulus = {e:e}\npoisson_ratio = 0.3\nshear_strength = {:e}\n\
         fracture_energies = [{:e}]\n[sliding]\nloads = [{:e}]\n",
        l / 16.0,
        l / 4.0,
        0.005 * l,
        0.01 * e,
        2.5e-7 * e * l,
        1e-3 * e * l * l
    )
}

/// (W/L², R², k, dN*₊/ds·L, V₀/L³) of the run at scale (l, e).
fn reduced_results(l: f64, e: f64) -> [f64; 5] {
    let config = RunConfig::from_toml(&run_file(l, e), Path::new(".")).unwrap();
    let runs = SlidingRun::prepare(&config).unwrap().run(|_| {}).unwrap().runs;
    let r = &runs[0].results[0];
    [
        r.wear_rate.expect("W defined") / (l * l),
        r.wear_rate_r2.expect("R² defined"),
        r.wear_coefficient.expect("k defined"),
        r.particle_rate.expect("dN/ds defined") * l,
        r.initial_volume / (l * l * l),
    ]
}

#[test]
fn a_problem_at_extreme_scales_gives_the_dimensionless_results_scaled() {
    let unit = reduced_results(1.0, 1.0);
    assert!(unit[0] > 0.0 && unit[4] > 0.0, "{unit:?}");
    for (l, e) in [(1e-80, 1.0), (1e80, 1.0), (1e-90, 1e90), (1e90, 1e-88), (1e-30, 1e-60)] {
        let scaled = reduced_results(l, e);
        for (name, (a, b)) in ["W/L²", "R²", "k", "dN*₊/ds·L", "V₀/L³"]
            .iter()
            .zip(unit.iter().zip(&scaled))
        {
            assert!(
                (a - b).abs() <= 1e-9 * a.abs(),
                "L = {l:e}, E = {e:e}: {name} {b} vs {a}"
            );
        }
    }
}

#[test]
fn scales_outside_the_representable_range_are_refused_naming_it() {
    for (l, e, field) in [
        (1e-91, 1.0, "length"),
        (1e91, 1.0, "length"),
        (1.0, 1e91, "youngs_modulus"),
        (1.0, 1e-89, "shear_strength"),
    ] {
        let err = RunConfig::from_toml(&run_file(l, e), Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains(field) && err.contains("1e-90 … 1e90"),
            "{l:e} {e:e}: {err}"
        );
    }
}

#[test]
fn a_job_result_json_cannot_hold_is_refused_instead_of_written_as_a_file_read_back_as_cut_short() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path().join("jobs")).unwrap();
    let text = run_file(1.0, 1.0).replace("grid = 64", "grid = 32");
    let study = wearsim::study::expand(&text, dir.path()).unwrap();
    let job = &study.jobs[0];
    let mut result = wearsim::study::run_job(job, &wearsim::Interrupt::default()).unwrap();
    wearsim::study::write_result(dir.path(), &result).unwrap();
    assert!(matches!(
        wearsim::study::stored_result(job, dir.path()).unwrap(),
        wearsim::study::Stored::Done(_)
    ));
    std::fs::remove_file(wearsim::study::job_path(dir.path(), job.index)).unwrap();
    result.flow_pressure = f64::NAN;
    let err = wearsim::study::write_result(dir.path(), &result)
        .unwrap_err()
        .to_string();
    assert!(err.contains("not a finite number"), "{err}");
    assert!(!wearsim::study::job_path(dir.path(), job.index).exists());
}
