//! The sliding simulation as a state that takes one step at a time (paper §3): set up once (the
//! solver and its fields, the labeller), then each [`SlidingState::step`] slides the top surface by
//! one offset of the schedule, solves the contact warm-started from the previous step, labels the
//! junctions, and advances the particle rule of every fracture energy, the static model and the
//! memory of the initial contact; a load's results are fitted when its last step is done. A
//! checkpoint saves the state between two steps and [`SlidingState::resume`] continues from one.
//! Every front end drives this one loop (through `run::SlidingRun`).

use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

use crate::contact::ContactSolver;
use crate::error::{Error, Result};
use crate::grid::Grid;
use crate::influence::Boundary;
use crate::junctions::{Junction, JunctionLabeller};
use crate::surface::Surface;
use crate::wear::shear::{JunctionGeometry, ShearCompliance};
use crate::wear::{
    static_wear, InitialContactMemory, JunctionState, LabelledStep, ParticleRule, ShearStep, StaticWear, StepWear,
};

use super::checkpoint::{
    inputs_key, load_checkpoint, save_checkpoint, LoadedState, Resumed, SavedState, CHECKPOINT_FORMAT,
};
use super::fit::results_of_load;
use super::records::{LoadRun, StepRecord, Timing};
use super::schedule::SlidingSetup;

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
    /// The time this step took, by part.
    pub timing: Timing,
    /// The labelled contact map of this step.
    pub labeller: &'a JunctionLabeller,
    /// The particle rule of every fracture energy, with the junction states of this step.
    pub rules: &'a [Box<dyn ParticleRule>],
    solver: &'a mut ContactSolver,
}

impl StepView<'_> {
    /// This step's contact pressure (row-major, x first), fetched from the solver only when asked.
    pub fn pressure(&mut self) -> &[f64] {
        self.solver.pressure()
    }

    /// The state of every junction of this step (indexed like the labeller's junctions) under the
    /// particle rule of fracture energy `energy` (its index in the material's list).
    pub fn junction_states(&self, energy: usize) -> &[JunctionState] {
        self.rules[energy].states()
    }
}

/// The load under way: what one step hands to the next.
struct LoadState {
    /// The particle rule of every fracture energy.
    rules: Vec<Box<dyn ParticleRule>>,
    memory: InitialContactMemory,
    steps: Vec<StepRecord>,
    timing: Timing,
}

/// The largest junction's equivalent diameter over the box's shorter side (0 without contact).
fn largest_junction(junctions: &[Junction], grid: Grid) -> f64 {
    let largest = junctions.iter().fold(0.0, |d: f64, j| d.max(j.diameter));
    largest / grid.length_x().min(grid.length_y())
}

/// The shear of this step for a rule that needs it: the junction geometry filled from the labels.
fn shear_step<'s>(
    shear: &'s mut Option<(ShearCompliance, JunctionGeometry)>,
    labeller: &JunctionLabeller,
    junctions: &[Junction],
) -> Option<ShearStep<'s>> {
    shear.as_mut().map(|(compliance, geometry)| {
        geometry.fill(labeller, junctions);
        ShearStep {
            compliance: &*compliance,
            geometry: &*geometry,
        }
    })
}

/// A sliding run between two steps (module documentation).
pub(crate) struct SlidingState<'a> {
    setup: SlidingSetup<'a>,
    /// The surfaces, shared with the solver, which composes each offset's heights from them.
    top: Arc<Surface>,
    bottom: Arc<Surface>,
    solver: ContactSolver,
    labeller: JunctionLabeller,
    /// Nx·Ny flags shared by the particle rules and the memory, all false between their steps.
    scratch: Vec<bool>,
    junctions: Vec<Junction>,
    /// The box's shear compliance (made once) and each step's junction geometry, for a particle
    /// rule that needs them (`ParticleRuleKind::needs_shear`); `None` otherwise.
    shear: Option<(ShearCompliance, JunctionGeometry)>,
    offsets: Vec<usize>,
    /// The running-in distance in pixels: the fit window starts there.
    running_in: usize,
    diameters: Vec<f64>,
    grid: Grid,
    /// Hash of the run's inputs, which a checkpoint carries (made when first needed).
    key: Option<String>,
    /// Loads finished, with their results.
    finished: Vec<LoadRun>,
    load: Option<LoadState>,
    done: usize,
    total: usize,
    /// The contact pressure after the last finished step, kept (one more Nx·Ny field) once
    /// [`SlidingState::keep_state_for_stops`] asks: a solve stopped part-way has already changed
    /// the solver's pressure, and a checkpoint saved then must hold the state between two steps.
    kept: Option<Vec<f64>>,
    /// A solve failed or was stopped part-way: the solver's pressure is no step's.
    pressure_unsettled: bool,
}

impl<'a> SlidingState<'a> {
    /// Checks the run and makes what every step reuses: the solver (its fields, FFT plans and
    /// influence operator) and the labeller. The surfaces are shared, not copied: a run's few
    /// probing steps and the run itself slide on the same two.
    pub(crate) fn new(top: Arc<Surface>, bottom: Arc<Surface>, setup: SlidingSetup<'a>) -> Result<Self> {
        let grid = top.grid();
        check_run(&top, &bottom, &setup)?;
        let offsets = setup.sliding.offsets(grid.nx());
        let mut solver = ContactSolver::on_device(setup.device, grid, setup.effective_modulus, Boundary::Periodic)?
            .with_options(setup.solver)
            .with_interrupt(setup.interrupt.clone());
        solver.bind_surfaces(Arc::clone(&top), Arc::clone(&bottom))?;
        Ok(Self {
            labeller: JunctionLabeller::new(grid.nx(), grid.ny(), setup.connectivity),
            scratch: vec![false; grid.pixels()],
            junctions: Vec::new(),
            shear: setup.sliding.particle_rule.kind.needs_shear.then(|| {
                (
                    ShearCompliance::new(grid.nx(), grid.ny(), setup.material.poisson_ratio),
                    JunctionGeometry::default(),
                )
            }),
            running_in: setup.sliding.running_in_pixels(grid.nx()),
            diameters: setup.material.critical_diameters(),
            total: offsets.len() * setup.sliding.loads.len(),
            offsets,
            grid,
            key: None,
            finished: Vec::new(),
            load: None,
            done: 0,
            kept: None,
            pressure_unsettled: false,
            solver,
            top,
            bottom,
            setup,
        })
    }

    /// Steps done, over all loads.
    pub(crate) fn done(&self) -> usize {
        self.done
    }

    /// Steps of every load together.
    pub(crate) fn total(&self) -> usize {
        self.total
    }

    /// Keeps the contact pressure of every finished step from now on, so that a run stopped
    /// part-way through a solve can still save the state between its last two steps.
    pub(crate) fn keep_state_for_stops(&mut self) {
        if self.kept.is_none() {
            let pressure = self.solver.pressure().to_vec();
            self.kept = Some(pressure);
        }
    }

    /// The hash of the run's inputs that its checkpoints carry.
    fn key(&mut self) -> &str {
        let (top, bottom, setup) = (&self.top, &self.bottom, &self.setup);
        self.key.get_or_insert_with(|| inputs_key(top, bottom, setup))
    }

    /// Takes the next step; `None` once every load is done. A raised interrupt ends the run with
    /// [`Error::Interrupted`] before the step.
    pub(crate) fn step(&mut self) -> Result<Option<StepView<'_>>> {
        self.end_load_if_done();
        if self.finished.len() == self.setup.sliding.loads.len() {
            return Ok(None);
        }
        self.setup.interrupt.check()?;
        if self.load.is_none() {
            self.load = Some(self.begin_load());
        }
        let load_index = self.finished.len();
        let load = self.setup.sliding.loads[load_index];
        let step_index = self.load.as_ref().expect("a load under way").steps.len();
        let offset = self.offsets[step_index];
        let dx = self.grid.pixel_size();
        let slid = step_index
            .checked_sub(1)
            .map_or(0.0, |i| (offset - self.offsets[i]) as f64 * dx);

        let t0 = Instant::now();
        let info = self.solve_at(offset, load)?;
        let t1 = Instant::now();
        let map = self.solver.contact_map();
        let count = self.labeller.label(|k| map.contains(k));
        self.labeller.junctions_into(dx, &mut self.junctions);
        let t2 = Instant::now();
        let statics: Vec<StaticWear> = self
            .diameters
            .iter()
            .map(|&d| static_wear(&self.junctions, d))
            .collect();
        let state = self.load.as_mut().expect("a load under way");
        let shear = shear_step(&mut self.shear, &self.labeller, &self.junctions);
        let labelled = LabelledStep {
            labeller: &self.labeller,
            junctions: &self.junctions,
            slid,
            shear,
        };
        let wear: Vec<StepWear> = state
            .rules
            .iter_mut()
            .map(|rule| rule.step(&labelled, &mut self.scratch))
            .collect();
        let initial_junctions = state.memory.step(&self.labeller, &mut self.scratch);
        let t3 = Instant::now();
        let timing = Timing {
            solve: (t1 - t0).as_secs_f64(),
            labelling: (t2 - t1).as_secs_f64(),
            bookkeeping: (t3 - t2).as_secs_f64(),
        };
        state.timing.solve += timing.solve;
        state.timing.labelling += timing.labelling;
        state.timing.bookkeeping += timing.bookkeeping;
        state.steps.push(StepRecord {
            offset,
            s: offset as f64 * dx,
            junctions: count,
            wrapping_junctions: self.labeller.wrapping(),
            contact_area: info.contact_pixels as f64 / self.grid.pixels() as f64,
            initial_junctions,
            merged_junctions: Some(state.memory.merged_junctions()),
            largest_junction: Some(largest_junction(&self.junctions, self.grid)),
            iterations: info.iterations,
            residual: info.residual,
            wear,
            statics,
        });
        self.done += 1;
        Ok(Some(StepView {
            done: self.done,
            total: self.total,
            load_index,
            step_index,
            timing,
            record: state.steps.last().expect("a step was just recorded"),
            labeller: &self.labeller,
            rules: &state.rules,
            solver: &mut self.solver,
        }))
    }

    /// The contact solve of a step at `offset` (pixels) under `load`, warm-started from the pressure
    /// in the solver (the previous step's); the pressure kept for a checkpoint follows it.
    fn solve_at(&mut self, offset: usize, load: f64) -> Result<crate::contact::SolveInfo> {
        self.pressure_unsettled = true;
        self.solver.compose(offset)?;
        let info = self
            .solver
            .solve_in_place(self.grid.mean_pressure(load), self.setup.material.flow_pressure())?;
        self.pressure_unsettled = false;
        if let Some(kept) = self.kept.as_mut() {
            kept.copy_from_slice(self.solver.pressure());
        }
        Ok(info)
    }

    /// A load begins at s = 0 from a cold start, with fresh particle rules and memory.
    fn begin_load(&mut self) -> LoadState {
        self.solver.set_pressure(|p| p.fill(0.0));
        LoadState {
            rules: self.new_rules(),
            memory: InitialContactMemory::default(),
            steps: Vec::with_capacity(self.offsets.len()),
            timing: Timing::default(),
        }
    }

    fn new_rules(&self) -> Vec<Box<dyn ParticleRule>> {
        let rule = &self.setup.sliding.particle_rule;
        let dx = self.grid.pixel_size();
        self.diameters.iter().map(|&d| rule.make(d, dx)).collect()
    }

    /// Once the load under way has taken its last step: its results fitted, the load finished.
    fn end_load_if_done(&mut self) {
        let Some(state) = self.load.take_if(|l| l.steps.len() == self.offsets.len()) else {
            return;
        };
        let load = self.setup.sliding.loads[self.finished.len()];
        let pm = self.setup.material.flow_pressure();
        let sides = (self.grid.length_x(), self.grid.length_y());
        let (mut results, mut warnings) = results_of_load(&self.setup, load, pm, &state.steps, self.running_in, sides);
        warnings.extend(state.rules.iter().flat_map(|r| r.warnings(load)));
        for (w, rule) in results.iter_mut().zip(&state.rules) {
            w.combined_particles = rule.combined_particles();
        }
        let steps = state.steps;
        self.finished.push(LoadRun {
            load,
            total_iterations: steps.iter().map(|r| r.iterations).sum(),
            max_iterations: steps.iter().map(|r| r.iterations).max().unwrap_or(0),
            steps,
            results,
            timing: state.timing,
            warnings,
        });
    }

    /// Slides the steps left, unobserved, and gives the runs of every load.
    pub(crate) fn finish(mut self) -> Result<Vec<LoadRun>> {
        while self.step()?.is_some() {}
        Ok(self.finished)
    }

    /// Saves the state between two steps to `path` (atomically: temporary sibling, then renamed over
    /// the old file): everything one step hands to the next (the contact pressure that warm-starts
    /// the solver, every particle rule's state, the memory of the initial contact, the records so
    /// far). Gives `false` when there is nothing to save (no step finished yet). After a solve
    /// stopped part-way it needs the pressure kept since [`SlidingState::keep_state_for_stops`].
    pub(crate) fn save_checkpoint(&mut self, path: &Path) -> Result<bool> {
        if self.done == 0 {
            return Ok(false);
        }
        if self.pressure_unsettled && self.kept.is_none() {
            return Err(Error::file(
                path,
                "the run was stopped part-way through a solve and did not keep the state of its last step",
            ));
        }
        let key = self.key().to_string();
        // Between two loads (or stopped before the first step of a load finished), the next load
        // starts cold: its particle rules and memory are fresh.
        let fresh = self.new_rules();
        let no_memory = InitialContactMemory::default();
        let (steps, timing, rules, memory) = match &self.load {
            Some(l) if !l.steps.is_empty() => (&l.steps[..], l.timing, &l.rules, &l.memory),
            _ => (&[][..], Timing::default(), &fresh, &no_memory),
        };
        let state = SavedState {
            format: CHECKPOINT_FORMAT,
            software: format!("wearsim {}", crate::io::VERSION),
            inputs: &key,
            done: self.done,
            finished: &self.finished,
            steps,
            timing,
            books: rules.iter().map(|r| r.carried()).collect(),
            memory,
        };
        let pressure = match &self.kept {
            Some(kept) => kept.as_slice(),
            None => self.solver.pressure(),
        };
        save_checkpoint(path, &state, pressure).map(|()| true)
    }

    /// Before the first step: continues from the checkpoint at `path` when it holds the state of a
    /// run of the same inputs (the results then equal those of an uninterrupted run bit for bit),
    /// and says what became of the file.
    pub(crate) fn resume(&mut self, path: &Path) -> Resumed {
        if self.done > 0 {
            return Resumed::Ignored(format!("{}: the run has already begun", path.display()));
        }
        let key = self.key().to_string();
        let (energies, steps) = (self.diameters.len(), self.offsets.len());
        let pm = self.setup.material.flow_pressure();
        match load_checkpoint(path, &key, &mut self.solver, pm, energies, steps) {
            Ok(None) => Resumed::Fresh,
            Err(why) => Resumed::Ignored(why),
            Ok(Some(state)) => match self.restore(state) {
                Ok(()) => Resumed::At {
                    done: self.done,
                    total: self.total,
                },
                Err(why) => {
                    self.solver.set_pressure(|p| p.fill(0.0));
                    Resumed::Ignored(format!(
                        "{}: {why}; the run starts over and replaces it",
                        path.display()
                    ))
                }
            },
        }
    }

    /// The state of a checkpoint made this run's (its pressure is already the solver's).
    fn restore(&mut self, state: LoadedState) -> std::result::Result<(), String> {
        let mut rules = self.new_rules();
        for (rule, carried) in rules.iter_mut().zip(state.books) {
            rule.restore(carried)
                .map_err(|e| format!("unreadable particle rule state ({e})"))?;
        }
        self.finished = state.finished;
        self.done = state.done;
        // A checkpoint between two loads holds no step of the next one: it begins cold.
        self.load = (!state.steps.is_empty()).then(|| LoadState {
            rules,
            memory: state.memory,
            steps: state.steps,
            timing: state.timing,
        });
        if let Some(kept) = self.kept.as_mut() {
            kept.copy_from_slice(self.solver.pressure());
        }
        Ok(())
    }
}

/// What a sliding run needs of its inputs, checked before any work: surfaces on one grid, memory
/// for the run, loads the flow pressure can carry, at least one fracture energy, a schedule that
/// fits the grid.
fn check_run(top: &Surface, bottom: &Surface, setup: &SlidingSetup) -> Result<()> {
    let grid = top.grid();
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
    crate::check::memory("a sliding run", nx, ny, setup.sliding.memory_arrays())?;
    let pm = setup.material.flow_pressure();
    for &load in &setup.sliding.loads {
        crate::check::load("loads", load, grid.area(), pm)?;
    }
    if setup.material.fracture_energies.is_empty() {
        return Err(Error::param(
            "fracture_energies",
            "the material has none; give at least one 𝒢 to count wear",
        ));
    }
    setup.sliding.check_grid(nx)
}
