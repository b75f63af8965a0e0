//! `wearsim study plot DIR`: figures of a finished study, as PNG and SVG, in the layout of the paper
//! (Brink, Frérot & Molinari 2021): static wear rate and k against F_N (Fig. 2), V(s) with its fitted
//! line and the running-in region (Fig. 3), sliding wear rate and k against F_N with min–max bars over
//! surface pairs (Fig. 4), dN*₊/ds against F_N (Fig. 5), N*₊, N*, N*₋ against s (appendix B), the
//! contact-severity fit (appendix F) and k against Kim et al.'s experiments (Fig. 6).

use std::collections::BTreeMap;
use std::path::PathBuf;

use anyhow::{anyhow, Context, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use wearsim::config::{SurfaceSource, Units};
use wearsim::output::{JobResult, StepRow};
use wearsim::sliding::WearResult;
use wearsim::study::{load_results, Job};

use crate::figures::{drawing, legend, log_range, save, Figure, FONT};

#[derive(clap::Args)]
pub struct Args {
    /// Study folder.
    dir: PathBuf,
}

/// Units of a study's axes: (load, length).
fn units_of(job: &Job) -> (&'static str, &'static str) {
    match job.run.units {
        Units::Reduced => ("E L²", "L"),
        Units::Si => ("N", "m"),
    }
}

/// A quantity drawn against load, read off one result.
type Quantity = fn(&WearResult) -> f64;

/// One curve against load: a material (and its varying inputs) and one fracture energy; per load,
/// the results over surface pairs.
struct Curve {
    label: String,
    points: BTreeMap<u64, (f64, Vec<WearResult>)>, // load bits → (load, results per pair)
}

impl Curve {
    /// Per load: (load, mean, min, max) of `quantity` over the surface pairs.
    fn stats(&self, quantity: Quantity) -> Vec<(f64, f64, f64, f64)> {
        self.points
            .values()
            .map(|(load, results)| {
                let v: Vec<f64> = results.iter().map(quantity).collect();
                let mean = v.iter().sum::<f64>() / v.len() as f64;
                let min = v.iter().copied().fold(f64::INFINITY, f64::min);
                let max = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                (*load, mean, min, max)
            })
            .collect()
    }
}

fn curves(jobs: &[Job], results: &[JobResult]) -> Vec<Curve> {
    let mut out: Vec<Curve> = Vec::new();
    let mut index: BTreeMap<String, usize> = BTreeMap::new();
    for (job, r) in jobs.iter().zip(results) {
        let (_, length) = units_of(job);
        let inputs: Vec<String> = job
            .varying
            .iter()
            .filter(|(k, _)| k.as_str() != "surface.seed")
            .map(|(k, v)| format!("{}={}", k.rsplit('.').next().unwrap_or(k), v))
            .collect();
        for w in &r.results {
            let d = match job.run.units {
                Units::Reduced => format!("d* = {:.4} {length}", w.critical_diameter),
                Units::Si => format!("d* = {:.2} µm", w.critical_diameter * 1e6),
            };
            let label = format!("{} {} G={:.3e}, {d}", job.material, inputs.join(" "), w.fracture_energy);
            let i = *index.entry(label.clone()).or_insert_with(|| {
                out.push(Curve {
                    label: label.clone(),
                    points: BTreeMap::new(),
                });
                out.len() - 1
            });
            out[i]
                .points
                .entry(r.load.to_bits())
                .or_insert((r.load, Vec::new()))
                .1
                .push(w.clone());
        }
    }
    out
}

/// One panel against load: mean over surface pairs with min–max bars, one series per curve.
struct LoadPanel<'a> {
    curves: &'a [Curve],
    quantity: Quantity,
    y_label: String,
    load_unit: &'a str,
    log_y: bool,
    /// A shaded range of y with its legend label (Kim et al.'s experiments).
    band: Option<(f64, f64, &'a str)>,
}

impl LoadPanel<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let all: Vec<(f64, f64, f64, f64)> = self.curves.iter().flat_map(|c| c.stats(self.quantity)).collect();
        let (x0, x1) = log_range(all.iter().map(|p| p.0)).unwrap_or((1e-4, 1e-2));
        let mut builder = ChartBuilder::on(area);
        builder
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(75)
            .caption(&self.y_label, (FONT, 16).into_font());
        let x_desc = format!("normal load F_N ({})", self.load_unit);
        if self.log_y {
            let band_values = self.band.iter().flat_map(|b| [b.0, b.1]);
            let (y0, y1) =
                log_range(all.iter().flat_map(|p| [p.1, p.2, p.3]).chain(band_values)).unwrap_or((1e-6, 1.0));
            let mut chart = builder
                .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
                .map_err(drawing)?;
            chart
                .configure_mesh()
                .x_desc(x_desc)
                .y_desc(&self.y_label)
                .y_label_formatter(&|y| format!("{y:.1e}"))
                .label_style((FONT, 13))
                .draw()
                .map_err(drawing)?;
            if let Some((lo, hi, label)) = self.band {
                let fill = RGBColor(200, 220, 240).mix(0.6);
                chart
                    .draw_series(std::iter::once(Rectangle::new([(x0, lo), (x1, hi)], fill.filled())))
                    .map_err(drawing)?
                    .label(label.to_string())
                    .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 18, y + 5)], fill.filled()));
            }
            self.draw_series(&mut chart)
        } else {
            let y1 = all.iter().map(|p| p.3).fold(0.0f64, f64::max).max(1e-12) * 1.1;
            let mut chart = builder
                .build_cartesian_2d((x0..x1).log_scale(), 0.0..y1)
                .map_err(drawing)?;
            chart
                .configure_mesh()
                .x_desc(x_desc)
                .y_desc(&self.y_label)
                .label_style((FONT, 13))
                .draw()
                .map_err(drawing)?;
            self.draw_series(&mut chart)
        }
    }

    fn draw_series<'a, DB: DrawingBackend + 'a, X, Y>(
        &self,
        chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    ) -> Result<()>
    where
        X: Ranged<ValueType = f64>,
        Y: Ranged<ValueType = f64>,
    {
        for (i, c) in self.curves.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
            let pts: Vec<(f64, f64, f64, f64)> = c
                .stats(self.quantity)
                .into_iter()
                .filter(|p| !self.log_y || p.1 > 0.0)
                .collect();
            chart
                .draw_series(LineSeries::new(pts.iter().map(|p| (p.0, p.1)), color.stroke_width(2)))
                .map_err(drawing)?
                .label(c.label.clone())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2)));
            chart
                .draw_series(pts.iter().map(|p| Circle::new((p.0, p.1), 3, color.filled())))
                .map_err(drawing)?;
            // Min–max over surface pairs.
            chart
                .draw_series(
                    pts.iter()
                        .filter(|p| !self.log_y || p.2 > 0.0)
                        .map(|p| PathElement::new(vec![(p.0, p.2), (p.0, p.3)], color.stroke_width(1))),
                )
                .map_err(drawing)?;
        }
        legend(chart, SeriesLabelPosition::UpperLeft)
    }
}

/// Panels side by side.
struct Panels<'a>(Vec<LoadPanel<'a>>);

impl Figure for Panels<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let areas = area.split_evenly((1, self.0.len()));
        for (panel, area) in self.0.iter().zip(&areas) {
            panel.draw(area)?;
        }
        Ok(())
    }
}

/// Contact severity (paper appendix F): points (material, S_c, W) and the fit W = α S_cⁿ.
struct Severity {
    points: Vec<(String, f64, f64)>,
    alpha: f64,
    n_exp: f64,
    length: &'static str,
}

impl Severity {
    /// S_c = p_N √h_rms / K_Ic with p_N = F_N/L² and K_Ic = √(𝒢 E/(1 − ν²)) for every job and
    /// fracture energy with W > 0, and the least-squares fit of ln W against ln S_c.
    fn of(jobs: &[Job], results: &[JobResult]) -> Option<Self> {
        let mut points: Vec<(String, f64, f64)> = Vec::new();
        for (job, r) in jobs.iter().zip(results) {
            let SurfaceSource::Generated { spectrum, .. } = &job.run.surfaces else {
                continue;
            };
            let m = &job.run.material;
            let p_n = r.load / (job.run.length() * job.run.length());
            for (w, wear_rate) in r
                .results
                .iter()
                .filter_map(|w| w.wear_rate.filter(|x| *x > 0.0).map(|x| (w, x)))
            {
                let k_ic = (w.fracture_energy * m.youngs_modulus / (1.0 - m.poisson_ratio * m.poisson_ratio)).sqrt();
                points.push((job.material.clone(), p_n * spectrum.rms_height.sqrt() / k_ic, wear_rate));
            }
        }
        if points.len() < 2 {
            return None;
        }
        let xs: Vec<f64> = points.iter().map(|p| p.1.ln()).collect();
        let ys: Vec<f64> = points.iter().map(|p| p.2.ln()).collect();
        let fit = wearsim::sliding::line_fit(&xs, &ys)?;
        let (n_exp, alpha) = (fit.slope, fit.intercept.exp());
        Some(Self {
            points,
            alpha,
            n_exp,
            length: units_of(&jobs[0]).1,
        })
    }
}

impl Figure for Severity {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let (alpha, n_exp, length) = (self.alpha, self.n_exp, self.length);
        let (x0, x1) = log_range(self.points.iter().map(|p| p.1)).unwrap_or((1e-3, 1.0));
        let (y0, y1) = log_range(self.points.iter().map(|p| p.2)).unwrap_or((1e-6, 1.0));
        let mut chart = ChartBuilder::on(area)
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(80)
            .caption(
                format!("contact severity: W = α S_cⁿ, α = {alpha:.3e} {length}², n = {n_exp:.3}"),
                (FONT, 15),
            )
            .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
            .map_err(drawing)?;
        chart
            .configure_mesh()
            .x_desc("S_c = p_N √h_rms / K_Ic")
            .x_label_formatter(&|x| format!("{x:.2e}"))
            .y_label_formatter(&|y| format!("{y:.1e}"))
            .y_desc(format!("wear rate W ({length}²)"))
            .label_style((FONT, 13))
            .draw()
            .map_err(drawing)?;
        let mut names: Vec<&String> = self.points.iter().map(|p| &p.0).collect();
        names.sort();
        names.dedup();
        for (i, name) in names.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
            chart
                .draw_series(
                    self.points
                        .iter()
                        .filter(|p| &p.0 == *name)
                        .map(|p| Circle::new((p.1, p.2), 3, color.filled())),
                )
                .map_err(drawing)?
                .label(name.to_string())
                .legend(move |(x, y)| Circle::new((x + 9, y), 3, color.filled()));
        }
        chart
            .draw_series(LineSeries::new(
                [(x0, alpha * x0.powf(n_exp)), (x1, alpha * x1.powf(n_exp))],
                BLACK.stroke_width(1),
            ))
            .map_err(drawing)?
            .label("fit")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], BLACK.stroke_width(1)));
        legend(&mut chart, SeriesLabelPosition::UpperLeft)
    }
}

/// A number read off one step of a job file.
type StepValue = Box<dyn Fn(&StepRow) -> f64>;

/// Series of one job: V(s) with the fitted line (Fig. 3), or N*₊, N*, N*₋ (appendix B).
struct SeriesFigure<'a> {
    job: &'a Job,
    result: &'a JobResult,
    counts: bool,
}

impl Figure for SeriesFigure<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let (job, r, counts) = (self.job, self.result, self.counts);
        let (_, length) = units_of(job);
        let sliding = job
            .run
            .sliding
            .as_ref()
            .ok_or_else(|| anyhow!("job without [sliding]"))?;
        let running_in = sliding.running_in * job.run.length();
        let s_max = r.steps.last().map(|s| s.s).unwrap_or(1.0).max(1e-300);
        let n_e = r.results.len();
        let y_max = r
            .steps
            .iter()
            .flat_map(|s| (0..n_e).map(move |e| if counts { s.n_formed[e] as f64 } else { s.volume[e] }))
            .fold(0.0f64, f64::max)
            .max(1e-300)
            * 1.1;
        let caption = if counts {
            "particles: N*₊ (formed), N* (critical now), N*₋ = N*₊ − N*"
        } else {
            "wear volume V(s)"
        };
        let mut chart = ChartBuilder::on(area)
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(80)
            .caption(format!("{caption}; F_N = {:.3e}, job {}", r.load, r.index), (FONT, 15))
            .build_cartesian_2d(0.0..s_max * 1.02, 0.0..y_max)
            .map_err(drawing)?;
        chart
            .configure_mesh()
            .x_desc(format!("sliding distance s ({length})"))
            .y_desc(if counts {
                "count".to_string()
            } else {
                format!("V ({length}³)")
            })
            .label_style((FONT, 13))
            .draw()
            .map_err(drawing)?;
        // Running-in region.
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(0.0, 0.0), (running_in, y_max)],
                RGBColor(230, 230, 230).filled(),
            )))
            .map_err(drawing)?
            .label("running-in")
            .legend(|(x, y)| Rectangle::new([(x, y - 5), (x + 18, y + 5)], RGBColor(230, 230, 230).filled()));
        for (e, w) in r.results.iter().enumerate() {
            let color = Palette99::pick(e).to_rgba();
            let d = format!("d* = {:.3e} {length}", w.critical_diameter);
            if counts {
                let styles: [(&str, StepValue); 3] = [
                    ("N*₊", Box::new(move |s| s.n_formed[e] as f64)),
                    ("N*", Box::new(move |s| s.n_critical[e] as f64)),
                    ("N*₋", Box::new(move |s| s.n_formed[e] as f64 - s.n_critical[e] as f64)),
                ];
                for (k, (name, f)) in styles.iter().enumerate() {
                    let c = color.mix(1.0 - 0.3 * k as f64);
                    chart
                        .draw_series(LineSeries::new(
                            r.steps.iter().map(|s| (s.s, f(s))),
                            c.stroke_width(2 - (k as u32).min(1)),
                        ))
                        .map_err(drawing)?
                        .label(format!("{name}, {d}"))
                        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], c.stroke_width(2)));
                }
            } else {
                chart
                    .draw_series(LineSeries::new(
                        r.steps.iter().map(|s| (s.s, s.volume[e])),
                        color.stroke_width(2),
                    ))
                    .map_err(drawing)?
                    .label(format!("V, {d}"))
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2)));
                // Fitted line W·s + b over s ≥ running-in (least squares, as in the results).
                let fit: Vec<(f64, f64)> = r
                    .steps
                    .iter()
                    .filter(|s| s.s >= running_in - 1e-12)
                    .map(|s| (s.s, s.volume[e]))
                    .collect();
                if fit.len() >= 2 {
                    let m = fit.len() as f64;
                    let (mx, my) = (
                        fit.iter().map(|p| p.0).sum::<f64>() / m,
                        fit.iter().map(|p| p.1).sum::<f64>() / m,
                    );
                    let Some(wear_rate) = w.wear_rate else { continue };
                    let b = my - wear_rate * mx;
                    chart
                        .draw_series(LineSeries::new(
                            [(0.0, b), (s_max, b + wear_rate * s_max)],
                            BLACK.stroke_width(1),
                        ))
                        .map_err(drawing)?
                        .label(format!(
                            "fit: W = {wear_rate:.3e} (R² = {})",
                            w.wear_rate_r2.map_or("undefined".into(), |r2| format!("{r2:.3}"))
                        ))
                        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], BLACK.stroke_width(1)));
                }
            }
        }
        legend(&mut chart, SeriesLabelPosition::LowerRight)
    }
}

pub fn run(args: &Args) -> Result<()> {
    let dir = &args.dir;
    let (study, results) = load_results(dir).with_context(|| format!("study folder {}", dir.display()))?;
    let first = study.jobs.first().ok_or_else(|| anyhow!("the study has no jobs"))?;
    let (load_unit, length) = units_of(first);
    let figures = wearsim::io::OutputDir::begin(&dir.join("figures"), "study plot", false)?;
    let out = figures.join("");
    let curves = curves(&study.jobs, &results);
    let area_unit = format!("{length}²");
    let panel = |quantity: Quantity, y_label: String, log_y: bool| LoadPanel {
        curves: &curves,
        quantity,
        y_label,
        load_unit,
        log_y,
        band: None,
    };
    save(
        &out,
        "fig2_static_model",
        (1500, 600),
        &Panels(vec![
            panel(
                |w| w.static_wear_rate,
                format!("static wear rate W/ω ({area_unit})"),
                true,
            ),
            panel(|w| w.static_wear_coefficient, "static wear coefficient k".into(), false),
        ]),
    )?;
    save(
        &out,
        "fig4_sliding_wear",
        (1500, 600),
        &Panels(vec![
            panel(
                |w| w.wear_rate.unwrap_or(f64::NAN),
                format!("sliding wear rate W ({area_unit})"),
                true,
            ),
            panel(
                |w| w.wear_coefficient.unwrap_or(f64::NAN),
                "wear coefficient k = W p̃ / F_N".into(),
                true,
            ),
        ]),
    )?;
    save(
        &out,
        "fig5_particle_rate",
        (800, 600),
        &Panels(vec![panel(
            |w| w.particle_rate.unwrap_or(f64::NAN),
            format!("particle rate dN*₊/ds (1/{length})"),
            true,
        )]),
    )?;
    if let Some(severity) = Severity::of(&study.jobs, &results) {
        save(&out, "appF_contact_severity", (900, 600), &severity)?;
        println!(
            "contact severity fit: W = α S_cⁿ with α = {:.4e} {length}², n = {:.3}",
            severity.alpha, severity.n_exp
        );
    }
    // Kim et al. (1986): rolling wear coefficients 6e-7 … 1.5e-3 (paper §4.3, Fig. 6). k is
    // dimensionless, so the comparison is drawn for studies in any units.
    let mut kim = panel(
        |w| w.wear_coefficient.unwrap_or(f64::NAN),
        "wear coefficient k".into(),
        true,
    );
    kim.band = Some((6e-7, 1.5e-3, "Kim et al. 1986, rolling experiments"));
    save(&out, "fig6_kim_comparison", (900, 600), &Panels(vec![kim]))?;
    // Series of one representative job: the first surface pair, the middle load, the first material.
    let mut loads: Vec<f64> = results.iter().map(|r| r.load).collect();
    loads.sort_by(f64::total_cmp);
    loads.dedup();
    let mid = loads[loads.len() / 2];
    let (job, result) = study
        .jobs
        .iter()
        .zip(&results)
        .find(|(_, r)| r.load == mid)
        .ok_or_else(|| anyhow!("no job at the middle load"))?;
    save(
        &out,
        "fig3_wear_volume",
        (900, 600),
        &SeriesFigure {
            job,
            result,
            counts: false,
        },
    )?;
    save(
        &out,
        "appB_particle_counts",
        (900, 600),
        &SeriesFigure {
            job,
            result,
            counts: true,
        },
    )?;
    figures.commit()?;
    println!("wrote figures to {}", dir.join("figures").display());
    Ok(())
}
