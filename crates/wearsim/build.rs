//! Records the versions of the crates that decide wearsim's numbers (the FFT and the random streams
//! of generated surfaces) for the provenance of every output: read from the workspace's Cargo.lock,
//! which is the lockfile the library was built with. Outside the workspace (no lockfile there) the
//! version is recorded as "unknown" rather than guessed.

use std::path::Path;

/// The crates named in the provenance of every output.
const CRATES: [&str; 4] = ["rustfft", "realfft", "rand_chacha", "rand_distr"];

fn main() {
    let lockfile = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../Cargo.lock");
    println!("cargo:rerun-if-changed={}", lockfile.display());
    let text = std::fs::read_to_string(&lockfile).unwrap_or_default();
    let versions: Vec<String> = CRATES
        .iter()
        .map(|name| format!("{name} {}", locked_version(&text, name).unwrap_or("unknown")))
        .collect();
    println!("cargo:rustc-env=WEARSIM_DEPENDENCY_VERSIONS={}", versions.join(", "));
}

/// The version of the package `name` in a Cargo.lock (the highest, if several are locked).
fn locked_version<'a>(lock: &'a str, name: &str) -> Option<&'a str> {
    let mut best: Option<&str> = None;
    for package in lock.split("[[package]]") {
        let mut lines = package.lines().map(str::trim);
        if lines.clone().any(|l| l == format!("name = \"{name}\"")) {
            if let Some(v) = lines
                .find(|l| l.starts_with("version = \""))
                .map(|l| l.trim_start_matches("version = \"").trim_end_matches('"'))
            {
                if best.is_none_or(|b| newer(v, b)) {
                    best = Some(v);
                }
            }
        }
    }
    best
}

/// Whether dotted version `a` is newer than `b` (numeric parts compared in order).
fn newer(a: &str, b: &str) -> bool {
    let parts = |v: &str| {
        v.split(['.', '-', '+'])
            .map(|p| p.parse::<u64>().unwrap_or(0))
            .collect::<Vec<_>>()
    };
    parts(a) > parts(b)
}
