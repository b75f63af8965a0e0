//! The study folder: the stored study (its canonical text, hash and base folder); one job file per
//! finished job, written atomically and checked against its job when read back; and one claim file
//! per job under way, so that runs sharing a folder (Slurm shards, a second run started by
//! mistake) never compute a job twice nor touch each other's files.

use std::path::{Path, PathBuf};
use std::time::SystemTime;

use crate::error::{Error, Result};
use crate::io::{
    claim_is_stale, create_claim_file, folder_owner, host_name, make_folder, marker, process_gone, read_text,
    remove_own_claim, temporary_sibling, write_json, write_text, FolderOwner, MARKER,
};
pub use crate::io::{CLAIM_EXPIRY, CLAIM_REFRESH};
use crate::model::WearModel;
use crate::output::{read_job_file, JobResult};
use crate::sliding::WearResult;
use crate::study::expand::{Job, Study};

/// Path of job `index`'s result file in a study folder.
pub fn job_path(dir: &Path, index: usize) -> PathBuf {
    dir.join("jobs").join(format!("job-{index:06}.json"))
}

/// Path of job `index`'s claim file.
fn claim_path(dir: &Path, index: usize) -> PathBuf {
    dir.join("jobs").join(format!("job-{index:06}.claim"))
}

/// Writes a job's result file atomically (the file whose presence marks the job done).
pub fn write_result(dir: &Path, result: &JobResult) -> Result<()> {
    let path = job_path(dir, result.index);
    let text = result.to_json();
    // JSON has no NaN or infinity (serde writes null): a result holding one would be read back
    // as a file cut short and recomputed on every rerun. Refuse it once, as the job's error.
    if let Err(e) = JobResult::from_json(&text) {
        return Err(Error::file(
            &path,
            format!(
                "not written: the job's results hold a value that is not a finite number ({e}); this is a bug of \
                 wearsim for inputs within its ranges, please report it with the study file"
            ),
        ));
    }
    write_text(&path, &with_checksum(&text))
}

/// A job file's text with the checksum of its JSON appended as its last key, so that a file
/// damaged or edited since it was written (one digit of a wear rate) is found when it is read.
fn with_checksum(json: &str) -> String {
    crate::io::with_checksum(json)
}

/// Checks the checksum of a job file's text; files of earlier versions have none and pass (their
/// values are still checked, [`out_of_range`]).
fn checksum_matches(text: &str) -> bool {
    crate::io::checksum_matches(text).unwrap_or(true)
}

/// What in a job's result is out of the range any run gives, if anything: results for another
/// number of fracture energies, negative rates, volumes or means, an R² outside [0, 1], a contact
/// area outside [0, 1], volumes or particle counts that fall along the slide.
pub fn out_of_range(r: &JobResult, job: &Job) -> Option<String> {
    let energies = &job.run.material.fracture_energies;
    if r.results.len() != energies.len() {
        return Some(format!(
            "results for {} fracture energies where the job has {}",
            r.results.len(),
            energies.len()
        ));
    }
    for (e, (w, &g)) in r.results.iter().zip(energies).enumerate() {
        if let Some((name, value, rule)) = result_out_of_range(w, g) {
            return Some(format!("`results[{e}].{name}` = {value:e}, which must be {rule}"));
        }
    }
    // Each model's own record in the job file.
    match job.run.model {
        WearModel::Sliding => {}
        WearModel::Estimate => return estimate_out_of_range(r, energies),
    }
    if !r.estimates.is_empty() {
        return Some("estimates in the file of a sliding job".into());
    }
    steps_out_of_range(r, energies.len())
}

/// A finite value ≥ 0.
fn nonneg(v: f64) -> bool {
    v.is_finite() && v >= 0.0
}

/// A finite value within [0, 1] (to round-off).
fn ratio(v: f64) -> bool {
    v.is_finite() && (-1e-9..=1.0 + 1e-9).contains(&v)
}

/// The first value of one result (of fracture energy `g`) out of its range: its name, the value and
/// the rule it breaks.
fn result_out_of_range(w: &WearResult, g: f64) -> Option<(&'static str, f64, &'static str)> {
    let optional = [
        ("wear_rate", w.wear_rate),
        ("wear_coefficient", w.wear_coefficient),
        ("particle_rate", w.particle_rate),
        ("wear_rate_estimate", w.wear_rate_estimate),
        ("memory_decay_length", w.memory_decay_length),
        ("memory_fit_initial_junctions", w.memory_fit_initial_junctions),
        ("running_in_decay_lengths", w.running_in_decay_lengths),
        ("initial_lineages_left", w.initial_lineages_left),
        ("critical_residence", w.critical_residence),
        ("contact_area_mean", w.contact_area_mean),
        ("largest_junction_max", w.largest_junction_max),
        ("critical_junction_growth", w.critical_junction_growth),
    ];
    let plain = [
        ("fit_window_start", w.fit_window_start),
        ("initial_volume", w.initial_volume),
        ("static_wear_rate", w.static_wear_rate),
        ("static_wear_coefficient_std", w.static_wear_coefficient_std),
        ("static_wear_rate_mean", w.static_wear_rate_mean),
        ("static_wear_rate_std", w.static_wear_rate_std),
        ("junctions_mean", w.junctions_mean),
        ("critical_junctions_mean", w.critical_junctions_mean),
    ];
    let ratios = [
        ("wear_rate_r2", w.wear_rate_r2),
        ("memory_decay_r2", w.memory_decay_r2),
        ("static_wear_coefficient", Some(w.static_wear_coefficient)),
        ("static_wear_coefficient_mean", Some(w.static_wear_coefficient_mean)),
        ("merged_junction_share", w.merged_junction_share),
    ];
    optional
        .iter()
        .find(|(_, v)| v.is_some_and(|v| !nonneg(v)))
        .map(|(name, v)| (*name, v.unwrap_or_default(), "≥ 0"))
        .or_else(|| plain.iter().find(|(_, v)| !nonneg(*v)).map(|(n, v)| (*n, *v, "≥ 0")))
        .or_else(|| {
            ratios
                .iter()
                .find(|(_, v)| v.is_some_and(|v| !ratio(v)))
                .map(|(n, v)| (*n, v.unwrap_or_default(), "within [0, 1]"))
        })
        .or_else(|| (w.fracture_energy != g).then_some(("fracture_energy", w.fracture_energy, "the job's")))
        .or_else(|| {
            (!(w.critical_diameter.is_finite() && w.critical_diameter > 0.0)).then_some((
                "critical_diameter",
                w.critical_diameter,
                "> 0",
            ))
        })
}

/// What in a sliding job's steps (`energies` fracture energies each) is out of range: none, a count
/// per step that is not one per energy, a negative distance, a contact area outside [0, 1], volumes
/// or particle counts that fall along the slide.
fn steps_out_of_range(r: &JobResult, energies: usize) -> Option<String> {
    if r.steps.is_empty() {
        return Some("no sliding step".into());
    }
    for (k, st) in r.steps.iter().enumerate() {
        let counts = [
            st.n_critical.len(),
            st.n_formed.len(),
            st.volume.len(),
            st.static_wear_coefficient.len(),
        ];
        let bad = counts.iter().any(|&c| c != energies)
            || !nonneg(st.s)
            || !ratio(st.contact_area)
            || st.volume.iter().any(|&v| !nonneg(v))
            || st.static_wear_coefficient.iter().any(|&v| !ratio(v));
        let falls = k > 0 && {
            let prev = &r.steps[k - 1];
            st.s < prev.s
                || st.volume.iter().zip(&prev.volume).any(|(a, b)| a < b)
                || st.n_formed.iter().zip(&prev.n_formed).any(|(a, b)| a < b)
        };
        if bad || falls {
            return Some(format!(
                "a step out of range (step {k}, s = {:e}: volumes and particle counts only grow along the slide, \
                 the contact area is within [0, 1])",
                st.s
            ));
        }
    }
    None
}

/// What in an estimate job's file is out of the range an estimate gives: sliding steps, estimates
/// for other fracture energies, negative or non-finite values, a value outside its interval.
fn estimate_out_of_range(r: &JobResult, energies: &[f64]) -> Option<String> {
    if !r.steps.is_empty() {
        return Some(format!(
            "{} sliding steps in the file of an estimate, which takes none",
            r.steps.len()
        ));
    }
    if r.estimates.len() != energies.len() || r.estimates.iter().zip(energies).any(|(e, &g)| e.fracture_energy != g) {
        return Some(format!(
            "estimates for {} fracture energies where the job has {}",
            r.estimates.len(),
            energies.len()
        ));
    }
    for (i, e) in r.estimates.iter().enumerate() {
        let triples = [
            ("wear_rate", e.wear_rate_low, e.wear_rate, e.wear_rate_high),
            (
                "wear_coefficient",
                e.wear_coefficient_low,
                e.wear_coefficient,
                e.wear_coefficient_high,
            ),
            (
                "particle_rate",
                e.particle_rate_low,
                e.particle_rate,
                e.particle_rate_high,
            ),
        ];
        for (name, lo, v, hi) in triples {
            let ok = match (lo, v, hi) {
                (None, None, None) => true,
                // Outside the calibrated domain the estimate gives W without an interval, and says why.
                (None, Some(v), None) => e.interval_withheld.is_some() && v.is_finite() && v >= 0.0,
                (Some(lo), Some(v), Some(hi)) => lo.is_finite() && hi.is_finite() && 0.0 <= lo && lo <= v && v <= hi,
                _ => false,
            };
            if !ok {
                return Some(format!(
                    "`estimates[{i}].{name}` = {v:?} with the interval [{lo:?}, {hi:?}], which must be finite, ≥ 0 \
                     and within it"
                ));
            }
        }
        if !(e.critical_junctions_mean.is_finite() && e.critical_junctions_mean >= 0.0) {
            return Some(format!(
                "`estimates[{i}].critical_junctions_mean` = {:e}, which must be ≥ 0",
                e.critical_junctions_mean
            ));
        }
    }
    None
}

/// What a study folder holds for one job.
#[derive(Debug)]
pub enum Stored {
    /// The job's result.
    Done(Box<JobResult>),
    /// Nothing yet.
    Missing,
    /// A file that cannot be read (cut short, empty, from another version of wearsim): the job is
    /// to be computed again, and the message says why.
    Unreadable(String),
}

/// Reads what the folder holds for `job`. A readable file written for another job is an error: it
/// was copied or renamed into the folder, and only the user can say what it is.
pub fn stored_result(job: &Job, dir: &Path) -> Result<Stored> {
    let path = job_path(dir, job.index);
    if !path.is_file() {
        return Ok(Stored::Missing);
    }
    let r = match read_job_file(&path) {
        Ok(r) => r,
        Err(Error::InvalidFile { message, .. }) => {
            return Ok(Stored::Unreadable(format!("{}: {message}", path.display())))
        }
        Err(e) => return Err(e),
    };
    if !checksum_matches(&read_text(&path)?) {
        return Ok(Stored::Unreadable(format!(
            "{}: its checksum does not match its contents: the file was edited or damaged since the job wrote it",
            path.display()
        )));
    }
    if r.format != crate::output::JOB_FORMAT {
        return Err(Error::StudyFolder {
            dir: dir.into(),
            message: format!(
                "{} was written by another version of wearsim ({}, job-file format {}; this one writes format {}); \
                 finish the study with that version, or start a new --out folder with this one",
                path.display(),
                r.provenance.software,
                r.format,
                crate::output::JOB_FORMAT
            ),
        });
    }
    if !job.is_result_of(&r) {
        let (theirs, ours) = (r.inputs.model.unwrap_or_default(), job.run.model);
        let model = if theirs == ours {
            format!("model {:?}", ours.name())
        } else {
            format!(
                "a result of model {:?} where this job is one of model {:?}",
                theirs.name(),
                ours.name()
            )
        };
        return Err(Error::file(
            &path,
            format!(
                "holds the result of job {} ({}, load {:e}; {model}) with other inputs than {}{}: the file was \
                 copied or renamed from another job or study; delete it and run the study again to recompute job {}",
                r.index,
                r.material,
                r.load,
                job.describe(),
                differing_inputs(&r.inputs, &job.inputs()),
                job.index
            ),
        ));
    }
    if let Some(why) = out_of_range(&r, job) {
        return Ok(Stored::Unreadable(format!(
            "{}: holds {why}; no run writes that, so the file was edited or damaged",
            path.display()
        )));
    }
    Ok(Stored::Done(Box::new(r)))
}

/// The inputs in which a job file's record differs from its job's, for messages: " (in
/// `sliding.model`: \"estimate\" in the file, none in the job)"; empty when they agree.
fn differing_inputs(file: &crate::config::InputRecord, job: &crate::config::InputRecord) -> String {
    let (Ok(serde_json::Value::Object(a)), Ok(serde_json::Value::Object(b))) =
        (serde_json::to_value(file), serde_json::to_value(job))
    else {
        return String::new();
    };
    let none = serde_json::Value::Null;
    let mut keys: Vec<&String> = a.keys().chain(b.keys()).collect();
    keys.dedup();
    let mut shown: Vec<String> = Vec::new();
    for k in keys {
        let (x, y) = (a.get(k).unwrap_or(&none), b.get(k).unwrap_or(&none));
        let text = |v: &serde_json::Value| if v.is_null() { "none".to_string() } else { v.to_string() };
        if x != y && !shown.iter().any(|s| s.starts_with(&format!("`{k}`"))) {
            shown.push(format!("`{k}`: {} in the file, {} in the job", text(x), text(y)));
        }
    }
    if shown.is_empty() {
        String::new()
    } else {
        format!(" (in {})", shown.join("; "))
    }
}

/// Reads `job`'s result file, checking that it was written for this job.
pub fn read_result(job: &Job, dir: &Path) -> Result<JobResult> {
    match stored_result(job, dir)? {
        Stored::Done(r) => Ok(*r),
        Stored::Missing => Err(Error::file(
            job_path(dir, job.index),
            "no result yet; run the study to compute it",
        )),
        // The message names the file already.
        Stored::Unreadable(message) => Err(Error::StudyFolder {
            dir: dir.into(),
            message: format!("{message} (`wearsim study run` recomputes it)"),
        }),
    }
}

/// A claim on a job: the file `job-NNNNNN.claim`, created exclusively before the job is computed
/// and removed when it is done (or abandoned). While it is held, the runner refreshes its
/// modification time every [`CLAIM_REFRESH`] from a thread of its own, so that other runs can tell a
/// live claim from one left by a killed process ([`claim_is_stale`]: the same rule as the claims of
/// output folders).
#[derive(Debug)]
pub struct Claim {
    path: PathBuf,
}

impl Claim {
    /// Claims job `index`; `Ok(None)` when another live run holds it. A stale claim (not refreshed
    /// for [`CLAIM_EXPIRY`]; on this host also one whose process is gone or whose process id now
    /// belongs to another process) is taken over.
    pub fn take(dir: &Path, index: usize) -> Result<Option<Claim>> {
        let path = claim_path(dir, index);
        for _ in 0..2 {
            if create_claim_file(&path)? {
                return Ok(Some(Claim { path }));
            }
            if !claim_is_stale(&path) {
                return Ok(None);
            }
            let _ = std::fs::remove_file(&path);
        }
        Ok(None)
    }

    /// After a run killed between writing job `index`'s file and releasing its claim: removes that
    /// claim when it is stale, and then the job's `checkpoint` (a finished job needs none). A live
    /// run's claim, and so its checkpoint, are left to it.
    pub fn release_abandoned(dir: &Path, index: usize, checkpoint: &Path) {
        let path = claim_path(dir, index);
        if path.exists() {
            if !claim_is_stale(&path) {
                return;
            }
            let _ = std::fs::remove_file(&path);
        }
        let _ = std::fs::remove_file(checkpoint);
    }

    /// Who holds job `index`'s claim, for messages: "process PID on HOST, refreshed N s ago (FILE)";
    /// `None` when there is no claim.
    pub fn holder(dir: &Path, index: usize) -> Option<String> {
        let path = claim_path(dir, index);
        let owner = std::fs::read_to_string(&path).ok()?;
        let mut words = owner.split_whitespace();
        let who = match (words.next(), words.next()) {
            (Some(host), Some(pid)) => format!("process {pid} on {host}"),
            _ => "a run that is starting".to_string(),
        };
        let age = std::fs::metadata(&path)
            .and_then(|m| m.modified())
            .ok()
            .and_then(|t| SystemTime::now().duration_since(t).ok())
            .map_or(String::new(), |a| format!(", refreshed {} s ago", a.as_secs()));
        Some(format!("{who}{age}: {}", path.display()))
    }

    /// The claim file.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

impl Drop for Claim {
    fn drop(&mut self) {
        remove_own_claim(&self.path);
    }
}

/// Prepares a study folder: stores the study, its hash and the folder its relative paths resolve
/// against on first use, refuses a folder made by a different study, and removes temporary files
/// that killed runs left behind (only those older than [`CLAIM_EXPIRY`]: a younger one may be
/// another run's file being written).
pub fn prepare_folder(dir: &Path, study: &Study, base: &Path) -> Result<()> {
    let mut inputs: Vec<&Path> = Vec::new();
    for job in &study.jobs {
        inputs.extend(job.run.surfaces.input_files());
    }
    crate::io::refuse_inputs_inside(dir, &inputs)?;
    refuse_foreign_study_folder(dir)?;
    make_folder(&dir.join("jobs"))?;
    let hash_path = dir.join("study.hash");
    // The folder belongs to the first study that links its hash file into place: a hard link
    // cannot replace an existing file, so of two studies started at once exactly one wins, and the
    // other finds its hash and is refused before any work.
    let stored = if hash_path.exists() {
        read_text(&hash_path)?
    } else {
        let tmp = temporary_sibling(&hash_path)?;
        write_text(&tmp, &study.hash)?;
        let linked = std::fs::hard_link(&tmp, &hash_path);
        let _ = std::fs::remove_file(&tmp);
        match linked {
            Ok(()) => study.hash.clone(),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => read_text(&hash_path)?,
            Err(e) => return Err(Error::io(&hash_path, e)),
        }
    };
    if stored.trim() != study.hash {
        return Err(Error::StudyFolder {
            dir: dir.into(),
            message: format!(
                "holds results of a different study (hash {} ≠ {}: another study file, or the study file or a surface \
                 file it names has changed); use a new --out folder or restore the original files",
                stored.trim(),
                study.hash
            ),
        });
    }
    // Written by the study that claimed the folder (or, if it was killed first, by the next run).
    if !dir.join(MARKER).is_file() {
        write_json(&dir.join(MARKER), &marker(STUDY_COMMAND, None))?;
    }
    if !dir.join("study.toml").is_file() {
        let base = base.canonicalize().map_err(|e| Error::io(base, e))?;
        write_text(&dir.join("study.base"), &base.to_string_lossy())?;
        write_text(&dir.join("study.toml"), &study.canonical)?;
    }
    let jobs = dir.join("jobs");
    for entry in std::fs::read_dir(&jobs).map_err(|e| Error::io(&jobs, e))?.flatten() {
        let name = entry.file_name().to_string_lossy().to_string();
        let old = entry
            .metadata()
            .and_then(|m| m.modified())
            .ok()
            .and_then(|t| SystemTime::now().duration_since(t).ok())
            .is_some_and(|age| age > CLAIM_EXPIRY);
        if name.starts_with('.') && name.ends_with(".tmp") && (old || abandoned_here(&name)) {
            let _ = std::fs::remove_file(entry.path());
        }
    }
    Ok(())
}

/// The command whose folders are study folders (the marker's `command`).
pub const STUDY_COMMAND: &str = "study run";

/// Refuses a study folder that is not empty and is not a study folder: another command's results,
/// the user's own files (a `results.csv` of theirs would be replaced by `collect`). A folder being
/// made by another study at this moment (only `jobs` and its hash file's temporaries) is left to the
/// hash-file race of [`prepare_folder`].
fn refuse_foreign_study_folder(dir: &Path) -> Result<()> {
    if dir.exists() && !dir.is_dir() {
        return Err(Error::file(dir, "exists and is not a folder; give another --out"));
    }
    let jobs = dir.join("jobs");
    if jobs.exists() && !jobs.is_dir() {
        return Err(Error::StudyFolder {
            dir: dir.into(),
            message: format!(
                "holds a file {} where a study keeps its job folder, so it is no study folder; give a new or empty \
                 --out folder for the study",
                jobs.display()
            ),
        });
    }
    // Listed once: what a study being made holds before its hash file (which never goes away) is
    // its `jobs` folder and the temporary files of that hash file.
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(());
    };
    let starting = entries.flatten().all(|e| {
        let name = e.file_name().to_string_lossy().to_string();
        name == "jobs" || name.starts_with('.') && name.contains(".study.hash.") && name.ends_with(".tmp")
    });
    if starting {
        return Ok(());
    }
    match folder_owner(dir)? {
        FolderOwner::Nobody => Ok(()),
        FolderOwner::Wearsim { command, .. } if command == STUDY_COMMAND => Ok(()),
        FolderOwner::Wearsim { command, .. } => Err(Error::StudyFolder {
            dir: dir.into(),
            message: format!(
                "holds the results of `wearsim {command}`, not a study; give a new or empty --out folder for the study"
            ),
        }),
        FolderOwner::Foreign => Err(Error::StudyFolder {
            dir: dir.into(),
            message: "holds files that wearsim did not write and is no study folder; give a new or empty --out \
                      folder for the study (wearsim writes results.csv and more there)"
                .into(),
        }),
    }
}

/// Whether a temporary file `.NAME.HOST.PID-K.tmp` belongs to a process of this host that is gone.
fn abandoned_here(name: &str) -> bool {
    let Some(owner) = name.strip_suffix(".tmp") else {
        return false;
    };
    let Some((rest, pid_k)) = owner.rsplit_once('.') else {
        return false;
    };
    let Some((pid, _)) = pid_k.split_once('-') else {
        return false;
    };
    rest.ends_with(&format!(".{}", host_name())) && process_gone(pid) == Some(true)
}

/// The stored study of a folder and the folder its relative paths resolve against, checked: a
/// stored study file that no longer expands, or that changed since the jobs were run (its hash is
/// not the one the folder recorded), is an error naming it and what to do, before any job file is
/// read (whose inputs would then differ from the changed study's jobs).
pub fn stored_study(dir: &Path) -> Result<(String, PathBuf)> {
    let file = dir.join("study.toml");
    if !file.is_file() {
        let what = if dir.is_dir() {
            "holds no study.toml, so it is no study folder"
        } else if dir.exists() {
            "is not a folder, so it is no study folder"
        } else {
            "does not exist"
        };
        return Err(Error::file(
            dir,
            format!("{what}; give the --out folder of a `wearsim study run`"),
        ));
    }
    let text = read_text(&file)?;
    let base = std::fs::read_to_string(dir.join("study.base"))
        .map(PathBuf::from)
        .unwrap_or_else(|_| dir.to_path_buf());
    let restore = "restore it as `wearsim study run` stored it, or run the changed study file into a new folder \
                   (`wearsim study run STUDY.toml --out NEW_FOLDER`)";
    let study = crate::study::expand::expand_stored(&text, &base).map_err(|e| {
        Error::file(
            &file,
            format!(
                "the copy of the study file that `wearsim study run` stored in its study folder cannot be read as a \
                 study: {e}; where that is a size or a load the study takes from its surface files (a map's import \
                 record, a column file's span, `pressures` on files), put those files back where the study ran; \
                 else the copy was edited or damaged since: {restore}"
            ),
        )
    })?;
    // The recorded hash covers the surface files too: checked when they can all be read (a folder
    // whose surfaces moved is still read without them, unless the study takes a size or a load
    // from them).
    let recorded = std::fs::read_to_string(dir.join("study.hash")).unwrap_or_default();
    if let Ok(hash) = crate::study::expand::hash_with_surfaces(&study) {
        if !recorded.trim().is_empty() && recorded.trim() != hash {
            let names_files = hash != study.hash;
            return Err(Error::file(
                &file,
                format!(
                    "the study file stored in the study folder{} changed since its jobs were run (hash {hash}, where \
                     the jobs were run for {}): the job files hold the results of the study as it was run and are \
                     not at fault; {restore}",
                    if names_files {
                        ", or a surface file it names,"
                    } else {
                        ""
                    },
                    recorded.trim()
                ),
            ));
        }
    }
    Ok((text, base))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_job_files_checksum_finds_one_changed_digit_and_files_without_one_pass() {
        let json = r#"{"format":3,"results":[{"wear_rate":1.2345e-4}]}"#;
        let text = with_checksum(json);
        assert!(text.starts_with(&json[..json.len() - 1]) && text.ends_with("\"}"));
        assert!(checksum_matches(&text) && checksum_matches(&format!("{text}\n")));
        assert!(!checksum_matches(&text.replace("1.2345", "1.2346")));
        assert!(!checksum_matches(&text.replace("fnv1a64:", "fnv1a64:0")));
        // Written before checksums: only range-checked.
        assert!(checksum_matches(json));
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(v["results"][0]["wear_rate"], 1.2345e-4);
    }

    #[test]
    fn a_finished_jobs_claim_and_checkpoint_left_by_a_killed_run_are_removed_a_live_ones_kept() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir_all(dir.path().join("jobs")).unwrap();
        let checkpoint = |i: usize| dir.path().join("jobs").join(format!("job-{i}.checkpoint"));
        // Killed after writing the job file: the claim of a process that does not exist.
        std::fs::write(claim_path(dir.path(), 1), format!("{} 4000000000\n", host_name())).unwrap();
        std::fs::write(checkpoint(1), "state").unwrap();
        Claim::release_abandoned(dir.path(), 1, &checkpoint(1));
        assert!(!claim_path(dir.path(), 1).exists() && !checkpoint(1).exists());
        // A live run finishing the job: its claim and checkpoint are its own.
        let live = Claim::take(dir.path(), 2).unwrap().expect("free");
        std::fs::write(checkpoint(2), "state").unwrap();
        Claim::release_abandoned(dir.path(), 2, &checkpoint(2));
        assert!(live.path().exists() && checkpoint(2).exists());
        drop(live);
        // No claim: a checkpoint left behind goes.
        Claim::release_abandoned(dir.path(), 2, &checkpoint(2));
        assert!(!checkpoint(2).exists());
    }

    #[test]
    fn a_claim_is_exclusive_and_one_left_by_a_dead_process_is_taken_over() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir_all(dir.path().join("jobs")).unwrap();
        let first = Claim::take(dir.path(), 3).unwrap().expect("free");
        assert!(
            Claim::take(dir.path(), 3).unwrap().is_none(),
            "held by a live process (this one)"
        );
        drop(first);
        assert!(!claim_path(dir.path(), 3).exists());
        // A claim of this host by a process that does not exist.
        std::fs::write(claim_path(dir.path(), 4), format!("{} 4000000000\n", host_name())).unwrap();
        assert!(Claim::take(dir.path(), 4).unwrap().is_some());
        // A claim of another host, refreshed recently: live.
        std::fs::write(claim_path(dir.path(), 5), "elsewhere 12\n").unwrap();
        assert!(Claim::take(dir.path(), 5).unwrap().is_none());
        // This process's id with another start time: a process that held the id before, gone.
        let me = std::process::id();
        std::fs::write(claim_path(dir.path(), 6), format!("{} {me} 1\n", host_name())).unwrap();
        assert!(Claim::take(dir.path(), 6).unwrap().is_some());
        // A live process's claim (this one's) not refreshed for longer than the expiry: stale, as
        // is another host's.
        // So is one of bytes that are no text.
        for (k, owner) in [
            (7, format!("{} {me}\n", host_name()).into_bytes()),
            (8, b"elsewhere 12\n".to_vec()),
            (9, b"\x00\x01garbage\xff".to_vec()),
        ] {
            let path = claim_path(dir.path(), k);
            std::fs::write(&path, owner).unwrap();
            let f = std::fs::OpenOptions::new().append(true).open(&path).unwrap();
            f.set_modified(SystemTime::now() - CLAIM_EXPIRY - std::time::Duration::from_secs(1))
                .unwrap();
            assert!(Claim::take(dir.path(), k).unwrap().is_some(), "claim {k}");
        }
    }

    #[test]
    fn a_changed_or_emptied_stored_study_is_named_and_the_job_files_not_blamed() {
        use crate::study::expand::{expand, tests::STUDY};
        let dir = tempfile::tempdir().unwrap();
        let study = expand(STUDY, Path::new(".")).unwrap();
        prepare_folder(dir.path(), &study, Path::new(".")).unwrap();
        assert!(stored_study(dir.path()).is_ok());
        let file = dir.path().join("study.toml");
        let stored = std::fs::read_to_string(&file).unwrap();
        // Edited: one shear strength changed.
        std::fs::write(&file, stored.replace("0.012", "0.011")).unwrap();
        let e = stored_study(dir.path()).unwrap_err().to_string();
        assert!(
            e.contains(&file.display().to_string())
                && e.contains("changed since its jobs were run")
                && e.contains("restore it")
                && e.contains("new folder")
                && !e.contains("delete"),
            "{e}"
        );
        // Emptied: named as the stored copy.
        std::fs::write(&file, "").unwrap();
        let e = stored_study(dir.path()).unwrap_err().to_string();
        assert!(
            e.contains(&file.display().to_string()) && e.contains("stored in its study folder") && e.contains("loads"),
            "{e}"
        );
        // Restored: read again.
        std::fs::write(&file, stored).unwrap();
        assert!(stored_study(dir.path()).is_ok());
    }
}
