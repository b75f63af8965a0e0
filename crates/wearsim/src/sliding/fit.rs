//! The fitted results of one load (paper §3 and appendices B, C) and the warnings about them.

use crate::junctions::particle_volume;
use crate::material::Material;
use crate::stats::{line_fit, mean_std, LineFit};

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
pub(crate) fn results_of_load(
    setup: &SlidingSetup,
    load: f64,
    pm: f64,
    steps: &[StepRecord],
    running_in: usize,
) -> (Vec<WearResult>, Vec<String>) {
    let fitted: Vec<&StepRecord> = steps.iter().filter(|r| r.offset >= running_in).collect();
    let mut warnings = Vec::new();
    let shared = load_fits(load, steps, &fitted, &mut warnings);
    let results = setup
        .material
        .critical_diameters()
        .into_iter()
        .enumerate()
        .map(|(e, d)| {
            let context = Context {
                load,
                pm,
                energy: e,
                fracture_energy: setup.material.fracture_energies[e],
                critical_diameter: d,
            };
            result_of_energy(&context, steps, &fitted, &shared, &mut warnings)
        })
        .collect();
    (results, warnings)
}

/// The memory of the initial contact ([`InitialContactMemory`]), the mean number of junctions and
/// the steps with a junction around the box, with their warnings.
fn load_fits(load: f64, steps: &[StepRecord], fitted: &[&StepRecord], warnings: &mut Vec<String>) -> LoadFits {
    let fit_start = fitted.first().map_or(0.0, |r| r.s);
    let memory = InitialContactMemory::of_steps(
        &steps.iter().map(|r| (r.s, r.initial_junctions)).collect::<Vec<_>>(),
        fit_start,
    );
    warnings.extend(memory.warning(load, fit_start));
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
    /// Flow pressure p_m.
    pm: f64,
    /// Index of the fracture energy in the material's list.
    energy: usize,
    fracture_energy: f64,
    critical_diameter: f64,
}

/// The warnings of the wear-rate fit of one setting (`context` names it): no particle or few over
/// the fit window, or V(s) far from a line (R² < 0.8).
fn fit_warnings(context: &str, particles_in_fit: usize, wear_rate_r2: Option<f64>, warnings: &mut Vec<String>) {
    if particles_in_fit == 0 {
        warnings.push(format!(
            "{context}: no particle formed after running-in, so W = 0 and its fit (R²) is undefined; no junction \
             grows to d* in this box at this load"
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
    fit_warnings(&context, particles_in_fit, wear_rate_r2, warnings);
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
        wear_coefficient: wear_rate.and_then(|w| finite(w * c.pm / load)),
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
    }
}
