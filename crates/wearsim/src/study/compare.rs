//! The static estimate against the sliding runs of a study: every finished sliding job estimated on
//! its own surfaces and schedule, row by row (W, k, dN*₊/ds of both, the estimate's interval and
//! whether it covers the sliding value), the errors summarised, and the points a calibration is
//! fitted on (`wearsim estimate-check`).

use std::path::{Path, PathBuf};

use crate::error::{Error, Interrupt, Result};
use crate::estimate::{
    fit_distance, load_estimate, run_reach, Calibration, CalibrationPoint, EstimateResult, OutsideReach, Sample,
    Sampling, CALIBRATED_DOMAIN,
};
use crate::run::SlidingRun;
use crate::study::expand::{expand, expand_stored, Study};
use crate::study::store::{job_path, read_result, stored_study};

/// One setting (job × fracture energy): what the sliding run measured beside the estimate.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct ComparisonRow {
    pub job: usize,
    #[serde(rename = "surface.seed")]
    pub seed: Option<u64>,
    #[serde(rename = "surface.grid")]
    pub grid: Option<usize>,
    #[serde(rename = "surface.length")]
    pub length: f64,
    #[serde(rename = "material.shear_strength")]
    pub shear_strength: f64,
    pub load: f64,
    pub nominal_pressure: f64,
    pub fracture_energy: f64,
    pub critical_diameter: f64,
    /// d* in pixels.
    pub critical_diameter_pixels: f64,
    /// Particles the sliding run fitted its rates on.
    pub particles_in_fit: usize,
    pub sliding_wear_rate: Option<f64>,
    pub sliding_wear_coefficient: Option<f64>,
    pub sliding_particle_rate: Option<f64>,
    pub sliding_critical_junctions_mean: f64,
    pub wear_rate: Option<f64>,
    pub wear_rate_low: Option<f64>,
    pub wear_rate_high: Option<f64>,
    pub wear_coefficient: Option<f64>,
    pub particle_rate: Option<f64>,
    pub particle_rate_low: Option<f64>,
    pub particle_rate_high: Option<f64>,
    pub critical_junctions_mean: f64,
    pub mean_critical_diameter: Option<f64>,
    pub critical_coverage: f64,
    pub static_maps: usize,
    /// estimate/sliding − 1 of W (k's is the same: both are W times p_m/F_N) and of dN*₊/ds.
    pub wear_rate_error: Option<f64>,
    pub particle_rate_error: Option<f64>,
    /// Particles the estimate expects such a run to count in its fit window.
    pub expected_particles: Option<f64>,
    /// The sliding W lies in the estimate's interval (absent where it has none).
    pub wear_rate_covered: Option<bool>,
    pub particle_rate_covered: Option<bool>,
    /// How the setting is scored ([`Scored`]).
    pub scored: Scored,
    /// Why the estimate gives no interval, where it gives none for a defined W.
    pub interval_withheld: Option<String>,
}

/// How one setting counts in the coverage of [`ComparisonSummary`]: every setting is one of these,
/// whatever the particles its sliding run formed (the interval includes the Poisson noise of that
/// count, so a run that formed few particles where the estimate expected many is a miss, not a
/// setting to leave out).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Scored {
    /// The sliding W lies in the estimate's 95 % interval.
    Covered,
    /// It lies outside.
    #[default]
    NotCovered,
    /// The estimate gives W without an interval: the setting lies outside the calibrated domain.
    Withheld,
    /// No static map holds a junction of d*: the estimate gives no W, and the sliding run formed no
    /// particle either.
    NoEstimateNoParticle,
    /// No static map holds a junction of d*, but the sliding run formed particles: a miss the
    /// estimate could not quantify.
    NoEstimateParticlesFormed,
    /// The sliding run gives no W (too few steps in its fit window).
    NoSlidingRate,
}

impl ComparisonRow {
    /// The calibration point of this row.
    pub fn point(&self) -> CalibrationPoint {
        CalibrationPoint {
            critical_junctions: self.critical_junctions_mean,
            mean_critical_diameter: self.mean_critical_diameter.unwrap_or(0.0),
            critical_coverage: self.critical_coverage,
            critical_diameter: self.critical_diameter,
            particle_rate: self.sliding_particle_rate.unwrap_or(0.0),
            wear_rate: self.sliding_wear_rate.unwrap_or(0.0),
            particles: self.particles_in_fit,
        }
    }
}

/// A finished sliding job with its static maps: estimated again under any calibration without
/// solving again.
#[derive(Debug, Clone)]
pub struct MappedJob {
    pub job: crate::output::JobResult,
    pub samples: Vec<Sample>,
    material: crate::material::Material,
    /// Lx × Ly.
    box_sides: (f64, f64),
    fit_distance: f64,
    pixel_size: f64,
    /// Where the job as a whole lies outside the library's calibration ([`run_reach`]): its
    /// estimates under the library's constants carry no interval there.
    reach: Vec<OutsideReach>,
}

/// The files a command that reads study folder `dir` reads: its stored study, its hash, its job
/// folder, the surface files its jobs name and the folder of the study file it was run from (where
/// its relative paths resolve: the user's study file and surfaces live there). An output folder may
/// be none of them and hold none of them ([`crate::io::refuse_inputs_inside`]), nor lie inside the
/// job folder, which holds only the study's own files.
pub fn study_inputs(dir: &Path) -> Result<Vec<PathBuf>> {
    let (text, base) = stored_study(dir)?;
    let study = expand_stored(&text, &base)?;
    let mut inputs = vec![dir.join("study.toml"), dir.join("study.hash"), dir.join("jobs"), base];
    for job in &study.jobs {
        for file in job.run.surfaces.input_files() {
            if !inputs.iter().any(|i| i == file) {
                inputs.push(file.to_path_buf());
            }
        }
    }
    Ok(inputs)
}

/// Refuses `out` as the output folder of a command reading study folder `dir`: one that is or
/// holds one of its inputs ([`study_inputs`]), or lies inside its job folder, whatever `--overwrite`
/// says (replacing it would delete job results or surfaces the study reads). Gives the inputs, for
/// the output folder's own checks ([`crate::io::OutputDir::begin`]).
pub fn refuse_output_in_study(out: &Path, dir: &Path) -> Result<Vec<PathBuf>> {
    let inputs = study_inputs(dir)?;
    let refs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
    crate::io::refuse_inputs_inside(out, &refs)?;
    let jobs = crate::io::canonical_path(&dir.join("jobs"));
    if crate::io::canonical_path(out).starts_with(&jobs) {
        return Err(Error::file(
            out,
            format!(
                "lies inside the study's job folder {}, which holds only the study's job files; give an --out folder \
                 outside it, e.g. --out check",
                jobs.display()
            ),
        ));
    }
    Ok(inputs)
}

/// The study of folder `dir` as its jobs were run, with its surface files read again: the stored
/// study refuses surface files changed since the jobs were run ([`stored_study`]), since a static
/// map of changed surfaces would be compared with sliding runs of the old ones, and here they must
/// be where the study file named them.
fn study_as_run(dir: &Path) -> Result<Study> {
    let (text, base) = stored_study(dir)?;
    expand(&text, &base).map_err(|e| Error::StudyFolder {
        dir: dir.into(),
        message: format!(
            "its jobs cannot be estimated again: {e}; the surface files the study was run with must be where the \
             study file named them"
        ),
    })
}

/// The finished sliding jobs of a study folder with the static maps of each, the jobs left out and
/// every warning of the estimates (each with the jobs it concerns).
#[derive(Debug, Clone)]
pub struct MappedStudy {
    pub jobs: Vec<MappedJob>,
    /// Jobs unfinished or of another model.
    pub left_out: usize,
    /// Each distinct warning of the jobs' estimates (the run's inputs, d* against the pixel size,
    /// junctions around the box, sampling, the results) with the jobs that gave it, in order.
    pub warnings: Vec<(String, Vec<usize>)>,
}

impl MappedStudy {
    /// Each warning of the jobs' estimates with the jobs that gave it, as ranges: `… (jobs 0–3, 7)`.
    pub fn warning_lines(&self) -> Vec<String> {
        self.warnings
            .iter()
            .map(|(w, on)| format!("{w} (job{} {})", if on.len() == 1 { "" } else { "s" }, job_ranges(on)))
            .collect()
    }
}

/// Job numbers (ascending) as ranges: 0–3, 7, 9–10.
pub fn job_ranges(jobs: &[usize]) -> String {
    let mut parts: Vec<String> = Vec::new();
    let mut i = 0;
    while i < jobs.len() {
        let mut j = i;
        while j + 1 < jobs.len() && jobs[j + 1] == jobs[j] + 1 {
            j += 1;
        }
        parts.push(if j == i {
            jobs[i].to_string()
        } else {
            format!("{}–{}", jobs[i], jobs[j])
        });
        i = j + 1;
    }
    parts.join(", ")
}

/// The finished sliding jobs of study folder `dir` with the static maps of each, taken as `samples`
/// says (else as each job's `estimate_samples`, else chosen by the sampling error); unfinished
/// jobs and jobs of a model other than the paper's sliding model
/// ([`feeds_findings`](crate::model::WearModel::feeds_findings): the estimate's) are left out
/// and counted. The surface files must be those the
/// study ran with. `on_job(done, total)` is told after each job.
pub fn map_jobs(
    dir: &Path,
    samples: Option<usize>,
    interrupt: &Interrupt,
    mut on_job: impl FnMut(usize, usize),
) -> Result<MappedStudy> {
    let study = study_as_run(dir)?;
    let finished: Vec<_> = study
        .jobs
        .iter()
        .filter(|j| j.run.model.feeds_findings() && job_path(dir, j.index).is_file())
        .collect();
    if finished.is_empty() {
        return Err(Error::StudyFolder {
            dir: dir.into(),
            message: "no finished sliding job to compare with: run `wearsim study run` first".into(),
        });
    }
    let left_out = study.jobs.len() - finished.len();
    let mut out = Vec::with_capacity(finished.len());
    let mut warnings: Vec<(String, Vec<usize>)> = Vec::new();
    for (i, job) in finished.iter().enumerate() {
        let result = read_result(job, dir)?;
        let sliding = crate::run::sliding_schedule(&job.run)?;
        let sampling = Sampling::of(samples.or(job.run.estimate_samples))?;
        let prepared = SlidingRun::prepare(&job.run)?.interrupted_by(interrupt);
        let grid = prepared.grid();
        let outcome = prepared.estimate(sampling, &crate::estimate::CALIBRATION, |_, _| {})?;
        for w in &outcome.warnings {
            match warnings.iter_mut().find(|(text, _)| text == w) {
                Some((_, jobs)) => jobs.push(job.index),
                None => warnings.push((w.clone(), vec![job.index])),
            }
        }
        let samples = outcome.loads.into_iter().next().map(|l| l.samples).unwrap_or_default();
        let kind = job.run.surfaces.estimate_kind(grid);
        out.push(MappedJob {
            job: result,
            samples,
            material: job.run.material.clone(),
            box_sides: (grid.length_x(), grid.length_y()),
            fit_distance: fit_distance(sliding, grid.length_x()),
            pixel_size: grid.pixel_size(),
            reach: run_reach(&CALIBRATED_DOMAIN, &kind, sliding, grid.length_x()),
        });
        on_job(i + 1, finished.len());
    }
    Ok(MappedStudy {
        jobs: out,
        left_out,
        warnings,
    })
}

/// What a fit of the constants on `rows` rests on that it should not: settings whose d* is under
/// [`crate::check::RESOLVED_PIXELS`] pixels (the same rule as the sliding run's and the estimate's
/// resolution warning), among those [`Calibration::fit`] uses.
pub fn fit_warnings(rows: &[ComparisonRow]) -> Vec<String> {
    let coarse: Vec<&ComparisonRow> = rows
        .iter()
        .filter(|r| r.particles_in_fit >= crate::estimate::FIT_MIN_PARTICLES)
        .filter(|r| r.critical_diameter_pixels < crate::check::RESOLVED_PIXELS)
        .collect();
    if coarse.is_empty() {
        return Vec::new();
    }
    let fewest = coarse
        .iter()
        .map(|r| r.critical_diameter_pixels)
        .fold(f64::INFINITY, f64::min);
    let most = coarse.iter().map(|r| r.critical_diameter_pixels).fold(0.0, f64::max);
    vec![format!(
        "the fit uses {} setting(s) whose d* is {fewest:.2}–{most:.2} pixels, under {}: junctions of the critical \
         size are not resolved there and their rates follow the grid, so constants fitted on them follow it too; \
         refine the study's `grid` (or raise its fracture energies) before fitting",
        coarse.len(),
        crate::check::RESOLVED_PIXELS
    )]
}

/// The rows of the mapped jobs under `calibration`, each estimate as `wearsim estimate` gives it
/// ([`load_estimate`]: under the library's constants without an interval outside their reach).
pub fn compare(jobs: &[MappedJob], calibration: &Calibration) -> Vec<ComparisonRow> {
    let mut rows = Vec::new();
    for m in jobs {
        let (estimates, _) = load_estimate(
            &m.samples,
            &m.material,
            m.job.load,
            m.box_sides,
            m.fit_distance,
            calibration,
            &m.reach,
        );
        for (w, e) in m.job.results.iter().zip(&estimates) {
            rows.push(row(m, w, e));
        }
    }
    rows
}

fn row(m: &MappedJob, w: &crate::sliding::WearResult, e: &EstimateResult) -> ComparisonRow {
    let inputs = &m.job.inputs;
    let error = |est: Option<f64>, slid: Option<f64>| match (est, slid) {
        (Some(a), Some(b)) if b > 0.0 => Some(a / b - 1.0),
        _ => None,
    };
    let scored = scored(e, w);
    let covered = |lo: Option<f64>, hi: Option<f64>, slid: Option<f64>| match (lo, hi, slid) {
        (Some(lo), Some(hi), Some(v)) => Some(lo <= v && v <= hi),
        _ => None,
    };
    ComparisonRow {
        job: m.job.index,
        seed: inputs.seed,
        grid: inputs.grid,
        length: inputs.length,
        shear_strength: inputs.shear_strength,
        load: m.job.load,
        nominal_pressure: inputs.nominal_pressure(m.job.load),
        fracture_energy: w.fracture_energy,
        critical_diameter: w.critical_diameter,
        critical_diameter_pixels: w.critical_diameter / m.pixel_size,
        particles_in_fit: w.particles_in_fit,
        sliding_wear_rate: w.wear_rate,
        sliding_wear_coefficient: w.wear_coefficient,
        sliding_particle_rate: w.particle_rate,
        sliding_critical_junctions_mean: w.critical_junctions_mean,
        wear_rate: e.wear_rate,
        wear_rate_low: e.wear_rate_low,
        wear_rate_high: e.wear_rate_high,
        wear_coefficient: e.wear_coefficient,
        particle_rate: e.particle_rate,
        particle_rate_low: e.particle_rate_low,
        particle_rate_high: e.particle_rate_high,
        critical_junctions_mean: e.critical_junctions_mean,
        mean_critical_diameter: e.mean_critical_diameter,
        critical_coverage: e.critical_coverage,
        static_maps: m.samples.len(),
        wear_rate_error: error(e.wear_rate, w.wear_rate),
        particle_rate_error: error(e.particle_rate, w.particle_rate),
        expected_particles: e.expected_particles,
        wear_rate_covered: scored.covered(),
        particle_rate_covered: covered(e.particle_rate_low, e.particle_rate_high, w.particle_rate),
        scored,
        interval_withheld: e.interval_withheld.clone(),
    }
}

impl Scored {
    /// Whether the sliding W lies in the interval, where the estimate gives one.
    pub fn covered(self) -> Option<bool> {
        match self {
            Scored::Covered => Some(true),
            Scored::NotCovered => Some(false),
            _ => None,
        }
    }
}

/// How a setting counts ([`Scored`]): `e` the estimate, `w` the sliding run's result.
fn scored(e: &EstimateResult, w: &crate::sliding::WearResult) -> Scored {
    let Some(slid) = w.wear_rate else {
        return Scored::NoSlidingRate;
    };
    if e.wear_rate.is_none() {
        return if w.particles_in_fit == 0 {
            Scored::NoEstimateNoParticle
        } else {
            Scored::NoEstimateParticlesFormed
        };
    }
    match (e.wear_rate_low, e.wear_rate_high) {
        (Some(lo), Some(hi)) if lo <= slid && slid <= hi => Scored::Covered,
        (Some(_), Some(_)) => Scored::NotCovered,
        _ => Scored::Withheld,
    }
}

/// The estimate against the sliding runs over every setting compared: the coverage of its 95 %
/// interval counted over all of them (each setting is one [`Scored`] kind, none left out), and its
/// errors over the settings whose sliding run formed at least `min_particles` particles (below
/// that a single run's W scatters by more than ±1/√min_particles by Poisson alone, so its error
/// says little of the estimate; those settings are still scored for coverage).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct ComparisonSummary {
    pub min_particles: usize,
    /// Every setting (job × 𝒢) compared.
    pub settings: usize,
    /// Settings the errors are summarised over (at least `min_particles` particles), and those left
    /// out of the errors for fewer.
    pub error_settings: usize,
    pub error_left_out: usize,
    /// Median and largest |estimate/sliding − 1| of W (and k) and of dN*₊/ds over `error_settings`.
    pub wear_rate_median_error: Option<f64>,
    pub wear_rate_worst_error: Option<f64>,
    pub particle_rate_median_error: Option<f64>,
    pub particle_rate_worst_error: Option<f64>,
    /// Settings whose estimate has an interval, and those whose sliding W (dN*₊/ds) lies in it.
    pub with_interval: usize,
    pub wear_rate_covered: usize,
    pub particle_rate_covered: usize,
    /// `wear_rate_covered / with_interval` (absent without an interval).
    pub coverage: Option<f64>,
    /// Settings whose estimate gives W without an interval (outside the calibrated domain), with
    /// each reason and how many settings it concerns.
    pub interval_withheld: usize,
    pub withheld_reasons: std::collections::BTreeMap<String, usize>,
    /// Settings where no static map holds a junction of d* (no estimate), and those of them where
    /// the sliding run formed particles all the same.
    pub no_estimate: usize,
    pub no_estimate_particles_formed: usize,
    /// Settings whose sliding run gives no W.
    pub no_sliding_rate: usize,
    /// The settings scored as misses: W outside the interval, or particles formed where the
    /// estimate had none (job, seed, p_N, d*, particles formed and expected, estimate/sliding).
    pub not_covered: Vec<String>,
}

impl ComparisonSummary {
    /// The summary in words, as `wearsim estimate-check` prints it under the heading `what`: the
    /// coverage over every setting, what was not scored by an interval and why, the errors, then
    /// one line per miss.
    pub fn describe(&self, what: &str) -> Vec<String> {
        let pct = |v: Option<f64>| v.map_or("undefined".into(), |v| format!("{:.1} %", 100.0 * v));
        let mut others = Vec::new();
        if self.interval_withheld > 0 {
            others.push(format!(
                "no interval in {} (outside the calibrated domain)",
                self.interval_withheld
            ));
        }
        if self.no_estimate > 0 {
            others.push(format!(
                "no estimate in {} (no junction of d* in any static map; the sliding run formed particles in {})",
                self.no_estimate, self.no_estimate_particles_formed
            ));
        }
        if self.no_sliding_rate > 0 {
            others.push(format!("no sliding W in {}", self.no_sliding_rate));
        }
        let coverage = match self.coverage {
            Some(c) => format!(
                "the 95 % interval covers W in {}/{} with an interval ({:.0} %) and dN*₊/ds in {}/{}",
                self.wear_rate_covered,
                self.with_interval,
                100.0 * c,
                self.particle_rate_covered,
                self.with_interval
            ),
            None => "no setting has an interval".into(),
        };
        let mut lines = vec![format!(
            "{what}: {} settings, every one scored: {coverage}{}; W and k median |error| {}, worst {}, dN*₊/ds median \
             {}, worst {}, over the {} with at least {} particles ({} with fewer left out of the errors only)",
            self.settings,
            if others.is_empty() {
                String::new()
            } else {
                format!("; {}", others.join("; "))
            },
            pct(self.wear_rate_median_error),
            pct(self.wear_rate_worst_error),
            pct(self.particle_rate_median_error),
            pct(self.particle_rate_worst_error),
            self.error_settings,
            self.min_particles,
            self.error_left_out,
        )];
        lines.extend(
            self.withheld_reasons
                .iter()
                .map(|(r, n)| format!("  no interval: {r} ({n} setting{})", if *n == 1 { "" } else { "s" })),
        );
        lines.extend(self.not_covered.iter().map(|n| format!("  not covered: {n}")));
        lines
    }
}

/// The comparison of a study's mapped jobs under the constants used (fitted on them, or the
/// library's), and its summaries under those and under the library's constants.
#[derive(Debug, Clone)]
pub struct CheckOutcome {
    /// The constants fitted on the jobs, if they were.
    pub fitted: Option<Calibration>,
    /// The constants of `rows` and `summary`: the fitted ones, else the library's.
    pub calibration: Calibration,
    pub rows: Vec<ComparisonRow>,
    pub summary: ComparisonSummary,
    /// The summary under the library's constants ([`crate::estimate::CALIBRATION`]).
    pub in_use: ComparisonSummary,
}

impl CheckOutcome {
    /// The rows of `jobs` under `fitted` (else the library's constants), summarised over the
    /// settings with at least `min_particles` particles.
    pub fn of(jobs: &[MappedJob], fitted: Option<Calibration>, min_particles: usize) -> Self {
        let calibration = fitted.unwrap_or(crate::estimate::CALIBRATION);
        let rows = compare(jobs, &calibration);
        let summary = summarize(&rows, min_particles);
        let in_use = summarize(&compare(jobs, &crate::estimate::CALIBRATION), min_particles);
        Self {
            fitted,
            calibration,
            rows,
            summary,
            in_use,
        }
    }

    /// The summary.json of `wearsim estimate-check` on study folder `study`: `mapped` its jobs,
    /// `samples` the static maps per job asked for (else the study's), `warnings` every warning said.
    pub fn document(
        &self,
        study: &Path,
        mapped: &MappedStudy,
        samples: Option<usize>,
        warnings: &[String],
    ) -> serde_json::Value {
        let jobs = &mapped.jobs;
        serde_json::json!({
            "provenance": crate::output::Provenance::current(),
            "study": study,
            "jobs_compared": jobs.len(),
            "jobs_left_out": mapped.left_out,
            "samples": samples.map_or("per job: the study's estimate_samples, else by the sampling error".into(),
                |k| format!("{k} static maps per job (--samples)")),
            "calibration": self.calibration,
            "fitted": self.fitted.is_some(),
            "calibration_in_use": crate::estimate::CALIBRATION,
            "summary": self.summary,
            "summary_with_calibration_in_use": self.in_use,
            "warnings": warnings,
            "error_convention": "estimate/sliding − 1 per setting; W and k share it (both W p_m/F_N)",
            "units_of_comparison": crate::output::units_map(
                jobs.first().map_or(crate::config::Units::Reduced, |m| m.job.inputs.units),
                crate::output::columns::<ComparisonRow>().iter().map(String::as_str)
            ),
        })
    }
}

fn median(mut v: Vec<f64>) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    Some(if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    })
}

/// Summarises `rows`: the coverage over every one, the errors over those with at least
/// `min_particles` particles ([`ComparisonSummary`]).
pub fn summarize(rows: &[ComparisonRow], min_particles: usize) -> ComparisonSummary {
    let used: Vec<&ComparisonRow> = rows
        .iter()
        .filter(|r| r.particles_in_fit >= min_particles && r.sliding_wear_rate.is_some())
        .collect();
    let abs = |f: fn(&ComparisonRow) -> Option<f64>| used.iter().filter_map(|r| f(r).map(f64::abs)).collect::<Vec<_>>();
    let (w, p) = (abs(|r| r.wear_rate_error), abs(|r| r.particle_rate_error));
    let count = |k: Scored| rows.iter().filter(|r| r.scored == k).count();
    let with_interval = count(Scored::Covered) + count(Scored::NotCovered);
    let covered = count(Scored::Covered);
    let mut withheld_reasons = std::collections::BTreeMap::new();
    for reason in rows
        .iter()
        .filter(|r| r.scored == Scored::Withheld)
        .filter_map(|r| r.interval_withheld.as_ref())
    {
        *withheld_reasons.entry(reason.clone()).or_insert(0) += 1;
    }
    ComparisonSummary {
        min_particles,
        settings: rows.len(),
        error_settings: used.len(),
        error_left_out: rows.len() - used.len(),
        wear_rate_worst_error: w.iter().copied().reduce(f64::max),
        wear_rate_median_error: median(w),
        particle_rate_worst_error: p.iter().copied().reduce(f64::max),
        particle_rate_median_error: median(p),
        with_interval,
        wear_rate_covered: covered,
        particle_rate_covered: rows.iter().filter(|r| r.particle_rate_covered == Some(true)).count(),
        coverage: (with_interval > 0).then(|| covered as f64 / with_interval as f64),
        interval_withheld: count(Scored::Withheld),
        withheld_reasons,
        no_estimate: count(Scored::NoEstimateNoParticle) + count(Scored::NoEstimateParticlesFormed),
        no_estimate_particles_formed: count(Scored::NoEstimateParticlesFormed),
        no_sliding_rate: count(Scored::NoSlidingRate),
        not_covered: rows
            .iter()
            .filter(|r| matches!(r.scored, Scored::NotCovered | Scored::NoEstimateParticlesFormed))
            .map(|r| {
                format!(
                    "job {} (seed {}, p_N = {:.3e}, d* = {:.1} px, {} particles formed, {} expected): {}",
                    r.job,
                    r.seed.map_or("-".into(), |s| s.to_string()),
                    r.nominal_pressure,
                    r.critical_diameter_pixels,
                    r.particles_in_fit,
                    r.expected_particles.map_or("none".into(), |n| format!("{n:.1}")),
                    match r.wear_rate_error {
                        Some(e) => format!("estimate/sliding = {:.2}", 1.0 + e),
                        None if r.sliding_wear_rate == Some(0.0) => "the sliding run formed none".into(),
                        None => "no estimate".into(),
                    }
                )
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r(particles: usize, error: f64, covered: bool) -> ComparisonRow {
        ComparisonRow {
            particles_in_fit: particles,
            sliding_wear_rate: Some(1.0),
            wear_rate_error: Some(error),
            particle_rate_error: Some(error),
            expected_particles: Some(particles as f64),
            wear_rate_covered: Some(covered),
            particle_rate_covered: Some(covered),
            scored: if covered { Scored::Covered } else { Scored::NotCovered },
            ..Default::default()
        }
    }

    #[test]
    fn jobs_are_listed_as_ranges_and_the_summary_in_words() {
        assert_eq!(job_ranges(&[0, 1, 2, 3, 7, 9, 10]), "0–3, 7, 9–10");
        assert_eq!(job_ranges(&[]), "");
        let mapped = MappedStudy {
            jobs: Vec::new(),
            left_out: 0,
            warnings: vec![("a".into(), vec![4]), ("b".into(), vec![1, 2, 5])],
        };
        assert_eq!(mapped.warning_lines(), ["a (job 4)", "b (jobs 1–2, 5)"]);
        let rows = [r(25, 0.1, true), r(30, -0.3, false)];
        let lines = summarize(&rows, 20).describe("with the constants in use");
        assert_eq!(
            lines[0],
            "with the constants in use: 2 settings, every one scored: the 95 % interval covers W in 1/2 with an \
             interval (50 %) and dN*₊/ds in 1/2; W and k median |error| 20.0 %, worst 30.0 %, dN*₊/ds median 20.0 %, \
             worst 30.0 %, over the 2 with at least 20 particles (0 with fewer left out of the errors only)"
        );
        assert_eq!(lines.len(), 2);
        assert!(lines[1].starts_with("  not covered: job 0 "), "{lines:?}");
    }

    #[test]
    fn errors_are_over_the_settings_with_enough_particles_and_coverage_over_all() {
        let rows = [r(25, 0.1, true), r(30, -0.3, false), r(40, 0.2, true), r(5, 3.0, false)];
        let s = summarize(&rows, 20);
        assert_eq!((s.settings, s.error_settings, s.error_left_out), (4, 3, 1));
        assert_eq!(s.wear_rate_median_error, Some(0.2));
        assert_eq!(s.wear_rate_worst_error, Some(0.3));
        // The setting with 5 particles is out of the errors, not out of the coverage: its miss counts.
        assert_eq!((s.wear_rate_covered, s.with_interval), (2, 4));
        assert_eq!(s.coverage, Some(0.5));
        assert_eq!(s.not_covered.len(), 2);
        assert!(
            s.not_covered[1].contains("5 particles formed, 5.0 expected"),
            "{:?}",
            s.not_covered
        );
    }

    /// A run that formed no particle where the estimate expected many is a miss; a setting outside
    /// the calibration is counted as without interval, with its reason; no estimate beside
    /// particles formed is a miss the summary names.
    #[test]
    fn no_setting_is_left_out_of_the_score() {
        let estimate = |lo: Option<f64>, w: Option<f64>, hi: Option<f64>, why: Option<&str>| EstimateResult {
            wear_rate: w,
            wear_rate_low: lo,
            wear_rate_high: hi,
            interval_withheld: why.map(String::from),
            expected_particles: w.map(|_| 50.0),
            ..Default::default()
        };
        let slid = |w: Option<f64>, particles: usize| crate::sliding::WearResult {
            wear_rate: w,
            particles_in_fit: particles,
            ..Default::default()
        };
        let inside = estimate(Some(0.5), Some(1.0), Some(2.0), None);
        assert_eq!(scored(&inside, &slid(Some(1.2), 40)), Scored::Covered);
        // Fifty particles expected, none formed: W = 0 exactly, outside [0.5, 2].
        assert_eq!(scored(&inside, &slid(Some(0.0), 0)), Scored::NotCovered);
        let outside = estimate(None, Some(1.0), None, Some("outside the calibrated domain: surfaces"));
        assert_eq!(scored(&outside, &slid(Some(0.02), 1)), Scored::Withheld);
        let none = estimate(None, None, None, None);
        assert_eq!(scored(&none, &slid(Some(0.0), 0)), Scored::NoEstimateNoParticle);
        assert_eq!(scored(&none, &slid(Some(0.3), 3)), Scored::NoEstimateParticlesFormed);
        assert_eq!(scored(&inside, &slid(None, 0)), Scored::NoSlidingRate);

        let row = |e: &EstimateResult, w: &crate::sliding::WearResult| ComparisonRow {
            particles_in_fit: w.particles_in_fit,
            sliding_wear_rate: w.wear_rate,
            wear_rate_error: match (e.wear_rate, w.wear_rate) {
                (Some(a), Some(b)) if b > 0.0 => Some(a / b - 1.0),
                _ => None,
            },
            expected_particles: e.expected_particles,
            scored: scored(e, w),
            interval_withheld: e.interval_withheld.clone(),
            ..Default::default()
        };
        let rows = [
            row(&inside, &slid(Some(1.2), 40)),
            row(&inside, &slid(Some(0.0), 0)),
            row(&outside, &slid(Some(0.02), 1)),
            row(&outside, &slid(Some(0.05), 2)),
            row(&none, &slid(Some(0.3), 3)),
        ];
        let s = summarize(&rows, 20);
        assert_eq!(s.settings, 5);
        assert_eq!((s.wear_rate_covered, s.with_interval), (1, 2));
        assert_eq!(s.interval_withheld, 2);
        assert_eq!(
            s.withheld_reasons.get("outside the calibrated domain: surfaces"),
            Some(&2)
        );
        assert_eq!((s.no_estimate, s.no_estimate_particles_formed), (1, 1));
        assert_eq!(s.not_covered.len(), 2, "{:?}", s.not_covered);
        assert!(s.not_covered[0].contains("0 particles formed, 50.0 expected): the sliding run formed none"));
        assert!(s.not_covered[1].contains("3 particles formed, none expected): no estimate"));
        let none = summarize(&rows[2..4], 20).describe("in use");
        assert!(
            none[0].starts_with("in use: 2 settings, every one scored: no setting has an interval; no interval in 2"),
            "{none:?}"
        );
        let lines = s.describe("with the constants in use");
        assert!(
            lines[0].contains("covers W in 1/2 with an interval (50 %)"),
            "{}",
            lines[0]
        );
        assert!(
            lines[0].contains("no interval in 2 (outside the calibrated domain)"),
            "{}",
            lines[0]
        );
        assert!(
            lines
                .iter()
                .any(|l| l == "  no interval: outside the calibrated domain: surfaces (2 settings)"),
            "{lines:?}"
        );
    }
}
