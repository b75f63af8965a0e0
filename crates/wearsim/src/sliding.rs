//! The sliding simulation (paper §3): slide the top surface over the bottom one along x,
//! solve the contact at every offset (warm-started from the previous step), label the junctions,
//! and advance one wear bookkeeping per fracture energy on the shared contact solutions. Ends with
//! the least-squares wear rate, particle rate and Archard wear coefficient after running-in.

use std::time::Instant;

use crate::check::positive;
use crate::contact::{ContactSolver, Device, SolverOptions};
use crate::error::{Error, Interrupt, Result};
use crate::grid::Grid;
use crate::influence::Boundary;
use crate::junctions::JunctionLabeller;
use crate::material::Material;
use crate::stats::{line_fit, mean_std, LineFit};
use crate::surface::Surface;
use crate::wear::{static_wear, InitialContactMemory, SlidingBookkeeping, StaticWear, StepWear};

mod checkpoint;

use checkpoint::{inputs_key, load_checkpoint, SavedState, StopSaver};
pub use checkpoint::{Checkpointing, Resumed, CHECKPOINT_EVERY};

/// The sliding schedule (paper §3); distances as fractions of the box side Lx along the sliding
/// direction x, steps in pixels.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SlidingConfig {
    /// Normal loads F_N (E·L² reduced, N in SI).
    pub loads: Vec<f64>,
    /// Total sliding distance as a fraction of Lx ([`DEFAULT_DISTANCE`] when not given).
    pub distance: f64,
    /// Running-in distance as a fraction of Lx ([`DEFAULT_RUNNING_IN`]).
    pub running_in: f64,
    /// Step during running-in, in pixels ([`DEFAULT_STEP_RUNNING_IN`]).
    pub step_running_in: usize,
    /// Step after running-in, in pixels ([`DEFAULT_STEP`]).
    pub step: usize,
}

/// The paper's sliding distance (§3): half the box side, s up to Lx/2.
pub const DEFAULT_DISTANCE: f64 = 0.5;

/// The paper's running-in distance (§3): a quarter of the box side, the safety margin it takes for
/// the memory of the initial contact to fade; the wear rate is fitted from there.
pub const DEFAULT_RUNNING_IN: f64 = 0.25;

/// The step during running-in, in pixels (§3: coarser steps while the fit does not yet count).
pub const DEFAULT_STEP_RUNNING_IN: usize = 4;

/// The step after running-in, in pixels (§3: every pixel of the fit window).
pub const DEFAULT_STEP: usize = 1;

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
                format!("{distance} must lie in (0, 1] (a fraction of the box side Lx)"),
            ));
        }
        if !(running_in >= 0.0 && running_in < distance) {
            return Err(Error::param(
                "running_in",
                format!("{running_in} must lie in [0, distance = {distance}) (a fraction of the box side Lx)"),
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

/// Sliding offsets in pixels along x (paper §3): see [`SlidingConfig::offsets`].
pub fn schedule(nx: usize, sliding: &SlidingConfig) -> Vec<usize> {
    sliding.offsets(nx)
}

/// One step of one load: the contact statistics and, per fracture energy, the wear record.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StepRecord {
    /// Offset in pixels.
    pub offset: usize,
    /// Sliding distance s in the run's length unit.
    pub s: f64,
    /// Number of junctions N.
    pub junctions: usize,
    /// Junctions that wrap the periodic box (full contact, a band across the box): no particles of
    /// the model, which needs finite junctions (paper §3), yet counted in N and the wear records.
    pub wrapping_junctions: usize,
    /// Real contact area as a fraction of the apparent area.
    pub contact_area: f64,
    /// Junctions of this step that descend from a junction present at s = 0 (paper §3's memory of
    /// the initial contact).
    pub initial_junctions: usize,
    /// Solver iterations of this step.
    pub iterations: usize,
    /// Solver residual of this step.
    pub residual: f64,
    /// Wear record per fracture energy, in the material's order.
    pub wear: Vec<StepWear>,
    /// Static model on this step's contact map per fracture energy (paper §2).
    pub statics: Vec<StaticWear>,
}

/// A finite number, or nothing.
fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

/// Results per load and fracture energy (paper §3–4 and appendices B, C); also the record stored in
/// study job files. Fitted quantities are absent (`null` in JSON, an empty cell in CSV) where they
/// are undefined; the run's `warnings` say why.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct WearResult {
    pub fracture_energy: f64,
    pub critical_diameter: f64,
    /// W = dV/ds fitted after running-in (volume per sliding distance).
    pub wear_rate: Option<f64>,
    /// R² of the wear-rate fit; absent where V does not change after running-in (no particle).
    pub wear_rate_r2: Option<f64>,
    /// Intercept b of the line V(s) ≈ W s + b fitted after running-in (volume), the dashed line of
    /// the paper's Fig. 3; absent with W. Absent in job files written before it existed.
    #[serde(default)]
    pub wear_volume_intercept: Option<f64>,
    /// Sliding distance at which the fit window starts (run's length unit): the first step at or
    /// past the running-in distance, where the fits of W and dN*₊/ds and the means over the fit
    /// window begin; the running-in (not fitted) part of the paper's Fig. 3 ends here. Read as 0
    /// from job files of format 2 only so that the job-format check, not a parse error, refuses them.
    #[serde(default)]
    pub fit_window_start: f64,
    /// k = W p̃ / F_N (Archard, paper Eq. 2).
    pub wear_coefficient: Option<f64>,
    /// dN*₊/ds fitted after running-in (particles per sliding distance).
    pub particle_rate: Option<f64>,
    /// Paper Eq. 5, ω d*³ dN*₊/ds with ω = π/6 (the paper finds it slightly below W, appendix B).
    pub wear_rate_estimate: Option<f64>,
    /// Particles formed after running-in (N*₊ at the end minus at the start of the fit window).
    pub particles_in_fit: usize,
    /// V₀, the volume counted at s = 0.
    pub initial_volume: f64,
    /// Static model at s = 0: k_static = Σ_{A_i ≥ A*} A_i / Σ A_i.
    pub static_wear_coefficient: f64,
    /// Static model at s = 0: W_static/ω = k_static Σ A_i.
    pub static_wear_rate: f64,
    /// Static model over every offset of the run (paper §2): mean and standard deviation of k_static.
    pub static_wear_coefficient_mean: f64,
    pub static_wear_coefficient_std: f64,
    /// Static model over every offset: mean and standard deviation of W_static/ω.
    pub static_wear_rate_mean: f64,
    pub static_wear_rate_std: f64,
    /// Mean number of junctions N over the fit window (paper appendix C).
    pub junctions_mean: f64,
    /// Mean number of junctions at least d* across, N*, over the fit window (paper appendix C).
    pub critical_junctions_mean: f64,
    /// Decay length ℓ of the memory of the initial contact, N₀(s) ≈ N₀(0) e^(−s/ℓ) (paper §3), fitted
    /// to ln N₀ over the steps where N₀ > 0; absent when it does not decay.
    pub memory_decay_length: Option<f64>,
    /// R² of that fit (in ln N₀).
    pub memory_decay_r2: Option<f64>,
    /// N₀(0) of that fit, e^b of the line ln N₀ ≈ b − s/ℓ: with ℓ, the fitted curve of the memory
    /// of the initial contact; absent with ℓ. Absent in job files written before it existed.
    #[serde(default)]
    pub memory_fit_initial_junctions: Option<f64>,
    /// Steps of the load at which a junction wrapped the periodic box (full contact near p_m, a
    /// contact band across the box). Such a junction is no particle of the model (paper §3 needs
    /// finite junctions), yet it is counted as one, so results with steps here are not the model's;
    /// the warnings say so. Absent in job files written before it existed: 0.
    #[serde(default)]
    pub box_wrapping_steps: usize,
    /// The running-in distance (start of the fit window) in decay lengths, s_r/ℓ; 0 when the memory
    /// does not decay, absent when it is gone by the first step after s = 0. Below
    /// [`RUN_IN_DECAY_LENGTHS`] the fit window starts while the initial contact is still remembered
    /// (paper §3) and the run is not run in; the run's `warnings` say so.
    pub running_in_decay_lengths: Option<f64>,
    /// N*/(dN*₊/ds): the sliding distance a junction stays at least d* per particle it forms
    /// (Little's law over the fit window). A junction forms one particle and is then disabled while
    /// it overlaps itself (paper §3), so when critical junctions grow and live longer with load, this
    /// grows and the particle rate per critical junction, and k, fall; absent without particles.
    pub critical_residence: Option<f64>,
}

impl WearResult {
    /// The unit of every field, declared beside the fields so that a new result states its unit
    /// where it is added: (field, reduced units, SI units); "" for counts, "1" for ratios. Read by
    /// `output::unit_of` for every table and summary that holds the field (`_mean`, `_min`, …
    /// of it included).
    pub const UNITS: &'static [(&'static str, &'static str, &'static str)] = &[
        ("fracture_energy", "E L", "J/m²"),
        ("critical_diameter", "L", "m"),
        ("wear_rate", "L²", "m²"),
        ("wear_rate_r2", "1", "1"),
        ("wear_volume_intercept", "L³", "m³"),
        ("fit_window_start", "L", "m"),
        ("wear_coefficient", "1", "1"),
        ("particle_rate", "1/L", "1/m"),
        ("wear_rate_estimate", "L²", "m²"),
        ("particles_in_fit", "", ""),
        ("initial_volume", "L³", "m³"),
        ("static_wear_coefficient", "1", "1"),
        ("static_wear_rate", "L²", "m²"),
        ("static_wear_coefficient_mean", "1", "1"),
        ("static_wear_coefficient_std", "1", "1"),
        ("static_wear_rate_mean", "L²", "m²"),
        ("static_wear_rate_std", "L²", "m²"),
        ("junctions_mean", "", ""),
        ("critical_junctions_mean", "", ""),
        ("memory_decay_length", "L", "m"),
        ("memory_decay_r2", "1", "1"),
        ("memory_fit_initial_junctions", "", ""),
        ("box_wrapping_steps", "", ""),
        ("running_in_decay_lengths", "1", "1"),
        ("critical_residence", "L", "m"),
    ];
}

/// Decay lengths of the memory of the initial contact after which a run counts as run in: e^−3, so
/// about 5 % of the junction lineages present at s = 0 are expected at the start of the fit window.
/// The paper (§3) finds the decay length not predictable and takes L/4 as a safety margin; this rule
/// checks that margin on each run's own measured decay.
pub const RUN_IN_DECAY_LENGTHS: f64 = 3.0;

/// Time spent per part of the sliding loop, in seconds.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Timing {
    pub solve: f64,
    pub labelling: f64,
    pub bookkeeping: f64,
}

/// One load's sliding run.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LoadRun {
    /// Normal load F_N.
    pub load: f64,
    pub steps: Vec<StepRecord>,
    pub results: Vec<WearResult>,
    pub total_iterations: usize,
    pub max_iterations: usize,
    pub timing: Timing,
    /// What makes a result of this load under-resolved or undefined, one sentence each.
    pub warnings: Vec<String>,
}

/// Everything a sliding run needs besides the surfaces.
#[derive(Debug, Clone)]
pub struct SlidingSetup<'a> {
    pub material: &'a Material,
    pub effective_modulus: f64,
    pub solver: SolverOptions,
    /// Where the contact solver computes (`[contact] device`).
    pub device: Device,
    pub connectivity: u8,
    pub sliding: &'a SlidingConfig,
    /// Raised by another thread to stop the run ([`Error::Interrupted`]).
    pub interrupt: Interrupt,
}

/// What an observer of a sliding run sees after each step.
pub struct StepView<'a> {
    /// Steps done so far, over all loads, and their total.
    pub done: usize,
    pub total: usize,
    /// Index of the load in `setup.sliding.loads`.
    pub load_index: usize,
    /// Position of this step in the schedule of its load.
    pub step_index: usize,
    /// This step's record.
    pub record: &'a StepRecord,
    /// This step's contact pressure (row-major, x first).
    pub pressure: &'a [f64],
    /// The labelled contact map of this step.
    pub labeller: &'a JunctionLabeller,
    /// The bookkeeping of every fracture energy, with the junction states of this step.
    pub bookkeeping: &'a [SlidingBookkeeping],
}

/// Fewest particles after running-in for a wear rate worth a number without a warning.
pub const FEW_PARTICLES: usize = 10;

/// Warnings about d* in pixels: a critical diameter of a few pixels is not resolved.
pub fn resolution_warnings(material: &Material, pixel_size: f64) -> Vec<String> {
    material
        .fracture_energies
        .iter()
        .zip(material.critical_diameters())
        .filter(|(_, d)| d / pixel_size < crate::check::RESOLVED_PIXELS)
        .map(|(g, d)| {
            format!(
                "d* = {d:.4e} for 𝒢 = {g:.4e} is {:.2} pixels, under {}: junctions of the critical size \
                 are not resolved and the wear results follow the grid; refine `grid`",
                d / pixel_size,
                crate::check::RESOLVED_PIXELS
            )
        })
        .collect()
}

/// Runs the sliding model for every load of `setup.sliding`. `observe` is called after every step
/// (progress bars, animations); it sees the step but cannot change the run.
pub fn run_sliding(
    top: &Surface,
    bottom: &Surface,
    setup: &SlidingSetup,
    observe: impl FnMut(&StepView),
) -> Result<Vec<LoadRun>> {
    run_sliding_resumable(top, bottom, setup, None, |_| {}, observe)
}

/// [`run_sliding`] that saves its state to `checkpointing.path` every `checkpointing.every` and,
/// when that file holds the state of a run of the same inputs, resumes from it instead of starting
/// at s = 0. The results equal those of an uninterrupted run bit for bit: the state saved is all one
/// step hands to the next (the contact pressure that warm-starts the solver, the bookkeeping of
/// every d*, the memory of the initial contact, the records so far). `on_resume` is told, before any
/// step, what became of the file. The caller removes the file once the results are written.
pub fn run_sliding_resumable(
    top: &Surface,
    bottom: &Surface,
    setup: &SlidingSetup,
    checkpointing: Option<&Checkpointing>,
    mut on_resume: impl FnMut(&Resumed),
    mut observe: impl FnMut(&StepView),
) -> Result<Vec<LoadRun>> {
    let grid: Grid = top.grid();
    let (nx, ny) = (grid.nx(), grid.ny());
    if bottom.nx() != nx || bottom.ny() != ny || (bottom.length() - top.length()).abs() > 1e-12 * top.length() {
        return Err(Error::param(
            "surface",
            format!(
                "top ({nx}×{ny} pixels, side {}) and bottom ({}×{} pixels, side {}) surfaces must share grid and side \
                 length",
                top.length(),
                bottom.nx(),
                bottom.ny(),
                bottom.length()
            ),
        ));
    }
    crate::check::memory("a sliding run", nx, ny, crate::check::SLIDING_ARRAYS)?;
    let area = grid.area();
    let dx = grid.pixel_size();
    let pm = setup.material.flow_pressure();
    for &load in &setup.sliding.loads {
        crate::check::load(load, area, pm)?;
    }
    if setup.material.fracture_energies.is_empty() {
        return Err(Error::param(
            "fracture_energies",
            "the material has none; give at least one 𝒢 to count wear",
        ));
    }
    setup.sliding.check_grid(nx)?;
    let offsets = setup.sliding.offsets(nx);
    let running_in = setup.sliding.running_in_pixels(nx);
    let diameters = setup.material.critical_diameters();
    let total_steps = offsets.len() * setup.sliding.loads.len();
    let mut solver = ContactSolver::on_device(setup.device, grid, setup.effective_modulus, Boundary::Periodic)?
        .with_options(setup.solver)
        .with_interrupt(setup.interrupt.clone());
    let mut labeller = JunctionLabeller::new(nx, ny, setup.connectivity);
    let mut scratch = vec![false; nx * ny];
    let mut junctions = Vec::new();
    let key = inputs_key(top, bottom, setup);
    let (mut saved, resumed) = match checkpointing {
        None => (None, Resumed::Fresh),
        Some(c) => match load_checkpoint(&c.path, &key, &mut solver, setup, diameters.len(), offsets.len()) {
            Ok(None) => (None, Resumed::Fresh),
            Ok(Some(state)) => {
                let at = Resumed::At {
                    done: state.done,
                    total: total_steps,
                };
                (Some(state), at)
            }
            Err(why) => (None, Resumed::Ignored(why)),
        },
    };
    on_resume(&resumed);
    let mut runs = saved
        .as_mut()
        .map(|s| std::mem::take(&mut s.finished))
        .unwrap_or_default();
    let mut done = saved.as_ref().map_or(0, |s| s.done);
    let mut last_save = Instant::now();
    // The state of the last finished step, saved when the run is stopped (a solve interrupted part
    // way has already changed the solver's pressure): one more Nx·Ny field while checkpointing.
    let mut saver = checkpointing.map(|c| StopSaver::new(c, done, total_steps, grid.pixels()));
    for (load_index, &load) in setup.sliding.loads.iter().enumerate().skip(runs.len()) {
        // A checkpoint taken between two loads holds no step of the next one: it starts cold.
        let (mut books, mut memory, mut steps, mut timing) = match saved.take().filter(|s| !s.steps.is_empty()) {
            // The checkpoint's pressure is already the solver's.
            Some(state) => (
                diameters
                    .iter()
                    .zip(state.books)
                    .map(|(&d, b)| SlidingBookkeeping::restored(d, b))
                    .collect::<Vec<_>>(),
                state.memory,
                state.steps,
                state.timing,
            ),
            None => {
                solver.set_pressure(|p| p.fill(0.0)); // cold start at s = 0 of every load
                (
                    diameters.iter().map(|&d| SlidingBookkeeping::new(d)).collect(),
                    InitialContactMemory::default(),
                    Vec::with_capacity(offsets.len()),
                    Timing::default(),
                )
            }
        };
        for (step_index, &offset) in offsets.iter().enumerate().skip(steps.len()) {
            let t0 = Instant::now();
            let info = setup
                .interrupt
                .check()
                .and_then(|()| solver.compose(top, bottom, offset))
                .and_then(|()| solver.solve_in_place(load / area, pm));
            let info = match (info, saver.as_mut()) {
                (Ok(info), _) => info,
                (Err(Error::Interrupted), Some(saver)) => {
                    let state = SavedState::of(&key, done, &runs, &steps, timing, &books, &memory);
                    saver.save_on_stop(&state, &mut on_resume);
                    return Err(Error::Interrupted);
                }
                (Err(e), _) => return Err(e),
            };
            let t1 = Instant::now();
            let map = solver.contact_map();
            let count = labeller.label(|k| map.contains(k));
            labeller.junctions_into(dx, &mut junctions);
            let t2 = Instant::now();
            let statics: Vec<StaticWear> = diameters.iter().map(|&d| static_wear(&junctions, d)).collect();
            let wear: Vec<StepWear> = books
                .iter_mut()
                .map(|b| b.step(&labeller, &junctions, &mut scratch))
                .collect();
            let initial_junctions = memory.step(&labeller, &mut scratch);
            let t3 = Instant::now();
            timing.solve += (t1 - t0).as_secs_f64();
            timing.labelling += (t2 - t1).as_secs_f64();
            timing.bookkeeping += (t3 - t2).as_secs_f64();
            steps.push(StepRecord {
                offset,
                s: offset as f64 * dx,
                junctions: count,
                wrapping_junctions: labeller.wrapping(),
                contact_area: info.contact_pixels as f64 / grid.pixels() as f64,
                initial_junctions,
                iterations: info.iterations,
                residual: info.residual,
                wear,
                statics,
            });
            done += 1;
            observe(&StepView {
                done,
                total: total_steps,
                load_index,
                step_index,
                record: steps.last().expect("a step was just recorded"),
                pressure: solver.pressure(),
                labeller: &labeller,
                bookkeeping: &books,
            });
            if let (Some(c), Some(saver)) = (checkpointing, saver.as_mut()) {
                saver.keep(solver.pressure(), done);
                if done < total_steps && last_save.elapsed() >= c.every {
                    let state = SavedState::of(&key, done, &runs, &steps, timing, &books, &memory);
                    saver.save(&state, &mut on_resume);
                    last_save = Instant::now();
                }
            }
        }
        let (results, warnings) = results_of_load(setup, load, pm, &steps, running_in);
        runs.push(LoadRun {
            load,
            total_iterations: steps.iter().map(|r| r.iterations).sum(),
            max_iterations: steps.iter().map(|r| r.iterations).max().unwrap_or(0),
            steps,
            results,
            timing,
            warnings,
        });
    }
    Ok(runs)
}

/// The fitted results of one load per fracture energy (paper §3 and appendices B, C), and the
/// warnings about them.
fn results_of_load(
    setup: &SlidingSetup,
    load: f64,
    pm: f64,
    steps: &[StepRecord],
    running_in: usize,
) -> (Vec<WearResult>, Vec<String>) {
    let fitted: Vec<&StepRecord> = steps.iter().filter(|r| r.offset >= running_in).collect();
    let s: Vec<f64> = fitted.iter().map(|r| r.s).collect();
    let mut warnings = Vec::new();
    // Memory of the initial contact: ln N₀ against s over the steps where N₀ > 0.
    let decaying: Vec<&StepRecord> = steps.iter().filter(|r| r.initial_junctions > 0).collect();
    let memory = line_fit(
        &decaying.iter().map(|r| r.s).collect::<Vec<_>>(),
        &decaying
            .iter()
            .map(|r| (r.initial_junctions as f64).ln())
            .collect::<Vec<_>>(),
    );
    let (memory_decay_length, memory_decay_r2, memory_fit_initial_junctions) = match memory {
        Some(f) if f.slope < 0.0 => {
            let length = finite(-1.0 / f.slope);
            (length, f.r2, length.and(finite(f.intercept.exp())))
        }
        _ => (None, None, None),
    };
    let fit_start = fitted.first().map_or(0.0, |r| r.s);
    let running_in_decay_lengths = match (memory_decay_length, memory) {
        (Some(l), _) => finite(fit_start / l),
        // The lineages of s = 0 do not thin out: an infinite decay length.
        (None, Some(_)) => Some(0.0),
        (None, None) => None,
    };
    if let Some(r) = running_in_decay_lengths.filter(|r| *r < RUN_IN_DECAY_LENGTHS) {
        let decay = memory_decay_length.map_or("does not decay".to_string(), |l| format!("decays over ℓ = {l:.4e}"));
        warnings.push(format!(
            "F_N = {load:.4e}: not run in: the memory of the initial contact {decay}, and the fit window starts at s = \
             {fit_start:.4e}, {r:.2} decay lengths (under {RUN_IN_DECAY_LENGTHS}), with {:.0} % of the junction \
             lineages of s = 0 expected still present; raise `running_in` (and `distance`) to at least \
             {RUN_IN_DECAY_LENGTHS} ℓ",
            100.0 * (-r).exp()
        ));
    }
    let (junctions_mean, _) = mean_std(fitted.iter().map(|r| r.junctions as f64));
    let wrapping: Vec<&StepRecord> = steps.iter().filter(|r| r.wrapping_junctions > 0).collect();
    if let Some(first) = wrapping.first() {
        warnings.push(format!(
            "F_N = {load:.4e}: at {} of {} steps (the first at s = {:.4e}) a junction wraps the periodic box \
             (contact area up to {:.3} of the box): it is no particle of the model, which needs finite junctions \
             (paper §3), yet it is counted as one in N, V and k_static; lower the load or enlarge the box",
            wrapping.len(),
            steps.len(),
            first.s,
            wrapping.iter().map(|r| r.contact_area).fold(0.0, f64::max),
        ));
    }
    let results = setup
        .material
        .critical_diameters()
        .into_iter()
        .enumerate()
        .map(|(e, d)| {
            let g = setup.material.fracture_energies[e];
            let v: Vec<f64> = fitted.iter().map(|r| r.wear[e].volume).collect();
            let nf: Vec<f64> = fitted.iter().map(|r| r.wear[e].n_formed as f64).collect();
            let particle_fit = line_fit(&s, &nf);
            let particles_in_fit = match (fitted.first(), fitted.last()) {
                (Some(a), Some(b)) => b.wear[e].n_formed - a.wear[e].n_formed,
                _ => 0,
            };
            // Without a particle V is constant over the window: W = 0 exactly and R² undefined (a
            // least-squares fit of equal values leaves round-off, a slope of ±1e-30 and any R²).
            let wear_fit = line_fit(&s, &v).map(|f| match v.first() {
                Some(&v0) if particles_in_fit == 0 => LineFit {
                    slope: 0.0,
                    intercept: v0,
                    r2: None,
                },
                _ => f,
            });
            let wear_rate = wear_fit.and_then(|f| finite(f.slope));
            let wear_volume_intercept = wear_fit.filter(|_| wear_rate.is_some()).and_then(|f| finite(f.intercept));
            let particle_rate = particle_fit.and_then(|f| finite(f.slope));
            let wear_rate_r2 = wear_fit.and_then(|f| f.r2);
            let context = format!("F_N = {load:.4e}, 𝒢 = {g:.4e} (d* = {d:.4e})");
            if particles_in_fit == 0 {
                warnings.push(format!(
                    "{context}: no particle formed after running-in, so W = 0 and its fit (R²) is undefined; no junction \
                     grows to d* in this box at this load"
                ));
            } else if particles_in_fit < FEW_PARTICLES {
                warnings.push(format!(
                    "{context}: only {particles_in_fit} particles formed after running-in (fewer than {FEW_PARTICLES}); W \
                     rests on a handful of events"
                ));
            }
            if let Some(r2) = wear_rate_r2.filter(|r2| *r2 < 0.8) {
                warnings.push(format!("{context}: the wear-rate fit is poor (R² = {r2:.3} < 0.8); V(s) is not linear"));
            }
            let (k_mean, k_std) = mean_std(steps.iter().map(|r| r.statics[e].wear_coefficient));
            let (w_mean, w_std) = mean_std(steps.iter().map(|r| r.statics[e].wear_rate_over_omega));
            let (critical_junctions_mean, _) = mean_std(fitted.iter().map(|r| r.wear[e].n_critical as f64));
            WearResult {
                fracture_energy: g,
                critical_diameter: d,
                wear_rate,
                wear_rate_r2,
                wear_volume_intercept,
                fit_window_start: fit_start,
                wear_coefficient: wear_rate.and_then(|w| finite(w * pm / load)),
                particle_rate,
                wear_rate_estimate: particle_rate
                    .and_then(|rate| finite(std::f64::consts::PI / 6.0 * d.powi(3) * rate)),
                particles_in_fit,
                initial_volume: steps[0].wear[e].volume,
                static_wear_coefficient: steps[0].statics[e].wear_coefficient,
                static_wear_rate: steps[0].statics[e].wear_rate_over_omega,
                static_wear_coefficient_mean: k_mean,
                static_wear_coefficient_std: k_std,
                static_wear_rate_mean: w_mean,
                static_wear_rate_std: w_std,
                junctions_mean,
                critical_junctions_mean,
                box_wrapping_steps: wrapping.len(),
                memory_decay_length,
                memory_decay_r2,
                memory_fit_initial_junctions,
                running_in_decay_lengths,
                critical_residence: particle_rate
                    .filter(|r| *r > 0.0)
                    .and_then(|r| finite(critical_junctions_mean / r)),
            }
        })
        .collect();
    (results, warnings)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn schedule(distance: f64, running_in: f64, step: usize) -> SlidingConfig {
        SlidingConfig {
            loads: vec![1e-3],
            distance,
            running_in,
            step_running_in: DEFAULT_STEP_RUNNING_IN,
            step,
        }
    }

    #[test]
    fn paper_schedule_has_1280_offsets_at_4096_and_160_at_512() {
        // The defaults are the paper's schedule (§3).
        let cfg = schedule(DEFAULT_DISTANCE, DEFAULT_RUNNING_IN, DEFAULT_STEP);
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
}
