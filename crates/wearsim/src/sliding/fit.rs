//! The fitted results of one load (paper §3 and appendices B, C) and the warnings about them.

use crate::junctions::particle_volume;
use crate::material::Material;
use crate::stats::{line_fit, mean_std, LineFit};

use super::breakdown::{breakdown_warning, BreakdownStep, LoadBreakdown};
use super::records::{finite, InitialContactMemory, StepRecord, WearResult};
use super::schedule::SlidingSetup;

/// Fewest particles after running-in for a wear rate worth a number without a warning.
pub const FEW_PARTICLES: usize = 10;

/// Warnings about d* in pixels: a critical diameter of a few pixels is not resolved.
pub fn resolution_warnings(material: &Material, pixel_size: f64) -> Vec<String> {
    material
        .critical_diameters_on(pixel_size)
        .into_iter()
        .filter(|c| c.pixels < crate::check::RESOLVED_PIXELS)
        .map(|c| {
            format!(
                "d* = {:.4e} for 𝒢 = {:.4e} is {:.2} pixels, under {}: junctions of the critical size \
                 are not resolved and the wear results follow the grid; refine `grid`",
                c.diameter,
                c.fracture_energy,
                c.pixels,
                crate::check::RESOLVED_PIXELS
            )
        })
        .collect()
}

/// Warnings about d* against the box of sides `lx` × `ly` (the run's length unit): a d* at least the
/// box's shorter side lets no junction reach it at any load (no particle can form), and one above a
/// quarter of it leaves room for a few critical junctions at most, next to their periodic images,
/// so the rates are this box's, not a larger surface's.
pub fn box_warnings(material: &Material, lx: f64, ly: f64) -> Vec<String> {
    let side = lx.min(ly);
    material
        .fracture_energies
        .iter()
        .zip(material.critical_diameters())
        .filter_map(|(&g, d)| {
            let boxes = d / side;
            if d >= side {
                Some(format!(
                    "d* = {d:.4e} for 𝒢 = {g:.4e} is {boxes:.2} times the box's shorter side ({side:.4e}): no junction \
                     can reach it in this box, so no particle forms at any load; take a box of several d* (the \
                     paper's is 43 d* at its largest 𝒢) or a smaller 𝒢"
                ))
            } else if d > side / 4.0 {
                Some(format!(
                    "d* = {d:.4e} for 𝒢 = {g:.4e} is {boxes:.2} of the box's shorter side ({side:.4e}), over a quarter: \
                     a few critical junctions at most fit in the box, next to their periodic images, so its rates are \
                     this box's rather than a larger surface's; take a box of at least 4 d*"
                ))
            } else {
                None
            }
        })
        .collect()
}

/// The warnings of a run whose W falls as the load rises, per fracture energy: for each two
/// neighbouring loads (in increasing order) where W at the higher load lies below W at the lower by
/// more than the Poisson scatter of their particle counts (the exact 95 % interval of the ratio of
/// two counts over equal fit windows, [`crate::stats::count_ratio`], scaled by the ratio of the mean
/// particle volumes, lies below 1). The paper's W grows with the load at every 𝒢 (§4.2, Fig. 4a), so
/// such a fall says the higher load lies where the model's picture fails; the warning names the
/// measures that tell which: the contact fraction, the steps with a junction around the box, the
/// run-in of both loads.
pub fn load_trend_warnings(runs: &[super::records::LoadRun]) -> Vec<String> {
    let mut order: Vec<&super::records::LoadRun> = runs.iter().collect();
    order.sort_by(|a, b| a.load.total_cmp(&b.load));
    let contact = |r: &super::records::LoadRun| mean_std(r.steps.iter().map(|s| s.contact_area)).0;
    let mut out = Vec::new();
    for pair in order.windows(2) {
        let (lo, hi) = (pair[0], pair[1]);
        for (a, b) in lo.results.iter().zip(&hi.results) {
            let (Some(wa), Some(wb)) = (a.wear_rate, b.wear_rate) else {
                continue;
            };
            if !(wb < wa && wa > 0.0) {
                continue;
            }
            let (na, nb) = (a.particles_in_fit as u64, b.particles_in_fit as u64);
            let Some(counts) = crate::stats::count_ratio(nb, na) else {
                continue;
            };
            // W = (particles × mean volume)/window: the volume ratio scales the counts' ratio.
            let volume = |w: f64, n: u64| if n > 0 { w / n as f64 } else { 0.0 };
            let scale = if nb > 0 { volume(wb, nb) / volume(wa, na) } else { 1.0 };
            let high = counts.high * scale;
            if high >= 1.0 {
                continue;
            }
            out.push(format!(
                "𝒢 = {:.4e} (d* = {:.4e}): W falls from {wa:.4e} at F_N = {:.4e} to {wb:.4e} at F_N = {:.4e} (×{:.3}, \
                 its 95 % upper end ×{high:.3} from {na} and {nb} particles), where the paper's W grows with the load \
                 (§4.2, Fig. 4a): the higher load lies where the model's picture fails; its contact fraction is {:.2} % \
                 against {:.2} %, its steps with a junction around the box {} against {}, and whether each load is \
                 run in its other warnings say (appendix C: junctions merge at high loads)",
                a.fracture_energy,
                a.critical_diameter,
                lo.load,
                hi.load,
                wb / wa,
                100.0 * contact(hi),
                100.0 * contact(lo),
                b.box_wrapping_steps,
                a.box_wrapping_steps,
            ));
        }
    }
    out
}

/// The paper's wear coefficients after running-in stay "smaller than around 0.1 in all cases"
/// (§4.2), and the dry-sliding experiments it compares with span 10⁻⁶–10⁻¹.
pub const PAPER_MAX_WEAR_COEFFICIENT: f64 = 0.1;

/// What the results of every fracture energy of a load share: where the fit window starts, the
/// memory of the initial contact, the junctions and the steps with a junction around the box.
struct LoadFits {
    fit_start: f64,
    junctions_mean: f64,
    box_wrapping_steps: usize,
    memory: InitialContactMemory,
}

/// The fitted results of one load per fracture energy (paper §3 and appendices B, C), and the
/// warnings about them.
/// `box_sides` is Lx × Ly in the run's length unit.
pub(crate) fn results_of_load(
    setup: &SlidingSetup,
    load: f64,
    pm: f64,
    steps: &[StepRecord],
    running_in: usize,
    box_sides: (f64, f64),
) -> (Vec<WearResult>, Vec<String>) {
    let fitted: Vec<&StepRecord> = steps.iter().filter(|r| r.offset >= running_in).collect();
    let mut warnings = Vec::new();
    let shared = load_fits(load, steps, &fitted, box_sides.0, &mut warnings);
    let mut results: Vec<WearResult> = setup
        .material
        .critical_diameters()
        .into_iter()
        .enumerate()
        .map(|(e, d)| {
            let context = Context {
                load,
                box_side: box_sides.0.min(box_sides.1),
                pm,
                energy: e,
                fracture_energy: setup.material.fracture_energies[e],
                critical_diameter: d,
            };
            result_of_energy(&context, steps, &fitted, &shared, &mut warnings)
        })
        .collect();
    // The breakdown measures over the fit window (appendix C); N*'s growth with load needs the
    // run's other loads and is added with them (`across_loads`).
    let measures = LoadBreakdown::of_steps(fitted.iter().map(|r| BreakdownStep::from(*r)));
    for w in &mut results {
        measures.apply_to(w);
    }
    warnings.extend(breakdown_warning(load, &measures, &[]));
    (results, warnings)
}

/// The memory of the initial contact ([`InitialContactMemory`]), the mean number of junctions and
/// the steps with a junction around the box, with their warnings.
fn load_fits(
    load: f64,
    steps: &[StepRecord],
    fitted: &[&StepRecord],
    box_length: f64,
    warnings: &mut Vec<String>,
) -> LoadFits {
    let fit_start = fitted.first().map_or(0.0, |r| r.s);
    let memory = InitialContactMemory::of_steps(
        &steps.iter().map(|r| (r.s, r.initial_junctions)).collect::<Vec<_>>(),
        fit_start,
    );
    warnings.extend(memory.warning(load, fit_start, box_length));
    let (junctions_mean, _) = mean_std(fitted.iter().map(|r| r.junctions as f64));
    let wrapping: Vec<&StepRecord> = steps.iter().filter(|r| r.wrapping_junctions > 0).collect();
    if let Some(first) = wrapping.first() {
        warnings.push(crate::wear::box_wrapping_warning(
            load,
            &format!(
                "at {} of {} steps (the first at s = {:.4e})",
                wrapping.len(),
                steps.len(),
                first.s
            ),
            wrapping.iter().map(|r| r.contact_area).fold(0.0, f64::max),
        ));
    }
    LoadFits {
        fit_start,
        junctions_mean,
        box_wrapping_steps: wrapping.len(),
        memory,
    }
}

/// The load and fracture energy a result is fitted for.
struct Context {
    load: f64,
    /// The box's shorter side (the run's length unit).
    box_side: f64,
    /// Flow pressure p_m.
    pm: f64,
    /// Index of the fracture energy in the material's list.
    energy: usize,
    fracture_energy: f64,
    critical_diameter: f64,
}

/// The warnings of the wear-rate fit of one setting (`context` names it): no particle or few over
/// the fit window (where d* is at least the box's shorter side, said as that: no load can help), or
/// V(s) far from a line (R² < 0.8).
fn fit_warnings(
    context: &str,
    particles_in_fit: usize,
    wear_rate_r2: Option<f64>,
    d_over_box: f64,
    warnings: &mut Vec<String>,
) {
    if particles_in_fit == 0 {
        let why = if d_over_box >= 1.0 {
            format!(
                "d* is {d_over_box:.2} times the box's shorter side, so no junction can reach it in this box at any \
                 load: take a box of several d*"
            )
        } else {
            "no junction grows to d* in this box at this load".into()
        };
        warnings.push(format!(
            "{context}: no particle formed after running-in, so W = 0 and its fit (R²) is undefined; {why}"
        ));
    } else if particles_in_fit < FEW_PARTICLES {
        warnings.push(format!(
            "{context}: only {particles_in_fit} particles formed after running-in (fewer than {FEW_PARTICLES}); W \
             rests on a handful of events"
        ));
    }
    if let Some(r2) = wear_rate_r2.filter(|r2| *r2 < 0.8) {
        warnings.push(format!(
            "{context}: the wear-rate fit is poor (R² = {r2:.3} < 0.8); V(s) is not linear"
        ));
    }
}

/// The warning of a wear coefficient above the paper's range ([`PAPER_MAX_WEAR_COEFFICIENT`]) by
/// more than the Poisson scatter of the `particles` it rests on: the lower end of k's exact 95 %
/// Poisson interval (k scaled by the count's) lies above it. A k of 0.13 from 20 particles is not
/// warned about; 0.77 from 40 is.
fn wear_coefficient_warning(context: &str, k: Option<f64>, particles: usize) -> Option<String> {
    let k = k.filter(|&k| k > PAPER_MAX_WEAR_COEFFICIENT && particles > 0)?;
    let low = k * crate::stats::poisson_interval(particles as u64).low / particles as f64;
    (low > PAPER_MAX_WEAR_COEFFICIENT).then(|| {
        format!(
            "{context}: k = {k:.3} (its Poisson 95 % lower end {low:.3}, from {particles} particles) lies above the \
             paper's range, k below about {PAPER_MAX_WEAR_COEFFICIENT} in every setting of §4.2 and 10⁻⁶–10⁻¹ in the \
             dry-sliding experiments it cites: severe wear, outside what the model was shown to describe; check \
             that d* is resolved and well inside the box, and the contact fraction (junctions merge at high loads, \
             appendix C)"
        )
    })
}

/// The result of one fracture energy: W, dN*₊/ds and k fitted over the fit window, the static
/// model over every offset, the means of appendix C, with the warnings about them.
fn result_of_energy(
    c: &Context,
    steps: &[StepRecord],
    fitted: &[&StepRecord],
    shared: &LoadFits,
    warnings: &mut Vec<String>,
) -> WearResult {
    let (e, d, load) = (c.energy, c.critical_diameter, c.load);
    let s: Vec<f64> = fitted.iter().map(|r| r.s).collect();
    let v: Vec<f64> = fitted.iter().map(|r| r.wear[e].volume).collect();
    let nf: Vec<f64> = fitted.iter().map(|r| r.wear[e].n_formed as f64).collect();
    let particle_fit = line_fit(&s, &nf);
    let particles_in_fit = match (fitted.first(), fitted.last()) {
        (Some(a), Some(b)) => b.wear[e].n_formed - a.wear[e].n_formed,
        _ => 0,
    };
    // Without a particle V is constant over the window: W = 0 exactly and R² undefined (a
    // least-squares fit of equal values leaves round-off, a slope of ±1e-30 and any R²).
    let wear_fit = line_fit(&s, &v).map(|f| match v.first() {
        Some(&v0) if particles_in_fit == 0 => LineFit {
            slope: 0.0,
            intercept: v0,
            r2: None,
        },
        _ => f,
    });
    let wear_rate = wear_fit.and_then(|f| finite(f.slope));
    let wear_volume_intercept = wear_fit
        .filter(|_| wear_rate.is_some())
        .and_then(|f| finite(f.intercept));
    let particle_rate = particle_fit.and_then(|f| finite(f.slope));
    let wear_rate_r2 = wear_fit.and_then(|f| f.r2);
    let context = format!("F_N = {load:.4e}, 𝒢 = {:.4e} (d* = {d:.4e})", c.fracture_energy);
    fit_warnings(&context, particles_in_fit, wear_rate_r2, d / c.box_side, warnings);
    let wear_coefficient = wear_rate.and_then(|w| finite(w * c.pm / load));
    if let Some(w) = wear_coefficient_warning(&context, wear_coefficient, particles_in_fit) {
        warnings.push(w);
    }
    let (k_mean, k_std) = mean_std(steps.iter().map(|r| r.statics[e].wear_coefficient));
    let (w_mean, w_std) = mean_std(steps.iter().map(|r| r.statics[e].wear_rate_over_omega));
    let (critical_junctions_mean, _) = mean_std(fitted.iter().map(|r| r.wear[e].n_critical as f64));
    WearResult {
        fracture_energy: c.fracture_energy,
        critical_diameter: d,
        wear_rate,
        wear_rate_r2,
        wear_volume_intercept,
        fit_window_start: shared.fit_start,
        wear_coefficient,
        particle_rate,
        wear_rate_estimate: particle_rate.and_then(|rate| finite(particle_volume(d) * rate)),
        particles_in_fit,
        initial_volume: steps[0].wear[e].volume,
        static_wear_coefficient: steps[0].statics[e].wear_coefficient,
        static_wear_rate: steps[0].statics[e].wear_rate_over_omega,
        static_wear_coefficient_mean: k_mean,
        static_wear_coefficient_std: k_std,
        static_wear_rate_mean: w_mean,
        static_wear_rate_std: w_std,
        junctions_mean: shared.junctions_mean,
        critical_junctions_mean,
        box_wrapping_steps: shared.box_wrapping_steps,
        memory_decay_length: shared.memory.decay_length,
        memory_decay_r2: shared.memory.r2,
        memory_fit_initial_junctions: shared.memory.fit_initial_junctions,
        running_in_decay_lengths: shared.memory.running_in_decay_lengths,
        initial_lineages_left: shared.memory.lineages_left,
        critical_residence: particle_rate
            .filter(|r| *r > 0.0)
            .and_then(|r| finite(critical_junctions_mean / r)),
        ..WearResult::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sliding::records::{LoadRun, Timing};

    #[test]
    fn d_star_is_warned_about_against_the_box() {
        let material = Material::new(1.0, 0.3, 0.010, vec![0.25e-6, 0.5e-6, 1.5e-6], 3.0).unwrap();
        let d = material.critical_diameters();
        // A box of 4 d₀ on its shorter side: the first d* fits, the second spans over a quarter, the
        // third exceeds it.
        let side = 4.0 * d[0] * 1.0001;
        assert!(d[1] > side / 4.0 && d[1] < side && d[2] >= side, "{d:?} {side}");
        let w = box_warnings(&material, 2.0 * side, side);
        assert_eq!(w.len(), 2, "{w:?}");
        assert!(
            w[0].contains("over a quarter") && w[0].contains("at least 4 d*"),
            "{w:?}"
        );
        assert!(
            w[1].contains("no particle forms at any load") && w[1].contains(&format!("{:.2} times", d[2] / side)),
            "{w:?}"
        );
        // No particle where d* exceeds the box: no load can help, and the warning does not say raise it.
        let mut out = Vec::new();
        fit_warnings("F_N = 1", 0, None, 1.5, &mut out);
        assert!(out[0].contains("1.50 times the box's shorter side") && !out[0].contains("at this load"));
        out.clear();
        fit_warnings("F_N = 1", 0, None, 0.5, &mut out);
        assert!(out[0].contains("in this box at this load"), "{out:?}");
    }

    #[test]
    fn k_above_the_papers_range_is_warned_about_beyond_its_poisson_scatter() {
        // 0.13 from 20 particles: the Poisson lower end (0.08) is within the range.
        assert!(wear_coefficient_warning("c", Some(0.13), 20).is_none());
        assert!(wear_coefficient_warning("c", Some(0.05), 400).is_none());
        assert!(wear_coefficient_warning("c", None, 0).is_none());
        let w = wear_coefficient_warning("c", Some(0.77), 40).unwrap();
        assert!(
            w.starts_with("c: k = 0.770 (its Poisson 95 % lower end 0.55") && w.contains("§4.2"),
            "{w}"
        );
    }

    fn run(load: f64, wear_rate: f64, particles: usize, contact: f64) -> LoadRun {
        let step = StepRecord {
            offset: 0,
            s: 0.0,
            junctions: 1,
            wrapping_junctions: 0,
            contact_area: contact,
            initial_junctions: 0,
            merged_junctions: None,
            largest_junction: None,
            iterations: 1,
            residual: 0.0,
            wear: Vec::new(),
            statics: Vec::new(),
        };
        LoadRun {
            load,
            steps: vec![step],
            results: vec![WearResult {
                fracture_energy: 1e-6,
                critical_diameter: 0.01,
                wear_rate: Some(wear_rate),
                particles_in_fit: particles,
                ..WearResult::default()
            }],
            total_iterations: 1,
            max_iterations: 1,
            timing: Timing::default(),
            warnings: Vec::new(),
        }
    }

    #[test]
    fn a_wear_rate_falling_with_load_beyond_its_scatter_is_warned_about() {
        // 150 particles at the lower load, 3 at twice it (the same volume each): W falls fiftyfold.
        let runs = [run(2e-3, 3.0, 3, 0.12), run(1e-3, 150.0, 150, 0.04)];
        let w = load_trend_warnings(&runs);
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(
            w[0].contains("W falls from 1.5000e2 at F_N = 1.0000e-3 to 3.0000e0 at F_N = 2.0000e-3")
                && w[0].contains("from 150 and 3 particles")
                && w[0].contains("12.00 % against 4.00 %"),
            "{w:?}"
        );
        // None at all at the higher load, where 30 formed at the lower: warned too.
        assert_eq!(
            load_trend_warnings(&[run(1e-3, 30.0, 30, 0.04), run(2e-3, 0.0, 0, 0.1)]).len(),
            1
        );
        // A fall within the Poisson scatter (20 against 17), or a rise: nothing.
        assert!(load_trend_warnings(&[run(1e-3, 20.0, 20, 0.04), run(2e-3, 17.0, 17, 0.1)]).is_empty());
        assert!(load_trend_warnings(&[run(1e-3, 20.0, 20, 0.04), run(2e-3, 40.0, 40, 0.1)]).is_empty());
        assert!(load_trend_warnings(&[run(1e-3, 20.0, 20, 0.04)]).is_empty());
    }
}
