//! One sliding run, from a validated [`RunConfig`] (a run file, or one built in memory) to its
//! results: the single path that `wearsim slide`, `wearsim bench-slide`, the Python `RunFile.slide`
//! and `slide`, and every study job take, so that they differ only in how they show the results.
//!
//! Two steps. [`SlidingRun::prepare`] makes the surfaces (generated, or read and prepared from
//! files; [`SlidingRun::with_surfaces`] takes arrays the caller holds), the [`SlidingSetup`] and
//! every warning known before the run: the run file's (λ_l of a few pixels), the surfaces' (a
//! measured map far from periodic) and d* against the pixel size. [`SlidingRun::run`] (or
//! [`SlidingRun::run_resumable`], with a checkpoint file) slides every load of the schedule (paper
//! §3), an observer seeing each step (progress, fields); the [`SlidingOutcome`] holds the runs, every
//! warning once, in a stable order (inputs, surfaces, resolution, then each load's results), and
//! the elapsed time, and gives the series and the summary.

use std::time::Instant;

use serde_json::Value;

use crate::config::{RunConfig, SurfacePair, SurfaceSource};
use crate::error::{Error, Interrupt, Result};
use crate::grid::Grid;
use crate::output::{series_csv, series_rows, sliding_summary, SeriesRow, SlidingInputs};
use crate::sliding::{
    resolution_warnings, run_sliding_resumable, Checkpointing, LoadRun, Resumed, SlidingConfig, SlidingSetup, StepView,
};

/// A sliding run ready to start: its surfaces, its setup and the warnings known before it runs.
#[derive(Debug)]
pub struct SlidingRun<'a> {
    config: &'a RunConfig,
    sliding: &'a SlidingConfig,
    pair: SurfacePair,
    setup: SlidingSetup<'a>,
    warnings: Vec<String>,
    surfaces_seconds: f64,
}

/// Every distinct warning once, in the order first given.
fn distinct(warnings: impl IntoIterator<Item = String>) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for w in warnings {
        if !out.contains(&w) {
            out.push(w);
        }
    }
    out
}

impl<'a> SlidingRun<'a> {
    /// The run `config` describes, with its surfaces generated or read from its files.
    pub fn prepare(config: &'a RunConfig) -> Result<Self> {
        schedule_of(config)?;
        let start = Instant::now();
        let pair = config.surface_pair()?;
        let mut run = Self::with_surfaces(config, pair)?;
        run.surfaces_seconds = start.elapsed().as_secs_f64();
        Ok(run)
    }

    /// The run `config` describes on surfaces the caller made (arrays handed over, see
    /// [`SurfacePair::of_arrays`]); where `config` fixes the grid, the surfaces must lie on it.
    pub fn with_surfaces(config: &'a RunConfig, pair: SurfacePair) -> Result<Self> {
        let sliding = schedule_of(config)?;
        let grid = pair.top.grid();
        if let SurfaceSource::Generated { grid: expected, .. } | SurfaceSource::Arrays { grid: expected, .. } =
            &config.surfaces
        {
            if grid != *expected {
                return Err(Error::param(
                    "surface",
                    format!(
                        "the surfaces' grid, {} × {} pixels of {:e}, differs from the run's, {} × {} pixels of {:e}",
                        grid.nx(),
                        grid.ny(),
                        grid.pixel_size(),
                        expected.nx(),
                        expected.ny(),
                        expected.pixel_size()
                    ),
                ));
            }
        }
        sliding.check_grid(grid.nx())?;
        let warnings = distinct(
            config
                .warnings()
                .into_iter()
                .chain(pair.warnings.iter().cloned())
                .chain(resolution_warnings(&config.material, grid.pixel_size())),
        );
        Ok(Self {
            config,
            sliding,
            setup: SlidingSetup::from_run(config, sliding),
            pair,
            warnings,
            surfaces_seconds: 0.0,
        })
    }

    /// The run stops with [`Error::Interrupted`] once `interrupt` is raised.
    pub fn interrupted_by(mut self, interrupt: &Interrupt) -> Self {
        self.setup.interrupt = interrupt.clone();
        self
    }

    /// The run's inputs.
    pub fn config(&self) -> &'a RunConfig {
        self.config
    }

    /// The run's schedule.
    pub fn sliding(&self) -> &'a SlidingConfig {
        self.sliding
    }

    /// The surfaces, with the notes on how files were read.
    pub fn surfaces(&self) -> &SurfacePair {
        &self.pair
    }

    /// Everything the sliding loop is given besides the surfaces.
    pub fn setup(&self) -> &SlidingSetup<'a> {
        &self.setup
    }

    /// The grid of the surfaces.
    pub fn grid(&self) -> Grid {
        self.pair.top.grid()
    }

    /// The sliding offsets of each load in pixels (paper §3).
    pub fn offsets(&self) -> Vec<usize> {
        self.sliding.offsets(self.grid().nx())
    }

    /// Steps of every load together.
    pub fn total_steps(&self) -> usize {
        self.offsets().len() * self.sliding.loads.len()
    }

    /// What the run is given, as its outputs record it (the summary's and the fields store's
    /// `inputs`).
    pub fn inputs(&self) -> SlidingInputs<'a> {
        SlidingInputs::of_run(self.config, self.sliding)
    }

    /// The warnings known before the run: the run file's, the surfaces', and d* against the pixel
    /// size.
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }

    /// Slides every load; `observe` sees each step (progress bars, fields, animations) but cannot
    /// change the run.
    pub fn run(self, observe: impl FnMut(&StepView)) -> Result<SlidingOutcome<'a>> {
        self.run_resumable(None, |_| {}, observe)
    }

    /// [`SlidingRun::run`] saving its state as `checkpointing` says and resuming from a checkpoint
    /// of the same run ([`run_sliding_resumable`]); `on_resume` is told what became of the file.
    pub fn run_resumable(
        self,
        checkpointing: Option<&Checkpointing>,
        on_resume: impl FnMut(&Resumed),
        observe: impl FnMut(&StepView),
    ) -> Result<SlidingOutcome<'a>> {
        let start = Instant::now();
        let runs = run_sliding_resumable(
            &self.pair.top,
            &self.pair.bottom,
            &self.setup,
            checkpointing,
            on_resume,
            observe,
        )?;
        let seconds = self.surfaces_seconds + start.elapsed().as_secs_f64();
        let steps_per_load = self.offsets().len();
        let warnings = distinct(
            self.warnings
                .into_iter()
                .chain(runs.iter().flat_map(|r| r.warnings.iter().cloned())),
        );
        Ok(SlidingOutcome {
            config: self.config,
            sliding: self.sliding,
            runs,
            warnings,
            seconds,
            steps_per_load,
        })
    }
}

/// The schedule of a run, or an error saying that sliding needs one.
fn schedule_of(config: &RunConfig) -> Result<&SlidingConfig> {
    config
        .sliding
        .as_ref()
        .ok_or_else(|| Error::run_file("a [sliding] table with `loads` is needed for a sliding run"))
}

/// What a sliding run gives: one [`LoadRun`] per load, every warning and the time taken.
#[derive(Debug, Clone)]
pub struct SlidingOutcome<'a> {
    config: &'a RunConfig,
    sliding: &'a SlidingConfig,
    /// Per load, in the schedule's order: its steps, results per fracture energy and warnings.
    pub runs: Vec<LoadRun>,
    /// Every warning of the run once: its inputs', its surfaces', d* against the pixel size, then
    /// each load's results'.
    pub warnings: Vec<String>,
    /// Wall time of the run in seconds, making the surfaces included.
    pub seconds: f64,
    /// Steps of each load.
    pub steps_per_load: usize,
}

impl SlidingOutcome<'_> {
    /// The series: one row per load, fracture energy and step.
    pub fn series_rows(&self) -> Vec<SeriesRow> {
        series_rows(&self.runs)
    }

    /// `series.csv`.
    pub fn series_csv(&self) -> String {
        series_csv(&self.runs)
    }

    /// `summary.json`: provenance, inputs, results per load and fracture energy, the warnings.
    pub fn summary(&self) -> Value {
        sliding_summary(
            &SlidingInputs::of_run(self.config, self.sliding),
            &self.runs,
            &self.warnings,
            self.seconds,
            self.steps_per_load,
        )
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::surface::Surface;

    const RUN: &str = "[surface]\ngrid = 32\nlambda_lower = 0.125\nlambda_upper = 0.5\nrms_height = 0.01\nseed = 3\n\
                       [material]\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.01\n\
                       fracture_energies = [0.25e-6]\n[sliding]\nloads = [2e-3, 4e-3]\n";

    #[test]
    fn a_run_file_runs_to_its_series_summary_and_warnings() {
        let config = RunConfig::from_toml(RUN, Path::new(".")).unwrap();
        let run = SlidingRun::prepare(&config).unwrap();
        assert_eq!(run.total_steps(), 2 * run.offsets().len());
        let before = run.warnings().to_vec();
        let mut seen = 0;
        let outcome = run.run(|view| seen = view.done).unwrap();
        assert_eq!(seen, 2 * outcome.steps_per_load);
        assert_eq!(outcome.runs.len(), 2);
        // The warnings before the run come first, then each load's, each once.
        assert_eq!(&outcome.warnings[..before.len()], &before[..]);
        let loads: Vec<String> = outcome.runs.iter().flat_map(|r| r.warnings.clone()).collect();
        assert!(loads.iter().all(|w| outcome.warnings.contains(w)));
        let summary = outcome.summary();
        assert_eq!(summary["warnings"], serde_json::json!(outcome.warnings));
        assert_eq!(summary["results"].as_array().unwrap().len(), 2);
        assert_eq!(outcome.series_csv().lines().count(), 1 + 2 * outcome.steps_per_load);
    }

    #[test]
    fn arrays_run_in_memory_with_their_periodicity_warnings() {
        let config = RunConfig::from_toml(RUN, Path::new(".")).unwrap();
        let (top, bottom) = config.surfaces().unwrap();
        // A step across the border of the top surface: not periodic.
        let grid = top.grid();
        let stepped: Vec<f64> = top
            .heights()
            .iter()
            .enumerate()
            .map(|(k, h)| h + if k / grid.ny() < grid.nx() / 2 { 0.0 } else { 0.05 })
            .collect();
        let top = Surface::new("top", grid, stepped).unwrap();
        let arrays = RunConfig {
            surfaces: SurfaceSource::Arrays { grid, length: 1.0 },
            ..config.clone()
        };
        let run = SlidingRun::with_surfaces(&arrays, SurfacePair::of_arrays(top, bottom.clone())).unwrap();
        assert!(
            run.warnings().iter().any(|w| w.starts_with("top is not periodic")),
            "{:?}",
            run.warnings()
        );
        let summary = run.run(|_| {}).unwrap().summary();
        assert_eq!(summary["inputs"]["surfaces"]["source"], "arrays");
        assert!(summary["warnings"][0]
            .as_str()
            .unwrap()
            .starts_with("top is not periodic"));
        // Surfaces off the run's grid are refused.
        let spectrum = crate::surface::SpectrumParams::paper_roughness(64, 1.0);
        let other = Surface::generate(Grid::square(64, 1.0).unwrap(), &spectrum, 1).unwrap();
        let e = SlidingRun::with_surfaces(&arrays, SurfacePair::of_arrays(other.clone(), other)).unwrap_err();
        assert!(e.to_string().contains("grid"), "{e}");
    }

    #[test]
    fn a_run_without_a_schedule_is_refused_before_its_surfaces_are_made() {
        let config = RunConfig::from_toml(RUN.split("[sliding]").next().unwrap(), Path::new(".")).unwrap();
        let e = SlidingRun::prepare(&config).unwrap_err().to_string();
        assert!(e.contains("[sliding]"), "{e}");
    }

    #[test]
    fn warnings_are_kept_once_in_their_first_place() {
        let w = |s: &[&str]| s.iter().map(|x| x.to_string()).collect::<Vec<_>>();
        assert_eq!(distinct(w(&["a", "b", "a", "c", "b"])), w(&["a", "b", "c"]));
    }
}
