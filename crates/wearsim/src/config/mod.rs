//! Run files: TOML parsed strictly (unknown keys are errors naming the key) and turned
//! into a validated [`RunConfig`] before any work starts.

mod raw;
mod record;
mod source;

pub use raw::Units;
pub use record::InputRecord;
pub use source::{SurfaceFiles, SurfacePair, SurfaceSource};

use std::path::Path;

use crate::check::connectivity as check_connectivity;
use crate::contact::{Device, SolverOptions, Stopping, SLIDING_STOPPING};
use crate::error::{Error, Interrupt, Result};
use crate::estimate::Sampling;
use crate::grid::Grid;
use crate::influence::Boundary;
use crate::io::{parent_or_dot, read_text};
use crate::junctions::DEFAULT_CONNECTIVITY;
use crate::material::{Material, ModulusConvention};
use crate::model::WearModel;
use crate::sliding::{
    SlidingConfig, SlidingSetup, DEFAULT_DISTANCE, DEFAULT_RUNNING_IN, DEFAULT_STEP, DEFAULT_STEP_RUNNING_IN,
};
use crate::surface::{Generation, Surface};
use crate::topography::{metres_per, FileSurface, Preprocess};
use crate::wear::ParticleRuleSpec;

use raw::{one_line, RawRun};
use source::{
    check_pair_memory, file_pair, file_surface_of, generated_pair, lateral_scale, spectrum_pair, surface_source,
};

/// A validated run: read from a run file ([`RunConfig::from_path`]) or built in memory
/// ([`RunConfig::builder`]), never assembled field by field, so that every run passes the same
/// checks; and never changed once built, so that it stays a run that passed them. Its settings are
/// read through [`RunSettings`], to which it dereferences (`config.material`, `config.sliding`);
/// there is no mutable access. A run that differs in a few settings is derived through the builder
/// and validated again: `config.to_builder().sliding(schedule).build()?`.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[serde(transparent)]
pub struct RunConfig {
    settings: RunSettings,
}

impl std::ops::Deref for RunConfig {
    type Target = RunSettings;

    fn deref(&self) -> &RunSettings {
        &self.settings
    }
}

/// The settings of a validated [`RunConfig`], read through it. `#[non_exhaustive]`: only the
/// library makes one, inside a `RunConfig` made by [`RunBuilder::build`]; a copy taken out of it
/// (`(*config).clone()`) can be changed but never becomes a run again except through the builder.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[non_exhaustive]
pub struct RunSettings {
    pub units: Units,
    pub surfaces: SurfaceSource,
    pub material: Material,
    pub modulus: ModulusConvention,
    pub solver: SolverOptions,
    /// Junction connectivity, 4 or 8.
    pub connectivity: u8,
    /// The half-space's boundary at the map's edges for `contact` (sliding is always periodic).
    pub boundary: Boundary,
    /// Where the contact solver computes.
    pub device: Device,
    pub sliding: Option<SlidingConfig>,
    /// When the contact solves of a sliding run stop (`[sliding] stopping`); single solves stop at
    /// the tolerance of `solver`.
    pub stopping: Stopping,
    /// Which model turns the run into wear results (`[sliding] model`): the sliding simulation, or
    /// the static estimate of `crate::estimate`.
    pub model: WearModel,
    /// The static maps of an estimate (`[sliding] estimate_samples`; absent: chosen by the
    /// sampling error).
    pub estimate_samples: Option<usize>,
    /// The static estimate's constants given in the run file (`[sliding] estimate_constants`, from
    /// `wearsim estimate-check --fit` on sliding runs of the user's own surfaces); absent: the
    /// library's [`crate::estimate::CALIBRATION`].
    pub estimate_constants: Option<crate::estimate::Calibration>,
    /// The run file's values given in another form than the model's inputs, each with the formula
    /// that turned it into one (a hardness into τ̃, a pressure into a load, the box from an imported
    /// map's record): what the front ends print before the work and the summaries keep.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub conversions: Vec<String>,
}

/// A run being built in memory ([`RunConfig::builder`]): the one way, besides a run file, to make a
/// [`RunConfig`], so that every front end's run passes the checks a run file's does.
#[derive(Debug, Clone)]
#[must_use = "a run is made by `build`"]
pub struct RunBuilder {
    units: Units,
    surfaces: SurfaceSource,
    material: Material,
    modulus: ModulusConvention,
    solver: SolverOptions,
    connectivity: u8,
    boundary: Boundary,
    device: Device,
    sliding: Option<SlidingConfig>,
    stopping: Stopping,
    model: WearModel,
    estimate_samples: Option<usize>,
    estimate_constants: Option<crate::estimate::Calibration>,
    conversions: Vec<String>,
}

macro_rules! setters {
    ($($(#[$doc:meta])* $name:ident: $ty:ty,)*) => {
        $(
            $(#[$doc])*
            pub fn $name(mut self, $name: $ty) -> Self {
                self.$name = $name;
                self
            }
        )*
    };
}

impl RunBuilder {
    setters! {
        /// The unit system (`units`).
        units: Units,
        /// The surfaces (`[surface]`).
        surfaces: SurfaceSource,
        /// The material (`[material]`).
        material: Material,
        /// The modulus convention (`[contact] modulus`).
        modulus: ModulusConvention,
        /// The contact solver's tolerance and iterations (`[contact]`).
        solver: SolverOptions,
        /// Junction connectivity, 4 or 8 (`[contact] connectivity`).
        connectivity: u8,
        /// The boundary of single contact solves (`[contact] boundary`).
        boundary: Boundary,
        /// Where the contact solver computes (`[contact] device`).
        device: Device,
        /// When a sliding run's solves stop (`[sliding] stopping`).
        stopping: Stopping,
        /// Which model turns the run into wear results (`[sliding] model`).
        model: WearModel,
        /// The static maps of an estimate (`[sliding] estimate_samples`).
        estimate_samples: Option<usize>,
        /// The static estimate's constants (`[sliding] estimate_constants`).
        estimate_constants: Option<crate::estimate::Calibration>,
    }

    /// The sliding schedule (`[sliding]`).
    pub fn sliding(mut self, sliding: SlidingConfig) -> Self {
        self.sliding = Some(sliding);
        self
    }

    /// The grid the surfaces fix (generated, arrays, a spectrum); `None` for files, whose grid is
    /// known once they are read.
    fn fixed_grid(&self) -> Option<Grid> {
        match &self.surfaces {
            SurfaceSource::Generated { grid, .. }
            | SurfaceSource::Arrays { grid, .. }
            | SurfaceSource::Spectrum { grid, .. } => Some(*grid),
            SurfaceSource::Files { .. } => None,
        }
    }

    /// The run, checked as a run file is: the connectivity, a free boundary only without
    /// `[sliding]`, the device available in this build, the estimate's samples and constants, the
    /// schedule against a fixed grid and each load against the flow pressure times the apparent
    /// area where the run fixes it. The errors are those of the same run file.
    pub fn build(self) -> Result<RunConfig> {
        check_connectivity(self.connectivity)?;
        if self.boundary == Boundary::Free && self.sliding.is_some() {
            return Err(Error::run_file(
                "[contact] `boundary = \"free\"` applies to single contact solves; sliding is periodic (paper §2), so a \
                 run file with [sliding] keeps the default \"periodic\" (for one free-boundary solve of its pair, use \
                 `wearsim contact --boundary free`)",
            ));
        }
        self.device
            .available()
            .map_err(|e| Error::run_file(format!("[contact] `device`: {e}")))?;
        Sampling::of(self.estimate_samples).map_err(|e| Error::run_file(format!("[sliding] {e}")))?;
        let estimate_constants = match self.estimate_constants {
            None => None,
            Some(c) => Some(
                c.checked("estimate_constants")
                    .map_err(|e| Error::run_file(format!("[sliding] {e}")))?,
            ),
        };
        if let (Some(sl), Some(grid)) = (&self.sliding, self.fixed_grid()) {
            sl.check_grid(grid.nx())?;
        }
        // The apparent area, where the run fixes it (a file's y side may come from its shape,
        // checked when the run starts).
        let area = fixed_area(&self.surfaces);
        if let (Some(sl), Some(area)) = (&self.sliding, area) {
            for &load in &sl.loads {
                crate::check::load("loads", load, area, self.material.flow_pressure())?;
            }
        }
        let settings = RunSettings {
            units: self.units,
            surfaces: self.surfaces,
            material: self.material,
            modulus: self.modulus,
            solver: self.solver,
            connectivity: self.connectivity,
            boundary: self.boundary,
            device: self.device,
            sliding: self.sliding,
            stopping: self.stopping,
            model: self.model,
            estimate_samples: self.estimate_samples,
            estimate_constants,
            conversions: self.conversions,
        };
        Ok(RunConfig { settings })
    }
}

impl RunConfig {
    /// Reads and validates a run file.
    pub fn from_path(path: &Path) -> Result<Self> {
        let text = read_text(path)?;
        Self::from_toml(&text, parent_or_dot(path)).map_err(|e| match e {
            Error::RunFile { path: None, message } => Error::RunFile {
                path: Some(path.into()),
                message,
            },
            other => other,
        })
    }

    /// Parses run-file text; relative surface paths are resolved against `base`.
    pub fn from_toml(text: &str, base: &Path) -> Result<Self> {
        let raw: RawRun = toml::from_str(text).map_err(|e| Error::run_file(one_line(&e.to_string())))?;
        Self::from_raw(raw, base, SurfaceFiles::MustExist)
    }

    /// A run described by a parsed TOML table (a study's job), without a round trip through text.
    pub fn from_table(table: toml::Table, base: &Path, files: SurfaceFiles) -> Result<Self> {
        let raw: RawRun = toml::Value::Table(table)
            .try_into()
            .map_err(|e| Error::run_file(one_line(&e.to_string())))?;
        Self::from_raw(raw, base, files)
    }

    fn from_raw(raw: RawRun, base: &Path, files: SurfaceFiles) -> Result<Self> {
        let mut conversions = Vec::new();
        let surfaces = surface_source(&raw.surface, raw.units, base, files, &mut conversions)?;
        let m = raw.material;
        let (shear_strength, fracture_energies) = material_inputs(&m, raw.units, &mut conversions)?;
        let material = Material::new(
            m.youngs_modulus,
            m.poisson_ratio,
            shear_strength,
            fracture_energies,
            m.geometry_factor.unwrap_or(3.0),
        )?;
        let c = raw.contact;
        let defaults = SolverOptions::default();
        let solver = SolverOptions::new(
            c.tolerance.unwrap_or(defaults.tolerance()),
            c.max_iterations.unwrap_or(defaults.max_iterations()),
        )?;
        let sliding_table = raw.sliding.as_ref();
        let estimate_constants =
            sliding_table
                .and_then(|sl| sl.estimate_constants.as_ref())
                .map(|c| crate::estimate::Calibration {
                    residence_factor: c.residence_factor,
                    merging_factor: c.merging_factor,
                    volume_factor: c.volume_factor,
                    rate_spread: c.rate_spread,
                    wear_spread: c.wear_spread,
                    settings: 0,
                    particles: 0,
                });
        let mut run = RunConfig::builder(surfaces, material)
            .units(raw.units)
            .modulus(c.modulus.unwrap_or_default())
            .solver(solver)
            .connectivity(c.connectivity.unwrap_or(DEFAULT_CONNECTIVITY))
            .boundary(c.boundary.unwrap_or_default())
            .device(c.device.unwrap_or_default())
            .stopping(sliding_table.and_then(|sl| sl.stopping).unwrap_or(SLIDING_STOPPING))
            .model(sliding_table.and_then(|sl| sl.model).unwrap_or_default())
            .estimate_samples(sliding_table.and_then(|sl| sl.estimate_samples))
            .estimate_constants(estimate_constants);
        if let Some(sl) = raw.sliding {
            let rule = match &sl.particle_rule {
                Some(raw::RawParticleRule::Named(text)) => text.parse::<ParticleRuleSpec>()?,
                Some(raw::RawParticleRule::Table(table)) => ParticleRuleSpec::from_table(table)?,
                None => ParticleRuleSpec::default(),
            };
            let grid = run.fixed_grid().map(|g| g.nx());
            let loads = normal_loads(sl.loads, sl.pressures, &run.surfaces, raw.units, &mut conversions)?;
            run = run.sliding(
                SlidingConfig::new(
                    loads,
                    sl.distance.unwrap_or(DEFAULT_DISTANCE),
                    sl.running_in.unwrap_or(DEFAULT_RUNNING_IN),
                    sl.step_running_in.unwrap_or(DEFAULT_STEP_RUNNING_IN),
                    sl.step.unwrap_or(DEFAULT_STEP),
                    grid,
                )?
                .with_particle_rule(rule),
            );
        }
        run.conversions = conversions;
        run.build()
    }

    /// A run built in memory (a front end's arguments, a benchmark), validated by
    /// [`RunBuilder::build`] exactly as a run file is: the other settings start at a run file's
    /// defaults (reduced units, the half-space modulus, the default solver, connectivity 8, a
    /// periodic boundary on the CPU, no `[sliding]`, the sliding model).
    pub fn builder(surfaces: SurfaceSource, material: Material) -> RunBuilder {
        RunBuilder {
            units: Units::default(),
            surfaces,
            material,
            modulus: ModulusConvention::default(),
            solver: SolverOptions::default(),
            connectivity: DEFAULT_CONNECTIVITY,
            boundary: Boundary::default(),
            device: Device::default(),
            sliding: None,
            stopping: SLIDING_STOPPING,
            model: WearModel::default(),
            estimate_samples: None,
            estimate_constants: None,
            conversions: Vec::new(),
        }
    }

    /// This run as a builder, to make another that differs in a few settings (validated again by
    /// [`RunBuilder::build`]).
    pub fn to_builder(&self) -> RunBuilder {
        let RunSettings {
            units,
            surfaces,
            material,
            modulus,
            solver,
            connectivity,
            boundary,
            device,
            sliding,
            stopping,
            model,
            estimate_samples,
            estimate_constants,
            conversions,
        } = self.settings.clone();
        RunBuilder {
            units,
            surfaces,
            material,
            modulus,
            solver,
            connectivity,
            boundary,
            device,
            sliding,
            stopping,
            model,
            estimate_samples,
            estimate_constants,
            conversions,
        }
    }

    /// The top and bottom surfaces: generated (seeds derived from the run's seed) or read.
    pub fn surfaces(&self) -> Result<(Surface, Surface)> {
        self.surface_pair().map(SurfacePair::into_surfaces)
    }

    /// The top and bottom surfaces with notes on how files were read and prepared, and warnings
    /// about them (a measured surface far from periodic). Arrays held by the caller are not the
    /// run's to make: an error.
    pub fn surface_pair(&self) -> Result<SurfacePair> {
        match &self.surfaces {
            SurfaceSource::Arrays { .. } => Err(Error::run_file(
                "[surface] the surfaces are arrays held by the caller, neither generated nor read from files",
            )),
            SurfaceSource::Generated { grid, spectrum, seed } => generated_pair(*grid, spectrum, *seed),
            SurfaceSource::Spectrum {
                grid,
                map,
                map_length,
                height_unit,
                lateral_unit,
                window,
                seed,
            } => {
                check_pair_memory(*grid)?;
                let how = FileSurface {
                    height_scale: match (self.units, height_unit) {
                        (Units::Si, Some(u)) => metres_per("height_unit", u)?,
                        _ => 1.0,
                    },
                    lateral_scale: lateral_scale(self.units, lateral_unit, height_unit)?,
                    length_x: Some(*map_length),
                    length_y: None,
                    preprocess: Preprocess::default(),
                };
                spectrum_pair(map, &how, *grid, *window, *seed)
            }
            SurfaceSource::Files { top, bottom, .. } => file_pair(top, bottom, &self.file_surface()?),
        }
    }

    /// How the run's surface files are read (units and preparation); an error for surfaces not read
    /// from files.
    fn file_surface(&self) -> Result<FileSurface> {
        file_surface_of(&self.surfaces, self.units)
    }

    /// The grid of the run: the generated one, or that of the top surface file (from its `.npy`
    /// header, or by reading a text file), after cropping to even sides.
    pub fn grid(&self) -> Result<Grid> {
        match &self.surfaces {
            SurfaceSource::Generated { grid, .. }
            | SurfaceSource::Arrays { grid, .. }
            | SurfaceSource::Spectrum { grid, .. } => Ok(*grid),
            SurfaceSource::Files { top, .. } => crate::topography::probe_grid(top, &self.file_surface()?),
        }
    }

    /// What makes this run under-resolved before it starts: a shortest wavelength λ_l of fewer than
    /// four pixels (the paper uses 16, appendix A), a solver tolerance loose enough to move the
    /// results ([`crate::check::tolerance_warning`]). One sentence each.
    pub fn warnings(&self) -> Vec<String> {
        let mut out: Vec<String> = crate::check::tolerance_warning(self.solver.tolerance())
            .into_iter()
            .collect();
        if let SurfaceSource::Generated { grid, spectrum, .. } = &self.surfaces {
            let pixels = spectrum.lambda_lower / grid.pixel_size();
            if pixels < crate::check::RESOLVED_PIXELS {
                out.push(format!(
                    "λ_l = {:.4e} is {pixels:.1} pixels, under {}: the shortest wavelength of the roughness is not \
                     resolved (the paper uses 16 pixels); refine `grid` or raise `lambda_lower`",
                    spectrum.lambda_lower,
                    crate::check::RESOLVED_PIXELS
                ));
            }
        }
        out
    }

    /// Side length Lx along the sliding direction, in the run's length unit: the generated grid's,
    /// or as given for files (a file cropped to even sides is one pixel shorter; see
    /// [`RunConfig::grid`]).
    pub fn length(&self) -> f64 {
        match &self.surfaces {
            SurfaceSource::Generated { grid, .. } | SurfaceSource::Spectrum { grid, .. } => grid.length_x(),
            SurfaceSource::Files { length, .. } | SurfaceSource::Arrays { length, .. } => *length,
        }
    }

    /// Effective modulus E* under the run's convention.
    pub fn effective_modulus(&self) -> f64 {
        self.material.effective_modulus(self.modulus)
    }

    /// The static estimate's constants of this run: the run file's own, else the library's.
    pub fn estimate_calibration(&self) -> crate::estimate::Calibration {
        self.estimate_constants.unwrap_or(crate::estimate::CALIBRATION)
    }

    /// Every input of the run as one flat record (the fracture energies and loads aside, which a
    /// results table has one row per).
    pub fn inputs(&self) -> InputRecord {
        let mut record = self.record_without_surfaces();
        self.record_surfaces(&mut record);
        record
    }

    /// The record of every input but the surfaces' (their fields left empty).
    fn record_without_surfaces(&self) -> InputRecord {
        let m = &self.material;
        InputRecord {
            units: self.units,
            grid: None,
            grid_y: None,
            length: self.length(),
            length_y: None,
            hurst: None,
            lambda_lower: None,
            lambda_upper: None,
            rms_height: None,
            seed: None,
            top: None,
            bottom: None,
            height_unit: None,
            detrend: None,
            taper: None,
            generation: None,
            lateral_unit: None,
            source: None,
            map: None,
            map_length: None,
            window: None,
            youngs_modulus: m.youngs_modulus,
            poisson_ratio: m.poisson_ratio,
            shear_strength: m.shear_strength,
            geometry_factor: m.geometry_factor,
            modulus: self.modulus,
            tolerance: self.solver.tolerance(),
            max_iterations: (self.solver.max_iterations() != crate::contact::DEFAULT_MAX_ITERATIONS)
                .then_some(self.solver.max_iterations()),
            connectivity: self.connectivity,
            device: (self.device != Device::default()).then_some(self.device),
            distance: self.sliding.as_ref().map(|s| s.distance),
            running_in: self.sliding.as_ref().map(|s| s.running_in),
            step_running_in: self.sliding.as_ref().map(|s| s.step_running_in),
            step: self.sliding.as_ref().map(|s| s.step),
            particle_rule: self
                .sliding
                .as_ref()
                .filter(|s| s.particle_rule != ParticleRuleSpec::default())
                .map(|s| s.particle_rule.to_string()),
            stopping: (self.sliding.is_some() && self.stopping != SLIDING_STOPPING).then_some(self.stopping),
            model: (self.model != WearModel::default()).then_some(self.model),
            estimate_samples: self.estimate_samples,
            estimate_constants: self.estimate_constants.map(|c| {
                format!(
                    "{}, {}, {}, {}, {}",
                    c.residence_factor, c.merging_factor, c.volume_factor, c.rate_spread, c.wear_spread
                )
            }),
        }
    }

    /// Where the surfaces come from, into `record`: the grid, and the spectrum, the measured map or
    /// the files with their units and preparation.
    fn record_surfaces(&self, record: &mut InputRecord) {
        let mut record_grid = |grid: &Grid| {
            record.grid = Some(grid.nx());
            if !grid.is_square() {
                record.grid_y = Some(grid.ny());
                record.length_y = Some(grid.length_y());
            }
        };
        match &self.surfaces {
            SurfaceSource::Generated { grid, .. }
            | SurfaceSource::Spectrum { grid, .. }
            | SurfaceSource::Arrays { grid, .. } => record_grid(grid),
            SurfaceSource::Files { .. } => {}
        }
        match &self.surfaces {
            SurfaceSource::Generated { spectrum, seed, .. } => {
                record.hurst = Some(spectrum.hurst);
                record.lambda_lower = Some(spectrum.lambda_lower);
                record.lambda_upper = Some(spectrum.lambda_upper);
                record.rms_height = Some(spectrum.rms_height);
                record.seed = Some(*seed);
                record.generation = (spectrum.generation != Generation::default()).then_some(spectrum.generation);
            }
            SurfaceSource::Spectrum {
                map,
                map_length,
                height_unit,
                lateral_unit,
                window,
                seed,
                ..
            } => {
                record.source = Some("spectrum".into());
                record.map = Some(map.display().to_string());
                record.map_length = Some(*map_length);
                record.height_unit = height_unit.clone();
                record.lateral_unit = lateral_unit.clone();
                record.window = *window;
                record.seed = Some(*seed);
            }
            SurfaceSource::Arrays { .. } => {}
            SurfaceSource::Files {
                top,
                bottom,
                length_y,
                height_unit,
                lateral_unit,
                preprocess,
                ..
            } => {
                record.lateral_unit = lateral_unit.clone();
                record.top = Some(top.display().to_string());
                record.bottom = Some(bottom.display().to_string());
                record.length_y = *length_y;
                record.height_unit = height_unit.clone();
                if *preprocess != Preprocess::default() {
                    record.detrend = Some(preprocess.detrend.name().to_string());
                    record.taper = Some(preprocess.taper);
                }
            }
        }
    }
}

/// The unit of a quantity the conversion notes name, in a run of `units` (as the outputs declare
/// it).
fn unit_of(units: Units, quantity: &str) -> &'static str {
    let (reduced, si) = match quantity {
        "load" => ("E L²", "N"),
        "nominal_area" => ("L²", "m²"),
        "fracture_energies" => ("E L", "J/m²"),
        "fracture_toughness" => ("E √L", "Pa √m"),
        // Strengths and pressures.
        _ => ("E", "Pa"),
    };
    if units == Units::Si {
        si
    } else {
        reduced
    }
}

/// A value with its unit in a run of `units`, for the conversion notes.
fn valued(units: Units, quantity: &str, value: f64) -> String {
    format!("{value:.4e} {}", unit_of(units, quantity))
}

/// τ̃ and the fracture energies 𝒢 of `[material]`, each given as the model's input or as its
/// alternative (a hardness or a yield strength for τ̃, fracture toughnesses for 𝒢), converted with
/// the formula noted in `conversions`. Exactly one form of each; every alternative is checked
/// under its own name before it is converted.
fn material_inputs(m: &raw::RawMaterial, units: Units, conversions: &mut Vec<String>) -> Result<(f64, Vec<f64>)> {
    let given: Vec<(&str, f64)> = [
        ("shear_strength", m.shear_strength),
        ("hardness", m.hardness),
        ("yield_strength", m.yield_strength),
    ]
    .into_iter()
    .filter_map(|(name, v)| v.map(|v| (name, v)))
    .collect();
    let shear_strength =
        match given.as_slice() {
            [] => return Err(Error::run_file(
                "[material] give the junction shear strength: `shear_strength` (τ̃), or `hardness` (H, converted as \
                 τ̃ = H/(3√3), the flow pressure p_m = 3√3 τ̃ being the hardness) or `yield_strength` (σ_y, τ̃ = σ_y/√3, \
                 von Mises)",
            )),
            [("shear_strength", tau)] => *tau,
            [(name, value)] => {
                crate::check::scale(name, *value)?;
                let (tau, formula) = if *name == "hardness" {
                    (
                        crate::material::shear_strength_from_hardness(*value),
                        "τ̃ = H/(3√3), the flow pressure p_m = 3√3 τ̃ being H",
                    )
                } else {
                    (
                        crate::material::shear_strength_from_yield_strength(*value),
                        "τ̃ = σ_y/√3 (von Mises), so p_m = 3 σ_y",
                    )
                };
                let symbol = if *name == "hardness" { "H" } else { "σ_y" };
                conversions.push(format!(
                    "[material] {name} {symbol} = {}: shear strength {formula}: τ̃ = {}",
                    valued(units, name, *value),
                    valued(units, "shear_strength", tau)
                ));
                tau
            }
            more => {
                let names: Vec<String> = more.iter().map(|(n, _)| format!("`{n}`")).collect();
                return Err(Error::run_file(format!(
                    "[material] {} each give the shear strength τ̃; keep one",
                    names.join(" and ")
                )));
            }
        };
    let energies =
        match (&m.fracture_energies, &m.fracture_toughness) {
            (Some(_), Some(_)) => return Err(Error::run_file(
                "[material] `fracture_energies` and `fracture_toughness` each give the fracture energies 𝒢; keep one",
            )),
            (Some(g), None) => g.clone(),
            (None, None) => Vec::new(),
            (None, Some(toughness)) => {
                let mut energies = Vec::with_capacity(toughness.len());
                for &k in toughness {
                    crate::check::positive("fracture_toughness", k)?;
                    let g = crate::material::fracture_energy_from_toughness(k, m.youngs_modulus, m.poisson_ratio);
                    conversions.push(format!(
                    "[material] fracture_toughness K_Ic = {}: fracture energy 𝒢 = K_Ic²(1 − ν²)/E (plane strain) = {}",
                    valued(units, "fracture_toughness", k),
                    valued(units, "fracture_energies", g)
                ));
                    energies.push(g);
                }
                energies
            }
        };
    Ok((shear_strength, energies))
}

/// The normal loads F_N of `[sliding]`: `loads` as given, or `pressures` p_N times the apparent
/// area Lx·Ly of the run's box (noted in `conversions`). Exactly one of the two.
fn normal_loads(
    loads: Option<Vec<f64>>,
    pressures: Option<Vec<f64>>,
    surfaces: &SurfaceSource,
    units: Units,
    conversions: &mut Vec<String>,
) -> Result<Vec<f64>> {
    match (loads, pressures) {
        (Some(loads), None) => Ok(loads),
        (Some(_), Some(_)) => Err(Error::run_file(
            "[sliding] `loads` (normal forces F_N) and `pressures` (nominal pressures p_N = F_N/(Lx·Ly)) both give the \
             loads; keep one",
        )),
        (None, None) => Err(Error::run_file(format!(
            "[sliding] `loads` is missing: give the normal loads F_N ({}), or `pressures`, the nominal pressures p_N \
             ({}) that F_N = p_N Lx·Ly makes loads of",
            unit_of(units, "load"),
            unit_of(units, "nominal_pressure")
        ))),
        (None, Some(pressures)) if pressures.is_empty() => Err(Error::param(
            "pressures",
            "the list is empty; give at least one nominal pressure p_N, e.g. pressures = [1e8] (Pa in SI)",
        )),
        (None, Some(pressures)) => {
            let area = apparent_area(surfaces, units)?;
            let mut loads = Vec::with_capacity(pressures.len());
            for p in pressures {
                crate::check::positive("pressures", p)?;
                let load = p * area;
                conversions.push(format!(
                    "[sliding] pressure p_N = {}: load F_N = p_N Lx·Ly = {} on the box's {}",
                    valued(units, "nominal_pressure", p),
                    valued(units, "load", load),
                    valued(units, "nominal_area", area)
                ));
                loads.push(load);
            }
            Ok(loads)
        }
    }
}

/// The apparent area Lx·Ly where the run fixes it without reading a file: the grid's, or the
/// surface files' `length = [Lx, Ly]`; `None` for files whose Ly comes from their shape.
fn fixed_area(surfaces: &SurfaceSource) -> Option<f64> {
    match surfaces {
        SurfaceSource::Generated { grid, .. }
        | SurfaceSource::Arrays { grid, .. }
        | SurfaceSource::Spectrum { grid, .. } => Some(grid.area()),
        SurfaceSource::Files {
            length,
            length_y: Some(ly),
            ..
        } => Some(length * ly),
        SurfaceSource::Files { .. } => None,
    }
}

/// The apparent area Lx·Ly of the run's box: the grid's, or that of the surface files (their
/// `length = [Lx, Ly]`, else Lx and the top file's shape); an error saying what to give where it
/// is not known (files not at hand).
fn apparent_area(surfaces: &SurfaceSource, units: Units) -> Result<f64> {
    if let Some(area) = fixed_area(surfaces) {
        return Ok(area);
    }
    match surfaces {
        SurfaceSource::Files { top, .. } if top.is_file() => {
            Ok(crate::topography::probe_grid(top, &file_surface_of(surfaces, units)?)?.area())
        }
        _ => Err(Error::run_file(
            "[sliding] `pressures` need the box's apparent area Lx·Ly, and the surface files are not at hand to give \
             Ly: give [surface] `length = [Lx, Ly]`, or the loads F_N as `loads`",
        )),
    }
}

impl<'a> SlidingSetup<'a> {
    /// The setup a run file describes, for the given schedule (the run's own, or one load of it).
    pub fn from_run(run: &'a RunConfig, sliding: &'a SlidingConfig) -> Self {
        Self {
            material: &run.material,
            effective_modulus: run.effective_modulus(),
            solver: run.solver.with_stopping(run.stopping),
            device: run.device,
            connectivity: run.connectivity,
            sliding,
            interrupt: Interrupt::default(),
        }
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn every_sliding_key_is_known_to_the_models() {
        // The keys a run file's [sliding] accepts, as serde lists them for an unknown one.
        let e = toml::from_str::<raw::RawSliding>("loads = [1e-3]\nnot_a_key = 1\n")
            .unwrap_err()
            .to_string();
        let expected = &e[e.find("expected").expect(&e)..];
        let mut accepted: Vec<&str> = expected.split('`').skip(1).step_by(2).collect();
        let mut known = crate::model::SLIDING_KEYS.to_vec();
        accepted.sort_unstable();
        known.sort_unstable();
        assert_eq!(accepted, known, "{e}");
        for m in WearModel::ALL {
            assert!(m.ignores().iter().all(|k| known.contains(k)), "{m:?}");
        }
    }

    /// The field names serde reads for `T` (renamed as in files), without a value: a deserializer
    /// that only records the list `deserialize_struct` is handed.
    fn field_names<T: for<'de> serde::Deserialize<'de>>() -> Vec<&'static str> {
        use serde::de::{self, Visitor};
        struct Names<'a>(&'a mut Vec<&'static str>);
        impl<'de> de::Deserializer<'de> for Names<'_> {
            type Error = de::value::Error;
            fn deserialize_any<V: Visitor<'de>>(self, _: V) -> std::result::Result<V::Value, Self::Error> {
                Err(de::Error::custom("field names only"))
            }
            fn deserialize_struct<V: Visitor<'de>>(
                self,
                _: &'static str,
                fields: &'static [&'static str],
                _: V,
            ) -> std::result::Result<V::Value, Self::Error> {
                self.0.extend(fields);
                Err(de::Error::custom("field names only"))
            }
            serde::forward_to_deserialize_any! {
                bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf option unit
                unit_struct newtype_struct seq tuple tuple_struct map enum identifier ignored_any
            }
        }
        let mut names = Vec::new();
        let _ = T::deserialize(Names(&mut names));
        names
    }

    #[test]
    fn every_input_of_a_run_file_is_a_column_of_the_input_record() {
        // Derived from the run file's own structs, so a new input cannot be forgotten: each key is
        // a column `section.key` (or `units`), except the lists a results table has one row per
        // (fracture energies, loads) and the sides of a rectangle, which are two columns each.
        let columns = field_names::<super::InputRecord>();
        assert!(!columns.is_empty());
        let sections: [(&str, Vec<&str>); 4] = [
            ("surface", field_names::<super::raw::RawSurface>()),
            ("material", field_names::<super::raw::RawMaterial>()),
            ("contact", field_names::<super::raw::RawContact>()),
            ("sliding", field_names::<super::raw::RawSliding>()),
        ];
        // `contact.boundary` distinguishes no study jobs: a run with `[sliding]` (every study job) is
        // periodic, and a free boundary is refused there.
        let per_row = ["material.fracture_energies", "sliding.loads", "contact.boundary"];
        // The alternatives to τ̃, 𝒢 and F_N are converted before the run and recorded as those.
        let converted = [
            "material.hardness",
            "material.yield_strength",
            "material.fracture_toughness",
            "sliding.pressures",
        ];
        let mut missing = Vec::new();
        for (section, keys) in &sections {
            assert!(!keys.is_empty(), "{section}");
            for key in keys {
                let column = format!("{section}.{key}");
                if !per_row.contains(&column.as_str())
                    && !converted.contains(&column.as_str())
                    && !columns.contains(&column.as_str())
                {
                    missing.push(column);
                }
            }
        }
        assert!(columns.contains(&"units"));
        for side in ["surface.grid_y", "surface.length_y"] {
            assert!(columns.contains(&side), "{side}");
        }
        assert!(
            missing.is_empty(),
            "inputs that are no column of InputRecord: {missing:?}"
        );
    }

    #[test]
    fn jobs_differing_only_in_generation_lateral_unit_or_max_iterations_have_different_inputs() {
        let base = "[surface]\ngrid = 64\nlambda_lower = 0.125\nlambda_upper = 0.25\nrms_height = 0.005\n\
                    [material]\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.01\n";
        let inputs = |text: &str| {
            super::RunConfig::from_toml(text, std::path::Path::new("."))
                .unwrap()
                .inputs()
        };
        let plain = inputs(base);
        assert_eq!((plain.generation, plain.max_iterations), (None, None));
        let noise = inputs(&base.replace("grid = 64", "grid = 64\ngeneration = \"filtered-noise\""));
        assert_eq!(noise.generation, Some(super::Generation::FilteredNoise));
        let capped = inputs(&format!("{base}[contact]\nmax_iterations = 500\n"));
        assert_eq!(capped.max_iterations, Some(500));
        assert!(plain != noise && plain != capped);
    }
    use super::*;

    const RUN: &str = r#"
units = "reduced"
[surface]
grid = 64
length = 1.0
hurst = 0.7
lambda_lower = 0.0625
lambda_upper = 0.25
rms_height = 0.005
seed = 3
[material]
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = 0.01
fracture_energies = [0.5e-6]
[contact]
modulus = "composite"
[sliding]
loads = [1e-3]
"#;

    #[test]
    fn parses_a_run_file() {
        let c = RunConfig::from_toml(RUN, Path::new(".")).unwrap();
        assert_eq!(c.modulus, ModulusConvention::Composite);
        assert_eq!(c.sliding.as_ref().unwrap().step_running_in, 4);
        let (t, b) = c.surfaces().unwrap();
        assert_ne!(t, b);
        assert_eq!(c.boundary, Boundary::Periodic);
    }

    #[test]
    fn the_device_is_read_checked_before_any_work_and_recorded_when_not_the_cpu() {
        let cpu = RunConfig::from_toml(
            &RUN.replace("modulus = \"composite\"", "device = \"cpu\""),
            Path::new("."),
        )
        .unwrap();
        assert_eq!(cpu.device, crate::contact::Device::Cpu);
        assert_eq!(cpu.inputs().device, None);
        assert_eq!(RunConfig::from_toml(RUN, Path::new(".")).unwrap().device, cpu.device);
        let cuda = RUN.replace("modulus = \"composite\"", "device = \"cuda\"");
        let err = RunConfig::from_toml(&cuda, Path::new(".")).unwrap_err().to_string();
        assert!(err.contains("[contact] `device`") && err.contains("\"cpu\""), "{err}");
        let typo = RUN.replace("modulus = \"composite\"", "device = \"gpu\"");
        let err = RunConfig::from_toml(&typo, Path::new(".")).unwrap_err().to_string();
        assert!(err.contains("device"), "{err}");
    }

    #[test]
    fn sliding_solves_stop_at_a_settled_map_unless_the_run_file_says_tolerance() {
        use crate::contact::Stopping;
        let default = RunConfig::from_toml(RUN, Path::new(".")).unwrap();
        assert_eq!(default.stopping, Stopping::SettledMap);
        // Single solves keep the tolerance; a sliding setup takes the run's rule.
        assert_eq!(default.solver.stopping(), Stopping::Tolerance);
        let sliding = default.sliding.clone().unwrap();
        assert_eq!(
            SlidingSetup::from_run(&default, &sliding).solver.stopping(),
            Stopping::SettledMap
        );
        assert_eq!(default.inputs().stopping, None);
        let tight = RunConfig::from_toml(&format!("{RUN}stopping = \"tolerance\"\n"), Path::new(".")).unwrap();
        assert_eq!(tight.stopping, Stopping::Tolerance);
        assert_eq!(tight.inputs().stopping, Some(Stopping::Tolerance));
        assert_eq!(
            SlidingSetup::from_run(&tight, &sliding).solver.stopping(),
            Stopping::Tolerance
        );
        assert_ne!(default.inputs(), tight.inputs());
        let err = RunConfig::from_toml(&format!("{RUN}stopping = \"loose\"\n"), Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(err.contains("stopping") && err.contains("settled-map"), "{err}");
    }

    #[test]
    fn a_free_boundary_is_for_contact_runs_only() {
        let contact_only = RUN.split("[sliding]").next().unwrap().to_string();
        let free = contact_only.replace("modulus = \"composite\"", "boundary = \"free\"");
        assert_eq!(
            RunConfig::from_toml(&free, Path::new(".")).unwrap().boundary,
            Boundary::Free
        );
        let err = RunConfig::from_toml(&format!("{free}[sliding]\nloads = [1e-3]\n"), Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(err.contains("boundary") && err.contains("periodic"), "{err}");
        let bad = contact_only.replace("modulus = \"composite\"", "boundary = \"open\"");
        assert!(RunConfig::from_toml(&bad, Path::new(".")).is_err());
    }

    #[test]
    fn unknown_keys_are_named() {
        let e = RunConfig::from_toml(&RUN.replace("hurst", "hurts"), Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(e.contains("hurts"), "{e}");
        let e = RunConfig::from_toml(&RUN.replace("loads = [1e-3]", "loads = []"), Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(e.contains("loads"), "{e}");
        let e = RunConfig::from_toml(&RUN.replace("0.3", "0.7"), Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(e.contains("poisson_ratio"), "{e}");
    }
}

#[cfg(test)]
mod builder_tests {
    use super::*;

    const RUN: &str = "[surface]\ngrid = 64\nlambda_lower = 0.125\nlambda_upper = 0.25\nrms_height = 0.005\n\
                       [material]\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.01\n\
                       fracture_energies = [0.5e-6]\n[sliding]\nloads = [1e-3]\n";

    fn file(text: &str) -> Result<RunConfig> {
        RunConfig::from_toml(text, Path::new("."))
    }

    #[test]
    fn a_built_run_is_the_run_file_it_describes() {
        let read = file(RUN).unwrap();
        let built = RunConfig::builder(read.surfaces.clone(), read.material.clone())
            .sliding(read.sliding.clone().unwrap())
            .build()
            .unwrap();
        assert_eq!(built, read);
        assert_eq!(read.to_builder().build().unwrap(), read);
    }

    #[test]
    fn a_built_run_with_a_bad_setting_fails_as_the_run_file_does() {
        let read = file(RUN).unwrap();
        let builder = || read.to_builder();
        let contact = |line: &str| RUN.replace("[sliding]", &format!("[contact]\n{line}\n[sliding]"));
        let sliding = |line: &str| format!("{RUN}{line}\n");
        let overloaded = RUN.replace("loads = [1e-3]", "loads = [1.0]");
        let cases: Vec<(Result<RunConfig>, Result<RunConfig>)> = vec![
            (builder().connectivity(6).build(), file(&contact("connectivity = 6"))),
            (
                builder().boundary(Boundary::Free).build(),
                file(&contact("boundary = \"free\"")),
            ),
            (
                builder().estimate_samples(Some(0)).build(),
                file(&sliding("estimate_samples = 0")),
            ),
            (
                builder()
                    .sliding(SlidingConfig::new(vec![1.0], DEFAULT_DISTANCE, DEFAULT_RUNNING_IN, 4, 1, None).unwrap())
                    .build(),
                file(&overloaded),
            ),
            (
                builder()
                    .sliding(SlidingConfig::new(vec![1e-3], DEFAULT_DISTANCE, DEFAULT_RUNNING_IN, 64, 1, None).unwrap())
                    .build(),
                file(&sliding("step_running_in = 64")),
            ),
        ];
        for (built, read) in cases {
            let (built, read) = (built.unwrap_err(), read.unwrap_err());
            assert_eq!(
                std::mem::discriminant(&built),
                std::mem::discriminant(&read),
                "{built} / {read}"
            );
            assert_eq!(built.to_string(), read.to_string());
        }
    }

    #[test]
    fn hardness_yield_strength_toughness_and_pressures_are_converted_with_their_formula() {
        let si = "units = \"si\"\n[surface]\ngrid = 64\nlength = 1e-4\nlambda_lower = 6.25e-6\nlambda_upper = 2.5e-5\n\
                  rms_height = 5e-7\n[material]\nyoungs_modulus = 300e9\npoisson_ratio = 0.25\n";
        let read = |extra: &str| RunConfig::from_toml(&format!("{si}{extra}"), Path::new("."));
        let by_tau = read("shear_strength = 3e9\nfracture_energies = [10.0]\n[sliding]\nloads = [1.0]\n").unwrap();
        assert!(by_tau.conversions.is_empty());
        // H = 3√3 τ̃, σ_y = √3 τ̃, K_Ic = √(𝒢 E/(1 − ν²)), F_N = p_N Lx·Ly: the same run.
        let (h, y) = (3.0 * 3f64.sqrt() * 3e9, 3f64.sqrt() * 3e9);
        let k = (10.0f64 * 300e9 / (1.0 - 0.25 * 0.25)).sqrt();
        for extra in [
            format!("hardness = {h:e}\nfracture_toughness = [{k:e}]\n[sliding]\npressures = [1e8]\n"),
            format!("yield_strength = {y:e}\nfracture_toughness = [{k:e}]\n[sliding]\nloads = [1.0]\n"),
        ] {
            let c = read(&extra).unwrap();
            let m = &c.material;
            assert!((m.shear_strength / 3e9 - 1.0).abs() < 1e-12, "{extra}");
            assert!((m.fracture_energies[0] / 10.0 - 1.0).abs() < 1e-12, "{extra}");
            assert!((c.sliding.as_ref().unwrap().loads[0] - 1.0).abs() < 1e-12, "{extra}");
            assert_eq!(c.inputs(), by_tau.inputs(), "{extra}");
            assert_eq!(c.conversions.len(), if extra.contains("pressures") { 3 } else { 2 });
        }
        let c = read(&format!(
            "hardness = {h:e}\nfracture_toughness = [{k:e}]\n[sliding]\npressures = [1e8]\n"
        ))
        .unwrap();
        let notes = c.conversions.join("\n");
        assert!(
            notes.contains("τ̃ = H/(3√3)") && notes.contains("τ̃ = 3.0000e9 Pa"),
            "{notes}"
        );
        assert!(
            notes.contains("𝒢 = K_Ic²(1 − ν²)/E") && notes.contains("1.0000e1 J/m²"),
            "{notes}"
        );
        assert!(notes.contains("F_N = p_N Lx·Ly = 1.0000e0 N"), "{notes}");
        // Two forms of one input, none, or a bad alternative: refused by name.
        let e = read("shear_strength = 3e9\nhardness = 1e10\n").unwrap_err().to_string();
        assert!(
            e.contains("`shear_strength` and `hardness`") && e.contains("keep one"),
            "{e}"
        );
        let e = read("fracture_energies = [1.0]\n").unwrap_err().to_string();
        assert!(e.contains("`hardness`") && e.contains("`yield_strength`"), "{e}");
        let e = read("hardness = -1.0\n").unwrap_err().to_string();
        assert!(e.contains("hardness"), "{e}");
        let e = read("shear_strength = 3e9\nfracture_energies = [1.0]\nfracture_toughness = [1e6]\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("`fracture_toughness`") && e.contains("keep one"), "{e}");
        let e = read("shear_strength = 3e9\n[sliding]\nloads = [1.0]\npressures = [1e8]\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("`pressures`") && e.contains("keep one"), "{e}");
        let e = read("shear_strength = 3e9\n[sliding]\ndistance = 1.0\n")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("`loads` is missing") && e.contains("`pressures`") && e.contains("(Pa)"),
            "{e}"
        );
        let e = read("shear_strength = 3e9\n[sliding]\npressures = [0.0]\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("pressures"), "{e}");
    }

    #[test]
    fn an_imported_map_gives_the_box_and_the_spectrums_box_is_at_its_pixel_size() {
        let dir = tempfile::tempdir().unwrap();
        let (nx, ny, pixel) = (16usize, 8usize, 2e-6);
        let heights: Vec<f64> = (0..nx * ny).map(|i| 1e-7 * ((i * 7919) % 13) as f64).collect();
        crate::io::write_npy_f64(&dir.path().join("heights.npy"), nx, ny, &heights).unwrap();
        crate::io::write_npy_f64(&dir.path().join("bottom.npy"), nx, ny, &heights).unwrap();
        let record = serde_json::json!({
            "written_by": "wearsim surface import",
            "heights_grid": [nx, ny],
            "length": [nx as f64 * pixel, ny as f64 * pixel],
            "bodies": {"top": {"file": "heights.npy"}, "bottom": {"file": "bottom.npy"}},
        });
        // Another array of the same shape in the folder is not the imported map.
        crate::io::write_npy_f64(&dir.path().join("filtered.npy"), nx, ny, &heights).unwrap();
        let other = "units = \"si\"\n[surface]\ntop = \"filtered.npy\"\nbottom = \"bottom.npy\"\n[material]\n\
                     youngs_modulus = 300e9\npoisson_ratio = 0.25\nshear_strength = 3e9\n";
        std::fs::write(dir.path().join("import.json"), record.to_string()).unwrap();
        let e = RunConfig::from_toml(other, dir.path()).unwrap_err().to_string();
        assert!(e.contains("`length` is missing"), "{e}");
        let material = "[material]\nyoungs_modulus = 300e9\npoisson_ratio = 0.25\nshear_strength = 3e9\n";
        let files = format!("units = \"si\"\n[surface]\ntop = \"heights.npy\"\nbottom = \"bottom.npy\"\n{material}");
        let c = RunConfig::from_toml(&format!("{files}[sliding]\npressures = [1e8]\n"), dir.path()).unwrap();
        let SurfaceSource::Files { length, length_y, .. } = &c.surfaces else {
            panic!("{:?}", c.surfaces)
        };
        assert_eq!((*length, *length_y), (nx as f64 * pixel, Some(ny as f64 * pixel)));
        let load = c.sliding.as_ref().unwrap().loads[0];
        assert!((load / (1e8 * 32e-6 * 16e-6) - 1.0).abs() < 1e-12, "{load}");
        assert!(c.conversions[0].contains("its import.json"), "{:?}", c.conversions);
        // A record of another grid, or a run in reduced units: the length is needed.
        let e = RunConfig::from_toml(&files.replace("\"si\"", "\"reduced\""), dir.path())
            .unwrap_err()
            .to_string();
        assert!(e.contains("`length` is missing"), "{e}");
        // The spectrum route: map_length from the record, the box of `grid` pixels at the map's size.
        let spectrum =
            format!("units = \"si\"\n[surface]\nsource = \"spectrum\"\nmap = \"heights.npy\"\ngrid = 32\n{material}");
        let c = RunConfig::from_toml(&spectrum, dir.path()).unwrap();
        let SurfaceSource::Spectrum { grid, map_length, .. } = &c.surfaces else {
            panic!("{:?}", c.surfaces)
        };
        assert_eq!(*map_length, nx as f64 * pixel);
        assert!((grid.pixel_size() / pixel - 1.0).abs() < 1e-12 && grid.nx() == 32 && grid.is_square());
        assert!(
            c.conversions
                .iter()
                .any(|n| n.contains("the box at the map's pixel size")),
            "{:?}",
            c.conversions
        );
        let record = serde_json::json!({"written_by": "wearsim surface import", "heights_grid": [nx, 2 * ny], "length": [1.0, 1.0]});
        std::fs::write(dir.path().join("import.json"), record.to_string()).unwrap();
        let e = RunConfig::from_toml(&files, dir.path()).unwrap_err().to_string();
        assert!(e.contains("`length` is missing"), "{e}");
    }
}
