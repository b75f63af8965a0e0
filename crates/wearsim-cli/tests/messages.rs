//! Inputs a user gets wrong, and the one-line error that names the input and the fix (each case
//! reproduced from a trial of the CLI as a user would try it).

use crate::common;

use common::{file, run, s, stderr, wearsim, GENERATED};

/// Runs `wearsim args` expecting failure; returns its one-line error.
fn fails(args: &[&str]) -> String {
    let o = run(args);
    assert!(!o.status.success(), "{args:?} succeeded");
    let e = stderr(&o);
    assert_eq!(e.trim_end().lines().count(), 1, "error is not one line: {e}");
    e
}

#[test]
fn zero_jobs_at_once_is_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let study = file(dir.path(), "s.toml", &format!("{GENERATED}[sliding]\nloads = [1e-3]\n"));
    let out = dir.path().join("o");
    let e = fails(&["study", "run", s(&study), "--out", s(&out), "--jobs", "0"]);
    assert!(e.contains("`jobs`") && e.contains("1 or more"), "{e}");
    assert!(!out.join("jobs").exists());
}

#[test]
fn a_slurm_array_of_zero_tasks_names_the_variable_and_the_fix_not_an_empty_range() {
    let dir = tempfile::tempdir().unwrap();
    let study = file(dir.path(), "s.toml", &format!("{GENERATED}[sliding]\nloads = [1e-3]\n"));
    let out = dir.path().join("o");
    let o = wearsim()
        .args(["study", "run", s(&study), "--out", s(&out)])
        .env("SLURM_ARRAY_TASK_ID", "1")
        .env("SLURM_ARRAY_TASK_COUNT", "0")
        .output()
        .unwrap();
    assert!(!o.status.success());
    let e = stderr(&o);
    assert_eq!(e.trim_end().lines().count(), 1, "{e}");
    assert!(
        e.contains("SLURM_ARRAY_TASK_COUNT = 0") && e.contains("--shard") && !e.contains("1-0"),
        "{e}"
    );
    assert!(!out.join("jobs").exists());
}

#[test]
fn an_animation_into_a_missing_folder_names_the_folder_not_a_temporary_file() {
    let dir = tempfile::tempdir().unwrap();
    let run_file = file(dir.path(), "r.toml", &format!("{GENERATED}[sliding]\nloads = [1e-3]\n"));
    let gif = dir.path().join("missing").join("x.gif");
    let e = fails(&["animate", s(&run_file), "--out", s(&gif)]);
    assert!(
        e.contains("missing") && e.contains("does not exist") && !e.contains(".x.gif") && !e.contains("Os {"),
        "{e}"
    );
}

#[test]
fn surface_fit_lengths_one_or_two_and_positive() {
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("h.npy");
    let h: Vec<f64> = (0..64 * 64)
        .map(|k| ((k % 64) as f64 * 0.3).sin() + ((k / 64) as f64 * 0.2).cos())
        .collect();
    common::write_npy(&map, &[64, 64], &h);
    let e = fails(&[
        "surface",
        "fit",
        s(&map),
        "--length",
        "1",
        "--length",
        "2",
        "--length",
        "3",
    ]);
    assert!(
        e.contains("--length given 3 times") && e.contains("--length LX --length LY"),
        "{e}"
    );
    // A negative length is a value to check, not an unknown option.
    let e = fails(&["surface", "fit", s(&map), "--length", "-1e-3"]);
    assert!(
        e.contains("--length") && e.contains("-0.001") && e.contains("positive") && !e.contains("unexpected"),
        "{e}"
    );
}

#[test]
fn a_negative_load_is_a_value_to_check_not_an_unknown_option() {
    let dir = tempfile::tempdir().unwrap();
    let runf = common::run_file(dir.path(), GENERATED);
    let out = dir.path().join("o");
    let e = fails(&["contact", s(&runf), "--load", "-1e-3", "--out", s(&out)]);
    assert!(e.contains("load") && !e.contains("unexpected argument"), "{e}");
}

#[test]
fn study_axes_that_repeat_or_could_be_rectangles_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    let seeds = GENERATED.replace("seed = 1", "seed = [1, 1, 2]");
    let study = file(dir.path(), "s.toml", &format!("{seeds}[sliding]\nloads = [1e-3]\n"));
    let e = fails(&["study", "run", s(&study), "--out", s(&out)]);
    assert!(e.contains("surface.seed") && e.contains("twice"), "{e}");
    let rect = GENERATED.replace("grid = 64", "grid = [64, 32]");
    let study = file(dir.path(), "r.toml", &format!("{rect}[sliding]\nloads = [1e-3]\n"));
    let e = fails(&["study", "run", s(&study), "--out", s(&out)]);
    assert!(e.contains("ambiguous") && e.contains("grid = [[64, 32]]"), "{e}");
    let units = file(
        dir.path(),
        "u.toml",
        &format!("units = [\"si\", \"reduced\"]\n{GENERATED}[sliding]\nloads = [1e-3]\n"),
    );
    let e = fails(&["study", "run", s(&units), "--out", s(&out)]);
    assert!(e.contains("units") && !e.contains("unit variant"), "{e}");
    assert!(!out.exists());
}

#[test]
fn collecting_what_is_not_a_study_folder_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let empty = dir.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    let plain = file(dir.path(), "plain.txt", "x");
    for (path, what) in [
        (empty.as_path(), "holds no study.toml"),
        (plain.as_path(), "is not a folder"),
        (std::path::Path::new("/dev/null"), "is not a folder"),
        (dir.path().join("missing").as_path(), "does not exist"),
    ] {
        for command in ["collect", "plot"] {
            let e = fails(&["study", command, s(path)]);
            assert!(
                e.contains(what) && e.contains("--out folder of a `wearsim study run`"),
                "{e}"
            );
            assert!(
                !e.contains("study.toml: No such file") && !e.contains("os error"),
                "{e}"
            );
        }
    }
}

#[test]
fn a_folder_given_for_a_file_is_said_in_words() {
    let dir = tempfile::tempdir().unwrap();
    let folder = dir.path().join("d");
    std::fs::create_dir(&folder).unwrap();
    let out = dir.path().join("o");
    for args in [
        vec!["slide", s(&folder), "--out", s(&out)],
        vec!["surface", "fit", s(&folder), "--length", "1"],
    ] {
        let e = fails(&args);
        assert!(
            e.contains("is a folder, where a file is needed") && !e.contains("os error"),
            "{e}"
        );
    }
}
