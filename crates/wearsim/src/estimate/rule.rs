//! The rule: N* and d̄ from the static maps, the residence R = c₁ d̄ (1 + c₂ θ), the rates and
//! their 95 % interval (the rule's spread, the sampling error of N*, the Poisson noise of a run).

use crate::material::Material;

use super::calibration::Calibration;
use crate::junctions::particle_volume;
use crate::sliding::WearResult;
use crate::wear::box_wrapping_warning;

use super::samples::{Sample, SampleCount, RESOLVED_CRITICAL_JUNCTIONS, TARGET_SAMPLING_ERROR, Z95};

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
    /// the calibrated domain (`load_estimate`); absent where the interval is given (or W is
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
pub(super) fn critical_stats(samples: &[Sample], e: usize) -> (f64, Option<f64>) {
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
