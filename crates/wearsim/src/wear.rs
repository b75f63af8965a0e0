//! The wear models: the static model of Frérot et al. (2018) (paper §2) and the particle rules of
//! the sliding model (paper §3): the seam [`ParticleRule`], one per critical diameter d*, with the
//! paper's rule [`OverlapRule`] as the default of [`PARTICLE_RULES`], the rules a run file can name.

use crate::error::{Error, Result};
use crate::junctions::{circle_area, Junction, JunctionLabeller, NO_JUNCTION};

/// Static model from one contact solution (paper §2).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StaticWear {
    /// k_static = Σ_{A_i ≥ A*} A_i / Σ_i A_i.
    pub wear_coefficient: f64,
    /// W_static/ω = k_static Σ_i A_i (volume per sliding distance, divided by the shape factor ω).
    pub wear_rate_over_omega: f64,
    /// Junctions with A_i ≥ A* = π d*²/4.
    pub critical_junctions: usize,
}

/// Whether a junction is critical for the critical area A* = π d*²/4: A_i ≥ A*, i.e. d_i ≥ d*
/// (paper §2–3). The one test of every model: the static model, the particle rules of the sliding
/// model and the static estimate count the same junctions. A junction that wraps the periodic box
/// is tested like any other (its area is that of a band or a sheet); every model that meets one
/// says so with [`box_wrapping_warning`].
pub fn is_critical(junction: &Junction, critical_area: f64) -> bool {
    junction.area >= critical_area
}

/// The warning of every model that met a junction wrapping the periodic box at load `load`: `where_`
/// says where (e.g. "at 3 of 120 steps (the first at s = 0.1)", "in 2 of 8 static maps (the first
/// at offset 64 px)"), `largest_contact_area` is the largest contact area of those maps as a
/// fraction of the box. Such a junction has no finite extent, so it is no particle of the model
/// (paper §3), yet it is counted as one: the results are not those of the model.
pub fn box_wrapping_warning(load: f64, where_: &str, largest_contact_area: f64) -> String {
    format!(
        "F_N = {load:.4e}: {where_} a junction wraps the periodic box (contact area up to {largest_contact_area:.3} \
         of the box): it is no particle of the model, which needs finite junctions (paper §3), yet it is counted as \
         one in N, N*, V and k_static; lower the load or enlarge the box"
    )
}

/// Evaluates the static model for critical diameter d* on the labelled junctions.
pub fn static_wear(junctions: &[Junction], critical_diameter: f64) -> StaticWear {
    let critical_area = circle_area(critical_diameter);
    // fold from +0.0: an empty f64 `sum()` is −0.0, which would print as "-0" in the outputs.
    let total = junctions.iter().fold(0.0, |a, j| a + j.area);
    let (large, critical_junctions) = junctions
        .iter()
        .filter(|j| is_critical(j, critical_area))
        .fold((0.0, 0), |(a, c), j| (a + j.area, c + 1));
    let k = if total > 0.0 { large / total } else { 0.0 };
    StaticWear {
        wear_coefficient: k,
        wear_rate_over_omega: k * total,
        critical_junctions,
    }
}

/// What one sliding step adds to the record of one d* (paper §3).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StepWear {
    /// N*: junctions with d_i ≥ d* at this step.
    pub n_critical: usize,
    /// N*₊: particles formed so far, from s = 0 included.
    pub n_formed: usize,
    /// V: wear volume so far, from s = 0 included.
    pub volume: f64,
}

impl StepWear {
    /// N*₋ := N*₊ − N* (paper appendix B), as a signed number.
    pub fn n_shrunk(&self) -> i64 {
        self.n_formed as i64 - self.n_critical as i64
    }
}

/// State of one junction at the current step, for display (the animation of `wearsim animate`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JunctionState {
    /// Active and smaller than d*: deforms plastically, forms no particle.
    Below,
    /// Active and at least d*: forms a particle at this step.
    Forming,
    /// Disabled (overlaps a junction that formed a particle or was disabled) and at least d*.
    DisabledCritical,
    /// Disabled and smaller than d*.
    Disabled,
}

/// What a particle rule is handed at each step of a sliding run.
#[derive(Debug, Clone, Copy)]
pub struct LabelledStep<'a> {
    /// The labelled contact map of this step (labels, contact pixels, junction sizes).
    pub labeller: &'a JunctionLabeller,
    /// The geometry of every junction, indexed like the labeller's junctions.
    pub junctions: &'a [Junction],
    /// Sliding distance since the previous step (0 at the first step, s = 0), in the run's length
    /// unit: what a rule that counts particles per distance slid (a rate) needs.
    pub slid: f64,
}

/// The seam of the wear model: a rule that turns the labelled junctions of each step into wear
/// particles, for one critical diameter d* (a sliding run makes one per fracture energy and hands
/// every one the same contact solution). The paper's §3 rule is [`OverlapRule`]; a run file
/// chooses a rule by name (`[sliding] particle_rule`, one of [`PARTICLE_RULES`]).
///
/// A rule keeps whatever it carries from step to step; [`ParticleRule::carried`] and
/// [`ParticleRule::restore`] save and restore it for a checkpoint, so that a resumed run takes the
/// steps an uninterrupted one would have.
pub trait ParticleRule: Send {
    /// Advances by one step: N* (junctions of this step at least d* across), N*₊ and V so far.
    /// `scratch` is an Nx·Ny flag buffer shared by the rules of a run, all false on entry and to be
    /// left all false on exit.
    fn step(&mut self, step: &LabelledStep, scratch: &mut [bool]) -> StepWear;

    /// The state of every junction of the last step (indexed like the labeller's junctions), for
    /// display.
    fn states(&self) -> &[JunctionState];

    /// What one step hands to the next, for a checkpoint (JSON).
    fn carried(&self) -> serde_json::Value;

    /// Continues from a state saved by [`ParticleRule::carried`] of the same rule and d*; `Err`
    /// says why the state is not one.
    fn restore(&mut self, carried: serde_json::Value) -> std::result::Result<(), String>;
}

/// A particle rule as a run file names it: its name (`[sliding] particle_rule`), what it does, and
/// how a run makes it for one critical diameter. Compared, printed and recorded by name.
#[derive(Clone, Copy)]
pub struct ParticleRuleKind {
    pub name: &'static str,
    /// One sentence for the documentation and error messages.
    pub description: &'static str,
    /// The rule for critical diameter d*.
    pub make: fn(critical_diameter: f64) -> Box<dyn ParticleRule>,
}

/// The paper's rule (§3), the default.
pub const OVERLAP: ParticleRuleKind = ParticleRuleKind {
    name: "overlap",
    description: "the paper's rule (§3): an active junction at least d* across forms one particle; a junction \
                  overlapping a formed or disabled junction of the previous step is disabled",
    make: OverlapRule::boxed,
};

/// The particle rules a run file can name; the first is the default.
pub const PARTICLE_RULES: &[ParticleRuleKind] = &[OVERLAP];

/// The particle rule when none is given: the paper's.
pub const DEFAULT_PARTICLE_RULE: ParticleRuleKind = PARTICLE_RULES[0];

impl ParticleRuleKind {
    /// The rule a run file names; an error naming the field and the choices otherwise.
    pub fn named(name: &str) -> Result<Self> {
        PARTICLE_RULES.iter().find(|k| k.name == name).copied().ok_or_else(|| {
            let choices: Vec<String> = PARTICLE_RULES
                .iter()
                .map(|k| format!("\"{}\" ({})", k.name, k.description))
                .collect();
            Error::param(
                "particle_rule",
                format!("{name:?} is not a particle rule; use one of: {}", choices.join("; ")),
            )
        })
    }
}

impl Default for ParticleRuleKind {
    fn default() -> Self {
        DEFAULT_PARTICLE_RULE
    }
}

impl std::fmt::Debug for ParticleRuleKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name)
    }
}

impl PartialEq for ParticleRuleKind {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
    }
}

impl serde::Serialize for ParticleRuleKind {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.serialize_str(self.name)
    }
}

impl std::str::FromStr for ParticleRuleKind {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        Self::named(s)
    }
}

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

    fn boxed(critical_diameter: f64) -> Box<dyn ParticleRule> {
        Box::new(Self::new(critical_diameter))
    }
}

impl ParticleRule for OverlapRule {
    fn step(&mut self, step: &LabelledStep, scratch: &mut [bool]) -> StepWear {
        mark_overlapping(step.labeller, &self.blocked, scratch, &mut self.overlap);
        let mut n_critical = 0;
        self.states.clear();
        for (j, overlap) in step.junctions.iter().zip(self.overlap.iter_mut()) {
            let critical = is_critical(j, self.critical_area);
            if critical {
                n_critical += 1;
            }
            self.states.push(match (*overlap, critical) {
                (false, false) => JunctionState::Below,
                (false, true) => JunctionState::Forming,
                (true, true) => JunctionState::DisabledCritical,
                (true, false) => JunctionState::Disabled,
            });
            if !*overlap && critical {
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
/// paper's particle rule does. The paper finds this number to decay exponentially with s.
/// Serialisable, so that a checkpoint of a long run carries it (its scratch `flags` included).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct InitialContactMemory {
    /// Pixels of the previous step's junctions that descend from s = 0.
    descendants: Vec<u32>,
    /// Per-junction scratch: descends from s = 0.
    flags: Vec<bool>,
    started: bool,
}

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
        self.flags.iter().filter(|&&f| f).count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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

    #[test]
    fn the_memory_of_the_initial_contact_follows_junctions_by_overlap() {
        let maps: [&[&str]; 4] = [
            &["##....", "##....", "......", "....#.", "......", "......"], // two junctions at s = 0
            &[".##...", "......", "......", "......", "......", "#....."], // the first moved on; a new one
            &["..####", "......", "......", "......", "......", "#....."], // the first merged with a new one
            &["......", "......", "......", ".#....", "......", "......"], // every old contact gone
        ];
        let n = 6;
        let mut labeller = JunctionLabeller::new(n, n, 4);
        let mut memory = InitialContactMemory::default();
        let mut scratch = vec![false; n * n];
        let counts: Vec<usize> = maps
            .iter()
            .map(|rows| {
                let flat: Vec<bool> = rows.iter().flat_map(|r| r.chars().map(|c| c == '#')).collect();
                labeller.label(|k| flat[k]);
                let c = memory.step(&labeller, &mut scratch);
                assert!(scratch.iter().all(|&b| !b));
                c
            })
            .collect();
        assert_eq!(counts, vec![2, 1, 1, 0]);
    }

    #[test]
    fn static_model() {
        let js = [Junction::new(1, 1.0), Junction::new(4, 1.0), Junction::new(5, 1.0)];
        let d_star = 2.0 * (3.0 / std::f64::consts::PI).sqrt();
        let s = static_wear(&js, d_star);
        assert!((s.wear_coefficient - 0.9).abs() < 1e-15);
        assert!((s.wear_rate_over_omega - 9.0).abs() < 1e-12);
    }
}
