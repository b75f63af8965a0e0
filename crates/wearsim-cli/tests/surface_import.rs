//! `wearsim surface import`: an instrument file (and the counter-body's, `--bottom`) turned into the
//! maps of a run's two bodies (in Python, with SurfaceTopography), and the pointer to it where an
//! instrument file is refused.

use crate::common;

use std::process::Command;

use common::{run, s, stderr, stdout};

#[test]
fn without_the_package_the_import_says_what_to_install_before_making_any_folder() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("map.x3p");
    std::fs::write(&file, b"PK\x03\x04\xff\xfe\x00\x01").unwrap();
    let out = dir.path().join("imported");
    for python in ["/bin/false", "/nonexistent/python3"] {
        let o = run(&["surface", "import", s(&file), "--out", s(&out), "--python", python]);
        let e = stderr(&o);
        assert!(!o.status.success(), "{e}");
        assert!(e.contains("pip install \"wearsim[measured]\""), "{e}");
        assert!(e.contains(python) && e.contains("--python"), "{e}");
        assert_eq!(e.trim().lines().count(), 1, "{e}");
        assert!(!out.exists(), "{e}");
    }
    // A missing file is named before Python is asked.
    let o = run(&["surface", "import", s(&dir.path().join("none.x3p")), "--out", s(&out)]);
    assert!(
        !o.status.success() && stderr(&o).contains("none.x3p: no such file"),
        "{}",
        stderr(&o)
    );
    assert!(!out.exists());
    // So is a missing second map.
    let o = run(&[
        "surface",
        "import",
        s(&file),
        "--bottom",
        s(&dir.path().join("other.x3p")),
        "--out",
        s(&out),
        "--python",
        "/bin/false",
    ]);
    assert!(
        !o.status.success() && stderr(&o).contains("other.x3p: no such file"),
        "{}",
        stderr(&o)
    );
    assert!(!out.exists());
}

#[test]
fn an_instrument_file_refused_by_surface_fit_points_to_surface_import() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("scan.x3p");
    std::fs::write(&file, b"PK\x03\x04\x14\x00\x08\x00\xff\xfe\xfd binary").unwrap();
    let o = run(&["surface", "fit", s(&file), "--length", "1"]);
    let e = stderr(&o);
    assert!(!o.status.success(), "{e}");
    assert!(e.contains("neither a .npy/.npz array nor text"), "{e}");
    assert!(e.contains("wearsim surface import FILE --out DIR"), "{e}");
    assert!(
        e.contains("read_topography") && e.contains("wearsim.heights_and_length"),
        "{e}"
    );
}

/// The interpreter of $WEARSIM_PYTHON when it has wearsim's `measured` module and SurfaceTopography.
fn python_with_the_package() -> Option<String> {
    let python = std::env::var("WEARSIM_PYTHON").ok()?;
    let ok = Command::new(&python)
        .args(["-c", "import wearsim.measured, SurfaceTopography"])
        .output()
        .map(|o| o.status.success())
        .unwrap_or(false);
    ok.then_some(python)
}

#[test]
fn an_imported_map_reads_in_surface_fit_and_in_a_run_file() {
    let Some(python) = python_with_the_package() else {
        eprintln!("skipped: WEARSIM_PYTHON names no interpreter with wearsim[measured] (SurfaceTopography)");
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("scan.nc");
    // A tilted self-affine 65×64 map in µm, 0.5 µm pixels, written by SurfaceTopography's own
    // NetCDF writer.
    let make = format!(
        "import numpy as np, wearsim; from SurfaceTopography import Topography\n\
         g = wearsim.generate_surface(64, length=32.0, hurst=0.8, lambda_lower=2.0, lambda_upper=16.0, \
         rms_height=0.1, seed=3)\n\
         h = np.vstack([g, g[:1]]) + 0.01 * np.arange(65)[:, None] + 0.002 * np.arange(64)[None, :]\n\
         Topography(h, (32.5, 32.0), unit='um').to_netcdf({:?})\n",
        s(&file)
    );
    let o = Command::new(&python).args(["-c", &make]).output().unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let out = dir.path().join("imported");
    let o = run(&["surface", "import", s(&file), "--out", s(&out), "--python", &python]);
    let text = stdout(&o);
    assert!(o.status.success(), "{}{text}", stderr(&o));
    assert!(text.contains("cropped") && text.contains("64×64"), "{text}");
    assert!(text.contains("[surface]") && text.contains("heights.npy"), "{text}");
    // Without --bottom the bottom body is the map rotated by 180° about its centre.
    assert!(
        text.contains("bottom.npy\"  # the map rotated by 180° about its centre"),
        "{text}"
    );
    let record: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("import.json")).unwrap()).unwrap();
    let lx = record["length"][0].as_f64().unwrap();
    assert!((lx - 32e-6).abs() < 1e-12, "{record}");
    assert_eq!(record["metres_per_unit"].as_f64().unwrap(), 1e-6, "{record}");
    assert_eq!(record["detrend"], "plane", "{record}");
    assert_eq!(record["bodies"]["bottom"]["rule"], "rotated-180", "{record}");
    assert!(out.join("bottom.npy").is_file());
    // Again into the same folder: it is the import's own, so it is replaced; a foreign one is not.
    let o = run(&["surface", "import", s(&file), "--out", s(&out), "--python", &python]);
    assert!(o.status.success(), "{}", stderr(&o));
    let foreign = dir.path().join("foreign");
    std::fs::create_dir(&foreign).unwrap();
    std::fs::write(foreign.join("notes.txt"), "mine").unwrap();
    let o = run(&["surface", "import", s(&file), "--out", s(&foreign), "--python", &python]);
    assert!(
        !o.status.success() && stderr(&o).contains("--overwrite"),
        "{}",
        stderr(&o)
    );
    assert_eq!(std::fs::read_to_string(foreign.join("notes.txt")).unwrap(), "mine");

    let map = out.join("heights.npy");
    let o = run(&["surface", "fit", s(&map), "--length", &lx.to_string()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("hurst"), "{}", stdout(&o));
    let run_file = dir.path().join("run.toml");
    std::fs::write(
        &run_file,
        format!(
            "units = \"si\"\n[surface]\ntop = \"imported/heights.npy\"\nbottom = \"imported/bottom.npy\"\nlength = {lx:e}\n\
             [material]\nyoungs_modulus = 3e11\npoisson_ratio = 0.25\nshear_strength = 3e9\nfracture_energies = [10.0]\n\
             [sliding]\nloads = [1e-6]\n"
        ),
    )
    .unwrap();
    let generated = dir.path().join("surfaces");
    let o = run(&["surface", s(&run_file), "--out", s(&generated)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("64×64 pixels"), "{}", stdout(&o));
}

/// Runs `code` in `python`, failing the test with its error.
fn python_run(python: &str, code: &str) {
    let o = Command::new(python).args(["-c", code]).output().unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn a_second_map_given_with_bottom_is_the_bottom_body_of_the_block_and_one_on_another_grid_is_refused() {
    let Some(python) = python_with_the_package() else {
        eprintln!("skipped: WEARSIM_PYTHON names no interpreter with wearsim[measured] (SurfaceTopography)");
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Two self-affine maps of 0.5 µm pixels by SurfaceTopography's NetCDF writer: the top one 65×64
    // in µm (its odd side cropped), the counter-body 64×64 in nm, written under a name that starts
    // with '-'; and a 64×48 one.
    python_run(
        &python,
        &format!(
            "import numpy as np, wearsim, os; from SurfaceTopography import Topography\n\
             os.chdir({:?})\n\
             g = lambda ny, seed: wearsim.generate_surface((64, ny), length=32.0, hurst=0.8, lambda_lower=2.0, \
             lambda_upper=16.0, rms_height=0.1, seed=seed)\n\
             a = g(64, 3)\n\
             Topography(np.vstack([a, a[:1]]), (32.5, 32.0), unit='um').to_netcdf('top.nc')\n\
             Topography(1e3 * g(64, 4), (32e3, 32e3), unit='nm').to_netcdf('-counter.nc')\n\
             Topography(g(48, 5), (32.0, 24.0), unit='um').to_netcdf('narrow.nc')\n",
            s(d)
        ),
    );
    let o = common::wearsim()
        .current_dir(d)
        .args([
            "surface",
            "import",
            "top.nc",
            "--bottom=-counter.nc",
            "--out",
            "pair",
            "--python",
            &python,
        ])
        .output()
        .unwrap();
    let text = stdout(&o);
    assert!(o.status.success(), "{}{text}", stderr(&o));
    assert!(
        text.contains("bottom: read -counter.nc") && text.contains("top: cropped"),
        "{text}"
    );
    assert!(text.contains("bottom body: the second map"), "{text}");
    assert!(
        text.contains("top = \"pair/heights.npy\"")
            && text.contains("bottom = \"pair/bottom.npy\"  # the second map \"-counter.nc\""),
        "{text}"
    );
    let record: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("pair").join("import.json")).unwrap()).unwrap();
    let bottom = &record["bodies"]["bottom"];
    assert_eq!(bottom["rule"], "second-map", "{record}");
    assert_eq!(bottom["file"], "bottom.npy", "{record}");
    assert!(bottom["source"].as_str().unwrap().ends_with("/-counter.nc"), "{record}");
    assert_eq!(record["bottom_map"]["unit"], "nm", "{record}");
    assert_eq!(record["bottom_map"]["heights_grid"], record["heights_grid"], "{record}");

    // The block as printed, in a run file beside the folder: `surface` and `contact` read both bodies.
    let block = record["surface_toml"].as_str().unwrap();
    let run_file = d.join("run.toml");
    std::fs::write(
        &run_file,
        format!(
            "{block}[material]\nyoungs_modulus = 3e11\npoisson_ratio = 0.25\nshear_strength = 3e9\n\
             fracture_energies = [10.0]\n[sliding]\nloads = [0.05]\n"
        ),
    )
    .unwrap();
    let o = run(&["surface", s(&run_file), "--out", s(&d.join("surfaces"))]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("bottom: 64×64 pixels"), "{}", stdout(&o));
    python_run(
        &python,
        &format!(
            "import numpy as np, os\nos.chdir({:?})\n\
             assert np.array_equal(np.load('surfaces/top.npy'), np.load('pair/heights.npy'))\n\
             assert np.array_equal(np.load('surfaces/bottom.npy'), np.load('pair/bottom.npy'))\n\
             assert not np.array_equal(np.load('pair/bottom.npy'), np.load('pair/heights.npy')[::-1, ::-1])\n",
            s(d)
        ),
    );
    let o = run(&[
        "contact",
        s(&run_file),
        "--load",
        "0.05",
        "--offset-px",
        "5",
        "--out",
        s(&d.join("contact")),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("contact").join("summary.json")).unwrap()).unwrap();
    let area = summary["contact_area"].as_f64().unwrap();
    assert!(area > 0.0 && area < 0.5, "{summary}");

    // A counter-body on another grid: refused in a line that names both grids and the fix; the
    // folder of the earlier import is left as it was.
    let before = std::fs::read(d.join("pair").join("bottom.npy")).unwrap();
    let o = common::wearsim()
        .current_dir(d)
        .args([
            "surface",
            "import",
            "top.nc",
            "--bottom",
            "narrow.nc",
            "--out",
            "pair",
            "--python",
            &python,
        ])
        .output()
        .unwrap();
    let e = stderr(&o);
    assert!(!o.status.success() && !e.contains("Traceback"), "{e}");
    // The import's one line (the command's own line after it says that it failed).
    let line = e.lines().next().unwrap_or_default();
    assert!(
        line.contains("64×64 pixels of 5e-07 m") && line.contains("64×48 pixels of 5e-07 m"),
        "{e}"
    );
    assert!(
        line.contains("narrow.nc (--bottom)") && line.contains("crop both to 64×48 pixels"),
        "{e}"
    );
    assert_eq!(std::fs::read(d.join("pair").join("bottom.npy")).unwrap(), before);
    assert!(std::fs::read_dir(d)
        .unwrap()
        .all(|f| !f.unwrap().file_name().to_string_lossy().ends_with(".tmp")));
}
