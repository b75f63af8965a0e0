//! Run files: TOML parsed strictly (unknown keys are errors naming the key) and turned
//! into a validated [`RunConfig`] before any work starts.

use std::path::{Path, PathBuf};

use serde::Deserialize;

use crate::check::{connectivity as check_connectivity, positive};
use crate::contact::SolverOptions;
use crate::error::{Error, Result};
use crate::io::{parent_or_dot, read_text};
use crate::material::{Material, ModulusConvention};
use crate::surface::{pair_seeds, Generation, SpectrumParams, Surface};

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
struct RawRun {
    #[serde(default)]
    units: Units,
    surface: RawSurface,
    material: RawMaterial,
    #[serde(default)]
    contact: RawContact,
    sliding: Option<RawSliding>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSurface {
    grid: Option<usize>,
    length: Option<f64>,
    hurst: Option<f64>,
    lambda_lower: Option<f64>,
    lambda_upper: Option<f64>,
    rms_height: Option<f64>,
    seed: Option<u64>,
    generation: Option<Generation>,
    top: Option<PathBuf>,
    bottom: Option<PathBuf>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMaterial {
    youngs_modulus: f64,
    poisson_ratio: f64,
    shear_strength: f64,
    #[serde(default)]
    fracture_energies: Vec<f64>,
    geometry_factor: Option<f64>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawContact {
    modulus: Option<ModulusConvention>,
    tolerance: Option<f64>,
    max_iterations: Option<usize>,
    connectivity: Option<u8>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSliding {
    loads: Vec<f64>,
    distance: Option<f64>,
    running_in: Option<f64>,
    step_running_in: Option<usize>,
    step: Option<usize>,
}

/// Where the two surfaces come from.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[serde(tag = "source", rename_all = "lowercase")]
pub enum SurfaceSource {
    /// Generated from spectral parameters and one seed (top and bottom seeds derived from it).
    Generated {
        grid: usize,
        length: f64,
        spectrum: SpectrumParams,
        seed: u64,
    },
    /// Read from `.npy` files (paths resolved against the run file's folder).
    Files { top: PathBuf, bottom: PathBuf, length: f64 },
}

/// The sliding schedule (paper §3); distances as fractions of L, steps in pixels.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SlidingConfig {
    /// Normal loads F_N (E·L² reduced, N in SI).
    pub loads: Vec<f64>,
    /// Total sliding distance as a fraction of L (default ½).
    pub distance: f64,
    /// Running-in distance as a fraction of L (default ¼).
    pub running_in: f64,
    /// Step during running-in, in pixels (default 4).
    pub step_running_in: usize,
    /// Step after running-in, in pixels (default 1).
    pub step: usize,
}

impl SlidingConfig {
    /// A validated schedule; `grid`, when known, bounds the steps and must leave at least two steps
    /// after running-in ([`SlidingConfig::check_grid`]).
    pub fn new(
        loads: Vec<f64>,
        distance: f64,
        running_in: f64,
        step_running_in: usize,
        step: usize,
        grid: Option<usize>,
    ) -> Result<Self> {
        if loads.is_empty() {
            return Err(Error::param(
                "loads",
                "the list is empty; give at least one normal load",
            ));
        }
        for &f in &loads {
            positive("loads", f)?;
        }
        if !(distance > 0.0 && distance <= 1.0) {
            return Err(Error::param(
                "distance",
                format!("{distance} must lie in (0, 1] (a fraction of L)"),
            ));
        }
        if !(running_in >= 0.0 && running_in < distance) {
            return Err(Error::param(
                "running_in",
                format!("{running_in} must lie in [0, distance = {distance}) (a fraction of L)"),
            ));
        }
        for (field, v) in [("step_running_in", step_running_in), ("step", step)] {
            if v == 0 {
                return Err(Error::param(field, format!("{v} pixels must be at least 1")));
            }
        }
        let config = Self {
            loads,
            distance,
            running_in,
            step_running_in,
            step,
        };
        if let Some(n) = grid {
            config.check_grid(n)?;
        }
        Ok(config)
    }

    /// Sliding offsets in pixels on an `n`-pixel grid (paper §3): from 0 in steps of
    /// `step_running_in` while below the running-in distance, then from the running-in distance in
    /// steps of `step` while below the total distance (the end point excluded). Distances are
    /// rounded to whole pixels. The paper's schedule gives 1,280 offsets at N = 4096.
    pub fn offsets(&self, n: usize) -> Vec<usize> {
        let (running_in, distance) = (self.running_in_pixels(n), self.distance_pixels(n));
        let mut offsets: Vec<usize> = (0..running_in).step_by(self.step_running_in).collect();
        offsets.extend((running_in..distance).step_by(self.step));
        offsets
    }

    /// The running-in distance in whole pixels.
    pub fn running_in_pixels(&self, n: usize) -> usize {
        (self.running_in * n as f64).round() as usize
    }

    fn distance_pixels(&self, n: usize) -> usize {
        (self.distance * n as f64).round() as usize
    }

    /// Checks the schedule on an `n`-pixel grid: steps below the grid size, and at least two steps
    /// after running-in, the fewest a wear rate can be fitted to.
    pub fn check_grid(&self, n: usize) -> Result<()> {
        for (field, step) in [("step_running_in", self.step_running_in), ("step", self.step)] {
            if step >= n {
                return Err(Error::param(
                    field,
                    format!("{step} pixels must be below the grid size {n}"),
                ));
            }
        }
        let fitted = (self.running_in_pixels(n)..self.distance_pixels(n))
            .step_by(self.step)
            .count();
        if fitted < 2 {
            return Err(Error::param(
                "distance",
                format!(
                    "{} − running_in {} leaves {fitted} step(s) of {} px on the {n}-pixel grid after running-in; the \
                     wear rate is a line fitted to at least two: raise `distance`, lower `running_in` or `step`, or \
                     refine `grid`",
                    self.distance, self.running_in, self.step
                ),
            ));
        }
        Ok(())
    }
}

/// Whether the surface files a run names must exist when it is read: for a run about to be
/// computed they must; a finished study's stored runs are read back without them (its results are
/// collected without the surfaces).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SurfaceFiles {
    MustExist,
    Recorded,
}

/// A validated run file.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct RunConfig {
    pub units: Units,
    pub surfaces: SurfaceSource,
    pub material: Material,
    pub modulus: ModulusConvention,
    pub solver: SolverOptions,
    /// Junction connectivity, 4 or 8.
    pub connectivity: u8,
    pub sliding: Option<SlidingConfig>,
}

fn missing(field: &str, hint: &str) -> Error {
    Error::run_file(format!("[surface] `{field}` is missing; {hint}"))
}

/// A TOML error message on one line (they come with a source excerpt over several lines).
fn one_line(message: &str) -> String {
    message.trim_end().replace('\n', " ")
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
        let s = raw.surface;
        let surfaces = match (&s.top, &s.bottom) {
            (Some(top), Some(bottom)) => {
                for (field, value) in [
                    ("grid", s.grid.is_some()),
                    ("hurst", s.hurst.is_some()),
                    ("lambda_lower", s.lambda_lower.is_some()),
                    ("lambda_upper", s.lambda_upper.is_some()),
                    ("rms_height", s.rms_height.is_some()),
                    ("seed", s.seed.is_some()),
                ] {
                    if value {
                        return Err(Error::run_file(format!(
                            "[surface] `{field}` has no meaning when `top` and `bottom` are read from files; remove it"
                        )));
                    }
                }
                let length = s
                    .length
                    .ok_or_else(|| missing("length", "give the physical side length of the files"))?;
                positive("length", length)?;
                let (top, bottom) = (base.join(top), base.join(bottom));
                for p in [&top, &bottom] {
                    if files == SurfaceFiles::MustExist && !p.is_file() {
                        return Err(Error::file(
                            p,
                            "surface file not found (paths are relative to the run file)",
                        ));
                    }
                }
                SurfaceSource::Files { top, bottom, length }
            }
            (None, None) => {
                let grid = s
                    .grid
                    .ok_or_else(|| missing("grid", "give the number of pixels per side, e.g. 512"))?;
                let length = s.length.unwrap_or(1.0);
                let spectrum = SpectrumParams {
                    hurst: s.hurst.unwrap_or(0.7),
                    lambda_lower: s
                        .lambda_lower
                        .ok_or_else(|| missing("lambda_lower", "e.g. 16 pixels, 16·length/grid"))?,
                    lambda_upper: s
                        .lambda_upper
                        .ok_or_else(|| missing("lambda_upper", "e.g. length/16"))?,
                    rms_height: s.rms_height.ok_or_else(|| missing("rms_height", "e.g. 0.005·length"))?,
                    generation: s.generation.unwrap_or_default(),
                };
                spectrum.validate(grid, length)?;
                SurfaceSource::Generated {
                    grid,
                    length,
                    spectrum,
                    seed: s.seed.unwrap_or(0),
                }
            }
            _ => {
                return Err(Error::run_file(
                    "[surface] give both `top` and `bottom` files, or neither (to generate the surfaces)",
                ))
            }
        };
        let m = raw.material;
        let material = Material::new(
            m.youngs_modulus,
            m.poisson_ratio,
            m.shear_strength,
            m.fracture_energies,
            m.geometry_factor.unwrap_or(3.0),
        )?;
        let c = raw.contact;
        let defaults = SolverOptions::default();
        let solver = SolverOptions::new(
            c.tolerance.unwrap_or(defaults.tolerance()),
            c.max_iterations.unwrap_or(defaults.max_iterations()),
        )?;
        let connectivity = c.connectivity.unwrap_or(4);
        check_connectivity(connectivity)?;
        let sliding = match raw.sliding {
            None => None,
            Some(sl) => {
                let grid = match &surfaces {
                    SurfaceSource::Generated { grid, .. } => Some(*grid),
                    SurfaceSource::Files { .. } => None,
                };
                Some(SlidingConfig::new(
                    sl.loads,
                    sl.distance.unwrap_or(0.5),
                    sl.running_in.unwrap_or(0.25),
                    sl.step_running_in.unwrap_or(4),
                    sl.step.unwrap_or(1),
                    grid,
                )?)
            }
        };
        if let Some(sl) = &sliding {
            let length = match &surfaces {
                SurfaceSource::Generated { length, .. } | SurfaceSource::Files { length, .. } => *length,
            };
            for &load in &sl.loads {
                crate::check::load(load, length * length, material.flow_pressure())?;
            }
        }
        Ok(Self {
            units: raw.units,
            surfaces,
            material,
            modulus: c.modulus.unwrap_or_default(),
            solver,
            connectivity,
            sliding,
        })
    }

    /// The top and bottom surfaces: generated (seeds derived from the run's seed) or read.
    pub fn surfaces(&self) -> Result<(Surface, Surface)> {
        match &self.surfaces {
            SurfaceSource::Generated {
                grid,
                length,
                spectrum,
                seed,
            } => {
                crate::check::memory("generating the surface pair", *grid, crate::check::SURFACE_ARRAYS)?;
                let (top_seed, bottom_seed) = pair_seeds(*seed);
                let (top, bottom) = rayon::join(
                    || Surface::generate(*grid, *length, spectrum, top_seed),
                    || Surface::generate(*grid, *length, spectrum, bottom_seed),
                );
                Ok((top?, bottom?))
            }
            SurfaceSource::Files { top, bottom, length } => {
                let t = Surface::read_npy(top, *length)?;
                let b = Surface::read_npy(bottom, *length)?;
                if t.n() != b.n() {
                    return Err(Error::InvalidSurface {
                        name: bottom.display().to_string(),
                        message: format!("grid {}² differs from the top surface's {}²", b.n(), t.n()),
                    });
                }
                Ok((t, b))
            }
        }
    }

    /// Grid size N: the generated grid, or that of the top surface file (read from its header).
    pub fn grid(&self) -> Result<usize> {
        match &self.surfaces {
            SurfaceSource::Generated { grid, .. } => Ok(*grid),
            SurfaceSource::Files { top, length, .. } => match crate::io::npy_shape(top, "a height map")? {
                (rows, cols) if rows == cols && crate::check::grid(rows).is_ok() => Ok(rows),
                // Reading the file says precisely what is wrong with it.
                _ => Surface::read_npy(top, *length).map(|s| s.n()),
            },
        }
    }

    /// What makes this run under-resolved before it starts: a shortest wavelength λ_l of fewer than
    /// four pixels (the paper uses 16, appendix A). One sentence each.
    pub fn warnings(&self) -> Vec<String> {
        let mut out = Vec::new();
        if let SurfaceSource::Generated {
            grid, length, spectrum, ..
        } = &self.surfaces
        {
            let pixels = spectrum.lambda_lower / (length / *grid as f64);
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

    /// Side length L of the surfaces, in the run's length unit.
    pub fn length(&self) -> f64 {
        match &self.surfaces {
            SurfaceSource::Generated { length, .. } | SurfaceSource::Files { length, .. } => *length,
        }
    }

    /// Effective modulus E* under the run's convention.
    pub fn effective_modulus(&self) -> f64 {
        self.material.effective_modulus(self.modulus)
    }

    /// Every input of the run as one flat record (the fracture energies and loads aside, which a
    /// results table has one row per).
    pub fn inputs(&self) -> InputRecord {
        let m = &self.material;
        let mut record = InputRecord {
            units: self.units,
            grid: None,
            length: self.length(),
            hurst: None,
            lambda_lower: None,
            lambda_upper: None,
            rms_height: None,
            seed: None,
            top: None,
            bottom: None,
            youngs_modulus: m.youngs_modulus,
            poisson_ratio: m.poisson_ratio,
            shear_strength: m.shear_strength,
            geometry_factor: m.geometry_factor,
            modulus: self.modulus,
            tolerance: self.solver.tolerance(),
            connectivity: self.connectivity,
            distance: self.sliding.as_ref().map(|s| s.distance),
            running_in: self.sliding.as_ref().map(|s| s.running_in),
            step_running_in: self.sliding.as_ref().map(|s| s.step_running_in),
            step: self.sliding.as_ref().map(|s| s.step),
        };
        match &self.surfaces {
            SurfaceSource::Generated {
                grid, spectrum, seed, ..
            } => {
                record.grid = Some(*grid);
                record.hurst = Some(spectrum.hurst);
                record.lambda_lower = Some(spectrum.lambda_lower);
                record.lambda_upper = Some(spectrum.lambda_upper);
                record.rms_height = Some(spectrum.rms_height);
                record.seed = Some(*seed);
            }
            SurfaceSource::Files { top, bottom, .. } => {
                record.top = Some(top.display().to_string());
                record.bottom = Some(bottom.display().to_string());
            }
        }
        record
    }
}

/// Every input of a run as one flat record with the same fields for every run (absent ones empty):
/// the input columns of a study's results table, and what identifies a study job in its job file.
/// Field names are the run file's `section.key`.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, Deserialize)]
pub struct InputRecord {
    pub units: Units,
    #[serde(rename = "surface.grid")]
    pub grid: Option<usize>,
    #[serde(rename = "surface.length")]
    pub length: f64,
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
    #[serde(rename = "contact.connectivity")]
    pub connectivity: u8,
    #[serde(rename = "sliding.distance")]
    pub distance: Option<f64>,
    #[serde(rename = "sliding.running_in")]
    pub running_in: Option<f64>,
    #[serde(rename = "sliding.step_running_in")]
    pub step_running_in: Option<usize>,
    #[serde(rename = "sliding.step")]
    pub step: Option<usize>,
}

#[cfg(test)]
mod tests {
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
    }

    fn schedule(distance: f64, running_in: f64, step: usize) -> SlidingConfig {
        SlidingConfig {
            loads: vec![1e-3],
            distance,
            running_in,
            step_running_in: 4,
            step,
        }
    }

    #[test]
    fn paper_schedule_has_1280_offsets_at_4096_and_160_at_512() {
        let cfg = schedule(0.5, 0.25, 1);
        let s = cfg.offsets(4096);
        assert_eq!(s.len(), 1280);
        assert_eq!(&s[..3], &[0, 4, 8]);
        assert_eq!(s[255], 1020);
        assert_eq!(s[256], 1024);
        assert_eq!(*s.last().unwrap(), 2047);
        assert_eq!(cfg.offsets(512).len(), 160);
    }

    #[test]
    fn a_schedule_needs_two_steps_after_running_in() {
        assert!(schedule(0.5, 0.25, 1).check_grid(64).is_ok());
        // 64 px: running-in 16 px, distance 17 px → one fitted step.
        let e = schedule(0.27, 0.25, 1).check_grid(64).unwrap_err().to_string();
        assert!(e.contains("`distance`") && e.contains("1 step"), "{e}");
        assert!(schedule(0.5, 0.25, 64)
            .check_grid(64)
            .unwrap_err()
            .to_string()
            .contains("`step`"));
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
