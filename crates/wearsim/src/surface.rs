//! Periodic self-affine rough surfaces (paper §2 and §4.1): generation, `.npy` input/output and statistics.

use std::f64::consts::PI;
use std::path::Path;

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha20Rng;
use rand_distr::StandardNormal;
use rayon::prelude::*;

use crate::check::positive;
use crate::error::{Error, Result};
use crate::fft::{radial_kernel, wavenumber, FftPlan, C64};
use crate::grid::Grid;
use crate::io::{read_npy_2d, write_npy_f64, NpyType};

/// A periodic height field on an Nx × Ny grid of square pixels; `heights[i * ny + j]`, i along x
/// (the sliding direction).
#[derive(Debug, Clone, PartialEq)]
pub struct Surface {
    grid: Grid,
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

    /// Checks the parameters against a grid: H in (0, 1], λ_l at least two pixels, λ_l < λ_u ≤ the
    /// longer side, and at least one Fourier mode of the grid in the band.
    pub fn validate(&self, grid: &Grid) -> Result<()> {
        if !(self.hurst > 0.0 && self.hurst <= 1.0) {
            return Err(Error::param("hurst", format!("{} must lie in (0, 1]", self.hurst)));
        }
        positive("rms_height", self.rms_height)?;
        positive("lambda_lower", self.lambda_lower)?;
        let dx = grid.pixel_size();
        let length = grid.length_x().max(grid.length_y());
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
        let lx = grid.length_x();
        if !band_has_modes(grid, lx / self.lambda_upper, lx / self.lambda_lower) {
            return Err(Error::param(
                "lambda_upper",
                format!(
                    "the band of wavelengths [{}, {}] holds no Fourier mode of the {} × {} grid of side {lx} (the \
                     wavenumbers Lx/λ between {:.4} and {:.4} include no lattice point), so the surface would be flat; \
                     widen the band between `lambda_lower` and `lambda_upper`",
                    self.lambda_lower,
                    self.lambda_upper,
                    grid.nx(),
                    grid.ny(),
                    lx / self.lambda_upper,
                    lx / self.lambda_lower
                ),
            ));
        }
        Ok(())
    }
}

/// Whether some non-zero wavenumber of the grid has q_lo ≤ |q| ≤ q_hi (|q| in units of 2π/Lx, with
/// the tolerance of the generator).
fn band_has_modes(grid: &Grid, q_lo: f64, q_hi: f64) -> bool {
    let (lo, hi) = (q_lo * (1.0 - 1e-12), q_hi * (1.0 + 1e-12));
    let r = grid.aspect();
    (0..=grid.nx() / 2).any(|qx| {
        let qx = qx as f64;
        (0..=grid.ny() / 2).any(|qy| {
            let q = (qx * qx + (qy as f64 * r) * (qy as f64 * r)).sqrt();
            q > 0.0 && q >= lo && q <= hi
        })
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
    /// Wraps a height field after checking it: Nx·Ny finite values on a valid grid.
    pub fn new(name: &str, grid: Grid, heights: Vec<f64>) -> Result<Self> {
        let (nx, ny) = (grid.nx(), grid.ny());
        if heights.is_empty() {
            return Err(Error::InvalidSurface {
                name: name.into(),
                message: "the height array is empty".into(),
            });
        }
        if heights.len() != nx * ny {
            return Err(Error::InvalidSurface {
                name: name.into(),
                message: format!("{} values do not fill a {nx}×{ny} grid", heights.len()),
            });
        }
        if let Some(k) = heights.iter().position(|h| !h.is_finite()) {
            return Err(Error::InvalidSurface {
                name: name.into(),
                message: format!(
                    "height at index ({}, {}) is {}; fill or crop non-finite pixels before use",
                    k / ny,
                    k % ny,
                    heights[k]
                ),
            });
        }
        let s = Self { grid, heights };
        if !s.rms_height().is_finite() {
            return Err(Error::InvalidSurface {
                name: name.into(),
                message: "the heights are so large that their statistics overflow; check the file's height unit".into(),
            });
        }
        Ok(s)
    }

    /// Wraps a height field of `rows × cols` values read from somewhere (a file, an array): the grid
    /// is checked with its errors reported as errors of the surface `name`.
    pub fn from_array(name: &str, rows: usize, cols: usize, length_x: f64, heights: Vec<f64>) -> Result<Self> {
        if heights.is_empty() || rows == 0 || cols == 0 {
            return Err(Error::InvalidSurface {
                name: name.into(),
                message: "the height array is empty".into(),
            });
        }
        let grid = Grid::new(rows, cols, length_x).map_err(|e| match e {
            Error::InvalidParameter { field, message } if field == "grid" => Error::InvalidSurface {
                name: name.into(),
                message: format!("a {rows}×{cols} array: {message}"),
            },
            other => other,
        })?;
        Self::new(name, grid, heights)
    }

    /// Generates a periodic self-affine surface with isotropic PSD Φ(q) ∝ |q|^(−2(1+H)) for
    /// q_u ≤ |q| ≤ q_l and zero elsewhere, zero mean and RMS height exactly `params.rms_height`.
    /// Bit-identical for a given seed whatever the thread count (random numbers are drawn
    /// sequentially; the FFTs are deterministic).
    pub fn generate(grid: Grid, params: &SpectrumParams, seed: u64) -> Result<Self> {
        params.validate(&grid)?;
        let (nx, ny) = (grid.nx(), grid.ny());
        let length = grid.length_x();
        let q_lower = length / params.lambda_upper; // q_u: smallest wavenumber, units of 2π/Lx
        let q_upper = length / params.lambda_lower; // q_l: largest wavenumber
        let exponent = -(1.0 + params.hurst); // √Φ ∝ |q|^−(1+H)
        let r = grid.aspect(); // q_y in units of 2π/Lx
        let amplitude = move |qx: f64, qy: f64| {
            let qy = qy * r;
            let q = (qx * qx + qy * qy).sqrt();
            if q >= q_lower * (1.0 - 1e-12) && q <= q_upper * (1.0 + 1e-12) && q > 0.0 {
                q.powf(exponent)
            } else {
                0.0
            }
        };
        let mut rng = ChaCha20Rng::seed_from_u64(seed);
        let mut plan = FftPlan::new(nx, ny);
        let mut heights = vec![0.0; nx * ny];
        match params.generation {
            Generation::RandomPhase => {
                let half = plan.half();
                let stride = plan.row_stride();
                let spec = plan.spectrum_mut();
                for qy in 0..half {
                    for qx in 0..nx {
                        let phase = rng.random::<f64>() * 2.0 * PI;
                        let a = amplitude(wavenumber(qx, nx), qy as f64);
                        spec[qy * stride + qx] = C64::from_polar(a, phase);
                    }
                }
                // Rows q_y = 0 and q_y = Ny/2 are their own conjugate partners: make them Hermitian in
                // q_x so that the heights are real.
                for qy in [0, ny / 2] {
                    let row = &mut spec[qy * stride..qy * stride + nx];
                    for qx in nx / 2 + 1..nx {
                        row[qx] = row[nx - qx].conj();
                    }
                    row[0].im = 0.0;
                    row[nx / 2].im = 0.0;
                }
                plan.inverse(&mut heights);
            }
            Generation::FilteredNoise => {
                let noise: Vec<f64> = (0..nx * ny).map(|_| rng.sample(StandardNormal)).collect();
                let kernel = radial_kernel(nx, ny, amplitude);
                plan.convolve(&noise, &kernel, &mut heights);
            }
        }
        let mut s = Self { grid, heights };
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

    /// Reads a 2D `.npy` array of f64 or f32 heights (C or Fortran order) whose side along x (the
    /// first axis) is `length_x`.
    pub fn read_npy(path: &Path, length_x: f64) -> Result<Self> {
        let name = path.display().to_string();
        let array = read_npy_2d(path, &[NpyType::Float64, NpyType::Float32], "a height map")?;
        Self::from_array(&name, array.rows, array.cols, length_x, array.values)
    }

    /// Writes the heights as a float64 `.npy` array (atomically: temporary file, then rename).
    pub fn write_npy(&self, path: &Path) -> Result<()> {
        write_npy_f64(path, self.grid.nx(), self.grid.ny(), &self.heights)
    }

    /// The grid.
    pub fn grid(&self) -> Grid {
        self.grid
    }

    /// Pixels along x (the sliding direction).
    pub fn nx(&self) -> usize {
        self.grid.nx()
    }

    /// Pixels along y.
    pub fn ny(&self) -> usize {
        self.grid.ny()
    }

    /// Side length along x, Lx.
    pub fn length(&self) -> f64 {
        self.grid.length_x()
    }

    /// Pixel size Δx.
    pub fn pixel_size(&self) -> f64 {
        self.grid.pixel_size()
    }

    /// Heights, row-major, i along x.
    pub fn heights(&self) -> &[f64] {
        &self.heights
    }

    /// The heights, taken out.
    pub fn into_heights(self) -> Vec<f64> {
        self.heights
    }

    /// RMS height about the mean.
    pub fn rms_height(&self) -> f64 {
        let n2 = self.heights.len() as f64;
        let mean = self.heights.iter().sum::<f64>() / n2;
        (self.heights.iter().map(|h| (h - mean) * (h - mean)).sum::<f64>() / n2).sqrt()
    }

    /// RMS slope √⟨|∇h|²⟩, computed spectrally (exact for the periodic band-limited field).
    pub fn rms_slope(&self) -> f64 {
        let (nx, ny) = (self.nx(), self.ny());
        let mut plan = FftPlan::new(nx, ny);
        plan.forward(&self.heights);
        let k0 = 2.0 * PI / self.length();
        let r = self.grid.aspect();
        let mut sum = 0.0;
        for_each_mode(&plan, |qx, qy, c, weight| {
            let qy = qy * r;
            sum += weight * (qx * qx + qy * qy) * k0 * k0 * c.norm_sqr();
        });
        (sum / ((nx * ny) as f64).powi(2)).sqrt()
    }

    /// Radially averaged power spectrum: for each integer wavenumber shell |q| ∈ [m − ½, m + ½)
    /// (m ≥ 1, q in units of 2π/Lx), the mean variance per Fourier mode ⟨|ĥ(q)|²⟩/(NxNy)² (length²),
    /// so that Σ over all modes equals h_rms². Returns `(q, psd)` pairs for non-empty shells.
    pub fn radial_psd(&self) -> Vec<(f64, f64)> {
        self.radial_psd_shells().into_iter().map(|s| (s.q, s.psd)).collect()
    }

    /// The shells of [`radial_psd`](Self::radial_psd) with the number of Fourier modes each averages
    /// (of the full spectrum, so conjugate pairs count twice): a shell of n modes holds n/2
    /// independent complex amplitudes, and its mean scatters by √(2/n) of itself for a Gaussian
    /// surface.
    pub fn radial_psd_shells(&self) -> Vec<PsdShell> {
        let (nx, ny) = (self.nx(), self.ny());
        let mut plan = FftPlan::new(nx, ny);
        plan.forward(&self.heights);
        let r = self.grid.aspect();
        let shells = nx; // |q| ≤ Nx/√2 < Nx
        let mut sum = vec![0.0; shells];
        let mut count = vec![0.0; shells];
        for_each_mode(&plan, |qx, qy, c, weight| {
            let qy = qy * r;
            let m = (qx * qx + qy * qy).sqrt().round() as usize;
            if m >= 1 && m < shells {
                sum[m] += weight * c.norm_sqr();
                count[m] += weight;
            }
        });
        let n4 = ((nx * ny) as f64).powi(2);
        (1..shells)
            .filter(|&m| count[m] > 0.0)
            .map(|m| PsdShell {
                q: m as f64,
                psd: sum[m] / count[m] / n4,
                modes: count[m],
            })
            .collect()
    }
}

/// One wavenumber shell of the radially averaged PSD ([`Surface::radial_psd_shells`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PsdShell {
    /// The shell's wavenumber m (|q| ∈ [m − ½, m + ½)), in units of 2π/Lx.
    pub q: f64,
    /// Mean variance per Fourier mode of the shell (length²).
    pub psd: f64,
    /// Fourier modes averaged (of the full spectrum).
    pub modes: f64,
}

/// Visits every mode of the half spectrum with its weight in the full spectrum (2 for the modes whose
/// conjugate partner is not stored); wavenumbers are integers in units of 2π/Lx and 2π/Ly.
fn for_each_mode(plan: &FftPlan, mut f: impl FnMut(f64, f64, C64, f64)) {
    let (nx, ny) = (plan.nx(), plan.ny());
    let stride = plan.row_stride();
    let spec = plan.spectrum();
    for qy in 0..plan.half() {
        let weight = if qy == 0 || qy == ny / 2 { 1.0 } else { 2.0 };
        for qx in 0..nx {
            f(wavenumber(qx, nx), qy as f64, spec[qy * stride + qx], weight);
        }
    }
}

/// Composite height of Johnson's equivalent rigid surface at a sliding offset of `offset` pixels
/// along x (paper §2): `bottom + np.roll(top, offset, axis=0)`, i.e.
/// `h[i, j] = bottom[i, j] + top[(i − offset) mod Nx, j]`. Written into `out` (Nx·Ny values).
pub fn composite_heights(top: &Surface, bottom: &Surface, offset: usize, out: &mut [f64]) {
    let (nx, ny) = (top.nx(), top.ny());
    assert!(bottom.nx() == nx && bottom.ny() == ny, "surfaces must share the grid");
    let (t, b) = (top.heights(), bottom.heights());
    out.par_chunks_mut(ny).enumerate().for_each(|(i, row)| {
        let src = (i + nx - offset % nx) % nx;
        for ((o, &bv), &tv) in row
            .iter_mut()
            .zip(&b[i * ny..(i + 1) * ny])
            .zip(&t[src * ny..(src + 1) * ny])
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

    fn square(n: usize) -> Grid {
        Grid::square(n, 1.0).unwrap()
    }

    #[test]
    fn exact_rms_and_zero_mean() {
        for generation in [Generation::RandomPhase, Generation::FilteredNoise] {
            for grid in [square(64), Grid::new(64, 32, 1.0).unwrap()] {
                let s = Surface::generate(grid, &SpectrumParams { generation, ..params() }, 7).unwrap();
                assert!((s.rms_height() - 0.005).abs() < 1e-15);
                let mean: f64 = s.heights().iter().sum::<f64>() / grid.pixels() as f64;
                assert!(mean.abs() < 1e-15);
            }
        }
    }

    #[test]
    fn same_seed_same_surface_on_any_thread_count() {
        let gen = |threads: usize, seed: u64| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| Surface::generate(square(128), &params(), seed).unwrap())
        };
        assert_eq!(gen(1, 3), gen(2, 3));
        assert_ne!(gen(1, 3), gen(1, 4));
        let (a, b) = pair_seeds(3);
        assert_ne!(a, b);
    }

    #[test]
    fn spectrum_is_band_limited() {
        for grid in [square(64), Grid::new(64, 128, 1.0).unwrap()] {
            let s = Surface::generate(grid, &params(), 1).unwrap();
            for (q, c) in s.radial_psd() {
                // Shells entirely outside [4, 32] must be empty (up to round-off).
                if q <= 3.0 || q >= 33.0 {
                    assert!(c < 1e-25, "q = {q}: {c}");
                }
            }
        }
    }

    #[test]
    fn a_rectangular_surface_is_isotropic() {
        // 128 × 64 pixels, box 1 × 0.5: the RMS slope along x and along y agree statistically.
        let grid = Grid::new(128, 64, 1.0).unwrap();
        let s = Surface::generate(
            grid,
            &SpectrumParams {
                lambda_lower: 1.0 / 16.0,
                lambda_upper: 0.25,
                ..params()
            },
            5,
        )
        .unwrap();
        let h = s.heights();
        let (mut gx, mut gy) = (0.0, 0.0);
        for i in 0..128 {
            for j in 0..64 {
                let dx = h[((i + 1) % 128) * 64 + j] - h[i * 64 + j];
                let dy = h[i * 64 + (j + 1) % 64] - h[i * 64 + j];
                gx += dx * dx;
                gy += dy * dy;
            }
        }
        assert!((gx / gy - 1.0).abs() < 0.3, "slopes along x and y: {gx} vs {gy}");
    }

    #[test]
    fn an_empty_band_or_an_overflowing_height_is_refused() {
        let empty = SpectrumParams {
            lambda_lower: 0.3,
            lambda_upper: 0.31,
            ..params()
        };
        let e = empty.validate(&square(64)).unwrap_err().to_string();
        assert!(e.contains("no Fourier mode"), "{e}");
        // A narrow band around an integer wavenumber is fine: |q| = 3.
        assert!(SpectrumParams {
            lambda_lower: 1.0 / 3.0,
            lambda_upper: 0.34,
            ..params()
        }
        .validate(&square(64))
        .is_ok());
        // Only a diagonal mode: |q| = √2 ≈ 1.414.
        assert!(SpectrumParams {
            lambda_lower: 1.0 / 1.42,
            lambda_upper: 1.0 / 1.41,
            ..params()
        }
        .validate(&square(64))
        .is_ok());
        let huge = SpectrumParams {
            rms_height: 1e300,
            ..params()
        };
        let e = match Surface::generate(square(64), &huge, 1) {
            Ok(_) => panic!("rms_height = 1e300 was accepted"),
            Err(e) => e.to_string(),
        };
        assert!(e.contains("rms_height"), "{e}");
    }

    #[test]
    fn rejects_bad_heights() {
        let mut h = vec![0.0; 256];
        h[17] = f64::NAN;
        let e = Surface::new("top", square(16), h).unwrap_err().to_string();
        assert!(e.contains("(1, 1)") && e.contains("NaN"), "{e}");
        assert!(Surface::new("top", square(16), vec![]).is_err());
        assert!(Surface::new("top", square(16), vec![0.0; 255]).is_err());
        let e = Surface::from_array("top", 16, 15, 1.0, vec![0.0; 240])
            .unwrap_err()
            .to_string();
        assert!(e.contains("top") && e.contains("16×15"), "{e}");
    }
}
