//! Self-affine parameters (H, λ_l, λ_u, h_rms) fitted to a surface's PSD, and the run-file block that
//! generates periodic surfaces with them.
//!
//! The paper's surfaces (§4.1) are a power law C(q) ∝ q^−2(1+H) between q_u = 2π/λ_u and
//! q_l = 2π/λ_l and nothing else, and their h_rms is that band's. A measured map also holds power
//! outside the band (a waviness or form beyond λ_u, noise beyond λ_l), so the h_rms of the block is
//! the band's, the map's variance held by the modes the block generates, not the whole map's: the
//! whole map's would raise the PSD level of the generated band by the variance outside it.

use std::f64::consts::PI;

use crate::error::{Error, Result};
use crate::grid::Grid;
use crate::stats::line_fit;
use crate::surface::{Generation, PsdShell, SpectrumParams, Surface};

use super::spectrum::{MeasuredPsd, Window};

/// Self-affine parameters estimated from a surface's radially averaged PSD, with the band of
/// wavenumbers they come from and what was left out around it.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SpectrumFit {
    /// Hurst exponent H from the slope −2(1 + H) of the PSD in the band (paper §4.1).
    pub hurst: f64,
    /// Shortest wavelength λ_l: where the PSD leaves the power law at high wavenumbers (a cut-off, a
    /// floor), or the pixel scale.
    pub lambda_lower: f64,
    /// Longest wavelength λ_u: where the PSD leaves the power law at low wavenumbers (a roll-off), or
    /// the box.
    pub lambda_upper: f64,
    /// h_rms of the self-affine band (paper §4.1): the square root of the map's variance held by
    /// the modes with q_u ≤ |q| ≤ q_l on its grid, with λ_l and λ_u as [`SpectrumFit::spectrum`]
    /// writes them in the block, from the PSD as measured (Hann-windowed and normalised for a map
    /// that is not periodic, so that it sums to the map's variance). The block's `rms_height`: the
    /// surfaces it generates then carry the measured PSD level in the band, where the whole map's
    /// rms would add to the band the variance that lies outside it.
    pub rms_height: f64,
    /// RMS height of the whole map as fitted (levelled): the band's and what lies outside it.
    pub map_rms_height: f64,
    /// Share of the map's variance outside the band, 1 − h_rms²/(map's h_rms)² (0 where the band's
    /// estimate holds more, as a Hann-windowed one of a map with little outside the band may):
    /// power beyond λ_u (a waviness, a form) or beyond λ_l (noise), and the interpolated
    /// wavevectors of a resampled map, which the block leaves out.
    pub out_of_band_share: f64,
    /// Native pixel sizes [Δx, Δy] of a map resampled onto finer pixels, in its length unit: the
    /// fit used only the measured wavevectors, |q_x| ≤ π/Δx and |q_y| ≤ π/Δy. None when the whole
    /// stored spectrum was measured.
    pub measured_pixel: Option<[f64; 2]>,
    /// R² of the power-law fit in log–log.
    pub r2: Option<f64>,
    /// Shells of the PSD the slope was fitted on.
    pub shells: usize,
    /// Wavenumbers q = 2π/λ (radians per unit length) of the first and the last shell of the slope fit.
    pub fitted_q: [f64; 2],
    /// Shells at longer wavelengths than λ_u, left out (below a roll-off, or nothing but round-off).
    pub shells_longer: usize,
    /// Shells at shorter wavelengths than λ_l, left out: the floor (round-off of a band-limited
    /// surface, noise of a measurement) and whatever lies below the power law beyond its cut-off.
    pub shells_shorter: usize,
    /// Level of the floor (the median PSD over the outermost half octave of wavenumbers) relative to
    /// the power law at λ_l: about 1e-30 for round-off, ≤ 0.1 for a noise floor left out.
    pub floor: f64,
    /// The window of the PSD: Hann for a map that is not periodic (the jump at its borders would
    /// leak power ∝ q⁻² into every shell and bias H low), none for a periodic one.
    pub window: Window,
    /// Power of wavevectors nearer the x axis over that of those nearer the y axis over the fitted
    /// shells ([`MeasuredPsd::anisotropy`]): 1 for an isotropic spectrum.
    pub anisotropy: f64,
    /// How far the shell standing highest above the fitted power law (from the longest wavelengths
    /// to the end of the band) stands above it, beyond three standard deviations of its average:
    /// about 1 or less for a self-affine spectrum, a peak above [`PEAK`].
    pub peak: f64,
}

/// Whether a spectrum is self-affine, and if not what was seen.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Verdict {
    pub self_affine: bool,
    /// One sentence per reason the spectrum is not self-affine (none when it is).
    pub reasons: Vec<String>,
}

/// Power along one axis more than this factor above the other's (over the fitted shells, each
/// counted alike) is a lay: an isotropic 128² map's ratio scatters by a few % about 1, and a factor
/// 2 is a difference of √2 in RMS slope between the directions, which a self-affine (isotropic)
/// description would lose.
pub const ANISOTROPIC: f64 = 2.0;
/// A shell standing this factor above the fitted power law beyond three standard deviations of its
/// average is a peak: the shells of a self-affine band follow the line within a factor 2.
pub const PEAK: f64 = 5.0;
/// H beyond 1 by more than this is outside (0, 1] (the fit recovers the H of generated surfaces
/// within 0.05).
const HURST_SLACK: f64 = 0.05;
/// The fitted band of a self-affine spectrum spans at least this ratio of wavenumbers, two octaves:
/// over less, a slope cannot be told from the bend of a roll-off. (Not a decade: wearsim's own
/// self-affine surfaces with λ_u/λ_l = 8, as in the paper's window studies, fit over a factor 5–6
/// once the end shells that straddle the cut-offs are left out.)
const TWO_OCTAVES: f64 = 4.0;
/// R² of the log–log line below this: the PSD is no power law.
const R2_MIN: f64 = 0.9;

/// How [`fit`] works, in one sentence for the documents that report a fit.
pub const FIT_METHOD: &str = "least-squares line through ln PSD against ln q over the band of shells where the PSD \
carries the signal: shells within a factor 10 of the floor (the median PSD over the outermost half octave: round-off \
or noise) or below 1e-12 of the peak are left out, and the band is the widest run of at least 6 shells over at least \
an octave that stays within a factor 2 (or 3 standard deviations of its shell average) of its line, falls faster than \
q^-1 and has no longer wavelength 10 times above it; slope −2(1+H); λ_l and λ_u where the PSD leaves the power law; \
h_rms the band's (the map's variance over the modes 2π/λ_u ≤ |q| ≤ 2π/λ_l); for a map resampled onto finer pixels, \
only the measured wavevectors (|q_x| ≤ π/Δx, |q_y| ≤ π/Δy of its native pixels) are used";

/// A share of the map's variance outside the fitted band above this is worth a note: the block's
/// h_rms (the band's) is then noticeably less than the whole map's.
pub const OUT_OF_BAND: f64 = 0.1;

/// Shells below this fraction of the PSD's peak hold nothing but round-off.
const ROUND_OFF: f64 = 1e-12;
/// Shells less than this factor above the floor are the floor.
const ABOVE_FLOOR: f64 = 10.0;
/// A shell follows the power law within this factor of the line (or three standard deviations of
/// its average where it holds few modes).
const FOLLOWS: f64 = 2.0;
/// A band needs at least this many shells, spanning at least an octave.
pub const MIN_SHELLS: usize = 6;
/// A run of shells that a longer wavelength lies this factor (beyond its scatter) above is a floor or
/// a tail under the band, not the band.
const UNDER: f64 = 10.0;

/// Why [`fit`] finds no power-law band in the shells `all`, of which `signal` stand above the floor.
fn no_band(all: &[PsdShell], signal: &[usize]) -> String {
    let span = match (signal.first(), signal.last()) {
        (Some(&a), Some(&b)) => format!(
            "{} shells stand a factor {ABOVE_FLOOR} above the floor, between q = {} and {} × 2π/L",
            signal.len(),
            all[a].q,
            all[b].q
        ),
        _ => format!("no shell stands a factor {ABOVE_FLOOR} above the floor"),
    };
    format!(
        "its PSD follows no power law C(q) ∝ q^−2(1+H) over at least {MIN_SHELLS} wavenumber shells and an octave \
         ({span}), so H cannot be fitted: use a larger map or finer pixels, or a measurement with less noise"
    )
}

/// Estimates H, λ_l, λ_u and h_rms from the radially averaged PSD C(q) of `surface` (paper §4.1:
/// C(q) ∝ q^−2(1+H) between q = 2π/λ_u and 2π/λ_l).
///
/// 1. The floor is found and left out: shells below 10⁻¹² of the peak (round-off) and shells within a
///    factor 10 of the floor level, the median PSD over the outermost half octave of wavenumbers (the
///    corners of the spectrum beyond the Nyquist wavenumber hold only the floor: round-off for a
///    band-limited surface, white noise for a measurement).
/// 2. The band is the run of the remaining shells that follows one power law over the widest range
///    of ln q: grown from every shell while each new shell stays within a factor 2 of the run's
///    least-squares line (or 3 standard deviations √(2/n) of a shell average over n modes, where
///    that is wider), then kept only if every shell of the run does, it has at least
///    six shells (`MIN_SHELLS`) over at least an octave, it falls faster than q⁻¹ (a roll-off plateau or
///    a white floor does not) and no shell at a longer wavelength lies a factor 10 above its line (a
///    run under the band, such as the leakage of a levelled periodic map beyond λ_l, is not the band).
/// 3. H comes from the slope of the line over the band less its two end shells (which straddle the
///    cut-offs); λ_u and λ_l are where the PSD leaves the power law: in the end shell of the band and
///    the next one out, placed by the fraction of the power law's power the two still hold.
///
/// 4. h_rms is the band's (`rms_height`): the map's variance over the modes q_u ≤ |q| ≤ q_l of the
///    block ([`SpectrumFit::spectrum`], after its clamps), beside the whole map's
///    (`map_rms_height`) and the share of the variance outside the band (`out_of_band_share`).
///
/// The PSD is that of the map as it is when it is periodic, and Hann-windowed when it is not
/// ([`Window::for_map`]): the jump at the borders of a measured map leaks power ∝ q⁻² into every
/// shell, which flattens the spectrum and biases H low.
///
/// A surface with no such band is an error, not a number.
pub fn fit(surface: &Surface) -> Result<SpectrumFit> {
    fit_measured(surface, None)
}

/// [`fit`] of a map resampled onto finer pixels than it was measured with, `measured_pixel` =
/// [Δx, Δy] its native pixel sizes in its length unit (`wearsim surface import --resample`
/// records them): beyond the native Nyquist wavenumber π/Δ along an axis its spectrum is the
/// interpolation's, so every step of the fit (the floor, the band, the slope, λ_l, the
/// anisotropy, the band's h_rms) takes only the measured wavevectors, |q_x| ≤ π/Δx and
/// |q_y| ≤ π/Δy ([`MeasuredPsd::with_measured_pixel`]). None, or the map's own pixel: the whole
/// stored spectrum is measured, as [`fit`].
pub fn fit_measured(surface: &Surface, measured_pixel: Option<[f64; 2]>) -> Result<SpectrumFit> {
    let window = Window::for_map(surface);
    let mut psd = MeasuredPsd::of(surface, window)?;
    if let Some(pixel) = measured_pixel {
        psd = psd.with_measured_pixel(pixel)?;
    }
    let measured_pixel = psd.is_resampled().then(|| psd.measured_pixel());
    let all = psd.radial_shells();
    let invalid = |message: String| Error::InvalidSurface {
        name: "surface".into(),
        message,
    };
    let peak = all.iter().map(|s| s.psd).fold(0.0f64, f64::max);
    if !(peak > 0.0 && peak.is_finite()) || all.len() < MIN_SHELLS {
        return Err(invalid(format!(
            "its spectrum has {} wavenumber shells and a peak of {peak:e}; nothing to fit",
            all.len()
        )));
    }
    let floor = floor_level(&all);
    // The shells that carry signal, as indices into `all`.
    let signal: Vec<usize> = (0..all.len())
        .filter(|&i| all[i].psd > ROUND_OFF * peak && all[i].psd >= ABOVE_FLOOR * floor)
        .collect();
    let runs = Runs::new(&all, &signal);
    let (lo, hi) = runs.band().ok_or_else(|| invalid(no_band(&all, &signal)))?;
    // The shells at the ends of the power law straddle the cut-offs (only part of their modes lie
    // inside the band), so the slope comes from the shells between them when there are enough.
    let (a, b) = if hi - lo >= 6 { (lo + 1, hi - 1) } else { (lo, hi) };
    let (x, y): (Vec<f64>, Vec<f64>) = (a..=b).map(|k| (runs.x[k], runs.y[k])).unzip();
    let line = line_fit(&x, &y).ok_or_else(|| invalid("its spectrum cannot be fitted by a power law".into()))?;
    let power_law = |q: f64| (line.intercept + line.slope * q.ln()).exp();
    // The fraction of the power law's power a shell holds (0 beyond a cut-off, ½ straddling it).
    let held = |i: usize| (all[i].psd / power_law(all[i].q)).clamp(0.0, 1.0);
    let (first, last) = (signal[lo], signal[hi]);
    let q_long = if first == 0 {
        all[first].q
    } else {
        all[first].q + 0.5 - held(first) - held(first - 1)
    };
    // Within the square (the rectangle, for a resampled map) of measured modes the band ends at
    // the Nyquist wavenumber Nx/2 at most (two pixels); only a band that runs into the corners of
    // the spectrum reaches beyond.
    let nyquist = psd.nyquist();
    let q_short = if last + 1 == all.len() {
        all[last].q
    } else {
        (all[last].q - 0.5 + held(last) + held(last + 1)).min(all[last].q.max(nyquist))
    };
    let length = surface.length();
    let k = 2.0 * PI / length;
    // From the longest wavelengths to the end of the band: beyond it lie the cut-off and the floor,
    // which may stand above the line extended.
    let peak = signal[..=hi]
        .iter()
        .map(|&i| all[i].psd / power_law(all[i].q) * (-3.0 * (2.0 / all[i].modes).sqrt()).exp())
        .fold(0.0f64, f64::max);
    let fit = SpectrumFit {
        hurst: -line.slope / 2.0 - 1.0,
        lambda_lower: length / q_short,
        lambda_upper: length / q_long,
        rms_height: f64::NAN,
        map_rms_height: surface.rms_height(),
        out_of_band_share: f64::NAN,
        measured_pixel,
        r2: line.r2,
        shells: b - a + 1,
        fitted_q: [k * runs.q(a), k * runs.q(b)],
        shells_longer: first,
        shells_shorter: all.len() - 1 - last,
        floor: floor / power_law(q_short),
        window,
        anisotropy: psd.anisotropy(runs.q(a), runs.q(b)),
        peak,
    };
    Ok(fit.with_band_rms(&psd))
}

/// The floor of the PSD: its median over the outermost half octave of wavenumbers, q ≥ q_max/√2.
fn floor_level(all: &[PsdShell]) -> f64 {
    let q_max = all.last().map_or(0.0, |s| s.q);
    let mut outer: Vec<f64> = all
        .iter()
        .filter(|s| s.q >= q_max / 2f64.sqrt())
        .map(|s| s.psd)
        .collect();
    outer.sort_by(f64::total_cmp);
    match outer.len() {
        0 => 0.0,
        n if n % 2 == 1 => outer[n / 2],
        n => 0.5 * (outer[n / 2 - 1] + outer[n / 2]),
    }
}

/// Runs of the shells that carry signal in log–log (x = ln q, y = ln C), with prefix sums for
/// least-squares lines over any run in O(1).
struct Runs {
    q: Vec<f64>,
    x: Vec<f64>,
    y: Vec<f64>,
    /// Tolerance of each shell about a line, in ln C.
    tolerance: Vec<f64>,
    /// Prefix sums of 1, x, y, x², xy.
    sums: Vec<[f64; 5]>,
}

impl Runs {
    fn new(all: &[PsdShell], signal: &[usize]) -> Self {
        let q: Vec<f64> = signal.iter().map(|&i| all[i].q).collect();
        let x: Vec<f64> = q.iter().map(|q| q.ln()).collect();
        let y: Vec<f64> = signal.iter().map(|&i| all[i].psd.ln()).collect();
        let tolerance = signal
            .iter()
            .map(|&i| FOLLOWS.ln().max(3.0 * (2.0 / all[i].modes).sqrt()))
            .collect();
        let mut sums = vec![[0.0; 5]];
        for (&a, &b) in x.iter().zip(&y) {
            let s = sums[sums.len() - 1];
            sums.push([s[0] + 1.0, s[1] + a, s[2] + b, s[3] + a * a, s[4] + a * b]);
        }
        Self {
            q,
            x,
            y,
            tolerance,
            sums,
        }
    }

    fn q(&self, k: usize) -> f64 {
        self.q[k]
    }

    /// Least-squares line (slope, intercept) over shells lo..=hi.
    fn line(&self, lo: usize, hi: usize) -> Option<(f64, f64)> {
        let (s, t) = (self.sums[hi + 1], self.sums[lo]);
        let n = s[0] - t[0];
        let (mx, my) = ((s[1] - t[1]) / n, (s[2] - t[2]) / n);
        let sxx = (s[3] - t[3]) / n - mx * mx;
        let sxy = (s[4] - t[4]) / n - mx * my;
        (sxx > 0.0 && sxx.is_finite()).then(|| {
            let slope = sxy / sxx;
            (slope, my - slope * mx)
        })
    }

    /// How far shell k lies above the line, in units of ln C.
    fn above(&self, k: usize, (slope, intercept): (f64, f64)) -> f64 {
        self.y[k] - (intercept + slope * self.x[k])
    }

    /// The run grown from the four shells at `seed` while each new shell follows its line.
    fn grow(&self, seed: usize) -> (usize, usize) {
        let (mut lo, mut hi) = (seed, seed + 3);
        while let Some(line) = self.line(lo, hi) {
            let follows = |k: usize| self.above(k, line).abs() < self.tolerance[k];
            let mut grew = false;
            if lo > 0 && follows(lo - 1) {
                lo -= 1;
                grew = true;
            }
            if hi + 1 < self.x.len() && follows(hi + 1) {
                hi += 1;
                grew = true;
            }
            if !grew {
                break;
            }
        }
        (lo, hi)
    }

    /// Whether the run lo..=hi is a self-affine band (see [`fit`]).
    fn is_band(&self, lo: usize, hi: usize) -> bool {
        if hi + 1 - lo < MIN_SHELLS || self.q[hi] < 2.0 * self.q[lo] {
            return false;
        }
        let Some(line) = self.line(lo, hi) else {
            return false;
        };
        line.0 < -1.0
            && (lo..=hi).all(|k| self.above(k, line).abs() < self.tolerance[k])
            && (0..lo).all(|k| self.above(k, line) < UNDER.ln() + self.tolerance[k])
    }

    /// The band: of the runs grown from every shell, the widest in ln q (the first of equals).
    fn band(&self) -> Option<(usize, usize)> {
        let mut best: Option<(usize, usize)> = None;
        for seed in 0..self.x.len().saturating_sub(3) {
            let (lo, hi) = self.grow(seed);
            let wider = best.is_none_or(|(a, b)| self.x[hi] - self.x[lo] > self.x[b] - self.x[a]);
            if wider && self.is_band(lo, hi) {
                best = Some((lo, hi));
            }
        }
        best
    }
}

impl Verdict {
    /// The verdict on a spectrum in which [`fit`] found no power-law band (`why`: its error).
    pub fn no_band(why: &str) -> Self {
        Self {
            self_affine: false,
            reasons: vec![format!("no power-law band: {why}")],
        }
    }
}

impl SpectrumFit {
    /// The fit with the band's h_rms (`rms_height`) and the share of the map's variance outside it,
    /// from `psd`, the map's PSD as fitted: the band as the block on the map's grid writes it.
    fn with_band_rms(mut self, psd: &MeasuredPsd) -> Self {
        let grid = psd.grid();
        let (lambda_lower, lambda_upper, _) = self.cutoffs(&grid);
        let length = grid.length_x();
        let band = psd.band_variance(length / lambda_upper, length / lambda_lower);
        // The map's own variance, not its windowed PSD's sum: a Hann window underestimates the
        // power of wavelengths near the map's side (a cosine of the side's wavelength by a factor
        // 3), which is where the variance outside the band mostly lies.
        let map = self.map_rms_height.powi(2);
        self.rms_height = band.sqrt();
        self.out_of_band_share = if map > 0.0 {
            (1.0 - band / map).clamp(0.0, 1.0)
        } else {
            0.0
        };
        self
    }

    /// Whether the spectrum is self-affine: isotropic within a factor [`ANISOTROPIC`], no peak
    /// above [`PEAK`], H in (0, 1], a fitted band of at least two octaves of wavenumbers and R² ≥ 0.9.
    pub fn verdict(&self) -> Verdict {
        let mut reasons = Vec::new();
        let a = self.anisotropy;
        if !(1.0 / ANISOTROPIC..=ANISOTROPIC).contains(&a) {
            let (more, less) = if a > 1.0 { ("x", "y") } else { ("y", "x") };
            reasons.push(format!(
                "anisotropic (a lay): wavevectors along {more} carry {:.1} times the power of those along {less} over \
                 the fitted band (over {ANISOTROPIC} is no isotropic spectrum)",
                a.max(1.0 / a)
            ));
        }
        if self.peak > PEAK {
            reasons.push(format!(
                "a peak: a shell stands {:.1} times above the fitted power law beyond its scatter (over {PEAK} is a \
                 feature, not roughness)",
                self.peak
            ));
        }
        if !(self.hurst > 0.0 && self.hurst <= 1.0 + HURST_SLACK) {
            reasons.push(format!(
                "H = {:.3} is outside (0, 1]: the slope of the PSD is no self-affine surface's",
                self.hurst
            ));
        }
        let span = self.fitted_q[1] / self.fitted_q[0];
        if span < TWO_OCTAVES {
            reasons.push(format!(
                "the power law is fitted over a factor {span:.1} of wavenumbers, under two octaves: too short to say it is \
                 one"
            ));
        }
        if let Some(r2) = self.r2.filter(|&r| r < R2_MIN) {
            reasons.push(format!("R² = {r2:.3} < {R2_MIN}: the PSD follows a power law poorly"));
        }
        Verdict {
            self_affine: reasons.is_empty(),
            reasons,
        }
    }

    /// [`poor_fit_warning`] of this fit.
    pub fn poor_fit_warning(&self) -> Option<String> {
        poor_fit_warning(self.r2)
    }

    /// Parameters to generate periodic surfaces with the fitted statistics on `grid`: λ_l raised to
    /// two pixels and λ_u lowered to the box where the fit ran past them (a note says so); h_rms
    /// the band's (`rms_height`, taken over the band these λ_l and λ_u bound on the map's grid).
    pub fn spectrum(&self, grid: &Grid) -> (SpectrumParams, Vec<String>) {
        let (lambda_lower, lambda_upper, mut notes) = self.cutoffs(grid);
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

    /// The note of a fit whose band leaves out more than [`OUT_OF_BAND`] of the map's variance: what
    /// share, and that the block carries the band's h_rms. None otherwise.
    pub fn out_of_band_note(&self) -> Option<String> {
        (self.out_of_band_share > OUT_OF_BAND).then(|| {
            format!(
                "{:.0} % of the map's variance lies outside the self-affine band λ_l … λ_u (beyond λ_u: a waviness \
                 or form; beyond λ_l: noise): the block's rms_height = {:.4e} is the band's, not the whole map's \
                 ({:.4e}), so that the generated surfaces carry the measured PSD level in the band (paper §4.1: \
                 the surfaces hold the power law between λ_u and λ_l and nothing else)",
                100.0 * self.out_of_band_share,
                self.rms_height,
                self.map_rms_height
            )
        })
    }

    /// λ_l and λ_u of the block on `grid`: λ_l raised to two pixels and λ_u lowered to the box
    /// where the fit ran past them, with a note for each.
    fn cutoffs(&self, grid: &Grid) -> (f64, f64, Vec<String>) {
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
        (lambda_lower, lambda_upper, notes)
    }
}

/// A change of the RMS slope between the map and the surfaces its fit generates beyond this share
/// is worth a note beside the h_rms change: the slope sets the junctions' sizes at a load (paper
/// §4.1, the contact area grows as F_N/(E* h'_rms)), so it moves the wear rate as much as h_rms.
pub const SLOPE_CHANGE: f64 = 0.1;

/// The RMS slopes of a measured map and of the surfaces its fitted block generates on the map's
/// grid, each by the same rule: forward differences between neighbouring pixels, never across the
/// map's border (a measured map is not periodic), √⟨(Δh/Δx)² + (Δh/Δy)²⟩.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SlopeComparison {
    /// RMS slope of the map as fitted (levelled).
    pub map: f64,
    /// RMS slope of a surface generated with the block's parameters on the map's grid (random
    /// phases, so every seed gives it alike to round-off).
    pub generated: f64,
}

impl SlopeComparison {
    /// The slopes of `map` and of a surface generated with `params` on its grid.
    pub fn of(map: &Surface, params: &SpectrumParams) -> Result<Self> {
        let generated = Surface::generate(map.grid(), params, 0)?;
        Ok(SlopeComparison {
            map: difference_rms_slope(map),
            generated: difference_rms_slope(&generated),
        })
    }

    /// The generated surfaces' slope relative to the map's, less one (−0.37: 37 % lower); NaN for
    /// a flat map.
    pub fn change(&self) -> f64 {
        self.generated / self.map - 1.0
    }

    /// The note of a change beyond [`SLOPE_CHANGE`]: both slopes, the change and what follows; None
    /// otherwise.
    pub fn note(&self) -> Option<String> {
        let change = self.change();
        (change.abs() > SLOPE_CHANGE).then(|| {
            format!(
                "the generated surfaces' rms slope {:.4e} is {:+.0} % of the map's ({:.4e}): the block leaves out \
                 what the map holds outside the self-affine band (or adds what the band holds beyond it), and the \
                 contact area at a load, the junctions and the wear rate follow the rms slope (paper §4.1); give \
                 `source = \"spectrum\"` to carry the measured spectrum instead",
                self.generated,
                100.0 * change,
                self.map
            )
        })
    }
}

/// √⟨(Δh/Δx)² + (Δh/Δy)²⟩ by forward differences inside the map (none across its border).
fn difference_rms_slope(s: &Surface) -> f64 {
    let (nx, ny, h) = (s.nx(), s.ny(), s.heights());
    let step = |a: usize, b: usize| (h[b] - h[a]).powi(2);
    // A grid has at least 16 pixels a side, so neither count is zero.
    let along_x: f64 = (0..(nx - 1) * ny).map(|k| step(k, k + ny)).sum::<f64>() / ((nx - 1) * ny) as f64;
    let along_y: f64 = (0..nx)
        .flat_map(|i| (0..ny - 1).map(move |j| i * ny + j))
        .map(|k| step(k, k + 1))
        .sum::<f64>()
        / (nx * (ny - 1)) as f64;
    (along_x + along_y).sqrt() / s.pixel_size()
}

/// The warning of a PSD fit whose log–log line follows the PSD poorly (`r2`, its R², below 0.9):
/// the slope −2(1 + H) of paper §4.1 is then a rough estimate of H. None for a good fit, or an
/// undefined R².
pub fn poor_fit_warning(r2: Option<f64>) -> Option<String> {
    r2.is_some_and(|r| r < R2_MIN)
        .then(|| format!("the PSD follows a power law poorly (R² < {R2_MIN}): H is a rough estimate"))
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

/// The `[surface]` block of a run file that generates periodic surfaces carrying the measured 2D
/// PSD of the map `map` (as the run file should name it) on the map's own `grid` and box;
/// `extra` holds further lines (`map_length`, units), each `key = value`.
pub fn spectrum_block(map: &str, grid: &Grid, window: Window, seed: u64, extra: &[String], unit: &str) -> String {
    let sides = |x: String, y: String| if x == y { x } else { format!("[{x}, {y}]") };
    let map = toml::Value::String(map.to_string());
    let mut block = format!(
        "# Periodic surfaces carrying the measured 2D PSD of the map (a lay, a roll-off, a peak as measured), on its \
         own grid and box; lengths in {unit}. Any grid and box may be given: wavelengths beyond the map's are empty.\n\
         [surface]\n\
         source = \"spectrum\"\n\
         map = {map}\n"
    );
    for line in extra {
        block.push_str(line);
        block.push('\n');
    }
    block.push_str(&format!(
        "grid = {}\nlength = {}\nwindow = \"{}\"\nseed = {seed}\n",
        sides(grid.nx().to_string(), grid.ny().to_string()),
        sides(grid.length_x().to_string(), grid.length_y().to_string()),
        window.name()
    ));
    block
}

#[cfg(test)]
mod tests {
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha20Rng;
    use rand_distr::StandardNormal;

    use super::super::prepare::{preprocess, Detrend, Preprocess};
    use super::super::spectrum::Window;
    use super::*;

    fn within(value: f64, truth: f64, factor: f64) -> bool {
        value / truth < factor && truth / value < factor
    }

    fn generated(grid: Grid, hurst: f64, lower: f64, upper: f64, generation: Generation, seed: u64) -> Surface {
        let params = SpectrumParams {
            hurst,
            lambda_lower: lower,
            lambda_upper: upper,
            rms_height: 0.01,
            generation,
        };
        Surface::generate(grid, &params, seed).unwrap()
    }

    /// The heights of `s` levelled by a least-squares plane, as `wearsim surface fit` does by default.
    fn levelled(s: &Surface) -> Surface {
        let mut h = s.heights().to_vec();
        let how = Preprocess {
            detrend: Detrend::Plane,
            taper: 0.0,
        };
        preprocess(&mut h, s.nx(), s.ny(), &how).unwrap();
        Surface::new("levelled", s.grid(), h).unwrap()
    }

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
            let s = generated(grid, hurst, lower, upper, generation, seed);
            let f = fit(&s).unwrap();
            assert!((f.hurst - hurst).abs() <= 0.05, "H {hurst}: {f:?}");
            assert!(within(f.lambda_lower, lower, 1.2), "λ_l {lower}: {f:?}");
            assert!(within(f.lambda_upper, upper, 1.2), "λ_u {upper}: {f:?}");
            // The whole map is the band: its h_rms is the band's, nothing lies outside.
            assert!((f.map_rms_height - 0.01).abs() < 1e-12);
            assert!((f.rms_height / 0.01 - 1.0).abs() < 0.01, "{f:?}");
            assert!(f.out_of_band_share < 0.01, "{f:?}");
            assert_eq!(f.spectrum(&grid).0.rms_height, f.rms_height);
            assert_eq!(f.measured_pixel, None);
        }
    }

    /// A measurement's white noise: the PSD flattens onto it beyond where the power law meets it,
    /// and the band ends above it.
    #[test]
    fn a_white_noise_floor_is_left_out() {
        let grid = Grid::square(256, 1.0).unwrap();
        for (hurst, seed) in [(0.5, 1), (0.8, 2)] {
            // Power down to the pixel scale, then white noise of 10 % of h_rms (1 % of its variance).
            let s = generated(grid, hurst, 2.0 / 256.0, 0.25, Generation::RandomPhase, seed);
            let mut rng = ChaCha20Rng::seed_from_u64(seed);
            let noisy: Vec<f64> = s
                .heights()
                .iter()
                .map(|h| h + 1e-3 * rng.sample::<f64, _>(StandardNormal))
                .collect();
            let f = fit(&Surface::new("noisy", grid, noisy).unwrap()).unwrap();
            assert!((f.hurst - hurst).abs() <= 0.05, "H {hurst}: {f:?}");
            assert!(within(f.lambda_upper, 0.25, 1.25), "{f:?}");
            // The power law meets the floor before the pixel scale; the band stops about a factor 10
            // above it.
            assert!(f.lambda_lower > 3.0 / 256.0 && f.floor < 0.2, "{f:?}");
        }
    }

    #[test]
    fn a_spectrum_without_a_band_is_an_error_not_a_number() {
        let grid = Grid::square(64, 1.0).unwrap();
        // Three shells of power law: too few to give a slope.
        let narrow = generated(grid, 0.8, 1.0 / 6.0, 0.25, Generation::RandomPhase, 1);
        // White noise: flat, no power law of a self-affine surface.
        let mut rng = ChaCha20Rng::seed_from_u64(1);
        let white = (0..64 * 64).map(|_| rng.sample::<f64, _>(StandardNormal)).collect();
        for s in [narrow, Surface::new("white", grid, white).unwrap()] {
            let e = fit(&s).unwrap_err().to_string();
            assert!(
                e.contains("H cannot be fitted") && e.contains("6 wavenumber shells"),
                "{e}"
            );
        }
    }

    /// The heights of the 256² corner (side 1) of a periodic self-affine surface four times its side
    /// (λ_l = 4 of its pixels, λ_u a quarter of its side): a map that is not periodic, as a
    /// measurement is.
    fn corner_of_a_larger_surface(hurst: f64, seed: u64) -> Vec<f64> {
        let big = generated(
            Grid::square(1024, 4.0).unwrap(),
            hurst,
            4.0 / 256.0,
            0.25,
            Generation::RandomPhase,
            seed,
        );
        (0..256 * 256)
            .map(|k| big.heights()[(k / 256) * 1024 + k % 256])
            .collect()
    }

    /// A map cut out of a larger periodic surface (not periodic, as a measurement): the fit takes
    /// its Hann-windowed PSD and recovers H, where the leakage of the border jump flattens the
    /// plain PSD; a periodic self-affine surface is judged self-affine with no window.
    #[test]
    fn a_measured_map_is_fitted_windowed_and_self_affine_surfaces_pass_the_verdict() {
        let h = corner_of_a_larger_surface(0.8, 2);
        let map = levelled(&Surface::new("map", Grid::square(256, 1.0).unwrap(), h).unwrap());
        let f = fit(&map).unwrap();
        assert_eq!(f.window, Window::Hann);
        assert!((f.hurst - 0.8).abs() <= 0.1, "{f:?}");
        for seed in 1..=3 {
            let s = generated(
                Grid::square(512, 1.0).unwrap(),
                0.7,
                1.0 / 128.0,
                0.25,
                Generation::RandomPhase,
                seed,
            );
            let f = fit(&s).unwrap();
            assert_eq!(f.window, Window::None);
            let v = f.verdict();
            assert!(v.self_affine && v.reasons.is_empty(), "{f:?} {v:?}");
        }
    }

    /// The warning of a poor fit: R² below 0.9 and only then, worded as both front ends print it.
    #[test]
    fn a_poor_power_law_fit_warns_that_h_is_rough() {
        let s = generated(
            Grid::square(128, 1.0).unwrap(),
            0.7,
            1.0 / 32.0,
            0.25,
            Generation::RandomPhase,
            1,
        );
        let good = fit(&s).unwrap();
        assert_eq!(good.poor_fit_warning(), None, "{good:?}");
        let poor = SpectrumFit { r2: Some(0.89), ..good };
        assert_eq!(
            poor.poor_fit_warning().as_deref(),
            Some("the PSD follows a power law poorly (R² < 0.9): H is a rough estimate")
        );
        for r2 in [Some(0.9), None] {
            assert_eq!(SpectrumFit { r2, ..good }.poor_fit_warning(), None);
        }
    }

    /// A lay (a surface squeezed along y: every other column of one twice as wide) is named.
    #[test]
    fn a_lay_is_not_self_affine() {
        let big = generated(
            Grid::new(256, 512, 1.0).unwrap(),
            0.7,
            8.0 / 256.0,
            0.25,
            Generation::RandomPhase,
            1,
        );
        let h: Vec<f64> = (0..256 * 256)
            .map(|k| big.heights()[(k / 256) * 512 + 2 * (k % 256)])
            .collect();
        let f = fit(&Surface::new("lay", Grid::square(256, 1.0).unwrap(), h).unwrap()).unwrap();
        let v = f.verdict();
        assert!(
            !v.self_affine && v.reasons.iter().any(|r| r.contains("anisotropic (a lay)")),
            "{f:?} {v:?}"
        );
    }

    /// A generated self-affine band (λ_u = 1/8, λ_l = 1/64, h_rms 0.01) with power beyond λ_u added,
    /// as a measured map has (a waviness, a form): a cosine of the box's wavelength, or a second
    /// self-affine band at wavelengths 1/2 to 1. The fit finds the band, and the block's h_rms is
    /// the band's (paper §4.1: the surfaces hold the power law between λ_u and λ_l and nothing
    /// else), not the whole map's; the whole map's and the share outside the band are reported.
    #[test]
    fn the_block_carries_the_rms_height_of_the_band_not_the_whole_maps() {
        let grid = Grid::square(512, 1.0).unwrap();
        let band = generated(grid, 0.7, 1.0 / 64.0, 1.0 / 8.0, Generation::RandomPhase, 2);
        // 56 % of the variance beyond λ_u: the band's 1e-4 and 1.27e-4 outside it.
        let outside: f64 = 1e-4 * 0.56 / 0.44;
        let cosine: Vec<f64> = (0..512 * 512)
            .map(|k| (2.0 * outside).sqrt() * (2.0 * PI * (k / 512) as f64 / 512.0).cos())
            .collect();
        let long = Surface::generate(
            grid,
            &SpectrumParams {
                hurst: 0.7,
                lambda_lower: 0.5,
                lambda_upper: 1.0,
                rms_height: outside.sqrt(),
                generation: Generation::RandomPhase,
            },
            9,
        )
        .unwrap();
        for (name, extra) in [
            ("a cosine of the box's wavelength", cosine),
            ("a band at 1/2 to 1", long.into_heights()),
        ] {
            let h = band.heights().iter().zip(&extra).map(|(a, b)| a + b).collect();
            let map = Surface::new("map", grid, h).unwrap();
            let f = fit(&map).unwrap();
            let case = format!("{name}: {f:?}");
            assert_eq!(f.window, Window::None, "{case}");
            assert!((f.hurst - 0.7).abs() <= 0.05, "{case}");
            assert!(within(f.lambda_upper, 1.0 / 8.0, 1.2), "{case}");
            assert!((f.rms_height / 0.01 - 1.0).abs() < 0.03, "{case}");
            assert!(
                (f.map_rms_height / (1e-4 + outside).sqrt() - 1.0).abs() < 1e-6,
                "{case}"
            );
            assert!((f.out_of_band_share - 0.56).abs() < 0.02, "{case}");
            // The block writes the band's h_rms, and a note says why.
            let (params, _) = f.spectrum(&grid);
            assert_eq!(params.rms_height, f.rms_height, "{case}");
            let note = f.out_of_band_note().unwrap();
            assert!(
                note.starts_with("56 % of the map's variance lies outside") && note.contains("the band's"),
                "{note}"
            );
        }
        // The band alone: no note.
        assert_eq!(fit(&band).unwrap().out_of_band_note(), None);
    }

    /// A map that is not periodic (a self-affine band cut out of a periodic surface four times its
    /// side, with a cosine of its side added) is fitted under a Hann window, whose power is
    /// normalised out: the band's h_rms is that of the band component within the scatter of a
    /// windowed variance (~8 % for one map, see the spectrum's tests), where a PSD not normalised
    /// would give a factor 8/3 less, and the share outside the band is the cosine's within what that
    /// scatter makes of it.
    #[test]
    fn the_band_rms_of_a_map_that_is_not_periodic_comes_from_its_windowed_psd() {
        let cut = corner_of_a_larger_surface(0.7, 3);
        let grid = Grid::square(256, 1.0).unwrap();
        let band_rms = levelled(&Surface::new("band", grid, cut.clone()).unwrap()).rms_height();
        let amplitude = 2.0 * band_rms;
        let h = cut
            .iter()
            .enumerate()
            .map(|(k, h)| h + amplitude * (2.0 * PI * (k / 256) as f64 / 256.0).cos())
            .collect();
        let map = levelled(&Surface::new("map", grid, h).unwrap());
        let f = fit(&map).unwrap();
        assert_eq!(f.window, Window::Hann);
        assert!((f.rms_height / band_rms - 1.0).abs() < 0.15, "{band_rms}: {f:?}");
        assert!((f.map_rms_height / map.rms_height() - 1.0).abs() < 1e-12);
        // The cosine holds 2 of the 3 parts of the variance (its amplitude²/2 = 2 h_rms²).
        assert!((f.out_of_band_share - 2.0 / 3.0).abs() < 0.08, "{f:?}");
    }

    /// A map resampled ×2 along y, as `wearsim surface import --resample` resamples a map with
    /// pixels twice as long along y: every other row of a self-affine surface whose power law runs
    /// to the pixel scale (λ_l = 2 pixels) is measured and the rows between are interpolated
    /// (each measured row repeated, or the mean of its neighbours). Beyond the native Nyquist
    /// wavenumber along y the spectrum is the interpolation's: fitted over it, H and the x/y power
    /// ratio are off (H by more than 0.08 with repeated rows); given the native pixel, the fit
    /// takes the measured wavevectors only, and H is the original map's within 0.05 and the ratio
    /// within 15 % with repeated rows. Linear interpolation also attenuates the measured band near
    /// the native Nyquist wavenumber (its transfer function, sinc⁴ in power, is 0.16 there), which
    /// no choice of wavevectors undoes: its fit on the measured wavevectors is closer to the
    /// original's than on all of them, not as close.
    #[test]
    fn a_resampled_map_is_fitted_on_its_measured_wavevectors() {
        for (n, hurst, seed) in [(256, 0.7, 1), (256, 0.5, 3), (256, 0.6, 2)] {
            let grid = Grid::square(n, 1.0).unwrap();
            let original = generated(grid, hurst, 2.0 / n as f64, 0.25, Generation::RandomPhase, seed);
            let h = original.heights();
            let repeated = (0..n * n).map(|k| h[k - k % 2]).collect();
            let linear = (0..n * n)
                .map(|k| {
                    let (i, j) = (k / n, k % n);
                    if j % 2 == 0 {
                        h[k]
                    } else {
                        0.5 * (h[k - 1] + h[i * n + (j + 1) % n])
                    }
                })
                .collect();
            let native = [1.0 / n as f64, 2.0 / n as f64];
            let o = fit(&original).unwrap();
            let ln_ratio = |f: &SpectrumFit| (f.anisotropy / o.anisotropy).ln().abs();
            for (how, heights) in [("repeated", repeated), ("linear", linear)] {
                let map = Surface::new("resampled", grid, heights).unwrap();
                let all = fit(&map).unwrap();
                let measured = fit_measured(&map, Some(native)).unwrap();
                let case = format!("n {n} H {hurst} {how}:\n original {o:?}\n all {all:?}\n measured {measured:?}");
                assert_eq!(all.measured_pixel, None, "{case}");
                assert_eq!(measured.measured_pixel, Some(native), "{case}");
                // The measured part of the spectrum ends at two native pixels along y.
                assert!(measured.lambda_lower >= 0.95 * 2.0 * native[1], "{case}");
                assert!((measured.rms_height / 0.01 - 1.0).abs() < 0.05, "{case}");
                let (dh_all, dh_measured) = ((all.hurst - o.hurst).abs(), (measured.hurst - o.hurst).abs());
                if how == "repeated" {
                    assert!(dh_measured <= 0.05 && dh_all > 0.08, "{case}");
                    assert!(
                        ln_ratio(&measured) < 1.15f64.ln() && ln_ratio(&all) > 1.15f64.ln(),
                        "{case}"
                    );
                } else {
                    assert!(dh_measured < dh_all && ln_ratio(&measured) < ln_ratio(&all), "{case}");
                }
            }
        }
        // The map's own pixel changes nothing; a native pixel finer than the map's is refused.
        let s = generated(
            Grid::square(128, 1.0).unwrap(),
            0.7,
            1.0 / 32.0,
            0.25,
            Generation::RandomPhase,
            1,
        );
        assert_eq!(fit_measured(&s, Some([1.0 / 128.0; 2])).unwrap(), fit(&s).unwrap());
        let e = fit_measured(&s, Some([1.0 / 128.0, 0.5 / 128.0]))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("measured_pixel") && e.contains("smaller than the map's pixel"),
            "{e}"
        );
    }
}
