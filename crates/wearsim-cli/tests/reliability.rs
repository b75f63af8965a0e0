//! Reliability: what a user running long studies must never meet — a study that cannot be collected,
//! runs that delete or mix each other's files, results overwritten without a word, garbage passed
//! on silently, a crash or a hang. One test per class, each running the real binary; the test names
//! say what used to break.

use crate::common;

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use common::{file, run, run_file, s, stderr, stdout, wearsim, write_npy, write_npy_raw, GENERATED};

/// A small study: 64², two seeds, two loads, 8 jobs of 20 steps.
const STUDY: &str = r#"
[surface]
grid = 64
lambda_lower = 0.0625
lambda_upper = 0.25
rms_height = 0.005
seed = [1, 2]
[material]
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = [0.008, 0.012]
fracture_energies = [0.25e-6, 1e-6]
[sliding]
loads = [5e-4, 1e-3]
"#;

fn study_run(study: &Path, out: &Path, extra: &[&str]) -> std::process::Output {
    wearsim()
        .args(["study", "run", s(study), "--out", s(out)])
        .args(extra)
        .output()
        .unwrap()
}

fn collect_csv(out: &Path) -> String {
    let o = run(&["study", "collect", s(out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    std::fs::read_to_string(out.join("results.csv")).unwrap()
}

/// The records of a CSV text, each checked to have the header's number of fields.
fn csv_records(text: &str) -> (Vec<String>, Vec<Vec<String>>) {
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    let rows: Vec<Vec<String>> = reader
        .records()
        .map(|r| r.unwrap().iter().map(String::from).collect::<Vec<String>>())
        .collect();
    for r in &rows {
        assert_eq!(
            r.len(),
            header.len(),
            "a row with another number of fields than the header: {r:?}"
        );
    }
    (header, rows)
}

fn column<'a>(header: &[String], rows: &'a [Vec<String>], name: &str) -> Vec<&'a str> {
    let i = header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name}"));
    rows.iter().map(|r| r[i].as_str()).collect()
}

#[test]
fn a_study_whose_results_are_undefined_stays_collectable_and_impossible_ones_are_refused_up_front() {
    let dir = tempfile::tempdir().unwrap();
    // Loads whose mean pressure underflows, a schedule with fewer than two fitted steps: refused
    // before any job runs and before the folder is made.
    for (edit, needle) in [
        (STUDY.replace("loads = [5e-4, 1e-3]", "loads = [5e-324]"), "loads"),
        (
            STUDY.replace(
                "loads = [5e-4, 1e-3]",
                "loads = [1e-3]\ndistance = 0.27\nrunning_in = 0.25",
            ),
            "distance",
        ),
    ] {
        let study = file(dir.path(), "bad.toml", &edit);
        let out = dir.path().join("bad");
        let o = study_run(&study, &out, &[]);
        assert!(!o.status.success() && stderr(&o).contains(needle), "{}", stderr(&o));
        assert!(!out.exists(), "the folder was made for a study refused before its jobs");
    }
    // No particle forms for a huge 𝒢 (d* beyond the box): the fit is undefined, yet the study is
    // finished, collected, plotted and resumed.
    let study = file(
        dir.path(),
        "none.toml",
        &STUDY.replace("[0.25e-6, 1e-6]", "[0.25e-6, 1e-2]"),
    );
    let out = dir.path().join("none");
    assert!(study_run(&study, &out, &[]).status.success());
    let (header, rows) = csv_records(&collect_csv(&out));
    let energies = column(&header, &rows, "fracture_energy");
    let r2 = column(&header, &rows, "wear_rate_r2");
    let warnings = column(&header, &rows, "warnings");
    for ((g, r2), w) in energies.iter().zip(&r2).zip(&warnings) {
        if g.starts_with("1e-2") {
            assert!(
                r2.is_empty() && w.contains("no particle formed"),
                "{g}: R² {r2:?}, warnings {w:?}"
            );
        }
    }
    assert!(run(&["study", "plot", s(&out)]).status.success());
    let again = study_run(&study, &out, &[]);
    assert!(
        again.status.success() && stdout(&again).contains("skipped 8"),
        "{}",
        stdout(&again)
    );
}

#[test]
fn two_runs_and_staggered_shards_on_one_folder_finish_every_job_once() {
    let dir = tempfile::tempdir().unwrap();
    let study = file(
        dir.path(),
        "study.toml",
        &STUDY.replace("seed = [1, 2]", "seed = [1, 2, 3]"),
    );
    let reference = dir.path().join("reference");
    assert!(study_run(&study, &reference, &[]).status.success());
    let expected = collect_csv(&reference);
    let total = 12;
    // Two full runs started together, one job at a time each.
    let both = dir.path().join("both");
    let spawn = |extra: &[&str]| {
        wearsim()
            .args(["study", "run", s(&study), "--out", s(&both), "--jobs", "1"])
            .args(extra)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap()
    };
    let (a, b) = (spawn(&[]), spawn(&[]));
    let (a, b) = (a.wait_with_output().unwrap(), b.wait_with_output().unwrap());
    assert!(a.status.success(), "{}", stderr(&a));
    assert!(b.status.success(), "{}", stderr(&b));
    let computed = |o: &std::process::Output| -> usize {
        let text = stdout(o);
        let at = text.find("computed ").unwrap() + "computed ".len();
        text[at..].split_whitespace().next().unwrap().parse().unwrap()
    };
    assert_eq!(
        computed(&a) + computed(&b),
        total,
        "a job was computed twice or not at all"
    );
    assert_eq!(collect_csv(&both), expected);
    // Eight shards started a few milliseconds apart.
    let sharded = dir.path().join("sharded");
    let children: Vec<_> = (1..=8)
        .map(|k| {
            std::thread::sleep(Duration::from_millis(15));
            wearsim()
                .args([
                    "study",
                    "run",
                    s(&study),
                    "--out",
                    s(&sharded),
                    "--shard",
                    &format!("{k}/8"),
                    "--jobs",
                    "1",
                ])
                .stdout(Stdio::null())
                .stderr(Stdio::piped())
                .spawn()
                .unwrap()
        })
        .collect();
    for child in children {
        let o = child.wait_with_output().unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
    }
    assert_eq!(collect_csv(&sharded), expected);
}

#[test]
fn a_folder_holding_other_results_is_refused_and_a_commands_outputs_appear_together_or_not_at_all() {
    let dir = tempfile::tempdir().unwrap();
    let run_path = run_file(dir.path(), &format!("{GENERATED}[sliding]\nloads = [5e-4, 1e-3]\n"));
    let out = dir.path().join("slide");
    assert!(run(&["slide", s(&run_path), "--out", s(&out)]).status.success());
    let summary = std::fs::read(out.join("summary.json")).unwrap();
    // Another command into the slide's folder: refused, the slide's files untouched.
    let o = run(&["contact", s(&run_path), "--load", "1e-3", "--out", s(&out)]);
    assert!(!o.status.success() && stderr(&o).contains("wearsim slide") && stderr(&o).contains("--overwrite"));
    assert_eq!(std::fs::read(out.join("summary.json")).unwrap(), summary);
    // With --overwrite the folder is replaced whole: no orphan series.csv next to the contact's summary.
    let o = run(&[
        "contact",
        s(&run_path),
        "--load",
        "1e-3",
        "--out",
        s(&out),
        "--overwrite",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(out.join("pressure.npy").is_file() && !out.join("series.csv").exists());
    // A disk that fills up during `slide` (a 2-block file-size limit here) leaves the earlier
    // results as they were, and no half-written folder.
    let full = dir.path().join("full");
    assert!(run(&["slide", s(&run_path), "--out", s(&full)]).status.success());
    let before: Vec<Vec<u8>> = ["summary.json", "series.csv"]
        .iter()
        .map(|f| std::fs::read(full.join(f)).unwrap())
        .collect();
    let script = format!(
        "trap '' XFSZ; ulimit -f 2; exec {} slide {} --out {}",
        env!("CARGO_BIN_EXE_wearsim"),
        s(&run_path),
        s(&full)
    );
    let o = Command::new("sh")
        .args(["-c", &script])
        .env("WEARSIM_NO_ESTIMATE", "1")
        .output()
        .unwrap();
    assert!(!o.status.success(), "the write should have failed");
    let after: Vec<Vec<u8>> = ["summary.json", "series.csv"]
        .iter()
        .map(|f| std::fs::read(full.join(f)).unwrap())
        .collect();
    assert_eq!(before, after);
    assert_eq!(
        std::fs::read_dir(dir.path())
            .unwrap()
            .filter(|e| e.as_ref().unwrap().file_name().to_string_lossy().starts_with('.'))
            .count(),
        0,
        "a temporary folder was left"
    );
    // Two slides with different loads into one folder at once: the folder holds one whole run.
    let other = file(
        dir.path(),
        "other.toml",
        &format!("{GENERATED}[sliding]\nloads = [2e-3]\n"),
    );
    let mixed = dir.path().join("mixed");
    let a = wearsim()
        .args(["slide", s(&run_path), "--out", s(&mixed)])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let b = wearsim()
        .args(["slide", s(&other), "--out", s(&mixed)])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let _ = (a.wait_with_output().unwrap(), b.wait_with_output().unwrap());
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(mixed.join("summary.json")).unwrap()).unwrap();
    let loads: Vec<f64> = summary["inputs"]["sliding"]["loads"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let (header, rows) = csv_records(&std::fs::read_to_string(mixed.join("series.csv")).unwrap());
    let mut in_series: Vec<f64> = column(&header, &rows, "load")
        .iter()
        .map(|v| v.parse().unwrap())
        .collect();
    in_series.dedup();
    assert_eq!(in_series, loads, "series.csv and summary.json come from different runs");
}

#[test]
fn an_output_folder_that_cannot_be_written_is_refused_before_the_computation() {
    let dir = tempfile::tempdir().unwrap();
    let run_path = run_file(dir.path(), &format!("{GENERATED}[sliding]\nloads = [5e-4]\n"));
    let in_the_way = file(dir.path(), "a-file", "x");
    let o = run(&["slide", s(&run_path), "--out", s(&in_the_way)]);
    let err = stderr(&o);
    assert!(
        !o.status.success() && err.contains("a-file") && err.contains("not a folder"),
        "{err}"
    );
    // Nothing was computed: the error is the only thing said (the run prints p_m once it starts).
    assert!(
        !err.contains("flow pressure") && err.trim_end().lines().count() == 1,
        "{err}"
    );
    let o = run(&["slide", s(&run_path), "--out", &format!("{}/below", s(&in_the_way))]);
    assert!(!o.status.success() && stderr(&o).contains("a-file"), "{}", stderr(&o));
}

#[test]
fn a_study_is_tied_to_its_surface_files_and_job_files_are_checked_and_repaired() {
    let dir = tempfile::tempdir().unwrap();
    let surfaces = dir.path().join("surfaces");
    let gen = run_file(dir.path(), GENERATED);
    assert!(run(&["surface", s(&gen), "--out", s(&surfaces)]).status.success());
    let text = format!(
        "[surface]\ntop = \"surfaces/top.npy\"\nbottom = \"surfaces/bottom.npy\"\nlength = 1.0\n{}[sliding]\nloads = [5e-4, 1e-3]\n",
        &GENERATED[GENERATED.find("[material]").unwrap()..]
    );
    let study = file(dir.path(), "files.toml", &text);
    let out = dir.path().join("out");
    assert!(study_run(&study, &out, &["--shard", "1/2"]).status.success());
    // The surface changes between the two halves: another study.
    let top = std::fs::read(surfaces.join("top.npy")).unwrap();
    let mut changed = top.clone();
    let last = changed.len() - 1;
    changed[last] ^= 0x01;
    std::fs::write(surfaces.join("top.npy"), &changed).unwrap();
    let o = study_run(&study, &out, &[]);
    assert!(
        !o.status.success() && stderr(&o).contains("different study"),
        "{}",
        stderr(&o)
    );
    std::fs::write(surfaces.join("top.npy"), &top).unwrap();
    assert!(study_run(&study, &out, &[]).status.success());
    let expected = collect_csv(&out);
    // A job file cut short: recomputed with a warning, the results unchanged.
    let job = out.join("jobs/job-000001.json");
    let full = std::fs::read(&job).unwrap();
    std::fs::write(&job, &full[..full.len() / 2]).unwrap();
    let o = run(&["study", "collect", s(&out)]);
    assert!(!o.status.success() && stderr(&o).contains("job-000001.json") && stderr(&o).contains("recomputes it"));
    // The file is named once.
    assert_eq!(stderr(&o).matches("job-000001.json").count(), 1, "{}", stderr(&o));
    let o = study_run(&study, &out, &[]);
    assert!(
        o.status.success() && stderr(&o).contains("recomputed") && stdout(&o).contains("computed 1 jobs"),
        "{}",
        stderr(&o)
    );
    assert_eq!(collect_csv(&out), expected);
    // Another job's file is named as such, not blamed on another version of the study.
    std::fs::copy(out.join("jobs/job-000000.json"), &job).unwrap();
    let o = study_run(&study, &out, &[]);
    let err = stderr(&o);
    assert!(
        !o.status.success() && err.contains("holds the result of job 0") && !err.contains("version"),
        "{err}"
    );
    std::fs::write(&job, &full).unwrap();
    // Collecting needs no surface file at its original place.
    std::fs::rename(&surfaces, dir.path().join("moved")).unwrap();
    assert_eq!(collect_csv(&out), expected);
}

#[test]
fn material_names_with_commas_and_quotes_keep_every_csv_row_whole_and_newlines_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let text = STUDY
        .replace("seed = [1, 2]", "seed = 1")
        .replace("[material]\n", "[[materials]]\nname = \"steel, \\\"hard\\\" rolled\"\n");
    let study = file(dir.path(), "names.toml", &text);
    let out = dir.path().join("out");
    let o = study_run(&study, &out, &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (header, rows) = csv_records(&collect_csv(&out));
    assert!(column(&header, &rows, "material")
        .iter()
        .all(|m| *m == "steel, \"hard\" rolled"));
    let aggregated = std::fs::read_to_string(out.join("results_aggregated.csv")).unwrap();
    let (header, rows) = csv_records(&aggregated);
    assert!(column(&header, &rows, "material").iter().all(|m| m.contains("rolled")));
    // A newline would start a line of findings.md that reads like another material's.
    let study = file(dir.path(), "newline.toml", &text.replace(" rolled", "\\nrolled"));
    let o = study_run(&study, &dir.path().join("newline"), &[]);
    assert!(!o.status.success() && stderr(&o).contains("`name`"), "{}", stderr(&o));
}

#[test]
fn garbage_inputs_are_errors_not_silent_results() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(String, &[&str], &str); 6] = [
        // Fewer than two steps after running-in: W would be NaN.
        (
            format!("{GENERATED}[sliding]\nloads = [1e-3]\ndistance = 0.27\nrunning_in = 0.25\n"),
            &["slide"],
            "distance",
        ),
        // A band of wavelengths with no Fourier mode: an all-NaN surface.
        (
            GENERATED
                .replace("lambda_lower = 0.0625", "lambda_lower = 0.3")
                .replace("lambda_upper = 0.25", "lambda_upper = 0.31"),
            &["surface"],
            "no Fourier mode",
        ),
        // Heights whose squares overflow.
        (
            GENERATED.replace("rms_height = 0.005", "rms_height = 1e300"),
            &["surface"],
            "rms_height",
        ),
        // A side length whose area overflows: named, not "invalid load 0".
        (
            format!(
                "{}[sliding]\nloads = [1e-3]\n",
                GENERATED
                    .replace("length = 1.0", "length = 1e300")
                    .replace("lambda_lower = 0.0625", "lambda_lower = 6.25e298")
                    .replace("lambda_upper = 0.25", "lambda_upper = 2.5e299")
                    .replace("rms_height = 0.005", "rms_height = 5e297")
            ),
            &["slide"],
            "length",
        ),
        // Zero loads in a run file.
        (format!("{GENERATED}[sliding]\nloads = [5e-324]\n"), &["slide"], "loads"),
        (
            format!("{GENERATED}[sliding]\nloads = [1e-3]\n"),
            &["contact", "--load", "1e-3", "--offset", "1e20"],
            "one period",
        ),
    ];
    for (text, args, needle) in cases {
        let run_path = run_file(dir.path(), &text);
        let out = dir.path().join("o");
        let o = wearsim()
            .args(&args[..1])
            .arg(s(&run_path))
            .args(&args[1..])
            .args(["--out", s(&out)])
            .output()
            .unwrap();
        let err = stderr(&o);
        assert!(!o.status.success(), "{args:?} {needle}: exited 0");
        assert!(
            err.contains(needle) && err.trim_end().lines().count() == 1,
            "{args:?} {needle}: {err}"
        );
        assert!(!out.exists(), "{args:?}: output written despite the error");
    }
    // Offsets: a fraction of a pixel is rounded with a note; --offset-px takes pixels.
    let run_path = run_file(dir.path(), GENERATED);
    let o = run(&[
        "contact",
        s(&run_path),
        "--load",
        "1e-3",
        "--offset",
        "0.031",
        "--out",
        s(&dir.path().join("a")),
    ]);
    assert!(
        o.status.success() && stderr(&o).contains("using 2 pixels"),
        "{}",
        stderr(&o)
    );
    let o = run(&[
        "contact",
        s(&run_path),
        "--load",
        "1e-3",
        "--offset-px",
        "2",
        "--out",
        s(&dir.path().join("b")),
    ]);
    assert!(o.status.success());
    assert_eq!(
        std::fs::read(dir.path().join("a/pressure.npy")).unwrap(),
        std::fs::read(dir.path().join("b/pressure.npy")).unwrap()
    );
}

#[test]
fn degenerate_results_say_so() {
    let dir = tempfile::tempdir().unwrap();
    // λ_l of two pixels and a d* far beyond the box: warnings on stderr and in summary.json, and the
    // wear-rate fit is undefined rather than R² = 1.
    let text = format!(
        "{}[sliding]\nloads = [5e-4]\n",
        GENERATED
            .replace("lambda_lower = 0.0625", "lambda_lower = 0.03125")
            .replace("[0.5e-6]", "[1e-2]")
    );
    let run_path = run_file(dir.path(), &text);
    let out = dir.path().join("o");
    let o = run(&["slide", s(&run_path), "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains("warning: λ_l") && err.contains("no particle formed"),
        "{err}"
    );
    assert!(stdout(&o).contains("R² = undefined"), "{}", stdout(&o));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert!(summary["results"][0]["wear_rate_r2"].is_null());
    assert!(summary["warnings"].as_array().unwrap().len() >= 2);
    // d* of under four pixels.
    let small = run_file(
        dir.path(),
        &format!(
            "{}[sliding]\nloads = [5e-4]\n",
            GENERATED.replace("[0.5e-6]", "[0.05e-6]")
        ),
    );
    let o = run(&["slide", s(&small), "--out", s(&dir.path().join("small"))]);
    assert!(
        o.status.success() && stderr(&o).contains("pixels, under 4"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn huge_sizes_are_refused_with_the_memory_they_need_instead_of_aborting() {
    let dir = tempfile::tempdir().unwrap();
    for grid in ["100000", "40000"] {
        let text = format!(
            "{}[sliding]\nloads = [1e-3]\n",
            GENERATED.replace("grid = 64", &format!("grid = {grid}"))
        );
        let run_path = run_file(dir.path(), &text);
        for command in ["slide", "surface"] {
            let out = dir.path().join("o");
            let o = run(&[command, s(&run_path), "--out", s(&out)]);
            let err = stderr(&o);
            assert_eq!(o.status.code(), Some(1), "{command} {grid}: {err}");
            assert!(err.contains("GiB") && err.contains("grid"), "{command} {grid}: {err}");
            assert!(!out.exists());
        }
        let study = file(
            dir.path(),
            "big.toml",
            &STUDY.replace("grid = 64", &format!("grid = {grid}")),
        );
        let out = dir.path().join("study");
        let o = study_run(&study, &out, &[]);
        assert!(
            o.status.code() == Some(1) && stderr(&o).contains("GiB"),
            "{}",
            stderr(&o)
        );
        assert!(!out.exists(), "the study folder was made before the refusal");
    }
    // A .npy header that promises more than the file holds.
    write_npy(&dir.path().join("top.npy"), &[16, 16], &[0.0; 256]);
    let mut bytes = std::fs::read(dir.path().join("top.npy")).unwrap();
    let at = bytes.windows(8).position(|w| w == b"(16, 16)").unwrap();
    bytes[at..at + 8].copy_from_slice(b"(99999, ");
    let end = bytes[at..].iter().position(|&b| b == b'}').unwrap() + at;
    bytes[at + 8..end].copy_from_slice(
        &b"99999), "[..end - at - 8]
            .iter()
            .copied()
            .chain(std::iter::repeat(b' '))
            .take(end - at - 8)
            .collect::<Vec<_>>(),
    );
    std::fs::write(dir.path().join("top.npy"), &bytes).unwrap();
    write_npy(&dir.path().join("bottom.npy"), &[16, 16], &[0.0; 256]);
    let read = format!(
        "[surface]\ntop = \"top.npy\"\nbottom = \"bottom.npy\"\nlength = 1.0\n{}",
        &GENERATED[GENERATED.find("[material]").unwrap()..]
    );
    let run_path = run_file(dir.path(), &read);
    let o = run(&[
        "contact",
        s(&run_path),
        "--load",
        "1e-3",
        "--out",
        s(&dir.path().join("c")),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("top.npy"), "{}", stderr(&o));
    let o = run(&["bench", "--sizes", "100000"]);
    assert!(
        o.status.code() == Some(1) && stderr(&o).contains("GiB"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn thousands_of_threads_are_capped_instead_of_hanging() {
    let dir = tempfile::tempdir().unwrap();
    let run_path = run_file(dir.path(), &format!("{GENERATED}[sliding]\nloads = [1e-3]\n"));
    let mut child = wearsim()
        .args([
            "--threads",
            "3000",
            "slide",
            s(&run_path),
            "--out",
            s(&dir.path().join("o")),
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(120) {
            child.kill().unwrap();
            panic!("`--threads 3000` hangs");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let o = child.wait_with_output().unwrap();
    assert!(
        o.status.success() && stderr(&o).contains("four per core"),
        "{}",
        stderr(&o)
    );
    let o = run(&[
        "--threads",
        "0",
        "slide",
        s(&run_path),
        "--out",
        s(&dir.path().join("z")),
    ]);
    assert!(!o.status.success() && stderr(&o).contains("threads"));
}

#[test]
fn a_failing_job_does_not_stop_the_others_and_keeps_its_cause() {
    let dir = tempfile::tempdir().unwrap();
    // Half the jobs may take one solver iteration only: they cannot converge.
    let study = file(
        dir.path(),
        "study.toml",
        &format!("{STUDY}[contact]\nmax_iterations = [1, 20000]\n"),
    );
    let out = dir.path().join("out");
    let o = study_run(&study, &out, &[]);
    let err = stderr(&o);
    assert!(!o.status.success(), "{err}");
    assert!(
        err.contains("8 of 16 jobs failed") && err.contains("did not converge") && err.contains("study job 0"),
        "{err}"
    );
    let done = std::fs::read_dir(out.join("jobs"))
        .unwrap()
        .filter(|e| e.as_ref().unwrap().file_name().to_string_lossy().ends_with(".json"))
        .count();
    assert_eq!(done, 8, "the converging jobs were not all finished");
    // A new run retries only the failed jobs.
    let o = study_run(&study, &out, &[]);
    assert!(!o.status.success() && stderr(&o).contains("8 of 16 jobs failed"));
}

#[test]
fn small_things_that_used_to_slip_through() {
    let dir = tempfile::tempdir().unwrap();
    // A study with no job.
    let o = study_run(
        &file(dir.path(), "empty.toml", &STUDY.replace("seed = [1, 2]", "seed = []")),
        &dir.path().join("e"),
        &[],
    );
    assert!(
        !o.status.success() && stderr(&o).contains("no jobs") && stderr(&o).contains("surface.seed"),
        "{}",
        stderr(&o)
    );
    // A material name that is not text.
    let o = study_run(
        &file(
            dir.path(),
            "name.toml",
            &STUDY.replace("[material]\n", "[material]\nname = 5\n"),
        ),
        &dir.path().join("n"),
        &[],
    );
    assert!(
        !o.status.success() && stderr(&o).contains("`name` must be a string"),
        "{}",
        stderr(&o)
    );
    // An animation delay beyond what a GIF stores.
    let run_path = run_file(dir.path(), &format!("{GENERATED}[sliding]\nloads = [1e-3]\n"));
    let o = run(&[
        "animate",
        s(&run_path),
        "--out",
        s(&dir.path().join("a.gif")),
        "--delay",
        "700000",
    ]);
    assert!(!o.status.success() && stderr(&o).contains("--delay"), "{}", stderr(&o));
    // Contact maps: NaN is refused; integer and float32 maps are read.
    let nan: Vec<f64> = (0..256)
        .map(|k| if k == 17 { f64::NAN } else { (k % 3) as f64 })
        .collect();
    write_npy(&dir.path().join("nan.npy"), &[16, 16], &nan);
    let o = run(&[
        "junctions",
        s(&dir.path().join("nan.npy")),
        "--out",
        s(&dir.path().join("j0")),
    ]);
    assert!(!o.status.success() && stderr(&o).contains("NaN"), "{}", stderr(&o));
    let ints: Vec<u8> = (0..256i32).flat_map(|k| ((k % 5 == 0) as i32).to_le_bytes()).collect();
    write_npy_raw(&dir.path().join("int.npy"), "<i4", &[16, 16], &ints);
    let floats: Vec<u8> = (0..256)
        .flat_map(|k| (((k % 5 == 0) as u8) as f32).to_le_bytes())
        .collect();
    write_npy_raw(&dir.path().join("f32.npy"), "<f4", &[16, 16], &floats);
    for (map, out) in [("int.npy", "j1"), ("f32.npy", "j2")] {
        let o = run(&["junctions", s(&dir.path().join(map)), "--out", s(&dir.path().join(out))]);
        assert!(o.status.success(), "{map}: {}", stderr(&o));
    }
    assert_eq!(
        std::fs::read(dir.path().join("j1/labels.npy")).unwrap(),
        std::fs::read(dir.path().join("j2/labels.npy")).unwrap()
    );
    // A file in the way of a study folder: the message names it, with no debug dump.
    let blocker = file(dir.path(), "blocker", "x");
    let o = study_run(&file(dir.path(), "ok.toml", STUDY), &blocker.join("sub"), &[]);
    let err = stderr(&o);
    assert!(
        !o.status.success() && err.contains("blocker") && !err.contains("Os {"),
        "{err}"
    );
    // The benchmark names what it needs, not a parameter the user never set.
    let o = run(&["bench", "--sizes", "16"]);
    assert!(
        !o.status.success() && stderr(&o).contains("64 pixels") && !stderr(&o).contains("lambda_upper"),
        "{}",
        stderr(&o)
    );
    // No timing to take a median of: an error naming the option, not a panic.
    let o = run(&["bench", "--sizes", "64", "--passes", "--fft-repeats", "0"]);
    assert!(
        !o.status.success() && stderr(&o).contains("--fft-repeats 0") && !stderr(&o).contains("panicked"),
        "{}",
        stderr(&o)
    );
    // A Slurm array with a step: the shard is the task's position in the array.
    let study = file(dir.path(), "slurm.toml", STUDY);
    let o = wearsim()
        .args(["study", "run", s(&study), "--out", s(&dir.path().join("slurm"))])
        .env("SLURM_ARRAY_TASK_ID", "3")
        .env("SLURM_ARRAY_TASK_COUNT", "4")
        .env("SLURM_ARRAY_TASK_MIN", "1")
        .env("SLURM_ARRAY_TASK_MAX", "7")
        .env("SLURM_ARRAY_TASK_STEP", "2")
        .output()
        .unwrap();
    assert!(o.status.success() && stderr(&o).contains("shard 2/4"), "{}", stderr(&o));
}

#[test]
fn ctrl_c_and_sigterm_stop_cleanly_and_the_study_resumes() {
    use std::os::unix::process::CommandExt;
    let dir = tempfile::tempdir().unwrap();
    // The signals at their default disposition (a background shell starts tests with SIGINT ignored).
    let wearsim = || {
        let mut c = wearsim();
        // SAFETY: signal(2) between fork and exec.
        unsafe {
            c.pre_exec(|| {
                libc::signal(libc::SIGINT, libc::SIG_DFL);
                libc::signal(libc::SIGTERM, libc::SIG_DFL);
                Ok(())
            });
        }
        c
    };
    let signal = |pid: u32, name: &str| {
        assert!(Command::new("kill")
            .args([&format!("-{name}"), &pid.to_string()])
            .status()
            .unwrap()
            .success());
    };
    // A slide interrupted part-way: status 130, neither its folder nor a temporary one left, only
    // the checkpoint it saved on the way out.
    let text = format!(
        "{}[sliding]\nloads = [5e-4, 1e-3, 2e-3]\ndistance = 1.0\nrunning_in = 0.5\n",
        GENERATED
            .replace("grid = 64", "grid = 256")
            .replace("lambda_lower = 0.0625", "lambda_lower = 0.03125")
    );
    let run_path = run_file(dir.path(), &text);
    let out = dir.path().join("slide");
    let child = wearsim()
        .args(["slide", s(&run_path), "--out", s(&out)])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(700));
    signal(child.id(), "INT");
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(130), "{}", stderr(&o));
    let left: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .collect();
    assert!(
        !out.exists() && left.iter().all(|f| !f.starts_with('.') || f == ".slide.checkpoint"),
        "{left:?}"
    );
    // A study stopped by SIGTERM: finished job files stay, claims are released, a new run finishes.
    let study = file(dir.path(), "study.toml", &STUDY.replace("grid = 64", "grid = 128"));
    let reference = dir.path().join("reference");
    assert!(study_run(&study, &reference, &["--jobs", "1"]).status.success());
    let out = dir.path().join("study");
    let child = wearsim()
        .args(["study", "run", s(&study), "--out", s(&out), "--jobs", "1"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while std::fs::read_dir(out.join("jobs"))
        .map(|d| {
            d.filter(|e| e.as_ref().unwrap().file_name().to_string_lossy().ends_with(".json"))
                .count()
        })
        .unwrap_or(0)
        < 1
    {
        assert!(start.elapsed() < Duration::from_secs(60));
        std::thread::sleep(Duration::from_millis(5));
    }
    signal(child.id(), "TERM");
    let o = child.wait_with_output().unwrap();
    if o.status.code() == Some(128 + libc::SIGTERM) {
        let files: Vec<String> = std::fs::read_dir(out.join("jobs"))
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
            .collect();
        assert!(
            files
                .iter()
                .all(|f| (f.ends_with(".json") || f.ends_with(".checkpoint")) && !f.starts_with('.')),
            "{files:?}"
        );
    } else {
        assert!(o.status.success(), "{}", stderr(&o)); // it finished before the signal arrived
    }
    assert!(study_run(&study, &out, &[]).status.success());
    assert_eq!(collect_csv(&out), collect_csv(&reference));
}
