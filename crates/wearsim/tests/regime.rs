//! The wear-regime study, committed as its job files (`evidence/wear-regime`): the paper's rule and
//! the rule of interacting junctions (its two particle shapes) on five surface pairs at the paper's
//! pixel size in a box of L/8 (`studies/wear-regime.toml`, 150 jobs of 240 steps at 512²), p_N from
//! the paper's range to four times its breakdown. Its map and findings are `wearsim study collect
//! evidence/wear-regime && wearsim study plot evidence/wear-regime`; the set is regenerated, into a
//! new folder, by `wearsim study run studies/wear-regime.toml --out evidence/wear-regime-new`
//! (about 14 minutes on 2 cores). These tests keep the committed files the code's (the first steps
//! of the cheapest job of the interacting rule computed again, number for number) and hold the
//! documentation's reading of them: where each rule departs from the paper's, and which loads lie
//! in the breakdown regime.

use std::path::PathBuf;

use wearsim::output::{StudyTable, Table, TidyRow};
use wearsim::run::SlidingRun;
use wearsim::study::figures::study_figures;
use wearsim::study::findings::{findings, Verdict};
use wearsim::study::store::{read_result, stored_study};
use wearsim::study::{expand_stored, load_results};

fn folder() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../evidence/wear-regime"))
}

#[test]
fn the_first_steps_of_the_cheapest_interacting_job_are_the_committed_ones() {
    let (text, base) = stored_study(&folder()).unwrap();
    let study = expand_stored(&text, &base).unwrap();
    assert_eq!(study.jobs.len(), 150);
    let (job, committed) = study
        .jobs
        .iter()
        .filter(|job| job.inputs().particle_rule.is_some())
        .filter_map(|job| read_result(job, &folder()).ok().map(|r| (job, r)))
        .min_by_key(|(_, r)| r.total_iterations)
        .expect("the wear-regime study's job files are committed");
    let run = SlidingRun::prepare(&job.run).unwrap();
    let mut slide = run.start().unwrap();
    // The cold solve, then 30 steps: contact maps, junctions, merging, particles, volumes.
    for (i, expected) in committed.steps.iter().take(31).enumerate() {
        let view = slide.step().unwrap().expect("the job has more steps");
        assert_eq!(
            &wearsim::output::StepRow::from(view.record),
            expected,
            "job {}, step {i}",
            job.index
        );
    }
}

#[test]
fn the_map_says_where_each_rule_departs_and_the_findings_mark_the_breakdown() {
    let (_, results) = load_results(&folder()).unwrap();
    let rows: Vec<TidyRow> = results.iter().flat_map(TidyRow::of_job).collect();
    let tidy = Table::of(&rows);
    let names = vec!["wear-regime".to_string()];
    let figures = study_figures(&StudyTable::of(tidy.clone()), &results, None, Some(&names)).unwrap();
    assert_eq!(figures.len(), 1);
    let map = &figures[0];
    for entry in &map.legend {
        println!("{}", entry.label);
    }
    let labels: Vec<&str> = map.legend.iter().map(|e| e.label.as_str()).collect();
    let with = |rule: &str, words: &str| labels.iter().filter(|l| l.contains(rule) && l.contains(words)).count();
    // The hull rule forms combined particles at s = 0 only: W is the paper's rule's at every load
    // of the four materials.
    assert_eq!(with("particle=hull", "agrees up to p_N = 0.008"), 4, "{labels:#?}");
    // The members' area: see docs/interacting-junctions.md.
    assert_eq!(
        with("particle=members", "agrees up to p_N = 0.008"),
        MEMBERS_AGREE,
        "{labels:#?}"
    );
    // Where the hull rule parts from the paper's: at s = 0, with combined particles that grow in
    // number with load (d* = 16 px: τ̃ = 0.012 E, 𝒢 = 0.25×10⁻⁶ E L, five pairs summed).
    let column = |name: &str| tidy.column(name).unwrap();
    let (rule, tau, energy) = (
        column("sliding.particle_rule"),
        column("material.shear_strength"),
        column("fracture_energy"),
    );
    let (pressure, combined) = (column("nominal_pressure"), column("combined_particles"));
    let mut by_load: Vec<(f64, f64)> = Vec::new();
    for row in tidy.rows.iter().filter(|r| {
        r[rule].text().contains("particle=hull") && r[tau].number() == 0.012 && r[energy].number() == 0.25e-6
    }) {
        match by_load.iter_mut().find(|(p, _)| *p == row[pressure].number()) {
            Some((_, n)) => *n += row[combined].number(),
            None => by_load.push((row[pressure].number(), row[combined].number())),
        }
    }
    by_load.sort_by(|a, b| a.0.total_cmp(&b.0));
    let counts: Vec<f64> = by_load.iter().map(|(_, n)| *n).collect();
    assert_eq!(counts, [0.0, 1.0, 10.0, 35.0, 65.0], "{by_load:?}");
    let all = findings(&tidy);
    let breakdown = all.iter().find(|f| f.key == "breakdown-regime").unwrap();
    assert_eq!(breakdown.verdict, Verdict::Diagnostic);
    println!("{}", breakdown.observed);
    assert_eq!(breakdown.units.len(), BREAKDOWN_SETTINGS, "{}", breakdown.observed);
}

/// Materials at which the members variant agrees with the paper's rule at every load.
const MEMBERS_AGREE: usize = 1;

/// Settings (material × load) with a surface pair in the breakdown regime.
const BREAKDOWN_SETTINGS: usize = 7;
