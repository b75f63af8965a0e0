//! Drawing the library's figures (`wearsim::study::figures`: panels of series, a legend) with
//! plotters: the figures' numbers, labels and styles are the library's; this file only maps them
//! onto the pieces of [`crate::figures`] (axes, lines, markers, bars, bands, the legend).

use std::collections::BTreeMap;

use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use wearsim::study::figures::{self as data, Color as Tint, Style};

use crate::figures::{color, layout, legend, Axis, Entry, Figure, Marker, Panel, Swatch};

/// A library figure, drawable on any backend.
pub(super) struct Drawn<'a>(pub &'a data::Figure);

/// The colour a library colour is drawn in.
fn rgb(c: Tint) -> RGBColor {
    match c {
        Tint::Palette(i) => color(i),
        Tint::Grey => RGBColor(120, 120, 120),
        Tint::Black => BLACK,
        Tint::Light => RGBColor(200, 200, 200),
        Tint::Band => RGBColor(86, 180, 233),
    }
}

fn xy(points: &[data::Point]) -> Vec<(f64, f64)> {
    points.iter().map(|p| (p.x, p.y)).collect()
}

/// A panel's axes: each spanning the data's values (the interval's ends and a shaded range
/// included; fitted and reference lines are drawn over them, not spanned); both spanning x and y
/// where the panel draws y = x.
fn axes(panel: &data::Panel) -> (Axis, Axis) {
    let points = || panel.series.iter().filter(|s| !s.reference).flat_map(|s| &s.points);
    let xs: Vec<f64> = points().map(|p| p.x).collect();
    let mut ys: Vec<f64> = points().flat_map(|p| [p.y, p.low, p.high]).collect();
    ys.extend(panel.y_band.iter().flat_map(|b| [b.low, b.high]));
    let (xs, ys) = if panel.diagonal {
        let both: Vec<f64> = xs.iter().chain(&ys).copied().collect();
        (both.clone(), both)
    } else {
        (xs, ys)
    };
    (
        Axis::spanning(&panel.x.label, panel.x.log, xs, panel.x.fallback),
        Axis::spanning(&panel.y.label, panel.y.log, ys, panel.y.fallback),
    )
}

/// Draws one panel of the figure.
fn panel<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, spec: &data::Panel, caption: &str) -> Result<()> {
    let (x, y) = axes(spec);
    let (lo, hi) = (x.lo.min(y.lo), x.hi.max(y.hi));
    let mut panel = Panel::new(area, caption, x, y)?;
    if let Some(b) = &spec.y_band {
        panel.band(b.low, b.high, rgb(b.color).mix(0.25))?;
    }
    if let Some(b) = &spec.x_band {
        panel.x_band(b.low, b.high, rgb(b.color).mix(0.35))?;
    }
    if spec.diagonal {
        panel.line(&[(lo, lo), (hi, hi)], rgb(Tint::Grey), true, 1)?;
    }
    // Per load, the no-wear markers drawn so far: the next stacks above them, so that curves
    // without wear at the same load stay visible side by side.
    let mut zeros_at: BTreeMap<u64, usize> = BTreeMap::new();
    for s in &spec.series {
        let (col, marker) = (rgb(s.color), Marker::nth(s.marker));
        match s.style {
            Style::Line { dashed, width } => panel.line(&xy(&s.points), col, dashed, width)?,
            Style::Markers => panel.markers(&xy(&s.points), col, marker)?,
            Style::Means => {
                panel.line(&xy(&s.points), col, false, 2)?;
                let (hollow, filled): (Vec<data::Point>, Vec<data::Point>) = s.points.iter().partition(|p| p.hollow);
                panel.markers(&xy(&filled), col, marker)?;
                panel.markers_hollow(&xy(&hollow), col, marker)?;
                let ringed: Vec<data::Point> = s.points.iter().filter(|p| p.breakdown).copied().collect();
                panel.rings(&xy(&ringed), rgb(Tint::Grey))?;
                // No wear in any surface pair: zero has no place on a log axis, so it is marked on
                // the axis itself.
                if spec.y.log {
                    let zeros: Vec<(f64, usize)> = s
                        .points
                        .iter()
                        .filter(|p| p.no_wear)
                        .map(|p| {
                            let level = zeros_at.entry(p.x.to_bits()).or_insert(0);
                            *level += 1;
                            (p.x, *level - 1)
                        })
                        .collect();
                    panel.zeros_at_axis(&zeros, col)?;
                }
                let bars: Vec<(f64, f64, f64)> = s
                    .points
                    .iter()
                    .filter(|p| p.low.is_finite() && p.high.is_finite())
                    .map(|p| (p.x, p.low, p.high))
                    .collect();
                panel.bars(&bars, col)?;
            }
        }
    }
    Ok(())
}

fn entry(e: &data::LegendEntry) -> Entry {
    let marker = Marker::nth(e.marker);
    Entry {
        label: e.label.clone(),
        color: rgb(e.color),
        swatch: match e.swatch {
            data::Swatch::Line { dashed } => Swatch::Line { dashed },
            data::Swatch::Marker => Swatch::Marker(marker),
            data::Swatch::LineMarker => Swatch::LineMarker(marker),
            data::Swatch::Hollow => Swatch::Hollow(marker),
            data::Swatch::AtAxis => Swatch::AtAxis,
            data::Swatch::Ring => Swatch::Ring,
            data::Swatch::Band => Swatch::Band,
        },
    }
}

impl Figure for Drawn<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let figure = self.0;
        if let Some(note) = &figure.note {
            // A figure with nothing to draw says why.
            let (_, h) = area.dim_in_pixel();
            let style = (crate::figures::FONT, 18).into_font().color(&BLACK);
            area.draw_text(note, &style, (40, h as i32 / 2))
                .map_err(crate::figures::drawing)?;
            return Ok(());
        }
        let (areas, legend_area) = layout(area, figure.panels.len());
        for (p, (spec, a)) in figure.panels.iter().zip(&areas).enumerate() {
            panel(a, spec, if p == 0 { &figure.title } else { "" })?;
        }
        let entries: Vec<Entry> = figure.legend.iter().map(entry).collect();
        legend(&legend_area, &figure.legend_title, &entries)
    }
}

/// The size a figure is drawn at: wider with more panels, and for the series against the sliding
/// distance, whose legends are long (its registry entry's layout).
pub(super) fn size(figure: &data::Figure) -> (u32, u32) {
    match (figure.panels.len(), data::layout_of(figure.entry)) {
        (3, _) => (2100, 640),
        (2, _) => (1700, 640),
        (1, data::Layout::Series) => (1400, 640),
        _ => (1150, 640),
    }
}
