//! The figures of a study as data (Brink, Frérot & Molinari 2021, Figs. 2–6 and appendices B, C, F,
//! and the memory of the initial contact of §3): one registry, [`FIGURES`], and per figure the
//! numbers it plots, computed once here from the study's tables and job files. Front ends only draw
//! them — the CLI's `study plot` (PNG and SVG, and each figure's numbers as CSV beside it,
//! [`Figure::to_csv`]), Python's `wearsim.plot` (matplotlib) — so both draw the same figures under
//! the same names from the same numbers.
//!
//! A figure is panels of series. A series is points (x, y) with, per point, the 95 % interval of
//! the mean over surface pairs where it has one, whether it rests on too few particles to be judged
//! (drawn hollow) and whether no surface pair wore at all (no place on a log axis: marked on the
//! axis). Colours are indices into the front end's palette, markers indices into its shapes.

use std::borrow::Cow;

use serde::Serialize;

use crate::config::Units;
use crate::error::{Error, Result};
use crate::output::{
    curve_labels, curves, distinct, equal_critical_diameter, has_kim_materials, job_series_rows, lineages_left, number,
    pretty, series_job, severity_fits, steps_of_rows, unit_of, Cell, CurveMaterial, JobResult, MaterialSeverity,
    SeriesRow, StepRow, Table, KIM_EXPERIMENTAL_K, KIM_SEVERITY_FIT, PAPER_SEVERITY_FIT,
};
use crate::sliding::{WearResult, RUN_IN_DECAY_LENGTHS, RUN_IN_LINEAGES_LEFT};
use crate::stats::{mean_interval, PowerLawFit};

use crate::study::findings::RESOLVED_PARTICLES;

mod regime;

/// One entry of the registry: the name `--figures` (and Python's `names`) takes, what it shows,
/// how it is laid out, and the function that builds its figures from a study: an entry cannot be
/// registered without what draws it.
#[derive(Clone, Copy, Serialize)]
pub struct FigureSpec {
    pub name: &'static str,
    pub about: &'static str,
    pub layout: Layout,
    /// Its figures of a study (none where the study cannot show it: Fig. 4c without curves of equal
    /// d*, the wear-regime map without a particle-rule axis).
    #[serde(skip)]
    build: fn(&Study) -> Vec<Figure>,
}

impl std::fmt::Debug for FigureSpec {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FigureSpec")
            .field("name", &self.name)
            .field("about", &self.about)
            .field("layout", &self.layout)
            .finish()
    }
}

/// How a front end lays a figure out.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Layout {
    /// Panels against load (or another quantity), the legend beside them.
    Panels,
    /// One panel of series against the sliding distance, whose legend entries are long: wider.
    Series,
}

/// The layout of the figures of registry entry `entry` (a figure's `entry`): panels where no entry
/// has the name.
pub fn layout_of(entry: &str) -> Layout {
    FIGURES
        .iter()
        .find(|f| f.name == entry)
        .map_or(Layout::Panels, |f| f.layout)
}

/// Every figure of a study, in the order drawn. A new figure is one entry here, with the function
/// that builds it.
pub const FIGURES: [FigureSpec; 12] = [
    FigureSpec {
        name: "fig2",
        about: "static model over every offset: W_static/ω per unit area and k_static against p_N (paper Fig. 2)",
        layout: Layout::Panels,
        build: build_fig2,
    },
    FigureSpec {
        name: "fig3",
        about: "V(s) of one job with the fitted lines and the running-in region (Fig. 3)",
        layout: Layout::Series,
        build: build_fig3,
    },
    FigureSpec {
        name: "fig4",
        about: "sliding W per unit area and k against p_N, 95 % intervals over surface pairs (Fig. 4)",
        layout: Layout::Panels,
        build: build_fig4,
    },
    FigureSpec {
        name: "fig4c",
        about: "W, k and dN*₊/ds for settings of (nearly) equal d* (Figs. 4c, 5c)",
        layout: Layout::Panels,
        build: build_fig4c,
    },
    FigureSpec {
        name: "fig5",
        about: "dN*₊/ds per unit area against p_N (Fig. 5)",
        layout: Layout::Panels,
        build: build_fig5,
    },
    FigureSpec {
        name: "fig6",
        about: "k against p_N per material, beside Kim et al.'s experimental range for Kim's ceramics (Fig. 6)",
        layout: Layout::Panels,
        build: build_fig6,
    },
    FigureSpec {
        name: "appB",
        about: "N*₊, N*, N*₋ against s of one job (appendix B, Fig. B.9a)",
        layout: Layout::Series,
        build: build_app_b,
    },
    FigureSpec {
        name: "appB-eq5",
        about: "Eq. 5, ω d*³ dN*₊/ds, against the summed W (Fig. B.9b), and Eq. 5 / W against load",
        layout: Layout::Panels,
        build: build_app_b_eq5,
    },
    FigureSpec {
        name: "appC",
        about: "junctions N and critical junctions N* against p_N (appendix C)",
        layout: Layout::Panels,
        build: build_app_c,
    },
    FigureSpec {
        name: "appF",
        about: "the contact-severity fits W = α S_cⁿ per material and over all (appendix F)",
        layout: Layout::Panels,
        build: build_app_f,
    },
    FigureSpec {
        name: "wear-regime",
        about: "the wear-regime map: W/F_N, the particle size and W of each particle rule over the paper's against \
                p_N, with the load where a rule of interacting junctions departs (a study with a particle_rule axis)",
        layout: Layout::Panels,
        build: build_wear_regime,
    },
    FigureSpec {
        name: "memory",
        about: "the memory of the initial contact N₀(s) of every surface pair of one setting, with fits (§3)",
        layout: Layout::Series,
        build: build_memory,
    },
];

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
    /// A fitted rate resting on fewer than [`RESOLVED_PARTICLES`] particles (summed over the
    /// pairs): drawn hollow.
    pub hollow: bool,
    /// No surface pair wore (the maximum over pairs is 0): on a log axis, marked on the axis.
    pub no_wear: bool,
    /// The load lies in the paper's breakdown regime (appendix C: a breakdown measure beyond its
    /// limit, `crate::sliding::LoadBreakdown`) in at least one surface pair: drawn ringed.
    pub breakdown: bool,
}

impl Point {
    fn at(x: f64, y: f64) -> Self {
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
    /// The registry entry it belongs to ([`FIGURES`]).
    pub entry: &'static str,
    /// The file name, without extension (`fig4_sliding_wear`).
    pub name: String,
    pub title: String,
    pub panels: Vec<Panel>,
    pub legend_title: String,
    pub legend: Vec<LegendEntry>,
    pub note: Option<String>,
}

impl Figure {
    fn note(entry: &'static str, name: &str, note: impl Into<String>) -> Self {
        Self {
            entry,
            name: name.into(),
            title: String::new(),
            panels: Vec::new(),
            legend_title: String::new(),
            legend: Vec::new(),
            note: Some(note.into()),
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
fn quote(text: &str) -> String {
    if text.contains([',', '"', '\n']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

/// The legend entry of the ringed points of the figures against load.
pub const BREAKDOWN_LEGEND: &str = "ringed: in the breakdown regime of the paper's appendix C (junctions merging, the \
largest junction a quarter of the box, or N* behind linear growth) in at least one surface pair";

/// The legend title of the figures against load: what points and bars are.
pub const MEANS: &str = "mean over surface pairs; bars: 95 % confidence interval of the mean (Student t)";

/// The same on a figure with log axes, whose bars are the interval drawn in log space.
pub const MEANS_ON_LOG_AXES: &str = "mean over surface pairs; bars: 95 % confidence interval of the mean \
(Student t); on a log axis drawn in log space: mean ×/÷ e^(t·se/mean)";

/// The 95 % interval of a mean `mean` whose Student-t interval reaches `high`, on a log axis: the
/// same interval in log space (the delta method, ln m ± t·se/m), mean ×/÷ e^(t·se/mean). Always
/// positive and symmetric about the mean on the axis, where the linear one reaches below zero
/// (and is cut off) whenever the pairs spread more than the mean; the point is the same mean as the
/// findings'. NaN where the mean is not positive or has no interval.
fn log_space_interval(mean: f64, high: f64) -> (f64, f64) {
    if !(mean > 0.0 && high.is_finite()) {
        return (f64::NAN, f64::NAN);
    }
    let factor = ((high - mean) / mean).exp();
    (mean / factor, mean * factor)
}

/// What the figures of one job's sliding series say instead when that job is a static estimate.
const NO_SERIES: &str = "this job is a static estimate: it takes no sliding step, so it has no wear-volume curve, \
particle counts or memory of the initial contact (those are the sliding model's; `--job` picks a sliding job)";

/// What the series figures say when only the tidy table was given.
const NO_JOB_FILES: &str = "this figure draws one job's sliding series, which are in the study's job files: \
draw it from the study folder";

/// The units of a study's axes and legends.
#[derive(Debug, Clone, Copy)]
struct Shown {
    system: Units,
}

impl Shown {
    fn si(self) -> bool {
        self.system == Units::Si
    }
    fn unit(self, quantity: &str) -> &'static str {
        unit_of(self.system, quantity)
    }
    /// A length for legends (µm in SI).
    fn length(self, v: f64) -> String {
        if self.si() {
            format!("{} µm", number(v * 1e6))
        } else {
            format!("{} L", number(v))
        }
    }
    fn stress(self, v: f64) -> String {
        if self.si() {
            format!("{} GPa", number(v / 1e9))
        } else {
            format!("{} E", number(v))
        }
    }
    /// The label of a rate `quantity` divided by the nominal area Lx·Ly: in reduced units the rate
    /// of a box L × L, the paper's; in SI a volume per sliding distance per area is a wear depth per
    /// sliding distance (m/m), a particle rate per area particles per metre slid per m².
    fn per_area(self, quantity: &str, label: &str) -> String {
        let unit = match (self.si(), quantity) {
            (false, _) => "per unit nominal area, = a box L × L (the paper's)",
            (true, "particle_rate") => "per unit nominal area, particles per m slid per m², 1/m³",
            (true, _) => "per unit nominal area: wear depth per sliding distance, m/m",
        };
        format!("{label} / (Lx·Ly) ({unit})")
    }
    /// The paper's load axis.
    fn load_axis(self) -> Axis {
        Axis {
            label: format!("nominal pressure p_N = F_N/(Lx·Ly) ({})", self.unit("nominal_pressure")),
            log: true,
            fallback: (1e-4, 1e-2),
        }
    }
    fn distance_axis(self) -> Axis {
        Axis {
            label: format!("sliding distance s ({})", self.unit("length")),
            log: false,
            fallback: (0.0, 1.0),
        }
    }
}

/// One curve against load: a setting (material and every varying input but the surface pair) and
/// one fracture energy, as the library groups them ([`curves`]), with its row of the aggregated
/// table per nominal pressure.
struct Curve {
    label: String,
    /// Index of its material among the study's, in order of appearance.
    material: usize,
    /// Index of its fracture energy among its setting's.
    energy: usize,
    critical_diameter: f64,
    shear_strength: f64,
    fracture_energy: f64,
    /// A curve of a model that takes no sliding step (the static estimate): it counts no particle,
    /// so none of its points is hollow.
    slides: bool,
    /// Its aggregated rows, by increasing nominal pressure.
    rows: Vec<Vec<Cell>>,
}

/// The study's curves against load, read from its tidy table.
struct Curves {
    columns: Vec<String>,
    curves: Vec<Curve>,
    materials: usize,
}

impl Curves {
    fn of(tidy: &Table) -> Result<Self> {
        let found = curves(tidy);
        let labels = curve_labels(tidy);
        // The fit-window results over the run-in pairs, the pairs the findings judge.
        let aggregated = crate::output::study_means(tidy);
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
                slides: model.is_none_or(|m| crate::estimate::WearModel::of_cell(&m).is_none_or(|m| m.slides())),
                rows: Vec::new(),
            });
        }
        let (Some(curve), Some(pressure)) = (aggregated.column("curve"), aggregated.column("nominal_pressure")) else {
            return Err(Error::param(
                "tidy table",
                "it has no nominal_pressure column: not a study's results table",
            ));
        };
        for row in aggregated.rows {
            let c = row[curve].number();
            let Some(target) = (c >= 0.0).then(|| out.get_mut(c as usize)).flatten() else {
                return Err(Error::param(
                    "tidy table",
                    format!("an aggregated row of an unknown curve {c}"),
                ));
            };
            target.rows.push(row);
        }
        for c in &mut out {
            c.rows
                .sort_by(|a, b| a[pressure].number().total_cmp(&b[pressure].number()));
        }
        Ok(Self {
            columns: aggregated.columns,
            curves: out,
            materials: materials.len(),
        })
    }

    fn get(&self, row: &[Cell], column: &str) -> f64 {
        self.columns
            .iter()
            .position(|c| c == column)
            .map_or(f64::NAN, |i| row[i].number())
    }

    /// The nominal area Lx·Ly of a row's box: the `nominal_area` column, else (a table of an
    /// older version, or made by hand) `surface.length` × `surface.length_y`, else 1.
    fn area(&self, row: &[Cell]) -> f64 {
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
    fn points(&self, c: &Curve, quantity: &str, per_area: bool, fitted: bool, log: bool) -> Vec<Point> {
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
struct LoadPanel {
    quantity: &'static str,
    label: String,
    log: bool,
    per_area: bool,
}

impl LoadPanel {
    fn new(quantity: &'static str, label: &str, log: bool) -> Self {
        Self {
            quantity,
            label: label.into(),
            log,
            per_area: false,
        }
    }
    fn per_area(quantity: &'static str, label: &str, shown: Shown) -> Self {
        Self {
            quantity,
            label: shown.per_area(quantity, label),
            log: true,
            per_area: true,
        }
    }
}

/// A figure of quantities against load: one panel per quantity, one series per curve.
struct LoadFigure<'a> {
    curves: Vec<&'a Curve>,
    panels: Vec<LoadPanel>,
    /// Whether the panels show fitted sliding rates (points on few particles hollow).
    fitted: bool,
    /// Colour by material, markers telling its curves apart (Kim's ceramics), instead of by curve.
    by_material: bool,
    /// Kim et al.'s experimental range, shaded on the last panel.
    band: Option<(f64, f64, &'static str)>,
}

impl LoadFigure<'_> {
    fn style(&self, i: usize) -> (Color, usize) {
        let c = self.curves[i];
        if self.by_material {
            let within = self.curves[..i].iter().filter(|d| d.material == c.material).count();
            (Color::Palette(c.material), within)
        } else {
            (Color::Palette(i), c.material)
        }
    }

    fn build(&self, data: &Curves, shown: Shown, entry: &'static str, name: &str, title: String) -> Figure {
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
            entry,
            name: name.into(),
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
        }
    }

    /// Each curve with the particle counts of its hollow points, then what hollow points, markers
    /// on the axis and the band are.
    fn legend(&self, data: &Curves, panels: &[Panel]) -> Vec<LegendEntry> {
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

/// What every figure is built from.
struct Study<'a> {
    tidy: &'a Table,
    data: Curves,
    shown: Shown,
    /// The job whose series fig3 and appB draw, and every surface pair of its setting (memory);
    /// None without job files.
    series: Option<(&'a JobResult, Vec<&'a JobResult>)>,
}

/// Every figure asked for by registry name (all without a list), in the registry's order, from a
/// study's tidy table (`results.csv`, [`crate::output::TidyRow`]) and its job files. The series
/// figures (fig3, appB, memory) draw job `job` (default: the one that formed the most particles
/// after running-in, the lowest index among equals) and need `jobs`; without them they are notes
/// that say so.
pub fn study_figures(
    tidy: &Table,
    jobs: &[JobResult],
    job: Option<usize>,
    names: Option<&[String]>,
) -> Result<Vec<Figure>> {
    if let Some(unknown) = names
        .into_iter()
        .flatten()
        .find(|n| !FIGURES.iter().any(|f| f.name == n.as_str()))
    {
        let known: Vec<&str> = FIGURES.iter().map(|f| f.name).collect();
        return Err(Error::param(
            "figures",
            format!("no figure is named {unknown:?}: the figures are {}", known.join(", ")),
        ));
    }
    let system = tidy.units();
    let series = if jobs.is_empty() {
        None
    } else {
        let index = match job {
            Some(i) => i,
            None => series_job(
                jobs.iter()
                    .flat_map(|r| r.results.iter().map(move |w| (r.index, w.particles_in_fit))),
            )
            .unwrap_or(jobs[0].index),
        };
        let shown = jobs.iter().find(|r| r.index == index).ok_or_else(|| {
            Error::param(
                "job",
                format!(
                    "the study has no job {index}: its jobs are 0 … {}",
                    jobs.iter().map(|r| r.index).max().unwrap_or(0)
                ),
            )
        })?;
        Some((shown, pairs_of(jobs, shown)))
    };
    let study = Study {
        tidy,
        data: Curves::of(tidy)?,
        shown: Shown { system },
        series,
    };
    let mut out = Vec::new();
    for spec in FIGURES
        .iter()
        .filter(|f| names.is_none_or(|w| w.iter().any(|n| n == f.name)))
    {
        let built = (spec.build)(&study);
        // A figure asked for by name that the study cannot show says so, rather than nothing.
        if built.is_empty() && names.is_some() {
            out.push(Figure::note(
                spec.name,
                spec.name,
                format!("this study has nothing for {}: {}", spec.name, spec.about),
            ));
        }
        out.extend(built);
    }
    Ok(out)
}

/// The jobs of the same setting and load as `job` (every input but the surface pair): its surface
/// pairs, in job order.
fn pairs_of<'a>(jobs: &'a [JobResult], job: &JobResult) -> Vec<&'a JobResult> {
    let key = |r: &JobResult| {
        let mut inputs = r.inputs.clone();
        inputs.seed = None;
        (r.material.clone(), inputs, r.load.to_bits())
    };
    let mine = key(job);
    jobs.iter().filter(|r| key(r) == mine).collect()
}

// The builders of the registry's entries, one per entry.
fn build_fig2(s: &Study) -> Vec<Figure> {
    vec![against_load(&s.data, s.shown, "fig2")]
}
fn build_fig4(s: &Study) -> Vec<Figure> {
    vec![against_load(&s.data, s.shown, "fig4")]
}
fn build_fig5(s: &Study) -> Vec<Figure> {
    vec![against_load(&s.data, s.shown, "fig5")]
}
fn build_fig4c(s: &Study) -> Vec<Figure> {
    constant_critical_diameter(&s.data, s.shown)
}
fn build_fig6(s: &Study) -> Vec<Figure> {
    vec![kim_comparison(s)]
}
fn build_app_c(s: &Study) -> Vec<Figure> {
    junction_counts(&s.data, s.shown)
}
fn build_app_b_eq5(s: &Study) -> Vec<Figure> {
    vec![equation_5(&s.data, s.tidy, s.shown)]
}
fn build_app_f(s: &Study) -> Vec<Figure> {
    contact_severity(s.tidy, s.shown).into_iter().collect()
}
fn build_wear_regime(s: &Study) -> Vec<Figure> {
    regime::wear_regime(s.tidy, s.shown).into_iter().collect()
}
fn build_fig3(s: &Study) -> Vec<Figure> {
    vec![series_figure(s, "fig3", "fig3_wear_volume", |r, _, shown| {
        wear_volume(r, shown)
    })]
}
fn build_app_b(s: &Study) -> Vec<Figure> {
    vec![series_figure(s, "appB", "appB_particle_counts", |r, _, shown| {
        particle_counts(r, shown)
    })]
}
fn build_memory(s: &Study) -> Vec<Figure> {
    vec![series_figure(
        s,
        "memory",
        "memory_of_initial_contact",
        |_, pairs, shown| memory(pairs, shown),
    )]
}

/// A figure against load of every curve, no band, coloured by curve.
fn every_curve(data: &Curves, panels: Vec<LoadPanel>, fitted: bool) -> LoadFigure<'_> {
    LoadFigure {
        curves: data.curves.iter().collect(),
        panels,
        fitted,
        by_material: false,
        band: None,
    }
}

/// Figs. 2 (the static model over every offset), 4 (the sliding model's W and k) and 5 (the
/// particle rate), against load.
fn against_load(data: &Curves, shown: Shown, entry: &'static str) -> Figure {
    let (panels, fitted, name, title) = match entry {
        "fig2" => (
            vec![
                LoadPanel::per_area("static_wear_rate_mean", "W_static/ω", shown),
                LoadPanel::new(
                    "static_wear_coefficient_mean",
                    "static wear coefficient k_static",
                    false,
                ),
            ],
            false,
            "fig2_static_model",
            "static model, mean over every offset (the paper's Fig. 2 rows: 𝒢 varied, τ̃ varied)".to_string(),
        ),
        "fig4" => (
            {
                let mut panels = vec![
                    LoadPanel::per_area("wear_rate", "sliding wear rate W = dV/ds", shown),
                    LoadPanel::new("wear_coefficient", "wear coefficient k = W p_m / F_N", true),
                ];
                // In SI, the specific wear rate K = W/F_N in the unit tribologists report it in (in
                // reduced units it is k/p_m, the panel above over the one flow pressure of a setting).
                if shown.si() {
                    panels.push(LoadPanel::new(
                        "specific_wear_rate",
                        &format!("specific wear rate K = W / F_N ({})", shown.unit("specific_wear_rate")),
                        true,
                    ));
                }
                panels
            },
            true,
            "fig4_sliding_wear",
            fig4_title(data),
        ),
        _ => (
            vec![LoadPanel::per_area("particle_rate", "particle rate dN*₊/ds", shown)],
            true,
            "fig5_particle_rate",
            "wear particles emitted per sliding distance, means over the run-in surface pairs (over all where none is)"
                .to_string(),
        ),
    };
    every_curve(data, panels, fitted).build(data, shown, entry, name, title)
}

/// Appendix C: the junctions N, one curve per setting (N does not depend on 𝒢), and the critical
/// junctions N*, one per curve.
fn junction_counts(data: &Curves, shown: Shown) -> Vec<Figure> {
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
        .build(data, shown, "appC", "appC_junctions", "number of junctions".into()),
        every_curve(data, vec![critical], false).build(
            data,
            shown,
            "appC",
            "appC_critical_junctions",
            "number of critical junctions".into(),
        ),
    ]
}

/// Fig. 4's title: what it draws, and, where the study holds them, that the estimate's curves are
/// labelled as such.
fn fig4_title(data: &Curves) -> String {
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
fn constant_critical_diameter(data: &Curves, shown: Shown) -> Vec<Figure> {
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
            "fig4c",
            "fig4c_constant_d_star",
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
                "fig4c",
                &format!("fig4c_constant_d_star_{}", g + 1),
                format!(
                    "settings of nearly equal d* ≈ {}",
                    shown.length(data.curves[group[0]].critical_diameter)
                ),
            )
        })
        .collect()
}

/// Fig. 6: k per material; Kim et al.'s rolling wear coefficients 6e-7 … 1.5e-3 (paper §4.2,
/// Fig. 6c) shaded only for a study of Kim's ceramics (the properties of the paper's Table 1).
fn kim_comparison(study: &Study) -> Figure {
    let kim = has_kim_materials(study.tidy);
    let title = if kim {
        "simulated sliding k per material against the experimental range"
    } else {
        "sliding k per material (no material of Kim et al.'s Table 1 here: no experimental band)"
    };
    LoadFigure {
        curves: study.data.curves.iter().collect(),
        panels: vec![LoadPanel::new("wear_coefficient", "wear coefficient k", true)],
        fitted: true,
        by_material: study.data.materials > 1,
        band: kim.then_some((
            KIM_EXPERIMENTAL_K.0,
            KIM_EXPERIMENTAL_K.1,
            "Kim et al. 1986, rolling experiments: k = 6×10⁻⁷ … 1.5×10⁻³",
        )),
    }
    .build(&study.data, study.shown, "fig6", "fig6_kim_comparison", title.into())
}

/// Eq. 5 / W against load, as the finding judges it: per curve and setting, the mean over its
/// run-in pairs with its Student-t interval, over the range of "slightly underestimates".
fn equation_5_over_w_panel(data: &Curves, tidy: &Table, shown: Shown) -> Panel {
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
fn equation_5(data: &Curves, tidy: &Table, shown: Shown) -> Figure {
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
        entry: "appB-eq5",
        name: "appB_eq5_against_w".into(),
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
    }
}

fn r2_text(fit: &PowerLawFit) -> String {
    fit.r2.map_or("undefined".into(), |r| format!("{r:.3}"))
}

/// A fitted power law drawn over a span of S_c.
type Line<'a> = &'a dyn Fn(f64, f64) -> Vec<Point>;

/// One material of appendix F: its points (S_c, W), its fit W = α S_cⁿ where it has one, and its
/// legend entry.
fn material_severity(m: usize, mat: &MaterialSeverity, line: Line) -> (Vec<Series>, LegendEntry) {
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
fn severity_references(all: PowerLawFit, kim: bool) -> Vec<((f64, f64), String, Color)> {
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
/// fits. None with fewer than two jobs with W > 0 on generated surfaces.
fn contact_severity(tidy: &Table, shown: Shown) -> Option<Figure> {
    let (materials, all) = severity_fits(tidy);
    let all = all?;
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
    Some(Figure {
        entry: "appF",
        name: "appF_contact_severity".into(),
        title: format!(
            "W = α S_cⁿ, all materials: α = {} {area}, n = {:.3}, R² = {}",
            number(all.prefactor),
            all.exponent,
            r2_text(&all)
        ),
        panels: one_panel(x, y, series),
        legend_title: String::new(),
        legend,
        note: None,
    })
}

/// A figure of one job's sliding series: a note without job files or for a job of the static
/// estimate.
fn series_figure(
    study: &Study,
    entry: &'static str,
    name: &str,
    draw: impl Fn(&SeriesOf, &[SeriesOf], Shown) -> Figure,
) -> Figure {
    match &study.series {
        None => Figure::note(entry, name, NO_JOB_FILES),
        Some((job, _)) if job.steps.is_empty() => Figure::note(entry, name, NO_SERIES),
        Some((job, pairs)) => {
            let pairs: Vec<SeriesOf> = pairs.iter().map(|r| SeriesOf::of_job(r, study.shown)).collect();
            Figure {
                entry,
                name: name.into(),
                ..draw(&SeriesOf::of_job(job, study.shown), &pairs, study.shown)
            }
        }
    }
}

/// What the series figures (fig3, appB, memory) draw of one job of a study, or of one run outside
/// one ([`run_figure`]): its steps at one load, its results per fracture energy, and the words that
/// name it.
struct SeriesOf<'a> {
    load: f64,
    steps: Cow<'a, [StepRow]>,
    results: Cow<'a, [WearResult]>,
    /// Who it is, in titles: "job 3 (Si3N4), surface pair 2, τ̃ = 0.012 E, p_N = 0.001 E", or a
    /// run's load.
    who: String,
    /// What the memory figure's title says it draws: "every surface pair — " and who without
    /// the pair, or a run's load.
    setting: String,
    /// Its name among the memory figure's curves: "pair 2", "job 3", or a run's label.
    name: String,
}

impl<'a> SeriesOf<'a> {
    fn of_job(r: &'a JobResult, shown: Shown) -> Self {
        Self {
            load: r.load,
            steps: Cow::Borrowed(&r.steps),
            results: Cow::Borrowed(&r.results),
            who: who(r, shown, true),
            setting: format!("every surface pair — {}", who(r, shown, false)),
            name: r
                .inputs
                .seed
                .map_or(format!("job {}", r.index), |s| format!("pair {s}")),
        }
    }
}

/// "job 3 (Si3N4), surface pair 2, τ̃ = 0.012 E, p_N = 0.001 E".
fn who(r: &JobResult, shown: Shown, with_pair: bool) -> String {
    let seed = match r.inputs.seed {
        Some(s) if with_pair => format!(", surface pair {s}"),
        _ => String::new(),
    };
    let material = if r.material == "material" {
        String::new()
    } else {
        format!(" ({})", r.material)
    };
    format!(
        "job {}{material}{seed}, τ̃ = {}, p_N = {} {}",
        r.index,
        shown.stress(r.inputs.shear_strength),
        number(r.inputs.nominal_pressure(r.load)),
        shown.unit("nominal_pressure")
    )
}

fn line_series(label: String, color: Color, dashed: bool, width: u32, points: Vec<Point>) -> Series {
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
fn fit_line(label: String, color: Color, points: Vec<Point>) -> Series {
    Series {
        reference: true,
        ..line_series(label, color, true, 1, points)
    }
}

fn one_panel(x: Axis, y: Axis, series: Vec<Series>) -> Vec<Panel> {
    vec![Panel {
        x,
        y,
        x_band: None,
        y_band: None,
        diagonal: false,
        series,
    }]
}

/// Whether a job's pair is run in by the findings' rule (paper §3): at most
/// [`RUN_IN_LINEAGES_LEFT`] of the junction lineages of s = 0 left where its fit window starts
/// (where none was there to count, its fit window after [`RUN_IN_DECAY_LENGTHS`] decay lengths ℓ);
/// the findings set a pair that is not aside.
fn run_in_words(r: &SeriesOf) -> String {
    let first = r.results.first();
    let left = first.and_then(|w| lineages_left(&r.steps, w));
    let lengths = first.and_then(|w| w.running_in_decay_lengths);
    // The findings' rule decides; the words say what it read.
    let run_in = crate::sliding::is_run_in(left, lengths);
    let why = match (left, lengths) {
        (Some(left), lengths) => format!(
            "{:.0} % of the lineages of s = 0 left at the fit window{}{}",
            100.0 * left,
            lengths.map_or(String::new(), |x| format!(", {} ℓ", number(x))),
            if run_in {
                String::new()
            } else {
                format!("; over {:.0} %", 100.0 * RUN_IN_LINEAGES_LEFT)
            }
        ),
        (None, Some(x)) => format!(
            "fit window from {} ℓ, {} {RUN_IN_DECAY_LENGTHS}",
            number(x),
            if run_in { "at least" } else { "under" }
        ),
        (None, None) => "no lineage of s = 0 to follow and no decay fitted: the memory of the initial contact is \
                         gone by the first step"
            .into(),
    };
    if run_in {
        format!("run in ({why})")
    } else {
        format!("not run in ({why}): the findings set this pair aside")
    }
}

/// Fig. 3: V(s) of one job per fracture energy, with the results' line W·s + b fitted over the fit
/// window, and the running-in shaded.
fn wear_volume(r: &SeriesOf, shown: Shown) -> Figure {
    let fit_start = r.results.first().map_or(0.0, |w| w.fit_window_start);
    let s_max = r.steps.last().map_or(1.0, |st| st.s);
    let mut legend = vec![LegendEntry {
        label: "running-in (not fitted)".into(),
        color: Color::Light,
        marker: 0,
        swatch: Swatch::Band,
    }];
    let mut series = Vec::new();
    for (e, w) in r.results.iter().enumerate() {
        let color = Color::Palette(e);
        let label = format!(
            "V, 𝒢 = {} {} (d* = {})",
            pretty(w.fracture_energy),
            shown.unit("fracture_energy"),
            shown.length(w.critical_diameter)
        );
        let v = r
            .steps
            .iter()
            .filter_map(|st| Some(Point::at(st.s, *st.volume.get(e)?)))
            .collect();
        series.push(line_series(label.clone(), color, false, 2, v));
        legend.push(LegendEntry {
            label,
            color,
            marker: 0,
            swatch: Swatch::Line { dashed: false },
        });
        if let (Some(slope), Some(intercept)) = (w.wear_rate, w.wear_volume_intercept) {
            let r2 = w
                .wear_rate_r2
                .map_or("undefined (no particle)".into(), |x| format!("{x:.3}"));
            let label = format!("fit: W = {} {}, R² = {r2}", number(slope), shown.unit("wear_rate"));
            let fit = vec![Point::at(0.0, intercept), Point::at(s_max, intercept + slope * s_max)];
            series.push(fit_line(label.clone(), color, fit));
            legend.push(LegendEntry {
                label,
                color,
                marker: 0,
                swatch: Swatch::Line { dashed: true },
            });
        }
    }
    let mut panels = one_panel(
        shown.distance_axis(),
        Axis {
            label: format!("wear volume V ({})", shown.unit("volume")),
            log: false,
            fallback: (0.0, 1.0),
        },
        series,
    );
    panels[0].x_band = Some(Band {
        low: 0.0,
        high: fit_start,
        color: Color::Light,
    });
    Figure {
        entry: "",
        name: String::new(),
        title: format!("wear volume V(s) — {}; {}", r.who, run_in_words(r)),
        panels,
        legend_title: String::new(),
        legend,
        note: None,
    }
}

/// One count of appendix B: its value in a series row, dashed, the line's width, what it is.
type Count = (fn(&SeriesRow) -> f64, bool, u32, &'static str);

/// Appendix B (Fig. B.9a): N*₊ (solid), N* (dashed) and N*₋ = N*₊ − N* (thin) of one job against s,
/// per fracture energy, from the library's series rows.
fn particle_counts(r: &SeriesOf, shown: Shown) -> Figure {
    let rows: Vec<SeriesRow> = job_series_rows(r.load, &r.results, &r.steps);
    let (mut series, mut legend) = (Vec::new(), Vec::new());
    for (e, w) in r.results.iter().enumerate() {
        let color = Color::Palette(e);
        let mine: Vec<&SeriesRow> = rows
            .iter()
            .filter(|row| row.fracture_energy == w.fracture_energy)
            .collect();
        let d = if w.critical_diameter.is_finite() {
            format!("d* = {}", shown.length(w.critical_diameter))
        } else {
            format!("𝒢 = {} {}", pretty(w.fracture_energy), shown.unit("fracture_energy"))
        };
        let counts: [Count; 3] = [
            (|r| r.n_formed as f64, false, 2, "N*₊ (particles formed)"),
            (|r| r.n_critical as f64, true, 2, "N* (junctions ≥ d* now)"),
            (|r| r.n_shrunk as f64, false, 1, "N*₋ (thin)"),
        ];
        for (value, dashed, width, what) in counts {
            let label = format!("{what}, {d}");
            let points = mine.iter().map(|row| Point::at(row.s, value(row))).collect();
            series.push(line_series(label.clone(), color, dashed, width, points));
            legend.push(LegendEntry {
                label,
                color,
                marker: 0,
                swatch: Swatch::Line { dashed },
            });
        }
    }
    Figure {
        entry: "",
        name: String::new(),
        title: format!(
            "particles formed N*₊, critical junctions N*, N*₋ = N*₊ − N* — {}",
            r.who
        ),
        panels: one_panel(
            shown.distance_axis(),
            Axis {
                label: "number of junctions".into(),
                log: false,
                fallback: (0.0, 1.0),
            },
            series,
        ),
        legend_title: String::new(),
        legend,
        note: None,
    }
}

/// One surface pair of the memory figure: N₀(s), its fit while it expects a junction or more, its
/// legend entry, and its decay length ℓ where it has a fit.
fn memory_of_pair(i: usize, r: &SeriesOf, shown: Shown) -> (Vec<Series>, LegendEntry, Option<f64>) {
    let color = Color::Palette(i);
    let points = r
        .steps
        .iter()
        .map(|st| Point::at(st.s, st.initial_junctions as f64))
        .collect();
    let pair = &r.name;
    let mut label = format!("{pair}: N₀(s)");
    let mut series = vec![line_series(label.clone(), color, false, 2, points)];
    let first = r.results.first();
    let fit = first.and_then(|w| Some((w.memory_decay_length?, w.memory_fit_initial_junctions?)));
    if let Some((decay_length, initial)) = fit {
        let curve = r
            .steps
            .iter()
            .map(|st| Point::at(st.s, initial * (-st.s / decay_length).exp()))
            .take_while(|p| p.y >= 1.0)
            .collect();
        series.push(fit_line(format!("{pair}: fit"), color, curve));
        let r2 = first
            .and_then(|w| w.memory_decay_r2)
            .map_or("undefined".into(), |x| format!("{x:.2}"));
        let run_in = first
            .and_then(|w| w.running_in_decay_lengths)
            .map_or(String::new(), |x| format!(", s_r = {} ℓ", number(x)));
        label = format!(
            "{label}, fit ℓ = {} {} (R² = {r2}{run_in})",
            number(decay_length),
            shown.unit("length")
        );
    }
    // Where the pair's fit window starts: its N₀ there, the count the run-in rule reads.
    if let Some(w) = first {
        let at_start = r.steps.iter().find(|st| st.s >= w.fit_window_start);
        if let Some(st) = at_start.filter(|st| st.initial_junctions > 0) {
            series.push(Series {
                label: format!("{pair}: N₀(s_r), where the running-in ends"),
                color,
                marker: 0,
                style: Style::Markers,
                points: vec![Point::at(st.s, st.initial_junctions as f64)],
                reference: false,
            });
        }
        if let Some(left) = lineages_left(&r.steps, w) {
            label = format!("{label}, N₀(s_r)/N₀(0) = {:.0} %", 100.0 * left);
        }
    }
    let run_in = run_in_words(r);
    let verdict = run_in.split(" (").next().unwrap_or(&run_in);
    label = format!("{label} — {verdict}");
    let entry = LegendEntry {
        label,
        color,
        marker: 0,
        swatch: Swatch::Line { dashed: false },
    };
    (series, entry, fit.map(|f| f.0))
}

/// The memory of the initial contact (§3): N₀(s) of every surface pair of one setting, each with its
/// fitted N₀(0) e^(−s/ℓ) (dashed, while it expects a junction or more), and the mean ℓ with its 95 %
/// interval over the pairs as the legend's title.
fn memory(pairs: &[SeriesOf], shown: Shown) -> Figure {
    // The fit window of every pair starts at the run's running-in distance: shaded before it.
    let fit_start = pairs
        .first()
        .and_then(|r| r.results.first())
        .map_or(0.0, |w| w.fit_window_start);
    let mut legend = vec![LegendEntry {
        label: format!(
            "running-in (not fitted): the fit window starts at s = {} {}",
            number(fit_start),
            shown.unit("length")
        ),
        color: Color::Light,
        marker: 0,
        swatch: Swatch::Band,
    }];
    let (mut series, mut lengths) = (Vec::new(), Vec::new());
    for (i, r) in pairs.iter().enumerate() {
        let (mine, entry, length) = memory_of_pair(i, r, shown);
        series.extend(mine);
        legend.push(entry);
        lengths.extend(length);
    }
    let markers = format!(
        "; markers: each pair's N₀ where its fit window starts (run in with at most {:.0} % of N₀(0) left)",
        100.0 * RUN_IN_LINEAGES_LEFT
    );
    let legend_title = match mean_interval(&lengths) {
        Some(i) => format!(
            "mean ℓ = {} [{}, {}] {} (95 % interval, Student t over {} pairs); dashed: each pair's fit{markers}",
            number(i.estimate),
            number(i.low),
            number(i.high),
            shown.unit("length"),
            i.n
        ),
        None => format!("dashed: each pair's fit N₀(0) e^(−s/ℓ){markers}"),
    };
    let title = match pairs.first() {
        Some(r) => format!("memory of the initial contact, {}", r.setting),
        None => "memory of the initial contact".into(),
    };
    Figure {
        entry: "",
        name: String::new(),
        title,
        panels: vec![Panel {
            x_band: Some(Band {
                low: 0.0,
                high: fit_start,
                color: Color::Light,
            }),
            ..one_panel(
                shown.distance_axis(),
                Axis {
                    label: "junctions descending from s = 0, N₀".into(),
                    log: true,
                    fallback: (0.5, 10.0),
                },
                series,
            )
            .remove(0)
        }],
        legend_title,
        legend,
        note: None,
    }
}

/// One sliding run as the series figures take it outside a study ([`run_figure`]): its series (the
/// columns of [`SeriesRow`]: `series.csv`, the data frame of Python's `slide`, a job's series) and
/// its results (the columns of [`WearResult`] and `load`: `summary["results"]` of a run, or the
/// job's rows of a study's tidy table), and its name in the memory figure's legend.
pub struct RunTables<'a> {
    pub label: &'a str,
    pub series: &'a Table,
    /// Required by the figures that draw a fit (fig3, memory); appB without them names each curve
    /// by its fracture energy instead of its d*.
    pub results: Option<&'a Table>,
}

/// A result row with its load, as a run's summary and a study's tidy table give it.
#[derive(serde::Deserialize)]
struct ResultOfLoad {
    load: f64,
    #[serde(flatten)]
    result: WearResult,
}

/// The load of a run's series rows that `load` names (matched as Python's `np.isclose(…,
/// rtol=1e-12)`: a load typed back from its printed form), or the series' last.
fn load_of_series(rows: &[SeriesRow], load: Option<f64>) -> Result<f64> {
    let loads = distinct(rows.iter().map(|r| r.load));
    match load {
        None => loads
            .last()
            .copied()
            .ok_or_else(|| Error::param("series", "it has no row")),
        Some(asked) => loads
            .iter()
            .copied()
            .find(|&l| (l - asked).abs() <= 1e-12 * asked.abs())
            .ok_or_else(|| {
                let have: Vec<String> = loads.iter().map(|&l| number(l)).collect();
                Error::param(
                    "load",
                    format!(
                        "the series has no load {}: its loads are {}",
                        number(asked),
                        have.join(", ")
                    ),
                )
            }),
    }
}

/// The results of `run` at `load`; without results, where the figure does not `need` them, the
/// fracture energies of the series in its order with nothing fitted (and d* unknown). An error
/// where none is left.
fn results_of_run(run: &RunTables, rows: &[SeriesRow], load: f64, need: bool) -> Result<Vec<WearResult>> {
    let results: Vec<WearResult> = match run.results {
        Some(table) => table
            .records::<ResultOfLoad>("results")?
            .into_iter()
            .filter(|r| r.load == load)
            .map(|r| r.result)
            .collect(),
        None if !need => distinct(rows.iter().filter(|r| r.load == load).map(|r| r.fracture_energy))
            .into_iter()
            .map(|g| WearResult {
                fracture_energy: g,
                critical_diameter: f64::NAN,
                ..WearResult::default()
            })
            .collect(),
        None => Vec::new(),
    };
    if results.is_empty() {
        return Err(Error::param(
            "results",
            format!(
                "{} of load {}: pass the run's results (`summary[\"results\"]` of a run, or the job's rows of the \
                 tidy table), whose fits (W and its intercept, the fit window, ℓ) the figure draws",
                if run.results.is_some() {
                    "none of its rows is"
                } else {
                    "none given, and the figure needs those"
                },
                number(load)
            ),
        ));
    }
    Ok(results)
}

/// The series of `run`, one of `runs`, at load `load` (default: its series' last) as the series
/// figures take it; without results, an error where the figure `needs_results`.
fn series_of_run<'a>(
    run: &RunTables,
    runs: usize,
    load: Option<f64>,
    needs_results: bool,
    shown: Shown,
) -> Result<SeriesOf<'a>> {
    let rows: Vec<SeriesRow> = run.series.records("series")?;
    let load = load_of_series(&rows, load)?;
    let results = results_of_run(run, &rows, load, needs_results)?;
    let energies: Vec<f64> = results.iter().map(|w| w.fracture_energy).collect();
    let steps = steps_of_rows(&rows, load, &energies)?;
    let who = format!("F_N = {} {}", number(load), shown.unit("load"));
    Ok(SeriesOf {
        load,
        steps: Cow::Owned(steps),
        results: Cow::Owned(results),
        setting: if runs > 1 {
            format!("{runs} runs — {who}")
        } else {
            who.clone()
        },
        who,
        name: run.label.to_string(),
    })
}

/// A series figure — `fig3` (V(s) with the fitted line), `appB` (N*₊, N*, N*₋) or `memory` (N₀(s)
/// with its fit) — of sliding runs outside a study, as Python's `wearsim.plot.wear_volume`,
/// `particle_counts` and `memory` draw them: at load `load` (default: the last of the first run's
/// series), per fracture energy of the results at that load; fig3 and appB draw the first run,
/// memory every run, as a study's memory figure draws every surface pair of a setting. The lines
/// are the results' fits (W and its intercept, the fit window, ℓ): a figure fits nothing of its own.
pub fn run_figure(entry: &str, runs: &[RunTables], load: Option<f64>, units: Units) -> Result<Figure> {
    let shown = Shown { system: units };
    let series: Vec<SeriesOf> = runs
        .iter()
        .map(|run| series_of_run(run, runs.len(), load, entry != "appB", shown))
        .collect::<Result<_>>()?;
    let first = series.first().ok_or_else(|| Error::param("series", "no run given"))?;
    let (entry, name, figure) = match entry {
        "fig3" => ("fig3", "fig3_wear_volume", wear_volume(first, shown)),
        "appB" => ("appB", "appB_particle_counts", particle_counts(first, shown)),
        "memory" => ("memory", "memory_of_initial_contact", memory(&series, shown)),
        other => {
            return Err(Error::param(
                "figure",
                format!("{other:?} is not a figure of one run's series: fig3, appB or memory"),
            ))
        }
    };
    Ok(Figure {
        entry,
        name: name.into(),
        ..figure
    })
}

/// The series figures (fig3, appB, memory: [`run_figure`]) of one `slide` run folder, from its
/// `series.csv` and the results of its `summary.json`, for every load of the run (names suffixed
/// `_load1`, `_load2`, … in the run's order where it has several), in the run's units. An error
/// names the file that is missing or not a sliding run's (an estimate's folder has no series).
pub fn slide_folder_figures(dir: &std::path::Path) -> Result<Vec<Figure>> {
    let summary_path = dir.join("summary.json");
    let summary: serde_json::Value = serde_json::from_str(&crate::io::read_text(&summary_path)?)
        .map_err(|e| Error::file(&summary_path, format!("not a run's summary ({e})")))?;
    if summary
        .get("model")
        .and_then(|m| m.as_str())
        .is_some_and(|m| m != "sliding")
    {
        return Err(Error::file(
            &summary_path,
            "the summary of a static estimate, which has no series to draw (`wearsim plot` draws a `slide` folder; \
             a study's estimates are drawn by `wearsim study plot`)",
        ));
    }
    let units: Units = serde_json::from_value(summary["units"].clone())
        .map_err(|e| Error::file(&summary_path, format!("no `units` of a run ({e})")))?;
    let records = summary["results"].as_array().ok_or_else(|| {
        Error::file(
            &summary_path,
            "no `results` of a sliding run: it is not the summary.json of `wearsim slide` (a study folder is drawn by \
             `wearsim study plot`)",
        )
    })?;
    let mut columns: Vec<String> = Vec::new();
    for r in records {
        for key in r.as_object().into_iter().flat_map(|o| o.keys()) {
            if !columns.contains(key) {
                columns.push(key.clone());
            }
        }
    }
    let results = Table {
        rows: records
            .iter()
            .map(|r| columns.iter().map(|c| Cell::of(&r[c])).collect())
            .collect(),
        columns,
    };
    let series_path = dir.join("series.csv");
    let series = Table::from_csv(&crate::io::read_text(&series_path)?)
        .map_err(|e| Error::file(&series_path, format!("not a run's series ({e})")))?;
    let loads = distinct(
        series
            .column("load")
            .map_or(Vec::new(), |c| series.rows.iter().map(|r| r[c].number()).collect()),
    );
    if loads.is_empty() {
        return Err(Error::file(
            &series_path,
            "no step of any load: the run has no series to draw",
        ));
    }
    let run = RunTables {
        label: "this run",
        series: &series,
        results: Some(&results),
    };
    let mut figures = Vec::new();
    for (i, &load) in loads.iter().enumerate() {
        for entry in ["fig3", "appB", "memory"] {
            let mut figure = run_figure(entry, std::slice::from_ref(&run), Some(load), units)?;
            if loads.len() > 1 {
                figure.name = format!("{}_load{}", figure.name, i + 1);
            }
            figures.push(figure);
        }
    }
    Ok(figures)
}

/// A study folder's figures, with the tidy table they were drawn from (the findings are judged on
/// the same) and the job whose series they show.
pub struct StudyFigures {
    pub tidy: Table,
    pub figures: Vec<Figure>,
    /// The job whose series fig3, appB and memory draw.
    pub series_job: Option<usize>,
}

/// [`study_figures`] of a finished study folder: its job files read (and checked) once.
pub fn study_folder_figures(
    dir: &std::path::Path,
    job: Option<usize>,
    names: Option<&[String]>,
) -> Result<StudyFigures> {
    let (_, results) = crate::study::collect::load_results(dir)?;
    let rows: Vec<crate::output::TidyRow> = results.iter().flat_map(crate::output::TidyRow::of_job).collect();
    let tidy = Table::of(&rows);
    let figures = study_figures(&tidy, &results, job, names)?;
    let series_job = match job {
        Some(j) => Some(j),
        None => series_job(
            results
                .iter()
                .flat_map(|r| r.results.iter().map(move |w| (r.index, w.particles_in_fit))),
        ),
    };
    Ok(StudyFigures {
        tidy,
        figures,
        series_job,
    })
}

#[cfg(test)]
mod tests;
