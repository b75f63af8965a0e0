//! Folders and files that are not wearsim's: a folder is a command's only when it is empty or carries
//! that command's marker (and holds only what it wrote); no command writes over a file it did not
//! make — an input, another command's output, the user's own — without `--overwrite`, however the
//! path is spelled; temporary files and claims of failed or killed runs never block or litter later
//! runs. Each test runs the real binary and fails on the behaviour it replaced.

use crate::common;

use std::path::Path;

use common::{file, run, run_file, s, stderr, wearsim, GENERATED};

/// A 64² study of two jobs.
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
shear_strength = 0.01
fracture_energies = [0.25e-6]
[sliding]
loads = [1e-3]
distance = 0.5
"#;

fn sliding() -> String {
    format!("{GENERATED}[sliding]\nloads = [1e-3]\ndistance = 0.5\n")
}

fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .collect();
    names.sort();
    names
}

#[test]
fn a_study_never_adopts_a_folder_of_the_users_nor_another_commands() {
    let dir = tempfile::tempdir().unwrap();
    let study = file(dir.path(), "s.toml", STUDY);
    // The user's own results.csv, which `study collect` would replace.
    let mine = dir.path().join("mine");
    std::fs::create_dir(&mine).unwrap();
    std::fs::write(mine.join("results.csv"), "my,own\n").unwrap();
    let o = run(&["study", "run", s(&study), "--out", s(&mine)]);
    assert!(!o.status.success(), "adopted the user's folder");
    assert!(stderr(&o).contains("did not write"), "{}", stderr(&o));
    assert_eq!(listing(&mine), ["results.csv"]);
    assert_eq!(std::fs::read_to_string(mine.join("results.csv")).unwrap(), "my,own\n");
    // A slide's folder is the slide's.
    let run_path = run_file(dir.path(), &sliding());
    let slid = dir.path().join("slid");
    assert!(run(&["slide", s(&run_path), "--out", s(&slid)]).status.success());
    let o = run(&["study", "run", s(&study), "--out", s(&slid)]);
    assert!(
        !o.status.success() && stderr(&o).contains("`wearsim slide`"),
        "{}",
        stderr(&o)
    );
    // A study folder is resumed, a new or empty one taken.
    let empty = dir.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    for _ in 0..2 {
        let o = run(&["study", "run", s(&study), "--out", s(&empty)]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    // A slide into the finished study is refused naming the study, its jobs kept.
    let o = run(&["slide", s(&run_path), "--out", s(&empty)]);
    assert!(
        !o.status.success() && stderr(&o).contains("`wearsim study run`"),
        "{}",
        stderr(&o)
    );
    assert_eq!(listing(&empty.join("jobs")).len(), 2);
}

#[test]
fn files_the_user_put_in_an_output_folder_are_never_replaced_with_it() {
    let dir = tempfile::tempdir().unwrap();
    let run_path = run_file(dir.path(), &sliding());
    let out = dir.path().join("out");
    assert!(run(&["slide", s(&run_path), "--out", s(&out)]).status.success());
    std::fs::write(out.join("notes.txt"), "what I saw").unwrap();
    let o = run(&["slide", s(&run_path), "--out", s(&out)]);
    assert!(
        !o.status.success() && stderr(&o).contains("notes.txt"),
        "{}",
        stderr(&o)
    );
    assert_eq!(std::fs::read_to_string(out.join("notes.txt")).unwrap(), "what I saw");
    // Without the user's file the same command replaces its folder; --overwrite replaces it anyway.
    let o = run(&["slide", s(&run_path), "--out", s(&out), "--overwrite"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!out.join("notes.txt").exists());
    let o = run(&["slide", s(&run_path), "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn animate_never_writes_over_its_inputs_or_a_file_it_did_not_make() {
    let dir = tempfile::tempdir().unwrap();
    // A run file whose name ends in .gif, given as --out under other spellings: never replaced.
    let run_path = file(dir.path(), "run.gif", &sliding());
    let text = std::fs::read_to_string(&run_path).unwrap();
    let link = dir.path().join("link.gif");
    std::os::unix::fs::symlink(&run_path, &link).unwrap();
    for out in ["run.gif", "./run.gif", "link.gif"] {
        let o = wearsim()
            .current_dir(dir.path())
            .args(["animate", "run.gif", "--out", out, "--overwrite"])
            .output()
            .unwrap();
        assert!(!o.status.success(), "--out {out} replaced the run file");
        assert!(stderr(&o).contains("input"), "{}", stderr(&o));
        assert_eq!(std::fs::read_to_string(&run_path).unwrap(), text);
    }
    // A GIF wearsim did not write is kept without --overwrite; one it wrote is replaced.
    let theirs = dir.path().join("theirs.gif");
    std::fs::write(&theirs, b"GIF89a not ours").unwrap();
    let o = run(&["animate", s(&run_path), "--out", s(&theirs)]);
    assert!(
        !o.status.success() && stderr(&o).contains("--overwrite"),
        "{}",
        stderr(&o)
    );
    assert_eq!(std::fs::read(&theirs).unwrap(), b"GIF89a not ours");
    let ours = dir.path().join("ours.gif");
    // A partial GIF of a killed run of this host, whose process is gone, is removed.
    let host = std::fs::read_to_string("/proc/sys/kernel/hostname").unwrap();
    let partial = dir.path().join(format!(".ours.gif.{}.4000000000-0.tmp", host.trim()));
    std::fs::write(&partial, b"GIF89a half").unwrap();
    for _ in 0..2 {
        let o = run(&["animate", s(&run_path), "--out", s(&ours)]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    assert!(!partial.exists(), "the killed run's partial GIF stays");
    let gif = std::fs::read(&ours).unwrap();
    assert!(gif.starts_with(b"GIF89a") && gif.ends_with(b";"));
}

#[test]
fn fields_to_netcdf_never_writes_into_its_store() {
    let dir = tempfile::tempdir().unwrap();
    let run_path = run_file(dir.path(), &sliding());
    let out = dir.path().join("out");
    let o = run(&["slide", s(&run_path), "--out", s(&out), "--save-fields"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let store = out.join("fields.zarr");
    let attrs = std::fs::read(store.join(".zattrs")).unwrap();
    for target in [store.join(".zattrs"), store.join("pressure/../.zgroup")] {
        let o = run(&["fields", "to-netcdf", s(&store), s(&target), "--overwrite"]);
        assert!(!o.status.success() && stderr(&o).contains("input"), "{}", stderr(&o));
    }
    assert_eq!(std::fs::read(store.join(".zattrs")).unwrap(), attrs);
}

#[test]
fn a_file_in_the_way_of_an_output_folder_is_named_in_words() {
    let dir = tempfile::tempdir().unwrap();
    let run_path = run_file(dir.path(), &sliding());
    let afile = file(dir.path(), "afile", "x");
    let o = run(&["slide", s(&run_path), "--out", s(&afile.join("sub"))]);
    let e = stderr(&o);
    assert!(
        !o.status.success() && e.contains("afile: is a file, not a folder"),
        "{e}"
    );
    assert!(!e.contains("os error"), "{e}");
    // A study folder whose `jobs` is a file.
    let study = file(dir.path(), "s.toml", STUDY);
    let folder = dir.path().join("study");
    std::fs::create_dir(&folder).unwrap();
    std::fs::write(folder.join("jobs"), "").unwrap();
    let o = run(&["study", "run", s(&study), "--out", s(&folder)]);
    let e = stderr(&o);
    assert!(
        !o.status.success() && e.contains("jobs") && e.contains("no study folder"),
        "{e}"
    );
    assert!(!e.contains("os error"), "{e}");
}

#[test]
fn a_claim_that_a_full_disk_left_empty_never_blocks_the_retry() {
    let dir = tempfile::tempdir().unwrap();
    let run_path = run_file(dir.path(), &sliding());
    let out = dir.path().join("out");
    // A file-size limit of 0: the claim is created but cannot be filled (as on a full disk).
    let o = std::process::Command::new("sh")
        .arg("-c")
        .arg(format!(
            "trap '' XFSZ; ulimit -f 0; exec {} slide {} --out {}",
            env!("CARGO_BIN_EXE_wearsim"),
            s(&run_path),
            s(&out)
        ))
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(
        listing(dir.path()).iter().all(|f| !f.ends_with(".claim")),
        "{:?}",
        listing(dir.path())
    );
    // The retry, at once, is not refused as "another run is writing this folder".
    let o = run(&["slide", s(&run_path), "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn a_checkpoints_temporary_file_cut_by_a_kill_is_removed_by_the_next_run() {
    let dir = tempfile::tempdir().unwrap();
    let run_path = run_file(dir.path(), &sliding());
    let host = std::fs::read_to_string("/proc/sys/kernel/hostname").unwrap();
    // A save of `.out.checkpoint` cut short by a kill, its process gone; and one of a live process
    // (this test's), which must stay.
    let gone = dir
        .path()
        .join(format!("..out.checkpoint.{}.4000000000-0.tmp", host.trim()));
    let live = dir
        .path()
        .join(format!("..out.checkpoint.{}.{}-0.tmp", host.trim(), std::process::id()));
    for partial in [&gone, &live] {
        std::fs::write(partial, b"wearsim sliding checkpoint, cut").unwrap();
    }
    let out = dir.path().join("out");
    let o = run(&["slide", s(&run_path), "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!gone.exists(), "the killed save's temporary file stays");
    assert!(live.exists(), "a live process's temporary file was removed");
    std::fs::remove_file(&live).unwrap();
    assert_eq!(listing(dir.path()), ["out", "run.toml"]);
}

/// This host's name, as wearsim writes it in claims.
fn host() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .unwrap()
        .trim()
        .to_string()
}

/// Writes a claim file holding `owner` and sets its modification time `age` in the past.
fn claim(path: &Path, owner: &str, age: std::time::Duration) {
    std::fs::write(path, owner).unwrap();
    let f = std::fs::OpenOptions::new().append(true).open(path).unwrap();
    f.set_modified(std::time::SystemTime::now() - age).unwrap();
}

/// Start time of process `pid` in clock ticks since boot (field 22 of /proc/PID/stat).
fn start_ticks(pid: u32) -> String {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).unwrap();
    let after = &stat[stat.rfind(')').unwrap() + 1..];
    after.split_whitespace().nth(19).unwrap().to_string()
}

#[test]
fn a_claim_whose_process_id_now_belongs_to_another_process_is_taken_over() {
    let dir = tempfile::tempdir().unwrap();
    let study = file(dir.path(), "s.toml", STUDY);
    let out = dir.path().join("study");
    let jobs = out.join("jobs");
    std::fs::create_dir_all(&jobs).unwrap();
    // An unrelated live process holds the process id the claims name.
    let mut sleeper = std::process::Command::new("sleep").arg("60").spawn().unwrap();
    let pid = sleeper.id();
    let twenty_minutes = std::time::Duration::from_secs(1200);
    // Job 0: a claim written long ago and not refreshed since (a killed run's, its id reused).
    claim(
        &jobs.join("job-000000.claim"),
        &format!("{} {pid}\n", host()),
        twenty_minutes,
    );
    // Job 1: a fresh claim whose process started at another time than the one holding the id now.
    claim(
        &jobs.join("job-000001.claim"),
        &format!("{} {pid} 1\n", host()),
        std::time::Duration::ZERO,
    );
    let o = run(&["study", "run", s(&study), "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(common::stdout(&o).contains("computed 2 jobs"), "{}", common::stdout(&o));
    assert!(jobs.join("job-000000.json").is_file() && jobs.join("job-000001.json").is_file());
    assert!(
        !listing(&jobs).iter().any(|f| f.ends_with(".claim")),
        "{:?}",
        listing(&jobs)
    );
    // A live claim (the right process, refreshed) is left to its holder, and the run says that the
    // job is not computed and who holds it.
    std::fs::remove_file(jobs.join("job-000001.json")).unwrap();
    let live = jobs.join("job-000001.claim");
    claim(
        &live,
        &format!("{} {pid} {}\n", host(), start_ticks(pid)),
        std::time::Duration::ZERO,
    );
    let o = run(&["study", "run", s(&study), "--out", s(&out)]);
    let e = stderr(&o);
    assert!(
        e.contains("1 jobs of this shard are not computed")
            && e.contains(&format!("job 1: process {pid} on"))
            && e.contains("job-000001.claim"),
        "{e}"
    );
    assert!(!jobs.join("job-000001.json").exists() && live.exists());
    let _ = sleeper.kill();
    let _ = sleeper.wait();
}

#[test]
fn an_output_claim_not_refreshed_for_long_is_taken_over_whatever_its_process_id() {
    let dir = tempfile::tempdir().unwrap();
    let run_path = run_file(dir.path(), &sliding());
    let out = dir.path().join("out");
    let mut sleeper = std::process::Command::new("sleep").arg("60").spawn().unwrap();
    claim(
        &dir.path().join(".out.claim"),
        &format!("{} {}\n", host(), sleeper.id()),
        std::time::Duration::from_secs(1200),
    );
    let o = run(&["slide", s(&run_path), "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(out.join("summary.json").is_file());
    // A fresh claim of the same live process with a wrong start time: another process, taken over.
    claim(
        &dir.path().join(".out.claim"),
        &format!("{} {} 1\n", host(), sleeper.id()),
        std::time::Duration::ZERO,
    );
    let o = run(&["slide", s(&run_path), "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let _ = sleeper.kill();
    let _ = sleeper.wait();
}
