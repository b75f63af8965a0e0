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

/// `fit.json` of an output folder of `surface fit`.
fn fit_record(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("fit.json")).unwrap()).unwrap()
}

/// A value `key = v` of the block `surface fit` printed.
/// `surface fit DIR/NAME.npy --length 1.0 --out DIR/NAME-fit`, which must succeed: its output and
/// fit.json.
fn fit_unit_box(dir: &Path, name: &str) -> (std::process::Output, serde_json::Value) {
    let out = dir.join(format!("{name}-fit"));
    let o = run(&[
        "surface",
        "fit",
        s(&dir.join(format!("{name}.npy"))),
        "--length",
        "1.0",
        "--out",
        s(&out),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    (o, fit_record(&out))
}

fn block_value(text: &str, key: &str) -> f64 {
    let line = text.lines().find(|l| l.starts_with(&format!("{key} = "))).unwrap();
    line[key.len() + 3..].parse().unwrap()
}

/// A map whose variance lies 56 % beyond λ_u (a self-affine band of h_rms 0.01 between λ_l = 1/64
/// and λ_u = 1/8, and a cosine of the box's wavelength): the block `surface fit` prints carries the
/// band's h_rms (paper §4.1: the generated surfaces hold the power law between λ_u and λ_l and
/// nothing else), not the whole map's, which would give them 2.3 times the measured PSD level in
/// the band; fit.json keeps the whole map's and the share outside the band, and a note says it.
/// A generated surface is its band: the two agree and no note is printed.
#[test]
fn surface_fit_writes_the_rms_height_of_the_band_and_reports_the_whole_maps() {
    let dir = tempfile::tempdir().unwrap();
    let grid = Grid::square(512, 1.0).unwrap();
    let spectrum = SpectrumParams {
        hurst: 0.7,
        lambda_lower: 1.0 / 64.0,
        lambda_upper: 1.0 / 8.0,
        rms_height: 0.01,
        generation: Generation::RandomPhase,
    };
    let band = Surface::generate(grid, &spectrum, 2).unwrap().into_heights();
    let outside: f64 = 1e-4 * 0.56 / 0.44;
    let map: Vec<f64> = band
        .iter()
        .enumerate()
        .map(|(k, h)| h + (2.0 * outside).sqrt() * (2.0 * std::f64::consts::PI * (k / 512) as f64 / 512.0).cos())
        .collect();
    write_npy(&dir.path().join("wavy.npy"), &[512, 512], &map);
    write_npy(&dir.path().join("band.npy"), &[512, 512], &band);
    let fit = |name: &str| fit_unit_box(dir.path(), name);
    let (o, record) = fit("wavy");
    let (text, f) = (stdout(&o), &record["fit"]);
    let value = |key: &str| f[key].as_f64().unwrap();
    assert!((value("hurst") - 0.7).abs() <= 0.05, "{f}");
    assert!((value("rms_height") / 0.01 - 1.0).abs() < 0.03, "{f}");
    // The whole map's, levelled by a plane (which takes a little of the cosine).
    assert!(
        (value("map_rms_height") / (1e-4 + outside).sqrt() - 1.0).abs() < 1e-3,
        "{f}"
    );
    assert!((value("out_of_band_share") - 0.56).abs() < 0.02, "{f}");
    assert!(
        f["measured_pixel"].is_null() && record["measured_pixel_from"].is_null(),
        "{record}"
    );
    // The block and the spectrum it generates carry the band's h_rms, to its four digits.
    assert_eq!(record["spectrum"]["rms_height"], f["rms_height"]);
    assert!(
        (block_value(&text, "rms_height") / value("rms_height") - 1.0).abs() < 1e-4,
        "{text}"
    );
    assert!(
        text.contains(&format!("h_rms of the band {:.4e}", value("rms_height")))
            && text.contains("56.0 % of its variance outside"),
        "{text}"
    );
    let e = stderr(&o);
    assert!(
        e.contains("note: 56 % of the map's variance lies outside the self-affine band")
            && e.contains("is the band's, not the whole map's"),
        "{e}"
    );
    assert!(
        record["notes"].to_string().contains("56 % of the map's variance"),
        "{record}"
    );

    let (o, record) = fit("band");
    let f = &record["fit"];
    assert!((f["rms_height"].as_f64().unwrap() / 0.01 - 1.0).abs() < 0.01, "{f}");
    assert!(f["out_of_band_share"].as_f64().unwrap() < 0.01, "{f}");
    assert!(!stderr(&o).contains("outside the self-affine band"), "{}", stderr(&o));
}

/// A map `wearsim surface import --resample` wrote: measured with pixels twice as long along y
/// (every other row of a 256² self-affine surface whose power law runs to the pixel scale) and
/// put on square pixels (each measured row repeated), with its import.json. `surface fit` on
/// DIR/heights.npy reads the native pixels there and fits the measured wavevectors only: H within
/// 0.05 of the original map's, where the same map elsewhere (no import.json) is fitted on the
/// interpolated part of its spectrum too and H is off by more than 0.08; `--measured-pixel` gives
/// the same fit as the import.json.
#[test]
fn surface_fit_of_a_resampled_map_uses_its_measured_wavevectors() {
    let dir = tempfile::tempdir().unwrap();
    let n = 256;
    let grid = Grid::square(n, 1.0).unwrap();
    let spectrum = SpectrumParams {
        hurst: 0.7,
        lambda_lower: 2.0 / n as f64,
        lambda_upper: 0.25,
        rms_height: 0.01,
        generation: Generation::RandomPhase,
    };
    let original = Surface::generate(grid, &spectrum, 1).unwrap().into_heights();
    let resampled: Vec<f64> = (0..n * n).map(|k| original[k - k % 2]).collect();
    write_npy(&dir.path().join("original.npy"), &[n, n], &original);
    write_npy(&dir.path().join("copy.npy"), &[n, n], &resampled);
    let imported = dir.path().join("imported");
    std::fs::create_dir(&imported).unwrap();
    write_npy(&imported.join("heights.npy"), &[n, n], &resampled);
    // As `surface import` records it: native pixels 0.5 µm × 1 µm, resampled onto 0.5 µm.
    let import = serde_json::json!({
        "written_by": "wearsim surface import",
        "grid": [n, n / 2],
        "physical_sizes": [n as f64 * 0.5, n as f64 * 0.5],
        "unit": "µm",
        "pixel_size": [0.5, 1.0],
        "resampled": {"grid": [n, n], "physical_sizes": [n as f64 * 0.5, n as f64 * 0.5], "pixel_size": 0.5, "method": "linear"},
        "metres_per_unit": 1e-6,
        "heights_grid": [n, n],
        "length": [n as f64 * 0.5e-6, n as f64 * 0.5e-6],
        "pixel_size_m": 0.5e-6,
    });
    std::fs::write(imported.join("import.json"), import.to_string()).unwrap();
    let fit = |map: &Path, name: &str, extra: &[&str]| {
        let out = dir.path().join(name);
        let mut args = vec!["surface", "fit", s(map), "--length", "1.0", "--out", s(&out)];
        args.extend_from_slice(extra);
        let o = run(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        (stderr(&o), fit_record(&out))
    };
    let hurst = |r: &serde_json::Value| r["fit"]["hurst"].as_f64().unwrap();
    let (_, o) = fit(&dir.path().join("original.npy"), "original", &[]);
    let (e, from_import) = fit(&imported.join("heights.npy"), "from-import", &[]);
    let (_, all) = fit(&dir.path().join("copy.npy"), "all", &[]);
    let pixel = (1.0 / n as f64).to_string();
    let twice = (2.0 / n as f64).to_string();
    let (_, given) = fit(
        &dir.path().join("copy.npy"),
        "given",
        &["--measured-pixel", &pixel, "--measured-pixel", &twice],
    );
    assert!(
        e.contains("note: the map was resampled onto finer pixels") && e.contains("import.json"),
        "{e}"
    );
    let native = &from_import["fit"]["measured_pixel"];
    assert!(
        (native[0].as_f64().unwrap() * n as f64 - 1.0).abs() < 1e-9
            && (native[1].as_f64().unwrap() * n as f64 - 2.0).abs() < 1e-9,
        "{from_import}"
    );
    assert!(from_import["measured_pixel_from"]
        .as_str()
        .unwrap()
        .contains("import.json"));
    assert!(all["fit"]["measured_pixel"].is_null());
    assert!((hurst(&from_import) - hurst(&o)).abs() <= 0.05, "{from_import}\n{o}");
    assert!((hurst(&all) - hurst(&o)).abs() > 0.08, "{all}\n{o}");
    assert_eq!(given["fit"], from_import["fit"]);
    assert_eq!(given["measured_pixel_from"], "--measured-pixel");

    // Three sides, a native pixel finer than the map's, and an import.json of another map are
    // refused by name.
    let e = stderr(&run(&[
        "surface",
        "fit",
        s(&dir.path().join("copy.npy")),
        "--length",
        "1.0",
        "--measured-pixel",
        "0.01",
        "--measured-pixel",
        "0.01",
        "--measured-pixel",
        "0.01",
    ]));
    assert!(e.contains("--measured-pixel given 3 times"), "{e}");
    let e = stderr(&run(&[
        "surface",
        "fit",
        s(&dir.path().join("copy.npy")),
        "--length",
        "1.0",
        "--measured-pixel",
        "0.001",
    ]));
    assert!(e.contains("smaller than the map's pixel"), "{e}");
    let mut other = import.clone();
    other["heights_grid"] = serde_json::json!([n, n / 2]);
    std::fs::write(imported.join("import.json"), other.to_string()).unwrap();
    let e = stderr(&run(&[
        "surface",
        "fit",
        s(&imported.join("heights.npy")),
        "--length",
        "1.0",
    ]));
    assert!(
        e.contains("import.json describes a 256 × 128 map") && e.contains("--measured-pixel"),
        "{e}"
    );
}

/// The generated surfaces' rms slope beside the map's, where the h_rms change is said: a band with
/// white noise at the pixel scale (left out of the fit beyond λ_l) keeps most of its h_rms and loses
/// most of its slope, which a note says, with both slopes in fit.json; the band alone changes its
/// slope by little, and no note is given.
#[test]
fn surface_fit_says_how_much_the_generated_surfaces_change_the_rms_slope() {
    let dir = tempfile::tempdir().unwrap();
    let grid = Grid::square(256, 1.0).unwrap();
    let spectrum = SpectrumParams {
        hurst: 0.8,
        lambda_lower: 1.0 / 32.0,
        lambda_upper: 1.0 / 4.0,
        rms_height: 0.01,
        generation: Generation::RandomPhase,
    };
    let band = Surface::generate(grid, &spectrum, 5).unwrap().into_heights();
    // Deterministic white noise of 10 % of the band's rms: as steep as the band at the pixel scale.
    let mut state = 12345u64;
    let noisy: Vec<f64> = band
        .iter()
        .map(|h| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            h + 1e-3 * 3f64.sqrt() * (2.0 * ((state >> 11) as f64 / (1u64 << 53) as f64) - 1.0)
        })
        .collect();
    write_npy(&dir.path().join("noisy.npy"), &[256, 256], &noisy);
    write_npy(&dir.path().join("band.npy"), &[256, 256], &band);
    let fit = |name: &str| fit_unit_box(dir.path(), name);
    let (o, record) = fit("noisy");
    let slopes = &record["rms_slope"];
    let (map, generated) = (slopes["map"].as_f64().unwrap(), slopes["generated"].as_f64().unwrap());
    assert!(generated < 0.8 * map, "{record}");
    let change = format!("{:+.0} %", 100.0 * (generated / map - 1.0));
    let e = stderr(&o);
    assert!(
        e.contains("note: the generated surfaces' rms slope") && e.contains(&change),
        "{e}\n{change}"
    );
    assert!(
        stdout(&o).contains("rms slope of the generated surfaces"),
        "{}",
        stdout(&o)
    );
    assert!(record["notes"].to_string().contains("rms slope"), "{record}");
    let (o, record) = fit("band");
    let slopes = &record["rms_slope"];
    let change = slopes["generated"].as_f64().unwrap() / slopes["map"].as_f64().unwrap() - 1.0;
    assert!(change.abs() < 0.1, "{record}");
    assert!(!stderr(&o).contains("rms slope"), "{}", stderr(&o));
}

/// A flat map (one value, or a plane that the levelling leaves as round-off) has a zero spectrum:
/// `surface fit` says so instead of writing a block that cannot run, and a run file's
/// `source = "spectrum"` on it says the same.
#[test]
fn a_flat_map_is_said_to_have_no_spectrum() {
    let dir = tempfile::tempdir().unwrap();
    write_npy(&dir.path().join("flat.npy"), &[32, 32], &[3.0; 32 * 32]);
    let plane: Vec<f64> = (0..32 * 32)
        .map(|k| 0.01 * (k / 32) as f64 + 0.002 * (k % 32) as f64)
        .collect();
    write_npy(&dir.path().join("plane.npy"), &[32, 32], &plane);
    for name in ["flat.npy", "plane.npy"] {
        let map = dir.path().join(name);
        let o = run(&[
            "surface",
            "fit",
            s(&map),
            "--length",
            "1",
            "--out",
            s(&dir.path().join("fit")),
        ]);
        let e = stderr(&o);
        assert!(!o.status.success(), "{e}");
        assert!(e.contains("the map is flat") && e.contains("spectrum is zero"), "{e}");
        assert!(
            !stdout(&o).contains("source = \"spectrum\"") && !dir.path().join("fit").exists(),
            "{e}"
        );
        let run_path = common::run_file(
            dir.path(),
            &format!(
                "[surface]\nsource = \"spectrum\"\nmap = {map:?}\nmap_length = 1\ngrid = 32\nlength = 1\n\
                 [material]\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.01\n\
                 fracture_energies = [1e-6]\n"
            ),
        );
        let o = run(&["surface", s(&run_path), "--out", s(&dir.path().join("pair"))]);
        let e = stderr(&o);
        assert!(!o.status.success() && e.contains("the map is flat"), "{e}");
        assert!(!e.contains("holds no wavevector"), "{e}");
    }
}
