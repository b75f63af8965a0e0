//! The figures against load (Figs. 2, 4, 4c, 5, 6 and appendix C): one curve per setting and
//! fracture energy, a point per nominal pressure, the mean over the run-in surface pairs with its
//! 95 % interval, from the study's one table of means ([`StudyTable::means`]).

use crate::error::{Error, Result};
use crate::output::{
    curve_labels, curves, equal_critical_diameter, has_kim_materials, number, Cell, CurveMaterial, StudyTable, Table,
    KIM_EXPERIMENTAL_K,
};
use crate::study::findings::RESOLVED_PARTICLES;

use super::labels::{Shown, BREAKDOWN_LEGEND, MEANS, MEANS_ON_LOG_AXES};
use super::model::{log_space_interval, Axis, Band, Color, Figure, LegendEntry, Panel, Point, Series, Style, Swatch};

/// One curve against load: a setting (material and every varying input but the surface pair) and
/// one fracture energy, as the library groups them ([`curves`]), with its row of the aggregated
/// table per nominal pressure.
pub(super) struct Curve {
    pub(super) label: String,
    /// Index of its material among the study's, in order of appearance.
    pub(super) material: usize,
    /// Index of its fracture energy among its setting's.
    pub(super) energy: usize,
    pub(super) critical_diameter: f64,
    pub(super) shear_strength: f64,
    pub(super) fracture_energy: f64,
    /// A curve of a model that takes no sliding step (the static estimate): it counts no particle,
    /// so none of its points is hollow.
    pub(super) slides: bool,
    /// Its aggregated rows, by increasing nominal pressure.
    pub(super) rows: Vec<Vec<Cell>>,
}

/// The study's curves against load, read from its tidy table.
pub(super) struct Curves {
    pub(super) columns: Vec<String>,
    pub(super) curves: Vec<Curve>,
    pub(super) materials: usize,
}

impl Curves {
    pub(super) fn of(table: &StudyTable) -> Result<Self> {
        let tidy = table.tidy();
        let found = curves(tidy);
        let labels = curve_labels(tidy);
        // The fit-window results over the run-in pairs, the pairs the findings judge.
        let aggregated = table.means();
        let column = |name: &str| tidy.column(name);
        let value = |row: &[Cell], name: &str| column(name).map_or(f64::NAN, |c| row[c].number());
        let mut materials: Vec<String> = Vec::new();
        // The settings less the fracture energy: the curves of one setting, one per 𝒢.
        let without_energy: Vec<usize> = found
            .settings
            .iter()
            .filter(|c| c.as_str() != "fracture_energy")
            .filter_map(|c| column(c))
            .collect();
        let mut settings: Vec<(String, Vec<String>)> = Vec::new();
        let mut out: Vec<Curve> = Vec::new();
        for (row, &c) in tidy.rows.iter().zip(&found.index) {
            if c < out.len() {
                continue;
            }
            let name = column("material").map_or("material".into(), |m| row[m].text());
            let material = materials.iter().position(|m| *m == name).unwrap_or_else(|| {
                materials.push(name.clone());
                materials.len() - 1
            });
            // The fracture energy's index among the curves of its setting, in order of appearance.
            let setting = (name, without_energy.iter().map(|&i| row[i].text()).collect());
            let energy = settings.iter().filter(|s| **s == setting).count();
            settings.push(setting);
            let model = column("sliding.model").map(|m| row[m].text());
            out.push(Curve {
                label: labels.get(c).cloned().unwrap_or_default(),
                material,
                energy,
                critical_diameter: value(row, "critical_diameter"),
                shear_strength: value(row, "material.shear_strength"),
                fracture_energy: value(row, "fracture_energy"),
                slides: model.is_none_or(|m| crate::model::WearModel::of_cell(&m).is_none_or(|m| m.slides())),
                rows: Vec::new(),
            });
        }
        let (Some(curve), Some(pressure)) = (aggregated.column("curve"), aggregated.column("nominal_pressure")) else {
            return Err(Error::param(
                "tidy table",
                "it has no nominal_pressure column: not a study's results table",
            ));
        };
        for row in &aggregated.rows {
            let c = row[curve].number();
            let Some(target) = (c >= 0.0).then(|| out.get_mut(c as usize)).flatten() else {
                return Err(Error::param(
                    "tidy table",
                    format!("an aggregated row of an unknown curve {c}"),
                ));
            };
            target.rows.push(row.clone());
        }
        for c in &mut out {
            c.rows
                .sort_by(|a, b| a[pressure].number().total_cmp(&b[pressure].number()));
        }
        Ok(Self {
            columns: aggregated.columns.clone(),
            curves: out,
            materials: materials.len(),
        })
    }

    pub(super) fn get(&self, row: &[Cell], column: &str) -> f64 {
        self.columns
            .iter()
            .position(|c| c == column)
            .map_or(f64::NAN, |i| row[i].number())
    }

    /// The nominal area Lx·Ly of a row's box: the `nominal_area` column, else (a table of an
    /// older version, or made by hand) `surface.length` × `surface.length_y`, else 1.
    pub(super) fn area(&self, row: &[Cell]) -> f64 {
        let (lx, ly) = (self.get(row, "surface.length"), self.get(row, "surface.length_y"));
        let from_box = lx * if ly.is_finite() { ly } else { lx };
        [self.get(row, "nominal_area"), from_box]
            .into_iter()
            .find(|a| a.is_finite() && *a > 0.0)
            .unwrap_or(1.0)
    }

    /// One curve's points of a quantity, per load where it is defined: its mean over the surface
    /// pairs with its 95 % interval, divided by the nominal area when `per_area`; hollow where
    /// `fitted` and the fit window holds fewer than [`RESOLVED_PARTICLES`] particles (summed over
    /// the pairs); marked "no wear" where no pair has a positive value; ringed where a pair is in the
    /// breakdown regime (its count of breakdown measures beyond their limits is above 0).
    pub(super) fn points(&self, c: &Curve, quantity: &str, per_area: bool, fitted: bool, log: bool) -> Vec<Point> {
        c.rows
            .iter()
            .filter_map(|r| {
                let scale = if per_area { 1.0 / self.area(r) } else { 1.0 };
                let mean = self.get(r, &format!("{quantity}_mean"));
                let particles = self.get(r, "particles_in_fit_total");
                let (low, high) = (
                    self.get(r, &format!("{quantity}_ci_low")),
                    self.get(r, &format!("{quantity}_ci_high")),
                );
                let (low, high) = if log {
                    log_space_interval(mean, high)
                } else {
                    (low, high)
                };
                mean.is_finite().then(|| Point {
                    x: self.get(r, "nominal_pressure"),
                    y: mean * scale,
                    low: low * scale,
                    high: high * scale,
                    hollow: fitted && c.slides && particles < RESOLVED_PARTICLES,
                    no_wear: self.get(r, &format!("{quantity}_max")) <= 0.0,
                    breakdown: self.get(r, "breakdown_measures_max") > 0.0,
                })
            })
            .collect()
    }
}

/// One panel of a figure against load: the quantity, its axis label, a log axis, and whether it is
/// divided by the nominal area.
pub(super) struct LoadPanel {
    pub(super) quantity: &'static str,
    pub(super) label: String,
    pub(super) log: bool,
    pub(super) per_area: bool,
}

impl LoadPanel {
    pub(super) fn new(quantity: &'static str, label: &str, log: bool) -> Self {
        Self {
            quantity,
            label: label.into(),
            log,
            per_area: false,
        }
    }
    pub(super) fn per_area(quantity: &'static str, label: &str, shown: Shown) -> Self {
        Self {
            quantity,
            label: shown.per_area(quantity, label),
            log: true,
            per_area: true,
        }
    }
}

/// A figure of quantities against load: one panel per quantity, one series per curve.
pub(super) struct LoadFigure<'a> {
    pub(super) curves: Vec<&'a Curve>,
    pub(super) panels: Vec<LoadPanel>,
    /// Whether the panels show fitted sliding rates (points on few particles hollow).
    pub(super) fitted: bool,
    /// Colour by material, markers telling its curves apart (Kim's ceramics), instead of by curve.
    pub(super) by_material: bool,
    /// Kim et al.'s experimental range, shaded on the last panel.
    pub(super) band: Option<(f64, f64, &'static str)>,
}

impl LoadFigure<'_> {
    pub(super) fn style(&self, i: usize) -> (Color, usize) {
        let c = self.curves[i];
        if self.by_material {
            let within = self.curves[..i].iter().filter(|d| d.material == c.material).count();
            (Color::Palette(c.material), within)
        } else {
            (Color::Palette(i), c.material)
        }
    }

    /// The figure, named by what it adds to its entry's stem (`suffix`, empty for an entry's one
    /// figure).
    pub(super) fn build(&self, data: &Curves, shown: Shown, suffix: &str, title: String) -> Figure {
        let mut panels = Vec::new();
        for (p, spec) in self.panels.iter().enumerate() {
            let series = self
                .curves
                .iter()
                .enumerate()
                .map(|(i, c)| {
                    let (color, marker) = self.style(i);
                    Series {
                        label: c.label.clone(),
                        color,
                        marker,
                        style: Style::Means,
                        points: data.points(c, spec.quantity, spec.per_area, self.fitted, spec.log),
                        reference: false,
                    }
                })
                .collect();
            let band = self.band.filter(|_| p + 1 == self.panels.len());
            panels.push(Panel {
                x: shown.load_axis(),
                y: Axis {
                    label: spec.label.clone(),
                    log: spec.log,
                    fallback: (1e-6, 1.0),
                },
                x_band: None,
                y_band: band.map(|(low, high, _)| Band {
                    low,
                    high,
                    color: Color::Band,
                }),
                diagonal: false,
                series,
            });
        }
        let legend = self.legend(data, &panels);
        Figure {
            entry: "",
            name: suffix.into(),
            title,
            panels,
            legend_title: if self.panels.iter().any(|p| p.log) {
                MEANS_ON_LOG_AXES
            } else {
                MEANS
            }
            .into(),
            legend,
            note: None,
            report: Vec::new(),
        }
    }

    /// Each curve with the particle counts of its hollow points, then what hollow points, markers
    /// on the axis and the band are.
    pub(super) fn legend(&self, data: &Curves, panels: &[Panel]) -> Vec<LegendEntry> {
        let mut entries = Vec::new();
        let mut any_hollow = false;
        for (i, c) in self.curves.iter().enumerate() {
            let (color, marker) = self.style(i);
            // A point without any particle has no wear: it is the marker on the axis, not a hollow one.
            let counts: Vec<String> = c
                .rows
                .iter()
                .map(|r| data.get(r, "particles_in_fit_total"))
                .filter(|&n| self.fitted && c.slides && n < RESOLVED_PARTICLES)
                .inspect(|_| any_hollow = true)
                .filter(|&n| n > 0.0)
                .map(|n| number((n * 10.0).round() / 10.0))
                .collect();
            let note = if counts.is_empty() {
                String::new()
            } else {
                format!(" — hollow: {} particles", counts.join(", "))
            };
            entries.push(LegendEntry {
                label: format!("{}{note}", c.label),
                color,
                marker,
                swatch: Swatch::LineMarker,
            });
        }
        if any_hollow {
            entries.push(LegendEntry {
                label: format!(
                    "hollow: < {RESOLVED_PARTICLES} particles in the fit window (summed over surface pairs)"
                ),
                color: Color::Grey,
                marker: 0,
                swatch: Swatch::Hollow,
            });
        }
        if panels
            .iter()
            .flat_map(|p| &p.series)
            .flat_map(|s| &s.points)
            .any(|q| q.breakdown)
        {
            entries.push(LegendEntry {
                label: BREAKDOWN_LEGEND.into(),
                color: Color::Grey,
                marker: 0,
                swatch: Swatch::Ring,
            });
        }
        let no_wear = panels
            .iter()
            .any(|p| p.y.log && p.series.iter().flat_map(|s| &s.points).any(|q| q.no_wear));
        if no_wear {
            entries.push(LegendEntry {
                label: "on the axis (stacked per load): zero (no wear) in every surface pair".into(),
                color: Color::Grey,
                marker: 0,
                swatch: Swatch::AtAxis,
            });
        }
        if let Some((_, _, label)) = self.band {
            entries.push(LegendEntry {
                label: label.into(),
                color: Color::Band,
                marker: 0,
                swatch: Swatch::Band,
            });
        }
        entries
    }
}

/// A figure against load of every curve, no band, coloured by curve.
pub(super) fn every_curve(data: &Curves, panels: Vec<LoadPanel>, fitted: bool) -> LoadFigure<'_> {
    LoadFigure {
        curves: data.curves.iter().collect(),
        panels,
        fitted,
        by_material: false,
        band: None,
    }
}

/// Fig. 2: the static model over every offset, W_static/ω and k_static against load.
pub(super) fn static_model(data: &Curves, shown: Shown) -> Figure {
    let panels = vec![
        LoadPanel::per_area("static_wear_rate_mean", "W_static/ω", shown),
        LoadPanel::new(
            "static_wear_coefficient_mean",
            "static wear coefficient k_static",
            false,
        ),
    ];
    every_curve(data, panels, false).build(
        data,
        shown,
        "",
        "static model, mean over every offset (the paper's Fig. 2 rows: 𝒢 varied, τ̃ varied)".into(),
    )
}

/// Fig. 4: the sliding model's W and k against load (and in SI the specific wear rate K).
pub(super) fn sliding_wear(data: &Curves, shown: Shown) -> Figure {
    let mut panels = vec![
        LoadPanel::per_area("wear_rate", "sliding wear rate W = dV/ds", shown),
        LoadPanel::new("wear_coefficient", "wear coefficient k = W p_m / F_N", true),
    ];
    // In SI, the specific wear rate K = W/F_N in the unit tribologists report it in (in reduced
    // units it is k/p_m, the panel above over the one flow pressure of a setting).
    if shown.si() {
        panels.push(LoadPanel::new(
            "specific_wear_rate",
            &format!("specific wear rate K = W / F_N ({})", shown.unit("specific_wear_rate")),
            true,
        ));
    }
    every_curve(data, panels, true).build(data, shown, "", fig4_title(data))
}

/// Fig. 5: the particle rate dN*₊/ds against load.
pub(super) fn particle_rate(data: &Curves, shown: Shown) -> Figure {
    let panels = vec![LoadPanel::per_area("particle_rate", "particle rate dN*₊/ds", shown)];
    every_curve(data, panels, true).build(
        data,
        shown,
        "",
        "wear particles emitted per sliding distance, means over the run-in surface pairs (over all where none is)"
            .into(),
    )
}

/// Fig. 6: k per material; Kim et al.'s rolling wear coefficients 6e-7 … 1.5e-3 (paper §4.2,
/// Fig. 6c) shaded only for a study of Kim's ceramics (the properties of the paper's Table 1).
pub(super) fn kim_comparison(data: &Curves, tidy: &Table, shown: Shown) -> Figure {
    let kim = has_kim_materials(tidy);
    let title = if kim {
        "simulated sliding k per material against the experimental range"
    } else {
        "sliding k per material (no material of Kim et al.'s Table 1 here: no experimental band)"
    };
    LoadFigure {
        curves: data.curves.iter().collect(),
        panels: vec![LoadPanel::new("wear_coefficient", "wear coefficient k", true)],
        fitted: true,
        by_material: data.materials > 1,
        band: kim.then_some((
            KIM_EXPERIMENTAL_K.0,
            KIM_EXPERIMENTAL_K.1,
            "Kim et al. 1986, rolling experiments: k = 6×10⁻⁷ … 1.5×10⁻³",
        )),
    }
    .build(data, shown, "", title.into())
}

/// Appendix C: the junctions N, one curve per setting (N does not depend on 𝒢), and the critical
/// junctions N*, one per curve.
pub(super) fn junction_counts(data: &Curves, shown: Shown) -> Vec<Figure> {
    let junctions = LoadPanel::new("junctions_mean", "junctions N (mean after running-in)", true);
    let critical = LoadPanel::new(
        "critical_junctions_mean",
        "junctions ≥ d*, N* (mean after running-in)",
        true,
    );
    vec![
        LoadFigure {
            curves: data.curves.iter().filter(|c| c.energy == 0).collect(),
            ..every_curve(data, vec![junctions], false)
        }
        .build(data, shown, "_junctions", "number of junctions".into()),
        every_curve(data, vec![critical], false).build(
            data,
            shown,
            "_critical_junctions",
            "number of critical junctions".into(),
        ),
    ]
}

/// Fig. 4's title: what it draws, and, where the study holds them, that the estimate's curves are
/// labelled as such.
pub(super) fn fig4_title(data: &Curves) -> String {
    let mut title =
        "sliding model (the paper's Fig. 4 rows: W, k), means over the run-in surface pairs (over all where none is)"
            .to_string();
    if data.curves.iter().any(|c| !c.slides) {
        title += "; curves labelled \"static estimate\" are the static estimate";
    }
    title
}

/// Figs. 4c/5c: W, k and dN*₊/ds for groups of settings of (nearly) equal d* (within 15 %) that
/// differ in τ̃ or 𝒢; one figure per group (`_1`, `_2`, …), or a note when the study has none.
pub(super) fn constant_critical_diameter(data: &Curves, shown: Shown) -> Vec<Figure> {
    let materials: Vec<CurveMaterial> = data
        .curves
        .iter()
        .map(|c| CurveMaterial {
            critical_diameter: c.critical_diameter,
            shear_strength: c.shear_strength,
            fracture_energy: c.fracture_energy,
        })
        .collect();
    let groups = equal_critical_diameter(&materials, 0.15);
    if groups.is_empty() {
        return vec![Figure::note(
            "Fig. 4c compares settings of equal d* (within 15 %) with different τ̃ or 𝒢; this study has none",
        )];
    }
    groups
        .iter()
        .enumerate()
        .map(|(g, group)| {
            LoadFigure {
                curves: group.iter().map(|&i| &data.curves[i]).collect(),
                panels: vec![
                    LoadPanel::per_area("wear_rate", "W", shown),
                    LoadPanel::new("wear_coefficient", "k = W p_m / F_N", true),
                    LoadPanel::per_area("particle_rate", "dN*₊/ds", shown),
                ],
                fitted: true,
                by_material: false,
                band: None,
            }
            .build(
                data,
                shown,
                &format!("_{}", g + 1),
                format!(
                    "settings of nearly equal d* ≈ {}",
                    shown.length(data.curves[group[0]].critical_diameter)
                ),
            )
        })
        .collect()
}
