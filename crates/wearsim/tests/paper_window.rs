//! The README's main job (studies/paper-window.toml) has the power to show what it claims: its
//! collected table, as the main job writes it (`tests/data/paper-window-results.csv`, regenerated
//! with `wearsim study run studies/paper-window.toml --out out/paper-window && wearsim study collect
//! out/paper-window`), counted under the findings' rules. Every setting is counted; the only
//! unresolved settings are those the study file names (d* = 33 px below its highest load); every
//! setting is run in; and the findings the job is built for are reproduced.

use wearsim::output::Table;
use wearsim::study::findings::{findings, Verdict};

/// "holds in 4 of 6 settings…" → (4, 6).
fn counts(observed: &str) -> (usize, usize) {
    let words: Vec<&str> = observed.split_whitespace().collect();
    assert_eq!(&words[..2], ["holds", "in"], "{observed}");
    (words[2].parse().unwrap(), words[4].parse().unwrap())
}

#[test]
fn the_main_job_judges_its_settings_and_reproduces_the_papers_findings() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/paper-window-results.csv"
    ))
    .unwrap();
    let table = Table::from_csv(&text).unwrap();
    let all = findings(&table);
    for f in &all {
        println!("{}: {} — {}", f.key, f.verdict.name(), f.observed);
    }
    let get = |key: &str| all.iter().find(|f| f.key == key).unwrap();
    // Six settings (one τ̃, two 𝒢, three loads), three contact histories, every one counted.
    for key in [
        "volume-linear-after-running-in",
        "sliding-k-below-0.1",
        "sliding-k-below-static",
        "equation-5-slightly-below-w",
        "particle-size-near-critical-diameter",
        "initial-volume-much-larger-than-increments",
    ] {
        let f = get(key);
        assert_eq!(counts(&f.observed).1, 6, "{key}: {}", f.observed);
        assert!(
            f.observed.contains("unresolved in 2 (< 20 particles)"),
            "{key}: {}",
            f.observed
        );
        assert!(f.observed.contains("not run in: 0"), "{key}: {}", f.observed);
    }
    assert_eq!(counts(&get("memory-decays-exponentially").observed).1, 3);
    assert_eq!(counts(&get("running-in-sufficient").observed), (3, 3));
    for key in [
        "static-k-below-one-and-rising",
        "volume-linear-after-running-in",
        "equation-5-slightly-below-w",
        "particle-size-near-critical-diameter",
        "initial-volume-much-larger-than-increments",
        "memory-decays-exponentially",
        "running-in-sufficient",
        "larger-d-star-wears-more-at-high-load",
        "hardest-least-tough-emits-most-particles",
    ] {
        let f = get(key);
        assert_eq!(f.verdict, Verdict::Reproduced, "{key}: {}", f.observed);
    }
    // k_static/k ≥ 5 for d* = 16 px, 1.8 for 33 px at the highest load: partly.
    assert_eq!(get("sliding-k-below-static").verdict, Verdict::Partly);
}
