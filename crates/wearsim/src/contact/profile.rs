//! The solver's passes timed one by one against the machine's memory bandwidth (`wearsim bench
//! --passes`): where an iteration's time goes, and how far each pass is from streaming its fields
//! through memory once.
//!
//! Each pass is timed on the fields a real solve left (the bound surfaces slid one pixel after a
//! solve), so that its branches see real contact maps. Its bytes are the Nx·Ny fields of f64 it
//! reads and writes ("streams"; the transposed half spectrum of a real FFT counts as one field),
//! as the CPU backend's passes are written; a copy pass over one field measures the bandwidth
//! floor on the same machine in the same run.

use std::time::Instant;

use rayon::prelude::*;

use super::backend::ContactBackend;

/// One pass of the solver, timed.
#[derive(Debug, Clone, Copy)]
pub struct PassTiming {
    /// What the pass does, as `ContactBackend` names it.
    pub name: &'static str,
    /// Median seconds per call over the repeats.
    pub seconds: f64,
    /// Nx·Ny fields of f64 read plus written (module documentation), as the passes stream them
    /// with the periodic operator (a free boundary's zero-padded transforms stream four times
    /// as much).
    pub streams: f64,
    /// Calls per iteration of a warm sliding step that changes no set (a conjugate-gradient step:
    /// the curvature, then the rest of its convolution in `advance`; with the pair sum, that and
    /// the forward half, timed as `curvature`), and per iteration that changes the sets (the
    /// curvature, by pairs where the backend takes them, the update, a fresh 𝒦p, the load balance
    /// by scaling, whose sums the update carries); 0 for the reference passes and the set-up's
    /// passes.
    pub per_cg_iteration: f64,
    pub per_set_change: f64,
}

/// The timing rule of the benchmarks (`wearsim bench`): the median of `repeats` (at least one)
/// wall times of `f`, after one untimed call.
pub fn median_seconds(repeats: usize, mut f: impl FnMut()) -> f64 {
    f();
    median(
        (0..repeats.max(1))
            .map(|_| {
                let t = Instant::now();
                f();
                t.elapsed().as_secs_f64()
            })
            .collect(),
    )
}

fn median(mut times: Vec<f64>) -> f64 {
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

/// The two reference timings: a copy of one field (the bandwidth floor) and an FFT round trip.
fn reference_passes(b: &mut dyn ContactBackend, row: usize, repeats: usize) -> (f64, f64) {
    let source: Vec<f64> = b.pressure().to_vec();
    let mut sink = vec![0.0; source.len()];
    let copy = median_seconds(repeats, || {
        sink.par_chunks_mut(row)
            .zip(source.par_chunks(row))
            .for_each(|(d, s)| d.copy_from_slice(s))
    });
    let fft = median_seconds(repeats, || b.apply_influence(&source, &mut sink));
    (copy, fft)
}

/// The curvature by the forward transform (its value and time) and by the pair sum, where the
/// backend has one and the free pixels are few (its time; no transform).
fn curvatures(b: &mut dyn ContactBackend, shift: f64, repeats: usize) -> (f64, f64, Option<f64>) {
    let curvature = b.curvature(shift);
    let form = median_seconds(repeats, || {
        std::hint::black_box(b.curvature(shift));
    });
    let direct = b.direct_curvature(shift).map(|_| {
        median_seconds(repeats, || {
            std::hint::black_box(b.direct_curvature(shift));
        })
    });
    (curvature, form, direct)
}

/// The pass profile of a solver's backend (`ContactSolver::profile_passes`), whose rows hold
/// `row` pixels, under the law bound to it.
pub(super) fn passes(b: &mut dyn ContactBackend, row: usize, repeats: usize) -> Vec<PassTiming> {
    let (copy, fft) = reference_passes(b, row, repeats);
    let stats = b.displacement_and_stats(0.0);
    let mean = stats.mean_gap(0.0);
    let displacement = median_seconds(repeats, || {
        std::hint::black_box(b.displacement_and_stats(mean));
    });
    let (sum_t, sum_dt) = b.direction(mean, 0.0);
    let direction = median_seconds(repeats, || {
        std::hint::black_box(b.direction(mean, 0.0));
    });
    let shift = if stats.n_free > 0.0 { sum_t / stats.n_free } else { 0.0 };
    let (curvature, form, direct) = curvatures(b, shift, repeats);
    let tau = if curvature > 0.0 && sum_dt > 0.0 {
        sum_dt / curvature / b.response_scale()
    } else {
        0.0
    };
    // Each update (which keeps a copy of p for an undo: 4 fields read, 2 written) is undone,
    // untimed, as the solver undoes a rejected step.
    let update = median(
        (0..=repeats.max(1))
            .map(|_| {
                let t = Instant::now();
                std::hint::black_box(b.update(mean, tau, shift));
                let seconds = t.elapsed().as_secs_f64();
                b.keep_displacement();
                b.undo();
                seconds
            })
            .skip(1)
            .collect(),
    );
    // The rest of the convolution from the transform a curvature (untimed) left; it moves u,
    // which the next solve recomputes (its set-up does not reuse u after a profile).
    let advance = median(
        (0..=repeats.max(1))
            .map(|_| {
                b.curvature(shift);
                let t = Instant::now();
                std::hint::black_box(b.advance(mean, tau, shift, true));
                t.elapsed().as_secs_f64()
            })
            .skip(1)
            .collect(),
    );
    let load_sums = median_seconds(repeats, || {
        std::hint::black_box(b.load_sums());
    });
    let scale = median_seconds(repeats, || b.scale(1.0, false));
    let contact_map = median_seconds(repeats, || {
        std::hint::black_box(b.contact_map());
    });
    let pass = |name, seconds, streams, per_cg_iteration, per_set_change| PassTiming {
        name,
        seconds,
        streams,
        per_cg_iteration,
        per_set_change,
    };
    // With the pair sum: a CG step's whole convolution in `advance`, a set change's none.
    let mut timings = vec![
        pass("copy (reference)", copy, 2.0, 0.0, 0.0),
        pass("fft round trip (reference)", fft, 6.0, 0.0, 0.0),
        pass("direction", direction, 5.0, 1.0, 1.0),
        pass("curvature", form, 4.0, 1.0, if direct.is_some() { 0.0 } else { 1.0 }),
        pass("update", update, 6.0, 1.0, 1.0),
        pass("advance", advance, 8.0, 1.0, 0.0),
        pass("displacement_and_stats", displacement, 8.0, 0.0, 1.0),
        pass("load_sums", load_sums, 1.0, 0.0, 0.0),
        pass("scale", scale, 2.0, 0.0, 1.0),
        pass("contact_map", contact_map, 1.0, 0.0, 0.0),
    ];
    if let Some(seconds) = direct {
        // It reads the rows of t that hold free pixels: at most one field.
        timings.insert(4, pass("direct_curvature", seconds, 1.0, 1.0, 1.0));
    }
    timings
}
