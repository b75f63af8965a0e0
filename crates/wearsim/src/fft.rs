//! Periodic 2D real FFTs laid out for fast convolution by a real kernel.
//!
//! Every solver iteration applies the half-space influence operator 𝒦 once, that is one real 2D FFT
//! round trip with a multiplication by a real kernel in between. This module is that round trip,
//! tuned for memory traffic (docs/performance.md has the measurements):
//! - plans are made once ([`FftPlan::new`]) and every Nx·Ny buffer is preallocated;
//! - the half spectrum is kept *transposed*: `N/2 + 1` rows (one per `q_y`) of length `N` (over
//!   `q_x`), each row padded to `N + 4` so that the stride is not a power of two;
//! - the transpose is fused into the row passes, in blocks of `BLOCK` rows;
//! - forward column FFT, kernel multiplication and inverse column FFT run in one pass per row;
//! - work is split with `rayon`, with per-thread scratch buffers that grow once and are then
//!   reused by every transform on that thread (no allocation per transform); every element is
//!   computed by the same sequence of operations whatever the thread count, so results are
//!   bit-identical across thread counts.
//!
//! Arrays are row-major `a[i * n + j]`: `i` is x (the first NumPy axis), `j` is y.

use std::cell::RefCell;
use std::sync::Arc;

use rayon::prelude::*;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

/// Complex number type of the spectra.
pub type C64 = Complex<f64>;

/// Work buffers of one thread: a real row, a block of complex rows and FFT scratch.
#[derive(Default)]
struct Work {
    real: Vec<f64>,
    block: Vec<C64>,
    scratch: Vec<C64>,
}

thread_local! {
    static WORK: RefCell<Work> = RefCell::new(Work::default());
}

/// Runs `f` on this thread's work buffers cut to the given lengths (grown, zero-filled, on first
/// use of a larger size). `f` must not start another transform on the same thread.
fn with_work<T>(
    real: usize,
    block: usize,
    scratch: usize,
    f: impl FnOnce(&mut [f64], &mut [C64], &mut [C64]) -> T,
) -> T {
    WORK.with(|w| {
        let mut w = w.borrow_mut();
        let w = &mut *w;
        if w.real.len() < real {
            w.real.resize(real, 0.0);
        }
        if w.block.len() < block {
            w.block.resize(block, C64::new(0.0, 0.0));
        }
        if w.scratch.len() < scratch {
            w.scratch.resize(scratch, C64::new(0.0, 0.0));
        }
        f(&mut w.real[..real], &mut w.block[..block], &mut w.scratch[..scratch])
    })
}

/// A zero-filled buffer of `len` values whose memory the kernel is asked to back with 2 MiB pages
/// (Linux `madvise(MADV_HUGEPAGE)`, before the first write). The transposing passes of a 4096² FFT
/// touch a 4 KiB page per row and spectrum row, thousands per block; a 2 MiB page covers 512 of
/// them with one TLB entry (docs/performance.md: 5–7 % off a 4096² round trip). Elsewhere, or
/// where the kernel declines, an ordinary buffer.
pub(crate) fn zeroed_buffer<T: Clone + Default>(len: usize) -> Vec<T> {
    let mut v = Vec::with_capacity(len);
    advise_huge_pages(v.as_ptr(), len);
    v.resize(len, T::default());
    v
}

#[cfg(target_os = "linux")]
fn advise_huge_pages<T>(start: *const T, len: usize) {
    const HUGE: usize = 2 << 20;
    let start = start as usize;
    let end = start + len * std::mem::size_of::<T>();
    let (first, last) = (start.next_multiple_of(HUGE), end / HUGE * HUGE);
    if last > first {
        // SAFETY: the range lies inside the buffer's allocation; MADV_HUGEPAGE only changes how the
        // kernel backs those pages, never their contents. A refusal leaves ordinary pages.
        unsafe { libc::madvise(first as *mut libc::c_void, last - first, libc::MADV_HUGEPAGE) };
    }
}

#[cfg(not(target_os = "linux"))]
fn advise_huge_pages<T>(_: *const T, _: usize) {}

/// Rows handled together in the transposing row passes (16 rows of a 4096² array fit in L2).
const BLOCK: usize = 16;

/// Raw pointer that may be shared between rayon workers writing disjoint elements.
struct SharedMut<T>(*mut T);
// Copy for any T (a derive would ask T: Copy): it copies the pointer, not the pointee.
impl<T> Clone for SharedMut<T> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<T> Copy for SharedMut<T> {}
impl<T> SharedMut<T> {
    /// The pointer (a method, so that closures capture the whole `Send` wrapper, not its field).
    fn get(self) -> *mut T {
        self.0
    }
}
// SAFETY: the pointer is only used to write disjoint elements from different threads (each use
// says which), which is sound when the elements themselves may be sent between threads.
unsafe impl<T: Send> Send for SharedMut<T> {}
unsafe impl<T: Send> Sync for SharedMut<T> {}

/// FFT plans and the transposed half-spectrum buffer for one Nx × Ny grid.
pub struct FftPlan {
    nx: usize,
    ny: usize,
    stride: usize,
    r2c: Arc<dyn RealToComplex<f64>>,
    c2r: Arc<dyn ComplexToReal<f64>>,
    col_forward: Arc<dyn Fft<f64>>,
    col_inverse: Arc<dyn Fft<f64>>,
    /// Transposed half spectrum: `spectrum[qy * stride + qx]`, `qy ∈ 0..=Ny/2`, `qx ∈ 0..Nx`.
    spectrum: Vec<C64>,
    /// Per-`q_y`-row partials of [`FftPlan::quadratic_form_with`], combined in row order.
    row_sums: Vec<f64>,
    /// The buffer holds the forward transform of the last [`FftPlan::quadratic_form_with`]'s
    /// input, for [`FftPlan::convolve_kept_with`].
    transform_kept: bool,
}

impl FftPlan {
    /// Plans the transforms for an `nx × ny` grid (`nx` rows along x, `ny` values along y; both
    /// even and at least 2).
    pub fn new(nx: usize, ny: usize) -> Self {
        assert!(
            nx >= 2 && nx & 1 == 0 && ny >= 2 && ny & 1 == 0,
            "FFT grid sizes must be even and at least 2"
        );
        let mut real = RealFftPlanner::<f64>::new();
        let mut complex = FftPlanner::<f64>::new();
        let stride = nx + 4;
        let half = ny / 2 + 1;
        Self {
            nx,
            ny,
            stride,
            r2c: real.plan_fft_forward(ny),
            c2r: real.plan_fft_inverse(ny),
            col_forward: complex.plan_fft_forward(nx),
            col_inverse: complex.plan_fft_inverse(nx),
            spectrum: zeroed_buffer(half * stride),
            row_sums: vec![0.0; half],
            transform_kept: false,
        }
    }

    /// Grid size along x, Nx (the number of rows).
    pub fn nx(&self) -> usize {
        self.nx
    }

    /// Grid size along y, Ny (the length of a row).
    pub fn ny(&self) -> usize {
        self.ny
    }

    /// Number of stored `q_y` rows, `Ny/2 + 1`.
    pub fn half(&self) -> usize {
        self.ny / 2 + 1
    }

    /// Read access to the transposed half spectrum after [`FftPlan::forward`]: element `(qx, qy)` is
    /// at `qy * row_stride() + qx`.
    pub fn spectrum(&self) -> &[C64] {
        &self.spectrum
    }

    /// Write access to the transposed half spectrum, to be followed by [`FftPlan::inverse`].
    pub fn spectrum_mut(&mut self) -> &mut [C64] {
        self.transform_kept = false;
        &mut self.spectrum
    }

    /// Distance between consecutive `q_y` rows of the spectrum buffer.
    pub fn row_stride(&self) -> usize {
        self.stride
    }

    /// Unnormalised forward transform of `input` (Nx·Ny values, row-major) into the spectrum buffer
    /// (row FFTs with the transpose fused in, then column FFTs).
    pub fn forward(&mut self, input: &[f64]) {
        self.transform_kept = false;
        self.row_forward(input, |_, _| {});
        let fft = Arc::clone(&self.col_forward);
        self.column_pass(&*fft);
    }

    /// Unnormalised inverse transform of the spectrum buffer into `output` (Nx·Ny values). The buffer
    /// is consumed. Divide by Nx·Ny for the inverse of [`FftPlan::forward`].
    pub fn inverse(&mut self, output: &mut [f64]) {
        self.transform_kept = false;
        let fft = Arc::clone(&self.col_inverse);
        self.column_pass(&*fft);
        self.row_inverse(output, |_, _| (), None);
    }

    /// `fft` applied in place to every (transposed) spectrum row.
    fn column_pass(&mut self, fft: &dyn Fft<f64>) {
        let n = self.nx;
        let scratch_len = fft.get_inplace_scratch_len();
        self.spectrum.par_chunks_mut(self.stride).for_each(|row| {
            with_work(0, 0, scratch_len, |_, _, scratch| {
                fft.process_with_scratch(&mut row[..n], scratch)
            })
        });
    }

    /// `output = IFFT(kernel · FFT(input))`, the periodic convolution by a real, even kernel given
    /// in the transposed half-spectrum layout without padding (`kernel[qy * Nx + qx]`), with the
    /// 1/(Nx·Ny) normalisation folded in. `input` and `output` may not alias.
    pub fn convolve(&mut self, input: &[f64], kernel: &[f64], output: &mut [f64]) {
        self.convolve_with(input, |_, _| {}, kernel, output, |_, _| (), None);
    }

    /// [`FftPlan::convolve`] with two hooks fused into its row passes, to save whole passes over the
    /// arrays in the solver: `pre(i, row)` may modify the copy of input row `i` before it is
    /// transformed; `post(i, row)` sees output row `i` once written, may rewrite it (the solver
    /// turns a response into the displacement it moves), and returns a value stored in
    /// `partials[i]` (when given), for deterministic reductions (a sum, the solver's statistics).
    pub fn convolve_with<R: Send>(
        &mut self,
        input: &[f64],
        pre: impl Fn(usize, &mut [f64]) + Sync,
        kernel: &[f64],
        output: &mut [f64],
        post: impl Fn(usize, &mut [f64]) -> R + Sync,
        partials: Option<&mut [R]>,
    ) {
        self.transform_kept = false;
        self.row_forward(input, pre);
        self.column_convolve(kernel, true);
        self.row_inverse(output, post, partials);
    }

    /// [`FftPlan::convolve_with`] of the input of the last [`FftPlan::quadratic_form_with`], from
    /// its forward transform still in the buffer (no other transform since): the other half of
    /// the convolution, bit for bit the numbers a whole `convolve_with` of that input (with the
    /// same `pre`) gives.
    pub fn convolve_kept_with<R: Send>(
        &mut self,
        kernel: &[f64],
        output: &mut [f64],
        post: impl Fn(usize, &mut [f64]) -> R + Sync,
        partials: Option<&mut [R]>,
    ) {
        assert!(
            self.transform_kept,
            "convolve_kept_with follows quadratic_form_with with no transform between"
        );
        self.transform_kept = false;
        self.column_convolve(kernel, false);
        self.row_inverse(output, post, partials);
    }

    /// Per (transposed) spectrum row: the forward column FFT (unless the buffer holds it
    /// already), the kernel, the inverse column FFT, in one pass.
    fn column_convolve(&mut self, kernel: &[f64], forward: bool) {
        let n = self.nx;
        assert_eq!(kernel.len(), self.half() * n, "kernel must hold (Ny/2+1)·Nx values");
        let fwd = &self.col_forward;
        let inv = &self.col_inverse;
        let scratch_len = fwd.get_inplace_scratch_len().max(inv.get_inplace_scratch_len());
        self.spectrum
            .par_chunks_mut(self.stride)
            .zip(kernel.par_chunks(n))
            .for_each(|(row, k)| {
                with_work(0, 0, scratch_len, |_, _, scratch| {
                    let row = &mut row[..n];
                    if forward {
                        fwd.process_with_scratch(row, scratch);
                    }
                    for (c, &w) in row.iter_mut().zip(k) {
                        *c *= w;
                    }
                    inv.process_with_scratch(row, scratch);
                })
            });
    }

    /// `factor · Σₓ input·(kernel ∗ input)`, the quadratic form of [`FftPlan::convolve`]'s
    /// operator, from the forward transform alone (half a convolution): by Parseval's identity it
    /// is `Σ_q (factor·kernel(q))·|FFT(input)(q)|²` over the whole spectrum, that is over the stored
    /// half with the `q_y` rows strictly between 0 and Ny/2 counted twice (a real, even kernel and
    /// a real input have mirror-symmetric `|FFT|²`). The factor enters every term, so that a sum
    /// whose plain value would leave double precision (a box far from unit size) stays inside it.
    /// `pre` modifies the copy of input row `i` first, as in [`FftPlan::convolve_with`]. Per-row
    /// partials are combined in row order, so the result does not depend on the thread count.
    pub fn quadratic_form_with(
        &mut self,
        input: &[f64],
        pre: impl Fn(usize, &mut [f64]) + Sync,
        kernel: &[f64],
        factor: f64,
    ) -> f64 {
        let (n, half) = (self.nx, self.half());
        assert_eq!(kernel.len(), half * n, "kernel must hold (Ny/2+1)·Nx values");
        self.transform_kept = false;
        self.row_forward(input, pre);
        let fwd = &self.col_forward;
        let scratch_len = fwd.get_inplace_scratch_len();
        self.spectrum
            .par_chunks_mut(self.stride)
            .zip(kernel.par_chunks(n))
            .zip(self.row_sums.par_iter_mut())
            .enumerate()
            .for_each(|(qy, ((row, k), sum))| {
                with_work(0, 0, scratch_len, |_, _, scratch| {
                    let row = &mut row[..n];
                    fwd.process_with_scratch(row, scratch);
                    let s: f64 = row.iter().zip(k).map(|(c, &w)| (w * factor) * c.norm_sqr()).sum();
                    *sum = if qy == 0 || qy == half - 1 { s } else { 2.0 * s };
                })
            });
        self.transform_kept = true;
        self.row_sums.iter().sum()
    }

    /// Real-to-complex FFT of every row of `input`, written transposed into the spectrum buffer.
    fn row_forward(&mut self, input: &[f64], pre: impl Fn(usize, &mut [f64]) + Sync) {
        let n = self.ny;
        assert_eq!(input.len(), self.nx * n, "input must hold Nx·Ny values");
        let half = self.half();
        let stride = self.stride;
        let r2c = &self.r2c;
        let spec = SharedMut(self.spectrum.as_mut_ptr());
        let scratch_len = r2c.get_scratch_len();
        input.par_chunks(BLOCK * n).enumerate().for_each(|(b, rows)| {
            with_work(n, BLOCK * half, scratch_len, |row_in, block_out, scratch| {
                let rows_here = rows.len() / n;
                for r in 0..rows_here {
                    // r2c overwrites its input: work on a copy of the row.
                    row_in.copy_from_slice(&rows[r * n..(r + 1) * n]);
                    pre(b * BLOCK + r, row_in);
                    r2c.process_with_scratch(row_in, &mut block_out[r * half..(r + 1) * half], scratch)
                        .expect("buffer sizes match the plan");
                }
                let i0 = b * BLOCK;
                for qy in 0..half {
                    // SAFETY: block `b` writes columns i0..i0+rows_here of every spectrum row, which no
                    // other block touches; all indices are inside the buffer.
                    let dst = unsafe { std::slice::from_raw_parts_mut(spec.get().add(qy * stride + i0), rows_here) };
                    for (r, d) in dst.iter_mut().enumerate() {
                        *d = block_out[r * half + qy];
                    }
                }
            })
        });
    }

    /// Gathers transposed spectrum columns back into rows and applies the complex-to-real FFT.
    fn row_inverse<R: Send>(
        &mut self,
        output: &mut [f64],
        post: impl Fn(usize, &mut [f64]) -> R + Sync,
        partials: Option<&mut [R]>,
    ) {
        let n = self.ny;
        assert_eq!(output.len(), self.nx * n, "output must hold Nx·Ny values");
        let partials = partials.map(|p| {
            assert_eq!(p.len(), self.nx, "one partial per row");
            SharedMut(p.as_mut_ptr())
        });
        let half = self.half();
        let stride = self.stride;
        let c2r = &self.c2r;
        let spec = &self.spectrum;
        let scratch_len = c2r.get_scratch_len();
        output.par_chunks_mut(BLOCK * n).enumerate().for_each(|(b, rows)| {
            with_work(0, BLOCK * half, scratch_len, |_, block_in, scratch| {
                let rows_here = rows.len() / n;
                let i0 = b * BLOCK;
                for qy in 0..half {
                    let src = &spec[qy * stride + i0..qy * stride + i0 + rows_here];
                    for (r, s) in src.iter().enumerate() {
                        block_in[r * half + qy] = *s;
                    }
                }
                for r in 0..rows_here {
                    let row_in = &mut block_in[r * half..(r + 1) * half];
                    // c2r requires real DC and Nyquist bins; round-off leaves tiny imaginary parts.
                    row_in[0].im = 0.0;
                    row_in[half - 1].im = 0.0;
                    let out = &mut rows[r * n..(r + 1) * n];
                    c2r.process_with_scratch(row_in, out, scratch)
                        .expect("buffer sizes match the plan");
                    let value = post(i0 + r, out);
                    if let Some(p) = partials {
                        // SAFETY: row i0 + r < Nx belongs to this block alone; the slot holds an
                        // initialised R, dropped by the assignment.
                        unsafe { *p.get().add(i0 + r) = value };
                    }
                }
            })
        });
    }
}

/// Signed integer wavenumber of FFT index `k` on an `n`-point grid (`k ≤ n/2` positive).
#[inline]
pub fn wavenumber(k: usize, n: usize) -> f64 {
    if k <= n / 2 {
        k as f64
    } else {
        k as f64 - n as f64
    }
}

/// Builds a kernel in the layout [`FftPlan::convolve`] expects from a function of the integer
/// wavenumbers `(qx, qy)` (in units of 2π/Lx and 2π/Ly) of an `nx × ny` grid.
pub fn radial_kernel(nx: usize, ny: usize, f: impl Fn(f64, f64) -> f64 + Sync) -> Vec<f64> {
    let half = ny / 2 + 1;
    let mut k = vec![0.0; half * nx];
    k.par_chunks_mut(nx).enumerate().for_each(|(qy, row)| {
        for (qx, v) in row.iter_mut().enumerate() {
            *v = f(wavenumber(qx, nx), qy as f64);
        }
    });
    k
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Naive O((NxNy)²) periodic convolution with a kernel given in Fourier space.
    fn naive_convolve(a: &[f64], nx: usize, ny: usize, kernel: impl Fn(f64, f64) -> f64) -> Vec<f64> {
        use std::f64::consts::PI;
        let mut out = vec![0.0; nx * ny];
        let mut spec = vec![C64::new(0.0, 0.0); nx * ny];
        for kx in 0..nx {
            for ky in 0..ny {
                let mut s = C64::new(0.0, 0.0);
                for i in 0..nx {
                    for j in 0..ny {
                        let ph = -2.0 * PI * ((kx * i) as f64 / nx as f64 + (ky * j) as f64 / ny as f64);
                        s += a[i * ny + j] * C64::new(ph.cos(), ph.sin());
                    }
                }
                spec[kx * ny + ky] = s * kernel(wavenumber(kx, nx), wavenumber(ky, ny).abs());
            }
        }
        for i in 0..nx {
            for j in 0..ny {
                let mut s = C64::new(0.0, 0.0);
                for kx in 0..nx {
                    for ky in 0..ny {
                        let ph = 2.0 * PI * ((kx * i) as f64 / nx as f64 + (ky * j) as f64 / ny as f64);
                        s += spec[kx * ny + ky] * C64::new(ph.cos(), ph.sin());
                    }
                }
                out[i * ny + j] = s.re / (nx * ny) as f64;
            }
        }
        out
    }

    #[test]
    fn convolution_matches_naive_dft_on_square_and_rectangular_grids() {
        for (nx, ny) in [(4usize, 4usize), (8, 8), (12, 12), (34, 34), (8, 20), (22, 6)] {
            let a: Vec<f64> = (0..nx * ny).map(|k| ((k * 7919) % 101) as f64 / 101.0 - 0.3).collect();
            let f = |qx: f64, qy: f64| 1.0 / (1.0 + qx * qx + 2.0 * qy * qy);
            let nn = (nx * ny) as f64;
            let kernel = radial_kernel(nx, ny, |qx, qy| f(qx, qy) / nn);
            let mut plan = FftPlan::new(nx, ny);
            let mut out = vec![0.0; nx * ny];
            plan.convolve(&a, &kernel, &mut out);
            let expected = naive_convolve(&a, nx, ny, f);
            for (x, y) in out.iter().zip(&expected) {
                assert!((x - y).abs() < 1e-12, "{nx}×{ny}: {x} vs {y}");
            }
        }
    }

    #[test]
    fn forward_then_inverse_is_identity_times_the_grid() {
        for (nx, ny) in [(40usize, 40usize), (24, 40)] {
            let a: Vec<f64> = (0..nx * ny).map(|k| (k as f64 * 0.37).sin()).collect();
            let mut plan = FftPlan::new(nx, ny);
            plan.forward(&a);
            // DC bin is the plain sum.
            let sum: f64 = a.iter().sum();
            assert!((plan.spectrum()[0].re - sum).abs() < 1e-9);
            let mut back = vec![0.0; nx * ny];
            plan.inverse(&mut back);
            for (x, y) in a.iter().zip(&back) {
                assert!((x - y / (nx * ny) as f64).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn the_quadratic_form_is_the_sum_of_input_times_its_convolution() {
        for (nx, ny) in [(8usize, 8usize), (34, 34), (8, 20), (22, 6), (64, 48)] {
            let a: Vec<f64> = (0..nx * ny).map(|k| ((k * 7919) % 101) as f64 / 101.0 - 0.3).collect();
            let nn = (nx * ny) as f64;
            let kernel = radial_kernel(nx, ny, |qx, qy| (qx * qx + 3.0 * qy * qy).sqrt() / nn);
            let mut plan = FftPlan::new(nx, ny);
            let mut out = vec![0.0; nx * ny];
            // The hook's change enters both sides.
            let pre = |i: usize, row: &mut [f64]| row[0] += i as f64;
            let mut shifted = a.clone();
            for i in 0..nx {
                shifted[i * ny] += i as f64;
            }
            plan.convolve(&shifted, &kernel, &mut out);
            let direct: f64 = shifted.iter().zip(&out).map(|(x, y)| x * y).sum();
            let parseval = plan.quadratic_form_with(&a, pre, &kernel, 1.0);
            assert!(
                (parseval - direct).abs() < 1e-12 * direct.abs(),
                "{nx}×{ny}: {parseval} vs {direct}"
            );
            // The transform it leaves completes the convolution, bit for bit, hooks included.
            let mut rest = vec![0.0; nx * ny];
            let mut rows = vec![0.0; nx];
            plan.convolve_kept_with(
                &kernel,
                &mut rest,
                |i, row| {
                    row[1] *= 2.0;
                    row[0] + i as f64
                },
                Some(&mut rows),
            );
            for i in 0..nx {
                assert_eq!(rows[i].to_bits(), (out[i * ny] + i as f64).to_bits());
                out[i * ny + 1] *= 2.0;
            }
            assert!(
                rest.iter().zip(&out).all(|(x, y)| x.to_bits() == y.to_bits()),
                "{nx}×{ny}"
            );
        }
    }

    #[test]
    #[should_panic(expected = "convolve_kept_with follows quadratic_form_with")]
    fn completing_a_convolution_after_another_transform_is_refused() {
        let (nx, ny) = (8, 8);
        let kernel = radial_kernel(nx, ny, |qx, qy| qx + qy);
        let mut plan = FftPlan::new(nx, ny);
        let a = vec![1.0; nx * ny];
        let mut out = vec![0.0; nx * ny];
        plan.quadratic_form_with(&a, |_, _| {}, &kernel, 1.0);
        plan.convolve(&a, &kernel, &mut out);
        plan.convolve_kept_with(&kernel, &mut out, |_, _| (), None);
    }

    #[test]
    fn results_do_not_depend_on_thread_count() {
        for (nx, ny) in [(64usize, 64usize), (48, 80)] {
            let a: Vec<f64> = (0..nx * ny).map(|k| ((k * 31) % 17) as f64).collect();
            let kernel = radial_kernel(nx, ny, |qx, qy| (qx * qx + qy * qy).sqrt());
            let run = |threads: usize| {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                pool.install(|| {
                    let mut plan = FftPlan::new(nx, ny);
                    let mut out = vec![0.0; nx * ny];
                    plan.convolve(&a, &kernel, &mut out);
                    (out, plan.quadratic_form_with(&a, |_, _| {}, &kernel, 0.5).to_bits())
                })
            };
            assert_eq!(run(1), run(3));
        }
    }
}
