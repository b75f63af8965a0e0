//! Drawing figures: the bundled font, one [`Figure`] drawn into both PNG and SVG by [`save`], and the
//! pieces the figures share. Plotting is a front-end concern and stays out of the library; the text
//! is drawn with the DejaVu Sans font shipped in `assets/`, so no system font is needed.

use std::path::Path;

use anyhow::{anyhow, Result};
use plotters::coord::Shift;
use plotters::prelude::*;

/// Family name the bundled font is registered under.
pub const FONT: &str = "sans-serif";

/// Registers the bundled DejaVu Sans font (once per process).
pub fn register_font() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        plotters::style::register_font(FONT, FontStyle::Normal, include_bytes!("../assets/DejaVuSans.ttf"))
            .map_err(|_| ())
            .expect("the bundled font is valid");
    });
}

/// A drawing error as an `anyhow` error.
pub fn drawing(e: impl std::fmt::Display) -> anyhow::Error {
    anyhow!("drawing failed: {e}")
}

/// A figure: drawn once, on any backend.
pub trait Figure {
    /// Draws the figure onto `area` (already filled white).
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()>;
}

/// Draws `figure` into `dir/name.png` and `dir/name.svg` (each written to a temporary file and
/// renamed into place, so a failed drawing leaves no half-written figure).
pub fn save(dir: &Path, name: &str, size: (u32, u32), figure: &impl Figure) -> Result<()> {
    register_font();
    let svg = dir.join(format!("{name}.svg"));
    let png = dir.join(format!("{name}.png"));
    let tmp_svg = dir.join(format!(".{name}.{}.tmp.svg", std::process::id()));
    let tmp_png = dir.join(format!(".{name}.{}.tmp.png", std::process::id()));
    let drawn = (|| -> Result<()> {
        {
            let root = SVGBackend::new(&tmp_svg, size).into_drawing_area();
            root.fill(&WHITE).map_err(drawing)?;
            figure.draw(&root)?;
            root.present().map_err(drawing)?;
        }
        {
            let root = BitMapBackend::new(&tmp_png, size).into_drawing_area();
            root.fill(&WHITE).map_err(drawing)?;
            figure.draw(&root)?;
            root.present().map_err(drawing)?;
        }
        std::fs::rename(&tmp_svg, &svg)?;
        std::fs::rename(&tmp_png, &png)?;
        Ok(())
    })();
    if drawn.is_err() {
        let _ = std::fs::remove_file(&tmp_svg);
        let _ = std::fs::remove_file(&tmp_png);
    }
    drawn
}

/// A log-axis range around the positive finite values, with some room.
pub fn log_range(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(a, b), v| (a.min(v), b.max(v)));
    (hi > 0.0).then(|| (lo / 1.5, hi * 1.5))
}

/// The legend box of every figure.
pub fn legend<'a, DB: DrawingBackend + 'a, X: Ranged, Y: Ranged>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    position: SeriesLabelPosition,
) -> Result<()> {
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font((FONT, 11))
        .position(position)
        .draw()
        .map_err(drawing)
}
