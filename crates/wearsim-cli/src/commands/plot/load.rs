//! Figures of quantities against load (paper Figs. 2, 4, 5, 6 and appendix C): one panel per
//! quantity, one curve per setting, points the mean over surface pairs with the 95 % interval of the
//! mean as bars; and Eq. 5 against W (Fig. B.9b).

use std::collections::BTreeMap;

use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use wearsim::study::findings::RESOLVED_PARTICLES;

use crate::figures::{color, layout, legend, number, Axis, Entry, Figure, Marker, Panel, Swatch};

use super::data::{Curve, Point, Quantity, Units2};

/// One panel: the quantity, its axis label, a log axis, and whether it is divided by the nominal
/// area (rates of boxes smaller than the paper's).
pub(super) struct LoadPanel {
    pub quantity: Quantity,
    pub label: String,
    pub log: bool,
    pub per_area: bool,
}

impl LoadPanel {
    pub fn new(quantity: Quantity, label: impl Into<String>, log: bool) -> Self {
        Self {
            quantity,
            label: label.into(),
            log,
            per_area: false,
        }
    }

    /// A rate divided by the nominal area Lx·Ly, labelled so.
    pub fn per_area(quantity: Quantity, label: &str, units: Units2, log: bool) -> Self {
        Self {
            quantity,
            label: format!("{label} / (Lx·Ly) ({})", units.per_area()),
            log,
            per_area: true,
        }
    }
}

/// Points (x, y) of a series.
type Points = Vec<(f64, f64)>;

/// The legend's title: what points and bars are.
pub(super) const BARS: &str = "mean over surface pairs; bars: 95 % confidence interval of the mean (Student t)";

/// A figure of quantities against load, one panel each, with a shared legend.
pub(super) struct LoadFigure<'a> {
    pub curves: Vec<&'a Curve>,
    pub panels: Vec<LoadPanel>,
    pub x_label: String,
    /// Shaded range of the last panel's y and its legend label (Kim et al.'s experiments).
    pub band: Option<(f64, f64, &'static str)>,
    /// Colour by material instead of by curve (its several series told apart by marker).
    pub by_material: bool,
    /// Whether the panels show fitted sliding rates, whose points with fewer than
    /// [`RESOLVED_PARTICLES`] particles are drawn hollow.
    pub fitted: bool,
    pub title: String,
}

impl LoadFigure<'_> {
    fn style(&self, i: usize, c: &Curve) -> (RGBColor, Marker) {
        if self.by_material {
            // The material's colour; its several series (surface variants, energies) by marker.
            let within = self.curves[..i].iter().filter(|d| d.material == c.material).count();
            (color(c.material), Marker::nth(within))
        } else {
            (color(i), Marker::nth(c.material))
        }
    }

    /// Whether curve `i`'s point at `x` rests on few particles (drawn hollow).
    fn thin(&self, i: usize, x: f64) -> bool {
        self.fitted
            && self.curves[i]
                .particles()
                .iter()
                .any(|p| p.0 == x && p.1 < RESOLVED_PARTICLES)
    }

    /// Draws one panel; returns whether it marked settings without wear on the axis.
    fn panel<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>, p: usize) -> Result<bool> {
        let spec = &self.panels[p];
        let stats: Vec<Vec<Point>> = self
            .curves
            .iter()
            .map(|c| c.stats(spec.quantity, spec.per_area))
            .collect();
        let band = if p + 1 == self.panels.len() { self.band } else { None };
        let xs = stats.iter().flatten().map(|s| s.0);
        let ys = stats
            .iter()
            .flatten()
            .flat_map(|s| [s.1, s.2, s.3])
            .filter(|v| v.is_finite())
            .chain(band.iter().flat_map(|b| [b.0, b.1]));
        let x = Axis::spanning(&self.x_label, true, xs, (1e-4, 1e-2));
        let y = Axis::spanning(&spec.label, spec.log, ys, (1e-6, 1.0));
        let caption = if p == 0 { self.title.clone() } else { String::new() };
        let mut panel = Panel::new(area, &caption, x, y)?;
        if let Some((lo, hi, _)) = band {
            panel.band(lo, hi, RGBColor(86, 180, 233).mix(0.25))?;
        }
        // Per load, the no-wear markers drawn so far: the next stacks above them, so that curves
        // without wear at the same load stay visible side by side.
        let mut zeros_at: BTreeMap<u64, usize> = BTreeMap::new();
        let mut zeros_drawn = false;
        for (i, (c, s)) in self.curves.iter().zip(&stats).enumerate() {
            let (col, marker) = self.style(i, c);
            let means: Vec<(f64, f64)> = s.iter().map(|p| (p.0, p.1)).collect();
            panel.line(&means, col, false, 2)?;
            let (hollow, filled): (Points, Points) = means.iter().partition(|p| self.thin(i, p.0));
            panel.markers(&filled, col, marker)?;
            panel.markers_hollow(&hollow, col, marker)?;
            // No wear in any surface pair: zero has no place on a log axis, so it is marked on
            // the axis itself.
            if spec.log {
                let zeros: Vec<(f64, usize)> = s
                    .iter()
                    .filter(|p| p.4 <= 0.0)
                    .map(|p| {
                        let level = zeros_at.entry(p.0.to_bits()).or_insert(0);
                        *level += 1;
                        (p.0, *level - 1)
                    })
                    .collect();
                zeros_drawn |= !zeros.is_empty();
                panel.zeros_at_axis(&zeros, col)?;
            }
            let bars: Vec<(f64, f64, f64)> = s
                .iter()
                .filter(|p| p.2.is_finite() && p.3.is_finite())
                .map(|p| (p.0, p.2, p.3))
                .collect();
            panel.bars(&bars, col)?;
        }
        Ok(zeros_drawn)
    }

    /// Each curve's legend entry with the particle counts of its hollow points, then what the
    /// hollow points, the markers on the axis and the band are.
    fn entries(&self, zeros_drawn: bool) -> Vec<Entry> {
        let mut entries: Vec<Entry> = Vec::new();
        let mut any_thin = false;
        for (i, c) in self.curves.iter().enumerate() {
            let (col, marker) = self.style(i, c);
            // A point without any particle has no wear: it is the marker on the axis, not a hollow one.
            let counts: Vec<String> = c
                .particles()
                .iter()
                .filter(|p| self.fitted && p.1 < RESOLVED_PARTICLES && p.1 > 0.0)
                .map(|p| number((p.1 * 10.0).round() / 10.0))
                .collect();
            any_thin |= self.fitted && c.particles().iter().any(|p| p.1 < RESOLVED_PARTICLES);
            let note = if counts.is_empty() {
                String::new()
            } else {
                format!(" — hollow: {} particles", counts.join(", "))
            };
            entries.push(Entry {
                label: format!("{}{note}", c.label),
                color: col,
                swatch: Swatch::LineMarker(marker),
            });
        }
        let grey = RGBColor(90, 90, 90);
        if any_thin {
            entries.push(Entry {
                label: format!(
                    "hollow: < {RESOLVED_PARTICLES} particles in the fit window (summed over surface pairs)"
                ),
                color: grey,
                swatch: Swatch::Hollow(Marker::Circle),
            });
        }
        if zeros_drawn {
            entries.push(Entry {
                label: "on the axis (stacked per load): zero (no wear) in every surface pair".into(),
                color: grey,
                swatch: Swatch::AtAxis,
            });
        }
        if let Some((_, _, label)) = self.band {
            entries.push(Entry {
                label: label.into(),
                color: RGBColor(86, 180, 233),
                swatch: Swatch::Band,
            });
        }
        entries
    }
}

impl Figure for LoadFigure<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let (panels, legend_area) = layout(area, self.panels.len());
        let mut zeros_drawn = false;
        for (p, panel_area) in panels.iter().enumerate().take(self.panels.len()) {
            zeros_drawn |= self.panel(panel_area, p)?;
        }
        legend(&legend_area, BARS, &self.entries(zeros_drawn))
    }
}

/// Eq. 5 against the summed wear rate (appendix B, Fig. B.9b): one point per setting and load.
pub(super) struct Eq5Figure<'a> {
    pub curves: Vec<&'a Curve>,
    pub units: Units2,
}

impl Figure for Eq5Figure<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let points: Vec<Vec<(f64, f64)>> = self
            .curves
            .iter()
            .map(|c| {
                let w = c.stats("wear_rate", false);
                let e = c.stats("wear_rate_estimate", false);
                w.iter()
                    .zip(&e)
                    .map(|(a, b)| (a.1, b.1))
                    .filter(|p| p.0 > 0.0 && p.1 > 0.0)
                    .collect()
            })
            .collect();
        let all: Vec<f64> = points.iter().flatten().flat_map(|p| [p.0, p.1]).collect();
        let (panels, legend_area) = layout(area, 1);
        let unit = self.units.area();
        let x = Axis::spanning(
            format!("wear rate W, summed particle volumes ({unit})"),
            true,
            all.iter().copied(),
            (1e-6, 1e-3),
        );
        let y = Axis::spanning(
            format!("Eq. 5: ω d*³ dN*₊/ds ({unit})"),
            true,
            all.iter().copied(),
            (1e-6, 1e-3),
        );
        let (lo, hi) = (x.lo.min(y.lo), x.hi.max(y.hi));
        let mut panel = Panel::new(
            &panels[0],
            "Eq. 5 against the summed wear rate (mean over surface pairs)",
            x,
            y,
        )?;
        panel.line(&[(lo, lo), (hi, hi)], RGBColor(120, 120, 120), true, 1)?;
        let mut entries = vec![Entry {
            label: "Eq. 5 = W".into(),
            color: RGBColor(120, 120, 120),
            swatch: Swatch::Line { dashed: true },
        }];
        for (i, (c, pts)) in self.curves.iter().zip(&points).enumerate() {
            panel.markers(pts, color(i), Marker::nth(c.material))?;
            entries.push(Entry {
                label: c.label.clone(),
                color: color(i),
                swatch: Swatch::Marker(Marker::nth(c.material)),
            });
        }
        legend(&legend_area, "", &entries)
    }
}
