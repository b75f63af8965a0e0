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
    // A cache that is no calibration (damaged, edited by hand) is set aside with a note and the
    // machine calibrated: never an estimate from it (the library's tests edit one number too). The
    // file is the one this test's thread count gives, as the program's does.
    let cached_path = wearsim::cost::Calibration::cache_path(&cache.join("wearsim"));
    std::fs::create_dir_all(cached_path.parent().unwrap()).unwrap();
    std::fs::write(&cached_path, "{\"format\": 1, \"seconds_per_iteration\": \"edited\"}").unwrap();
    let first = dry(&["slide", s(&run), "--out", s(&out), "--dry-run"]);
    let text = stderr(&first);
    assert!(first.status.success(), "{text}");
    assert!(
        text.contains("the cached cost calibration is not used: it is not a calibration this wearsim reads")
            && text.contains("set aside")
            && text.contains("calibrating this machine"),
        "{text}"
    );
    assert!(cached_path.with_extension("json.set-aside").is_file() && cached_path.is_file());
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
    let cached: Vec<_> = std::fs::read_dir(cache.join("wearsim"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    assert_eq!(cached, std::slice::from_ref(&cached_path));
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
        text.contains("estimate: 4 jobs") && text.contains("CPU hours") && !text.contains("calibrating"),
        "{text}"
    );
    assert!(!folder.exists(), "a dry run made the study folder");
    // A study's dry run prints its conversions (hardness, pressures) and what its jobs would warn
    // about before their first step, each line once with its jobs: the harder material's d* is
    // under a pixel in both of its jobs, the softer one's (5.2 px) warns in none.
    let study = file(
        dir.path(),
        "si-study.toml",
        &format!(
            "{}hardness = [5e9, 40e9]\nfracture_toughness = [1e6]\n[sliding]\npressures = [2e8, 4e8]\n",
            common::SI_SIC
        ),
    );
    let o = dry(&["study", "run", s(&study), "--out", s(&folder), "--dry-run"]);
    let text = stderr(&o);
    assert!(o.status.success() && !text.contains("calibrating"), "{text}");
    assert!(
        text.contains("hardness H = 5.0000e9 Pa") && text.contains("(jobs 0–1 (2 of 4))"),
        "{text}"
    );
    assert!(
        text.contains("pressure p_N = 2.0000e8 Pa") && text.contains("(jobs 0, 2 (2 of 4))"),
        "{text}"
    );
    let warned: Vec<&str> = text.lines().filter(|l| l.starts_with("warning: d* = ")).collect();
    assert_eq!(warned.len(), 1, "{text}");
    assert!(
        warned[0].contains("pixels") && warned[0].ends_with("(jobs 2–3 (2 of 4))"),
        "{text}"
    );
    assert!(!folder.exists(), "a dry run made the study folder");
}
