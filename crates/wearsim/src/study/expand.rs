//! Study file → jobs: the Cartesian product of the list-valued keys, each combination deserialised
//! straight into a validated [`RunConfig`] with a single load.

use std::collections::BTreeMap;
use std::path::Path;

use toml::{Table, Value};

use crate::config::{InputRecord, RunConfig, SurfaceFiles};
use crate::error::{Error, Result};
use crate::model::WearModel;
use crate::output::JobResult;

/// One job of a study: a single-load run and the parameters that vary across the study.
#[derive(Debug, Clone)]
pub struct Job {
    /// Position in the expansion order; the job file is `jobs/job-{index:06}.json`.
    pub index: usize,
    /// Name of the material (`[[materials]]` `name`, or "material").
    pub material: String,
    /// The run, with a single load.
    pub run: RunConfig,
    /// Values of the study's list-valued keys for this job ("section.key" → value), for labels.
    pub varying: BTreeMap<String, Value>,
}

impl Job {
    /// Every input of the job (the columns of the tidy table beside the results).
    pub fn inputs(&self) -> InputRecord {
        self.run.inputs()
    }

    /// The job's single load.
    pub fn load(&self) -> f64 {
        self.run
            .sliding
            .as_ref()
            .and_then(|s| s.loads.first().copied())
            .unwrap_or(f64::NAN)
    }

    /// Whether a job result was computed for this job: same index, material, load and inputs
    /// (compared as values), but for where the surface files lay: a job file records them as
    /// absolute paths, and a study folder committed to a repository or moved with its surface files
    /// is read where it is now. The files themselves are compared by their contents, which the
    /// study's hash covers (a folder whose surface files changed is refused when its stored study
    /// is read, before any job file is).
    pub fn is_result_of(&self, r: &JobResult) -> bool {
        r.index == self.index
            && r.material == self.material
            && r.load == self.load()
            && without_file_paths(&r.inputs) == without_file_paths(&self.inputs())
    }

    /// One line saying which job this is, for messages.
    pub fn describe(&self) -> String {
        format!("job {} ({}, load {:e})", self.index, self.material, self.load())
    }
}

/// `record` without the paths of its surface files (`top`, `bottom`, a spectrum's `map`), as a job
/// is identified ([`Job::is_result_of`]): absolute where the study ran, they say where the folder
/// lay, not which surfaces it ran (the study's hash holds their contents).
fn without_file_paths(record: &InputRecord) -> InputRecord {
    let seen = |p: &Option<String>| p.as_ref().map(|_| String::new());
    InputRecord {
        top: seen(&record.top),
        bottom: seen(&record.bottom),
        map: seen(&record.map),
        ..record.clone()
    }
}

/// An expanded study.
#[derive(Debug, Clone)]
pub struct Study {
    pub jobs: Vec<Job>,
    /// FNV-1a hash of the parsed study (comments and layout do not count) and of the contents of
    /// the surface files it names, so that a changed surface makes it another study.
    pub hash: String,
    /// The study file's canonical TOML.
    pub canonical: String,
    /// What the study file gives that no job reads (a single `[sliding]` setting that the study's
    /// model ignores), one sentence each.
    pub warnings: Vec<String>,
}

fn fnv1a(bytes: &[u8]) -> u64 {
    fnv1a_continue(0xcbf2_9ce4_8422_2325u64, bytes)
}

fn fnv1a_continue(hash: u64, bytes: &[u8]) -> u64 {
    bytes
        .iter()
        .fold(hash, |h, &b| (h ^ b as u64).wrapping_mul(0x0100_0000_01b3))
}

/// Keys whose run-file value may be a two-element list `[along x, along y]` (a rectangle).
const PER_SIDE: [&str; 2] = ["grid", "length"];

/// Cartesian product of the list-valued keys of `table` (except `keep_lists`): every combination as
/// a table of single values, with the chosen values. An axis that lists a value twice is refused (it
/// would run and average the same job twice), and so is a two-element list of `grid` or `length`,
/// which a run file reads as one rectangle and a study as two squares.
fn product(table: &Table, section: &str, keep_lists: &[&str]) -> Result<Vec<(Table, BTreeMap<String, Value>)>> {
    let mut out = vec![(Table::new(), BTreeMap::new())];
    for (key, value) in table {
        let varies = matches!(value, Value::Array(_)) && !keep_lists.contains(&key.as_str());
        let choices: Vec<Value> = match value {
            Value::Array(items) if varies => items.clone(),
            other => vec![other.clone()],
        };
        if varies {
            axis_is_unambiguous(section, key, &choices)?;
        }
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
    Ok(out)
}

/// Refuses an axis `section.key = choices` that lists a value twice, or that could be a rectangle.
fn axis_is_unambiguous(section: &str, key: &str, choices: &[Value]) -> Result<()> {
    let field = format!("{section}.{key}");
    let list = Value::Array(choices.to_vec());
    if let Some((i, repeated)) = choices
        .iter()
        .enumerate()
        .find(|(i, c)| choices[..*i].iter().any(|d| d == *c))
    {
        return Err(Error::param(
            &field,
            format!(
                "`{key} = {list}` lists {repeated} twice (entry {}): every value of a list is a job, so the jobs \
                 would repeat and be averaged twice; give each value once",
                i + 1
            ),
        ));
    }
    if section == "surface" && PER_SIDE.contains(&key) && choices.len() == 2 && choices.iter().all(is_number) {
        let (a, b) = (&choices[0], &choices[1]);
        return Err(Error::param(
            &field,
            format!(
                "`{key} = {list}` is ambiguous in a study: a run file reads it as one rectangle, a study as two \
                 values; write `{key} = [[{a}, {b}]]` for one rectangle ({a} along x, {b} along y), or \
                 `{key} = [[{a}, {a}], [{b}, {b}]]` for two squares"
            ),
        ));
    }
    Ok(())
}

fn is_number(v: &Value) -> bool {
    matches!(v, Value::Integer(_) | Value::Float(_))
}

/// One material of a study: its name, its table of single values, the values that vary, and the
/// surface keys it overrides.
type MaterialChoice = (String, Table, BTreeMap<String, Value>, Table);

/// The materials of a study: one `[material]` table (lists allowed) or a `[[materials]]` array of
/// named tables, each possibly with a `surface` table of its own surface parameters.
fn materials(table: &Table) -> Result<Vec<MaterialChoice>> {
    let mut materials = Vec::new();
    match (table.get("material"), table.get("materials")) {
        (Some(_), Some(_)) => return Err(Error::run_file("give either [material] or [[materials]], not both")),
        (_, Some(Value::Array(items))) => {
            for (i, item) in items.iter().enumerate() {
                let Value::Table(t) = item else {
                    return Err(Error::run_file("[[materials]] entries must be tables"));
                };
                let mut t = t.clone();
                let name = match t.remove("name") {
                    Some(Value::String(s)) => s,
                    None => format!("material{}", i + 1),
                    Some(_) => return Err(Error::run_file("[[materials]] `name` must be a string")),
                };
                crate::check::name("[[materials]] `name`", &name).map_err(Error::run_file)?;
                // A material may carry its own surface parameters (e.g. the steady-state h_rms of
                // Kim et al.'s ceramics): `[materials.surface]` keys replace those of [surface].
                let overrides = match t.remove("surface") {
                    None => Table::new(),
                    Some(Value::Table(o)) => o,
                    Some(_) => {
                        return Err(Error::run_file(format!(
                            "[[materials]] `{name}`: `surface` must be a table"
                        )))
                    }
                };
                for (m, v) in product(&t, "material", &["fracture_energies", "fracture_toughness"])? {
                    materials.push((name.clone(), m, v, overrides.clone()));
                }
            }
        }
        (_, Some(_)) => {
            return Err(Error::run_file(
                "`materials` must be an array of tables ([[materials]])",
            ))
        }
        (_, None) => {
            let mut t = section(table, "material")?;
            let name = match t.remove("name") {
                Some(Value::String(s)) => s,
                None => "material".to_string(),
                Some(other) => {
                    return Err(Error::run_file(format!(
                        "[material] `name` must be a string, not {other}"
                    )))
                }
            };
            crate::check::name("[material] `name`", &name).map_err(Error::run_file)?;
            for (m, v) in product(&t, "material", &["fracture_energies", "fracture_toughness"])? {
                materials.push((name.clone(), m, v, Table::new()));
            }
        }
    }
    Ok(materials)
}

fn section(table: &Table, name: &str) -> Result<Table> {
    match table.get(name) {
        None => Ok(Table::new()),
        Some(Value::Table(t)) => Ok(t.clone()),
        Some(_) => Err(Error::run_file(format!("`{name}` must be a table"))),
    }
}

/// Expands a study file's text; relative surface paths resolve against `base`, and surface files
/// must exist (their contents enter the study's hash).
pub fn expand(text: &str, base: &Path) -> Result<Study> {
    let mut study = expand_with(text, base, SurfaceFiles::MustExist)?;
    study.hash = hash_with_surfaces(&study)?;
    Ok(study)
}

/// The hash of a study with the contents of the surface files it names: the study's own hash when
/// it names none; an error when one cannot be read.
pub(crate) fn hash_with_surfaces(study: &Study) -> Result<String> {
    let mut files: Vec<&Path> = Vec::new();
    for job in &study.jobs {
        for p in job.run.surfaces.input_files() {
            if !files.contains(&p) {
                files.push(p);
            }
        }
    }
    if files.is_empty() {
        return Ok(study.hash.clone());
    }
    let mut hash = u64::from_str_radix(&study.hash, 16).unwrap_or(0);
    for file in files {
        let bytes = std::fs::read(file).map_err(|e| Error::io(file, e))?;
        hash = fnv1a_continue(hash, &bytes);
    }
    Ok(format!("{hash:016x}"))
}

/// Expands the study stored in a study folder, whose surface files need not be where they were
/// (the folder keeps the study's hash; its results are read without recomputing anything).
pub fn expand_stored(text: &str, base: &Path) -> Result<Study> {
    expand_with(text, base, SurfaceFiles::Recorded)
}

fn expand_with(text: &str, base: &Path, files: SurfaceFiles) -> Result<Study> {
    let table: Table = text
        .parse::<Table>()
        .map_err(|e| Error::run_file(e.to_string().trim_end().replace('\n', " ")))?;
    let canonical = toml::to_string(&table).map_err(|e| Error::run_file(e.to_string()))?;
    let hash = format!("{:016x}", fnv1a(canonical.as_bytes()));
    check_top_level(&table)?;
    let materials = materials(&table)?;
    let base_surface = section(&table, "surface")?;
    let contacts = product(&section(&table, "contact")?, "contact", &[])?;
    let sliding = section(&table, "sliding")?;
    // The loads, as normal forces F_N (`loads`) or nominal pressures p_N (`pressures`, turned into
    // loads by each job's run).
    let (load_key, loads) =
        match (sliding.get("loads"), sliding.get("pressures")) {
            (Some(_), Some(_)) => return Err(Error::param(
                "loads",
                "[sliding] `loads` (normal forces F_N) and `pressures` (nominal pressures p_N) both give the loads; \
                 keep one",
            )),
            (Some(Value::Array(l)), None) if !l.is_empty() => ("loads", l.clone()),
            (None, Some(Value::Array(p))) if !p.is_empty() => ("pressures", p.clone()),
            _ => return Err(Error::param(
                "loads",
                "a study needs a non-empty [sliding] `loads` list (normal forces F_N) or `pressures` list (nominal \
                 pressures p_N = F_N/(Lx·Ly))",
            )),
        };
    // Schedule settings may be lists too (e.g. `step_running_in`); the loads are the innermost axis.
    let (schedules, warnings) = per_model(&sliding, product(&sliding, "sliding", &["loads", "pressures"])?)?;
    axis_is_unambiguous("sliding", load_key, &loads)?;
    let mut jobs = Vec::new();
    for (name, material, mv, overrides) in &materials {
        let mut surface_table = base_surface.clone();
        surface_table.extend(overrides.clone());
        for (surface, sv) in &product(&surface_table, "surface", &[])? {
            for ((contact, cv), (schedule, schv)) in contacts.iter().flat_map(|c| schedules.iter().map(move |s| (c, s)))
            {
                for load in &loads {
                    let mut run = Table::new();
                    if let Some(u) = table.get("units") {
                        run.insert("units".into(), u.clone());
                    }
                    run.insert("surface".into(), Value::Table(surface.clone()));
                    run.insert("material".into(), Value::Table(material.clone()));
                    run.insert("contact".into(), Value::Table(contact.clone()));
                    let mut sl = schedule.clone();
                    sl.insert(load_key.into(), Value::Array(vec![load.clone()]));
                    run.insert("sliding".into(), Value::Table(sl));
                    let index = jobs.len();
                    let config = RunConfig::from_table(run, base, files)
                        .map_err(|e| Error::run_file(format!("study job {index} ({name}): {e}")))?;
                    let mut varying = sv.clone();
                    varying.extend(mv.clone());
                    varying.extend(cv.clone());
                    varying.extend(schv.clone());
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
    if jobs.is_empty() {
        return Err(no_jobs(&table, base, files));
    }
    Ok(Study {
        jobs,
        hash,
        canonical,
        warnings,
    })
}

/// The top-level keys of a study file: the tables a run file has, `materials`, and one unit system.
fn check_top_level(table: &Table) -> Result<()> {
    for key in table.keys() {
        if !["units", "surface", "material", "materials", "contact", "sliding"].contains(&key.as_str()) {
            return Err(Error::run_file(format!(
                "unknown key `{key}` at the top of the study file"
            )));
        }
    }
    if let Some(Value::Array(units)) = table.get("units") {
        return Err(Error::param(
            "units",
            format!(
                "`units = {}` is a list, but the unit system is one value for the whole study: give `units = \
                 \"reduced\"` or `units = \"si\"`, and run one study per unit system",
                Value::Array(units.clone())
            ),
        ));
    }
    Ok(())
}

/// Why a study expands to no jobs: an empty list, named; or a key in the wrong place (`materials =
/// []` under [surface]), which the study with one value in place of each empty list names.
fn no_jobs(table: &Table, base: &Path, files: SurfaceFiles) -> Error {
    let mut probe = table.clone();
    fill_empty_lists(&mut probe);
    if probe != *table {
        let text = match toml::to_string(&probe) {
            Ok(text) => text,
            Err(e) => return Error::run_file(e.to_string()),
        };
        if let Err(e) = expand_with(&text, base, files) {
            if e.to_string().contains("unknown field") {
                return e;
            }
        }
    }
    let empty: Vec<String> = find_empty_lists(table);
    Error::run_file(format!(
        "the study expands to no jobs: {} empty; give at least one value",
        if empty.is_empty() {
            "a list is".to_string()
        } else {
            format!("{} is", empty.join(", "))
        }
    ))
}

/// The model of a schedule (`[sliding] model`, the default when absent); `None` for a value that is
/// no model (the job's validation names it).
fn model_of(schedule: &Table) -> Option<WearModel> {
    match schedule.get("model") {
        None => Some(WearModel::default()),
        Some(Value::String(s)) => s.parse().ok(),
        Some(_) => None,
    }
}

/// The models that read `[sliding]` key `key`, as `"a"` or `"a" and "b"`.
fn models_reading(key: &str) -> String {
    let names: Vec<String> = WearModel::ALL
        .iter()
        .filter(|m| m.uses(key))
        .map(|m| format!("{:?}", m.name()))
        .collect();
    names.join(" and ")
}

/// The schedules of a study with each list of a `[sliding]` setting varied only in the jobs whose
/// model reads it ([`WearModel::ignores`]): the jobs of a model that ignores it leave it out (they
/// record its default) and appear once, not once per value. A list of a setting that no model of
/// the study reads is refused (every value would be the same jobs); a single such value is a warning.
#[allow(clippy::type_complexity)]
fn per_model(
    sliding: &Table,
    schedules: Vec<(Table, BTreeMap<String, Value>)>,
) -> Result<(Vec<(Table, BTreeMap<String, Value>)>, Vec<String>)> {
    let mut models: Vec<WearModel> = Vec::new();
    for m in schedules.iter().filter_map(|(t, _)| model_of(t)) {
        if !models.contains(&m) {
            models.push(m);
        }
    }
    let mut warnings = Vec::new();
    if !models.is_empty() {
        let names: Vec<String> = models.iter().map(|m| format!("{:?}", m.name())).collect();
        let (names, does) = if names.len() == 1 {
            (format!("model {}", names[0]), "does")
        } else {
            (format!("models {}", names.join(" and ")), "do")
        };
        for (key, value) in sliding {
            if models.iter().any(|m| m.uses(key)) {
                continue;
            }
            let readers = models_reading(key);
            if matches!(value, Value::Array(_)) {
                return Err(Error::param(
                    format!("sliding.{key}"),
                    format!(
                        "`{key} = {value}` lists values of a setting that the study's {names} {does} not use (only \
                         model {readers} reads `{key}`): every value would compute the same jobs again; give the \
                         model that uses it in `model`, or remove `{key}`"
                    ),
                ));
            }
            warnings.push(format!(
                "[sliding] `{key} = {value}` is ignored: the study's {names} {does} not use `{key}` (only model \
                 {readers} reads it)"
            ));
        }
    }
    let mut out: Vec<(Table, BTreeMap<String, Value>)> = Vec::with_capacity(schedules.len());
    for (mut table, mut varying) in schedules {
        if let Some(model) = model_of(&table) {
            for key in model.ignores() {
                if matches!(sliding.get(*key), Some(Value::Array(_))) {
                    table.remove(*key);
                    varying.remove(&format!("sliding.{key}"));
                }
            }
        }
        if !out.iter().any(|(t, v)| *t == table && *v == varying) {
            out.push((table, varying));
        }
    }
    Ok((out, warnings))
}

/// Puts one value (1) in place of every empty list, at the top and in every table.
fn fill_empty_lists(table: &mut Table) {
    for (_, v) in table.iter_mut() {
        match v {
            Value::Array(items) if items.is_empty() => *v = Value::Integer(1),
            Value::Table(t) => fill_empty_lists(t),
            Value::Array(items) => {
                for t in items.iter_mut().filter_map(|i| i.as_table_mut()) {
                    fill_empty_lists(t);
                }
            }
            _ => {}
        }
    }
}

/// The keys (`section.key`) whose value is an empty list.
fn find_empty_lists(table: &Table) -> Vec<String> {
    let mut out = Vec::new();
    for (section, value) in table {
        let tables: Vec<&Table> = match value {
            Value::Table(t) => vec![t],
            Value::Array(items) => items.iter().filter_map(|i| i.as_table()).collect(),
            _ => vec![],
        };
        if matches!(value, Value::Array(items) if items.is_empty()) {
            out.push(format!("`{section}`"));
        }
        for t in tables {
            for (key, v) in t {
                if matches!(v, Value::Array(items) if items.is_empty()) {
                    out.push(format!("`{section}.{key}`"));
                }
            }
        }
    }
    out
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    pub(crate) const STUDY: &str = r#"
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

    /// A study over the seeds of `source = "spectrum"` surfaces expands to one pair per seed, as
    /// for generated surfaces; the map enters the study's hash, and each job's source and record
    /// read back as written.
    #[test]
    fn a_study_over_seeds_of_a_measured_spectrum_gives_one_pair_per_seed() {
        let dir = tempfile::tempdir().unwrap();
        let grid = crate::grid::Grid::square(64, 1.0).unwrap();
        let map = crate::surface::Surface::generate(grid, &crate::surface::SpectrumParams::paper_roughness(64, 1.0), 1)
            .unwrap();
        map.write_npy(&dir.path().join("map.npy")).unwrap();
        let study = STUDY
            .replace(
                "grid = 64\nlambda_lower = 0.125\nlambda_upper = 0.25\nrms_height = 0.005\nseed = [1, 2, 3]",
                "source = \"spectrum\"\nmap = \"map.npy\"\nmap_length = 1.0\ngrid = 32\nlength = 0.5\nseed = [1, 2]",
            )
            .split("[[materials]]\nname = \"hard\"")
            .next()
            .unwrap()
            .replace("shear_strength = [0.008, 0.01]", "shear_strength = 0.01")
            .replace("fracture_energies = [0.5e-6, 1e-6]", "fracture_energies = [0.5e-6]")
            + "[sliding]\nloads = [1e-3]\n";
        let s = expand(&study, dir.path()).unwrap();
        assert_eq!(s.jobs.len(), 2, "{study}");
        let pairs: Vec<_> = s.jobs.iter().map(|j| j.run.surfaces().unwrap()).collect();
        assert_ne!(pairs[0], pairs[1]);
        assert_eq!(pairs[0], s.jobs[0].run.surfaces().unwrap());
        assert_eq!(pairs[0].0.grid(), crate::grid::Grid::square(32, 0.5).unwrap());
        // The map's contents are part of the hash.
        let mut other = map.heights().to_vec();
        other[0] += 1e-3;
        crate::surface::Surface::new("m", grid, other)
            .unwrap()
            .write_npy(&dir.path().join("map.npy"))
            .unwrap();
        assert_ne!(expand(&study, dir.path()).unwrap().hash, s.hash);
        // The source as serialized is a run file's [surface] table, and reads back.
        let job = &s.jobs[1].run;
        let table: toml::Table = serde_json::from_value(serde_json::to_value(&job.surfaces).unwrap()).unwrap();
        let text = format!(
            "[surface]\n{}[material]\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.01\n",
            toml::to_string(&table).unwrap()
        );
        let back = RunConfig::from_toml(&text, dir.path()).unwrap();
        assert_eq!(back.surfaces, job.surfaces);
        let record = job.inputs();
        assert_eq!(record.source.as_deref(), Some("spectrum"));
        let json = serde_json::to_string(&record).unwrap();
        assert_eq!(serde_json::from_str::<InputRecord>(&json).unwrap(), record);
    }

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
    fn schedule_settings_may_be_study_axes() {
        let s = expand(
            &STUDY.replace("loads = [5e-4, 1e-3]", "loads = [5e-4, 1e-3]\nstep_running_in = [1, 4]"),
            Path::new("."),
        )
        .unwrap();
        assert_eq!(s.jobs.len(), 36);
        assert!(s.jobs.iter().all(|j| j.varying.contains_key("sliding.step_running_in")));
        let steps: Vec<usize> = s.jobs.iter().map(|j| j.inputs().step_running_in.unwrap()).collect();
        assert_eq!(steps.iter().filter(|&&k| k == 1).count(), 18);
    }

    #[test]
    fn a_list_of_a_setting_one_model_ignores_varies_only_the_jobs_of_the_model_that_reads_it() {
        let with = |extra: &str| STUDY.replace("loads = [5e-4, 1e-3]", &format!("loads = [5e-4, 1e-3]\n{extra}"));
        let distinct = |s: &Study| {
            let keys: Vec<String> = s
                .jobs
                .iter()
                .map(|j| format!("{} {} {:?}", j.material, j.load(), j.inputs()))
                .collect();
            keys.iter().enumerate().all(|(i, k)| !keys[..i].contains(k))
        };
        // 18 jobs per schedule: sliding once, the estimate once per number of maps.
        let s = expand(
            &with("model = [\"sliding\", \"estimate\"]\nestimate_samples = [4, 8]"),
            Path::new("."),
        )
        .unwrap();
        let model = |m: WearModel| s.jobs.iter().filter(move |j| j.run.model == m);
        assert_eq!(model(WearModel::Sliding).count(), 18);
        assert_eq!(model(WearModel::Estimate).count(), 36);
        assert!(model(WearModel::Sliding)
            .all(|j| j.inputs().estimate_samples.is_none() && !j.varying.contains_key("sliding.estimate_samples")));
        assert!(model(WearModel::Estimate).all(|j| j.varying.contains_key("sliding.estimate_samples")));
        assert!(distinct(&s) && s.warnings.is_empty());
        // The running-in step varies the sliding jobs only; the estimate's record the default.
        let s = expand(
            &with("model = [\"sliding\", \"estimate\"]\nstep_running_in = [1, 4]"),
            Path::new("."),
        )
        .unwrap();
        let model = |m: WearModel| s.jobs.iter().filter(move |j| j.run.model == m);
        assert_eq!(
            (model(WearModel::Sliding).count(), model(WearModel::Estimate).count()),
            (36, 18)
        );
        assert!(model(WearModel::Estimate).all(|j| j.inputs().step_running_in
            == Some(crate::sliding::DEFAULT_STEP_RUNNING_IN)
            && !j.varying.contains_key("sliding.step_running_in")));
        assert!(distinct(&s));
        // A list that no model of the study reads is refused, naming the setting and the models.
        for (extra, key, model) in [
            ("estimate_samples = [4, 8]", "estimate_samples", "\"sliding\""),
            (
                "model = \"estimate\"\nstep_running_in = [1, 4]",
                "step_running_in",
                "\"estimate\"",
            ),
        ] {
            let e = expand(&with(extra), Path::new(".")).unwrap_err().to_string();
            assert!(
                e.contains(&format!("sliding.{key}")) && e.contains(&format!("model {model}")) && e.contains("not use"),
                "{e}"
            );
        }
        // A single value that no model reads is a warning naming it.
        let s = expand(&with("estimate_samples = 8"), Path::new(".")).unwrap();
        assert_eq!(s.jobs.len(), 18);
        assert!(
            s.warnings.len() == 1
                && s.warnings[0].contains("estimate_samples = 8")
                && s.warnings[0].contains("model \"sliding\""),
            "{:?}",
            s.warnings
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
    fn a_study_without_jobs_or_with_a_bad_name_is_an_error() {
        let e = expand(&STUDY.replace("seed = [1, 2, 3]", "seed = []"), Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(e.contains("no jobs") && e.contains("surface.seed"), "{e}");
        let single = "[surface]\ngrid = 64\nlambda_lower = 0.125\nlambda_upper = 0.25\nrms_height = 0.005\n[material]\n\
                      name = 5\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.01\n[sliding]\nloads = [1e-3]\n";
        let e = expand(single, Path::new(".")).unwrap_err().to_string();
        assert!(e.contains("`name` must be a string"), "{e}");
    }

    #[test]
    fn repeated_values_and_two_element_grids_are_refused_with_the_fix() {
        let e = |text: String| expand(&text, Path::new(".")).unwrap_err().to_string();
        let seeds = e(STUDY.replace("seed = [1, 2, 3]", "seed = [1, 1, 2]"));
        assert!(
            seeds.contains("surface.seed") && seeds.contains("lists 1 twice") && seeds.contains("once"),
            "{seeds}"
        );
        let loads = e(STUDY.replace("loads = [5e-4, 1e-3]", "loads = [5e-4, 5e-4]"));
        assert!(loads.contains("loads") && loads.contains("twice"), "{loads}");
        let grid = e(STUDY.replace("grid = 64", "grid = [64, 32]"));
        assert!(
            grid.contains("surface.grid") && grid.contains("[[64, 32]]") && grid.contains("[[64, 64], [32, 32]]"),
            "{grid}"
        );
        // The unambiguous spellings: one rectangle, or two squares.
        let rect = expand(&STUDY.replace("grid = 64", "grid = [[64, 32]]"), Path::new(".")).unwrap();
        assert!(rect
            .jobs
            .iter()
            .all(|j| j.inputs().grid == Some(64) && j.inputs().grid_y == Some(32)));
        let squares = expand(
            &STUDY.replace("grid = 64", "grid = [[64, 64], [32, 32]]"),
            Path::new("."),
        )
        .unwrap();
        let n: Vec<Option<usize>> = squares.jobs.iter().map(|j| j.inputs().grid).collect();
        assert!(
            n.contains(&Some(64)) && n.contains(&Some(32)) && squares.jobs.iter().all(|j| j.inputs().grid_y.is_none())
        );
        // Three values are an axis as before.
        assert_eq!(
            expand(&STUDY.replace("grid = 64", "grid = [64, 32, 128]"), Path::new("."))
                .unwrap()
                .jobs
                .len(),
            54
        );
    }

    #[test]
    fn a_list_of_unit_systems_and_a_misplaced_empty_list_name_the_fix() {
        let e = expand(&format!("units = [\"si\", \"reduced\"]\n{STUDY}"), Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("units") && e.contains("one study per unit system") && !e.contains("unit variant"),
            "{e}"
        );
        let e = expand(
            &STUDY.replace("seed = [1, 2, 3]", "seed = [1, 2, 3]\nmaterials = []"),
            Path::new("."),
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("unknown") && e.contains("materials"), "{e}");
    }

    #[test]
    fn the_hash_covers_the_surface_files() {
        let dir = tempfile::tempdir().unwrap();
        let write = |name: &str, v: f64| {
            let h: Vec<f64> = (0..256).map(|k| v * (k as f64 * 0.1).sin()).collect();
            crate::io::write_npy_f64(&dir.path().join(name), 16, 16, &h).unwrap();
        };
        write("top.npy", 1e-3);
        write("bottom.npy", 2e-3);
        let text = "[surface]\ntop = \"top.npy\"\nbottom = \"bottom.npy\"\nlength = 1.0\n[material]\nyoungs_modulus = 1.0\n\
                    poisson_ratio = 0.3\nshear_strength = 0.01\nfracture_energies = [1e-6]\n[sliding]\nloads = [1e-3]\n";
        let before = expand(text, dir.path()).unwrap().hash;
        write("top.npy", 1.5e-3);
        let after = expand(text, dir.path()).unwrap().hash;
        assert_ne!(before, after);
        // A stored study is read back without its surfaces.
        std::fs::remove_file(dir.path().join("top.npy")).unwrap();
        assert!(expand(text, dir.path()).is_err());
        assert_eq!(expand_stored(text, dir.path()).unwrap().jobs.len(), 1);
    }

    /// A study folder committed to a repository or moved with its surface files: its job files,
    /// which record the map where the study ran, are the jobs of the study read where it lies
    /// now. The map is compared by its contents (the hash), not by its path.
    #[test]
    fn a_job_is_known_by_its_surfaces_contents_not_by_where_the_folder_lies() {
        let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
        let h: Vec<f64> = (0..256).map(|k| 1e-3 * (k as f64 * 0.37).sin()).collect();
        for dir in [&a, &b] {
            crate::io::write_npy_f64(&dir.path().join("map.npy"), 16, 16, &h).unwrap();
        }
        let text = "[surface]\nsource = \"spectrum\"\nmap = \"map.npy\"\nmap_length = 1.0\ngrid = 32\nlength = 0.5\n\
                    seed = 1\n[material]\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.01\n\
                    fracture_energies = [0.5e-6]\n[sliding]\nloads = [1e-3]\n";
        let (there, here) = (expand(text, a.path()).unwrap(), expand(text, b.path()).unwrap());
        assert_eq!(there.hash, here.hash);
        let job = &there.jobs[0];
        assert_ne!(job.inputs().map, here.jobs[0].inputs().map);
        let result = JobResult {
            format: crate::output::JOB_FORMAT,
            provenance: crate::output::Provenance::current(),
            index: 0,
            material: job.material.clone(),
            inputs: job.inputs(),
            load: job.load(),
            flow_pressure: 0.0,
            effective_modulus: 0.0,
            results: Vec::new(),
            steps: Vec::new(),
            total_iterations: 0,
            seconds: 0.0,
            warnings: Vec::new(),
            estimates: Vec::new(),
        };
        assert!(here.jobs[0].is_result_of(&result));
        // Any other input is another job.
        let longer = expand(&text.replace("map_length = 1.0", "map_length = 2.0"), b.path()).unwrap();
        assert!(!longer.jobs[0].is_result_of(&result));
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
