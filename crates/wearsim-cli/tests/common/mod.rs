//! Helpers shared by the CLI tests: the binary, small run files, a `.npy` writer.
#![allow(dead_code)] // each test file uses its own part

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The binary, without the cost estimate before a run (its calibration would take seconds in every
/// test; `tests/cost.rs` tests it).
pub fn wearsim() -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_wearsim"));
    command.env("WEARSIM_NO_ESTIMATE", "1");
    command
}

/// Runs `wearsim` with `args`.
pub fn run(args: &[&str]) -> Output {
    wearsim().args(args).output().unwrap()
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).to_string()
}

pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).to_string()
}

/// A path as &str for arguments.
pub fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Minimal NumPy v1.0 writer for little-endian arrays of any shape; `descr` as NumPy writes it
/// (`<f8`, `<i4`, …) and `bytes` the raw data.
pub fn write_npy_raw(path: &Path, descr: &str, shape: &[usize], data: &[u8]) {
    let shape_txt = match shape.len() {
        1 => format!("({},)", shape[0]),
        _ => format!(
            "({})",
            shape.iter().map(|s| s.to_string()).collect::<Vec<_>>().join(", ")
        ),
    };
    let mut header = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape_txt}, }}");
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend_from_slice(&(header.len() as u16).to_le_bytes());
    bytes.extend_from_slice(header.as_bytes());
    bytes.extend_from_slice(data);
    std::fs::write(path, bytes).unwrap();
}

/// Float64 `.npy` of any shape.
pub fn write_npy(path: &Path, shape: &[usize], values: &[f64]) {
    let data: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
    write_npy_raw(path, "<f8", shape, &data);
}

/// A 64² generated run without a [sliding] table.
/// An SI run's [surface] and the start of its [material]: a 64² box of 0.5 µm pixels, SiC-like
/// moduli; the strength and fracture energies are the test's.
pub const SI_SIC: &str = "units = \"si\"\n[surface]\ngrid = 64\nlength = 32e-6\nlambda_lower = 4e-6\n\
    lambda_upper = 8e-6\nrms_height = 1.6e-7\nseed = 1\n[material]\nyoungs_modulus = 400e9\npoisson_ratio = 0.2\n";

pub const GENERATED: &str = r#"
[surface]
grid = 64
length = 1.0
lambda_lower = 0.0625
lambda_upper = 0.25
rms_height = 0.005
seed = 1
[material]
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = 0.01
fracture_energies = [0.5e-6]
"#;

/// Writes `text` as `name` in `dir`.
pub fn file(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

pub fn run_file(dir: &Path, text: &str) -> PathBuf {
    file(dir, "run.toml", text)
}
