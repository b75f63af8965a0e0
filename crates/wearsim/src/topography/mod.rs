//! Measured topographies: reading height maps in the common formats, converting their units,
//! preparing them for a periodic contact solution, and fitting the self-affine parameters the
//! paper's model needs.
//!
//! A measured surface is not periodic, but the FFT solver treats every surface as one period of an
//! infinite periodic one: where the heights at opposite borders differ, the periodic surface has a
//! ridge or a cliff there, which carries load and makes junctions that the real surface does not
//! have. `detrend` removes the tilt (a plane) or the form (a quadratic) that causes most of the
//! jump, `taper` brings the heights smoothly to their mean over a fraction of each border (at the
//! cost of flattening that strip), and [`periodicity`] measures what is left. The cleanest route for the
//! paper's model, which assumes periodic self-affine surfaces, is [`fit`]: estimate H, λ_l, λ_u and
//! h_rms from the measurement and generate periodic surfaces with them; where the spectrum is not
//! self-affine (a lay, a peak), [`MeasuredPsd`] keeps it as measured and generates periodic
//! surfaces that carry it (`source = "spectrum"` in a run file).

mod fit;
mod formats;
mod load;
mod prepare;
mod spectrum;

pub use fit::{
    fit, fit_measured, poor_fit_warning, spectrum_block, surface_block, SlopeComparison, SpectrumFit, Verdict,
    ANISOTROPIC, FIT_METHOD, OUT_OF_BAND, PEAK, SLOPE_CHANGE,
};
pub use formats::{array_shape, metres_per, read, regular_file, Measured, LENGTH_UNITS};
pub use load::{file_grid, file_span, imported_length, load, probe_grid, FileSurface, Loaded};
pub use prepare::{flat_map, periodicity, preprocess, Detrend, Periodicity, Preprocess, NOT_PERIODIC};
pub use spectrum::{MeasuredPsd, Window};
