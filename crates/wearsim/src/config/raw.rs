//! The run file as written: the TOML tables parsed strictly (unknown keys are errors naming the
//! key), before any value is checked.

use std::path::PathBuf;

use serde::Deserialize;

use crate::contact::{Device, Stopping};
use crate::influence::Boundary;
use crate::material::ModulusConvention;
use crate::model::WearModel;
use crate::surface::Generation;
use crate::topography::{Detrend, Window};

/// Unit system of a run file: reduced (E = 1, L = 1 by convention) or SI (Pa, m, J/m², N).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Units {
    #[default]
    Reduced,
    Si,
}

impl Units {
    /// Name of the length unit.
    pub fn length_unit(self) -> &'static str {
        match self {
            Units::Reduced => "L",
            Units::Si => "m",
        }
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawRun {
    #[serde(default)]
    pub(super) units: Units,
    pub(super) surface: RawSurface,
    pub(super) material: RawMaterial,
    #[serde(default)]
    pub(super) contact: RawContact,
    pub(super) sliding: Option<RawSliding>,
}

/// A value per side: one for both (`grid = 512`) or `[x, y]` (`grid = [1024, 512]`).
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(untagged, expecting = "one number, or two as [along x, along y]")]
pub(super) enum PerSide<T> {
    Both(T),
    Each([T; 2]),
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSurface {
    pub(super) grid: Option<PerSide<usize>>,
    pub(super) length: Option<PerSide<f64>>,
    pub(super) hurst: Option<f64>,
    pub(super) lambda_lower: Option<f64>,
    pub(super) lambda_upper: Option<f64>,
    pub(super) rms_height: Option<f64>,
    pub(super) seed: Option<u64>,
    pub(super) generation: Option<Generation>,
    pub(super) top: Option<PathBuf>,
    pub(super) bottom: Option<PathBuf>,
    pub(super) height_unit: Option<String>,
    pub(super) lateral_unit: Option<String>,
    pub(super) detrend: Option<Detrend>,
    pub(super) taper: Option<f64>,
    /// Where the surfaces come from when the keys do not say it alone: "spectrum" (generated from
    /// the measured PSD of `map`); "generated" and "files" are what the other keys say.
    pub(super) source: Option<String>,
    pub(super) map: Option<PathBuf>,
    pub(super) map_length: Option<f64>,
    pub(super) window: Option<Window>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawMaterial {
    pub(super) youngs_modulus: f64,
    pub(super) poisson_ratio: f64,
    /// τ̃, or one of its alternatives: `hardness` H (τ̃ = H/(3√3)) or `yield_strength` σ_y
    /// (τ̃ = σ_y/√3).
    pub(super) shear_strength: Option<f64>,
    pub(super) hardness: Option<f64>,
    pub(super) yield_strength: Option<f64>,
    /// 𝒢, or the alternative `fracture_toughness` K_Ic (𝒢 = K_Ic²(1 − ν²)/E).
    pub(super) fracture_energies: Option<Vec<f64>>,
    pub(super) fracture_toughness: Option<Vec<f64>>,
    pub(super) geometry_factor: Option<f64>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawContact {
    pub(super) modulus: Option<ModulusConvention>,
    pub(super) tolerance: Option<f64>,
    pub(super) max_iterations: Option<usize>,
    pub(super) connectivity: Option<u8>,
    pub(super) boundary: Option<Boundary>,
    pub(super) device: Option<Device>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSliding {
    /// The normal loads F_N, or the alternative `pressures`, nominal pressures p_N = F_N/(Lx·Ly).
    pub(super) loads: Option<Vec<f64>>,
    pub(super) pressures: Option<Vec<f64>>,
    pub(super) distance: Option<f64>,
    pub(super) running_in: Option<f64>,
    pub(super) step_running_in: Option<usize>,
    pub(super) step: Option<usize>,
    pub(super) particle_rule: Option<RawParticleRule>,
    pub(super) stopping: Option<Stopping>,
    pub(super) model: Option<WearModel>,
    pub(super) estimate_samples: Option<usize>,
    pub(super) estimate_constants: Option<RawConstants>,
}

/// `[sliding] particle_rule`: a rule's name (`"overlap"`, or `"interacting(reach=2)"` with
/// parameters), or a `[sliding.particle_rule]` table with `name` and the rule's parameters.
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub(super) enum RawParticleRule {
    Named(String),
    Table(toml::Table),
}

/// `[sliding] estimate_constants`: the static estimate's constants, as `wearsim estimate-check
/// --fit` prints them.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawConstants {
    pub(super) residence_factor: f64,
    pub(super) merging_factor: f64,
    pub(super) volume_factor: f64,
    pub(super) rate_spread: f64,
    pub(super) wear_spread: f64,
}

/// A TOML error message on one line (they come with a source excerpt over several lines).
pub(super) fn one_line(message: &str) -> String {
    message.trim_end().replace('\n', " ")
}
