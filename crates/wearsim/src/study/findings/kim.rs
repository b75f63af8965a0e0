//! The comparison with Kim et al. (1986) (paper §4.2, Table 1, Fig. 6): judged on the settings whose
//! materials carry the properties of the paper's Table 1 (a study of other materials has no unit).

use crate::stats::Region;

use super::rules::{compare, per_setting, Compared};
use super::setting::Setting;
use super::{finding, Finding, Tally};

/// Kim's ceramics from the most to the least wear, as the paper and the experiments rank them.
const HIERARCHY: [&str; 3] = ["Al2O3", "SiC", "Si3N4"];

/// §4.2, Fig. 6c: Al₂O₃ wears the most and Si₃N₄ the least over the load range.
pub(super) fn kim_hierarchy(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    let rank = |s: &Setting| s.kim.and_then(|k| HIERARCHY.iter().position(|h| *h == k));
    for a in all {
        for b in all {
            match (rank(a), rank(b)) {
                (Some(ra), Some(rb)) if ra < rb && a.pressure == b.pressure => {
                    tally.file(compare(
                        a,
                        b,
                        "Kim's hierarchy",
                        Compared::WearRate,
                        Region::Above(1.0),
                        true,
                    ));
                }
                _ => {}
            }
        }
    }
    finding(
        "kim-hierarchy",
        "§4.2, Fig. 6c: Al₂O₃ wears the most and Si₃N₄ the least for the presented load range, the experiments' \
         hierarchy",
        "per load and pair of Kim's ceramics (the properties of Table 1): W(the one Kim ranks as wearing more)/W(the \
         other) > 1, over the shared surface pairs (their surfaces share the seed and differ in h_rms), paired or by \
         the count test; a study without two of Kim's ceramics has no unit"
            .into(),
        "pairs of settings",
        tally,
    )
}

/// §4.2: the simulated k are at least two to three orders of magnitude above Kim's rolling k.
pub(super) fn kim_k_above_experiments(all: &[Setting]) -> Finding {
    let kim: Vec<Setting> = all.iter().filter(|s| s.kim.is_some()).cloned().collect();
    let upper = crate::output::KIM_EXPERIMENTAL_K.1;
    let tally = per_setting(&kim, "k", Region::Above(100.0 * upper), |_, p| {
        p.get("wear_coefficient")
    });
    finding(
        "kim-k-above-experiments",
        "§4.2: the wear coefficients are at least two to three orders of magnitude higher than the experimental ones \
         (k_exp = 6×10⁻⁷ to 1.5×10⁻³)",
        "per setting of Kim's ceramics: k > 100 × 1.5×10⁻³ by its Student-t interval over the run-in pairs (a study \
         of one pair has no interval)"
            .into(),
        "settings",
        tally,
    )
}
