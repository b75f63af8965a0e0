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
//! the elapsed time, and gives the series and the summary. Both are [`SlidingRun::start`] (the
//! set-up) followed by the steps of the [`Slide`] it gives (one at a time, with checkpoints between
//! them) and [`Slide::finish`]; a front end that needs the steps themselves (a benchmark) drives
//! the [`Slide`] itself.

use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

use serde_json::Value;

use crate::config::{RunConfig, SurfacePair, SurfaceSource};
use crate::cost::{IterationProbe, StepIterations};
use crate::error::{Error, Interrupt, Result};
use crate::estimate::{Calibration, Estimator, LoadEstimate, Sampling, MAX_SAMPLES, TARGET_SAMPLING_ERROR};
use crate::grid::Grid;
use crate::output::{
    distinct, estimate_rows, estimate_summary, series_csv, series_rows, sliding_summary, SeriesRow, SlidingInputs,
    Table,
};
use crate::sliding::{
    box_warnings, load_trend_warnings, resolution_warnings, Checkpointing, LoadRun, Resumed, SlidingConfig,
    SlidingSetup, SlidingState, StepView,
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

impl<'a> SlidingRun<'a> {
    /// The run `config` describes, with its surfaces generated or read from its files; refused
    /// before they are made when the run needs more memory than this process may use
    /// ([`check_memory`]).
    pub fn prepare(config: &'a RunConfig) -> Result<Self> {
        let sliding = sliding_schedule(config)?;
        check_memory(config.grid()?, sliding)?;
        let start = Instant::now();
        let pair = config.surface_pair()?;
        let mut run = Self::on_surfaces(config, sliding, pair)?;
        run.surfaces_seconds = start.elapsed().as_secs_f64();
        Ok(run)
    }

    /// The run `config` describes on surfaces the caller made (arrays handed over, see
    /// [`SurfacePair::of_arrays`]); where `config` fixes the grid, the surfaces must lie on it. The
    /// memory is checked as [`SlidingRun::prepare`] checks it, with the same message.
    pub fn with_surfaces(config: &'a RunConfig, pair: SurfacePair) -> Result<Self> {
        let sliding = sliding_schedule(config)?;
        check_memory(pair.top.grid(), sliding)?;
        Self::on_surfaces(config, sliding, pair)
    }

    /// The run of `config` and its schedule `sliding` on `pair`, its memory checked.
    fn on_surfaces(config: &'a RunConfig, sliding: &'a SlidingConfig, pair: SurfacePair) -> Result<Self> {
        let grid = pair.top.grid();
        if let SurfaceSource::Generated { grid: expected, .. }
        | SurfaceSource::Arrays { grid: expected, .. }
        | SurfaceSource::Spectrum { grid: expected, .. } = &config.surfaces
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
        let warnings = warnings_before_run(config, grid, &pair.warnings);
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

    /// The critical diameter d* of every fracture energy, also in pixels of the run's grid.
    pub fn critical_diameters(&self) -> Vec<crate::material::CriticalDiameter> {
        self.config.material.critical_diameters_on(self.grid().pixel_size())
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

    /// Sets the run up (the solver and its fields, the labeller): the state that takes its steps
    /// ([`Slide::step`]), saves and resumes checkpoints, and finishes into the outcome. Every
    /// front end slides through it.
    pub fn start(self) -> Result<Slide<'a>> {
        let start = Instant::now();
        let SurfacePair { top, bottom, .. } = self.pair;
        let state = SlidingState::new(top, bottom, self.setup)?;
        Ok(Slide {
            config: self.config,
            sliding: self.sliding,
            state,
            warnings: self.warnings,
            surfaces_seconds: self.surfaces_seconds,
            start,
        })
    }

    /// Slides every load; `observe` sees each step (progress bars, fields, animations) but cannot
    /// change the run.
    pub fn run(self, observe: impl FnMut(&mut StepView)) -> Result<SlidingOutcome<'a>> {
        self.run_resumable(None, |_| {}, observe)
    }

    /// [`SlidingRun::run`] saving its state as `checkpointing` says and resuming from a checkpoint
    /// of the same run ([`Slide::resume`]); `on_resume` is told what became of the file, of a
    /// checkpoint that could not be written (the run goes on to its results) and of the state saved
    /// when the run is stopped (a signal, a Slurm time limit: [`Error::Interrupted`]), which the same
    /// run resumes from. The caller removes the file once the results are written.
    pub fn run_resumable(
        self,
        checkpointing: Option<&Checkpointing>,
        mut on_resume: impl FnMut(&Resumed),
        mut observe: impl FnMut(&mut StepView),
    ) -> Result<SlidingOutcome<'a>> {
        let mut slide = self.start()?;
        let Some(c) = checkpointing else {
            on_resume(&Resumed::Fresh);
            while let Some(mut view) = slide.step()? {
                observe(&mut view);
            }
            return slide.finish();
        };
        slide.keep_state_for_stops();
        on_resume(&slide.resume(&c.path));
        let mut saved_done = slide.done();
        let mut last_save = Instant::now();
        loop {
            let stepped = slide.step().map(|view| view.map(|mut v| observe(&mut v)).is_some());
            match stepped {
                Ok(true) => {}
                Ok(false) => break,
                Err(Error::Interrupted) => {
                    if slide.done() > saved_done {
                        on_resume(&match slide.save_checkpoint(&c.path) {
                            Ok(_) => Resumed::Saved {
                                done: slide.done(),
                                total: slide.total(),
                            },
                            Err(e) => Resumed::NotSaved(e.to_string()),
                        });
                    }
                    return Err(Error::Interrupted);
                }
                Err(e) => return Err(e),
            }
            if slide.done() < slide.total() && last_save.elapsed() >= c.every {
                match slide.save_checkpoint(&c.path) {
                    Ok(_) => saved_done = slide.done(),
                    Err(e) => on_resume(&Resumed::NotSaved(format!(
                        "{e}; the run goes on, but a kill now would lose the steps since the last checkpoint"
                    ))),
                }
                last_save = Instant::now();
            }
        }
        slide.finish()
    }
}

/// Steps of each warm kind an [`IterationProbe`] solves.
pub const PROBE_STEPS: usize = 3;

impl<'a> SlidingRun<'a> {
    /// The iterations of this run's steps measured on its own surfaces, for its cost estimate
    /// ([`crate::cost::Calibration::estimate_measured`]): at the heaviest load, the cold first step
    /// and [`PROBE_STEPS`] steps of each of the schedule's kinds (`step_running_in`, then `step`),
    /// solved as the run solves them (its stopping rule, warm-started from the step before). About
    /// 2 + 2·[`PROBE_STEPS`] sliding steps' worth of solver work: a few steps of the run's hundreds.
    pub fn probe_iterations(&self) -> Result<IterationProbe> {
        let start = Instant::now();
        let nx = self.grid().nx();
        let load = self.sliding.loads.iter().copied().fold(f64::MIN, f64::max);
        let (coarse, fine) = (self.sliding.step_running_in, self.sliding.step);
        let running_in = (PROBE_STEPS * coarse) as f64 / nx as f64;
        let distance = running_in + (PROBE_STEPS * fine) as f64 / nx as f64;
        let probe = SlidingConfig::new(vec![load], distance, running_in, coarse, fine, Some(nx))?
            .with_particle_rule(self.sliding.particle_rule.clone());
        let setup = SlidingSetup {
            sliding: &probe,
            ..self.setup.clone()
        };
        let (top, bottom) = (Arc::clone(&self.pair.top), Arc::clone(&self.pair.bottom));
        let runs = SlidingState::new(top, bottom, setup)?.finish()?;
        let steps = &runs[0].steps;
        let (mut kinds, mut counts) = ([0.0f64; 3], [0usize; 3]);
        for (k, step) in steps.iter().enumerate() {
            let kind = match k {
                0 => 0,
                _ if step.offset - steps[k - 1].offset > 1 => 1,
                _ => 2,
            };
            kinds[kind] += step.iterations as f64;
            counts[kind] += 1;
        }
        let mean = |i: usize| (counts[i] > 0).then(|| kinds[i] / counts[i] as f64);
        let warm = mean(1).or(mean(2)).unwrap_or(0.0);
        Ok(IterationProbe {
            iterations: StepIterations {
                cold: mean(0).unwrap_or(0.0),
                coarse: mean(1).unwrap_or(warm),
                fine: mean(2).unwrap_or(warm),
            },
            load,
            steps: steps.len(),
            seconds: start.elapsed().as_secs_f64(),
        })
    }

    /// The static estimate of the run instead of sliding it (`crate::estimate`): static maps at
    /// offsets spread over the box, taken as `sampling` says, every load solved at each offset;
    /// `on_solve` is told the solves done and the most there can be. The outcome is marked as an
    /// estimate in every document it gives.
    pub fn estimate(
        self,
        sampling: Sampling,
        calibration: &Calibration,
        mut on_solve: impl FnMut(usize, usize),
    ) -> Result<EstimateOutcome<'a>> {
        let start = Instant::now();
        let kind = self.config.surfaces.estimate_kind(self.pair.top.grid());
        let (top, bottom) = self.pair.into_surfaces();
        let mut estimator = Estimator::new(top, bottom, &self.setup)?;
        let loads = self.sliding.loads.len();
        let most = loads
            * match sampling {
                Sampling::Fixed(k) => k,
                Sampling::Auto => MAX_SAMPLES,
            };
        let mut done = 0;
        estimator.sample(sampling, || {
            done += 1;
            on_solve(done, most);
        })?;
        let samples = estimator.samples_done();
        let sampling_error = estimator.sampling_error();
        let estimates = estimator.finish(calibration, &kind);
        let mut warnings = self.warnings;
        if sampling == Sampling::Auto && sampling_error > TARGET_SAMPLING_ERROR {
            warnings.push(format!(
                "after {samples} static maps the sampling error of N* is still {:.1} % for some load and 𝒢 (target \
                 {:.0} %; the standard error between maps, at least the Poisson error of the junctions counted): the \
                 interval includes it; a larger box samples more junctions per map",
                100.0 * sampling_error,
                100.0 * TARGET_SAMPLING_ERROR
            ));
        }
        let warnings = distinct(
            warnings
                .into_iter()
                .chain(estimates.iter().flat_map(|l| l.warnings.iter().cloned())),
        );
        Ok(EstimateOutcome {
            config: self.config,
            sliding: self.sliding,
            loads: estimates,
            calibration: *calibration,
            warnings,
            samples,
            seconds: self.surfaces_seconds + start.elapsed().as_secs_f64(),
        })
    }
}

/// What an estimate gives: per load, the estimate of every fracture energy and the static maps.
#[derive(Debug, Clone)]
pub struct EstimateOutcome<'a> {
    config: &'a RunConfig,
    sliding: &'a SlidingConfig,
    pub loads: Vec<LoadEstimate>,
    /// The constants used.
    pub calibration: Calibration,
    /// Every warning once: the run's inputs', its surfaces', d* against the pixel size, then the
    /// estimates'.
    pub warnings: Vec<String>,
    /// Static maps taken per load.
    pub samples: usize,
    /// Wall time in seconds, making the surfaces included.
    pub seconds: f64,
}

impl EstimateOutcome<'_> {
    /// `summary.json`, marked as an estimate.
    pub fn summary(&self) -> Value {
        estimate_summary(
            &SlidingInputs::of_run(self.config, self.sliding),
            &self.loads,
            &self.calibration,
            &self.warnings,
            self.seconds,
        )
    }

    /// `results.csv`: one row per load and fracture energy.
    pub fn results_csv(&self) -> String {
        Table::of(&estimate_rows(&self.loads, self.config.units)).to_csv()
    }
}

/// What a sliding run of `config` on `grid` warns about before its first step: the run file's
/// ([`RunConfig::warnings`]), its surfaces' (`surfaces`, known once they are made; none for a
/// study's dry run, which makes no surfaces), d* against the pixel and against the box.
pub fn warnings_before_run(config: &RunConfig, grid: Grid, surfaces: &[String]) -> Vec<String> {
    distinct(
        config
            .warnings()
            .into_iter()
            .chain(surfaces.iter().cloned())
            .chain(resolution_warnings(&config.material, grid.pixel_size()))
            .chain(box_warnings(&config.material, grid.length_x(), grid.length_y())),
    )
}

/// Refuses a sliding run on `grid` that needs more memory ([`SlidingConfig::memory_arrays`]: the
/// run's arrays of Nx·Ny doubles with its particle rule's, and the program) than this process may use ([`crate::check::memory_room`]: the
/// machine, cgroup and Slurm limits, `ulimit`), before anything is allocated: the one check of
/// every front end that slides ([`SlidingRun::prepare`], [`SlidingRun::with_surfaces`]), with one
/// message.
pub fn check_memory(grid: Grid, sliding: &SlidingConfig) -> Result<()> {
    crate::check::memory("a sliding run", grid.nx(), grid.ny(), sliding.memory_arrays())
}

/// The schedule of a run, or an error saying that sliding needs one: the one check of every front
/// end that slides, made before any output.
pub fn sliding_schedule(config: &RunConfig) -> Result<&SlidingConfig> {
    config
        .sliding
        .as_ref()
        .ok_or_else(|| Error::run_file("a [sliding] table with `loads` is needed for a sliding run"))
}

/// A sliding run under way (paper §3): it takes one step at a time ([`Slide::step`]); between two
/// steps its state can be saved to a checkpoint ([`Slide::save_checkpoint`]) from which a run of
/// the same inputs continues ([`Slide::resume`]); [`Slide::finish`] gives the outcome.
pub struct Slide<'a> {
    config: &'a RunConfig,
    sliding: &'a SlidingConfig,
    state: SlidingState<'a>,
    warnings: Vec<String>,
    surfaces_seconds: f64,
    start: Instant,
}

impl<'a> Slide<'a> {
    /// Takes the next step (solve, label, count particles; a load's results once its last step is
    /// done) and shows it; `None` once every load is done. A raised interrupt ends the run with
    /// [`Error::Interrupted`] before the step.
    pub fn step(&mut self) -> Result<Option<StepView<'_>>> {
        self.state.step()
    }

    /// Steps done, over all loads.
    pub fn done(&self) -> usize {
        self.state.done()
    }

    /// Steps of every load together.
    pub fn total(&self) -> usize {
        self.state.total()
    }

    /// Saves the state between two steps to `path`, atomically: a run of the same inputs resumes
    /// from it ([`Slide::resume`]) to the results of an uninterrupted run, bit for bit; `false` when
    /// no step has finished (nothing to save). Callable from an interrupt path: after a solve
    /// stopped part-way, with the state kept since [`Slide::keep_state_for_stops`].
    pub fn save_checkpoint(&mut self, path: &Path) -> Result<bool> {
        self.state.save_checkpoint(path)
    }

    /// Keeps the contact pressure of every finished step (one more Nx·Ny field), so that a run
    /// stopped part-way through a solve can still save the state after its last finished step
    /// ([`Slide::save_checkpoint`] on the interrupt path).
    pub fn keep_state_for_stops(&mut self) {
        self.state.keep_state_for_stops();
    }

    /// Before the first step: continues from the checkpoint at `path` when it holds the state of a
    /// run of the same inputs, and says what became of the file (none, used, or set aside and why).
    pub fn resume(&mut self, path: &Path) -> Resumed {
        self.state.resume(path)
    }

    /// Takes the steps left (unobserved), fits the results of every load, and gives the outcome
    /// with every warning once.
    pub fn finish(self) -> Result<SlidingOutcome<'a>> {
        let steps_per_load = self.state.total() / self.sliding.loads.len();
        let mut runs = self.state.finish()?;
        crate::sliding::across_loads(&mut runs);
        let seconds = self.surfaces_seconds + self.start.elapsed().as_secs_f64();
        let warnings = distinct(
            self.warnings
                .into_iter()
                .chain(runs.iter().flat_map(|r| r.warnings.iter().cloned()))
                .chain(load_trend_warnings(&runs)),
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
        let arrays = config
            .to_builder()
            .surfaces(SurfaceSource::Arrays { grid, length: 1.0 })
            .build()
            .unwrap();
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
    fn a_run_too_large_for_the_memory_is_refused_as_a_sliding_run_before_its_surfaces_are_made() {
        // 65534² (the largest grid): some 450 GB for the run, 140 GB for its surface pair alone.
        let config = RunConfig::from_toml(&RUN.replace("grid = 32", "grid = 65534"), Path::new(".")).unwrap();
        let grid = config.grid().unwrap();
        let need = crate::check::memory_need(grid.nx(), grid.ny(), crate::check::SLIDING_ARRAYS);
        if crate::check::memory_room().is_none_or(|room| room.bytes as f64 >= need) {
            return; // a machine this large, or one whose limits cannot be read
        }
        let e = SlidingRun::prepare(&config).unwrap_err().to_string();
        assert!(e.contains("a sliding run on 65534×65534 pixels"), "{e}");
        assert_eq!(
            e,
            check_memory(grid, config.sliding.as_ref().unwrap())
                .unwrap_err()
                .to_string()
        );
        let (top, bottom) = RunConfig::from_toml(RUN, Path::new(".")).unwrap().surfaces().unwrap();
        let small = RunConfig::from_toml(RUN, Path::new(".")).unwrap();
        assert!(SlidingRun::with_surfaces(&small, SurfacePair::of_arrays(top, bottom)).is_ok());
    }

    #[test]
    fn warnings_are_kept_once_in_their_first_place() {
        let w = |s: &[&str]| s.iter().map(|x| x.to_string()).collect::<Vec<_>>();
        assert_eq!(distinct(w(&["a", "b", "a", "c", "b"])), w(&["a", "b", "c"]));
    }
}
