//! Long runs that resume: `slide` and study jobs killed (SIGKILL, as a Slurm wall-time limit does)
//! after a checkpoint, then run again by the same command, give the results of an uninterrupted run
//! byte for byte, and leave no checkpoint behind.

use crate::common;

use std::path::Path;
use std::process::Stdio;
use std::time::{Duration, Instant};

use common::{file, run, s, stderr, wearsim};

/// 128², three loads: long enough (a few seconds) to be killed part-way.
const RUN: &str = r#"
[surface]
grid = 128
length = 1.0
lambda_lower = 0.0625
lambda_upper = 0.25
rms_height = 0.005
seed = 3
[material]
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = 0.01
fracture_energies = [0.25e-6, 1e-6]
[sliding]
loads = [5e-4, 1e-3, 2e-3]
"#;

/// Starts `args`, kills it with SIGKILL as soon as `checkpoint` exists; false when the command
/// finished first.
fn kill_after_checkpoint(args: &[&str], checkpoint: &Path, delay: Duration) -> bool {
    let mut child = wearsim()
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let start = Instant::now();
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            assert!(status.success(), "{args:?} failed on its own");
            return false;
        }
        if checkpoint.exists() {
            std::thread::sleep(delay);
            child.kill().unwrap();
            let status = child.wait().unwrap();
            return !status.success();
        }
        assert!(start.elapsed() < Duration::from_secs(300), "{args:?} hangs");
        std::thread::sleep(Duration::from_millis(2));
    }
}

#[test]
fn a_slide_killed_after_a_checkpoint_resumes_to_the_same_series_byte_for_byte() {
    let dir = tempfile::tempdir().unwrap();
    let run_toml = file(dir.path(), "run.toml", RUN);
    let reference = dir.path().join("reference");
    let o = run(&["slide", s(&run_toml), "--out", s(&reference), "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        !dir.path().join(".reference.checkpoint").exists(),
        "a finished run leaves its checkpoint"
    );
    let expected = std::fs::read_to_string(reference.join("series.csv")).unwrap();
    let out = dir.path().join("killed");
    let checkpoint = dir.path().join(".killed.checkpoint");
    let args = [
        "slide",
        s(&run_toml),
        "--out",
        s(&out),
        "--quiet",
        "--checkpoint-every",
        "0s",
    ];
    let mut killed = 0;
    for delay_ms in [0, 30, 90, 200] {
        let _ = std::fs::remove_dir_all(&out);
        if !kill_after_checkpoint(&args, &checkpoint, Duration::from_millis(delay_ms)) {
            continue;
        }
        killed += 1;
        assert!(checkpoint.exists() && !out.join("series.csv").exists());
        let again = wearsim().args(args).output().unwrap();
        assert!(again.status.success(), "{}", stderr(&again));
        assert!(
            stderr(&again).contains("resuming from the checkpoint after"),
            "{}",
            stderr(&again)
        );
        let series = std::fs::read_to_string(out.join("series.csv")).unwrap();
        assert!(series == expected, "resumed series differs from the uninterrupted one");
        assert!(!checkpoint.exists(), "the checkpoint outlives the finished run");
    }
    assert!(killed > 0, "no run was killed part-way: every run finished first");
    // A checkpoint of other inputs is set aside with a reason, and the run starts over.
    let _ = std::fs::remove_dir_all(&out);
    assert!(kill_after_checkpoint(&args, &checkpoint, Duration::ZERO));
    let other = file(dir.path(), "run.toml", &RUN.replace("seed = 3", "seed = 4"));
    let o = wearsim()
        .args(["slide", s(&other), "--out", s(&out), "--quiet"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("checkpoint not used") && stderr(&o).contains("other inputs"),
        "{}",
        stderr(&o)
    );
    assert!(!checkpoint.exists());
}

#[test]
fn a_study_job_killed_after_a_checkpoint_resumes_to_the_same_job_file_results() {
    let dir = tempfile::tempdir().unwrap();
    let study = file(dir.path(), "study.toml", &RUN.replace("[5e-4, 1e-3, 2e-3]", "[1e-3]"));
    let reference = dir.path().join("reference");
    let o = run(&["study", "run", s(&study), "--out", s(&reference), "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let collect = |out: &Path| {
        let o = run(&["study", "collect", s(out)]);
        assert!(o.status.success(), "{}", stderr(&o));
        std::fs::read_to_string(out.join("results.csv")).unwrap()
    };
    let expected = collect(&reference);
    let out = dir.path().join("killed");
    let checkpoint = out.join("jobs").join("job-000000.checkpoint");
    let args = [
        "study",
        "run",
        s(&study),
        "--out",
        s(&out),
        "--quiet",
        "--checkpoint-every",
        "0s",
    ];
    let mut killed = 0;
    for delay_ms in [0, 50] {
        let _ = std::fs::remove_dir_all(&out);
        if !kill_after_checkpoint(&args, &checkpoint, Duration::from_millis(delay_ms)) {
            continue;
        }
        killed += 1;
        let again = wearsim().args(args).output().unwrap();
        assert!(again.status.success(), "{}", stderr(&again));
        assert!(!checkpoint.exists(), "the checkpoint outlives the finished job");
        // The tables hold the results, not the timings: equal byte for byte.
        assert!(
            collect(&out) == expected,
            "resumed job differs from the uninterrupted one"
        );
    }
    assert!(killed > 0, "no study was killed part-way");
}
