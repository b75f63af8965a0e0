//! Atomic writes: a temporary sibling renamed into place, so a killed run never leaves a
//! half-written file; text and JSON files; output folders that appear whole.

use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, MutexGuard};
use std::time::{Duration, SystemTime};

use crate::error::{Error, Result};

/// Version of the library, recorded in every output file.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// Counter that makes temporary names unique within a process (with the process id, across
/// processes sharing a folder).
static TMP_COUNTER: AtomicU64 = AtomicU64::new(0);

/// The temporary files and folders this process is writing and the claims it holds: what a command
/// stopped by a signal removes before it exits ([`abandon_outputs`]). Its lock is also held while
/// outputs are put in place, so that a stop never falls between moving an earlier folder aside and
/// renaming the new one into place.
static LIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn live() -> MutexGuard<'static, Vec<PathBuf>> {
    LIVE.lock().unwrap_or_else(|e| e.into_inner())
}

fn register(path: &Path) {
    live().push(path.to_path_buf());
}

/// Creates a temporary file or folder with `create` and registers it in the same step, under the
/// lock: a stop removing this process's temporaries ([`abandon_outputs`]) finds every one that
/// exists, and none is created after it (one created while it lists a folder's entries would
/// keep that folder from being removed).
fn create_registered<T>(path: &Path, create: impl FnOnce(&Path) -> std::io::Result<T>) -> std::io::Result<T> {
    let mut list = live();
    let made = create(path)?;
    list.push(path.to_path_buf());
    Ok(made)
}

fn release(list: &mut Vec<PathBuf>, path: &Path) {
    if let Some(k) = list.iter().rposition(|p| p == path) {
        list.swap_remove(k);
    }
}

/// Removes every temporary file and folder this process is writing and every claim it holds, and
/// returns a guard that keeps any output from being put in place while it is held: a command that a
/// signal stops at once (one that does not poll its interrupt flag) calls it, then exits holding
/// the guard. Earlier outputs stay whole: a folder being replaced is either still in place or
/// already replaced, never moved aside.
pub fn abandon_outputs() -> MutexGuard<'static, Vec<PathBuf>> {
    let mut list = live();
    for p in list.drain(..) {
        let _ = if p.is_dir() {
            std::fs::remove_dir_all(&p)
        } else {
            std::fs::remove_file(&p)
        };
    }
    list
}

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

/// The key a JSON file's checksum is written under, last in the file.
const CHECKSUM_KEY: &str = ",\"checksum\":\"fnv1a64:";

/// FNV-1a, 64 bits.
fn fnv1a64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// A JSON object's text with the checksum of its text appended as its last key, `checksum`, so
/// that a file damaged or edited since it was written (one digit of a number) is found when it is
/// read ([`checksum_matches`]).
pub fn with_checksum(json: &str) -> String {
    let body = json.trim_end();
    let open = body.strip_suffix('}').unwrap_or(body);
    format!("{open}{CHECKSUM_KEY}{:016x}\"}}", fnv1a64(body.as_bytes()))
}

/// Whether the checksum of a text written by [`with_checksum`] matches its contents; `None` for a
/// text without one.
pub fn checksum_matches(text: &str) -> Option<bool> {
    let text = text.trim_end();
    let k = text.rfind(CHECKSUM_KEY)?;
    let given = &text[k + CHECKSUM_KEY.len()..];
    let Some(given) = given.strip_suffix("\"}") else {
        return Some(false);
    };
    Some(given == format!("{:016x}", fnv1a64(format!("{}}}", &text[..k]).as_bytes())))
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

/// Refuses a single output file `out` (an animation, a NetCDF file) that is, or lies inside, one of
/// `inputs`, whatever `overwrite` says, and an existing file there that `ours` does not recognise as
/// one `command` wrote, unless `overwrite` is set: another command's output (a `summary.json`), an
/// input of another run, a file of the user's. Paths are compared in canonical form.
pub fn refuse_foreign_file(
    out: &Path,
    command: &str,
    overwrite: bool,
    inputs: &[&Path],
    ours: impl Fn(&Path) -> bool,
) -> Result<()> {
    let target = canonical_path(out);
    for input in inputs {
        let input = canonical_path(input);
        if target.starts_with(&input) {
            return Err(Error::file(
                out,
                format!(
                    "is {} the input {}: writing there would destroy it, --overwrite or not; give another path",
                    if target == input { "" } else { "inside" },
                    input.display()
                )
                .replace("is  the", "is the"),
            ));
        }
    }
    if target.is_dir() {
        return Err(Error::file(
            out,
            "is a folder, where the file to write is needed; give a file path",
        ));
    }
    if target.exists() && !overwrite && !ours(&target) {
        return Err(Error::file(
            out,
            format!(
                "exists and was not written by `wearsim {command}`; give another path, or --overwrite to replace it"
            ),
        ));
    }
    Ok(())
}

/// A claim on an output path: the file `.{name}.claim` beside it, created exclusively (two processes
/// cannot both create it) before any work and holding `host pid start`; refreshed every
/// [`CLAIM_REFRESH`] while held and removed when dropped. A stale claim ([`claim_is_stale`]) is
/// taken over.
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
            // Made and registered under the lock, so that a stop in between never leaves it behind.
            let mut list = live();
            if create_claim_file(&path)? {
                list.push(path.clone());
                drop(list);
                keep_output_claims_fresh();
                return Ok(Self { path });
            }
            drop(list);
            if !claim_is_stale(&path) {
                let owner = std::fs::read_to_string(&path).unwrap_or_default();
                let mut words = owner.split_whitespace();
                let (host, pid) = (words.next().unwrap_or(""), words.next().unwrap_or(""));
                let who = if owner.is_empty() {
                    "another wearsim run is starting to write this folder".to_string()
                } else {
                    format!("another wearsim run (process {pid} on {host}) is writing this folder")
                };
                return Err(Error::file(
                    target,
                    format!(
                        "{who}; wait for it to finish or give another --out (a claim not refreshed for {} min is \
                         taken over; if that run is gone, remove {})",
                        CLAIM_EXPIRY.as_secs() / 60,
                        path.display()
                    ),
                ));
            }
            let _ = std::fs::remove_file(&path);
        }
        Err(Error::file(
            target,
            "another wearsim run claimed this folder at the same moment; give another --out",
        ))
    }
}

/// A claim (a study's job, an output folder) not refreshed for this long is stale, whoever holds it
/// and whatever host it names: its holder refreshes it every [`CLAIM_REFRESH`] from a thread of its
/// own, whatever its work is doing.
pub const CLAIM_EXPIRY: Duration = Duration::from_secs(600);

/// How often a held claim's modification time is refreshed.
pub const CLAIM_REFRESH: Duration = Duration::from_secs(60);

/// Start time of process `pid` of this host, in clock ticks since boot (field 22 of
/// `/proc/PID/stat`); `None` where that cannot be told.
pub fn process_start(pid: &str) -> Option<u64> {
    if pid.is_empty() || !pid.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    let stat = std::fs::read_to_string(Path::new("/proc").join(pid).join("stat")).ok()?;
    // The command name (field 2) is in parentheses and may hold spaces: count after its end.
    let after = &stat[stat.rfind(')')? + 1..];
    after.split_whitespace().nth(19)?.parse().ok()
}

/// What a claim file of this process holds: `host pid start` (the start time of [`process_start`],
/// so that a later process given the same id is not taken for the claim's holder).
fn claim_owner() -> String {
    let pid = std::process::id().to_string();
    match process_start(&pid) {
        Some(start) => format!("{} {pid} {start}\n", host_name()),
        None => format!("{} {pid}\n", host_name()),
    }
}

/// Whether the claim file `path` is stale, to be taken over: one rule for every claim, whatever its
/// process id. Stale when not refreshed for [`CLAIM_EXPIRY`] (on any host); on this host also when
/// its process is gone, or when the process now holding its id is another one (started at another
/// time than the claim records); an empty claim (its writer died between creating and filling it)
/// after five seconds. A claim that cannot be read is stale only by its age; one whose bytes are no
/// text is read as what of it is.
pub fn claim_is_stale(path: &Path) -> bool {
    let age = std::fs::metadata(path)
        .and_then(|m| m.modified())
        .ok()
        .and_then(|t| SystemTime::now().duration_since(t).ok());
    // Not refreshed for long: stale whatever it holds, bytes that are no text included.
    if age.is_some_and(|a| a > CLAIM_EXPIRY) {
        return true;
    }
    let Ok(bytes) = std::fs::read(path) else {
        return false;
    };
    let owner = String::from_utf8_lossy(&bytes);
    let mut words = owner.split_whitespace();
    match (words.next(), words.next()) {
        (Some(host), Some(pid)) if host == host_name() => {
            if process_gone(pid) == Some(true) {
                return true;
            }
            let recorded = words.next().and_then(|s| s.parse::<u64>().ok());
            matches!((recorded, process_start(pid)), (Some(r), Some(now)) if r != now)
        }
        (Some(_), Some(_)) => false,
        _ => owner.trim().is_empty() && age.is_some_and(|a| a > Duration::from_secs(5)),
    }
}

/// Sets a claim file's modification time to now (its holder is alive).
pub fn refresh_claim(path: &Path) {
    if let Ok(f) = std::fs::OpenOptions::new().append(true).open(path) {
        let _ = f.set_modified(SystemTime::now());
    }
}

/// Removes the claim file `path` if it is still this process's: a claim taken over after it went
/// stale (a process stopped for longer than [`CLAIM_EXPIRY`]) belongs to its new holder.
pub fn remove_own_claim(path: &Path) {
    if std::fs::read_to_string(path).is_ok_and(|owner| owner == claim_owner()) {
        let _ = std::fs::remove_file(path);
    }
}

/// Starts, once per process, the thread that refreshes the output claims this process holds every
/// [`CLAIM_REFRESH`] (a long run holds its output folder's claim for hours).
fn keep_output_claims_fresh() {
    static STARTED: std::sync::Once = std::sync::Once::new();
    STARTED.call_once(|| {
        let _ = std::thread::Builder::new()
            .name("wearsim-claims".into())
            .spawn(|| loop {
                std::thread::sleep(CLAIM_REFRESH);
                let list = live();
                for p in list.iter().filter(|p| p.to_string_lossy().ends_with(".claim")) {
                    refresh_claim(p);
                }
            });
    });
}

/// Creates the claim file `path` exclusively, holding this process's `host pid start`: `Ok(false)`
/// when it exists already. A claim that cannot be filled (a full disk) is removed again, so that it
/// never blocks a retry as the empty claim of a run that seems to be starting.
pub fn create_claim_file(path: &Path) -> Result<bool> {
    match std::fs::OpenOptions::new().write(true).create_new(true).open(path) {
        Ok(mut f) => {
            let owner = claim_owner();
            if let Err(e) = f.write_all(owner.as_bytes()).and_then(|()| f.sync_all()) {
                drop(f);
                let _ = std::fs::remove_file(path);
                return Err(Error::io(path, e));
            }
            Ok(true)
        }
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => Ok(false),
        Err(e) => Err(Error::io(path, e)),
    }
}

impl Drop for OutputClaim {
    fn drop(&mut self) {
        let mut list = live();
        remove_own_claim(&self.path);
        release(&mut list, &self.path);
    }
}

/// Makes `dir` and its missing parents, saying which part of the path is a file in the way (the
/// system says only "File exists").
pub fn make_folder(dir: &Path) -> Result<()> {
    if dir.is_dir() {
        return Ok(());
    }
    if let Some(file) = dir.ancestors().find(|a| a.exists() && !a.is_dir()) {
        let what = if file == dir {
            "exists and is not a folder".to_string()
        } else {
            format!("is a file, not a folder, so {} cannot be made inside it", dir.display())
        };
        return Err(Error::file(file, format!("{what}; give another path")));
    }
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))
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
        let file = create_registered(&tmp, |p| std::fs::File::create(p))?;
        let mut w = BufWriter::new(file);
        write(&mut w)?;
        let file = w.into_inner().map_err(|e| e.into_error())?;
        file.sync_all()?;
        // Put in place only while no stop is removing this process's temporaries.
        let mut list = live();
        if !list.contains(&tmp) {
            return Err(std::io::Error::other("stopped"));
        }
        let renamed = std::fs::rename(&tmp, path);
        release(&mut list, &tmp);
        renamed
    })();
    if let Err(e) = result {
        let mut list = live();
        let _ = std::fs::remove_file(&tmp);
        release(&mut list, &tmp);
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
    command: String,
    committed: bool,
    /// Held until the outputs are in place (or abandoned): one run per folder.
    _claim: OutputClaim,
}

/// The marker file that says which command wrote a folder, and which files it wrote there.
pub const MARKER: &str = ".wearsim.json";

/// The marker of a folder written by `command` holding `files` (none listed: a folder that grows,
/// as a study folder does).
pub fn marker(command: &str, files: Option<&[String]>) -> serde_json::Value {
    let mut m = serde_json::json!({"command": command, "software": format!("wearsim {VERSION}")});
    if let Some(files) = files {
        m["files"] = serde_json::json!(files);
    }
    m
}

/// Whose a folder is, from its entries and its marker ([`MARKER`]).
#[derive(Debug, Clone, PartialEq)]
pub enum FolderOwner {
    /// Missing or empty.
    Nobody,
    /// Written by `wearsim {command}`; `foreign` lists the entries it did not write (known only
    /// where the marker lists the files).
    Wearsim { command: String, foreign: Vec<String> },
    /// Entries but no marker: not wearsim's.
    Foreign,
}

/// Whose the folder `dir` is. A study folder of an earlier version (a `study.hash`, no marker) is
/// `study run`'s.
pub fn folder_owner(dir: &Path) -> Result<FolderOwner> {
    if !dir.is_dir() {
        return Ok(FolderOwner::Nobody);
    }
    let entries: Vec<String> = std::fs::read_dir(dir)
        .map_err(|e| Error::io(dir, e))?
        .flatten()
        .map(|e| e.file_name().to_string_lossy().to_string())
        .collect();
    if entries.is_empty() {
        return Ok(FolderOwner::Nobody);
    }
    let marker = std::fs::read_to_string(dir.join(MARKER))
        .ok()
        .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok());
    let command = marker
        .as_ref()
        .and_then(|v| v.get("command").and_then(|c| c.as_str()).map(String::from));
    let Some(command) = command.or_else(|| dir.join("study.hash").is_file().then(|| "study run".to_string())) else {
        return Ok(FolderOwner::Foreign);
    };
    let listed: Option<Vec<String>> = marker
        .as_ref()
        .and_then(|v| v.get("files"))
        .and_then(|f| serde_json::from_value(f.clone()).ok());
    // The figures that `wearsim plot` drew of a run into its folder are the run's own: a run into
    // the folder again replaces them with the rest (figures of an earlier run are never kept).
    let drawn = |e: &str| {
        matches!(folder_owner(&dir.join(e)), Ok(FolderOwner::Wearsim { command, foreign })
            if command == "plot" && foreign.is_empty())
    };
    let foreign = match listed {
        Some(files) => entries
            .into_iter()
            .filter(|e| e != MARKER && !files.contains(e) && !drawn(e))
            .collect(),
        None => Vec::new(),
    };
    Ok(FolderOwner::Wearsim { command, foreign })
}

/// Refuses to replace or add to the folder `target` for `command` unless it is wearsim's folder of
/// that command holding only what it wrote: another command's results, files wearsim did not write
/// (the user's own, added beside its outputs or in a folder of their own) are never replaced without
/// `--overwrite`.
pub fn refuse_foreign_folder(target: &Path, command: &str) -> Result<()> {
    let more = |names: &[String]| {
        let shown: Vec<&str> = names.iter().take(3).map(String::as_str).collect();
        format!(
            "{}{}",
            shown.join(", "),
            if names.len() > 3 {
                format!(" and {} more", names.len() - 3)
            } else {
                String::new()
            }
        )
    };
    match folder_owner(target)? {
        FolderOwner::Nobody => Ok(()),
        FolderOwner::Wearsim { command: c, foreign } if c == command => {
            if foreign.is_empty() {
                Ok(())
            } else {
                Err(Error::file(
                    target,
                    format!(
                        "holds files that `wearsim {c}` did not write ({}) beside its results; move them out, give \
                         another --out, or --overwrite to replace the folder with them",
                        more(&foreign)
                    ),
                ))
            }
        }
        FolderOwner::Wearsim { command: c, .. } => Err(Error::file(
            target,
            format!(
                "holds the results of `wearsim {c}`; give another --out, or --overwrite to replace them with those of \
                 `wearsim {command}`"
            ),
        )),
        FolderOwner::Foreign => Err(Error::file(
            target,
            "holds files that wearsim did not write; give another --out, or --overwrite to replace the folder",
        )),
    }
}

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
        if let Some(file) = target.ancestors().skip(1).find(|a| a.exists() && !a.is_dir()) {
            return Err(Error::file(
                file,
                format!(
                    "is a file, not a folder, so the output folder {} cannot be made inside it; give another --out",
                    given.display()
                ),
            ));
        }
        make_folder(parent_or_dot(target))?;
        let claim = OutputClaim::take(target)?;
        remove_abandoned_siblings(target);
        if target.exists() && !target.is_dir() {
            return Err(Error::file(target, "exists and is not a folder; give another --out"));
        }
        if !overwrite {
            refuse_foreign_folder(target, command)?;
        }
        let staging = temporary_sibling(target)?;
        create_registered(&staging, |p| std::fs::create_dir(p)).map_err(|e| Error::io(&staging, e))?;
        let dir = Self {
            target: target.to_path_buf(),
            staging,
            command: command.to_string(),
            committed: false,
            _claim: claim,
        };
        write_json(&dir.join(MARKER), &marker(command, None))?;
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
        let mut files: Vec<String> = std::fs::read_dir(&self.staging)
            .map_err(|e| Error::io(&self.staging, e))?
            .flatten()
            .map(|e| e.file_name().to_string_lossy().to_string())
            .filter(|name| name != MARKER)
            .collect();
        files.sort();
        write_json(&self.join(MARKER), &marker(&self.command, Some(&files)))?;
        // Held throughout: a stop removing this process's temporaries waits until the folder is in place.
        let mut list = live();
        if !list.contains(&self.staging) {
            return Err(Error::Interrupted);
        }
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
        release(&mut list, &self.staging);
        // The earlier folder, moved aside, is removed before the lock is let go: a stop never
        // leaves it beside the new one.
        if let Some(aside) = aside {
            let _ = std::fs::remove_dir_all(aside);
        }
        drop(list);
        Ok(())
    }
}

impl Drop for OutputDir {
    fn drop(&mut self) {
        if !self.committed {
            let mut list = live();
            let _ = std::fs::remove_dir_all(&self.staging);
            release(&mut list, &self.staging);
        }
    }
}

/// Writes several files so that they appear together: each into a temporary sibling, then all
/// renamed into place (a failed write leaves none of them changed). The temporary files are
/// registered as being written, so that a command stopped by a signal removes them
/// ([`abandon_outputs`]) and none is put in place after that.
pub fn write_texts_together(files: &[(&Path, &str)]) -> Result<()> {
    let mut written: Vec<(std::path::PathBuf, &Path)> = Vec::new();
    let result = (|| -> Result<()> {
        for (path, text) in files {
            let tmp = temporary_sibling(path)?;
            register(&tmp);
            written.push((tmp.clone(), path));
            write_text(&tmp, text)?;
        }
        let in_place = live();
        if let Some((_, path)) = written.iter().find(|(tmp, _)| !in_place.contains(tmp)) {
            return Err(Error::io(path, std::io::Error::other("stopped")));
        }
        for (tmp, path) in &written {
            std::fs::rename(tmp, path).map_err(|e| Error::io(path, e))?;
        }
        Ok(())
    })();
    let mut list = live();
    for (tmp, _) in &written {
        if result.is_err() {
            let _ = std::fs::remove_file(tmp);
        }
        release(&mut list, tmp);
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
    fn a_folder_is_a_commands_only_with_its_marker_and_only_what_it_wrote() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        assert_eq!(folder_owner(&out).unwrap(), FolderOwner::Nobody);
        let staged = OutputDir::begin(&out, "slide", false, &[]).unwrap();
        write_text(&staged.join("series.csv"), "a\n").unwrap();
        staged.commit().unwrap();
        let owner = |c: &str, f: &[&str]| FolderOwner::Wearsim {
            command: c.into(),
            foreign: f.iter().map(|s| s.to_string()).collect(),
        };
        assert_eq!(folder_owner(&out).unwrap(), owner("slide", &[]));
        std::fs::write(out.join("notes.txt"), "mine").unwrap();
        assert_eq!(folder_owner(&out).unwrap(), owner("slide", &["notes.txt"]));
        let e = OutputDir::begin(&out, "slide", false, &[]).unwrap_err().to_string();
        assert!(e.contains("notes.txt") && e.contains("--overwrite"), "{e}");
        // A study folder of an earlier version: its hash file, no marker.
        let study = dir.path().join("study");
        std::fs::create_dir_all(study.join("jobs")).unwrap();
        std::fs::write(study.join("study.hash"), "0123").unwrap();
        assert_eq!(folder_owner(&study).unwrap(), owner("study run", &[]));
        std::fs::write(dir.path().join("theirs"), "x").unwrap();
        std::fs::create_dir(dir.path().join("user")).unwrap();
        std::fs::write(dir.path().join("user").join("results.csv"), "x").unwrap();
        assert_eq!(folder_owner(&dir.path().join("user")).unwrap(), FolderOwner::Foreign);
        // A single output file: never an input (any spelling), never a foreign file without overwrite.
        let input = dir.path().join("run.gif");
        std::fs::write(&input, "[surface]").unwrap();
        let spelled = dir.path().join("user").join("..").join("run.gif");
        for overwrite in [false, true] {
            let e = refuse_foreign_file(&spelled, "animate", overwrite, &[&input], |_| true).unwrap_err();
            assert!(e.to_string().contains("input"), "{e}");
        }
        let theirs = dir.path().join("theirs");
        assert!(refuse_foreign_file(&theirs, "animate", false, &[], |_| false).is_err());
        assert!(refuse_foreign_file(&theirs, "animate", true, &[], |_| false).is_ok());
        assert!(refuse_foreign_file(&theirs, "animate", false, &[], |_| true).is_ok());
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
