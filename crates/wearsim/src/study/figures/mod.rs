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

use crate::error::{Error, Result};
use crate::output::{series_job, JobResult, StudyTable, Table};

mod labels;
mod load;
mod model;
mod regime;
mod runs;
mod series;
mod severity;

use labels::Shown;
use load::Curves;
use series::SeriesOf;

pub use labels::{BREAKDOWN_LEGEND, MEANS, MEANS_ON_LOG_AXES};
pub use model::{Axis, Band, Color, Figure, LegendEntry, Panel, Point, Series, Style, Swatch};
pub use runs::{run_figure, slide_folder_figures, RunTables};

/// One entry of the registry: the name `--figures` (and Python's `names`) takes, the file stem of
/// its figure, what it shows, and the function that draws it: an entry cannot be registered
/// without what draws it, and its name and stem are written here only.
#[derive(Clone, Copy)]
pub struct FigureSpec {
    pub name: &'static str,
    /// The file stem of its figure (`study plot` writes `<stem>.png`, `.svg` and `.csv`); an entry
    /// of several figures adds to it what tells them apart (appC's `_junctions`, fig4c's `_2`).
    pub stem: &'static str,
    pub about: &'static str,
    build: Build,
}

/// How an entry draws its figures.
#[derive(Clone, Copy)]
enum Build {
    /// From the study's tables, against load or another quantity: its figures, each named by what
    /// it adds to the stem (a note where the study cannot show it, as Fig. 4c without curves of
    /// equal d*; none for the wear-regime map of a study without a particle-rule axis, which only
    /// such a study draws).
    Tables(fn(&Study) -> Vec<Figure>),
    /// One figure of sliding series against the sliding distance: of one job (given first) and of
    /// every surface pair of its setting in a study, of the runs given outside one
    /// ([`run_figure`]).
    Series {
        draw: fn(&SeriesOf, &[SeriesOf], Shown) -> Figure,
        /// Whether it draws the results' fits (W and its intercept, the fit window, ℓ), which a
        /// run outside a study must then be given.
        fits: bool,
    },
}

impl FigureSpec {
    /// How a front end lays its figures out.
    pub fn layout(&self) -> Layout {
        match self.build {
            Build::Tables(_) => Layout::Panels,
            Build::Series { .. } => Layout::Series,
        }
    }

    /// Its figures under its name and stem.
    fn stamp(&self, figures: Vec<Figure>) -> Vec<Figure> {
        figures
            .into_iter()
            .map(|f| Figure {
                entry: self.name,
                name: format!("{}{}", self.stem, f.name),
                ..f
            })
            .collect()
    }
}

impl std::fmt::Debug for FigureSpec {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FigureSpec")
            .field("name", &self.name)
            .field("stem", &self.stem)
            .field("about", &self.about)
            .field("layout", &self.layout())
            .finish()
    }
}

/// How a front end lays a figure out.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Layout {
    /// Panels against load (or another quantity), the legend beside them.
    Panels,
    /// One panel of series against the sliding distance, whose legend entries are long: wider.
    Series,
}

/// The registry entry named `entry` (a figure's `entry`).
pub fn spec(entry: &str) -> Option<&'static FigureSpec> {
    FIGURES.iter().find(|f| f.name == entry)
}

/// The layout of the figures of registry entry `entry` (a figure's `entry`): panels where no entry
/// has the name.
pub fn layout_of(entry: &str) -> Layout {
    spec(entry).map_or(Layout::Panels, FigureSpec::layout)
}

/// Every figure of a study, in the order drawn. A new figure is one entry here, with the function
/// that draws it.
pub const FIGURES: [FigureSpec; 12] = [
    FigureSpec {
        name: "fig2",
        stem: "fig2_static_model",
        about: "static model over every offset: W_static/ω per unit area and k_static against p_N (paper Fig. 2)",
        build: Build::Tables(|s| vec![load::static_model(&s.data, s.shown)]),
    },
    FigureSpec {
        name: "fig3",
        stem: "fig3_wear_volume",
        about: "V(s) of one job with the fitted lines and the running-in region (Fig. 3)",
        build: Build::Series {
            draw: |job, _, shown| series::wear_volume(job, shown),
            fits: true,
        },
    },
    FigureSpec {
        name: "fig4",
        stem: "fig4_sliding_wear",
        about: "sliding W per unit area and k against p_N, 95 % intervals over surface pairs (Fig. 4)",
        build: Build::Tables(|s| vec![load::sliding_wear(&s.data, s.shown)]),
    },
    FigureSpec {
        name: "fig4c",
        stem: "fig4c_constant_d_star",
        about: "W, k and dN*₊/ds for settings of (nearly) equal d* (Figs. 4c, 5c)",
        build: Build::Tables(|s| load::constant_critical_diameter(&s.data, s.shown)),
    },
    FigureSpec {
        name: "fig5",
        stem: "fig5_particle_rate",
        about: "dN*₊/ds per unit area against p_N (Fig. 5)",
        build: Build::Tables(|s| vec![load::particle_rate(&s.data, s.shown)]),
    },
    FigureSpec {
        name: "fig6",
        stem: "fig6_kim_comparison",
        about: "k against p_N per material, beside Kim et al.'s experimental range for Kim's ceramics (Fig. 6)",
        build: Build::Tables(|s| vec![load::kim_comparison(&s.data, s.table.tidy(), s.shown)]),
    },
    FigureSpec {
        name: "appB",
        stem: "appB_particle_counts",
        about: "N*₊, N*, N*₋ against s of one job (appendix B, Fig. B.9a)",
        build: Build::Series {
            draw: |job, _, shown| series::particle_counts(job, shown),
            fits: false,
        },
    },
    FigureSpec {
        name: "appB-eq5",
        stem: "appB_eq5_against_w",
        about: "Eq. 5, ω d*³ dN*₊/ds, against the summed W (Fig. B.9b), and Eq. 5 / W against load",
        build: Build::Tables(|s| vec![severity::equation_5(&s.data, s.table.tidy(), s.shown)]),
    },
    FigureSpec {
        name: "appC",
        stem: "appC",
        about: "junctions N and critical junctions N* against p_N (appendix C)",
        build: Build::Tables(|s| load::junction_counts(&s.data, s.shown)),
    },
    FigureSpec {
        name: "appF",
        stem: "appF_contact_severity",
        about: "the contact-severity fits W = α S_cⁿ per material and over all (appendix F)",
        build: Build::Tables(|s| vec![severity::contact_severity(s.table.tidy(), s.shown)]),
    },
    FigureSpec {
        name: "wear-regime",
        stem: "wear_regime",
        about: "the wear-regime map: W/F_N, the particle size and W of each particle rule over the paper's against \
                p_N, with the load where a rule of interacting junctions departs (a study with a particle_rule axis)",
        build: Build::Tables(|s| regime::wear_regime(s.table, s.shown).into_iter().collect()),
    },
    FigureSpec {
        name: "memory",
        stem: "memory_of_initial_contact",
        about: "the memory of the initial contact N₀(s) of every surface pair of one setting, with fits (§3)",
        build: Build::Series {
            draw: |_, pairs, shown| series::memory(pairs, shown),
            fits: true,
        },
    },
];

/// What every figure is built from.
struct Study<'a> {
    table: &'a StudyTable,
    data: Curves,
    shown: Shown,
    /// The job whose series fig3 and appB draw, and every surface pair of its setting (memory);
    /// None without job files.
    series: Option<(&'a JobResult, Vec<&'a JobResult>)>,
}

/// Every figure asked for by registry name (all without a list), in the registry's order, from a
/// study's table (its tidy table, `results.csv`, and the means derived from it) and its job files. The series
/// figures (fig3, appB, memory) draw job `job` (default: the one that formed the most particles
/// after running-in, the lowest index among equals) and need `jobs`; without them they are notes
/// that say so.
pub fn study_figures(
    table: &StudyTable,
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
    let system = table.units();
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
        table,
        data: Curves::of(table)?,
        shown: Shown { system },
        series,
    };
    let mut out = Vec::new();
    for spec in FIGURES
        .iter()
        .filter(|f| names.is_none_or(|w| w.iter().any(|n| n == f.name)))
    {
        let mut built = match spec.build {
            Build::Tables(draw) => draw(&study),
            Build::Series { draw, .. } => vec![series::of_study(study.series.as_ref(), study.shown, draw)],
        };
        // A figure asked for by name that the study cannot show says so, rather than nothing.
        if built.is_empty() && names.is_some() {
            built.push(Figure::note(format!(
                "this study has nothing for {}: {}",
                spec.name, spec.about
            )));
        }
        out.extend(spec.stamp(built));
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

/// A study folder's figures, with the table they were drawn from (the findings are judged on the
/// same) and the job whose series they show.
pub struct StudyFigures {
    pub table: StudyTable,
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
    let table = StudyTable::of(Table::of(&rows));
    let figures = study_figures(&table, &results, job, names)?;
    let series_job = match job {
        Some(j) => Some(j),
        None => series_job(
            results
                .iter()
                .flat_map(|r| r.results.iter().map(move |w| (r.index, w.particles_in_fit))),
        ),
    };
    Ok(StudyFigures {
        table,
        figures,
        series_job,
    })
}

#[cfg(test)]
mod tests;
