//! `wearsim study plot DIR`: the figures of a finished study, as PNG and SVG in `DIR/figures`, in the
//! layout of the paper (Brink, Frérot & Molinari 2021), and the paper's findings judged on the study
//! (`findings.md`, also printed). The figures are the entries of one registry, [`FIGURES`] (name,
//! what it shows, how it is drawn); `--figures` takes their names and `--help` lists them. By
//! family: [`load`] (quantities against load), [`series`] (against the sliding distance),
//! [`severity`] (appendix F); [`data`] loads the study.

mod data;
mod load;
mod series;
mod severity;

use std::path::{Path, PathBuf};

use anyhow::{Context as _, Result};
use wearsim::output::{has_kim_materials, severity_fits, KIM_EXPERIMENTAL_K};
use wearsim::study::findings::{findings, markdown};
use wearsim::study::{load_results, Job};

use crate::figures::{number, save, write_into, Figure};
use crate::out::say;

use data::{equal_d_star, series_job, Data};
use load::{Eq5Figure, LoadFigure, LoadPanel};
use series::{CountsFigure, MemoryFigure, VolumeFigure};
use severity::{Note, Severity};

#[derive(clap::Args)]
pub struct Args {
    /// Study folder.
    dir: PathBuf,
    /// The job whose series fig3, appB and memory show (its index, as in results.csv; default: the
    /// job that formed the most particles after running-in, the lowest index among equals); the
    /// memory figure shows every surface pair of its setting.
    #[arg(long)]
    job: Option<usize>,
    /// Figures to draw, comma-separated (default: all).
    #[arg(long, value_delimiter = ',', value_parser = figure_names())]
    figures: Option<Vec<String>>,
}

/// What every figure is drawn from: the study, the job whose series are shown, and the folder the
/// files go to.
struct Context<'a> {
    data: &'a Data,
    series: (&'a Job, &'a wearsim::output::JobResult),
    out: &'a Path,
    /// The folder the figures end up in (`out` is its temporary stand-in until the end).
    shown: &'a Path,
}

impl<'a> Context<'a> {
    /// Quantities against load for every curve of the study, one panel each.
    fn by_load(&self, panels: Vec<LoadPanel>, fitted: bool, title: &str) -> LoadFigure<'a> {
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
        save(self.out, self.shown, name, size, figure)
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
        about: "static model over every offset: W_static/ω per unit area and k_static against p_N (paper Fig. 2)",
        draw: fig2,
    },
    Plot {
        name: "fig3",
        about: "V(s) of one job with the fitted lines and the running-in region (Fig. 3)",
        draw: fig3,
    },
    Plot {
        name: "fig4",
        about: "sliding W per unit area and k against p_N, 95 % intervals over surface pairs (Fig. 4)",
        draw: fig4,
    },
    Plot {
        name: "fig4c",
        about: "W, k and dN*₊/ds for settings of (nearly) equal d* (Figs. 4c, 5c)",
        draw: fig4c,
    },
    Plot {
        name: "fig5",
        about: "dN*₊/ds per unit area against p_N (Fig. 5)",
        draw: fig5,
    },
    Plot {
        name: "fig6",
        about: "k against p_N per material, beside Kim et al.'s experimental range for Kim's ceramics (Fig. 6)",
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
        about: "the contact-severity fits W = α S_cⁿ per material and over all (appendix F)",
        draw: app_f,
    },
    Plot {
        name: "memory",
        about: "the memory of the initial contact N₀(s) of every surface pair of one setting, with fits (§3)",
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

/// Sizes of figures of two panels and of one.
const WIDE: (u32, u32) = (1700, 640);
const NARROW: (u32, u32) = (1150, 640);

fn fig2(cx: &Context) -> Result<()> {
    let u = cx.data.units;
    let fig = cx.by_load(
        vec![
            LoadPanel::per_area("static_wear_rate_mean", "W_static/ω", u, true),
            LoadPanel::new(
                "static_wear_coefficient_mean",
                "static wear coefficient k_static",
                false,
            ),
        ],
        false,
        "static model, mean over every offset (the paper's Fig. 2 rows: 𝒢 varied, τ̃ varied)",
    );
    cx.save("fig2_static_model", WIDE, &fig)
}

fn fig4(cx: &Context) -> Result<()> {
    let u = cx.data.units;
    let fig = cx.by_load(
        vec![
            LoadPanel::per_area("wear_rate", "sliding wear rate W = dV/ds", u, true),
            LoadPanel::new("wear_coefficient", "wear coefficient k = W p_m / F_N", true),
        ],
        true,
        "sliding model (the paper's Fig. 4 rows: W, k); curves labelled \"static estimate\" are the estimate",
    );
    cx.save("fig4_sliding_wear", WIDE, &fig)
}

fn fig5(cx: &Context) -> Result<()> {
    let fig = cx.by_load(
        vec![LoadPanel::per_area(
            "particle_rate",
            "particle rate dN*₊/ds",
            cx.data.units,
            true,
        )],
        true,
        "wear particles emitted per sliding distance",
    );
    cx.save("fig5_particle_rate", NARROW, &fig)
}

fn fig4c(cx: &Context) -> Result<()> {
    let u = cx.data.units;
    let groups = equal_d_star(&cx.data.curves);
    if groups.is_empty() {
        let note = "Fig. 4c compares settings of equal d* (within 15 %) with different τ̃ or 𝒢; this study has none";
        say!("fig4c: {note}");
        cx.save("fig4c_constant_d_star", NARROW, &Note(note))?;
    }
    for (g, group) in groups.iter().enumerate() {
        let fig = LoadFigure {
            curves: group.clone(),
            panels: vec![
                LoadPanel::per_area("wear_rate", "W", u, true),
                LoadPanel::new("wear_coefficient", "k = W p_m / F_N", true),
                LoadPanel::per_area("particle_rate", "dN*₊/ds", u, true),
            ],
            fitted: true,
            title: format!(
                "settings of nearly equal d* ≈ {}",
                u.show_length(group[0].critical_diameter)
            ),
            ..cx.by_load(Vec::new(), true, "")
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
    // Kim et al. (1986): rolling wear coefficients 6e-7 … 1.5e-3 (paper §4.2, Fig. 6c), drawn only
    // for a study of Kim's ceramics (properties of the paper's Table 1).
    let kim = has_kim_materials(&cx.data.tidy);
    let band = kim.then_some((
        KIM_EXPERIMENTAL_K.0,
        KIM_EXPERIMENTAL_K.1,
        "Kim et al. 1986, rolling experiments: k = 6×10⁻⁷ … 1.5×10⁻³",
    ));
    let title = if kim {
        "simulated sliding k per material against the experimental range"
    } else {
        "sliding k per material (no material of Kim et al.'s Table 1 here: no experimental band)"
    };
    let fig = LoadFigure {
        band,
        // One colour and marker per material where the study has several (Kim et al.'s ceramics).
        by_material: cx.data.materials.len() > 1,
        ..cx.by_load(
            vec![LoadPanel::new("wear_coefficient", "wear coefficient k", true)],
            true,
            title,
        )
    };
    cx.save("fig6_kim_comparison", NARROW, &fig)
}

fn app_c(cx: &Context) -> Result<()> {
    let fig = LoadFigure {
        curves: cx.data.curves.iter().filter(|c| c.energy == 0).collect(),
        ..cx.by_load(
            vec![LoadPanel::new(
                "junctions_mean",
                "junctions N (mean after running-in)",
                true,
            )],
            false,
            "number of junctions",
        )
    };
    let critical = cx.by_load(
        vec![LoadPanel::new(
            "critical_junctions_mean",
            "junctions ≥ d*, N* (mean after running-in)",
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
    let (materials, all) = severity_fits(&cx.data.tidy);
    let Some(all) = all else {
        say!("appF: fewer than two jobs with W > 0 on generated surfaces; not drawn");
        return Ok(());
    };
    for m in &materials {
        if let Some(fit) = m.fit {
            say!(
                "contact severity fit, {}: W = α S_cⁿ with α = {} {}, n = {:.3}",
                m.material,
                number(fit.prefactor),
                cx.data.units.area(),
                fit.exponent
            );
        }
    }
    let figure = Severity {
        materials,
        all,
        units: cx.data.units,
    };
    cx.save("appF_contact_severity", NARROW, &figure)
}

/// What the figures of one job's sliding series draw instead when that job is a static estimate.
const NO_SERIES: &str = "this job is a static estimate: it takes no sliding step, so it has no wear-volume curve, \
particle counts or memory of the initial contact (those are the sliding model's; `--job` picks a sliding job)";

fn fig3(cx: &Context) -> Result<()> {
    let (job, result) = cx.series;
    if result.steps.is_empty() {
        return cx.save("fig3_wear_volume", NARROW, &Note(NO_SERIES));
    }
    let fig = VolumeFigure {
        job,
        result,
        units: cx.data.units,
    };
    cx.save("fig3_wear_volume", (1400, 640), &fig)
}

fn app_b(cx: &Context) -> Result<()> {
    let (job, result) = cx.series;
    if result.steps.is_empty() {
        return cx.save("appB_particle_counts", NARROW, &Note(NO_SERIES));
    }
    let fig = CountsFigure {
        job,
        result,
        units: cx.data.units,
    };
    cx.save("appB_particle_counts", (1400, 640), &fig)
}

fn memory(cx: &Context) -> Result<()> {
    if cx.series.1.steps.is_empty() {
        return cx.save("memory_of_initial_contact", NARROW, &Note(NO_SERIES));
    }
    let fig = MemoryFigure {
        pairs: cx.data.pairs_of(cx.series.0),
        units: cx.data.units,
    };
    cx.save("memory_of_initial_contact", (1400, 640), &fig)
}

/// Draws the figures asked for (all without a list) of a loaded study into `out`.
fn draw(data: &Data, job: Option<usize>, figures: Option<&[String]>, out: &Path, shown: &Path) -> Result<usize> {
    let cx = Context {
        data,
        series: series_job(data, job)?,
        out,
        shown,
    };
    for figure in &FIGURES {
        if figures.is_none_or(|w| w.iter().any(|n| n == figure.name)) {
            (figure.draw)(&cx)?;
        }
    }
    Ok(cx.series.1.index)
}

pub fn run(args: &Args) -> Result<()> {
    let dir = &args.dir;
    let (study, results) = load_results(dir)?;
    let data = Data::new(study.jobs, results)?;
    let figures = wearsim::io::OutputDir::begin(&dir.join("figures"), "study plot", false, &[])?;
    let (out, shown) = (figures.join(""), dir.join("figures"));
    let series = draw(&data, args.job, args.figures.as_deref(), &out, &shown)?;
    // The paper's findings on this study, judged on the runs of its sliding model only: an estimate
    // (or any other model) is no sliding run.
    let (sliding, others) = wearsim::output::sliding_rows(&data.tidy);
    let found = if sliding.rows.is_empty() {
        Vec::new()
    } else {
        findings(&data.tidy)
    };
    let note = match (others, sliding.rows.len()) {
        (0, _) => String::new(),
        (_, 0) => "This study holds no run of the sliding model (its `sliding.model` is another, such as \
                   \"estimate\": static estimates): the paper's findings are judged on sliding runs, so none is \
                   judged here. Its figures draw the other models' results, labelled by model (\"static \
                   estimate\").\n\n"
            .to_string(),
        (n, _) => format!(
            "{n} rows of this study are not sliding runs (their `sliding.model` is another, such as \"estimate\": \
             static estimates); the findings below are judged on its sliding jobs only.\n\n"
        ),
    };
    let text = format!(
        "# The paper's findings on this study\n\nBrink, Frérot & Molinari (2021); `wearsim study plot` on {}.\n\n{note}{}",
        dir.display(),
        markdown(&found)
    );
    write_into(&out, &shown, "findings.md", text.as_bytes())
        .with_context(|| format!("cannot write findings.md into {}", shown.display()))?;
    figures.commit()?;
    for f in &found {
        say!("{:<18} {}: {}", f.verdict.name(), f.key, f.observed);
    }
    say!(
        "wrote figures and findings.md to {} (series of job {series})",
        shown.display()
    );
    Ok(())
}

#[cfg(test)]
mod tests;
