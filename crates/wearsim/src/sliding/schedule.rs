//! The sliding schedule (paper §3) and everything a sliding run needs besides the surfaces.

use crate::check::positive;
use crate::contact::{Device, SolverOptions};
use crate::error::{Error, Interrupt, Result};
use crate::material::Material;
use crate::wear::ParticleRuleSpec;

/// The sliding schedule (paper §3); distances as fractions of the box side Lx along the sliding
/// direction x, steps in pixels.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SlidingConfig {
    /// Normal loads F_N (E·L² reduced, N in SI).
    pub loads: Vec<f64>,
    /// Total sliding distance as a fraction of Lx ([`DEFAULT_DISTANCE`] when not given).
    pub distance: f64,
    /// Running-in distance as a fraction of Lx ([`DEFAULT_RUNNING_IN`]).
    pub running_in: f64,
    /// Step during running-in, in pixels ([`DEFAULT_STEP_RUNNING_IN`]).
    pub step_running_in: usize,
    /// Step after running-in, in pixels ([`DEFAULT_STEP`]).
    pub step: usize,
    /// The rule that turns each step's junctions into wear particles, with its parameters
    /// (`particle_rule`; the paper's, [`crate::wear::DEFAULT_PARTICLE_RULE`], when not given).
    pub particle_rule: ParticleRuleSpec,
}

/// The paper's sliding distance (§3): half the box side, s up to Lx/2.
pub const DEFAULT_DISTANCE: f64 = 0.5;

/// The paper's running-in distance (§3): a quarter of the box side, the safety margin it takes for
/// the memory of the initial contact to fade; the wear rate is fitted from there.
pub const DEFAULT_RUNNING_IN: f64 = 0.25;

/// The step during running-in, in pixels (§3: coarser steps while the fit does not yet count).
pub const DEFAULT_STEP_RUNNING_IN: usize = 4;

/// The step after running-in, in pixels (§3: every pixel of the fit window).
pub const DEFAULT_STEP: usize = 1;

impl SlidingConfig {
    /// A validated schedule; `grid`, when known, bounds the steps and must leave at least two steps
    /// after running-in ([`SlidingConfig::check_grid`]).
    pub fn new(
        loads: Vec<f64>,
        distance: f64,
        running_in: f64,
        step_running_in: usize,
        step: usize,
        grid: Option<usize>,
    ) -> Result<Self> {
        if loads.is_empty() {
            return Err(Error::param(
                "loads",
                "the list is empty; give at least one normal load",
            ));
        }
        for &f in &loads {
            positive("loads", f)?;
        }
        if !(distance > 0.0 && distance <= 1.0) {
            return Err(Error::param(
                "distance",
                format!("{distance} must lie in (0, 1] (a fraction of the box side Lx)"),
            ));
        }
        if !(running_in >= 0.0 && running_in < distance) {
            return Err(Error::param(
                "running_in",
                format!("{running_in} must lie in [0, distance = {distance}) (a fraction of the box side Lx)"),
            ));
        }
        for (field, v) in [("step_running_in", step_running_in), ("step", step)] {
            if v == 0 {
                return Err(Error::param(field, format!("{v} pixels must be at least 1")));
            }
        }
        let config = Self {
            loads,
            distance,
            running_in,
            step_running_in,
            step,
            particle_rule: ParticleRuleSpec::default(),
        };
        if let Some(n) = grid {
            config.check_grid(n)?;
        }
        Ok(config)
    }

    /// The peak memory of a sliding run with this schedule, in arrays of Nx·Ny doubles: the
    /// run's own ([`crate::check::SLIDING_ARRAYS`]) and what its particle rule adds.
    pub fn memory_arrays(&self) -> f64 {
        crate::check::SLIDING_ARRAYS + self.particle_rule.kind.memory_arrays
    }

    /// The schedule with particles counted by `rule` (a rule with its parameters, or a rule's kind
    /// with its defaults).
    pub fn with_particle_rule(self, rule: impl Into<ParticleRuleSpec>) -> Self {
        Self {
            particle_rule: rule.into(),
            ..self
        }
    }

    /// Sliding offsets in pixels on an `n`-pixel grid (paper §3): from 0 in steps of
    /// `step_running_in` while below the running-in distance, then from the running-in distance in
    /// steps of `step` while below the total distance (the end point excluded). Distances are
    /// rounded to whole pixels. The paper's schedule gives 1,280 offsets at N = 4096.
    pub fn offsets(&self, n: usize) -> Vec<usize> {
        let (running_in, distance) = (self.running_in_pixels(n), self.distance_pixels(n));
        let mut offsets: Vec<usize> = (0..running_in).step_by(self.step_running_in).collect();
        offsets.extend((running_in..distance).step_by(self.step));
        offsets
    }

    /// The running-in distance in whole pixels.
    pub fn running_in_pixels(&self, n: usize) -> usize {
        (self.running_in * n as f64).round() as usize
    }

    fn distance_pixels(&self, n: usize) -> usize {
        (self.distance * n as f64).round() as usize
    }

    /// Checks the schedule on an `n`-pixel grid: steps below the grid size, and at least two steps
    /// after running-in, the fewest a wear rate can be fitted to.
    pub fn check_grid(&self, n: usize) -> Result<()> {
        for (field, step) in [("step_running_in", self.step_running_in), ("step", self.step)] {
            if step >= n {
                return Err(Error::param(
                    field,
                    format!("{step} pixels must be below the grid size {n}"),
                ));
            }
        }
        let fitted = (self.running_in_pixels(n)..self.distance_pixels(n))
            .step_by(self.step)
            .count();
        if fitted < 2 {
            return Err(Error::param(
                "distance",
                format!(
                    "{} − running_in {} leaves {fitted} step(s) of {} px on the {n}-pixel grid after running-in; the \
                     wear rate is a line fitted to at least two: raise `distance`, lower `running_in` or `step`, or \
                     refine `grid`",
                    self.distance, self.running_in, self.step
                ),
            ));
        }
        Ok(())
    }
}

/// Sliding offsets in pixels along x (paper §3): see [`SlidingConfig::offsets`].
pub fn schedule(nx: usize, sliding: &SlidingConfig) -> Vec<usize> {
    sliding.offsets(nx)
}

/// Everything a sliding run needs besides the surfaces.
#[derive(Debug, Clone)]
pub struct SlidingSetup<'a> {
    pub material: &'a Material,
    pub effective_modulus: f64,
    pub solver: SolverOptions,
    /// Where the contact solver computes (`[contact] device`).
    pub device: Device,
    pub connectivity: u8,
    pub sliding: &'a SlidingConfig,
    /// Raised by another thread to stop the run ([`Error::Interrupted`]).
    pub interrupt: Interrupt,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn schedule(distance: f64, running_in: f64, step: usize) -> SlidingConfig {
        SlidingConfig {
            loads: vec![1e-3],
            distance,
            running_in,
            step_running_in: DEFAULT_STEP_RUNNING_IN,
            step,
            particle_rule: Default::default(),
        }
    }

    #[test]
    fn paper_schedule_has_1280_offsets_at_4096_and_160_at_512() {
        // The defaults are the paper's schedule (§3).
        let cfg = schedule(DEFAULT_DISTANCE, DEFAULT_RUNNING_IN, DEFAULT_STEP);
        let s = cfg.offsets(4096);
        assert_eq!(s.len(), 1280);
        assert_eq!(&s[..3], &[0, 4, 8]);
        assert_eq!(s[255], 1020);
        assert_eq!(s[256], 1024);
        assert_eq!(*s.last().unwrap(), 2047);
        assert_eq!(cfg.offsets(512).len(), 160);
    }

    #[test]
    fn a_schedule_needs_two_steps_after_running_in() {
        assert!(schedule(0.5, 0.25, 1).check_grid(64).is_ok());
        // 64 px: running-in 16 px, distance 17 px → one fitted step.
        let e = schedule(0.27, 0.25, 1).check_grid(64).unwrap_err().to_string();
        assert!(e.contains("`distance`") && e.contains("1 step"), "{e}");
        assert!(schedule(0.5, 0.25, 64)
            .check_grid(64)
            .unwrap_err()
            .to_string()
            .contains("`step`"));
    }
}
