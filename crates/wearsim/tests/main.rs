//! The library's integration tests, one file per subject, compiled into one test binary: one build
//! and link instead of one per file. `cargo test -p wearsim --test integration cost::` runs one
//! file's tests. Cargo.toml sets `autotests = false` and declares this file: a file added to tests/
//! is compiled only once it is named here, and the test at the end fails until it is.

mod contact_validation;
mod cost;
mod estimate;
mod every_file;
mod evidence;
mod fuzz_parsers;
mod golden;
mod measured_set;
mod module_graph;
mod paper_comparison;
mod paper_window;
mod particle_rule;
mod rectangular;
mod regime;
mod scales;
mod sliding;
mod spectrum_fit;
mod stopping;
mod studies;
mod units;
mod volume;
