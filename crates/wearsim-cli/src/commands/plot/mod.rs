//! `wearsim study plot DIR`: the figures of a finished study, as PNG and SVG in `DIR/figures`, in the
//! layout of the paper (Brink, Frérot & Molinari 2021), and the paper's findings judged on the study
//! (`findings.md`, also printed, with every unit's numbers in `findings_units.csv`). The figures and their numbers are the library's
//! (`wearsim::study::figures`: one registry, [`FIGURES`], whose names `--figures` takes and
//! `--help` lists; Python's `wearsim.plot` draws the same); this command draws them ([`mod@draw`]) and
//! writes each figure's numbers as CSV beside its PNG and SVG.

mod draw;

use std::path::{Path, PathBuf};

use anyhow::{Context as _, Result};
use wearsim::study::figures::{study_folder_figures, Figure, FIGURES};

use crate::figures::{save, write_into};
use crate::out::say;

use draw::{size, Drawn};

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

#[derive(clap::Args)]
pub struct SlideArgs {
    /// Folder of a `wearsim slide` run (its summary.json and series.csv).
    dir: PathBuf,
}

/// `wearsim plot DIR`: the series figures of one `slide` folder, every load, into DIR/figures
/// (the library's `slide_folder_figures`; a figure with nothing to draw says why). A study folder
/// is refused with the command that draws it.
pub fn run_slide(args: &SlideArgs) -> Result<()> {
    let dir = &args.dir;
    if dir.join("jobs").is_dir() {
        anyhow::bail!(
            "{} is a study folder (it has jobs/): draw it with `wearsim study plot {}`",
            dir.display(),
            dir.display()
        );
    }
    let figures = wearsim::study::figures::slide_folder_figures(dir)?;
    let folder = wearsim::io::OutputDir::begin(&dir.join("figures"), "plot", false, &[])?;
    let (out, shown) = (folder.join(""), dir.join("figures"));
    draw(&figures, &out, &shown)?;
    folder.commit()?;
    say!("wrote {} figures to {}", figures.len(), shown.display());
    Ok(())
}

/// The values `--figures` takes: the names of the library's registry, each with what it shows.
fn figure_names() -> clap::builder::PossibleValuesParser {
    clap::builder::PossibleValuesParser::new(
        FIGURES
            .iter()
            .map(|f| clap::builder::PossibleValue::new(f.name).help(f.about)),
    )
}

/// Writes each figure into `out` as PNG and SVG, and its numbers as CSV beside them; a figure with
/// nothing to draw says why. `shown` is the folder the files end up in (`out` is its temporary
/// stand-in until the end).
fn draw(figures: &[Figure], out: &Path, shown: &Path) -> Result<()> {
    for figure in figures {
        if let Some(note) = &figure.note {
            say!("{}: {note}", figure.entry);
        }
        for line in &figure.report {
            say!("{line}");
        }
        save(out, shown, &figure.name, size(figure), &Drawn(figure))?;
        write_into(out, shown, &format!("{}.csv", figure.name), figure.to_csv().as_bytes())
            .with_context(|| format!("cannot write the numbers of {} into {}", figure.name, shown.display()))?;
    }
    Ok(())
}

pub fn run(args: &Args) -> Result<()> {
    let dir = &args.dir;
    let study = study_folder_figures(dir, args.job, args.figures.as_deref()).map_err(|e| match e {
        // The library names its argument; here it is the option.
        wearsim::Error::InvalidParameter { field, message } if field == "job" => wearsim::Error::InvalidParameter {
            field: format!("--job {}", args.job.unwrap_or_default()),
            message,
        },
        other => other,
    })?;
    let figures = wearsim::io::OutputDir::begin(&dir.join("figures"), "study plot", false, &[])?;
    let (out, shown) = (figures.join(""), dir.join("figures"));
    draw(&study.figures, &out, &shown)?;
    // The paper's findings on this study: the library's document, which Python writes too.
    let document = wearsim::study::findings::document(&study.table);
    write_into(&out, &shown, "findings.md", document.markdown.as_bytes())
        .with_context(|| format!("cannot write findings.md into {}", shown.display()))?;
    write_into(&out, &shown, "findings_units.csv", document.units_csv.as_bytes())
        .with_context(|| format!("cannot write findings_units.csv into {}", shown.display()))?;
    figures.commit()?;
    for f in &document.findings {
        say!("{:<18} {}: {}", f.verdict.name(), f.key, f.observed);
    }
    match study.series_job {
        Some(job) => say!(
            "wrote figures, findings.md and findings_units.csv to {} (series of job {job})",
            shown.display()
        ),
        None => say!(
            "wrote figures, findings.md and findings_units.csv to {}",
            shown.display()
        ),
    }
    Ok(())
}

#[cfg(test)]
mod tests;
