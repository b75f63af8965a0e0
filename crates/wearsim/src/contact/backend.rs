//! The seam between the contact algorithm and the hardware it runs on.
//!
//! `ContactSolver` writes the saturated conjugate-gradient algorithm once, in scalars: step
//! lengths, conjugation coefficients, the load's Newton iteration, the convergence test. Everything
//! that touches an Nx·Ny field goes through a [`ContactBackend`]: the backend owns the fields of a
//! solve (heights h, pressure p, displacement u = 𝒦p and its spare, the conjugate direction t and
//! the transform of its curvature, the previous pressure) for as long as the solver lives (a whole
//! sliding run), performs the convolutions and the fused element-wise passes, and returns only the
//! scalars of their reductions ([`Stats`], [`LoadSums`], sums). The surfaces of a sliding run are
//! bound once ([`ContactBackend::bind_surfaces`]) and composed where the fields live at each
//! offset. The law at the surface, elastic or saturated at the flow pressure ([`SurfaceLaw`]), is
//! bound once per solve ([`ContactBackend::bind_law`]) and read by every pass that clips or
//! classifies a pressure, so that no pass takes p_m as an argument. What crosses back per step is
//! the contact map as one bit per pixel, made by the backend ([`ContactBackend::contact_map`]), and
//! the pressure only when a caller asks ([`ContactBackend::pressure`]).
//!
//! A backend fixes the order of its reductions, so that its results do not depend on the thread
//! count: the CPU backend takes per-row partials combined in row order, and for the load sums
//! ([`ContactBackend::load_sums`], [`ContactBackend::scaled_load`]) partials over chunks of
//! [`LOAD_CHUNK`] pixels combined in chunk order. Each method's arithmetic is written out once more,
//! plainly, in the reference backend of the conformance test (`contact::conformance`), which any
//! backend must pass: exactly, for a backend that keeps these orders, or within the round-off of
//! its own.
//!
//! The law describes the surface only, and the heights may be rewritten between solves
//! ([`ContactBackend::write_heights`]). A model of plasticity in the volume beneath the surface, as
//! the Fourier-accelerated volume-integral method of Frérot et al. (2019) computes it, is therefore
//! an outer loop around the solver, not a backend's concern: between its iterations the surface
//! displacement of the plastic strains is added to the heights, and each solve is an ordinary one
//! under a surface law (in that method, the elastic one). Nothing in this trait would change for
//! it.

use std::sync::Arc;

use crate::influence::Boundary;
use crate::surface::Surface;

/// The law at the surface: what pressure a pixel may carry (paper §2, appendix A). Bound to a
/// backend for a solve ([`ContactBackend::bind_law`]); the passes read p_m from it
/// ([`SurfaceLaw::flow_pressure`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum SurfaceLaw {
    /// Elastic contact: p ≥ 0, no upper bound.
    Elastic,
    /// The saturated pressure of an elastic–perfectly-plastic surface: 0 ≤ p ≤ p_m, the flow
    /// pressure (the hardness, p_m = 3√3 τ̃ by von Mises in the paper's model).
    Saturated { flow_pressure: f64 },
}

impl SurfaceLaw {
    /// The law of a flow pressure as `ContactSolver::solve` takes it: ∞ is elastic, any other value
    /// saturated there (it is validated by the solve's set-up, not here).
    pub fn of_flow_pressure(flow_pressure: f64) -> Self {
        if flow_pressure == f64::INFINITY {
            SurfaceLaw::Elastic
        } else {
            SurfaceLaw::Saturated { flow_pressure }
        }
    }

    /// The bound p_m that the passes clip to and classify by: ∞ for the elastic law. An elastic
    /// solve thus takes exactly the operations of a saturated one whose bound no finite pressure
    /// reaches, so that the algorithm of `ContactSolver` and every pass are written once for both.
    #[inline]
    pub fn flow_pressure(self) -> f64 {
        match self {
            SurfaceLaw::Elastic => f64::INFINITY,
            SurfaceLaw::Saturated { flow_pressure } => flow_pressure,
        }
    }
}

/// Pixels per partial of the load sums (row-major order), combined in order.
pub(crate) const LOAD_CHUNK: usize = 4096;

/// The contact map as a backend hands it over: bit `k % 64` of word `k / 64` is set when pixel `k`
/// (row-major) carries pressure, p > 0.
pub(crate) fn contact_bit(bits: &[u64], k: usize) -> bool {
    bits[k / 64] >> (k % 64) & 1 == 1
}

/// κ of the settled-map stopping rule of `ContactSolver`: a pixel's margin from flipping must exceed
/// κ times what its gap or pressure moved in the last iteration ([`Stats::add_change`]).
pub(crate) const SETTLED_CHANGE_FACTOR: f64 = 2.0;

/// Statistics of g = u − h over the three regions of the pressure field (free 0 < p < p_m,
/// non-contact p = 0, plastic p = p_m), gathered by one pass; per-row partials are combined in row
/// order so that results do not depend on the thread count.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Stats {
    pub n_free: f64,
    /// Σ over free pixels of (g − reference).
    pub sum: f64,
    /// Σ over free pixels of (g − reference)².
    pub sum_sq: f64,
    pub max_free: f64,
    pub min_free: f64,
    /// Smallest g over non-contact pixels.
    pub min_zero: f64,
    /// Largest g over plastic pixels.
    pub max_plastic: f64,
    pub n_plastic: f64,
    /// Smallest p over contact pixels: how close the contact map is to losing a pixel (the
    /// settled-map stopping rule of `ContactSolver`).
    pub min_pressure: f64,
    /// Smallest g − κ|Δu| over non-contact pixels and p − κ|Δp| over contact pixels, with Δ the
    /// change of the last iteration and κ = [`SETTLED_CHANGE_FACTOR`] ([`Stats::add_change`]):
    /// how close a pixel is to flipping in units of its own last move. Gathered by the update pass
    /// of a conjugate-gradient step only (∞ elsewhere).
    pub settle_gap: f64,
    pub settle_pressure: f64,
    /// Objective ½⟨p, 𝒦p⟩ − ⟨p, h⟩ (its merit for the step safeguard).
    pub energy: f64,
    /// Load carried by free and by plastic pixels, and the largest free pressure (for the load
    /// balance of `ContactSolver`).
    pub load: LoadSums,
}

/// Sums of the pressure field that the load balance needs.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct LoadSums {
    pub free: f64,
    pub plastic: f64,
    pub n_contact: usize,
    pub max_free: f64,
}

impl LoadSums {
    /// Adds a pixel of pressure p, plastic where p reaches the law's p_m.
    #[inline]
    pub fn add(&mut self, p: f64, law: SurfaceLaw) {
        if p >= law.flow_pressure() {
            self.plastic += p;
            self.n_contact += 1;
        } else if p > 0.0 {
            self.free += p;
            self.n_contact += 1;
            self.max_free = self.max_free.max(p);
        }
    }

    pub fn merge(a: LoadSums, b: LoadSums) -> LoadSums {
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
            min_pressure: f64::INFINITY,
            settle_gap: f64::INFINITY,
            settle_pressure: f64::INFINITY,
            energy: 0.0,
            load: LoadSums::default(),
        }
    }
}

impl Stats {
    /// Adds pixel (p, u, h) with g = u − h, free-pixel sums taken about `reference`, its region
    /// (free or plastic) by the law's p_m.
    #[inline]
    pub fn add(&mut self, p: f64, u: f64, h: f64, reference: f64, law: SurfaceLaw) {
        let g = u - h;
        let flow_pressure = law.flow_pressure();
        self.load.add(p, law);
        if p <= 0.0 {
            self.min_zero = self.min_zero.min(g);
        } else {
            self.energy += p * (0.5 * u - h);
            self.min_pressure = self.min_pressure.min(p);
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

    /// Adds the last move of a pixel after a conjugate-gradient step: its new pressure p, the change
    /// Δp of this step, its new g = u − h and the change −Δu = τr of its displacement.
    #[inline]
    pub fn add_change(&mut self, p: f64, dp: f64, g: f64, du: f64) {
        if p > 0.0 {
            self.settle_pressure = self.settle_pressure.min(p - SETTLED_CHANGE_FACTOR * dp.abs());
        } else {
            self.settle_gap = self.settle_gap.min(g - SETTLED_CHANGE_FACTOR * du.abs());
        }
    }

    /// The statistics of the union of `parts`, combined in order.
    pub fn combine(parts: &[Stats]) -> Stats {
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
            s.min_pressure = s.min_pressure.min(p.min_pressure);
            s.settle_gap = s.settle_gap.min(p.settle_gap);
            s.settle_pressure = s.settle_pressure.min(p.settle_pressure);
            s.energy += p.energy;
            s.load = LoadSums::merge(s.load, p.load);
        }
        s
    }

    /// Mean of g over free pixels (−c), or, without free pixels, a value between the bounds.
    pub fn mean_gap(&self, reference: f64) -> f64 {
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
    pub fn gradient_norm_sq(&self, reference: f64, mean: f64) -> f64 {
        let shift = mean - reference;
        (self.sum_sq - self.n_free * shift * shift).max(0.0)
    }

    /// Largest violation of the optimality conditions, in length units.
    pub fn violation(&self, mean: f64) -> f64 {
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

/// Statistics of the heights h of a solve, from one pass: sums are taken about the first height h₀
/// for accuracy.
#[derive(Debug, Clone, Copy)]
pub(crate) struct HeightStats {
    /// Σ(h − h₀) and Σ(h − h₀)².
    pub sum: f64,
    pub sum_sq: f64,
    pub max: f64,
    /// The first height that is not finite (row-major index and value), if any.
    pub not_finite: Option<(usize, f64)>,
}

/// What the update pass reports: the load sums of the new p, its total Σp, and whether any pixel
/// was released from or clipped to a bound.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Update {
    pub load: LoadSums,
    pub total: f64,
    pub released: bool,
    pub clipped: bool,
}

/// The fields of a contact solve and the passes over them (module documentation). Each method is
/// one fused pass (or one convolution with its fused reduction) of the algorithm of
/// `ContactSolver`; the arithmetic of each is specified in the CPU backend's methods, which
/// another backend must reproduce up to the order of its reductions.
pub(crate) trait ContactBackend: Send + Sync {
    /// The half-space's boundary condition of the backend's influence operator.
    fn boundary(&self) -> Boundary;

    /// 𝒦ᵢᵢ, the displacement of a unit-pressure pixel at that pixel.
    fn self_influence(&self) -> f64;

    /// `out = 𝒦 input` for host fields (a solution's displacement, the Python `influence`).
    fn apply_influence(&mut self, input: &[f64], out: &mut [f64]);

    /// Sets the heights h: `fill` writes them, row-major, into a host buffer of Nx·Ny values.
    fn write_heights(&mut self, fill: &mut dyn FnMut(&mut [f64]));

    /// Binds the two surfaces of a sliding run, fixed for the run: a device backend copies them to
    /// the device once; the CPU backend keeps the shared handles.
    fn bind_surfaces(&mut self, top: Arc<Surface>, bottom: Arc<Surface>);

    /// Sets the heights to the composite topography of the bound surfaces, the top one slid by
    /// `offset` pixels over the bottom one ([`crate::surface::composite_heights`]), where the fields
    /// live. Only after [`ContactBackend::bind_surfaces`].
    fn compose(&mut self, offset: usize);

    /// Binds the law at the surface for the passes that follow (the solver does so at the set-up of
    /// every solve; a backend is made elastic). Only the surface: a change of the heights between
    /// solves (volume plasticity, module documentation) goes through
    /// [`ContactBackend::write_heights`].
    fn bind_law(&mut self, law: SurfaceLaw);

    /// Sets the pressure p (initial guess or warm start): `fill` writes it into a host buffer.
    fn write_pressure(&mut self, fill: &mut dyn FnMut(&mut [f64]));

    /// The pressure p, row-major, on the host (a device backend copies it back).
    fn pressure(&mut self) -> &[f64];

    /// The contact map of p: one bit per pixel, set where p > 0 ([`contact_bit`]), Nx·Ny/64 words
    /// rounded up (the bits past the last pixel are 0); a device backend makes it there and copies
    /// back only the bits.
    fn contact_map(&mut self) -> &[u64];

    /// Statistics of h ([`HeightStats`]), per-row partials combined in row order.
    fn height_stats(&mut self) -> HeightStats;

    /// The initial guess: p clipped to p_m where it is usable (finite, ≥ 0, not all zero), else
    /// the uniform pressure `mean_pressure`. Returns whether p was left exactly as it was (usable
    /// and nowhere above p_m). Here and below, p_m is that of the bound law
    /// ([`SurfaceLaw::flow_pressure`], ∞ when elastic).
    fn initial_guess(&mut self, mean_pressure: f64) -> bool;

    /// [`LoadSums`] of p, over chunks of [`LOAD_CHUNK`] pixels combined in order.
    fn load_sums(&mut self) -> LoadSums;

    /// p ← p_m on every contact pixel (the contact cannot carry the load and must grow).
    fn saturate_contact(&mut self);

    /// Σ min(p_m, s·pᵢ) and its derivative in s, over the movable pixels (free ones, or every
    /// contact pixel when `scale_plastic`), over chunks of [`LOAD_CHUNK`] pixels combined in order.
    fn scaled_load(&mut self, s: f64, scale_plastic: bool) -> (f64, f64);

    /// pᵢ ← min(p_m, s·pᵢ) on the movable pixels.
    fn scale(&mut self, s: f64, scale_plastic: bool);

    /// Gives the load missing from Σp = `total` to the non-contact pixels in proportion to their
    /// penetration −(g − `mean`) (all of them evenly when `mean` is NaN or none penetrates).
    fn spread_missing_load(&mut self, total: f64, mean: f64);

    /// u = 𝒦p, and the [`Stats`] of g = u − h about `reference`.
    fn displacement_and_stats(&mut self, reference: f64) -> Stats;

    /// The [`Stats`] of g = u − h about `reference` for the u held (no convolution), bit for bit
    /// those that [`ContactBackend::displacement_and_stats`] returns when u = 𝒦p already: for a
    /// warm start whose p is unchanged since its u was computed (only the heights moved).
    fn stats(&mut self, reference: f64) -> Stats;

    /// t ← (g − `mean`) + β t on free pixels, 0 elsewhere; returns (Σ t, Σ (g − `mean`) t) over
    /// free pixels.
    fn direction(&mut self, mean: f64, beta: f64) -> (f64, f64);

    /// A power of two near 𝒦ᵢᵢ: [`ContactBackend::curvature`] returns its form divided by it, since
    /// Σ t_f·𝒦t_f itself scales as L³/E* and leaves double precision for boxes far from unit size
    /// (division by a power of two is exact, so nothing else changes).
    fn response_scale(&self) -> f64;

    /// Σ t_f·𝒦t_f / response_scale with t_f = t − `shift` where t ≠ 0 (else 0), from the forward
    /// transform of t_f alone, by Parseval's identity (half a convolution). The transform stays
    /// where the fields live, for [`ContactBackend::advance`]: the other half, needed only when
    /// the step turns out to stay on the CG line.
    fn curvature(&mut self, shift: f64) -> f64;

    /// The same form summed over the pairs of free pixels (t ≠ 0 after the last
    /// [`ContactBackend::direction`]) with the kernel in real space,
    /// [`PairForm`](crate::influence::PairForm), where the operator is periodic and the free
    /// pixels are few enough ([`PairForm::worth`](crate::influence::PairForm::worth)); else `None`
    /// (the caller then takes [`ContactBackend::curvature`]). A backend decides as the reference
    /// of the conformance test does, which checks the choice too. No transform is left: a step
    /// on the CG line takes [`ContactBackend::advance`] afresh, and a step that changes the sets
    /// (most of a warm solve's) saves half a convolution.
    fn direct_curvature(&mut self, shift: f64) -> Option<f64>;

    /// The update pass (copying p first, for [`ContactBackend::undo`]): with `shift` finite, free
    /// pixels take the CG step p −= τ(t − shift), clipped to [0, p_m]; non-contact pixels that
    /// penetrate and plastic pixels whose gap opens take a gradient step p −= τ(g − `mean`). With
    /// `shift` NaN no CG step is taken. u is not moved: after a step that changed the sets the
    /// caller recomputes u = 𝒦p, after one on the CG line it calls [`ContactBackend::advance`].
    fn update(&mut self, mean: f64, tau: f64, shift: f64) -> Update;

    /// After an [`ContactBackend::update`] whose CG step changed no set: r = 𝒦t_f, from the
    /// transform the last [`ContactBackend::curvature`] left when `kept` (no convolution since),
    /// else afresh from t; then u −= τr, and the [`Stats`] of the new p about `mean`, with each
    /// pixel's move ([`Stats::add_change`]: Δp against the copy of p, −Δu = τr).
    fn advance(&mut self, mean: f64, tau: f64, shift: f64, kept: bool) -> Stats;

    /// Swaps u with its spare buffer: the u of the step's start is kept there (for an undo) while
    /// the next [`ContactBackend::displacement_and_stats`] writes a fresh 𝒦p into u.
    fn keep_displacement(&mut self);

    /// Undoes an update: p from its copy, u back to the kept displacement.
    fn undo(&mut self);
}
