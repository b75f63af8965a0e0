//! Self-affine parameters (H, λ_l, λ_u, h_rms) fitted to a surface's PSD, and the run-file block that
//! generates periodic surfaces with them.

use crate::error::{Error, Result};
use crate::grid::Grid;
use crate::stats::line_fit;
use crate::surface::{Generation, SpectrumParams, Surface};

/// Self-affine parameters estimated from a surface's radially averaged PSD.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SpectrumFit {
    /// Hurst exponent H from the slope −2(1 + H) of the PSD between the cut-offs.
    pub hurst: f64,
    /// Shortest wavelength λ_l (the high-wavenumber end of the power law).
    pub lambda_lower: f64,
    /// Longest wavelength λ_u (the low-wavenumber end of the power law, or the box).
    pub lambda_upper: f64,
    pub rms_height: f64,
    /// R² of the power-law fit in log–log.
    pub r2: Option<f64>,
    /// Shells of the PSD the fit used.
    pub shells: usize,
}

/// How [`fit`] works, in one sentence for the documents that report a fit.
pub const FIT_METHOD: &str =
    "least-squares line through ln PSD against ln q over the shells that follow it (grown from \
the middle of the spectrum while each shell stays within a factor 2 of the line); slope −2(1+H); λ_l and λ_u where the \
power law ends";

/// Estimates H, λ_l, λ_u and h_rms from the radially averaged PSD of `surface`: the power law is
/// fitted in log–log over the wavenumbers where the PSD follows it (grown from the middle of the
/// spectrum while each shell stays within a factor 2 of the line), and the cut-offs are where it
/// stops following it (the PSD drops or flattens).
pub fn fit(surface: &Surface) -> Result<SpectrumFit> {
    let psd: Vec<(f64, f64)> = surface.radial_psd();
    let peak = psd.iter().map(|p| p.1).fold(0.0f64, f64::max);
    let live: Vec<(f64, f64)> = psd
        .into_iter()
        .filter(|p| p.1 > 1e-12 * peak)
        .map(|(q, c)| (q.ln(), c.ln()))
        .collect();
    if live.len() < 4 {
        return Err(Error::InvalidSurface {
            name: "surface".into(),
            message: "its spectrum has fewer than four non-empty wavenumber shells; nothing to fit".into(),
        });
    }
    let line = |lo: usize, hi: usize| {
        let (x, y): (Vec<f64>, Vec<f64>) = live[lo..=hi].iter().copied().unzip();
        line_fit(&x, &y).map(|f| (f.slope, f.intercept, f.r2))
    };
    // Start from the middle half of the live shells and grow while the PSD follows the line.
    let (mut lo, mut hi) = (
        live.len() / 4,
        (3 * live.len() / 4).max(live.len() / 4 + 2).min(live.len() - 1),
    );
    let tolerance = 2f64.ln();
    while let Some((slope, intercept, _)) = line(lo, hi) {
        let follows = |k: usize| (live[k].1 - (intercept + slope * live[k].0)).abs() < tolerance;
        let mut grew = false;
        if lo > 0 && follows(lo - 1) {
            lo -= 1;
            grew = true;
        }
        if hi + 1 < live.len() && follows(hi + 1) {
            hi += 1;
            grew = true;
        }
        if !grew {
            break;
        }
    }
    // The shells at the ends of the power law straddle the cut-offs (only part of their modes lie
    // inside the band), so the slope comes from the shells between them when there are enough.
    let (a, b) = if hi - lo >= 6 { (lo + 1, hi - 1) } else { (lo, hi) };
    let (slope, _, r2) = line(a, b).ok_or_else(|| Error::InvalidSurface {
        name: "surface".into(),
        message: "its spectrum cannot be fitted by a power law".into(),
    })?;
    let length = surface.length();
    Ok(SpectrumFit {
        hurst: -slope / 2.0 - 1.0,
        lambda_lower: length / live[hi].0.exp(),
        lambda_upper: length / live[lo].0.exp(),
        rms_height: surface.rms_height(),
        r2,
        shells: hi - lo + 1,
    })
}

impl SpectrumFit {
    /// Parameters to generate periodic surfaces with the fitted statistics on `grid`: λ_l raised to
    /// two pixels and λ_u lowered to the box where the fit ran past them (a note says so).
    pub fn spectrum(&self, grid: &Grid) -> (SpectrumParams, Vec<String>) {
        let mut notes = Vec::new();
        let two_pixels = 2.0 * grid.pixel_size();
        let lambda_lower = if self.lambda_lower < two_pixels {
            notes.push(format!(
                "the power law runs to the pixel scale, so λ_l = {:.4e} is set to two pixels ({two_pixels:.4e}): it is \
                 the resolution of the measurement, not a property of the surface",
                self.lambda_lower
            ));
            two_pixels
        } else {
            self.lambda_lower
        };
        let longest = grid.length_x().max(grid.length_y());
        let lambda_upper = if self.lambda_upper > longest {
            notes.push(format!(
                "λ_u = {:.4e} is beyond the box and is set to its side ({longest:.4e}): the measurement is too small \
                 to see where the power law ends at long wavelengths",
                self.lambda_upper
            ));
            longest
        } else {
            self.lambda_upper
        };
        let params = SpectrumParams {
            hurst: self.hurst.clamp(0.01, 1.0),
            lambda_lower,
            lambda_upper,
            rms_height: self.rms_height,
            generation: Generation::RandomPhase,
        };
        if params.hurst != self.hurst {
            notes.push(format!(
                "H = {:.3} is outside (0, 1] and is set to {:.3}",
                self.hurst, params.hurst
            ));
        }
        (params, notes)
    }
}

/// The `[surface]` block of a run file that generates periodic surfaces with `spectrum` on `grid`,
/// headed by a comment saying where the parameters come from; lengths in `unit`.
pub fn surface_block(grid: &Grid, spectrum: &SpectrumParams, seed: u64, source: &str, unit: &str) -> String {
    let sides = |x: String, y: String| if x == y { x } else { format!("[{x}, {y}]") };
    // Whole numbers of the box as written; fitted values to four significant digits.
    format!(
        "# Periodic self-affine surfaces with the statistics of {source}; lengths in {unit}.\n\
         [surface]\n\
         grid = {}\n\
         length = {}\n\
         hurst = {:.4}\n\
         lambda_lower = {:.4e}\n\
         lambda_upper = {:.4e}\n\
         rms_height = {:.4e}\n\
         seed = {seed}\n",
        sides(grid.nx().to_string(), grid.ny().to_string()),
        sides(grid.length_x().to_string(), grid.length_y().to_string()),
        spectrum.hurst,
        spectrum.lambda_lower,
        spectrum.lambda_upper,
        spectrum.rms_height,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fitting_recovers_the_parameters_of_generated_surfaces() {
        let (square, oblong) = (Grid::square(512, 1.0).unwrap(), Grid::new(512, 256, 1.0).unwrap());
        for (hurst, lower, upper, generation, grid, seed) in [
            (0.7, 1.0 / 64.0, 1.0 / 4.0, Generation::RandomPhase, square, 3),
            (0.5, 1.0 / 32.0, 1.0 / 8.0, Generation::RandomPhase, square, 3),
            (0.9, 1.0 / 100.0, 1.0 / 5.0, Generation::RandomPhase, square, 3),
            (0.3, 1.0 / 128.0, 1.0 / 4.0, Generation::RandomPhase, square, 4),
            (0.7, 1.0 / 64.0, 1.0 / 4.0, Generation::FilteredNoise, square, 3),
            (0.5, 1.0 / 100.0, 1.0 / 8.0, Generation::FilteredNoise, square, 5),
            (0.8, 1.0 / 64.0, 1.0 / 4.0, Generation::RandomPhase, oblong, 6),
            (0.6, 1.0 / 64.0, 1.0 / 8.0, Generation::FilteredNoise, oblong, 7),
        ] {
            let params = SpectrumParams {
                hurst,
                lambda_lower: lower,
                lambda_upper: upper,
                rms_height: 0.01,
                generation,
            };
            let s = Surface::generate(grid, &params, seed).unwrap();
            let f = fit(&s).unwrap();
            assert!((f.hurst - hurst).abs() <= 0.05, "H {hurst}: {f:?}");
            assert!(
                f.lambda_lower / lower < 1.2 && lower / f.lambda_lower < 1.2,
                "λ_l {lower}: {f:?}"
            );
            assert!(
                f.lambda_upper / upper < 1.2 && upper / f.lambda_upper < 1.2,
                "λ_u {upper}: {f:?}"
            );
            assert!((f.rms_height - 0.01).abs() < 1e-12);
        }
    }
}
