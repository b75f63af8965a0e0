//! Checkpoints and job files that lie: a checkpoint with one digit changed, a flipped bit or NaN
//! bytes never resumes (it is set aside with a warning and the run starts over, to the
//! uninterrupted results); a job file edited to results no run gives (none, a negative wear rate,
//! R² = 7, one digit changed) is never collected: `collect` names it and `study run` recomputes it;
//! a checkpoint that cannot be written warns and the run goes on to its results.

use crate::common;

use std::os::unix::process::CommandExt;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Duration;

use common::{file, run, run_file, s, stderr, GENERATED};

fn wearsim() -> Command {
    let mut c = common::wearsim();
    // SAFETY: signal(2) between fork and exec: SIGTERM at its default disposition.
    unsafe {
        c.pre_exec(|| {
            libc::signal(libc::SIGTERM, libc::SIG_DFL);
            Ok(())
        });
    }
    c
}

fn long_run() -> String {
    format!(
        "{}[sliding]\nloads = [5e-4, 1e-3, 2e-3]\ndistance = 0.5\n",
        GENERATED
            .replace("grid = 64", "grid = 128")
            .replace("lambda_lower = 0.0625", "lambda_lower = 0.03125")
    )
}

/// Runs `slide` into `out` with a checkpoint after every step and kills it (SIGKILL) once it has
/// saved its third step: the checkpoint, if the run had not finished.
fn killed_slide(run_path: &Path, out: &Path) -> Option<Vec<u8>> {
    let name = out.file_name().unwrap().to_string_lossy().to_string();
    let checkpoint = out.parent().unwrap().join(format!(".{name}.checkpoint"));
    let mut child = wearsim()
        .args(["slide", s(run_path), "--out", s(out), "--checkpoint-every", "0s"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let steps = |bytes: &[u8]| bytes.windows(4).filter(|w| w == b"\"s\":").count();
    loop {
        if child.try_wait().unwrap().is_some() {
            return None;
        }
        if let Ok(bytes) = std::fs::read(&checkpoint) {
            if steps(&bytes) >= 3 {
                child.kill().unwrap();
                child.wait().unwrap();
                return std::fs::read(&checkpoint).ok();
            }
        }
        std::thread::sleep(Duration::from_millis(5));
    }
}

#[test]
fn a_damaged_checkpoint_is_set_aside_and_never_resumed() {
    let dir = tempfile::tempdir().unwrap();
    let run_path = run_file(dir.path(), &long_run());
    let reference = dir.path().join("reference");
    assert!(run(&["slide", s(&run_path), "--out", s(&reference)]).status.success());
    let expected = std::fs::read(reference.join("series.csv")).unwrap();
    let out = dir.path().join("out");
    let checkpoint = dir.path().join(".out.checkpoint");
    let saved = killed_slide(&run_path, &out).expect("the run was killed after three steps");
    // A digit of the sliding distance of the third step recorded.
    let key = b"\"s\":";
    let third = saved
        .windows(key.len())
        .enumerate()
        .filter(|(_, w)| *w == key)
        .nth(2)
        .map(|(k, _)| k)
        .expect("three steps recorded");
    let digit = (third + key.len()..saved.len())
        .find(|&k| saved[k].is_ascii_digit() && saved[k] != b'0' && saved[k] != b'7')
        .unwrap();
    let mut damaged = Vec::new();
    let mut one_digit = saved.clone();
    one_digit[digit] = b'7';
    damaged.push(one_digit);
    let mut flipped = saved.clone();
    let last = flipped.len() - 8;
    flipped[last] ^= 0x04;
    damaged.push(flipped);
    let mut nan = saved.clone();
    let at = nan.len() - 64;
    nan[at..at + 8].copy_from_slice(&f64::NAN.to_le_bytes());
    damaged.push(nan);
    for bytes in damaged {
        std::fs::write(&checkpoint, &bytes).unwrap();
        let o = run(&["slide", s(&run_path), "--out", s(&out), "--overwrite"]);
        assert!(o.status.success(), "{}", stderr(&o));
        let e = stderr(&o);
        assert!(e.contains("checkpoint not used") && !e.contains("resuming"), "{e}");
        assert_eq!(std::fs::read(out.join("series.csv")).unwrap(), expected);
        assert!(!checkpoint.exists());
    }
}

#[test]
fn a_checkpoint_that_cannot_be_written_warns_and_the_run_finishes() {
    let dir = tempfile::tempdir().unwrap();
    let run_path = run_file(dir.path(), &long_run());
    let reference = dir.path().join("reference");
    assert!(run(&["slide", s(&run_path), "--out", s(&reference)]).status.success());
    // The checkpoint's place is taken by a folder: every save fails, the results are written.
    let out = dir.path().join("out");
    std::fs::create_dir(dir.path().join(".out.checkpoint")).unwrap();
    std::fs::write(dir.path().join(".out.checkpoint").join("x"), "").unwrap();
    let o = run(&["slide", s(&run_path), "--out", s(&out), "--checkpoint-every", "0s"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("checkpoint not saved"), "{}", stderr(&o));
    assert_eq!(
        std::fs::read(out.join("series.csv")).unwrap(),
        std::fs::read(reference.join("series.csv")).unwrap()
    );
}

/// A 64² study of two jobs, two fracture energies.
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
fracture_energies = [0.25e-6, 1e-6]
[sliding]
loads = [1e-3]
"#;

#[test]
fn job_files_edited_to_results_no_run_gives_are_never_collected() {
    let dir = tempfile::tempdir().unwrap();
    let study = file(dir.path(), "s.toml", STUDY);
    let out = dir.path().join("out");
    let o = run(&["study", "run", s(&study), "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(run(&["study", "collect", s(&out)]).status.success());
    let expected = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let job = out.join("jobs").join("job-000001.json");
    let original = std::fs::read_to_string(&job).unwrap();
    let value: serde_json::Value = serde_json::from_str(&original).unwrap();
    let edit = |f: &dyn Fn(&mut serde_json::Value)| {
        let mut v = value.clone();
        f(&mut v);
        v.as_object_mut().unwrap().remove("checksum");
        serde_json::to_string(&v).unwrap()
    };
    let digit = {
        // One digit of the wear rate changed, the checksum kept.
        let w = value["results"][0]["wear_rate"].as_f64().unwrap();
        let text = format!("{w}");
        let changed = text.replacen(|c: char| c.is_ascii_digit() && c != '0' && c != '9', "9", 1);
        original.replacen(&text, &changed, 1)
    };
    assert_ne!(digit, original);
    let cases = [
        edit(&|v| v["results"] = serde_json::json!([])),
        edit(&|v| v["results"][0]["wear_rate"] = serde_json::json!(-1e-3)),
        edit(&|v| v["results"][1]["wear_rate_r2"] = serde_json::json!(7.0)),
        digit,
    ];
    for text in cases {
        std::fs::write(&job, &text).unwrap();
        let o = run(&["study", "collect", s(&out)]);
        assert!(!o.status.success(), "an edited job file was collected");
        assert!(stderr(&o).contains("job-000001.json"), "{}", stderr(&o));
        let o = run(&["study", "run", s(&study), "--out", s(&out)]);
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(stderr(&o).contains("recomputed"), "{}", stderr(&o));
        assert!(run(&["study", "collect", s(&out)]).status.success());
        assert_eq!(std::fs::read_to_string(out.join("results.csv")).unwrap(), expected);
    }
}

#[test]
fn an_undefined_wear_rate_fit_is_stored_as_null_with_a_wear_rate_of_zero() {
    // d* far above every junction after running-in (a large 𝒢): V stays constant in the window.
    let dir = tempfile::tempdir().unwrap();
    // (Surface pair 3 at three loads gave R² = 0.0 for one of them: the round-off of equal values.)
    let text = format!(
        "{}[sliding]\nloads = [5e-4, 1e-3, 2e-3]\ndistance = 0.5\n",
        GENERATED
            .replace(
                "fracture_energies = [0.5e-6]",
                "fracture_energies = [0.3e-6, 3e-6, 30e-6]"
            )
            .replace("seed = 1", "seed = 3")
    );
    let run_path = run_file(dir.path(), &text);
    let out = dir.path().join("out");
    let o = run(&["slide", s(&run_path), "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let mut undefined = 0;
    for r in summary["results"].as_array().unwrap() {
        if r["particles_in_fit"] == 0 {
            undefined += 1;
            assert!(r["wear_rate_r2"].is_null(), "{r}");
            assert_eq!(r["wear_rate"], 0.0, "{r}");
        }
    }
    assert!(undefined > 0, "no result without a particle after running-in");
}
