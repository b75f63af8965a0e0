//! Figures against the sliding distance: V(s) of one job with the library's fitted line (Fig. 3),
//! the particle counts of its series (appendix B), and the memory of the initial contact N₀(s) of
//! every surface pair of its setting with each pair's fit and the mean decay length (§3).

use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use wearsim::output::{unit_of, JobResult, SeriesRow};
use wearsim::stats::mean_interval;
use wearsim::study::Job;

use crate::figures::{color, layout, legend, number, pretty, Axis, Entry, Figure, Panel, Swatch};

use super::data::Units2;

/// "job 3 (Si3N4), surface pair 2, τ̃ = 0.012 E, p_N = 0.001 E".
fn who(job: &Job, r: &JobResult, u: Units2, with_pair: bool) -> String {
    let seed = match job.inputs().seed {
        Some(s) if with_pair => format!(", surface pair {s}"),
        _ => String::new(),
    };
    format!(
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
    )
}

/// V(s) of one job (paper Fig. 3): per fracture energy, the volume and the library's line W·s + b
/// over the fit window, and the running-in shaded.
pub(super) struct VolumeFigure<'a> {
    pub job: &'a Job,
    pub result: &'a JobResult,
    pub units: Units2,
}

impl Figure for VolumeFigure<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let (r, u) = (self.result, self.units);
        let fit_start = r.results.first().map_or(0.0, |w| w.fit_window_start);
        let s: Vec<f64> = r.steps.iter().map(|st| st.s).collect();
        let (panels, legend_area) = layout(area, 1);
        let x = Axis::spanning(
            format!("sliding distance s ({})", u.length()),
            false,
            s.iter().copied(),
            (0.0, 1.0),
        );
        let ys = r.steps.iter().flat_map(|st| st.volume.iter().copied());
        let y = Axis::spanning(format!("wear volume V ({})", u.volume()), false, ys, (0.0, 1.0));
        let title = format!("wear volume V(s) — {}", who(self.job, r, u, true));
        let mut panel = Panel::new(&panels[0], &title, x, y)?;
        panel.x_band(0.0, fit_start, RGBColor(200, 200, 200).mix(0.35))?;
        let mut entries = vec![Entry {
            label: "running-in (not fitted)".into(),
            color: RGBColor(200, 200, 200),
            swatch: Swatch::Band,
        }];
        for (e, w) in r.results.iter().enumerate() {
            let col = color(e);
            let v: Vec<(f64, f64)> = r
                .steps
                .iter()
                .filter_map(|st| Some((st.s, *st.volume.get(e)?)))
                .collect();
            panel.line(&v, col, false, 2)?;
            entries.push(Entry {
                label: format!(
                    "V, 𝒢 = {} {} (d* = {})",
                    pretty(w.fracture_energy),
                    unit_of(u.system, "fracture_energy"),
                    u.show_length(w.critical_diameter)
                ),
                color: col,
                swatch: Swatch::Line { dashed: false },
            });
            // The results' line W·s + b, fitted over the fit window.
            if let (Some(slope), Some(intercept)) = (w.wear_rate, w.wear_volume_intercept) {
                let s_max = *s.last().unwrap_or(&1.0);
                panel.line(&[(0.0, intercept), (s_max, intercept + slope * s_max)], col, true, 1)?;
                let r2 = w
                    .wear_rate_r2
                    .map_or("undefined (no particle)".into(), |x| format!("{x:.3}"));
                entries.push(Entry {
                    label: format!("fit: W = {} {}, R² = {r2}", number(slope), u.area()),
                    color: col,
                    swatch: Swatch::Line { dashed: true },
                });
            }
        }
        legend(&legend_area, "", &entries)
    }
}

/// The particle counts of one job (appendix B, Fig. B.9a), from the library's series rows:
/// N*₊ (solid), N* (dashed), N*₋ (thin).
pub(super) struct CountsFigure<'a> {
    pub job: &'a Job,
    pub result: &'a JobResult,
    pub units: Units2,
}

impl Figure for CountsFigure<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let (r, u) = (self.result, self.units);
        let rows: Vec<SeriesRow> = r.series_rows();
        let (panels, legend_area) = layout(area, 1);
        let x = Axis::spanning(
            format!("sliding distance s ({})", u.length()),
            false,
            rows.iter().map(|row| row.s),
            (0.0, 1.0),
        );
        let y = Axis::spanning(
            "number of junctions",
            false,
            rows.iter().map(|row| row.n_formed as f64),
            (0.0, 1.0),
        );
        let title = format!(
            "particles formed N*₊, critical junctions N*, N*₋ = N*₊ − N* — {}",
            who(self.job, r, u, true)
        );
        let mut panel = Panel::new(&panels[0], &title, x, y)?;
        let mut entries = Vec::new();
        for (e, w) in r.results.iter().enumerate() {
            let col = color(e);
            let mine: Vec<&SeriesRow> = rows
                .iter()
                .filter(|row| row.fracture_energy == w.fracture_energy)
                .collect();
            let series =
                |f: fn(&SeriesRow) -> f64| -> Vec<(f64, f64)> { mine.iter().map(|row| (row.s, f(row))).collect() };
            let d = format!("d* = {}", u.show_length(w.critical_diameter));
            for (points, dashed, width, what) in [
                (series(|r| r.n_formed as f64), false, 2, "N*₊ (particles formed)"),
                (series(|r| r.n_critical as f64), true, 2, "N* (junctions ≥ d* now)"),
                (series(|r| r.n_shrunk as f64), false, 1, "N*₋ (thin)"),
            ] {
                panel.line(&points, col, dashed, width)?;
                entries.push(Entry {
                    label: format!("{what}, {d}"),
                    color: col,
                    swatch: Swatch::Line { dashed },
                });
            }
        }
        legend(&legend_area, "", &entries)
    }
}

/// The memory of the initial contact (§3): N₀(s) of every surface pair of one setting, each with
/// its fitted N₀(0) e^(−s/ℓ) (dashed, while it expects a junction or more), and the mean ℓ with its
/// 95 % interval over the pairs.
pub(super) struct MemoryFigure<'a> {
    /// The setting's jobs, one per surface pair.
    pub pairs: Vec<(&'a Job, &'a JobResult)>,
    pub units: Units2,
}

impl Figure for MemoryFigure<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let u = self.units;
        let (panels, legend_area) = layout(area, 1);
        let s = self.pairs.iter().flat_map(|(_, r)| r.steps.iter().map(|st| st.s));
        let n0 = self
            .pairs
            .iter()
            .flat_map(|(_, r)| r.steps.iter().map(|st| st.initial_junctions as f64));
        let x = Axis::spanning(format!("sliding distance s ({})", u.length()), false, s, (0.0, 1.0));
        let y = Axis::spanning("junctions descending from s = 0, N₀", true, n0, (0.5, 10.0));
        let title = match self.pairs.first() {
            Some((job, r)) => format!(
                "memory of the initial contact, every surface pair — {}",
                who(job, r, u, false)
            ),
            None => "memory of the initial contact".into(),
        };
        let mut panel = Panel::new(&panels[0], &title, x, y)?;
        let mut entries = Vec::new();
        let mut lengths = Vec::new();
        for (i, (job, r)) in self.pairs.iter().enumerate() {
            let col = color(i);
            let points: Vec<(f64, f64)> = r.steps.iter().map(|st| (st.s, st.initial_junctions as f64)).collect();
            panel.line(&points, col, false, 2)?;
            let first = r.results.first();
            let fit = first.and_then(|w| Some((w.memory_decay_length?, w.memory_fit_initial_junctions?)));
            let pair = job
                .inputs()
                .seed
                .map_or(format!("job {}", r.index), |s| format!("pair {s}"));
            let mut label = format!("{pair}: N₀(s)");
            if let Some((decay_length, initial)) = fit {
                lengths.push(decay_length);
                let curve: Vec<(f64, f64)> = r
                    .steps
                    .iter()
                    .map(|st| (st.s, initial * (-st.s / decay_length).exp()))
                    .take_while(|p| p.1 >= 1.0)
                    .collect();
                panel.line(&curve, col, true, 1)?;
                let r2 = first
                    .and_then(|w| w.memory_decay_r2)
                    .map_or("undefined".into(), |x| format!("{x:.2}"));
                let run_in = first
                    .and_then(|w| w.running_in_decay_lengths)
                    .map_or(String::new(), |x| format!(", s_r = {} ℓ", number(x)));
                label = format!(
                    "{label}, fit ℓ = {} {} (R² = {r2}{run_in})",
                    number(decay_length),
                    u.length()
                );
            }
            entries.push(Entry {
                label,
                color: col,
                swatch: Swatch::Line { dashed: false },
            });
        }
        let summary = match mean_interval(&lengths) {
            Some(i) => format!(
                "mean ℓ = {} [{}, {}] {} (95 % interval, Student t over {} pairs); dashed: each pair's fit",
                number(i.estimate),
                number(i.low),
                number(i.high),
                u.length(),
                i.n
            ),
            None => "dashed: each pair's fit N₀(0) e^(−s/ℓ)".into(),
        };
        legend(&legend_area, &summary, &entries)
    }
}
