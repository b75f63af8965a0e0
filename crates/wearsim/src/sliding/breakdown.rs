//! The measures that tell a load has entered the regime the paper calls unreliable (appendix C):
//! above a load its smaller box's wear rate "breaks down", N* stops growing linearly with F_N, and
//! "contact junctions also start to merge … the contacts are expected to interact if they come
//! closer together, at which point their wear particle sizes are no longer predictable from the
//! individual contact areas … we have to treat data after this 'breakdown' as unreliable".
//!
//! Per load, over the fit window: the share of junctions that formed by merging, the real contact
//! fraction, the largest junction against the box; per load and fracture energy, across the loads
//! of one run (or of one surface pair of a study): N*/F_N against its best at a lower load. A load
//! is in the breakdown regime when one of the measures crosses its limit; its warning names the
//! load and the measures.

use super::records::{LoadRun, StepRecord, WearResult};

/// The share of a step's junctions that formed by merging (summed over the fit window) from which
/// a load counts as merging: one junction in fifty. Some junctions merge at every load; in the
/// wear-regime study (the paper's pixel size, box L/8, τ̃ = 0.008 and 0.012 E) the share stays at
/// most 1.7 % in every surface pair at the paper's loads (p_N ≤ 2×10⁻³ E) and grows with the load
/// to 2.0–3.0 % at 8×10⁻³ E, where W/F_N at d* = 16 and 33 px has fallen to 0.28 and 0.31 of its
/// value at 2×10⁻³ E.
pub const MERGED_SHARE_LIMIT: f64 = 0.02;

/// The largest junction's equivalent diameter over the box's shorter side from which a load
/// counts as beyond the box: a quarter, where no more than a few junctions of its size fit beside
/// their periodic images (the same quarter as the warning of d* against the box).
pub const LARGEST_JUNCTION_LIMIT: f64 = 0.25;

/// N*/F_N at a load over its largest value at a lower load of the same surfaces below which N* has
/// fallen behind linear growth with load (appendix C, Fig. C.1c): three quarters. Where N* grows
/// linearly the ratio scatters between surface pairs by about ±13 % (0.87–1.08 at p_N = 1 and
/// 2×10⁻³ E, d* = 16 px, in the wear-regime study); it falls to 0.56–0.66 at 8×10⁻³ E.
pub const CRITICAL_GROWTH_LIMIT: f64 = 0.75;

/// The fewest critical junctions N* (mean over the fit window) a lower load needs to serve as the
/// reference of N*/F_N: three. Between surface pairs N* scatters by 11 % about a mean of 3 and by
/// 22–31 % about means of 1.6–1.9 (the wear-regime study), as much as the quarter
/// [`CRITICAL_GROWTH_LIMIT`] allows; a reference of fewer would flag noise.
pub const GROWTH_REFERENCE_JUNCTIONS: f64 = 3.0;

/// The measures and their limits in words, as a run's summary states them.
pub fn breakdown_convention() -> String {
    format!(
        "over the fit window: contact_area_mean = mean A/A₀; merged_junction_share = Σ merged_junctions / Σ \
         junctions; largest_junction_max = the largest junction's diameter over the box's shorter side; \
         critical_junction_growth = (N*/F_N) over its largest value at a lower load of the run with N* ≥ {}; a load \
         is in the paper's breakdown regime (appendix C) when merged_junction_share ≥ {}, largest_junction_max ≥ {} \
         or critical_junction_growth < {}; breakdown_measures counts those beyond their limits",
        GROWTH_REFERENCE_JUNCTIONS, MERGED_SHARE_LIMIT, LARGEST_JUNCTION_LIMIT, CRITICAL_GROWTH_LIMIT
    )
}

/// The breakdown measures of one load, over its fit window (appendix C).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct LoadBreakdown {
    /// Mean real contact fraction A/A₀.
    pub contact_area_mean: Option<f64>,
    /// Junctions that formed by merging over all junctions, summed over the steps.
    pub merged_junction_share: Option<f64>,
    /// The largest junction's diameter over the box's shorter side, its largest value.
    pub largest_junction_max: Option<f64>,
}

/// What [`LoadBreakdown::of_steps`] reads of a step.
#[derive(Debug, Clone, Copy)]
pub struct BreakdownStep {
    pub junctions: usize,
    pub contact_area: f64,
    pub merged_junctions: Option<usize>,
    pub largest_junction: Option<f64>,
}

impl From<&StepRecord> for BreakdownStep {
    fn from(r: &StepRecord) -> Self {
        BreakdownStep {
            junctions: r.junctions,
            contact_area: r.contact_area,
            merged_junctions: r.merged_junctions,
            largest_junction: r.largest_junction,
        }
    }
}

impl LoadBreakdown {
    /// The measures over the steps of a fit window; a measure that a step does not keep (job files
    /// written before merging was counted) is absent.
    pub fn of_steps(steps: impl IntoIterator<Item = BreakdownStep>) -> Self {
        let steps: Vec<BreakdownStep> = steps.into_iter().collect();
        if steps.is_empty() {
            return Self::default();
        }
        let contact = steps.iter().map(|s| s.contact_area).sum::<f64>() / steps.len() as f64;
        let merged: Option<usize> = steps.iter().map(|s| s.merged_junctions).sum();
        let junctions: usize = steps.iter().map(|s| s.junctions).sum();
        let largest = steps
            .iter()
            .map(|s| s.largest_junction)
            .collect::<Option<Vec<f64>>>()
            .map(|v| v.into_iter().fold(0.0, f64::max));
        LoadBreakdown {
            contact_area_mean: super::records::finite(contact),
            merged_junction_share: merged.map(|m| {
                if junctions > 0 {
                    m as f64 / junctions as f64
                } else {
                    0.0
                }
            }),
            largest_junction_max: largest,
        }
    }

    /// The measures beyond their limits, in words, one each.
    pub fn beyond_limits(&self) -> Vec<String> {
        let mut out = Vec::new();
        if let Some(m) = self.merged_junction_share.filter(|&m| m >= MERGED_SHARE_LIMIT) {
            out.push(format!(
                "{:.1} % of its junctions formed by merging (limit {:.0} %)",
                100.0 * m,
                100.0 * MERGED_SHARE_LIMIT
            ));
        }
        if let Some(l) = self.largest_junction_max.filter(|&l| l >= LARGEST_JUNCTION_LIMIT) {
            out.push(format!(
                "its largest junction spans {l:.2} of the box's shorter side (limit {LARGEST_JUNCTION_LIMIT})"
            ));
        }
        out
    }

    /// `w` with these measures and their count beyond the limits (N*'s growth is counted where it
    /// is known, [`across_loads`]).
    pub fn apply_to(&self, w: &mut WearResult) {
        w.contact_area_mean = self.contact_area_mean;
        w.merged_junction_share = self.merged_junction_share;
        w.largest_junction_max = self.largest_junction_max;
        w.breakdown_measures = Some(self.beyond_limits().len() + growth_beyond_limit(w.critical_junction_growth));
    }
}

/// Whether N*'s growth `g` counts as fallen behind (1) or not (0).
fn growth_beyond_limit(g: Option<f64>) -> usize {
    usize::from(g.is_some_and(|g| g < CRITICAL_GROWTH_LIMIT))
}

/// N*/F_N of each load over its largest value at a lower load whose N* is at least
/// [`GROWTH_REFERENCE_JUNCTIONS`]: `points` are (F_N, N*) of one fracture energy on one set of
/// surfaces, in any order; absent at the lowest load and where no lower load qualifies.
pub fn critical_junction_growth(points: &[(f64, f64)]) -> Vec<Option<f64>> {
    points
        .iter()
        .map(|&(load, n)| {
            let best = points
                .iter()
                .filter(|&&(l, m)| l < load && l > 0.0 && m >= GROWTH_REFERENCE_JUNCTIONS)
                .map(|&(l, m)| m / l)
                .fold(f64::NAN, f64::max);
            (best > 0.0 && load > 0.0)
                .then(|| n / load / best)
                .and_then(super::records::finite)
        })
        .collect()
}

/// The words that open the breakdown warning of load `load`.
pub fn breakdown_opening(load: f64) -> String {
    format!("F_N = {load:.4e}: in the breakdown regime (paper appendix C): ")
}

/// The warning of a load in the breakdown regime, naming the load and every measure beyond its
/// limit; `growth` holds, per fracture energy beyond the limit, its words. `None` when no measure is.
pub fn breakdown_warning(load: f64, measures: &LoadBreakdown, growth: &[String]) -> Option<String> {
    let mut why = measures.beyond_limits();
    why.extend(growth.iter().cloned());
    if why.is_empty() {
        return None;
    }
    let contact = measures.contact_area_mean.map_or(String::new(), |a| {
        format!(" (real contact {:.2} % of the box)", 100.0 * a)
    });
    Some(format!(
        "{}{}{contact}: the paper treats data past its breakdown as unreliable, its junctions being expected \
         to interact; read this W as the model's in this box, not as wear to expect (a larger box moves the \
         breakdown to higher loads; `particle_rule = \"interacting\"` lets nearby junctions detach together)",
        breakdown_opening(load),
        why.join("; ")
    ))
}

/// The words of N* fallen behind linear growth for one fracture energy.
fn growth_words(w: &WearResult) -> Option<String> {
    let g = w.critical_junction_growth.filter(|&g| g < CRITICAL_GROWTH_LIMIT)?;
    Some(format!(
        "for 𝒢 = {:.4e} N*/F_N is {g:.2} of its value at a lower load (limit {CRITICAL_GROWTH_LIMIT}): N* has \
         fallen behind linear growth with load",
        w.fracture_energy
    ))
}

/// The breakdown measures of a run's loads that need the other loads: N*'s growth with load, per
/// fracture energy; each load's count of measures beyond the limits and its breakdown warning (in
/// place of the one its own measures gave).
pub fn across_loads(runs: &mut [LoadRun]) {
    let mut loads: Vec<LoadOfRun> = runs
        .iter_mut()
        .map(|r| LoadOfRun {
            load: r.load,
            results: &mut r.results,
            warnings: &mut r.warnings,
        })
        .collect();
    growth_across(&mut loads);
}

/// One load of a run of several, as N*'s growth across them reads and writes it: a run's
/// [`LoadRun`], or a study's job of one surface pair.
pub struct LoadOfRun<'a> {
    pub load: f64,
    pub results: &'a mut [WearResult],
    pub warnings: &'a mut Vec<String>,
}

/// N*'s growth with load across the loads of one run ([`critical_junction_growth`] per fracture
/// energy), each load's count of measures beyond their limits, and its breakdown warning made again.
pub fn growth_across(loads: &mut [LoadOfRun]) {
    let energies = loads.iter().map(|l| l.results.len()).min().unwrap_or(0);
    for e in 0..energies {
        let points: Vec<(f64, f64)> = loads
            .iter()
            .map(|l| (l.load, l.results[e].critical_junctions_mean))
            .collect();
        for (l, g) in loads.iter_mut().zip(critical_junction_growth(&points)) {
            l.results[e].critical_junction_growth = g;
        }
    }
    for l in loads {
        let measures = measures_of(l.results);
        for w in l.results.iter_mut() {
            measures.apply_to(w);
        }
        replace_warning(l.load, l.results, l.warnings);
    }
}

/// `warnings` with the breakdown warning of load `load` made again from its `results` (their
/// measures and N*'s growth), in place of the one they held.
pub fn replace_warning(load: f64, results: &[WearResult], warnings: &mut Vec<String>) {
    let growth: Vec<String> = results.iter().filter_map(growth_words).collect();
    let opening = breakdown_opening(load);
    warnings.retain(|m| !m.starts_with(&opening));
    warnings.extend(breakdown_warning(load, &measures_of(results), &growth));
}

/// The per-load measures that a load's results hold (the same in each).
fn measures_of(results: &[WearResult]) -> LoadBreakdown {
    results.first().map_or_else(LoadBreakdown::default, |w| LoadBreakdown {
        contact_area_mean: w.contact_area_mean,
        merged_junction_share: w.merged_junction_share,
        largest_junction_max: w.largest_junction_max,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn step(junctions: usize, merged: usize, largest: f64) -> BreakdownStep {
        BreakdownStep {
            junctions,
            contact_area: 0.1,
            merged_junctions: Some(merged),
            largest_junction: Some(largest),
        }
    }

    #[test]
    fn merging_is_counted_over_the_window_and_the_largest_junction_is_its_maximum() {
        let m = LoadBreakdown::of_steps([step(40, 1, 0.05), step(60, 1, 0.3)]);
        assert_eq!(m.merged_junction_share, Some(0.02));
        assert_eq!(m.largest_junction_max, Some(0.3));
        assert!((m.contact_area_mean.unwrap() - 0.1).abs() < 1e-15);
        let words = m.beyond_limits();
        assert_eq!(words.len(), 2, "{words:?}");
        assert!(words[0].starts_with("2.0 % of its junctions"), "{words:?}");
        // Below both limits: nothing.
        let calm = LoadBreakdown::of_steps([step(100, 1, 0.24)]);
        assert!(calm.beyond_limits().is_empty());
        assert!(breakdown_warning(1e-4, &calm, &[]).is_none());
        // A step of a job file written before merging was counted: that measure is absent.
        let old = LoadBreakdown::of_steps([BreakdownStep {
            merged_junctions: None,
            largest_junction: None,
            ..step(10, 0, 0.0)
        }]);
        assert_eq!((old.merged_junction_share, old.largest_junction_max), (None, None));
        assert_eq!(old.contact_area_mean, Some(0.1));
        assert_eq!(LoadBreakdown::of_steps([]), LoadBreakdown::default());
    }

    #[test]
    fn n_star_growth_is_against_the_best_lower_load_with_enough_critical_junctions() {
        // Linear up to 4, then flat: the fourth load has half the best N*/F_N.
        let points = [(1.0, 0.5), (2.0, 4.0), (4.0, 8.0), (8.0, 8.0), (16.0, 40.0)];
        let g = critical_junction_growth(&points);
        // The lowest load has no reference; the second none with N* ≥ 3 below it.
        assert_eq!(g[0], None);
        assert_eq!(g[1], None);
        assert_eq!(g[2], Some(1.0));
        assert_eq!(g[3], Some(0.5));
        assert_eq!(g[4], Some(1.25));
        // Order does not matter.
        let mut shuffled = points;
        shuffled.reverse();
        let mut back = critical_junction_growth(&shuffled);
        back.reverse();
        assert_eq!(back, g);
    }

    #[test]
    fn a_run_of_several_loads_warns_where_n_star_falls_behind() {
        let result = |n: f64| WearResult {
            fracture_energy: 1e-6,
            critical_junctions_mean: n,
            ..WearResult::default()
        };
        let run = |load: f64, n: f64| LoadRun {
            load,
            steps: Vec::new(),
            results: vec![result(n)],
            total_iterations: 0,
            max_iterations: 0,
            timing: Default::default(),
            warnings: vec![format!("{}stale", breakdown_opening(load))],
        };
        let mut runs = vec![run(2.0, 10.0), run(1.0, 5.0), run(4.0, 8.0)];
        across_loads(&mut runs);
        assert_eq!(runs[0].results[0].critical_junction_growth, Some(1.0));
        assert_eq!(runs[1].results[0].critical_junction_growth, None);
        assert_eq!(runs[2].results[0].critical_junction_growth, Some(0.4));
        // At the limit (three quarters) N* has not fallen behind.
        assert_eq!(
            critical_junction_growth(&[(1.0, 4.0), (2.0, 6.0)])[1],
            Some(CRITICAL_GROWTH_LIMIT)
        );
        assert_eq!(growth_beyond_limit(Some(CRITICAL_GROWTH_LIMIT)), 0);
        assert_eq!(runs[0].results[0].breakdown_measures, Some(0));
        assert_eq!(runs[2].results[0].breakdown_measures, Some(1));
        // The stale warnings are replaced: none at the two lower loads, one at the top load.
        assert!(runs[0].warnings.is_empty() && runs[1].warnings.is_empty());
        assert_eq!(runs[2].warnings.len(), 1);
        let w = &runs[2].warnings[0];
        assert!(w.starts_with("F_N = 4.0000e0: in the breakdown regime"), "{w}");
        assert!(w.contains("𝒢 = 1.0000e-6 N*/F_N is 0.40"), "{w}");
    }
}
