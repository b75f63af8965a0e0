//! Periodic self-affine rough surfaces (paper §2 and §4.1): generation, `.npy` input/output and statistics.

use std::f64::consts::PI;
use std::path::Path;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha20Rng;
use rand_distr::StandardNormal;
use rayon::prelude::*;

use crate::check::{grid as check_grid, positive};
use crate::error::{Error, Result};
use crate::fft::{radial_kernel, wavenumber, FftPlan, C64};
use crate::io::{read_npy_2d, write_npy_f64, NpyType};

/// A periodic height field on an N×N grid of side `length`; `heights[i * n + j]`, i along x.
#[derive(Debug, Clone, PartialEq)]
pub struct Surface {
    n: usize,
    length: f64,
    heights: Vec<f64>,
}

/// How random heights are drawn from the power spectrum.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Generation {
    /// Amplitude √Φ(q) with uniformly random phases (Wu 2000), the default.
    #[default]
    RandomPhase,
    /// Gaussian white noise filtered by √Φ(q).
    FilteredNoise,
}

impl std::str::FromStr for Generation {
    type Err = Error;

    /// Parses the name written in run files (`generation = "random-phase"`).
    fn from_str(name: &str) -> Result<Self> {
        match name {
            "random-phase" => Ok(Generation::RandomPhase),
            "filtered-noise" => Ok(Generation::FilteredNoise),
            other => Err(Error::param(
                "generation",
                format!("\"{other}\"; use \"random-phase\" or \"filtered-noise\""),
            )),
        }
    }
}

/// Statistics of a self-affine surface (paper §4.1). Lengths in the run's length unit.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SpectrumParams {
    /// Hurst exponent H, in (0, 1].
    pub hurst: f64,
    /// Shortest wavelength λ_l (large-wavenumber cut-off q_l = L/λ_l).
    pub lambda_lower: f64,
    /// Longest wavelength λ_u (small-wavenumber cut-off q_u = L/λ_u).
    pub lambda_upper: f64,
    /// RMS height the generated surface is scaled to exactly.
    pub rms_height: f64,
    /// Random-phase or filtered-noise generation.
    pub generation: Generation,
}

impl SpectrumParams {
    /// The paper's roughness on an `n`-pixel grid of side `length` (paper §4.1, used by the benchmarks):
    /// H = 0.7, λ_l = 16 Δx, λ_u = min(256 Δx, L/2), h_rms = 0.005 L, random phases.
    pub fn paper_roughness(n: usize, length: f64) -> Self {
        let dx = length / n as f64;
        Self {
            hurst: 0.7,
            lambda_lower: 16.0 * dx,
            lambda_upper: (256.0f64).min(n as f64 / 2.0) * dx,
            rms_height: 0.005 * length,
            generation: Generation::RandomPhase,
        }
    }

    /// Checks the parameters against a grid of `n` pixels over `length`.
    pub fn validate(&self, n: usize, length: f64) -> Result<()> {
        check_grid(n)?;
        positive("length", length)?;
        if !(self.hurst > 0.0 && self.hurst <= 1.0) {
            return Err(Error::param("hurst", format!("{} must lie in (0, 1]", self.hurst)));
        }
        positive("rms_height", self.rms_height)?;
        positive("lambda_lower", self.lambda_lower)?;
        let dx = length / n as f64;
        if self.lambda_lower < 2.0 * dx * (1.0 - 1e-12) {
            return Err(Error::param(
                "lambda_lower",
                format!(
                    "{:e} is below two pixels ({:e}); refine `grid` or raise `lambda_lower`",
                    self.lambda_lower,
                    2.0 * dx
                ),
            ));
        }
        if !(self.lambda_upper > self.lambda_lower && self.lambda_upper <= length * (1.0 + 1e-12)) {
            return Err(Error::param(
                "lambda_upper",
                format!(
                    "{:e} must lie between `lambda_lower` ({:e}) and the side length ({length:e})",
                    self.lambda_upper, self.lambda_lower
                ),
            ));
        }
        if !band_has_modes(n, length / self.lambda_upper, length / self.lambda_lower) {
            return Err(Error::param(
                "lambda_upper",
                format!(
                    "the band of wavelengths [{}, {}] holds no Fourier mode of the {n}-pixel grid of side {length} (the \
                     wavenumbers L/λ between {:.4} and {:.4} include no lattice point), so the surface would be flat; \
                     widen the band between `lambda_lower` and `lambda_upper`",
                    self.lambda_lower,
                    self.lambda_upper,
                    length / self.lambda_upper,
                    length / self.lambda_lower
                ),
            ));
        }
        Ok(())
    }
}

/// Whether some non-zero wavenumber (q_x, q_y) of an `n`-pixel grid has q_lo ≤ |q| ≤ q_hi (with the
/// tolerance of the generator).
fn band_has_modes(n: usize, q_lo: f64, q_hi: f64) -> bool {
    let (lo, hi) = (q_lo * (1.0 - 1e-12), q_hi * (1.0 + 1e-12));
    let half = (n / 2) as f64;
    (0..=n / 2).any(|qx| {
        let qx = qx as f64;
        let rest = lo * lo - qx * qx;
        let mut qy = if rest <= 0.0 { 0.0 } else { rest.sqrt().ceil() };
        if qx == 0.0 && qy == 0.0 {
            qy = 1.0;
        }
        while qy > 0.0 && qx * qx + (qy - 1.0) * (qy - 1.0) >= lo * lo && !(qx == 0.0 && qy == 1.0) {
            qy -= 1.0;
        }
        qy <= half && (qx * qx + qy * qy).sqrt() <= hi
    })
}

/// Seeds of the top and bottom surfaces derived from one user seed (SplitMix64 steps), so that the
/// two surfaces are independent yet reproducible.
pub fn pair_seeds(seed: u64) -> (u64, u64) {
    fn splitmix(mut z: u64) -> u64 {
        z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    (splitmix(seed ^ 0x746f_7000), splitmix(seed ^ 0x626f_7474_6f6d))
}

impl Surface {
    /// Wraps a height field after checking it: square, at least 16², even side, all finite.
    pub fn new(name: &str, n: usize, length: f64, heights: Vec<f64>) -> Result<Self> {
        if heights.is_empty() {
            return Err(Error::InvalidSurface {
                name: name.into(),
                message: "the height array is empty".into(),
            });
        }
        if heights.len() != n * n {
            return Err(Error::InvalidSurface {
                name: name.into(),
                message: format!("{} values do not fill a {n}×{n} grid", heights.len()),
            });
        }
        check_grid(n).map_err(|e| Error::InvalidSurface {
            name: name.into(),
            message: e.to_string(),
        })?;
        positive("length", length)?;
        if let Some(k) = heights.iter().position(|h| !h.is_finite()) {
            return Err(Error::InvalidSurface {
                name: name.into(),
                message: format!(
                    "height at index ({}, {}) is {}; fill or crop non-finite pixels before use",
                    k / n,
                    k % n,
                    heights[k]
                ),
            });
        }
        let s = Self { n, length, heights };
        if !s.rms_height().is_finite() {
            return Err(Error::InvalidSurface {
                name: name.into(),
                message: "the heights are so large that their statistics overflow; check the file's height unit".into(),
            });
        }
        Ok(s)
    }

    /// Generates a periodic self-affine surface with isotropic PSD Φ(q) ∝ |q|^(−2(1+H)) for
    /// q_u ≤ |q| ≤ q_l and zero elsewhere, zero mean and RMS height exactly `params.rms_height`.
    /// Bit-identical for a given seed whatever the thread count (random numbers are drawn
    /// sequentially; the FFTs are deterministic).
    pub fn generate(n: usize, length: f64, params: &SpectrumParams, seed: u64) -> Result<Self> {
        params.validate(n, length)?;
        let q_lower = length / params.lambda_upper; // q_u: smallest wavenumber
        let q_upper = length / params.lambda_lower; // q_l: largest wavenumber
        let exponent = -(1.0 + params.hurst); // √Φ ∝ |q|^−(1+H)
        let amplitude = move |qx: f64, qy: f64| {
            let q = (qx * qx + qy * qy).sqrt();
            if q >= q_lower * (1.0 - 1e-12) && q <= q_upper * (1.0 + 1e-12) && q > 0.0 {
                q.powf(exponent)
            } else {
                0.0
            }
        };
        let mut rng = ChaCha20Rng::seed_from_u64(seed);
        let mut plan = FftPlan::new(n);
        let mut heights = vec![0.0; n * n];
        match params.generation {
            Generation::RandomPhase => {
                let half = plan.half();
                let stride = plan.row_stride();
                let spec = plan.spectrum_mut();
                for qy in 0..half {
                    for qx in 0..n {
                        let phase = rng.gen::<f64>() * 2.0 * PI;
                        let a = amplitude(wavenumber(qx, n), qy as f64);
                        spec[qy * stride + qx] = C64::from_polar(a, phase);
                    }
                }
                // Rows q_y = 0 and q_y = N/2 are their own conjugate partners: make them Hermitian in
                // q_x so that the heights are real.
                for qy in [0, n / 2] {
                    let row = &mut spec[qy * stride..qy * stride + n];
                    for qx in n / 2 + 1..n {
                        row[qx] = row[n - qx].conj();
                    }
                    row[0].im = 0.0;
                    row[n / 2].im = 0.0;
                }
                plan.inverse(&mut heights);
            }
            Generation::FilteredNoise => {
                let noise: Vec<f64> = (0..n * n).map(|_| rng.sample(StandardNormal)).collect();
                let kernel = radial_kernel(n, amplitude);
                plan.convolve(&noise, &kernel, &mut heights);
            }
        }
        let mut s = Self { n, length, heights };
        s.rescale(params.rms_height);
        // Heights and their statistics (squares) must stay in the floating-point range.
        if s.heights.iter().any(|h| !h.is_finite()) || !s.rms_height().is_finite() {
            return Err(Error::param(
                "rms_height",
                format!(
                    "{} makes the heights overflow the floating-point range; give a physical value",
                    params.rms_height
                ),
            ));
        }
        Ok(s)
    }

    /// Removes the mean and scales to the given RMS height.
    fn rescale(&mut self, rms_height: f64) {
        let mean = self.heights.iter().sum::<f64>() / self.heights.len() as f64;
        self.heights.par_iter_mut().for_each(|h| *h -= mean);
        let rms = self.rms_height();
        let factor = rms_height / rms;
        self.heights.par_iter_mut().for_each(|h| *h *= factor);
    }

    /// Reads a square 2D `.npy` array of f64 or f32 heights (C or Fortran order).
    pub fn read_npy(path: &Path, length: f64) -> Result<Self> {
        let name = path.display().to_string();
        let array = read_npy_2d(path, &[NpyType::Float64, NpyType::Float32], "a height map")?;
        if array.rows != array.cols {
            return Err(Error::InvalidSurface {
                name,
                message: format!(
                    "array is {}×{}; a periodic surface must be square",
                    array.rows, array.cols
                ),
            });
        }
        Self::new(&name, array.rows, length, array.values)
    }

    /// Writes the heights as a float64 `.npy` array (atomically: temporary file, then rename).
    pub fn write_npy(&self, path: &Path) -> Result<()> {
        write_npy_f64(path, self.n, self.n, &self.heights)
    }

    /// Grid size N.
    pub fn n(&self) -> usize {
        self.n
    }

    /// Side length L.
    pub fn length(&self) -> f64 {
        self.length
    }

    /// Pixel size Δx = L/N.
    pub fn pixel_size(&self) -> f64 {
        self.length / self.n as f64
    }

    /// Heights, row-major, i along x.
    pub fn heights(&self) -> &[f64] {
        &self.heights
    }

    /// RMS height about the mean.
    pub fn rms_height(&self) -> f64 {
        let n2 = self.heights.len() as f64;
        let mean = self.heights.iter().sum::<f64>() / n2;
        (self.heights.iter().map(|h| (h - mean) * (h - mean)).sum::<f64>() / n2).sqrt()
    }

    /// RMS slope √⟨|∇h|²⟩, computed spectrally (exact for the periodic band-limited field).
    pub fn rms_slope(&self) -> f64 {
        let n = self.n;
        let mut plan = FftPlan::new(n);
        plan.forward(&self.heights);
        let k0 = 2.0 * PI / self.length;
        let mut sum = 0.0;
        for_each_mode(&plan, |qx, qy, c, weight| {
            sum += weight * (qx * qx + qy * qy) * k0 * k0 * c.norm_sqr();
        });
        (sum / ((n * n) as f64).powi(2)).sqrt()
    }

    /// Radially averaged power spectrum: for each integer wavenumber shell |q| ∈ [m − ½, m + ½)
    /// (m ≥ 1, q in units of 2π/L), the mean variance per Fourier mode ⟨|ĥ(q)|²⟩/N⁴ (length²), so
    /// that Σ over all modes equals h_rms². Returns `(q, psd)` pairs for non-empty shells.
    pub fn radial_psd(&self) -> Vec<(f64, f64)> {
        let n = self.n;
        let mut plan = FftPlan::new(n);
        plan.forward(&self.heights);
        let shells = n; // |q| ≤ N/√2 < N
        let mut sum = vec![0.0; shells];
        let mut count = vec![0.0; shells];
        for_each_mode(&plan, |qx, qy, c, weight| {
            let m = (qx * qx + qy * qy).sqrt().round() as usize;
            if m >= 1 && m < shells {
                sum[m] += weight * c.norm_sqr();
                count[m] += weight;
            }
        });
        let n4 = ((n * n) as f64).powi(2);
        (1..shells)
            .filter(|&m| count[m] > 0.0)
            .map(|m| (m as f64, sum[m] / count[m] / n4))
            .collect()
    }
}

/// Visits every mode of the half spectrum with its weight in the full spectrum (2 for the modes whose
/// conjugate partner is not stored).
fn for_each_mode(plan: &FftPlan, mut f: impl FnMut(f64, f64, C64, f64)) {
    let n = plan.n();
    let stride = plan.row_stride();
    let spec = plan.spectrum();
    for qy in 0..plan.half() {
        let weight = if qy == 0 || qy == n / 2 { 1.0 } else { 2.0 };
        for qx in 0..n {
            f(wavenumber(qx, n), qy as f64, spec[qy * stride + qx], weight);
        }
    }
}

/// Composite height of Johnson's equivalent rigid surface at a sliding offset of `offset` pixels
/// along x (paper §2): `bottom + np.roll(top, offset, axis=0)`, i.e.
/// `h[i, j] = bottom[i, j] + top[(i − offset) mod N, j]`. Written into `out` (N² values).
pub fn composite_heights(top: &Surface, bottom: &Surface, offset: usize, out: &mut [f64]) {
    let n = top.n();
    assert_eq!(bottom.n(), n, "surfaces must share the grid");
    let (t, b) = (top.heights(), bottom.heights());
    out.par_chunks_mut(n).enumerate().for_each(|(i, row)| {
        let src = (i + n - offset % n) % n;
        for ((o, &bv), &tv) in row
            .iter_mut()
            .zip(&b[i * n..(i + 1) * n])
            .zip(&t[src * n..(src + 1) * n])
        {
            *o = bv + tv;
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params() -> SpectrumParams {
        SpectrumParams {
            hurst: 0.7,
            lambda_lower: 1.0 / 32.0,
            lambda_upper: 1.0 / 4.0,
            rms_height: 0.005,
            generation: Generation::RandomPhase,
        }
    }

    #[test]
    fn exact_rms_and_zero_mean() {
        for generation in [Generation::RandomPhase, Generation::FilteredNoise] {
            let s = Surface::generate(64, 1.0, &SpectrumParams { generation, ..params() }, 7).unwrap();
            assert!((s.rms_height() - 0.005).abs() < 1e-15);
            let mean: f64 = s.heights().iter().sum::<f64>() / 4096.0;
            assert!(mean.abs() < 1e-15);
        }
    }

    #[test]
    fn same_seed_same_surface_on_any_thread_count() {
        let gen = |threads: usize, seed: u64| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| Surface::generate(128, 1.0, &params(), seed).unwrap())
        };
        assert_eq!(gen(1, 3), gen(2, 3));
        assert_ne!(gen(1, 3), gen(1, 4));
        let (a, b) = pair_seeds(3);
        assert_ne!(a, b);
    }

    #[test]
    fn spectrum_is_band_limited() {
        let s = Surface::generate(64, 1.0, &params(), 1).unwrap();
        for (q, c) in s.radial_psd() {
            // Shells entirely outside [4, 32] must be empty (up to round-off).
            if q <= 3.0 || q >= 33.0 {
                assert!(c < 1e-25, "q = {q}: {c}");
            }
        }
    }

    #[test]
    fn an_empty_band_or_an_overflowing_height_is_refused() {
        let empty = SpectrumParams {
            lambda_lower: 0.3,
            lambda_upper: 0.31,
            ..params()
        };
        let e = empty.validate(64, 1.0).unwrap_err().to_string();
        assert!(e.contains("no Fourier mode"), "{e}");
        // A narrow band around an integer wavenumber is fine: |q| = 3.
        assert!(SpectrumParams {
            lambda_lower: 1.0 / 3.0,
            lambda_upper: 0.34,
            ..params()
        }
        .validate(64, 1.0)
        .is_ok());
        // Only a diagonal mode: |q| = √2 ≈ 1.414.
        assert!(SpectrumParams {
            lambda_lower: 1.0 / 1.42,
            lambda_upper: 1.0 / 1.41,
            ..params()
        }
        .validate(64, 1.0)
        .is_ok());
        let huge = SpectrumParams {
            rms_height: 1e300,
            ..params()
        };
        let e = match Surface::generate(64, 1.0, &huge, 1) {
            Ok(_) => panic!("rms_height = 1e300 was accepted"),
            Err(e) => e.to_string(),
        };
        assert!(e.contains("rms_height"), "{e}");
    }

    #[test]
    fn rejects_bad_heights() {
        let mut h = vec![0.0; 256];
        h[17] = f64::NAN;
        let e = Surface::new("top", 16, 1.0, h).unwrap_err().to_string();
        assert!(e.contains("(1, 1)") && e.contains("NaN"), "{e}");
        assert!(Surface::new("top", 16, 1.0, vec![]).is_err());
        assert!(Surface::new("top", 16, 1.0, vec![0.0; 255]).is_err());
    }
}
