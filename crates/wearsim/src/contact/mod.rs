//! Saturated-pressure (elastic–perfectly-plastic) contact of a rigid rough surface on an elastic
//! half-space, solved by FFT boundary elements (paper §2 and appendix A).
//!
//! Problem: find p minimising ½⟨p, 𝒦p⟩ − ⟨p, h⟩ subject to 0 ≤ p ≤ p_m and mean(p) = F_N/(Lx Ly), where
//! 𝒦 is the half-space's influence operator ([`crate::influence`]): periodic, û(q) = 2 p̂(q)/(E*|k|)
//! as in the paper, or with a free boundary around the map (Hockney's zero-padded FFT), the
//! pressure confined to the map. Its optimality conditions, with
//! g = 𝒦p − h and c the Lagrange multiplier of the load (the rigid body's position), are
//! g + c ≥ 0 where p = 0, g + c = 0 where 0 < p < p_m, g + c ≤ 0 where p = p_m.
//! The bound p_m is the law at the surface (`backend::SurfaceLaw`: saturated, or elastic where
//! p_m = ∞), bound to the backend at the set-up of each solve; plasticity in the volume beneath is
//! not modelled, and would be an outer loop around the solves that rewrites the heights between
//! them (`contact::backend` says how).
//!
//! Algorithm: the constrained conjugate gradient of Polonsky & Keer (1999), extended to the upper
//! bound as in the bound-constrained CG of Vollebregt (2014): conjugate directions live on the free
//! pixels 0 < p < p_m (made zero-mean there so that a step keeps the load); pixels that cross a bound
//! are clipped to it (exact zeros outside the contact); bound pixels whose gap says they should move
//! (penetrating non-contact pixels, plastic pixels whose gap opens) are released with a gradient step
//! and restart the conjugation; the load is then restored exactly by scaling. A step that left the
//! CG line is kept where the objective descends, else undone and shortened fourfold (projected
//! search). One that clipped so many free pixels to p_m that the plastic pixels alone carry more
//! than the load is shortened at once, before its 𝒦p: the scaling could balance it only by
//! lowering the whole plastic zone, and where that zone holds most of the load (the paper's
//! setting) the objective then rises.
//!
//! Cost: one convolution 𝒦t per iteration, in two halves. The step length needs only the
//! curvature Σ t·𝒦t, which by Parseval's identity comes from the forward transform of t alone;
//! the inverse half, r = 𝒦t, is completed from that transform only when the step stays on the CG
//! line, and carries the displacement u = 𝒦p along as u ← u − τr. A step that clipped, released
//! or rescaled p off the line recomputes u = 𝒦p instead (so it never needs r), as does the last
//! iteration before convergence is declared, so that the final residual is that of a freshly
//! computed 𝒦p. Where the conjugate direction lives on few pixels (the free pixels of a contact
//! that is almost all plastic, as in the paper's setting), the curvature is summed over their
//! pairs with the kernel in real space instead ([`crate::influence::PairForm`]): a step that
//! changes the sets then makes only its 𝒦p, one that stays on the line its whole convolution 𝒦t.
//! A warm start (a sliding step) keeps the u of the previous solve's final 𝒦p, bit for bit, when
//! its set-up leaves p as it is (a guess that carries the load to round-off is not rescaled): only
//! the heights moved, so its first statistics need no convolution.
//!
//! Residual (the convergence criterion, reported with every result): the largest pixel-wise
//! violation of the three optimality conditions above, divided by the RMS of h about its mean:
//! `max_i v_i / std(h)` with v_i = |g_i + c| on free pixels, max(0, −(g_i + c)) on non-contact pixels
//! and max(0, g_i + c) on plastic pixels, c = −mean over free pixels of g.
//!
//! Stopping ([`Stopping`]): a solve stops when the residual reaches the tolerance, or, for the
//! solves of a sliding run, as soon as its contact map is settled. The wear model reads only the
//! contact map {p > 0} (its connected components are the junctions, paper §3), never the pressure
//! to the tolerance, so a sliding step needs the map exact, not the pressure. The map counts as
//! settled when, on a freshly computed displacement,
//! 1. the last iteration was a pure conjugate-gradient step: it changed neither the contact nor
//!    the plastic set (nothing clipped to or released from a bound, no load rebalanced);
//! 2. no pixel is about to flip by its own motion: every non-contact pixel's gap g + c exceeds
//!    [`SETTLED_CHANGE_FACTOR`] times what that gap moved in the last iteration, and every contact
//!    pixel's pressure that many times what its pressure moved;
//! 3. no pixel is within a fraction of the residual ρ of flipping: every non-contact pixel's gap,
//!    and every contact pixel's pressure as the gap it would open, 𝒦ᵢᵢ p (𝒦ᵢᵢ the displacement of
//!    a pixel under its own unit pressure), exceed [`SETTLED_MARGIN`] ρ std(h);
//! 4. ρ is at most [`SETTLED_MAX_RESIDUAL`] (the floor: a solve far from converged is never
//!    certified, whatever its margins), or the tolerance is reached.
//!
//! Conditions 2 and 3 are estimates, not a proof: they assume that no pixel moves, on the way to
//! the converged solution, by much more than it moved in the last iteration or by the residual. A
//! rigorous bound exists (the duality gap bounds ‖p − p*‖ in the 𝒦-norm, and
//! |(𝒦e)ᵢ| ≤ √(𝒦ᵢᵢ) ‖e‖_𝒦), but on these problems it is orders of magnitude looser than the
//! residual and would certify nothing before the tolerance. What the rule promises is therefore
//! the tested one: on the problems of `docs/validation.md` (small grids at many offsets, and the
//! sliding runs there) every settled map equals the map of the tight solve, pixel for pixel. It
//! holds for this solver's path, not for the rule alone: two other restart rules, tried, made the
//! stop certify a map one pixel off, so a change of the path must pass those checks again.

pub(crate) mod backend;
#[cfg(test)]
mod conformance;
mod cpu;
mod options;
mod profile;
#[cfg(test)]
mod spy;

use std::sync::Arc;

use rayon::prelude::*;

use self::backend::{ContactBackend, LoadSums, Stats, SurfaceLaw, Update};
use self::cpu::CpuBackend;
pub use self::options::{
    SolveInfo, SolverOptions, Stopping, Termination, DEFAULT_MAX_ITERATIONS, DEFAULT_TOLERANCE, MIN_TOLERANCE,
    SETTLED_CHANGE_FACTOR, SETTLED_MARGIN, SETTLED_MAX_RESIDUAL, SLIDING_STOPPING,
};
pub use self::profile::{median_seconds, PassTiming};
use crate::check::positive;
use crate::error::{Error, Interrupt, Result};
use crate::grid::Grid;
use crate::influence::Boundary;
use crate::surface::Surface;

/// The displacement and gap of a solution ([`ContactSolver::gap_and_displacement`]), Nx·Ny values
/// each in length units.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactFields {
    /// Surface displacement of the half-space, u = 𝒦p (zero-mean when periodic).
    pub displacement: Vec<f64>,
    /// Gap g = 𝒦p − h + δ between the rigid surface and the deformed half-space.
    pub gap: Vec<f64>,
}

/// Where the contact solver computes: the backend behind the algorithm's field passes
/// (backend (`contact::backend`)), chosen by `[contact] device` in a run file.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Device {
    /// Host memory and threads (rayon), the FFT of `realfft`.
    #[default]
    Cpu,
    /// An NVIDIA GPU through CUDA. No backend for it is part of this build: choosing it is an error.
    Cuda,
}

impl Device {
    /// The name used in run files, on the command line and in Python.
    pub fn name(self) -> &'static str {
        match self {
            Device::Cpu => "cpu",
            Device::Cuda => "cuda",
        }
    }

    /// Whether this build can compute on the device: checked when a run file is read, before any
    /// output is made, and again when a solver is made.
    pub fn available(self) -> Result<()> {
        match self {
            Device::Cpu => Ok(()),
            Device::Cuda => Err(no_gpu_backend()),
        }
    }
}

/// The error of a device this build has no backend for.
fn no_gpu_backend() -> Error {
    Error::param(
        "device",
        "\"cuda\" asks for the GPU backend, which this build of wearsim does not contain; use \"cpu\" (the default)",
    )
}

impl std::str::FromStr for Device {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "cpu" => Ok(Device::Cpu),
            "cuda" => Ok(Device::Cuda),
            other => Err(Error::param(
                "device",
                format!("{other:?} is not a device; use \"cpu\" (or \"cuda\" for an NVIDIA GPU)"),
            )),
        }
    }
}

/// Whether a pixel of pressure `p` is in contact: p > 0 (paper §3: the connected components of the
/// contact map are the junctions). NaN is not.
#[inline]
pub fn in_contact(p: f64) -> bool {
    p > 0.0
}

/// The contact map of a pressure field, one bool per pixel in its order ([`in_contact`]): what
/// `wearsim contact` writes as contact.npy and Python's `ContactResult.contact` is.
pub fn contact_map(pressure: &[f64]) -> Vec<bool> {
    pressure.iter().map(|&p| in_contact(p)).collect()
}

/// Which pixels are in contact (p > 0) after a solve, as labelling reads them: one bit per pixel,
/// made by the backend where the fields live (only the bits cross to the host).
#[derive(Debug, Clone, Copy)]
pub struct ContactMap<'a> {
    bits: &'a [u64],
}

impl ContactMap<'_> {
    /// Whether pixel `k` (row-major) is in contact.
    #[inline]
    pub fn contains(&self, k: usize) -> bool {
        backend::contact_bit(self.bits, k)
    }
}

/// FFT contact solver for one grid: the algorithm of the module documentation over a
/// backend (`contact::backend`) that holds the fields (made once here and reused by every solve: a sliding run makes
/// one solver).
pub struct ContactSolver {
    grid: Grid,
    effective_modulus: f64,
    device: Device,
    backend: Box<dyn ContactBackend>,
    /// Whether surfaces are bound for [`ContactSolver::compose`].
    bound: bool,
    options: SolverOptions,
    /// Checked once per iteration: a raised flag ends the solve with [`Error::Interrupted`].
    interrupt: Interrupt,
    /// Whether the backend's u is 𝒦p of its p: the last solve ended on a freshly computed 𝒦p and
    /// p has not been written since. A warm start whose p the set-up leaves as it is then reads
    /// its statistics from that u (only the heights moved) instead of convolving again.
    displacement_current: bool,
}

/// Largest gap between an initial guess's Σp and the load, relative to the load on the free
/// pixels, under which the set-up takes the guess as it is (the load balance would move the free
/// pixels by at most this fraction: round-off of the last solve's balance, summed in another order).
const WARM_LOAD_ROUNDOFF: f64 = 1e-12;

/// The constants of one solve and the state carried from one iteration to the next.
struct SolveState {
    /// The law at the surface, bound to the backend for this solve: its flow pressure p_m enters
    /// the load balance's scalars here, and every pass there.
    law: SurfaceLaw,
    /// Total load Σp = Nx Ny F_N/(Lx Ly).
    total: f64,
    /// Residual scale: std(h), or P·L/E* for a flat surface.
    scale: f64,
    h_std: f64,
    h_max: f64,
    /// Statistics of g = 𝒦p − h over the free, non-contact and plastic pixels of the current p.
    stats: Stats,
    /// Shift subtracted from g in `stats` (the previous mean gap), for accurate sums.
    reference: f64,
    /// Whether u was computed from p by FFT, not carried along.
    fresh: bool,
    /// Whether the next direction restarts the conjugation.
    restart: bool,
    g_norm_old: f64,
    iterations: usize,
    convolutions: usize,
    /// After a pure conjugate-gradient step: the least slack of conditions 2 of the module
    /// documentation over non-contact pixels (gap) and contact pixels (pressure), positive where
    /// every pixel is farther from flipping than κ times its last move; `None` after a step that
    /// changed the sets.
    moves: Option<(f64, f64)>,
}

impl ContactSolver {
    /// Solver for a periodic grid (Nx × Ny square pixels) on a half-space of effective modulus E*,
    /// on the CPU.
    pub fn new(grid: Grid, effective_modulus: f64) -> Result<Self> {
        Self::on_device(Device::Cpu, grid, effective_modulus, Boundary::Periodic)
    }

    /// Solver on a half-space of effective modulus E* whose map is periodic or has a free boundary
    /// (see [`crate::influence`]), on the CPU; the algorithm is the same, only 𝒦 differs.
    pub fn with_boundary(grid: Grid, effective_modulus: f64, boundary: Boundary) -> Result<Self> {
        Self::on_device(Device::Cpu, grid, effective_modulus, boundary)
    }

    /// Solver on `device`: the one place a backend is chosen. A device this build has no backend
    /// for is an error naming the fix.
    pub fn on_device(device: Device, grid: Grid, effective_modulus: f64, boundary: Boundary) -> Result<Self> {
        positive("effective_modulus", effective_modulus)?;
        let backend: Box<dyn ContactBackend> = match device {
            Device::Cpu => {
                crate::check::memory("the contact solver", grid.nx(), grid.ny(), cpu::arrays(boundary))?;
                Box::new(CpuBackend::new(grid, effective_modulus, boundary)?)
            }
            Device::Cuda => return Err(no_gpu_backend()),
        };
        Ok(Self {
            device,
            ..Self::with_backend(grid, effective_modulus, backend)
        })
    }

    /// A solver over a backend made elsewhere (the conformance test's reference).
    pub(crate) fn with_backend(grid: Grid, effective_modulus: f64, backend: Box<dyn ContactBackend>) -> Self {
        Self {
            grid,
            effective_modulus,
            device: Device::Cpu,
            backend,
            bound: false,
            options: SolverOptions::default(),
            interrupt: Interrupt::default(),
            displacement_current: false,
        }
    }

    /// The grid.
    pub fn grid(&self) -> Grid {
        self.grid
    }

    /// Effective modulus E*.
    pub fn effective_modulus(&self) -> f64 {
        self.effective_modulus
    }

    /// Where the solver computes.
    pub fn device(&self) -> Device {
        self.device
    }

    /// The solver with these convergence settings (validated by [`SolverOptions::new`]).
    pub fn with_options(mut self, options: SolverOptions) -> Self {
        self.options = options;
        self
    }

    /// The solver checking `interrupt` once per iteration.
    pub fn with_interrupt(mut self, interrupt: Interrupt) -> Self {
        self.interrupt = interrupt;
        self
    }

    /// Replaces the interrupt flag (a solver kept across calls that each bring their own flag).
    pub fn set_interrupt(&mut self, interrupt: Interrupt) {
        self.interrupt = interrupt;
    }

    /// Convergence settings.
    pub fn options(&self) -> SolverOptions {
        self.options
    }

    /// The half-space's boundary condition at the edges of the map.
    pub fn boundary(&self) -> Boundary {
        self.backend.boundary()
    }

    /// Applies the influence operator: `out = 𝒦 p`, the displacement of the half-space (zero-mean
    /// when periodic).
    pub fn apply_influence(&mut self, pressure: &[f64], out: &mut [f64]) {
        self.backend.apply_influence(pressure, out);
    }

    /// The fields of a solution that other programs read beside the pressure: the displacement
    /// u = 𝒦p and the gap g = 𝒦p − h + δ, with δ = max(h) − approach the rigid body's position (the
    /// c of the module documentation), all in length units. g is the separation of the two surfaces:
    /// 0 on contact pixels below the flow pressure, ≥ 0 outside the contact, ≤ 0 (interpenetration
    /// taken up by plastic flow) on pixels at p_m, each to within the solve's residual × std(h).
    pub fn gap_and_displacement(
        &mut self,
        heights: &[f64],
        pressure: &[f64],
        info: &SolveInfo,
    ) -> Result<ContactFields> {
        self.check_len(heights, pressure)?;
        let mut displacement = vec![0.0; heights.len()];
        self.backend.apply_influence(pressure, &mut displacement);
        let h_max = heights.par_iter().copied().reduce(|| f64::NEG_INFINITY, f64::max);
        let shift = h_max - info.approach;
        let gap = displacement
            .par_iter()
            .zip(heights.par_iter())
            .map(|(&u, &h)| u - h + shift)
            .collect();
        Ok(ContactFields { displacement, gap })
    }

    fn check_len(&self, heights: &[f64], pressure: &[f64]) -> Result<()> {
        let nn = self.grid.pixels();
        if heights.len() != nn || pressure.len() != nn {
            return Err(Error::param(
                "heights",
                format!(
                    "heights and pressure must hold {}×{} values",
                    self.grid.nx(),
                    self.grid.ny()
                ),
            ));
        }
        Ok(())
    }

    /// Solves the contact of the rigid surface of heights `heights` at mean pressure
    /// `mean_pressure` = F_N/(Lx Ly), with flow pressure `flow_pressure` (`f64::INFINITY` for a purely
    /// elastic solve). `pressure` is both the initial guess and the result: pass the previous
    /// step's converged field to warm-start, or zeros for a cold start (uniform pressure).
    /// Reaching the iteration limit is an [`Error::NotConverged`].
    pub fn solve(
        &mut self,
        heights: &[f64],
        mean_pressure: f64,
        flow_pressure: f64,
        pressure: &mut [f64],
    ) -> Result<SolveInfo> {
        let info = self.run(heights, mean_pressure, flow_pressure, pressure)?;
        converged(info)
    }

    /// [`ContactSolver::solve`] that returns the state reached at the iteration limit instead of an
    /// error: the caller inspects [`SolveInfo::termination`] (and `pressure` holds the last
    /// iterate). A raised interrupt flag still ends the solve with [`Error::Interrupted`].
    pub fn run(
        &mut self,
        heights: &[f64],
        mean_pressure: f64,
        flow_pressure: f64,
        pressure: &mut [f64],
    ) -> Result<SolveInfo> {
        self.check_len(heights, pressure)?;
        self.backend.write_heights(&mut |h| h.copy_from_slice(heights));
        self.backend.write_pressure(&mut |p| p.copy_from_slice(pressure));
        self.displacement_current = false;
        let info = self.run_in_place(mean_pressure, flow_pressure)?;
        pressure.copy_from_slice(self.backend.pressure());
        Ok(info)
    }

    /// Binds the two surfaces of a sliding run, fixed for the run (a device backend copies them
    /// there once; the CPU keeps the shared handles, no copy): [`ContactSolver::compose`] then
    /// sets the heights of each offset where the solver's fields live.
    pub fn bind_surfaces(&mut self, top: Arc<Surface>, bottom: Arc<Surface>) -> Result<()> {
        let (nx, ny) = (self.grid.nx(), self.grid.ny());
        if top.nx() != nx || top.ny() != ny || bottom.nx() != nx || bottom.ny() != ny {
            return Err(Error::param(
                "surface",
                format!("the surfaces must have the solver's {nx}×{ny} grid"),
            ));
        }
        self.backend.bind_surfaces(top, bottom);
        self.bound = true;
        Ok(())
    }

    /// Sets the heights of the next in-place solve to the composite topography of the bound top
    /// surface slid by `offset` pixels over the bound bottom one
    /// ([`composite_heights`](crate::surface::composite_heights)).
    pub fn compose(&mut self, offset: usize) -> Result<()> {
        if !self.bound {
            return Err(Error::param(
                "surface",
                "no surfaces are bound to the solver; bind them (`bind_surfaces`) before composing",
            ));
        }
        self.backend.compose(offset);
        Ok(())
    }

    /// Sets the pressure that the next in-place solve starts from: `fill` writes it, row-major,
    /// into Nx·Ny values (zeros for a cold start; a warm start keeps the previous solution, which
    /// needs no call).
    pub fn set_pressure(&mut self, mut fill: impl FnMut(&mut [f64])) {
        self.backend.write_pressure(&mut fill);
        self.displacement_current = false;
    }

    /// The pressure of the last solve (or as set), row-major.
    pub fn pressure(&mut self) -> &[f64] {
        self.backend.pressure()
    }

    /// The contact map of the last solve (or of the pressure as set), as the backend makes it.
    pub fn contact_map(&mut self) -> ContactMap<'_> {
        ContactMap {
            bits: self.backend.contact_map(),
        }
    }

    /// Times each pass of an iteration on the solver's current fields (call it after a solve and
    /// [`ContactSolver::compose`] of the next offset; `wearsim bench --passes`), `repeats` calls
    /// each, median kept, with flow pressure `flow_pressure`. The first two entries are the
    /// references: a copy pass over one field (the bandwidth floor) and an FFT round trip with the
    /// kernel multiply. The pressure is left as it was; the next solve recomputes the rest.
    pub fn profile_passes(&mut self, flow_pressure: f64, repeats: usize) -> Vec<PassTiming> {
        // Its timed `advance` steps move u.
        self.displacement_current = false;
        self.backend.bind_law(SurfaceLaw::of_flow_pressure(flow_pressure));
        profile::passes(&mut *self.backend, self.grid.ny(), repeats)
    }

    /// [`ContactSolver::solve`] on the heights set by [`ContactSolver::compose`] from the
    /// solver's own pressure (the previous solution, a warm start), which it replaces: no field
    /// crosses between the caller and the backend.
    pub fn solve_in_place(&mut self, mean_pressure: f64, flow_pressure: f64) -> Result<SolveInfo> {
        let info = self.run_in_place(mean_pressure, flow_pressure)?;
        converged(info)
    }

    /// The algorithm: set-up, iterations until the residual reaches the tolerance (confirmed on a
    /// freshly computed displacement) or the iteration limit.
    fn run_in_place(&mut self, mean_pressure: f64, flow_pressure: f64) -> Result<SolveInfo> {
        let mut state = self.start(mean_pressure, flow_pressure)?;
        // Until this solve ends on a fresh 𝒦p.
        self.displacement_current = false;
        loop {
            let mean = state.stats.mean_gap(state.reference);
            let residual = state.stats.violation(mean) / state.scale;
            let converged = residual <= self.options.tolerance;
            if converged || self.settled(&state, mean, residual) {
                if state.fresh {
                    self.displacement_current = true;
                    let termination = if converged {
                        Termination::Converged
                    } else {
                        Termination::Settled
                    };
                    return Ok(self.finish(&state, mean, residual, termination));
                }
                // Confirm with an exactly balanced load and a freshly computed displacement.
                self.balance_load(&state, mean, Some(state.stats.load));
                state.reference = mean;
                state.stats = self.backend.displacement_and_stats(state.reference);
                state.convolutions += 1;
                state.fresh = true;
                continue;
            }
            if state.iterations >= self.options.max_iterations {
                return Ok(self.finish(&state, mean, residual, Termination::MaxIterations));
            }
            self.interrupt.check()?;
            self.iterate(&mut state, mean);
        }
    }

    /// Set-up of a solve: checks the inputs, measures the heights, makes the initial guess (the
    /// given field when usable, else uniform pressure) carry the load (to within
    /// [`WARM_LOAD_ROUNDOFF`] of the free pixels' load), and computes its statistics (from the
    /// displacement kept from the last solve where that is still 𝒦p).
    fn start(&mut self, mean_pressure: f64, flow_pressure: f64) -> Result<SolveState> {
        let nn = self.grid.pixels();
        positive("load", mean_pressure)?;
        if flow_pressure.is_nan() || flow_pressure <= 0.0 {
            return Err(Error::param(
                "flow_pressure",
                format!("{flow_pressure} must be positive"),
            ));
        }
        if mean_pressure >= flow_pressure {
            return Err(Error::InfeasibleLoad {
                mean_pressure,
                flow_pressure,
            });
        }
        let heights = self.backend.height_stats();
        if let Some((k, h)) = heights.not_finite {
            let n = self.grid.ny();
            return Err(Error::InvalidSurface {
                name: "composite".into(),
                message: format!("height at ({}, {}) is {}", k / n, k % n, h),
            });
        }
        // The law at the surface, bound once for the passes of this solve.
        let law = SurfaceLaw::of_flow_pressure(flow_pressure);
        self.backend.bind_law(law);
        let total = mean_pressure * nn as f64;
        let shift_mean = heights.sum / nn as f64;
        let h_std = (heights.sum_sq / nn as f64 - shift_mean * shift_mean).max(0.0).sqrt();
        // Residual scale: the surface's RMS height, or for a flat surface the elastic length P·L/E*.
        let scale = if h_std > 0.0 {
            h_std
        } else {
            mean_pressure * self.grid.length_x() / self.effective_modulus
        };
        let kept = self.backend.initial_guess(mean_pressure);
        let mut state = SolveState {
            law,
            total,
            scale,
            h_std,
            h_max: heights.max,
            stats: Stats::default(),
            reference: 0.0,
            fresh: true,
            restart: true,
            g_norm_old: 1.0,
            iterations: 0,
            convolutions: 0,
            moves: None,
        };
        // A guess that carries the load to round-off (a warm start: the last solve balanced it,
        // and these sums, in another order, differ in the last bits) is taken as it is. If it is
        // also the p of the last solve's final 𝒦p, u is that 𝒦p bit for bit (only the heights
        // moved): its statistics need no convolution, and equal a fresh one's.
        let sums = self.backend.load_sums();
        let slack = (sums.free + sums.plastic - total).abs();
        let balanced = slack <= WARM_LOAD_ROUNDOFF * sums.free;
        if !balanced {
            self.balance_load(&state, f64::NAN, Some(sums));
        }
        if kept && balanced && self.displacement_current {
            state.stats = self.backend.stats(state.reference);
        } else {
            state.stats = self.backend.displacement_and_stats(state.reference);
            state.convolutions += 1;
        }
        Ok(state)
    }

    /// One iteration: the conjugate direction on the free pixels, its convolution, and the step
    /// (clipped to the bounds, releasing bound pixels whose gap points inwards), shortened until the
    /// objective descends when it left the CG line.
    fn iterate(&mut self, state: &mut SolveState, mean: f64) {
        let total = state.total;
        state.iterations += 1;

        // Conjugate direction on the free pixels: t = (g − ḡ) + β t.
        let g_norm = state.stats.gradient_norm_sq(state.reference, mean);
        let beta = if state.restart || state.g_norm_old <= 0.0 {
            0.0
        } else {
            g_norm / state.g_norm_old
        };
        state.g_norm_old = g_norm;
        let (sum_t, sum_dt) = self.backend.direction(mean, beta);
        let n_free = state.stats.n_free;
        let shift = if n_free > 0.0 { sum_t / n_free } else { 0.0 };

        // The step's curvature Σ_free t_f·𝒦t_f (scaled), t_f = t − shift on free pixels (zero mean
        // there), from the pairs of the free pixels where they are few (no transform), else from the
        // forward transform of t_f alone (half a convolution): r = 𝒦t_f is needed only if the step
        // stays on the CG line, and then comes from the same transform when one was made.
        let (curvature, kept) = match self.backend.direct_curvature(shift) {
            Some(form) => (form, false),
            None => (self.backend.curvature(shift), true),
        };
        state.convolutions += usize::from(kept);
        let (tau, cg_step) = if n_free > 0.0 && curvature > 0.0 && sum_dt > 0.0 {
            // Σ r·t_f = curvature × response_scale, both exact: τ = Σ (g − ḡ)t / Σ r·t_f.
            (sum_dt / curvature / self.backend.response_scale(), true)
        } else {
            (1.0 / self.backend.self_influence(), false)
        };

        // Step, clip to the bounds, release bound pixels whose gap points inwards. A step on the
        // CG line carries u along, u −= τ𝒦t_f, with the next iteration's statistics in the same
        // pass; a step that changed p off the line is checked on the objective and shortened until
        // it descends (projected search). `intact`: the transform of t_f is still there.
        let (energy_before, plastic_before) = (state.stats.energy, state.stats.load.plastic);
        let slack = 1e-13 * (energy_before.abs() + total * state.h_std.max(state.h_max.abs()));
        let (mut tau, mut intact, mut backtracks) = (tau, kept, 0);
        loop {
            let update = self.backend.update(mean, tau, if cg_step { shift } else { f64::NAN });
            let drift = (update.total - total).abs() > 1e-12 * total;
            if !(update.clipped || update.released || drift || !cg_step) {
                self.advance_on_line(state, mean, (tau, shift), intact);
                break;
            }
            // A step that clipped so many free pixels to p_m that the plastic pixels alone now
            // carry the load (they did not before) could be balanced only by lowering the whole
            // plastic zone, whose gaps ask for more pressure. Where that zone holds most of the
            // load (a warm solve in the paper's setting) the objective then rises to first order,
            // as every such step traced at 4096² did: the step is shortened at once, without its
            // 𝒦p (u stays as it is). Early in a cold solve such a step may descend; shortening it
            // there changes the path, not the solution.
            let overloaded = update.load.plastic >= total && plastic_before < total;
            if overloaded && backtracks < 40 {
                self.backend.keep_displacement();
            } else {
                let carried = (cg_step && !update.released).then_some(intact);
                let energy = self.step_off_line(state, mean, &update, (tau, shift), carried);
                state.restart = update.released || backtracks > 0;
                if energy <= energy_before + slack || backtracks >= 40 {
                    break;
                }
                intact = false;
            }
            // Undo: p from its copy, u as it was.
            self.backend.undo();
            tau *= 0.25;
            backtracks += 1;
        }
        state.reference = mean;
    }

    /// A step off the CG line, which may have moved pixels between the sets (clipped, released,
    /// the load balanced): the load restored (with u carried along the CG step `(τ, shift)` first
    /// where the contact cannot carry it and `carried` says so, [`ContactSolver::spread_stepped_load`]),
    /// then u = 𝒦p and its statistics; returns the objective. The u of the step's start is kept
    /// for an undo.
    fn step_off_line(
        &mut self,
        state: &mut SolveState,
        mean: f64,
        update: &Update,
        step: (f64, f64),
        carried: Option<bool>,
    ) -> f64 {
        state.moves = None;
        if self.scale_to_load(state, Some(update.load)) {
            self.backend.keep_displacement();
        } else {
            state.convolutions += self.spread_stepped_load(state, mean, step, carried);
        }
        state.stats = self.backend.displacement_and_stats(mean);
        state.convolutions += 1;
        state.fresh = true;
        state.stats.energy
    }

    /// Whether the contact map of the current state counts as settled under
    /// [`Stopping::SettledMap`] (the conditions of the module documentation; the caller
    /// confirms on a freshly computed displacement).
    fn settled(&self, state: &SolveState, mean: f64, residual: f64) -> bool {
        let Some((gap_slack, pressure_slack)) = state.moves else {
            return false;
        };
        if self.options.stopping != Stopping::SettledMap
            || residual > SETTLED_MAX_RESIDUAL
            || gap_slack <= 0.0
            || pressure_slack <= 0.0
        {
            return false;
        }
        let stats = &state.stats;
        // Smallest gap g + c of a non-contact pixel, and smallest pressure of a contact pixel as
        // the gap it would open, both over std(h) (infinite where there is no such pixel).
        let gap_margin = (stats.min_zero - mean) / state.scale;
        let pressure_margin = stats.min_pressure * self.backend.self_influence() / state.scale;
        let needed = SETTLED_MARGIN * residual;
        gap_margin > needed && pressure_margin > needed
    }

    /// What a solve reports, from its last statistics.
    fn finish(&self, state: &SolveState, mean: f64, residual: f64, termination: Termination) -> SolveInfo {
        SolveInfo {
            termination,
            iterations: state.iterations,
            convolutions: state.convolutions,
            residual,
            tolerance: self.options.tolerance,
            approach: state.h_max + mean,
            contact_pixels: state.stats.load.n_contact,
            plastic_pixels: state.stats.n_plastic as usize,
        }
    }

    /// A step that stayed on the CG line: u follows it, u −= τ𝒦t_f, with the next statistics
    /// and each pixel's move (for the settled-map stop). 𝒦t_f is completed from the transform the
    /// curvature left when `kept`, else (after a backtrack, whose 𝒦p replaced it) afresh.
    fn advance_on_line(&mut self, state: &mut SolveState, mean: f64, (tau, shift): (f64, f64), kept: bool) {
        state.stats = self.backend.advance(mean, tau, shift, kept);
        state.convolutions += usize::from(!kept);
        state.fresh = false;
        state.restart = false;
        // Each gap moved by its τr and by the change of the mean gap −c.
        let moved = state.stats.mean_gap(mean);
        state.moves = Some((
            state.stats.settle_gap - moved - SETTLED_CHANGE_FACTOR * (moved - mean).abs(),
            state.stats.settle_pressure,
        ));
    }

    /// After a step whose contact cannot carry the load even at the flow pressure (early in a cold
    /// solve; the contact was saturated): the missing load goes to the pixels that penetrate most
    /// ([`ContactSolver::balance_load`]) once u has followed the CG step `(τ, shift)`, u −= τ𝒦t_f,
    /// when `carried` says so (`Some(kept)`, the transform of t_f kept, [`ContactBackend::advance`]),
    /// else by the u of the step's start. Leaves the u of the step's start in the spare buffer, as
    /// [`ContactBackend::keep_displacement`] does; returns the convolutions made.
    fn spread_stepped_load(
        &mut self,
        state: &SolveState,
        mean: f64,
        (tau, shift): (f64, f64),
        carried: Option<bool>,
    ) -> usize {
        match carried {
            Some(kept) => {
                self.backend.advance(mean, tau, shift, kept);
                self.balance_load(state, mean, None);
                usize::from(!kept)
            }
            None => {
                self.balance_load(state, mean, None);
                self.backend.keep_displacement();
                0
            }
        }
    }

    /// Restores the load exactly ([`ContactSolver::scale_to_load`]). Where the contact cannot carry
    /// it even at the flow pressure, the missing load goes to the non-contact pixels that penetrate
    /// most, in proportion to their penetration −(g − ḡ) (all non-contact pixels evenly when `mean`
    /// is NaN or none penetrates), then the load is balanced again.
    fn balance_load(&mut self, state: &SolveState, mean: f64, mut sums: Option<LoadSums>) {
        for _ in 0..4 {
            if self.scale_to_load(state, sums.take()) {
                return;
            }
            self.backend.spread_missing_load(state.total, mean);
        }
        self.scale_to_load(state, None);
    }

    /// Restores Σp = the state's total by scaling the free pixels, pᵢ ← min(p_m, s·pᵢ) for 0 < pᵢ < p_m, which
    /// keeps exact zeros and leaves plastic pixels at p_m (scaling them too would free the whole
    /// plastic zone at once). s solves the monotone, concave, piecewise-linear equation by Newton's
    /// method from below, which ends in finitely many steps. Where the plastic pixels alone exceed
    /// the load, every contact pixel is scaled; where even p_m on every contact pixel cannot carry
    /// it, the contact pixels are set to p_m and `false` is returned: the contact must grow.
    fn scale_to_load(&mut self, state: &SolveState, sums: Option<LoadSums>) -> bool {
        let (total, pm) = (state.total, state.law.flow_pressure());
        let sums = sums.unwrap_or_else(|| self.backend.load_sums());
        let (free_sum, plastic_sum, n_contact) = (sums.free, sums.plastic, sums.n_contact);
        if free_sum + plastic_sum == total {
            return true;
        }
        // Which pixels scale: the free ones, or all contact pixels if the plastic zone alone is too much.
        let scale_plastic = plastic_sum >= total || free_sum == 0.0;
        let (fixed, movable) = if scale_plastic {
            (0.0, free_sum + plastic_sum)
        } else {
            (plastic_sum, free_sum)
        };
        if movable <= 0.0 || pm * n_contact as f64 <= total {
            self.backend.saturate_contact();
            return false;
        }
        let target = total - fixed;
        let mut s = target / movable;
        // Without a pixel pushed to p_m the first guess is exact; otherwise Newton from below.
        let max_movable = if scale_plastic { pm } else { sums.max_free };
        let iterations = if s * max_movable < pm { 0 } else { 100 };
        for _ in 0..iterations {
            let (f, df) = self.backend.scaled_load(s, scale_plastic);
            let err = target - f;
            if err.abs() <= 1e-15 * total || df <= 0.0 {
                break;
            }
            s += err / df;
        }
        self.backend.scale(s, scale_plastic);
        true
    }
}

/// A solve that reached the iteration limit as [`Error::NotConverged`].
fn converged(info: SolveInfo) -> Result<SolveInfo> {
    match info.termination {
        Termination::Converged | Termination::Settled => Ok(info),
        Termination::MaxIterations => Err(Error::NotConverged {
            iterations: info.iterations,
            residual: info.residual,
            tolerance: info.tolerance,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::conformance::{agree_fields, backend_passes, uniform, MakeBackend, GRIDS};
    use super::spy::{Call, Spy};
    use super::*;

    #[test]
    fn the_contact_map_is_the_pixels_of_positive_pressure() {
        let p = [0.0, 1e-300, -0.0, 2.5, f64::NAN, -1.0];
        assert_eq!(contact_map(&p), [false, true, false, true, false, false]);
    }

    /// Whole solves with the backend `make` builds against solves with the reference backend, both
    /// boundaries, saturated and elastic, cold and warm-started: pressures and reports agree.
    fn solves(make: &MakeBackend, grid: Grid, boundary: Boundary, exact: bool) {
        let e_star = 1.0 / 0.91;
        for (pm, mean_pressure) in [(0.05, 4e-3), (f64::INFINITY, 2e-3)] {
            let heights: Vec<f64> = uniform(21, grid.pixels()).iter().map(|x| 0.01 * x * x).collect();
            let shifted: Vec<f64> = heights
                .iter()
                .enumerate()
                .map(|(k, h)| h + 1e-4 * (k % 7) as f64)
                .collect();
            let mut results = Vec::new();
            for backend in [
                make(grid, e_star, boundary),
                conformance::reference(grid, e_star, boundary),
            ] {
                let mut solver = ContactSolver::with_backend(grid, e_star, backend);
                let mut p = vec![0.0; grid.pixels()];
                let cold = solver.solve(&heights, mean_pressure, pm, &mut p).unwrap();
                let warm = solver.solve(&shifted, mean_pressure, pm, &mut p).unwrap();
                results.push((cold, warm, p));
            }
            let (a, b) = (&results[0], &results[1]);
            let what = format!("{boundary:?} solve on {}×{}, p_m = {pm}", grid.nx(), grid.ny());
            if exact {
                assert_eq!((&a.0, &a.1), (&b.0, &b.1), "{what}");
            } else {
                assert_eq!(
                    (a.0.contact_pixels, a.1.contact_pixels),
                    (b.0.contact_pixels, b.1.contact_pixels),
                    "{what}"
                );
            }
            agree_fields(&a.2, &b.2, exact, &what);
        }
    }

    /// The conformance test of a backend (`contact::conformance`): every pass against the plain
    /// reference, then whole solves. A new backend adds a test calling this with its constructor.
    fn conformance(make: &MakeBackend, exact: bool) {
        backend_passes(make, exact);
        for (nx, ny) in GRIDS {
            let grid = Grid::new(nx, ny, 0.1 * nx as f64).unwrap();
            for boundary in [Boundary::Periodic, Boundary::Free] {
                solves(make, grid, boundary, exact);
            }
        }
    }

    #[test]
    fn the_cpu_backend_passes_the_conformance_test_exactly() {
        conformance(&super::conformance::cpu, true);
    }

    #[test]
    fn the_conformance_test_fails_a_backend_that_breaks_a_rule() {
        let make: &MakeBackend =
            &|grid, e_star, boundary| Box::new(Spy::broken(conformance::cpu(grid, e_star, boundary)));
        let failed = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| conformance(make, false))).is_err();
        assert!(failed, "a backend that counts plastic load as free passed");
    }

    #[test]
    fn unreachable_or_meaningless_settings_are_refused() {
        assert!(SolverOptions::new(1e-8, 100).is_ok());
        for bad in [0.0, 1.0, f64::NAN, 5e-324, 1e-16] {
            assert!(
                SolverOptions::new(bad, 100)
                    .unwrap_err()
                    .to_string()
                    .contains("`tolerance`"),
                "{bad}"
            );
        }
        assert!(SolverOptions::new(1e-8, 0)
            .unwrap_err()
            .to_string()
            .contains("`max_iterations`"));
    }

    /// A solver on the paper's roughness at 64², solved at offset 0 and composed at offset 1.
    fn solved_at_offset_0_composed_at_1() -> ContactSolver {
        let grid = Grid::square(64, 1.0).unwrap();
        let spectrum = crate::surface::SpectrumParams::paper_roughness(64, 1.0);
        let top = Surface::generate(grid, &spectrum, 1).unwrap();
        let bottom = Surface::generate(grid, &spectrum, 2).unwrap();
        let mut solver = ContactSolver::new(grid, 1.0 / 0.91).unwrap();
        solver.bind_surfaces(Arc::new(top), Arc::new(bottom)).unwrap();
        solver.compose(0).unwrap();
        solver.solve_in_place(1e-3, 0.03).unwrap();
        solver.compose(1).unwrap();
        solver
    }

    /// The next solves of `a` and `b` (F_N = 10⁻³, p_m = 0.03) report the same and leave the same
    /// pressure, bit for bit.
    fn solve_alike(a: &mut ContactSolver, b: &mut ContactSolver) {
        let (x, y) = (
            a.solve_in_place(1e-3, 0.03).unwrap(),
            b.solve_in_place(1e-3, 0.03).unwrap(),
        );
        assert_eq!(x, y);
        assert_eq!(a.pressure(), b.pressure());
    }

    #[test]
    fn a_step_that_overloads_the_plastic_zone_is_shortened_without_a_convolution() {
        // A cold solve and three warm steps on the paper's roughness at 64² (F_N = 10⁻³,
        // p_m = 0.03), the backend's calls logged.
        let grid = Grid::square(64, 1.0).unwrap();
        let spectrum = crate::surface::SpectrumParams::paper_roughness(64, 1.0);
        let surface = |seed| Arc::new(Surface::generate(grid, &spectrum, seed).unwrap());
        let (spy, calls) = Spy::new(conformance::cpu(grid, 1.0 / 0.91, Boundary::Periodic));
        let mut solver = ContactSolver::with_backend(grid, 1.0 / 0.91, Box::new(spy));
        solver.bind_surfaces(surface(1), surface(2)).unwrap();
        let mut plain = solved_at_offset_0_composed_at_1();
        solver.compose(0).unwrap();
        solver.solve_in_place(1e-3, 0.03).unwrap();
        for offset in 1..4 {
            solver.compose(offset).unwrap();
            solve_alike(&mut solver, &mut plain);
            plain.compose(offset + 1).unwrap();
        }
        // A step whose p_m pixels alone carry the load Σp, where those of the iteration's start
        // did not, is undone before any 𝒦p: the next call that changes the state is the undo.
        let total = 1e-3 * grid.pixels() as f64;
        let calls = calls.lock().unwrap();
        let (mut plastic, mut before, mut overloads) = (0.0, 0.0, 0);
        for (k, call) in calls.iter().enumerate() {
            match *call {
                Call::Stats { plastic: p } => plastic = p,
                Call::Direction => before = plastic,
                Call::Update { plastic: p } if p >= total && before < total => {
                    overloads += 1;
                    assert_eq!(calls.get(k + 1), Some(&Call::Undo), "call {k}: {:?}", &calls[k..]);
                }
                _ => {}
            }
        }
        // Not vacuous: the cold solve (above all) takes such steps.
        assert!(overloads >= 3, "{overloads} overloading steps");
    }

    #[test]
    fn a_warm_start_reuses_the_displacement_of_the_last_solve() {
        // Ten warm steps, on a solver that keeps its u and on one whose pressure is written back
        // as it is before each step (which clears what it knows of u): the same solves bit for
        // bit, one convolution fewer per step.
        let (mut kept, mut written) = (solved_at_offset_0_composed_at_1(), solved_at_offset_0_composed_at_1());
        let mut saved = 0;
        for offset in 2..12 {
            let a = kept.solve_in_place(1e-3, 0.03).unwrap();
            let p = written.pressure().to_vec();
            written.set_pressure(|q| q.copy_from_slice(&p));
            let b = written.solve_in_place(1e-3, 0.03).unwrap();
            assert_eq!(kept.pressure(), written.pressure(), "offset {offset}");
            saved += b.convolutions - a.convolutions;
            assert_eq!(SolveInfo { convolutions: 0, ..a }, SolveInfo { convolutions: 0, ..b });
            for s in [&mut kept, &mut written] {
                s.compose(offset).unwrap();
            }
        }
        assert_eq!(saved, 10, "warm starts that reused their displacement");
        // A pressure the caller writes is never taken for one whose u is known: the same field
        // rolled by a row carries the same load, and the solve from it is a fresh solver's.
        let p = kept.pressure().to_vec();
        let rolled: Vec<f64> = p[64..].iter().chain(&p[..64]).copied().collect();
        let mut other = solved_at_offset_0_composed_at_1();
        other.compose(11).unwrap();
        for s in [&mut kept, &mut other] {
            s.set_pressure(|q| q.copy_from_slice(&rolled));
        }
        solve_alike(&mut kept, &mut other);
    }

    #[test]
    fn every_pass_is_timed_and_the_next_warm_solve_is_unchanged() {
        let (mut profiled, mut plain) = (solved_at_offset_0_composed_at_1(), solved_at_offset_0_composed_at_1());
        let timings = profiled.profile_passes(0.03, 3);
        let names: Vec<_> = timings.iter().map(|t| t.name).collect();
        assert_eq!(names.len(), 10, "{names:?}");
        for name in ["update", "advance", "curvature"] {
            assert!(names.contains(&name), "{names:?}");
        }
        for t in &timings {
            assert!(t.seconds > 0.0 && t.seconds.is_finite() && t.streams >= 1.0, "{t:?}");
        }
        // An iteration is the direction, the curvature, the update and the rest of the
        // convolution; a set change takes a fresh 𝒦p and the scaling instead of the rest.
        let per_iteration: f64 = timings.iter().map(|t| t.per_cg_iteration * t.streams).sum();
        assert_eq!(per_iteration, 23.0);
        let per_set_change: f64 = timings.iter().map(|t| t.per_set_change * t.streams).sum();
        assert_eq!(per_set_change, 25.0);
        // Profiling leaves p exactly and the rest is recomputed by a solve: the next warm solve
        // equals one on a solver that was never profiled, bit for bit, once that one too is told
        // its u is not to be kept (profiling moves u: the timed `advance` steps it).
        let p = plain.pressure().to_vec();
        plain.set_pressure(|q| q.copy_from_slice(&p));
        solve_alike(&mut profiled, &mut plain);
    }
}
