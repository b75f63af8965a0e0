//! What the calibration covered ([`CALIBRATED_DOMAIN`]) and where a run or a load lies outside it.

use crate::material::Material;

use super::calibration::{Calibration, CALIBRATION};
use super::rule::{critical_stats, results_of, EstimateResult};
use super::samples::Sample;

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
/// each fracture energy (any N* > 0 outside the range: below [`RESOLVED_CRITICAL_JUNCTIONS`](super::samples::RESOLVED_CRITICAL_JUNCTIONS) the
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
