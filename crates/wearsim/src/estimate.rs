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

use std::sync::Arc;

use crate::contact::{ContactSolver, Stopping};
use crate::error::{Error, Result};
use crate::influence::Boundary;
use crate::junctions::{circle_area, particle_volume, Junction, JunctionLabeller};
use crate::material::Material;
use crate::sliding::{SlidingSetup, WearResult};
use crate::surface::Surface;
use crate::wear::{box_wrapping_warning, is_critical, static_wear};

/// Fewest static maps of an estimate with samples chosen automatically.
pub const MIN_SAMPLES: usize = 4;
/// Most static maps of an estimate (the slots of the offset sequence).
pub const MAX_SAMPLES: usize = 16;
/// With samples chosen automatically, maps are added until the sampling error of N* that each
/// result reports ([`sampling_error`]: the standard error between maps, at least the Poisson error of
/// the junctions counted) is at most this for every load and 𝒢 with N* ≥
/// [`RESOLVED_CRITICAL_JUNCTIONS`], or [`MAX_SAMPLES`] are taken (then a warning says so): small
/// beside the rule's own spread about the sliding runs.
pub const TARGET_SAMPLING_ERROR: f64 = 0.10;
/// Below this mean number of critical junctions per map, N* is a count of a few junctions and the
/// estimate is flagged as under-resolved.
pub const RESOLVED_CRITICAL_JUNCTIONS: f64 = 2.0;
/// Two-sided 95 % quantile of the normal distribution, for the intervals in ln.
const Z95: f64 = 1.959_963_984_540_054;

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

/// What the calibration's runs covered ([`CALIBRATED_DOMAIN`]): a setting outside it is an
/// extrapolation of the rule, and its estimate says so ([`run_reach_warnings`], [`load_reach_warnings`]).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Domain {
    /// Hurst exponent H of wearsim's generated surfaces (lowest, highest).
    pub hurst: (f64, f64),
    /// λ_l/Δx, the lower cut-off in pixels.
    pub lower_cutoff_pixels: (f64, f64),
    /// λ_u/Lx, the upper cut-off in box lengths.
    pub upper_cutoff_box: (f64, f64),
    /// The fraction of the box in contact in the static maps.
    pub contact_fraction: (f64, f64),
    /// N*, the mean number of junctions with d_i ≥ d* per static map, of the settings fitted on.
    pub critical_junctions: (f64, f64),
    /// The running-in the calibration's runs were fitted after, in box lengths and in λ_u.
    pub running_in_box: f64,
    pub running_in_upper_cutoffs: f64,
}

/// The reach of [`CALIBRATION`]: the settings of `studies/estimate-calibration.toml` (surfaces of
/// wearsim's generator with H = 0.7, λ_l = 16 Δx, λ_u = Lx/4; p_N = 0.5 … 2.5×10⁻³ E; running-in
/// Lx/4 = λ_u) and of the held-out checks that held (docs/estimate.md: the box of side L/2, where
/// λ_u = Lx/8 and N* per map reached about 120 at d* = 23.6 px). Contact fractions and N* are
/// those of the calibration's static maps (`wearsim estimate` on its three pairs, four maps per
/// load: contact 0.96–4.82 %; N* 6.2–29 at d* = 23.6 px and from about 3 at 47.3 px among the
/// settings with at least 10 particles that the fit used).
pub const CALIBRATED_DOMAIN: Domain = Domain {
    hurst: (0.7, 0.7),
    lower_cutoff_pixels: (16.0, 16.0),
    upper_cutoff_box: (0.125, 0.25),
    contact_fraction: (0.009, 0.05),
    critical_junctions: (3.0, 120.0),
    running_in_box: 0.25,
    running_in_upper_cutoffs: 1.0,
};

/// The surfaces of an estimate, as far as the calibration's reach is concerned.
#[derive(Debug, Clone, PartialEq)]
pub enum SurfaceKind {
    /// Made by wearsim's self-affine generator.
    Generated {
        hurst: f64,
        /// λ_l/Δx.
        lower_cutoff_pixels: f64,
        /// λ_u/Lx.
        upper_cutoff_box: f64,
        /// λ_u itself, in the run's length unit.
        upper_cutoff: f64,
    },
    /// Anything else (a measured map read from files, arrays a caller gave, …), as the warning
    /// names it.
    Other(String),
}

/// What to do about a setting outside the calibration's reach, the end of every reach warning.
const REFIT_ADVICE: &str = "run a few sliding runs of your own surface family (a small study), then `wearsim \
    estimate-check STUDY --out CHECK --fit` and give the constants it prints as `[sliding] estimate_constants` \
    (docs/estimate.md, \"Your own surfaces\")";

fn outside(value: f64, (lo, hi): (f64, f64)) -> bool {
    // A relative slack of 10⁻⁶: the calibrated values themselves, as a run file writes them, are inside.
    value < lo * (1.0 - 1e-6) || value > hi * (1.0 + 1e-6)
}

fn range((lo, hi): (f64, f64), digits: usize) -> String {
    if lo == hi {
        format!("{lo:.digits$}")
    } else {
        format!("{lo:.digits$}–{hi:.digits$}")
    }
}

/// One way a setting lies outside the calibration's reach: what (a few words, as a result's
/// `interval_withheld` names it), the fracture energy it concerns (index in the material's order;
/// none: every one) and the warning that says it in full, with what to do.
#[derive(Debug, Clone, PartialEq)]
pub struct OutsideReach {
    pub what: String,
    pub energy: Option<usize>,
    pub warning: String,
}

/// Where the settings of the run as a whole lie outside `domain`: the surfaces (any kind but
/// [`SurfaceKind::Generated`] with H, λ_l/Δx and λ_u/Lx in range is outside) and the running-in
/// of `sliding` on a box of side `length` along x.
pub fn run_reach(
    domain: &Domain,
    surfaces: &SurfaceKind,
    sliding: &crate::sliding::SlidingConfig,
    length: f64,
) -> Vec<OutsideReach> {
    let mut out = Vec::new();
    let mut not_calibrated = |what: &str, text: String| {
        out.push(OutsideReach {
            what: what.into(),
            energy: None,
            warning: format!(
                "{text}: the static estimate's constants were not calibrated there, so its W, k and dN*₊/ds are an \
                 extrapolation and are given without an interval (on pairs carrying measured spectra its median \
                 error of W was 19 % for a self-affine one and 37–82 % for two that are not, and on measured maps \
                 slid tapered it missed by factors of 3 to 13: docs/estimate.md); {REFIT_ADVICE}"
            ),
        })
    };
    match surfaces {
        SurfaceKind::Generated {
            hurst,
            lower_cutoff_pixels,
            upper_cutoff_box,
            ..
        } => {
            for (name, value, calibrated, digits) in [
                ("Hurst exponent H", *hurst, domain.hurst, 2),
                ("λ_l/Δx", *lower_cutoff_pixels, domain.lower_cutoff_pixels, 1),
                ("λ_u/Lx", *upper_cutoff_box, domain.upper_cutoff_box, 3),
            ] {
                if outside(value, calibrated) {
                    not_calibrated(
                        &format!("the surfaces' {name}"),
                        format!(
                            "the surfaces' {name} is {value:.digits$}, outside the calibrated {}",
                            range(calibrated, digits)
                        ),
                    );
                }
            }
        }
        SurfaceKind::Other(what) => not_calibrated(
            "surfaces not of the calibrated spectrum",
            format!(
                "the surfaces are {what}, not the self-affine spectrum of wearsim's generator that the calibration \
                 used (H = {}, λ_l/Δx = {}, λ_u/Lx = {})",
                range(domain.hurst, 2),
                range(domain.lower_cutoff_pixels, 0),
                range(domain.upper_cutoff_box, 3)
            ),
        ),
    }
    let short_box = sliding.running_in < domain.running_in_box * (1.0 - 1e-6);
    let short_cutoffs = match surfaces {
        SurfaceKind::Generated { upper_cutoff, .. } if *upper_cutoff > 0.0 => {
            let n = sliding.running_in * length / upper_cutoff;
            (n < domain.running_in_upper_cutoffs * (1.0 - 1e-6)).then_some(n)
        }
        _ => None,
    };
    if short_box || short_cutoffs.is_some() {
        out.push(OutsideReach {
            what: "a shorter running-in".into(),
            energy: None,
            warning: format!(
                "the run's running-in is {:.3} box lengths{}, shorter than the calibration's runs were fitted after \
                 ({} box lengths, {} λ_u): a sliding run of this schedule is fitted while the memory of the initial \
                 contact still fades, where its rates are lower than the estimate's, so no interval is given; \
                 lengthen `[sliding] running_in` (and `distance`), or calibrate on runs of this schedule: \
                 {REFIT_ADVICE}",
                sliding.running_in,
                short_cutoffs.map_or(String::new(), |n| format!(" ({n:.2} λ_u)")),
                domain.running_in_box,
                domain.running_in_upper_cutoffs
            ),
        });
    }
    out
}

/// The warnings of [`run_reach`].
pub fn run_reach_warnings(
    domain: &Domain,
    surfaces: &SurfaceKind,
    sliding: &crate::sliding::SlidingConfig,
    length: f64,
) -> Vec<String> {
    run_reach(domain, surfaces, sliding, length)
        .into_iter()
        .map(|r| r.warning)
        .collect()
}

/// Where one load's static maps lie outside `domain`: their contact fraction, and N* per map of
/// each fracture energy (any N* > 0 outside the range: below [`RESOLVED_CRITICAL_JUNCTIONS`] the
/// warning about a few junctions says it too).
pub fn load_reach(domain: &Domain, samples: &[Sample], material: &Material, load: f64) -> Vec<OutsideReach> {
    let mut out = Vec::new();
    if samples.is_empty() {
        return out;
    }
    let contact = samples.iter().map(|s| s.contact_area).sum::<f64>() / samples.len() as f64;
    if outside(contact, domain.contact_fraction) {
        out.push(OutsideReach {
            what: format!("contact fraction {:.2} %", 100.0 * contact),
            energy: None,
            warning: format!(
                "F_N = {load:.4e}: the static maps' contact fraction is {:.2} %, outside the calibrated {:.1}–{:.1} %: \
                 the junctions merge and live differently there than the constants say, so no interval is given; \
                 {REFIT_ADVICE}",
                100.0 * contact,
                100.0 * domain.contact_fraction.0,
                100.0 * domain.contact_fraction.1
            ),
        });
    }
    for (e, (&g, d)) in material
        .fracture_energies
        .iter()
        .zip(material.critical_diameters())
        .enumerate()
    {
        let (n, _) = critical_stats(samples, e);
        let (lo, hi) = domain.critical_junctions;
        // Below the range the interval goes too (the held-out sets: with N* ≲ 1 per map the rule
        // missed by factors of 2); the warning of a few junctions already says why under 2 per map.
        let low = n > 0.0 && n < lo;
        if low || n > hi {
            out.push(OutsideReach {
                what: format!("N* = {n:.1} per map"),
                energy: Some(e),
                warning: format!(
                    "F_N = {load:.4e}, 𝒢 = {g:.4e} (d* = {d:.4e}): {n:.1} critical junctions (d_i ≥ d*) per static map, \
                     {} the calibrated {lo:.0}–{hi:.0}, so no interval is given; {REFIT_ADVICE}",
                    if low { "below" } else { "above" }
                ),
            });
        }
    }
    out
}

/// The warnings of [`load_reach`].
pub fn load_reach_warnings(domain: &Domain, samples: &[Sample], material: &Material, load: f64) -> Vec<String> {
    load_reach(domain, samples, material, load)
        .into_iter()
        .map(|r| r.warning)
        .collect()
}

/// The estimate of one load as every front end gives it: [`results_of`] under `calibration`, and,
/// with the library's constants ([`CALIBRATION`]), its reach checked: `run_reach` (the run's,
/// [`run_reach`]) and the load's own ([`load_reach`]) are warned about, and every result they
/// concern loses its interval ([`EstimateResult::withhold_interval`]). Outside the calibrated
/// domain the constants have missed sliding runs by more than any interval of their spread allows
/// (docs/estimate.md), so a 95 % interval there would promise what the rule cannot keep. With
/// constants of one's own the intervals stand: their reach is the runs they were fitted on.
#[allow(clippy::too_many_arguments)]
pub fn load_estimate(
    samples: &[Sample],
    material: &Material,
    load: f64,
    box_sides: (f64, f64),
    fit_distance: f64,
    calibration: &Calibration,
    run_reach: &[OutsideReach],
) -> (Vec<EstimateResult>, Vec<String>) {
    let (mut results, mut warnings) = results_of(samples, material, load, box_sides, fit_distance, calibration);
    if !calibration.same_constants(&CALIBRATION) {
        return (results, warnings);
    }
    let own = load_reach(&CALIBRATED_DOMAIN, samples, material, load);
    let reach: Vec<&OutsideReach> = run_reach.iter().chain(&own).collect();
    warnings.extend(reach.iter().map(|r| r.warning.clone()));
    for (e, r) in results.iter_mut().enumerate() {
        let whats: Vec<&str> = reach
            .iter()
            .filter(|o| o.energy.is_none_or(|i| i == e))
            .map(|o| o.what.as_str())
            .collect();
        if !whats.is_empty() {
            r.withhold_interval(format!("outside the calibrated domain: {}", whats.join("; ")));
        }
    }
    (results, warnings)
}

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

/// What one static map gives for one d*.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SampleCount {
    /// Junctions with d_i ≥ d*.
    pub critical_junctions: usize,
    /// The sum of their diameters.
    pub diameter_sum: f64,
    /// The static model's k (paper §2) of this map.
    pub static_wear_coefficient: f64,
    /// The static model's W_static/ω = k Σ A_i of this map.
    pub static_wear_rate: f64,
}

/// One static map of one load.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Sample {
    /// The offset of the top surface, pixels along x.
    pub offset: usize,
    /// All junctions of the map.
    pub junctions: usize,
    /// The fraction of the box in contact.
    pub contact_area: f64,
    /// Junctions that wrap the periodic box (no particles of the model, paper §3; counted as the
    /// sliding model counts them, and warned about).
    #[serde(default)]
    pub wrapping_junctions: usize,
    /// Solver iterations.
    pub iterations: usize,
    /// Per fracture energy, in the material's order.
    pub counts: Vec<SampleCount>,
}

/// The estimate for one load and fracture energy.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct EstimateResult {
    pub fracture_energy: f64,
    pub critical_diameter: f64,
    /// W, the wear rate (volume per sliding distance), and its 95 % interval for a sliding run of
    /// this box and distance (module documentation); absent without a critical junction.
    pub wear_rate: Option<f64>,
    pub wear_rate_low: Option<f64>,
    pub wear_rate_high: Option<f64>,
    /// k = W p_m/F_N (Eq. 2), with its interval.
    pub wear_coefficient: Option<f64>,
    pub wear_coefficient_low: Option<f64>,
    pub wear_coefficient_high: Option<f64>,
    /// dN*₊/ds = N*/R (particles per sliding distance), with its interval.
    pub particle_rate: Option<f64>,
    pub particle_rate_low: Option<f64>,
    pub particle_rate_high: Option<f64>,
    /// N*, the mean number of critical junctions over the static maps.
    pub critical_junctions_mean: f64,
    /// The relative standard error of N* over the maps, and at least the Poisson error 1/√n of
    /// the n critical junctions counted (the estimate's own sampling error, as its interval takes
    /// it); absent without a critical junction.
    pub critical_junctions_sampling_error: Option<f64>,
    /// d̄, the mean diameter of the critical junctions.
    pub mean_critical_diameter: Option<f64>,
    /// θ = N* d̄²/(Lx Ly).
    pub critical_coverage: f64,
    /// R = c₁ d̄ (1 + c₂ θ): the sliding distance a critical junction lives per particle.
    pub critical_residence: Option<f64>,
    /// Particles a sliding run of this box would count after running-in (dN*₊/ds times the fit
    /// window), whose Poisson noise the interval includes.
    pub expected_particles: Option<f64>,
    /// N, the mean number of junctions over the maps.
    pub junctions_mean: f64,
    /// The static model (paper §2) over the maps: mean and standard deviation of k_static and of
    /// W_static/ω.
    pub static_wear_coefficient_mean: f64,
    pub static_wear_coefficient_std: f64,
    #[serde(default)]
    pub static_wear_rate_mean: f64,
    #[serde(default)]
    pub static_wear_rate_std: f64,
    /// Why W, k and dN*₊/ds carry no interval although they are defined: the setting lies outside
    /// the calibrated domain ([`load_estimate`]); absent where the interval is given (or W is
    /// undefined).
    #[serde(default)]
    pub interval_withheld: Option<String>,
}

impl EstimateResult {
    /// Drops the 95 % intervals of W, k and dN*₊/ds, saying why (`reason`); the point values stay.
    pub fn withhold_interval(&mut self, reason: String) {
        if self.wear_rate.is_none() {
            return;
        }
        self.wear_rate_low = None;
        self.wear_rate_high = None;
        self.wear_coefficient_low = None;
        self.wear_coefficient_high = None;
        self.particle_rate_low = None;
        self.particle_rate_high = None;
        self.interval_withheld = Some(reason);
    }

    /// The unit of every field: (field, reduced units, SI units), as `WearResult::UNITS`.
    pub const UNITS: &'static [(&'static str, &'static str, &'static str)] = &[
        ("fracture_energy", "E L", "J/m²"),
        ("critical_diameter", "L", "m"),
        ("wear_rate", "L²", "m²"),
        ("wear_rate_low", "L²", "m²"),
        ("wear_rate_high", "L²", "m²"),
        ("wear_coefficient", "1", "1"),
        ("wear_coefficient_low", "1", "1"),
        ("wear_coefficient_high", "1", "1"),
        ("particle_rate", "1/L", "1/m"),
        ("particle_rate_low", "1/L", "1/m"),
        ("particle_rate_high", "1/L", "1/m"),
        ("critical_junctions_mean", "", ""),
        ("critical_junctions_sampling_error", "1", "1"),
        ("mean_critical_diameter", "L", "m"),
        ("critical_coverage", "1", "1"),
        ("critical_residence", "L", "m"),
        ("expected_particles", "", ""),
        ("junctions_mean", "", ""),
        ("static_wear_coefficient_mean", "1", "1"),
        ("static_wear_coefficient_std", "1", "1"),
        ("static_wear_rate_mean", "L²", "m²"),
        ("static_wear_rate_std", "L²", "m²"),
        ("interval_withheld", "", ""),
    ];
}

impl EstimateResult {
    /// The estimate in the sliding model's result columns, for a study's tables and figures: W, k,
    /// dN*₊/ds, Eq. 5's ω d*³ dN*₊/ds (W/c_v), N*, N, the residence and the static model over the
    /// maps (its "s = 0" columns from the first map, at offset 0); what only a sliding run measures
    /// (R² of the fits, V₀, the memory, particles counted) is absent or zero. The job that holds it
    /// is marked `sliding.model = "estimate"`.
    pub fn as_wear_result(&self, first_map: Option<&SampleCount>) -> WearResult {
        WearResult {
            fracture_energy: self.fracture_energy,
            critical_diameter: self.critical_diameter,
            wear_rate: self.wear_rate,
            wear_coefficient: self.wear_coefficient,
            particle_rate: self.particle_rate,
            wear_rate_estimate: self.particle_rate.map(|r| particle_volume(self.critical_diameter) * r),
            static_wear_coefficient: first_map.map_or(0.0, |m| m.static_wear_coefficient),
            static_wear_rate: first_map.map_or(0.0, |m| m.static_wear_rate),
            static_wear_coefficient_mean: self.static_wear_coefficient_mean,
            static_wear_coefficient_std: self.static_wear_coefficient_std,
            static_wear_rate_mean: self.static_wear_rate_mean,
            static_wear_rate_std: self.static_wear_rate_std,
            junctions_mean: self.junctions_mean,
            critical_junctions_mean: self.critical_junctions_mean,
            critical_residence: self.critical_residence,
            ..WearResult::default()
        }
    }
}

/// The estimate of one load.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LoadEstimate {
    pub load: f64,
    pub results: Vec<EstimateResult>,
    pub samples: Vec<Sample>,
    pub warnings: Vec<String>,
}

/// The offsets of the static maps: slot j of sixteen at j·Lx/16, taken in van der Corput order
/// (0, 8, 4, 12, 2, …), so that the first k of them are spread over the box for every k.
pub fn sample_offsets(nx: usize, samples: usize) -> Vec<usize> {
    (0..samples.min(MAX_SAMPLES))
        .map(|k| {
            let slot = (k as u32).reverse_bits() >> 28;
            (slot as usize * nx) / MAX_SAMPLES
        })
        .collect()
}

/// How many static maps: a fixed number, or chosen as the sampling error asks
/// ([`TARGET_SAMPLING_ERROR`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sampling {
    Auto,
    Fixed(usize),
}

impl Sampling {
    /// `[sliding] estimate_samples`, checked: absent is [`Sampling::Auto`].
    pub fn of(samples: Option<usize>) -> Result<Sampling> {
        match samples {
            None => Ok(Sampling::Auto),
            Some(k) if (1..=MAX_SAMPLES).contains(&k) => Ok(Sampling::Fixed(k)),
            Some(k) => Err(Error::param(
                "estimate_samples",
                format!(
                    "{k} static maps: give 1 to {MAX_SAMPLES}, or leave it out to choose them by the sampling error"
                ),
            )),
        }
    }
}

/// An estimate under way: the solver bound to the surfaces, and the maps solved so far.
pub struct Estimator<'a> {
    setup: &'a SlidingSetup<'a>,
    solver: ContactSolver,
    labeller: JunctionLabeller,
    junctions: Vec<Junction>,
    diameters: Vec<f64>,
    nx: usize,
    area: f64,
    /// Lx × Ly.
    box_sides: (f64, f64),
    dx: f64,
    /// Per load, the maps so far.
    samples: Vec<Vec<Sample>>,
}

impl<'a> Estimator<'a> {
    /// Binds the solver to the surfaces (periodic, the settled contact map as in a sliding step).
    pub fn new(top: Surface, bottom: Surface, setup: &'a SlidingSetup<'a>) -> Result<Self> {
        let grid = top.grid();
        if bottom.grid() != grid {
            return Err(Error::param(
                "surface",
                "the top and bottom surfaces lie on different grids; give both on one grid",
            ));
        }
        let mut solver = ContactSolver::on_device(setup.device, grid, setup.effective_modulus, Boundary::Periodic)?
            .with_options(setup.solver.with_stopping(Stopping::SettledMap))
            .with_interrupt(setup.interrupt.clone());
        solver.bind_surfaces(Arc::new(top), Arc::new(bottom))?;
        Ok(Self {
            setup,
            solver,
            labeller: JunctionLabeller::new(grid.nx(), grid.ny(), setup.connectivity),
            junctions: Vec::new(),
            diameters: setup.material.critical_diameters(),
            nx: grid.nx(),
            area: grid.area(),
            box_sides: (grid.length_x(), grid.length_y()),
            dx: grid.pixel_size(),
            samples: vec![Vec::new(); setup.sliding.loads.len()],
        })
    }

    /// Maps solved so far per load.
    pub fn samples_done(&self) -> usize {
        self.samples.first().map_or(0, Vec::len)
    }

    /// Solves the next offset of the sequence at every load (each load warm-started from the
    /// previous one's pressure, the first cold) and labels its junctions. `on_solve` is called after
    /// each solve.
    pub fn add_sample(&mut self, mut on_solve: impl FnMut()) -> Result<()> {
        let k = self.samples_done();
        if k >= MAX_SAMPLES {
            return Err(Error::param(
                "estimate_samples",
                format!("at most {MAX_SAMPLES} static maps"),
            ));
        }
        let offset = sample_offsets(self.nx, k + 1)[k];
        self.solver.compose(offset)?;
        self.solver.set_pressure(|p| p.fill(0.0));
        let pm = self.setup.material.flow_pressure();
        for (l, &load) in self.setup.sliding.loads.iter().enumerate() {
            self.setup.interrupt.check()?;
            let info = self.solver.solve_in_place(load / self.area, pm)?;
            let map = self.solver.contact_map();
            let count = self.labeller.label(|i| map.contains(i));
            self.labeller.junctions_into(self.dx, &mut self.junctions);
            let counts = self
                .diameters
                .iter()
                .map(|&d| {
                    let a = circle_area(d);
                    let (n, sum) = self
                        .junctions
                        .iter()
                        .filter(|j| is_critical(j, a))
                        .fold((0, 0.0), |(n, s), j| (n + 1, s + j.diameter));
                    let statics = static_wear(&self.junctions, d);
                    SampleCount {
                        critical_junctions: n,
                        diameter_sum: sum,
                        static_wear_coefficient: statics.wear_coefficient,
                        static_wear_rate: statics.wear_rate_over_omega,
                    }
                })
                .collect();
            self.samples[l].push(Sample {
                offset,
                junctions: count,
                wrapping_junctions: self.labeller.wrapping(),
                contact_area: info.contact_pixels as f64 / (self.area / (self.dx * self.dx)),
                iterations: info.iterations,
                counts,
            });
            on_solve();
        }
        Ok(())
    }

    /// The largest sampling error of N* ([`sampling_error`], the one each result reports and its
    /// interval takes) among the loads and 𝒢 with N* ≥ [`RESOLVED_CRITICAL_JUNCTIONS`] (0 when
    /// there is none).
    pub fn sampling_error(&self) -> f64 {
        self.samples
            .iter()
            .flat_map(|s| (0..self.diameters.len()).map(move |e| (critical_stats(s, e).0, sampling_error(s, e))))
            .filter(|(mean, _)| *mean >= RESOLVED_CRITICAL_JUNCTIONS)
            .filter_map(|(_, err)| err)
            .fold(0.0, f64::max)
    }

    /// Takes maps until `sampling` is met: a fixed number, or from [`MIN_SAMPLES`] until the
    /// sampling error is at most [`TARGET_SAMPLING_ERROR`] (or [`MAX_SAMPLES`] are taken).
    pub fn sample(&mut self, sampling: Sampling, mut on_solve: impl FnMut()) -> Result<()> {
        loop {
            let k = self.samples_done();
            let enough = match sampling {
                Sampling::Fixed(n) => k >= n,
                Sampling::Auto => {
                    k >= MAX_SAMPLES || (k >= MIN_SAMPLES && self.sampling_error() <= TARGET_SAMPLING_ERROR)
                }
            };
            if enough {
                return Ok(());
            }
            self.add_sample(&mut on_solve)?;
        }
    }

    /// The estimate of every load from the maps taken, with `calibration`'s constants, on surfaces
    /// of kind `surfaces`. With the library's constants ([`CALIBRATION`]) each load's warnings say
    /// where its setting lies outside their reach ([`CALIBRATED_DOMAIN`]: [`run_reach_warnings`],
    /// [`load_reach_warnings`]); with constants of one's own, a note says that their reach is the
    /// runs they were fitted on.
    pub fn finish(self, calibration: &Calibration, surfaces: &SurfaceKind) -> Vec<LoadEstimate> {
        let length = self.nx as f64 * self.dx;
        let fit_distance = fit_distance(self.setup.sliding, length);
        let own = !calibration.same_constants(&CALIBRATION);
        let (run_warnings, reach) = if own {
            let note = format!(
                "the estimate uses the run file's `estimate_constants` (c₁ = {:.4}, c₂ = {:.4}, c_v = {:.4}), not the \
                 library's calibration: their reach is the sliding runs they were fitted on, which this estimate cannot \
                 check",
                calibration.residence_factor, calibration.merging_factor, calibration.volume_factor
            );
            (vec![note], Vec::new())
        } else {
            (
                Vec::new(),
                run_reach(&CALIBRATED_DOMAIN, surfaces, self.setup.sliding, length),
            )
        };
        self.setup
            .sliding
            .loads
            .iter()
            .zip(self.samples)
            .map(|(&load, samples)| {
                let (results, mut warnings) = load_estimate(
                    &samples,
                    self.setup.material,
                    load,
                    self.box_sides,
                    fit_distance,
                    calibration,
                    &reach,
                );
                warnings.extend(run_warnings.iter().cloned());
                LoadEstimate {
                    load,
                    results,
                    samples,
                    warnings,
                }
            })
            .collect()
    }
}

/// The sliding distance over which a sliding run of this schedule fits its rates (after
/// running-in), for a box of side `length` along x.
pub fn fit_distance(sliding: &crate::sliding::SlidingConfig, length: f64) -> f64 {
    (sliding.distance - sliding.running_in) * length
}

/// The estimate of one load for every fracture energy of `material` from its static maps, with
/// `calibration`'s constants, and the warnings about it: `box_sides` is the box's Lx × Ly, `fit_distance`
/// the sliding distance of the run whose interval is given ([`fit_distance`]).
pub fn results_of(
    samples: &[Sample],
    material: &Material,
    load: f64,
    box_sides: (f64, f64),
    fit_distance: f64,
    calibration: &Calibration,
) -> (Vec<EstimateResult>, Vec<String>) {
    let pm = material.flow_pressure();
    let mut warnings = Vec::new();
    let wrapping: Vec<&Sample> = samples.iter().filter(|s| s.wrapping_junctions > 0).collect();
    if let Some(first) = wrapping.first() {
        warnings.push(box_wrapping_warning(
            load,
            &format!(
                "in {} of {} static maps (the first at offset {} px)",
                wrapping.len(),
                samples.len(),
                first.offset
            ),
            wrapping.iter().map(|s| s.contact_area).fold(0.0, f64::max),
        ));
    }
    let results = material
        .fracture_energies
        .iter()
        .zip(material.critical_diameters())
        .enumerate()
        .map(|(e, (&g, d))| {
            let r = estimate_of(
                samples,
                e,
                g,
                d,
                load,
                pm,
                box_sides.0 * box_sides.1,
                fit_distance,
                calibration,
            );
            warnings.extend(result_warnings(&r, load, samples.len(), box_sides.0.min(box_sides.1)));
            r
        })
        .collect();
    (results, warnings)
}

/// The sampling error of N* over the maps of fracture energy `e`, as a result reports it and its
/// interval takes it: the relative standard error between maps, and never below the Poisson error
/// 1/√n of the n critical junctions counted (maps that happen to agree, or a single map, do not make
/// N* exact); absent without a critical junction. Automatic sampling stops on this same number.
pub fn sampling_error(samples: &[Sample], e: usize) -> Option<f64> {
    let count: usize = samples.iter().map(|s| s.counts[e].critical_junctions).sum();
    if count == 0 {
        return None;
    }
    let (_, between_maps) = critical_stats(samples, e);
    Some(between_maps.unwrap_or(0.0).max(1.0 / (count as f64).sqrt()))
}

/// Mean N* over the maps of fracture energy `e`, and its relative standard error (absent with
/// fewer than two maps or no critical junction).
fn critical_stats(samples: &[Sample], e: usize) -> (f64, Option<f64>) {
    let n: Vec<f64> = samples.iter().map(|s| s.counts[e].critical_junctions as f64).collect();
    let k = n.len() as f64;
    let mean = n.iter().sum::<f64>() / k.max(1.0);
    if n.len() < 2 || mean <= 0.0 {
        return (mean, None);
    }
    let var = n.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (k - 1.0);
    (mean, Some((var / k).sqrt() / mean))
}

/// The estimate of one load and fracture energy (module documentation).
#[allow(clippy::too_many_arguments)]
fn estimate_of(
    samples: &[Sample],
    e: usize,
    fracture_energy: f64,
    critical_diameter: f64,
    load: f64,
    pm: f64,
    area: f64,
    fit_distance: f64,
    c: &Calibration,
) -> EstimateResult {
    let (n_crit, _) = critical_stats(samples, e);
    let count: usize = samples.iter().map(|s| s.counts[e].critical_junctions).sum();
    let diameter_sum: f64 = samples.iter().map(|s| s.counts[e].diameter_sum).sum();
    let k = samples.len().max(1) as f64;
    let (static_mean, static_std) = crate::stats::mean_std(samples.iter().map(|s| s.counts[e].static_wear_coefficient));
    let (static_w_mean, static_w_std) = crate::stats::mean_std(samples.iter().map(|s| s.counts[e].static_wear_rate));
    let mut r = EstimateResult {
        fracture_energy,
        critical_diameter,
        critical_junctions_mean: n_crit,
        critical_junctions_sampling_error: None,
        junctions_mean: samples.iter().map(|s| s.junctions as f64).sum::<f64>() / k,
        static_wear_coefficient_mean: static_mean,
        static_wear_coefficient_std: static_std,
        static_wear_rate_mean: static_w_mean,
        static_wear_rate_std: static_w_std,
        ..Default::default()
    };
    if count == 0 {
        return r;
    }
    let d_bar = diameter_sum / count as f64;
    let coverage = n_crit * d_bar * d_bar / area;
    let residence = c.residence(d_bar, coverage);
    let rate = n_crit / residence;
    let wear = c.wear_rate(critical_diameter, rate);
    let expected = rate * fit_distance;
    // ln-variance of a sliding run about the estimate: the rule's spread, the sampling error of N*,
    // the run's Poisson noise.
    let sampling = sampling_error(samples, e).unwrap_or(0.0);
    r.critical_junctions_sampling_error = Some(sampling);
    let poisson = 1.0 / expected.max(1e-300);
    let interval = |value: f64, spread: f64| {
        let s = (spread * spread + sampling * sampling + poisson).sqrt();
        (value * (-Z95 * s).exp(), value * (Z95 * s).exp())
    };
    let (mut w_lo, w_hi) = interval(wear, c.wear_spread);
    let (mut r_lo, r_hi) = interval(rate, c.rate_spread);
    // The lower 2.5 % quantile of the run's Poisson count N with mean μ = `expected` is 0 exactly
    // when P(N = 0) = e^{−μ} ≥ 2.5 %: then a sliding run forms no particle, W = 0, often enough
    // that the interval starts at 0.
    if zero_allowed(expected) {
        w_lo = 0.0;
        r_lo = 0.0;
    }
    let to_k = |w: f64| w * pm / load;
    r.mean_critical_diameter = Some(d_bar);
    r.critical_coverage = coverage;
    r.critical_residence = Some(residence);
    r.expected_particles = Some(expected);
    r.particle_rate = Some(rate);
    r.particle_rate_low = Some(r_lo);
    r.particle_rate_high = Some(r_hi);
    r.wear_rate = Some(wear);
    r.wear_rate_low = Some(w_lo);
    r.wear_rate_high = Some(w_hi);
    r.wear_coefficient = Some(to_k(wear));
    r.wear_coefficient_low = Some(to_k(w_lo));
    r.wear_coefficient_high = Some(to_k(w_hi));
    r
}

/// P(N = 0) = e^{−μ} of a sliding run's count of particles, μ the count the estimate expects, above
/// which the interval of W, k and dN*₊/ds starts at 0 (the lower 2.5 % tail of a two-sided 95 %
/// interval).
pub const ZERO_PROBABILITY: f64 = 0.025;

/// Whether a sliding run expected to count `expected` particles forms none with probability at
/// least [`ZERO_PROBABILITY`] (μ ≤ ln 40 ≈ 3.69): the exact lower 2.5 % quantile of its Poisson
/// count is then 0.
pub fn zero_allowed(expected: f64) -> bool {
    (-expected).exp() >= ZERO_PROBABILITY
}

/// What a result cannot promise, said loudly; `box_side` is the box's shorter side, beside which
/// d* decides whether a higher load could help.
fn result_warnings(r: &EstimateResult, load: f64, samples: usize, box_side: f64) -> Vec<String> {
    let mut out = Vec::new();
    let what = format!(
        "F_N = {load:.4e}, 𝒢 = {:.4e} (d* = {:.4e})",
        r.fracture_energy, r.critical_diameter
    );
    if r.wear_rate.is_none() {
        let advice = if r.critical_diameter >= box_side {
            format!(
                "; d* is {:.2} times the box's shorter side, so no junction can reach it in this box at any load: \
                 take a box of several d*",
                r.critical_diameter / box_side
            )
        } else {
            " (the sliding model may still form a rare particle); raise the load or take a larger box".into()
        };
        out.push(format!(
            "{what}: no junction of the {samples} static map(s) reaches d*, so no particle is expected and W, k and \
             dN*₊/ds are undefined{advice}"
        ));
    } else if r.critical_junctions_mean < RESOLVED_CRITICAL_JUNCTIONS {
        out.push(format!(
            "{what}: {:.2} critical junctions per static map, under {RESOLVED_CRITICAL_JUNCTIONS}: the estimate rests \
             on a few junctions, its sampling error is {:.0} % (maps are added for the {:.0} % target only from \
             {RESOLVED_CRITICAL_JUNCTIONS} per map on); take a larger box",
            r.critical_junctions_mean,
            100.0 * r.critical_junctions_sampling_error.unwrap_or(f64::NAN),
            100.0 * TARGET_SAMPLING_ERROR
        ));
    }
    if let Some(n) = r.expected_particles.filter(|&n| zero_allowed(n)) {
        out.push(format!(
            "{what}: a sliding run of this box would count about {n:.2} particles after running-in, and none at all \
             with probability e^(−{n:.2}) = {:.0} %: the interval of W, k and dN*₊/ds starts at 0",
            100.0 * (-n).exp()
        ));
    } else if let Some(n) = r.expected_particles.filter(|&n| n < 20.0) {
        out.push(format!(
            "{what}: a sliding run of this box would count about {n:.1} particles after running-in, so its own W would \
             scatter by more than ±{:.0} % (Poisson); the interval includes that",
            100.0 / n.max(1e-9).sqrt()
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offsets_are_spread_for_every_count() {
        assert_eq!(sample_offsets(1024, 4), vec![0, 512, 256, 768]);
        let all = sample_offsets(1024, 16);
        let mut sorted = all.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..16).map(|j| j * 64).collect::<Vec<_>>());
    }

    fn point(n: f64, d: f64, theta: f64, c: &Calibration, particles: usize) -> CalibrationPoint {
        let p = CalibrationPoint {
            critical_junctions: n,
            mean_critical_diameter: d,
            critical_coverage: theta,
            critical_diameter: 0.8 * d,
            particle_rate: 0.0,
            wear_rate: 0.0,
            particles,
        };
        let rate = c.particle_rate(&p);
        CalibrationPoint {
            particle_rate: rate,
            wear_rate: c.wear_rate(p.critical_diameter, rate),
            ..p
        }
    }

    #[test]
    fn the_fit_recovers_known_constants() {
        let truth = Calibration {
            residence_factor: 2.1,
            merging_factor: 12.5,
            volume_factor: 1.15,
            ..CALIBRATION
        };
        let points: Vec<_> = (0..12)
            .map(|i| {
                point(
                    3.0 + i as f64,
                    0.01 + 0.001 * i as f64,
                    0.005 * i as f64,
                    &truth,
                    10_000,
                )
            })
            .collect();
        let fit = Calibration::fit(&points).unwrap();
        assert!((fit.residence_factor - 2.1).abs() < 1e-9, "{fit:?}");
        assert!((fit.merging_factor - 12.5).abs() < 1e-9, "{fit:?}");
        assert!((fit.volume_factor - 1.15).abs() < 1e-9, "{fit:?}");
        assert_eq!(fit.rate_spread, 0.0);
        assert_eq!(fit.settings, 12);
    }

    #[test]
    fn a_fit_needs_three_settings_with_particles() {
        let points: Vec<_> = (0..5)
            .map(|i| point(3.0, 0.01, 0.01 * i as f64, &CALIBRATION, 5))
            .collect();
        let e = Calibration::fit(&points).unwrap_err().to_string();
        assert!(e.contains("at least 3"), "{e}");
    }

    fn sample(contact_area: f64, critical: usize, diameter: f64) -> Sample {
        Sample {
            contact_area,
            junctions: critical,
            counts: vec![SampleCount {
                critical_junctions: critical,
                diameter_sum: critical as f64 * diameter,
                ..Default::default()
            }],
            ..Default::default()
        }
    }

    #[test]
    fn settings_outside_the_calibration_are_warned_about_and_paper_like_ones_not() {
        let sliding = crate::sliding::SlidingConfig::new(vec![1e-3], 0.5, 0.25, 4, 1, Some(1024)).unwrap();
        let paper = SurfaceKind::Generated {
            hurst: 0.7,
            lower_cutoff_pixels: 16.0,
            upper_cutoff_box: 0.25,
            upper_cutoff: 0.0625,
        };
        assert!(run_reach_warnings(&CALIBRATED_DOMAIN, &paper, &sliding, 0.25).is_empty());
        let measured = SurfaceKind::Other("read from height-map files (a measured map)".into());
        let w = run_reach_warnings(&CALIBRATED_DOMAIN, &measured, &sliding, 0.25);
        assert!(
            w.len() == 1 && w[0].contains("measured map") && w[0].contains("--fit"),
            "{w:?}"
        );
        let rough = SurfaceKind::Generated {
            hurst: 0.5,
            lower_cutoff_pixels: 16.0,
            upper_cutoff_box: 0.25,
            upper_cutoff: 0.0625,
        };
        let w = run_reach_warnings(&CALIBRATED_DOMAIN, &rough, &sliding, 0.25);
        assert!(
            w.len() == 1 && w[0].contains("Hurst exponent H is 0.50") && w[0].contains("0.70"),
            "{w:?}"
        );
        // A schedule not run in as the calibration's runs were.
        let short = crate::sliding::SlidingConfig::new(vec![1e-3], 0.2, 0.05, 4, 1, Some(1024)).unwrap();
        let w = run_reach_warnings(&CALIBRATED_DOMAIN, &paper, &short, 0.25);
        assert!(
            w.len() == 1 && w[0].contains("running-in is 0.050 box lengths"),
            "{w:?}"
        );
        // Contact fraction and N* per map.
        let material = Material::new(1.0, 0.3, 0.010, vec![0.25e-6], 3.0).unwrap();
        let d = material.critical_diameters()[0];
        let inside = vec![sample(0.03, 10, d); 4];
        assert!(load_reach_warnings(&CALIBRATED_DOMAIN, &inside, &material, 1e-3).is_empty());
        let crowded = vec![sample(0.2, 200, d); 4];
        let w = load_reach_warnings(&CALIBRATED_DOMAIN, &crowded, &material, 1e-3);
        assert!(w.len() == 2, "{w:?}");
        assert!(
            w[0].contains("contact fraction is 20.00 %") && w[0].contains("0.9–5.0 %"),
            "{w:?}"
        );
        assert!(
            w[1].contains("200.0 critical junctions") && w[1].contains("above the calibrated 3–120"),
            "{w:?}"
        );
    }

    /// Outside the calibrated domain the library's constants give W without an interval, and say
    /// why; inside, and with constants of one's own, the interval stands.
    #[test]
    fn outside_the_calibration_the_interval_is_withheld_and_said_why() {
        let material = Material::new(1.0, 0.3, 0.010, vec![0.25e-6, 1.0e-6], 3.0).unwrap();
        let d = material.critical_diameters();
        let sample2 = |contact: f64, n: [usize; 2]| Sample {
            contact_area: contact,
            junctions: n[0],
            counts: (0..2)
                .map(|e| SampleCount {
                    critical_junctions: n[e],
                    diameter_sum: n[e] as f64 * 1.2 * d[e],
                    ..Default::default()
                })
                .collect(),
            ..Default::default()
        };
        let sliding = crate::sliding::SlidingConfig::new(vec![1e-3], 0.5, 0.25, 4, 1, Some(1024)).unwrap();
        let paper = SurfaceKind::Generated {
            hurst: 0.7,
            lower_cutoff_pixels: 16.0,
            upper_cutoff_box: 0.25,
            upper_cutoff: 0.0625,
        };
        let measured = SurfaceKind::Other("read from height-map files (a measured map)".into());
        let inside = vec![sample2(0.03, [10, 4]); 4];
        let estimate = |samples: &[Sample], kind: &SurfaceKind, c: &Calibration| {
            let reach = run_reach(&CALIBRATED_DOMAIN, kind, &sliding, 0.25);
            load_estimate(samples, &material, 1e-3, (0.25, 0.25), 0.0625, c, &reach)
        };
        let (r, w) = estimate(&inside, &paper, &CALIBRATION);
        assert!(
            r.iter()
                .all(|r| r.wear_rate_low.is_some() && r.interval_withheld.is_none()),
            "{r:?} {w:?}"
        );
        // Measured surfaces: every 𝒢 loses its interval, the point value stays, the warning says so.
        let (r, w) = estimate(&inside, &measured, &CALIBRATION);
        for r in &r {
            assert!(r.wear_rate.is_some() && r.wear_coefficient.is_some() && r.particle_rate.is_some());
            assert_eq!((r.wear_rate_low, r.wear_rate_high), (None, None));
            assert_eq!((r.wear_coefficient_low, r.particle_rate_high), (None, None));
            assert_eq!(
                r.interval_withheld.as_deref(),
                Some("outside the calibrated domain: surfaces not of the calibrated spectrum")
            );
        }
        assert!(w.iter().any(|w| w.contains("given without an interval")), "{w:?}");
        // N* above the range for the first 𝒢 only: that one loses its interval, the other keeps it.
        let (r, _) = estimate(&vec![sample2(0.03, [200, 4]); 4], &paper, &CALIBRATION);
        assert_eq!(
            r[0].interval_withheld.as_deref(),
            Some("outside the calibrated domain: N* = 200.0 per map")
        );
        assert!(r[1].interval_withheld.is_none() && r[1].wear_rate_low.is_some());
        // Rare critical junctions, one per map (below the calibrated 3): no interval either.
        let (r, _) = estimate(&vec![sample2(0.03, [10, 1]); 4], &paper, &CALIBRATION);
        assert_eq!(
            r[1].interval_withheld.as_deref(),
            Some("outside the calibrated domain: N* = 1.0 per map")
        );
        assert!(r[0].interval_withheld.is_none());
        // A contact fraction outside the range concerns every 𝒢, with the surfaces' reason beside it.
        let (r, _) = estimate(&vec![sample2(0.2, [10, 4]); 4], &measured, &CALIBRATION);
        assert_eq!(
            r[1].interval_withheld.as_deref(),
            Some("outside the calibrated domain: surfaces not of the calibrated spectrum; contact fraction 20.00 %")
        );
        // Constants of one's own keep their interval: their reach is the runs they were fitted on.
        let own = Calibration {
            residence_factor: 2.0,
            ..CALIBRATION
        };
        let (r, _) = estimate(&inside, &measured, &own);
        assert!(r
            .iter()
            .all(|r| r.wear_rate_low.is_some() && r.interval_withheld.is_none()));
        // No critical junction: nothing to withhold.
        let (r, _) = estimate(&vec![sample2(0.03, [0, 0]); 4], &measured, &CALIBRATION);
        assert!(r.iter().all(|r| r.wear_rate.is_none() && r.interval_withheld.is_none()));
    }

    #[test]
    fn the_interval_starts_at_zero_where_a_run_likely_forms_no_particle() {
        let material = Material::new(1.0, 0.3, 0.010, vec![0.25e-6], 3.0).unwrap();
        let d = material.critical_diameters()[0];
        let samples = vec![sample(0.03, 1, 1.2 * d); 4];
        // A short fit window: μ well under ln 40, so P(N = 0) > 2.5 %.
        let (r, w) = results_of(&samples, &material, 1e-6, (0.03125, 0.03125), 1e-3, &CALIBRATION);
        let mu = r[0].expected_particles.unwrap();
        assert!(mu < 40f64.ln(), "{mu}");
        assert_eq!(r[0].wear_rate_low, Some(0.0));
        assert_eq!(r[0].particle_rate_low, Some(0.0));
        assert_eq!(r[0].wear_coefficient_low, Some(0.0));
        assert!(r[0].wear_rate_high.unwrap() > r[0].wear_rate.unwrap());
        assert!(w.iter().any(|w| w.contains("none at all with probability")), "{w:?}");
        // A long one: many particles, the lower end above 0.
        let (r, _) = results_of(&samples, &material, 1e-6, (0.03125, 0.03125), 10.0, &CALIBRATION);
        assert!(r[0].expected_particles.unwrap() > 40f64.ln());
        assert!(r[0].wear_rate_low.unwrap() > 0.0);
        assert!(zero_allowed(3.68) && !zero_allowed(3.70));
    }

    #[test]
    fn the_number_of_static_maps_is_checked() {
        assert!(Sampling::of(Some(0)).is_err());
        assert_eq!(Sampling::of(None).unwrap(), Sampling::Auto);
    }
}
