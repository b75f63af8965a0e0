//! The library's integration tests, one file per subject, compiled into one test binary: one build
//! and link instead of one per file. `cargo test -p wearsim --test integration cost::` runs one
//! file's tests. Cargo.toml sets `autotests = false` and declares this file: a file added to tests/
//! is compiled only once it is named here, and the test at the end fails until it is.

mod contact_validation;
mod cost;
mod estimate;
mod fuzz_parsers;
mod golden;
mod module_graph;
mod paper_window;
mod particle_rule;
mod rectangular;
mod scales;
mod sliding;
mod stopping;
mod studies;
mod units;

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
