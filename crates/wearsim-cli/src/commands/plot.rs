//! `wearsim study plot DIR`: the figures of a finished study, as PNG and SVG in `DIR/figures`, in the
//! layout of the paper (Brink, Frérot & Molinari 2021), and the paper's findings checked on the study
//! (`findings.md`, also printed). The figures are the entries of one registry, [`FIGURES`] (name,
//! what it shows, how it is drawn); `--figures` takes their names and `--help` lists them.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::{anyhow, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use wearsim::config::Units;
use wearsim::output::{
    aggregate, curves as output_curves, equal_critical_diameter, unit_of, Cell, CurveMaterial, JobResult, Table,
    TidyRow,
};
use wearsim::stats::power_law_fit;
use wearsim::study::findings::{findings, markdown, RESOLVED_PARTICLES};
use wearsim::study::{load_results, Job};

use crate::figures::{color, layout, legend, number, pretty, save, Axis, Entry, Figure, Marker, Panel, Swatch};

#[derive(clap::Args)]
pub struct Args {
    /// Study folder.
    dir: PathBuf,
    /// The job whose series fig3, appB and memory show (its index, as in results.csv; default: the
    /// job that formed the most particles after running-in, the lowest index among equals).
    #[arg(long)]
    job: Option<usize>,
    /// Figures to draw, comma-separated (default: all).
    #[arg(long, value_delimiter = ',', value_parser = figure_names())]
    figures: Option<Vec<String>>,
}

/// The unit names of a study's axes: those of the library's tables ([`unit_of`]), and values shown
/// in legends with their unit.
#[derive(Debug, Clone, Copy)]
struct Units2 {
    system: Units,
    si: bool,
}

impl Units2 {
    fn of(system: Units) -> Self {
        Self {
            system,
            si: system == Units::Si,
        }
    }
    fn length(self) -> &'static str {
        unit_of(self.system, "length")
    }
    fn area(self) -> &'static str {
        unit_of(self.system, "wear_rate")
    }
    fn volume(self) -> &'static str {
        unit_of(self.system, "volume")
    }
    /// A length for legends (µm in SI).
    fn show_length(self, v: f64) -> String {
        if self.si {
            format!("{} µm", number(v * 1e6))
        } else {
            format!("{} L", number(v))
        }
    }
    fn show_stress(self, v: f64) -> String {
        if self.si {
            format!("{} GPa", number(v / 1e9))
        } else {
            format!("{} E", number(v))
        }
    }
    fn show_energy(self, v: f64) -> String {
        if self.si {
            format!("{} J/m²", number(v))
        } else {
            format!("{} E L", pretty(v))
        }
    }
}

/// How a varying input is named in legends.
fn input_label(key: &str, value: &toml::Value, units: Units2) -> String {
    let num = value.as_float().or(value.as_integer().map(|i| i as f64));
    let name = key.rsplit('.').next().unwrap_or(key);
    match (name, num) {
        ("shear_strength", Some(v)) => format!("τ̃ = {}", units.show_stress(v)),
        ("youngs_modulus", Some(v)) => format!("E = {}", units.show_stress(v)),
        ("rms_height", Some(v)) => format!("h_rms = {}", units.show_length(v)),
        ("lambda_lower", Some(v)) => format!("λ_l = {}", units.show_length(v)),
        ("lambda_upper", Some(v)) => format!("λ_u = {}", units.show_length(v)),
        ("length", Some(v)) => format!("box {}", units.show_length(v)),
        ("grid", Some(v)) => format!("{v}² px"),
        ("step_running_in", Some(v)) => format!("running-in step {v} px"),
        (_, Some(v)) => format!("{name} = {}", number(v)),
        (_, None) => format!("{name} = {value}"),
    }
}

/// One curve against load: a setting (material and varying inputs but the seed) and one fracture
/// energy, as the library groups them (`output::curves`); per nominal pressure p_N = F_N/(Lx·Ly),
/// its row of the library's aggregated table (`output::aggregate`: statistics over surface pairs).
struct Curve {
    label: String,
    material: usize,
    energy: usize,
    critical_diameter: f64,
    shear_strength: f64,
    fracture_energy: f64,
    /// The aggregated rows of this curve, by increasing nominal pressure.
    rows: Vec<Vec<Cell>>,
    /// The aggregated table's columns.
    columns: Arc<Vec<String>>,
}

/// A result column of the tables (its `_mean`, `_min` and `_max` in the aggregated one).
type Quantity = &'static str;

/// Points (x, y) of a series.
type Points = Vec<(f64, f64)>;

impl Curve {
    fn get(&self, row: &[Cell], column: &str) -> f64 {
        self.columns
            .iter()
            .position(|c| c == column)
            .map_or(f64::NAN, |i| row[i].number())
    }

    /// Per load: the particles formed in the fit window, summed over the surface pairs (the
    /// library's `particles_in_fit_total`, what the findings judge against [`RESOLVED_PARTICLES`]).
    fn particles(&self) -> Vec<(f64, f64)> {
        self.rows
            .iter()
            .map(|r| (self.get(r, "nominal_pressure"), self.get(r, "particles_in_fit_total")))
            .collect()
    }

    /// Per load: (load, mean, min, max) of a quantity over the surface pairs where it is defined.
    fn stats(&self, q: Quantity) -> Vec<(f64, f64, f64, f64)> {
        self.rows
            .iter()
            .filter_map(|r| {
                let mean = self.get(r, &format!("{q}_mean"));
                mean.is_finite().then(|| {
                    (
                        self.get(r, "nominal_pressure"),
                        mean,
                        self.get(r, &format!("{q}_min")),
                        self.get(r, &format!("{q}_max")),
                    )
                })
            })
            .collect()
    }
}

/// A study loaded for plotting.
struct Data {
    jobs: Vec<Job>,
    results: Vec<JobResult>,
    units: Units2,
    curves: Vec<Curve>,
    /// Material names, in order of appearance.
    materials: Vec<String>,
}

impl Data {
    fn new(jobs: Vec<Job>, results: Vec<JobResult>) -> Result<Self> {
        let first = jobs.first().ok_or_else(|| anyhow!("the study has no jobs"))?;
        let units = Units2::of(first.run.units);
        let mut materials: Vec<String> = Vec::new();
        // The library's tables: one tidy row per job and fracture energy, aggregated over pairs.
        let mut tidy_rows = Vec::new();
        let mut origin = Vec::new();
        for (j, r) in results.iter().enumerate() {
            for (e, row) in TidyRow::of_job(r).into_iter().enumerate() {
                tidy_rows.push(row);
                origin.push((j, e));
            }
        }
        let tidy = Table::of(&tidy_rows);
        let of_row = output_curves(&tidy).index;
        let aggregated = aggregate(&tidy);
        let columns = Arc::new(aggregated.columns.clone());
        // Each curve named after the first job and fracture energy it holds.
        let mut curves: Vec<Curve> = Vec::new();
        for (&c, &(j, e)) in of_row.iter().zip(&origin) {
            if c < curves.len() {
                continue;
            }
            let (job, w) = (&jobs[j], &results[j].results[e]);
            let m = materials.iter().position(|x| *x == job.material).unwrap_or_else(|| {
                materials.push(job.material.clone());
                materials.len() - 1
            });
            let mut parts: Vec<String> = Vec::new();
            if job.material != "material" {
                parts.push(job.material.clone());
            }
            parts.extend(
                job.varying
                    .iter()
                    .filter(|(k, _)| k.as_str() != "surface.seed")
                    .map(|(k, v)| input_label(k, v, units)),
            );
            curves.push(Curve {
                label: format!(
                    "{}{}𝒢 = {} (d* = {})",
                    parts.join(", "),
                    if parts.is_empty() { "" } else { ", " },
                    units.show_energy(w.fracture_energy),
                    units.show_length(w.critical_diameter)
                ),
                material: m,
                energy: e,
                critical_diameter: w.critical_diameter,
                shear_strength: job.run.material.shear_strength,
                fracture_energy: w.fracture_energy,
                rows: Vec::new(),
                columns: Arc::clone(&columns),
            });
        }
        let curve = aggregated
            .column("curve")
            .ok_or_else(|| anyhow!("the aggregated table has no curve column"))?;
        let pressure = aggregated
            .column("nominal_pressure")
            .ok_or_else(|| anyhow!("the aggregated table has no nominal_pressure column"))?;
        for row in aggregated.rows {
            let c = usize::try_from(row[curve].number() as i64).unwrap_or(usize::MAX);
            curves
                .get_mut(c)
                .ok_or_else(|| anyhow!("aggregated row of an unknown curve {c}"))?
                .rows
                .push(row);
        }
        for c in &mut curves {
            c.rows
                .sort_by(|a, b| a[pressure].number().total_cmp(&b[pressure].number()));
        }
        Ok(Self {
            jobs,
            results,
            units,
            curves,
            materials,
        })
    }

    /// The paper's load axis: the nominal pressure.
    fn load_label(&self) -> String {
        format!(
            "nominal pressure p_N = F_N/(Lx·Ly) ({})",
            unit_of(self.units.system, "nominal_pressure")
        )
    }
}

/// A figure of quantities against load, one panel each, with a shared legend.
struct LoadFigure<'a> {
    curves: Vec<&'a Curve>,
    panels: Vec<(Quantity, String, bool)>,
    x_label: String,
    /// Shaded range of the last panel's y and its legend label (Kim et al.'s experiments).
    band: Option<(f64, f64, &'static str)>,
    /// Colour by material instead of by curve (its several series told apart by marker).
    by_material: bool,
    /// Whether the panels show fitted sliding rates, whose points with fewer than
    /// [`RESOLVED_PARTICLES`] particles are drawn hollow.
    fitted: bool,
    title: String,
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
}

/// "a", "b", … : the panel letters of the paper's multi-panel figures.
fn panel_letter(p: usize) -> char {
    (b'a' + (p % 26) as u8) as char
}

impl Figure for LoadFigure<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let (panels, legend_area) = layout(area, self.panels.len());
        let particles: Vec<Vec<(f64, f64)>> = self.curves.iter().map(|c| c.particles()).collect();
        let thin = |i: usize, x: f64| self.fitted && particles[i].iter().any(|p| p.0 == x && p.1 < RESOLVED_PARTICLES);
        let mut zeros_drawn = false;
        for (p, (area, (q, label, log))) in self.panels.iter().enumerate().map(|(p, x)| (p, (&panels[p], x))) {
            let stats: Vec<Vec<(f64, f64, f64, f64)>> = self.curves.iter().map(|c| c.stats(q)).collect();
            let xs = stats.iter().flatten().map(|s| s.0);
            let band = if p + 1 == self.panels.len() { self.band } else { None };
            let ys = stats
                .iter()
                .flatten()
                .flat_map(|s| [s.1, s.2, s.3])
                .chain(band.iter().flat_map(|b| [b.0, b.1]));
            let x = Axis::spanning(&self.x_label, true, xs, (1e-4, 1e-2));
            let y = Axis::spanning(label, *log, ys, (1e-6, 1.0));
            let caption = match (self.panels.len() > 1, p == 0) {
                (true, true) => format!("({}) {}", panel_letter(p), self.title),
                (true, false) => format!("({})", panel_letter(p)),
                (false, _) => self.title.clone(),
            };
            let mut panel = Panel::new(area, &caption, x, y)?;
            // Per load, the no-wear markers drawn so far: the next stacks above them, so that
            // curves without wear at the same load stay visible side by side.
            let mut zeros_at: BTreeMap<u64, usize> = BTreeMap::new();
            if let Some((lo, hi, _)) = band {
                panel.band(lo, hi, RGBColor(86, 180, 233).mix(0.25))?;
            }
            for (i, (c, s)) in self.curves.iter().zip(&stats).enumerate() {
                let (col, marker) = self.style(i, c);
                let means: Vec<(f64, f64)> = s.iter().map(|p| (p.0, p.1)).collect();
                panel.line(&means, col, false, 2)?;
                let (hollow, filled): (Points, Points) = means.iter().partition(|p| thin(i, p.0));
                panel.markers(&filled, col, marker)?;
                panel.markers_hollow(&hollow, col, marker)?;
                // No wear in any surface pair: zero has no place on a log axis, so it is marked on
                // the axis itself.
                if *log {
                    let zeros: Vec<(f64, usize)> = s
                        .iter()
                        .filter(|p| p.3 <= 0.0)
                        .map(|p| {
                            let level = zeros_at.entry(p.0.to_bits()).or_insert(0);
                            *level += 1;
                            (p.0, *level - 1)
                        })
                        .collect();
                    zeros_drawn |= !zeros.is_empty();
                    panel.zeros_at_axis(&zeros, col)?;
                }
                panel.bars(&s.iter().map(|p| (p.0, p.2, p.3)).collect::<Vec<_>>(), col)?;
            }
        }
        // Each curve's legend entry: its label, and the particle counts of its hollow points (a
        // point without any particle has no wear: it is the marker on the axis, not a hollow one).
        let thin_counts = |i: usize| -> String {
            let counts: Vec<String> = particles[i]
                .iter()
                .filter(|p| self.fitted && p.1 < RESOLVED_PARTICLES && p.1 > 0.0)
                .map(|p| number((p.1 * 10.0).round() / 10.0))
                .collect();
            if counts.is_empty() {
                String::new()
            } else {
                format!(" — hollow: {} particles", counts.join(", "))
            }
        };
        // One entry per series (each material its own colour), with its hollow points' counts.
        let mut entries: Vec<Entry> = Vec::new();
        for (i, c) in self.curves.iter().enumerate() {
            let (col, marker) = self.style(i, c);
            entries.push(Entry {
                label: format!("{}{}", c.label, thin_counts(i)),
                color: col,
                swatch: Swatch::LineMarker(marker),
            });
        }
        if self.fitted && particles.iter().flatten().any(|p| p.1 < RESOLVED_PARTICLES) {
            entries.push(Entry {
                label: format!(
                    "hollow: < {RESOLVED_PARTICLES} particles in the fit window (summed over surface pairs)"
                ),
                color: RGBColor(90, 90, 90),
                swatch: Swatch::Hollow(Marker::Circle),
            });
        }
        if zeros_drawn {
            entries.push(Entry {
                label: "on the axis (stacked per load): zero (no wear) in every surface pair".into(),
                color: RGBColor(90, 90, 90),
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
        legend(&legend_area, "mean over surface pairs; bars: min–max", &entries)
    }
}

/// The series of one job against s: V(s) (Fig. 3), the particle counts (appendix B) or the memory of
/// the initial contact (§3).
#[derive(Clone, Copy, PartialEq, Eq)]
enum SeriesKind {
    Volume,
    Counts,
    Memory,
}

struct SeriesFigure<'a> {
    job: &'a Job,
    result: &'a JobResult,
    kind: SeriesKind,
    units: Units2,
}

impl Figure for SeriesFigure<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let (job, r, u) = (self.job, self.result, self.units);
        // The fit window of the results (the same for every fracture energy).
        let fit_start = r.results.first().map_or(0.0, |w| w.fit_window_start);
        let s: Vec<f64> = r.steps.iter().map(|st| st.s).collect();
        let seed = job
            .inputs()
            .seed
            .map_or(String::new(), |s| format!(", surface pair {s}"));
        let who = format!(
            "job {}{}{seed}, τ̃ = {}, p_N = {} {}",
            r.index,
            if job.material == "material" {
                String::new()
            } else {
                format!(" ({})", job.material)
            },
            u.show_stress(job.run.material.shear_strength),
            number(r.inputs.nominal_pressure(r.load)),
            unit_of(u.system, "nominal_pressure")
        );
        let (panels, legend_area) = layout(area, 1);
        let x_label = format!("sliding distance s ({})", u.length());
        let mut entries = Vec::new();
        match self.kind {
            SeriesKind::Volume => {
                let x = Axis::spanning(&x_label, false, s.iter().copied(), (0.0, 1.0));
                let ys = r.steps.iter().flat_map(|st| st.volume.iter().copied());
                let y = Axis::spanning(format!("wear volume V ({})", u.volume()), false, ys, (0.0, 1.0));
                let mut panel = Panel::new(&panels[0], &format!("wear volume V(s) — {who}"), x, y)?;
                panel.x_band(0.0, fit_start, RGBColor(200, 200, 200).mix(0.35))?;
                entries.push(Entry {
                    label: "running-in (not fitted)".into(),
                    color: RGBColor(200, 200, 200),
                    swatch: Swatch::Band,
                });
                for (e, w) in r.results.iter().enumerate() {
                    let col = color(e);
                    let v: Vec<(f64, f64)> = r.steps.iter().map(|st| (st.s, st.volume[e])).collect();
                    panel.line(&v, col, false, 2)?;
                    entries.push(Entry {
                        label: format!(
                            "V, 𝒢 = {} (d* = {})",
                            u.show_energy(w.fracture_energy),
                            u.show_length(w.critical_diameter)
                        ),
                        color: col,
                        swatch: Swatch::Line { dashed: false },
                    });
                    // The results' line W·s + b, fitted over the fit window.
                    if let (Some(slope), Some(intercept)) = (w.wear_rate, w.wear_volume_intercept) {
                        let s_max = *s.last().unwrap_or(&1.0);
                        panel.line(&[(0.0, intercept), (s_max, intercept + slope * s_max)], col, true, 1)?;
                        entries.push(Entry {
                            label: format!(
                                "fit: W = {} {}, R² = {}",
                                number(slope),
                                u.area(),
                                w.wear_rate_r2
                                    .map_or("undefined (no particle)".into(), |x| format!("{x:.3}"))
                            ),
                            color: col,
                            swatch: Swatch::Line { dashed: true },
                        });
                    }
                }
            }
            SeriesKind::Counts => {
                let x = Axis::spanning(&x_label, false, s.iter().copied(), (0.0, 1.0));
                let ys = r.steps.iter().flat_map(|st| st.n_formed.iter().map(|&n| n as f64));
                let y = Axis::spanning("number of junctions", false, ys, (0.0, 1.0));
                let mut panel = Panel::new(
                    &panels[0],
                    &format!("particles formed N*₊, critical junctions N*, N*₋ = N*₊ − N* — {who}"),
                    x,
                    y,
                )?;
                for (e, w) in r.results.iter().enumerate() {
                    let col = color(e);
                    let d = format!("d* = {}", u.show_length(w.critical_diameter));
                    let formed: Vec<(f64, f64)> = r.steps.iter().map(|st| (st.s, st.n_formed[e] as f64)).collect();
                    let critical: Vec<(f64, f64)> = r.steps.iter().map(|st| (st.s, st.n_critical[e] as f64)).collect();
                    let shrunk: Vec<(f64, f64)> = r
                        .steps
                        .iter()
                        .map(|st| (st.s, st.n_formed[e] as f64 - st.n_critical[e] as f64))
                        .collect();
                    panel.line(&formed, col, false, 2)?;
                    panel.line(&critical, col, true, 2)?;
                    panel.line(&shrunk, col, false, 1)?;
                    entries.push(Entry {
                        label: format!("N*₊ (particles formed), {d}"),
                        color: col,
                        swatch: Swatch::Line { dashed: false },
                    });
                    entries.push(Entry {
                        label: format!("N* (junctions ≥ d* now), {d}"),
                        color: col,
                        swatch: Swatch::Line { dashed: true },
                    });
                    entries.push(Entry {
                        label: format!("N*₋ = N*₊ − N* (thin), {d}"),
                        color: col,
                        swatch: Swatch::Line { dashed: false },
                    });
                }
            }
            SeriesKind::Memory => {
                let n0: Vec<(f64, f64)> = r.steps.iter().map(|st| (st.s, st.initial_junctions as f64)).collect();
                let x = Axis::spanning(&x_label, false, s.iter().copied(), (0.0, 1.0));
                let y = Axis::spanning(
                    "junctions descending from s = 0, N₀",
                    true,
                    n0.iter().map(|p| p.1),
                    (0.5, 10.0),
                );
                let mut panel = Panel::new(&panels[0], &format!("memory of the initial contact — {who}"), x, y)?;
                panel.line(&n0, color(0), false, 2)?;
                entries.push(Entry {
                    label: "N₀(s)".into(),
                    color: color(0),
                    swatch: Swatch::Line { dashed: false },
                });
                // The results' fit of the memory (the same for every fracture energy).
                let fit = r.results.first().and_then(|w| {
                    Some((
                        w.memory_decay_length?,
                        w.memory_fit_initial_junctions?,
                        w.memory_decay_r2,
                    ))
                });
                if let Some((decay_length, initial, r2)) = fit {
                    // Drawn while it expects one junction or more.
                    let curve: Vec<(f64, f64)> = s
                        .iter()
                        .map(|&x| (x, initial * (-x / decay_length).exp()))
                        .take_while(|p| p.1 >= 1.0)
                        .collect();
                    panel.line(&curve, color(1), true, 2)?;
                    entries.push(Entry {
                        label: format!(
                            "fit N₀(0) e^(−s/ℓ): ℓ = {} {}, R² = {}",
                            number(decay_length),
                            u.length(),
                            r2.map_or("undefined".into(), |x| format!("{x:.3}"))
                        ),
                        color: color(1),
                        swatch: Swatch::Line { dashed: true },
                    });
                }
            }
        }
        legend(&legend_area, "", &entries)
    }
}

/// Eq. 5 against the summed wear rate (appendix B, Fig. B.9b): one point per setting and load.
struct Eq5Figure<'a> {
    curves: Vec<&'a Curve>,
    units: Units2,
}

impl Figure for Eq5Figure<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let points: Vec<Vec<(f64, f64)>> = self
            .curves
            .iter()
            .map(|c| {
                let w = c.stats("wear_rate");
                let e = c.stats("wear_rate_estimate");
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

/// Contact severity (paper appendix F): points (material, S_c, W) and the fit W = α S_cⁿ.
struct Severity {
    points: Vec<(usize, String, f64, f64)>,
    alpha: f64,
    n_exp: f64,
    r2: Option<f64>,
    units: Units2,
}

impl Severity {
    /// The contact severity S_c of the library's table (appendix F) against W, for every job and
    /// fracture energy with W > 0 and S_c defined (generated surfaces), and the library's fit
    /// W = α S_cⁿ ([`power_law_fit`]).
    fn of(data: &Data) -> Option<Self> {
        let mut points = Vec::new();
        for r in &data.results {
            let m = data.materials.iter().position(|n| *n == r.material).unwrap_or(0);
            for row in TidyRow::of_job(r) {
                if let (Some(s_c), Some(w)) = (row.contact_severity, row.result.wear_rate.filter(|x| *x > 0.0)) {
                    points.push((m, r.material.clone(), s_c, w));
                }
            }
        }
        let s_c: Vec<f64> = points.iter().map(|p| p.2).collect();
        let w: Vec<f64> = points.iter().map(|p| p.3).collect();
        let fit = power_law_fit(&s_c, &w)?;
        Some(Self {
            points,
            alpha: fit.prefactor,
            n_exp: fit.exponent,
            r2: fit.r2,
            units: data.units,
        })
    }

    /// The fit of one material's points: (α, n), when it has two distinct S_c.
    fn of_material(&self, m: usize) -> Option<(f64, f64)> {
        let mine: Vec<&(usize, String, f64, f64)> = self.points.iter().filter(|p| p.0 == m).collect();
        let s_c: Vec<f64> = mine.iter().map(|p| p.2).collect();
        let w: Vec<f64> = mine.iter().map(|p| p.3).collect();
        power_law_fit(&s_c, &w).map(|f| (f.prefactor, f.exponent))
    }
}

impl Figure for Severity {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let (panels, legend_area) = layout(area, 1);
        let x = Axis::spanning(
            "contact severity S_c = p_N √h_rms / K_Ic",
            true,
            self.points.iter().map(|p| p.2),
            (1e-3, 1.0),
        );
        let y = Axis::spanning(
            format!("wear rate W ({})", self.units.area()),
            true,
            self.points.iter().map(|p| p.3),
            (1e-6, 1.0),
        );
        let (x0, x1) = (x.lo, x.hi);
        let r2 = self.r2.map_or("undefined".into(), |r| format!("{r:.3}"));
        let title = format!(
            "W = α S_cⁿ: α = {} {}, n = {:.3}, R² = {r2}",
            number(self.alpha),
            self.units.area(),
            self.n_exp
        );
        let mut panel = Panel::new(&panels[0], &title, x, y)?;
        let mut entries = Vec::new();
        let mut seen = Vec::new();
        for p in &self.points {
            panel.markers(&[(p.2, p.3)], color(p.0), Marker::nth(p.0))?;
            if !seen.contains(&p.0) {
                seen.push(p.0);
            }
        }
        // Appendix F fits each material apart; one line per material with two or more points.
        let several = seen.len() > 1;
        for &m in &seen {
            let name = self.points.iter().find(|p| p.0 == m).map_or("", |p| p.1.as_str());
            match self.of_material(m).filter(|_| several) {
                Some((alpha, n)) => {
                    let line = [(x0, alpha * x0.powf(n)), (x1, alpha * x1.powf(n))];
                    panel.line(&line, color(m), false, 1)?;
                    entries.push(Entry {
                        label: format!("{name}: α = {}, n = {:.2}", number(alpha), n),
                        color: color(m),
                        swatch: Swatch::LineMarker(Marker::nth(m)),
                    });
                }
                None => entries.push(Entry {
                    label: name.to_string(),
                    color: color(m),
                    swatch: Swatch::Marker(Marker::nth(m)),
                }),
            }
        }
        let line = [
            (x0, self.alpha * x0.powf(self.n_exp)),
            (x1, self.alpha * x1.powf(self.n_exp)),
        ];
        panel.line(&line, BLACK, true, 1)?;
        entries.push(Entry {
            label: format!("all materials, least-squares fit (log–log), R² = {r2}"),
            color: BLACK,
            swatch: Swatch::Line { dashed: true },
        });
        legend(&legend_area, "", &entries)
    }
}

/// A figure that only says why it has no data.
struct Note(&'static str);

impl Figure for Note {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let (_, h) = area.dim_in_pixel();
        let style = (crate::figures::FONT, 18).into_font().color(&BLACK);
        area.draw_text(self.0, &style, (40, h as i32 / 2))
            .map_err(crate::figures::drawing)?;
        Ok(())
    }
}

/// Groups of curves of (nearly) equal d* (within 15 %) and different τ̃ or 𝒢, for Figs. 4c/5c: the
/// library's grouping ([`equal_critical_diameter`]).
fn equal_d_star(curves: &[Curve]) -> Vec<Vec<&Curve>> {
    let materials: Vec<CurveMaterial> = curves
        .iter()
        .map(|c| CurveMaterial {
            critical_diameter: c.critical_diameter,
            shear_strength: c.shear_strength,
            fracture_energy: c.fracture_energy,
        })
        .collect();
    equal_critical_diameter(&materials, 0.15)
        .into_iter()
        .map(|g| g.into_iter().map(|i| &curves[i]).collect())
        .collect()
}

/// The job whose series are drawn: the one asked for, or the one that formed the most particles
/// after running-in.
fn series_job(data: &Data, asked: Option<usize>) -> Result<(&Job, &JobResult)> {
    match asked {
        Some(i) => data
            .jobs
            .iter()
            .zip(&data.results)
            .find(|(j, _)| j.index == i)
            .ok_or_else(|| {
                anyhow!(
                    "invalid `--job {i}`: the study has jobs 0 … {}",
                    data.jobs.len().saturating_sub(1)
                )
            }),
        None => {
            let particles = data
                .results
                .iter()
                .flat_map(|r| r.results.iter().map(move |w| (r.index, w.particles_in_fit)));
            let index = wearsim::output::series_job(particles).ok_or_else(|| anyhow!("the study has no jobs"))?;
            data.jobs
                .iter()
                .zip(&data.results)
                .find(|(j, _)| j.index == index)
                .ok_or_else(|| anyhow!("the study has no job {index}"))
        }
    }
}

/// What every figure is drawn from: the study, the job whose series are shown, and the folder the
/// files go to.
struct Context<'a> {
    data: &'a Data,
    series: (&'a Job, &'a JobResult),
    out: &'a Path,
}

impl<'a> Context<'a> {
    /// Quantities against load for every curve of the study, one panel each.
    fn by_load(&self, panels: Vec<(Quantity, String, bool)>, fitted: bool, title: &str) -> LoadFigure<'a> {
        LoadFigure {
            curves: self.data.curves.iter().collect(),
            panels,
            x_label: self.data.load_label(),
            band: None,
            by_material: false,
            fitted,
            title: title.into(),
        }
    }

    fn save(&self, name: &str, size: (u32, u32), figure: &impl Figure) -> Result<()> {
        save(self.out, name, size, figure)
    }
}

/// One figure of `wearsim study plot`: the name `--figures` takes, what it shows (listed by
/// `--help`), and how it is drawn. A new figure is one entry of [`FIGURES`] and its drawing code.
struct Plot {
    name: &'static str,
    about: &'static str,
    draw: fn(&Context) -> Result<()>,
}

/// Every figure, in the order drawn.
const FIGURES: [Plot; 11] = [
    Plot {
        name: "fig2",
        about: "static model over every offset: W_static/ω and k_static against p_N (paper Fig. 2)",
        draw: fig2,
    },
    Plot {
        name: "fig3",
        about: "V(s) of one job with the fitted lines and the running-in region (Fig. 3)",
        draw: fig3,
    },
    Plot {
        name: "fig4",
        about: "sliding W and k against p_N, min–max bars over surface pairs (Fig. 4a–b)",
        draw: fig4,
    },
    Plot {
        name: "fig4c",
        about: "W, k and dN*₊/ds for settings of (nearly) equal d* (Figs. 4c, 5c)",
        draw: fig4c,
    },
    Plot {
        name: "fig5",
        about: "dN*₊/ds against p_N (Fig. 5)",
        draw: fig5,
    },
    Plot {
        name: "fig6",
        about: "k against p_N per material beside Kim et al.'s experimental range (Fig. 6)",
        draw: fig6,
    },
    Plot {
        name: "appB",
        about: "N*₊, N*, N*₋ against s of one job (appendix B, Fig. B.9a)",
        draw: app_b,
    },
    Plot {
        name: "appB-eq5",
        about: "Eq. 5, ω d*³ dN*₊/ds, against the summed W (Fig. B.9b)",
        draw: app_b_eq5,
    },
    Plot {
        name: "appC",
        about: "junctions N and critical junctions N* against p_N (appendix C)",
        draw: app_c,
    },
    Plot {
        name: "appF",
        about: "the contact-severity fit W = α S_cⁿ with its R² (appendix F)",
        draw: app_f,
    },
    Plot {
        name: "memory",
        about: "the memory of the initial contact N₀(s) of one job with its exponential fit (§3)",
        draw: memory,
    },
];

/// The values `--figures` takes: the names of [`FIGURES`], each with what it shows.
fn figure_names() -> clap::builder::PossibleValuesParser {
    clap::builder::PossibleValuesParser::new(
        FIGURES
            .iter()
            .map(|f| clap::builder::PossibleValue::new(f.name).help(f.about)),
    )
}

fn fig2(cx: &Context) -> Result<()> {
    let area = cx.data.units.area();
    let fig = cx.by_load(
        vec![
            (
                "static_wear_rate_mean",
                format!("static wear rate W_static/ω ({area})"),
                true,
            ),
            (
                "static_wear_coefficient_mean",
                "static wear coefficient k_static".into(),
                false,
            ),
        ],
        false,
        "static model, mean over every offset of the sliding run",
    );
    cx.save("fig2_static_model", WIDE, &fig)
}

fn fig4(cx: &Context) -> Result<()> {
    let area = cx.data.units.area();
    let fig = cx.by_load(
        vec![
            ("wear_rate", format!("sliding wear rate W = dV/ds ({area})"), true),
            ("wear_coefficient", "wear coefficient k = W p_m / F_N".into(), true),
        ],
        true,
        "sliding model",
    );
    cx.save("fig4_sliding_wear", WIDE, &fig)
}

fn fig5(cx: &Context) -> Result<()> {
    let fig = cx.by_load(
        vec![(
            "particle_rate",
            format!("particle rate dN*₊/ds (1/{})", cx.data.units.length()),
            true,
        )],
        true,
        "wear particles emitted per sliding distance",
    );
    cx.save("fig5_particle_rate", NARROW, &fig)
}

fn fig4c(cx: &Context) -> Result<()> {
    let (u, area) = (cx.data.units, cx.data.units.area());
    let groups = equal_d_star(&cx.data.curves);
    if groups.is_empty() {
        let note = "Fig. 4c compares settings of equal d* (within 15 %) with different τ̃ or 𝒢; this study has none";
        println!("fig4c: {note}");
        cx.save("fig4c_constant_d_star", NARROW, &Note(note))?;
    }
    for (g, group) in groups.iter().enumerate() {
        let fig = LoadFigure {
            curves: group.clone(),
            panels: vec![
                ("wear_rate", format!("W ({area})"), true),
                ("wear_coefficient", "k = W p_m / F_N".into(), true),
                ("particle_rate", format!("dN*₊/ds (1/{})", u.length()), true),
            ],
            x_label: cx.data.load_label(),
            band: None,
            by_material: false,
            fitted: true,
            title: format!(
                "settings of nearly equal d* ≈ {}",
                u.show_length(group[0].critical_diameter)
            ),
        };
        let name = if groups.len() == 1 {
            "fig4c_constant_d_star".to_string()
        } else {
            format!("fig4c_constant_d_star_{}", g + 1)
        };
        cx.save(&name, (2100, 640), &fig)?;
    }
    Ok(())
}

fn fig6(cx: &Context) -> Result<()> {
    // Kim et al. (1986): rolling wear coefficients 6e-7 … 1.5e-3 (paper §4.3, Fig. 6c). k is
    // dimensionless, so the comparison is drawn for studies in any units.
    let fig = LoadFigure {
        band: Some((
            6e-7,
            1.5e-3,
            "Kim et al. 1986, rolling experiments: k = 6×10⁻⁷ … 1.5×10⁻³",
        )),
        // One colour and marker per material where the study has several (Kim et al.'s ceramics).
        by_material: cx.data.materials.len() > 1,
        ..cx.by_load(
            vec![("wear_coefficient", "wear coefficient k".into(), true)],
            true,
            "simulated sliding k per material against the experimental range",
        )
    };
    cx.save("fig6_kim_comparison", NARROW, &fig)
}

fn app_c(cx: &Context) -> Result<()> {
    let fig = LoadFigure {
        curves: cx.data.curves.iter().filter(|c| c.energy == 0).collect(),
        ..cx.by_load(
            vec![("junctions_mean", "junctions N (mean after running-in)".into(), true)],
            false,
            "number of junctions",
        )
    };
    let critical = cx.by_load(
        vec![(
            "critical_junctions_mean",
            "junctions ≥ d*, N* (mean after running-in)".into(),
            true,
        )],
        false,
        "number of critical junctions",
    );
    cx.save("appC_junctions", NARROW, &fig)?;
    cx.save("appC_critical_junctions", NARROW, &critical)
}

fn app_b_eq5(cx: &Context) -> Result<()> {
    let fig = Eq5Figure {
        curves: cx.data.curves.iter().collect(),
        units: cx.data.units,
    };
    cx.save("appB_eq5_against_w", NARROW, &fig)
}

fn app_f(cx: &Context) -> Result<()> {
    match Severity::of(cx.data) {
        Some(severity) => {
            cx.save("appF_contact_severity", NARROW, &severity)?;
            println!(
                "contact severity fit: W = α S_cⁿ with α = {} {}, n = {:.3}, R² = {}",
                number(severity.alpha),
                cx.data.units.area(),
                severity.n_exp,
                severity.r2.map_or("undefined".into(), |r| format!("{r:.3}"))
            );
        }
        None => println!("appF: fewer than two jobs with W > 0 on generated surfaces; not drawn"),
    }
    Ok(())
}

/// A series figure of the chosen job.
fn series(cx: &Context, file: &str, kind: SeriesKind) -> Result<()> {
    let (job, result) = cx.series;
    let fig = SeriesFigure {
        job,
        result,
        kind,
        units: cx.data.units,
    };
    cx.save(file, (1400, 640), &fig)
}

fn fig3(cx: &Context) -> Result<()> {
    series(cx, "fig3_wear_volume", SeriesKind::Volume)
}

fn app_b(cx: &Context) -> Result<()> {
    series(cx, "appB_particle_counts", SeriesKind::Counts)
}

fn memory(cx: &Context) -> Result<()> {
    series(cx, "memory_of_initial_contact", SeriesKind::Memory)
}

/// Sizes of figures of two panels and of one.
const WIDE: (u32, u32) = (1700, 640);
const NARROW: (u32, u32) = (1150, 640);

pub fn run(args: &Args) -> Result<()> {
    let dir = &args.dir;
    let (study, results) = load_results(dir)?;
    let data = Data::new(study.jobs, results)?;
    let series = series_job(&data, args.job)?;
    let figures = wearsim::io::OutputDir::begin(&dir.join("figures"), "study plot", false, &[])?;
    let out = figures.join("");
    let cx = Context {
        data: &data,
        series,
        out: &out,
    };
    for figure in &FIGURES {
        if args.figures.as_ref().is_none_or(|w| w.iter().any(|n| n == figure.name)) {
            (figure.draw)(&cx)?;
        }
    }
    // The paper's findings on this study.
    let rows: Vec<TidyRow> = data.results.iter().flat_map(TidyRow::of_job).collect();
    let found = findings(&Table::of(&rows));
    let text = format!(
        "# The paper's findings on this study\n\nBrink, Frérot & Molinari (2021); `wearsim study plot` on {}.\n\n{}",
        dir.display(),
        markdown(&found)
    );
    wearsim::io::write_text(&figures.join("findings.md"), &text)?;
    figures.commit()?;
    for f in &found {
        println!("{:<18} {}: {}", f.verdict.name(), f.key, f.observed);
    }
    println!(
        "wrote figures and findings.md to {} (series of job {})",
        dir.join("figures").display(),
        cx.series.1.index
    );
    Ok(())
}
