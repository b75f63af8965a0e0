//! The static estimate's unit tests: its samples, rule, calibration fit and reach.

use super::*;
use crate::material::Material;

#[test]
fn offsets_are_spread_for_every_count() {
    assert_eq!(sample_offsets(1024, 4), vec![0, 512, 256, 768]);
    let all = sample_offsets(1024, 16);
    let mut sorted = all.clone();
    sorted.sort_unstable();
    assert_eq!(sorted, (0..16).map(|j| j * 64).collect::<Vec<_>>());
}

fn point(n: f64, d: f64, theta: f64, c: &Calibration, particles: usize) -> CalibrationPoint {
    let p = CalibrationPoint {
        critical_junctions: n,
        mean_critical_diameter: d,
        critical_coverage: theta,
        critical_diameter: 0.8 * d,
        particle_rate: 0.0,
        wear_rate: 0.0,
        particles,
    };
    let rate = c.particle_rate(&p);
    CalibrationPoint {
        particle_rate: rate,
        wear_rate: c.wear_rate(p.critical_diameter, rate),
        ..p
    }
}

#[test]
fn the_fit_recovers_known_constants() {
    let truth = Calibration {
        residence_factor: 2.1,
        merging_factor: 12.5,
        volume_factor: 1.15,
        ..CALIBRATION
    };
    let points: Vec<_> = (0..12)
        .map(|i| {
            point(
                3.0 + i as f64,
                0.01 + 0.001 * i as f64,
                0.005 * i as f64,
                &truth,
                10_000,
            )
        })
        .collect();
    let fit = Calibration::fit(&points).unwrap();
    assert!((fit.residence_factor - 2.1).abs() < 1e-9, "{fit:?}");
    assert!((fit.merging_factor - 12.5).abs() < 1e-9, "{fit:?}");
    assert!((fit.volume_factor - 1.15).abs() < 1e-9, "{fit:?}");
    assert_eq!(fit.rate_spread, 0.0);
    assert_eq!(fit.settings, 12);
}

#[test]
fn a_fit_needs_three_settings_with_particles() {
    let points: Vec<_> = (0..5)
        .map(|i| point(3.0, 0.01, 0.01 * i as f64, &CALIBRATION, 5))
        .collect();
    let e = Calibration::fit(&points).unwrap_err().to_string();
    assert!(e.contains("at least 3"), "{e}");
}

fn sample(contact_area: f64, critical: usize, diameter: f64) -> Sample {
    Sample {
        contact_area,
        junctions: critical,
        counts: vec![SampleCount {
            critical_junctions: critical,
            diameter_sum: critical as f64 * diameter,
            ..Default::default()
        }],
        ..Default::default()
    }
}

#[test]
fn settings_outside_the_calibration_are_warned_about_and_paper_like_ones_not() {
    let sliding = crate::sliding::SlidingConfig::new(vec![1e-3], 0.5, 0.25, 4, 1, Some(1024)).unwrap();
    let paper = SurfaceKind::Generated {
        hurst: 0.7,
        lower_cutoff_pixels: 16.0,
        upper_cutoff_box: 0.25,
        upper_cutoff: 0.0625,
    };
    assert!(run_reach_warnings(&CALIBRATED_DOMAIN, &paper, &sliding, 0.25).is_empty());
    let measured = SurfaceKind::Other("read from height-map files (a measured map)".into());
    let w = run_reach_warnings(&CALIBRATED_DOMAIN, &measured, &sliding, 0.25);
    assert!(
        w.len() == 1 && w[0].contains("measured map") && w[0].contains("--fit"),
        "{w:?}"
    );
    let rough = SurfaceKind::Generated {
        hurst: 0.5,
        lower_cutoff_pixels: 16.0,
        upper_cutoff_box: 0.25,
        upper_cutoff: 0.0625,
    };
    let w = run_reach_warnings(&CALIBRATED_DOMAIN, &rough, &sliding, 0.25);
    assert!(
        w.len() == 1 && w[0].contains("Hurst exponent H is 0.50") && w[0].contains("0.70"),
        "{w:?}"
    );
    // A schedule not run in as the calibration's runs were.
    let short = crate::sliding::SlidingConfig::new(vec![1e-3], 0.2, 0.05, 4, 1, Some(1024)).unwrap();
    let w = run_reach_warnings(&CALIBRATED_DOMAIN, &paper, &short, 0.25);
    assert!(
        w.len() == 1 && w[0].contains("running-in is 0.050 box lengths"),
        "{w:?}"
    );
    // Contact fraction and N* per map.
    let material = Material::new(1.0, 0.3, 0.010, vec![0.25e-6], 3.0).unwrap();
    let d = material.critical_diameters()[0];
    let inside = vec![sample(0.03, 10, d); 4];
    assert!(load_reach_warnings(&CALIBRATED_DOMAIN, &inside, &material, 1e-3).is_empty());
    let crowded = vec![sample(0.2, 200, d); 4];
    let w = load_reach_warnings(&CALIBRATED_DOMAIN, &crowded, &material, 1e-3);
    assert!(w.len() == 2, "{w:?}");
    assert!(
        w[0].contains("contact fraction is 20.00 %") && w[0].contains("0.9–5.0 %"),
        "{w:?}"
    );
    assert!(
        w[1].contains("200.0 critical junctions") && w[1].contains("above the calibrated 3–120"),
        "{w:?}"
    );
}

/// Outside the calibrated domain the library's constants give W without an interval, and say
/// why; inside, and with constants of one's own, the interval stands.
#[test]
fn outside_the_calibration_the_interval_is_withheld_and_said_why() {
    let material = Material::new(1.0, 0.3, 0.010, vec![0.25e-6, 1.0e-6], 3.0).unwrap();
    let d = material.critical_diameters();
    let sample2 = |contact: f64, n: [usize; 2]| Sample {
        contact_area: contact,
        junctions: n[0],
        counts: (0..2)
            .map(|e| SampleCount {
                critical_junctions: n[e],
                diameter_sum: n[e] as f64 * 1.2 * d[e],
                ..Default::default()
            })
            .collect(),
        ..Default::default()
    };
    let sliding = crate::sliding::SlidingConfig::new(vec![1e-3], 0.5, 0.25, 4, 1, Some(1024)).unwrap();
    let paper = SurfaceKind::Generated {
        hurst: 0.7,
        lower_cutoff_pixels: 16.0,
        upper_cutoff_box: 0.25,
        upper_cutoff: 0.0625,
    };
    let measured = SurfaceKind::Other("read from height-map files (a measured map)".into());
    let inside = vec![sample2(0.03, [10, 4]); 4];
    let estimate = |samples: &[Sample], kind: &SurfaceKind, c: &Calibration| {
        let reach = run_reach(&CALIBRATED_DOMAIN, kind, &sliding, 0.25);
        load_estimate(samples, &material, 1e-3, (0.25, 0.25), 0.0625, c, &reach)
    };
    let (r, w) = estimate(&inside, &paper, &CALIBRATION);
    assert!(
        r.iter()
            .all(|r| r.wear_rate_low.is_some() && r.interval_withheld.is_none()),
        "{r:?} {w:?}"
    );
    // Measured surfaces: every 𝒢 loses its interval, the point value stays, the warning says so.
    let (r, w) = estimate(&inside, &measured, &CALIBRATION);
    for r in &r {
        assert!(r.wear_rate.is_some() && r.wear_coefficient.is_some() && r.particle_rate.is_some());
        assert_eq!((r.wear_rate_low, r.wear_rate_high), (None, None));
        assert_eq!((r.wear_coefficient_low, r.particle_rate_high), (None, None));
        assert_eq!(
            r.interval_withheld.as_deref(),
            Some("outside the calibrated domain: surfaces not of the calibrated spectrum")
        );
    }
    assert!(w.iter().any(|w| w.contains("given without an interval")), "{w:?}");
    // N* above the range for the first 𝒢 only: that one loses its interval, the other keeps it.
    let (r, _) = estimate(&vec![sample2(0.03, [200, 4]); 4], &paper, &CALIBRATION);
    assert_eq!(
        r[0].interval_withheld.as_deref(),
        Some("outside the calibrated domain: N* = 200.0 per map")
    );
    assert!(r[1].interval_withheld.is_none() && r[1].wear_rate_low.is_some());
    // Rare critical junctions, one per map (below the calibrated 3): no interval either.
    let (r, _) = estimate(&vec![sample2(0.03, [10, 1]); 4], &paper, &CALIBRATION);
    assert_eq!(
        r[1].interval_withheld.as_deref(),
        Some("outside the calibrated domain: N* = 1.0 per map")
    );
    assert!(r[0].interval_withheld.is_none());
    // A contact fraction outside the range concerns every 𝒢, with the surfaces' reason beside it.
    let (r, _) = estimate(&vec![sample2(0.2, [10, 4]); 4], &measured, &CALIBRATION);
    assert_eq!(
        r[1].interval_withheld.as_deref(),
        Some("outside the calibrated domain: surfaces not of the calibrated spectrum; contact fraction 20.00 %")
    );
    // Constants of one's own keep their interval: their reach is the runs they were fitted on.
    let own = Calibration {
        residence_factor: 2.0,
        ..CALIBRATION
    };
    let (r, _) = estimate(&inside, &measured, &own);
    assert!(r
        .iter()
        .all(|r| r.wear_rate_low.is_some() && r.interval_withheld.is_none()));
    // No critical junction: nothing to withhold.
    let (r, _) = estimate(&vec![sample2(0.03, [0, 0]); 4], &measured, &CALIBRATION);
    assert!(r.iter().all(|r| r.wear_rate.is_none() && r.interval_withheld.is_none()));
}

#[test]
fn the_interval_starts_at_zero_where_a_run_likely_forms_no_particle() {
    let material = Material::new(1.0, 0.3, 0.010, vec![0.25e-6], 3.0).unwrap();
    let d = material.critical_diameters()[0];
    let samples = vec![sample(0.03, 1, 1.2 * d); 4];
    // A short fit window: μ well under ln 40, so P(N = 0) > 2.5 %.
    let (r, w) = results_of(&samples, &material, 1e-6, (0.03125, 0.03125), 1e-3, &CALIBRATION);
    let mu = r[0].expected_particles.unwrap();
    assert!(mu < 40f64.ln(), "{mu}");
    assert_eq!(r[0].wear_rate_low, Some(0.0));
    assert_eq!(r[0].particle_rate_low, Some(0.0));
    assert_eq!(r[0].wear_coefficient_low, Some(0.0));
    assert!(r[0].wear_rate_high.unwrap() > r[0].wear_rate.unwrap());
    assert!(w.iter().any(|w| w.contains("none at all with probability")), "{w:?}");
    // A long one: many particles, the lower end above 0.
    let (r, _) = results_of(&samples, &material, 1e-6, (0.03125, 0.03125), 10.0, &CALIBRATION);
    assert!(r[0].expected_particles.unwrap() > 40f64.ln());
    assert!(r[0].wear_rate_low.unwrap() > 0.0);
    assert!(zero_allowed(3.68) && !zero_allowed(3.70));
}

#[test]
fn the_number_of_static_maps_is_checked() {
    assert!(Sampling::of(Some(0)).is_err());
    assert_eq!(Sampling::of(None).unwrap(), Sampling::Auto);
}
