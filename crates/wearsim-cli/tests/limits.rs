//! Limits a cluster sets and inputs that grow without bound: memory is checked against what the
//! process may use (Slurm's allocation, `ulimit -v`, the cgroup, the machine) before anything is
//! allocated, with a clean error naming the need and the limit, never an abort; an `.npz` is
//! checked from its header before it is inflated; names that grow figures and reports are bounded;
//! devices are no surfaces; a constant offset of a measured map changes nothing; a solver tolerance
//! loose enough to move the results is warned about.

use crate::common;

use std::io::Write;
use std::path::Path;
use std::process::Command;

use common::{file, run, run_file, s, stderr, write_npy, GENERATED};

fn sh(script: &str) -> std::process::Output {
    Command::new("sh").arg("-c").arg(script).output().unwrap()
}

fn big(grid: usize) -> String {
    format!(
        "{}[sliding]\nloads = [1e-3]\ndistance = 0.1\nrunning_in = 0.05\n",
        GENERATED.replace("grid = 64", &format!("grid = {grid}")).replace(
            "lambda_lower = 0.0625",
            &format!("lambda_lower = {}", 16.0 / grid as f64)
        )
    )
}

#[test]
fn work_beyond_slurms_allocation_or_ulimit_is_refused_naming_the_need_and_the_limit() {
    let dir = tempfile::tempdir().unwrap();
    let run_path = run_file(dir.path(), &big(2048));
    let bin = env!("CARGO_BIN_EXE_wearsim");
    // Slurm's --mem=200M: a 2048² slide needs about 400 MiB.
    for args in [
        vec!["slide", s(&run_path), "--out", "o1"],
        vec!["contact", s(&run_path), "--load", "1e-3", "--out", "o2"],
        vec!["surface", s(&run_path), "--out", "o3"],
    ] {
        let o = common::wearsim()
            .current_dir(dir.path())
            .env("SLURM_MEM_PER_NODE", if args[0] == "surface" { "50" } else { "200" })
            .args(&args)
            .output()
            .unwrap();
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{}: {e}", args[0]);
        assert!(e.contains("MiB") && e.contains("SLURM_MEM_PER_NODE"), "{e}");
    }
    let study = file(dir.path(), "s.toml", &big(2048));
    let o = common::wearsim()
        .env("SLURM_MEM_PER_NODE", "200")
        .args(["study", "run", s(&study), "--out", s(&dir.path().join("st"))])
        .output()
        .unwrap();
    assert!(
        o.status.code() == Some(1) && stderr(&o).contains("SLURM_MEM_PER_NODE"),
        "{}",
        stderr(&o)
    );
    // ulimit -v: the address space; never "memory allocation failed" (exit 134).
    let o = sh(&format!(
        "ulimit -v 300000; exec {bin} slide {} --out {}",
        s(&run_path),
        s(&dir.path().join("o4"))
    ));
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("address-space limit") && !e.contains("allocation"), "{e}");
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .flatten()
        .map(|e| e.file_name())
        .collect();
    assert_eq!(left.len(), 2, "{left:?}"); // run.toml, s.toml
}

/// An `.npz` holding `heights` of `rows × cols` zeros, deflated.
fn zeros_npz(path: &Path, rows: usize, cols: usize) {
    let mut zip = zip::ZipWriter::new(std::fs::File::create(path).unwrap());
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated)
        .large_file(true);
    zip.start_file("heights.npy", options).unwrap();
    let mut header = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': ({rows}, {cols}), }}");
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    zip.write_all(b"\x93NUMPY\x01\x00").unwrap();
    zip.write_all(&(header.len() as u16).to_le_bytes()).unwrap();
    zip.write_all(header.as_bytes()).unwrap();
    let row = vec![0u8; cols * 8];
    for _ in 0..rows {
        zip.write_all(&row).unwrap();
    }
    zip.finish().unwrap();
}

#[test]
fn a_compressed_map_too_large_to_hold_is_refused_from_its_header_before_inflating() {
    let dir = tempfile::tempdir().unwrap();
    // 4000 × 4000 zeros: 128 MB inflated, a few hundred kB on disk.
    zeros_npz(&dir.path().join("zeros.npz"), 4000, 4000);
    assert!(std::fs::metadata(dir.path().join("zeros.npz")).unwrap().len() < 2_000_000);
    let run_path = run_file(
        dir.path(),
        "[surface]\ntop = \"zeros.npz\"\nbottom = \"zeros.npz\"\nlength = 1.0\n[material]\nyoungs_modulus = 1.0\n\
         poisson_ratio = 0.3\nshear_strength = 0.01\nfracture_energies = [1e-6]\n",
    );
    for args in [
        vec!["surface", s(&run_path), "--out", "o"],
        vec!["surface", "fit", "zeros.npz", "--length", "1"],
    ] {
        let start = std::time::Instant::now();
        let o = common::wearsim()
            .current_dir(dir.path())
            .env("SLURM_MEM_PER_NODE", "100")
            .args(&args)
            .output()
            .unwrap();
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{e}");
        assert!(e.contains("4000×4000") && e.contains("SLURM_MEM_PER_NODE"), "{e}");
        // Refused from the header: far faster than inflating 128 MB and holding it.
        assert!(start.elapsed().as_secs_f64() < 5.0);
    }
}

#[test]
fn names_that_would_grow_reports_and_figures_are_refused_naming_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let study = |name: &str| {
        format!(
            "[surface]\ngrid = 64\nlambda_lower = 0.0625\nlambda_upper = 0.25\nrms_height = 0.005\nseed = 1\n\
             [[materials]]\nname = {name}\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.01\n\
             fracture_energies = [1e-6]\n[sliding]\nloads = [1e-3]\n"
        )
    };
    for name in [
        "\"steel\\nhard: W = 0\"".to_string(),
        format!("\"{}\"", "x".repeat(60_000)),
    ] {
        let path = file(dir.path(), "s.toml", &study(&name));
        let o = run(&["study", "run", s(&path), "--out", s(&dir.path().join("o"))]);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{}", &e[..e.len().min(300)]);
        assert!(
            e.contains("[[materials]] `name`") && e.len() < 1000,
            "{}",
            &e[..e.len().min(300)]
        );
        assert!(!dir.path().join("o").exists());
    }
}

#[test]
fn a_device_is_no_surface_and_a_constant_offset_changes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let base = "[material]\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.01\n\
                fracture_energies = [1e-6]\n";
    let device = run_file(
        dir.path(),
        &format!("[surface]\ntop = \"/dev/zero\"\nbottom = \"/dev/zero\"\nlength = 1.0\n{base}"),
    );
    let o = run(&["surface", s(&device), "--out", s(&dir.path().join("d"))]);
    assert!(stderr(&o).contains("not a regular file"), "{}", stderr(&o));
    let o = run(&["surface", "fit", "/dev/zero", "--length", "1"]);
    assert!(stderr(&o).contains("not a regular file"), "{}", stderr(&o));
    // A measured pair with and without 1e6 added, no levelling: the same contact.
    let surfaces = dir.path().join("o");
    let generated = run_file(dir.path(), GENERATED);
    assert!(run(&["surface", s(&generated), "--out", s(&surfaces)]).status.success());
    let read = |name: &str| -> Vec<f64> {
        let bytes = std::fs::read(surfaces.join(name)).unwrap();
        let data = 10 + u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
        bytes[data..]
            .chunks_exact(8)
            .map(|b| f64::from_le_bytes(b.try_into().unwrap()))
            .collect()
    };
    for (name, offset) in [("top", 0.0), ("bottom", 0.0), ("top_off", 1e6), ("bottom_off", 1e6)] {
        let h: Vec<f64> = read(&format!("{}.npy", &name[..name.find('_').unwrap_or(name.len())]))
            .iter()
            .map(|v| v + offset)
            .collect();
        write_npy(&dir.path().join(format!("{name}.npy")), &[64, 64], &h);
    }
    let mut areas = Vec::new();
    for suffix in ["", "_off"] {
        let run_path = file(
            dir.path(),
            &format!("c{suffix}.toml"),
            &format!("[surface]\ntop = \"top{suffix}.npy\"\nbottom = \"bottom{suffix}.npy\"\nlength = 1.0\n{base}"),
        );
        let out = dir.path().join(format!("c{suffix}"));
        let o = run(&["contact", s(&run_path), "--load", "1e-3", "--out", s(&out)]);
        assert!(o.status.success(), "{}", stderr(&o));
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
        areas.push(summary["contact_area"].as_f64().unwrap());
        if !suffix.is_empty() {
            assert!(stderr(&o).contains("mean height"), "{}", stderr(&o));
        }
    }
    assert!((areas[0] - areas[1]).abs() < 1e-9, "{areas:?}");
}

#[test]
fn a_tolerance_loose_enough_to_move_the_results_is_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    for (tolerance, warned) in [("1e-8", false), ("1e-6", false), ("1e-3", true), ("0.5", true)] {
        let text =
            format!("{GENERATED}[contact]\ntolerance = {tolerance}\n[sliding]\nloads = [1e-3]\ndistance = 0.5\n");
        let run_path = run_file(dir.path(), &text);
        let out = dir.path().join("o");
        let o = run(&["slide", s(&run_path), "--out", s(&out), "--overwrite"]);
        assert!(o.status.success(), "{}", stderr(&o));
        let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
        assert_eq!(stderr(&o).contains("tolerance"), warned, "{tolerance}: {}", stderr(&o));
        assert_eq!(summary.contains("[contact] tolerance"), warned, "{tolerance}");
    }
}

#[test]
fn a_figure_or_report_that_a_full_disk_cuts_short_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let text = format!("{GENERATED}[sliding]\nloads = [1e-3]\n").replace("seed = 1", "seed = [1, 2]");
    let study = file(dir.path(), "s.toml", &text);
    let out = dir.path().join("st");
    let o = run(&["study", "run", s(&study), "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    // A file-size limit (as a full disk): the first write past it fails; the message names the file.
    for blocks in [4, 64] {
        let o = sh(&format!(
            "trap '' XFSZ; ulimit -f {blocks}; exec {} study plot {}",
            env!("CARGO_BIN_EXE_wearsim"),
            s(&out)
        ));
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{blocks} blocks: {e}");
        assert!(
            [".png", ".svg", ".md", ".csv"].iter().any(|x| e.contains(x)),
            "{blocks} blocks: {e}"
        );
        // Nothing half-written left, in the study folder or its figures.
        let left: Vec<_> = [out.clone(), out.join("figures")]
            .iter()
            .filter_map(|d| std::fs::read_dir(d).ok())
            .flat_map(|entries| entries.flatten())
            .map(|e| e.file_name().to_string_lossy().to_string())
            .filter(|n| n.ends_with(".tmp"))
            .collect();
        assert!(left.is_empty(), "{left:?}");
    }
}

/// Peak resident size, in MiB, of `wearsim args` run to its end (the child's own rusage).
fn peak_mib(dir: &Path, args: &[&str]) -> f64 {
    #[allow(clippy::zombie_processes)] // reaped by wait4 below, which also gives its rusage
    let child = common::wearsim()
        .current_dir(dir)
        .args(args)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let mut status = 0;
    // SAFETY: wait4 on our own child, into a zeroed rusage it fills.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    let pid = unsafe { libc::wait4(child.id() as i32, &mut status, 0, &mut usage) };
    assert_eq!(pid, child.id() as i32);
    assert!(
        libc::WIFEXITED(status) && libc::WEXITSTATUS(status) == 0,
        "{args:?} failed"
    );
    usage.ru_maxrss as f64 / 1024.0
}

#[test]
fn the_memory_checked_is_within_ten_percent_of_the_measured_peak() {
    let dir = tempfile::tempdir().unwrap();
    // The slide as short as a run goes (one running-in step, the two steps of 1 px a wear rate
    // needs): every step holds the same arrays, so more steps would not raise the peak.
    let text = big(1024)
        .replace("distance = 0.1", "distance = 0.003")
        .replace("running_in = 0.05", "running_in = 0.001");
    let run_path = run_file(dir.path(), &text);
    // A surface pair on 1024² needs only ~25 MiB of arrays beside the program's ~10–19 MiB: on 2048²
    // (~100 MiB of arrays, half a second) the program's share is small and the test checks arrays.
    let surface_path = dir.path().join("surface.toml");
    std::fs::write(&surface_path, big(2048)).unwrap();
    for args in [
        vec!["slide", s(&run_path), "--out", "o1"],
        vec!["contact", s(&run_path), "--load", "1e-3", "--out", "o2"],
        vec!["surface", s(&surface_path), "--out", "o3"],
    ] {
        // The estimate, as the refusal under a 1 MB allocation states it.
        let o = common::wearsim()
            .current_dir(dir.path())
            .env("SLURM_MEM_PER_NODE", "1")
            .args(&args)
            .output()
            .unwrap();
        let e = stderr(&o);
        let estimate: f64 = e
            .split("needs about ")
            .nth(1)
            .and_then(|r| r.strip_suffix('\n').unwrap_or(r).split(" MiB").next())
            .and_then(|v| v.parse().ok())
            .unwrap_or_else(|| panic!("no estimate in MiB: {e}"));
        // The estimate is for the largest peak: the largest of three runs (a sliding run's threads do
        // not always overlap their largest arrays; the surface pair's two surfaces are made one after
        // the other, so its peak is the same on an idle or a loaded machine).
        let peak = (0..3).map(|_| peak_mib(dir.path(), &args)).fold(0.0, f64::max);
        let ratio = estimate / peak;
        assert!(
            (0.9..=1.1).contains(&ratio),
            "{}: estimate {estimate} MiB, peak {peak:.0} MiB",
            args[0]
        );
    }
}

#[test]
fn every_command_that_slides_refuses_a_run_too_large_for_the_memory_with_one_message() {
    // The library's sliding run checks the memory, so `slide`, `animate` and `bench-slide` on the
    // same 2048² grid are refused with the same words (Slurm's --mem=200M; the run needs ~400 MiB).
    let dir = tempfile::tempdir().unwrap();
    let run_path = run_file(dir.path(), &big(2048));
    let refusal = |args: &[&str]| {
        let o = common::wearsim()
            .current_dir(dir.path())
            .env("SLURM_MEM_PER_NODE", "200")
            .args(args)
            .output()
            .unwrap();
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {e}");
        e.lines()
            .find(|l| l.contains("needs about"))
            .unwrap_or_else(|| panic!("{args:?}: no memory refusal in {e}"))
            .to_string()
    };
    let slide = refusal(&["slide", s(&run_path), "--out", "o1"]);
    assert!(
        slide.contains("a sliding run on 2048×2048 pixels") && slide.contains("SLURM_MEM_PER_NODE"),
        "{slide}"
    );
    assert_eq!(refusal(&["animate", s(&run_path), "--out", "a.gif"]), slide);
    assert_eq!(refusal(&["bench-slide", "--n", "2048", "--warm-n", "0"]), slide);
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .flatten()
        .map(|e| e.file_name())
        .collect();
    assert_eq!(left.len(), 1, "{left:?}"); // run.toml
}
