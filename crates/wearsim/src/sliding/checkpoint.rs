//! Checkpoints of a sliding run: its state between two steps saved atomically (every
//! `Checkpointing::every` and when the run is stopped), with a checksum of the payload, and read
//! back only when the checksum, the layout, the version, the run's inputs and the ranges of its
//! values all agree, so that a resumed run equals an uninterrupted one bit for bit.

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
    /// short, damaged: its checksum or a value out of range); the message says why. The run starts
    /// at s = 0 and replaces it.
    Ignored(String),
    /// The run was stopped (a signal, a Slurm time limit) and its state after `done` of `total`
    /// steps was saved: the same run resumes from there.
    Saved { done: usize, total: usize },
    /// A checkpoint could not be written (a full disk); the message says why. The run goes on to its
    /// results, and a kill would lose the steps since the last checkpoint.
    NotSaved(String),
}

/// Version of the checkpoint layout (2: finished loads' results hold `fit_window_start`; 3: a
/// checksum of the payload, the layout below).
pub(crate) const CHECKPOINT_FORMAT: u32 = 3;

/// First bytes of a checkpoint file; then the length of the JSON state (u64, little-endian), the
/// checksum of the payload ([`payload_checksum`], u64 little-endian), the state, and the contact
/// pressure (Nx·Ny f64, little-endian, exact).
const CHECKPOINT_MAGIC: &[u8] = b"wearsim sliding checkpoint 3\n";

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

/// Checksum of a checkpoint's payload (its JSON state and the pressure's bits): FNV-1a over the
/// bytes of the state and the 64-bit words of the field. It finds a changed digit, a flipped bit or
/// bytes overwritten with NaN, which would otherwise resume a run to wrong results.
fn payload_checksum(json: &[u8], pressure_bits: impl Iterator<Item = u64>) -> u64 {
    const PRIME: u64 = 0x0100_0000_01b3;
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in json {
        hash = (hash ^ u64::from(b)).wrapping_mul(PRIME);
    }
    for w in pressure_bits {
        hash = (hash ^ w).wrapping_mul(PRIME);
        hash ^= hash >> 29;
    }
    hash
}

/// Writes a checkpoint atomically (temporary sibling, then renamed over the old one).
pub(crate) fn save_checkpoint(path: &Path, state: &SavedState, pressure: &[f64]) -> Result<()> {
    let json =
        serde_json::to_vec(state).map_err(|e| Error::file(path, format!("cannot encode the checkpoint: {e}")))?;
    let checksum = payload_checksum(&json, pressure.iter().map(|p| p.to_bits()));
    crate::io::atomic_write(path, |w| {
        w.write_all(CHECKPOINT_MAGIC)?;
        w.write_all(&(json.len() as u64).to_le_bytes())?;
        w.write_all(&checksum.to_le_bytes())?;
        w.write_all(&json)?;
        for p in pressure {
            w.write_all(&p.to_le_bytes())?;
        }
        Ok(())
    })
}

/// Reads a checkpoint of the run whose inputs hash to `key` into the solver's pressure; `Ok(None)`
/// when there is no file, `Err(why)` when it cannot be used: another layout, version or run, cut
/// short, a checksum that does not match its payload, or values out of range. Temporary files of
/// saves cut short by a kill are removed.
pub(crate) fn load_checkpoint(
    path: &Path,
    key: &str,
    solver: &mut ContactSolver,
    pm: f64,
    energies: usize,
    steps_per_load: usize,
) -> std::result::Result<Option<LoadedState>, String> {
    crate::io::remove_abandoned_siblings(path);
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(format!("{}: cannot be read ({e})", path.display())),
    };
    let unusable = |why: &str| format!("{}: {why}; the run starts over and replaces it", path.display());
    if bytes.starts_with(b"wearsim sliding checkpoint\n") {
        return Err(unusable(
            "written by an earlier version of wearsim (checkpoint format 2)",
        ));
    }
    let rest = bytes
        .strip_prefix(CHECKPOINT_MAGIC)
        .ok_or_else(|| unusable("not a checkpoint of a wearsim sliding run"))?;
    let cut = || unusable("cut short");
    let (len, rest) = rest.split_first_chunk::<8>().ok_or_else(cut)?;
    let (checksum, rest) = rest.split_first_chunk::<8>().ok_or_else(cut)?;
    let len = usize::try_from(u64::from_le_bytes(*len)).map_err(|_| cut())?;
    if rest.len() < len {
        return Err(cut());
    }
    let (json, field) = rest.split_at(len);
    if field.len() != solver.grid().pixels() * 8 {
        return Err(cut());
    }
    let bits = || {
        field
            .chunks_exact(8)
            .map(|b| u64::from_le_bytes(b.try_into().expect("8 bytes")))
    };
    if payload_checksum(json, bits()) != u64::from_le_bytes(*checksum) {
        return Err(unusable(
            "damaged: its checksum does not match its contents (a changed byte, a disk or copy error)",
        ));
    }
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
    if let Some(why) = out_of_range(&state, bits().map(f64::from_bits), pm, energies, steps_per_load) {
        return Err(unusable(&format!("holds {why}")));
    }
    if state.steps.is_empty() && state.finished.is_empty() {
        return Err(cut());
    }
    solver.set_pressure(|pressure| {
        for (p, b) in pressure.iter_mut().zip(bits()) {
            *p = f64::from_bits(b);
        }
    });
    Ok(Some(state))
}

/// What in a checkpoint's state is out of range, if anything: the pressure outside [0, p_m], counts
/// that do not add up, records with too many values or values no run makes (NaN, negative volumes).
fn out_of_range(
    state: &LoadedState,
    mut pressure: impl Iterator<Item = f64>,
    pm: f64,
    energies: usize,
    steps_per_load: usize,
) -> Option<String> {
    if let Some(p) = pressure.find(|p| !(*p >= 0.0 && *p <= pm * (1.0 + 1e-9))) {
        return Some(format!("a contact pressure of {p:e} outside [0, p_m = {pm:e}]"));
    }
    let recorded = state.finished.iter().map(|r| r.steps.len()).sum::<usize>() + state.steps.len();
    if recorded != state.done || state.books.len() != energies || state.steps.len() > steps_per_load {
        return Some(format!(
            "{} steps done but {recorded} recorded, {} bookkeepings for {energies} fracture energies",
            state.done,
            state.books.len()
        ));
    }
    let steps = state.finished.iter().flat_map(|r| r.steps.iter()).chain(&state.steps);
    for r in steps {
        let bad = !(r.s.is_finite() && r.s >= 0.0 && (0.0..=1.0).contains(&r.contact_area))
            || r.wear.len() != energies
            || r.statics.len() != energies
            || r.wear.iter().any(|w| !(w.volume.is_finite() && w.volume >= 0.0));
        if bad {
            return Some(format!("a step record out of range (at s = {:e})", r.s));
        }
    }
    None
}
