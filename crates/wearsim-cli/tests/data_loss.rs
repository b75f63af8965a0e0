//! Data loss: studies that could not be collected for the way their paths were spelled, two runs
//! mixing or deleting each other's results in one folder, `--overwrite` deleting the run's inputs,
//! staging folders of killed runs left forever. One test per class, each running the real binary.

use crate::common;

use std::path::Path;
use std::process::Output;

use common::{file, run, s, stderr, stdout, wearsim, GENERATED};

/// A study on the measured surfaces a.npy and b.npy of its folder, one load.
const MEASURED_STUDY: &str = r#"
[surface]
top = "a.npy"
bottom = "b.npy"
length = 1.0
[material]
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = 0.01
fracture_energies = [0.5e-6]
[sliding]
loads = [1e-3]
distance = 0.25
running_in = 0.125
"#;

/// `wearsim args…` run in `cwd`.
fn run_in(cwd: &Path, args: &[&str]) -> Output {
    wearsim().current_dir(cwd).args(args).output().unwrap()
}

fn ok(o: &Output) -> bool {
    o.status.success()
}

/// A folder `m` holding a.npy and b.npy (a generated 64² pair) and the measured study s.toml.
fn measured_folder(dir: &Path) -> std::path::PathBuf {
    let run_toml = file(dir, "gen.toml", GENERATED);
    let pair = dir.join("pair");
    assert!(ok(&run(&["surface", s(&run_toml), "--out", s(&pair), "--quiet"])));
    let m = dir.join("m");
    std::fs::create_dir(&m).unwrap();
    std::fs::copy(pair.join("top.npy"), m.join("a.npy")).unwrap();
    std::fs::copy(pair.join("bottom.npy"), m.join("b.npy")).unwrap();
    file(&m, "s.toml", MEASURED_STUDY);
    m
}

#[test]
fn a_study_on_measured_surfaces_is_collected_however_its_path_was_spelled() {
    let dir = tempfile::tempdir().unwrap();
    let m = measured_folder(dir.path());
    let collect_and_plot = |cwd: &Path, out: &str| {
        for verb in ["collect", "plot"] {
            let o = run_in(cwd, &["study", verb, out]);
            assert!(ok(&o), "study {verb} {out} (in {}): {}", cwd.display(), stderr(&o));
        }
    };
    // Relative study paths, from the study's folder and from its parent.
    for (cwd, study, out) in [
        (&m, "s.toml", "o1"),
        (&m, "./s.toml", "o2"),
        (&dir.path().to_path_buf(), "m/s.toml", "o3"),
        (&dir.path().to_path_buf(), "./m/../m/s.toml", "o4"),
    ] {
        let o = run_in(cwd, &["study", "run", study, "--out", out, "--quiet"]);
        assert!(ok(&o), "study run {study}: {}", stderr(&o));
        collect_and_plot(cwd, out);
    }
    // A list axis of files.
    file(
        &m,
        "axis.toml",
        &MEASURED_STUDY.replace("top = \"a.npy\"", "top = [\"a.npy\", \"./b.npy\"]"),
    );
    assert!(ok(&run_in(
        &m,
        &["study", "run", "axis.toml", "--out", "o5", "--quiet"]
    )));
    collect_and_plot(&m, "o5");
    // Started through an absolute path, resumed through a relative one: nothing to recompute.
    let absolute = m.join("s.toml");
    assert!(ok(&run_in(
        dir.path(),
        &["study", "run", s(&absolute), "--out", "m/o6", "--quiet"]
    )));
    let again = run_in(&m, &["study", "run", "s.toml", "--out", "o6", "--quiet"]);
    assert!(
        ok(&again) && stdout(&again).contains("skipped 1"),
        "{}{}",
        stdout(&again),
        stderr(&again)
    );
    collect_and_plot(&m, "o6");
}

/// A 64² generated run with a short schedule: a second or so.
const SLIDE: &str = r#"
[surface]
grid = 64
length = 1.0
lambda_lower = 0.0625
lambda_upper = 0.25
rms_height = 0.005
seed = 1
[material]
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = 0.01
fracture_energies = [0.5e-6]
[sliding]
loads = [5e-4, 1e-3]
"#;

fn host() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .unwrap()
        .trim()
        .to_string()
}

/// Entries of `dir` whose names start with `prefix`.
fn named(dir: &Path, prefix: &str) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .filter(|n| n.starts_with(prefix))
        .collect()
}

#[test]
fn two_different_studies_started_at_once_into_one_folder_never_mix() {
    let dir = tempfile::tempdir().unwrap();
    let a = file(dir.path(), "a.toml", SLIDE);
    let b = file(dir.path(), "b.toml", &SLIDE.replace("[5e-4, 1e-3]", "[5e-4, 2e-3]"));
    for trial in 0..3 {
        let out = dir.path().join(format!("o{trial}"));
        let spawn = |study: &Path| {
            wearsim()
                .args(["study", "run", s(study), "--out", s(&out), "--quiet"])
                .stdout(std::process::Stdio::null())
                .stderr(std::process::Stdio::piped())
                .spawn()
                .unwrap()
        };
        let (pa, pb) = (spawn(&a), spawn(&b));
        let (oa, ob) = (pa.wait_with_output().unwrap(), pb.wait_with_output().unwrap());
        assert!(
            oa.status.success() != ob.status.success(),
            "exactly one study owns the folder: {} / {}",
            stderr(&oa),
            stderr(&ob)
        );
        let (winner, loser, load) = if oa.status.success() {
            (&a, &ob, "1e-3")
        } else {
            (&b, &oa, "2e-3")
        };
        assert!(stderr(loser).contains("different study"), "{}", stderr(loser));
        let o = run(&["study", "collect", s(&out)]);
        assert!(ok(&o), "{}", stderr(&o));
        let table = std::fs::read_to_string(out.join("results.csv")).unwrap();
        assert!(
            table.contains(load),
            "{} won, yet its load {load} is missing",
            winner.display()
        );
        // The winner resumes its own folder once the other is gone.
        let again = run(&["study", "run", s(winner), "--out", s(&out), "--quiet"]);
        assert!(ok(&again) && stdout(&again).contains("skipped 2"), "{}", stderr(&again));
    }
}

#[test]
fn different_commands_into_one_new_out_at_once_leave_one_whole_result() {
    let dir = tempfile::tempdir().unwrap();
    let run_toml = file(dir.path(), "run.toml", SLIDE);
    for trial in 0..3 {
        let out = dir.path().join(format!("o{trial}"));
        let commands: [&[&str]; 3] = [
            &["slide", s(&run_toml), "--out", s(&out), "--quiet"],
            &["surface", s(&run_toml), "--out", s(&out), "--quiet"],
            &[
                "contact",
                s(&run_toml),
                "--load",
                "1e-3",
                "--offset-px",
                "0",
                "--out",
                s(&out),
                "--quiet",
            ],
        ];
        let children: Vec<_> = commands
            .iter()
            .map(|args| {
                wearsim()
                    .args(*args)
                    .stdout(std::process::Stdio::null())
                    .stderr(std::process::Stdio::piped())
                    .spawn()
                    .unwrap()
            })
            .collect();
        let outputs: Vec<Output> = children.into_iter().map(|c| c.wait_with_output().unwrap()).collect();
        let winners: Vec<&str> = commands
            .iter()
            .zip(&outputs)
            .filter(|(_, o)| o.status.success())
            .map(|(args, _)| args[0])
            .collect();
        assert_eq!(
            winners.len(),
            1,
            "{winners:?}: {:?}",
            outputs.iter().map(stderr).collect::<Vec<_>>()
        );
        for o in outputs.iter().filter(|o| !o.status.success()) {
            let e = stderr(o);
            assert!(
                e.contains("another wearsim run") || e.contains("holds the results of"),
                "{e}"
            );
        }
        let marker = std::fs::read_to_string(out.join(".wearsim.json")).unwrap();
        assert!(marker.contains(&format!("\"{}\"", winners[0])), "{marker}");
        assert!(
            named(dir.path(), &format!(".o{trial}.")).is_empty(),
            "claims or staging folders left"
        );
    }
}

#[test]
fn an_out_that_is_or_holds_an_input_is_refused_however_it_is_spelled() {
    let dir = tempfile::tempdir().unwrap();
    let m = measured_folder(dir.path());
    let run_toml = file(
        &m,
        "run.toml",
        &MEASURED_STUDY.replace("loads = [1e-3]", "loads = [1e-3]\n"),
    );
    std::os::unix::fs::symlink(&m, dir.path().join("link")).unwrap();
    let before = named(&m, "");
    let m_slash = format!("{}/", m.display());
    let spellings: [(&Path, &str); 6] = [
        (&m, "."),
        (&m, "./"),
        (&m, m_slash.as_str()),
        (&m, "../m"),
        (&m, "../link"),
        (&m, ".."),
    ];
    for (cwd, out) in spellings {
        for overwrite in [true, false] {
            let mut args = vec!["slide", "run.toml", "--out", out, "--quiet"];
            if overwrite {
                args.push("--overwrite");
            }
            let o = run_in(cwd, &args);
            let e = stderr(&o);
            assert!(!ok(&o) && e.contains("holds the input"), "--out {out}: {e}");
            assert!(!e.contains("not a file path"), "{e}");
        }
    }
    // Surfaces named by the run file count too, and so does the study file.
    let o = run_in(
        dir.path(),
        &["surface", "m/run.toml", "--out", "m", "--overwrite", "--quiet"],
    );
    assert!(!ok(&o) && stderr(&o).contains("holds the input"), "{}", stderr(&o));
    let o = run_in(&m, &["study", "run", "s.toml", "--out", ".", "--quiet"]);
    assert!(!ok(&o) && stderr(&o).contains("holds the input"), "{}", stderr(&o));
    assert_eq!(named(&m, ""), before, "an input folder changed");
    // `--out .` in a folder without inputs: a clear word about the current folder.
    let empty = dir.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    let o = run_in(&empty, &["slide", s(&run_toml), "--out", ".", "--quiet"]);
    assert!(!ok(&o) && stderr(&o).contains("current folder"), "{}", stderr(&o));
}

#[test]
fn staging_folders_of_killed_runs_are_removed_by_the_next_run_but_never_another_hosts() {
    let dir = tempfile::tempdir().unwrap();
    let run_toml = file(dir.path(), "run.toml", &SLIDE.replace("grid = 64", "grid = 128"));
    let out = dir.path().join("out");
    let mut child = wearsim()
        .args(["slide", s(&run_toml), "--out", s(&out), "--quiet", "--save-fields"])
        .spawn()
        .unwrap();
    let pid = child.id();
    let staging = loop {
        let found: Vec<String> = named(dir.path(), ".out.")
            .into_iter()
            .filter(|n| n.ends_with(".tmp"))
            .collect();
        if let Some(n) = found.first() {
            break n.clone();
        }
        assert!(
            child.try_wait().unwrap().is_none(),
            "the run ended before its staging folder was seen"
        );
        std::thread::sleep(std::time::Duration::from_millis(2));
    };
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(
        staging.contains(&format!(".{}.{pid}-", host())),
        "{staging} names neither host nor process"
    );
    assert!(dir.path().join(&staging).exists());
    let elsewhere = dir.path().join(".out.node-elsewhere.12-0.tmp");
    std::fs::create_dir(&elsewhere).unwrap();
    let o = run(&["slide", s(&run_toml), "--out", s(&out), "--quiet"]);
    assert!(ok(&o), "{}", stderr(&o));
    assert!(
        !dir.path().join(&staging).exists(),
        "the killed run's staging folder stays"
    );
    assert!(elsewhere.exists(), "another host's staging folder was removed");
}

/// The bytes of every file under `dir`, by path.
fn snapshot(dir: &Path) -> Vec<(std::path::PathBuf, Vec<u8>)> {
    let mut files = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else {
                files.push((p.clone(), std::fs::read(&p).unwrap()));
            }
        }
    }
    files.sort();
    files
}

#[test]
fn estimate_check_never_writes_over_the_study_it_reads_nor_compares_changed_surfaces() {
    let dir = tempfile::tempdir().unwrap();
    let m = measured_folder(dir.path());
    file(
        &m,
        "s.toml",
        &MEASURED_STUDY.replace("running_in = 0.125", "running_in = 0.125\nestimate_samples = 2"),
    );
    let o = run_in(&m, &["study", "run", "s.toml", "--out", "st", "--quiet"]);
    assert!(ok(&o), "{}", stderr(&o));
    let before = snapshot(dir.path());
    // The study folder, its job folder (and a folder inside it), the folder of its surface files,
    // however spelled, and with --overwrite: refused, nothing touched.
    for out in [
        "st/jobs",
        "st/jobs/",
        "./st/jobs",
        "st/../st/jobs",
        "st",
        "st/",
        ".",
        "..",
        "st/jobs/check",
    ] {
        for overwrite in [false, true] {
            let mut args = vec!["estimate-check", "st", "--out", out, "--quiet"];
            if overwrite {
                args.push("--overwrite");
            }
            let o = run_in(&m, &args);
            assert!(!ok(&o), "estimate-check --out {out} was not refused");
            let e = stderr(&o);
            assert!(
                e.contains("input") || e.contains("job folder") || e.contains("current folder"),
                "{out}: {e}"
            );
            assert_eq!(
                snapshot(dir.path()),
                before,
                "--out {out} (overwrite {overwrite}) changed files"
            );
        }
    }
    // From the parent folder, the surfaces' folder itself.
    let o = run_in(
        dir.path(),
        &["estimate-check", "m/st", "--out", "m", "--overwrite", "--quiet"],
    );
    assert!(!ok(&o) && stderr(&o).contains("holds the input"), "{}", stderr(&o));
    assert_eq!(snapshot(dir.path()), before);
    // A folder of its own: the study's estimate_samples is used (2 static maps per job).
    let o = run_in(
        &m,
        &[
            "estimate-check",
            "st",
            "--out",
            "check",
            "--min-particles",
            "0",
            "--quiet",
        ],
    );
    assert!(ok(&o), "{}", stderr(&o));
    let csv = std::fs::read_to_string(m.join("check/comparison.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let maps = header.iter().position(|c| *c == "static_maps").unwrap();
    for line in csv.lines().skip(1) {
        assert_eq!(line.split(',').nth(maps), Some("2"), "{csv}");
    }
    // A surface file changed since the study ran: refused, naming it, rather than comparing maps of
    // the new surfaces with sliding runs of the old.
    let mut bytes = std::fs::read(m.join("a.npy")).unwrap();
    let last = bytes.len() - 3;
    bytes[last] ^= 0x40;
    std::fs::write(m.join("a.npy"), bytes).unwrap();
    let o = run_in(&m, &["estimate-check", "st", "--out", "check2", "--quiet"]);
    assert!(!ok(&o), "estimate-check compared changed surfaces");
    assert!(stderr(&o).contains("changed since its jobs were run"), "{}", stderr(&o));
    assert!(!m.join("check2").exists());
}
