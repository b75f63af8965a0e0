//! How `wearsim study plot` writes DIR/figures: a stop signal at any moment leaves no staging
//! folder or half-written figure beside it, and an earlier figures folder stays whole; a full disk
//! (here a file-size limit) is said in words, naming the folder, not in the drawing backend's terms.

use crate::common;

use std::collections::BTreeMap;
use std::os::unix::process::CommandExt;
use std::os::unix::process::ExitStatusExt;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Duration;

use common::{file, run, s, stderr, GENERATED};

/// A finished study of two surface pairs at 64², collected.
fn study(dir: &Path) -> std::path::PathBuf {
    let text = format!("{GENERATED}[sliding]\nloads = [1e-3]\n").replace("seed = 1", "seed = [1, 2]");
    let study = file(dir, "s.toml", &text);
    let out = dir.join("st");
    let o = run(&["study", "run", s(&study), "--out", s(&out), "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    out
}

/// Every file of `dir` with its bytes.
fn contents(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap())
        .map(|e| {
            (
                e.file_name().to_string_lossy().to_string(),
                std::fs::read(e.path()).unwrap(),
            )
        })
        .collect()
}

/// The hidden entries of the study folder left by writing its figures (staging or moved aside).
fn left_beside(study: &Path) -> Vec<String> {
    std::fs::read_dir(study)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .filter(|n| n.starts_with(".figures"))
        .collect()
}

/// An earlier figures folder of fig4 only (the stopped plots draw them all).
fn earlier(study: &Path) -> BTreeMap<String, Vec<u8>> {
    let o = run(&["study", "plot", s(study), "--figures", "fig4", "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    contents(&study.join("figures"))
}

#[test]
fn a_stopped_study_plot_leaves_no_staging_folder_and_the_earlier_figures_whole() {
    let dir = tempfile::tempdir().unwrap();
    let study = study(dir.path());
    // The files of a whole plot, then an earlier folder of fig4 alone.
    let o = run(&["study", "plot", s(&study), "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let complete: Vec<String> = contents(&study.join("figures")).into_keys().collect();
    let mut before = earlier(&study);
    // Stopped at moments spread over the plot's tenth of a second or so, every 1.5 ms. (Before its
    // figures were written through the library's registered temporary files, about one stop in
    // ten left the staging folder, often with a half-written PNG in it.)
    let mut stopped = 0;
    for k in 0..80u64 {
        let signal = [libc::SIGTERM, libc::SIGINT, libc::SIGUSR1, libc::SIGUSR2][k as usize % 4];
        let mut command = common::wearsim();
        // SAFETY: signal(2) is async-signal-safe, called between fork and exec.
        unsafe {
            command.pre_exec(|| {
                for sig in [libc::SIGINT, libc::SIGTERM, libc::SIGUSR1, libc::SIGUSR2] {
                    libc::signal(sig, libc::SIG_DFL);
                }
                Ok(())
            });
        }
        let child = command
            .args(["study", "plot", s(&study), "--quiet"])
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_micros(1500 * k));
        // SAFETY: kill(2) on our own child's pid.
        assert_eq!(unsafe { libc::kill(child.id() as i32, signal) }, 0);
        let o = child.wait_with_output().unwrap();
        let by_signal = o.status.code() == Some(128 + signal) || o.status.signal() == Some(signal);
        assert!(o.status.success() || by_signal, "{:?}: {}", o.status, stderr(&o));
        let left = left_beside(&study);
        assert!(left.is_empty(), "stopped after {} ms: {left:?}", 1.5 * k as f64);
        // The figures folder is the earlier one or the whole new one, never a mix.
        let now = contents(&study.join("figures"));
        if now != before {
            assert_eq!(
                now.keys().cloned().collect::<Vec<_>>(),
                complete,
                "after {} ms",
                1.5 * k as f64
            );
            before = earlier(&study);
        }
        stopped += usize::from(by_signal);
    }
    assert!(stopped > 0, "every plot finished before its signal");
}

#[test]
fn a_full_disk_under_study_plot_is_said_in_words_naming_the_folder() {
    let dir = tempfile::tempdir().unwrap();
    let study = study(dir.path());
    let before = earlier(&study);
    let figures = study.join("figures");
    // A file-size limit (as a full disk): the SVG (4 blocks) or the PNG (64 blocks) cannot be written.
    for blocks in [4, 64] {
        let o = Command::new("sh")
            .arg("-c")
            .arg(format!(
                "trap '' XFSZ; ulimit -f {blocks}; exec {} study plot {}",
                env!("CARGO_BIN_EXE_wearsim"),
                s(&study)
            ))
            .env("WEARSIM_NO_ESTIMATE", "1")
            .output()
            .unwrap();
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{blocks} blocks: {e}");
        assert!(
            e.contains(&format!("into {}:", figures.display())),
            "{blocks} blocks: {e}"
        );
        assert!(
            e.contains("the file-size limit is reached (file too large") && e.contains("free space"),
            "{blocks} blocks: {e}"
        );
        for internal in ["backend error", "ImageError", "os error", ".figures."] {
            assert!(!e.contains(internal), "{blocks} blocks: {e}");
        }
        assert!(left_beside(&study).is_empty(), "{:?}", left_beside(&study));
        assert_eq!(
            contents(&figures),
            before,
            "{blocks} blocks: the earlier figures changed"
        );
    }
}
