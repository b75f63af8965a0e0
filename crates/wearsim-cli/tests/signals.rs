//! Stop signals — Ctrl-C (SIGINT), `kill` and a Slurm time limit (SIGTERM), Slurm's `--signal`
//! (SIGUSR1, SIGUSR2) — stop every command promptly and cleanly: a non-zero exit (128 + the signal),
//! nothing half-written, and a long run's state saved on the way out, so that the same command run
//! again resumes to the uninterrupted results byte for byte. The children's signal dispositions are
//! set to the default first: a test started from a background shell inherits SIGINT ignored.

use crate::common;

use std::os::unix::process::CommandExt;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use common::{run, run_file, s, stderr, GENERATED};

/// `wearsim` with the stop signals at their default disposition.
fn wearsim() -> Command {
    let mut c = common::wearsim();
    // SAFETY: signal(2) is async-signal-safe, called between fork and exec.
    unsafe {
        c.pre_exec(|| {
            for sig in [libc::SIGINT, libc::SIGTERM, libc::SIGHUP, libc::SIGUSR1, libc::SIGUSR2] {
                libc::signal(sig, libc::SIG_DFL);
            }
            Ok(())
        });
    }
    c
}

fn send(child: &Child, signal: i32) {
    // SAFETY: kill(2) on our own child's pid.
    assert_eq!(unsafe { libc::kill(child.id() as i32, signal) }, 0);
}

/// Waits until `path` exists (the command is at work), at most a minute.
fn wait_for(path: &Path) {
    let start = Instant::now();
    while !path.exists() {
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "{} never appeared",
            path.display()
        );
        std::thread::sleep(Duration::from_millis(2));
    }
}

fn hidden(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .filter(|n| n.starts_with('.'))
        .collect()
}

/// 256², three loads: a slide of several seconds.
fn long_run() -> String {
    format!(
        "{}[sliding]\nloads = [5e-4, 1e-3, 2e-3]\ndistance = 0.5\n",
        GENERATED.replace("grid = 64", "grid = 256")
    )
}

#[test]
fn a_slide_stopped_by_any_stop_signal_saves_its_state_and_resumes_byte_for_byte() {
    let dir = tempfile::tempdir().unwrap();
    let run_path = run_file(dir.path(), &long_run());
    let reference = dir.path().join("reference");
    let o = run(&["slide", s(&run_path), "--out", s(&reference)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let expected = std::fs::read(reference.join("series.csv")).unwrap();
    let mut stopped = 0;
    for (k, signal) in [libc::SIGTERM, libc::SIGUSR1, libc::SIGUSR2, libc::SIGINT]
        .into_iter()
        .enumerate()
    {
        let out = dir.path().join(format!("stopped{k}"));
        let checkpoint = dir.path().join(format!(".stopped{k}.checkpoint"));
        // Long between checkpoints (as a Slurm job's default five minutes): only the stop saves.
        let args = ["slide", s(&run_path), "--out", s(&out), "--checkpoint-every", "1h"];
        let child = wearsim()
            .args(args)
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // At work (its claim exists from the start), past its first steps.
        wait_for(&dir.path().join(format!(".stopped{k}.claim")));
        std::thread::sleep(Duration::from_millis(600));
        send(&child, signal);
        let stopped_at = Instant::now();
        let o = child.wait_with_output().unwrap();
        assert!(stopped_at.elapsed() < Duration::from_secs(10), "slow to stop");
        if o.status.success() {
            continue; // it finished before the signal: nothing to check
        }
        stopped += 1;
        assert_eq!(o.status.code(), Some(128 + signal), "{}", stderr(&o));
        assert!(stderr(&o).contains("saved the state after"), "{}", stderr(&o));
        assert!(!out.exists(), "a stopped run left its folder");
        assert!(checkpoint.is_file(), "no checkpoint saved on the way out");
        let again = wearsim().args(args).output().unwrap();
        assert!(again.status.success(), "{}", stderr(&again));
        assert!(
            stderr(&again).contains("resuming from the checkpoint"),
            "{}",
            stderr(&again)
        );
        assert_eq!(std::fs::read(out.join("series.csv")).unwrap(), expected);
        assert!(!checkpoint.exists());
    }
    let left = hidden(dir.path());
    assert!(left.is_empty(), "{left:?}");
    assert!(
        stopped >= 2,
        "only {stopped} of 4 runs were stopped part-way: they finished first"
    );
}

#[test]
fn commands_that_do_not_poll_stop_at_once_writing_nothing() {
    let dir = tempfile::tempdir().unwrap();
    // `surface` on a grid large enough to take a while: stopped as soon as it has claimed its folder.
    let big = GENERATED
        .replace("grid = 64", "grid = 2048")
        .replace("lambda_lower = 0.0625", "lambda_lower = 0.0078125");
    let run_path = run_file(dir.path(), &big);
    for signal in [libc::SIGTERM, libc::SIGUSR1, libc::SIGINT] {
        let out = dir.path().join("surface");
        let child = wearsim()
            .args(["surface", s(&run_path), "--out", s(&out)])
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        wait_for(&dir.path().join(".surface.claim"));
        send(&child, signal);
        let o = child.wait_with_output().unwrap();
        if o.status.success() {
            continue;
        }
        assert_eq!(o.status.code(), Some(128 + signal), "{}", stderr(&o));
        assert!(!out.exists(), "a stopped `surface` left its folder");
        let left = hidden(dir.path());
        assert!(left.is_empty(), "{left:?}");
    }
    // `bench`: stopped mid-run, no --json file.
    let json = dir.path().join("bench.json");
    let child = wearsim()
        .args(["bench", "--sizes", "1024,1024,1024", "--json", s(&json)])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(800));
    send(&child, libc::SIGTERM);
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(128 + libc::SIGTERM), "{}", stderr(&o));
    assert!(!json.exists());
}

#[test]
fn a_study_collect_stopped_while_writing_its_tables_leaves_no_temporary_file() {
    use std::os::unix::process::ExitStatusExt;
    let dir = tempfile::tempdir().unwrap();
    let study = common::file(
        dir.path(),
        "s.toml",
        &format!("{GENERATED}[sliding]\nloads = [5e-4, 1e-3]\n").replace("seed = 1", "seed = [1, 2, 3, 4]"),
    );
    let out = dir.path().join("st");
    let o = run(&["study", "run", s(&study), "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    // Stopped at moments spread over its few tens of milliseconds, every half millisecond:
    // results.csv and its aggregate are written (and synced) into temporary files, then renamed
    // together. (Before their temporary files were registered for removal, about one stop in
    // fifty fell into that window and left one.)
    let mut stopped = 0;
    for k in 0..100u64 {
        let signal = [libc::SIGUSR1, libc::SIGTERM, libc::SIGINT][k as usize % 3];
        let child = wearsim()
            .args(["study", "collect", s(&out)])
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_micros(500 * k));
        send(&child, signal);
        let o = child.wait_with_output().unwrap();
        let by_signal = o.status.code() == Some(128 + signal) || o.status.signal() == Some(signal);
        assert!(o.status.success() || by_signal, "{:?}: {}", o.status, stderr(&o));
        stopped += usize::from(by_signal);
        let left: Vec<_> = hidden(&out).into_iter().filter(|n| n.ends_with(".tmp")).collect();
        assert!(left.is_empty(), "stopped after {} ms: {left:?}", 0.5 * k as f64);
    }
    assert!(stopped > 0, "every collect finished before its signal");
}

/// An executable shell script `name` in `dir` with `body`: a stand-in for a Python interpreter.
fn script(dir: &Path, name: &str, body: &str) -> std::path::PathBuf {
    use std::os::unix::fs::PermissionsExt;
    let path = dir.join(name);
    std::fs::write(&path, format!("#!/bin/sh\n{body}\n")).unwrap();
    std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755)).unwrap();
    path
}

#[test]
fn the_commands_that_run_python_stop_at_once_while_it_hangs_and_never_take_silence_for_success() {
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("scan.x3p");
    std::fs::write(&map, b"PK\x03\x04 not read by these stand-ins").unwrap();
    let store = dir.path().join("fields.zarr");
    std::fs::create_dir(&store).unwrap();
    std::fs::write(store.join(".zgroup"), "{\"zarr_format\": 2}").unwrap();
    let out = dir.path().join("imported");
    let nc = dir.path().join("fields.nc");
    let commands = |python: &Path| -> [Vec<String>; 2] {
        let p = s(python).to_string();
        [
            ["surface", "import", s(&map), "--out", s(&out), "--python", &p]
                .map(String::from)
                .to_vec(),
            ["fields", "to-netcdf", s(&store), s(&nc), "--python", &p]
                .map(String::from)
                .to_vec(),
        ]
    };
    // The probe hangs (an interpreter on a dead file system): each stop signal stops the command at
    // once, 128 + the signal, nothing written, and no word that the package is missing.
    let hang = script(dir.path(), "hang", "exec sleep 60");
    for args in commands(&hang) {
        for signal in [libc::SIGTERM, libc::SIGUSR1] {
            let child = wearsim()
                .args(&args)
                .stdout(Stdio::null())
                .stderr(Stdio::piped())
                .spawn()
                .unwrap();
            std::thread::sleep(Duration::from_millis(300));
            let sent = Instant::now();
            send(&child, signal);
            let o = child.wait_with_output().unwrap();
            let e = stderr(&o);
            assert!(
                sent.elapsed() < Duration::from_secs(5),
                "{args:?}: took {:?}",
                sent.elapsed()
            );
            assert_eq!(o.status.code(), Some(128 + signal), "{args:?}: {e}");
            assert!(!e.contains("lacks the wearsim package"), "{e}");
            assert!(!out.exists() && !nc.exists(), "{args:?}");
        }
        // Left alone, it is given up after WEARSIM_PYTHON_TIMEOUT and said to hang.
        let started = Instant::now();
        let o = wearsim()
            .args(&args)
            .env("WEARSIM_PYTHON_TIMEOUT", "0.5")
            .output()
            .unwrap();
        let e = stderr(&o);
        assert!(started.elapsed() < Duration::from_secs(10), "{:?}", started.elapsed());
        assert_eq!(o.status.code(), Some(1), "{e}");
        assert!(e.contains("did not answer within") && e.contains("--python"), "{e}");
    }
    // An interpreter that answers every question with success and does nothing: the command fails,
    // saying that nothing was written, rather than exiting 0 with no folder.
    let silent = script(dir.path(), "silent", "exit 0");
    for args in commands(&silent) {
        let o = wearsim().args(&args).output().unwrap();
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {e}");
        assert!(
            e.contains("ended with success but wrote nothing") && e.contains("missing"),
            "{e}"
        );
    }
    // Nor does an earlier output count as this run's.
    std::fs::create_dir(&out).unwrap();
    std::fs::write(&nc, b"an earlier conversion").unwrap();
    for args in commands(&silent) {
        let o = wearsim().args(&args).output().unwrap();
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {e}");
        assert!(e.contains("wrote nothing") && e.contains("unchanged"), "{e}");
    }
}
