//! One module per subcommand; the helpers they share.

pub mod animate;
pub mod bench;
pub mod contact;
pub mod estimate;
pub mod fields;
pub mod junctions;
pub mod plot;
pub mod slide;
pub mod study;
pub mod surface;

use std::path::Path;

use anyhow::{Context, Result};
use wearsim::config::RunConfig;

/// The flag Ctrl-C and SIGTERM raise: the library stops at its next iteration, the command cleans up
/// (temporary files, claims) and exits with status 130.
pub fn interrupt() -> &'static wearsim::Interrupt {
    static FLAG: std::sync::OnceLock<wearsim::Interrupt> = std::sync::OnceLock::new();
    FLAG.get_or_init(|| {
        let flag = wearsim::Interrupt::default();
        let raised = flag.clone();
        // Without a handler (e.g. one already installed) the signal keeps its default action.
        let _ = ctrlc::set_handler(move || raised.request());
        flag
    })
}

/// Reads and validates a run file.
pub fn load_run(run: &Path) -> Result<RunConfig> {
    RunConfig::from_path(run).with_context(|| format!("run file {}", run.display()))
}

/// The files a run reads, its run file and surface files: an output folder may hold none of them.
pub fn run_inputs<'a>(run: &'a Path, config: &'a RunConfig) -> Vec<&'a Path> {
    let mut inputs = vec![run];
    if let wearsim::config::SurfaceSource::Files { top, bottom, .. } = &config.surfaces {
        inputs.extend([top.as_path(), bottom.as_path()]);
    }
    inputs
}

/// Prints what was done to surfaces read from files (cropping, detrending, header lines skipped),
/// and, with `warnings`, what about them may spoil the results (a surface far from periodic).
pub fn report_surfaces(pair: &wearsim::config::SurfacePair, warnings: bool) {
    for note in &pair.notes {
        eprintln!("note: {note}");
    }
    if warnings {
        for w in &pair.warnings {
            eprintln!("warning: {w}");
        }
    }
}
