//! Every result document wearsim writes, built in one place: the provenance block they share, the
//! summary and series of a sliding run, the summary of one contact solve, surface statistics,
//! junction tables, study job files and the tidy results tables. Front ends (the CLI, the Python
//! bindings) call these and only choose where the files go.
//!
//! Tables are derived from one typed row each ([`SeriesRow`], [`TidyRow`]): their columns are the
//! rows' serde fields in order, so a column list is never kept by hand. Numbers are written in
//! Rust's shortest round-trip form (`{:e}` for floats); an undefined value (NaN, a missing input) is
//! an empty cell.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};
use serde_json::{json, Value};

use crate::config::{InputRecord, RunConfig, SlidingConfig, SurfaceSource, Units};
use crate::contact::{SolveInfo, SolverOptions};
use crate::error::{Error, Result};
use crate::material::{Material, ModulusConvention};
use crate::sliding::{LoadRun, StepRecord, WearResult};
use crate::surface::Surface;

/// Where a result came from: software version, the command line of the process that wrote it, and
/// the date (UTC, RFC 3339).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Provenance {
    pub software: String,
    pub command: String,
    pub date: String,
}

impl Provenance {
    /// This process, now.
    pub fn current() -> Self {
        let command = std::env::args_os()
            .map(|a| {
                let a = a.to_string_lossy().to_string();
                if a.is_empty() || a.contains(char::is_whitespace) {
                    format!("'{a}'")
                } else {
                    a
                }
            })
            .collect::<Vec<_>>()
            .join(" ");
        Self {
            software: format!("wearsim {}", crate::VERSION),
            command,
            date: humantime::format_rfc3339_seconds(std::time::SystemTime::now()).to_string(),
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Units

/// The unit of a quantity (a result field, a series or table column, an input) in a unit system:
/// reduced units are multiples of E and L; SI units are Pa, m, N and J/m². Dimensionless numbers and
/// counts have "" (counts) or "1" (ratios). Column suffixes `_mean`, `_std`, `_min`, `_max` and the
/// `surface.`/`material.`/`contact.` prefixes are looked through.
pub fn unit_of(units: Units, quantity: &str) -> &'static str {
    let mut q = quantity.rsplit('.').next().unwrap_or(quantity);
    for suffix in ["_mean", "_std", "_min", "_max"] {
        q = q.strip_suffix(suffix).unwrap_or(q);
    }
    let si = units == Units::Si;
    let pick = |reduced: &'static str, si_unit: &'static str| if si { si_unit } else { reduced };
    match q {
        "load" => pick("E L²", "N"),
        "fracture_energy" | "fracture_energies" => pick("E L", "J/m²"),
        "flow_pressure" | "effective_modulus" | "youngs_modulus" | "shear_strength" | "mean_pressure" => {
            pick("E", "Pa")
        }
        "critical_diameter"
        | "s"
        | "length"
        | "lambda_lower"
        | "lambda_upper"
        | "rms_height"
        | "approach"
        | "memory_decay_length"
        | "pixel_size" => pick("L", "m"),
        "wear_rate" | "wear_rate_estimate" | "static_wear_rate" => pick("L²", "m²"),
        "volume" | "initial_volume" => pick("L³", "m³"),
        "particle_rate" => pick("1/L", "1/m"),
        "contact_area" => "1 (fraction of L²)",
        "wear_coefficient"
        | "static_wear_coefficient"
        | "wear_rate_r2"
        | "memory_decay_r2"
        | "poisson_ratio"
        | "geometry_factor"
        | "hurst"
        | "tolerance"
        | "residual" => "1",
        _ => "",
    }
}

/// The units of the given columns (those with one), for a table's companion file or a summary.
pub fn units_map<'a>(units: Units, columns: impl IntoIterator<Item = &'a str>) -> BTreeMap<String, String> {
    columns
        .into_iter()
        .map(|c| (c.to_string(), unit_of(units, c)))
        .filter(|(_, u)| !u.is_empty())
        .map(|(c, u)| (c, u.to_string()))
        .collect()
}

// ---------------------------------------------------------------------------------------------
// Tables

/// One cell of a table.
#[derive(Debug, Clone, PartialEq)]
pub enum Cell {
    Float(f64),
    Int(i64),
    Text(String),
    /// An undefined number (NaN) or an input that does not apply.
    Empty,
}

impl Cell {
    fn of(value: &Value) -> Cell {
        match value {
            Value::Null => Cell::Empty,
            Value::Bool(b) => Cell::Text(b.to_string()),
            Value::Number(n) => match (n.as_i64(), n.as_u64(), n.as_f64()) {
                (Some(i), _, _) => Cell::Int(i),
                (None, Some(u), _) => Cell::Int(i64::try_from(u).unwrap_or(i64::MAX)),
                (_, _, Some(f)) => Cell::Float(f),
                _ => Cell::Empty,
            },
            Value::String(s) => Cell::Text(s.clone()),
            other => Cell::Text(other.to_string()),
        }
    }

    /// The cell as CSV text.
    pub fn text(&self) -> String {
        match self {
            Cell::Float(f) if f.is_finite() => format!("{f:e}"),
            Cell::Float(_) | Cell::Empty => String::new(),
            Cell::Int(i) => i.to_string(),
            Cell::Text(s) => s.clone(),
        }
    }

    /// The cell as a number (NaN where it is not one).
    pub fn number(&self) -> f64 {
        match self {
            Cell::Float(f) => *f,
            Cell::Int(i) => *i as f64,
            _ => f64::NAN,
        }
    }
}

/// A table: named columns and rows of cells.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Table {
    pub columns: Vec<String>,
    pub rows: Vec<Vec<Cell>>,
}

/// The fields of a serialised row, in order (nested `#[serde(flatten)]` structs inline).
fn fields<T: Serialize>(row: &T) -> Vec<(String, Value)> {
    match serde_json::to_value(row).expect("result rows serialise to JSON") {
        Value::Object(map) => map.into_iter().collect(),
        other => vec![("value".into(), other)],
    }
}

/// The column names of row type `T`, from a default row.
pub fn columns<T: Serialize + Default>() -> Vec<String> {
    fields(&T::default()).into_iter().map(|(k, _)| k).collect()
}

impl Table {
    /// The table of `rows`, one column per field of `T`.
    pub fn of<T: Serialize + Default>(rows: &[T]) -> Self {
        Self {
            columns: columns::<T>(),
            rows: rows
                .iter()
                .map(|r| fields(r).iter().map(|(_, v)| Cell::of(v)).collect())
                .collect(),
        }
    }

    /// Index of a column.
    pub fn column(&self, name: &str) -> Option<usize> {
        self.columns.iter().position(|c| c == name)
    }

    /// A table read back from CSV text: empty cells are [`Cell::Empty`], whole numbers
    /// [`Cell::Int`], other numbers [`Cell::Float`], the rest text.
    pub fn from_csv(text: &str) -> std::result::Result<Self, csv::Error> {
        let mut reader = csv::Reader::from_reader(text.as_bytes());
        let columns: Vec<String> = reader.headers()?.iter().map(String::from).collect();
        let mut rows = Vec::new();
        for record in reader.records() {
            rows.push(
                record?
                    .iter()
                    .map(|t| {
                        if t.is_empty() {
                            Cell::Empty
                        } else if let Ok(i) = t.parse::<i64>() {
                            Cell::Int(i)
                        } else if let Ok(f) = t.parse::<f64>() {
                            Cell::Float(f)
                        } else {
                            Cell::Text(t.to_string())
                        }
                    })
                    .collect(),
            );
        }
        Ok(Self { columns, rows })
    }

    /// The table as CSV (RFC 4180 quoting: text with commas, quotes or newlines stays one field).
    pub fn to_csv(&self) -> String {
        let mut w = csv::Writer::from_writer(Vec::new());
        let write = |w: &mut csv::Writer<Vec<u8>>| -> csv::Result<()> {
            w.write_record(&self.columns)?;
            for row in &self.rows {
                w.write_record(row.iter().map(Cell::text))?;
            }
            w.flush()?;
            Ok(())
        };
        write(&mut w).expect("writing CSV into memory cannot fail");
        String::from_utf8(w.into_inner().expect("flushed")).expect("cells are UTF-8")
    }
}

// ---------------------------------------------------------------------------------------------
// Sliding runs

/// One row of a sliding run's series (`series.csv` of `wearsim slide`, the DataFrame of the Python
/// `slide`): one step of one load for one fracture energy. The first nine columns are the paper's
/// record per step (§3), then the memory of the initial contact and the static model at this step;
/// `iterations` and `residual` are the contact solver's.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct SeriesRow {
    /// Normal load F_N.
    pub load: f64,
    /// Fracture energy 𝒢.
    pub fracture_energy: f64,
    /// Sliding distance s in the run's length unit.
    pub s: f64,
    /// Number of junctions N.
    pub junctions: usize,
    /// Real contact area as a fraction of the apparent area L².
    pub contact_area: f64,
    /// N*: junctions with d_i ≥ d* at this step.
    pub n_critical: usize,
    /// N*₊: particles formed so far, s = 0 included.
    pub n_formed: usize,
    /// N*₋ = N*₊ − N*.
    pub n_shrunk: i64,
    /// V: wear volume so far, s = 0 included.
    pub volume: f64,
    /// Junctions descending from a junction present at s = 0 (the memory of the initial contact,
    /// paper §3).
    pub initial_junctions: usize,
    /// Static model on this step's contact map: k_static and W_static/ω (paper §2).
    pub static_wear_coefficient: f64,
    pub static_wear_rate: f64,
    /// Contact solver iterations of this step.
    pub iterations: usize,
    /// Contact solver residual of this step.
    pub residual: f64,
}

/// The series of every load and fracture energy: load by load, then fracture energy, then step.
pub fn series_rows(runs: &[LoadRun]) -> Vec<SeriesRow> {
    let mut rows = Vec::new();
    for r in runs {
        for (e, w) in r.results.iter().enumerate() {
            for st in &r.steps {
                let sw = &st.wear[e];
                rows.push(SeriesRow {
                    load: r.load,
                    fracture_energy: w.fracture_energy,
                    s: st.s,
                    junctions: st.junctions,
                    contact_area: st.contact_area,
                    n_critical: sw.n_critical,
                    n_formed: sw.n_formed,
                    n_shrunk: sw.n_shrunk(),
                    volume: sw.volume,
                    initial_junctions: st.initial_junctions,
                    static_wear_coefficient: st.statics[e].wear_coefficient,
                    static_wear_rate: st.statics[e].wear_rate_over_omega,
                    iterations: st.iterations,
                    residual: st.residual,
                });
            }
        }
    }
    rows
}

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
    pub sliding: &'a SlidingConfig,
    /// Warnings about the inputs (e.g. λ_l of a few pixels), reported with the results'.
    pub warnings: Vec<String>,
}

impl<'a> SlidingInputs<'a> {
    /// The inputs of a run file with a sliding schedule.
    pub fn of_run(config: &'a RunConfig, sliding: &'a SlidingConfig) -> Self {
        Self {
            units: config.units,
            surfaces: surface_source(&config.surfaces),
            material: &config.material,
            modulus: config.modulus,
            solver: config.solver,
            connectivity: config.connectivity,
            sliding,
            warnings: config.warnings(),
        }
    }

    /// The `inputs` block of the run's outputs (summary.json, the fields store).
    pub fn to_json(&self) -> Value {
        json!({
            "surfaces": self.surfaces,
            "material": self.material,
            "contact": contact_inputs(self.modulus, self.solver, self.connectivity),
            "sliding": self.sliding,
        })
    }
}

/// Every warning of a sliding run: about its inputs, d* against the pixel size, and each load's
/// results.
pub fn run_warnings(inputs: &SlidingInputs, pixel_size: f64, runs: &[LoadRun]) -> Vec<String> {
    let mut all = inputs.warnings.clone();
    all.extend(crate::sliding::resolution_warnings(inputs.material, pixel_size));
    all.extend(runs.iter().flat_map(|r| r.warnings.iter().cloned()));
    all
}

fn surface_source(source: &SurfaceSource) -> Value {
    serde_json::to_value(source).expect("plain data serialises")
}

/// The contact settings of a run as they appear in its outputs.
fn contact_inputs(modulus: ModulusConvention, solver: SolverOptions, connectivity: u8) -> Value {
    json!({
        "modulus": modulus.name(),
        "tolerance": solver.tolerance(),
        "max_iterations": solver.max_iterations(),
        "connectivity": connectivity,
    })
}

/// How the residual is defined, as written into every output that reports one.
pub const RESIDUAL_DEFINITION: &str = "max over pixels of the violation of the optimality conditions (|g+c| on \
free, max(0,-(g+c)) on non-contact, max(0,g+c) on plastic pixels) divided by std(h)";

/// `summary.json` of a sliding run: provenance, inputs, derived quantities, solver statistics and
/// the results per load and fracture energy, with the conventions they follow.
pub fn sliding_summary(
    inputs: &SlidingInputs,
    runs: &[LoadRun],
    pixel_size: f64,
    seconds: f64,
    steps_per_load: usize,
) -> Value {
    let m = inputs.material;
    let results: Vec<Value> = runs
        .iter()
        .flat_map(|r| {
            r.results.iter().map(move |w| {
                let mut v = serde_json::to_value(w).expect("plain numbers serialise");
                v.as_object_mut()
                    .expect("a struct serialises to an object")
                    .insert("load".into(), json!(r.load));
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
    json!({
        "provenance": Provenance::current(),
        "units": inputs.units,
        "inputs": inputs.to_json(),
        "flow_pressure": m.flow_pressure(),
        "critical_diameter": m.fracture_energies.iter().zip(m.critical_diameters()).map(|(g, d)| json!({"fracture_energy": g, "critical_diameter": d})).collect::<Vec<_>>(),
        "effective_modulus": m.effective_modulus(inputs.modulus),
        "modulus_convention": inputs.modulus.name(),
        "solver": {"tolerance": inputs.solver.tolerance(), "residual_definition": RESIDUAL_DEFINITION, "per_load": solver},
        "steps_per_load": steps_per_load,
        "fit": "least-squares lines of V and N*₊ against s over the steps with s ≥ running_in·L",
        "static_wear_rate_convention": "W_static/ω = k_static Σ A_i; static_wear_coefficient and static_wear_rate at s = 0, *_mean and *_std over every offset of the run",
        "wear_rate_estimate_convention": "ω d*³ dN*₊/ds with ω = π/6",
        "memory_convention": "initial_junctions: junctions descending by step-to-step pixel overlap from a junction present at s = 0; memory_decay_length ℓ from a least-squares fit of ln N₀ = ln N₀(0) − s/ℓ",
        "results": results,
        "units_of_results": units_map(inputs.units, columns::<WearResult>().iter().map(String::as_str).chain(["load", "flow_pressure", "effective_modulus"])),
        "units_of_series": units_map(inputs.units, columns::<SeriesRow>().iter().map(String::as_str)),
        "warnings": run_warnings(inputs, pixel_size, runs),
        "seconds": seconds,
    })
}

// ---------------------------------------------------------------------------------------------
// One contact solve

/// What one contact solve reports: the numbers of `wearsim contact`'s summary and of the Python
/// `ContactResult`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ContactRecord {
    /// Real contact area as a fraction of L².
    pub contact_area: f64,
    pub contact_pixels: usize,
    pub plastic_pixels: usize,
    /// Mean pressure of the solution, F_N/L² to round-off.
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

/// `summary.json` of `wearsim contact`: provenance, the solve's record, the load and offset, and
/// the run's inputs and derived quantities.
pub fn contact_summary(
    config: &RunConfig,
    load: f64,
    offset: f64,
    offset_pixels: usize,
    record: &ContactRecord,
) -> Value {
    let mut doc = json!({
        "provenance": Provenance::current(),
        "units": config.units,
        "load": load,
        "offset": offset,
        "offset_pixels": offset_pixels,
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
            contact_inputs(config.modulus, config.solver, config.connectivity),
        ),
    ]);
    doc
}

// ---------------------------------------------------------------------------------------------
// Surfaces and junctions

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
/// spectrum a run would generate from them and what was adjusted on the way (`notes`).
pub fn surface_fit_summary(
    file: &std::path::Path,
    preprocess: &crate::topography::Preprocess,
    length_unit: &str,
    grid: &crate::grid::Grid,
    fit: &crate::topography::SpectrumFit,
    spectrum: &crate::surface::SpectrumParams,
    notes: &[String],
) -> Value {
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
        "notes": notes,
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

// ---------------------------------------------------------------------------------------------
// Studies

/// The format of the job files this version writes; raised whenever what identifies a job or what
/// a job file holds changes.
pub const JOB_FORMAT: u32 = 2;

/// What a study's job file holds: which job it is (checked when the file is read back, so that a
/// file can never be attributed to another job), and its results.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JobResult {
    /// The job-file format ([`JOB_FORMAT`]); files of another format come from another version of
    /// wearsim and are not mixed with this one's.
    #[serde(default)]
    pub format: u32,
    pub provenance: Provenance,
    pub index: usize,
    pub material: String,
    /// Every input of the job.
    pub inputs: InputRecord,
    pub load: f64,
    pub flow_pressure: f64,
    pub effective_modulus: f64,
    pub results: Vec<WearResult>,
    /// Per step: s, junctions, contact area, memory; per fracture energy: n_critical, n_formed,
    /// volume and the static model.
    pub steps: Vec<StepRow>,
    pub total_iterations: usize,
    pub seconds: f64,
    /// What makes a result of this job under-resolved or undefined.
    pub warnings: Vec<String>,
}

/// One step of a job file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StepRow {
    pub s: f64,
    pub junctions: usize,
    pub contact_area: f64,
    pub initial_junctions: usize,
    pub n_critical: Vec<usize>,
    pub n_formed: Vec<usize>,
    pub volume: Vec<f64>,
    pub static_wear_coefficient: Vec<f64>,
}

impl From<&StepRecord> for StepRow {
    fn from(r: &StepRecord) -> Self {
        Self {
            s: r.s,
            junctions: r.junctions,
            contact_area: r.contact_area,
            initial_junctions: r.initial_junctions,
            static_wear_coefficient: r.statics.iter().map(|w| w.wear_coefficient).collect(),
            n_critical: r.wear.iter().map(|w| w.n_critical).collect(),
            n_formed: r.wear.iter().map(|w| w.n_formed).collect(),
            volume: r.wear.iter().map(|w| w.volume).collect(),
        }
    }
}

impl JobResult {
    /// The job file's text.
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).expect("job results serialise")
    }

    /// Parses a job file's text.
    pub fn from_json(text: &str) -> std::result::Result<Self, serde_json::Error> {
        serde_json::from_str(text)
    }
}

/// One row of a study's tidy table (`results.csv`): one job × fracture energy, with every input of
/// the job, the load and the results.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct TidyRow {
    pub job: usize,
    pub material: String,
    #[serde(flatten)]
    pub inputs: InputRecord,
    pub load: f64,
    #[serde(flatten)]
    pub result: WearResult,
    pub flow_pressure: f64,
    /// The job's warnings that concern this row (its fracture energy, or all of them), joined by
    /// "; "; empty when the result is well resolved.
    pub warnings: String,
}

impl TidyRow {
    /// The rows of one job file, one per fracture energy.
    pub fn of_job(result: &JobResult) -> Vec<TidyRow> {
        result
            .results
            .iter()
            .map(|w| {
                // A warning that names a fracture energy belongs to that row only.
                let tag = format!("𝒢 = {:.4e}", w.fracture_energy);
                let mine: Vec<&str> = result
                    .warnings
                    .iter()
                    .filter(|m| m.contains(&tag) || !m.contains("𝒢 = "))
                    .map(String::as_str)
                    .collect();
                TidyRow {
                    job: result.index,
                    material: result.material.clone(),
                    inputs: result.inputs.clone(),
                    load: result.load,
                    result: w.clone(),
                    flow_pressure: result.flow_pressure,
                    warnings: mine.join("; "),
                }
            })
            .collect()
    }
}

/// Columns of the tidy table that vary between surface pairs of one setting and are averaged over
/// in the aggregated table: the results.
fn result_columns() -> Vec<String> {
    let mut c: Vec<String> = columns::<WearResult>()
        .into_iter()
        .filter(|c| c != "fracture_energy")
        .collect();
    c.push("flow_pressure".into());
    c
}

/// Columns that neither identify a setting nor are averaged: the job index, the seed, the warnings.
const NOT_A_SETTING: [&str; 3] = ["job", "surface.seed", "warnings"];

/// The aggregated table of a tidy table: one row per setting (every column but the job index, the
/// seed and the results), with the number of surface pairs and the mean, min and max over them of
/// every result column, and the number of surface pairs with a warning. Rows keep the order in which
/// settings first appear; undefined results (empty cells) are left out of the statistics.
pub fn aggregate(tidy: &Table) -> Table {
    let values = result_columns();
    let value_index: Vec<usize> = values.iter().filter_map(|c| tidy.column(c)).collect();
    let key_index: Vec<usize> = (0..tidy.columns.len())
        .filter(|i| !value_index.contains(i) && !NOT_A_SETTING.contains(&tidy.columns[*i].as_str()))
        .collect();
    let mut order: BTreeMap<Vec<String>, usize> = BTreeMap::new();
    let mut groups: Vec<(Vec<Cell>, Vec<&Vec<Cell>>)> = Vec::new();
    for row in &tidy.rows {
        let key: Vec<Cell> = key_index.iter().map(|&i| row[i].clone()).collect();
        let text: Vec<String> = key.iter().map(Cell::text).collect();
        let g = *order.entry(text).or_insert_with(|| {
            groups.push((key, Vec::new()));
            groups.len() - 1
        });
        groups[g].1.push(row);
    }
    let warnings = tidy.column("warnings");
    let mut columns: Vec<String> = key_index.iter().map(|&i| tidy.columns[i].clone()).collect();
    columns.push("surface_pairs".into());
    columns.push("pairs_with_warnings".into());
    for &i in &value_index {
        let c = &tidy.columns[i];
        columns.extend([format!("{c}_mean"), format!("{c}_min"), format!("{c}_max")]);
    }
    let rows = groups
        .into_iter()
        .map(|(key, members)| {
            let mut line = key;
            line.push(Cell::Int(members.len() as i64));
            let warned = warnings.map_or(0, |w| members.iter().filter(|m| !m[w].text().is_empty()).count());
            line.push(Cell::Int(warned as i64));
            for &i in &value_index {
                let v: Vec<f64> = members.iter().map(|m| m[i].number()).filter(|x| !x.is_nan()).collect();
                if v.is_empty() {
                    line.extend([Cell::Empty, Cell::Empty, Cell::Empty]);
                    continue;
                }
                let mean = v.iter().sum::<f64>() / v.len() as f64;
                let min = v.iter().copied().fold(f64::INFINITY, f64::min);
                let max = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                line.extend([Cell::Float(mean), Cell::Float(min), Cell::Float(max)]);
            }
            line
        })
        .collect();
    Table { columns, rows }
}

/// Writes `results.csv` (tidy), `results_aggregated.csv` and `results.units.json` (the unit of every
/// column that has one) into `dir`, together (a failure leaves the earlier files); returns the row
/// counts of the two tables.
pub fn write_results_tables(dir: &std::path::Path, rows: &[TidyRow]) -> Result<(usize, usize)> {
    let tidy = Table::of(rows);
    let aggregated = aggregate(&tidy);
    let units = rows.first().map_or(Units::Reduced, |r| r.inputs.units);
    let unit_map = units_map(
        units,
        tidy.columns.iter().chain(&aggregated.columns).map(String::as_str),
    );
    let units_text = serde_json::to_string_pretty(&json!({"units": units, "columns": unit_map})).expect("plain data");
    let (tidy_csv, aggregated_csv) = (tidy.to_csv(), aggregated.to_csv());
    crate::io::write_texts_together(&[
        (&dir.join("results.csv"), &tidy_csv),
        (&dir.join("results_aggregated.csv"), &aggregated_csv),
        (&dir.join("results.units.json"), &units_text),
    ])?;
    Ok((tidy.rows.len(), aggregated.rows.len()))
}

/// Reads a job file, with the fix in the message when it cannot be used.
pub fn read_job_file(path: &std::path::Path) -> Result<JobResult> {
    let text = crate::io::read_text(path)?;
    JobResult::from_json(&text).map_err(|e| {
        Error::file(
            path,
            format!(
                "not a readable job result ({e}); it was cut short or written by another version of wearsim: delete \
                 it and run the study again to recompute that job"
            ),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_come_from_the_row_types() {
        assert_eq!(
            columns::<SeriesRow>(),
            [
                "load",
                "fracture_energy",
                "s",
                "junctions",
                "contact_area",
                "n_critical",
                "n_formed",
                "n_shrunk",
                "volume",
                "initial_junctions",
                "static_wear_coefficient",
                "static_wear_rate",
                "iterations",
                "residual"
            ]
        );
        let tidy = columns::<TidyRow>();
        assert_eq!(&tidy[..3], ["job", "material", "units"]);
        assert!(tidy.contains(&"surface.seed".to_string()) && tidy.contains(&"wear_rate".to_string()));
        assert_eq!(tidy.last().map(String::as_str), Some("warnings"));
    }

    #[test]
    fn csv_quotes_text_and_leaves_undefined_numbers_empty() {
        #[derive(Default, Serialize)]
        struct Row {
            name: String,
            x: f64,
            n: Option<u64>,
        }
        let rows = [
            Row {
                name: "a, \"b\"\nc".into(),
                x: f64::NAN,
                n: None,
            },
            Row {
                name: "d".into(),
                x: 2.5e-4,
                n: Some(3),
            },
        ];
        let text = Table::of(&rows).to_csv();
        assert_eq!(text, "name,x,n\n\"a, \"\"b\"\"\nc\",,\nd,2.5e-4,3\n");
    }

    #[test]
    fn aggregation_groups_over_seeds_and_skips_undefined_results() {
        let row = |job: usize, seed: u64, wear_rate: Option<f64>| TidyRow {
            job,
            material: "m".into(),
            inputs: InputRecord {
                seed: Some(seed),
                ..InputRecord::default()
            },
            load: 1e-3,
            result: WearResult {
                wear_rate,
                ..WearResult::default()
            },
            flow_pressure: 0.05,
            warnings: if wear_rate.is_none() {
                "no particle".into()
            } else {
                String::new()
            },
        };
        let tidy = Table::of(&[row(0, 1, Some(1.0)), row(1, 2, Some(3.0)), row(2, 3, None)]);
        let agg = aggregate(&tidy);
        assert_eq!(agg.rows.len(), 1);
        let at = |name: &str| agg.rows[0][agg.column(name).unwrap()].clone();
        assert_eq!(
            (at("surface_pairs"), at("pairs_with_warnings")),
            (Cell::Int(3), Cell::Int(1))
        );
        assert_eq!(
            (at("wear_rate_mean"), at("wear_rate_min"), at("wear_rate_max")),
            (Cell::Float(2.0), Cell::Float(1.0), Cell::Float(3.0))
        );
        assert!(agg.column("surface.seed").is_none() && agg.column("job").is_none());
    }
}

// ---------------------------------------------------------------------------------------------
// Fields of a sliding run

/// Which steps of a sliding run keep their fields: the loads (indices into the run's `loads`,
/// all when empty) and every `every`-th step of the schedule (the first, s = 0, always).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FieldSelection {
    pub loads: Vec<usize>,
    pub every: usize,
}

/// Longest side of a chunk: a 4096² map is stored in 16 chunks of 1024² so that a reader can load
/// a window of it without decompressing the whole map.
const FIELD_CHUNK: usize = 1024;

/// The per-step maps of a sliding run in a Zarr store that `xarray.open_zarr` opens as a Dataset:
/// `pressure` (contact pressure, the run's pressure unit), `contact` (pressure > 0) and
/// `junctions` (junction labels, 0 outside the contact, 1… per junction, periodic as in the paper's
/// junction counting), each with dimensions (load, s, x, y); coordinates `load`, `s` (sliding
/// distance), `offset` (the same in pixels), `x` and `y` (pixel positions); units as attributes,
/// provenance and the run's inputs on the group.
#[derive(Debug)]
pub struct FieldsWriter {
    group: crate::io::ZarrGroup,
    pressure: crate::io::ZarrArray,
    contact: crate::io::ZarrArray,
    junctions: crate::io::ZarrArray,
    /// Position in the store of each load of the run (None: not kept).
    load_slot: Vec<Option<usize>>,
    every: usize,
}

impl FieldsWriter {
    /// Creates the store at `path` (a folder that must not exist) for a run of `loads` over the
    /// schedule `offsets` (pixels) on `grid`.
    pub fn create(
        path: &std::path::Path,
        grid: crate::grid::Grid,
        units: Units,
        loads: &[f64],
        offsets: &[usize],
        selection: &FieldSelection,
        inputs: Value,
    ) -> Result<Self> {
        if selection.every == 0 {
            return Err(Error::param("fields every", "must be at least 1 (every step)"));
        }
        if let Some(&bad) = selection.loads.iter().find(|&&i| i >= loads.len()) {
            return Err(Error::param(
                "fields loads",
                format!(
                    "load index {bad} does not exist; the run has {} loads, indices 0 … {}",
                    loads.len(),
                    loads.len().saturating_sub(1)
                ),
            ));
        }
        let kept: Vec<usize> = if selection.loads.is_empty() {
            (0..loads.len()).collect()
        } else {
            let mut k = selection.loads.clone();
            k.sort_unstable();
            k.dedup();
            k
        };
        let mut load_slot = vec![None; loads.len()];
        for (slot, &i) in kept.iter().enumerate() {
            load_slot[i] = Some(slot);
        }
        let steps: Vec<usize> = offsets.iter().step_by(selection.every).copied().collect();
        let (nx, ny, dx) = (grid.nx(), grid.ny(), grid.pixel_size());
        let length = unit_of(units, "s");
        let mut group = crate::io::ZarrGroup::create(
            path,
            json!({
                "title": "wearsim sliding run: contact fields per step",
                "provenance": Provenance::current(),
                "units": units,
                "inputs": inputs,
                "sliding_direction": "x",
                "pixel_size": dx,
            }),
        )?;
        let kept_loads: Vec<f64> = kept.iter().map(|&i| loads[i]).collect();
        group.coordinate_f64(
            "load",
            &kept_loads,
            json!({"units": unit_of(units, "load"), "long_name": "normal load F_N"}),
        )?;
        let s: Vec<f64> = steps.iter().map(|&o| o as f64 * dx).collect();
        group.coordinate_f64(
            "s",
            &s,
            json!({"units": length, "long_name": "sliding distance of the top surface along x"}),
        )?;
        let offset = group.array(
            "offset",
            &["s"],
            &[steps.len()],
            &[steps.len().max(1)],
            crate::io::ZarrType::I64,
            json!({"units": "pixels", "long_name": "sliding offset in pixels"}),
        )?;
        offset.write_chunk(
            &[0],
            &steps
                .iter()
                .flat_map(|&o| (o as i64).to_le_bytes())
                .collect::<Vec<u8>>(),
        )?;
        let x: Vec<f64> = (0..nx).map(|i| i as f64 * dx).collect();
        let y: Vec<f64> = (0..ny).map(|j| j as f64 * dx).collect();
        group.coordinate_f64(
            "x",
            &x,
            json!({"units": length, "long_name": "position along x (sliding)"}),
        )?;
        group.coordinate_f64("y", &y, json!({"units": length, "long_name": "position along y"}))?;
        let dims = ["load", "s", "x", "y"];
        let shape = [kept.len(), steps.len(), nx, ny];
        let chunks = [1, 1, nx.min(FIELD_CHUNK), ny.min(FIELD_CHUNK)];
        let mut map = |name: &str, dtype, attrs: Value| group.array(name, &dims, &shape, &chunks, dtype, attrs);
        let pressure = map(
            "pressure",
            crate::io::ZarrType::F64,
            json!({"units": unit_of(units, "flow_pressure"), "long_name": "contact pressure", "coordinates": "offset"}),
        )?;
        let contact = map(
            "contact",
            crate::io::ZarrType::Bool,
            json!({"long_name": "in contact (pressure > 0)", "coordinates": "offset"}),
        )?;
        let junctions = map(
            "junctions",
            crate::io::ZarrType::U32,
            json!({
                "long_name": "junction label (0: no contact; junctions wrap around the periodic borders)",
                "coordinates": "offset",
            }),
        )?;
        Ok(Self {
            group,
            pressure,
            contact,
            junctions,
            load_slot,
            every: selection.every,
        })
    }

    /// Bytes the kept maps take before compression (13 per pixel and step).
    pub fn raw_bytes(grid: crate::grid::Grid, loads: usize, steps: usize, selection: &FieldSelection) -> u64 {
        let kept = if selection.loads.is_empty() {
            loads
        } else {
            selection.loads.len().min(loads)
        };
        let steps = steps.div_ceil(selection.every.max(1));
        (kept * steps) as u64 * grid.pixels() as u64 * 13
    }

    /// Stores step `step_index` (position in the schedule) of load `load_index` if the selection
    /// keeps it.
    pub fn record(&mut self, load_index: usize, step_index: usize, pressure: &[f64], labels: &[u32]) -> Result<()> {
        let Some(slot) = self.load_slot.get(load_index).copied().flatten() else {
            return Ok(());
        };
        if !step_index.is_multiple_of(self.every) {
            return Ok(());
        }
        let lead = [slot, step_index / self.every];
        self.pressure
            .write_map(&lead, pressure, |v: f64, b| b.extend_from_slice(&v.to_le_bytes()))?;
        self.contact
            .write_map(&lead, pressure, |v: f64, b| b.push(u8::from(v > 0.0)))?;
        self.junctions
            // Junction k is stored as k + 1, so that 0 is "no contact" (NO_JUNCTION wraps to 0).
            .write_map(&lead, labels, |v: u32, b| {
                b.extend_from_slice(&v.wrapping_add(1).to_le_bytes())
            })?;
        Ok(())
    }

    /// Writes the consolidated metadata; the store is complete.
    pub fn finish(self) -> Result<()> {
        self.group.finish()
    }
}
