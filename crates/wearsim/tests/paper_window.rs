//! The README's main job (studies/paper-window.toml) has the power to show what it claims: its
//! collected table, as the main job writes it (`tests/data/paper-window-results.csv`, regenerated
//! with `wearsim study run studies/paper-window.toml --out out/paper-window && wearsim study collect
//! out/paper-window`), judged under the findings' rules. Every unit is counted; run-in is judged
//! pair by pair; the central claims (Archard-like wear, k against load) are judged; most verdicts
//! of the findings the study can test are decided, and each inconclusive one names the surface
//! pairs that would decide it; a verdict that another run-in rule would change says so.

use std::collections::BTreeSet;

use wearsim::output::Table;
use wearsim::study::findings::{findings, markdown, Verdict};

fn table() -> Table {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/paper-window-results.csv"
    ))
    .unwrap();
    Table::from_csv(&text).unwrap()
}

#[test]
fn the_main_job_decides_most_of_the_papers_findings_it_can_test() {
    let table = table();
    let seed = table.column("surface.seed").unwrap();
    let pairs: BTreeSet<String> = table.rows.iter().map(|r| r[seed].text()).collect();
    let all = findings(&table);
    for f in &all {
        println!("{}: {} {:?} — {}", f.key, f.verdict.name(), f.counts, f.observed);
    }
    let get = |key: &str| all.iter().find(|f| f.key == key).unwrap();
    let units = |key: &str| {
        let (h, c, i, n) = get(key).counts;
        h + c + i + n
    };
    // Six settings (one τ̃, two 𝒢, three loads), three contact histories, two curves: every one counted.
    for key in [
        "volume-linear-after-running-in",
        "sliding-k-below-0.1",
        "sliding-k-below-static",
        "equation-5-slightly-below-w",
        "initial-volume-much-larger-than-increments",
        "running-in-steeper",
    ] {
        assert_eq!(units(key), 6, "{key}: {}", get(key).observed);
    }
    assert_eq!(units("memory-decays-exponentially"), 3);
    assert_eq!(units("archard-like"), 2);
    assert_eq!(units("k-rises-with-load"), 2);
    // Run-in is judged for each surface pair of each contact history.
    assert_eq!(units("running-in-sufficient"), 3 * pairs.len());
    // The central claims are judged, not left untested.
    for key in ["archard-like", "k-rises-with-load", "tougher-reaches-k-max-later"] {
        assert_ne!(get(key).verdict, Verdict::NotTestable, "{key}");
    }
    // What one τ̃ of generic materials on one kind of surface cannot test, and nothing else, is not testable.
    let untestable: Vec<&str> = all
        .iter()
        .filter(|f| f.verdict == Verdict::NotTestable)
        .map(|f| f.key)
        .collect();
    assert_eq!(
        untestable,
        [
            "static-wear-grows-with-hardness",
            "toughest-not-yet-ahead",
            "soft-tough-fewest-particles",
            "kim-hierarchy",
            "kim-k-above-experiments",
            "appendix-a-discretization",
            "appendix-c-box-size",
            "appendix-c-more-spots-not-more-wear",
            "appendix-d-lambda-lower",
            "appendix-e-rms-height"
        ]
    );
    // Most of the rest are decided; every inconclusive one says what would decide it or why not.
    let testable = all.len() - untestable.len();
    let inconclusive: Vec<_> = all.iter().filter(|f| f.verdict == Verdict::Inconclusive).collect();
    assert!(
        2 * inconclusive.len() < testable,
        "{} of {testable} inconclusive",
        inconclusive.len()
    );
    let md = markdown(&all);
    assert!(md.contains("95 % confidence interval over surface pairs"));
    // One line per finding first, then the table of rules: a header and a row per finding each.
    assert_eq!(md.lines().filter(|l| l.starts_with("| ")).count(), 2 * (all.len() + 1));
    // The particle sizes Eq. 5 fixes are shown against (d*₁/d*₂)³, not counted again.
    assert_eq!(get("severe-wear-from-large-particles").verdict, Verdict::Cited);
    assert!(get("severe-wear-from-large-particles")
        .observed
        .contains("Eq. 5's (d*₁/d*₂)³ = "));
    // The findings the paper's sliding model rests on hold.
    for key in [
        "static-k-below-one-and-rising",
        "static-wear-superlinear",
        "equation-5-slightly-below-w",
        "sliding-k-below-0.1",
        "smaller-g-wears-more-at-low-load",
        "delayed-onset-for-large-g",
    ] {
        assert_eq!(get(key).verdict, Verdict::Reproduced, "{key}: {}", get(key).observed);
    }
    // Run in by the lineages left (at most 5 % at the start of the fit window): 24 of the 30 pair
    // histories, where s_r ≥ 3 ℓ counts 20. The verdicts of the central claims that rest on which
    // pairs are run in change with the rule, and say so.
    assert_eq!(get("running-in-sufficient").counts, (24, 6, 0, 0));
    for (key, other) in [
        ("archard-like", Verdict::Reproduced),
        ("k-rises-with-load", Verdict::Inconclusive),
        ("tougher-reaches-k-max-later", Verdict::Inconclusive),
    ] {
        assert_eq!(get(key).verdict_under_decay_lengths, Some(other), "{key}");
        assert!(
            get(key).kind().contains("if a pair counts as run in by s_r ≥ 3 ℓ"),
            "{key}"
        );
    }
}
