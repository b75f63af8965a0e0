//! The static maps of an estimate: how many, at which offsets, and what each counts.

use crate::error::{Error, Result};

/// Fewest static maps of an estimate with samples chosen automatically.
pub const MIN_SAMPLES: usize = 4;
/// Most static maps of an estimate (the slots of the offset sequence).
pub const MAX_SAMPLES: usize = 16;
/// With samples chosen automatically, maps are added until the sampling error of N* that each
/// result reports (`sampling_error`: the standard error between maps, at least the Poisson error of
/// the junctions counted) is at most this for every load and 𝒢 with N* ≥
/// [`RESOLVED_CRITICAL_JUNCTIONS`], or [`MAX_SAMPLES`] are taken (then a warning says so): small
/// beside the rule's own spread about the sliding runs.
pub const TARGET_SAMPLING_ERROR: f64 = 0.10;
/// Below this mean number of critical junctions per map, N* is a count of a few junctions and the
/// estimate is flagged as under-resolved.
pub const RESOLVED_CRITICAL_JUNCTIONS: f64 = 2.0;
/// Two-sided 95 % quantile of the normal distribution, for the intervals in ln.
pub(super) const Z95: f64 = 1.959_963_984_540_054;

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
