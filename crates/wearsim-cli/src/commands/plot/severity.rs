//! Appendix F: the wear rate against the contact severity S_c = p_N √h_rms / K_Ic, fitted as
//! W = α S_cⁿ per material and over all of them (the library's `severity_fits`); Kim et al.'s and
//! the paper's fits drawn only beside Kim's ceramics. And a figure that only says why it is empty.

use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use wearsim::output::{MaterialSeverity, KIM_SEVERITY_FIT, PAPER_SEVERITY_FIT};
use wearsim::stats::PowerLawFit;

use crate::figures::{color, layout, legend, number, Axis, Entry, Figure, Marker, Panel, Swatch};

use super::data::Units2;

/// Contact severity (appendix F): each material's points and fit, and the fit over all.
pub(super) struct Severity {
    pub materials: Vec<MaterialSeverity>,
    pub all: PowerLawFit,
    pub units: Units2,
}

fn r2_text(fit: &PowerLawFit) -> String {
    fit.r2.map_or("undefined".into(), |r| format!("{r:.3}"))
}

impl Figure for Severity {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let (panels, legend_area) = layout(area, 1);
        let points = || self.materials.iter().flat_map(|m| m.points.iter().copied());
        let x = Axis::spanning(
            "contact severity S_c = p_N √h_rms / K_Ic",
            true,
            points().map(|p| p.0),
            (1e-3, 1.0),
        );
        let y = Axis::spanning(
            format!("wear rate W ({})", self.units.area()),
            true,
            points().map(|p| p.1),
            (1e-6, 1.0),
        );
        let (x0, x1) = (x.lo, x.hi);
        let line = |alpha: f64, n: f64| [(x0, alpha * x0.powf(n)), (x1, alpha * x1.powf(n))];
        let title = format!(
            "W = α S_cⁿ, all materials: α = {} {}, n = {:.3}, R² = {}",
            number(self.all.prefactor),
            self.units.area(),
            self.all.exponent,
            r2_text(&self.all)
        );
        let mut panel = Panel::new(&panels[0], &title, x, y)?;
        let mut entries = Vec::new();
        for (m, mat) in self.materials.iter().enumerate() {
            panel.markers(&mat.points, color(m), Marker::nth(m))?;
            let kim = mat.kim.map_or(String::new(), |k| format!(" (Kim et al.'s {})", k.name));
            match mat.fit {
                Some(fit) => {
                    panel.line(&line(fit.prefactor, fit.exponent), color(m), false, 1)?;
                    entries.push(Entry {
                        label: format!(
                            "{}{kim}: α = {}, n = {:.2}, R² = {}",
                            mat.material,
                            number(fit.prefactor),
                            fit.exponent,
                            r2_text(&fit)
                        ),
                        color: color(m),
                        swatch: Swatch::LineMarker(Marker::nth(m)),
                    });
                }
                None => entries.push(Entry {
                    label: format!("{}{kim}: one S_c, no fit", mat.material),
                    color: color(m),
                    swatch: Swatch::Marker(Marker::nth(m)),
                }),
            }
        }
        panel.line(&line(self.all.prefactor, self.all.exponent), BLACK, true, 1)?;
        entries.push(Entry {
            label: "all materials, least-squares fit (log–log)".into(),
            color: BLACK,
            swatch: Swatch::Line { dashed: true },
        });
        // The paper's numbers belong to Kim's ceramics (SI units) only.
        if self.materials.iter().any(|m| m.kim.is_some()) {
            let grey = RGBColor(120, 120, 120);
            for ((alpha, n), who) in [
                (
                    PAPER_SEVERITY_FIT,
                    "the paper's fit to its simulations of Kim's ceramics",
                ),
                (KIM_SEVERITY_FIT, "Kim et al.'s fit to their experiments"),
            ] {
                panel.line(&line(alpha, n), grey, true, 1)?;
                entries.push(Entry {
                    label: format!("{who}: α = {} m², n = {n}", number(alpha)),
                    color: grey,
                    swatch: Swatch::Line { dashed: true },
                });
            }
        }
        legend(&legend_area, "", &entries)
    }
}

/// A figure that only says why it has no data.
pub(super) struct Note(pub &'static str);

impl Figure for Note {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let (_, h) = area.dim_in_pixel();
        let style = (crate::figures::FONT, 18).into_font().color(&BLACK);
        area.draw_text(self.0, &style, (40, h as i32 / 2))
            .map_err(crate::figures::drawing)?;
        Ok(())
    }
}
