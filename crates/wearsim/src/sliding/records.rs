//! What a sliding run records: one [`StepRecord`] per step, one [`WearResult`] per load and
//! fracture energy, and the [`LoadRun`] that holds them with the time taken.

use crate::stats::weighted_line_fit;
use crate::wear::{StaticWear, StepWear};

/// One step of one load: the contact statistics and, per fracture energy, the wear record.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StepRecord {
    /// Offset in pixels.
    pub offset: usize,
    /// Sliding distance s in the run's length unit.
    pub s: f64,
    /// Number of junctions N.
    pub junctions: usize,
    /// Junctions that wrap the periodic box (full contact, a band across the box): no particles of
    /// the model, which needs finite junctions (paper §3), yet counted in N and the wear records.
    pub wrapping_junctions: usize,
    /// Real contact area as a fraction of the apparent area.
    pub contact_area: f64,
    /// Junctions of this step that descend from a junction present at s = 0 (paper §3's memory of
    /// the initial contact).
    pub initial_junctions: usize,
    /// Junctions of this step that share pixels with two or more junctions of the previous step:
    /// junctions merging, the paper's sign of its high-load breakdown (appendix C). Absent where a
    /// study's job file written before it was kept gives the step.
    #[serde(default)]
    pub merged_junctions: Option<usize>,
    /// The largest junction's equivalent diameter over the box's shorter side (absent as above).
    #[serde(default)]
    pub largest_junction: Option<f64>,
    /// Solver iterations of this step.
    pub iterations: usize,
    /// Solver residual of this step.
    pub residual: f64,
    /// Wear record per fracture energy, in the material's order.
    pub wear: Vec<StepWear>,
    /// Static model on this step's contact map per fracture energy (paper §2).
    pub statics: Vec<StaticWear>,
}

/// A finite number, or nothing.
pub(crate) fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

/// Results per load and fracture energy (paper §3–4 and appendices B, C); also the record stored in
/// study job files. Fitted quantities are absent (`null` in JSON, an empty cell in CSV) where they
/// are undefined; the run's `warnings` say why.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct WearResult {
    pub fracture_energy: f64,
    pub critical_diameter: f64,
    /// W = dV/ds fitted after running-in (volume per sliding distance).
    pub wear_rate: Option<f64>,
    /// R² of the wear-rate fit; absent where V does not change after running-in (no particle).
    pub wear_rate_r2: Option<f64>,
    /// Intercept b of the line V(s) ≈ W s + b fitted after running-in (volume), the dashed line of
    /// the paper's Fig. 3; absent with W. Absent in job files written before it existed.
    #[serde(default)]
    pub wear_volume_intercept: Option<f64>,
    /// Sliding distance at which the fit window starts (run's length unit): the first step at or
    /// past the running-in distance, where the fits of W and dN*₊/ds and the means over the fit
    /// window begin; the running-in (not fitted) part of the paper's Fig. 3 ends here. Read as 0
    /// from job files of format 2 only so that the job-format check, not a parse error, refuses them.
    #[serde(default)]
    pub fit_window_start: f64,
    /// k = W p̃ / F_N (Archard, paper Eq. 2).
    pub wear_coefficient: Option<f64>,
    /// dN*₊/ds fitted after running-in (particles per sliding distance).
    pub particle_rate: Option<f64>,
    /// Paper Eq. 5, ω d*³ dN*₊/ds with ω = π/6 (the paper finds it slightly below W, appendix B).
    pub wear_rate_estimate: Option<f64>,
    /// Particles formed after running-in (N*₊ at the end minus at the start of the fit window).
    pub particles_in_fit: usize,
    /// V₀, the volume counted at s = 0.
    pub initial_volume: f64,
    /// Static model at s = 0: k_static = Σ_{A_i ≥ A*} A_i / Σ A_i.
    pub static_wear_coefficient: f64,
    /// Static model at s = 0: W_static/ω = k_static Σ A_i.
    pub static_wear_rate: f64,
    /// Static model over every offset of the run (paper §2): mean and standard deviation of k_static.
    pub static_wear_coefficient_mean: f64,
    pub static_wear_coefficient_std: f64,
    /// Static model over every offset: mean and standard deviation of W_static/ω.
    pub static_wear_rate_mean: f64,
    pub static_wear_rate_std: f64,
    /// Mean number of junctions N over the fit window (paper appendix C).
    pub junctions_mean: f64,
    /// Mean number of junctions at least d* across, N*, over the fit window (paper appendix C).
    pub critical_junctions_mean: f64,
    /// Decay length ℓ of the memory of the initial contact, N₀(s) ≈ N₀(0) e^(−s/ℓ) (paper §3), fitted
    /// to ln N₀ over the steps where N₀ > 0, weighted by N₀ ([`InitialContactMemory::of_steps`]);
    /// absent when it does not decay.
    pub memory_decay_length: Option<f64>,
    /// R² of that fit (in ln N₀, weighted).
    pub memory_decay_r2: Option<f64>,
    /// N₀(0) of that fit, e^b of the line ln N₀ ≈ b − s/ℓ: with ℓ, the fitted curve of the memory
    /// of the initial contact; absent with ℓ. Absent in job files written before it existed.
    #[serde(default)]
    pub memory_fit_initial_junctions: Option<f64>,
    /// Steps of the load at which a junction wrapped the periodic box (full contact near p_m, a
    /// contact band across the box). Such a junction is no particle of the model (paper §3 needs
    /// finite junctions), yet it is counted as one, so results with steps here are not the model's;
    /// the warnings say so. Absent in job files written before it existed: 0.
    #[serde(default)]
    pub box_wrapping_steps: usize,
    /// The running-in distance (start of the fit window) in decay lengths, s_r/ℓ; 0 when the memory
    /// does not decay, absent when it is gone by the first step after s = 0. Below
    /// [`RUN_IN_DECAY_LENGTHS`] the fit window starts while the initial contact is still remembered
    /// (paper §3) and the run is not run in; the run's `warnings` say so.
    pub running_in_decay_lengths: Option<f64>,
    /// N₀(s_r)/N₀(0): the fraction of the junction lineages of s = 0 still present where the fit
    /// window starts, counted (paper §3: run in once the memory of the initial contact has faded;
    /// at most [`RUN_IN_LINEAGES_LEFT`]); absent without a junction at s = 0. Job files written before
    /// it existed have it filled from their steps when collected.
    #[serde(default)]
    pub initial_lineages_left: Option<f64>,
    /// N*/(dN*₊/ds): the sliding distance a junction stays at least d* per particle it forms
    /// (Little's law over the fit window). A junction forms one particle and is then disabled while
    /// it overlaps itself (paper §3), so when critical junctions grow and live longer with load, this
    /// grows and the particle rate per critical junction, and k, fall; absent without particles.
    pub critical_residence: Option<f64>,
    /// The breakdown measures of the load (paper appendix C, `LoadBreakdown` of `breakdown`), over the fit
    /// window: the mean real contact fraction A/A₀. Absent in job files written before it existed
    /// until filled from their steps when read.
    #[serde(default)]
    pub contact_area_mean: Option<f64>,
    /// Junctions that formed by merging over all junctions, summed over the fit window; absent where
    /// the steps do not count merging (job files written before it was counted).
    #[serde(default)]
    pub merged_junction_share: Option<f64>,
    /// The largest junction's equivalent diameter over the box's shorter side, its largest value
    /// over the fit window; absent as above.
    #[serde(default)]
    pub largest_junction_max: Option<f64>,
    /// N*/F_N at this load over its largest value at a lower load of the same surfaces (a run's other
    /// loads, or a study's other jobs on the same surface pair, read together when collected); below
    /// three quarters, N* has fallen behind linear growth with load (appendix C). Absent at the
    /// lowest load, where no lower load has N* ≥ 3, and in a run of one load.
    #[serde(default)]
    pub critical_junction_growth: Option<f64>,
    /// How many of the breakdown measures lie beyond their limits (0 to 3): above 0 the load is in
    /// the regime the paper treats as unreliable, and a warning names it and the measures. Absent for
    /// a static estimate, which measures none.
    #[serde(default)]
    pub breakdown_measures: Option<usize>,
    /// Particles that combine several junctions, over the whole run (s = 0 included), under a rule
    /// of interacting junctions (`particle_rule = "interacting"`); absent under the paper's rule,
    /// whose every particle is one junction's.
    #[serde(default)]
    pub combined_particles: Option<usize>,
}

impl WearResult {
    /// The unit of every field, declared beside the fields so that a new result states its unit
    /// where it is added: (field, reduced units, SI units); "" for counts, "1" for ratios. Read by
    /// `output::unit_of` for every table and summary that holds the field (`_mean`, `_min`, …
    /// of it included).
    pub const UNITS: &'static [(&'static str, &'static str, &'static str)] = &[
        ("fracture_energy", "E L", "J/m²"),
        ("critical_diameter", "L", "m"),
        ("wear_rate", "L²", "m²"),
        ("wear_rate_r2", "1", "1"),
        ("wear_volume_intercept", "L³", "m³"),
        ("fit_window_start", "L", "m"),
        ("wear_coefficient", "1", "1"),
        ("particle_rate", "1/L", "1/m"),
        ("wear_rate_estimate", "L²", "m²"),
        ("particles_in_fit", "", ""),
        ("initial_volume", "L³", "m³"),
        ("static_wear_coefficient", "1", "1"),
        ("static_wear_rate", "L²", "m²"),
        ("static_wear_coefficient_mean", "1", "1"),
        ("static_wear_coefficient_std", "1", "1"),
        ("static_wear_rate_mean", "L²", "m²"),
        ("static_wear_rate_std", "L²", "m²"),
        ("junctions_mean", "", ""),
        ("critical_junctions_mean", "", ""),
        ("memory_decay_length", "L", "m"),
        ("memory_decay_r2", "1", "1"),
        ("memory_fit_initial_junctions", "", ""),
        ("box_wrapping_steps", "", ""),
        ("running_in_decay_lengths", "1", "1"),
        ("initial_lineages_left", "1", "1"),
        ("critical_residence", "L", "m"),
        ("contact_area_mean", "1", "1"),
        ("merged_junction_share", "1", "1"),
        ("largest_junction_max", "1", "1"),
        ("critical_junction_growth", "1", "1"),
        ("breakdown_measures", "", ""),
        ("combined_particles", "", ""),
    ];
}

/// Decay lengths of the memory of the initial contact after which a run counts as run in: e^−3, so
/// about 5 % of the junction lineages present at s = 0 are expected at the start of the fit window.
/// The paper (§3) finds the decay length not predictable and takes L/4 as a safety margin; this rule
/// checks that margin on each run's own measured decay.
pub const RUN_IN_DECAY_LENGTHS: f64 = 3.0;

/// The shortest fit window, in box lengths, that the advice to lengthen the running-in leaves after
/// it: the paper's (§3: s from L/4 to L/2).
pub const MIN_FIT_WINDOW: f64 = 0.25;

/// Whether [`RUN_IN_DECAY_LENGTHS`] decay lengths `decay_length` and a fit window of
/// [`MIN_FIT_WINDOW`] fit in one period of a box of side `box_length` along the sliding direction
/// (a schedule slides at most one period: `distance` ≤ 1).
pub fn run_in_fits(decay_length: f64, box_length: f64) -> bool {
    RUN_IN_DECAY_LENGTHS * decay_length <= (1.0 - MIN_FIT_WINDOW) * box_length
}

/// The fraction of the junction lineages of s = 0 at most left at the start of the fit window for a
/// run to count as run in: what [`RUN_IN_DECAY_LENGTHS`] aims at (e^−3 ≈ 5 %), counted instead of
/// extrapolated from a fitted ℓ, which a tail of a few persisting lineages can dominate.
pub const RUN_IN_LINEAGES_LEFT: f64 = 0.05;

/// Whether a run is run in (paper §3: the memory of the initial contact has faded by the start of
/// its fit window), from its counted share of the lineages of s = 0 left there
/// ([`RUN_IN_LINEAGES_LEFT`] at most) or, where none was there to count, from the running-in in
/// fitted decay lengths ([`RUN_IN_DECAY_LENGTHS`] at least); a run with neither (its memory gone by
/// the first step) is run in. The findings, the figures and the run's warning ask this one rule.
pub fn is_run_in(lineages_left: Option<f64>, decay_lengths: Option<f64>) -> bool {
    match (
        lineages_left.filter(|x| x.is_finite()),
        decay_lengths.filter(|x| x.is_finite()),
    ) {
        (Some(left), _) => left <= RUN_IN_LINEAGES_LEFT,
        (None, Some(r)) => r >= RUN_IN_DECAY_LENGTHS,
        (None, None) => true,
    }
}

/// N₀(s_r)/N₀(0) of a run's steps (s, N₀): the lineages of s = 0 left at the first step at or after
/// `fit_start`; `None` without a junction at s = 0 or without such a step.
pub fn lineages_left(steps: impl IntoIterator<Item = (f64, usize)>, fit_start: f64) -> Option<f64> {
    let mut steps = steps.into_iter();
    let (_, initial) = steps.next()?;
    if initial == 0 {
        return None;
    }
    let at = std::iter::once((0.0, initial))
        .chain(steps)
        .find(|(s, _)| *s >= fit_start - 1e-9 * fit_start.abs().max(f64::MIN_POSITIVE))?;
    Some(at.1 as f64 / initial as f64)
}

/// The memory of the initial contact of one load (paper §3), from its steps (s, N₀): the decay
/// length ℓ of N₀(s) ≈ N₀(0) e^(−s/ℓ), the fit's R² and N₀(0), the start of the fit window in decay
/// lengths and the lineages of s = 0 counted there. Computed by the run, and again from the steps
/// of a job file when it is read, so that every job file is judged by this version's fit.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct InitialContactMemory {
    pub decay_length: Option<f64>,
    pub r2: Option<f64>,
    pub fit_initial_junctions: Option<f64>,
    pub running_in_decay_lengths: Option<f64>,
    pub lineages_left: Option<f64>,
}

impl InitialContactMemory {
    /// ln N₀ against s over the steps where N₀ > 0, weighted by N₀ (the inverse of the Poisson
    /// variance 1/N₀ of ln N₀): a tail of one to three persisting lineages, whose ln N₀ is noise of
    /// order one, weighs as little as its few lineages against the decay of tens before it, and
    /// stretches ℓ much less than in an unweighted fit (it still stretches it: a lineage that
    /// persists is data; the run-in rule counts the lineages left instead). `fit_start` is the start
    /// of the fit window.
    pub fn of_steps(steps: &[(f64, usize)], fit_start: f64) -> Self {
        let decaying: Vec<&(f64, usize)> = steps.iter().filter(|(_, n)| *n > 0).collect();
        let column = |f: fn(&(f64, usize)) -> f64| decaying.iter().map(|p| f(p)).collect::<Vec<f64>>();
        let fit = weighted_line_fit(
            &column(|p| p.0),
            &column(|p| (p.1 as f64).ln()),
            &column(|p| p.1 as f64),
        );
        let (decay_length, r2, fit_initial_junctions) = match fit {
            Some(f) if f.slope < 0.0 => {
                let length = finite(-1.0 / f.slope);
                (length, f.r2, length.and(finite(f.intercept.exp())))
            }
            _ => (None, None, None),
        };
        let running_in_decay_lengths = match (decay_length, fit) {
            (Some(l), _) => finite(fit_start / l),
            // The lineages of s = 0 do not thin out: an infinite decay length.
            (None, Some(_)) => Some(0.0),
            (None, None) => None,
        };
        InitialContactMemory {
            decay_length,
            r2,
            fit_initial_junctions,
            running_in_decay_lengths,
            lineages_left: lineages_left(steps.iter().copied(), fit_start),
        }
    }

    /// The warning of a load that is not run in by [`is_run_in`]; it opens with [`not_run_in`]'s
    /// words for the load. `box_length` is Lx: the advice to lengthen the running-in is given only
    /// where [`RUN_IN_DECAY_LENGTHS`] ℓ and a fit window fit in the one period a periodic box can
    /// be slid ([`run_in_fits`]); else the warning says that this box cannot be run in.
    pub fn warning(&self, load: f64, fit_start: f64, box_length: f64) -> Option<String> {
        if is_run_in(self.lineages_left, self.running_in_decay_lengths) {
            return None;
        }
        let left = self
            .lineages_left
            .unwrap_or_else(|| (-self.running_in_decay_lengths.unwrap_or(0.0)).exp());
        let decay = self
            .decay_length
            .map_or("does not decay".to_string(), |l| format!("decays over ℓ = {l:.4e}"));
        let lengths = self
            .running_in_decay_lengths
            .map_or(String::new(), |r| format!(", {r:.2} decay lengths"));
        let advice = match self.decay_length {
            Some(l) if !run_in_fits(l, box_length) => format!(
                "{RUN_IN_DECAY_LENGTHS} ℓ = {:.2} box lengths, and with a fit window after it more than the one \
                 period (`distance` ≤ 1) a periodic box can be slid: this box cannot be run in at this load, so its \
                 rates are those of a surface that still remembers its first contact; take a larger box (ℓ follows \
                 the junctions, not the box)",
                RUN_IN_DECAY_LENGTHS * l / box_length
            ),
            _ => format!("raise `running_in` (and `distance`), to at least {RUN_IN_DECAY_LENGTHS} ℓ"),
        };
        Some(format!(
            "{}the memory of the initial contact {decay}, and the fit window starts at s = {fit_start:.4e}{lengths}, \
             with {:.0} % of the junction lineages of s = 0 still present (at most {:.0} % run in); {advice}",
            not_run_in(load),
            100.0 * left,
            100.0 * RUN_IN_LINEAGES_LEFT
        ))
    }

    /// `w` with this memory's fields.
    pub fn apply_to(&self, w: &mut WearResult) {
        w.memory_decay_length = self.decay_length;
        w.memory_decay_r2 = self.r2;
        w.memory_fit_initial_junctions = self.fit_initial_junctions;
        w.running_in_decay_lengths = self.running_in_decay_lengths;
        w.initial_lineages_left = self.lineages_left;
    }
}

/// The words that open the warning of load `load` not run in (this version's and earlier ones').
pub fn not_run_in(load: f64) -> String {
    format!("F_N = {load:.4e}: not run in: ")
}

/// Time spent per part of the sliding loop, in seconds.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Timing {
    pub solve: f64,
    pub labelling: f64,
    pub bookkeeping: f64,
}

/// One load's sliding run.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LoadRun {
    /// Normal load F_N.
    pub load: f64,
    pub steps: Vec<StepRecord>,
    pub results: Vec<WearResult>,
    pub total_iterations: usize,
    pub max_iterations: usize,
    pub timing: Timing,
    /// What makes a result of this load under-resolved or undefined, one sentence each.
    pub warnings: Vec<String>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_lineages_left_are_counted_at_the_first_step_of_the_fit_window() {
        let steps = [(0.0, 40), (0.01, 12), (0.02, 3), (0.03, 1), (0.04, 0)];
        // The fit window starts at the step of s = 0.02 (or between steps: at the next one).
        assert_eq!(lineages_left(steps, 0.02), Some(3.0 / 40.0));
        assert_eq!(lineages_left(steps, 0.025), Some(1.0 / 40.0));
        assert_eq!(lineages_left(steps, 0.04), Some(0.0));
        assert_eq!(lineages_left(steps, 0.0), Some(1.0));
        // No junction at s = 0, no step there, or no step as far: not counted.
        assert_eq!(lineages_left([(0.0, 0), (0.01, 0)], 0.01), None);
        assert_eq!(lineages_left(steps, 0.05), None);
        assert_eq!(lineages_left(std::iter::empty(), 0.0), None);
    }

    #[test]
    fn the_memory_fit_weights_each_step_by_its_lineages() {
        // An exact exponential, 64 e^(−s/0.01): ℓ and N₀(0) recovered whatever the weights.
        let exact: Vec<(f64, usize)> = (0..7).map(|i| (0.01 * i as f64 * 2f64.ln(), 64 >> i)).collect();
        let m = InitialContactMemory::of_steps(&exact, 0.03);
        assert!((m.decay_length.unwrap() - 0.01).abs() < 1e-12, "{m:?}");
        assert!((m.fit_initial_junctions.unwrap() - 64.0).abs() < 1e-9);
        assert!((m.r2.unwrap() - 1.0).abs() < 1e-12);
        assert!((m.running_in_decay_lengths.unwrap() - 3.0).abs() < 1e-9);
        // The same decay with one lineage that persists over 10 more steps: the tail stretches the
        // unweighted fit threefold, the weighted one (weights N₀) by less than twice. Both values as
        // numpy.polyfit gives them (weights √N₀ on the residuals): 0.030677, 0.018876.
        let mut tailed = exact.clone();
        tailed.extend((7..17).map(|i| (0.01 * i as f64 * 2f64.ln(), 1)));
        let weighted = InitialContactMemory::of_steps(&tailed, 0.03).decay_length.unwrap();
        let (s, n): (Vec<f64>, Vec<f64>) = tailed.iter().map(|(s, n)| (*s, (*n as f64).ln())).unzip();
        let unweighted = -1.0 / crate::stats::line_fit(&s, &n).unwrap().slope;
        assert!((weighted - 0.018876153492838957).abs() < 1e-12, "ℓ weighted {weighted}");
        assert!(
            (unweighted - 0.03067669172932329).abs() < 1e-12,
            "ℓ unweighted {unweighted}"
        );
        // The warning: at s_r = 0.02 (the step of s = 0.0208) 8 of 64 are left, over 5 %: not run in,
        // said with the load; at s_r = 0.03, 2 of 64: run in, no warning.
        let early = InitialContactMemory::of_steps(&exact, 0.02);
        assert_eq!(early.lineages_left, Some(0.125));
        let warning = early.warning(0.5, 0.02, 1.0).unwrap();
        assert!(
            warning.starts_with(&not_run_in(0.5)) && warning.contains("decays over ℓ = 1.0000e-2"),
            "{warning}"
        );
        assert!(warning.ends_with("to at least 3 ℓ"), "{warning}");
        // In a box of 0.03: 3 ℓ and a fit window do not fit in one period; no advice to raise it.
        let small = early.warning(0.5, 0.02, 0.03).unwrap();
        assert!(
            small.contains("3 ℓ = 1.00 box lengths") && small.contains("cannot be run in") && !small.contains("raise"),
            "{small}"
        );
        assert_eq!((m.lineages_left, m.warning(0.5, 0.03, 1.0)), (Some(2.0 / 64.0), None));
        // No lineage at all: nothing fitted, nothing counted, run in.
        let none = InitialContactMemory::of_steps(&[(0.0, 0), (0.01, 0)], 0.01);
        assert_eq!(none, InitialContactMemory::default());
    }

    #[test]
    fn a_run_is_run_in_by_the_lineages_counted_else_by_the_decay_lengths() {
        // Counted: at most 5 % left, whatever ℓ says (a tail of persisting lineages stretches it).
        assert!(is_run_in(Some(0.05), Some(0.4)));
        assert!(!is_run_in(Some(0.06), Some(8.0)));
        // Not counted (no junction at s = 0): s_r ≥ 3 ℓ; neither: its memory is gone, run in.
        assert!(is_run_in(None, Some(3.0)) && !is_run_in(None, Some(2.9)));
        assert!(is_run_in(Some(f64::NAN), None) && is_run_in(None, None));
    }
}
