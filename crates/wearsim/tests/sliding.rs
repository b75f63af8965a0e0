//! The sliding model end to end on a small grid: bookkeeping invariants, V₀ from an independent
//! labelling, and independence from the thread count.

use wearsim::config::{RunConfig, SurfacePair, SurfaceSource, Units};
use wearsim::junctions::JunctionLabeller;
use wearsim::run::SlidingRun;
use wearsim::sliding::SlidingConfig;
use wearsim::sliding::{schedule, LoadRun};
use wearsim::surface::pair_seeds;
use wearsim::{composite_heights, ContactSolver, Generation, Material, ModulusConvention, SpectrumParams, Surface};

/// The run of `material` and `sliding` on the arrays `top` and `bottom` (connectivity 4, the
/// default solver), as a front end would build it.
fn arrays_run(top: &Surface, material: &Material, sliding: &SlidingConfig) -> RunConfig {
    RunConfig::builder(
        SurfaceSource::Arrays {
            grid: top.grid(),
            length: top.length(),
        },
        material.clone(),
    )
    .units(Units::Reduced)
    .modulus(ModulusConvention::HalfSpace)
    .connectivity(4)
    .sliding(sliding.clone())
    .stopping(wearsim::contact::SLIDING_STOPPING)
    .model(wearsim::model::WearModel::Sliding)
    .build()
    .unwrap()
}

/// Slides `config` on `top` and `bottom` through the one way in.
fn slide(config: &RunConfig, top: &Surface, bottom: &Surface) -> Vec<LoadRun> {
    SlidingRun::with_surfaces(config, SurfacePair::of_arrays(top.clone(), bottom.clone()))
        .unwrap()
        .run(|_| {})
        .unwrap()
        .runs
}

fn setup_surfaces(n: usize) -> (Surface, Surface) {
    let spectrum = SpectrumParams {
        hurst: 0.7,
        lambda_lower: 8.0 / n as f64,
        lambda_upper: 0.25,
        rms_height: 0.005,
        generation: Generation::RandomPhase,
    };
    let (a, b) = pair_seeds(21);
    (
        Surface::generate(wearsim::Grid::square(n, 1.0).unwrap(), &spectrum, a).unwrap(),
        Surface::generate(wearsim::Grid::square(n, 1.0).unwrap(), &spectrum, b).unwrap(),
    )
}

fn run(threads: usize) -> (Vec<LoadRun>, Material, SlidingConfig, Surface, Surface) {
    let n = 64;
    let (top, bottom) = setup_surfaces(n);
    let material = Material::new(1.0, 0.3, 0.01, vec![0.1e-6, 0.5e-6], 3.0).unwrap();
    let sliding = SlidingConfig {
        loads: vec![5e-4, 2e-3],
        distance: 0.5,
        running_in: 0.25,
        step_running_in: 4,
        step: 1,
        particle_rule: Default::default(),
    };
    let runs = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(|| slide(&arrays_run(&top, &material, &sliding), &top, &bottom));
    (runs, material, sliding, top, bottom)
}

#[test]
fn bookkeeping_invariants_and_initial_volume() {
    let (runs, material, sliding, top, bottom) = run(2);
    let n = top.nx();
    assert_eq!(runs.len(), 2);
    for r in &runs {
        assert_eq!(r.steps.len(), schedule(n, &sliding).len());
        for e in 0..2 {
            let mut last = (0usize, 0.0f64);
            for st in &r.steps {
                let w = st.wear[e];
                assert!(
                    w.n_formed >= last.0 && w.volume >= last.1,
                    "cumulative counts must not decrease"
                );
                assert!(w.n_critical <= st.junctions);
                assert_eq!(w.n_shrunk(), w.n_formed as i64 - w.n_critical as i64);
                last = (w.n_formed, w.volume);
            }
            let res = &r.results[e];
            let (w, k) = (res.wear_rate.unwrap(), res.wear_coefficient.unwrap());
            assert!(w >= 0.0 && k >= 0.0);
            assert!((k - w * material.flow_pressure() / r.load).abs() < 1e-15);
            // The static model over offsets: s = 0 is the first step's, the mean lies within the steps'.
            let ks: Vec<f64> = r.steps.iter().map(|st| st.statics[e].wear_coefficient).collect();
            assert_eq!(res.static_wear_coefficient, ks[0]);
            let (lo, hi) = ks
                .iter()
                .fold((f64::INFINITY, 0.0f64), |(a, b), &k| (a.min(k), b.max(k)));
            assert!(lo <= res.static_wear_coefficient_mean && res.static_wear_coefficient_mean <= hi);
            assert!(res.static_wear_coefficient_std >= 0.0 && res.static_wear_coefficient_std <= hi - lo);
            // Appendix C counts are means over the fit window.
            let window: Vec<&wearsim::sliding::StepRecord> = r.steps.iter().filter(|st| st.s >= 0.25 - 1e-12).collect();
            // The fit window starts at its first step (16 of 64 px), as the results say.
            assert_eq!(res.fit_window_start, window[0].s);
            assert_eq!(res.fit_window_start, 0.25);
            let n_star = window.iter().map(|st| st.wear[e].n_critical as f64).sum::<f64>() / window.len() as f64;
            assert!((res.critical_junctions_mean - n_star).abs() < 1e-12);
            assert!(res.junctions_mean >= res.critical_junctions_mean);
            // Particles in the fit window and the check value of Eq. 5.
            assert_eq!(
                res.particles_in_fit,
                window.last().unwrap().wear[e].n_formed - window[0].wear[e].n_formed
            );
            let d = res.critical_diameter;
            let eq5 = std::f64::consts::PI / 6.0 * d.powi(3) * res.particle_rate.unwrap();
            assert!((res.wear_rate_estimate.unwrap() - eq5).abs() <= 1e-12 * eq5.abs().max(1e-300));
            // The residence of a critical junction per particle, N*/(dN*₊/ds), wherever particles form.
            match res.particle_rate.filter(|r| *r > 0.0) {
                Some(rate) => {
                    let residence = res.critical_residence.unwrap();
                    assert!((residence - n_star / rate).abs() <= 1e-12 * residence);
                }
                None => assert_eq!(res.critical_residence, None),
            }
        }
        // The memory of the initial contact starts at every junction of s = 0 and never exceeds N.
        assert_eq!(r.steps[0].initial_junctions, r.steps[0].junctions);
        assert!(r.steps.iter().all(|st| st.initial_junctions <= st.junctions));
        assert!(r.steps.last().unwrap().initial_junctions < r.steps[0].initial_junctions);
        // V₀ from an independent solve and labelling at s = 0.
        let mut solver = ContactSolver::new(
            wearsim::Grid::square(n, 1.0).unwrap(),
            material.effective_modulus(ModulusConvention::HalfSpace),
        )
        .unwrap();
        let mut h = vec![0.0; n * n];
        composite_heights(&top, &bottom, 0, &mut h);
        let mut p = vec![0.0; n * n];
        solver.solve(&h, r.load, material.flow_pressure(), &mut p).unwrap();
        let mut labeller = JunctionLabeller::new(n, n, 4);
        labeller.label(|k| p[k] > 0.0);
        for (e, d) in material.critical_diameters().into_iter().enumerate() {
            let v0: f64 = labeller
                .junctions(1.0 / n as f64)
                .iter()
                .filter(|j| j.diameter >= d)
                .map(|j| j.volume)
                .sum();
            assert!(
                (r.results[e].initial_volume - v0).abs() <= 1e-12 * v0.max(1e-300),
                "V₀ {} vs {v0}",
                r.results[e].initial_volume
            );
        }
    }
    // The smaller d* forms at least as many particles at s = 0.
    assert!(runs[1].steps[0].wear[0].n_formed >= runs[1].steps[0].wear[1].n_formed);
}

#[test]
fn sliding_results_do_not_depend_on_thread_count() {
    // Everything but the wall-clock timings.
    let strip = |runs: Vec<LoadRun>| {
        runs.into_iter()
            .map(|r| (r.steps, r.results, r.total_iterations))
            .collect::<Vec<_>>()
    };
    assert!(
        strip(run(1).0) == strip(run(2).0),
        "results differ between 1 and 2 threads"
    );
}

/// A run stopped after `stop_after` steps (of all loads), then resumed, equals the uninterrupted run
/// bit for bit (steps, results, warnings), whether its state was saved by a checkpoint after every
/// step or only when it was stopped (the last step of a load included: the next load begins cold); a
/// checkpoint of other inputs is set aside with a reason.
#[test]
fn a_checkpointed_run_stopped_anywhere_resumes_to_the_uninterrupted_results() {
    use wearsim::sliding::{Checkpointing, Resumed};
    let (reference, material, sliding, top, bottom) = run(2);
    let config = arrays_run(&top, &material, &sliding);
    let pair = || SurfacePair::of_arrays(top.clone(), bottom.clone());
    let total = 2 * schedule(top.nx(), &sliding).len();
    let dir = tempfile::tempdir().unwrap();
    let cases = [1, 7, total / 2, total / 2 + 1, total - 1]
        .into_iter()
        .flat_map(|stop_after| [(stop_after, 0), (stop_after, 3600)]);
    for (stop_after, every) in cases {
        let checkpointing = Checkpointing {
            path: dir.path().join(format!("run-{stop_after}-{every}.checkpoint")),
            every: std::time::Duration::from_secs(every),
        };
        let interrupt = wearsim::Interrupt::default();
        let mut said = Vec::new();
        let first = SlidingRun::with_surfaces(&config, pair())
            .unwrap()
            .interrupted_by(&interrupt)
            .run_resumable(
                Some(&checkpointing),
                |r| said.push(r.clone()),
                |v| {
                    if v.done == stop_after {
                        interrupt.request();
                    }
                },
            );
        assert!(matches!(first, Err(wearsim::Error::Interrupted)), "{first:?}");
        // Saved on the way out only when no checkpoint held that state already.
        let saved_on_stop = Resumed::Saved {
            done: stop_after,
            total,
        };
        assert_eq!(
            said.contains(&saved_on_stop),
            every > 0,
            "stopped after {stop_after}: {said:?}"
        );
        let mut resumed = None;
        let runs = SlidingRun::with_surfaces(&config, pair())
            .unwrap()
            .run_resumable(Some(&checkpointing), |r| resumed = Some(r.clone()), |_| {})
            .unwrap()
            .runs;
        assert_eq!(
            resumed,
            Some(Resumed::At {
                done: stop_after,
                total
            })
        );
        assert_eq!(runs.len(), reference.len());
        for (a, b) in runs.iter().zip(&reference) {
            assert_eq!(
                (&a.steps, &a.results, &a.warnings),
                (&b.steps, &b.results, &b.warnings),
                "stopped after {stop_after}, checkpoints every {every} s"
            );
        }
    }
    // The checkpoint of another schedule is not used.
    let other = SlidingConfig {
        step: 2,
        ..sliding.clone()
    };
    let checkpointing = Checkpointing {
        path: dir.path().join(format!("run-{}-0.checkpoint", total - 1)),
        every: std::time::Duration::from_secs(3600),
    };
    let mut resumed = None;
    SlidingRun::with_surfaces(&arrays_run(&top, &material, &other), pair())
        .unwrap()
        .run_resumable(Some(&checkpointing), |r| resumed = Some(r.clone()), |_| {})
        .unwrap();
    match resumed {
        Some(Resumed::Ignored(why)) => assert!(why.contains("other inputs"), "{why}"),
        r => panic!("{r:?}"),
    }
}

/// Driving the steps by hand (as a benchmark does) takes the steps of a whole run: the step state
/// is the one loop, and saving a checkpoint mid-run from outside the loop (an interrupt path)
/// resumes to the same results.
#[test]
fn steps_taken_one_by_one_are_the_run() {
    let (reference, material, sliding, top, bottom) = run(2);
    let config = arrays_run(&top, &material, &sliding);
    let pair = || SurfacePair::of_arrays(top.clone(), bottom.clone());
    let mut slide = SlidingRun::with_surfaces(&config, pair()).unwrap().start().unwrap();
    let total = slide.total();
    let mut seen = Vec::new();
    while let Some(mut view) = slide.step().unwrap() {
        assert_eq!(view.pressure().len(), top.nx() * top.ny());
        assert_eq!(view.junction_states(0).len(), view.record.junctions);
        seen.push((view.load_index, view.step_index, view.done));
        if view.done == 5 {
            break;
        }
    }
    assert_eq!(seen.last(), Some(&(0, 4, 5)));
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("by-hand.checkpoint");
    assert!(slide.save_checkpoint(&path).unwrap(), "five steps are saved");
    let outcome = slide.finish().unwrap();
    assert_eq!(outcome.runs.len(), 2);
    let mut resumed = SlidingRun::with_surfaces(&config, pair()).unwrap().start().unwrap();
    assert_eq!(resumed.resume(&path), wearsim::sliding::Resumed::At { done: 5, total });
    let again = resumed.finish().unwrap();
    for ((a, b), c) in outcome.runs.iter().zip(&again.runs).zip(&reference) {
        assert_eq!((&a.steps, &a.results), (&c.steps, &c.results));
        assert_eq!((&b.steps, &b.results), (&c.steps, &c.results));
    }
}

#[test]
fn full_contact_near_the_flow_pressure_is_flagged_as_no_particle() {
    // Near p_m the whole box is in contact: one junction around the torus, counted as a particle
    // (k_static = 1) by the bookkeeping, which the results must flag.
    let (top, bottom) = setup_surfaces(64);
    let material = Material::new(1.0, 0.3, 0.01, vec![0.1e-6], 3.0).unwrap();
    let pm = material.flow_pressure();
    let sliding = SlidingConfig {
        loads: vec![1e-4, 0.999 * pm],
        distance: 0.25,
        running_in: 0.125,
        step_running_in: 4,
        step: 1,
        particle_rule: Default::default(),
    };
    let runs = slide(&arrays_run(&top, &material, &sliding), &top, &bottom);
    let (light, full) = (&runs[0], &runs[1]);
    assert!(light.steps.iter().all(|r| r.wrapping_junctions == 0));
    assert_eq!(light.results[0].box_wrapping_steps, 0);
    assert!(!light.warnings.iter().any(|w| w.contains("wraps the periodic box")));
    assert!(
        full.steps.iter().all(|r| r.wrapping_junctions == 1),
        "{:?}",
        full.steps.iter().map(|r| r.contact_area).collect::<Vec<_>>()
    );
    assert_eq!(full.results[0].box_wrapping_steps, full.steps.len());
    assert!(
        full.warnings
            .iter()
            .any(|w| w.contains("wraps the periodic box") && w.contains("no particle")),
        "{:?}",
        full.warnings
    );
}

#[test]
fn a_fit_window_inside_the_memory_of_the_initial_contact_is_not_run_in() {
    // Running-in of 4 pixels (s_r = L/16): shorter than the decay length of the initial contact's
    // memory on this 64² box, which is of the order of λ_u = L/4.
    let (top, bottom) = setup_surfaces(64);
    let material = Material::new(1.0, 0.3, 0.01, vec![0.1e-6], 3.0).unwrap();
    let sliding = SlidingConfig {
        loads: vec![2e-3],
        distance: 0.5,
        running_in: 0.0625,
        step_running_in: 4,
        step: 1,
        particle_rule: Default::default(),
    };
    let runs = slide(&arrays_run(&top, &material, &sliding), &top, &bottom);
    let result = &runs[0].results[0];
    let decay = result.memory_decay_length.expect("the memory decays");
    assert!(decay > 0.0625, "decay length {decay} is not above the running-in");
    let ratio = result.running_in_decay_lengths.unwrap();
    assert!((ratio - 0.0625 / decay).abs() < 1e-12);
    assert!(
        runs[0].warnings.iter().any(|w| w.contains("not run in")),
        "{:?}",
        runs[0].warnings
    );
    // The same run with a running-in of three decay lengths or more is run in: no warning.
    let long = SlidingConfig {
        running_in: ((3.0 * decay * 64.0).ceil() / 64.0).min(0.75),
        distance: 1.0,
        ..sliding.clone()
    };
    let runs = slide(&arrays_run(&top, &material, &long), &top, &bottom);
    let result = &runs[0].results[0];
    let ratio = result.running_in_decay_lengths.unwrap_or(f64::INFINITY);
    assert_eq!(
        runs[0].warnings.iter().any(|w| w.contains("not run in")),
        ratio < wearsim::sliding::RUN_IN_DECAY_LENGTHS,
        "ratio {ratio}: {:?}",
        runs[0].warnings
    );
}
