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

/// A temporary sibling of `path`, unique to this process and call: `.{name}.{host}.{pid}-{k}.tmp`.
/// The host and process in the name tell a later run whether its owner is gone
/// ([`remove_abandoned_siblings`]), and keep runs on different cluster nodes sharing a folder apart.
pub fn temporary_sibling(path: &Path) -> Result<std::path::PathBuf> {
    let name = path.file_name().ok_or_else(|| Error::file(path, "not a file path"))?;
    let k = TMP_COUNTER.fetch_add(1, Ordering::Relaxed);
    Ok(parent_or_dot(path).join(format!(
        ".{}.{}.{}-{k}.tmp",
        sibling_stem(&name.to_string_lossy()),
        host_name(),
        std::process::id()
    )))
}

/// Longest file name, in bytes, that a temporary sibling or claim embeds whole: with the host name
/// (≤ 64 bytes), the process and counter, the sibling stays within the 255 bytes file systems allow.
const STEM_BYTES: usize = 160;

/// The part of a file name that its siblings' names embed: the name itself, or for a long one (a
/// legal 250-byte name) its first bytes and a hash of the whole, so that the sibling's name stays
/// legal and two long names sharing a beginning keep distinct siblings.
fn sibling_stem(name: &str) -> String {
    if name.len() <= STEM_BYTES {
        return name.to_string();
    }
    let mut cut = STEM_BYTES - 17;
    while !name.is_char_boundary(cut) {
        cut -= 1;
    }
    let hash = name.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
        (h ^ b as u64).wrapping_mul(0x0100_0000_01b3)
    });
    format!("{}~{hash:016x}", &name[..cut])
}

/// This machine's name, as written in claims and temporary names.
pub fn host_name() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .map(|h| h.trim().to_string())
        .or_else(|_| std::env::var("HOSTNAME"))
        .ok()
        .filter(|h| !h.is_empty() && !h.contains(['/', ' ', '\n']))
        .unwrap_or_else(|| "unknown".into())
}

/// Whether process `pid` of this host is gone; `None` where that cannot be told (no `/proc`).
pub fn process_gone(pid: &str) -> Option<bool> {
    if !Path::new("/proc/self").exists() || pid.is_empty() || !pid.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    Some(!Path::new("/proc").join(pid).exists())
}

/// Removes the temporary siblings of `path` ([`temporary_sibling`]) left by processes of this host
/// that are gone (killed runs: a staging folder with a partial Zarr store, a half-written file).
/// Those of another host, or of a live process, are never touched.
pub fn remove_abandoned_siblings(path: &Path) {
    let Some(name) = path.file_name() else { return };
    let prefix = format!(".{}.", sibling_stem(&name.to_string_lossy()));
    let host = host_name();
    let Ok(entries) = std::fs::read_dir(parent_or_dot(path)) else {
        return;
    };
    for entry in entries.flatten() {
        let file = entry.file_name().to_string_lossy().to_string();
        let Some(owner) = file.strip_prefix(&prefix).and_then(|r| r.strip_suffix(".tmp")) else {
            continue;
        };
        let Some((owner_host, pid_k)) = owner.rsplit_once('.') else {
            continue;
        };
        let Some((pid, _)) = pid_k.split_once('-') else {
            continue;
        };
        if owner_host == host && process_gone(pid) == Some(true) {
            let p = entry.path();
            let _ = if p.is_dir() {
                std::fs::remove_dir_all(&p)
            } else {
                std::fs::remove_file(&p)
            };
        }
    }
}

/// Refuses an output folder `out` that is, or contains, one of `inputs` (a run file, surfaces, a
/// study file): outputs replace or add to their folder, which would delete or overwrite them.
/// Paths are compared in their canonical form ([`canonical_path`]), whatever their spelling (`.`,
/// `..`, a trailing slash, symbolic links).
pub fn refuse_inputs_inside(out: &Path, inputs: &[&Path]) -> Result<()> {
    let target = canonical_path(out);
    for input in inputs {
        let input = canonical_path(input);
        if input.starts_with(&target) {
            return Err(Error::file(
                out,
                format!(
                    "holds the input {}: wearsim writes its outputs there, which would delete or overwrite it; \
                     give an --out folder outside the inputs, e.g. --out results",
                    input.display()
                ),
            ));
        }
    }
    Ok(())
}

/// A claim on an output path: the file `.{name}.claim` beside it, created exclusively (two processes
/// cannot both create it) before any work and holding `host pid`; removed when dropped. A claim
/// whose process is gone (this host, no such process) is taken over.
#[derive(Debug)]
pub struct OutputClaim {
    path: std::path::PathBuf,
}

impl OutputClaim {
    /// Claims `target` (a canonical path with a file name) for this process.
    pub fn take(target: &Path) -> Result<Self> {
        let name = target
            .file_name()
            .ok_or_else(|| Error::file(target, "not a folder name"))?;
        let path = parent_or_dot(target).join(format!(".{}.claim", sibling_stem(&name.to_string_lossy())));
        for _ in 0..2 {
            match std::fs::OpenOptions::new().write(true).create_new(true).open(&path) {
                Ok(mut f) => {
                    let owner = format!("{} {}\n", host_name(), std::process::id());
                    f.write_all(owner.as_bytes()).map_err(|e| Error::io(&path, e))?;
                    return Ok(Self { path });
                }
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                    let owner = std::fs::read_to_string(&path).unwrap_or_default();
                    let mut words = owner.split_whitespace();
                    let (host, pid) = (words.next().unwrap_or(""), words.next().unwrap_or(""));
                    let age = std::fs::metadata(&path)
                        .and_then(|m| m.modified())
                        .ok()
                        .and_then(|t| std::time::SystemTime::now().duration_since(t).ok());
                    // An empty claim is one whose writer died between creating and filling it.
                    let dead = (host == host_name() && process_gone(pid) == Some(true))
                        || owner.is_empty() && age.is_some_and(|a| a.as_secs() > 5);
                    if !dead {
                        return Err(Error::file(
                            target,
                            format!(
                                "another wearsim run (process {pid} on {host}) is writing this folder; wait for it \
                                 to finish or give another --out (if that run is gone, remove {})",
                                path.display()
                            ),
                        ));
                    }
                    let _ = std::fs::remove_file(&path);
                }
                Err(e) => return Err(Error::io(&path, e)),
            }
        }
        Err(Error::file(
            target,
            "another wearsim run claimed this folder at the same moment; give another --out",
        ))
    }
}

impl Drop for OutputClaim {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

/// The folder holding `path` (`.` for a bare file name).
pub fn parent_or_dot(path: &Path) -> &Path {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    }
}

/// `path` in one canonical form, so that one file named several ways (`a.npy`, `./a.npy`,
/// `m/../a.npy`, through a symbolic link, relative or absolute) compares equal wherever it is
/// recorded: absolute, symbolic links resolved. Of a path that does not exist, the nearest existing
/// ancestor is resolved and the rest appended with `.` and `..` removed.
pub fn canonical_path(path: &Path) -> std::path::PathBuf {
    if let Ok(p) = std::fs::canonicalize(path) {
        return p;
    }
    let absolute = if path.is_absolute() {
        path.to_path_buf()
    } else {
        std::env::current_dir().map_or_else(|_| path.to_path_buf(), |d| d.join(path))
    };
    let mut lexical = std::path::PathBuf::new();
    for c in absolute.components() {
        match c {
            std::path::Component::CurDir => {}
            std::path::Component::ParentDir => {
                lexical.pop();
            }
            other => lexical.push(other),
        }
    }
    let mut existing = lexical.clone();
    let mut rest = Vec::new();
    while !existing.exists() {
        match existing.file_name() {
            Some(name) => {
                rest.push(name.to_os_string());
                existing.pop();
            }
            None => break,
        }
    }
    let mut out = std::fs::canonicalize(&existing).unwrap_or(existing);
    out.extend(rest.iter().rev());
    out
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
    /// Held until the outputs are in place (or abandoned): one run per folder.
    _claim: OutputClaim,
}

/// The marker file that says which command wrote a folder.
const MARKER: &str = ".wearsim.json";

impl OutputDir {
    /// Prepares to write the outputs of `command` into `target`. An existing `target` must be a
    /// folder that is empty or holds an earlier run of the same command (which the new outputs
    /// replace whole); another command's results, or files wearsim did not write, are refused unless
    /// `overwrite` is set. A `target` that is or holds one of `inputs` or the current folder is
    /// refused whatever `overwrite` says; so is one another live run is writing (a claim beside it,
    /// taken before anything else, decides). Staging folders of killed runs beside it are removed.
    pub fn begin(target: &Path, command: &str, overwrite: bool, inputs: &[&Path]) -> Result<Self> {
        let given = target;
        let target = &canonical_path(target);
        if target.file_name().is_none() {
            return Err(Error::file(
                given,
                "is the root folder; give a folder to write into, e.g. --out results",
            ));
        }
        refuse_inputs_inside(target, inputs)?;
        if std::env::current_dir().is_ok_and(|cwd| canonical_path(&cwd).starts_with(target)) {
            return Err(Error::file(
                given,
                "is the current folder (or holds it): the output folder is replaced whole; give a new folder, e.g. \
                 --out results",
            ));
        }
        let parent = parent_or_dot(target);
        std::fs::create_dir_all(parent).map_err(|e| Error::io(parent, e))?;
        let claim = OutputClaim::take(target)?;
        remove_abandoned_siblings(target);
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
        let staging = temporary_sibling(target)?;
        std::fs::create_dir(&staging).map_err(|e| Error::io(&staging, e))?;
        let dir = Self {
            target: target.to_path_buf(),
            staging,
            committed: false,
            _claim: claim,
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
    fn files_and_folders_with_the_longest_legal_names_are_written() {
        let dir = tempfile::tempdir().unwrap();
        // 250 bytes, two-byte characters included: legal, but too long to embed whole in a sibling.
        let name = format!("{}{}", "ü".repeat(60), "a".repeat(130));
        assert_eq!(name.len(), 250);
        let file = dir.path().join(&name);
        write_text(&file, "whole").unwrap();
        assert_eq!(std::fs::read_to_string(&file).unwrap(), "whole");
        let out = dir.path().join(format!("{}{}", "ü".repeat(60), "c".repeat(130)));
        let staged = OutputDir::begin(&out, "test", false, &[]).unwrap();
        write_text(&staged.join("summary.json"), "{}").unwrap();
        staged.commit().unwrap();
        assert!(out.join("summary.json").is_file());
        // Two long names that share their first 150 bytes keep distinct siblings.
        let other = format!("{}{}", "ü".repeat(60), "b".repeat(130));
        assert_ne!(sibling_stem(&name), sibling_stem(&other));
        assert!(sibling_stem(&name).len() <= STEM_BYTES);
        assert_eq!(sibling_stem("short.npy"), "short.npy");
        // Nothing but the two results is left beside them.
        let left: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .flatten()
            .map(|e| e.file_name())
            .collect();
        assert_eq!(left.len(), 2, "{left:?}");
    }

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
        let first = OutputDir::begin(&out, "slide", false, &[]).unwrap();
        write_text(&first.join("summary.json"), "{}").unwrap();
        write_text(&first.join("series.csv"), "a\n").unwrap();
        assert!(!out.exists(), "nothing appears before the commit");
        first.commit().unwrap();
        assert!(out.join("series.csv").is_file());
        // The same command replaces the folder whole: no file of the earlier run survives.
        let again = OutputDir::begin(&out, "slide", false, &[]).unwrap();
        write_text(&again.join("summary.json"), "{\"new\": 1}").unwrap();
        again.commit().unwrap();
        assert!(!out.join("series.csv").exists());
        // Another command is refused without --overwrite, and the folder is left alone.
        let e = OutputDir::begin(&out, "contact", false, &[]).unwrap_err().to_string();
        assert!(e.contains("wearsim slide") && e.contains("--overwrite"), "{e}");
        // A run that fails before its commit leaves no trace.
        let failed = OutputDir::begin(&out, "slide", false, &[]).unwrap();
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
        assert!(OutputDir::begin(&file, "slide", true, &[])
            .unwrap_err()
            .to_string()
            .contains("not a folder"));
        std::fs::write(dir.path().join("mine.txt"), "x").unwrap();
        assert!(OutputDir::begin(dir.path(), "slide", false, &[])
            .unwrap_err()
            .to_string()
            .contains("did not write"));
    }
}
