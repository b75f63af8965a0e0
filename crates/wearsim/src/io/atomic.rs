//! Atomic writes: a temporary sibling renamed into place, so a killed run never leaves a
//! half-written file; text and JSON files; output folders that appear whole.

use std::io::{BufWriter, Write};
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

use crate::error::{Error, Result};

/// Version of the library, recorded in every output file.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// Counter that makes temporary names unique within a process (with the process id, across
/// processes sharing a folder).
static TMP_COUNTER: AtomicU64 = AtomicU64::new(0);

/// A temporary sibling of `path`, unique to this process and call: `.{name}.{pid}-{k}.tmp`.
pub fn temporary_sibling(path: &Path) -> Result<std::path::PathBuf> {
    let name = path.file_name().ok_or_else(|| Error::file(path, "not a file path"))?;
    let k = TMP_COUNTER.fetch_add(1, Ordering::Relaxed);
    Ok(parent_or_dot(path).join(format!(".{}.{}-{k}.tmp", name.to_string_lossy(), std::process::id())))
}

/// The folder holding `path` (`.` for a bare file name).
pub fn parent_or_dot(path: &Path) -> &Path {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    }
}

/// Writes `path` atomically: `write` fills a temporary sibling (named uniquely for this process),
/// which is then flushed, synced and renamed over `path`. On error the temporary file is removed
/// and `path` is untouched.
pub fn atomic_write(path: &Path, write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>) -> Result<()> {
    let tmp = temporary_sibling(path)?;
    let result = (|| -> std::io::Result<()> {
        let file = std::fs::File::create(&tmp)?;
        let mut w = BufWriter::new(file);
        write(&mut w)?;
        let file = w.into_inner().map_err(|e| e.into_error())?;
        file.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(Error::io(path, e));
    }
    Ok(())
}

/// Writes a text file atomically.
pub fn write_text(path: &Path, text: &str) -> Result<()> {
    atomic_write(path, |w| w.write_all(text.as_bytes()))
}

/// Writes a value as pretty-printed JSON, atomically.
pub fn write_json(path: &Path, value: &impl serde::Serialize) -> Result<()> {
    let text = serde_json::to_string_pretty(value).map_err(|e| Error::file(path, format!("cannot encode: {e}")))?;
    write_text(path, &(text + "\n"))
}

/// Reads a whole text file.
pub fn read_text(path: &Path) -> Result<String> {
    std::fs::read_to_string(path).map_err(|e| Error::io(path, e))
}

/// A command's output folder, written as a whole: files go into a temporary sibling folder, which
/// replaces the output folder in one step on [`OutputDir::commit`], so a command's outputs appear
/// together or not at all and never mix with an earlier run's. Made before any work, so that a
/// folder that cannot be written is found before the computation; dropped without a commit, it
/// removes its temporary folder.
#[derive(Debug)]
pub struct OutputDir {
    target: std::path::PathBuf,
    staging: std::path::PathBuf,
    committed: bool,
}

/// The marker file that says which command wrote a folder.
const MARKER: &str = ".wearsim.json";

impl OutputDir {
    /// Prepares to write the outputs of `command` into `target`. An existing `target` must be a
    /// folder that is empty or holds an earlier run of the same command (which the new outputs
    /// replace whole); another command's results, or files wearsim did not write, are refused unless
    /// `overwrite` is set.
    pub fn begin(target: &Path, command: &str, overwrite: bool) -> Result<Self> {
        if target.exists() && !target.is_dir() {
            return Err(Error::file(target, "exists and is not a folder; give another --out"));
        }
        if target.is_dir() && !overwrite {
            let mut entries = std::fs::read_dir(target).map_err(|e| Error::io(target, e))?;
            if entries.next().is_some() {
                let marker = std::fs::read_to_string(target.join(MARKER)).ok();
                let writer = marker
                    .as_deref()
                    .and_then(|t| serde_json::from_str::<serde_json::Value>(t).ok())
                    .and_then(|v| v.get("command").and_then(|c| c.as_str()).map(String::from));
                match writer {
                    Some(c) if c == command => {}
                    Some(c) => {
                        return Err(Error::file(
                            target,
                            format!(
                                "holds the results of `wearsim {c}`; give another --out, or --overwrite to replace \
                                 them with those of `wearsim {command}`"
                            ),
                        ))
                    }
                    None => return Err(Error::file(
                        target,
                        "holds files that wearsim did not write; give another --out, or --overwrite to replace the \
                             folder",
                    )),
                }
            }
        }
        let parent = parent_or_dot(target);
        std::fs::create_dir_all(parent).map_err(|e| Error::io(parent, e))?;
        let staging = temporary_sibling(target)?;
        std::fs::create_dir(&staging).map_err(|e| Error::io(&staging, e))?;
        let dir = Self {
            target: target.to_path_buf(),
            staging,
            committed: false,
        };
        let provenance = serde_json::json!({"command": command, "software": format!("wearsim {VERSION}")});
        write_json(&dir.join(MARKER), &provenance)?;
        Ok(dir)
    }

    /// Where a file of the outputs is written (inside the temporary folder until the commit).
    pub fn join(&self, name: &str) -> std::path::PathBuf {
        self.staging.join(name)
    }

    /// The folder the outputs will have once committed.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Puts the outputs in place: the temporary folder replaces `target` (an earlier folder there is
    /// moved aside first and removed after).
    pub fn commit(mut self) -> Result<()> {
        let aside = if self.target.exists() {
            let aside = temporary_sibling(&self.target)?;
            std::fs::rename(&self.target, &aside).map_err(|e| Error::io(&self.target, e))?;
            Some(aside)
        } else {
            None
        };
        if let Err(e) = std::fs::rename(&self.staging, &self.target) {
            if let Some(aside) = &aside {
                let _ = std::fs::rename(aside, &self.target);
            }
            return Err(Error::io(&self.target, e));
        }
        self.committed = true;
        if let Some(aside) = aside {
            let _ = std::fs::remove_dir_all(aside);
        }
        Ok(())
    }
}

impl Drop for OutputDir {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.staging);
        }
    }
}

/// Writes several files so that they appear together: each into a temporary sibling, then all
/// renamed into place (a failed write leaves none of them changed).
pub fn write_texts_together(files: &[(&Path, &str)]) -> Result<()> {
    let mut written: Vec<(std::path::PathBuf, &Path)> = Vec::new();
    let result = (|| -> Result<()> {
        for (path, text) in files {
            let tmp = temporary_sibling(path)?;
            written.push((tmp.clone(), path));
            write_text(&tmp, text)?;
        }
        for (tmp, path) in &written {
            std::fs::rename(tmp, path).map_err(|e| Error::io(path, e))?;
        }
        Ok(())
    })();
    if result.is_err() {
        for (tmp, _) in &written {
            let _ = std::fs::remove_file(tmp);
        }
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failed_write_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.txt");
        let err = atomic_write(&path, |w| {
            w.write_all(b"half")?;
            Err(std::io::Error::other("boom"))
        });
        assert!(err.is_err());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
        write_text(&path, "whole").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "whole");
    }

    #[test]
    fn an_output_folder_appears_whole_and_refuses_another_commands_results() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        let first = OutputDir::begin(&out, "slide", false).unwrap();
        write_text(&first.join("summary.json"), "{}").unwrap();
        write_text(&first.join("series.csv"), "a\n").unwrap();
        assert!(!out.exists(), "nothing appears before the commit");
        first.commit().unwrap();
        assert!(out.join("series.csv").is_file());
        // The same command replaces the folder whole: no file of the earlier run survives.
        let again = OutputDir::begin(&out, "slide", false).unwrap();
        write_text(&again.join("summary.json"), "{\"new\": 1}").unwrap();
        again.commit().unwrap();
        assert!(!out.join("series.csv").exists());
        // Another command is refused without --overwrite, and the folder is left alone.
        let e = OutputDir::begin(&out, "contact", false).unwrap_err().to_string();
        assert!(e.contains("wearsim slide") && e.contains("--overwrite"), "{e}");
        // A run that fails before its commit leaves no trace.
        let failed = OutputDir::begin(&out, "slide", false).unwrap();
        write_text(&failed.join("series.csv"), "half").unwrap();
        drop(failed);
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
        assert_eq!(
            std::fs::read_to_string(out.join("summary.json")).unwrap(),
            "{\"new\": 1}"
        );
        // A file in the way is refused before any work.
        let file = dir.path().join("file");
        std::fs::write(&file, "x").unwrap();
        assert!(OutputDir::begin(&file, "slide", true)
            .unwrap_err()
            .to_string()
            .contains("not a folder"));
        std::fs::write(dir.path().join("mine.txt"), "x").unwrap();
        assert!(OutputDir::begin(dir.path(), "slide", false)
            .unwrap_err()
            .to_string()
            .contains("did not write"));
    }
}
