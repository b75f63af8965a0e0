//! Drawing figures: the bundled font, one [`Figure`] drawn into both PNG and SVG by [`save`], and the
//! pieces every figure shares — axes that may be logarithmic (drawn in log₁₀ of the value, with
//! ticks at 1, 2 and 5 of each decade and labels such as `2.5e-4`), a legend in its own column so
//! that it never hides data, a colour-blind-safe palette and marker shapes. What a study's figures
//! plot is the library's (`wearsim::study::figures`); drawing it is this front end's. The text is
//! drawn with the DejaVu Sans font shipped in
//! `assets/` (STIX General for the script 𝒢 it lacks, see [`crate::raster`]), so no system font is
//! needed.

use std::path::Path;

use anyhow::{anyhow, Context, Result};
use image::ImageEncoder;
use plotters::coord::ranged1d::{KeyPointHint, NoDefaultFormatting, Ranged};
use plotters::coord::Shift;
use plotters::prelude::*;

/// Family name the bundled font is registered under.
pub const FONT: &str = "sans-serif";

/// Registers the bundled DejaVu Sans font (once per process).
pub fn register_font() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        plotters::style::register_font(FONT, FontStyle::Normal, crate::raster::FONT_BYTES)
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

/// Draws `figure` into `dir/name.png` and `dir/name.svg`: both are drawn in memory, then written by
/// the library's atomic writer (a temporary file renamed into place, removed by a stop), so a failed
/// drawing or write leaves no half-written figure. `shown` is the folder the figures end up in,
/// named by a write that fails (a full disk).
pub fn save(dir: &Path, shown: &Path, name: &str, size: (u32, u32), figure: &impl Figure) -> Result<()> {
    register_font();
    // A first drawing, thrown away, measures the legend; the figure is then widened so that the
    // legend column fits its longest entry on one line and the panels keep at least three quarters
    // of the width (and no less than they were given).
    // Likewise the panels are widened until the first panel's caption fits above it.
    LEGEND.with(|l| l.set((LEGEND_WIDTH, 0)));
    CAPTION.with(|c| c.set(0.0));
    {
        let mut sink = String::new();
        let root = SVGBackend::with_string(&mut sink, size).into_drawing_area();
        figure.draw(&root)?;
    }
    let needed = LEGEND.with(|l| l.get().1);
    let caption = CAPTION.with(|c| c.get()).max(1.0);
    let size = if needed == 0 {
        size
    } else {
        let given = size.0.saturating_sub(LEGEND_WIDTH);
        let panels = given.max(3 * needed).max((f64::from(given) * caption).ceil() as u32);
        LEGEND.with(|l| l.set((needed, 0)));
        (panels + needed, size.1)
    };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(drawing)?;
        figure.draw(&root)?;
        root.present().map_err(drawing)?;
    }
    let mut pixels = vec![0u8; 3 * size.0 as usize * size.1 as usize];
    {
        let backend = BitMapBackend::with_buffer(&mut pixels, size);
        let root = crate::raster::Raster::new(backend).into_drawing_area();
        root.fill(&WHITE).map_err(drawing)?;
        figure.draw(&root)?;
        root.present().map_err(drawing)?;
    }
    let mut png = Vec::new();
    image::codecs::png::PngEncoder::new(&mut png)
        .write_image(&pixels, size.0, size.1, image::ColorType::Rgb8)
        .map_err(drawing)?;
    for (file, bytes) in [
        (format!("{name}.svg"), svg.as_bytes()),
        (format!("{name}.png"), &png[..]),
    ] {
        write_into(dir, shown, &file, bytes)
            .with_context(|| format!("cannot write the figure {name} into {}", shown.display()))?;
    }
    Ok(())
}

/// Writes `bytes` to `dir/file` atomically; a failed write (a full disk, in words) names the file
/// as it will be once `dir` is put in place as `shown`, not its place in the temporary folder.
pub fn write_into(dir: &Path, shown: &Path, file: &str, bytes: &[u8]) -> Result<()> {
    wearsim::io::atomic_write(&dir.join(file), |w| w.write_all(bytes)).map_err(|e| match e {
        wearsim::Error::Io { source, .. } => wearsim::Error::io(shown.join(file), source).into(),
        other => other.into(),
    })
}

/// Colour-blind-safe palette (Okabe & Ito), then greys.
const PALETTE: [RGBColor; 8] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
    RGBColor(150, 150, 150),
];

/// The `i`-th colour of the palette.
pub fn color(i: usize) -> RGBColor {
    PALETTE[i % PALETTE.len()]
}

/// Marker shapes, one per material in figures that separate materials by shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Marker {
    Circle,
    Triangle,
    Square,
    Diamond,
    Cross,
}

impl Marker {
    pub fn nth(i: usize) -> Self {
        [
            Marker::Circle,
            Marker::Triangle,
            Marker::Square,
            Marker::Diamond,
            Marker::Cross,
        ][i % 5]
    }

    /// The marker's outline, relative to its centre, in pixels.
    pub fn outline(self) -> Vec<(i32, i32)> {
        let r = 4;
        match self {
            Marker::Circle => (0..12)
                .map(|k| {
                    let a = k as f64 * std::f64::consts::PI / 6.0;
                    ((r as f64 * a.cos()).round() as i32, (r as f64 * a.sin()).round() as i32)
                })
                .collect(),
            Marker::Triangle => vec![(0, -r - 1), (-r - 1, r), (r + 1, r)],
            Marker::Square => vec![(-r, -r), (r, -r), (r, r), (-r, r)],
            Marker::Diamond => vec![(0, -r - 1), (r + 1, 0), (0, r + 1), (-r - 1, 0)],
            Marker::Cross => vec![
                (-r, -r + 1),
                (-r + 1, -r),
                (0, -1),
                (r - 1, -r),
                (r, -r + 1),
                (1, 0),
                (r, r - 1),
                (r - 1, r),
                (0, 1),
                (-r + 1, r),
                (-r, r - 1),
                (-1, 0),
            ],
        }
    }
}

/// A linear coordinate with the tick positions chosen by [`Axis`] (plotters' own key points would
/// fall at 10^-3.5 on a log₁₀ axis).
#[derive(Debug, Clone)]
struct Ticked {
    lo: f64,
    hi: f64,
    ticks: Vec<f64>,
}

impl plotters::coord::ranged1d::ValueFormatter<f64> for Ticked {
    fn format(value: &f64) -> String {
        number(*value)
    }
}

impl Ranged for Ticked {
    type FormatOption = NoDefaultFormatting;
    type ValueType = f64;

    fn map(&self, v: &f64, limit: (i32, i32)) -> i32 {
        let t = (v - self.lo) / (self.hi - self.lo);
        limit.0 + (t * (limit.1 - limit.0) as f64).round() as i32
    }

    fn key_points<Hint: KeyPointHint>(&self, _hint: Hint) -> Vec<f64> {
        self.ticks.clone()
    }

    fn range(&self) -> std::ops::Range<f64> {
        self.lo..self.hi
    }
}

/// An axis: its label (quantity and unit), whether it is logarithmic, and its range.
#[derive(Debug, Clone)]
pub struct Axis {
    pub label: String,
    pub log: bool,
    pub lo: f64,
    pub hi: f64,
}

impl Axis {
    /// An axis spanning `values` (non-positive and non-finite values are left out on a log axis),
    /// with some room, or `fallback` without values.
    pub fn spanning(
        label: impl Into<String>,
        log: bool,
        values: impl IntoIterator<Item = f64>,
        fallback: (f64, f64),
    ) -> Self {
        let (lo, hi) = values
            .into_iter()
            .filter(|v| v.is_finite() && (!log || *v > 0.0))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
        let (lo, hi) = if lo.is_finite() { (lo, hi) } else { fallback };
        let (lo, hi) = if log {
            let (lo, hi) = if hi > lo { (lo, hi) } else { (lo / 2.0, hi * 2.0) };
            (lo / 1.4, hi * 1.4)
        } else {
            let lo = lo.min(0.0);
            let span = if hi > lo { hi - lo } else { hi.abs().max(1e-300) };
            (lo, hi + 0.08 * span)
        };
        Self {
            label: label.into(),
            log,
            lo,
            hi,
        }
    }

    /// Where a value goes on the drawn (linear) axis: its log₁₀ on a log axis.
    pub fn map(&self, v: f64) -> f64 {
        if self.log {
            v.log10()
        } else {
            v
        }
    }

    /// Whether a value can be drawn on this axis.
    pub fn shows(&self, v: f64) -> bool {
        v.is_finite() && (!self.log || v > 0.0)
    }

    fn coordinate(&self) -> Ticked {
        Ticked {
            lo: self.map(self.lo),
            hi: self.map(self.hi),
            ticks: self.ticks(),
        }
    }

    /// Tick positions (in drawn coordinates): 1, 2, 5 × 10ᵏ on a log axis (every decade alone when
    /// the range spans many), round steps on a linear one.
    fn ticks(&self) -> Vec<f64> {
        if self.log {
            let (a, b) = (self.lo.log10().floor() as i32, self.hi.log10().ceil() as i32);
            let decades = b - a;
            let mantissas: &[f64] = if decades > 5 {
                &[1.0]
            } else if decades > 2 {
                &[1.0, 3.0]
            } else {
                &[1.0, 2.0, 5.0]
            };
            let step = if decades > 10 { 2 } else { 1 };
            (a..=b)
                .step_by(step)
                .flat_map(|k| mantissas.iter().map(move |m| m * 10f64.powi(k)))
                .filter(|v| *v >= self.lo && *v <= self.hi)
                .map(f64::log10)
                .collect()
        } else {
            let span = self.hi - self.lo;
            let raw = span / 5.0;
            let mag = 10f64.powf(raw.log10().floor());
            let step = [1.0, 2.0, 2.5, 5.0, 10.0]
                .iter()
                .map(|m| m * mag)
                .find(|s| span / s <= 6.0)
                .unwrap_or(10.0 * mag);
            let first = (self.lo / step).ceil() as i64;
            let last = (self.hi / step).floor() as i64;
            (first..=last).map(|k| k as f64 * step).collect()
        }
    }

    /// The label of a tick at drawn position `v`.
    fn tick_label(&self, v: f64) -> String {
        if self.log {
            let v = 10f64.powf(v);
            // Decades below 0.01 read best in one style: 5e-4, 1e-3, 2e-3.
            if v < 1e-2 {
                let s = format!("{v:.1e}");
                let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
                return format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.'));
            }
            number(v)
        } else {
            number(v)
        }
    }
}

/// Numbers as legends and tick labels print them: the library's, so that both front ends print
/// the same digits.
pub use wearsim::output::number;

type Coords = Cartesian2d<Ticked, Ticked>;

/// One panel: a chart with its axes, taking data in the axes' own (unmapped) values.
pub struct Panel<'a, DB: DrawingBackend> {
    chart: ChartContext<'a, DB, Coords>,
    pub x: Axis,
    pub y: Axis,
}

impl<'a, DB: DrawingBackend + 'a> Panel<'a, DB> {
    /// A panel on `area` with a caption, its axes, ticks and light grid drawn.
    pub fn new(area: &'a DrawingArea<DB, Shift>, caption: &str, x: Axis, y: Axis) -> Result<Self> {
        let (xr, yr) = (x.coordinate(), y.coordinate());
        if !caption.is_empty() {
            let font = (FONT, 15).into_font().color(&BLACK);
            let wide = area.estimate_text_size(caption, &font).map_or(0, |(w, _)| w) + 40;
            let given = area.dim_in_pixel().0.max(1);
            CAPTION.with(|c| c.set(c.get().max(f64::from(wide) / f64::from(given))));
        }
        let mut chart = ChartBuilder::on(area)
            .margin(10)
            .margin_right(18)
            .x_label_area_size(48)
            .y_label_area_size(78)
            .caption(caption, (FONT, 15))
            .build_cartesian_2d(xr, yr)
            .map_err(drawing)?;
        let (xa, ya) = (x.clone(), y.clone());
        chart
            .configure_mesh()
            .x_desc(&x.label)
            .y_desc(&y.label)
            .x_label_formatter(&|v| xa.tick_label(*v))
            .y_label_formatter(&|v| ya.tick_label(*v))
            .bold_line_style(RGBColor(225, 225, 225))
            .light_line_style(TRANSPARENT)
            .axis_desc_style((FONT, 14))
            .label_style((FONT, 12))
            .draw()
            .map_err(drawing)?;
        Ok(Self { chart, x, y })
    }

    fn point(&self, (x, y): (f64, f64)) -> Option<(f64, f64)> {
        (self.x.shows(x) && self.y.shows(y)).then(|| (self.x.map(x), self.y.map(y)))
    }

    /// A line through the drawable points, solid or dashed.
    pub fn line(&mut self, points: &[(f64, f64)], color: RGBColor, dashed: bool, width: u32) -> Result<()> {
        let pts: Vec<(f64, f64)> = points.iter().filter_map(|p| self.point(*p)).collect();
        if pts.len() < 2 {
            return Ok(());
        }
        if dashed {
            self.chart
                .draw_series(DashedLineSeries::new(pts, 8, 5, color.stroke_width(width)))
                .map_err(drawing)?;
        } else {
            self.chart
                .draw_series(LineSeries::new(pts, color.stroke_width(width)))
                .map_err(drawing)?;
        }
        Ok(())
    }

    /// Markers at the drawable points.
    pub fn markers(&mut self, points: &[(f64, f64)], color: RGBColor, marker: Marker) -> Result<()> {
        let pts: Vec<(f64, f64)> = points.iter().filter_map(|p| self.point(*p)).collect();
        let shape = marker.outline();
        self.chart
            .draw_series(
                pts.into_iter()
                    .map(|p| EmptyElement::at(p) + Polygon::new(shape.clone(), color.filled())),
            )
            .map_err(drawing)?;
        Ok(())
    }

    /// Markers at the drawable points, filled or hollow (an outline on white).
    pub fn markers_hollow(&mut self, points: &[(f64, f64)], color: RGBColor, marker: Marker) -> Result<()> {
        let pts: Vec<(f64, f64)> = points.iter().filter_map(|p| self.point(*p)).collect();
        let shape = marker.outline();
        let mut closed = shape.clone();
        closed.push(shape[0]);
        self.chart
            .draw_series(pts.into_iter().map(|p| {
                EmptyElement::at(p)
                    + Polygon::new(shape.clone(), WHITE.filled())
                    + PathElement::new(closed.clone(), color.stroke_width(2))
            }))
            .map_err(drawing)?;
        Ok(())
    }

    /// A ring around each drawable point (a load in the paper's breakdown regime), wider than any
    /// marker.
    pub fn rings(&mut self, points: &[(f64, f64)], color: RGBColor) -> Result<()> {
        let pts: Vec<(f64, f64)> = points.iter().filter_map(|p| self.point(*p)).collect();
        self.chart
            .draw_series(
                pts.into_iter()
                    .map(|p| EmptyElement::at(p) + Circle::new((0, 0), 10, color.stroke_width(2))),
            )
            .map_err(drawing)?;
        Ok(())
    }

    /// A value of zero on a log axis: a downward triangle resting on the x axis at each x, the
    /// `level`-th of several at one x stacked that many triangles higher.
    pub fn zeros_at_axis(&mut self, at: &[(f64, usize)], color: RGBColor) -> Result<()> {
        let y = self.y.map(self.y.lo);
        let pts: Vec<((f64, f64), i32)> = at
            .iter()
            .filter(|(x, _)| self.x.shows(*x))
            .map(|&(x, level)| ((self.x.map(x), y), 13 * level as i32))
            .collect();
        self.chart
            .draw_series(pts.into_iter().map(|(p, up)| {
                EmptyElement::at(p) + Polygon::new(vec![(-6, -12 - up), (6, -12 - up), (0, -up)], color.filled())
            }))
            .map_err(drawing)?;
        Ok(())
    }

    /// Vertical bars from `lo` to `hi` at each x (min–max over surface pairs); on a log axis a
    /// minimum of zero (or below) is drawn down to the axis.
    pub fn bars(&mut self, bars: &[(f64, f64, f64)], color: RGBColor) -> Result<()> {
        let floor = self.y.lo;
        let segments: Vec<Vec<(f64, f64)>> = bars
            .iter()
            .filter_map(|&(x, lo, hi)| {
                let lo = if self.y.log && lo <= 0.0 { floor } else { lo };
                Some(vec![self.point((x, lo))?, self.point((x, hi))?])
            })
            .collect();
        self.chart
            .draw_series(segments.into_iter().map(|s| PathElement::new(s, color.stroke_width(1))))
            .map_err(drawing)?;
        Ok(())
    }

    /// A horizontal band between two y values across the panel.
    pub fn band(&mut self, lo: f64, hi: f64, color: RGBAColor) -> Result<()> {
        let (x0, x1) = (self.x.map(self.x.lo), self.x.map(self.x.hi));
        let (y0, y1) = (self.y.map(lo.max(self.y.lo)), self.y.map(hi.min(self.y.hi)));
        self.chart
            .draw_series(std::iter::once(Rectangle::new([(x0, y0), (x1, y1)], color.filled())))
            .map_err(drawing)?;
        Ok(())
    }

    /// A vertical band between two x values (the running-in region).
    pub fn x_band(&mut self, lo: f64, hi: f64, color: RGBAColor) -> Result<()> {
        let (x0, x1) = (self.x.map(lo.max(self.x.lo)), self.x.map(hi.min(self.x.hi)));
        let (y0, y1) = (self.y.map(self.y.lo), self.y.map(self.y.hi));
        self.chart
            .draw_series(std::iter::once(Rectangle::new([(x0, y0), (x1, y1)], color.filled())))
            .map_err(drawing)?;
        Ok(())
    }
}

/// How a legend entry is drawn.
#[derive(Debug, Clone, Copy)]
pub enum Swatch {
    Line {
        dashed: bool,
    },
    LineMarker(Marker),
    Marker(Marker),
    Hollow(Marker),
    AtAxis,
    Band,
    /// A ring: a point in the paper's breakdown regime.
    Ring,
}

/// One legend entry.
#[derive(Debug, Clone)]
pub struct Entry {
    pub label: String,
    pub color: RGBColor,
    pub swatch: Swatch,
}

/// Width of the legend column before [`save`] has measured the legend.
pub const LEGEND_WIDTH: u32 = 360;

thread_local! {
    /// The legend column's width for the drawing under way (set by [`save`]), and the widest that a
    /// legend drawn asked for.
    static LEGEND: std::cell::Cell<(u32, u32)> = const { std::cell::Cell::new((LEGEND_WIDTH, 0)) };
    /// How many times wider than its panel the widest caption drawn was (0 when all fit): [`save`]
    /// widens the panels by that much, so that a caption is never cut at the panel's edges.
    static CAPTION: std::cell::Cell<f64> = const { std::cell::Cell::new(0.0) };
}

/// Splits a figure into `n` panels side by side and a legend column on the right.
pub fn layout<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    n: usize,
) -> (Vec<DrawingArea<DB, Shift>>, DrawingArea<DB, Shift>) {
    let (w, _) = area.dim_in_pixel();
    let width = LEGEND.with(|l| l.get().0);
    let (panels, legend) = area.split_horizontally(w.saturating_sub(width));
    (panels.split_evenly((1, n.max(1))), legend)
}

/// Draws a legend (entries one per line, never wrapped) from the top, and records the width it needs.
pub fn legend<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, title: &str, entries: &[Entry]) -> Result<()> {
    let font = (FONT, 12).into_font().color(&BLACK);
    // The title one clause (up to "; ") per line, so that a long one does not widen the figure.
    let lines: Vec<&str> = title.split("; ").filter(|l| !l.is_empty()).collect();
    for (k, line) in lines.iter().enumerate() {
        area.draw_text(line, &(FONT, 13).into_font().color(&BLACK), (8, 14 + 17 * k as i32))
            .map_err(drawing)?;
    }
    let mut y = 34 + 17 * (lines.len().max(1) as i32 - 1);
    let text_width = |t: &str, size: u32| {
        area.estimate_text_size(t, &(FONT, size).into_font().color(&BLACK))
            .map_or(7 * t.chars().count() as u32, |(w, _)| w)
    };
    let needed = entries
        .iter()
        .map(|e| 42 + text_width(&e.label, 12) + 12)
        .chain(lines.iter().map(|l| 8 + text_width(l, 13) + 12))
        .max()
        .unwrap_or(0);
    LEGEND.with(|l| l.set((l.get().0, l.get().1.max(needed))));
    for e in entries {
        let mid = y + 6;
        match e.swatch {
            Swatch::Line { dashed } => {
                if dashed {
                    for k in 0..3 {
                        area.draw(&PathElement::new(
                            vec![(8 + 10 * k, mid), (14 + 10 * k, mid)],
                            e.color.stroke_width(2),
                        ))
                        .map_err(drawing)?;
                    }
                } else {
                    area.draw(&PathElement::new(vec![(8, mid), (34, mid)], e.color.stroke_width(2)))
                        .map_err(drawing)?;
                }
            }
            Swatch::LineMarker(m) => {
                area.draw(&PathElement::new(vec![(8, mid), (34, mid)], e.color.stroke_width(2)))
                    .map_err(drawing)?;
                area.draw(&(EmptyElement::at((21, mid)) + Polygon::new(m.outline(), e.color.filled())))
                    .map_err(drawing)?;
            }
            Swatch::Marker(m) => area
                .draw(&(EmptyElement::at((21, mid)) + Polygon::new(m.outline(), e.color.filled())))
                .map_err(drawing)?,
            Swatch::Hollow(m) => {
                let mut closed = m.outline();
                closed.push(closed[0]);
                area.draw(&(EmptyElement::at((21, mid)) + PathElement::new(closed, e.color.stroke_width(2))))
                    .map_err(drawing)?
            }
            Swatch::AtAxis => area
                .draw(
                    &(EmptyElement::at((21, mid + 6))
                        + Polygon::new(vec![(-6, -12), (6, -12), (0, 0)], e.color.filled())),
                )
                .map_err(drawing)?,
            Swatch::Ring => area
                .draw(&(EmptyElement::at((21, mid)) + Circle::new((0, 0), 7, e.color.stroke_width(2))))
                .map_err(drawing)?,
            Swatch::Band => area
                .draw(&Rectangle::new(
                    [(8, mid - 6), (34, mid + 6)],
                    e.color.mix(0.35).filled(),
                ))
                .map_err(drawing)?,
        }
        area.draw_text(&e.label, &font, (42, y)).map_err(drawing)?;
        y += 20;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_labels_are_short() {
        assert_eq!(number(3.0000000000000004e-5), "3e-5");
        assert_eq!(number(2.5e-4), "2.5e-4");
        assert_eq!(number(1e-3), "0.001");
        assert_eq!(number(5e-4), "5e-4");
        assert_eq!(number(0.25), "0.25");
        assert_eq!(number(0.0090144), "0.00901");
        assert_eq!(number(1500.0), "1500");
        assert_eq!(number(12.0), "12");
        assert_eq!(wearsim::output::pretty(2.5e-7), "2.5×10⁻⁷");
        assert_eq!(wearsim::output::pretty(1e-6), "10⁻⁶");
        let axis = Axis::spanning("F_N", true, [1.5e-4, 2.5e-3], (1.0, 2.0));
        let ticks: Vec<String> = axis.ticks().iter().map(|t| axis.tick_label(*t)).collect();
        // Every decade in the range has ticks, the lower loads included.
        assert!(
            ticks.contains(&"2e-4".to_string()) && ticks.contains(&"1e-3".to_string()),
            "{ticks:?}"
        );
    }
}
