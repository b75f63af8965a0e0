//! `wearsim estimate` and `wearsim estimate-check`: the documents they write are marked as an
//! estimate and hold the intervals; the comparison with a study's sliding runs and the fit of the
//! constants run on a small study; bad input is named.

mod common;

use common::{file, s, stderr, stdout, wearsim};

/// A 128² box of side L/32 at the paper's pixel size (d* = 23.6 px), two surface pairs.
const STUDY: &str = "units = \"reduced\"\n[surface]\ngrid = 128\nlength = 0.03125\nhurst = 0.7\n\
    lambda_lower = 0.00390625\nlambda_upper = 0.0078125\nrms_height = 0.005\nseed = [1, 2]\n\
    [material]\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.010\n\
    fracture_energies = [0.25e-6]\n[sliding]\nloads = [1.5e-6, 2.4e-6]\n";

/// Runs the study `text` in `dir` into `dir/study`, which it returns.
fn run_study(dir: &std::path::Path, text: &str) -> std::path::PathBuf {
    let study = file(dir, "study.toml", text);
    let folder = dir.join("study");
    let o = wearsim()
        .args(["study", "run", s(&study), "--out", s(&folder), "--quiet"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    folder
}

#[test]
fn estimate_writes_a_marked_summary_with_intervals() {
    let dir = tempfile::tempdir().unwrap();
    let run = file(dir.path(), "run.toml", &STUDY.replace("seed = [1, 2]", "seed = 1"));
    let out = dir.path().join("out");
    let o = wearsim()
        .args(["estimate", s(&run), "--out", s(&out), "--quiet"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stdout(&o).starts_with("ESTIMATE (static estimate, not a sliding run"),
        "{}",
        stdout(&o)
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["model"], "estimate");
    assert!(summary["notice"].as_str().unwrap().contains("not a sliding run"));
    assert!(summary["calibration"]["residence_factor"].as_f64().unwrap() > 0.0);
    let results = summary["results"].as_array().unwrap();
    assert_eq!(results.len(), 2);
    for r in results {
        let (w, lo, hi) = (&r["wear_rate"], &r["wear_rate_low"], &r["wear_rate_high"]);
        if let (Some(w), Some(lo), Some(hi)) = (w.as_f64(), lo.as_f64(), hi.as_f64()) {
            assert!(lo < w && w < hi, "{r}");
        }
    }
    assert_eq!(summary["units_of_results"]["wear_rate_low"], "L²");
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    assert!(
        csv.starts_with("load,fracture_energy,critical_diameter,wear_rate,wear_rate_low"),
        "{csv}"
    );
    // A bad sample count is named before any work.
    let o = wearsim()
        .args([
            "estimate",
            s(&run),
            "--out",
            s(&dir.path().join("bad")),
            "--samples",
            "40",
        ])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains("estimate_samples") && stderr(&o).contains("16"),
        "{}",
        stderr(&o)
    );
    assert!(!dir.path().join("bad").exists());
}

#[test]
fn estimate_check_compares_a_studys_sliding_runs_and_fits() {
    let dir = tempfile::tempdir().unwrap();
    let folder = run_study(dir.path(), STUDY);
    let out = dir.path().join("check");
    let o = wearsim()
        .args([
            "estimate-check",
            s(&folder),
            "--out",
            s(&out),
            "--min-particles",
            "1",
            "--quiet",
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("with the constants in use: "), "{}", stdout(&o));
    let csv = std::fs::read_to_string(out.join("comparison.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 4, "one row per job and 𝒢: {csv}");
    assert!(csv.lines().next().unwrap().contains("wear_rate_error"));
    // Too few particles on so small a box to fit: said, not a panic or a silent fit.
    let o = wearsim()
        .args([
            "estimate-check",
            s(&folder),
            "--out",
            s(&dir.path().join("fit")),
            "--fit",
            "--quiet",
        ])
        .output()
        .unwrap();
    let said = format!("{}{}", stdout(&o), stderr(&o));
    assert!(o.status.success() || said.contains("at least 3"), "{said}");
}

#[test]
fn a_fit_on_unresolved_critical_diameters_is_warned_about() {
    // A 128² box of side L/2: Δx = L/256, so d* = 1.5 px for 𝒢 = 0.25×10⁻⁶ E L; 16–35 particles
    // per setting, enough for a fit.
    let coarse = STUDY
        .replace("length = 0.03125", "length = 0.5")
        .replace("lambda_lower = 0.00390625", "lambda_lower = 0.0625")
        .replace("lambda_upper = 0.0078125", "lambda_upper = 0.25")
        .replace(
            "loads = [1.5e-6, 2.4e-6]",
            "loads = [3.75e-4, 6e-4]\ndistance = 1.0\nrunning_in = 0.25",
        );
    let dir = tempfile::tempdir().unwrap();
    let folder = run_study(dir.path(), &coarse);
    let o = wearsim()
        .args([
            "estimate-check",
            s(&folder),
            "--out",
            s(&dir.path().join("fit")),
            "--fit",
            "--min-particles",
            "1",
            "--quiet",
        ])
        .output()
        .unwrap();
    let e = stderr(&o);
    // The estimates' own warning of d* against the pixel size, naming the jobs, and the fit's.
    assert!(e.contains("pixels, under 4") && e.contains("(jobs 0–3)"), "{e}");
    assert!(
        e.contains("the fit uses") && e.contains("refine the study's `grid`"),
        "{e}"
    );
}
