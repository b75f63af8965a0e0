//! The cost of a sliding run before it starts: its wall time and peak memory on this machine, so
//! that a Slurm job can be sized (`--time`, `--mem`) before it is submitted.
//!
//! Model. A sliding step (paper §3) costs convolutions 𝒦t over the N = Nx·Ny pixels (a pair of
//! FFTs, ∝ N log₂ N, with the fused passes around them): about one per solver iteration (an
//! iteration that moved pixels between the sets recomputes 𝒦p, after half a convolution for its
//! curvature, or none where the free pixels are few and their pairs give it) and about
//! [`STEP_CONVOLUTIONS`] more per step (the solve's first displacement and the confirming one);
//! labelling and bookkeeping add about 1 %. So
//!
//! t_step = (I + 2) · a N log₂ N,
//!
//! with I the step's iterations and a this machine's seconds per iteration and N log₂ N pixel at
//! the run's thread count, for the run's stopping rule (the iterations a settled-map solve saves
//! are the cheap ones, a single convolution each, so its iterations cost more on average).
//! [`Calibration::measure`] times short sliding runs of the paper's roughness (λ_l = 16 px,
//! h_rms = 0.005 L, τ̃ = 0.010 E, F_N/(Lx·Ly) = 1.25×10⁻³ E) at 128², 256² and 512² pixels with
//! both stopping rules (each twice, the faster kept), about ten seconds in all, and takes a of
//! each rule as the ratio of its runs' summed times to their summed (I + 2) N log₂ N (the 512²
//! runs weigh most). Measured with `wearsim bench`, the cost of an iteration at 512² scaled by
//! N log₂ N predicts one at 4096² within 10 % on an idle machine; on a shared one, 2048² steps
//! took 1.4–1.5 times their estimate in processor time (docs/performance.md).
//!
//! I comes from the same runs, per kind of step and stopping rule (the cold first step of a load,
//! a step of several pixels during running-in, a one-pixel step), at the calibration grid nearest
//! the run's; above 512² the warm steps' counts fall as (512/N_side)^[`ITERATION_EXPONENT`], as
//! measured on one-pixel steps solved to the tolerance: 24.5, 18.8, 15.2 and 13.8 iterations at
//! 512², 1024², 2048² and 4096² (a slide of one pixel disturbs the contact less where junctions
//! span more pixels).
//!
//! What an estimate assumes, and says: the machine as free as during the calibration (an idle one
//! for a calibration made on an idle machine; the calibration records the load average), the
//! calibration's thread count, and iterations as on the paper's roughness (heavier loads and
//! rougher surfaces take more). Grid sides that are not powers of two make FFTs slower than the
//! model. Peak memory is the library's estimate of a sliding run's arrays ([`peak_memory`]).

use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::contact::{SolverOptions, Stopping};
use crate::error::{Error, Interrupt, Result};
use crate::grid::Grid;
use crate::material::{Material, ModulusConvention};
use crate::sliding::{LoadRun, SlidingConfig, SlidingSetup, SlidingState};
use crate::surface::{pair_seeds, SpectrumParams, Surface};

/// Bumped whenever the calibration's runs or fields change, or the solver's cost per iteration
/// does: older cached calibrations are remade.
const CALIBRATION_FORMAT: u32 = 5;

/// Grid sides of the calibration runs.
const CALIBRATION_SIZES: [usize; 3] = [128, 256, 512];

/// Convolutions of a step besides its iterations' (module documentation).
pub const STEP_CONVOLUTIONS: f64 = 2.0;

/// How the iterations of a warm step fall with the grid side above the calibration's largest
/// (module documentation).
pub const ITERATION_EXPONENT: f64 = 0.28;

/// Iterations per step of each kind, for one stopping rule.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StepIterations {
    /// The first step of a load (cold start from uniform pressure).
    pub cold: f64,
    /// A warm step of several pixels (the running-in's `step_running_in`).
    pub coarse: f64,
    /// A warm one-pixel step.
    pub fine: f64,
}

/// A constant of the model for each stopping rule.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub struct PerRule {
    pub tolerance: f64,
    pub settled_map: f64,
}

impl PerRule {
    /// The constant of `stopping`.
    pub fn of(&self, stopping: Stopping) -> f64 {
        match stopping {
            Stopping::Tolerance => self.tolerance,
            Stopping::SettledMap => self.settled_map,
        }
    }
}

/// One calibration run: a sliding run of the paper's roughness on an n² grid.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CalibrationRun {
    pub n: usize,
    pub stopping: Stopping,
    pub steps: usize,
    pub iterations: usize,
    /// Wall time of the steps (solve, labelling, bookkeeping), in seconds.
    pub seconds: f64,
    pub step_iterations: StepIterations,
}

/// This machine's cost constants ([module documentation](self)), as measured and cached.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Calibration {
    pub format: u32,
    /// The wearsim that measured it ("wearsim 0.1.0").
    pub software: String,
    /// Host name and processor model.
    pub machine: String,
    /// Worker threads of the calibration runs (estimates hold for runs on as many).
    pub threads: usize,
    /// Cores of the machine, and its load average (1 min) when the calibration began, where known:
    /// a calibration on a busy machine gives estimates that run high.
    pub cores: usize,
    pub load_average: Option<f64>,
    /// When it was measured, seconds since 1970 (UTC).
    pub measured_at: u64,
    /// a: seconds per iteration per N log₂ N pixels, per stopping rule.
    pub seconds_per_iteration: PerRule,
    /// The calibration runs, with the iterations of their steps.
    pub runs: Vec<CalibrationRun>,
}

/// What a run (or a study's jobs) will cost on this machine.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Estimate {
    /// Sliding steps over every load.
    pub steps: usize,
    /// Contact solver iterations expected over every step.
    pub iterations: f64,
    /// Wall time in seconds on [`Estimate::threads`] threads.
    pub seconds: f64,
    /// Peak memory in bytes.
    pub peak_memory: f64,
    pub threads: usize,
    /// The iterations expected over every step under the calibration's own (the paper's
    /// roughness), whatever [`Estimate::measured`] says.
    pub assumed_iterations: f64,
    /// Iterations per step of each kind measured on the run's own surfaces
    /// ([`IterationProbe`]), used instead of the calibration's where given.
    pub measured: Option<StepIterations>,
}

/// What a few steps of a run on its own surfaces took (measured by `SlidingRun::probe_iterations` of
/// the run module, which builds on this one): the cold first solve and a few warm steps of each kind
/// at the run's heaviest load, solved as the run solves them.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct IterationProbe {
    /// Iterations per step of each kind (a kind the schedule has no step of is scaled from the
    /// other warm kind by the calibration's ratio).
    pub iterations: StepIterations,
    /// The load probed (the heaviest).
    pub load: f64,
    /// Steps solved, and the seconds they took (the cost of measuring).
    pub steps: usize,
    pub seconds: f64,
}

impl Estimate {
    /// Processor time in hours (wall time × threads).
    pub fn cpu_hours(&self) -> f64 {
        self.seconds * self.threads as f64 / 3600.0
    }
}

/// What a Slurm job of an estimated cost should ask for, with room to spare: half the wall time
/// again (at least a minute), and a quarter of the memory again plus 100 MiB for the process itself.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct SlurmRequest {
    /// `--time`, in whole seconds.
    pub time_seconds: u64,
    /// `--mem`, in MiB.
    pub memory_mib: u64,
}

impl SlurmRequest {
    /// The request for `seconds` of wall time and `bytes` of peak memory.
    pub fn with_margins(seconds: f64, bytes: f64) -> Self {
        Self {
            time_seconds: (seconds * 1.5).ceil().max(60.0) as u64,
            memory_mib: (bytes * 1.25 / (1u64 << 20) as f64 + 100.0).ceil() as u64,
        }
    }
}

impl std::fmt::Display for SlurmRequest {
    /// As `sbatch` options: `--time=D-HH:MM:SS --mem=<MiB>M`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let s = self.time_seconds;
        write!(
            f,
            "--time={}-{:02}:{:02}:{:02} --mem={}M",
            s / 86_400,
            s % 86_400 / 3600,
            s % 3600 / 60,
            s % 60,
            self.memory_mib
        )
    }
}

/// The peak memory of one sliding run on `grid`, in bytes: the library's estimate of the arrays a
/// run holds (the one place an estimate reads it).
pub fn peak_memory(grid: Grid, sliding: &SlidingConfig) -> f64 {
    sliding.memory_arrays() * 8.0 * grid.pixels() as f64
}

impl Calibration {
    /// Measures this machine on the current rayon thread count: the calibration runs of the
    /// [module documentation](self), about ten seconds on two cores; a raised `interrupt` stops it
    /// ([`Error::Interrupted`]).
    pub fn measure(interrupt: &Interrupt) -> Result<Self> {
        let start = Instant::now();
        Self::measure_with(interrupt, &|| start.elapsed().as_secs_f64())
    }

    /// [`Calibration::measure`] timed by `clock` (seconds from any origin) instead of the wall
    /// clock: processor time, for a check of the model on a busy machine.
    pub fn measure_with(interrupt: &Interrupt, clock: &dyn Fn() -> f64) -> Result<Self> {
        let load_average = std::fs::read_to_string("/proc/loadavg")
            .ok()
            .and_then(|l| l.split_whitespace().next().and_then(|v| v.parse().ok()));
        // A first small run pays for thread start-up and FFT planning outside the timed runs.
        calibration_run(64, Stopping::SettledMap, interrupt, clock)?;
        let mut runs = Vec::new();
        // Each run twice, the faster kept: other work that takes the processor for a moment slows
        // one of them, not both (a machine busy throughout still slows both: the estimate says so).
        for n in CALIBRATION_SIZES {
            for stopping in [Stopping::SettledMap, Stopping::Tolerance] {
                let first = calibration_run(n, stopping, interrupt, clock)?;
                let second = calibration_run(n, stopping, interrupt, clock)?;
                runs.push(if second.seconds < first.seconds { second } else { first });
            }
        }
        let a = PerRule {
            tolerance: fit(&runs, Stopping::Tolerance),
            settled_map: fit(&runs, Stopping::SettledMap),
        };
        Ok(Self {
            format: CALIBRATION_FORMAT,
            software: format!("wearsim {}", crate::io::VERSION),
            machine: machine(),
            threads: rayon::current_num_threads(),
            cores: std::thread::available_parallelism().map_or(1, |c| c.get()),
            load_average,
            measured_at: std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(0, |d| d.as_secs()),
            seconds_per_iteration: a,
            runs,
        })
    }

    /// The file in `dir` that caches the calibration of this machine, version and thread count.
    pub fn cache_path(dir: &Path) -> PathBuf {
        cache_file(dir)
    }

    /// The cached calibration of this machine, version and thread count from `dir`: `Ok(None)` when
    /// there is none (or one of another format, wearsim, machine or thread count, remade). A cached
    /// file is trusted only when its checksum matches its contents and every number in it is within
    /// the range a calibration gives ([`Calibration::implausible`]); one that is not is set aside
    /// (renamed `….json.set-aside`, so that the next calibration replaces it) and the error says why:
    /// an edited or damaged cache never gives an estimate.
    pub fn cached(dir: &Path) -> Result<Option<Self>> {
        let path = cache_file(dir);
        let Ok(text) = std::fs::read_to_string(&path) else {
            return Ok(None);
        };
        let Ok(calibration) = serde_json::from_str::<Self>(&text) else {
            return Err(set_aside(&path, "it is not a calibration this wearsim reads"));
        };
        if !(calibration.format == CALIBRATION_FORMAT
            && calibration.software == format!("wearsim {}", crate::io::VERSION)
            && calibration.machine == machine()
            && calibration.threads == rayon::current_num_threads())
        {
            return Ok(None);
        }
        if crate::io::checksum_matches(&text) != Some(true) {
            return Err(set_aside(
                &path,
                "its checksum does not match its contents: it was edited or damaged since it was written",
            ));
        }
        if let Some(why) = calibration.implausible() {
            return Err(set_aside(&path, &format!("{why}, which no calibration measures")));
        }
        Ok(Some(calibration))
    }

    /// What in the calibration is out of the range a measurement gives, if anything: a constant `a`
    /// that is not a positive finite number between 10⁻¹⁴ and 10⁻⁴ s (an iteration on 128² pixels
    /// from nanoseconds to tens of seconds) or is not the fit of its runs, runs missing for a
    /// stopping rule or a grid, steps, iterations or seconds that are not positive and finite,
    /// iterations per step above the solver's default maximum, no threads, a negative load average, a
    /// date in the future.
    pub fn implausible(&self) -> Option<String> {
        let a = self.seconds_per_iteration;
        for (rule, stopping, value) in [
            ("tolerance", Stopping::Tolerance, a.tolerance),
            ("settled-map", Stopping::SettledMap, a.settled_map),
        ] {
            if !(value.is_finite() && (1e-14..=1e-4).contains(&value)) {
                return Some(format!("`seconds_per_iteration.{rule}` = {value:e} s"));
            }
            let fitted = fit(&self.runs, stopping);
            let off = (value / fitted - 1.0).abs();
            if off.is_nan() || off >= 1e-9 {
                return Some(format!(
                    "`seconds_per_iteration.{rule}` = {value:e} s where its runs give {fitted:e} s"
                ));
            }
            for n in CALIBRATION_SIZES {
                if !self.runs.iter().any(|r| r.n == n && r.stopping == stopping) {
                    return Some(format!("no {rule} run on {n}² pixels"));
                }
            }
        }
        let most = crate::contact::DEFAULT_MAX_ITERATIONS as f64;
        for (k, r) in self.runs.iter().enumerate() {
            let i = r.step_iterations;
            let bad = if !CALIBRATION_SIZES.contains(&r.n) {
                Some(("n", r.n as f64))
            } else if r.steps == 0 {
                Some(("steps", 0.0))
            } else if r.iterations == 0 || r.iterations as f64 > most * r.steps as f64 {
                Some(("iterations", r.iterations as f64))
            } else if !(r.seconds.is_finite() && r.seconds > 0.0 && r.seconds < 86_400.0) {
                Some(("seconds", r.seconds))
            } else {
                [("cold", i.cold), ("coarse", i.coarse), ("fine", i.fine)]
                    .into_iter()
                    .find(|(_, v)| !(v.is_finite() && *v > 0.0 && *v <= most))
            };
            if let Some((field, value)) = bad {
                return Some(format!("`runs[{k}].{field}` = {value:e}"));
            }
        }
        let now = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_secs());
        if self.threads == 0 || self.cores == 0 {
            return Some(format!("{} threads on {} cores", self.threads, self.cores));
        }
        if let Some(l) = self.load_average.filter(|l| !(l.is_finite() && *l >= 0.0)) {
            return Some(format!("a load average of {l}"));
        }
        if self.measured_at > now + 86_400 {
            return Some(format!("a measurement dated {} s after now", self.measured_at - now));
        }
        None
    }

    /// Writes the calibration into `dir` (made if missing), atomically, with a checksum of its
    /// contents; returns the file.
    pub fn save(&self, dir: &Path) -> Result<PathBuf> {
        std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
        let path = cache_file(dir);
        let json = serde_json::to_string_pretty(self).map_err(|e| Error::file(&path, e.to_string()))?;
        crate::io::write_text(&path, &format!("{}\n", crate::io::with_checksum(&json)))?;
        Ok(path)
    }

    /// Whole days since the calibration was measured.
    pub fn age_days(&self) -> u64 {
        let now = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_secs());
        now.saturating_sub(self.measured_at) / 86_400
    }

    /// Iterations per step under a stopping rule on `grid` (module documentation): those of the
    /// calibration run nearest in size, scaled down above the largest calibration grid.
    pub fn iterations(&self, grid: Grid, stopping: Stopping) -> StepIterations {
        let side = (grid.pixels() as f64).sqrt();
        let nearest = self.runs.iter().filter(|r| r.stopping == stopping).min_by(|a, b| {
            (a.n as f64 / side)
                .ln()
                .abs()
                .total_cmp(&(b.n as f64 / side).ln().abs())
        });
        let Some(run) = nearest else {
            return StepIterations {
                cold: 0.0,
                coarse: 0.0,
                fine: 0.0,
            };
        };
        // Scaled only above the largest calibration grid; between them, the nearest run's counts.
        let largest = self.runs.iter().map(|r| r.n).max().unwrap_or(run.n);
        let scale = (largest as f64 / side).min(1.0).powf(ITERATION_EXPONENT);
        let i = run.step_iterations;
        StepIterations {
            cold: i.cold,
            coarse: i.coarse * scale,
            fine: i.fine * scale,
        }
    }

    /// Seconds of one step of `iterations` iterations on `grid` under a stopping rule.
    pub fn step_seconds(&self, grid: Grid, iterations: f64, stopping: Stopping) -> f64 {
        let pixels = grid.pixels() as f64;
        (iterations + STEP_CONVOLUTIONS) * self.seconds_per_iteration.of(stopping) * pixels * pixels.log2()
    }

    /// The estimate of a sliding run on `grid` with schedule `sliding` whose solves stop by
    /// `stopping`, with iterations as on the paper's roughness (the calibration's).
    pub fn estimate(&self, grid: Grid, sliding: &SlidingConfig, stopping: Stopping) -> Estimate {
        self.estimate_measured(grid, sliding, stopping, None)
    }

    /// [`Calibration::estimate`] with the iterations per step of each kind `measured` on the run's
    /// own surfaces (an [`IterationProbe`]'s) instead of the calibration's, for every load: rougher
    /// surfaces and heavier loads take more than the paper's roughness. The assumed count is kept
    /// beside it ([`Estimate::assumed_iterations`]).
    pub fn estimate_measured(
        &self,
        grid: Grid,
        sliding: &SlidingConfig,
        stopping: Stopping,
        measured: Option<StepIterations>,
    ) -> Estimate {
        let assumed = self.iterations(grid, stopping);
        let (assumed_iterations, _) = self.iterations_of(&assumed, grid, sliding);
        let per_step = measured.unwrap_or(assumed);
        let (iterations, _) = self.iterations_of(&per_step, grid, sliding);
        let loads = sliding.loads.len() as f64;
        let offsets = sliding.offsets(grid.nx()).len();
        Estimate {
            steps: offsets * sliding.loads.len(),
            iterations: iterations * loads,
            seconds: self.step_seconds_total(grid, iterations, offsets, stopping) * loads,
            peak_memory: peak_memory(grid, sliding),
            threads: self.threads,
            assumed_iterations: assumed_iterations * loads,
            measured,
        }
    }

    /// Iterations of one load's steps under `per_step`, and the count of its steps.
    fn iterations_of(&self, per_step: &StepIterations, grid: Grid, sliding: &SlidingConfig) -> (f64, usize) {
        let offsets = sliding.offsets(grid.nx());
        let mut iterations = 0.0;
        for (k, offset) in offsets.iter().enumerate() {
            iterations += match k {
                0 => per_step.cold,
                _ if offset - offsets[k - 1] > 1 => per_step.coarse,
                _ => per_step.fine,
            };
        }
        (iterations, offsets.len())
    }

    /// Seconds of `steps` steps of `iterations` iterations in all.
    fn step_seconds_total(&self, grid: Grid, iterations: f64, steps: usize, stopping: Stopping) -> f64 {
        let pixels = grid.pixels() as f64;
        (iterations + STEP_CONVOLUTIONS * steps as f64)
            * self.seconds_per_iteration.of(stopping)
            * pixels
            * pixels.log2()
    }

    /// The old path, kept for its test: one step at a time.
    #[cfg(test)]
    fn estimate_stepwise(&self, grid: Grid, sliding: &SlidingConfig, stopping: Stopping) -> Estimate {
        let per_step = self.iterations(grid, stopping);
        let offsets = sliding.offsets(grid.nx());
        let mut iterations = 0.0;
        let mut seconds = 0.0;
        for (k, offset) in offsets.iter().enumerate() {
            let i = match k {
                0 => per_step.cold,
                _ if offset - offsets[k - 1] > 1 => per_step.coarse,
                _ => per_step.fine,
            };
            iterations += i;
            seconds += self.step_seconds(grid, i, stopping);
        }
        let loads = sliding.loads.len() as f64;
        Estimate {
            steps: offsets.len() * sliding.loads.len(),
            iterations: iterations * loads,
            seconds: seconds * loads,
            peak_memory: peak_memory(grid, sliding),
            threads: self.threads,
            assumed_iterations: iterations * loads,
            measured: None,
        }
    }
}

/// Renames a cached calibration that cannot be trusted out of the way, and the error saying why.
fn set_aside(path: &Path, why: &str) -> Error {
    let aside = path.with_extension("json.set-aside");
    let moved = match std::fs::rename(path, &aside) {
        Ok(()) => format!("set aside as {}", aside.display()),
        Err(e) => format!("not set aside ({e})"),
    };
    Error::file(path, format!("the cached cost calibration is not used: {why}; {moved}"))
}

/// The calibration file in `dir` of this machine, wearsim version and thread count.
fn cache_file(dir: &Path) -> PathBuf {
    let key = format!(
        "{}\n{}\n{}",
        machine(),
        crate::io::VERSION,
        rayon::current_num_threads()
    );
    let hash = key.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    });
    dir.join(format!("calibration-{hash:016x}.json"))
}

/// Where calibrations are cached: `$XDG_CACHE_HOME/wearsim`, else `$HOME/.cache/wearsim`; `None`
/// where neither is set.
pub fn cache_dir() -> Option<PathBuf> {
    let non_empty = |v: &str| std::env::var_os(v).filter(|s| !s.is_empty()).map(PathBuf::from);
    non_empty("XDG_CACHE_HOME")
        .or_else(|| non_empty("HOME").map(|h| h.join(".cache")))
        .map(|d| d.join("wearsim"))
}

/// Host name and processor model, as the cache key and for the record.
fn machine() -> String {
    let host = std::fs::read_to_string("/proc/sys/kernel/hostname")
        .ok()
        .or_else(|| std::env::var("HOSTNAME").ok())
        .unwrap_or_else(|| "unknown host".into());
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|info| {
            info.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, m)| m.trim().to_string())
        })
        .unwrap_or_else(|| std::env::consts::ARCH.to_string());
    format!("{} / {cpu}", host.trim())
}

/// One calibration run: 4 steps of 4 px (the first cold) and 16 of 1 px on an n² grid.
fn calibration_run(
    n: usize,
    stopping: Stopping,
    interrupt: &Interrupt,
    clock: &dyn Fn() -> f64,
) -> Result<CalibrationRun> {
    let grid = Grid::square(n, 1.0)?;
    let spectrum = SpectrumParams::paper_roughness(n, 1.0);
    let (s1, s2) = pair_seeds(1);
    let (top, bottom) = (
        Surface::generate(grid, &spectrum, s1)?,
        Surface::generate(grid, &spectrum, s2)?,
    );
    let material = Material::new(1.0, 0.3, 0.010, vec![0.25e-6, 0.5e-6, 0.75e-6, 1.0e-6], 3.0)?;
    let sliding = SlidingConfig::new(vec![1.25e-3], 32.0 / n as f64, 16.0 / n as f64, 4, 1, Some(n))?;
    let setup = SlidingSetup {
        material: &material,
        effective_modulus: material.effective_modulus(ModulusConvention::HalfSpace),
        solver: SolverOptions::default().with_stopping(stopping),
        device: Default::default(),
        connectivity: crate::junctions::DEFAULT_CONNECTIVITY,
        sliding: &sliding,
        interrupt: interrupt.clone(),
    };
    let t = clock();
    let runs = SlidingState::new(top.into(), bottom.into(), setup)?.finish()?;
    let seconds = clock() - t;
    let run: &LoadRun = &runs[0];
    let mean = |steps: &[crate::sliding::StepRecord]| {
        steps.iter().map(|s| s.iterations as f64).sum::<f64>() / steps.len().max(1) as f64
    };
    Ok(CalibrationRun {
        n,
        stopping,
        steps: run.steps.len(),
        iterations: run.total_iterations,
        seconds,
        step_iterations: StepIterations {
            cold: run.steps[0].iterations as f64,
            coarse: mean(&run.steps[1..4]),
            fine: mean(&run.steps[4..]),
        },
    })
}

/// a of the model for a stopping rule from the calibration runs: their summed seconds over their
/// summed (I + 2) N log₂ N, so that the largest runs weigh most.
fn fit(runs: &[CalibrationRun], stopping: Stopping) -> f64 {
    let (seconds, work) = runs
        .iter()
        .filter(|r| r.stopping == stopping)
        .fold((0.0, 0.0), |(t, w), r| {
            let pixels = (r.n * r.n) as f64;
            let convolutions = r.iterations as f64 + STEP_CONVOLUTIONS * r.steps as f64;
            (t + r.seconds, w + convolutions * pixels * pixels.log2())
        });
    seconds / work
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slurm_requests_leave_room() {
        let r = SlurmRequest::with_margins(3600.0, 1024.0 * 1024.0 * 1024.0);
        assert_eq!((r.time_seconds, r.memory_mib), (5400, 1380));
        assert_eq!(r.to_string(), "--time=0-01:30:00 --mem=1380M");
        // A short job still asks for a minute; days are counted apart.
        assert_eq!(
            SlurmRequest::with_margins(1.0, 0.0).to_string(),
            "--time=0-00:01:00 --mem=100M"
        );
        assert_eq!(
            SlurmRequest::with_margins(2.0 * 86_400.0, 0.0).to_string(),
            "--time=3-00:00:00 --mem=100M"
        );
    }

    fn run(n: usize, stopping: Stopping, iterations: usize, seconds: f64, fine: f64) -> CalibrationRun {
        CalibrationRun {
            n,
            stopping,
            steps: 20,
            iterations,
            seconds,
            step_iterations: StepIterations {
                cold: 2.0 * fine,
                coarse: 1.5 * fine,
                fine,
            },
        }
    }

    fn calibration(runs: Vec<CalibrationRun>) -> Calibration {
        Calibration {
            format: CALIBRATION_FORMAT,
            software: String::new(),
            machine: String::new(),
            threads: 2,
            cores: 2,
            load_average: None,
            measured_at: 0,
            seconds_per_iteration: PerRule {
                tolerance: fit(&runs, Stopping::Tolerance),
                settled_map: fit(&runs, Stopping::SettledMap),
            },
            runs,
        }
    }

    #[test]
    fn the_fit_recovers_the_constant_of_exact_timings() {
        let a = 3e-9;
        let time = |n: usize, i: usize| {
            let p = (n * n) as f64;
            a * (i as f64 + STEP_CONVOLUTIONS * 20.0) * p * p.log2()
        };
        let runs: Vec<_> = [(128, 300), (256, 320), (512, 280)]
            .into_iter()
            .map(|(n, i)| run(n, Stopping::SettledMap, i, time(n, i), 10.0))
            .collect();
        assert!((fit(&runs, Stopping::SettledMap) / a - 1.0).abs() < 1e-12);
    }

    #[test]
    fn an_estimate_counts_every_step_of_every_load_with_the_iterations_of_its_size() {
        let c = calibration(vec![
            run(256, Stopping::SettledMap, 300, 1.0, 12.0),
            run(256, Stopping::Tolerance, 400, 1.2, 18.0),
            run(512, Stopping::SettledMap, 300, 4.0, 10.0),
            run(512, Stopping::Tolerance, 400, 5.0, 15.0),
        ]);
        let sliding = SlidingConfig::new(vec![1e-3, 2e-3], 0.5, 0.25, 4, 1, Some(1024)).unwrap();
        let grid = Grid::square(1024, 1.0).unwrap();
        let e = c.estimate(grid, &sliding, Stopping::SettledMap);
        let stepwise = c.estimate_stepwise(grid, &sliding, Stopping::SettledMap);
        assert!((e.seconds / stepwise.seconds - 1.0).abs() < 1e-12 && e.iterations == stepwise.iterations);
        assert_eq!(e.assumed_iterations, e.iterations);
        // Measured iterations replace the assumed ones, which are kept beside them.
        let measured = StepIterations {
            cold: 100.0,
            coarse: 30.0,
            fine: 20.0,
        };
        let m = c.estimate_measured(grid, &sliding, Stopping::SettledMap, Some(measured));
        assert!((m.iterations - 2.0 * (100.0 + 64.0 * 30.0 + 255.0 * 20.0)).abs() < 1e-9);
        assert_eq!((m.assumed_iterations, m.measured), (e.iterations, Some(measured)));
        assert!(m.seconds > e.seconds);
        // Per load: 64 running-in steps (the first cold), the 4-px step onto L/4, 255 one-pixel
        // steps; above 512² the warm steps' iterations fall as (512/1024)^0.28.
        let scale = 0.5f64.powf(ITERATION_EXPONENT);
        let per_load = 20.0 + 64.0 * 15.0 * scale + 255.0 * 10.0 * scale;
        assert_eq!(e.steps, 640);
        assert!((e.iterations / (2.0 * per_load) - 1.0).abs() < 1e-12);
        let pixels = 1024.0 * 1024.0f64;
        let a = c.seconds_per_iteration.settled_map;
        let expected = (e.iterations + STEP_CONVOLUTIONS * 640.0) * a * pixels * pixels.log2();
        assert!((e.seconds / expected - 1.0).abs() < 1e-12);
        assert_eq!(e.peak_memory, peak_memory(grid, &sliding));
        let interacting = sliding.clone().with_particle_rule(crate::wear::INTERACTING);
        assert!(peak_memory(grid, &interacting) > peak_memory(grid, &sliding));
        assert!(c.estimate(grid, &sliding, Stopping::Tolerance).seconds > e.seconds);
        assert!((e.cpu_hours() - e.seconds * 2.0 / 3600.0).abs() < 1e-12);
        // A small grid takes the iterations of the nearest calibration run, unscaled.
        let small = Grid::square(256, 1.0).unwrap();
        assert_eq!(c.iterations(small, Stopping::SettledMap).fine, 12.0);
        let fine = |n| c.iterations(Grid::square(n, 1.0).unwrap(), Stopping::Tolerance).fine;
        assert_eq!((fine(320), fine(384)), (18.0, 15.0));
    }

    /// A calibration of this machine, version and thread count as measured, from made-up runs.
    fn plausible() -> Calibration {
        let runs: Vec<_> = CALIBRATION_SIZES
            .into_iter()
            .flat_map(|n| {
                let t = (n * n) as f64 * 1e-7;
                [
                    run(n, Stopping::SettledMap, 300, t, 10.0),
                    run(n, Stopping::Tolerance, 400, 1.3 * t, 15.0),
                ]
            })
            .collect();
        Calibration {
            software: format!("wearsim {}", crate::io::VERSION),
            machine: machine(),
            threads: rayon::current_num_threads(),
            ..calibration(runs)
        }
    }

    #[test]
    fn an_edited_or_implausible_cache_is_set_aside_never_used() {
        let dir = tempfile::tempdir().unwrap();
        let good = plausible();
        assert_eq!(good.implausible(), None);
        let path = good.save(dir.path()).unwrap();
        assert_eq!(Calibration::cached(dir.path()).unwrap(), Some(good.clone()));
        // One exponent changed by hand: the checksum no longer matches.
        let text = std::fs::read_to_string(&path).unwrap();
        let a = serde_json::to_string(&good.seconds_per_iteration.settled_map).unwrap();
        let (mantissa, exponent) = a.split_once('e').expect(&a);
        let edited = text.replacen(&a, &format!("{mantissa}e{}", exponent.parse::<i32>().unwrap() - 10), 1);
        assert_ne!(edited, text);
        std::fs::write(&path, &edited).unwrap();
        let e = Calibration::cached(dir.path()).unwrap_err().to_string();
        assert!(e.contains("checksum") && e.contains("set aside"), "{e}");
        assert!(!path.exists() && path.with_extension("json.set-aside").exists());
        // An absurd value written with a checksum that matches: out of range.
        let mut absurd = good.clone();
        absurd.seconds_per_iteration.settled_map *= 1e-10;
        absurd.save(dir.path()).unwrap();
        let e = Calibration::cached(dir.path()).unwrap_err().to_string();
        assert!(
            e.contains("seconds_per_iteration.settled-map") && e.contains("set aside"),
            "{e}"
        );
        assert!(!path.exists());
        // Runs whose iterations are absurd, with the constant refitted to them.
        let mut runs = good.runs.clone();
        runs[0].step_iterations.fine = 0.0;
        let absurd = Calibration { runs, ..good.clone() };
        absurd.save(dir.path()).unwrap();
        let e = Calibration::cached(dir.path()).unwrap_err().to_string();
        assert!(e.contains("runs[0].fine"), "{e}");
        // A file that is no calibration at all.
        std::fs::write(&path, "{\"format\": 4}").unwrap();
        assert!(Calibration::cached(dir.path()).is_err());
        // None cached: none, no error.
        assert_eq!(Calibration::cached(dir.path()).unwrap(), None);
    }
}
