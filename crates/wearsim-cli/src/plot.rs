//! `wearsim study plot DIR`: figures of a finished study, as PNG and SVG, in the layout of the paper
//! (Brink, Frérot & Molinari 2021): static wear rate and k against F_N (Fig. 2), V(s) with its fitted
//! line and the running-in region (Fig. 3), sliding wear rate and k against F_N with min–max bars over
//! surface pairs (Fig. 4), dN*₊/ds against F_N (Fig. 5), and N*₊, N*, N*₋ against s (appendix B).
//! Plotting is a front-end concern and stays out of the library; the text is drawn with the DejaVu
//! Sans font shipped in `assets/`, so no system font is needed.

use std::collections::BTreeMap;
use std::path::Path;

use anyhow::{anyhow, Context, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use wearsim::config::Units;
use wearsim::study::{load_results, Job, JobResult};

const FONT: &str = "sans-serif";

fn register_font() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        plotters::style::register_font(FONT, FontStyle::Normal, include_bytes!("../assets/DejaVuSans.ttf"))
            .map_err(|_| ())
            .expect("the bundled font is valid");
    });
}

/// One curve against load: a material (and its varying inputs) and one fracture energy; per load,
/// the values over surface pairs.
struct Curve {
    label: String,
    points: BTreeMap<u64, (f64, Vec<[f64; 5]>)>, // load bits → (load, [W_static/ω, k_static, W, k, dN/ds] per pair)
}

fn units_of(job: &Job) -> (Units, &'static str, &'static str) {
    match job.run.units {
        Units::Reduced => (Units::Reduced, "E L²", "L"),
        Units::Si => (Units::Si, "N", "m"),
    }
}

fn curves(jobs: &[Job], results: &[JobResult]) -> Vec<Curve> {
    let mut out: Vec<Curve> = Vec::new();
    let mut index: BTreeMap<String, usize> = BTreeMap::new();
    for (job, r) in jobs.iter().zip(results) {
        let (units, _, length) = units_of(job);
        let inputs: Vec<String> = job
            .varying
            .iter()
            .filter(|(k, _)| k.as_str() != "surface.seed")
            .map(|(k, v)| format!("{}={}", k.rsplit('.').next().unwrap_or(k), v))
            .collect();
        for w in &r.results {
            let d = match units {
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
                .push([
                    w.static_wear_rate,
                    w.static_wear_coefficient,
                    w.wear_rate,
                    w.wear_coefficient,
                    w.particle_rate,
                ]);
        }
    }
    out
}

fn log_range(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(a, b), v| (a.min(v), b.max(v)));
    (hi > 0.0).then(|| (lo / 1.5, hi * 1.5))
}

/// Draws one panel: mean over surface pairs against load with min–max bars, one series per curve.
fn panel(
    area: &DrawingArea<impl DrawingBackend, Shift>,
    curves: &[Curve],
    column: usize,
    y_label: &str,
    load_unit: &str,
    log_y: bool,
    band: Option<(f64, f64, &str)>,
) -> Result<()> {
    let err = |e: String| anyhow!("drawing failed: {e}");
    let stats = |c: &Curve| -> Vec<(f64, f64, f64, f64)> {
        c.points
            .values()
            .map(|(load, vals)| {
                let v: Vec<f64> = vals.iter().map(|x| x[column]).collect();
                let mean = v.iter().sum::<f64>() / v.len() as f64;
                let min = v.iter().copied().fold(f64::INFINITY, f64::min);
                let max = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                (*load, mean, min, max)
            })
            .collect()
    };
    let all: Vec<(f64, f64, f64, f64)> = curves.iter().flat_map(stats).collect();
    let (x0, x1) = log_range(all.iter().map(|p| p.0)).unwrap_or((1e-4, 1e-2));
    let title_style = (FONT, 16).into_font();
    let mut builder = ChartBuilder::on(area);
    builder
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(75)
        .caption(y_label, title_style);
    let x_desc = format!("normal load F_N ({load_unit})");
    if log_y {
        let band_values = band.iter().flat_map(|b| [b.0, b.1]);
        let (y0, y1) = log_range(all.iter().flat_map(|p| [p.1, p.2, p.3]).chain(band_values)).unwrap_or((1e-6, 1.0));
        let mut chart = builder
            .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
            .map_err(|e| err(e.to_string()))?;
        chart
            .configure_mesh()
            .x_desc(x_desc)
            .y_desc(y_label)
            .y_label_formatter(&|y| format!("{y:.1e}"))
            .label_style((FONT, 13))
            .draw()
            .map_err(|e| err(e.to_string()))?;
        if let Some((lo, hi, label)) = band {
            let fill = RGBColor(200, 220, 240).mix(0.6);
            chart
                .draw_series(std::iter::once(Rectangle::new([(x0, lo), (x1, hi)], fill.filled())))
                .map_err(|e| err(e.to_string()))?
                .label(label.to_string())
                .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 18, y + 5)], fill.filled()));
        }
        draw_series(&mut chart, curves, &stats, true)?;
    } else {
        let y1 = all.iter().map(|p| p.3).fold(0.0f64, f64::max).max(1e-12) * 1.1;
        let mut chart = builder
            .build_cartesian_2d((x0..x1).log_scale(), 0.0..y1)
            .map_err(|e| err(e.to_string()))?;
        chart
            .configure_mesh()
            .x_desc(x_desc)
            .y_desc(y_label)
            .label_style((FONT, 13))
            .draw()
            .map_err(|e| err(e.to_string()))?;
        draw_series(&mut chart, curves, &stats, false)?;
    }
    Ok(())
}

fn draw_series<'a, DB: DrawingBackend + 'a, X, Y>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    curves: &[Curve],
    stats: &dyn Fn(&Curve) -> Vec<(f64, f64, f64, f64)>,
    log_y: bool,
) -> Result<()>
where
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    let err = |e: String| anyhow!("drawing failed: {e}");
    for (i, c) in curves.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        let pts: Vec<(f64, f64, f64, f64)> = stats(c).into_iter().filter(|p| !log_y || p.1 > 0.0).collect();
        chart
            .draw_series(LineSeries::new(pts.iter().map(|p| (p.0, p.1)), color.stroke_width(2)))
            .map_err(|e| err(e.to_string()))?
            .label(c.label.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2)));
        chart
            .draw_series(pts.iter().map(|p| Circle::new((p.0, p.1), 3, color.filled())))
            .map_err(|e| err(e.to_string()))?;
        // Min–max over surface pairs.
        chart
            .draw_series(
                pts.iter()
                    .filter(|p| !log_y || p.2 > 0.0)
                    .map(|p| PathElement::new(vec![(p.0, p.2), (p.0, p.3)], color.stroke_width(1))),
            )
            .map_err(|e| err(e.to_string()))?;
    }
    legend(chart, SeriesLabelPosition::UpperLeft)?;
    Ok(())
}

/// The legend box of every figure.
fn legend<'a, DB: DrawingBackend + 'a, X: Ranged, Y: Ranged>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    position: SeriesLabelPosition,
) -> Result<()> {
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font((FONT, 11))
        .position(position)
        .draw()
        .map_err(|e| anyhow!("drawing failed: {e}"))
}

/// Draws `figure` into `name.png` and `name.svg`.
fn save(
    dir: &Path,
    name: &str,
    size: (u32, u32),
    figure: impl Fn(&DrawingArea<SVGBackend, Shift>) -> Result<()>,
    figure_png: impl Fn(&DrawingArea<BitMapBackend, Shift>) -> Result<()>,
) -> Result<()> {
    let svg = dir.join(format!("{name}.svg"));
    let png = dir.join(format!("{name}.png"));
    let tmp_svg = dir.join(format!(".{name}.svg.tmp"));
    let tmp_png = dir.join(format!(".{name}.tmp.png"));
    {
        let root = SVGBackend::new(&tmp_svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
        figure(&root)?;
        root.present().map_err(|e| anyhow!("{e}"))?;
    }
    {
        let root = BitMapBackend::new(&tmp_png, size).into_drawing_area();
        root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
        figure_png(&root)?;
        root.present().map_err(|e| anyhow!("{e}"))?;
    }
    std::fs::rename(&tmp_svg, &svg)?;
    std::fs::rename(&tmp_png, &png)?;
    Ok(())
}

/// Contact severity (paper appendix F): S_c = p_N √h_rms / K_Ic with p_N = F_N/L² and
/// K_Ic = √(𝒢 E/(1 − ν²)); fits W = α S_cⁿ by least squares in log–log over every job and fracture
/// energy with W > 0, and draws the points with the fitted line. Returns (α, n).
fn severity_figure(out: &Path, jobs: &[Job], results: &[JobResult]) -> Result<Option<(f64, f64)>> {
    use wearsim::config::SurfaceSource;
    let mut points: Vec<(String, f64, f64)> = Vec::new();
    for (job, r) in jobs.iter().zip(results) {
        let SurfaceSource::Generated { spectrum, .. } = &job.run.surfaces else {
            continue;
        };
        let m = &job.run.material;
        let p_n = r.load / (job.run.length() * job.run.length());
        for w in r.results.iter().filter(|w| w.wear_rate > 0.0) {
            let k_ic = (w.fracture_energy * m.youngs_modulus / (1.0 - m.poisson_ratio * m.poisson_ratio)).sqrt();
            points.push((
                job.material.clone(),
                p_n * spectrum.rms_height.sqrt() / k_ic,
                w.wear_rate,
            ));
        }
    }
    if points.len() < 2 {
        return Ok(None);
    }
    let xs: Vec<f64> = points.iter().map(|p| p.1.ln()).collect();
    let ys: Vec<f64> = points.iter().map(|p| p.2.ln()).collect();
    let (n_exp, _) = wearsim::sliding::line_fit(&xs, &ys);
    let m = xs.len() as f64;
    let alpha = ((ys.iter().sum::<f64>() - n_exp * xs.iter().sum::<f64>()) / m).exp();
    let length = units_of(&jobs[0]).2;
    let svg = |root: &DrawingArea<SVGBackend, Shift>| draw_severity(root, &points, alpha, n_exp, length);
    let png = |root: &DrawingArea<BitMapBackend, Shift>| draw_severity(root, &points, alpha, n_exp, length);
    save(out, "appF_contact_severity", (900, 600), svg, png)?;
    println!("contact severity fit: W = α S_cⁿ with α = {alpha:.4e} {length}², n = {n_exp:.3}");
    Ok(Some((alpha, n_exp)))
}

fn draw_severity(
    area: &DrawingArea<impl DrawingBackend, Shift>,
    points: &[(String, f64, f64)],
    alpha: f64,
    n_exp: f64,
    length: &str,
) -> Result<()> {
    let err = |e: String| anyhow!("drawing failed: {e}");
    let (x0, x1) = log_range(points.iter().map(|p| p.1)).unwrap_or((1e-3, 1.0));
    let (y0, y1) = log_range(points.iter().map(|p| p.2)).unwrap_or((1e-6, 1.0));
    let mut chart = ChartBuilder::on(area)
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(80)
        .caption(
            format!("contact severity: W = α S_cⁿ, α = {alpha:.3e} {length}², n = {n_exp:.3}"),
            (FONT, 15),
        )
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
        .map_err(|e| err(e.to_string()))?;
    chart
        .configure_mesh()
        .x_desc("S_c = p_N √h_rms / K_Ic")
        .x_label_formatter(&|x| format!("{x:.2e}"))
        .y_label_formatter(&|y| format!("{y:.1e}"))
        .y_desc(format!("wear rate W ({length}²)"))
        .label_style((FONT, 13))
        .draw()
        .map_err(|e| err(e.to_string()))?;
    let mut names: Vec<&String> = points.iter().map(|p| &p.0).collect();
    names.sort();
    names.dedup();
    for (i, name) in names.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        chart
            .draw_series(
                points
                    .iter()
                    .filter(|p| &p.0 == *name)
                    .map(|p| Circle::new((p.1, p.2), 3, color.filled())),
            )
            .map_err(|e| err(e.to_string()))?
            .label(name.to_string())
            .legend(move |(x, y)| Circle::new((x + 9, y), 3, color.filled()));
    }
    chart
        .draw_series(LineSeries::new(
            [(x0, alpha * x0.powf(n_exp)), (x1, alpha * x1.powf(n_exp))],
            BLACK.stroke_width(1),
        ))
        .map_err(|e| err(e.to_string()))?
        .label("fit")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], BLACK.stroke_width(1)));
    legend(&mut chart, SeriesLabelPosition::UpperLeft)?;
    Ok(())
}

/// Series panels of one job: V(s) with the fitted line (Fig. 3), or N*₊, N*, N*₋ (appendix B).
fn series_panel(area: &DrawingArea<impl DrawingBackend, Shift>, job: &Job, r: &JobResult, counts: bool) -> Result<()> {
    let err = |e: String| anyhow!("drawing failed: {e}");
    let (_, _, length) = units_of(job);
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
        .map_err(|e| err(e.to_string()))?;
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
        .map_err(|e| err(e.to_string()))?;
    // Running-in region.
    chart
        .draw_series(std::iter::once(Rectangle::new(
            [(0.0, 0.0), (running_in, y_max)],
            RGBColor(230, 230, 230).filled(),
        )))
        .map_err(|e| err(e.to_string()))?
        .label("running-in")
        .legend(|(x, y)| Rectangle::new([(x, y - 5), (x + 18, y + 5)], RGBColor(230, 230, 230).filled()));
    for (e, w) in r.results.iter().enumerate() {
        let color = Palette99::pick(e).to_rgba();
        let d = format!("d* = {:.3e} {length}", w.critical_diameter);
        if counts {
            let styles: [(&str, Box<dyn Fn(&wearsim::study::StepRow) -> f64>); 3] = [
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
                    .map_err(|er| err(er.to_string()))?
                    .label(format!("{name}, {d}"))
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], c.stroke_width(2)));
            }
        } else {
            chart
                .draw_series(LineSeries::new(
                    r.steps.iter().map(|s| (s.s, s.volume[e])),
                    color.stroke_width(2),
                ))
                .map_err(|er| err(er.to_string()))?
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
                let b = my - w.wear_rate * mx;
                chart
                    .draw_series(LineSeries::new(
                        [(0.0, b), (s_max, b + w.wear_rate * s_max)],
                        BLACK.stroke_width(1),
                    ))
                    .map_err(|er| err(er.to_string()))?
                    .label(format!("fit: W = {:.3e} (R² = {:.3})", w.wear_rate, w.wear_rate_r2))
                    .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], BLACK.stroke_width(1)));
            }
        }
    }
    legend(&mut chart, SeriesLabelPosition::LowerRight)?;
    Ok(())
}

pub fn plot(dir: &Path) -> Result<()> {
    register_font();
    let (study, results) = load_results(dir).with_context(|| format!("study folder {}", dir.display()))?;
    let first = study.jobs.first().ok_or_else(|| anyhow!("the study has no jobs"))?;
    let (_, load_unit, length) = units_of(first);
    let out = dir.join("figures");
    std::fs::create_dir_all(&out)?;
    let curves = curves(&study.jobs, &results);
    let area_unit = format!("{length}²");
    let two = |name: &str, a: (usize, String, bool), b: (usize, String, bool)| -> Result<()> {
        let draw_svg = |root: &DrawingArea<SVGBackend, Shift>| -> Result<()> {
            let panels = root.split_evenly((1, 2));
            panel(&panels[0], &curves, a.0, &a.1, load_unit, a.2, None)?;
            panel(&panels[1], &curves, b.0, &b.1, load_unit, b.2, None)
        };
        let draw_png = |root: &DrawingArea<BitMapBackend, Shift>| -> Result<()> {
            let panels = root.split_evenly((1, 2));
            panel(&panels[0], &curves, a.0, &a.1, load_unit, a.2, None)?;
            panel(&panels[1], &curves, b.0, &b.1, load_unit, b.2, None)
        };
        save(&out, name, (1500, 600), draw_svg, draw_png)
    };
    two(
        "fig2_static_model",
        (0, format!("static wear rate W/ω ({area_unit})"), true),
        (1, "static wear coefficient k".into(), false),
    )?;
    two(
        "fig4_sliding_wear",
        (2, format!("sliding wear rate W ({area_unit})"), true),
        (3, "wear coefficient k = W p̃ / F_N".into(), true),
    )?;
    {
        let svg = |root: &DrawingArea<SVGBackend, Shift>| {
            panel(
                root,
                &curves,
                4,
                &format!("particle rate dN*₊/ds (1/{length})"),
                load_unit,
                true,
                None,
            )
        };
        let png = |root: &DrawingArea<BitMapBackend, Shift>| {
            panel(
                root,
                &curves,
                4,
                &format!("particle rate dN*₊/ds (1/{length})"),
                load_unit,
                true,
                None,
            )
        };
        save(&out, "fig5_particle_rate", (800, 600), svg, png)?;
    }
    severity_figure(&out, &study.jobs, &results)?;
    {
        // Kim et al. (1986): rolling wear coefficients 6e-7 … 1.5e-3 (paper §4.3, Fig. 6). k is
        // dimensionless, so the comparison is drawn for studies in any units.
        let band = Some((6e-7, 1.5e-3, "Kim et al. 1986, rolling experiments"));
        let svg = |root: &DrawingArea<SVGBackend, Shift>| {
            panel(root, &curves, 3, "wear coefficient k", load_unit, true, band)
        };
        let png = |root: &DrawingArea<BitMapBackend, Shift>| {
            panel(root, &curves, 3, "wear coefficient k", load_unit, true, band)
        };
        save(&out, "fig6_kim_comparison", (900, 600), svg, png)?;
    }
    // Series of one representative job: the first surface pair, the middle load, the first material.
    let loads: Vec<f64> = {
        let mut l: Vec<f64> = results.iter().map(|r| r.load).collect();
        l.sort_by(f64::total_cmp);
        l.dedup();
        l
    };
    let mid = loads[loads.len() / 2];
    let (job, r) = study
        .jobs
        .iter()
        .zip(&results)
        .find(|(_, r)| r.load == mid)
        .ok_or_else(|| anyhow!("no job at the middle load"))?;
    save(
        &out,
        "fig3_wear_volume",
        (900, 600),
        |root| series_panel(root, job, r, false),
        |root| series_panel(root, job, r, false),
    )?;
    save(
        &out,
        "appB_particle_counts",
        (900, 600),
        |root| series_panel(root, job, r, true),
        |root| series_panel(root, job, r, true),
    )?;
    println!("wrote figures to {}", out.display());
    Ok(())
}

/// `wearsim animate`: the sliding run of one load as an animated GIF, like the paper's Video 1. Each
/// frame is the contact map of one step, junctions coloured by their state for one fracture energy:
/// grey below d*, red forming a particle now, orange at or above d* but disabled (its particle is
/// already counted), blue disabled below d*; s and V are written on the frame.
pub fn animate(run: &Path, out: &Path, load_index: usize, energy_index: usize, delay_ms: u32) -> Result<()> {
    use wearsim::config::RunConfig;
    use wearsim::junctions::NO_JUNCTION;
    use wearsim::sliding::{run_sliding, SlidingSetup};
    use wearsim::wear::JunctionState;
    register_font();
    let config = RunConfig::from_path(run).with_context(|| format!("run file {}", run.display()))?;
    let mut sliding = config
        .sliding
        .clone()
        .ok_or_else(|| anyhow!("run file {}: a [sliding] table is needed", run.display()))?;
    let load = *sliding.loads.get(load_index).ok_or_else(|| {
        anyhow!(
            "invalid `--load-index {load_index}`: the run has {} loads",
            sliding.loads.len()
        )
    })?;
    sliding.loads = vec![load];
    if energy_index >= config.material.fracture_energies.len() {
        anyhow::bail!(
            "invalid `--energy-index {energy_index}`: the run has {} fracture energies",
            config.material.fracture_energies.len()
        );
    }
    if out.extension().and_then(|e| e.to_str()) != Some("gif") {
        anyhow::bail!("invalid `--out {}`: the animation is a .gif file", out.display());
    }
    let (top, bottom) = config.surfaces()?;
    let n = top.n();
    let scale = (512 / n).max(1) as u32; // frames of at least 512 px where the grid is smaller
    let step_px = (n / 512).max(1); // and at most about 1024 px where it is larger
    let side = (n / step_px) as u32 * scale;
    let setup = SlidingSetup::from_run(&config, &sliding);
    let d_star = config
        .material
        .critical_diameter(config.material.fracture_energies[energy_index]);
    let tmp = out.with_extension("tmp.gif");
    let length_unit = config.units.length_unit();
    let mut frame_error: Option<anyhow::Error> = None;
    {
        let root = BitMapBackend::gif(&tmp, (side, side + 40), delay_ms)
            .map_err(|e| anyhow!("cannot write {}: {e}", tmp.display()))?
            .into_drawing_area();
        run_sliding(&top, &bottom, &setup, |view| {
            if frame_error.is_some() {
                return;
            }
            let draw = || -> Result<()> {
                root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
                let labels = view.labeller.labels();
                let states = view.bookkeeping[energy_index].states();
                for i in (0..n).step_by(step_px) {
                    for j in (0..n).step_by(step_px) {
                        let l = labels[i * n + j];
                        if l == NO_JUNCTION {
                            continue;
                        }
                        let color = match states[l as usize] {
                            JunctionState::Below => RGBColor(150, 150, 150),
                            JunctionState::Forming => RGBColor(220, 30, 30),
                            JunctionState::DisabledCritical => RGBColor(245, 150, 20),
                            JunctionState::Disabled => RGBColor(40, 90, 200),
                        };
                        // x (first axis, the sliding direction) runs left to right.
                        let (x, y) = (
                            (i / step_px) as i32 * scale as i32,
                            (j / step_px) as i32 * scale as i32 + 40,
                        );
                        root.draw(&Rectangle::new(
                            [(x, y), (x + scale as i32, y + scale as i32)],
                            color.filled(),
                        ))
                        .map_err(|e| anyhow!("{e}"))?;
                    }
                }
                let w = view.record.wear[energy_index];
                let font = (FONT, 13).into_font().color(&BLACK);
                root.draw_text(
                    &format!(
                        "s = {:.4} {length_unit}   V = {:.3e}   N*₊ = {}   d* = {:.3e} {length_unit}",
                        view.record.s, w.volume, w.n_formed, d_star
                    ),
                    &font,
                    (6, 4),
                )
                .map_err(|e| anyhow!("{e}"))?;
                root.draw_text(
                    "grey: below d*   red: forming a particle   orange: disabled, ≥ d*   blue: disabled",
                    &font,
                    (6, 22),
                )
                .map_err(|e| anyhow!("{e}"))?;
                root.present().map_err(|e| anyhow!("{e}"))
            };
            if let Err(e) = draw() {
                frame_error = Some(e);
            }
        })?;
    }
    if let Some(e) = frame_error {
        let _ = std::fs::remove_file(&tmp);
        return Err(e);
    }
    std::fs::rename(&tmp, out)?;
    println!("wrote {}", out.display());
    Ok(())
}
