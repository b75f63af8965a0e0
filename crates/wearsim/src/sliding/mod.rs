//! The sliding simulation (paper §3): slide the top surface over the bottom one along x, solve the
//! contact at every offset (warm-started from the previous step), label the junctions, and advance
//! one particle rule per fracture energy on the shared contact solutions. Ends with the
//! least-squares wear rate, particle rate and Archard wear coefficient after running-in.
//!
//! `schedule` (the offsets and what a run needs besides the surfaces), `records` (what a step and a
//! load record), `fit` (a load's results and warnings), `breakdown` (the measures of the paper's
//! high-load breakdown, appendix C), `checkpoint` (the state between two steps saved and read
//! back), `state` (the run as a state taking one step at a time, which every front end drives
//! through `run::SlidingRun`).

mod breakdown;
mod checkpoint;
mod fit;
mod records;
mod schedule;
mod state;

pub use breakdown::{
    across_loads, breakdown_convention, breakdown_opening, breakdown_warning, critical_junction_growth, growth_across,
    replace_warning, BreakdownStep, LoadBreakdown, LoadOfRun, CRITICAL_GROWTH_LIMIT, GROWTH_REFERENCE_JUNCTIONS,
    LARGEST_JUNCTION_LIMIT, MERGED_SHARE_LIMIT,
};
pub use checkpoint::{Checkpointing, Resumed, CHECKPOINT_EVERY};
pub use fit::{box_warnings, load_trend_warnings, resolution_warnings, FEW_PARTICLES, PAPER_MAX_WEAR_COEFFICIENT};
pub use records::{
    is_run_in, lineages_left, not_run_in, run_in_fits, InitialContactMemory, LoadRun, StepRecord, Timing, WearResult,
    MIN_FIT_WINDOW, RUN_IN_DECAY_LENGTHS, RUN_IN_LINEAGES_LEFT,
};
pub use schedule::{
    schedule, SlidingConfig, SlidingSetup, DEFAULT_DISTANCE, DEFAULT_RUNNING_IN, DEFAULT_STEP, DEFAULT_STEP_RUNNING_IN,
};
pub(crate) use state::SlidingState;
pub use state::StepView;
