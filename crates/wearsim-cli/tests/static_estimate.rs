//! `wearsim estimate` and `wearsim estimate-check`: the documents they write are marked as an
//! estimate and hold the intervals; the comparison with a study's sliding runs and the fit of the
//! constants run on a small study; bad input is named.

use crate::common;

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
    let header = csv.lines().next().unwrap();
    assert!(
        header.contains("wear_rate_error") && header.contains(",scored,"),
        "{header}"
    );
    // Every setting is scored, whatever its particles: the kinds add up to the rows.
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let s_ = &summary["summary_with_calibration_in_use"];
    let n = |k: &str| s_[k].as_u64().unwrap_or_else(|| panic!("{k}: {s_}"));
    assert_eq!(n("settings"), 4, "{s_}");
    assert_eq!(
        n("with_interval") + n("interval_withheld") + n("no_estimate") + n("no_sliding_rate"),
        4,
        "{s_}"
    );
    assert_eq!(n("error_settings") + n("error_left_out"), 4, "{s_}");
    let scored: Vec<&str> = csv
        .lines()
        .skip(1)
        .map(|l| {
            l.split(',')
                .nth(header.split(',').position(|c| c == "scored").unwrap())
                .unwrap()
        })
        .collect();
    assert_eq!(
        scored.iter().filter(|k| **k == "covered").count() as u64,
        n("wear_rate_covered"),
        "{scored:?}"
    );
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

/// Surfaces that are not the calibration's: pairs carrying the measured 2D PSD of `lay.npy`
/// ([`lay_map`]) on a 128² box, d* ≈ 9 px.
const OWN_SURFACES: &str = "units = \"reduced\"\n[surface]\nsource = \"spectrum\"\nmap = \"lay.npy\"\n\
    map_length = 0.03125\ngrid = 128\nlength = 0.03125\nseed = [1, 2, 3]\n\
    [material]\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.010\n\
    fracture_energies = [0.1e-6]\n[sliding]\nloads = [3.6e-6, 7.2e-6]\ndistance = 1.0\n";

/// A periodic 128² map of side L/32 whose spectrum is not self-affine: a self-affine surface
/// (H = 0.5, λ_l = 4 px, λ_u = Lx/2) plus a lay, grooves along y whose profile along x is another
/// such surface's first column, which puts the power of a whole surface onto the qx axis (`wearsim
/// surface fit` finds no decade of power law in it). Written as `lay.npy` into `dir`.
fn lay_map(dir: &std::path::Path) {
    use wearsim::{Generation, Grid, SpectrumParams, Surface};
    let n = 128;
    let params = SpectrumParams {
        hurst: 0.5,
        lambda_lower: 0.0009765625,
        lambda_upper: 0.015625,
        rms_height: 0.005,
        generation: Generation::RandomPhase,
    };
    let grid = Grid::square(n, 0.03125).unwrap();
    let (a, b) = wearsim::surface::pair_seeds(11);
    let (rough, lay) = (
        Surface::generate(grid, &params, a).unwrap(),
        Surface::generate(grid, &params, b).unwrap(),
    );
    let h: Vec<f64> = (0..n * n)
        .map(|k| rough.heights()[k] + lay.heights()[(k / n) * n])
        .collect();
    common::write_npy(&dir.join("lay.npy"), &[n, n], &h);
}

/// The W of every job of a study folder, in job order, with the particles it was fitted on.
fn job_wear_rates(folder: &std::path::Path) -> Vec<(f64, u64)> {
    let mut files: Vec<_> = std::fs::read_dir(folder.join("jobs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    files.sort();
    files
        .iter()
        .map(|p| {
            let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap();
            let r = &v["results"][0];
            (
                r["wear_rate"].as_f64().unwrap_or(0.0),
                r["particles_in_fit"].as_u64().unwrap_or(0),
            )
        })
        .collect()
}

#[test]
fn constants_refitted_on_psd_matched_surfaces_are_applied_and_bring_the_error_down() {
    let dir = tempfile::tempdir().unwrap();
    lay_map(dir.path());
    let sliding = run_study(dir.path(), OWN_SURFACES);
    let o = wearsim()
        .args([
            "estimate-check",
            s(&sliding),
            "--out",
            s(&dir.path().join("check")),
            "--fit",
            "--quiet",
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    let line = out
        .lines()
        .map(str::trim)
        .find(|l| l.starts_with("estimate_constants = {"))
        .unwrap_or_else(|| panic!("the fit prints the line to paste: {out}"));
    // The same settings estimated with the library's constants and with the fitted ones.
    let estimate = |name: &str, extra: &str| {
        let sub = dir.path().join(name);
        std::fs::create_dir(&sub).unwrap();
        lay_map(&sub);
        let text = format!("{OWN_SURFACES}model = \"estimate\"\n{extra}\n");
        job_wear_rates(&run_study(&sub, &text))
    };
    let slid = job_wear_rates(&sliding);
    // Over the settings the fit could use (at least 10 particles in the sliding run).
    let median_error = |w: &[(f64, u64)]| {
        let mut e: Vec<f64> = w
            .iter()
            .zip(&slid)
            .filter(|(_, b)| b.1 >= 10)
            .map(|(a, b)| (a.0 / b.0 - 1.0).abs())
            .collect();
        assert!(e.len() >= 3, "{e:?}");
        e.sort_by(f64::total_cmp);
        e[e.len() / 2]
    };
    let default = median_error(&estimate("default", ""));
    let fitted = median_error(&estimate("fitted", line));
    eprintln!("median |error| of W: {default:.3} with the library's constants, {fitted:.3} with the fitted ones");
    assert!(
        fitted < 0.5 * default,
        "median |error| of W on PSD-matched surfaces: {fitted:.3} with the fitted constants, {default:.3} with the \
         library's"
    );
    // The run file's constants are checked.
    let bad = file(
        dir.path(),
        "bad.toml",
        &OWN_SURFACES.replace("seed = [1, 2, 3]", "seed = 1").replace(
            "distance = 1.0",
            "estimate_constants = { residence_factor = -1.0, merging_factor = 2.0, volume_factor = 1.0, rate_spread = 0.1, wear_spread = 0.1 }",
        ),
    );
    let o = wearsim()
        .args(["estimate", s(&bad), "--out", s(&dir.path().join("bad")), "--quiet"])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains("estimate_constants") && stderr(&o).contains("residence_factor"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn a_measured_map_is_warned_outside_the_calibration_and_a_paper_like_box_is_not() {
    let dir = tempfile::tempdir().unwrap();
    // The paper's spectrum in the calibration's box proportions (λ_u = Lx/4, λ_l = 16 px).
    let paper = "units = \"reduced\"\n[surface]\ngrid = 128\nlength = 0.03125\nhurst = 0.7\n\
        lambda_lower = 0.00390625\nlambda_upper = 0.0078125\nrms_height = 0.005\nseed = 1\n\
        [material]\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.010\n\
        fracture_energies = [0.25e-6]\n[sliding]\nloads = [1.5e-6]\n";
    let run = file(dir.path(), "paper.toml", paper);
    let o = wearsim()
        .args(["estimate", s(&run), "--out", s(&dir.path().join("paper")), "--quiet"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let summary = std::fs::read_to_string(dir.path().join("paper/summary.json")).unwrap();
    assert!(!summary.contains("not calibrated there"), "{summary}");
    // The same surfaces read from files: outside, said with what to do.
    let o = wearsim()
        .args(["surface", s(&run), "--out", s(&dir.path().join("maps"))])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let files = file(
        dir.path(),
        "files.toml",
        &paper.replace(
            "grid = 128\nlength = 0.03125\nhurst = 0.7\nlambda_lower = 0.00390625\nlambda_upper = 0.0078125\nrms_height = 0.005\nseed = 1\n",
            "top = \"maps/top.npy\"\nbottom = \"maps/bottom.npy\"\nlength = 0.03125\n",
        ),
    );
    let o = wearsim()
        .args(["estimate", s(&files), "--out", s(&dir.path().join("files")), "--quiet"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("files/summary.json")).unwrap()).unwrap();
    let warnings = summary["warnings"].to_string();
    assert!(
        warnings.contains("read from height-map files") && warnings.contains("estimate-check STUDY --out CHECK --fit"),
        "{warnings}"
    );
}
