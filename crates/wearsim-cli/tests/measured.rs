//! Measured surfaces end to end: a height map as a profilometer gives it (ASCII, rectangular,
//! odd-sized, tilted, not periodic, heights in µm, a header line) runs through `wearsim surface`,
//! `contact` and `slide` with its units converted and its tilt removed; column files state their
//! size; `wearsim surface fit` recovers the parameters of generated surfaces and writes a block that
//! runs; a study on measured maps keeps their warnings as `slide` does.

use crate::common;

use std::fmt::Write as _;
use std::path::Path;

use common::{run, s, stderr, stdout, write_npy};
use wearsim::surface::pair_seeds;
use wearsim::{Generation, Grid, SpectrumParams, Surface};

/// A measured-style map: a 64 × 48 self-affine surface (pixel 1 µm, h_rms 0.3 µm) with a tilt and an
/// offset, cropped to 63 × 47, written in µm as comma-separated text under a header line, one line
/// per scan along x. Returns the heights in µm indexed [x, y].
fn measured(path: &Path, seed: u64) -> Vec<f64> {
    let grid = Grid::new(64, 48, 64e-6).unwrap();
    let spectrum = SpectrumParams {
        hurst: 0.8,
        lambda_lower: 4e-6,
        lambda_upper: 32e-6,
        rms_height: 0.3e-6,
        generation: Generation::RandomPhase,
    };
    let h = Surface::generate(grid, &spectrum, seed).unwrap().into_heights();
    let mut text = String::from("Profilometer export, heights in um\n");
    let um = |i: usize, j: usize| h[i * 48 + j] * 1e6 + 5.0 + 0.02 * i as f64 - 0.01 * j as f64;
    for j in 0..47 {
        let line: Vec<String> = (0..63).map(|i| format!("{:.6}", um(i, j))).collect();
        writeln!(text, "{}", line.join(",")).unwrap();
    }
    std::fs::write(path, text).unwrap();
    (0..63)
        .flat_map(|i| (0..47).map(move |j| (i, j)))
        .map(|(i, j)| (um(i, j) * 1e6).round() / 1e6)
        .collect()
}

const MATERIAL: &str = r#"
[material]
youngs_modulus = 200e9
poisson_ratio = 0.3
shear_strength = 2e9
fracture_energies = [2.0]
"#;

#[test]
fn a_measured_map_runs_end_to_end_with_units_and_levelling() {
    let dir = tempfile::tempdir().unwrap();
    measured(&dir.path().join("top.csv"), pair_seeds(5).0);
    measured(&dir.path().join("bottom.csv"), pair_seeds(5).1);
    let surface =
        "units = \"si\"\n[surface]\ntop = \"top.csv\"\nbottom = \"bottom.csv\"\nlength = 63e-6\nheight_unit = \"um\"\n";
    let raw = dir.path().join("raw.toml");
    std::fs::write(&raw, format!("{surface}{MATERIAL}")).unwrap();
    // As read: cropped to even sides (62 × 46 pixels of 1 µm), heights in m, tilted and not periodic.
    let o = run(&["surface", s(&raw), "--out", s(&dir.path().join("raw"))]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("cropped to 62 × 46") && stderr(&o).contains("header line"),
        "{}",
        stderr(&o)
    );
    assert!(stderr(&o).contains("not periodic"), "{}", stderr(&o));
    assert!(stdout(&o).contains("62×46 pixels"), "{}", stdout(&o));
    let stats: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("raw/statistics.json")).unwrap()).unwrap();
    assert!((stats["top"]["pixel_size"].as_f64().unwrap() - 1e-6).abs() < 1e-15);
    assert!((stats["top"]["length_y"].as_f64().unwrap() - 46e-6).abs() < 1e-15);
    let h_raw = stats["top"]["rms_height"].as_f64().unwrap();
    assert!(h_raw > 0.4e-6, "the tilt is part of the raw heights: {h_raw}");

    // Levelled (plane) and tapered: the tilt is gone, h_rms back near 0.3 µm, and it slides.
    let levelled = format!("{surface}detrend = \"plane\"\ntaper = 0.1\n{MATERIAL}[sliding]\nloads = [0.05]\n");
    let run_file = dir.path().join("levelled.toml");
    std::fs::write(&run_file, levelled).unwrap();
    let o = run(&["surface", s(&run_file), "--out", s(&dir.path().join("levelled"))]);
    assert!(o.status.success(), "{}", stderr(&o));
    let stats: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("levelled/statistics.json")).unwrap()).unwrap();
    let h = stats["top"]["rms_height"].as_f64().unwrap();
    assert!(h > 0.15e-6 && h < 0.35e-6, "{h}");
    assert_eq!(stats["surfaces"]["detrend"], "plane");
    let out = dir.path().join("slide");
    let o = run(&["slide", s(&run_file), "--out", s(&out), "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["inputs"]["surfaces"]["height_unit"], "um");
    assert!(summary["results"][0]["static_wear_coefficient"].as_f64().is_some());
    // A contact at an offset given in pixels.
    let o = run(&[
        "contact",
        s(&run_file),
        "--load",
        "0.05",
        "--offset-px",
        "3",
        "--out",
        s(&dir.path().join("c")),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn column_files_state_their_size_and_bad_files_name_the_line() {
    let dir = tempfile::tempdir().unwrap();
    for (name, seed) in [("top.xyz", 1), ("bottom.xyz", 2)] {
        let h = measured(&dir.path().join("tmp.csv"), seed);
        let mut text = String::from("# x y z in um\n");
        for i in 0..63 {
            for j in 0..47 {
                writeln!(text, "{} {} {}", i as f64 * 0.5, j as f64 * 0.5, h[i * 47 + j]).unwrap();
            }
        }
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    let surface = "units = \"si\"\n[surface]\ntop = \"top.xyz\"\nbottom = \"bottom.xyz\"\nheight_unit = \"um\"\n";
    let run_file = dir.path().join("xyz.toml");
    std::fs::write(&run_file, format!("{surface}{MATERIAL}")).unwrap();
    let o = run(&["surface", s(&run_file), "--out", s(&dir.path().join("o"))]);
    assert!(o.status.success(), "{}", stderr(&o));
    let stats: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("o/statistics.json")).unwrap()).unwrap();
    assert!((stats["top"]["pixel_size"].as_f64().unwrap() - 0.5e-6).abs() < 1e-15);
    // A length that contradicts the coordinates, a unit in a reduced run, a ragged matrix.
    std::fs::write(&run_file, format!("{surface}length = 1e-3\n{MATERIAL}")).unwrap();
    let e = stderr(&run(&["surface", s(&run_file), "--out", s(&dir.path().join("p"))]));
    assert!(e.contains("top.xyz") && e.contains("coordinates span"), "{e}");
    std::fs::write(
        &run_file,
        format!("{}{MATERIAL}", surface.replace("units = \"si\"\n", "")),
    )
    .unwrap();
    let e = stderr(&run(&["surface", s(&run_file), "--out", s(&dir.path().join("p"))]));
    assert!(e.contains("height_unit") && e.contains("si"), "{e}");
    std::fs::write(dir.path().join("top.csv"), "1,2,3\n4,5\n").unwrap();
    std::fs::write(
        &run_file,
        format!("[surface]\ntop = \"top.csv\"\nbottom = \"top.csv\"\nlength = 1.0\n{MATERIAL}"),
    )
    .unwrap();
    let e = stderr(&run(&["surface", s(&run_file), "--out", s(&dir.path().join("p"))]));
    assert!(e.contains("top.csv") && e.contains("line 2"), "{e}");
    assert!(!dir.path().join("p").exists());
}

#[test]
fn surface_fit_recovers_generated_parameters_and_its_block_runs() {
    let dir = tempfile::tempdir().unwrap();
    let generated = dir.path().join("gen.toml");
    std::fs::write(
        &generated,
        format!(
            "[surface]\ngrid = [256, 128]\nlength = 1.0\nhurst = 0.6\nlambda_lower = 0.015625\nlambda_upper = 0.25\n\
             rms_height = 0.004\nseed = 3\n{}",
            "[material]\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.01\nfracture_energies = [1e-7]\n"
        ),
    )
    .unwrap();
    assert!(run(&["surface", s(&generated), "--out", s(&dir.path().join("s"))])
        .status
        .success());
    let fit = dir.path().join("fit");
    let o = run(&[
        "surface",
        "fit",
        s(&dir.path().join("s/top.npy")),
        "--length",
        "1.0",
        "--detrend",
        "none",
        "--out",
        s(&fit),
        "--generate",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // An array states no size: the error says which flag gives it, once, naming the file once.
    let e = stderr(&run(&["surface", "fit", s(&dir.path().join("s/top.npy"))]));
    assert!(e.contains("--length") && e.matches("top.npy").count() == 1, "{e}");
    let record: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(fit.join("fit.json")).unwrap()).unwrap();
    let f = &record["fit"];
    let within = |v: &serde_json::Value, truth: f64| {
        let v = v.as_f64().unwrap();
        v / truth < 1.2 && truth / v < 1.2
    };
    assert!((f["hurst"].as_f64().unwrap() - 0.6).abs() <= 0.05, "{f}");
    assert!(
        within(&f["lambda_lower"], 0.015625) && within(&f["lambda_upper"], 0.25),
        "{f}"
    );
    assert!(fit.join("top.npy").is_file() && fit.join("bottom.npy").is_file());
    // The block is a run file's [surface] table as it stands.
    let block = std::fs::read_to_string(fit.join("surface.toml")).unwrap();
    assert!(stdout(&o).contains(&block));
    let run_file = dir.path().join("from-fit.toml");
    std::fs::write(
        &run_file,
        format!(
            "{block}[material]\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.01\nfracture_energies = \
             [1e-7]\n"
        ),
    )
    .unwrap();
    let o = run(&["surface", s(&run_file), "--out", s(&dir.path().join("again"))]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("256×128 pixels"));
}

#[test]
fn a_study_on_maps_that_are_not_periodic_keeps_their_warnings_as_slide_does() {
    let dir = tempfile::tempdir().unwrap();
    // Two 64² maps with a tilt along x: a step across the border of 0.05 L against neighbouring
    // steps of a few 1e-3 L, as a measured map has before levelling.
    let grid = Grid::square(64, 1.0).unwrap();
    let spectrum = SpectrumParams::paper_roughness(64, 1.0);
    let (top_seed, bottom_seed) = pair_seeds(2);
    for (name, seed) in [("top.npy", top_seed), ("bottom.npy", bottom_seed)] {
        let h = Surface::generate(grid, &spectrum, seed).unwrap().into_heights();
        let tilted: Vec<f64> = h
            .iter()
            .enumerate()
            .map(|(k, h)| h + 0.05 * (k / 64) as f64 / 64.0)
            .collect();
        write_npy(&dir.path().join(name), &[64, 64], &tilted);
    }
    let run_file = dir.path().join("measured.toml");
    std::fs::write(
        &run_file,
        "[surface]\ntop = \"top.npy\"\nbottom = \"bottom.npy\"\nlength = 1.0\n[material]\nyoungs_modulus = 1.0\n\
         poisson_ratio = 0.3\nshear_strength = 0.01\nfracture_energies = [0.5e-6]\n[sliding]\nloads = [1e-3]\n",
    )
    .unwrap();
    let read = |p: &Path| -> serde_json::Value { serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap() };
    let o = run(&["slide", s(&run_file), "--out", s(&dir.path().join("slide")), "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let slide = read(&dir.path().join("slide/summary.json"))["warnings"].clone();
    let not_periodic = |w: &serde_json::Value| -> Vec<String> {
        w.as_array()
            .unwrap()
            .iter()
            .filter_map(|w| w.as_str())
            .filter(|w| w.contains("is not periodic"))
            .map(String::from)
            .collect()
    };
    let from_slide = not_periodic(&slide);
    assert_eq!(from_slide.len(), 2, "{slide}");
    assert!(from_slide[0].contains("top.npy") && from_slide[1].contains("bottom.npy"));

    // The same run file as a study of one job: its job file has every warning of `slide`, in order.
    let study = dir.path().join("study");
    let o = run(&["study", "run", s(&run_file), "--out", s(&study)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let job = read(&study.join("jobs/job-000000.json"));
    assert_eq!(job["warnings"], slide);
    assert_eq!(not_periodic(&job["warnings"]), from_slide);
    // And the results table, whose warnings column holds those of each row.
    let o = run(&["study", "collect", s(&study)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let table = std::fs::read_to_string(study.join("results.csv")).unwrap();
    let mut reader = csv::Reader::from_reader(table.as_bytes());
    let column = reader.headers().unwrap().iter().position(|c| c == "warnings").unwrap();
    let row = reader.records().next().unwrap().unwrap();
    // The row's warnings joined by "; " (which some warnings hold too).
    assert!(
        from_slide.iter().all(|w| row[column].contains(w.as_str())),
        "{}",
        &row[column]
    );
}

/// `surface fit` on surfaces `wearsim surface` generated, levelled by a plane as by default: beyond
/// λ_l such a surface holds only round-off and the leakage of the levelling, far under the band; the
/// fit leaves that floor out and recovers H, λ_l and λ_u, for both generation methods.
#[test]
fn surface_fit_leaves_out_the_floor_beyond_the_cut_off_of_generated_surfaces() {
    let dir = tempfile::tempdir().unwrap();
    for (generation, hurst, lower, seed) in [
        ("random-phase", 0.8, 1.0 / 64.0, 1),
        ("random-phase", 0.5, 1.0 / 32.0, 2),
        ("filtered-noise", 0.7, 1.0 / 64.0, 3),
        ("filtered-noise", 0.8, 1.0 / 32.0, 1),
    ] {
        let case = format!("{generation} H {hurst} λ_l {lower} seed {seed}");
        let run_file = dir.path().join(format!("{generation}-{seed}.toml"));
        std::fs::write(
            &run_file,
            format!(
                "[surface]\ngrid = 512\nlength = 1.0\nhurst = {hurst}\nlambda_lower = {lower}\nlambda_upper = 0.25\n\
                 rms_height = 0.01\nseed = {seed}\ngeneration = \"{generation}\"\n[material]\nyoungs_modulus = 1.0\n\
                 poisson_ratio = 0.3\nshear_strength = 0.01\nfracture_energies = [1e-7]\n"
            ),
        )
        .unwrap();
        let generated = dir.path().join(format!("{generation}-{seed}"));
        assert!(run(&["surface", s(&run_file), "--out", s(&generated)]).status.success());
        let out = dir.path().join(format!("{generation}-{seed}-fit"));
        let o = run(&[
            "surface",
            "fit",
            s(&generated.join("top.npy")),
            "--length",
            "1.0",
            "--out",
            s(&out),
        ]);
        let text = stdout(&o);
        assert!(o.status.success(), "{case}: {}", stderr(&o));
        let value = |key: &str| -> f64 {
            let line = text.lines().find(|l| l.starts_with(&format!("{key} = "))).unwrap();
            line[key.len() + 3..].parse().unwrap()
        };
        let within = |v: f64, truth: f64| v / truth < 1.25 && truth / v < 1.25;
        assert!((value("hurst") - hurst).abs() <= 0.05, "{case}:\n{text}");
        assert!(
            within(value("lambda_lower"), lower) && within(value("lambda_upper"), 0.25),
            "{case}:\n{text}"
        );
        // The output says which band was fitted and that the floor beyond it was left out.
        assert!(
            text.contains("fitted C(q) ∝ q^−2(1+H) over q = ") && text.contains("left out: "),
            "{text}"
        );
        let record: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("fit.json")).unwrap()).unwrap();
        let f = &record["fit"];
        let q = f["fitted_q"].as_array().unwrap();
        assert!(
            q[1].as_f64().unwrap() <= 2.0 * std::f64::consts::PI / lower,
            "{case}: {f}"
        );
        assert!(
            f["shells_shorter"].as_u64().unwrap() > 200 && f["floor"].as_f64().unwrap() < 1e-6,
            "{case}: {f}"
        );
    }
}
