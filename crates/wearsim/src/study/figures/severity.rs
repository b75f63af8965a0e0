//! The figures of the paper's appendices B and F that relate one wear measure to another: Eq. 5
//! against the sliding W (Fig. B.9b), and the contact-severity fits W = α S_cⁿ.

use crate::output::{number, severity_fits, MaterialSeverity, Table, KIM_SEVERITY_FIT, PAPER_SEVERITY_FIT};
use crate::stats::PowerLawFit;

use super::labels::{Shown, MEANS};
use super::load::Curves;
use super::model::{fit_line, one_panel, Axis, Band, Color, Figure, LegendEntry, Panel, Point, Series, Style, Swatch};

/// Eq. 5 / W against load, as the finding judges it: per curve and setting, the mean over its
/// run-in pairs with its Student-t interval, over the range of "slightly underestimates".
pub(super) fn equation_5_over_w_panel(data: &Curves, tidy: &Table, shown: Shown) -> Panel {
    let ratios = crate::study::findings::equation_5_over_w(tidy);
    let (low, high) = crate::study::findings::EQUATION_5_OVER_W;
    let series: Vec<Series> = data
        .curves
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let mut points: Vec<Point> = ratios
                .iter()
                .filter(|(curve, _, _)| *curve == i)
                .filter_map(|(_, pressure, interval)| {
                    interval.map(|r| Point {
                        low: r.low,
                        high: r.high,
                        ..Point::at(*pressure, r.estimate)
                    })
                })
                .collect();
            points.sort_by(|a, b| a.x.total_cmp(&b.x));
            Series {
                label: c.label.clone(),
                color: Color::Palette(i),
                marker: c.material,
                style: Style::Means,
                points,
                reference: false,
            }
        })
        .collect();
    Panel {
        x: shown.load_axis(),
        y: Axis {
            label: "Eq. 5 / W, mean over the run-in surface pairs (over all where none is)".into(),
            log: false,
            fallback: (0.0, 1.5),
        },
        x_band: None,
        y_band: Some(Band {
            low,
            high,
            color: Color::Band,
        }),
        diagonal: false,
        series,
    }
}

/// Fig. B.9b: Eq. 5 (ω d*³ dN*₊/ds) against the summed wear rate, one point per setting and load
/// (means over surface pairs, aligned by row), with the line Eq. 5 = W; beside it Eq. 5 / W against
/// load with its interval, as the finding of appendix B judges it.
pub(super) fn equation_5(data: &Curves, tidy: &Table, shown: Shown) -> Figure {
    let unit = shown.unit("wear_rate");
    let (low, high) = crate::study::findings::EQUATION_5_OVER_W;
    let mut legend = vec![LegendEntry {
        label: "Eq. 5 = W".into(),
        color: Color::Grey,
        marker: 0,
        swatch: Swatch::Line { dashed: true },
    }];
    let mut series = Vec::new();
    for (i, c) in data.curves.iter().enumerate() {
        let points = c
            .rows
            .iter()
            .map(|r| Point::at(data.get(r, "wear_rate_mean"), data.get(r, "wear_rate_estimate_mean")))
            .filter(|p| p.x > 0.0 && p.y > 0.0)
            .collect();
        series.push(Series {
            label: c.label.clone(),
            color: Color::Palette(i),
            marker: c.material,
            style: Style::Markers,
            points,
            reference: false,
        });
        legend.push(LegendEntry {
            label: c.label.clone(),
            color: Color::Palette(i),
            marker: c.material,
            swatch: Swatch::Marker,
        });
    }
    Figure {
        entry: "",
        name: String::new(),
        title: "Eq. 5 against the summed wear rate (mean over surface pairs), and their ratio against load".into(),
        panels: vec![
            Panel {
                x: Axis {
                    label: format!("wear rate W, summed particle volumes ({unit})"),
                    log: true,
                    fallback: (1e-6, 1e-3),
                },
                y: Axis {
                    label: format!("Eq. 5: ω d*³ dN*₊/ds ({unit})"),
                    log: true,
                    fallback: (1e-6, 1e-3),
                },
                x_band: None,
                y_band: None,
                diagonal: true,
                series,
            },
            equation_5_over_w_panel(data, tidy, shown),
        ],
        legend_title: format!(
            "right: {MEANS}; shaded: Eq. 5 / W in [{low}, {high}], appendix B's \"slightly underestimates\""
        ),
        legend,
        note: None,
        report: Vec::new(),
    }
}

pub(super) fn r2_text(fit: &PowerLawFit) -> String {
    fit.r2.map_or("undefined".into(), |r| format!("{r:.3}"))
}

/// A fitted power law drawn over a span of S_c.
pub(super) type Line<'a> = &'a dyn Fn(f64, f64) -> Vec<Point>;

/// One material of appendix F: its points (S_c, W), its fit W = α S_cⁿ where it has one, and its
/// legend entry.
pub(super) fn material_severity(m: usize, mat: &MaterialSeverity, line: Line) -> (Vec<Series>, LegendEntry) {
    let kim = mat.kim.map_or(String::new(), |k| format!(" (Kim et al.'s {})", k.name));
    let mut series = vec![Series {
        label: format!("{}{kim}", mat.material),
        color: Color::Palette(m),
        marker: m,
        style: Style::Markers,
        points: mat.points.iter().map(|&(x, y)| Point::at(x, y)).collect(),
        reference: false,
    }];
    let label = match mat.fit {
        Some(fit) => {
            series.push(Series {
                label: format!("{}: fit", mat.material),
                color: Color::Palette(m),
                marker: m,
                style: Style::Line {
                    dashed: false,
                    width: 1,
                },
                points: line(fit.prefactor, fit.exponent),
                reference: true,
            });
            format!(
                "{}{kim}: α = {}, n = {:.2}, R² = {}",
                mat.material,
                number(fit.prefactor),
                fit.exponent,
                r2_text(&fit)
            )
        }
        None => format!("{}{kim}: one S_c, no fit", mat.material),
    };
    let swatch = if mat.fit.is_some() {
        Swatch::LineMarker
    } else {
        Swatch::Marker
    };
    let entry = LegendEntry {
        label,
        color: Color::Palette(m),
        marker: m,
        swatch,
    };
    (series, entry)
}

/// The reference lines of appendix F: the fit over all materials, and beside Kim's ceramics (SI
/// units; the paper's numbers belong to them only) the paper's fit to its simulations and Kim et
/// al.'s to their experiments.
pub(super) fn severity_references(all: PowerLawFit, kim: bool) -> Vec<((f64, f64), String, Color)> {
    let mut references = vec![(
        (all.prefactor, all.exponent),
        "all materials, least-squares fit (log–log)".to_string(),
        Color::Black,
    )];
    if kim {
        for ((alpha, n), who) in [
            (
                PAPER_SEVERITY_FIT,
                "the paper's fit to its simulations of Kim's ceramics",
            ),
            (KIM_SEVERITY_FIT, "Kim et al.'s fit to their experiments"),
        ] {
            references.push((
                (alpha, n),
                format!("{who}: α = {} m², n = {n}", number(alpha)),
                Color::Grey,
            ));
        }
    }
    references
}

/// Appendix F: W against the contact severity S_c = p_N √h_rms / K_Ic per material with its fit
/// W = α S_cⁿ, the fit over all materials, and beside Kim's ceramics the paper's and Kim et al.'s
/// fits; a note with fewer than two jobs with W > 0 on generated surfaces.
pub(super) fn contact_severity(tidy: &Table, shown: Shown) -> Figure {
    let (materials, all) = severity_fits(tidy);
    let Some(all) = all else {
        return Figure::note(
            "appendix F fits W = α S_cⁿ to the jobs with W > 0 on generated surfaces (S_c needs their h_rms): this \
             study has fewer than two such jobs of distinct S_c, so there is nothing to fit",
        );
    };
    let s_c = materials.iter().flat_map(|m| m.points.iter().map(|p| p.0));
    let (lo, hi) = s_c.fold((f64::INFINITY, 0.0_f64), |(a, b), x| (a.min(x), b.max(x)));
    // Fitted lines over the points' span of S_c.
    let line = |alpha: f64, n: f64| vec![Point::at(lo, alpha * lo.powf(n)), Point::at(hi, alpha * hi.powf(n))];
    let area = shown.unit("wear_rate");
    let (mut series, mut legend) = (Vec::new(), Vec::new());
    for (m, mat) in materials.iter().enumerate() {
        let (mine, entry) = material_severity(m, mat, &line);
        series.extend(mine);
        legend.push(entry);
    }
    for ((alpha, n), label, color) in severity_references(all, materials.iter().any(|m| m.kim.is_some())) {
        series.push(fit_line(label.clone(), color, line(alpha, n)));
        legend.push(LegendEntry {
            label,
            color,
            marker: 0,
            swatch: Swatch::Line { dashed: true },
        });
    }
    let x = Axis {
        label: "contact severity S_c = p_N √h_rms / K_Ic".into(),
        log: true,
        fallback: (1e-3, 1.0),
    };
    let y = Axis {
        label: format!("wear rate W ({area})"),
        log: true,
        fallback: (1e-6, 1.0),
    };
    let title = format!(
        "W = α S_cⁿ, all materials: α = {} {area}, n = {:.3}, R² = {}",
        number(all.prefactor),
        all.exponent,
        r2_text(&all)
    );
    // The fits in words: over all materials (the title), then each material's (its legend entry;
    // the reference lines' entries are the paper's and Kim et al.'s numbers).
    let report = std::iter::once(&title)
        .chain(
            legend
                .iter()
                .filter(|e| !matches!(e.swatch, Swatch::Line { .. }))
                .map(|e| &e.label),
        )
        .map(|line| format!("contact severity fit, {line}"))
        .collect();
    Figure {
        entry: "",
        name: String::new(),
        title,
        panels: one_panel(x, y, series),
        legend_title: String::new(),
        legend,
        note: None,
        report,
    }
}
