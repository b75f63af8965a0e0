//! The seam of the sliding model (paper §3): what a particle rule is handed at each step and what it
//! gives back, for one critical diameter d*.

use crate::junctions::{Junction, JunctionLabeller};

use super::shear::{JunctionGeometry, ShearCompliance};

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
    /// Active and forming a particle at this step: at least d* across, or (under the rule of
    /// interacting junctions) a member of a combined particle.
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
    /// The junctions' geometry and the box's shear compliance, handed only to a rule that asks for
    /// them (`ParticleRuleKind::needs_shear`); `None` otherwise.
    pub shear: Option<ShearStep<'a>>,
}

/// What a rule of interacting junctions needs beyond the labels: the periodic tangential
/// compliance of the box (made once per run) and the geometry of this step's junctions (their
/// pixels unwrapped, their centroids, their self-energies under shear).
#[derive(Debug, Clone, Copy)]
pub struct ShearStep<'a> {
    pub compliance: &'a ShearCompliance,
    pub geometry: &'a JunctionGeometry,
}

/// The seam of the wear model: a rule that turns the labelled junctions of each step into wear
/// particles, for one critical diameter d* (a sliding run makes one per fracture energy and hands
/// every one the same contact solution). The paper's §3 rule is `OverlapRule`; a run file
/// chooses a rule by name (`[sliding] particle_rule`, one of `PARTICLE_RULES`).
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

    /// The particles formed so far that combine several junctions (a rule of interacting
    /// junctions); `None` for a rule that forms one particle per junction, as the paper's does.
    fn combined_particles(&self) -> Option<usize> {
        None
    }

    /// What the rule has to say about the load `load` once its last step is done (e.g. groups of
    /// junctions it refused as particles), one sentence each; nothing by default.
    fn warnings(&self, load: f64) -> Vec<String> {
        let _ = load;
        Vec::new()
    }
}

/// A parameter of a particle rule as a run file gives it: a number or one of named choices.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ParameterValue {
    Number(f64),
    Choice(&'static str),
}

impl std::fmt::Display for ParameterValue {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ParameterValue::Number(x) => write!(f, "{x}"),
            ParameterValue::Choice(c) => f.write_str(c),
        }
    }
}

/// What values a parameter takes.
#[derive(Debug, Clone, Copy)]
pub enum Allowed {
    /// A number in `[min, max]`.
    Range { min: f64, max: f64 },
    /// One of these names.
    Choices(&'static [&'static str]),
}

/// A parameter a particle rule declares: its key in `[sliding.particle_rule]`, what it means, its
/// default and the values it takes.
#[derive(Debug, Clone, Copy)]
pub struct RuleParameter {
    pub name: &'static str,
    pub description: &'static str,
    pub default: ParameterValue,
    pub allowed: Allowed,
}

/// The values of a rule's parameters, in the order the rule declares them (every one given or
/// defaulted).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RuleParameters(pub Vec<(&'static str, ParameterValue)>);

impl RuleParameters {
    /// The number `name`; panics if the rule declared no such number (a programming error).
    pub fn number(&self, name: &str) -> f64 {
        match self.0.iter().find(|(n, _)| *n == name) {
            Some((_, ParameterValue::Number(x))) => *x,
            _ => panic!("the rule declares no number parameter {name:?}"),
        }
    }

    /// The choice `name`; panics if the rule declared no such choice (a programming error).
    pub fn choice(&self, name: &str) -> &'static str {
        match self.0.iter().find(|(n, _)| *n == name) {
            Some((_, ParameterValue::Choice(c))) => c,
            _ => panic!("the rule declares no choice parameter {name:?}"),
        }
    }
}

/// What a run hands a rule's constructor: the critical diameter d* of this rule (in the run's
/// length unit), the pixel size Δx, and the rule's parameters.
#[derive(Debug, Clone, Copy)]
pub struct RuleSetup<'a> {
    pub critical_diameter: f64,
    pub pixel_size: f64,
    pub parameters: &'a RuleParameters,
}
