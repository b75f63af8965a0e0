//! Saturated-pressure (elastic–perfectly-plastic) contact of a rigid rough surface on an elastic
//! half-space, solved by FFT boundary elements (paper §2 and appendix A).
//!
//! Problem: find p minimising ½⟨p, 𝒦p⟩ − ⟨p, h⟩ subject to 0 ≤ p ≤ p_m and mean(p) = F_N/(Lx Ly), where
//! 𝒦 is the half-space's influence operator ([`crate::influence`]): periodic, û(q) = 2 p̂(q)/(E*|k|)
//! as in the paper, or with a free boundary around the map (Hockney's zero-padded FFT), the
//! pressure confined to the map. Its optimality conditions, with
//! g = 𝒦p − h and c the Lagrange multiplier of the load (the rigid body's position), are
//! g + c ≥ 0 where p = 0, g + c = 0 where 0 < p < p_m, g + c ≤ 0 where p = p_m.
//!
//! Algorithm: the constrained conjugate gradient of Polonsky & Keer (1999), extended to the upper
//! bound as in the bound-constrained CG of Vollebregt (2014): conjugate directions live on the free
//! pixels 0 < p < p_m (made zero-mean there so that a step keeps the load); pixels that cross a bound
//! are clipped to it (exact zeros outside the contact); bound pixels whose gap says they should move
//! (penetrating non-contact pixels, plastic pixels whose gap opens) are released with a gradient step
//! and restart the conjugation; the load is then restored exactly by scaling.
//!
//! Cost: one convolution 𝒦t per iteration. The displacement u = 𝒦p is carried along as
//! u ← u − τ𝒦t, and recomputed only after a clip, release or rescale changed p off the line, and
//! once more before convergence is declared, so that the final residual is that of a freshly
//! computed 𝒦p.
//!
//! Residual (the convergence criterion, reported with every result): the largest pixel-wise
//! violation of the three optimality conditions above, divided by the RMS of h about its mean:
//! `max_i v_i / std(h)` with v_i = |g_i + c| on free pixels, max(0, −(g_i + c)) on non-contact pixels
//! and max(0, g_i + c) on plastic pixels, c = −mean over free pixels of g.

use rayon::prelude::*;

use crate::check::positive;
use crate::error::{Error, Interrupt, Result};
use crate::grid::Grid;
use crate::influence::{self, Boundary, Influence};

/// Default convergence tolerance on the residual (see the module documentation). A hundredfold
/// tighter tolerance changes no contact pixel on the paper-roughness problems (validated in
/// `tests/contact_validation.rs`).
pub const DEFAULT_TOLERANCE: f64 = 1e-8;

/// Smallest tolerance a solve in double precision can reach (round-off in 𝒦p is about 1e-16 of h).
pub const MIN_TOLERANCE: f64 = 1e-15;

/// Default iteration limit of one solve.
pub const DEFAULT_MAX_ITERATIONS: usize = 20_000;

/// Convergence settings of the contact solver.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SolverOptions {
    tolerance: f64,
    max_iterations: usize,
}

impl SolverOptions {
    /// Validated settings: `tolerance` in (0, 1), `max_iterations` at least 1.
    pub fn new(tolerance: f64, max_iterations: usize) -> Result<Self> {
        if !(tolerance > 0.0 && tolerance < 1.0) {
            return Err(Error::param("tolerance", format!("{tolerance} must lie in (0, 1)")));
        }
        if tolerance < MIN_TOLERANCE {
            return Err(Error::param(
                "tolerance",
                format!(
                    "{tolerance:e} is below {MIN_TOLERANCE:e}, which double precision cannot reach; use e.g. 1e-10"
                ),
            ));
        }
        if max_iterations == 0 {
            return Err(Error::param("max_iterations", "must be at least 1"));
        }
        Ok(Self {
            tolerance,
            max_iterations,
        })
    }

    /// Tolerance on the residual (module documentation).
    pub fn tolerance(&self) -> f64 {
        self.tolerance
    }

    /// Iteration limit; reaching it is an [`Error::NotConverged`] from [`ContactSolver::solve`].
    pub fn max_iterations(&self) -> usize {
        self.max_iterations
    }
}

impl Default for SolverOptions {
    fn default() -> Self {
        Self {
            tolerance: DEFAULT_TOLERANCE,
            max_iterations: DEFAULT_MAX_ITERATIONS,
        }
    }
}

/// Why a solve stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Termination {
    /// The residual reached the tolerance, confirmed on a freshly computed displacement.
    Converged,
    /// The iteration limit was reached first.
    MaxIterations,
}

/// What one solve reports beside the pressure field.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SolveInfo {
    /// Why the solve stopped ([`ContactSolver::solve`] returns only converged solves).
    pub termination: Termination,
    /// Conjugate-gradient iterations (one convolution 𝒦t each).
    pub iterations: usize,
    /// Convolutions performed in all (iterations plus recomputations of 𝒦p).
    pub convolutions: usize,
    /// Final residual (module documentation).
    pub residual: f64,
    /// Tolerance the residual was required to reach.
    pub tolerance: f64,
    /// Rigid-body approach since first contact, max(h) − c, in length units: how far the rigid
    /// surface has moved towards the zero-mean deformed half-space from the position where it first
    /// touched it (h's highest point).
    pub approach: f64,
    /// Pixels in contact (p > 0).
    pub contact_pixels: usize,
    /// Pixels at the flow pressure (p = p_m).
    pub plastic_pixels: usize,
}

/// The displacement and gap of a solution ([`ContactSolver::gap_and_displacement`]), Nx·Ny values
/// each in length units.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactFields {
    /// Surface displacement of the half-space, u = 𝒦p (zero-mean when periodic).
    pub displacement: Vec<f64>,
    /// Gap g = 𝒦p − h + δ between the rigid surface and the deformed half-space.
    pub gap: Vec<f64>,
}

/// Per-row partial sums of one pass, combined sequentially so that results do not depend on the
/// thread count.
#[derive(Debug, Clone, Copy)]
struct Stats {
    n_free: f64,
    /// Σ over free pixels of (g − reference).
    sum: f64,
    /// Σ over free pixels of (g − reference)².
    sum_sq: f64,
    max_free: f64,
    min_free: f64,
    /// Smallest g over non-contact pixels.
    min_zero: f64,
    /// Largest g over plastic pixels.
    max_plastic: f64,
    n_plastic: f64,
    /// Objective ½⟨p, 𝒦p⟩ − ⟨p, h⟩ (its merit for the step safeguard).
    energy: f64,
    /// Load carried by free and by plastic pixels, and the largest free pressure (for
    /// [`scale_to_load`]).
    load: LoadSums,
}

/// Sums of the pressure field that [`scale_to_load`] needs.
#[derive(Debug, Clone, Copy, Default)]
struct LoadSums {
    free: f64,
    plastic: f64,
    n_contact: usize,
    max_free: f64,
}

impl LoadSums {
    fn of(pressure: &[f64], pm: f64, min_len: usize) -> Self {
        pressure
            .par_chunks(4096)
            .with_min_len(min_len)
            .map(|c| {
                let mut s = LoadSums::default();
                for &p in c {
                    s.add(p, pm);
                }
                s
            })
            .collect::<Vec<_>>()
            .into_iter()
            .fold(LoadSums::default(), LoadSums::merge)
    }

    #[inline]
    fn add(&mut self, p: f64, pm: f64) {
        if p >= pm {
            self.plastic += p;
            self.n_contact += 1;
        } else if p > 0.0 {
            self.free += p;
            self.n_contact += 1;
            self.max_free = self.max_free.max(p);
        }
    }

    fn merge(a: LoadSums, b: LoadSums) -> LoadSums {
        LoadSums {
            free: a.free + b.free,
            plastic: a.plastic + b.plastic,
            n_contact: a.n_contact + b.n_contact,
            max_free: a.max_free.max(b.max_free),
        }
    }
}

impl Default for Stats {
    fn default() -> Self {
        Self {
            n_free: 0.0,
            sum: 0.0,
            sum_sq: 0.0,
            max_free: f64::NEG_INFINITY,
            min_free: f64::INFINITY,
            min_zero: f64::INFINITY,
            max_plastic: f64::NEG_INFINITY,
            n_plastic: 0.0,
            energy: 0.0,
            load: LoadSums::default(),
        }
    }
}

impl Stats {
    #[inline]
    fn add(&mut self, p: f64, u: f64, h: f64, reference: f64, flow_pressure: f64) {
        let g = u - h;
        self.load.add(p, flow_pressure);
        if p <= 0.0 {
            self.min_zero = self.min_zero.min(g);
        } else {
            self.energy += p * (0.5 * u - h);
            if p >= flow_pressure {
                self.n_plastic += 1.0;
                self.max_plastic = self.max_plastic.max(g);
            } else {
                let d = g - reference;
                self.n_free += 1.0;
                self.sum += d;
                self.sum_sq += d * d;
                self.max_free = self.max_free.max(g);
                self.min_free = self.min_free.min(g);
            }
        }
    }

    fn combine(parts: &[Stats]) -> Stats {
        let mut s = Stats::default();
        for p in parts {
            s.n_free += p.n_free;
            s.sum += p.sum;
            s.sum_sq += p.sum_sq;
            s.max_free = s.max_free.max(p.max_free);
            s.min_free = s.min_free.min(p.min_free);
            s.min_zero = s.min_zero.min(p.min_zero);
            s.max_plastic = s.max_plastic.max(p.max_plastic);
            s.n_plastic += p.n_plastic;
            s.energy += p.energy;
            s.load = LoadSums::merge(s.load, p.load);
        }
        s
    }

    /// Mean of g over free pixels (−c), or, without free pixels, a value between the bounds.
    fn mean_gap(&self, reference: f64) -> f64 {
        if self.n_free > 0.0 {
            reference + self.sum / self.n_free
        } else {
            match (self.min_zero.is_finite(), self.max_plastic.is_finite()) {
                (true, true) => 0.5 * (self.min_zero + self.max_plastic),
                (true, false) => self.min_zero,
                (false, true) => self.max_plastic,
                (false, false) => reference,
            }
        }
    }

    /// Σ over free pixels of (g − ḡ)².
    fn gradient_norm_sq(&self, reference: f64, mean: f64) -> f64 {
        let shift = mean - reference;
        (self.sum_sq - self.n_free * shift * shift).max(0.0)
    }

    /// Largest violation of the optimality conditions, in length units.
    fn violation(&self, mean: f64) -> f64 {
        let mut v: f64 = 0.0;
        if self.n_free > 0.0 {
            v = v.max(self.max_free - mean).max(mean - self.min_free);
        }
        if self.min_zero.is_finite() {
            v = v.max(mean - self.min_zero);
        }
        if self.max_plastic.is_finite() {
            v = v.max(self.max_plastic - mean);
        }
        v
    }
}

/// FFT contact solver for one grid: plans, the influence kernel and all Nx·Ny work buffers are made
/// once here and reused by every solve (a sliding run makes one solver).
pub struct ContactSolver {
    grid: Grid,
    effective_modulus: f64,
    /// 𝒦, periodic or with a free boundary.
    influence: Influence,
    u: Vec<f64>,
    t: Vec<f64>,
    r: Vec<f64>,
    /// p before the last step, to undo a step that raised the objective.
    p_old: Vec<f64>,
    /// Spare displacement buffer: receives 𝒦p after a step off the CG line.
    u_alt: Vec<f64>,
    stats: Vec<Stats>,
    sums: Vec<[f64; 2]>,
    row_partials: Vec<f64>,
    options: SolverOptions,
    /// Checked once per iteration: a raised flag ends the solve with [`Error::Interrupted`].
    interrupt: Interrupt,
}

/// The constants of one solve and the state carried from one iteration to the next.
struct SolveState {
    /// Flow pressure p_m.
    pm: f64,
    /// Total load Σp = Nx Ny F_N/(Lx Ly).
    total: f64,
    /// Residual scale: std(h), or P·L/E* for a flat surface.
    scale: f64,
    h_std: f64,
    h_max: f64,
    /// Rows per rayon task in the element-wise passes.
    min_len: usize,
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
}

impl ContactSolver {
    /// Solver for a periodic grid (Nx × Ny square pixels) on a half-space of effective modulus E*.
    pub fn new(grid: Grid, effective_modulus: f64) -> Result<Self> {
        Self::with_boundary(grid, effective_modulus, Boundary::Periodic)
    }

    /// Solver on a half-space of effective modulus E* whose map is periodic or has a free boundary
    /// (see [`crate::influence`]); the algorithm is the same, only 𝒦 differs.
    pub fn with_boundary(grid: Grid, effective_modulus: f64, boundary: Boundary) -> Result<Self> {
        positive("effective_modulus", effective_modulus)?;
        let (nx, ny) = (grid.nx(), grid.ny());
        crate::check::memory("the contact solver", nx, ny, 6.5 + influence::arrays(boundary))?;
        Ok(Self {
            grid,
            effective_modulus,
            influence: Influence::new(grid, effective_modulus, boundary)?,
            u: vec![0.0; nx * ny],
            t: vec![0.0; nx * ny],
            r: vec![0.0; nx * ny],
            p_old: vec![0.0; nx * ny],
            u_alt: vec![0.0; nx * ny],
            stats: vec![Stats::default(); nx],
            sums: vec![[0.0; 2]; nx],
            row_partials: vec![0.0; nx],
            options: SolverOptions::default(),
            interrupt: Interrupt::default(),
        })
    }

    /// The grid.
    pub fn grid(&self) -> Grid {
        self.grid
    }

    /// Effective modulus E*.
    pub fn effective_modulus(&self) -> f64 {
        self.effective_modulus
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
        self.influence.boundary()
    }

    /// Applies the influence operator: `out = 𝒦 p`, the displacement of the half-space (zero-mean
    /// when periodic).
    pub fn apply_influence(&mut self, pressure: &[f64], out: &mut [f64]) {
        self.influence.apply(pressure, out);
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
        let nn = self.grid.nx() * self.grid.ny();
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
        let mut displacement = vec![0.0; nn];
        self.influence.apply(pressure, &mut displacement);
        let h_max = heights.par_iter().copied().reduce(|| f64::NEG_INFINITY, f64::max);
        let shift = h_max - info.approach;
        let gap = displacement
            .par_iter()
            .zip(heights.par_iter())
            .map(|(&u, &h)| u - h + shift)
            .collect();
        Ok(ContactFields { displacement, gap })
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
        match info.termination {
            Termination::Converged => Ok(info),
            Termination::MaxIterations => Err(Error::NotConverged {
                iterations: info.iterations,
                residual: info.residual,
                tolerance: info.tolerance,
            }),
        }
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
        let mut state = self.start(heights, mean_pressure, flow_pressure, pressure)?;
        loop {
            let mean = state.stats.mean_gap(state.reference);
            let residual = state.stats.violation(mean) / state.scale;
            if residual <= self.options.tolerance {
                if state.fresh {
                    return Ok(self.finish(&state, mean, residual, Termination::Converged));
                }
                // Confirm with an exactly balanced load and a freshly computed displacement.
                self.balance_load(heights, pressure, &state, mean, Some(state.stats.load));
                state.reference = mean;
                state.stats = self.displacement_and_stats(heights, pressure, state.reference, state.pm);
                state.convolutions += 1;
                state.fresh = true;
                continue;
            }
            if state.iterations >= self.options.max_iterations {
                return Ok(self.finish(&state, mean, residual, Termination::MaxIterations));
            }
            self.interrupt.check()?;
            self.iterate(&mut state, heights, pressure, mean);
        }
    }

    /// Set-up of a solve: checks the inputs, measures the heights, makes the initial guess (the
    /// given field when usable, else uniform pressure) carry the load, and computes its statistics.
    fn start(
        &mut self,
        heights: &[f64],
        mean_pressure: f64,
        flow_pressure: f64,
        pressure: &mut [f64],
    ) -> Result<SolveState> {
        let (nx, n) = (self.grid.nx(), self.grid.ny());
        let nn = nx * n;
        if heights.len() != nn || pressure.len() != nn {
            return Err(Error::param("heights", format!("arrays must hold {nx}×{n} values")));
        }
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
        // Height statistics in one deterministic parallel pass: Σ(h − h₀), Σ(h − h₀)², max, finite.
        let h0 = heights[0];
        let (sum, sum_sq, h_max, finite) = heights
            .par_chunks(n)
            .map(|row| {
                row.iter()
                    .fold((0.0, 0.0, f64::NEG_INFINITY, true), |(s, q, m, f), &h| {
                        (s + (h - h0), q + (h - h0) * (h - h0), m.max(h), f && h.is_finite())
                    })
            })
            .collect::<Vec<_>>()
            .into_iter()
            .fold((0.0, 0.0, f64::NEG_INFINITY, true), |a, b| {
                (a.0 + b.0, a.1 + b.1, a.2.max(b.2), a.3 && b.3)
            });
        if !finite || !h0.is_finite() {
            let k = heights.iter().position(|h| !h.is_finite()).unwrap_or(0);
            return Err(Error::InvalidSurface {
                name: "composite".into(),
                message: format!("height at ({}, {}) is {}", k / n, k % n, heights[k]),
            });
        }
        let pm = flow_pressure;
        let total = mean_pressure * nn as f64;
        let shift_mean = sum / nn as f64;
        let h_std = (sum_sq / nn as f64 - shift_mean * shift_mean).max(0.0).sqrt();
        // Residual scale: the surface's RMS height, or for a flat surface the elastic length P·L/E*.
        let scale = if h_std > 0.0 {
            h_std
        } else {
            mean_pressure * self.grid.length_x() / self.effective_modulus
        };
        let min_len = (8192 / n).max(1);

        let usable = pressure.par_iter().all(|p| p.is_finite() && *p >= 0.0) && pressure.par_iter().any(|&p| p > 0.0);
        if usable {
            pressure.par_iter_mut().for_each(|p| *p = p.min(pm));
        } else {
            pressure.par_iter_mut().for_each(|p| *p = mean_pressure);
        }
        let mut state = SolveState {
            pm,
            total,
            scale,
            h_std,
            h_max,
            min_len,
            stats: Stats::default(),
            reference: 0.0,
            fresh: true,
            restart: true,
            g_norm_old: 1.0,
            iterations: 0,
            convolutions: 0,
        };
        self.balance_load(heights, pressure, &state, f64::NAN, None);
        state.stats = self.displacement_and_stats(heights, pressure, state.reference, pm);
        state.convolutions += 1;
        Ok(state)
    }

    /// One iteration: the conjugate direction on the free pixels, its convolution, and the step
    /// (clipped to the bounds, releasing bound pixels whose gap points inwards), shortened until the
    /// objective descends when it left the CG line.
    fn iterate(&mut self, state: &mut SolveState, heights: &[f64], pressure: &mut [f64], mean: f64) {
        let n = self.grid.ny();
        let (pm, total, min_len) = (state.pm, state.total, state.min_len);
        state.iterations += 1;

        // Conjugate direction on the free pixels: t = (g − ḡ) + β t.
        let g_norm = state.stats.gradient_norm_sq(state.reference, mean);
        let beta = if state.restart || state.g_norm_old <= 0.0 {
            0.0
        } else {
            g_norm / state.g_norm_old
        };
        state.g_norm_old = g_norm;
        let (sum_t, sum_dt) = self.pass_direction(heights, pressure, mean, beta, pm, min_len);
        let n_free = state.stats.n_free;
        let shift = if n_free > 0.0 { sum_t / n_free } else { 0.0 };

        // r = 𝒦 t_f with t_f = t − shift on free pixels (zero mean there), and Σ_free r·t_f.
        // t is zero outside the free pixels, so `t ≠ 0` marks them without reading p (a free
        // pixel whose t is exactly 0 is left out consistently here and in the update).
        let t = &self.t;
        self.influence.apply_with(
            &self.t,
            |_, row| {
                for v in row.iter_mut() {
                    if *v != 0.0 {
                        *v -= shift;
                    }
                }
            },
            &mut self.r,
            |i, row| {
                let mut s = 0.0;
                for (&r, &tv) in row.iter().zip(&t[i * n..(i + 1) * n]) {
                    if tv != 0.0 {
                        s += r * (tv - shift);
                    }
                }
                s
            },
            Some(&mut self.row_partials),
        );
        state.convolutions += 1;
        let curvature: f64 = self.row_partials.iter().sum();
        let (tau, cg_step) = if n_free > 0.0 && curvature > 0.0 && sum_dt > 0.0 {
            (sum_dt / curvature, true)
        } else {
            (1.0 / self.influence.self_influence(), false)
        };

        // Step, clip to the bounds, release bound pixels whose gap points inwards; the next
        // iteration's statistics come out of the same pass. A step that changed p off the CG
        // line is checked on the objective and shortened until it descends (projected search).
        let energy_before = state.stats.energy;
        let slack = 1e-13 * (energy_before.abs() + total * state.h_std.max(state.h_max.abs()));
        let mut tau = tau;
        let mut backtracks = 0;
        loop {
            let (next, changed_total, released, clipped) = self.pass_update(
                heights,
                pressure,
                mean,
                tau,
                if cg_step { shift } else { f64::NAN },
                pm,
                min_len,
            );
            let drift = (changed_total - total).abs() > 1e-12 * total;
            if !(clipped || released || drift || !cg_step) {
                state.stats = next;
                state.fresh = false;
                state.restart = false;
                break;
            }
            self.balance_load(heights, pressure, state, mean, Some(next.load));
            // The carried-along u moves to the spare buffer (kept for an undo); 𝒦p goes into u.
            std::mem::swap(&mut self.u, &mut self.u_alt);
            state.stats = self.displacement_and_stats(heights, pressure, mean, pm);
            state.convolutions += 1;
            state.fresh = true;
            state.restart = released || backtracks > 0;
            if state.stats.energy <= energy_before + slack || backtracks >= 40 {
                break;
            }
            // Undo: p from its copy, u = (u − τr) + τr from the carried-along field.
            pressure
                .par_iter_mut()
                .zip(self.p_old.par_iter())
                .for_each(|(p, &o)| *p = o);
            let step = if cg_step { tau } else { 0.0 };
            self.u
                .par_iter_mut()
                .zip(self.u_alt.par_iter().zip(self.r.par_iter()))
                .for_each(|(u, (&a, &r))| *u = a + step * r);
            tau *= 0.25;
            backtracks += 1;
        }
        state.reference = mean;
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

    /// Restores the load exactly ([`scale_to_load`]). Where the contact cannot carry it even at the
    /// flow pressure, the missing load goes to the non-contact pixels that penetrate most, in
    /// proportion to their penetration −(g − ḡ) (all non-contact pixels evenly when `mean` is NaN or
    /// none penetrates), then the load is balanced again.
    fn balance_load(
        &self,
        heights: &[f64],
        pressure: &mut [f64],
        state: &SolveState,
        mean: f64,
        mut sums: Option<LoadSums>,
    ) {
        let (total, pm, min_len) = (state.total, state.pm, state.min_len);
        for _ in 0..4 {
            if scale_to_load(pressure, total, pm, min_len, sums.take()) {
                return;
            }
            let carried: f64 = pressure.iter().sum();
            let missing = total - carried;
            let u = &self.u;
            let penetration = |i: usize| {
                if mean.is_nan() {
                    0.0
                } else {
                    (mean - (u[i] - heights[i])).max(0.0)
                }
            };
            let (weight_sum, n_zero) = pressure
                .iter()
                .enumerate()
                .filter(|(_, &p)| p <= 0.0)
                .fold((0.0, 0usize), |(w, c), (i, _)| (w + penetration(i), c + 1));
            for (i, p) in pressure.iter_mut().enumerate() {
                if *p <= 0.0 {
                    let share = if weight_sum > 0.0 {
                        missing * penetration(i) / weight_sum
                    } else {
                        missing / n_zero.max(1) as f64
                    };
                    *p = share.min(pm);
                }
            }
        }
        scale_to_load(pressure, total, pm, min_len, None);
    }

    /// u = 𝒦p, and the statistics of g = u − h over the regions defined by p, gathered row by
    /// row as the inverse transform writes u (one pass over the arrays fewer than computing them
    /// after the convolution).
    fn displacement_and_stats(&mut self, heights: &[f64], pressure: &[f64], reference: f64, pm: f64) -> Stats {
        let n = self.grid.ny();
        self.influence.apply_with(
            pressure,
            |_, _| {},
            &mut self.u,
            |i, u| {
                let mut s = Stats::default();
                for ((&p, &u), &h) in pressure[i * n..(i + 1) * n]
                    .iter()
                    .zip(u)
                    .zip(&heights[i * n..(i + 1) * n])
                {
                    s.add(p, u, h, reference, pm);
                }
                s
            },
            Some(&mut self.stats),
        );
        Stats::combine(&self.stats)
    }

    /// t ← (g − ḡ) + β t on free pixels, 0 elsewhere; returns (Σ t, Σ (g − ḡ) t) over free pixels.
    fn pass_direction(
        &mut self,
        heights: &[f64],
        pressure: &[f64],
        mean: f64,
        beta: f64,
        pm: f64,
        min_len: usize,
    ) -> (f64, f64) {
        let n = self.grid.ny();
        self.sums
            .par_iter_mut()
            .with_min_len(min_len)
            .zip(self.t.par_chunks_mut(n))
            .zip(
                pressure
                    .par_chunks(n)
                    .zip(self.u.par_chunks(n).zip(heights.par_chunks(n))),
            )
            .for_each(|((acc, t), (p, (u, h)))| {
                let (mut st, mut sdt) = (0.0, 0.0);
                for (((t, &p), &u), &h) in t.iter_mut().zip(p).zip(u).zip(h) {
                    if p > 0.0 && p < pm {
                        let d = u - h - mean;
                        *t = d + beta * *t;
                        st += *t;
                        sdt += d * *t;
                    } else {
                        *t = 0.0;
                    }
                }
                *acc = [st, sdt];
            });
        self.sums.iter().fold((0.0, 0.0), |(a, b), s| (a + s[0], b + s[1]))
    }

    /// The update pass. With `shift` finite, free pixels take the CG step p −= τ(t − shift) and u
    /// follows (u −= τ r); with `shift` NaN no CG step is taken. Non-contact pixels that penetrate
    /// and plastic pixels whose gap opens take a gradient step p −= τ(g − ḡ). Returns the
    /// statistics for the next iteration (valid when nothing was clipped or released), the new
    /// total load, and whether any pixel was released or clipped.
    #[allow(clippy::too_many_arguments)]
    fn pass_update(
        &mut self,
        heights: &[f64],
        pressure: &mut [f64],
        mean: f64,
        tau: f64,
        shift: f64,
        pm: f64,
        min_len: usize,
    ) -> (Stats, f64, bool, bool) {
        let n = self.grid.ny();
        let cg_step = shift.is_finite();
        let results = &mut self.stats;
        let mut totals = std::mem::take(&mut self.row_partials);
        let mut events = std::mem::take(&mut self.sums);
        results
            .par_iter_mut()
            .with_min_len(min_len)
            .zip(totals.par_iter_mut().zip(events.par_iter_mut()))
            .zip(pressure.par_chunks_mut(n).zip(self.u.par_chunks_mut(n)))
            .zip(
                self.t
                    .par_chunks(n)
                    .zip(self.r.par_chunks(n).zip(heights.par_chunks(n))),
            )
            .zip(self.p_old.par_chunks_mut(n))
            .for_each(|((((acc, (total, event)), (p, u)), (t, (r, h))), p_old)| {
                p_old.copy_from_slice(p);
                let mut s = Stats::default();
                let mut sum_p = 0.0;
                let (mut released, mut clipped) = (0.0, 0.0);
                for ((((p, u), &t), &r), &h) in p.iter_mut().zip(u.iter_mut()).zip(t).zip(r).zip(h) {
                    let d = *u - h - mean;
                    if *p <= 0.0 {
                        if d < 0.0 {
                            *p = (-tau * d).min(pm);
                            released += 1.0;
                        }
                    } else if *p >= pm {
                        if d > 0.0 {
                            *p = (pm - tau * d).max(0.0);
                            released += 1.0;
                        }
                    } else if cg_step && t != 0.0 {
                        let q = *p - tau * (t - shift);
                        if q <= 0.0 {
                            *p = 0.0;
                            clipped += 1.0;
                        } else if q >= pm {
                            *p = pm;
                            clipped += 1.0;
                        } else {
                            *p = q;
                        }
                    }
                    if cg_step {
                        *u -= tau * r;
                    }
                    sum_p += *p;
                    s.add(*p, *u, h, mean, pm);
                }
                *acc = s;
                *total = sum_p;
                *event = [released, clipped];
            });
        let stats = Stats::combine(results);
        let total: f64 = totals.iter().sum();
        let released = events.iter().any(|e| e[0] > 0.0);
        let clipped = events.iter().any(|e| e[1] > 0.0);
        self.row_partials = totals;
        self.sums = events;
        (stats, total, released, clipped)
    }
}

/// Restores Σp = `total` by scaling the free pixels, pᵢ ← min(p_m, s·pᵢ) for 0 < pᵢ < p_m, which keeps
/// exact zeros and leaves plastic pixels at p_m (scaling them too would free the whole plastic zone
/// at once). s solves the monotone, concave, piecewise-linear equation by Newton's method from below,
/// which ends in finitely many steps. Where the plastic pixels alone exceed the load, every contact
/// pixel is scaled; where even p_m on every contact pixel cannot carry it, the contact pixels are set
/// to p_m and `false` is returned: the contact must grow.
fn scale_to_load(pressure: &mut [f64], total: f64, pm: f64, min_len: usize, sums: Option<LoadSums>) -> bool {
    let sums = sums.unwrap_or_else(|| LoadSums::of(pressure, pm, min_len));
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
        pressure.par_iter_mut().for_each(|p| {
            if *p > 0.0 {
                *p = pm
            }
        });
        return false;
    }
    let movable_pixel = |p: f64| p > 0.0 && (scale_plastic || p < pm);
    let sum_and_slope = |s: f64| -> (f64, f64) {
        pressure
            .par_chunks(4096)
            .with_min_len(min_len)
            .map(|c| {
                let (mut f, mut df) = (0.0, 0.0);
                for &p in c {
                    if movable_pixel(p) {
                        let v = s * p;
                        if v >= pm {
                            f += pm;
                        } else {
                            f += v;
                            df += p;
                        }
                    }
                }
                (f, df)
            })
            .collect::<Vec<_>>()
            .into_iter()
            .fold((0.0, 0.0), |(a, b), (f, df)| (a + f, b + df))
    };
    let target = total - fixed;
    let mut s = target / movable;
    // Without a pixel pushed to p_m the first guess is exact; otherwise Newton from below.
    let max_movable = if scale_plastic { pm } else { sums.max_free };
    let iterations = if s * max_movable < pm { 0 } else { 100 };
    for _ in 0..iterations {
        let (f, df) = sum_and_slope(s);
        let err = target - f;
        if err.abs() <= 1e-15 * total || df <= 0.0 {
            break;
        }
        s += err / df;
    }
    pressure.par_iter_mut().for_each(|p| {
        if movable_pixel(*p) {
            *p = (s * *p).min(pm);
        }
    });
    true
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
