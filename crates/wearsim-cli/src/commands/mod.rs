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
