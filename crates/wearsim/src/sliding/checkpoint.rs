//! Checkpoints of a long sliding run: its state between two steps saved to a file and read back,
//! so that a run killed (a Slurm job at its wall-time limit) resumes to the results of an
//! uninterrupted run bit for bit.

use std::path::{Path, PathBuf};
use std::time::Duration;

use crate::contact::ContactSolver;
use crate::error::{Error, Result};
use crate::surface::Surface;
use crate::wear::InitialContactMemory;

use super::records::{LoadRun, StepRecord, Timing};
use super::schedule::SlidingSetup;

/// Where and how often a long sliding run saves its state, so that a rerun of a run killed (a Slurm
/// job at its wall-time limit) resumes instead of starting over.
#[derive(Debug, Clone, PartialEq)]
pub struct Checkpointing {
    /// The checkpoint file, replaced atomically at every save.
    pub path: PathBuf,
    /// Least time between two saves; zero saves after every step.
    pub every: Duration,
}

/// The interval between checkpoints when none is given: a killed run loses at most a few minutes.
pub const CHECKPOINT_EVERY: Duration = Duration::from_secs(300);

/// What a run made of the checkpoint file it was given.
#[derive(Debug, Clone, PartialEq)]
pub enum Resumed {
    /// There was none: the run starts at s = 0.
    Fresh,
    /// The run continues after `done` of its `total` steps.
    At { done: usize, total: usize },
    /// The file holds no usable state of this run (other inputs, another version of wearsim, cut
    /// short); the message says why. The run starts at s = 0 and replaces it.
    Ignored(String),
}

/// Version of the checkpoint layout (2: finished loads' results hold `fit_window_start`).
pub(crate) const CHECKPOINT_FORMAT: u32 = 2;

/// First bytes of a checkpoint file; then the length of the JSON state (u64, little-endian), the
/// state, and the contact pressure (Nx·Ny f64, little-endian, exact).
const CHECKPOINT_MAGIC: &[u8] = b"wearsim sliding checkpoint\n";

/// The state of a run between two steps, as saved.
#[derive(serde::Serialize)]
pub(crate) struct SavedState<'a> {
    pub(crate) format: u32,
    pub(crate) software: String,
    /// Hash of every input of the run (see [`inputs_key`]).
    pub(crate) inputs: &'a str,
    /// Steps done over all loads.
    pub(crate) done: usize,
    /// Loads finished.
    pub(crate) finished: &'a [LoadRun],
    /// Records of the load under way.
    pub(crate) steps: &'a [StepRecord],
    pub(crate) timing: Timing,
    pub(crate) books: Vec<serde_json::Value>,
    pub(crate) memory: &'a InitialContactMemory,
}

/// [`SavedState`] as read back.
#[derive(serde::Deserialize)]
pub(crate) struct LoadedState {
    pub(crate) format: u32,
    pub(crate) software: String,
    pub(crate) inputs: String,
    pub(crate) done: usize,
    pub(crate) finished: Vec<LoadRun>,
    pub(crate) steps: Vec<StepRecord>,
    pub(crate) timing: Timing,
    pub(crate) books: Vec<serde_json::Value>,
    pub(crate) memory: InitialContactMemory,
}

/// FNV-1a hash of everything that decides a run's results: the version, the material, modulus,
/// solver options, connectivity and schedule, and both surfaces' sizes and heights (bit patterns).
pub(crate) fn inputs_key(top: &Surface, bottom: &Surface, setup: &SlidingSetup) -> String {
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    let mut feed = |bytes: &[u8]| {
        for b in bytes {
            hash ^= u64::from(*b);
            hash = hash.wrapping_mul(0x0100_0000_01b3);
        }
    };
    feed(crate::io::VERSION.as_bytes());
    let settings = serde_json::json!({
        "material": setup.material,
        "effective_modulus": setup.effective_modulus.to_bits(),
        "solver": setup.solver,
        "connectivity": setup.connectivity,
        "sliding": setup.sliding,
    });
    feed(settings.to_string().as_bytes());
    for surface in [top, bottom] {
        feed(&(surface.nx() as u64).to_le_bytes());
        feed(&(surface.ny() as u64).to_le_bytes());
        feed(&surface.length().to_bits().to_le_bytes());
        feed(&surface.pixel_size().to_bits().to_le_bytes());
        for h in surface.heights() {
            feed(&h.to_bits().to_le_bytes());
        }
    }
    format!("{hash:016x}")
}

/// Writes a checkpoint atomically (temporary sibling, then renamed over the old one).
pub(crate) fn save_checkpoint(path: &Path, state: &SavedState, pressure: &[f64]) -> Result<()> {
    let json =
        serde_json::to_vec(state).map_err(|e| Error::file(path, format!("cannot encode the checkpoint: {e}")))?;
    crate::io::atomic_write(path, |w| {
        w.write_all(CHECKPOINT_MAGIC)?;
        w.write_all(&(json.len() as u64).to_le_bytes())?;
        w.write_all(&json)?;
        for p in pressure {
            w.write_all(&p.to_le_bytes())?;
        }
        Ok(())
    })
}

/// Reads a checkpoint of the run whose inputs hash to `key` into `pressure`; `Ok(None)` when there
/// is no file, `Err(why)` when it cannot be used.
pub(crate) fn load_checkpoint(
    path: &Path,
    key: &str,
    solver: &mut ContactSolver,
    energies: usize,
    steps_per_load: usize,
) -> std::result::Result<Option<LoadedState>, String> {
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(format!("{}: cannot be read ({e})", path.display())),
    };
    let unusable = |why: &str| format!("{}: {why}; the run starts over and replaces it", path.display());
    let rest = bytes
        .strip_prefix(CHECKPOINT_MAGIC)
        .ok_or_else(|| unusable("not a checkpoint of a wearsim sliding run"))?;
    let cut = || unusable("cut short");
    let (len, rest) = rest.split_first_chunk::<8>().ok_or_else(cut)?;
    let len = usize::try_from(u64::from_le_bytes(*len)).map_err(|_| cut())?;
    if rest.len() < len {
        return Err(cut());
    }
    let (json, field) = rest.split_at(len);
    let state: LoadedState = serde_json::from_slice(json).map_err(|e| unusable(&format!("unreadable state ({e})")))?;
    if state.format != CHECKPOINT_FORMAT || state.software != format!("wearsim {}", crate::io::VERSION) {
        return Err(unusable(&format!(
            "written by {} (checkpoint format {}), not by this wearsim {}",
            state.software,
            state.format,
            crate::io::VERSION
        )));
    }
    if state.inputs != key {
        return Err(unusable(
            "saved by a run of other inputs (run file, surfaces or schedule changed since)",
        ));
    }
    if field.len() != solver.grid().pixels() * 8
        || state.books.len() != energies
        || state.steps.len() > steps_per_load
        || state.steps.is_empty() && state.finished.is_empty()
    {
        return Err(cut());
    }
    solver.set_pressure(|pressure| {
        for (p, b) in pressure.iter_mut().zip(field.chunks_exact(8)) {
            *p = f64::from_le_bytes(b.try_into().expect("8 bytes"));
        }
    });
    Ok(Some(state))
}
