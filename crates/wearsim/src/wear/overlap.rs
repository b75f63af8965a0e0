//! The paper's particle rule (§3), carried from step to step by pixel overlap, and the memory of the
//! initial contact that follows junctions the same way.

use crate::junctions::{circle_area, JunctionLabeller, NO_JUNCTION};

use super::rule::{is_critical, JunctionState, LabelledStep, ParticleRule, RuleSetup, StepWear};

/// The paper's particle rule (§3): formed / disabled / active states carried from step to step by
/// pixel overlap. A junction that shares a pixel with a junction of the previous step that formed a
/// particle or was disabled is disabled; every other junction is active, and an active junction
/// with d_i ≥ d* forms a particle (V += v_i, N*₊ += 1) and counts as formed for the next step.
#[derive(Debug, Clone)]
pub struct OverlapRule {
    critical_area: f64,
    /// Pixels of the previous step's formed or disabled junctions.
    blocked: Vec<u32>,
    n_formed: usize,
    volume: f64,
    /// Per-junction scratch: overlaps a blocked pixel.
    overlap: Vec<bool>,
    /// State of every junction of the last step.
    states: Vec<JunctionState>,
}

impl OverlapRule {
    /// Empty bookkeeping for critical diameter d*; the first [`ParticleRule::step`] is s = 0,
    /// where every junction is active (so V₀ = Σ v_i over d_i ≥ d*).
    pub fn new(critical_diameter: f64) -> Self {
        Self {
            critical_area: circle_area(critical_diameter),
            blocked: Vec::new(),
            n_formed: 0,
            volume: 0.0,
            overlap: Vec::new(),
            states: Vec::new(),
        }
    }

    /// The rule for a run's setup (the overlap rule has no parameters).
    pub fn boxed(setup: &RuleSetup) -> Box<dyn ParticleRule> {
        Box::new(Self::new(setup.critical_diameter))
    }

    /// The first half of a step: marks the junctions of `step` disabled (sharing a pixel with a
    /// junction of the previous step that formed a particle or was disabled) and gives those flags.
    pub(super) fn mark_disabled(&mut self, step: &LabelledStep, scratch: &mut [bool]) -> &[bool] {
        mark_overlapping(step.labeller, &self.blocked, scratch, &mut self.overlap);
        &self.overlap
    }

    /// The flags [`OverlapRule::mark_disabled`] gave, until [`OverlapRule::settle`].
    pub(super) fn disabled(&self) -> &[bool] {
        &self.overlap
    }

    /// One particle of volume `volume` formed at this step from junctions the rule settles as
    /// `joined` (between [`OverlapRule::mark_disabled`] and [`OverlapRule::settle`]).
    pub(super) fn add_particle(&mut self, volume: f64) {
        self.volume += volume;
        self.n_formed += 1;
    }

    /// The second half of a step: every junction's state; an active junction at least d* across
    /// forms its own particle, an active one `joined` to others (whose particle
    /// [`OverlapRule::add_particle`] counted) forms with them; both count as formed for the next
    /// step.
    pub(super) fn settle(&mut self, step: &LabelledStep, joined: impl Fn(usize) -> bool) -> StepWear {
        let mut n_critical = 0;
        self.states.clear();
        for (k, (j, overlap)) in step.junctions.iter().zip(self.overlap.iter_mut()).enumerate() {
            let critical = is_critical(j, self.critical_area);
            if critical {
                n_critical += 1;
            }
            let joined = joined(k);
            self.states.push(match (*overlap, critical || joined) {
                (false, false) => JunctionState::Below,
                (false, true) => JunctionState::Forming,
                (true, true) => JunctionState::DisabledCritical,
                (true, false) => JunctionState::Disabled,
            });
            if !*overlap && joined {
                *overlap = true;
            } else if !*overlap && critical {
                // Active and large enough: forms a particle, and is "formed" for the next step.
                self.volume += j.volume;
                self.n_formed += 1;
                *overlap = true;
            }
            // From here on `overlap` means "formed or disabled", the state the next step sees.
        }
        flagged_pixels(step.labeller, &self.overlap, &mut self.blocked);
        StepWear {
            n_critical,
            n_formed: self.n_formed,
            volume: self.volume,
        }
    }
}

impl ParticleRule for OverlapRule {
    fn step(&mut self, step: &LabelledStep, scratch: &mut [bool]) -> StepWear {
        self.mark_disabled(step, scratch);
        self.settle(step, |_| false)
    }

    fn states(&self) -> &[JunctionState] {
        &self.states
    }

    /// The pixels of formed or disabled junctions, N*₊ and V ([`CarriedBookkeeping`]).
    fn carried(&self) -> serde_json::Value {
        serde_json::to_value(CarriedBookkeeping {
            blocked: self.blocked.clone(),
            n_formed: self.n_formed,
            volume: self.volume,
        })
        .expect("plain data serialises")
    }

    fn restore(&mut self, carried: serde_json::Value) -> std::result::Result<(), String> {
        let c: CarriedBookkeeping = serde_json::from_value(carried).map_err(|e| e.to_string())?;
        self.blocked = c.blocked;
        self.n_formed = c.n_formed;
        self.volume = c.volume;
        Ok(())
    }
}

/// Marks, in `overlap` (one flag per junction of `labeller`), the junctions that share a pixel with
/// `pixels` (a previous step's pixels). `scratch` is an Nx·Ny flag buffer, all false on entry and exit.
fn mark_overlapping(labeller: &JunctionLabeller, pixels: &[u32], scratch: &mut [bool], overlap: &mut Vec<bool>) {
    let labels = labeller.labels();
    for &k in pixels {
        scratch[k as usize] = true;
    }
    overlap.clear();
    overlap.resize(labeller.sizes().len(), false);
    for &k in labeller.contact_pixels() {
        if scratch[k as usize] {
            overlap[labels[k as usize] as usize] = true;
        }
    }
    for &k in pixels {
        scratch[k as usize] = false;
    }
}

/// The pixels of the junctions whose flag is set, for the next step's overlap test.
fn flagged_pixels(labeller: &JunctionLabeller, flags: &[bool], out: &mut Vec<u32>) {
    let labels = labeller.labels();
    out.clear();
    for &k in labeller.contact_pixels() {
        let l = labels[k as usize];
        debug_assert_ne!(l, NO_JUNCTION);
        if flags[l as usize] {
            out.push(k);
        }
    }
}

/// The state of an [`OverlapRule`] between two steps (see [`ParticleRule::carried`]).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CarriedBookkeeping {
    pub blocked: Vec<u32>,
    pub n_formed: usize,
    pub volume: f64,
}

/// The memory of the initial contact (paper §3): how many junctions of the current step descend from
/// a junction present at s = 0, following junctions from step to step by shared pixels as the
/// paper's particle rule does. The paper finds this number to decay exponentially with s. Followed
/// the same way, a junction that shares pixels with two or more junctions of the previous step is
/// junctions merging, which the paper's appendix C names as the sign of its high-load breakdown:
/// [`InitialContactMemory::merged_junctions`] counts them.
/// Serialisable, so that a checkpoint of a long run carries it (its scratch `flags` included).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct InitialContactMemory {
    /// Pixels of the previous step's junctions that descend from s = 0.
    descendants: Vec<u32>,
    /// Per-junction scratch: descends from s = 0.
    flags: Vec<bool>,
    started: bool,
    /// Every contact pixel of the previous step with its junction's label.
    #[serde(default)]
    previous: Vec<(u32, u32)>,
    /// Junctions of the last step that share pixels with two or more junctions of the one before.
    #[serde(default)]
    merged: usize,
    /// Per-junction scratch: the first previous junction met, or [`MERGED`].
    #[serde(skip)]
    parent: Vec<u32>,
}

/// A junction met by two or more junctions of the previous step (in `InitialContactMemory::parent`).
const MERGED: u32 = u32::MAX - 1;

impl InitialContactMemory {
    /// Advances by one step; the first step is s = 0, whose junctions all count. Returns the number
    /// of junctions of this step that descend from s = 0. `scratch` as for
    /// [`ParticleRule::step`].
    pub fn step(&mut self, labeller: &JunctionLabeller, scratch: &mut [bool]) -> usize {
        if self.started {
            mark_overlapping(labeller, &self.descendants, scratch, &mut self.flags);
        } else {
            self.flags.clear();
            self.flags.resize(labeller.sizes().len(), true);
            self.started = true;
        }
        flagged_pixels(labeller, &self.flags, &mut self.descendants);
        self.count_merged(labeller);
        self.flags.iter().filter(|&&f| f).count()
    }

    /// Junctions of the last step that share pixels with two or more junctions of the step
    /// before it (0 at s = 0).
    pub fn merged_junctions(&self) -> usize {
        self.merged
    }

    fn count_merged(&mut self, labeller: &JunctionLabeller) {
        let labels = labeller.labels();
        self.parent.clear();
        self.parent.resize(labeller.sizes().len(), NO_JUNCTION);
        self.merged = 0;
        for &(k, was) in &self.previous {
            let now = labels[k as usize];
            if now == NO_JUNCTION {
                continue;
            }
            let p = &mut self.parent[now as usize];
            if *p == NO_JUNCTION {
                *p = was;
            } else if *p != was && *p != MERGED {
                *p = MERGED;
                self.merged += 1;
            }
        }
        self.previous.clear();
        self.previous
            .extend(labeller.contact_pixels().iter().map(|&k| (k, labels[k as usize])));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::junctions::Junction;

    /// Runs the bookkeeping on a sequence of hand-built maps (strings, '#' = contact) with d* given
    /// as a pixel area; returns the records.
    fn run(maps: &[&[&str]], critical_pixels: f64) -> Vec<StepWear> {
        let n = maps[0].len();
        let dx = 1.0;
        let d_star = 2.0 * (critical_pixels / std::f64::consts::PI).sqrt();
        let mut labeller = JunctionLabeller::new(n, n, 4);
        let mut book = OverlapRule::new(d_star);
        let mut scratch = vec![false; n * n];
        maps.iter()
            .map(|rows| {
                let flat: Vec<bool> = rows.iter().flat_map(|r| r.chars().map(|c| c == '#')).collect();
                labeller.label(|k| flat[k]);
                let j = labeller.junctions(dx);
                let step = LabelledStep {
                    labeller: &labeller,
                    junctions: &j,
                    slid: 1.0,
                    shear: None,
                };
                let rec = book.step(&step, &mut scratch);
                assert!(scratch.iter().all(|&b| !b));
                rec
            })
            .collect()
    }

    fn v(pixels: usize) -> f64 {
        Junction::new(pixels, 1.0).volume
    }

    fn assert_record(r: StepWear, n_critical: usize, n_formed: usize, volume: f64) {
        assert_eq!((r.n_critical, r.n_formed), (n_critical, n_formed), "{r:?}");
        assert!(
            (r.volume - volume).abs() <= 1e-12 * volume.abs(),
            "{r:?} vs volume {volume}"
        );
    }

    #[test]
    fn initial_step_counts_every_large_junction() {
        let recs = run(&[&["##..", "##..", "....", "...#"]], 3.0);
        assert_record(recs[0], 1, 1, v(4));
    }

    #[test]
    fn a_growing_junction_forms_exactly_one_particle() {
        let recs = run(
            &[
                &["#...", "....", "....", "...."],
                &["##..", "....", "....", "...."],
                &["##..", "##..", "....", "...."], // reaches 4 ≥ 3 pixels: forms
                &["###.", "##..", "....", "...."], // successor: disabled
                &["###.", "###.", "....", "...."],
            ],
            3.0,
        );
        let formed: Vec<usize> = recs.iter().map(|r| r.n_formed).collect();
        assert_eq!(formed, vec![0, 0, 1, 1, 1]);
        assert_record(recs[4], 1, 1, v(4));
        assert_eq!(recs[4].n_critical, 1);
        assert_eq!(recs[4].n_shrunk(), 0);
    }

    #[test]
    fn disabled_until_it_vanishes_then_a_new_junction_can_form() {
        let recs = run(
            &[
                &["##..", "##..", "....", "...."], // forms at s = 0
                &["##..", "#...", "....", "...."], // shrinks, still disabled
                &["....", "....", "....", "...."], // vanishes
                &["##..", "##..", "....", "...."], // new junction at the same place: forms again
            ],
            3.0,
        );
        let formed: Vec<usize> = recs.iter().map(|r| r.n_formed).collect();
        assert_eq!(formed, vec![1, 1, 1, 2]);
        assert_record(recs[3], 1, 2, 2.0 * v(4));
    }

    #[test]
    fn a_disabled_junction_merging_with_a_fresh_one_disables_it() {
        let recs = run(
            &[
                &["##....", "##....", "......", "......", "......", "......"], // forms
                &["##..#.", "##..#.", "......", "......", "......", "......"], // disabled + fresh small one
                &["######", "##..#.", "......", "......", "......", "......"], // merged: disabled
            ],
            3.0,
        );
        let formed: Vec<usize> = recs.iter().map(|r| r.n_formed).collect();
        assert_eq!(formed, vec![1, 1, 1]);
        assert_eq!(recs[2].n_critical, 1);
    }

    #[test]
    fn a_junction_across_the_periodic_edge_is_one_particle() {
        let recs = run(&[&["#..#", "....", "....", "#..#"]], 3.0);
        assert_record(recs[0], 1, 1, v(4));
    }

    /// The memory stepped over 6 × 6 maps ('#' = contact): per step, the junctions descending from
    /// s = 0 and the junctions merging.
    fn memory_over(maps: &[&[&str]]) -> Vec<(usize, usize)> {
        let n = 6;
        let mut labeller = JunctionLabeller::new(n, n, 4);
        let mut memory = InitialContactMemory::default();
        let mut scratch = vec![false; n * n];
        maps.iter()
            .map(|rows| {
                let flat: Vec<bool> = rows.iter().flat_map(|r| r.chars().map(|c| c == '#')).collect();
                labeller.label(|k| flat[k]);
                let c = memory.step(&labeller, &mut scratch);
                assert!(scratch.iter().all(|&b| !b));
                (c, memory.merged_junctions())
            })
            .collect()
    }

    #[test]
    fn junctions_merging_are_those_that_meet_two_of_the_previous_step() {
        let maps: [&[&str]; 4] = [
            &["##.##.", "......", "......", "#.....", "......", "......"], // three junctions
            &["#####.", "......", "......", "#.....", "......", "......"], // two of them joined
            &["#####.", "......", "......", "##....", "......", "......"], // one grows: no merge
            &["......", "......", "......", "......", "......", "......"], // none
        ];
        let merged: Vec<usize> = memory_over(&maps).into_iter().map(|(_, m)| m).collect();
        assert_eq!(merged, vec![0, 1, 0, 0]);
    }

    #[test]
    fn the_memory_of_the_initial_contact_follows_junctions_by_overlap() {
        let maps: [&[&str]; 4] = [
            &["##....", "##....", "......", "....#.", "......", "......"], // two junctions at s = 0
            &[".##...", "......", "......", "......", "......", "#....."], // the first moved on; a new one
            &["..####", "......", "......", "......", "......", "#....."], // the first merged with a new one
            &["......", "......", "......", ".#....", "......", "......"], // every old contact gone
        ];
        let counts: Vec<usize> = memory_over(&maps).into_iter().map(|(c, _)| c).collect();
        assert_eq!(counts, vec![2, 1, 1, 0]);
    }
}
