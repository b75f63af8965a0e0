//! The sliding simulation (paper §3): slide the top surface over the bottom one along x,
//! solve the contact at every offset (warm-started from the previous step), label the junctions,
//! and advance one wear bookkeeping per fracture energy on the shared contact solutions. Ends with
//! the least-squares wear rate, particle rate and Archard wear coefficient after running-in.

use std::time::Instant;

use crate::config::{RunConfig, SlidingConfig};
use crate::contact::{ContactSolver, SolverOptions};
use crate::error::{Error, Interrupt, Result};
use crate::junctions::JunctionLabeller;
use crate::material::Material;
use crate::surface::{composite_heights, Surface};
use crate::wear::{static_wear, SlidingBookkeeping, StaticWear, StepWear};

/// Sliding offsets in pixels (paper §3): from 0 in steps of `step_running_in` while below the
/// running-in distance, then from the running-in distance in steps of `step` while below the total
/// distance (the end point excluded). Distances are rounded to whole pixels.
pub fn schedule(n: usize, sliding: &SlidingConfig) -> Vec<usize> {
    let running_in = (sliding.running_in * n as f64).round() as usize;
    let distance = (sliding.distance * n as f64).round() as usize;
    let mut offsets: Vec<usize> = (0..running_in).step_by(sliding.step_running_in).collect();
    offsets.extend((running_in..distance).step_by(sliding.step));
    offsets
}

/// One step of one load: the contact statistics and, per fracture energy, the wear record.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct StepRecord {
    /// Offset in pixels.
    pub offset: usize,
    /// Sliding distance s in the run's length unit.
    pub s: f64,
    /// Number of junctions N.
    pub junctions: usize,
    /// Real contact area as a fraction of the apparent area.
    pub contact_area: f64,
    /// Solver iterations of this step.
    pub iterations: usize,
    /// Solver residual of this step.
    pub residual: f64,
    /// Wear record per fracture energy, in the material's order.
    pub wear: Vec<StepWear>,
}

/// Least-squares slope of y against x, and its coefficient of determination R².
pub fn line_fit(x: &[f64], y: &[f64]) -> (f64, f64) {
    let m = x.len() as f64;
    if x.len() < 2 {
        return (f64::NAN, f64::NAN);
    }
    let (mx, my) = (x.iter().sum::<f64>() / m, y.iter().sum::<f64>() / m);
    let sxx: f64 = x.iter().map(|a| (a - mx) * (a - mx)).sum();
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let syy: f64 = y.iter().map(|b| (b - my) * (b - my)).sum();
    let slope = sxy / sxx;
    let ss_res = syy - slope * sxy;
    let r2 = if syy > 0.0 { 1.0 - ss_res / syy } else { 1.0 };
    (slope, r2)
}

/// Results per load and fracture energy (paper §3–4); also the record stored in study job files.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct WearResult {
    pub fracture_energy: f64,
    pub critical_diameter: f64,
    /// W = dV/ds fitted after running-in (volume per sliding distance).
    pub wear_rate: f64,
    /// R² of the wear-rate fit.
    pub wear_rate_r2: f64,
    /// k = W p̃ / F_N (Archard).
    pub wear_coefficient: f64,
    /// dN*₊/ds fitted after running-in (particles per sliding distance).
    pub particle_rate: f64,
    /// Check value ω d*³ dN*₊/ds with ω = π/6 (the paper finds it slightly below W).
    pub wear_rate_estimate: f64,
    /// V₀, the volume counted at s = 0.
    pub initial_volume: f64,
    /// Static model at s = 0: k_static.
    pub static_wear_coefficient: f64,
    /// Static model at s = 0: W_static/ω = k_static Σ A_i.
    pub static_wear_rate: f64,
}

/// Time spent per part of the sliding loop, in seconds.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct Timing {
    pub solve: f64,
    pub labelling: f64,
    pub bookkeeping: f64,
}

/// One load's sliding run.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct LoadRun {
    /// Normal load F_N.
    pub load: f64,
    pub steps: Vec<StepRecord>,
    pub results: Vec<WearResult>,
    pub total_iterations: usize,
    pub max_iterations: usize,
    pub timing: Timing,
}

/// Everything a sliding run needs besides the surfaces.
#[derive(Debug, Clone)]
pub struct SlidingSetup<'a> {
    pub material: &'a Material,
    pub effective_modulus: f64,
    pub solver: SolverOptions,
    pub connectivity: u8,
    pub sliding: &'a SlidingConfig,
    /// Raised by another thread to stop the run ([`Error::Interrupted`]).
    pub interrupt: Interrupt,
}

impl<'a> SlidingSetup<'a> {
    /// The setup a run file describes, for the given schedule (the run's own, or one load of it).
    pub fn from_run(run: &'a RunConfig, sliding: &'a SlidingConfig) -> Self {
        Self {
            material: &run.material,
            effective_modulus: run.effective_modulus(),
            solver: run.solver,
            connectivity: run.connectivity,
            sliding,
            interrupt: Interrupt::default(),
        }
    }
}

/// What an observer of a sliding run sees after each step.
pub struct StepView<'a> {
    /// Steps done so far, over all loads, and their total.
    pub done: usize,
    pub total: usize,
    /// Index of the load in `setup.sliding.loads`.
    pub load_index: usize,
    /// This step's record.
    pub record: &'a StepRecord,
    /// The labelled contact map of this step.
    pub labeller: &'a JunctionLabeller,
    /// The bookkeeping of every fracture energy, with the junction states of this step.
    pub bookkeeping: &'a [SlidingBookkeeping],
}

/// Runs the sliding model for every load of `setup.sliding`. `observe` is called after every step
/// (progress bars, animations); it sees the step but cannot change the run.
pub fn run_sliding(
    top: &Surface,
    bottom: &Surface,
    setup: &SlidingSetup,
    mut observe: impl FnMut(&StepView),
) -> Result<Vec<LoadRun>> {
    let n = top.n();
    if bottom.n() != n || (bottom.length() - top.length()).abs() > 1e-12 * top.length() {
        return Err(Error::param(
            "surface",
            "top and bottom surfaces must share grid and side length",
        ));
    }
    let length = top.length();
    let area = length * length;
    let dx = top.pixel_size();
    let pm = setup.material.flow_pressure();
    for &load in &setup.sliding.loads {
        if load / area >= pm {
            return Err(Error::InfeasibleLoad {
                mean_pressure: load / area,
                flow_pressure: pm,
            });
        }
    }
    if setup.material.fracture_energies.is_empty() {
        return Err(Error::param(
            "fracture_energies",
            "the material has none; give at least one 𝒢 to count wear",
        ));
    }
    for (field, step) in [
        ("step_running_in", setup.sliding.step_running_in),
        ("step", setup.sliding.step),
    ] {
        if step >= n {
            return Err(Error::param(
                field,
                format!("{step} pixels must be below the grid size {n}"),
            ));
        }
    }
    let offsets = schedule(n, setup.sliding);
    if offsets.len() < 2 {
        return Err(Error::param(
            "distance",
            "the schedule holds fewer than two offsets; raise `distance` or refine `grid`",
        ));
    }
    let running_in = (setup.sliding.running_in * n as f64).round() as usize;
    let diameters = setup.material.critical_diameters();
    let total_steps = offsets.len() * setup.sliding.loads.len();
    let mut solver = ContactSolver::new(n, length, setup.effective_modulus)?
        .with_options(setup.solver)
        .with_interrupt(setup.interrupt.clone());
    let mut labeller = JunctionLabeller::new(n, setup.connectivity);
    let mut heights = vec![0.0; n * n];
    let mut pressure = vec![0.0; n * n];
    let mut scratch = vec![false; n * n];
    let mut junctions = Vec::new();
    let mut runs = Vec::new();
    let mut done = 0;
    for (load_index, &load) in setup.sliding.loads.iter().enumerate() {
        let mut books: Vec<SlidingBookkeeping> = diameters.iter().map(|&d| SlidingBookkeeping::new(d)).collect();
        let mut statics: Vec<StaticWear> = Vec::new();
        let mut steps = Vec::with_capacity(offsets.len());
        let mut timing = Timing::default();
        pressure.iter_mut().for_each(|p| *p = 0.0); // cold start at s = 0 of every load
        for &offset in &offsets {
            setup.interrupt.check()?;
            let t0 = Instant::now();
            composite_heights(top, bottom, offset, &mut heights);
            let info = solver.solve(&heights, load / area, pm, &mut pressure)?;
            let t1 = Instant::now();
            let count = labeller.label(|k| pressure[k] > 0.0);
            labeller.junctions_into(dx, &mut junctions);
            let t2 = Instant::now();
            if offset == 0 {
                statics = diameters.iter().map(|&d| static_wear(&junctions, d)).collect();
            }
            let wear: Vec<StepWear> = books
                .iter_mut()
                .map(|b| b.step(&labeller, &junctions, &mut scratch))
                .collect();
            let t3 = Instant::now();
            timing.solve += (t1 - t0).as_secs_f64();
            timing.labelling += (t2 - t1).as_secs_f64();
            timing.bookkeeping += (t3 - t2).as_secs_f64();
            steps.push(StepRecord {
                offset,
                s: offset as f64 * dx,
                junctions: count,
                contact_area: info.contact_pixels as f64 / (n * n) as f64,
                iterations: info.iterations,
                residual: info.residual,
                wear,
            });
            done += 1;
            observe(&StepView {
                done,
                total: total_steps,
                load_index,
                record: steps.last().expect("a step was just recorded"),
                labeller: &labeller,
                bookkeeping: &books,
            });
        }
        let fitted: Vec<&StepRecord> = steps.iter().filter(|r| r.offset >= running_in).collect();
        let s: Vec<f64> = fitted.iter().map(|r| r.s).collect();
        let results = diameters
            .iter()
            .enumerate()
            .map(|(e, &d)| {
                let v: Vec<f64> = fitted.iter().map(|r| r.wear[e].volume).collect();
                let nf: Vec<f64> = fitted.iter().map(|r| r.wear[e].n_formed as f64).collect();
                let (wear_rate, wear_rate_r2) = line_fit(&s, &v);
                let (particle_rate, _) = line_fit(&s, &nf);
                WearResult {
                    fracture_energy: setup.material.fracture_energies[e],
                    critical_diameter: d,
                    wear_rate,
                    wear_rate_r2,
                    wear_coefficient: wear_rate * pm / load,
                    particle_rate,
                    wear_rate_estimate: std::f64::consts::PI / 6.0 * d.powi(3) * particle_rate,
                    initial_volume: steps[0].wear[e].volume,
                    static_wear_coefficient: statics[e].wear_coefficient,
                    static_wear_rate: statics[e].wear_rate_over_omega,
                }
            })
            .collect();
        runs.push(LoadRun {
            load,
            total_iterations: steps.iter().map(|r| r.iterations).sum(),
            max_iterations: steps.iter().map(|r| r.iterations).max().unwrap_or(0),
            steps,
            results,
            timing,
        });
    }
    Ok(runs)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_schedule_has_1280_offsets_at_4096_and_160_at_512() {
        let cfg = SlidingConfig {
            loads: vec![1e-3],
            distance: 0.5,
            running_in: 0.25,
            step_running_in: 4,
            step: 1,
        };
        let s = schedule(4096, &cfg);
        assert_eq!(s.len(), 1280);
        assert_eq!(&s[..3], &[0, 4, 8]);
        assert_eq!(s[255], 1020);
        assert_eq!(s[256], 1024);
        assert_eq!(*s.last().unwrap(), 2047);
        assert_eq!(schedule(512, &cfg).len(), 160);
    }

    #[test]
    fn line_fit_is_exact_on_a_line() {
        let x = [0.0, 1.0, 2.0, 3.0];
        let y = [1.0, 3.0, 5.0, 7.0];
        let (slope, r2) = line_fit(&x, &y);
        assert!((slope - 2.0).abs() < 1e-14 && (r2 - 1.0).abs() < 1e-14);
    }
}
