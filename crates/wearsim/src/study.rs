//! Studies (SPEC §7, §9): a study file is a run file whose fields may be lists, or whose materials
//! are a `[[materials]]` array of named tables. It expands into jobs, one per surface pair ×
//! material × contact setting × load (every fracture energy inside the job), each run by the sliding
//! model and stored as one JSON file written atomically, so that a killed study resumes where it
//! stopped. [`collect`] turns the job files into one tidy table and its aggregate over surface pairs.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use serde::{Deserialize, Serialize};
use toml::{Table, Value};

use crate::config::RunConfig;
use crate::error::{Error, Interrupt, Result};
use crate::output::write_text;
use crate::sliding::{run_sliding, SlidingSetup, StepRecord, WearResult};

/// One job of a study: a single-load run file and the parameters that vary across the study.
#[derive(Debug, Clone)]
pub struct Job {
    /// Position in the expansion order; the job file is `jobs/job-{index:06}.json`.
    pub index: usize,
    /// Name of the material (`[[materials]]` `name`, or "material").
    pub material: String,
    /// The run, with a single load.
    pub run: RunConfig,
    /// Values of the study's list-valued keys for this job ("section.key" → value).
    pub varying: BTreeMap<String, Value>,
}

impl Job {
    /// The varying inputs as text, as stored in the job file.
    pub fn parameters(&self) -> BTreeMap<String, String> {
        self.varying.iter().map(|(k, v)| (k.clone(), csv_value(v))).collect()
    }

    /// Every input of the job as (column, text), the same columns for every job: what a tidy table
    /// row carries beside the results.
    pub fn inputs(&self) -> Vec<(&'static str, String)> {
        use crate::config::SurfaceSource;
        let r = &self.run;
        let m = &r.material;
        let (mut grid, mut hurst, mut lower, mut upper, mut rms, mut seed, mut top, mut bottom) = (
            String::new(),
            String::new(),
            String::new(),
            String::new(),
            String::new(),
            String::new(),
            String::new(),
            String::new(),
        );
        match &r.surfaces {
            SurfaceSource::Generated {
                grid: g,
                spectrum,
                seed: s,
                ..
            } => {
                grid = g.to_string();
                hurst = format!("{:e}", spectrum.hurst);
                lower = format!("{:e}", spectrum.lambda_lower);
                upper = format!("{:e}", spectrum.lambda_upper);
                rms = format!("{:e}", spectrum.rms_height);
                seed = s.to_string();
            }
            SurfaceSource::Files { top: t, bottom: b, .. } => {
                top = t.display().to_string().replace(',', ";");
                bottom = b.display().to_string().replace(',', ";");
            }
        }
        vec![
            (
                "units",
                if r.units == crate::config::Units::Si {
                    "si".into()
                } else {
                    "reduced".into()
                },
            ),
            ("surface.grid", grid),
            ("surface.length", format!("{:e}", r.length())),
            ("surface.hurst", hurst),
            ("surface.lambda_lower", lower),
            ("surface.lambda_upper", upper),
            ("surface.rms_height", rms),
            ("surface.seed", seed),
            ("surface.top", top),
            ("surface.bottom", bottom),
            ("material.youngs_modulus", format!("{:e}", m.youngs_modulus)),
            ("material.poisson_ratio", format!("{:e}", m.poisson_ratio)),
            ("material.shear_strength", format!("{:e}", m.shear_strength)),
            ("material.geometry_factor", format!("{:e}", m.geometry_factor)),
            ("contact.modulus", r.modulus.name().into()),
            ("contact.tolerance", format!("{:e}", r.solver.tolerance)),
            ("contact.connectivity", r.connectivity.to_string()),
        ]
    }

    /// The job's single load.
    pub fn load(&self) -> f64 {
        self.run
            .sliding
            .as_ref()
            .and_then(|s| s.loads.first().copied())
            .unwrap_or(f64::NAN)
    }

    /// Reads this job's result file, checking that it was written for this job.
    pub fn read_result(&self, dir: &Path) -> Result<JobResult> {
        let p = job_path(dir, self.index);
        let text = std::fs::read_to_string(&p).map_err(|e| Error::io(&p, e))?;
        let r: JobResult = serde_json::from_str(&text).map_err(|e| Error::io(&p, format!("not a job result ({e})")))?;
        if r.index != self.index
            || r.material != self.material
            || r.load != self.load()
            || r.parameters != self.parameters()
        {
            return Err(Error::Config(format!(
                "{} was written for another job ({} at load {:e}, {:?}), not for {} at load {:e}, {:?}; \
                 the folder comes from another version of this study: use a new --out folder",
                p.display(),
                r.material,
                r.load,
                r.parameters,
                self.material,
                self.load(),
                self.parameters()
            )));
        }
        Ok(r)
    }
}

/// An expanded study.
#[derive(Debug, Clone)]
pub struct Study {
    pub jobs: Vec<Job>,
    /// FNV-1a hash of the parsed study (comments and layout do not count).
    pub hash: String,
    /// The study file's canonical TOML.
    pub canonical: String,
}

fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| {
        (h ^ b as u64).wrapping_mul(0x0100_0000_01b3)
    })
}

/// Cartesian product of the list-valued keys of `table` (except `keep_lists`): every combination as
/// a table of single values, with the chosen values.
fn product(table: &Table, section: &str, keep_lists: &[&str]) -> Vec<(Table, BTreeMap<String, Value>)> {
    let mut out = vec![(Table::new(), BTreeMap::new())];
    for (key, value) in table {
        let choices: Vec<Value> = match value {
            Value::Array(items) if !keep_lists.contains(&key.as_str()) => items.clone(),
            other => vec![other.clone()],
        };
        let varies = matches!(value, Value::Array(_)) && !keep_lists.contains(&key.as_str());
        let mut next = Vec::with_capacity(out.len() * choices.len());
        for (t, v) in &out {
            for c in &choices {
                let mut t = t.clone();
                t.insert(key.clone(), c.clone());
                let mut v = v.clone();
                if varies {
                    v.insert(format!("{section}.{key}"), c.clone());
                }
                next.push((t, v));
            }
        }
        out = next;
    }
    out
}

/// Expands a study file's text; relative surface paths resolve against `base`.
pub fn expand(text: &str, base: &Path) -> Result<Study> {
    let table: Table = text
        .parse::<Table>()
        .map_err(|e| Error::Config(e.to_string().trim_end().replace('\n', " ")))?;
    let canonical = toml::to_string(&table).map_err(|e| Error::Config(e.to_string()))?;
    let hash = format!("{:016x}", fnv1a(canonical.as_bytes()));
    let section = |name: &str| -> Result<Table> {
        match table.get(name) {
            None => Ok(Table::new()),
            Some(Value::Table(t)) => Ok(t.clone()),
            Some(_) => Err(Error::Config(format!("`{name}` must be a table"))),
        }
    };
    for key in table.keys() {
        if !["units", "surface", "material", "materials", "contact", "sliding"].contains(&key.as_str()) {
            return Err(Error::Config(format!(
                "unknown key `{key}` at the top of the study file"
            )));
        }
    }
    // Materials: one [material] table (lists allowed) or a [[materials]] array of named tables.
    // (name, material table, varying material values, surface overrides of this material)
    let mut materials: Vec<(String, Table, BTreeMap<String, Value>, Table)> = Vec::new();
    match (table.get("material"), table.get("materials")) {
        (Some(_), Some(_)) => {
            return Err(Error::Config(
                "give either [material] or [[materials]], not both".into(),
            ))
        }
        (_, Some(Value::Array(items))) => {
            for (i, item) in items.iter().enumerate() {
                let Value::Table(t) = item else {
                    return Err(Error::Config("[[materials]] entries must be tables".into()));
                };
                let mut t = t.clone();
                let name = match t.remove("name") {
                    Some(Value::String(s)) => s,
                    None => format!("material{}", i + 1),
                    Some(_) => return Err(Error::Config("[[materials]] `name` must be a string".into())),
                };
                // A material may carry its own surface parameters (e.g. the steady-state h_rms of
                // Kim et al.'s ceramics): `[materials.surface]` keys replace those of [surface].
                let overrides = match t.remove("surface") {
                    None => Table::new(),
                    Some(Value::Table(o)) => o,
                    Some(_) => {
                        return Err(Error::Config(format!(
                            "[[materials]] `{name}`: `surface` must be a table"
                        )))
                    }
                };
                for (m, v) in product(&t, "material", &["fracture_energies"]) {
                    materials.push((name.clone(), m, v, overrides.clone()));
                }
            }
        }
        (_, Some(_)) => {
            return Err(Error::Config(
                "`materials` must be an array of tables ([[materials]])".into(),
            ))
        }
        (_, None) => {
            let mut t = section("material")?;
            let name = match t.remove("name") {
                Some(Value::String(s)) => s,
                _ => "material".to_string(),
            };
            for (m, v) in product(&t, "material", &["fracture_energies"]) {
                materials.push((name.clone(), m, v, Table::new()));
            }
        }
    }
    let base_surface = section("surface")?;
    let contacts = product(&section("contact")?, "contact", &[]);
    let sliding = section("sliding")?;
    let loads = match sliding.get("loads") {
        Some(Value::Array(l)) if !l.is_empty() => l.clone(),
        _ => {
            return Err(Error::param(
                "loads",
                "a study needs a non-empty [sliding] `loads` list",
            ))
        }
    };
    let mut jobs = Vec::new();
    for (name, material, mv, overrides) in &materials {
        let mut surface_table = base_surface.clone();
        surface_table.extend(overrides.clone());
        for (surface, sv) in &product(&surface_table, "surface", &[]) {
            for (contact, cv) in &contacts {
                for load in &loads {
                    let mut run = Table::new();
                    if let Some(u) = table.get("units") {
                        run.insert("units".into(), u.clone());
                    }
                    run.insert("surface".into(), Value::Table(surface.clone()));
                    run.insert("material".into(), Value::Table(material.clone()));
                    run.insert("contact".into(), Value::Table(contact.clone()));
                    let mut sl = sliding.clone();
                    sl.insert("loads".into(), Value::Array(vec![load.clone()]));
                    run.insert("sliding".into(), Value::Table(sl));
                    let text = toml::to_string(&run).map_err(|e| Error::Config(e.to_string()))?;
                    let index = jobs.len();
                    let config = RunConfig::from_toml(&text, base)
                        .map_err(|e| Error::Config(format!("study job {index} ({name}): {e}")))?;
                    let mut varying = sv.clone();
                    varying.extend(mv.clone());
                    varying.extend(cv.clone());
                    jobs.push(Job {
                        index,
                        material: name.clone(),
                        run: config,
                        varying,
                    });
                }
            }
        }
    }
    Ok(Study { jobs, hash, canonical })
}

/// What a job file holds.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct JobResult {
    pub index: usize,
    pub material: String,
    /// The job's varying inputs ("section.key" → value as text), checked when the file is read back so
    /// that a file can never be attributed to another job.
    pub parameters: BTreeMap<String, String>,
    pub load: f64,
    pub flow_pressure: f64,
    pub effective_modulus: f64,
    pub results: Vec<WearResult>,
    /// Per step: s, junctions, contact area; per fracture energy: n_critical, n_formed, volume.
    pub steps: Vec<StepRow>,
    pub total_iterations: usize,
    pub seconds: f64,
}

/// One step of a job file.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct StepRow {
    pub s: f64,
    pub junctions: usize,
    pub contact_area: f64,
    pub n_critical: Vec<usize>,
    pub n_formed: Vec<usize>,
    pub volume: Vec<f64>,
}

impl From<&StepRecord> for StepRow {
    fn from(r: &StepRecord) -> Self {
        Self {
            s: r.s,
            junctions: r.junctions,
            contact_area: r.contact_area,
            n_critical: r.wear.iter().map(|w| w.n_critical).collect(),
            n_formed: r.wear.iter().map(|w| w.n_formed).collect(),
            volume: r.wear.iter().map(|w| w.volume).collect(),
        }
    }
}

/// Writes a job's result file atomically (the file whose presence marks the job done).
pub fn write_result(dir: &Path, result: &JobResult) -> Result<()> {
    let path = job_path(dir, result.index);
    let text = serde_json::to_string(result).map_err(|e| Error::io(&path, e))?;
    write_text(&path, &text)
}

/// Path of job `index`'s result file in a study folder.
pub fn job_path(dir: &Path, index: usize) -> PathBuf {
    dir.join("jobs").join(format!("job-{index:06}.json"))
}

/// Runs one job; a raised `interrupt` stops it with [`Error::Interrupted`].
pub fn run_job(job: &Job, interrupt: &Interrupt) -> Result<JobResult> {
    let start = std::time::Instant::now();
    let run = &job.run;
    let sliding = run
        .sliding
        .as_ref()
        .ok_or_else(|| Error::param("loads", "job without [sliding]"))?;
    let (top, bottom) = run.surfaces()?;
    let mut setup = SlidingSetup::from_run(run, sliding);
    setup.interrupt = interrupt.clone();
    let mut runs = run_sliding(&top, &bottom, &setup, |_| {})?;
    let r = runs.pop().ok_or_else(|| Error::param("loads", "job without a load"))?;
    Ok(JobResult {
        index: job.index,
        material: job.material.clone(),
        parameters: job.parameters(),
        load: r.load,
        flow_pressure: run.material.flow_pressure(),
        effective_modulus: run.effective_modulus(),
        results: r.results,
        steps: r.steps.iter().map(StepRow::from).collect(),
        total_iterations: r.total_iterations,
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// Prepares a study folder: stores the study, its hash and the folder its relative paths resolve
/// against on first use, refuses a folder made by a different study, and removes temporary files a
/// killed run left behind.
pub fn prepare_folder(dir: &Path, study: &Study, base: &Path) -> Result<()> {
    std::fs::create_dir_all(dir.join("jobs")).map_err(|e| Error::io(dir, e))?;
    let hash_path = dir.join("study.hash");
    match std::fs::read_to_string(&hash_path) {
        Ok(existing) if existing.trim() != study.hash => {
            return Err(Error::Config(format!(
                "{} holds results of a different study (hash {} ≠ {}); use a new --out folder or restore the original study file",
                dir.display(),
                existing.trim(),
                study.hash
            )))
        }
        Ok(_) => {}
        Err(_) => {
            write_text(&dir.join("study.toml"), &study.canonical)?;
            let base = base.canonicalize().map_err(|e| Error::io(base, e))?;
            write_text(&dir.join("study.base"), &base.to_string_lossy())?;
            write_text(&hash_path, &study.hash)?;
        }
    }
    for entry in std::fs::read_dir(dir.join("jobs"))
        .map_err(|e| Error::io(dir, e))?
        .flatten()
    {
        let name = entry.file_name().to_string_lossy().to_string();
        if name.starts_with('.') && name.contains(".tmp") {
            let _ = std::fs::remove_file(entry.path());
        }
    }
    Ok(())
}

/// Jobs of shard `k` of `count` (1-based k): indices ≡ k − 1 (mod count).
pub fn shard(jobs: &[Job], k: usize, count: usize) -> Vec<&Job> {
    jobs.iter().filter(|j| j.index % count == k - 1).collect()
}

/// Runs the given jobs with `workers` jobs at once, the threads of the current rayon pool shared
/// between them (one worker: every thread on each job, for large grids; as many workers as threads:
/// one thread per job, for many small jobs), skipping jobs whose file exists. `progress(done, total)`
/// is called after each job. A raised `interrupt` stops the jobs under way (finished job files stay,
/// so a later run resumes) and returns [`Error::Interrupted`]. Returns (computed, skipped).
pub fn run_jobs(
    dir: &Path,
    jobs: &[&Job],
    workers: usize,
    interrupt: &Interrupt,
    progress: impl Fn(usize, usize) + Sync,
) -> Result<(usize, usize)> {
    // A finished job is skipped only once its file is confirmed to be this job's.
    let mut pending: Vec<&Job> = Vec::new();
    for &job in jobs {
        if job_path(dir, job.index).is_file() {
            job.read_result(dir)?;
        } else {
            pending.push(job);
        }
    }
    let skipped = jobs.len() - pending.len();
    let next = AtomicUsize::new(0);
    let done = AtomicUsize::new(0);
    let first_error: Mutex<Option<Error>> = Mutex::new(None);
    let workers = workers.clamp(1, pending.len().max(1));
    let threads_per_worker = (rayon::current_num_threads() / workers).max(1);
    std::thread::scope(|scope| {
        for _ in 0..workers {
            scope.spawn(|| {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads_per_worker)
                    .build()
                    .expect("a worker's thread pool");
                loop {
                    if first_error.lock().map(|e| e.is_some()).unwrap_or(true) {
                        return;
                    }
                    let i = next.fetch_add(1, Ordering::SeqCst);
                    let Some(job) = pending.get(i) else { return };
                    let outcome = pool
                        .install(|| run_job(job, interrupt))
                        .and_then(|result| write_result(dir, &result));
                    match outcome {
                        Ok(()) => progress(done.fetch_add(1, Ordering::SeqCst) + 1, pending.len()),
                        Err(e) => {
                            let e = match e {
                                Error::Interrupted => e,
                                e => Error::Config(format!("study job {}: {e}", job.index)),
                            };
                            if let Ok(mut slot) = first_error.lock() {
                                slot.get_or_insert(e);
                            }
                            return;
                        }
                    }
                }
            });
        }
    });
    if let Some(e) = first_error.into_inner().ok().flatten() {
        return Err(e);
    }
    Ok((done.into_inner(), skipped))
}

fn csv_value(v: &Value) -> String {
    match v {
        Value::String(s) => s.clone(),
        Value::Integer(i) => i.to_string(),
        Value::Float(f) => format!("{f:e}"),
        Value::Boolean(b) => b.to_string(),
        other => other.to_string().replace(',', ";"),
    }
}

const RESULT_COLUMNS: [&str; 10] = [
    "wear_rate",
    "wear_rate_r2",
    "wear_coefficient",
    "particle_rate",
    "wear_rate_estimate",
    "initial_volume",
    "static_wear_coefficient",
    "static_wear_rate",
    "critical_diameter",
    "flow_pressure",
];

/// Reads a study folder: the stored study, expanded, and every job's result in job order. Fails
/// naming the missing jobs when the study is unfinished.
pub fn load_results(dir: &Path) -> Result<(Study, Vec<JobResult>)> {
    let path = dir.join("study.toml");
    let text = std::fs::read_to_string(&path).map_err(|e| Error::io(&path, e))?;
    let base = std::fs::read_to_string(dir.join("study.base"))
        .map(PathBuf::from)
        .unwrap_or_else(|_| dir.to_path_buf());
    let study = expand(&text, &base)?;
    let missing: Vec<usize> = study
        .jobs
        .iter()
        .map(|j| j.index)
        .filter(|&i| !job_path(dir, i).is_file())
        .collect();
    if !missing.is_empty() {
        return Err(Error::Config(format!(
            "{} of {} jobs have no result yet (first: {}); run `wearsim study run` again to finish them",
            missing.len(),
            study.jobs.len(),
            missing[0]
        )));
    }
    let results = study
        .jobs
        .iter()
        .map(|job| job.read_result(dir))
        .collect::<Result<Vec<_>>>()?;
    Ok((study, results))
}

/// Collects the job files of a study folder into `results.csv` (one row per job × fracture energy:
/// every input of [`Job::inputs`], then the results) and `results_aggregated.csv` (mean, min and max over surface pairs, i.e.
/// over `surface.seed`). Returns the number of rows of each. Fails naming the missing jobs when
/// the study is unfinished.
pub fn collect(dir: &Path) -> Result<(usize, usize)> {
    let (study, results) = load_results(dir)?;
    let input_keys: Vec<&str> = study
        .jobs
        .first()
        .map(|j| j.inputs().iter().map(|(k, _)| *k).collect())
        .unwrap_or_default();
    let mut header = vec!["job".to_string(), "material".into()];
    header.extend(input_keys.iter().map(|k| k.to_string()));
    header.extend(["load", "fracture_energy"].map(String::from));
    header.extend(RESULT_COLUMNS.map(String::from));
    let mut tidy = header.join(",") + "\n";
    // Aggregation key: everything but the job index and the seed; groups keep the study's order.
    let mut group_index: BTreeMap<Vec<String>, usize> = BTreeMap::new();
    let mut groups: Vec<(Vec<String>, Vec<Vec<f64>>)> = Vec::new();
    let mut rows = 0;
    for (job, r) in study.jobs.iter().zip(&results) {
        for w in &r.results {
            let inputs: Vec<String> = job.inputs().into_iter().map(|(_, v)| v).collect();
            let values = [
                w.wear_rate,
                w.wear_rate_r2,
                w.wear_coefficient,
                w.particle_rate,
                w.wear_rate_estimate,
                w.initial_volume,
                w.static_wear_coefficient,
                w.static_wear_rate,
                w.critical_diameter,
                r.flow_pressure,
            ];
            let mut line = vec![job.index.to_string(), job.material.clone()];
            line.extend(inputs.iter().cloned());
            line.push(format!("{:e}", r.load));
            line.push(format!("{:e}", w.fracture_energy));
            line.extend(values.iter().map(|v| format!("{v:e}")));
            tidy += &(line.join(",") + "\n");
            rows += 1;
            let mut key = vec![job.material.clone()];
            key.extend(
                input_keys
                    .iter()
                    .zip(&inputs)
                    .filter(|(k, _)| **k != "surface.seed")
                    .map(|(_, v)| v.clone()),
            );
            key.push(format!("{:e}", r.load));
            key.push(format!("{:e}", w.fracture_energy));
            let g = *group_index.entry(key.clone()).or_insert_with(|| {
                groups.push((key, Vec::new()));
                groups.len() - 1
            });
            groups[g].1.push(values.to_vec());
        }
    }
    let group_keys: Vec<String> = input_keys
        .iter()
        .filter(|k| **k != "surface.seed")
        .map(|k| k.to_string())
        .collect();
    let mut agg_header = vec!["material".to_string()];
    agg_header.extend(group_keys);
    agg_header.extend(["load", "fracture_energy", "surface_pairs"].map(String::from));
    for c in RESULT_COLUMNS {
        agg_header.extend([format!("{c}_mean"), format!("{c}_min"), format!("{c}_max")]);
    }
    let mut agg = agg_header.join(",") + "\n";
    for (key, members) in &groups {
        let mut line = key.clone();
        line.push(members.len().to_string());
        for c in 0..RESULT_COLUMNS.len() {
            let vals: Vec<f64> = members.iter().map(|m| m[c]).collect();
            let mean = vals.iter().sum::<f64>() / vals.len() as f64;
            let min = vals.iter().copied().fold(f64::INFINITY, f64::min);
            let max = vals.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            line.extend([format!("{mean:e}"), format!("{min:e}"), format!("{max:e}")]);
        }
        agg += &(line.join(",") + "\n");
    }
    write_text(&dir.join("results.csv"), &tidy)?;
    write_text(&dir.join("results_aggregated.csv"), &agg)?;
    Ok((rows, groups.len()))
}

#[cfg(test)]
mod tests {
    use super::*;

    const STUDY: &str = r#"
[surface]
grid = 64
lambda_lower = 0.125
lambda_upper = 0.25
rms_height = 0.005
seed = [1, 2, 3]
[[materials]]
name = "soft"
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = [0.008, 0.01]
fracture_energies = [0.5e-6, 1e-6]
[[materials]]
name = "hard"
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = 0.012
fracture_energies = [0.5e-6]
[sliding]
loads = [5e-4, 1e-3]
"#;

    #[test]
    fn expansion_is_the_cartesian_product() {
        let s = expand(STUDY, Path::new(".")).unwrap();
        // 3 seeds × (2 + 1) materials × 2 loads.
        assert_eq!(s.jobs.len(), 18);
        assert_eq!(s.jobs[0].varying.get("surface.seed"), Some(&Value::Integer(1)));
        assert!(s.jobs.iter().all(|j| j.run.sliding.as_ref().unwrap().loads.len() == 1));
        assert_eq!(s.jobs.iter().filter(|j| j.material == "hard").count(), 6);
        // Layout and comments do not change the hash; values do.
        let again = expand(&format!("# comment\n{STUDY}"), Path::new(".")).unwrap();
        assert_eq!(s.hash, again.hash);
        assert_ne!(
            s.hash,
            expand(&STUDY.replace("0.012", "0.011"), Path::new(".")).unwrap().hash
        );
    }

    #[test]
    fn materials_may_override_surface_parameters() {
        let text = STUDY.replace(
            "name = \"hard\"\n",
            "name = \"hard\"\nsurface = { rms_height = [0.004, 0.006] }\n",
        );
        let s = expand(&text, Path::new(".")).unwrap();
        // 3 seeds × (2 soft + 2 hard surface variants) × 2 loads.
        assert_eq!(s.jobs.len(), 24);
        let hard: Vec<&Job> = s.jobs.iter().filter(|j| j.material == "hard").collect();
        assert_eq!(hard.len(), 12);
        assert!(hard.iter().all(|j| j.varying.contains_key("surface.rms_height")));
        assert!(s
            .jobs
            .iter()
            .filter(|j| j.material == "soft")
            .all(|j| !j.varying.contains_key("surface.rms_height")));
    }

    #[test]
    fn shards_partition_the_jobs() {
        let s = expand(STUDY, Path::new(".")).unwrap();
        let mut all: Vec<usize> = (1..=4).flat_map(|k| shard(&s.jobs, k, 4)).map(|j| j.index).collect();
        all.sort();
        assert_eq!(all, (0..18).collect::<Vec<_>>());
    }

    #[test]
    fn bad_study_files_are_errors() {
        assert!(expand(&STUDY.replace("loads = [5e-4, 1e-3]", "loads = []"), Path::new(".")).is_err());
        let e = expand(
            &STUDY
                .replace("hurst", "x")
                .replace("grid = 64", "grid = 64\nhurts = 0.7"),
            Path::new("."),
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("hurts"), "{e}");
    }
}
