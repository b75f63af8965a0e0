//! Cost estimates before the work: `slide --dry-run` and `study run --dry-run` print the wall time
//! and peak memory and write nothing; the calibration is made once and then read from the cache.

use crate::common;

use common::{file, run_file, s, stderr, wearsim, GENERATED};

#[test]
fn dry_runs_print_the_estimate_and_write_nothing_and_the_calibration_is_cached() {
    let dir = tempfile::tempdir().unwrap();
    let cache = dir.path().join("cache");
    let run = run_file(dir.path(), &format!("{GENERATED}[sliding]\nloads = [1e-3, 2e-3]\n"));
    let out = dir.path().join("out");
    let dry = |args: &[&str]| {
        wearsim()
            .args(args)
            .env("XDG_CACHE_HOME", &cache)
            .env_remove("WEARSIM_NO_ESTIMATE")
            .output()
            .unwrap()
    };
    let first = dry(&["slide", s(&run), "--out", s(&out), "--dry-run"]);
    let text = stderr(&first);
    assert!(first.status.success(), "{text}");
    assert!(text.contains("calibrating this machine"), "{text}");
    // 64²: 4 running-in steps of 4 px and 16 of 1 px per load, two loads.
    assert!(
        text.contains("estimate: 40 steps at 64×64") && text.contains("peak memory"),
        "{text}"
    );
    assert!(text.contains("--time=") && text.contains("--mem="), "{text}");
    assert!(!out.exists(), "a dry run made its output folder");
    // A run prints the estimate (from the cache) before the work, unless told not to.
    let real = dry(&["slide", s(&run), "--out", s(&out)]);
    let text = stderr(&real);
    assert!(real.status.success() && out.join("summary.json").is_file(), "{text}");
    assert!(
        text.contains("estimate: 40 steps") && !text.contains("calibrating"),
        "{text}"
    );
    let quiet = wearsim()
        .args(["slide", s(&run), "--out", s(&out), "--overwrite"])
        .env("XDG_CACHE_HOME", &cache)
        .output()
        .unwrap();
    assert!(quiet.status.success(), "{}", stderr(&quiet));
    assert!(!stderr(&quiet).contains("estimate:"), "{}", stderr(&quiet));
    let cached: Vec<_> = std::fs::read_dir(cache.join("wearsim")).unwrap().collect();
    assert_eq!(cached.len(), 1, "{cached:?}");
    // The second estimate reads the cache.
    let second = dry(&["slide", s(&run), "--out", s(&out), "--dry-run"]);
    assert!(
        second.status.success() && !stderr(&second).contains("calibrating"),
        "{}",
        stderr(&second)
    );
    // A dry run says what the run would warn about before its first step: d* against the pixel
    // (0.74 px here) and against the box (the second 𝒢's d* is 1.15 box lengths), no load to raise.
    let coarse = file(
        dir.path(),
        "coarse.toml",
        &format!(
            "{}[sliding]\nloads = [1e-3]\n",
            GENERATED.replace("fracture_energies = [0.5e-6]", "fracture_energies = [0.5e-6, 50e-6]")
        ),
    );
    let third = dry(&["slide", s(&coarse), "--out", s(&out), "--dry-run"]);
    let text = stderr(&third);
    assert!(third.status.success(), "{text}");
    assert!(
        text.contains("warning: d* = 1.1538e-2 for 𝒢 = 5.0000e-7 is 0.74 pixels"),
        "{text}"
    );
    assert!(
        text.contains("is 1.15 times the box's shorter side") && text.contains("no particle forms at any load"),
        "{text}"
    );
    // A study's jobs.
    let study = file(
        dir.path(),
        "study.toml",
        &format!(
            "{}[sliding]\nloads = [1e-3, 2e-3]\n",
            GENERATED.replace("seed = 1", "seed = [1, 2]")
        ),
    );
    let folder = dir.path().join("study");
    let o = dry(&[
        "study",
        "run",
        s(&study),
        "--out",
        s(&folder),
        "--dry-run",
        "--jobs",
        "1",
    ]);
    let text = stderr(&o);
    assert!(o.status.success(), "{text}");
    assert!(
        text.contains("estimate: 4 jobs") && text.contains("CPU hours"),
        "{text}"
    );
    assert!(!folder.exists(), "a dry run made the study folder");
    // A cache edited by hand (one exponent) is set aside with a note and the machine calibrated
    // again: never an estimate from the edited numbers.
    let cached = cached[0].as_ref().unwrap().path();
    let text = std::fs::read_to_string(&cached).unwrap();
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let a = serde_json::to_string(&json["seconds_per_iteration"]["settled-map"]).unwrap();
    assert!(a.contains("e-"), "{a}");
    let edited = text.replacen(&a, &a.replace("e-", "e-1"), 1);
    assert_ne!(edited, text);
    std::fs::write(&cached, edited).unwrap();
    let o = dry(&["slide", s(&run), "--out", s(&out), "--dry-run"]);
    let text = stderr(&o);
    assert!(o.status.success(), "{text}");
    assert!(
        text.contains("the cached cost calibration is not used: its checksum does not match")
            && text.contains("set aside")
            && text.contains("calibrating this machine")
            && text.contains("estimate: 40 steps"),
        "{text}"
    );
    assert!(cached.with_extension("json.set-aside").is_file() && cached.is_file());
}
