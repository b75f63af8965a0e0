//! The command-line program's tests (they drive the `wearsim` binary), one file per subject,
//! compiled into one test binary: one build and link instead of one per file.
//! `cargo test -p wearsim-cli --test integration cost::` runs one file's tests. Cargo.toml sets
//! `autotests = false` and declares this file: a file added to tests/ is compiled only once it is
//! named here, and the test at the end fails until it is.

mod common;

mod cli;
mod closed_pipe;
mod cost;
mod data_loss;
mod integrity;
mod limits;
mod measured;
mod messages;
mod ownership;
mod plot_writes;
mod reliability;
mod resume;
mod signals;
mod spectrum;
mod static_estimate;
mod study;
mod surface_import;

#[test]
fn every_file_in_tests_is_compiled() {
    let here = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let main = std::fs::read_to_string(here.join("main.rs")).unwrap();
    let mut missing = Vec::new();
    for entry in std::fs::read_dir(&here).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_stem().unwrap().to_str().unwrap().to_string();
        let is_module = path.extension().is_some_and(|e| e == "rs") || path.join("mod.rs").is_file();
        if is_module && name != "main" && !main.contains(&format!("\nmod {name};\n")) {
            missing.push(name);
        }
    }
    assert!(
        missing.is_empty(),
        "test files not named in tests/main.rs (never compiled): {missing:?}"
    );
}
