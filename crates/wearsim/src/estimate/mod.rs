//! A static estimate of the sliding model's wear rate from a few contact solutions, the "closed form"
//! the paper asks for in its outlook (§5): N* from static maps, and the sliding distance a critical
//! junction lives, instead of sliding through every offset.
//!
//! The rule (derived from the sliding model of §3, its constants calibrated on sliding runs):
//!
//! 1. **N* and d̄ from static maps.** The top surface is put at `samples` offsets spread over the
//!    box (a van der Corput sequence over sixteenths of Lx, so that any number of samples is
//!    spread), the contact solved (the settled contact map, as a sliding step), and the junctions
//!    labelled. N* is the mean number of junctions with d_i ≥ d*, d̄ the mean diameter of those
//!    junctions, θ = N* d̄²/(Lx Ly) the area they cover in units of the box.
//! 2. **The life of a critical junction.** In the sliding model a junction forms one particle and
//!    stays disabled while it overlaps its previous self (§3): a lineage ends only when its patch of
//!    contact has slid off. Two asperities of size ~d̄ overlap over a sliding distance proportional
//!    to d̄; a lineage that meets a neighbouring critical junction on its way merges with it and
//!    lives on, with a chance that grows with the area the critical junctions cover. So the
//!    residence is R = c₁ d̄ (1 + c₂ θ) (Little's law: N* = R · dN*₊/ds).
//! 3. **Rates.** dN*₊/ds = N*/R; the wear rate W = c_v ω d*³ dN*₊/ds (Eq. 5, with c_v the mean
//!    particle volume over ω d*³: a junction forms its particle when it first reaches d*, a little
//!    above it on a discrete grid, appendix B); k = W p_m/F_N (Eq. 2).
//!
//! The constants c₁, c₂, c_v and the spread of the rule about the sliding runs are [`CALIBRATION`],
//! fitted by [`Calibration::fit`] on the sliding runs of a study (`wearsim estimate-check --fit`).
//! The interval given with every estimate is where a sliding run of the same box and sliding
//! distance would fall with 95 % probability: the rule's own spread, the sampling error of N* over
//! the static maps, and the Poisson noise of the particles such a run counts.
//!
//! What it is not: it predicts the rates after running-in, not the running-in itself, the memory of
//! the initial contact, or the wear-volume curve; it is as good as its calibration, which spans the
//! settings its documentation lists.

mod calibration;
mod estimator;
mod reach;
mod rule;
mod samples;
#[cfg(test)]
mod tests;

pub use calibration::{Calibration, CalibrationPoint, CALIBRATION, FIT_MIN_PARTICLES};
pub use estimator::Estimator;
pub use reach::{
    load_estimate, load_reach, load_reach_warnings, run_reach, run_reach_warnings, Domain, OutsideReach, SurfaceKind,
    CALIBRATED_DOMAIN,
};
pub use rule::{
    fit_distance, results_of, sampling_error, zero_allowed, EstimateResult, LoadEstimate, ZERO_PROBABILITY,
};
pub use samples::{
    sample_offsets, Sample, SampleCount, Sampling, MAX_SAMPLES, MIN_SAMPLES, RESOLVED_CRITICAL_JUNCTIONS,
    TARGET_SAMPLING_ERROR,
};
