//! A closed pipe — `wearsim … | head -2`, `| less` quit early, `| grep -m1` — stops nothing: every
//! command run with its stdout and stderr on pipes whose reader has gone finishes, writes its
//! results and exits as if nothing had been printed (not 101, "failed printing to stdout: Broken
//! pipe", with no results); an error or a stop signal still exits with its own status.

use crate::common;

use std::path::Path;
use std::process::{ExitStatus, Stdio};
use std::time::{Duration, Instant};

use common::{file, run_file, GENERATED};

/// Runs `wearsim args` in `dir` with stdout and stderr on pipes closed at once (progress as lines).
fn closed(dir: &Path, args: &[&str]) -> ExitStatus {
    let mut child = common::wearsim()
        .current_dir(dir)
        .arg("--log")
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    drop(child.stderr.take());
    child.wait().unwrap()
}

#[track_caller]
fn finishes(dir: &Path, args: &[&str], results: &[&str]) {
    let status = closed(dir, args);
    assert_eq!(status.code(), Some(0), "{args:?}: {status:?}");
    for r in results {
        assert!(dir.join(r).exists(), "{args:?} did not write {r}");
    }
}

#[test]
fn every_command_finishes_and_writes_its_results_when_its_output_pipes_are_closed() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    run_file(d, &format!("{GENERATED}[sliding]\nloads = [1e-3]\ndistance = 0.5\n"));
    finishes(d, &["surface", "run.toml", "--out", "surf"], &["surf/top.npy"]);
    finishes(
        d,
        &["surface", "fit", "surf/top.npy", "--length", "1", "--out", "fit"],
        &["fit/fit.json", "fit/surface.toml"],
    );
    finishes(
        d,
        &["contact", "run.toml", "--load", "1e-3", "--out", "contact"],
        &["contact/summary.json", "contact/contact.npy"],
    );
    finishes(
        d,
        &["junctions", "contact/contact.npy", "--out", "junctions"],
        &["junctions/junctions.json"],
    );
    finishes(
        d,
        &["slide", "run.toml", "--out", "slide"],
        &["slide/summary.json", "slide/series.csv"],
    );
    finishes(
        d,
        &["estimate", "run.toml", "--out", "estimate"],
        &["estimate/summary.json"],
    );
    finishes(d, &["animate", "run.toml", "--out", "slide.gif"], &["slide.gif"]);
    let study = format!("{GENERATED}[sliding]\nloads = [1e-3]\n").replace("seed = 1", "seed = [1, 2]");
    file(d, "study.toml", &study);
    finishes(d, &["study", "run", "study.toml", "--out", "st"], &["st/jobs"]);
    finishes(d, &["study", "collect", "st"], &["st/results.csv"]);
    finishes(
        d,
        &["study", "plot", "st", "--figures", "fig4,appF"],
        &["st/figures/findings.md"],
    );
    finishes(
        d,
        &["estimate-check", "st", "--out", "check", "--min-particles", "1"],
        &["check/comparison.csv"],
    );
    finishes(
        d,
        &[
            "bench",
            "--sizes",
            "64",
            "--fft-repeats",
            "1",
            "--passes",
            "--json",
            "bench.json",
        ],
        &["bench.json"],
    );
    finishes(
        d,
        &[
            "bench-slide",
            "--n",
            "64",
            "--warm-n",
            "64",
            "--warm-steps",
            "1",
            "--estimate-samples",
            "1",
        ],
        &[],
    );
}

#[test]
fn an_error_or_a_stop_on_closed_pipes_keeps_its_own_exit_status() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // The error line cannot be printed: still the error's status, 1.
    run_file(d, "[surface]\ngrid = 3\n");
    assert_eq!(closed(d, &["slide", "run.toml", "--out", "o"]).code(), Some(1));
    // The stop signal's message cannot be printed: still 128 + the signal, its folder not left.
    let big = GENERATED
        .replace("grid = 64", "grid = 2048")
        .replace("lambda_lower = 0.0625", "lambda_lower = 0.0078125");
    run_file(d, &big);
    let mut child = common::wearsim()
        .current_dir(d)
        .args(["surface", "run.toml", "--out", "surf"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    drop(child.stderr.take());
    let start = Instant::now();
    while !d.join(".surf.claim").exists() {
        assert!(start.elapsed() < Duration::from_secs(60), "no claim appeared");
        std::thread::sleep(Duration::from_millis(2));
    }
    // SAFETY: kill(2) on our own child's pid.
    assert_eq!(unsafe { libc::kill(child.id() as i32, libc::SIGTERM) }, 0);
    let status = child.wait().unwrap();
    if status.code() != Some(0) {
        assert_eq!(status.code(), Some(128 + libc::SIGTERM), "{status:?}");
        assert!(!d.join("surf").exists());
    }
}
