//! The CPU backend: the fields in host memory, the passes as rayon loops over rows with per-row
//! partials combined in row order (results independent of the thread count), 𝒦 by the real FFT of
//! [`crate::influence`].

use rayon::prelude::*;

use std::sync::Arc;

use super::backend::{
    ContactBackend, HeightStats, LoadSums, Stats, SurfaceLaw, Update, LOAD_CHUNK, SETTLED_CHANGE_FACTOR,
};
use crate::error::Result;
use crate::fft::zeroed_buffer;
use crate::grid::Grid;
use crate::influence::{self, Boundary, Influence, PairForm};
use crate::surface::Surface;

/// Arrays of Nx·Ny doubles the CPU backend holds besides its influence operator: h, p, u, t, the
/// previous p and the spare u (6), rounding for the per-row partials and FFT rows, and with a
/// periodic operator the real-space kernel of its [`PairForm`] (a quarter of the offsets).
pub(crate) fn arrays(boundary: Boundary) -> f64 {
    let pair_form = if boundary == Boundary::Periodic { 0.25 } else { 0.0 };
    7.5 + influence::arrays(boundary) + pair_form
}

/// The fields of a solve in host memory, the influence operator and the partials of every
/// reduction, all made once: no pass allocates.
pub(crate) struct CpuBackend {
    ny: usize,
    /// 𝒦, periodic or with a free boundary.
    influence: Influence,
    heights: Vec<f64>,
    pressure: Vec<f64>,
    u: Vec<f64>,
    t: Vec<f64>,
    /// p before the last step, to undo a step that raised the objective.
    p_old: Vec<f64>,
    /// Spare displacement buffer: keeps the u of a step's start while 𝒦p is computed after a
    /// step off the CG line (for an undo); receives the new u in `advance`.
    u_alt: Vec<f64>,
    /// The surfaces of a sliding run, shared with the caller (no copy).
    surfaces: Option<(Arc<Surface>, Arc<Surface>)>,
    /// The law at the surface ([`ContactBackend::bind_law`]), elastic until one is bound.
    law: SurfaceLaw,
    /// The contact map, one bit per pixel.
    bits: Vec<u64>,
    stats: Vec<Stats>,
    load_rows: Vec<LoadSums>,
    sums: Vec<[f64; 2]>,
    row_partials: Vec<f64>,
    /// Per-row partials of the height statistics: Σ(h − h₀), Σ(h − h₀)², max, all finite; taken
    /// by `compose` for the heights it writes (`height_rows_ready`).
    height_rows: Vec<(f64, f64, f64, bool)>,
    height_rows_ready: bool,
    /// Per-row partials of the initial guess's tests: all finite and ≥ 0, any > 0, all ≤ p_m.
    guess_rows: Vec<(bool, bool, bool)>,
    /// Per-chunk partials of the load sums and of the scaled load ([`LOAD_CHUNK`] pixels each).
    load_chunks: Vec<LoadSums>,
    scaled_chunks: Vec<(f64, f64)>,
    /// Rows per rayon task in the element-wise passes.
    min_len: usize,
    /// [`ContactBackend::response_scale`].
    response_scale: f64,
    /// The kernel in real space, for [`ContactBackend::direct_curvature`] (periodic only).
    pair_form: Option<PairForm>,
    /// Per row, the pixels where the last `direction` left t ≠ 0 (the free pixels).
    free_rows: Vec<u32>,
    /// Those pixels (row, column, t_f) in row-major order, and the partials of their pair sum;
    /// both grow to the largest free set seen, then are reused.
    free_points: Vec<(u32, u32, f64)>,
    pair_partials: Vec<f64>,
}

impl CpuBackend {
    pub fn new(grid: Grid, effective_modulus: f64, boundary: Boundary) -> Result<Self> {
        let (nx, ny) = (grid.nx(), grid.ny());
        let mut influence = Influence::new(grid, effective_modulus, boundary)?;
        let response_scale = 2f64.powi(influence.self_influence().log2().floor() as i32);
        let (mut u, mut t) = (zeroed_buffer(nx * ny), zeroed_buffer(nx * ny));
        let pair_form = PairForm::new(&mut influence, 1.0 / response_scale, &mut t, &mut u);
        Ok(Self {
            ny,
            influence,
            heights: zeroed_buffer(nx * ny),
            pressure: zeroed_buffer(nx * ny),
            u,
            t,
            p_old: zeroed_buffer(nx * ny),
            u_alt: zeroed_buffer(nx * ny),
            surfaces: None,
            law: SurfaceLaw::Elastic,
            bits: vec![0; (nx * ny).div_ceil(64)],
            stats: vec![Stats::default(); nx],
            load_rows: vec![LoadSums::default(); nx],
            sums: vec![[0.0; 2]; nx],
            row_partials: vec![0.0; nx],
            height_rows: vec![(0.0, 0.0, 0.0, true); nx],
            height_rows_ready: false,
            guess_rows: vec![(true, false, true); nx],
            load_chunks: vec![LoadSums::default(); (nx * ny).div_ceil(LOAD_CHUNK)],
            scaled_chunks: vec![(0.0, 0.0); (nx * ny).div_ceil(LOAD_CHUNK)],
            min_len: (8192 / ny).max(1),
            response_scale,
            pair_form,
            free_rows: vec![0; nx],
            free_points: Vec::new(),
            pair_partials: Vec::new(),
        })
    }
}

impl ContactBackend for CpuBackend {
    fn boundary(&self) -> Boundary {
        self.influence.boundary()
    }

    fn self_influence(&self) -> f64 {
        self.influence.self_influence()
    }

    fn response_scale(&self) -> f64 {
        self.response_scale
    }

    fn apply_influence(&mut self, input: &[f64], out: &mut [f64]) {
        self.influence.apply(input, out);
    }

    fn write_heights(&mut self, fill: &mut dyn FnMut(&mut [f64])) {
        fill(&mut self.heights);
        self.height_rows_ready = false;
    }

    fn write_pressure(&mut self, fill: &mut dyn FnMut(&mut [f64])) {
        fill(&mut self.pressure);
    }

    fn bind_surfaces(&mut self, top: Arc<Surface>, bottom: Arc<Surface>) {
        self.surfaces = Some((top, bottom));
    }

    fn bind_law(&mut self, law: SurfaceLaw) {
        self.law = law;
    }

    /// [`composite_heights`](crate::surface::composite_heights), with the row partials of
    /// [`ContactBackend::height_stats`] taken in the same pass (one pass over h fewer per step).
    fn compose(&mut self, offset: usize) {
        let (top, bottom) = self.surfaces.as_ref().expect("surfaces bound before composing");
        let (nx, ny) = (top.nx(), top.ny());
        let (t, b) = (top.heights(), bottom.heights());
        let source = |i: usize| (i + nx - offset % nx) % nx;
        let h0 = b[0] + t[source(0) * ny];
        self.heights
            .par_chunks_mut(ny)
            .zip(self.height_rows.par_iter_mut())
            .enumerate()
            .for_each(|(i, (row, acc))| {
                let src = source(i);
                for ((o, &bv), &tv) in row
                    .iter_mut()
                    .zip(&b[i * ny..(i + 1) * ny])
                    .zip(&t[src * ny..(src + 1) * ny])
                {
                    *o = bv + tv;
                }
                *acc = height_row(row, h0);
            });
        self.height_rows_ready = true;
    }

    fn pressure(&mut self) -> &[f64] {
        &self.pressure
    }

    /// 64 pixels per word, in parallel.
    fn contact_map(&mut self) -> &[u64] {
        self.bits
            .par_iter_mut()
            .with_min_len(64)
            .zip(self.pressure.par_chunks(64))
            .for_each(|(word, p)| {
                *word = p.iter().enumerate().fold(0, |w, (b, &p)| w | (u64::from(p > 0.0) << b));
            });
        &self.bits
    }

    /// One deterministic parallel pass (none after [`ContactBackend::compose`], which took the
    /// row partials): Σ(h − h₀), Σ(h − h₀)², max, finite.
    fn height_stats(&mut self) -> HeightStats {
        let heights = &self.heights;
        let h0 = heights[0];
        if !self.height_rows_ready {
            self.height_rows
                .par_iter_mut()
                .zip(heights.par_chunks(self.ny))
                .for_each(|(acc, row)| *acc = height_row(row, h0));
        }
        let (sum, sum_sq, max, finite) = self
            .height_rows
            .iter()
            .fold((0.0, 0.0, f64::NEG_INFINITY, true), |a, b| {
                (a.0 + b.0, a.1 + b.1, a.2.max(b.2), a.3 && b.3)
            });
        let not_finite = if finite && h0.is_finite() {
            None
        } else {
            let k = heights.iter().position(|h| !h.is_finite()).unwrap_or(0);
            Some((k, heights[k]))
        };
        HeightStats {
            sum,
            sum_sq,
            max,
            not_finite,
        }
    }

    /// One pass over rows for the tests, one to set p (none when p stays as it is).
    fn initial_guess(&mut self, mean_pressure: f64) -> bool {
        let (n, pm) = (self.ny, self.law.flow_pressure());
        self.guess_rows
            .par_iter_mut()
            .with_min_len(self.min_len)
            .zip(self.pressure.par_chunks(n))
            .for_each(|(acc, row)| {
                *acc = row.iter().fold((true, false, true), |(valid, any, below), &p| {
                    (valid && p.is_finite() && p >= 0.0, any || p > 0.0, below && p <= pm)
                });
            });
        let usable = self.guess_rows.iter().all(|r| r.0) && self.guess_rows.iter().any(|r| r.1);
        if usable && self.guess_rows.iter().all(|r| r.2) {
            return true;
        }
        self.pressure
            .par_chunks_mut(n)
            .with_min_len(self.min_len)
            .for_each(|row| {
                for p in row {
                    *p = if usable { p.min(pm) } else { mean_pressure };
                }
            });
        false
    }

    fn load_sums(&mut self) -> LoadSums {
        let law = self.law;
        self.load_chunks
            .par_iter_mut()
            .zip(self.pressure.par_chunks(LOAD_CHUNK))
            .with_min_len(self.min_len)
            .for_each(|(acc, c)| {
                let mut s = LoadSums::default();
                for &p in c {
                    s.add(p, law);
                }
                *acc = s;
            });
        self.load_chunks
            .iter()
            .fold(LoadSums::default(), |a, &b| LoadSums::merge(a, b))
    }

    fn saturate_contact(&mut self) {
        let pm = self.law.flow_pressure();
        self.pressure
            .par_chunks_mut(self.ny)
            .with_min_len(self.min_len)
            .for_each(|row| {
                for p in row.iter_mut().filter(|p| **p > 0.0) {
                    *p = pm;
                }
            });
    }

    fn scaled_load(&mut self, s: f64, scale_plastic: bool) -> (f64, f64) {
        let pm = self.law.flow_pressure();
        let movable_pixel = |p: f64| p > 0.0 && (scale_plastic || p < pm);
        self.scaled_chunks
            .par_iter_mut()
            .zip(self.pressure.par_chunks(LOAD_CHUNK))
            .with_min_len(self.min_len)
            .for_each(|(acc, c)| {
                let (mut f, mut df) = (0.0, 0.0);
                for &p in c {
                    if movable_pixel(p) {
                        let v = s * p;
                        if v >= pm {
                            f += pm;
                        } else {
                            f += v;
                            df += p;
                        }
                    }
                }
                *acc = (f, df);
            });
        self.scaled_chunks
            .iter()
            .fold((0.0, 0.0), |(a, b), &(f, df)| (a + f, b + df))
    }

    fn scale(&mut self, s: f64, scale_plastic: bool) {
        let pm = self.law.flow_pressure();
        let movable_pixel = |p: f64| p > 0.0 && (scale_plastic || p < pm);
        self.pressure
            .par_chunks_mut(self.ny)
            .with_min_len(self.min_len)
            .for_each(|row| {
                for p in row {
                    if movable_pixel(*p) {
                        *p = (s * *p).min(pm);
                    }
                }
            });
    }

    fn spread_missing_load(&mut self, total: f64, mean: f64) {
        let pm = self.law.flow_pressure();
        let pressure = &mut self.pressure;
        let carried: f64 = pressure.iter().sum();
        let missing = total - carried;
        let (u, heights) = (&self.u, &self.heights);
        let penetration = |i: usize| {
            if mean.is_nan() {
                0.0
            } else {
                (mean - (u[i] - heights[i])).max(0.0)
            }
        };
        let (weight_sum, n_zero) = pressure
            .iter()
            .enumerate()
            .filter(|(_, &p)| p <= 0.0)
            .fold((0.0, 0usize), |(w, c), (i, _)| (w + penetration(i), c + 1));
        for (i, p) in pressure.iter_mut().enumerate() {
            if *p <= 0.0 {
                let share = if weight_sum > 0.0 {
                    missing * penetration(i) / weight_sum
                } else {
                    missing / n_zero.max(1) as f64
                };
                *p = share.min(pm);
            }
        }
    }

    /// Gathers the statistics row by row as the inverse transform writes u (one pass over the
    /// arrays fewer than computing them after the convolution).
    fn displacement_and_stats(&mut self, reference: f64) -> Stats {
        let (n, law) = (self.ny, self.law);
        let (pressure, heights) = (&self.pressure, &self.heights);
        self.influence.apply_with(
            pressure,
            |_, _| {},
            &mut self.u,
            |i, u| {
                row_stats(
                    &pressure[i * n..(i + 1) * n],
                    u,
                    &heights[i * n..(i + 1) * n],
                    reference,
                    law,
                )
            },
            Some(&mut self.stats),
        );
        Stats::combine(&self.stats)
    }

    /// The post hook of `displacement_and_stats` as a pass of its own, row by row.
    fn stats(&mut self, reference: f64) -> Stats {
        let (n, law) = (self.ny, self.law);
        self.stats
            .par_iter_mut()
            .with_min_len(self.min_len)
            .zip(self.pressure.par_chunks(n))
            .zip(self.u.par_chunks(n).zip(self.heights.par_chunks(n)))
            .for_each(|((acc, p), (u, h))| *acc = row_stats(p, u, h, reference, law));
        Stats::combine(&self.stats)
    }

    fn direction(&mut self, mean: f64, beta: f64) -> (f64, f64) {
        let (n, pm) = (self.ny, self.law.flow_pressure());
        self.sums
            .par_iter_mut()
            .with_min_len(self.min_len)
            .zip(self.free_rows.par_iter_mut())
            .zip(self.t.par_chunks_mut(n))
            .zip(
                self.pressure
                    .par_chunks(n)
                    .zip(self.u.par_chunks(n).zip(self.heights.par_chunks(n))),
            )
            .for_each(|(((acc, free), t), (p, (u, h)))| {
                let (mut st, mut sdt, mut count) = (0.0, 0.0, 0);
                for (((t, &p), &u), &h) in t.iter_mut().zip(p).zip(u).zip(h) {
                    if p > 0.0 && p < pm {
                        let d = u - h - mean;
                        *t = d + beta * *t;
                        st += *t;
                        sdt += d * *t;
                        count += u32::from(*t != 0.0);
                    } else {
                        *t = 0.0;
                    }
                }
                *acc = [st, sdt];
                *free = count;
            });
        self.sums.iter().fold((0.0, 0.0), |(a, b), s| (a + s[0], b + s[1]))
    }

    /// t_f shifted in the forward transform's row hook; 1/response_scale (exact, a power of two)
    /// in every term.
    fn curvature(&mut self, shift: f64) -> f64 {
        self.influence
            .quadratic_form_with(&self.t, |_, row| shift_free(row, shift), 1.0 / self.response_scale)
    }

    /// The free pixels (t ≠ 0) gathered from the rows `direction` counted them in, t_f = t −
    /// `shift` on each, then their pair sum.
    fn direct_curvature(&mut self, shift: f64) -> Option<f64> {
        let pair_form = self.pair_form.as_ref()?;
        let n_free = self.free_rows.iter().map(|&c| c as usize).sum();
        if !pair_form.worth(n_free) {
            return None;
        }
        let n = self.ny;
        self.free_points.clear();
        for (i, _) in self.free_rows.iter().enumerate().filter(|(_, &c)| c > 0) {
            let row = &self.t[i * n..(i + 1) * n];
            for (j, &t) in row.iter().enumerate().filter(|(_, &t)| t != 0.0) {
                self.free_points.push((i as u32, j as u32, t - shift));
            }
        }
        Some(pair_form.form(&self.free_points, &mut self.pair_partials))
    }

    /// t is zero outside the free pixels, so `t ≠ 0` marks them without reading p (a free pixel
    /// whose t is exactly 0 is left out consistently here and in `update`).
    fn update(&mut self, mean: f64, tau: f64, shift: f64) -> Update {
        let n = self.ny;
        let step = StepParameters {
            mean,
            tau,
            shift,
            law: self.law,
        };
        let mut loads = std::mem::take(&mut self.load_rows);
        let mut totals = std::mem::take(&mut self.row_partials);
        let mut events = std::mem::take(&mut self.sums);
        loads
            .par_iter_mut()
            .with_min_len(self.min_len)
            .zip(totals.par_iter_mut().zip(events.par_iter_mut()))
            .zip(self.pressure.par_chunks_mut(n).zip(self.p_old.par_chunks_mut(n)))
            .zip(
                self.t
                    .par_chunks(n)
                    .zip(self.u.par_chunks(n).zip(self.heights.par_chunks(n))),
            )
            .for_each(|(((load, (total, event)), (p, p_old)), (t, (u, h)))| {
                (*load, *total, *event) = update_row(&step, p, p_old, t, u, h);
            });
        let load = loads.iter().fold(LoadSums::default(), |a, &b| LoadSums::merge(a, b));
        let total: f64 = totals.iter().sum();
        let released = events.iter().any(|e| e[0] > 0.0);
        let clipped = events.iter().any(|e| e[1] > 0.0);
        self.load_rows = loads;
        self.row_partials = totals;
        self.sums = events;
        Update {
            load,
            total,
            released,
            clipped,
        }
    }

    /// r goes into the spare buffer, whose row the post hook turns into the new u = (old u) − τr
    /// while it gathers the statistics; the buffers are then swapped.
    fn advance(&mut self, mean: f64, tau: f64, shift: f64, kept: bool) -> Stats {
        let (n, law) = (self.ny, self.law);
        let (pressure, p_old, u, heights) = (&self.pressure, &self.p_old, &self.u, &self.heights);
        let post = |i: usize, row: &mut [f64]| {
            let rows = i * n..(i + 1) * n;
            advance_row(
                (mean, tau, law),
                row,
                &u[rows.clone()],
                &pressure[rows.clone()],
                &p_old[rows.clone()],
                &heights[rows],
            )
        };
        if kept {
            self.influence
                .apply_kept_with(&mut self.u_alt, post, Some(&mut self.stats));
        } else {
            self.influence.apply_with(
                &self.t,
                |_, row| shift_free(row, shift),
                &mut self.u_alt,
                post,
                Some(&mut self.stats),
            );
        }
        std::mem::swap(&mut self.u, &mut self.u_alt);
        Stats::combine(&self.stats)
    }

    fn keep_displacement(&mut self) {
        std::mem::swap(&mut self.u, &mut self.u_alt);
    }

    fn undo(&mut self) {
        let n = self.ny;
        self.pressure
            .par_chunks_mut(n)
            .with_min_len(self.min_len)
            .zip(self.p_old.par_chunks(n))
            .for_each(|(p, o)| p.copy_from_slice(o));
        std::mem::swap(&mut self.u, &mut self.u_alt);
    }
}

/// t_f = t − `shift` on one row's free pixels, those where t ≠ 0 (`curvature`, `advance`).
fn shift_free(row: &mut [f64], shift: f64) {
    for v in row.iter_mut().filter(|v| **v != 0.0) {
        *v -= shift;
    }
}

/// The [`Stats`] of one row of g = u − h about `reference`, pixels in order.
fn row_stats(p: &[f64], u: &[f64], h: &[f64], reference: f64, law: SurfaceLaw) -> Stats {
    let mut s = Stats::default();
    for ((&p, &u), &h) in p.iter().zip(u).zip(h) {
        s.add(p, u, h, reference, law);
    }
    s
}

/// The scalars of one update pass ([`ContactBackend::update`]).
struct StepParameters {
    mean: f64,
    tau: f64,
    /// NaN when no conjugate-gradient step is taken.
    shift: f64,
    law: SurfaceLaw,
}

/// The update pass over one row: p in place, its copy `p_old` made pixel by pixel as p is read;
/// returns the row's load sums, its Σp and the pixels [released, clipped].
#[inline]
fn update_row(
    step: &StepParameters,
    p: &mut [f64],
    p_old: &mut [f64],
    t: &[f64],
    u: &[f64],
    h: &[f64],
) -> (LoadSums, f64, [f64; 2]) {
    let StepParameters { mean, tau, shift, law } = *step;
    let pm = law.flow_pressure();
    let cg_step = shift.is_finite();
    let mut load = LoadSums::default();
    let mut sum_p = 0.0;
    let (mut released, mut clipped) = (0.0, 0.0);
    for ((((p, old), &t), &u), &h) in p.iter_mut().zip(p_old).zip(t).zip(u).zip(h) {
        if *p <= 0.0 && u - h - mean >= 0.0 {
            // Out of contact and staying out (most pixels): p = ±0 adds nothing. Its copy
            // mostly holds this p already (the pixel was out at the last update too) and is
            // written only where it differs, bit for bit: a read instead of a write.
            if old.to_bits() != p.to_bits() {
                *old = *p;
            }
            continue;
        }
        *old = *p;
        if *p <= 0.0 {
            let d = u - h - mean;
            *p = (-tau * d).min(pm);
            released += 1.0;
        } else if *p >= pm {
            let d = u - h - mean;
            if d > 0.0 {
                *p = (pm - tau * d).max(0.0);
                released += 1.0;
            }
        } else if cg_step && t != 0.0 {
            let q = *p - tau * (t - shift);
            if q <= 0.0 {
                *p = 0.0;
                clipped += 1.0;
            } else if q >= pm {
                *p = pm;
                clipped += 1.0;
            } else {
                *p = q;
            }
        }
        sum_p += *p;
        load.add(*p, law);
    }
    (load, sum_p, [released, clipped])
}

/// The post hook of `advance` over one row: `row` holds r on entry and the new u = `u` − τr on
/// return; returns the statistics of the row about `mean` with each pixel's move. After a step
/// on the CG line a pixel with p = 0 was out of contact and stays out: it only moves u and takes
/// part in two minima, kept apart from the sums (a minimum is the same in any order).
#[inline]
fn advance_row(
    (mean, tau, law): (f64, f64, SurfaceLaw),
    row: &mut [f64],
    u: &[f64],
    p: &[f64],
    p_old: &[f64],
    h: &[f64],
) -> Stats {
    let mut s = Stats::default();
    let (mut min_zero, mut settle_gap) = (f64::INFINITY, f64::INFINITY);
    for ((((v, &u), &p), &before), &h) in row.iter_mut().zip(u).zip(p).zip(p_old).zip(h) {
        let r = *v;
        *v = u - tau * r;
        let g = *v - h;
        if p == 0.0 {
            min_zero = min_zero.min(g);
            settle_gap = settle_gap.min(g - SETTLED_CHANGE_FACTOR * (tau * r).abs());
        } else {
            s.add(p, *v, h, mean, law);
            s.add_change(p, p - before, g, tau * r);
        }
    }
    s.min_zero = s.min_zero.min(min_zero);
    s.settle_gap = s.settle_gap.min(settle_gap);
    s
}

/// The partial of the height statistics over one row, about h₀: Σ(h − h₀), Σ(h − h₀)², max, all
/// finite.
#[inline]
fn height_row(row: &[f64], h0: f64) -> (f64, f64, f64, bool) {
    row.iter()
        .fold((0.0, 0.0, f64::NEG_INFINITY, true), |(s, q, m, f), &h| {
            (s + (h - h0), q + (h - h0) * (h - h0), m.max(h), f && h.is_finite())
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bits of a field, so that −0 and +0 differ.
    fn bits(field: &[f64]) -> Vec<u64> {
        field.iter().map(|v| v.to_bits()).collect()
    }

    #[test]
    fn an_undo_restores_the_pressure_of_the_update_bit_for_bit() {
        // The update writes its copy of a pixel that stays out of contact only where the copy
        // differs: a pressure written after an earlier update (whose copy holds that update's
        // pressure) must still come back exactly, −0 against +0 included.
        let (n, pm) = (16, 0.05);
        let grid = Grid::square(n, 1.0).unwrap();
        let mut backend = CpuBackend::new(grid, 1.0, Boundary::Periodic).unwrap();
        backend.bind_law(SurfaceLaw::Saturated { flow_pressure: pm });
        backend.write_heights(&mut |h| {
            for (k, v) in h.iter_mut().enumerate() {
                *v = 1e-3 * ((k * 7) % 11) as f64;
            }
        });
        // Pixels in contact, some plastic, one in five at +0; then half of them out of contact
        // (an exact zero, a −0 where the first field had +0), the rest new values.
        let first: Vec<f64> = (0..n * n)
            .map(|k| match k % 5 {
                0 => pm,
                1 => 0.0,
                _ => 1e-3 * (1 + k % 13) as f64,
            })
            .collect();
        let second: Vec<f64> = (0..n * n)
            .map(|k| match k % 4 {
                0 | 2 if k % 5 == 1 => -0.0,
                0 | 2 => 0.0,
                1 => pm,
                _ => 2e-3 * (1 + k % 7) as f64,
            })
            .collect();
        for field in [&first, &second] {
            backend.write_pressure(&mut |p| p.copy_from_slice(field));
            // A mean gap of −1 keeps every non-contact pixel out (g − ḡ > 0); plastic pixels
            // are released, so the update changes p.
            backend.update(-1.0, 0.5, f64::NAN);
            assert_ne!(bits(backend.pressure()), bits(field), "the update changed nothing");
            backend.undo();
            assert_eq!(bits(backend.pressure()), bits(field));
        }
    }
}
