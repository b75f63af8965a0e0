//! `wearsim bench`: the contact engine's benchmark, all numbers measured in one run on the
//! same surfaces. Paper roughness: λ_l = 16 px, λ_u = min(256 px, N/2), h_rms = 0.005 L, H = 0.7,
//! τ̃ = 0.010 E, F_N = 10⁻³ E L², E = 1, ν = 0.3, default tolerance.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use anyhow::{Context, Result};
use serde_json::json;
use wearsim::config::{RunConfig, SurfaceSource, Units};
use wearsim::fft::{radial_kernel, FftPlan};
use wearsim::junctions::DEFAULT_CONNECTIVITY;
use wearsim::run::SlidingRun;
use wearsim::sliding::{
    SlidingConfig, Timing, DEFAULT_DISTANCE, DEFAULT_RUNNING_IN, DEFAULT_STEP, DEFAULT_STEP_RUNNING_IN,
};
use wearsim::surface::pair_seeds;
use wearsim::{ContactSolver, Material, ModulusConvention, SpectrumParams, Surface};

use crate::out::say;

#[derive(clap::Args)]
pub struct Args {
    /// Grid sizes to time.
    #[arg(long, value_delimiter = ',', default_values_t = vec![512usize, 1024, 2048, 4096])]
    sizes: Vec<usize>,
    /// Repetitions of the FFT round trip (median reported).
    #[arg(long, default_value_t = 7)]
    fft_repeats: usize,
    /// Write the results as JSON here too.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Where the contact solver computes: cpu (or cuda, in builds with a GPU backend).
    #[arg(long, default_value = "cpu")]
    device: wearsim::Device,
    /// Only measure this machine's calibration for the cost estimates of `slide` and `study run`
    /// (about ten seconds), cache it and print it.
    #[arg(long)]
    calibrate: bool,
    /// After each size's warm solve, time the solver's passes one by one (median of
    /// `--fft-repeats`) against a copy pass on the same machine: where an iteration's time goes and
    /// how far each pass is from the memory bandwidth floor.
    #[arg(long)]
    passes: bool,
}

/// Peak resident memory of this process so far (VmHWM), in MiB; None where /proc is missing.
pub fn peak_memory_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024.0)
}

/// A grid size the benchmark can run: at least 64 pixels (the paper's λ_l = 16 px and λ_u up to
/// 256 px) and a valid grid (the memory is checked as for every sliding run, by
/// `SlidingRun::prepare`).
fn check_size(n: usize) -> Result<()> {
    if n < 64 {
        anyhow::bail!(
            "invalid grid size {n} for the benchmark: its surfaces have the paper's λ_l = 16 pixels and λ_u up to 256 \
             pixels, which needs grids of at least 64 pixels"
        );
    }
    wearsim::check::grid(n)?;
    Ok(())
}

/// The benchmark's surface pair (seed 1): paper roughness on an N² grid of side 1.
fn paper_pair(n: usize) -> Result<(Surface, Surface)> {
    check_size(n)?;
    let spectrum = SpectrumParams::paper_roughness(n, 1.0);
    let (s1, s2) = pair_seeds(1);
    Ok((
        Surface::generate(wearsim::Grid::square(n, 1.0)?, &spectrum, s1)?,
        Surface::generate(wearsim::Grid::square(n, 1.0)?, &spectrum, s2)?,
    ))
}

/// The header of the table `bench` prints, one column per number of a row.
fn print_header() {
    say!(
        "{:>5} {:>9} {:>10} {:>6} {:>6} {:>9} {:>10} {:>6} {:>6} {:>9} {:>9} {:>9} {:>9}",
        "N",
        "fft_ms",
        "cold_s",
        "iters",
        "convs",
        "ms/iter",
        "warm_s",
        "iters",
        "convs",
        "iter/fft",
        "conv/fft",
        "warm/cold",
        "peak_MiB"
    );
}

/// The sizes and repeats of `bench`, checked before anything is timed.
fn check_args(args: &Args) -> Result<()> {
    for &n in &args.sizes {
        check_size(n).with_context(|| format!("--sizes {n}"))?;
    }
    if args.fft_repeats == 0 {
        anyhow::bail!("invalid `--fft-repeats 0`: a median needs at least one timing; use 1 or more");
    }
    // The JSON is written after minutes of timing: a folder that is not there fails now, not then.
    if let Some(path) = &args.json {
        let folder = wearsim::io::parent_or_dot(path);
        if !folder.is_dir() {
            anyhow::bail!(
                "--json {}: the folder {} does not exist; create it or give another path",
                path.display(),
                folder.display()
            );
        }
    }
    Ok(())
}

/// With `--passes`, the pass profile at the next offset (the fields a warm step starts from).
fn profile(args: &Args, solver: &mut ContactSolver, flow_pressure: f64) -> Result<Vec<wearsim::contact::PassTiming>> {
    if !args.passes {
        return Ok(Vec::new());
    }
    solver.compose(2)?;
    Ok(solver.profile_passes(flow_pressure, args.fft_repeats))
}

/// The pass profile of one size: each pass's time, the Nx·Ny f64 fields it streams, its
/// bandwidth, and its time over the floor of streaming those fields at the copy pass's bandwidth;
/// then the iterations of a warm step built from them.
fn print_passes(n: usize, timings: &[wearsim::contact::PassTiming]) {
    let field_bytes = (n * n * 8) as f64;
    let per_field = timings[0].seconds / timings[0].streams;
    say!(
        "\npasses at N = {n}: copy pass {:.1} GB/s (a read and a write of one field in {:.2} ms)",
        timings[0].streams * field_bytes / timings[0].seconds / 1e9,
        timings[0].seconds * 1e3
    );
    say!(
        "{:<28} {:>9} {:>7} {:>7} {:>9} {:>7}",
        "pass",
        "ms",
        "fields",
        "GB/s",
        "floor_ms",
        "×floor"
    );
    for t in timings {
        say!(
            "{:<28} {:>9.2} {:>7.1} {:>7.1} {:>9.2} {:>7.1}",
            t.name,
            t.seconds * 1e3,
            t.streams,
            t.streams * field_bytes / t.seconds / 1e9,
            t.streams * per_field * 1e3,
            t.seconds / (t.streams * per_field)
        );
    }
    for (what, pick) in [
        (
            "a conjugate-gradient iteration",
            (|t: &wearsim::contact::PassTiming| t.per_cg_iteration) as fn(&_) -> f64,
        ),
        ("an iteration that changes the sets", |t| t.per_set_change),
    ] {
        let (seconds, streams) = timings.iter().fold((0.0, 0.0), |(s, f), t| {
            (s + pick(t) * t.seconds, f + pick(t) * t.streams)
        });
        say!(
            "{what}: {:.1} ms, {streams:.0} fields streamed ({:.1} ms at the copy bandwidth, ×{:.1}; {:.1} FFT round trips)",
            seconds * 1e3,
            streams * per_field * 1e3,
            seconds / (streams * per_field),
            seconds / timings[1].seconds
        );
    }
}

/// The median wall time of `repeats` FFT round trips (r2c + c2r with the kernel multiply fused) on
/// the grid of `top`: the floor of one solver iteration.
fn fft_seconds(top: &Surface, repeats: usize) -> f64 {
    let (nx, ny) = (top.nx(), top.ny());
    let mut plan = FftPlan::new(nx, ny);
    let kernel = radial_kernel(nx, ny, |qx, qy| 1.0 / (1.0 + qx * qx + qy * qy));
    let mut out = vec![0.0; nx * ny];
    wearsim::contact::median_seconds(repeats, || plan.convolve(top.heights(), &kernel, &mut out))
}

pub fn run(args: &Args) -> Result<()> {
    if args.calibrate {
        return super::cost::recalibrate();
    }
    check_args(args)?;
    let threads = rayon::current_num_threads();
    say!(
        "wearsim {} bench, {threads} threads; paper roughness, τ̃ = 0.010 E, F_N = 1e-3 E L²",
        wearsim::VERSION
    );
    print_header();
    let mut rows = Vec::new();
    let mut profiles = Vec::new();
    let material = Material::new(1.0, 0.3, 0.010, vec![], 3.0)?;
    let e_star = material.effective_modulus(ModulusConvention::HalfSpace);
    for &n in &args.sizes {
        let (top, bottom) = paper_pair(n)?;

        let fft_s = fft_seconds(&top, args.fft_repeats);

        // As a sliding run solves: the fields stay in the solver, composed there, warm-started.
        let grid = wearsim::Grid::square(n, 1.0)?;
        let mut solver = ContactSolver::on_device(args.device, grid, e_star, wearsim::Boundary::Periodic)?;
        solver.bind_surfaces(Arc::new(top), Arc::new(bottom))?;
        solver.compose(0)?;
        let t = Instant::now();
        let cold = solver.solve_in_place(1e-3, material.flow_pressure())?;
        let cold_s = t.elapsed().as_secs_f64();
        solver.compose(1)?;
        let t = Instant::now();
        let warm = solver.solve_in_place(1e-3, material.flow_pressure())?;
        let warm_s = t.elapsed().as_secs_f64();
        let per_iter = cold_s / cold.iterations.max(1) as f64;
        let per_conv = cold_s / cold.convolutions.max(1) as f64;
        let peak = peak_memory_mib().unwrap_or(f64::NAN);
        // After the peak is read: the profile's copy buffers are not the solver's memory.
        let passes = profile(args, &mut solver, material.flow_pressure())?;
        say!(
            "{:>5} {:>9.2} {:>10.3} {:>6} {:>6} {:>9.2} {:>10.3} {:>6} {:>6} {:>9.2} {:>9.2} {:>9.2} {:>9.0}",
            n,
            fft_s * 1e3,
            cold_s,
            cold.iterations,
            cold.convolutions,
            per_iter * 1e3,
            warm_s,
            warm.iterations,
            warm.convolutions,
            per_iter / fft_s,
            per_conv / fft_s,
            warm.iterations as f64 / cold.iterations.max(1) as f64,
            peak
        );
        rows.push(json!({
            "n": n, "fft_round_trip_s": fft_s,
            "cold": {"seconds": cold_s, "iterations": cold.iterations, "convolutions": cold.convolutions, "residual": cold.residual, "contact_pixels": cold.contact_pixels},
            "warm_after_one_pixel": {"seconds": warm_s, "iterations": warm.iterations, "convolutions": warm.convolutions, "residual": warm.residual},
            "seconds_per_iteration_over_fft": per_iter / fft_s,
            "peak_memory_mib": peak,
            "passes": passes.iter().map(|p| json!({
                "pass": p.name, "seconds": p.seconds, "fields_streamed": p.streams,
                "per_cg_iteration": p.per_cg_iteration, "per_set_change": p.per_set_change,
            })).collect::<Vec<_>>(),
        }));
        profiles.push((n, passes));
    }
    for (n, timings) in profiles.iter().filter(|(_, t)| !t.is_empty()) {
        print_passes(*n, timings);
    }
    if let Some(path) = &args.json {
        let doc = json!({"provenance": wearsim::output::Provenance::current(), "threads": threads, "tolerance": wearsim::contact::DEFAULT_TOLERANCE, "rows": rows});
        wearsim::io::write_json(path, &doc)?;
    }
    Ok(())
}

/// `wearsim bench-slide`: a full sliding run at N (paper roughness, four loads, four fracture
/// energies, the paper's schedule) with its time per step split into solve / labelling /
/// bookkeeping; then warm steps at `--warm-n`, extrapolated to the paper's schedule.
#[derive(clap::Args)]
pub struct SlideArgs {
    /// Grid of the full sliding run.
    #[arg(long, default_value_t = 512)]
    n: usize,
    /// Grid of the warm-step timing (0 to skip).
    #[arg(long, default_value_t = 4096)]
    warm_n: usize,
    /// Warm one-pixel steps timed at `--warm-n`.
    #[arg(long, default_value_t = 10)]
    warm_steps: usize,
    /// Where the contact solver computes: cpu (or cuda, in builds with a GPU backend).
    #[arg(long, default_value = "cpu")]
    device: wearsim::Device,
    /// After the warm steps, time the static estimate (`wearsim estimate`) of the same load at
    /// `--warm-n` with this many static maps, against the sliding load extrapolated from the warm
    /// steps (0 to skip).
    #[arg(long, default_value_t = 8)]
    estimate_samples: usize,
}

pub fn run_slide(args: &SlideArgs) -> Result<()> {
    check_size(args.n).context("--n")?;
    if args.warm_n > 0 {
        check_size(args.warm_n).context("--warm-n")?;
    }
    let threads = rayon::current_num_threads();
    say!("wearsim {} bench-slide, {threads} threads", wearsim::VERSION);
    // Both particle rules on the same runs: the paper's, then the rule of interacting junctions,
    // whose cost beyond the paper's is the shear energies of the junctions it tries to join.
    let rules = [wearsim::wear::OVERLAP, wearsim::wear::INTERACTING];
    let mut full = Vec::new();
    for rule in rules {
        full.push(full_run(args, rule.into())?);
    }
    // The solves are the same in both runs: the rule's own cost is its labelling and bookkeeping
    // beyond the paper's rule, timed step by step; the ratio of whole steps also carries the noise
    // of two solves of the same contact.
    let (a, b) = (&full[0].1, &full[1].1);
    say!(
        "  interacting / overlap at N = {}: whole step {:.3}; the rule's added labelling + bookkeeping {:.3} ms/step = {:.2} % of the paper's step",
        args.n,
        b.whole / a.whole,
        (b.rule - a.rule) * 1e3,
        (b.rule - a.rule) / a.whole * 100.0
    );
    if args.warm_n > 0 && args.warm_steps > 0 {
        let mut warm = Vec::new();
        for (i, (config, _)) in full.iter().enumerate() {
            // The static estimate uses no particle rule: timed once, beside the paper's rule.
            warm.push(warm_steps(args, config, i == 0)?);
        }
        say!(
            "  interacting / overlap at N = {}: whole warm step {:.3}; the rule's added labelling + bookkeeping {:.1} ms/step = {:.2} % of the paper's step",
            args.warm_n,
            warm[1].whole / warm[0].whole,
            (warm[1].rule - warm[0].rule) * 1e3,
            (warm[1].rule - warm[0].rule) / warm[0].whole * 100.0
        );
    }
    Ok(())
}

/// Seconds per step: the whole step, and its labelling and bookkeeping (what a particle rule adds to).
struct PerStep {
    whole: f64,
    rule: f64,
}

/// The full sliding run at `--n` with particle rule `rule`: its configuration and time per step.
fn full_run(args: &SlideArgs, rule: wearsim::wear::ParticleRuleSpec) -> Result<(RunConfig, PerStep)> {
    let material = Material::new(1.0, 0.3, 0.010, vec![0.25e-6, 0.5e-6, 0.75e-6, 1.0e-6], 3.0)?;
    let sliding = SlidingConfig::new(
        vec![2.5e-4, 5e-4, 1e-3, 2e-3],
        DEFAULT_DISTANCE,
        DEFAULT_RUNNING_IN,
        DEFAULT_STEP_RUNNING_IN,
        DEFAULT_STEP,
        Some(args.n),
    )?
    .with_particle_rule(rule.clone());
    // The benchmark's surface pair (`paper_pair`) as a run: generated, seed 1.
    let config = RunConfig::builder(
        SurfaceSource::Generated {
            grid: wearsim::Grid::square(args.n, 1.0)?,
            spectrum: SpectrumParams::paper_roughness(args.n, 1.0),
            seed: 1,
        },
        material,
    )
    .units(Units::Reduced)
    .modulus(ModulusConvention::HalfSpace)
    .connectivity(DEFAULT_CONNECTIVITY)
    .device(args.device)
    .sliding(sliding)
    .stopping(wearsim::contact::SLIDING_STOPPING)
    .model(wearsim::model::WearModel::Sliding)
    .build()?;
    let material = &config.material;
    let prepared = SlidingRun::prepare(&config)?;
    let sliding = prepared.sliding();
    let t = Instant::now();
    let runs = prepared.run(|_| {})?.runs;
    let total = t.elapsed().as_secs_f64();
    let steps: usize = runs.iter().map(|r| r.steps.len()).sum();
    let (solve, label, book) = runs.iter().fold((0.0, 0.0, 0.0), |a, r| {
        (
            a.0 + r.timing.solve,
            a.1 + r.timing.labelling,
            a.2 + r.timing.bookkeeping,
        )
    });
    let iterations: usize = runs.iter().map(|r| r.total_iterations).sum();
    say!(
        "particle rule {rule}: sliding run N = {}: {} loads × {} offsets × {} fracture energies, {steps} contact solves in {total:.2} s ({:.2} ms/step; {:.1} iterations/step)",
        args.n,
        sliding.loads.len(),
        sliding.offsets(args.n).len(),
        material.fracture_energies.len(),
        total / steps as f64 * 1e3,
        iterations as f64 / steps as f64
    );
    say!(
        "  per step: solve {:.3} ms, labelling {:.3} ms, bookkeeping {:.3} ms; labelling + bookkeeping = {:.2} % of a step; peak memory {:.0} MiB",
        solve / steps as f64 * 1e3,
        label / steps as f64 * 1e3,
        book / steps as f64 * 1e3,
        (label + book) / (solve + label + book) * 100.0,
        peak_memory_mib().unwrap_or(f64::NAN)
    );
    let per_step = PerStep {
        whole: total / steps as f64,
        rule: (label + book) / steps as f64,
    };
    Ok((config, per_step))
}

/// Warm one-pixel steps of a sliding run at `--warm-n` (F_N = 1e-3, the full run's material and
/// particle rule), each
/// a whole step of the run (solve, labelling, the particle rules and static model of every 𝒢),
/// extrapolated to the paper's schedule. Gives the time per warm step.
fn warm_steps(args: &SlideArgs, full: &RunConfig, with_estimate: bool) -> Result<PerStep> {
    let (n, rule) = (
        args.warm_n,
        &full.sliding.as_ref().expect("a sliding run").particle_rule,
    );
    // One-pixel steps from s = 0 (no running-in), as the fit window slides, under the full run's rule.
    let sliding = SlidingConfig::new(
        vec![1e-3],
        DEFAULT_DISTANCE,
        0.0,
        DEFAULT_STEP_RUNNING_IN,
        DEFAULT_STEP,
        Some(n),
    )?
    .with_particle_rule(rule.clone());
    let config = full
        .to_builder()
        .surfaces(SurfaceSource::Generated {
            grid: wearsim::Grid::square(n, 1.0)?,
            spectrum: SpectrumParams::paper_roughness(n, 1.0),
            seed: 1,
        })
        .sliding(sliding)
        .build()?;
    let mut slide = SlidingRun::prepare(&config)?.start()?;
    slide.step()?; // s = 0: the cold solve, not timed
    let (mut step_s, mut split, mut iters) = (0.0, Timing::default(), 0);
    for _ in 0..args.warm_steps {
        let t = Instant::now();
        let view = slide
            .step()?
            .context("the schedule has fewer steps than --warm-steps")?;
        step_s += t.elapsed().as_secs_f64();
        split.solve += view.timing.solve;
        split.labelling += view.timing.labelling;
        split.bookkeeping += view.timing.bookkeeping;
        iters += view.record.iterations;
    }
    let k = args.warm_steps as f64;
    let per_step = step_s / k;
    let offsets = SlidingConfig::new(
        vec![1e-3],
        DEFAULT_DISTANCE,
        DEFAULT_RUNNING_IN,
        DEFAULT_STEP_RUNNING_IN,
        DEFAULT_STEP,
        Some(n),
    )?
    .offsets(n)
    .len();
    say!(
        "particle rule {rule}: warm steps at N = {n} (F_N = 1e-3): {:.3} s/step ({:.1} iterations; solve {:.3} s, labelling {:.1} ms, \
         bookkeeping {:.1} ms); × {offsets} offsets = {:.1} min per load; peak memory {:.0} MiB",
        per_step,
        iters as f64 / k,
        split.solve / k,
        split.labelling / k * 1e3,
        split.bookkeeping / k * 1e3,
        per_step * offsets as f64 / 60.0,
        peak_memory_mib().unwrap_or(f64::NAN),
    );
    // The sliding run's fields are freed before the estimate, so that the peak is either's.
    drop(slide);
    if with_estimate && args.estimate_samples > 0 {
        time_estimate(args, &config, per_step * offsets as f64)?;
    }
    Ok(PerStep {
        whole: per_step,
        rule: (split.labelling + split.bookkeeping) / k,
    })
}

/// The static estimate of the warm steps' load at `--warm-n` (`config`), timed against the sliding
/// load's `sliding_load` seconds.
fn time_estimate(args: &SlideArgs, config: &RunConfig, sliding_load: f64) -> Result<()> {
    let n = args.warm_n;
    // The same load of the same pair, estimated as a study job of it is: its static maps cold.
    let sampling = wearsim::estimate::Sampling::of(Some(args.estimate_samples)).context("--estimate-samples")?;
    let t = Instant::now();
    let outcome = SlidingRun::prepare(config)?.estimate(sampling, &wearsim::estimate::CALIBRATION, |_, _| {})?;
    let seconds = t.elapsed().as_secs_f64();
    say!(
        "static estimate at N = {n} (F_N = 1e-3, {} static maps, surfaces made included): {seconds:.1} s per load; \
         sliding / estimate = {:.0}× per load; N* = {:.1} at d* = {:.1} px",
        outcome.samples,
        sliding_load / seconds,
        outcome.loads[0].results[0].critical_junctions_mean,
        outcome.loads[0].results[0].critical_diameter * n as f64,
    );
    Ok(())
}
