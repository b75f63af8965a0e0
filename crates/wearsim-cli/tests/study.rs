//! Studies through the CLI: a study killed part-way (a real SIGKILL to a real process) resumes to
//! the same results without recomputing finished jobs; shards and worker counts change nothing.

use std::path::{Path, PathBuf};
use std::process::Stdio;
use std::sync::OnceLock;
use std::time::{Duration, Instant};

use crate::common;

use common::wearsim;

const STUDY: &str = r#"
[surface]
grid = 128
lambda_lower = 0.0625
lambda_upper = 0.25
rms_height = 0.005
seed = [1, 2, 3]
[material]
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = [0.008, 0.012]
fracture_energies = [0.25e-6, 1e-6]
[sliding]
loads = [2.5e-4, 5e-4, 1e-3, 2e-3]
"#;

fn run_study(study: &Path, out: &Path, extra: &[&str]) -> String {
    let o = wearsim()
        .args(["study", "run", study.to_str().unwrap(), "--out", out.to_str().unwrap()])
        .args(extra)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8(o.stdout).unwrap()
}

fn collect(out: &Path) -> (String, String) {
    let o = wearsim()
        .args(["study", "collect", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    (
        std::fs::read_to_string(out.join("results.csv")).unwrap(),
        std::fs::read_to_string(out.join("results_aggregated.csv")).unwrap(),
    )
}

fn job_files(out: &Path) -> Vec<String> {
    match std::fs::read_dir(out.join("jobs")) {
        Ok(d) => d
            .flatten()
            .map(|e| e.file_name().to_string_lossy().to_string())
            .collect(),
        Err(_) => Vec::new(),
    }
}

/// The study of [`STUDY`] run whole, one job at a time (`--jobs 1`), and collected: the results
/// that every other way of running it (killed and resumed, sharded, other worker counts, Slurm
/// array tasks) must give. Run once for the tests of this file, in a folder of Cargo's temporary
/// directory that no test changes (a test that damages a study folder works on its own copy).
struct Reference {
    folder: PathBuf,
    tidy: String,
    aggregated: String,
}

fn reference() -> &'static Reference {
    static REFERENCE: OnceLock<Reference> = OnceLock::new();
    REFERENCE.get_or_init(|| {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("study-reference");
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let study = dir.join("study.toml");
        std::fs::write(&study, STUDY).unwrap();
        let folder = dir.join("whole");
        run_study(&study, &folder, &["--jobs", "1"]);
        let (tidy, aggregated) = collect(&folder);
        Reference {
            folder,
            tidy,
            aggregated,
        }
    })
}

/// A copy of the folder `from` (files and subfolders) at `to`.
fn copy_folder(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            copy_folder(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), &target).unwrap();
        }
    }
}

#[test]
fn killed_study_resumes_to_the_same_results() {
    let dir = tempfile::tempdir().unwrap();
    let study = dir.path().join("study.toml");
    std::fs::write(&study, STUDY).unwrap();
    let reference = reference();
    let (tidy_ref, agg_ref) = (reference.tidy.clone(), reference.aggregated.clone());
    let total = job_files(&reference.folder).len();
    assert_eq!(total, 24);

    let out = dir.path().join("killed");
    let mut child = wearsim()
        .args([
            "study",
            "run",
            study.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--jobs",
            "1",
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let start = Instant::now();
    loop {
        let done = job_files(&out)
            .iter()
            .filter(|f| f.ends_with(".json") && !f.starts_with('.'))
            .count();
        // One job at a time: the kill lands after the second job file, well before the 24th.
        if done >= 2 || start.elapsed() > Duration::from_secs(120) {
            break;
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    child.kill().unwrap(); // SIGKILL
    child.wait().unwrap();
    // Finished jobs: their result files (the killed run also leaves the claim of the job it was on).
    let finished: Vec<String> = job_files(&out)
        .into_iter()
        .filter(|f| f.ends_with(".json") && !f.starts_with('.'))
        .collect();
    assert!(
        !finished.is_empty() && finished.len() < total,
        "kill did not land part-way: {} jobs",
        finished.len()
    );
    // Collecting an unfinished study is an error naming what is missing.
    let o = wearsim()
        .args(["study", "collect", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(!o.status.success() && String::from_utf8_lossy(&o.stderr).contains("no result yet"));

    let stdout = run_study(&study, &out, &[]);
    assert!(
        stdout.contains(&format!(
            "computed {} jobs, skipped {}",
            total - finished.len(),
            finished.len()
        )),
        "a finished job was recomputed: {stdout}"
    );
    assert!(
        job_files(&out)
            .iter()
            .all(|f| f.ends_with(".json") && !f.starts_with('.')),
        "partial or claim file left: {:?}",
        job_files(&out)
    );
    assert_eq!(collect(&out), (tidy_ref, agg_ref));
}

#[test]
fn shards_and_worker_counts_give_the_unsharded_results() {
    let dir = tempfile::tempdir().unwrap();
    let study = dir.path().join("study.toml");
    std::fs::write(&study, STUDY).unwrap();
    // The whole study, one job at a time (shared; copied here, as this test damages it below).
    let whole = dir.path().join("whole");
    copy_folder(&reference().folder, &whole);
    let expected = (reference().tidy.clone(), reference().aggregated.clone());
    assert_eq!(collect(&whole), expected, "the copy of the reference collects the same");
    let sharded = dir.path().join("sharded");
    for k in 1..=3 {
        run_study(&study, &sharded, &["--shard", &format!("{k}/3"), "--jobs", "2"]);
    }
    assert_eq!(collect(&sharded), expected);
    // Figures from the collected study: every one as PNG and SVG.
    let o = wearsim()
        .args(["study", "plot", sharded.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for name in [
        "fig2_static_model",
        "fig3_wear_volume",
        "fig4_sliding_wear",
        "fig5_particle_rate",
        "appB_particle_counts",
        "appB_eq5_against_w",
        "appC_junctions",
        "appC_critical_junctions",
        "appF_contact_severity",
        "fig6_kim_comparison",
        "memory_of_initial_contact",
    ] {
        for ext in ["png", "svg", "csv"] {
            let f = sharded.join("figures").join(format!("{name}.{ext}"));
            assert!(
                std::fs::metadata(&f).map(|m| m.len() > 1000).unwrap_or(false),
                "{} missing or empty",
                f.display()
            );
        }
    }
    let findings = std::fs::read_to_string(sharded.join("figures/findings.md")).unwrap();
    // It opens with the count line and one short row per finding; every unit's numbers are in
    // findings_units.csv.
    assert!(
        findings.starts_with("# The paper's findings")
            && findings.contains("independent results (each statistic counted once)")
            && findings.contains(
                "| finding | claim | verdict | holds / contrary / inconclusive / not run in | the deciding unit, 95 % interval |"
            )
            && findings.contains("static model"),
        "{findings}"
    );
    let units = std::fs::read_to_string(sharded.join("figures/findings_units.csv")).unwrap();
    assert!(
        units.starts_with("finding,unit,outcome,quantity,estimate,low,high,n,method,rule,p,p_holm,margin,")
            && units.lines().count() > 10,
        "{units}"
    );
    // A chosen job's series, a chosen set of figures; the folder is replaced whole.
    let o = wearsim()
        .args([
            "study",
            "plot",
            sharded.to_str().unwrap(),
            "--job",
            "5",
            "--figures",
            "fig3,memory",
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let names: Vec<String> = std::fs::read_dir(sharded.join("figures"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .filter(|n| !n.starts_with('.'))
        .collect();
    // Two figures, each as PNG, SVG and its numbers as CSV, findings.md and findings_units.csv.
    assert_eq!(names.len(), 8, "{names:?}");
    assert!(String::from_utf8_lossy(&o.stdout).contains("series of job 5"));
    for bad in [&["--job", "999"][..], &["--figures", "fig9"][..]] {
        let o = wearsim()
            .args(["study", "plot", sharded.to_str().unwrap()])
            .args(bad)
            .output()
            .unwrap();
        assert!(
            !o.status.success() && String::from_utf8_lossy(&o.stderr).contains(bad[0]),
            "{bad:?}"
        );
    }
    // A Slurm job array picks its shard from the environment.
    let slurm = dir.path().join("slurm");
    for id in 1..=2 {
        let o = wearsim()
            .args([
                "study",
                "run",
                study.to_str().unwrap(),
                "--out",
                slurm.to_str().unwrap(),
            ])
            .env("SLURM_ARRAY_TASK_ID", id.to_string())
            .env("SLURM_ARRAY_TASK_COUNT", "2")
            .env("SLURM_ARRAY_TASK_MIN", "1")
            .output()
            .unwrap();
        assert!(o.status.success());
        assert!(String::from_utf8_lossy(&o.stderr).contains(&format!("shard {id}/2 holds 12")));
    }
    assert_eq!(collect(&slurm), expected);
    // A job file can never be attributed to another job.
    std::fs::copy(whole.join("jobs/job-000000.json"), whole.join("jobs/job-000001.json")).unwrap();
    let o = wearsim()
        .args(["study", "collect", whole.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(!o.status.success() && String::from_utf8_lossy(&o.stderr).contains("holds the result of job 0"));
    let o = wearsim()
        .args([
            "study",
            "run",
            study.to_str().unwrap(),
            "--out",
            whole.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(!o.status.success() && String::from_utf8_lossy(&o.stderr).contains("holds the result of job 0"));
    // A changed study file is refused in an existing folder.
    std::fs::write(&study, STUDY.replace("0.012", "0.011")).unwrap();
    let o = wearsim()
        .args([
            "study",
            "run",
            study.to_str().unwrap(),
            "--out",
            whole.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(!o.status.success() && String::from_utf8_lossy(&o.stderr).contains("different study"));
}

/// Two materials on one surface, as in the Kim et al. studies (studies/kim1986*.toml), reduced.
const TWO_MATERIALS: &str = r#"
units = "reduced"
[surface]
grid = 128
lambda_lower = 0.0625
lambda_upper = 0.25
rms_height = 0.005
seed = 1
[[materials]]
name = "ceramicA"
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = 0.008
fracture_energies = [0.25e-6]
[[materials]]
name = "ceramicB"
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = 0.012
fracture_energies = [1e-6]
[sliding]
loads = [5e-4, 2e-3]
"#;

/// Fig. 6: each material its own series; Kim et al.'s band of wear coefficients only for Kim's
/// ceramics (the paper's Table 1), so generic materials get none and the title says so (the band
/// of Kim's ceramics is checked by the plot command's unit tests).
#[test]
fn fig6_draws_each_material_and_kims_band_only_for_kims_ceramics() {
    let dir = tempfile::tempdir().unwrap();
    let study = dir.path().join("study.toml");
    std::fs::write(&study, TWO_MATERIALS).unwrap();
    let out = dir.path().join("out");
    run_study(&study, &out, &[]);
    collect(&out);
    let o = wearsim()
        .args(["study", "plot", out.to_str().unwrap(), "--figures", "fig6"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let svg = std::fs::read_to_string(out.join("figures/fig6_kim_comparison.svg")).unwrap();
    // The SVG backend writes each text on its own line between the tags.
    let texts: Vec<&str> = svg
        .split("<text")
        .skip(1)
        .filter_map(|t| {
            t.split_once('>')
                .map(|(_, rest)| rest.split("</text>").next().unwrap_or("").trim())
        })
        .collect();
    for name in ["ceramicA", "ceramicB"] {
        assert_eq!(
            texts.iter().filter(|t| t.starts_with(&format!("{name}, "))).count(),
            1,
            "one series of {name}: {texts:?}"
        );
    }
    assert!(
        !texts.iter().any(|t| t.starts_with("Kim et al. 1986")),
        "no band for generic materials: {texts:?}"
    );
    assert!(
        texts.iter().any(|t| t.contains("no experimental band")),
        "the title says why: {texts:?}"
    );
    // The legend column is fitted to its longest entry; the panel keeps three quarters of the width.
    let width: f64 = svg
        .split("width=\"")
        .nth(1)
        .and_then(|w| w.split('"').next())
        .and_then(|w| w.parse().ok())
        .unwrap();
    assert!(width >= 1150.0, "{width}");
}
