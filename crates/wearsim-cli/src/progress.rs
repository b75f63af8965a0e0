//! Progress of long commands, for a person watching: a live bar (done / total, rate, time left) on
//! a terminal; plain lines, at least every 30 seconds and at the end, when stderr is not a terminal
//! (a Slurm log) or with `--log`; nothing with `--quiet`. The numerics never print: the commands
//! feed this from the library's observers and callbacks.

use std::io::IsTerminal;
use std::sync::{Mutex, OnceLock};
use std::time::{Duration, Instant};

use crate::out::tell;

/// How progress is shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    Bar,
    Lines,
    Quiet,
}

static MODE: OnceLock<Mode> = OnceLock::new();

/// Chooses the mode once for the process, from the global flags and whether stderr is a terminal.
pub fn configure(quiet: bool, log: bool) {
    let mode = if quiet {
        Mode::Quiet
    } else if log || !std::io::stderr().is_terminal() {
        Mode::Lines
    } else {
        Mode::Bar
    };
    let _ = MODE.set(mode);
}

fn mode() -> Mode {
    *MODE.get().unwrap_or(&Mode::Lines)
}

/// Longest silence in line mode.
const LINE_EVERY: Duration = Duration::from_secs(30);

/// One progress display of `unit`s (steps, jobs).
pub struct Progress {
    label: String,
    unit: &'static str,
    bar: Option<indicatif::ProgressBar>,
    start: Instant,
    last_line: Mutex<Option<Instant>>,
}

impl Progress {
    pub fn new(label: &str, unit: &'static str, total: u64) -> Self {
        let bar = (mode() == Mode::Bar).then(|| {
            let b = indicatif::ProgressBar::new(total);
            b.set_style(
                indicatif::ProgressStyle::with_template(&format!(
                    "{label} {{wide_bar}} {{pos}}/{{len}} {unit}, {{per_sec}}, {{eta}} left, {{msg}}"
                ))
                .expect("valid template"),
            );
            b.enable_steady_tick(Duration::from_millis(500));
            b
        });
        Self {
            label: label.into(),
            unit,
            bar,
            start: Instant::now(),
            last_line: Mutex::new(None),
        }
    }

    /// Reports `done` of `total`, with an optional note (e.g. which job).
    pub fn set(&self, done: u64, total: u64, note: &str) {
        match (&self.bar, mode()) {
            (Some(b), _) => {
                b.set_length(total);
                b.set_position(done);
                b.set_message(note.to_string());
            }
            (None, Mode::Lines) => {
                let Ok(mut last) = self.last_line.lock() else { return };
                let due = last.is_none_or(|t| t.elapsed() >= LINE_EVERY) || done >= total;
                if due {
                    let elapsed = self.start.elapsed().as_secs_f64();
                    let rate = done as f64 / elapsed.max(1e-9);
                    let left = if done > 0 {
                        (total - done.min(total)) as f64 / rate
                    } else {
                        f64::NAN
                    };
                    tell!(
                        "{}: {done}/{total} {} ({:.0} %), {:.1} s elapsed, {} left{}{note}",
                        self.label,
                        self.unit,
                        100.0 * done as f64 / total.max(1) as f64,
                        elapsed,
                        if left.is_finite() {
                            format!("{left:.0} s")
                        } else {
                            "?".into()
                        },
                        if note.is_empty() { "" } else { "; " },
                    );
                    *last = Some(Instant::now());
                }
            }
            _ => {}
        }
    }

    /// Removes the bar (line mode has printed the last line already).
    pub fn finish(self) {
        if let Some(b) = self.bar {
            b.finish_and_clear();
        }
    }
}
