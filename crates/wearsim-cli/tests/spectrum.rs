//! `source = "spectrum"`: periodic surface pairs carrying a measured map's 2D PSD slide through the
//! CLI, note what the map cannot say, refuse keys of other sources; `surface fit` says when a
//! spectrum is not self-affine and writes the block that carries it.

use crate::common;

use std::path::Path;

use common::{run, s, stderr, stdout, write_npy};
use wearsim::{Generation, Grid, SpectrumParams, Surface};

const MATERIAL: &str = "[material]\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.01\n\
                        fracture_energies = [0.5e-6]\n";

fn generated(grid: Grid, lower: f64, seed: u64) -> Surface {
    let params = SpectrumParams {
        hurst: 0.7,
        lambda_lower: lower,
        lambda_upper: grid.length_x() / 4.0,
        rms_height: 0.005 * grid.length_x(),
        generation: Generation::RandomPhase,
    };
    Surface::generate(grid, &params, seed).unwrap()
}

/// A measured-style map of n² pixels and side 1 (not periodic: cut out of a surface four times its
/// side); with `squeeze` 2 its features are half as long along y (a lay).
fn map(path: &Path, n: usize, squeeze: usize) {
    let big = generated(Grid::new(4 * n, 4 * n * squeeze, 4.0).unwrap(), 8.0 / n as f64, 3);
    let stride = 4 * n * squeeze;
    let h: Vec<f64> = (0..n * n)
        .map(|k| big.heights()[(k / n) * stride + (k % n) * squeeze])
        .collect();
    write_npy(path, &[n, n], &h);
}

#[test]
fn a_spectrum_pair_slides_notes_a_larger_box_and_refuses_foreign_keys() {
    let dir = tempfile::tempdir().unwrap();
    map(&dir.path().join("map.npy"), 64, 1);
    let surface =
        "[surface]\nsource = \"spectrum\"\nmap = \"map.npy\"\nmap_length = 1.0\ngrid = 32\nlength = 1.0\nseed = 2\n";
    let run_file = dir.path().join("run.toml");
    std::fs::write(
        &run_file,
        format!("{surface}{MATERIAL}[sliding]\nloads = [1e-3]\ndistance = 0.5\n"),
    )
    .unwrap();
    let o = run(&["slide", s(&run_file), "--out", s(&dir.path().join("slide"))]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("carry its measured PSD (hann window"),
        "{}",
        stderr(&o)
    );
    // A box twice the map's: a note that it says nothing about the longer wavelengths.
    let twice = dir.path().join("twice.toml");
    std::fs::write(
        &twice,
        format!(
            "{}{MATERIAL}",
            surface.replace("grid = 32\nlength = 1.0", "grid = 64\nlength = 2.0")
        ),
    )
    .unwrap();
    let o = run(&["surface", s(&twice), "--out", s(&dir.path().join("twice"))]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("is larger than the map"), "{}", stderr(&o));
    assert!(stdout(&o).contains("64×64 pixels"), "{}", stdout(&o));
    // Keys of the other sources, a missing map and one with a missing point are refused by name.
    for (text, expected) in [
        (
            surface.replace("seed = 2", "seed = 2\nhurst = 0.7"),
            "`hurst` has no meaning with source = \"spectrum\"",
        ),
        (surface.replace("map = \"map.npy\"\n", ""), "`map` is missing"),
        (surface.replace("map.npy", "gone.npy"), "height map not found"),
        (
            surface.replace("source = \"spectrum\"\n", ""),
            "`map` applies to source = \"spectrum\"",
        ),
        (
            surface.replace("\"spectrum\"", "\"spectra\""),
            "use \"generated\", \"files\" or \"spectrum\"",
        ),
        (surface.replace("seed = 2", "seed = 2\nwindow = \"hamming\""), "window"),
        (surface.replace("seed = 2", "seed = 2\nmap_size = 1"), "map_size"),
    ] {
        let bad = dir.path().join("bad.toml");
        std::fs::write(&bad, format!("{text}{MATERIAL}")).unwrap();
        let o = run(&["surface", s(&bad), "--out", s(&dir.path().join("bad"))]);
        assert!(
            !o.status.success() && stderr(&o).contains(expected),
            "{expected}: {}",
            stderr(&o)
        );
    }
    let mut h = vec![0.0; 64 * 64];
    h[70] = f64::NAN;
    write_npy(&dir.path().join("nan.npy"), &[64, 64], &h);
    let bad = dir.path().join("nan.toml");
    std::fs::write(&bad, format!("{}{MATERIAL}", surface.replace("map.npy", "nan.npy"))).unwrap();
    let o = run(&["surface", s(&bad), "--out", s(&dir.path().join("nan"))]);
    assert!(
        !o.status.success() && stderr(&o).contains("nan.npy") && stderr(&o).contains("NaN"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn surface_fit_names_a_lay_and_writes_a_spectrum_block_that_runs() {
    let dir = tempfile::tempdir().unwrap();
    let lay = dir.path().join("lay.npy");
    map(&lay, 128, 2);
    let out = dir.path().join("fit");
    let o = run(&["surface", "fit", s(&lay), "--length", "1", "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("is not self-affine (anisotropic (a lay)"),
        "{}",
        stderr(&o)
    );
    assert!(
        stdout(&o).contains("source = \"spectrum\"") && stdout(&o).contains("# hurst = "),
        "{}",
        stdout(&o)
    );
    let fit: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(out.join("fit.json")).unwrap()).unwrap();
    assert_eq!(fit["self_affine"], false, "{fit}");
    assert!(fit["reasons"][0].as_str().unwrap().contains("anisotropic"), "{fit}");
    // The block runs as written (on a smaller grid).
    let block = std::fs::read_to_string(out.join("surface.toml")).unwrap();
    let run_file = dir.path().join("run.toml");
    std::fs::write(
        &run_file,
        format!(
            "{}{MATERIAL}",
            block
                .replace("grid = 128", "grid = 32")
                .replace("length = 1\n", "length = 0.25\n")
        ),
    )
    .unwrap();
    let o = run(&["surface", s(&run_file), "--out", s(&dir.path().join("pair"))]);
    assert!(o.status.success(), "{}\n{block}", stderr(&o));
    assert!(stdout(&o).contains("32×32 pixels"), "{}", stdout(&o));

    // A generated self-affine surface: no note, the self-affine block alone.
    let plain = dir.path().join("plain.npy");
    let g = generated(Grid::square(256, 1.0).unwrap(), 1.0 / 128.0, 1);
    write_npy(&plain, &[256, 256], g.heights());
    let out = dir.path().join("plain");
    let o = run(&["surface", "fit", s(&plain), "--length", "1", "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!stderr(&o).contains("self-affine"), "{}", stderr(&o));
    assert!(!stdout(&o).contains("spectrum\""), "{}", stdout(&o));
    let fit: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(out.join("fit.json")).unwrap()).unwrap();
    assert_eq!(fit["self_affine"], true, "{fit}");
}
