//! The static maps solved: one contact solver bound to the surfaces, every load per offset, the
//! settled contact map and its junctions labelled.

use std::sync::Arc;

use crate::contact::{ContactSolver, Stopping};
use crate::error::{Error, Result};
use crate::influence::Boundary;
use crate::junctions::{circle_area, Junction, JunctionLabeller};
use crate::sliding::SlidingSetup;
use crate::surface::Surface;
use crate::wear::{is_critical, static_wear};

use super::calibration::{Calibration, CALIBRATION};
use super::reach::{load_estimate, run_reach, SurfaceKind, CALIBRATED_DOMAIN};
use super::rule::{critical_stats, fit_distance, sampling_error, LoadEstimate};
use super::samples::{
    sample_offsets, Sample, SampleCount, Sampling, MAX_SAMPLES, MIN_SAMPLES, RESOLVED_CRITICAL_JUNCTIONS,
    TARGET_SAMPLING_ERROR,
};

/// An estimate under way: the solver bound to the surfaces, and the maps solved so far.
pub struct Estimator<'a> {
    setup: &'a SlidingSetup<'a>,
    solver: ContactSolver,
    labeller: JunctionLabeller,
    junctions: Vec<Junction>,
    diameters: Vec<f64>,
    nx: usize,
    area: f64,
    /// Lx × Ly.
    box_sides: (f64, f64),
    dx: f64,
    /// Per load, the maps so far.
    samples: Vec<Vec<Sample>>,
}

impl<'a> Estimator<'a> {
    /// Binds the solver to the surfaces (periodic, the settled contact map as in a sliding step).
    pub fn new(top: Surface, bottom: Surface, setup: &'a SlidingSetup<'a>) -> Result<Self> {
        let grid = top.grid();
        if bottom.grid() != grid {
            return Err(Error::param(
                "surface",
                "the top and bottom surfaces lie on different grids; give both on one grid",
            ));
        }
        let mut solver = ContactSolver::on_device(setup.device, grid, setup.effective_modulus, Boundary::Periodic)?
            .with_options(setup.solver.with_stopping(Stopping::SettledMap))
            .with_interrupt(setup.interrupt.clone());
        solver.bind_surfaces(Arc::new(top), Arc::new(bottom))?;
        Ok(Self {
            setup,
            solver,
            labeller: JunctionLabeller::new(grid.nx(), grid.ny(), setup.connectivity),
            junctions: Vec::new(),
            diameters: setup.material.critical_diameters(),
            nx: grid.nx(),
            area: grid.area(),
            box_sides: (grid.length_x(), grid.length_y()),
            dx: grid.pixel_size(),
            samples: vec![Vec::new(); setup.sliding.loads.len()],
        })
    }

    /// Maps solved so far per load.
    pub fn samples_done(&self) -> usize {
        self.samples.first().map_or(0, Vec::len)
    }

    /// Solves the next offset of the sequence at every load (each load warm-started from the
    /// previous one's pressure, the first cold) and labels its junctions. `on_solve` is called after
    /// each solve.
    pub fn add_sample(&mut self, mut on_solve: impl FnMut()) -> Result<()> {
        let k = self.samples_done();
        if k >= MAX_SAMPLES {
            return Err(Error::param(
                "estimate_samples",
                format!("at most {MAX_SAMPLES} static maps"),
            ));
        }
        let offset = sample_offsets(self.nx, k + 1)[k];
        self.solver.compose(offset)?;
        self.solver.set_pressure(|p| p.fill(0.0));
        let pm = self.setup.material.flow_pressure();
        for (l, &load) in self.setup.sliding.loads.iter().enumerate() {
            self.setup.interrupt.check()?;
            let info = self.solver.solve_in_place(load / self.area, pm)?;
            let map = self.solver.contact_map();
            let count = self.labeller.label(|i| map.contains(i));
            self.labeller.junctions_into(self.dx, &mut self.junctions);
            let counts = self
                .diameters
                .iter()
                .map(|&d| {
                    let a = circle_area(d);
                    let (n, sum) = self
                        .junctions
                        .iter()
                        .filter(|j| is_critical(j, a))
                        .fold((0, 0.0), |(n, s), j| (n + 1, s + j.diameter));
                    let statics = static_wear(&self.junctions, d);
                    SampleCount {
                        critical_junctions: n,
                        diameter_sum: sum,
                        static_wear_coefficient: statics.wear_coefficient,
                        static_wear_rate: statics.wear_rate_over_omega,
                    }
                })
                .collect();
            self.samples[l].push(Sample {
                offset,
                junctions: count,
                wrapping_junctions: self.labeller.wrapping(),
                contact_area: info.contact_pixels as f64 / (self.area / (self.dx * self.dx)),
                iterations: info.iterations,
                counts,
            });
            on_solve();
        }
        Ok(())
    }

    /// The largest sampling error of N* ([`sampling_error`], the one each result reports and its
    /// interval takes) among the loads and 𝒢 with N* ≥ [`RESOLVED_CRITICAL_JUNCTIONS`] (0 when
    /// there is none).
    pub fn sampling_error(&self) -> f64 {
        self.samples
            .iter()
            .flat_map(|s| (0..self.diameters.len()).map(move |e| (critical_stats(s, e).0, sampling_error(s, e))))
            .filter(|(mean, _)| *mean >= RESOLVED_CRITICAL_JUNCTIONS)
            .filter_map(|(_, err)| err)
            .fold(0.0, f64::max)
    }

    /// Takes maps until `sampling` is met: a fixed number, or from [`MIN_SAMPLES`] until the
    /// sampling error is at most [`TARGET_SAMPLING_ERROR`] (or [`MAX_SAMPLES`] are taken).
    pub fn sample(&mut self, sampling: Sampling, mut on_solve: impl FnMut()) -> Result<()> {
        loop {
            let k = self.samples_done();
            let enough = match sampling {
                Sampling::Fixed(n) => k >= n,
                Sampling::Auto => {
                    k >= MAX_SAMPLES || (k >= MIN_SAMPLES && self.sampling_error() <= TARGET_SAMPLING_ERROR)
                }
            };
            if enough {
                return Ok(());
            }
            self.add_sample(&mut on_solve)?;
        }
    }

    /// The estimate of every load from the maps taken, with `calibration`'s constants, on surfaces
    /// of kind `surfaces`. With the library's constants ([`CALIBRATION`]) each load's warnings say
    /// where its setting lies outside their reach ([`CALIBRATED_DOMAIN`]: [`run_reach_warnings`](super::reach::run_reach_warnings),
    /// [`load_reach_warnings`](super::reach::load_reach_warnings)); with constants of one's own, a note says that their reach is the
    /// runs they were fitted on.
    pub fn finish(self, calibration: &Calibration, surfaces: &SurfaceKind) -> Vec<LoadEstimate> {
        let length = self.nx as f64 * self.dx;
        let fit_distance = fit_distance(self.setup.sliding, length);
        let own = !calibration.same_constants(&CALIBRATION);
        let (run_warnings, reach) = if own {
            let note = format!(
                "the estimate uses the run file's `estimate_constants` (c₁ = {:.4}, c₂ = {:.4}, c_v = {:.4}), not the \
                 library's calibration: their reach is the sliding runs they were fitted on, which this estimate cannot \
                 check",
                calibration.residence_factor, calibration.merging_factor, calibration.volume_factor
            );
            (vec![note], Vec::new())
        } else {
            (
                Vec::new(),
                run_reach(&CALIBRATED_DOMAIN, surfaces, self.setup.sliding, length),
            )
        };
        self.setup
            .sliding
            .loads
            .iter()
            .zip(self.samples)
            .map(|(&load, samples)| {
                let (results, mut warnings) = load_estimate(
                    &samples,
                    self.setup.material,
                    load,
                    self.box_sides,
                    fit_distance,
                    calibration,
                    &reach,
                );
                warnings.extend(run_warnings.iter().cloned());
                LoadEstimate {
                    load,
                    results,
                    samples,
                    warnings,
                }
            })
            .collect()
    }
}
