//! What a contact solve is asked and what it reports: the tolerance and the stopping rule
//! ([`SolverOptions`], [`Stopping`]: the residual at the tolerance, or for sliding a settled contact
//! map, the module documentation of `contact`), why it stopped and what it measured ([`SolveInfo`]).

use crate::error::{Error, Result};

use super::backend;

/// Default convergence tolerance on the residual (see the module documentation). A hundredfold
/// tighter tolerance changes no contact pixel on the paper-roughness problems (validated in
/// `tests/contact_validation.rs`).
pub const DEFAULT_TOLERANCE: f64 = 1e-8;

/// Smallest tolerance a solve in double precision can reach (round-off in 𝒦p is about 1e-16 of h).
pub const MIN_TOLERANCE: f64 = 1e-15;

/// Default iteration limit of one solve.
pub const DEFAULT_MAX_ITERATIONS: usize = 20_000;

/// How many times its move in the last iteration every pixel must be from flipping for its map to
/// count as settled (module documentation, condition 2).
pub const SETTLED_CHANGE_FACTOR: f64 = backend::SETTLED_CHANGE_FACTOR;

/// How far, in residuals, every pixel must be from flipping for its map to count as settled
/// (module documentation, condition 3).
pub const SETTLED_MARGIN: f64 = 0.1;

/// The largest residual at which a map can count as settled (module documentation, condition 4).
pub const SETTLED_MAX_RESIDUAL: f64 = 1e-5;

/// When a solve stops (module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Stopping {
    /// When the residual reaches the tolerance: single solves (`wearsim contact`, the Python
    /// solver) and the validation against analytic solutions and tamaas.
    Tolerance,
    /// When the contact map is settled, or when the residual reaches the tolerance if that comes
    /// first: the default of sliding runs ([`SLIDING_STOPPING`]).
    SettledMap,
}

/// How the solves of a sliding run stop unless the run file says otherwise (`[sliding] stopping`).
pub const SLIDING_STOPPING: Stopping = Stopping::SettledMap;

impl Stopping {
    /// The name used in run files and in Python.
    pub fn name(self) -> &'static str {
        match self {
            Stopping::Tolerance => "tolerance",
            Stopping::SettledMap => "settled-map",
        }
    }
}

impl std::str::FromStr for Stopping {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "tolerance" => Ok(Stopping::Tolerance),
            "settled-map" => Ok(Stopping::SettledMap),
            other => Err(Error::param(
                "stopping",
                format!(
                    "{other:?} is not a stopping rule; use \"settled-map\" (stop once the contact map is settled) \
                     or \"tolerance\" (stop at the residual tolerance)"
                ),
            )),
        }
    }
}

/// Convergence settings of the contact solver.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SolverOptions {
    pub(super) tolerance: f64,
    pub(super) max_iterations: usize,
    pub(super) stopping: Stopping,
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
            stopping: Stopping::Tolerance,
        })
    }

    /// The settings with another stopping rule (the tolerance stays the residual at which every
    /// solve stops).
    pub fn with_stopping(mut self, stopping: Stopping) -> Self {
        self.stopping = stopping;
        self
    }

    /// Tolerance on the residual (module documentation).
    pub fn tolerance(&self) -> f64 {
        self.tolerance
    }

    /// When a solve stops.
    pub fn stopping(&self) -> Stopping {
        self.stopping
    }

    /// Iteration limit; reaching it is an [`Error::NotConverged`] from `ContactSolver::solve`.
    pub fn max_iterations(&self) -> usize {
        self.max_iterations
    }
}

impl Default for SolverOptions {
    fn default() -> Self {
        Self {
            tolerance: DEFAULT_TOLERANCE,
            max_iterations: DEFAULT_MAX_ITERATIONS,
            stopping: Stopping::Tolerance,
        }
    }
}

/// Why a solve stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Termination {
    /// The residual reached the tolerance, confirmed on a freshly computed displacement.
    Converged,
    /// The contact map was settled ([`Stopping::SettledMap`]) before the residual reached the
    /// tolerance, confirmed on a freshly computed displacement.
    Settled,
    /// The iteration limit was reached first.
    MaxIterations,
}

/// What one solve reports beside the pressure field.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SolveInfo {
    /// Why the solve stopped (`ContactSolver::solve` returns only converged or settled solves).
    pub termination: Termination,
    /// Conjugate-gradient iterations.
    pub iterations: usize,
    /// Convolutions performed in all: the recomputations of 𝒦p, and per iteration one, whether it
    /// completes its convolution 𝒦t (a step on the CG line) or needs only the forward half for its
    /// curvature (a step that changes the sets, whose 𝒦p is recomputed); none for its curvature
    /// where it came from the pairs of few free pixels (a step on the CG line then counts its
    /// whole convolution 𝒦t).
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
