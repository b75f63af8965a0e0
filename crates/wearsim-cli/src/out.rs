//! The one way the CLI prints, to stdout ([`say!`], [`say_part!`]) and stderr ([`tell!`]): results,
//! progress lines, notes, warnings and errors alike. A write that fails — a pipe whose reader has
//! gone (`| head`, `| less` quit early, `| grep -m1`: EPIPE, as Rust ignores SIGPIPE), a closed
//! terminal, a full disk under a redirection — stops printing to that stream for the rest of the
//! run, silently, and the command goes on: it finishes, writes its results and exits as if nothing
//! had been printed. (`println!` and `eprintln!` panic there instead, losing the results; the crate
//! denies them.)

use std::fmt::Arguments;
use std::io::Write;
use std::sync::atomic::{AtomicBool, Ordering};

/// Whether a write to stdout, or to stderr, has failed: nothing more is printed there.
static STDOUT_GONE: AtomicBool = AtomicBool::new(false);
static STDERR_GONE: AtomicBool = AtomicBool::new(false);

/// Prints `text` to stdout, unless a write there has failed.
pub fn stdout(text: Arguments) {
    write(&STDOUT_GONE, &mut std::io::stdout().lock(), text);
}

/// Prints `text` to stderr, unless a write there has failed.
pub fn stderr(text: Arguments) {
    write(&STDERR_GONE, &mut std::io::stderr().lock(), text);
}

fn write(gone: &AtomicBool, stream: &mut impl Write, text: Arguments) {
    if gone.load(Ordering::Relaxed) {
        return;
    }
    // Stdout is line-buffered: a line is written (and any error found) at its newline.
    if stream.write_fmt(text).is_err() {
        gone.store(true, Ordering::Relaxed);
    }
}

/// `println!` that survives a closed stdout (see the module).
macro_rules! say {
    () => {
        $crate::out::stdout(format_args!("\n"))
    };
    ($($arg:tt)*) => {
        $crate::out::stdout(format_args!("{}\n", format_args!($($arg)*)))
    };
}

/// `print!` that survives a closed stdout (see the module).
macro_rules! say_part {
    ($($arg:tt)*) => {
        $crate::out::stdout(format_args!($($arg)*))
    };
}

/// `eprintln!` that survives a closed stderr (see the module).
macro_rules! tell {
    () => {
        $crate::out::stderr(format_args!("\n"))
    };
    ($($arg:tt)*) => {
        $crate::out::stderr(format_args!("{}\n", format_args!($($arg)*)))
    };
}

pub(crate) use {say, say_part, tell};

#[cfg(test)]
mod tests {
    use super::*;

    /// A stream whose reader has gone.
    struct Closed(usize);

    impl Write for Closed {
        fn write(&mut self, _: &[u8]) -> std::io::Result<usize> {
            self.0 += 1;
            Err(std::io::ErrorKind::BrokenPipe.into())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn a_failed_write_stops_printing_to_that_stream_without_a_panic() {
        let gone = AtomicBool::new(false);
        let mut stream = Closed(0);
        write(&gone, &mut stream, format_args!("first {}\n", 1));
        assert!(gone.load(Ordering::Relaxed));
        write(&gone, &mut stream, format_args!("second\n"));
        assert_eq!(stream.0, 1, "written to again after it failed");
    }
}
