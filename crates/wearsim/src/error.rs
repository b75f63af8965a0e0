//! Typed errors of the library. Front ends add context (which file, which command).

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// Everything that can go wrong in wearsim's library, each with the field at fault and the fix.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A parameter outside its physical or numerical range.
    #[error("invalid `{field}`: {message}")]
    InvalidParameter { field: String, message: String },

    /// A height field that cannot be used as a surface.
    #[error("invalid surface `{name}`: {message}")]
    InvalidSurface { name: String, message: String },

    /// A file that could not be read or written.
    #[error("{path}: {message}")]
    Io { path: PathBuf, message: String },

    /// A run or study file that does not describe a valid simulation.
    #[error("{0}")]
    Config(String),

    /// The mean pressure reaches the flow pressure: the surfaces would have to be in full plastic
    /// contact, where the saturated model has no solution.
    #[error(
        "load cannot be carried: mean pressure F_N/L² = {mean_pressure:.6e} is at or above the flow \
         pressure p_m = {flow_pressure:.6e}; lower the load (`loads`) below p_m·L² or raise `shear_strength`"
    )]
    InfeasibleLoad { mean_pressure: f64, flow_pressure: f64 },

    /// The contact solver stopped at its iteration limit before reaching the tolerance.
    #[error(
        "contact solver did not converge: residual {residual:.3e} after {iterations} iterations, \
         tolerance {tolerance:.3e}; raise `max_iterations` or loosen `tolerance` in [contact]"
    )]
    NotConverged {
        iterations: usize,
        residual: f64,
        tolerance: f64,
    },

    /// The caller asked the computation to stop (Ctrl-C in the Python front end).
    #[error("interrupted")]
    Interrupted,
}

/// Result type of the library.
pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    /// Shorthand for [`Error::InvalidParameter`].
    pub fn param(field: impl Into<String>, message: impl Into<String>) -> Self {
        Error::InvalidParameter {
            field: field.into(),
            message: message.into(),
        }
    }

    /// Shorthand for [`Error::Io`].
    pub fn io(path: impl Into<PathBuf>, message: impl ToString) -> Self {
        Error::Io {
            path: path.into(),
            message: message.to_string(),
        }
    }
}

/// A flag another thread may raise to stop a long computation (a contact solve, a sliding run, a
/// study) at its next iteration, which then returns [`Error::Interrupted`]. Clones share the flag.
#[derive(Debug, Clone, Default)]
pub struct Interrupt(Arc<AtomicBool>);

impl Interrupt {
    /// Asks every computation holding this flag to stop.
    pub fn request(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    /// Whether a stop was requested.
    pub fn is_requested(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }

    /// `Err(Error::Interrupted)` once a stop was requested.
    pub fn check(&self) -> Result<()> {
        if self.is_requested() {
            Err(Error::Interrupted)
        } else {
            Ok(())
        }
    }
}
