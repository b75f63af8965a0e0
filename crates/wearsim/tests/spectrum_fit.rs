//! The spectrum fit (`wearsim::topography::fit`) on generated surfaces of 512², against the
//! optimised library: 72 fits, which the library's unoptimised unit-test build would take tens of
//! seconds over.

use std::f64::consts::PI;

use wearsim::surface::{pair_seeds, Generation};
use wearsim::topography::{fit, preprocess, Detrend, Preprocess};
use wearsim::{Grid, SpectrumParams, Surface};

fn within(value: f64, truth: f64, factor: f64) -> bool {
    value / truth < factor && truth / value < factor
}

fn generated(grid: Grid, hurst: f64, lower: f64, upper: f64, generation: Generation, seed: u64) -> Surface {
    let params = SpectrumParams {
        hurst,
        lambda_lower: lower,
        lambda_upper: upper,
        rms_height: 0.01,
        generation,
    };
    Surface::generate(grid, &params, seed).unwrap()
}

fn levelled(s: &Surface) -> Surface {
    let mut h = s.heights().to_vec();
    let how = Preprocess {
        detrend: Detrend::Plane,
        taper: 0.0,
    };
    preprocess(&mut h, s.nx(), s.ny(), &how).unwrap();
    Surface::new("levelled", s.grid(), h).unwrap()
}

/// A generated surface has nothing beyond λ_l but round-off (~1e-30 of the band), and levelling
/// it by a plane (which a periodic map does not need) adds the leakage of a sawtooth there, a
/// power law of its own far under the band: the fit finds the band above both, as levelled and
/// as generated. The surfaces are the top surfaces `wearsim surface` makes from seeds 1–3
/// (filtered noise carries the scatter of its random amplitudes: H of one 512² sample with a band
/// of less than a decade scatters by about 0.03 about the generator's).
#[test]
fn the_floor_beyond_the_cut_off_is_left_out_for_both_generation_methods() {
    let grid = Grid::square(512, 1.0).unwrap();
    for generation in [Generation::RandomPhase, Generation::FilteredNoise] {
        for hurst in [0.5, 0.7, 0.8] {
            for lower in [1.0 / 64.0, 1.0 / 32.0] {
                for seed in 1..=3 {
                    let s = generated(grid, hurst, lower, 0.25, generation, pair_seeds(seed).0);
                    for (how, s) in [("as generated", s.clone()), ("levelled", levelled(&s))] {
                        let f = fit(&s).unwrap();
                        let case = format!("{generation:?} H {hurst} λ_l {lower} seed {seed} {how}: {f:?}");
                        assert!((f.hurst - hurst).abs() <= 0.05, "{case}");
                        assert!(within(f.lambda_lower, lower, 1.25), "{case}");
                        assert!(within(f.lambda_upper, 0.25, 1.25), "{case}");
                        // The fitted range lies inside the band; what lies beyond λ_l is left out.
                        let [q0, q1] = f.fitted_q;
                        assert!(q0 >= 2.0 * PI * 4.0 && q1 <= 2.0 * PI / lower, "{case}");
                        assert!(f.shells_shorter > 200 && f.shells_longer >= 3, "{case}");
                        assert!(f.floor < 1e-6, "{case}");
                    }
                }
            }
        }
    }
}
