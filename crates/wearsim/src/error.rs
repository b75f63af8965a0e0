//! Typed errors of the library, each naming what is at fault and the fix. Front ends add context
//! (which command) and map the kinds onto their own (exit codes, Python exceptions).

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// Everything that can go wrong in wearsim's library.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A parameter outside its physical or numerical range.
    #[error("invalid `{field}`: {message}")]
    InvalidParameter { field: String, message: String },

    /// A height field that cannot be used as a surface.
    #[error("invalid surface `{name}`: {message}")]
    InvalidSurface { name: String, message: String },

    /// A file or folder that could not be read or written.
    #[error("{}: {}", path.display(), explain(source))]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },

    /// A file whose content is not what it should be (a `.npy` header, a job file, a stored study).
    #[error("{}: {message}", path.display())]
    InvalidFile { path: PathBuf, message: String },

    /// A run or study file that does not describe a valid simulation (syntax, unknown or missing
    /// keys, wrong types); `path` is the file when it came from one.
    #[error("{}{message}", path.as_ref().map(|p| format!("{}: ", p.display())).unwrap_or_default())]
    RunFile { path: Option<PathBuf>, message: String },

    /// A study folder that cannot take this study's results (another study's, or another
    /// version's, job files).
    #[error("{}: {message}", dir.display())]
    StudyFolder { dir: PathBuf, message: String },

    /// One job of a study failed; `source` says why.
    #[error("study job {index} ({material}, load {load:e}): {source}")]
    Job {
        index: usize,
        material: String,
        load: f64,
        #[source]
        source: Box<Error>,
    },

    /// Some jobs of a study failed; the others were finished and their files written, so that a
    /// new run computes only the failed ones.
    #[error(
        "{} of {total} jobs failed (the other finished jobs are saved; run the study again to retry only the failed ones): {}",
        failed.len(),
        failed.iter().map(|e| e.to_string()).collect::<Vec<_>>().join("; ")
    )]
    JobsFailed { failed: Vec<Error>, total: usize },

    /// The mean pressure reaches the flow pressure: the surfaces would have to be in full plastic
    /// contact, where the saturated model has no solution.
    #[error(
        "load cannot be carried: mean pressure F_N/(Lx·Ly) = {mean_pressure:.6e} is at or above the flow \
         pressure p_m = {flow_pressure:.6e}; lower the load (`loads`) below p_m·Lx·Ly or raise `shear_strength`"
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

    /// The caller asked the computation to stop (Ctrl-C).
    #[error("interrupted")]
    Interrupted,
}

/// Result type of the library.
pub type Result<T> = std::result::Result<T, Error>;

/// The system's error in a user's words where the fix is plain: a folder given for a file, a
/// missing path, a file standing where a folder is needed.
fn explain(e: &std::io::Error) -> String {
    use std::io::ErrorKind;
    match e.kind() {
        ErrorKind::IsADirectory => "is a folder, where a file is needed; give the file's path".into(),
        ErrorKind::NotADirectory => "a part of this path is a file, where a folder is needed; check the path".into(),
        ErrorKind::NotFound => "does not exist; check the path".into(),
        ErrorKind::StorageFull => {
            "the disk is full (no space left on device); free space on it, or write to another disk".into()
        }
        ErrorKind::QuotaExceeded => {
            "the disk quota is full (disk quota exceeded); free space within the quota, or write to another disk".into()
        }
        ErrorKind::FileTooLarge => {
            "the file-size limit is reached (file too large: a `ulimit -f`, a quota or the file \
                                    system's largest file); free space, raise the limit, or write to another disk"
                .into()
        }
        _ => e.to_string(),
    }
}

impl Error {
    /// Shorthand for [`Error::InvalidParameter`].
    pub fn param(field: impl Into<String>, message: impl Into<String>) -> Self {
        Error::InvalidParameter {
            field: field.into(),
            message: message.into(),
        }
    }

    /// Shorthand for [`Error::Io`]; the message says what is wrong with the path in words (a
    /// folder where a file is needed, a path that does not exist) rather than the system's text.
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::Io {
            path: path.into(),
            source,
        }
    }

    /// Shorthand for [`Error::InvalidFile`].
    pub fn file(path: impl Into<PathBuf>, message: impl Into<String>) -> Self {
        Error::InvalidFile {
            path: path.into(),
            message: message.into(),
        }
    }

    /// Shorthand for [`Error::RunFile`] without a path (text handed over by the caller).
    pub fn run_file(message: impl Into<String>) -> Self {
        Error::RunFile {
            path: None,
            message: message.into(),
        }
    }

    /// The error that decides the kind: the cause of a failed job, the first of several failed
    /// jobs, otherwise the error itself. Front ends pick their exception type from it.
    pub fn root(&self) -> &Error {
        match self {
            Error::Job { source, .. } => source.root(),
            Error::JobsFailed { failed, .. } => failed.first().map_or(self, Error::root),
            other => other,
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn folders_for_files_and_missing_paths_are_said_in_words() {
        let dir = tempfile::tempdir().unwrap();
        let folder = std::fs::read_to_string(dir.path()).map_err(|e| Error::io(dir.path(), e));
        let e = folder.unwrap_err().to_string();
        assert!(
            e.contains("is a folder, where a file is needed") && !e.contains("os error"),
            "{e}"
        );
        let missing = dir.path().join("missing.toml");
        let e = Error::io(&missing, std::fs::read_to_string(&missing).unwrap_err()).to_string();
        assert!(
            e.contains("missing.toml: does not exist") && !e.contains("os error"),
            "{e}"
        );
        let e = Error::io("/dev/null/x", std::fs::read_to_string("/dev/null/x").unwrap_err()).to_string();
        assert!(e.contains("is a file, where a folder is needed"), "{e}");
    }

    #[test]
    fn a_full_disk_quota_or_file_size_limit_is_said_in_words_with_the_fix() {
        for (errno, words) in [
            (28, "the disk is full"),
            (122, "the disk quota is full"),
            (27, "the file-size limit is reached (file too large"),
        ] {
            let e = Error::io("out/a.png", std::io::Error::from_raw_os_error(errno)).to_string();
            assert!(e.starts_with("out/a.png: ") && e.contains(words), "{e}");
            assert!(e.contains("free space") && e.contains("write to another disk"), "{e}");
            assert!(!e.contains("os error"), "{e}");
        }
    }

    #[test]
    fn a_failed_job_keeps_the_kind_of_its_cause() {
        let cause = Error::NotConverged {
            iterations: 3,
            residual: 1.0,
            tolerance: 1e-8,
        };
        let job = Error::Job {
            index: 4,
            material: "steel".into(),
            load: 1e-3,
            source: Box::new(cause),
        };
        assert!(matches!(job.root(), Error::NotConverged { .. }));
        let text = job.to_string();
        assert!(
            text.starts_with("study job 4 (steel, load 1e-3)") && text.contains("did not converge"),
            "{text}"
        );
        let all = Error::JobsFailed {
            failed: vec![job],
            total: 9,
        };
        assert!(matches!(all.root(), Error::NotConverged { .. }));
        assert!(all.to_string().starts_with("1 of 9 jobs failed"));
        let io = Error::io("x", std::io::Error::other("disk full"));
        let source = std::error::Error::source(&io).map(|s| s.to_string());
        assert_eq!(source.as_deref(), Some("disk full"));
    }
}
