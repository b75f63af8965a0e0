//! The particle-rule seam (`wear::ParticleRule`): a rule written outside the library, with a known
//! answer, plugged into a run through `[sliding] particle_rule`'s type alone, slides like the
//! paper's rule (same contact solutions, its own particles), is recorded in the summary, keeps its
//! state through a checkpoint and shows its junction states to an observer.

use std::path::Path;

use wearsim::config::RunConfig;
use wearsim::run::SlidingRun;
use wearsim::sliding::{Checkpointing, Resumed};
use wearsim::wear::shear::ShearCompliance;
use wearsim::wear::{
    JunctionState, LabelledStep, ParticleRule, ParticleRuleKind, ParticleRuleSpec, StepWear, INTERACTING,
    PARTICLE_RULES,
};

/// A trivial rule: every junction at least d* across forms a particle at every step, with no
/// memory of the previous step. Its answer: N*₊ is the running sum of N*, V the running sum of the
/// critical junctions' particle volumes.
struct EveryCriticalJunction {
    critical_area: f64,
    n_formed: usize,
    volume: f64,
    /// The distance slid over the run, from what each step is handed.
    slid: f64,
    states: Vec<JunctionState>,
}

impl ParticleRule for EveryCriticalJunction {
    fn step(&mut self, step: &LabelledStep, _scratch: &mut [bool]) -> StepWear {
        self.slid += step.slid;
        self.states.clear();
        let mut n_critical = 0;
        for j in step.junctions {
            if j.area >= self.critical_area {
                n_critical += 1;
                self.volume += j.volume;
                self.states.push(JunctionState::Forming);
            } else {
                self.states.push(JunctionState::Below);
            }
        }
        self.n_formed += n_critical;
        StepWear {
            n_critical,
            n_formed: self.n_formed,
            volume: self.volume,
        }
    }

    fn states(&self) -> &[JunctionState] {
        &self.states
    }

    fn carried(&self) -> serde_json::Value {
        serde_json::json!([self.n_formed, self.volume, self.slid])
    }

    fn restore(&mut self, carried: serde_json::Value) -> Result<(), String> {
        let (n, v, s): (usize, f64, f64) = serde_json::from_value(carried).map_err(|e| e.to_string())?;
        (self.n_formed, self.volume, self.slid) = (n, v, s);
        Ok(())
    }
}

const EVERY_CRITICAL_JUNCTION: ParticleRuleKind = ParticleRuleKind {
    name: "every-critical-junction",
    description: "every junction at least d* across forms a particle at every step",
    parameters: &[],
    needs_shear: false,
    memory_arrays: 0.0,
    make: |setup| {
        Box::new(EveryCriticalJunction {
            critical_area: wearsim::junctions::circle_area(setup.critical_diameter),
            n_formed: 0,
            volume: 0.0,
            slid: 0.0,
            states: Vec::new(),
        })
    },
};

const RUN: &str = "[surface]\ngrid = 32\nlambda_lower = 0.125\nlambda_upper = 0.5\nrms_height = 0.01\nseed = 3\n\
                   [material]\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.01\n\
                   fracture_energies = [0.25e-6, 1e-6]\n[sliding]\nloads = [2e-3, 4e-3]\n";

/// The run of `RUN` with `rule`, derived through the builder (a built run is not changed).
fn config(rule: ParticleRuleKind) -> RunConfig {
    let config = RunConfig::from_toml(RUN, Path::new(".")).unwrap();
    let sliding = config.sliding.clone().unwrap().with_particle_rule(rule);
    config.to_builder().sliding(sliding).build().unwrap()
}

#[test]
fn a_rule_written_outside_the_library_slides_with_its_known_answer() {
    let paper = config(ParticleRuleKind::default());
    let reference = SlidingRun::prepare(&paper).unwrap().run(|_| {}).unwrap();
    let trivial = config(EVERY_CRITICAL_JUNCTION);
    let mut states_seen = 0;
    let outcome = SlidingRun::prepare(&trivial)
        .unwrap()
        .run(|view| {
            // The observer sees the rule's own junction states.
            for e in 0..2 {
                let states = view.junction_states(e);
                assert_eq!(states.len(), view.record.junctions);
                assert_eq!(
                    states.iter().filter(|s| **s == JunctionState::Forming).count(),
                    view.record.wear[e].n_critical
                );
                states_seen += states.len();
                // Each step is handed the distance slid since the previous one.
                let slid = view.rules[e].carried()[2].as_f64().unwrap();
                assert!((slid - view.record.s).abs() < 1e-12, "{slid} vs s = {}", view.record.s);
            }
        })
        .unwrap();
    assert!(states_seen > 0);
    for (run, paper_run) in outcome.runs.iter().zip(&reference.runs) {
        for e in 0..2 {
            let mut formed = 0;
            for (step, paper_step) in run.steps.iter().zip(&paper_run.steps) {
                // The same contact solutions and junctions: the rules differ only in particles.
                assert_eq!(
                    (step.junctions, step.contact_area, step.iterations),
                    (paper_step.junctions, paper_step.contact_area, paper_step.iterations)
                );
                assert_eq!(step.wear[e].n_critical, paper_step.wear[e].n_critical);
                formed += step.wear[e].n_critical;
                assert_eq!(step.wear[e].n_formed, formed);
                assert!(step.wear[e].n_formed >= paper_step.wear[e].n_formed);
            }
            // V₀ is the same at s = 0, where both rules count every critical junction once.
            assert_eq!(run.results[e].initial_volume, paper_run.results[e].initial_volume);
        }
    }
    let summary = outcome.summary();
    assert_eq!(summary["inputs"]["sliding"]["particle_rule"], "every-critical-junction");
    assert_eq!(
        reference.summary()["inputs"]["sliding"]["particle_rule"],
        PARTICLE_RULES[0].name
    );
}

#[test]
fn a_rule_keeps_its_state_through_a_checkpoint() {
    for rule in [EVERY_CRITICAL_JUNCTION, INTERACTING] {
        resumes_as_if_uninterrupted(rule);
    }
}

/// A run of `rule` stopped after 11 steps and resumed from its checkpoint takes the steps an
/// uninterrupted run takes; the paper's rule does not take its checkpoint.
fn resumes_as_if_uninterrupted(rule: ParticleRuleKind) {
    let run = config(rule);
    let whole = SlidingRun::prepare(&run).unwrap().run(|_| {}).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let checkpointing = Checkpointing {
        path: dir.path().join("run.checkpoint"),
        every: std::time::Duration::ZERO,
    };
    let interrupt = wearsim::Interrupt::default();
    let stopped = SlidingRun::prepare(&run)
        .unwrap()
        .interrupted_by(&interrupt)
        .run_resumable(
            Some(&checkpointing),
            |_| {},
            |view| {
                if view.done == 11 {
                    interrupt.request();
                }
            },
        );
    assert!(matches!(stopped, Err(wearsim::Error::Interrupted)));
    // The paper's rule does not take another rule's checkpoint.
    let paper_config = config(ParticleRuleKind::default());
    let mut paper = SlidingRun::prepare(&paper_config).unwrap().start().unwrap();
    assert!(matches!(paper.resume(&checkpointing.path), Resumed::Ignored(_)));
    let mut resumed = None;
    let again = SlidingRun::prepare(&run)
        .unwrap()
        .run_resumable(Some(&checkpointing), |r| resumed = Some(r.clone()), |_| {})
        .unwrap();
    assert!(matches!(resumed, Some(Resumed::At { done: 11, .. })), "{resumed:?}");
    for (a, b) in whole.runs.iter().zip(&again.runs) {
        assert_eq!((&a.steps, &a.results), (&b.steps, &b.results));
    }
}

#[test]
fn a_run_file_names_the_rule_and_an_unknown_name_is_refused_with_the_choices() {
    let named = RunConfig::from_toml(&format!("{RUN}particle_rule = \"overlap\"\n"), Path::new(".")).unwrap();
    assert_eq!(
        named.sliding.as_ref().unwrap().particle_rule,
        ParticleRuleKind::default().into()
    );
    let e = RunConfig::from_toml(&format!("{RUN}particle_rule = \"sometimes\"\n"), Path::new("."))
        .unwrap_err()
        .to_string();
    assert!(e.contains("particle_rule") && e.contains("\"overlap\""), "{e}");
}

#[test]
fn a_run_file_gives_a_rule_its_parameters_in_a_table_or_in_its_name() {
    let table = format!("{RUN}\n[sliding.particle_rule]\nname = \"interacting\"\nreach = 2\n");
    let config = RunConfig::from_toml(&table, Path::new(".")).unwrap();
    let rule = config.sliding.as_ref().unwrap().particle_rule.clone();
    assert_eq!(rule.to_string(), "interacting(reach=2, particle=hull)");
    let short = RunConfig::from_toml(
        &format!("{RUN}particle_rule = \"interacting(reach=2)\"\n"),
        Path::new("."),
    );
    assert_eq!(short.unwrap().sliding.as_ref().unwrap().particle_rule, rule);
    let e = RunConfig::from_toml(
        &format!("{RUN}\n[sliding.particle_rule]\nname = \"interacting\"\nreach = \"far\"\n"),
        Path::new("."),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("sliding.particle_rule.reach") && e.contains("not a number"),
        "{e}"
    );
    // Recorded with every parameter in the summary's inputs.
    assert_eq!(
        config.inputs().particle_rule.as_deref(),
        Some("interacting(reach=2, particle=hull)")
    );
}

/// The interacting rule slides the same contact solutions as the paper's rule; where it forms no
/// combined particle, its N*, N*₊ and V are the paper's at every step; it keeps its state through
/// a checkpoint like any rule.
#[test]
fn the_interacting_rule_is_the_papers_where_no_junctions_join() {
    // d* well under a pixel (every neighbour joins) and of 7 px (junctions of a few pixels: none do).
    let run = RUN.replace("[0.25e-6, 1e-6]", "[0.25e-6, 2.5e-5]");
    let config = |rule: ParticleRuleKind| {
        let config = RunConfig::from_toml(&run, Path::new(".")).unwrap();
        let sliding = config.sliding.clone().unwrap().with_particle_rule(rule);
        config.to_builder().sliding(sliding).build().unwrap()
    };
    let (paper, interacting) = (config(ParticleRuleKind::default()), config(INTERACTING));
    let paper = SlidingRun::prepare(&paper).unwrap().run(|_| {}).unwrap();
    // The combined particles so far at each step of each d*, from the rule's checkpoint state.
    let mut combined: Vec<[u64; 2]> = Vec::new();
    let interacting = SlidingRun::prepare(&interacting)
        .unwrap()
        .run(|view| combined.push([0, 1].map(|e| view.rules[e].carried()["combined"].as_u64().unwrap())))
        .unwrap();
    let (mut compared, mut joined) = (0, 0);
    let steps = interacting
        .runs
        .iter()
        .zip(&paper.runs)
        .flat_map(|(r, p)| r.steps.iter().zip(&p.steps));
    for ((step, paper_step), combined) in steps.zip(&combined) {
        assert_eq!(step.junctions, paper_step.junctions);
        for (e, &combined) in combined.iter().enumerate() {
            assert_eq!(step.wear[e].n_critical, paper_step.wear[e].n_critical);
            if combined == 0 {
                assert_eq!(step.wear[e], paper_step.wear[e]);
                compared += 1;
            } else {
                // Joining only adds particles or makes them larger.
                assert!(step.wear[e].volume > paper_step.wear[e].volume);
                joined += 1;
            }
        }
    }
    eprintln!("steps equal to the paper's rule: {compared}; after a combined particle: {joined}");
    assert!(
        compared > 0 && joined > 0,
        "{compared} steps equal, {joined} after a combined particle"
    );
    assert_eq!(
        interacting.summary()["inputs"]["sliding"]["particle_rule"],
        "interacting(reach=1, particle=hull)"
    );
}

#[derive(serde::Deserialize)]
struct Reference {
    grid: usize,
    poisson_ratio: f64,
    disc: Disc,
    along_x: Vec<(f64, f64)>,
    along_y: Vec<(f64, f64)>,
}

#[derive(serde::Deserialize)]
struct Disc {
    radius_squared_strict: i32,
    pixels: usize,
}

/// The interaction energy of two sheared junctions against tamaas's tangential (Neumann) solve of
/// the same traction (`bench/interaction_energy_reference.py`, tamaas 2.9): two discs of 16 px in
/// a 256² box, the energy of the pair over twice one disc's, from 1.30 at contact to 1.02 with
/// their centres four diameters apart along the shear (1.004 at five).
#[test]
fn the_interaction_energy_of_two_junctions_is_tamaas_s() {
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/interaction_energy_reference.json"),
    )
    .unwrap();
    let r: Reference = serde_json::from_str(&text).unwrap();
    let c = ShearCompliance::new(r.grid, r.grid, r.poisson_ratio);
    let disc = |x0: i32, y0: i32| -> Vec<(i32, i32)> {
        let mut out = Vec::new();
        for i in x0 - 9..=x0 + 9 {
            for j in y0 - 9..=y0 + 9 {
                if (i - x0).pow(2) + (j - y0).pow(2) < r.disc.radius_squared_strict {
                    out.push((i, j));
                }
            }
        }
        out
    };
    let one = disc(128, 128);
    assert_eq!(one.len(), r.disc.pixels);
    let single = c.self_energy(&one);
    for (along, rows) in [((1, 0), &r.along_x), ((0, 1), &r.along_y)] {
        for &(s, expected) in rows {
            let s = s as i32;
            let a = disc(128 - along.0 * (s / 2), 128 - along.1 * (s / 2));
            let b = disc(
                128 - along.0 * (s / 2) + along.0 * s,
                128 - along.1 * (s / 2) + along.1 * s,
            );
            let ratio = (c.self_energy(&a) + c.self_energy(&b) + c.cross_energy(&a, &b)) / (2.0 * single);
            assert!(
                (ratio - expected).abs() < 1e-9,
                "s = {s} along {along:?}: {ratio} vs tamaas {expected}"
            );
        }
    }
    // The end points the rule's documentation states.
    assert!((r.along_x[0].1 - 1.30).abs() < 0.01 && (r.along_x.last().unwrap().1 - 1.0).abs() < 0.01);
    let spec: ParticleRuleSpec = "interacting".parse().unwrap();
    assert_eq!(spec.kind, INTERACTING);
}
