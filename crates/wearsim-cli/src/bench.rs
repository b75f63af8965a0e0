//! `wearsim bench`: the contact engine's benchmark (issue 2), all numbers measured in one run on the
//! same surfaces. Paper roughness: λ_l = 16 px, λ_u = min(256 px, N/2), h_rms = 0.005 L, H = 0.7,
//! τ̃ = 0.010 E, F_N = 10⁻³ E L², E = 1, ν = 0.3, default tolerance.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::Result;
use serde_json::json;
use wearsim::fft::{radial_kernel, FftPlan};
use wearsim::surface::pair_seeds;
use wearsim::{composite_heights, ContactSolver, Generation, Material, ModulusConvention, SpectrumParams, Surface};

#[derive(clap::Args)]
pub struct BenchArgs {
    /// Grid sizes to time.
    #[arg(long, value_delimiter = ',', default_values_t = vec![512usize, 1024, 2048, 4096])]
    sizes: Vec<usize>,
    /// Repetitions of the FFT round trip (median reported).
    #[arg(long, default_value_t = 7)]
    fft_repeats: usize,
    /// Write the results as JSON here too.
    #[arg(long)]
    json: Option<PathBuf>,
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Peak resident memory of this process so far (VmHWM), in MiB; None where /proc is missing.
pub fn peak_memory_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024.0)
}

pub fn run(args: &BenchArgs) -> Result<()> {
    let threads = rayon::current_num_threads();
    println!("wearsim {} bench, {threads} threads; paper roughness, τ̃ = 0.010 E, F_N = 1e-3 E L²", wearsim::VERSION);
    println!(
        "{:>5} {:>9} {:>10} {:>6} {:>6} {:>9} {:>10} {:>6} {:>6} {:>9} {:>9} {:>9} {:>9}",
        "N", "fft_ms", "cold_s", "iters", "convs", "ms/iter", "warm_s", "iters", "convs", "iter/fft", "conv/fft", "warm/cold", "peak_MiB"
    );
    let mut rows = Vec::new();
    let material = Material::new(1.0, 0.3, 0.010, vec![], 3.0)?;
    let e_star = material.effective_modulus(ModulusConvention::HalfSpace);
    for &n in &args.sizes {
        let dx = 1.0 / n as f64;
        let spectrum = SpectrumParams {
            hurst: 0.7,
            lambda_lower: 16.0 * dx,
            lambda_upper: (256.0f64).min(n as f64 / 2.0) * dx,
            rms_height: 0.005,
            generation: Generation::RandomPhase,
        };
        let (s1, s2) = pair_seeds(1);
        let top = Surface::generate(n, 1.0, &spectrum, s1)?;
        let bottom = Surface::generate(n, 1.0, &spectrum, s2)?;

        // FFT round trip (r2c + c2r with the kernel multiply fused), the floor of one iteration.
        let mut plan = FftPlan::new(n);
        let kernel = radial_kernel(n, |qx, qy| 1.0 / (1.0 + qx * qx + qy * qy));
        let mut out = vec![0.0; n * n];
        plan.convolve(top.heights(), &kernel, &mut out);
        let fft_s = median(
            (0..args.fft_repeats)
                .map(|_| {
                    let t = Instant::now();
                    plan.convolve(top.heights(), &kernel, &mut out);
                    t.elapsed().as_secs_f64()
                })
                .collect(),
        );
        drop((plan, kernel, out));

        let mut solver = ContactSolver::new(n, 1.0, e_star)?;
        let mut heights = vec![0.0; n * n];
        composite_heights(&top, &bottom, 0, &mut heights);
        let mut pressure = vec![0.0; n * n];
        let t = Instant::now();
        let cold = solver.solve(&heights, 1e-3, material.flow_pressure(), &mut pressure)?;
        let cold_s = t.elapsed().as_secs_f64();
        composite_heights(&top, &bottom, 1, &mut heights);
        let t = Instant::now();
        let warm = solver.solve(&heights, 1e-3, material.flow_pressure(), &mut pressure)?;
        let warm_s = t.elapsed().as_secs_f64();
        let per_iter = cold_s / cold.iterations.max(1) as f64;
        let per_conv = cold_s / cold.convolutions.max(1) as f64;
        let peak = peak_memory_mib().unwrap_or(f64::NAN);
        println!(
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
        }));
    }
    if let Some(path) = &args.json {
        let doc = json!({"software": format!("wearsim {}", wearsim::VERSION), "threads": threads, "tolerance": wearsim::contact::DEFAULT_TOLERANCE, "rows": rows});
        wearsim::output::write_text(path, &serde_json::to_string_pretty(&doc)?)?;
    }
    Ok(())
}
