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

/// Poisson's ratio of an isotropic elastic solid: within (−1, 0.5).
pub fn poisson_ratio(value: f64) -> Result<()> {
    if value > -1.0 && value < 0.5 {
        Ok(())
    } else {
        Err(Error::param(
            "poisson_ratio",
            format!("{value} is outside (−1, 0.5); use e.g. 0.3"),
        ))
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

/// The smallest grid side, in pixels: the FFT and the periodic junction labelling need at least a
/// few pixels per side. Every reader of a height map refuses a smaller one, and so does
/// `wearsim surface import`.
pub const MIN_GRID: usize = 16;

/// A grid side: an even number of pixels, at least [`MIN_GRID`] (powers of two are fastest).
pub fn grid(n: usize) -> Result<()> {
    if n < MIN_GRID || n & 1 != 0 {
        return Err(Error::param(
            "grid",
            format!("{n} must be an even number of pixels ≥ {MIN_GRID} (powers of two are fastest)"),
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
/// contact, where the saturated model has no solution). `field` names the load where it was given
/// (`loads` of a run file, `--load` of `wearsim contact`).
pub fn load(field: &str, load: f64, area: f64, flow_pressure: f64) -> Result<()> {
    positive(field, load)?;
    let mean_pressure = load / area;
    if !mean_pressure.is_normal() {
        return Err(Error::param(
            field,
            format!(
                "{load:e} over the apparent area L² = {area:e} gives a mean pressure of {mean_pressure:e}, which is not a \
                 usable number; check `{field}` and `length` (and their units)"
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

/// How much memory this process may reach in all (resident, in bytes), and the limit that decides
/// it, in words for messages.
#[derive(Debug, Clone, PartialEq)]
pub struct MemoryRoom {
    pub bytes: u64,
    pub limit: String,
}

/// A `kB` field of `/proc/self/status` (VmRSS, VmSize, VmData), in bytes.
fn status_bytes(field: &str) -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with(field))?;
    Some(line.split_whitespace().nth(1)?.parse::<u64>().ok()? * 1024)
}

/// The soft limit `name` of `/proc/self/limits` ("Max address space", "Max data size"), in bytes;
/// `None` when unlimited or unknown.
fn rlimit(name: &str) -> Option<u64> {
    let limits = std::fs::read_to_string("/proc/self/limits").ok()?;
    let line = limits.lines().find(|l| l.starts_with(name))?;
    line[name.len()..].split_whitespace().next()?.parse().ok()
}

/// The memory limits of the cgroups (v2 `memory.max`, v1 `memory.limit_in_bytes`) this process is
/// in, from its own group up to the root, as (limit, usage) pairs in bytes.
fn cgroup_limits() -> Vec<(u64, u64, &'static str)> {
    let mut found = Vec::new();
    let Ok(groups) = std::fs::read_to_string("/proc/self/cgroup") else {
        return found;
    };
    for line in groups.lines() {
        let mut parts = line.splitn(3, ':');
        let (Some(_), Some(controllers), Some(path)) = (parts.next(), parts.next(), parts.next()) else {
            continue;
        };
        let (root, limit, usage, name) = if controllers.is_empty() {
            (
                "/sys/fs/cgroup",
                "memory.max",
                "memory.current",
                "the cgroup memory limit (memory.max)",
            )
        } else if controllers.split(',').any(|c| c == "memory") {
            (
                "/sys/fs/cgroup/memory",
                "memory.limit_in_bytes",
                "memory.usage_in_bytes",
                "the cgroup memory limit (memory.limit_in_bytes)",
            )
        } else {
            continue;
        };
        let mut dir = std::path::PathBuf::from(root);
        dir.push(path.trim_start_matches('/'));
        for d in dir.ancestors().take_while(|d| d.starts_with(root)) {
            let read = |f: &str| std::fs::read_to_string(d.join(f)).ok()?.trim().parse::<u64>().ok();
            // v1 writes "no limit" as a number near 2⁶³.
            if let (Some(l), Some(u)) = (read(limit), read(usage)) {
                if l < 1 << 60 {
                    found.push((l, u, name));
                }
            }
        }
    }
    found
}

/// Slurm's memory allocation of this job on this node (`--mem`: SLURM_MEM_PER_NODE, or
/// `--mem-per-cpu`: SLURM_MEM_PER_CPU × the CPUs on the node), in bytes, with its name. An
/// allocation of more bytes than a u64 holds is no limit: `u64::MAX`, named so.
fn slurm_allocation(var: impl Fn(&str) -> Option<String>) -> Option<(u64, String)> {
    let mib = |name: &str| var(name)?.trim().parse::<u64>().ok().filter(|&m| m > 0);
    let bytes = |m: u64, what: String| match m.checked_mul(1 << 20) {
        Some(b) => (b, format!("Slurm's allocation ({what})")),
        None => (
            u64::MAX,
            format!("Slurm's allocation ({what}, more than 2⁶⁴ bytes: taken as no limit)"),
        ),
    };
    if let Some(m) = mib("SLURM_MEM_PER_NODE") {
        return Some(bytes(m, format!("SLURM_MEM_PER_NODE = {m} MB")));
    }
    let per_cpu = mib("SLURM_MEM_PER_CPU")?;
    let cpus = mib("SLURM_CPUS_ON_NODE")
        .or_else(|| mib("SLURM_CPUS_PER_TASK"))
        .unwrap_or(1);
    let what = format!("SLURM_MEM_PER_CPU = {per_cpu} MB × {cpus} CPUs");
    Some(match per_cpu.checked_mul(cpus) {
        Some(m) => bytes(m, what),
        None => bytes(u64::MAX, what),
    })
}

/// What this process may reach in all, the smallest of: the machine's available memory, the
/// memory limits of its cgroups (what a container or Slurm enforces), Slurm's allocation, and the
/// address-space and data-size limits (`ulimit -v`, `ulimit -d`; these count the address space a
/// process reserves beyond what it touches, which is taken off). `None` where nothing is known.
pub fn memory_room() -> Option<MemoryRoom> {
    let rss = status_bytes("VmRSS:").unwrap_or(0);
    let mut rooms: Vec<(u64, String)> = Vec::new();
    if let Some(have) = available_memory() {
        rooms.push((have + rss, "this machine's available memory".into()));
    }
    for (limit, usage, name) in cgroup_limits() {
        rooms.push((limit.saturating_sub(usage) + rss.min(usage), name.into()));
    }
    if let Some(slurm) = slurm_allocation(|n| std::env::var(n).ok()) {
        rooms.push(slurm);
    }
    let reserved = |field: &str| status_bytes(field).map_or(0, |v| v.saturating_sub(rss));
    if let Some(l) = rlimit("Max address space") {
        rooms.push((
            l.saturating_sub(reserved("VmSize:")),
            "the address-space limit (ulimit -v)".into(),
        ));
    }
    if let Some(l) = rlimit("Max data size") {
        rooms.push((
            l.saturating_sub(reserved("VmData:")),
            "the data-size limit (ulimit -d)".into(),
        ));
    }
    rooms
        .into_iter()
        .min_by_key(|r| r.0)
        .map(|(bytes, limit)| MemoryRoom { bytes, limit })
}

/// Memory of the program itself (code, libraries, thread stacks touched, the allocator's own), in
/// bytes, measured as the peak of runs on grids of 256²: added to every estimate.
pub const BASE_MEMORY: f64 = 10.0 * 1048576.0;

/// Peak memory, in bytes, of work that holds `arrays` arrays of Nx·Ny doubles at once on an
/// `nx × ny` grid (the constants below), the program included.
pub fn memory_need(nx: usize, ny: usize, arrays: f64) -> f64 {
    arrays * 8.0 * (nx as f64) * (ny as f64) + BASE_MEMORY
}

/// Refuses work that needs `arrays` arrays of Nx·Ny doubles on an `nx × ny` grid when its peak
/// ([`memory_need`]) is more than this process may use ([`memory_room`]: the machine, cgroup and
/// Slurm limits, `ulimit`), before anything is allocated (an allocation that fails aborts the
/// process). `what` names the work in the message.
pub fn memory(what: &str, nx: usize, ny: usize, arrays: f64) -> Result<()> {
    match memory_shortfall(what, nx, ny, arrays) {
        Some(message) => Err(Error::param("grid", message)),
        None => Ok(()),
    }
}

/// What [`memory`] says when the work does not fit, without the field: for work on a file (a
/// height map too large to read), whose error names the file.
pub fn memory_shortfall(what: &str, nx: usize, ny: usize, arrays: f64) -> Option<String> {
    let need = memory_need(nx, ny, arrays);
    let room = memory_room().filter(|room| need > room.bytes as f64)?;
    Some(format!(
        "{what} on {nx}×{ny} pixels needs about {} of memory ({arrays} arrays of Nx·Ny doubles and the program) and \
         this process may use {} ({}); lower `grid`, or run where more memory is allowed (Slurm: --mem)",
        bytes_in_words(need),
        bytes_in_words(room.bytes as f64),
        room.limit
    ))
}

/// A memory size for messages: MiB below a GiB, else GiB with two decimals.
fn bytes_in_words(bytes: f64) -> String {
    let mib = bytes / 1048576.0;
    if mib < 1024.0 {
        format!("{mib:.0} MiB")
    } else {
        format!("{:.2} GiB", mib / 1024.0)
    }
}

/// Memory of a sliding run at its peak, in arrays of N² doubles, measured (peak resident size of
/// `wearsim slide` at 512² … 4096², within 10 %): the two surfaces, the solver's work fields with
/// its kernel and spectrum, heights and pressure, the junction labeller, and the pressure of the
/// last finished step that a checkpoint saves when the run is stopped.
pub const SLIDING_ARRAYS: f64 = 13.0;

/// Memory of generating a surface pair, in arrays of N² doubles, measured (peak resident size of
/// `wearsim surface` at 2048², within 2 %; 4096² about 7 % below): the surfaces are generated one
/// after the other, so the first one's heights and the second one's spectrum and heights.
pub const SURFACE_ARRAYS: f64 = 3.0;

/// Memory of `wearsim contact` (periodic boundary), in arrays of N² doubles, measured: the solver's
/// fields, the surfaces, heights and pressure, and the displacement, gap and contact map written.
pub const CONTACT_ARRAYS: f64 = 15.0;

/// Memory of `wearsim contact` with the free boundary, in arrays of N² doubles, measured: the
/// solver works on a zero-padded 2Nx × 2Ny grid.
pub const CONTACT_FREE_ARRAYS: f64 = 40.0;

/// The loosest contact-solver tolerance whose sliding results equal those of the default 1e-8:
/// measured on 256² runs (three surface pairs, two loads, two 𝒢; docs/reliability.md), W was the
/// same to four digits for every tolerance up to 1e-6; from 1e-5 single particles come and go (W
/// moves by about 1 %), from 1e-3 W is biased upwards (1e-3: +1 %, 1e-2: up to +13 %, 0.1: up to
/// +135 %, 0.5: up to +18×).
pub const RESULTS_STEADY_TOLERANCE: f64 = 1e-6;

/// The warning a run gets whose `[contact] tolerance` is looser than [`RESULTS_STEADY_TOLERANCE`].
pub fn tolerance_warning(tolerance: f64) -> Option<String> {
    (tolerance > RESULTS_STEADY_TOLERANCE).then(|| {
        format!(
            "[contact] tolerance = {tolerance:e} is looser than {RESULTS_STEADY_TOLERANCE:e}, beyond which the wear \
             results move with it (at 1e-3 W is about 1 % too high, at 1e-2 up to 13 %, at 0.1 up to 135 %); keep \
             the default 1e-8 or at most {RESULTS_STEADY_TOLERANCE:e} for results"
        )
    })
}

/// Longest name (of a material) in characters: names label curves in figures and rows of tables.
pub const MAX_NAME: usize = 100;

/// A name that labels results (a material's): at most [`MAX_NAME`] characters and no control
/// characters (a newline in a name would start a line of a report that reads like another entry, and
/// a name of thousands of characters would grow every figure's legend). The message names `field`.
pub fn name(field: &str, value: &str) -> std::result::Result<(), String> {
    if let Some(c) = value.chars().find(|c| c.is_control()) {
        return Err(format!(
            "{field} {value:?} holds the control character {c:?}; names are one line of printable text"
        ));
    }
    let count = value.chars().count();
    if count > MAX_NAME {
        return Err(format!(
            "{field} is {count} characters long, more than {MAX_NAME}; give a shorter name"
        ));
    }
    Ok(())
}

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
        assert!(name("`name`", "Si₃N₄, 1200 °C").is_ok());
        assert!(name("`name`", "steel\nhard").unwrap_err().contains("`name`"));
        assert!(name("`name`", &"a".repeat(60_000))
            .unwrap_err()
            .contains("60000 characters"));
    }

    #[test]
    fn work_beyond_the_machine_is_refused_and_threads_are_capped() {
        if memory_room().is_some() {
            let e = memory("a sliding run", 100_000, 100_000, SLIDING_ARRAYS)
                .unwrap_err()
                .to_string();
            assert!(e.contains("GiB") && e.contains("`grid`"), "{e}");
            let e = memory_shortfall("a sliding run", 2048, 2048, SLIDING_ARRAYS);
            assert!(e.as_deref().is_none_or(|e| e.contains("426 MiB")), "{e:?}");
        }
        assert!(memory("a sliding run", 64, 32, SLIDING_ARRAYS).is_ok());
        assert!(threads(0).is_err());
        let slurm = |vars: &'static [(&'static str, &'static str)]| {
            slurm_allocation(move |n| vars.iter().find(|(k, _)| *k == n).map(|(_, v)| v.to_string()))
        };
        assert_eq!(slurm(&[("SLURM_MEM_PER_NODE", "4000")]).unwrap().0, 4000 << 20);
        let (bytes, name) = slurm(&[("SLURM_MEM_PER_CPU", "1000"), ("SLURM_CPUS_ON_NODE", "4")]).unwrap();
        assert!(bytes == 4000 << 20 && name.contains("SLURM_MEM_PER_CPU"), "{name}");
        assert!(slurm(&[]).is_none());
        // 2⁴⁴ MB is 2⁶⁴ bytes: no limit, never 0 bytes.
        for vars in [
            &[("SLURM_MEM_PER_NODE", "17592186044416")][..],
            &[("SLURM_MEM_PER_CPU", "17592186044416"), ("SLURM_CPUS_ON_NODE", "2")][..],
            &[
                ("SLURM_MEM_PER_CPU", "18446744073709551615"),
                ("SLURM_CPUS_ON_NODE", "2"),
            ][..],
        ] {
            let vars: &'static [(&'static str, &'static str)] = vars;
            let (bytes, name) = slurm(vars).unwrap();
            assert!(
                bytes == u64::MAX && name.contains("taken as no limit"),
                "{bytes} {name}"
            );
        }
        assert_eq!(threads(1).unwrap(), (1, None));
        let (t, warning) = threads(1_000_000).unwrap();
        assert!(t < 1_000_000 && warning.is_some());
    }

    #[test]
    fn loads_that_give_no_usable_pressure_are_refused() {
        assert!(load("loads", 1e-3, 1.0, 0.05).is_ok());
        assert!(load("loads", 5e-324, 1.0, 0.05)
            .unwrap_err()
            .to_string()
            .contains("`loads`"));
        let e = load("--load", 1e-310, 1.0, 0.05).unwrap_err().to_string();
        assert!(e.contains("`--load`") && !e.contains("`loads`"), "{e}");
        assert!(load("loads", 1e-3, 1e300 * 1e300, 0.05).is_err());
        assert!(matches!(
            load("loads", 0.06, 1.0, 0.05),
            Err(Error::InfeasibleLoad { .. })
        ));
    }
}
