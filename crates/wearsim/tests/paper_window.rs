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

pub(crate) fn table() -> Table {
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
    assert_eq!(get("k-rises-with-load").units.len(), 2);
    // The running-in is a diagnostic, one row per contact history, not a verdict.
    let run_in = get("running-in-sufficient");
    assert_eq!((run_in.verdict, run_in.units.len()), (Verdict::Diagnostic, 3));
    assert!(run_in.units[0]
        .text
        .contains(&format!("of {} run in by the lineages left", pairs.len())));
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
    // The opening table (a header and a row per finding), then the running-in table (a header and a
    // row per contact history).
    assert_eq!(
        md.lines().filter(|l| l.starts_with("| ")).count(),
        all.len() + 1 + 3 + 1
    );
    // The opening table: five short columns, no cell over 300 characters.
    for line in md.lines().filter(|l| l.starts_with("| `")) {
        let cells: Vec<&str> = line.trim_matches('|').split(" | ").map(str::trim).collect();
        assert_eq!(cells.len(), 5, "{line}");
        assert!(cells.iter().all(|c| c.chars().count() <= 300), "{line}");
    }
    // The particle sizes Eq. 5 fixes are shown against (d*₁/d*₂)³, not counted again.
    assert_eq!(get("severe-wear-from-large-particles").verdict, Verdict::Cited);
    assert!(get("severe-wear-from-large-particles")
        .observed
        .contains("Eq. 5's (d*₁/d*₂)³ = "));
    // The findings the paper's sliding model rests on hold.
    for key in [
        "static-k-below-one-and-rising",
        "static-wear-superlinear",
        "volume-linear-after-running-in",
        "equation-5-slightly-below-w",
        "sliding-k-below-0.1",
        "smaller-g-wears-more-at-low-load",
    ] {
        assert_eq!(get(key).verdict, Verdict::Reproduced, "{key}: {}", get(key).observed);
    }
    // One statistic, one count: k = W p_m/F_N makes k's slope Archard's exponent less one; the
    // slopes' difference of two curves is the crossover's; the 150-against-3 particles at the
    // lowest load are the smaller-𝒢 finding's; k > 10⁻² and k < 0.12 read the same k.
    for (key, owner) in [
        ("sliding-k-high-end-of-experiments", "sliding-k-below-0.1"),
        ("k-rises-with-load", "archard-like"),
        ("tougher-reaches-k-max-later", "larger-d-star-wears-more-at-high-load"),
        ("delayed-onset-for-large-g", "smaller-g-wears-more-at-low-load"),
    ] {
        assert_eq!(
            (get(key).verdict, get(key).same_data_as),
            (Verdict::SameData, Some(owner)),
            "{key}"
        );
    }
    // The crossover needs the larger d* seen wearing more: W(33 px)/W(16 px) = 1.23 [0.79, 1.92] at
    // the top load decides nothing, whatever the slope.
    let crossover = get("larger-d-star-wears-more-at-high-load");
    assert_eq!(crossover.verdict, Verdict::Inconclusive, "{}", crossover.observed);
    assert!(
        crossover.observed.contains("W ratio = 1.23 [0.786, 1.92]"),
        "{}",
        crossover.observed
    );
    // Fig. 5: its wear half is the crossover's comparison, so it has no unit of its own, and the
    // finding cannot be reproduced on its emission half alone.
    let fig5 = get("hardest-least-tough-emits-most-wears-least");
    assert_eq!(fig5.verdict, Verdict::Inconclusive, "{}", fig5.observed);
    assert!(fig5.kind().contains("emission half: reproduced") && fig5.kind().contains("one τ̃"));
    // The verdicts another run-in rule would change are rule-dependent, with the three verdicts.
    for (key, three) in [
        (
            "sliding-k-below-static",
            [Verdict::NotReproduced, Verdict::Partly, Verdict::NotReproduced],
        ),
        (
            "archard-like",
            [Verdict::Inconclusive, Verdict::Reproduced, Verdict::Inconclusive],
        ),
    ] {
        assert_eq!(
            (get(key).verdict, get(key).verdicts_by_rule),
            (Verdict::RuleDependent, Some(three)),
            "{key}"
        );
    }
    wearsim::study::findings::check_counted_once(&all).unwrap();
}
