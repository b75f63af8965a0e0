//! The study folder: the stored study (its canonical text, hash and base folder), and one job file
//! per finished job, written atomically and checked against its job when read back.

use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::io::{read_text, write_text};
use crate::output::{read_job_file, JobResult};
use crate::study::expand::{Job, Study};

/// Path of job `index`'s result file in a study folder.
pub fn job_path(dir: &Path, index: usize) -> PathBuf {
    dir.join("jobs").join(format!("job-{index:06}.json"))
}

/// Writes a job's result file atomically (the file whose presence marks the job done).
pub fn write_result(dir: &Path, result: &JobResult) -> Result<()> {
    write_text(&job_path(dir, result.index), &result.to_json())
}

/// Reads `job`'s result file, checking that it was written for this job.
pub fn read_result(job: &Job, dir: &Path) -> Result<JobResult> {
    let path = job_path(dir, job.index);
    let r = read_job_file(&path)?;
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
    Ok(r)
}

/// Prepares a study folder: stores the study, its hash and the folder its relative paths resolve
/// against on first use, refuses a folder made by a different study, and removes temporary files a
/// killed run left behind.
pub fn prepare_folder(dir: &Path, study: &Study, base: &Path) -> Result<()> {
    std::fs::create_dir_all(dir.join("jobs")).map_err(|e| Error::io(dir, e))?;
    let hash_path = dir.join("study.hash");
    match std::fs::read_to_string(&hash_path) {
        Ok(existing) if existing.trim() != study.hash => {
            return Err(Error::StudyFolder {
                dir: dir.into(),
                message: format!(
                    "holds results of a different study (hash {} ≠ {}); use a new --out folder or restore the original \
                     study file",
                    existing.trim(),
                    study.hash
                ),
            })
        }
        Ok(_) => {}
        Err(_) => {
            write_text(&dir.join("study.toml"), &study.canonical)?;
            let base = base.canonicalize().map_err(|e| Error::io(base, e))?;
            write_text(&dir.join("study.base"), &base.to_string_lossy())?;
            write_text(&hash_path, &study.hash)?;
        }
    }
    let jobs = dir.join("jobs");
    for entry in std::fs::read_dir(&jobs).map_err(|e| Error::io(&jobs, e))?.flatten() {
        let name = entry.file_name().to_string_lossy().to_string();
        if name.starts_with('.') && name.contains(".tmp") {
            let _ = std::fs::remove_file(entry.path());
        }
    }
    Ok(())
}

/// The stored study of a folder and the folder its relative paths resolve against.
pub fn stored_study(dir: &Path) -> Result<(String, PathBuf)> {
    let text = read_text(&dir.join("study.toml"))?;
    let base = std::fs::read_to_string(dir.join("study.base"))
        .map(PathBuf::from)
        .unwrap_or_else(|_| dir.to_path_buf());
    Ok((text, base))
}
