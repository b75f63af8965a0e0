//! The estimate's constants c₁, c₂, c_v and their spread ([`CALIBRATION`]), and their fit on
//! sliding runs ([`Calibration::fit`], `wearsim estimate-check --fit`).

use crate::error::{Error, Result};
use crate::junctions::particle_volume;

/// The constants of the rule (module documentation), with what they were fitted on.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Calibration {
    /// c₁: the residence of a lone critical junction in units of d̄ (about 2: two asperities of
    /// size d̄ slide past each other completely).
    pub residence_factor: f64,
    /// c₂: how much longer a lineage lives per unit of critical coverage θ (merging).
    pub merging_factor: f64,
    /// c_v: the mean particle volume over ω d*³.
    pub volume_factor: f64,
    /// The rule's own spread about the sliding runs, as the standard deviation of ln(sliding/estimate)
    /// of the particle rate, once the calibration runs' Poisson noise is taken out.
    pub rate_spread: f64,
    /// The same for the wear rate W.
    pub wear_spread: f64,
    /// Settings (load, 𝒢, pair) and particles the constants were fitted on.
    pub settings: usize,
    pub particles: usize,
}

/// The calibration in use: fitted by `wearsim estimate-check studies/estimate-calibration.toml`'s
/// folder `--fit` (docs/estimate.md gives the runs, the command and the fit).
pub const CALIBRATION: Calibration = Calibration {
    residence_factor: 1.750,
    merging_factor: 17.35,
    volume_factor: 1.121,
    rate_spread: 0.087,
    wear_spread: 0.063,
    settings: 25,
    particles: 754,
};

/// One point of a calibration: the static features of a setting and what its sliding run measured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CalibrationPoint {
    /// N*, d̄ and θ of the static maps.
    pub critical_junctions: f64,
    pub mean_critical_diameter: f64,
    pub critical_coverage: f64,
    /// d* of the setting.
    pub critical_diameter: f64,
    /// The sliding run's dN*₊/ds and W, and the particles they were fitted on.
    pub particle_rate: f64,
    pub wear_rate: f64,
    pub particles: usize,
}

/// Settings with fewer particles than this are left out of a fit: their rates are mostly noise.
pub const FIT_MIN_PARTICLES: usize = 10;

impl Calibration {
    /// Fits c₁, c₂ and c_v to sliding runs, by weighted least squares in ln with each setting
    /// weighted by its particles (the inverse of its Poisson variance): c₂ by a search over
    /// [0, 100] (steps of 0.05), c₁ and c_v then in closed form. The spreads are the weighted
    /// residual variances less the mean Poisson variance 1/n of the runs (at least 0). Points with
    /// fewer than [`FIT_MIN_PARTICLES`] particles are left out; at least three must remain.
    pub fn fit(points: &[CalibrationPoint]) -> Result<Calibration> {
        let used: Vec<&CalibrationPoint> = points
            .iter()
            .filter(|p| {
                p.particles >= FIT_MIN_PARTICLES
                    && p.particle_rate > 0.0
                    && p.wear_rate > 0.0
                    && p.critical_junctions > 0.0
                    && p.mean_critical_diameter > 0.0
            })
            .collect();
        if used.len() < 3 {
            return Err(Error::param(
                "calibration",
                format!(
                    "{} setting(s) with at least {FIT_MIN_PARTICLES} particles and critical junctions in the static \
                     maps; the fit needs at least 3: slide longer, larger boxes or higher loads",
                    used.len()
                ),
            ));
        }
        let w: Vec<f64> = used.iter().map(|p| p.particles as f64).collect();
        let wsum: f64 = w.iter().sum();
        let wmean = |v: &dyn Fn(usize) -> f64| (0..used.len()).map(|i| w[i] * v(i)).sum::<f64>() / wsum;
        // ln(R/d̄) = ln c₁ + ln(1 + c₂ θ), R = N*/(dN*₊/ds).
        let y: Vec<f64> = used
            .iter()
            .map(|p| (p.critical_junctions / p.particle_rate / p.mean_critical_diameter).ln())
            .collect();
        let mut best = (f64::INFINITY, 0.0, 0.0);
        for step in 0..=2000 {
            let c2 = step as f64 * 0.05;
            let z = |i: usize| y[i] - (c2 * used[i].critical_coverage).ln_1p();
            let ln_c1 = wmean(&z);
            let var = wmean(&|i| (z(i) - ln_c1).powi(2));
            if var < best.0 {
                best = (var, c2, ln_c1);
            }
        }
        let (rate_var, merging_factor, ln_c1) = best;
        // ln(W / (ω d*³ dN*₊/ds)) = ln c_v on the sliding runs themselves.
        let v: Vec<f64> = used
            .iter()
            .map(|p| (p.wear_rate / (particle_volume(p.critical_diameter) * p.particle_rate)).ln())
            .collect();
        let ln_cv = wmean(&|i| v[i]);
        let residence_factor = ln_c1.exp();
        let volume_factor = ln_cv.exp();
        let cal = Calibration {
            residence_factor,
            merging_factor,
            volume_factor,
            rate_spread: 0.0,
            wear_spread: 0.0,
            settings: used.len(),
            particles: used.iter().map(|p| p.particles).sum(),
        };
        let wear_var = wmean(&|i| {
            let p = used[i];
            (p.wear_rate / cal.wear_rate(p.critical_diameter, cal.particle_rate(p)))
                .ln()
                .powi(2)
        });
        // The Poisson part of each run's ln-rate variance is 1/n; weighted by n it averages to
        // (settings)/(particles).
        let poisson = used.len() as f64 / wsum;
        Ok(Calibration {
            rate_spread: (rate_var - poisson).max(0.0).sqrt(),
            wear_spread: (wear_var - poisson).max(0.0).sqrt(),
            ..cal
        })
    }

    /// Whether `other` has the same constants and spreads (what an estimate uses of it).
    pub fn same_constants(&self, other: &Calibration) -> bool {
        self.residence_factor == other.residence_factor
            && self.merging_factor == other.merging_factor
            && self.volume_factor == other.volume_factor
            && self.rate_spread == other.rate_spread
            && self.wear_spread == other.wear_spread
    }

    /// Checks constants given by a user (`[sliding] estimate_constants`): c₁, c₂... positive and
    /// finite, the spreads finite and not negative; `field` names where they were given.
    pub fn checked(self, field: &str) -> Result<Calibration> {
        for (name, value, positive) in [
            ("residence_factor", self.residence_factor, true),
            ("merging_factor", self.merging_factor, false),
            ("volume_factor", self.volume_factor, true),
            ("rate_spread", self.rate_spread, false),
            ("wear_spread", self.wear_spread, false),
        ] {
            let ok = value.is_finite() && if positive { value > 0.0 } else { value >= 0.0 };
            if !ok {
                return Err(Error::param(
                    field,
                    format!(
                        "{name} = {value} is not {}: give the constants `wearsim estimate-check STUDY --fit` printed",
                        if positive {
                            "a positive number"
                        } else {
                            "a number ≥ 0"
                        }
                    ),
                ));
            }
        }
        Ok(self)
    }

    /// The residence R = c₁ d̄ (1 + c₂ θ).
    pub fn residence(&self, mean_critical_diameter: f64, critical_coverage: f64) -> f64 {
        self.residence_factor * mean_critical_diameter * (1.0 + self.merging_factor * critical_coverage)
    }

    /// dN*₊/ds = N*/R of a point's static features.
    pub fn particle_rate(&self, p: &CalibrationPoint) -> f64 {
        p.critical_junctions / self.residence(p.mean_critical_diameter, p.critical_coverage)
    }

    /// W = c_v ω d*³ dN*₊/ds.
    pub fn wear_rate(&self, critical_diameter: f64, particle_rate: f64) -> f64 {
        self.volume_factor * particle_volume(critical_diameter) * particle_rate
    }
}
