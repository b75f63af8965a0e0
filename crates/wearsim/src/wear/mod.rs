//! The wear models: the static model of Frérot et al. (2018) (paper §2) and the particle rules of
//! the sliding model (paper §3): the seam [`ParticleRule`] (in `rule`), one per critical diameter
//! d*, with the paper's rule [`OverlapRule`] as the default of [`PARTICLE_RULES`] and the rule of
//! interacting micro-contacts [`InteractingRule`], the rules a run file can name (in `registry`).

mod interacting;
mod overlap;
mod registry;
mod rule;
pub mod shear;

pub use interacting::InteractingRule;
pub use overlap::{CarriedBookkeeping, InitialContactMemory, OverlapRule};
pub use registry::{ParticleRuleKind, ParticleRuleSpec, DEFAULT_PARTICLE_RULE, INTERACTING, OVERLAP, PARTICLE_RULES};
pub use rule::{
    box_wrapping_warning, is_critical, Allowed, JunctionState, LabelledStep, ParameterValue, ParticleRule,
    RuleParameter, RuleParameters, RuleSetup, ShearStep, StepWear,
};

use crate::junctions::{circle_area, Junction};

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn static_model() {
        let js = [Junction::new(1, 1.0), Junction::new(4, 1.0), Junction::new(5, 1.0)];
        let d_star = 2.0 * (3.0 / std::f64::consts::PI).sqrt();
        let s = static_wear(&js, d_star);
        assert!((s.wear_coefficient - 0.9).abs() < 1e-15);
        assert!((s.wear_rate_over_omega - 9.0).abs() < 1e-12);
    }
}
