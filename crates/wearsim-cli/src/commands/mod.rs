//! One module per subcommand; the helpers they share.

pub mod animate;
pub mod bench;
pub mod contact;
pub mod junctions;
pub mod plot;
pub mod slide;
pub mod study;
pub mod surface;

use std::path::Path;

use anyhow::{Context, Result};
use wearsim::config::RunConfig;

/// Reads and validates a run file.
pub fn load_run(run: &Path) -> Result<RunConfig> {
    RunConfig::from_path(run).with_context(|| format!("run file {}", run.display()))
}

/// Creates an output folder (and its parents).
pub fn create_dir(out: &Path) -> Result<()> {
    std::fs::create_dir_all(out).with_context(|| format!("cannot create output folder {}", out.display()))
}
