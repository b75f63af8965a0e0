//! The study folder: the stored study (its canonical text, hash and base folder); one job file per
//! finished job, written atomically and checked against its job when read back; and one claim file
//! per job under way, so that runs sharing a folder (Slurm shards, a second run started by
//! mistake) never compute a job twice nor touch each other's files.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime};

use crate::error::{Error, Result};
use crate::io::{host_name, read_text, temporary_sibling, write_text};
use crate::output::{read_job_file, JobResult};
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
    write_text(&path, &text)
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
        return Err(Error::file(
            &path,
            format!(
                "holds the result of job {} ({}, load {:e}) with other inputs than {}: the file was copied or renamed \
                 from another job or study; delete it and run the study again to recompute job {}",
                r.index,
                r.material,
                r.load,
                job.describe(),
                job.index
            ),
        ));
    }
    Ok(Stored::Done(Box::new(r)))
}

/// Reads `job`'s result file, checking that it was written for this job.
pub fn read_result(job: &Job, dir: &Path) -> Result<JobResult> {
    match stored_result(job, dir)? {
        Stored::Done(r) => Ok(*r),
        Stored::Missing => Err(Error::file(
            job_path(dir, job.index),
            "no result yet; run the study to compute it",
        )),
        Stored::Unreadable(message) => Err(Error::file(
            job_path(dir, job.index),
            format!("{message} (`wearsim study run` recomputes it)"),
        )),
    }
}

/// A claim on a job: the file `job-NNNNNN.claim`, created exclusively before the job is computed
/// and removed when it is done (or abandoned). While it is held, the runner refreshes its
/// modification time every [`CLAIM_REFRESH`], so that other runs can tell a live claim from one left
/// by a killed process.
#[derive(Debug)]
pub struct Claim {
    path: PathBuf,
}

/// A claim not refreshed for this long belongs to a process that is gone.
pub const CLAIM_EXPIRY: Duration = Duration::from_secs(600);

/// How often a live claim is refreshed.
pub const CLAIM_REFRESH: Duration = Duration::from_secs(60);

impl Claim {
    /// Claims job `index`; `Ok(None)` when another live run holds it. A claim left by a process that
    /// is gone (on this host: no such process; elsewhere: not refreshed for [`CLAIM_EXPIRY`]) is
    /// taken over.
    pub fn take(dir: &Path, index: usize) -> Result<Option<Claim>> {
        let path = claim_path(dir, index);
        for _ in 0..2 {
            match std::fs::OpenOptions::new().write(true).create_new(true).open(&path) {
                Ok(mut f) => {
                    let owner = format!("{} {}\n", host_name(), std::process::id());
                    f.write_all(owner.as_bytes()).map_err(|e| Error::io(&path, e))?;
                    return Ok(Some(Claim { path }));
                }
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                    if !Self::is_stale(&path) {
                        return Ok(None);
                    }
                    let _ = std::fs::remove_file(&path);
                }
                Err(e) => return Err(Error::io(&path, e)),
            }
        }
        Ok(None)
    }

    fn is_stale(path: &Path) -> bool {
        let owner = std::fs::read_to_string(path).unwrap_or_default();
        let mut words = owner.split_whitespace();
        if let (Some(host), Some(pid)) = (words.next(), words.next()) {
            if host == host_name() && Path::new("/proc/self").exists() {
                return !Path::new("/proc").join(pid).exists();
            }
        }
        let age = std::fs::metadata(path)
            .and_then(|m| m.modified())
            .ok()
            .and_then(|t| SystemTime::now().duration_since(t).ok());
        // An empty claim is one whose writer died between creating and filling it.
        owner.is_empty() && age.is_some_and(|a| a > Duration::from_secs(5)) || age.is_some_and(|a| a > CLAIM_EXPIRY)
    }

    /// The claim file.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

impl Drop for Claim {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

/// Prepares a study folder: stores the study, its hash and the folder its relative paths resolve
/// against on first use, refuses a folder made by a different study, and removes temporary files
/// that killed runs left behind (only those older than [`CLAIM_EXPIRY`]: a younger one may be
/// another run's file being written).
pub fn prepare_folder(dir: &Path, study: &Study, base: &Path) -> Result<()> {
    let mut inputs: Vec<&Path> = Vec::new();
    for job in &study.jobs {
        if let crate::config::SurfaceSource::Files { top, bottom, .. } = &job.run.surfaces {
            inputs.extend([top.as_path(), bottom.as_path()]);
        }
    }
    crate::io::refuse_inputs_inside(dir, &inputs)?;
    std::fs::create_dir_all(dir.join("jobs")).map_err(|e| Error::io(dir, e))?;
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
        if name.starts_with('.') && name.ends_with(".tmp") && old {
            let _ = std::fs::remove_file(entry.path());
        }
    }
    Ok(())
}

/// The stored study of a folder and the folder its relative paths resolve against.
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
    Ok((text, base))
}

#[cfg(test)]
mod tests {
    use super::*;

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
    }
}
