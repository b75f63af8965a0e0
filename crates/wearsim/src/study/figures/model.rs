//! A figure as data: panels of series of points, with their axes, shaded ranges and legend, and
//! its numbers as CSV for a reader who re-plots it.

use serde::Serialize;

/// A colour: an index into the front end's palette (colour-blind safe), or a neutral.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Color {
    Palette(usize),
    /// Reference lines and legend notes.
    Grey,
    Black,
    /// The shading of the running-in.
    Light,
    /// The shading of an experimental range.
    Band,
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Style {
    /// A line through the points (`width` in pixels of the CLI's figures: 2 for data, 1 for fits).
    Line { dashed: bool, width: u32 },
    /// Markers only.
    Markers,
    /// A line with a marker at each point, and each point's interval as a bar: the means over
    /// surface pairs of the figures against load.
    Means,
}

/// What a legend entry shows beside its label.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Swatch {
    Line {
        dashed: bool,
    },
    Marker,
    LineMarker,
    /// A hollow marker: a point resting on few particles.
    Hollow,
    /// The marker of a setting without wear, on the axis.
    AtAxis,
    /// A ring around a marker: a load in the paper's breakdown regime (appendix C).
    Ring,
    /// A shaded range.
    Band,
}

/// One point of a series.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Point {
    pub x: f64,
    pub y: f64,
    /// The 95 % interval of the mean over surface pairs (NaN where there is none: one pair, or a
    /// line that is no mean).
    pub low: f64,
    pub high: f64,
    /// A fitted rate resting on fewer than [`RESOLVED_PARTICLES`](crate::study::findings::RESOLVED_PARTICLES) particles (summed over the
    /// pairs): drawn hollow.
    pub hollow: bool,
    /// No surface pair wore (the maximum over pairs is 0): on a log axis, marked on the axis.
    pub no_wear: bool,
    /// The load lies in the paper's breakdown regime (appendix C: a breakdown measure beyond its
    /// limit, `crate::sliding::LoadBreakdown`) in at least one surface pair: drawn ringed.
    pub breakdown: bool,
}

impl Point {
    pub(super) fn at(x: f64, y: f64) -> Self {
        Self {
            x,
            y,
            low: f64::NAN,
            high: f64::NAN,
            hollow: false,
            no_wear: false,
            breakdown: false,
        }
    }
}

/// A series of one panel.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Series {
    /// What it is (the curve's setting, "fit", …): its legend label where it has an entry.
    pub label: String,
    pub color: Color,
    /// Index into the front end's marker shapes.
    pub marker: usize,
    pub style: Style,
    pub points: Vec<Point>,
    /// A fitted or reference line drawn over the data: the axes span the data, not it.
    pub reference: bool,
}

/// An axis: its label with its unit, whether it is logarithmic, and the range shown when it has no
/// data.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Axis {
    pub label: String,
    pub log: bool,
    pub fallback: (f64, f64),
}

/// A shaded range of one axis.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Band {
    pub low: f64,
    pub high: f64,
    pub color: Color,
}

/// One panel.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Panel {
    pub x: Axis,
    pub y: Axis,
    /// A shaded range of x (the running-in of Fig. 3).
    pub x_band: Option<Band>,
    /// A shaded range of y (Kim et al.'s experimental k, Fig. 6).
    pub y_band: Option<Band>,
    /// A y = x line over the shown range (Eq. 5 against W).
    pub diagonal: bool,
    pub series: Vec<Series>,
}

/// One entry of a figure's legend.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LegendEntry {
    pub label: String,
    pub color: Color,
    pub marker: usize,
    pub swatch: Swatch,
}

/// One figure as data: the file name it is written under, its title (above the first panel), its
/// panels, its legend and the legend's title; or, with no data to draw, a note that says why.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Figure {
    /// The registry entry it belongs to ([`super::FIGURES`]), set by the registry.
    pub entry: &'static str,
    /// The file name, without extension (`fig4_sliding_wear`): the entry's stem, and what a figure
    /// of an entry of several adds to it (its builder gives only that part).
    pub name: String,
    pub title: String,
    pub panels: Vec<Panel>,
    pub legend_title: String,
    pub legend: Vec<LegendEntry>,
    pub note: Option<String>,
    /// What a front end prints of the figure beside drawing it, one line each (the appendix F
    /// fits: over all materials, then each material's); empty for most figures.
    pub report: Vec<String>,
}

impl Figure {
    /// A figure that says why it has no data, in place of the entry's.
    pub(super) fn note(note: impl Into<String>) -> Self {
        Self {
            entry: "",
            name: String::new(),
            title: String::new(),
            panels: Vec::new(),
            legend_title: String::new(),
            legend: Vec::new(),
            note: Some(note.into()),
            report: Vec::new(),
        }
    }

    /// The figure's numbers as CSV, one row per point and per shaded range, for a reader who
    /// re-plots it: `panel, x_label, y_label, series, kind, x, y, low, high, hollow, no_wear,
    /// breakdown`. `kind`
    /// is `point` (low/high the 95 % interval of y, empty where there is none), `x_band` or
    /// `y_band` (low/high the shaded range). Numbers in Rust's shortest round-trip form.
    pub fn to_csv(&self) -> String {
        let mut out = String::from("panel,x_label,y_label,series,kind,x,y,low,high,hollow,no_wear,breakdown\n");
        let f = |v: f64| if v.is_finite() { format!("{v:e}") } else { String::new() };
        for (p, panel) in self.panels.iter().enumerate() {
            let head = format!("{p},{},{}", quote(&panel.x.label), quote(&panel.y.label));
            for (band, kind) in [(&panel.x_band, "x_band"), (&panel.y_band, "y_band")] {
                if let Some(b) = band {
                    out += &format!("{head},,{kind},,,{},{},,,\n", f(b.low), f(b.high));
                }
            }
            for s in &panel.series {
                for q in &s.points {
                    out += &format!(
                        "{head},{},point,{},{},{},{},{},{},{}\n",
                        quote(&s.label),
                        f(q.x),
                        f(q.y),
                        f(q.low),
                        f(q.high),
                        q.hollow,
                        q.no_wear,
                        q.breakdown
                    );
                }
            }
        }
        out
    }
}

/// A CSV field, quoted when it holds a comma, a quote or a line break.
pub(super) fn quote(text: &str) -> String {
    if text.contains([',', '"', '\n']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

/// The 95 % interval of a mean `mean` whose Student-t interval reaches `high`, on a log axis: the
/// same interval in log space (the delta method, ln m ± t·se/m), mean ×/÷ e^(t·se/mean). Always
/// positive and symmetric about the mean on the axis, where the linear one reaches below zero
/// (and is cut off) whenever the pairs spread more than the mean; the point is the same mean as the
/// findings'. NaN where the mean is not positive or has no interval.
pub(super) fn log_space_interval(mean: f64, high: f64) -> (f64, f64) {
    if !(mean > 0.0 && high.is_finite()) {
        return (f64::NAN, f64::NAN);
    }
    let factor = ((high - mean) / mean).exp();
    (mean / factor, mean * factor)
}

pub(super) fn line_series(label: String, color: Color, dashed: bool, width: u32, points: Vec<Point>) -> Series {
    Series {
        label,
        color,
        marker: 0,
        style: Style::Line { dashed, width },
        points,
        reference: false,
    }
}

/// A fitted or reference line (dashed, thin): drawn over the data, not widening the axes.
pub(super) fn fit_line(label: String, color: Color, points: Vec<Point>) -> Series {
    Series {
        reference: true,
        ..line_series(label, color, true, 1, points)
    }
}

pub(super) fn one_panel(x: Axis, y: Axis, series: Vec<Series>) -> Vec<Panel> {
    vec![Panel {
        x,
        y,
        x_band: None,
        y_band: None,
        diagonal: false,
        series,
    }]
}
