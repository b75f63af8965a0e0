//! The rules every input obeys, one function each, shared by run files, the CLI and the Python
//! bindings so that a value is refused with the same message wherever it enters.

use crate::error::{Error, Result};

/// Smallest d* and λ_l, in pixels, that a grid resolves without a warning.
pub const RESOLVED_PIXELS: f64 = 4.0;

/// `value` must be finite and strictly positive.
pub fn positive(field: &str, value: f64) -> Result<()> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(Error::param(field, format!("{value} must be a finite positive number")))
    }
}

/// Range of a box side (in the run's length unit) and of a modulus or strength (in its stress
/// unit) within which every result is representable in double precision and equals the
/// dimensionless result scaled: wear volumes grow as L³, the solver's curvature as L³/E*, loads as
/// E·L². Outside it a result would underflow to 0 or overflow.
pub const SCALE_RANGE: (f64, f64) = (1e-90, 1e90);

/// `value` (positive) must lie within [`SCALE_RANGE`].
pub fn scale(field: &str, value: f64) -> Result<()> {
    positive(field, value)?;
    let (low, high) = SCALE_RANGE;
    if (low..=high).contains(&value) {
        Ok(())
    } else {
        Err(Error::param(
            field,
            format!(
                "{value:e} is outside {low:e} … {high:e} of its unit, the range in which wearsim's double-precision \
                 results stay representable (wear volumes scale as L³, loads as E·L²); state the run in other units \
                 (e.g. µm and GPa, or units = \"reduced\")"
            ),
        ))
    }
}

/// A grid side: an even number of pixels, at least 16 (the FFT and the periodic junction labelling
/// need at least a few pixels per side; powers of two are fastest).
pub fn grid(n: usize) -> Result<()> {
    if n < 16 || n & 1 != 0 {
        return Err(Error::param(
            "grid",
            format!("{n} must be an even number of pixels ≥ 16 (powers of two are fastest)"),
        ));
    }
    // Junction labels are 32-bit pixel indices.
    if n > MAX_GRID {
        let gib = SLIDING_ARRAYS * 8.0 * (n as f64).powi(2) / (1u64 << 30) as f64;
        return Err(Error::param(
            "grid",
            format!(
                "{n} pixels is above the largest grid, {MAX_GRID} (junction labels are 32-bit), and a sliding run on \
                 it would need about {gib:.0} GiB of memory; lower `grid`"
            ),
        ));
    }
    Ok(())
}

/// The largest grid side: junction labels index N² pixels with 32-bit integers.
pub const MAX_GRID: usize = 65_534;

/// A junction connectivity: 4 (edge neighbours) or 8 (edge and corner neighbours).
pub fn connectivity(connectivity: u8) -> Result<()> {
    if connectivity == 4 || connectivity == 8 {
        Ok(())
    } else {
        Err(Error::param("connectivity", format!("{connectivity} must be 4 or 8")))
    }
}

/// A normal load F_N the model can run on an apparent area Lx·Ly: its mean pressure F_N/(Lx·Ly) a normal
/// positive number below the flow pressure p_m (above it the surfaces would be in full plastic
/// contact, where the saturated model has no solution).
pub fn load(load: f64, area: f64, flow_pressure: f64) -> Result<()> {
    positive("loads", load)?;
    let mean_pressure = load / area;
    if !mean_pressure.is_normal() {
        return Err(Error::param(
            "loads",
            format!(
                "{load:e} over the apparent area L² = {area:e} gives a mean pressure of {mean_pressure:e}, which is not a \
                 usable number; check `loads` and `length` (and their units)"
            ),
        ));
    }
    if mean_pressure >= flow_pressure {
        return Err(Error::InfeasibleLoad {
            mean_pressure,
            flow_pressure,
        });
    }
    Ok(())
}

/// Bytes of memory this machine can still give (Linux `MemAvailable`); `None` where unknown.
pub fn available_memory() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// Refuses work that needs `arrays` arrays of Nx·Ny doubles on an `nx × ny` grid when that is more
/// than the machine can give, before anything is allocated (an allocation that fails aborts the
/// process). `what` names the work in the message.
pub fn memory(what: &str, nx: usize, ny: usize, arrays: f64) -> Result<()> {
    let need = arrays * 8.0 * (nx as f64) * (ny as f64);
    let gib = |b: f64| b / (1u64 << 30) as f64;
    match available_memory() {
        Some(have) if need > have as f64 => Err(Error::param(
            "grid",
            format!(
                "{what} on {nx}×{ny} pixels needs about {:.1} GiB of memory ({arrays} arrays of Nx·Ny doubles) and this \
                 machine has {:.1} GiB available; lower `grid` or run on a larger machine",
                gib(need),
                gib(have as f64)
            ),
        )),
        _ => Ok(()),
    }
}

/// Memory of a sliding run, in arrays of N² doubles: the two surfaces, the solver's five work fields
/// with its kernel and spectrum, heights and pressure, and the junction labeller.
pub const SLIDING_ARRAYS: f64 = 12.0;

/// Memory of generating a surface pair, in arrays of N² doubles (both surfaces are generated at
/// once, each with its spectrum and noise).
pub const SURFACE_ARRAYS: f64 = 6.0;

/// The number of worker threads to use for a request: at least 1, and at most four per core (more
/// only adds overhead, and thousands of threads exhaust the machine). Returns the count and, when
/// the request was lowered, a warning saying so.
pub fn threads(requested: usize) -> Result<(usize, Option<String>)> {
    if requested == 0 {
        return Err(Error::param(
            "threads",
            "0 must be at least 1 (leave it out to use every core)",
        ));
    }
    let cores = std::thread::available_parallelism().map_or(1, |c| c.get());
    let most = 4 * cores;
    if requested > most {
        Ok((
            most,
            Some(format!(
                "{requested} threads on {cores} cores would only add overhead; using {most} (four per core)"
            )),
        ))
    } else {
        Ok((requested, None))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_rule_names_its_field() {
        assert!(positive("length", 1.0).is_ok());
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(positive("length", bad).unwrap_err().to_string().contains("`length`"));
        }
        assert!(grid(16).is_ok() && grid(14).is_err() && grid(17).is_err());
        assert!(connectivity(8).is_ok() && connectivity(6).unwrap_err().to_string().contains("`connectivity`"));
    }

    #[test]
    fn work_beyond_the_machine_is_refused_and_threads_are_capped() {
        if available_memory().is_some() {
            let e = memory("a sliding run", 100_000, 100_000, SLIDING_ARRAYS)
                .unwrap_err()
                .to_string();
            assert!(e.contains("GiB") && e.contains("`grid`"), "{e}");
        }
        assert!(memory("a sliding run", 64, 32, SLIDING_ARRAYS).is_ok());
        assert!(threads(0).is_err());
        assert_eq!(threads(1).unwrap(), (1, None));
        let (t, warning) = threads(1_000_000).unwrap();
        assert!(t < 1_000_000 && warning.is_some());
    }

    #[test]
    fn loads_that_give_no_usable_pressure_are_refused() {
        assert!(load(1e-3, 1.0, 0.05).is_ok());
        assert!(load(5e-324, 1.0, 0.05).unwrap_err().to_string().contains("`loads`"));
        assert!(load(1e-3, 1e300 * 1e300, 0.05).is_err());
        assert!(matches!(load(0.06, 1.0, 0.05), Err(Error::InfeasibleLoad { .. })));
    }
}
