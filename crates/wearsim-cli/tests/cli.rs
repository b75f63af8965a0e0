//! The CLI on good and bad input: one-line errors naming the field, non-zero exit, nothing written.

use crate::common;

use std::path::Path;

use common::{run_file, wearsim, write_npy, GENERATED};

/// Runs `wearsim contact` expecting failure; returns stderr and checks that nothing was written.
fn contact_fails(dir: &Path, text: &str, load: &str) -> String {
    let run = run_file(dir, text);
    let out = dir.join("out");
    let o = wearsim()
        .args([
            "contact",
            run.to_str().unwrap(),
            "--load",
            load,
            "--out",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(!out.exists(), "output written despite the error");
    let err = String::from_utf8(o.stderr).unwrap();
    assert_eq!(err.trim_end().lines().count(), 1, "error is not one line: {err}");
    err
}

#[test]
fn surface_and_contact_write_their_files() {
    let dir = tempfile::tempdir().unwrap();
    let run = run_file(dir.path(), GENERATED);
    let out = dir.path().join("o");
    let ok = wearsim()
        .args(["surface", run.to_str().unwrap(), "--out", out.to_str().unwrap()])
        .status()
        .unwrap();
    assert!(ok.success());
    for f in ["top.npy", "bottom.npy", "statistics.json"] {
        assert!(out.join(f).is_file(), "{f}");
    }
    let contact = dir.path().join("c");
    let ok = wearsim()
        .args([
            "contact",
            run.to_str().unwrap(),
            "--load",
            "1e-3",
            "--offset",
            "0.03125",
            "--out",
            contact.to_str().unwrap(),
        ])
        .status()
        .unwrap();
    assert!(ok.success());
    let summary = std::fs::read_to_string(contact.join("summary.json")).unwrap();
    for key in [
        "contact_area",
        "mean_pressure",
        "approach",
        "iterations",
        "residual",
        "tolerance",
        "effective_modulus",
        "flow_pressure",
        "seconds",
        "boundary",
        "gap.npy",
    ] {
        assert!(summary.contains(&format!("\"{key}\"")), "summary lacks {key}");
    }
    for f in ["pressure.npy", "contact.npy", "displacement.npy", "gap.npy"] {
        assert!(contact.join(f).is_file(), "{f}");
    }
    // A free boundary has no periodic box to slide the top surface around.
    let o = wearsim()
        .args([
            "contact",
            run.to_str().unwrap(),
            "--load",
            "1e-3",
            "--offset",
            "0.03125",
            "--boundary",
            "free",
            "--out",
            dir.path().join("free").to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(!o.status.success() && String::from_utf8_lossy(&o.stderr).contains("free boundary"));
    // Read the written surfaces back as a run (files relative to the run file).
    let read = format!(
        "[surface]\ntop = \"o/top.npy\"\nbottom = \"o/bottom.npy\"\nlength = 1.0\n{}",
        &GENERATED[GENERATED.find("[material]").unwrap()..]
    );
    let run2 = dir.path().join("read.toml");
    std::fs::write(&run2, read).unwrap();
    let out2 = dir.path().join("o2");
    let ok = wearsim()
        .args([
            "contact",
            run2.to_str().unwrap(),
            "--load",
            "1e-3",
            "--offset",
            "0.03125",
            "--out",
            out2.to_str().unwrap(),
        ])
        .status()
        .unwrap();
    assert!(ok.success());
    assert_eq!(
        std::fs::read(contact.join("pressure.npy")).unwrap(),
        std::fs::read(out2.join("pressure.npy")).unwrap()
    );
}

#[test]
fn bad_material_and_load_are_one_line_errors() {
    let dir = tempfile::tempdir().unwrap();
    let e = contact_fails(
        dir.path(),
        &GENERATED.replace("youngs_modulus = 1.0", "youngs_modulus = -1.0"),
        "1e-3",
    );
    assert!(e.contains("youngs_modulus"), "{e}");
    let e = contact_fails(
        dir.path(),
        &GENERATED.replace("poisson_ratio = 0.3", "poisson_ratio = 0.5"),
        "1e-3",
    );
    assert!(e.contains("poisson_ratio"), "{e}");
    // p_m = 3√3·0.01 ≈ 0.052: a load of 0.06 E L² cannot be carried.
    let e = contact_fails(dir.path(), GENERATED, "0.06");
    assert!(e.contains("load cannot be carried") && e.contains("loads"), "{e}");
    let e = contact_fails(dir.path(), &GENERATED.replace("seed = 1", "seed = 1\nsede = 2"), "1e-3");
    assert!(e.contains("sede"), "{e}");
}

#[test]
fn bad_surface_files_are_one_line_errors() {
    let dir = tempfile::tempdir().unwrap();
    let material = &GENERATED[GENERATED.find("[material]").unwrap()..];
    let read = format!("[surface]\ntop = \"top.npy\"\nbottom = \"bottom.npy\"\nlength = 1.0\n{material}");
    write_npy(&dir.path().join("bottom.npy"), &[16, 16], &vec![0.0; 256]);

    let mut h = vec![0.0; 256];
    h[5] = f64::NAN;
    write_npy(&dir.path().join("top.npy"), &[16, 16], &h);
    let e = contact_fails(dir.path(), &read, "1e-3");
    assert!(e.contains("top.npy") && e.contains("NaN"), "{e}");

    // Rectangular surfaces are fine, but the two must share the grid.
    write_npy(&dir.path().join("top.npy"), &[16, 32], &vec![0.0; 512]);
    let e = contact_fails(dir.path(), &read, "1e-3");
    assert!(
        e.contains("bottom.npy") && e.contains("16 × 32") && e.contains("differs"),
        "{e}"
    );
    // Length = [Lx, Ly] must give square pixels.
    let e = contact_fails(dir.path(), &read.replace("length = 1.0", "length = [1.0, 1.0]"), "1e-3");
    assert!(e.contains("top.npy") && e.contains("square pixels"), "{e}");

    write_npy(&dir.path().join("top.npy"), &[0, 0], &[]);
    let e = contact_fails(dir.path(), &read, "1e-3");
    assert!(e.contains("top.npy") && e.contains("empty"), "{e}");

    std::fs::write(dir.path().join("top.npy"), b"not a numpy file").unwrap();
    let e = contact_fails(dir.path(), &read, "1e-3");
    assert!(e.contains("top.npy"), "{e}");
}

const SLIDING: &str = "[sliding]\nloads = [5e-4, 1e-3]\n";

#[test]
fn slide_writes_summary_and_series() {
    let dir = tempfile::tempdir().unwrap();
    let run = run_file(dir.path(), &format!("{GENERATED}{SLIDING}"));
    let out = dir.path().join("o");
    let o = wearsim()
        .args(["slide", run.to_str().unwrap(), "--out", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
    for key in [
        "flow_pressure",
        "critical_diameter",
        "effective_modulus",
        "wear_rate",
        "wear_coefficient",
        "particle_rate",
        "initial_volume",
        "static_wear_coefficient",
        "static_wear_rate",
        "tolerance",
    ] {
        assert!(summary.contains(&format!("\"{key}\"")), "summary lacks {key}");
    }
    let series = std::fs::read_to_string(out.join("series.csv")).unwrap();
    let mut lines = series.lines();
    assert_eq!(
        lines.next().unwrap(),
        "load,fracture_energy,s,junctions,contact_area,n_critical,n_formed,n_shrunk,volume,initial_junctions,\
         static_wear_coefficient,static_wear_rate,iterations,residual,wrapping_junctions,merged_junctions,\
         largest_junction"
    );
    // 64 px: 4 offsets of 4 px in running-in, then 16 of 1 px; 2 loads × 1 fracture energy.
    assert_eq!(lines.count(), 2 * 20);
}

#[test]
fn bad_sliding_input_is_a_one_line_error() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (format!("{GENERATED}[sliding]\nloads = []\n"), "loads"),
        (
            format!("{GENERATED}[sliding]\nloads = [1e-3]\ndistance = 0.2\nrunning_in = 0.25\n"),
            "running_in",
        ),
        (format!("{GENERATED}[sliding]\nloads = [1e-3]\nstep = 64\n"), "step"),
        (format!("{GENERATED}[sliding]\nloads = [1e-3]\nspeed = 1\n"), "speed"),
        (
            GENERATED.replace("grid = 64\n", "grid = 64\ntop = \"missing.npy\"\n"),
            "surface",
        ),
    ];
    for (text, needle) in cases {
        let run = run_file(dir.path(), &text);
        let out = dir.path().join("o");
        let o = wearsim()
            .args(["slide", run.to_str().unwrap(), "--out", out.to_str().unwrap()])
            .output()
            .unwrap();
        assert!(!o.status.success());
        assert!(!out.exists());
        let err = String::from_utf8(o.stderr).unwrap();
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains(needle), "{needle}: {err}");
    }
    let missing = format!(
        "[surface]\ntop = \"a.npy\"\nbottom = \"b.npy\"\nlength = 1.0\n{}{SLIDING}",
        &GENERATED[GENERATED.find("[material]").unwrap()..]
    );
    let run = run_file(dir.path(), &missing);
    let o = wearsim()
        .args([
            "slide",
            run.to_str().unwrap(),
            "--out",
            dir.path().join("o").to_str().unwrap(),
        ])
        .output()
        .unwrap();
    let err = String::from_utf8(o.stderr).unwrap();
    assert!(
        !o.status.success() && err.contains("a.npy") && err.contains("not found"),
        "{err}"
    );
    // A fields selection that names no load or no step is refused before any solve, and nothing is
    // left behind.
    let run = run_file(dir.path(), &format!("{GENERATED}[sliding]\nloads = [1e-3]\n"));
    for (flags, needle) in [
        (
            vec!["--save-fields", "--fields-loads", "1"],
            "load index 1 does not exist",
        ),
        (vec!["--save-fields", "--fields-every", "0"], "fields every"),
        (vec!["--fields-every", "2"], "--save-fields"),
    ] {
        let out = dir.path().join("o");
        let o = wearsim()
            .args(["slide", run.to_str().unwrap(), "--out", out.to_str().unwrap()])
            .args(&flags)
            .output()
            .unwrap();
        let err = String::from_utf8(o.stderr).unwrap();
        assert!(!o.status.success() && err.contains(needle), "{flags:?}: {err}");
        assert!(!out.exists(), "{flags:?}");
    }
}

#[test]
fn animate_writes_a_gif_with_one_frame_per_step() {
    let dir = tempfile::tempdir().unwrap();
    let run = run_file(dir.path(), &format!("{GENERATED}{SLIDING}"));
    let gif = dir.path().join("slide.gif");
    let o = wearsim()
        .args([
            "animate",
            run.to_str().unwrap(),
            "--out",
            gif.to_str().unwrap(),
            "--load-index",
            "1",
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let bytes = std::fs::read(&gif).unwrap();
    assert!(bytes.starts_with(b"GIF89a"));
    // 20 offsets at 64 px: one image descriptor (0x2C after a graphic control block) per frame.
    let frames = bytes
        .windows(3)
        .filter(|w| w[0] == 0x00 && w[1] == 0x2C && w[2] == 0x00)
        .count();
    assert!(frames >= 20, "{frames} frames");
    let o = wearsim()
        .args([
            "animate",
            run.to_str().unwrap(),
            "--out",
            dir.path().join("a.png").to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(!o.status.success() && String::from_utf8_lossy(&o.stderr).contains(".gif"));
    let o = wearsim()
        .args([
            "animate",
            run.to_str().unwrap(),
            "--out",
            gif.to_str().unwrap(),
            "--load-index",
            "5",
        ])
        .output()
        .unwrap();
    assert!(!o.status.success() && String::from_utf8_lossy(&o.stderr).contains("load-index"));
}

#[test]
fn bench_passes_prints_and_records_each_pass_against_the_copy_floor() {
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("bench.json");
    let o = wearsim()
        .args(["bench", "--sizes", "64", "--fft-repeats", "1", "--passes", "--json"])
        .arg(&json)
        .output()
        .unwrap();
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for line in [
        "passes at N = 64: copy pass",
        "update",
        "displacement_and_stats",
        "a conjugate-gradient iteration:",
        "curvature",
        "advance",
        "an iteration that changes the sets:",
    ] {
        assert!(out.contains(line), "{line:?} missing from:\n{out}");
    }
    let doc: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let passes = doc["rows"][0]["passes"].as_array().unwrap();
    assert_eq!(passes.len(), 10);
    assert!(
        passes.iter().all(|p| p["seconds"].as_f64().unwrap() > 0.0),
        "{passes:?}"
    );
    // Without --passes, no profile is taken.
    let o = wearsim()
        .args(["bench", "--sizes", "64", "--fft-repeats", "1"])
        .output()
        .unwrap();
    assert!(!String::from_utf8_lossy(&o.stdout).contains("passes at N"));
    // A JSON path in a folder that is not there is refused before any timing.
    let missing = dir.path().join("no-such-folder").join("bench.json");
    let o = wearsim()
        .args(["bench", "--sizes", "64", "--fft-repeats", "1", "--json"])
        .arg(&missing)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("--json") && err.contains("does not exist"),
        "{err}"
    );
    assert!(String::from_utf8_lossy(&o.stdout).is_empty(), "timed before refusing");
}

/// A material given as a tribologist measures it (hardness, fracture toughness) and loads as
/// nominal pressures: the conversions are printed with their formula where the run file is read
/// (here by `surface`, which makes the pair only; a study's dry run prints them too, see the cost
/// tests).
#[test]
fn hardness_toughness_and_pressures_are_converted_aloud() {
    let dir = tempfile::tempdir().unwrap();
    // SiC-like, on a 64² box of 0.5 µm pixels: H = 3√3 τ̃ with τ̃ = 2.5 GPa, K_Ic = 3 MPa√m.
    let run = common::file(
        dir.path(),
        "run.toml",
        &format!(
            "{}hardness = 12.99038105676658e9\nfracture_toughness = [3e6]\n[sliding]\npressures = [4e8]\n",
            common::SI_SIC
        ),
    );
    let o = wearsim()
        .args(["surface", common::s(&run), "--out", common::s(&dir.path().join("out"))])
        .output()
        .unwrap();
    let text = common::stderr(&o);
    assert!(o.status.success(), "{text}");
    assert!(
        text.contains("hardness H = 1.2990e10 Pa: shear strength τ̃ = H/(3√3)"),
        "{text}"
    );
    assert!(text.contains("τ̃ = 2.5000e9 Pa"), "{text}");
    assert!(
        text.contains("𝒢 = K_Ic²(1 − ν²)/E (plane strain) = 2.1600e1 J/m²"),
        "{text}"
    );
    assert!(text.contains("load F_N = p_N Lx·Ly = 4.0960e-1 N"), "{text}");
}

/// `summary.json` gives the specific wear rate K = W/F_N beside W and k, with its unit, and
/// `wearsim plot` draws the folder's series figures for each load.
#[test]
fn a_slides_summary_has_the_specific_wear_rate_and_its_folder_is_plotted() {
    let dir = tempfile::tempdir().unwrap();
    let run = run_file(dir.path(), &format!("{GENERATED}[sliding]\nloads = [1e-3, 2e-3]\n"));
    let out = dir.path().join("out");
    let o = wearsim()
        .args(["slide", common::s(&run), "--out", common::s(&out)])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", common::stderr(&o));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["units_of_results"]["specific_wear_rate"], "1/E");
    // It says which model made it, as an estimate's summary does.
    assert_eq!(summary["model"], "sliding");
    let results = summary["results"].as_array().unwrap();
    assert!(results.iter().any(|r| r["wear_rate"].is_number()), "{results:?}");
    for r in results {
        match r["wear_rate"].as_f64() {
            Some(w) => {
                let expected = w / r["load"].as_f64().unwrap();
                assert!(
                    (r["specific_wear_rate"].as_f64().unwrap() / expected - 1.0).abs() < 1e-12,
                    "{r}"
                );
            }
            None => assert!(r["specific_wear_rate"].is_null(), "{r}"),
        }
    }
    let o = wearsim().args(["plot", common::s(&out)]).output().unwrap();
    assert!(o.status.success(), "{}", common::stderr(&o));
    for load in [1, 2] {
        for name in ["fig3_wear_volume", "appB_particle_counts", "memory_of_initial_contact"] {
            for ext in ["png", "svg", "csv"] {
                let file = out.join("figures").join(format!("{name}_load{load}.{ext}"));
                assert!(file.is_file(), "{}", file.display());
            }
        }
    }
    // The fitted line of Fig. 3 is the summary's W, at the second load.
    let csv = std::fs::read_to_string(out.join("figures/fig3_wear_volume_load2.csv")).unwrap();
    assert!(csv.contains("fit: W = "), "{csv}");
    // Drawn again, the figures are replaced; the run into the same folder again replaces them with
    // the rest (no figure of the earlier run stays); a study folder is sent to `study plot`.
    assert!(wearsim()
        .args(["plot", common::s(&out)])
        .output()
        .unwrap()
        .status
        .success());
    let again = wearsim()
        .args(["slide", common::s(&run), "--out", common::s(&out)])
        .output()
        .unwrap();
    assert!(again.status.success(), "{}", common::stderr(&again));
    assert!(!out.join("figures").exists());
    std::fs::create_dir_all(dir.path().join("study/jobs")).unwrap();
    let o = wearsim()
        .args(["plot", common::s(&dir.path().join("study"))])
        .output()
        .unwrap();
    assert!(
        !o.status.success() && common::stderr(&o).contains("wearsim study plot"),
        "{}",
        common::stderr(&o)
    );
}
