//! The measured-surface set, committed in `evidence/measured`: six 256² crops of public instrument
//! maps (`maps/NAME/heights.npy`; `SOURCE.md` gives their origin and licence), each slid as two
//! periodic pairs carrying its measured spectrum (`source = "spectrum"`) at three loads and two d*
//! (`studies/NAME.toml`, run into the study folder `NAME`, whose job files are committed like
//! `evidence/paper-l4`), and the static maps that `wearsim estimate-check` takes of every job
//! (`static-maps.json`). docs/estimate.md ("Measured surfaces, committed") gives the table these
//! tests print and how to regenerate the set:
//!
//! ```text
//! python bench/measured_set.py --wearsim target/ci/wearsim --commit COMMIT FILE…   # the crops and studies
//! wearsim study run evidence/measured/studies/NAME.toml --out evidence/measured/NAME   # each map
//! WEARSIM_WRITE_STATIC_MAPS=1 cargo test --profile ci -p wearsim --test integration \
//!     measured_set::the_static_maps_are_the_codes -- --ignored
//! ```
//!
//! Every setting (map × load × 𝒢 × seed) is scored, none left out for its particles: the estimate
//! as every front end gives it (`load_estimate`) must hold the sliding W in its interval or decline
//! the interval (`interval_withheld`) — on measured surfaces it declines, their spectrum not being
//! the calibrated one — and the decline must still be needed: the library's sampling interval
//! before any withholding (`results_of`) must miss the sliding W in more than 10 % of the settings.
//! The static maps are read from the committed file (solving them again takes about a minute);
//! the first map of the cheapest job is solved again here, and all of them by the ignored test.

use std::collections::BTreeMap;
use std::path::PathBuf;

use wearsim::error::Interrupt;
use wearsim::estimate::{
    fit_distance, load_estimate, results_of, run_reach, EstimateResult, Sample, Sampling, CALIBRATED_DOMAIN,
    CALIBRATION,
};
use wearsim::output::JobResult;
use wearsim::run::{sliding_schedule, SlidingRun};
use wearsim::study::compare::map_jobs;
use wearsim::study::store::{read_result, stored_study};
use wearsim::study::{expand_stored, Job};
use wearsim::Grid;

/// The maps of the set, each a study folder of `evidence/measured`.
const MAPS: [&str; 6] = ["di-1", "di-3", "mi-1", "opd-1", "plu-1", "x3p-2"];

/// The coverage the estimate's 95 % interval must reach where it is given.
const COVERAGE: f64 = 0.9;

fn set() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../evidence/measured"))
}

/// The committed study of one map: its jobs with their job files as read back (each checked to be
/// the job's: its inputs, its checksum, the study's hash over the map's contents).
fn committed(name: &str) -> Vec<(Job, JobResult)> {
    let dir = set().join(name);
    let (text, base) = stored_study(&dir).unwrap_or_else(|e| {
        panic!("evidence/measured/{name}: {e}; regenerate the study as the header of tests/measured_set.rs says")
    });
    let study = expand_stored(&text, &base).unwrap();
    assert_eq!(study.jobs.len(), 6, "{name}: 2 seeds × 3 loads");
    study
        .jobs
        .into_iter()
        .map(|job| {
            let r = read_result(&job, &dir).unwrap_or_else(|e| {
                panic!("evidence/measured/{name}, {}: {e}", job.describe());
            });
            (job, r)
        })
        .collect()
}

/// `static-maps.json`: per map, per job index, the static maps `wearsim estimate-check` takes.
type StaticMaps = BTreeMap<String, Vec<Vec<Sample>>>;

fn static_maps_path() -> PathBuf {
    set().join("static-maps.json")
}

fn static_maps() -> StaticMaps {
    let text = std::fs::read_to_string(static_maps_path()).expect("evidence/measured/static-maps.json is committed");
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    serde_json::from_value(v["maps"].clone()).unwrap()
}

/// One setting of the set: the sliding run's W and particles beside the estimate as every front
/// end gives it (`given`) and the library's sampling estimate before any withholding (`sampled`).
struct Setting {
    map: &'static str,
    job: usize,
    seed: u64,
    nominal_pressure: f64,
    critical_diameter_pixels: f64,
    particles: usize,
    sliding: f64,
    given: EstimateResult,
    sampled: EstimateResult,
}

fn settings() -> Vec<Setting> {
    let maps = static_maps();
    let mut out = Vec::new();
    for name in MAPS {
        let samples = maps
            .get(name)
            .unwrap_or_else(|| panic!("static-maps.json holds no maps of {name}: regenerate it (the ignored test)"));
        for (job, r) in committed(name) {
            let samples = &samples[job.index];
            let inputs = job.inputs();
            let sliding = sliding_schedule(&job.run).unwrap();
            let (n, length) = (inputs.grid.unwrap(), inputs.length);
            let kind = job.run.surfaces.estimate_kind(Grid::square(n, length).unwrap());
            let reach = run_reach(&CALIBRATED_DOMAIN, &kind, sliding, length);
            let fit = fit_distance(sliding, length);
            let material = &job.run.material;
            let box_sides = (length, length);
            let (given, _) = load_estimate(samples, material, job.load(), box_sides, fit, &CALIBRATION, &reach);
            let (sampled, _) = results_of(samples, material, job.load(), box_sides, fit, &CALIBRATION);
            for ((w, g), s) in r.results.iter().zip(given).zip(sampled) {
                let sliding = w.wear_rate.unwrap_or_else(|| {
                    panic!(
                        "evidence/measured/{name}, {}: the sliding run gives no W (its fit window holds too few \
                         steps); regenerate the set with a longer `distance`",
                        job.describe()
                    )
                });
                out.push(Setting {
                    map: name,
                    job: job.index,
                    seed: inputs.seed.unwrap(),
                    nominal_pressure: inputs.nominal_pressure(job.load()),
                    critical_diameter_pixels: w.critical_diameter / (length / n as f64),
                    particles: w.particles_in_fit,
                    sliding,
                    given: g,
                    sampled: s,
                });
            }
        }
    }
    assert_eq!(out.len(), 72, "6 maps × 2 seeds × 3 loads × 2 𝒢");
    out
}

/// How an estimate fares against one sliding run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Outcome {
    /// The sliding W lies in the interval.
    Covered,
    /// It lies outside (a run that formed no particle where the estimate expected some included).
    NotCovered,
    /// W without an interval, the reason named.
    Declined,
    /// No static map holds a junction of d*, and the sliding run formed none: the estimate's "no
    /// particle" held.
    NoneAndNone,
    /// No static map holds a junction of d*, but the sliding run formed particles: a miss.
    NoneButFormed,
}

impl Outcome {
    fn of(e: &EstimateResult, sliding: f64, particles: usize) -> Outcome {
        match (e.wear_rate, e.wear_rate_low, e.wear_rate_high) {
            (None, _, _) if particles == 0 => Outcome::NoneAndNone,
            (None, _, _) => Outcome::NoneButFormed,
            (Some(_), Some(lo), Some(hi)) if lo <= sliding && sliding <= hi => Outcome::Covered,
            (Some(_), Some(_), Some(_)) => Outcome::NotCovered,
            _ => {
                assert!(
                    e.interval_withheld.is_some(),
                    "an interval dropped without a reason: {e:?}"
                );
                Outcome::Declined
            }
        }
    }

    /// Whether the estimate held the sliding run (a W in the interval, or no particle on either side).
    fn held(self) -> Option<bool> {
        match self {
            Outcome::Covered | Outcome::NoneAndNone => Some(true),
            Outcome::NotCovered | Outcome::NoneButFormed => Some(false),
            Outcome::Declined => None,
        }
    }
}

fn describe(s: &Setting, e: &EstimateResult) -> String {
    format!(
        "{} job {} (seed {}, p_N = {:.3e} Pa, d* = {:.0} px): sliding W {:.3e} from {} particles, estimate {} [{}, {}], \
         {:.1} particles expected",
        s.map,
        s.job,
        s.seed,
        s.nominal_pressure,
        s.critical_diameter_pixels,
        s.sliding,
        s.particles,
        e.wear_rate.map_or("none".into(), |w| format!("{w:.3e}")),
        e.wear_rate_low.map_or("-".into(), |w| format!("{w:.3e}")),
        e.wear_rate_high.map_or("-".into(), |w| format!("{w:.3e}")),
        e.expected_particles.unwrap_or(0.0)
    )
}

#[test]
fn the_first_steps_and_the_first_static_map_of_the_cheapest_measured_job_are_the_committed_ones() {
    let source = std::fs::read_to_string(set().join("SOURCE.md")).expect("evidence/measured/SOURCE.md is committed");
    assert!(
        source.contains("MIT license") && MAPS.iter().all(|m| source.contains(&format!("`{m}`"))),
        "evidence/measured/SOURCE.md must give every map's origin and SurfaceTopography's licence"
    );
    // Each study file beside the folders is the study its folder ran (the same hash over the study
    // and its map's contents), read from where it lies.
    for name in MAPS {
        let file = set().join("studies").join(format!("{name}.toml"));
        let study = wearsim::study::expand(&std::fs::read_to_string(&file).unwrap(), &set().join("studies")).unwrap();
        let recorded = std::fs::read_to_string(set().join(name).join("study.hash")).unwrap();
        assert_eq!(
            study.hash,
            recorded.trim(),
            "evidence/measured/studies/{name}.toml is not the study of evidence/measured/{name}: run it into a new \
             folder and commit that (the header of tests/measured_set.rs)"
        );
    }
    let (name, job, committed) = MAPS
        .iter()
        .flat_map(|&name| committed(name).into_iter().map(move |(j, r)| (name, j, r)))
        .min_by_key(|(_, _, r)| r.total_iterations)
        .unwrap();
    let run = SlidingRun::prepare(&job.run).unwrap();
    let mut slide = run.start().unwrap();
    // The cold solve and 11 steps: the pair made from the committed map's spectrum, its contact
    // maps, junctions, lineages and particles, as the committed file has them.
    for (i, expected) in committed.steps.iter().take(12).enumerate() {
        let view = slide.step().unwrap().expect("the job has more steps");
        assert_eq!(
            &super::evidence::as_committed(view.record, expected),
            expected,
            "evidence/measured/{name}, {}, step {i}: the sliding model no longer gives the committed steps; if the \
             change is meant, regenerate the set (the header of tests/measured_set.rs)",
            job.describe()
        );
    }
    let first = SlidingRun::prepare(&job.run)
        .unwrap()
        .estimate(Sampling::Fixed(1), &CALIBRATION, |_, _| {})
        .unwrap();
    assert_eq!(
        first.loads[0].samples[0],
        static_maps()[name][job.index][0],
        "evidence/measured/{name}, {}: the first static map is no longer the committed one; if the change is meant, \
         regenerate static-maps.json (the ignored test the_static_maps_are_the_codes)",
        job.describe()
    );
}

#[test]
#[ignore = "solves every static map of the set again: about a minute on 2 cores"]
fn the_static_maps_are_the_codes() {
    // The maps `wearsim estimate-check` takes of every job (automatic sampling), and with
    // WEARSIM_WRITE_STATIC_MAPS=1 the file written from them.
    let mut maps = StaticMaps::new();
    for name in MAPS {
        let mapped = map_jobs(&set().join(name), None, &Interrupt::default(), |_, _| {}).unwrap();
        let mut per_job = vec![Vec::new(); mapped.jobs.len()];
        for m in mapped.jobs {
            per_job[m.job.index] = m.samples;
        }
        maps.insert(name.to_string(), per_job);
    }
    if std::env::var_os("WEARSIM_WRITE_STATIC_MAPS").is_some() {
        let doc = serde_json::json!({
            "about": "the static maps (estimate::Sample) that `wearsim estimate-check` takes of every job of the \
                      study folders beside this file, with the number of maps chosen by the sampling error; \
                      written by tests/measured_set.rs (the_static_maps_are_the_codes, WEARSIM_WRITE_STATIC_MAPS=1)",
            "wearsim": wearsim::VERSION,
            "maps": maps,
        });
        std::fs::write(static_maps_path(), serde_json::to_string(&doc).unwrap() + "\n").unwrap();
        return;
    }
    assert!(
        maps == static_maps(),
        "the static maps of the measured set are no longer the committed ones; if the change is meant, regenerate \
         evidence/measured/static-maps.json with WEARSIM_WRITE_STATIC_MAPS=1 and this test"
    );
}

#[test]
fn on_the_measured_set_the_estimate_holds_the_sliding_w_or_declines_its_interval() {
    let all = settings();
    let outcomes: Vec<Outcome> = all
        .iter()
        .map(|s| Outcome::of(&s.given, s.sliding, s.particles))
        .collect();
    let count = |o: Outcome| outcomes.iter().filter(|x| **x == o).count();
    let (covered, missed) = (count(Outcome::Covered), count(Outcome::NotCovered));
    let (declined, none_none, none_formed) = (
        count(Outcome::Declined),
        count(Outcome::NoneAndNone),
        count(Outcome::NoneButFormed),
    );
    println!(
        "{} settings: interval covers {covered}, misses {missed}; declined {declined}; no W (no junction of d* in \
         any static map) {}, of which the sliding run formed particles in {none_formed}",
        all.len(),
        none_none + none_formed
    );
    // Declined for the surfaces: a measured spectrum is not the calibrated one, whatever its load.
    for (s, o) in all.iter().zip(&outcomes) {
        if *o == Outcome::Declined {
            let why = s.given.interval_withheld.as_deref().unwrap();
            assert!(
                why.contains("surfaces not of the calibrated spectrum"),
                "{}: {why}",
                describe(s, &s.given)
            );
        }
    }
    let misses: Vec<String> = all
        .iter()
        .zip(&outcomes)
        .filter(|(_, o)| **o == Outcome::NotCovered)
        .map(|(s, _)| describe(s, &s.given))
        .collect();
    assert!(
        (covered as f64) >= COVERAGE * (covered + missed) as f64,
        "on the committed measured surfaces the estimate gives a 95 % interval in {} settings and it holds the \
         sliding W in only {covered}, under {:.0} %: decline the interval there (estimate::load_estimate, \
         CALIBRATED_DOMAIN) or mend the rule, then say so in docs/estimate.md; the misses:\n{}",
        covered + missed,
        100.0 * COVERAGE,
        misses.join("\n")
    );
    // Where no static map holds a junction of d* the estimate gives no W, hence no interval to
    // decline; it warns that the sliding model may still form a rare particle. On this set that
    // is 11 settings, and the sliding run formed 1–3 particles in 4 of them: misses (as
    // `estimate-check` scores them), pinned here with the table of docs/estimate.md.
    let formed: Vec<usize> = all
        .iter()
        .zip(&outcomes)
        .filter(|(_, o)| **o == Outcome::NoneButFormed)
        .map(|(s, _)| s.particles)
        .collect();
    assert!(
        (none_none, none_formed) == (7, 4) && formed.iter().all(|&n| n <= 3),
        "the estimate now gives no W in {} settings of the committed measured set and the sliding run formed \
         particles in {none_formed} of them ({formed:?} particles), where 11 and 4 (1–3 particles each) were \
         measured: a change of the static maps or of the rule; if it is meant, update the section \"Measured \
         surfaces, committed\" of docs/estimate.md and these numbers",
        none_none + none_formed
    );
}

#[test]
fn on_the_measured_set_the_sampling_interval_alone_would_miss_the_sliding_w() {
    let all = settings();
    let outcomes: Vec<Outcome> = all
        .iter()
        .map(|s| Outcome::of(&s.sampled, s.sliding, s.particles))
        .collect();
    let held = outcomes.iter().filter(|o| o.held() == Some(true)).count();
    assert!(
        outcomes.iter().all(|o| *o != Outcome::Declined),
        "results_of withholds nothing"
    );
    println!("{}", table(&all));
    let mut errors: Vec<f64> = all
        .iter()
        .filter(|s| s.particles >= 20)
        .filter_map(|s| s.sampled.wear_rate.map(|w| (w / s.sliding - 1.0).abs()))
        .collect();
    errors.sort_by(f64::total_cmp);
    println!(
        "W: median |estimate/sliding − 1| {:.0} %, worst {:.0} %, over the {} settings with at least 20 particles",
        100.0 * 0.5 * (errors[(errors.len() - 1) / 2] + errors[errors.len() / 2]),
        100.0 * errors[errors.len() - 1],
        errors.len()
    );
    println!(
        "the sampling interval holds the sliding W in {held} of {} settings ({:.0} %)",
        all.len(),
        100.0 * held as f64 / all.len() as f64
    );
    assert!(
        (held as f64) < COVERAGE * all.len() as f64,
        "on the committed measured surfaces the library's sampling interval (estimate::results_of), which the \
         estimate declines to give there, holds the sliding W in {held} of {} settings, at least {:.0} %: the \
         decline may no longer be needed; revisit it (the surfaces' reach in estimate::run_reach and \
         CALIBRATED_DOMAIN) and the section \"Measured surfaces, committed\" of docs/estimate.md",
        all.len(),
        100.0 * COVERAGE
    );
}

/// A number of the table: 0 as 0, any other in three digits.
fn num(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else {
        format!("{x:.2e}")
    }
}

/// The table of docs/estimate.md: per map, load and d*, the two seeds side by side ("a; b").
fn table(all: &[Setting]) -> String {
    let mut rows: BTreeMap<(usize, i64, i64), Vec<&Setting>> = BTreeMap::new();
    for s in all {
        let map = MAPS.iter().position(|m| *m == s.map).unwrap();
        let key = (
            map,
            (s.nominal_pressure / 1e5).round() as i64,
            s.critical_diameter_pixels.round() as i64,
        );
        rows.entry(key).or_default().push(s);
    }
    let mut out = String::from(
        "| map | p_N (MPa) | d* (px) | particles | W sliding (m³/m): mean ± half the difference (seeds) | W estimate \
         (declined: no interval) | estimate/sliding | sampling interval | it covers |\n\
         |---|---|---|---|---|---|---|---|---|\n",
    );
    let each = |v: &[&Setting], f: &dyn Fn(&Setting) -> String| v.iter().map(|s| f(s)).collect::<Vec<_>>().join("; ");
    for ((_, _, d), v) in rows {
        let sliding: Vec<f64> = v.iter().map(|s| s.sliding).collect();
        let mean = sliding.iter().sum::<f64>() / sliding.len() as f64;
        let spread = sliding.iter().map(|w| (w - mean).abs()).fold(0.0, f64::max);
        out += &format!(
            "| `{}` | {:.0} | {d} | {} | {} ± {} ({}) | {} | {} | {} | {} |\n",
            v[0].map,
            v[0].nominal_pressure / 1e6,
            each(&v, &|s| s.particles.to_string()),
            num(mean),
            num(spread),
            each(&v, &|s| num(s.sliding)),
            each(&v, &|s| match (s.given.wear_rate, &s.given.interval_withheld) {
                (None, _) => "none".into(),
                (Some(w), Some(_)) => num(w),
                (Some(w), None) => format!("{} (interval given)", num(w)),
            }),
            each(&v, &|s| match s.given.wear_rate {
                None => "-".into(),
                Some(_) if s.sliding == 0.0 => "(none formed)".into(),
                Some(w) => format!("{:.2}", w / s.sliding),
            }),
            each(&v, &|s| match (s.sampled.wear_rate_low, s.sampled.wear_rate_high) {
                (Some(lo), Some(hi)) => format!("[{}, {}]", num(lo), num(hi)),
                _ => "-".into(),
            }),
            each(&v, &|s| match Outcome::of(&s.sampled, s.sliding, s.particles) {
                Outcome::Covered => "yes".into(),
                Outcome::NoneAndNone => "yes (none, none)".into(),
                Outcome::NotCovered => "**no**".into(),
                Outcome::NoneButFormed => "**no** (none estimated)".into(),
                Outcome::Declined => unreachable!(),
            }),
        );
    }
    out
}
