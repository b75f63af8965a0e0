//! The documents of one run or command: the series and summary of a sliding run, the summary of one
//! contact solve, surface statistics and fits, junction tables.

use serde::Serialize;
use serde_json::{json, Value};

use crate::config::{RunConfig, SurfaceSource, Units};
use crate::contact::{Device, SolveInfo, SolverOptions};
use crate::estimate::{Calibration, EstimateResult, LoadEstimate};
use crate::influence::Boundary;
use crate::material::{Material, ModulusConvention};
use crate::model::WearModel;
use crate::sliding::{LoadRun, SlidingConfig, WearResult};
use crate::surface::Surface;

use super::provenance::Provenance;
use super::series::{series_rows, SeriesRow};
use super::tables::{columns, Table};
use super::units::{unit_of, units_map};

/// `series.csv` of a sliding run: plain CSV for pandas and R; units and provenance are in the
/// summary beside it.
pub fn series_csv(runs: &[LoadRun]) -> String {
    Table::of(&series_rows(runs)).to_csv()
}

/// What a sliding run was given, for its summary.
pub struct SlidingInputs<'a> {
    pub units: Units,
    /// Where the surfaces came from (a run file's [`SurfaceSource`], or a description of arrays
    /// handed over by the caller).
    pub surfaces: Value,
    pub material: &'a Material,
    pub modulus: ModulusConvention,
    pub solver: SolverOptions,
    pub connectivity: u8,
    /// Where the contact solver computed.
    pub device: Device,
    pub sliding: &'a SlidingConfig,
    /// The run file's values given in another form than the model's inputs, each with its
    /// conversion ([`RunSettings::conversions`](crate::config::RunSettings::conversions)).
    pub conversions: &'a [String],
}

impl<'a> SlidingInputs<'a> {
    /// The inputs of a run (from a file, or built in memory) with a sliding schedule.
    pub fn of_run(config: &'a RunConfig, sliding: &'a SlidingConfig) -> Self {
        Self {
            units: config.units,
            surfaces: surface_source(&config.surfaces),
            material: &config.material,
            modulus: config.modulus,
            solver: config.solver.with_stopping(config.stopping),
            connectivity: config.connectivity,
            device: config.device,
            sliding,
            conversions: &config.conversions,
        }
    }

    /// The `inputs` block of the run's outputs (summary.json, the fields store).
    pub fn to_json(&self) -> Value {
        let mut inputs = json!({
            "surfaces": self.surfaces,
            "material": self.material,
            "contact": contact_inputs(self.modulus, self.solver, self.connectivity, self.device),
            "sliding": self.sliding,
        });
        if !self.conversions.is_empty() {
            inputs["conversions"] = json!(self.conversions);
        }
        inputs
    }
}

fn surface_source(source: &SurfaceSource) -> Value {
    serde_json::to_value(source).expect("plain data serialises")
}

/// The contact settings of a run as they appear in its outputs, the device the solver computed on
/// included.
fn contact_inputs(modulus: ModulusConvention, solver: SolverOptions, connectivity: u8, device: Device) -> Value {
    json!({
        "modulus": modulus.name(),
        "tolerance": solver.tolerance(),
        "stopping": solver.stopping().name(),
        "max_iterations": solver.max_iterations(),
        "connectivity": connectivity,
        "device": device.name(),
    })
}

/// How the residual is defined, as written into every output that reports one.
pub const RESIDUAL_DEFINITION: &str = "max over pixels of the violation of the optimality conditions (|g+c| on \
free, max(0,-(g+c)) on non-contact, max(0,g+c) on plastic pixels) divided by std(h)";

/// What the summary of every run starts with, slid or estimated: provenance, units, inputs, p_m,
/// d* per 𝒢 and E* with its convention.
fn run_header(inputs: &SlidingInputs) -> serde_json::Map<String, Value> {
    let m = inputs.material;
    fields(json!({
        "provenance": Provenance::current(),
        "units": inputs.units,
        "inputs": inputs.to_json(),
        "flow_pressure": m.flow_pressure(),
        "critical_diameter": m.fracture_energies.iter().zip(m.critical_diameters()).map(|(g, d)| json!({"fracture_energy": g, "critical_diameter": d})).collect::<Vec<_>>(),
        "effective_modulus": m.effective_modulus(inputs.modulus),
        "modulus_convention": inputs.modulus.name(),
    }))
}

/// The fields of a JSON object (`json!` of `{…}` is one).
fn fields(value: Value) -> serde_json::Map<String, Value> {
    match value {
        Value::Object(map) => map,
        _ => unreachable!("json!({{…}}) makes an object"),
    }
}

/// `summary.json` of a sliding run: provenance, inputs, derived quantities, solver statistics and
/// the results per load and fracture energy, with the conventions they follow, and `warnings`, every
/// warning of the run (its inputs, its surfaces, d* against the pixel size, each load's results).
pub fn sliding_summary(
    inputs: &SlidingInputs,
    runs: &[LoadRun],
    warnings: &[String],
    seconds: f64,
    steps_per_load: usize,
) -> Value {
    let results: Vec<Value> = runs
        .iter()
        .flat_map(|r| {
            r.results.iter().map(move |w| {
                let mut v = serde_json::to_value(w).expect("plain numbers serialise");
                let object = v.as_object_mut().expect("a struct serialises to an object");
                object.insert("load".into(), json!(r.load));
                object.insert(
                    "specific_wear_rate".into(),
                    json!(w
                        .wear_rate
                        .map(|rate| super::units::specific_wear_rate(inputs.units, rate, r.load))),
                );
                v
            })
        })
        .collect();
    let solver: Vec<Value> = runs
        .iter()
        .map(|r| {
            json!({
                "load": r.load,
                "total_iterations": r.total_iterations,
                "max_iterations": r.max_iterations,
                "mean_iterations": r.total_iterations as f64 / r.steps.len() as f64,
                "max_residual": r.steps.iter().map(|s| s.residual).fold(0.0, f64::max),
                "seconds": {"solve": r.timing.solve, "labelling": r.timing.labelling, "bookkeeping": r.timing.bookkeeping},
            })
        })
        .collect();
    // Which model made it, as an estimate's summary says too.
    let mut summary = fields(json!({"model": WearModel::Sliding.name()}));
    summary.extend(run_header(inputs));
    summary.extend(fields(json!({
        "solver": {"tolerance": inputs.solver.tolerance(), "stopping": inputs.solver.stopping().name(), "residual_definition": RESIDUAL_DEFINITION, "per_load": solver},
        "steps_per_load": steps_per_load,
        "fit": "least-squares lines of V and N*₊ against s over the steps with s ≥ running_in·L",
        "static_wear_rate_convention": "W_static/ω = k_static Σ A_i; static_wear_coefficient and static_wear_rate at s = 0, *_mean and *_std over every offset of the run",
        "wear_rate_estimate_convention": "ω d*³ dN*₊/ds with ω = π/6",
        "memory_convention": "initial_junctions: junctions descending by step-to-step pixel overlap from a junction present at s = 0; memory_decay_length ℓ from a least-squares fit of ln N₀ = ln N₀(0) − s/ℓ; running_in_decay_lengths = s_r/ℓ at the start s_r of the fit window; initial_lineages_left = N₀(s_r)/N₀(0), counted; a run counts as run in with at most 5 % of the lineages left (where N₀(0) = 0, from s_r/ℓ ≥ 3)",
        "breakdown_convention": crate::sliding::breakdown_convention(),
        "results": results,
        "units_of_results": units_map(inputs.units, columns::<WearResult>().iter().map(String::as_str).chain(["load", "specific_wear_rate", "flow_pressure", "effective_modulus"])),
        "units_of_series": units_map(inputs.units, columns::<SeriesRow>().iter().map(String::as_str)),
        "warnings": warnings,
        "seconds": seconds,
    })));
    Value::Object(summary)
}

/// One row of an estimate's `results.csv`: a load and the estimate of one fracture energy.
#[derive(Debug, Clone, Default, Serialize)]
pub struct EstimateRow {
    pub load: f64,
    #[serde(flatten)]
    pub result: EstimateResult,
    /// The specific wear rate K = W/F_N of the estimate's W.
    pub specific_wear_rate: Option<f64>,
}

/// The rows of an estimate's `results.csv`, load by load, in a run of `units`.
pub fn estimate_rows(loads: &[LoadEstimate], units: Units) -> Vec<EstimateRow> {
    loads
        .iter()
        .flat_map(|l| {
            l.results.iter().map(move |r| EstimateRow {
                load: l.load,
                result: r.clone(),
                specific_wear_rate: r
                    .wear_rate
                    .map(|rate| super::units::specific_wear_rate(units, rate, l.load)),
            })
        })
        .collect()
}

/// What an estimate is, as every document of one says it.
pub const ESTIMATE_NOTICE: &str = "static estimate, not a sliding run: dN*₊/ds = N*/R with N* and the critical \
junctions' mean diameter d̄ from static contact maps at spread offsets, the residence R = c₁ d̄ (1 + c₂ θ), θ = N* d̄²/(Lx Ly), \
W = c_v (π/6) d*³ dN*₊/ds, k = W p_m/F_N; constants calibrated on sliding runs (see `calibration`)";

/// `summary.json` of an estimate: marked as one (`model`, `notice`), with the calibration used,
/// the static maps taken and the results per load and fracture energy with their 95 % intervals.
pub fn estimate_summary(
    inputs: &SlidingInputs,
    loads: &[LoadEstimate],
    calibration: &Calibration,
    warnings: &[String],
    seconds: f64,
) -> Value {
    let results: Vec<Value> = estimate_rows(loads, inputs.units)
        .iter()
        .map(|r| serde_json::to_value(r).expect("plain numbers serialise"))
        .collect();
    let samples: Vec<Value> = loads
        .iter()
        .map(|l| json!({"load": l.load, "maps": l.samples}))
        .collect();
    let mut summary = fields(json!({
        "model": WearModel::Estimate.name(),
        "notice": ESTIMATE_NOTICE,
    }));
    summary.extend(run_header(inputs));
    summary.extend(fields(json!({
        "calibration": calibration,
        "interval_convention": "95 % interval of the value a sliding run of this box and sliding distance would give: \
            exp(±1.96 σ) about the estimate, σ² = the rule's spread² (calibration) + the relative sampling error of N*² + \
            1/expected_particles (the run's Poisson noise); the lower end is 0 where such a run forms no particle \
            with probability exp(−expected_particles) ≥ 2.5 % (the lower 2.5 % quantile of its Poisson count is 0)",
        "static_maps": loads.first().map_or(0, |l| l.samples.len()),
        "results": results,
        "maps": samples,
        "units_of_results": units_map(inputs.units, columns::<EstimateRow>().iter().map(String::as_str).chain(["flow_pressure", "effective_modulus"])),
        "warnings": warnings,
        "seconds": seconds,
    })));
    Value::Object(summary)
}

/// What one contact solve reports: the numbers of `wearsim contact`'s summary and of the Python
/// `ContactResult`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ContactRecord {
    /// Real contact area as a fraction of the apparent area Lx·Ly.
    pub contact_area: f64,
    pub contact_pixels: usize,
    pub plastic_pixels: usize,
    /// Mean pressure of the solution, F_N/(Lx·Ly) to round-off.
    pub mean_pressure: f64,
    /// Rigid-body approach since first contact (length unit).
    pub approach: f64,
    pub iterations: usize,
    pub convolutions: usize,
    pub residual: f64,
    pub tolerance: f64,
    pub seconds: f64,
}

impl ContactRecord {
    /// The record of a solve that produced `pressure`.
    pub fn new(info: &SolveInfo, pressure: &[f64], seconds: f64) -> Self {
        let pixels = pressure.len().max(1) as f64;
        Self {
            contact_area: info.contact_pixels as f64 / pixels,
            contact_pixels: info.contact_pixels,
            plastic_pixels: info.plastic_pixels,
            mean_pressure: pressure.iter().sum::<f64>() / pixels,
            approach: info.approach,
            iterations: info.iterations,
            convolutions: info.convolutions,
            residual: info.residual,
            tolerance: info.tolerance,
            seconds,
        }
    }
}

/// How the gap written by `wearsim contact` (and returned by Python's `contact`) is defined.
pub const GAP_DEFINITION: &str = "g = Kp - h + delta, the separation of the rigid surface h and the deformed \
half-space (Kp: displacement.npy; delta = max(h) - approach, the rigid body's position): 0 on contact pixels below \
the flow pressure, >= 0 outside the contact, <= 0 (interpenetration taken up by plastic flow) at p = p_m, each to \
within residual * std(h)";

/// The fields `wearsim contact` writes, each with its unit and meaning, for its summary.
fn contact_fields(units: Units, boundary: Boundary) -> Value {
    let displacement = match boundary {
        Boundary::Periodic => "surface displacement u = Kp of the periodic half-space (zero mean)",
        Boundary::Free => "surface displacement u = Kp of the half-space, zero far from the map",
    };
    json!({
        "pressure.npy": {"unit": unit_of(units, "pressure"), "definition": "contact pressure p, exactly 0 outside the contact"},
        "contact.npy": {"unit": "", "definition": "contact map, p > 0"},
        "displacement.npy": {"unit": unit_of(units, "displacement"), "definition": displacement},
        "gap.npy": {"unit": unit_of(units, "gap"), "definition": GAP_DEFINITION},
    })
}

/// `summary.json` of `wearsim contact`: provenance, the solve's record, the load and offset, the
/// boundary condition, the fields written with their units, and the run's inputs and derived
/// quantities.
pub fn contact_summary(
    config: &RunConfig,
    load: f64,
    offset: f64,
    offset_pixels: usize,
    boundary: Boundary,
    record: &ContactRecord,
) -> Value {
    let mut doc = json!({
        "provenance": Provenance::current(),
        "units": config.units,
        "load": load,
        "offset": offset,
        "offset_pixels": offset_pixels,
        "boundary": boundary.name(),
        "fields": contact_fields(config.units, boundary),
    });
    let object = doc.as_object_mut().expect("an object");
    if let Value::Object(fields) = serde_json::to_value(record).expect("plain numbers serialise") {
        object.extend(fields);
    }
    object.extend([
        ("residual_definition".to_string(), json!(RESIDUAL_DEFINITION)),
        ("effective_modulus".to_string(), json!(config.effective_modulus())),
        ("modulus_convention".to_string(), json!(config.modulus.name())),
        ("flow_pressure".to_string(), json!(config.material.flow_pressure())),
        (
            "critical_diameters".to_string(),
            json!(config.material.critical_diameters()),
        ),
        ("material".to_string(), json!(config.material)),
        ("surfaces".to_string(), surface_source(&config.surfaces)),
        (
            "contact".to_string(),
            contact_inputs(config.modulus, config.solver, config.connectivity, config.device),
        ),
    ]);
    doc
}

/// Statistics of one surface, as `wearsim surface` writes them and Python's `surface_statistics`
/// returns them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SurfaceStatistics {
    /// Pixels along x (the sliding direction) and along y.
    pub grid: usize,
    pub grid_y: usize,
    /// Sides along x and y.
    pub length: f64,
    pub length_y: f64,
    pub pixel_size: f64,
    pub rms_height: f64,
    pub rms_slope: f64,
    /// Radially averaged PSD as (q, C(q)) pairs (see [`PSD_CONVENTION`]).
    pub psd: Vec<[f64; 2]>,
}

/// How the radially averaged PSD is defined.
pub const PSD_CONVENTION: &str = "psd[q] = mean over the shell |q| ∈ [m−½, m+½) of |ĥ(q)|²/(Nx·Ny)² (variance \
per Fourier mode, length²); q in units of 2π/Lx";

impl SurfaceStatistics {
    /// The statistics of `s`.
    pub fn of(s: &Surface) -> Self {
        Self {
            grid: s.nx(),
            grid_y: s.ny(),
            length: s.length(),
            length_y: s.grid().length_y(),
            pixel_size: s.pixel_size(),
            rms_height: s.rms_height(),
            rms_slope: s.rms_slope(),
            psd: s.radial_psd().iter().map(|(q, c)| [*q, *c]).collect(),
        }
    }
}

/// `statistics.json` of `wearsim surface`.
pub fn surface_summary(config: &RunConfig, top: &SurfaceStatistics, bottom: &SurfaceStatistics) -> Value {
    json!({
        "provenance": Provenance::current(),
        "units": config.units,
        "surfaces": surface_source(&config.surfaces),
        "psd_convention": PSD_CONVENTION,
        "top": top,
        "bottom": bottom,
    })
}

/// `fit.json` of `wearsim surface fit`: the file, how it was prepared, the fitted parameters, the
/// spectrum a run would generate from them, what was adjusted on the way and what the band leaves
/// out (`notes`), and where the native pixels of a resampled map came from (`measured_pixel_from`:
/// `--measured-pixel` or the import.json beside the map; null when the whole stored spectrum was
/// measured).
#[allow(clippy::too_many_arguments)] // the parts of fit.json, one each
pub fn surface_fit_summary(
    file: &std::path::Path,
    preprocess: &crate::topography::Preprocess,
    length_unit: &str,
    grid: &crate::grid::Grid,
    fit: Option<(&crate::topography::SpectrumFit, &crate::surface::SpectrumParams)>,
    verdict: &crate::topography::Verdict,
    notes: &[String],
    rms_slope: Option<&crate::topography::SlopeComparison>,
    measured_pixel_from: Option<&str>,
) -> Value {
    let (fit, spectrum) = fit.unzip();
    json!({
        "provenance": Provenance::current(),
        "file": file,
        "detrend": preprocess.detrend.name(),
        "taper": preprocess.taper,
        "length_unit": length_unit,
        "grid": [grid.nx(), grid.ny()],
        "length": [grid.length_x(), grid.length_y()],
        "fit": fit,
        "spectrum": spectrum,
        "self_affine": verdict.self_affine,
        "reasons": verdict.reasons,
        "notes": notes,
        "rms_slope": rms_slope,
        "measured_pixel_from": measured_pixel_from,
        "method": crate::topography::FIT_METHOD,
    })
}

/// `junctions.json` of `wearsim junctions`: pixel count per junction.
pub fn junctions_summary(connectivity: u8, pixels: &[usize]) -> Value {
    json!({
        "provenance": Provenance::current(),
        "connectivity": connectivity,
        "junctions": pixels.len(),
        "pixels": pixels,
    })
}
