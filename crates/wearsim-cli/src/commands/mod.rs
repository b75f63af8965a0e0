//! One module per subcommand; the helpers they share.

pub mod animate;
pub mod bench;
pub mod contact;
pub mod cost;
pub mod estimate;
pub mod fields;
pub mod junctions;
pub mod plot;
pub mod slide;
pub mod study;
pub mod surface;

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::Stdio;
use std::sync::atomic::{AtomicBool, AtomicI32, Ordering};
use std::time::{Duration, Instant};

use anyhow::{Context, Result};
use wearsim::config::RunConfig;

use crate::out::tell;

/// `--overwrite`, the same flag and help in every command that writes an output folder
/// (flattened: `#[command(flatten)]`).
#[derive(clap::Args, Debug, Clone, Copy)]
pub struct Overwrite {
    /// Replace the output folder even when it holds another command's results or other files.
    #[arg(long = "overwrite")]
    pub replace: bool,
}

/// `--out` and `--overwrite` of a command that writes one output folder of its own, whose `--out`
/// needs no more words (`slide`, `estimate`, `junctions`; flattened).
#[derive(clap::Args, Debug, Clone)]
pub struct OutputFolder {
    /// Output folder (created if missing; an earlier run of the same command there is replaced
    /// whole).
    #[arg(long)]
    pub out: PathBuf,
    #[command(flatten)]
    pub overwrite: Overwrite,
}

/// The signals that stop a command: Ctrl-C, a closed terminal, `kill`, and a Slurm job's time
/// limit (SIGTERM, then SIGKILL after a grace period) and `--signal` (SIGUSR1, SIGUSR2).
const STOP_SIGNALS: [i32; 5] = [
    signal_hook::consts::SIGINT,
    signal_hook::consts::SIGTERM,
    signal_hook::consts::SIGHUP,
    signal_hook::consts::SIGUSR1,
    signal_hook::consts::SIGUSR2,
];

/// The first stop signal received (0: none).
static SIGNAL: AtomicI32 = AtomicI32::new(0);
/// Whether the command polls [`interrupt`] (stops at its next step, saving what a rerun resumes
/// from) rather than stopping at once.
static POLLS: AtomicBool = AtomicBool::new(false);
/// A child process that the stop signal is passed on to (`fields to-netcdf`).
static CHILD: AtomicI32 = AtomicI32::new(0);

/// The flag a stop signal raises: the library stops at its next iteration, the command cleans up
/// (temporary files, claims), long runs save their state, and it exits with 128 + the signal.
pub fn interrupt() -> &'static wearsim::Interrupt {
    static FLAG: std::sync::OnceLock<wearsim::Interrupt> = std::sync::OnceLock::new();
    FLAG.get_or_init(wearsim::Interrupt::default)
}

/// Handles the stop signals for the whole run. A command that polls the flag ([`polls_interrupt`])
/// stops at its next step; any other stops at once: its temporary files and claims are removed
/// (outputs being put in place are finished first) and it exits with 128 + the signal. A second
/// signal stops any command at once. SIGINT and SIGHUP keep an ignored disposition they inherit
/// (`nohup`, a background job), as other Unix programs do.
pub fn handle_signals() {
    let wanted: Vec<i32> = STOP_SIGNALS
        .into_iter()
        .filter(|&s| {
            let keep = s == signal_hook::consts::SIGINT || s == signal_hook::consts::SIGHUP;
            !(keep && inherited_ignored(s))
        })
        .collect();
    let Ok(mut signals) = signal_hook::iterator::Signals::new(&wanted) else {
        return;
    };
    std::thread::spawn(move || {
        for sig in signals.forever() {
            let first = SIGNAL
                .compare_exchange(0, sig, Ordering::SeqCst, Ordering::SeqCst)
                .is_ok();
            interrupt().request();
            let child = CHILD.load(Ordering::SeqCst);
            if child > 0 {
                // SAFETY: kill(2) on the pid of a child this process started and still waits for.
                unsafe {
                    libc::kill(child, libc::SIGTERM);
                }
            }
            if !first || !POLLS.load(Ordering::SeqCst) {
                stop_now(sig);
            }
        }
    });
}

/// Whether `signal` was ignored when the program started.
fn inherited_ignored(signal: i32) -> bool {
    // SAFETY: sigaction(2) with a null new action only reads the current one into `old`.
    unsafe {
        let mut old: libc::sigaction = std::mem::zeroed();
        libc::sigaction(signal, std::ptr::null(), &mut old) == 0 && old.sa_sigaction == libc::SIG_IGN
    }
}

/// Stops the command now: removes its temporary files and claims and exits with 128 + `signal`.
fn stop_now(signal: i32) -> ! {
    let _in_place = wearsim::io::abandon_outputs();
    tell!("error: stopped by {}; nothing was written", signal_name(signal));
    std::process::exit(128 + signal);
}

/// The command polls [`interrupt`] at every step of its work and stops there, cleanly, when a
/// stop signal raises it (a long run saving its state first).
pub fn polls_interrupt() {
    POLLS.store(true, Ordering::SeqCst);
}

/// A child process to pass a stop signal on to (as SIGTERM), while it runs; 0 when it is done.
pub fn set_child(pid: u32) {
    CHILD.store(i32::try_from(pid).unwrap_or(0), Ordering::SeqCst);
}

/// The stop signal received, if any.
pub fn stop_signal() -> Option<i32> {
    Some(SIGNAL.load(Ordering::SeqCst)).filter(|&s| s != 0)
}

/// A signal's name (SIGTERM).
pub fn signal_name(signal: i32) -> String {
    signal_hook::low_level::signal_name(signal).map_or(format!("signal {signal}"), String::from)
}

/// `Err(Interrupted)` once a stop signal arrived: checked before outputs are put in place, so
/// that a command stopped after its last step writes nothing and exits non-zero.
pub fn check_interrupt() -> Result<()> {
    interrupt().check().map_err(Into::into)
}

/// Reads and validates a run file.
pub fn load_run(run: &Path) -> Result<RunConfig> {
    let config = RunConfig::from_path(run).with_context(|| format!("run file {}", run.display()))?;
    // Values given in another form than the model's inputs, with the formula of each conversion.
    for note in &config.conversions {
        tell!("{note}");
    }
    Ok(config)
}

/// The files a run reads, its run file and surface files: an output folder may hold none of them.
pub fn run_inputs<'a>(run: &'a Path, config: &'a RunConfig) -> Vec<&'a Path> {
    let mut inputs = vec![run];
    inputs.extend(config.surfaces.input_files());
    inputs
}

/// Prints what was done to surfaces read from files (cropping, detrending, header lines skipped),
/// and, with `warnings`, what about them may spoil the results (a surface far from periodic).
pub fn report_surfaces(pair: &wearsim::config::SurfacePair, warnings: bool) {
    for note in &pair.notes {
        tell!("note: {note}");
    }
    if warnings {
        for w in &pair.warnings {
            tell!("warning: {w}");
        }
    }
}

/// How long the interpreter may take to answer whether it has what the work needs before it is
/// given up as hanging (a Python on an unreachable network file system, an import that deadlocks):
/// `$WEARSIM_PYTHON_TIMEOUT` seconds, default 120 — an import of SurfaceTopography and its
/// dependencies takes a few seconds, tens on a cold cluster file system.
fn probe_timeout() -> Duration {
    let seconds = std::env::var("WEARSIM_PYTHON_TIMEOUT")
        .ok()
        .and_then(|v| v.trim().parse::<f64>().ok())
        .filter(|s| s.is_finite() && *s > 0.0)
        .unwrap_or(120.0);
    Duration::from_secs_f64(seconds)
}

/// The Python program that asks an interpreter whether it has wearsim's `module` (imported) and the
/// `packages` of its extra (found, not imported: SurfaceTopography alone takes seconds to import,
/// which the work itself then spends again), failing with the import error of what is missing.
fn probe_program(module: &str, packages: &[&str]) -> String {
    format!(
        "import importlib.util, {module}\n\
         for name in {packages:?}:\n    \
             if importlib.util.find_spec(name) is None:\n        \
                 raise ModuleNotFoundError(f\"No module named '{{name}}'\")\n"
    )
}

/// The Python interpreter a command runs its work in (`--python`, else `$WEARSIM_PYTHON`, else
/// python3), once asked whether it has what the work needs (wearsim's `module` and the `packages`
/// of its `extra`) — before any folder is made, so that the error says what to install: the
/// package with its extra (`pip install "wearsim[EXTRA]"`). `work` says what runs there ("the
/// conversion"). The question is a child process like the work itself: a stop signal stops it and
/// the command at once, and one that does not answer within [`probe_timeout`] is stopped and said
/// to hang.
pub fn python_with(
    python: Option<&Path>,
    module: &str,
    packages: &[&str],
    extra: &str,
    work: &str,
) -> Result<std::path::PathBuf> {
    let python = python
        .map(Path::to_path_buf)
        .or_else(|| std::env::var_os("WEARSIM_PYTHON").map(std::path::PathBuf::from))
        .unwrap_or_else(|| std::path::PathBuf::from("python3"));
    let asked = format!("{module} and {}", packages.join(", "));
    let mut probe = std::process::Command::new(&python);
    probe
        .args(["-c", &probe_program(module, packages)])
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    let cannot_run = || {
        format!(
            "cannot run {} ({work} runs in Python); install Python 3 with `pip install \"wearsim[{extra}]\"`, or name \
             the interpreter with --python",
            python.display()
        )
    };
    let mut child = probe.spawn().with_context(cannot_run)?;
    set_child(child.id());
    // Its error stream read beside it, so that a long message cannot fill the pipe and stall it.
    let mut stderr = child.stderr.take();
    let reader = std::thread::spawn(move || {
        let mut text = String::new();
        if let Some(e) = stderr.as_mut() {
            let _ = e.read_to_string(&mut text);
        }
        text
    });
    let timeout = probe_timeout();
    let started = Instant::now();
    let status = loop {
        match child.try_wait() {
            Ok(Some(status)) => break Some(status),
            Ok(None) => {}
            Err(_) => break None,
        }
        if interrupt().is_requested() || started.elapsed() >= timeout {
            let _ = child.kill();
            let _ = child.wait();
            set_child(0);
            check_interrupt()?;
            anyhow::bail!(
                "{} did not answer within {:.0} s when asked whether it has {asked} (it hangs: an interpreter on \
                 an unreachable file system, an import that deadlocks); name a working one with --python or \
                 $WEARSIM_PYTHON, or allow it longer with WEARSIM_PYTHON_TIMEOUT=SECONDS",
                python.display(),
                timeout.as_secs_f64()
            );
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    set_child(0);
    check_interrupt()?;
    let status = status.with_context(cannot_run)?;
    if !status.success() {
        let why = reader.join().unwrap_or_default();
        anyhow::bail!(
            "{} lacks the wearsim package or its `{extra}` extra ({}); install them with `pip install \"wearsim[{extra}]\"` \
             into that interpreter, or name another with --python",
            python.display(),
            why.trim().lines().last().unwrap_or("import failed")
        );
    }
    Ok(python)
}

/// The identity of a file or folder (its device and inode), None where there is none: a rename into
/// place gives the path a new one.
fn identity(path: &Path) -> Option<(u64, u64)> {
    use std::os::unix::fs::MetadataExt;
    std::fs::symlink_metadata(path).ok().map(|m| (m.dev(), m.ino()))
}

/// Runs `command` (the work of a front end that runs in Python, `what` in the messages, e.g. "the
/// import") as a child process and waits for it: a stop signal is passed on to it (it removes its
/// temporary files and exits), and its failure is an error whose cause it printed itself. The work
/// puts `output` in place by a rename: a child that exits with success without having done so (an
/// interpreter that is not the one asked, a wrapper script that swallows the work) is an error too.
pub fn run_child(mut command: std::process::Command, what: &str, output: &Path) -> Result<()> {
    let program = command.get_program().to_string_lossy().to_string();
    let before = identity(output);
    let mut child = command.spawn().with_context(|| format!("cannot run {program}"))?;
    set_child(child.id());
    if interrupt().is_requested() {
        let _ = child.kill(); // the signal came before the child could be told
    }
    let status = child.wait();
    set_child(0);
    let status = status.with_context(|| format!("cannot run {program}"))?;
    check_interrupt()?;
    if !status.success() {
        anyhow::bail!("{what} failed ({status}); its error is above");
    }
    let after = identity(output);
    if after.is_none() || after == before {
        anyhow::bail!(
            "{what} ended with success but wrote nothing: {} is {}; {program} did not do the work (is it the Python \
             with the wearsim package, or a wrapper that drops it?); name the interpreter with --python",
            output.display(),
            if after.is_none() { "missing" } else { "unchanged" }
        );
    }
    Ok(())
}
