//! The 2D power spectrum of a measured map as measured (a lay, a roll-off, a peak: not only a
//! power law), and periodic surfaces generated from it on any grid and box.
//!
//! The PSD is kept on the map's own wavevector grid, q = (2π m/Lx, 2π n/Ly), without radial
//! averaging, so that an anisotropic map (a lay) stays anisotropic. A map that is not periodic is
//! levelled by a plane and multiplied by a Hann window before its FFT: the jump at its borders
//! would otherwise leak power ∝ q⁻² into every wavevector and bias the spectrum (and a fitted H)
//! low. The window's power is normalised out (the periodogram is divided by the mean of w²), so
//! that Σ C Δq over the map's modes is its variance.
//!
//! The periodogram is **not smoothed**. A 3×3 average in q is a convolution that raises a steep
//! spectrum by about α²/(3ρ²) at ρ modes from the origin (C ∝ q^−α, α = 2(1 + H)): +24 % at ρ = 4
//! for H = 0.7, exactly where most of the height lies, and it blurs a lay or a peak, the features
//! this spectrum is kept for, by a mode in every direction. Unsmoothed, each mode's power is the
//! map's own draw (exponentially distributed about the expected PSD), carried into every seed:
//! seeds differ in their phases, as the random-phase generation of self-affine surfaces does
//! ([`crate::surface::Generation::RandomPhase`] has exact amplitudes too).
//!
//! A map resampled onto finer pixels along one axis (`wearsim surface import --resample` puts a
//! map with non-square pixels on square pixels of the smaller size) holds interpolated pixels:
//! beyond the Nyquist wavenumber of its native pixel along that axis, π/Δ, its spectrum is the
//! interpolation's (images of the measured band, attenuated), not the surface's.
//! [`MeasuredPsd::with_measured_pixel`] keeps only the measured wavevectors, |q_x| ≤ π/Δx and
//! |q_y| ≤ π/Δy of the native pixels: the radial shells, the anisotropy and the band variance
//! are taken over them, and generated surfaces carry nothing beyond them.

use std::f64::consts::PI;

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha20Rng;

use crate::error::{Error, Result};
use crate::fft::{wavenumber, FftPlan, C64};
use crate::grid::Grid;
use crate::surface::{PsdShell, Surface};

use super::prepare::{flat_map, is_flat, periodicity, preprocess, Detrend, Preprocess, NOT_PERIODIC};

/// The window a map is multiplied by before its FFT.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Window {
    /// None: for a periodic map (levelled by its mean only, which keeps it periodic).
    None,
    /// Hann (sin²) along each side, after levelling by a plane: for a map that is not periodic.
    Hann,
}

impl Window {
    /// The name written in run files.
    pub fn name(self) -> &'static str {
        match self {
            Window::None => "none",
            Window::Hann => "hann",
        }
    }

    /// The window a map needs: Hann when the jumps across its borders exceed [`NOT_PERIODIC`]
    /// typical steps (the measure of [`periodicity`]), none for a periodic map.
    pub fn for_map(map: &Surface) -> Window {
        let p = periodicity(map.heights(), map.nx(), map.ny());
        if p.border_step_x.max(p.border_step_y) > NOT_PERIODIC {
            Window::Hann
        } else {
            Window::None
        }
    }
}

impl std::str::FromStr for Window {
    type Err = Error;

    fn from_str(name: &str) -> Result<Self> {
        match name {
            "none" => Ok(Window::None),
            "hann" => Ok(Window::Hann),
            other => Err(Error::param(
                "window",
                format!("\"{other}\"; use \"hann\" (a map that is not periodic) or \"none\" (a periodic map)"),
            )),
        }
    }
}

/// The 2D PSD of a measured map on its own wavevector grid.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredPsd {
    grid: Grid,
    window: Window,
    /// C(q) in length⁴ (h_rms² = Σ C Δq, Δq = (2π)²/(Lx Ly)), every mode of the full spectrum:
    /// `c[ix * ny + iy]` at FFT indices (ix along x); the mean (ix = iy = 0) is zero.
    c: Vec<f64>,
    /// RMS height of the levelled map, unwindowed.
    rms_height: f64,
    /// The largest |mode index| along x and along y that was measured (not interpolated): Nx/2 and
    /// Ny/2, or less for a map resampled onto finer pixels ([`MeasuredPsd::with_measured_pixel`]).
    measured: [f64; 2],
}

/// Sum of C Δq over the carried modes of a target grid below this fraction of the map's: no mode
/// of the target lies in the measured band.
const EMPTY: f64 = 1e-300;

impl MeasuredPsd {
    /// The PSD of `map` under `window`: levelled (plane under a Hann window, mean without one),
    /// windowed, transformed, normalised by the window's power.
    pub fn of(map: &Surface, window: Window) -> Result<Self> {
        let (nx, ny) = (map.nx(), map.ny());
        let mut h = map.heights().to_vec();
        let detrend = match window {
            Window::None => Detrend::Mean,
            Window::Hann => Detrend::Plane,
        };
        preprocess(&mut h, nx, ny, &Preprocess { detrend, taper: 0.0 })?;
        let rms_height = (h.iter().map(|v| v * v).sum::<f64>() / h.len() as f64).sqrt();
        // A flat map (one value, or a plane levelled away to round-off) has no spectrum to carry.
        let spread = map.heights().iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if is_flat(rms_height, spread) {
            return Err(flat_map("map", detrend, rms_height));
        }
        let mut power = 1.0;
        if window == Window::Hann {
            let hann = |k: usize, n: usize| (PI * (k as f64 + 0.5) / n as f64).sin().powi(2);
            let wx: Vec<f64> = (0..nx).map(|i| hann(i, nx)).collect();
            let wy: Vec<f64> = (0..ny).map(|j| hann(j, ny)).collect();
            // The window's weighted mean removed, so that no constant leaks through the window.
            let (mut sw, mut swh) = (0.0, 0.0);
            for i in 0..nx {
                for j in 0..ny {
                    let w = wx[i] * wy[j];
                    sw += w;
                    swh += w * h[i * ny + j];
                }
            }
            let mean = swh / sw;
            for i in 0..nx {
                for j in 0..ny {
                    h[i * ny + j] = (h[i * ny + j] - mean) * wx[i] * wy[j];
                }
            }
            let mean_square = |w: &[f64]| w.iter().map(|v| v * v).sum::<f64>() / w.len() as f64;
            power = mean_square(&wx) * mean_square(&wy);
        }
        let mut plan = FftPlan::new(nx, ny);
        plan.forward(&h);
        let (stride, spec) = (plan.row_stride(), plan.spectrum());
        let dq = (2.0 * PI) * (2.0 * PI) / (map.grid().length_x() * map.grid().length_y());
        // |ĥ|²/N² is the variance per mode; divided by the window's power and by Δq it is C.
        let scale = 1.0 / (((nx * ny) as f64).powi(2) * power * dq);
        let mut c = vec![0.0; nx * ny];
        for iy in 0..=ny / 2 {
            for ix in 0..nx {
                let v = spec[iy * stride + ix].norm_sqr() * scale;
                c[ix * ny + iy] = v;
                // The conjugate partner, −q.
                c[((nx - ix) % nx) * ny + (ny - iy) % ny] = v;
            }
        }
        c[0] = 0.0;
        Ok(Self {
            grid: map.grid(),
            window,
            c,
            rms_height,
            measured: [(nx / 2) as f64, (ny / 2) as f64],
        })
    }

    /// The PSD with only the wavevectors that the native pixels `pixel` = [Δx, Δy] (in the map's
    /// length unit) of a map resampled onto finer pixels measured: |q_x| ≤ π/Δx, |q_y| ≤ π/Δy.
    /// Beyond those Nyquist wavenumbers the map's pixels are interpolated and its spectrum is the
    /// interpolation's. A native pixel equal to the map's own (within 1e-6) changes nothing; one
    /// smaller than the map's, or not positive, is an error (a resampled map's native pixels are
    /// at least its own).
    pub fn with_measured_pixel(mut self, pixel: [f64; 2]) -> Result<Self> {
        let own = self.grid.pixel_size();
        let (lx, ly) = (self.grid.length_x(), self.grid.length_y());
        for (k, (p, side, n)) in [(pixel[0], lx, self.grid.nx()), (pixel[1], ly, self.grid.ny())]
            .into_iter()
            .enumerate()
        {
            let axis = ["x", "y"][k];
            if !(p.is_finite() && p > 0.0) {
                return Err(Error::param(
                    "measured_pixel",
                    format!("{p} along {axis}: a native pixel size must be a positive length"),
                ));
            }
            if p < own * (1.0 - 1e-6) {
                return Err(Error::param(
                    "measured_pixel",
                    format!(
                        "{p:e} along {axis} is smaller than the map's pixel, {own:e}: a map resampled onto finer \
                         pixels has native pixels at least as large as its own (check the unit: the map's length \
                         unit)"
                    ),
                ));
            }
            // The measured modes: |m| ≤ L/(2Δ), at most the stored Nyquist N/2.
            self.measured[k] = if p <= own * (1.0 + 1e-6) {
                (n / 2) as f64
            } else {
                (side / (2.0 * p)).min((n / 2) as f64)
            };
        }
        Ok(self)
    }

    /// The native pixel sizes the measured wavevectors end at (the map's own when nothing is
    /// interpolated), [Δx, Δy] in the map's length unit.
    pub fn measured_pixel(&self) -> [f64; 2] {
        [
            self.grid.length_x() / (2.0 * self.measured[0]),
            self.grid.length_y() / (2.0 * self.measured[1]),
        ]
    }

    /// Whether only part of the stored spectrum was measured ([`MeasuredPsd::with_measured_pixel`]).
    pub fn is_resampled(&self) -> bool {
        self.measured[0] < (self.grid.nx() / 2) as f64 || self.measured[1] < (self.grid.ny() / 2) as f64
    }

    /// Whether the mode of FFT indices (ix, iy) was measured.
    fn is_measured(&self, ix: usize, iy: usize) -> bool {
        let tol = 1.0 + 1e-9;
        wavenumber(ix, self.grid.nx()).abs() <= self.measured[0] * tol
            && wavenumber(iy, self.grid.ny()).abs() <= self.measured[1] * tol
    }

    /// The largest measured wavenumber along either axis, in units of 2π/Lx (the Nyquist
    /// wavenumber Nx/2 of a map that is not resampled).
    pub fn nyquist(&self) -> f64 {
        self.measured[0].max(self.measured[1] * self.grid.aspect())
    }

    /// The PSD of `map` under `window`, or, without one, under the window the map needs
    /// ([`Window::for_map`]: Hann when it is not periodic): as a `source = "spectrum"` run takes
    /// its map's.
    pub fn of_map(map: &Surface, window: Option<Window>) -> Result<Self> {
        Self::of(map, window.unwrap_or_else(|| Window::for_map(map)))
    }

    /// The (top, bottom) pair of a `source = "spectrum"` run with `seed` on `target`: two surfaces
    /// of [`MeasuredPsd::generate`] whose seeds are derived from `seed` by
    /// [`crate::surface::pair_seeds`], as a generated run's are. The run file and the Python
    /// binding both make their pairs here, so that one seed gives the same surfaces, bit for bit.
    pub fn generate_pair(&self, target: Grid, seed: u64) -> Result<(Surface, Surface)> {
        let (top_seed, bottom_seed) = crate::surface::pair_seeds(seed);
        // One after the other, as generated pairs are: a peak memory that does not depend on the load.
        Ok((self.generate(target, top_seed)?, self.generate(target, bottom_seed)?))
    }

    /// The map's grid.
    pub fn grid(&self) -> Grid {
        self.grid
    }

    /// The window the PSD was taken with.
    pub fn window(&self) -> Window {
        self.window
    }

    /// RMS height of the levelled map (unwindowed).
    pub fn rms_height(&self) -> f64 {
        self.rms_height
    }

    /// Δq of the map's wavevector grid, (2π)²/(Lx Ly).
    fn dq(&self) -> f64 {
        4.0 * PI * PI / (self.grid.length_x() * self.grid.length_y())
    }

    /// C at the map's mode (m, n), signed integer indices.
    fn node(&self, m: i64, n: i64) -> f64 {
        let (nx, ny) = (self.grid.nx() as i64, self.grid.ny() as i64);
        self.c[(m.rem_euclid(nx) * ny + n.rem_euclid(ny)) as usize]
    }

    /// C at the wavevector (qx, qy) in radians per length unit: bilinear in the map's (qx, qy) grid
    /// (of C, not ln C: each mode of one map's periodogram is an exponentially distributed draw,
    /// and the geometric mean ln-interpolation takes of such draws is e^−γ ≈ 0.56 of their power
    /// on average, while linear interpolation is unbiased for the scatter and overestimates only the
    /// curvature of a steep spectrum between modes, by α(α+1)/(8ρ²) at ρ modes from the origin). The
    /// mean (q = 0) takes no part: its weight goes to the other corners. Zero outside the measured
    /// band: wavelengths longer than the map's extent along their direction (ρ < 1) or shorter
    /// than two of its pixels along either axis (two of its native pixels, for a map resampled
    /// onto finer ones: [`MeasuredPsd::with_measured_pixel`]).
    pub fn at(&self, qx: f64, qy: f64) -> f64 {
        let (lx, ly) = (self.grid.length_x(), self.grid.length_y());
        let (u, v) = (qx * lx / (2.0 * PI), qy * ly / (2.0 * PI));
        let tol = 1e-9;
        let [hx, hy] = self.measured;
        if u * u + v * v < 1.0 - tol || u.abs() > hx * (1.0 + tol) || v.abs() > hy * (1.0 + tol) {
            return 0.0;
        }
        // Snapped to a mode where within round-off of one, so that the map's own grid reads its
        // modes exactly.
        let snap = |x: f64| if (x - x.round()).abs() < tol { x.round() } else { x };
        let (u, v) = (snap(u), snap(v));
        let (m0, n0) = (u.floor(), v.floor());
        let (fx, fy) = (u - m0, v - n0);
        let (m0, n0) = (m0 as i64, n0 as i64);
        let (mut sum, mut weight) = (0.0, 0.0);
        for (dm, wx) in [(0, 1.0 - fx), (1, fx)] {
            for (dn, wy) in [(0, 1.0 - fy), (1, fy)] {
                let w = wx * wy;
                let (m, n) = (m0 + dm, n0 + dn);
                let measured = (m.abs() as f64) <= hx * (1.0 + tol) && (n.abs() as f64) <= hy * (1.0 + tol);
                if w > 0.0 && (m, n) != (0, 0) && measured {
                    sum += w * self.node(m, n);
                    weight += w;
                }
            }
        }
        if weight > 0.0 {
            sum / weight
        } else {
            0.0
        }
    }

    /// C at every mode of `target` (`[ix * ny + iy]`, FFT indices) and the variance they carry,
    /// Σ C Δq over them.
    fn carried(&self, target: &Grid) -> (Vec<f64>, f64) {
        let (nx, ny) = (target.nx(), target.ny());
        let (kx, ky) = (2.0 * PI / target.length_x(), 2.0 * PI / target.length_y());
        let mut c = vec![0.0; nx * ny];
        for ix in 0..nx {
            for iy in 0..ny {
                c[ix * ny + iy] = self.at(kx * wavenumber(ix, nx), ky * wavenumber(iy, ny));
            }
        }
        let variance = c.iter().sum::<f64>() * kx * ky;
        (c, variance)
    }

    /// What a target grid leaves out of the measured spectrum (one sentence each): a box larger
    /// than the map (the map says nothing about longer wavelengths) or a pixel smaller than its
    /// (nor about wavelengths shorter than two of its pixels).
    pub fn notes(&self, target: &Grid, map: &str) -> Vec<String> {
        let mut notes = Vec::new();
        let (lx, ly) = (self.grid.length_x(), self.grid.length_y());
        let (tx, ty) = (target.length_x(), target.length_y());
        let tol = 1.0 + 1e-9;
        if tx > lx * tol || ty > ly * tol {
            notes.push(format!(
                "the box, {tx:e} × {ty:e}, is larger than the map {map} ({lx:e} × {ly:e}): the map says nothing about \
                 wavelengths longer than its sides, so the surfaces carry no power there (they repeat the map's \
                 statistics with nothing longer)"
            ));
        }
        let [px, py] = self.measured_pixel();
        if self.is_resampled() && target.pixel_size() * tol < px.max(py) {
            notes.push(format!(
                "the pixel, {:e}, is smaller than the native pixels the map {map} was measured with ({px:e} × \
                 {py:e}; it was resampled onto finer ones): the map says nothing about wavelengths shorter than two \
                 native pixels along each axis, so the surfaces carry no power there",
                target.pixel_size()
            ));
        } else if target.pixel_size() * tol < self.grid.pixel_size() {
            notes.push(format!(
                "the pixel, {:e}, is smaller than the map's ({:e}): the map says nothing about wavelengths shorter than \
                 two of its pixels, so the surfaces carry no power there (they are smooth below the map's resolution)",
                target.pixel_size(),
                self.grid.pixel_size()
            ));
        }
        notes
    }

    /// A periodic surface on `target` (any grid and box) with Fourier amplitudes √C(q) at the
    /// target's wavevectors ([`MeasuredPsd::at`]) and random phases from `seed`, drawn
    /// sequentially in the order of [`Surface::generate`] (bit-identical whatever the thread
    /// count), with its Hermitian rows; zero mean and h_rms² = Σ C Δq over the carried modes, so
    /// that a box smaller than the map carries less RMS (its longest wavelengths are shorter). An
    /// error when no mode of the target lies in the measured band.
    pub fn generate(&self, target: Grid, seed: u64) -> Result<Surface> {
        let (nx, ny) = (target.nx(), target.ny());
        let (c, variance) = self.carried(&target);
        let map_variance = self.c.iter().sum::<f64>() * self.dq();
        if variance.is_nan() || variance <= EMPTY.max(1e-30 * map_variance) {
            return Err(Error::param(
                "grid",
                format!(
                    "a {nx} × {ny} grid of box {:e} × {:e} holds no wavevector of the measured band (wavelengths from \
                     two pixels of the map, {:e}, to its sides, {:e} × {:e}), so the surface would be flat; choose a \
                     box and pixel that overlap the map's",
                    target.length_x(),
                    target.length_y(),
                    2.0 * self.grid.pixel_size(),
                    self.grid.length_x(),
                    self.grid.length_y()
                ),
            ));
        }
        let mut rng = ChaCha20Rng::seed_from_u64(seed);
        let mut plan = FftPlan::new(nx, ny);
        let half = plan.half();
        let stride = plan.row_stride();
        let spec = plan.spectrum_mut();
        for qy in 0..half {
            for qx in 0..nx {
                let phase = rng.random::<f64>() * 2.0 * PI;
                spec[qy * stride + qx] = C64::from_polar(c[qx * ny + qy].sqrt(), phase);
            }
        }
        // Rows q_y = 0 and q_y = Ny/2 are their own conjugate partners: Hermitian in q_x, as
        // `Surface::generate` makes them.
        for qy in [0, ny / 2] {
            let row = &mut spec[qy * stride..qy * stride + nx];
            for qx in nx / 2 + 1..nx {
                row[qx] = row[nx - qx].conj();
            }
            row[0].im = 0.0;
            row[nx / 2].im = 0.0;
        }
        let mut heights = vec![0.0; nx * ny];
        plan.inverse(&mut heights);
        let n = heights.len() as f64;
        let mean = heights.iter().sum::<f64>() / n;
        let rms = (heights.iter().map(|h| (h - mean) * (h - mean)).sum::<f64>() / n).sqrt();
        let factor = variance.sqrt() / rms;
        heights.iter_mut().for_each(|h| *h = (*h - mean) * factor);
        Surface::new("spectrum", target, heights)
    }

    /// RMS height a target grid carries, √(Σ C Δq) over its modes in the measured band.
    pub fn carried_rms(&self, target: &Grid) -> f64 {
        self.carried(target).1.sqrt()
    }

    /// The radially averaged PSD in the convention of [`Surface::radial_psd_shells`]: shells of
    /// integer |q| in units of 2π/Lx, mean variance per mode C Δq, modes of the full spectrum (the
    /// measured ones only, for a resampled map: [`MeasuredPsd::with_measured_pixel`]).
    pub fn radial_shells(&self) -> Vec<PsdShell> {
        let nx = self.grid.nx();
        let (sum, count) = self.shell_sums();
        (1..nx)
            .filter(|&m| count[m] > 0.0)
            .map(|m| PsdShell {
                q: m as f64,
                psd: sum[m] / count[m],
                modes: count[m],
            })
            .collect()
    }

    /// |q| of the mode of FFT indices (ix, iy), in units of 2π/Lx (the convention of
    /// [`Surface::generate`]).
    fn modulus(&self, ix: usize, iy: usize) -> f64 {
        let (nx, ny) = (self.grid.nx(), self.grid.ny());
        let (qx, qy) = (wavenumber(ix, nx), wavenumber(iy, ny) * self.grid.aspect());
        (qx * qx + qy * qy).sqrt()
    }

    /// Per shell of integer |q| (units of 2π/Lx, shells 0 to Nx − 1): the sum of C Δq over its
    /// measured modes and their number.
    fn shell_sums(&self) -> (Vec<f64>, Vec<f64>) {
        let (nx, ny) = (self.grid.nx(), self.grid.ny());
        let dq = self.dq();
        let mut sum = vec![0.0; nx];
        let mut count = vec![0.0; nx];
        for ix in 0..nx {
            for iy in 0..ny {
                let m = self.modulus(ix, iy).round() as usize;
                if m >= 1 && m < nx && self.is_measured(ix, iy) {
                    sum[m] += self.c[ix * ny + iy] * dq;
                    count[m] += 1.0;
                }
            }
        }
        (sum, count)
    }

    /// The variance Σ C Δq held by the modes of the map's grid with q_lower ≤ |q| ≤ q_upper (units
    /// of 2π/Lx, the band [`Surface::generate`] fills for λ_u = Lx/q_lower, λ_l = Lx/q_upper):
    /// the variance of the map's self-affine band (paper §4.1). For a resampled map, a mode of the
    /// band that was not measured (beyond the native Nyquist wavenumber along an axis) counts with
    /// the mean C Δq of the measured modes of its shell, as an isotropic band would hold it.
    pub fn band_variance(&self, q_lower: f64, q_upper: f64) -> f64 {
        let (nx, ny) = (self.grid.nx(), self.grid.ny());
        let (sum, count) = self.shell_sums();
        let dq = self.dq();
        let mut variance = 0.0;
        for ix in 0..nx {
            for iy in 0..ny {
                let q = self.modulus(ix, iy);
                if !(q > 0.0 && q >= q_lower * (1.0 - 1e-12) && q <= q_upper * (1.0 + 1e-12)) {
                    continue;
                }
                if self.is_measured(ix, iy) {
                    variance += self.c[ix * ny + iy] * dq;
                } else {
                    let m = q.round() as usize;
                    if m < nx && count[m] > 0.0 {
                        variance += sum[m] / count[m];
                    }
                }
            }
        }
        variance
    }

    /// The ratio of the power of wavevectors nearer the x axis (|qx| > |qy|) to that of wavevectors
    /// nearer the y axis, over the shells of |q| between `q_lo` and `q_hi` (units of 2π/Lx): the
    /// geometric mean of the shells' ratios of mean C, so that every shell counts alike (a sum of
    /// C would be the few longest wavelengths' alone). 1 for an isotropic spectrum; above 1 when
    /// the heights vary faster along x (a lay along y). Over the measured modes only, for a
    /// resampled map ([`MeasuredPsd::with_measured_pixel`]): the interpolated ones along one axis
    /// would make a lay of the interpolation.
    pub fn anisotropy(&self, q_lo: f64, q_hi: f64) -> f64 {
        let (nx, ny) = (self.grid.nx(), self.grid.ny());
        let r = self.grid.aspect();
        let shells = nx;
        let mut along = vec![[0.0f64; 4]; shells];
        for ix in 0..nx {
            for iy in 0..ny {
                let (qx, qy) = (wavenumber(ix, nx), wavenumber(iy, ny) * r);
                let m = (qx * qx + qy * qy).sqrt().round() as usize;
                if m < 1
                    || m >= shells
                    || (m as f64) < q_lo
                    || (m as f64) > q_hi
                    || qx.abs() == qy.abs()
                    || !self.is_measured(ix, iy)
                {
                    continue;
                }
                let k = if qx.abs() > qy.abs() { 0 } else { 2 };
                along[m][k] += self.c[ix * ny + iy];
                along[m][k + 1] += 1.0;
            }
        }
        let (mut sum, mut n) = (0.0, 0.0);
        for [cx, nx_, cy, ny_] in along {
            if nx_ > 0.0 && ny_ > 0.0 && cx > 0.0 && cy > 0.0 {
                sum += ((cx / nx_) / (cy / ny_)).ln();
                n += 1.0;
            }
        }
        if n > 0.0 {
            (sum / n).exp()
        } else {
            1.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::{Generation, SpectrumParams};

    fn self_affine(grid: Grid, upper: f64, seed: u64) -> Surface {
        let params = SpectrumParams {
            hurst: 0.7,
            lambda_lower: 8.0 * grid.pixel_size(),
            lambda_upper: upper,
            rms_height: 0.01,
            generation: Generation::RandomPhase,
        };
        Surface::generate(grid, &params, seed).unwrap()
    }

    /// A measured map of n² pixels of side 1: a self-affine surface (λ_u a quarter of the map)
    /// cut out of a periodic one four times its side, so that its borders do not match (not
    /// periodic), as a measurement's; with `squeeze` 2, every other column of one twice as wide,
    /// so that its features are half as long along y as along x (a lay along x).
    fn measured(n: usize, squeeze: usize, seed: u64) -> Surface {
        measured_up_to(n, squeeze, 0.25, seed)
    }

    fn measured_up_to(n: usize, squeeze: usize, upper: f64, seed: u64) -> Surface {
        let big = self_affine(Grid::new(4 * n, 4 * n * squeeze, 4.0).unwrap(), upper, seed);
        let stride = 4 * n * squeeze;
        let h = (0..n * n)
            .map(|k| big.heights()[(k / n) * stride + (k % n) * squeeze])
            .collect();
        Surface::new("map", Grid::square(n, 1.0).unwrap(), h).unwrap()
    }

    /// Generated on the map's own grid and box, the surfaces carry the map's windowed spectrum:
    /// their radial PSD (periodic: no window needed) matches the map's Hann-windowed radial PSD
    /// shell by shell, exactly up to the Hermitian rows (a few modes per shell, whose phases are
    /// made real), so within 10 % over the shells of ≥ 24 modes, and the RMS follows from the
    /// spectrum: that of the windowed PSD exactly, and the map's within 3 % on average over eight
    /// maps (the window weighs the middle of a map more than its borders, so one map's windowed
    /// variance scatters by ~8 % about its plain one when λ_u is a quarter of the map: within
    /// 15 % each; the mean of eight, ~3 %, tests that it is unbiased).
    #[test]
    fn surfaces_on_the_maps_own_grid_carry_its_windowed_spectrum_and_rms() {
        let mut ratios = Vec::new();
        for seed in 1..=8 {
            let map = measured(128, 1, seed);
            let window = Window::for_map(&map);
            assert_eq!(window, Window::Hann);
            let psd = MeasuredPsd::of(&map, window).unwrap();
            let s = psd.generate(map.grid(), seed).unwrap();
            let measured_shells = psd.radial_shells();
            for (a, b) in s.radial_psd_shells().iter().zip(&measured_shells) {
                assert_eq!(a.q, b.q);
                if b.modes >= 24.0 && b.q <= 64.0 {
                    assert!(
                        (a.psd / b.psd - 1.0).abs() < 0.1,
                        "shell {}: {} vs {}",
                        a.q,
                        a.psd,
                        b.psd
                    );
                }
            }
            assert!((s.rms_height() / psd.carried_rms(&map.grid()) - 1.0).abs() < 1e-9);
            let ratio = s.rms_height() / psd.rms_height();
            assert!((ratio - 1.0).abs() < 0.15, "seed {seed}: {ratio}");
            ratios.push(ratio);
            assert!(psd.notes(&map.grid(), "map").is_empty());
        }
        let mean = ratios.iter().sum::<f64>() / ratios.len() as f64;
        assert!((mean - 1.0).abs() < 0.03, "{ratios:?}");
    }

    /// An anisotropic map (a surface squeezed along y: it varies faster along y, so wavevectors
    /// along y carry more power) gives surfaces with the same anisotropy, on its grid and box and
    /// on another grid and box of the same pixel, within a factor 1.5 (the ratio, a mean over the
    /// band's shells, scatters by ~10 % between seeds).
    #[test]
    fn an_anisotropic_map_gives_anisotropic_surfaces() {
        let map = measured(128, 2, 3);
        let psd = MeasuredPsd::of(&map, Window::Hann).unwrap();
        let band = (8.0, 16.0);
        let measured_ratio = psd.anisotropy(band.0, band.1);
        assert!(measured_ratio < 0.5, "{measured_ratio}");
        for target in [
            map.grid(),
            Grid::new(128, 64, 1.0).unwrap(),
            Grid::square(256, 2.0).unwrap(),
        ] {
            let s = psd.generate(target, 7).unwrap();
            // The same wavenumbers, in units of 2π over the target's side.
            let scale = target.length_x() / map.length();
            let ratio = MeasuredPsd::of(&s, Window::None)
                .unwrap()
                .anisotropy(band.0 * scale, band.1 * scale);
            assert!(
                (ratio / measured_ratio).ln().abs() < 1.5f64.ln(),
                "{target:?}: {ratio} vs {measured_ratio}"
            );
        }
        // An isotropic map is not anisotropic.
        let iso = MeasuredPsd::of(&measured(128, 1, 4), Window::Hann)
            .unwrap()
            .anisotropy(4.0, 32.0);
        assert!((iso.ln()).abs() < 0.2, "{iso}");
    }

    #[test]
    fn a_larger_box_or_a_finer_pixel_carries_a_note_and_seeds_differ_reproducibly() {
        let map = measured_up_to(64, 1, 2.0, 2);
        let psd = MeasuredPsd::of(&map, Window::Hann).unwrap();
        let twice = Grid::square(128, 2.0).unwrap();
        let notes = psd.notes(&twice, "map.npy");
        assert_eq!(notes.len(), 1, "{notes:?}");
        assert!(
            notes[0].contains("larger than the map map.npy") && notes[0].contains("longer"),
            "{notes:?}"
        );
        let fine = psd.notes(&Grid::square(128, 1.0).unwrap(), "map.npy");
        assert!(
            fine.len() == 1 && fine[0].contains("shorter than two of its pixels"),
            "{fine:?}"
        );
        // A smaller box carries less RMS (its longest wavelengths are shorter).
        let small = Grid::square(32, 0.5).unwrap();
        assert!(psd.notes(&small, "m").is_empty());
        assert!(psd.carried_rms(&small) < psd.carried_rms(&map.grid()));
        let gen = |threads: usize, seed: u64| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| psd.generate(twice, seed).unwrap())
        };
        assert_eq!(gen(1, 3), gen(2, 3));
        assert_ne!(gen(1, 3), gen(1, 4));
        // Nothing beyond the map's side in the box twice its size: the modes of wavelength 2 are empty.
        let s = gen(1, 3);
        let shells = s.radial_psd_shells();
        assert!(shells[0].psd < 1e-25 * shells[1].psd, "{:?}", &shells[..2]);
        // A box holding no wavevector of the band is refused by name.
        let e = psd
            .generate(Grid::square(16, 0.01).unwrap(), 1)
            .unwrap_err()
            .to_string();
        assert!(e.contains("grid") && e.contains("flat"), "{e}");
    }

    /// A map resampled ×2 along y (each row repeated: native pixels twice as long along y) with
    /// its native pixel given: only the wavevectors |q_y| ≤ π/Δy_native count (the shells hold
    /// fewer modes, the band variance counts the others with their shell's mean), and surfaces
    /// generated from it carry nothing beyond the native Nyquist wavenumber along y, where the
    /// interpolation's images lie.
    #[test]
    fn a_resampled_map_keeps_only_its_measured_wavevectors() {
        let n = 128;
        let grid = Grid::square(n, 1.0).unwrap();
        let original = self_affine(grid, 0.25, 5);
        let h: Vec<f64> = (0..n * n).map(|k| original.heights()[k - k % 2]).collect();
        let map = Surface::new("resampled", grid, h).unwrap();
        let all = MeasuredPsd::of(&map, Window::None).unwrap();
        // The band variance over every mode is the map's variance (periodic: Parseval).
        let whole = all.band_variance(0.5, n as f64);
        assert!((whole / map.rms_height().powi(2) - 1.0).abs() < 1e-9, "{whole}");
        assert!(!all.is_resampled() && all.measured_pixel() == [1.0 / n as f64; 2]);
        let native = [1.0 / n as f64, 2.0 / n as f64];
        let psd = all.clone().with_measured_pixel(native).unwrap();
        assert!(psd.is_resampled());
        assert_eq!(psd.measured_pixel(), native);
        assert_eq!(psd.nyquist(), n as f64 / 2.0);
        // The interpolated modes beyond |q_y| = n/4 carry power in the map and are left out.
        let ky = 2.0 * PI;
        assert!(all.at(0.0, ky * 50.0) > 0.0 && psd.at(0.0, ky * 50.0) == 0.0);
        assert_eq!(psd.at(ky * 20.0, ky * 10.0), all.at(ky * 20.0, ky * 10.0));
        let (shells_all, shells) = (all.radial_shells(), psd.radial_shells());
        let modes = |s: &[PsdShell], m: f64| s.iter().find(|s| s.q == m).map_or(0.0, |s| s.modes);
        assert_eq!(modes(&shells, 20.0), modes(&shells_all, 20.0));
        assert!(modes(&shells, 50.0) < 0.6 * modes(&shells_all, 50.0));
        // Surfaces generated from it: nothing beyond the native Nyquist wavenumber along y.
        let s = psd.generate(grid, 3).unwrap();
        let generated = MeasuredPsd::of(&s, Window::None).unwrap();
        let (mut beyond, mut within) = (0.0, 0.0);
        for ix in 0..n {
            for iy in 0..n {
                let c = generated.c[ix * n + iy];
                if wavenumber(iy, n).abs() > n as f64 / 4.0 {
                    beyond += c;
                } else {
                    within += c;
                }
            }
        }
        assert!(beyond < 1e-25 * within, "{beyond} {within}");
        // A finer target pixel is told against the native pixels.
        let notes = psd.notes(&Grid::square(2 * n, 1.0).unwrap(), "map.npy");
        assert!(notes.len() == 1 && notes[0].contains("native pixels"), "{notes:?}");
        let notes = psd.notes(&grid, "map.npy");
        assert!(notes.len() == 1 && notes[0].contains("native pixels"), "{notes:?}");
        for bad in [[0.0, 1.0], [1.0 / n as f64, 0.5 / n as f64], [f64::NAN, 1.0]] {
            let e = all.clone().with_measured_pixel(bad).unwrap_err().to_string();
            assert!(e.contains("measured_pixel"), "{e}");
        }
    }
}
