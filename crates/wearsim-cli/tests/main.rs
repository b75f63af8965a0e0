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

/// The check that every file of tests/ is named above, shared with the library's tests.
#[path = "../../wearsim/tests/every_file.rs"]
mod every_file;
