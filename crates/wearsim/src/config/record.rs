//! Every input of a run as one flat record: the input columns of a study's tables.

use serde::Deserialize;

use crate::contact::{Device, Stopping};
use crate::material::ModulusConvention;
use crate::model::WearModel;
use crate::surface::Generation;

use super::raw::Units;

/// Every input of a run as one flat record with the same fields for every run (absent ones empty):
/// the input columns of a study's results table, and what identifies a study job in its job file.
/// Field names are the run file's `section.key`.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, Deserialize)]
pub struct InputRecord {
    pub units: Units,
    #[serde(rename = "surface.grid")]
    pub grid: Option<usize>,
    /// Pixels along y, on rectangular grids only (square runs leave it empty).
    #[serde(rename = "surface.grid_y", default)]
    pub grid_y: Option<usize>,
    #[serde(rename = "surface.length")]
    pub length: f64,
    /// Side along y, on rectangular grids only.
    #[serde(rename = "surface.length_y", default)]
    pub length_y: Option<f64>,
    #[serde(rename = "surface.hurst")]
    pub hurst: Option<f64>,
    #[serde(rename = "surface.lambda_lower")]
    pub lambda_lower: Option<f64>,
    #[serde(rename = "surface.lambda_upper")]
    pub lambda_upper: Option<f64>,
    #[serde(rename = "surface.rms_height")]
    pub rms_height: Option<f64>,
    #[serde(rename = "surface.seed")]
    pub seed: Option<u64>,
    #[serde(rename = "surface.top")]
    pub top: Option<String>,
    #[serde(rename = "surface.bottom")]
    pub bottom: Option<String>,
    #[serde(rename = "surface.height_unit", default)]
    pub height_unit: Option<String>,
    #[serde(rename = "surface.detrend", default)]
    pub detrend: Option<String>,
    #[serde(rename = "surface.taper", default)]
    pub taper: Option<f64>,
    /// How generated heights are drawn, when not the default (random phases); absent in job files
    /// written before it was recorded.
    #[serde(rename = "surface.generation", default)]
    pub generation: Option<Generation>,
    /// Unit of a column file's x y coordinates, when given.
    #[serde(rename = "surface.lateral_unit", default)]
    pub lateral_unit: Option<String>,
    /// "spectrum" for surfaces generated from a measured map's PSD; empty otherwise.
    #[serde(rename = "surface.source", default)]
    pub source: Option<String>,
    /// The measured map of a `source = "spectrum"` run.
    #[serde(rename = "surface.map", default)]
    pub map: Option<String>,
    #[serde(rename = "surface.map_length", default)]
    pub map_length: Option<f64>,
    #[serde(rename = "surface.window", default)]
    pub window: Option<crate::topography::Window>,
    #[serde(rename = "material.youngs_modulus")]
    pub youngs_modulus: f64,
    #[serde(rename = "material.poisson_ratio")]
    pub poisson_ratio: f64,
    #[serde(rename = "material.shear_strength")]
    pub shear_strength: f64,
    #[serde(rename = "material.geometry_factor")]
    pub geometry_factor: f64,
    #[serde(rename = "contact.modulus")]
    pub modulus: ModulusConvention,
    #[serde(rename = "contact.tolerance")]
    pub tolerance: f64,
    /// The solver's iteration limit, when not the default.
    #[serde(rename = "contact.max_iterations", default)]
    pub max_iterations: Option<usize>,
    #[serde(rename = "contact.connectivity")]
    pub connectivity: u8,
    /// Where the contact solver computed, when not the CPU.
    #[serde(rename = "contact.device", default)]
    pub device: Option<Device>,
    #[serde(rename = "sliding.distance")]
    pub distance: Option<f64>,
    #[serde(rename = "sliding.running_in")]
    pub running_in: Option<f64>,
    #[serde(rename = "sliding.step_running_in")]
    pub step_running_in: Option<usize>,
    #[serde(rename = "sliding.step")]
    pub step: Option<usize>,
    /// The particle rule, when not the paper's; absent in job files written before it was recorded.
    #[serde(rename = "sliding.particle_rule", default)]
    pub particle_rule: Option<String>,
    /// When each step's contact solve stopped, when not the default (the contact map settled);
    /// absent in job files written before it was recorded, whose runs stopped at the tolerance and
    /// whose wear results the settled map reproduces.
    #[serde(rename = "sliding.stopping", default)]
    pub stopping: Option<Stopping>,
    /// The wear model, when not the sliding simulation (`estimate`: the static estimate).
    #[serde(rename = "sliding.model", default)]
    pub model: Option<WearModel>,
    /// The static maps of an estimate, when fixed in the run file.
    #[serde(rename = "sliding.estimate_samples", default)]
    pub estimate_samples: Option<usize>,
    /// The static estimate's constants, when the run file gives its own (c₁, c₂, c_v, rate and wear
    /// spread).
    #[serde(rename = "sliding.estimate_constants", default)]
    pub estimate_constants: Option<String>,
}

impl InputRecord {
    /// The nominal pressure p_N = F_N/(Lx·Ly) under a normal load F_N: the load axis of the paper's
    /// figures.
    pub fn nominal_pressure(&self, load: f64) -> f64 {
        load / self.nominal_area()
    }

    /// The nominal area Lx·Ly of the box: what rates are divided by to compare boxes (per unit
    /// nominal area; in reduced units, a box L × L is the paper's).
    pub fn nominal_area(&self) -> f64 {
        self.length * self.length_y.unwrap_or(self.length)
    }
}
