//! Library errors as Python exceptions, and long calls run off the GIL with Ctrl-C and progress.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc::{channel, RecvTimeoutError};
use std::time::Duration;

use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyKeyboardInterrupt, PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use wearsim::{Error, Interrupt};

create_exception!(_wearsim, WearsimError, PyException, "Base class of wearsim's errors.");
create_exception!(
    _wearsim,
    NotConvergedError,
    WearsimError,
    "The contact solver reached its iteration limit before its tolerance."
);

/// Library error → Python exception, the one place where kinds are mapped: bad input is a
/// `ValueError`, file trouble an `OSError`, a solver that does not converge a `NotConvergedError`.
/// A failed study job takes the kind of its cause; the message is the library's, whole.
pub fn to_py(e: Error) -> PyErr {
    let message = e.to_string();
    match e.root() {
        Error::Io { .. } | Error::InvalidFile { .. } => PyOSError::new_err(message),
        Error::NotConverged { .. } => NotConvergedError::new_err(message),
        Error::Interrupted => PyKeyboardInterrupt::new_err(message),
        Error::InvalidParameter { .. }
        | Error::InvalidSurface { .. }
        | Error::RunFile { .. }
        | Error::StudyFolder { .. }
        | Error::InfeasibleLoad { .. }
        | Error::Job { .. }
        | Error::JobsFailed { .. } => PyValueError::new_err(message),
    }
}

/// Steps or jobs done so far and their total, updated by the worker thread and reported to a Python
/// callback by the calling thread.
#[derive(Default)]
pub struct Progress {
    done: AtomicUsize,
    total: AtomicUsize,
}

impl Progress {
    pub fn set(&self, done: usize, total: usize) {
        self.total.store(total, Ordering::Relaxed);
        self.done.store(done, Ordering::Relaxed);
    }
}

/// Runs `work` on a worker thread with the GIL released. Every 50 ms the calling thread checks for
/// signals; on Ctrl-C it raises the interrupt flag, waits for the work to stop and re-raises the
/// KeyboardInterrupt. `threads`, when given, runs the work on a pool of that many threads.
pub fn interruptible<T: Send>(
    py: Python<'_>,
    threads: Option<usize>,
    work: impl FnOnce(&Interrupt) -> wearsim::Result<T> + Send,
) -> PyResult<T> {
    interruptible_with_progress(py, threads, None, |interrupt, _| work(interrupt))
}

/// The pool of `threads` threads a call asked for (None: the global pool), with a `UserWarning`
/// when the library's check lowers or questions the number.
fn thread_pool(py: Python<'_>, threads: Option<usize>) -> PyResult<Option<rayon::ThreadPool>> {
    let threads = match threads {
        Some(requested) => {
            let (t, note) = wearsim::check::threads(requested).map_err(to_py)?;
            if let Some(note) = note {
                let category = py.get_type::<pyo3::exceptions::PyUserWarning>();
                PyErr::warn(
                    py,
                    &category,
                    &std::ffi::CString::new(format!("threads: {note}")).unwrap_or_default(),
                    1,
                )?;
            }
            Some(t)
        }
        None => None,
    };
    Ok(match threads {
        Some(t) => Some(
            rayon::ThreadPoolBuilder::new()
                .num_threads(t)
                .build()
                .map_err(|e| PyRuntimeError::new_err(format!("cannot start {t} threads: {e}")))?,
        ),
        None => None,
    })
}

/// [`interruptible`] with progress: when `callback` is given, the calling thread calls
/// `callback(done, total)` whenever the work has advanced its [`Progress`], and once at the end. An
/// exception in the callback stops the work like Ctrl-C and is raised.
pub fn interruptible_with_progress<T: Send>(
    py: Python<'_>,
    threads: Option<usize>,
    callback: Option<&Bound<'_, PyAny>>,
    work: impl FnOnce(&Interrupt, &Progress) -> wearsim::Result<T> + Send,
) -> PyResult<T> {
    let interrupt = Interrupt::default();
    let progress = Progress::default();
    let pool = thread_pool(py, threads)?;
    let mut reported = 0;
    let mut report = || -> PyResult<()> {
        let done = progress.done.load(Ordering::Relaxed);
        match callback {
            Some(f) if done != reported => {
                reported = done;
                f.call1((done, progress.total.load(Ordering::Relaxed))).map(|_| ())
            }
            _ => Ok(()),
        }
    };
    let (tx, rx) = channel();
    std::thread::scope(|scope| {
        let flag = interrupt.clone();
        let (pool, progress) = (&pool, &progress);
        scope.spawn(move || {
            let result = match pool {
                Some(p) => p.install(|| work(&flag, progress)),
                None => work(&flag, progress),
            };
            let _ = tx.send(result);
        });
        // The receiver is moved into each detached wait and handed back (it is Send, not Sync).
        let mut rx = rx;
        loop {
            let (back, received) = py.detach(move || {
                let r = rx.recv_timeout(Duration::from_millis(50));
                (rx, r)
            });
            rx = back;
            match received {
                Ok(result) => {
                    let value = result.map_err(to_py)?;
                    report()?;
                    return Ok(value);
                }
                Err(RecvTimeoutError::Timeout) => {
                    if let Err(stop) = py.check_signals().and_then(|_| report()) {
                        interrupt.request();
                        let _ = py.detach(move || rx.recv());
                        return Err(stop);
                    }
                }
                Err(RecvTimeoutError::Disconnected) => {
                    return Err(PyRuntimeError::new_err(
                        "wearsim's worker thread stopped without a result",
                    ))
                }
            }
        }
    })
}
