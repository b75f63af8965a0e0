//! The README's main job (studies/paper-window.toml) shows the paper's physics: its collected table,
//! as the main job writes it (`tests/data/paper-window-results.csv`, regenerated with
//! `wearsim study run studies/paper-window.toml --out out/paper-window && wearsim study collect
//! out/paper-window`), checked against the paper's findings: k_static < 1 and rising with load,
//! static W rising with hardness, the larger d* wearing more at the highest load, V(s) linear after
//! running-in, and the rest that the window resolves.

use wearsim::output::Table;
use wearsim::study::findings::{findings, Verdict};

#[test]
fn the_main_job_reproduces_the_papers_findings() {
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
    for key in [
        "static-k-below-one-and-rising",
        "static-wear-grows-with-hardness",
        "larger-d-star-wears-more-at-high-load",
        "volume-linear-after-running-in",
        "hardest-least-tough-emits-most-particles",
        "equation-5-slightly-below-w",
        "initial-volume-much-larger-than-increments",
        "memory-decays-exponentially",
    ] {
        let f = all.iter().find(|f| f.key == key).unwrap();
        assert_eq!(f.verdict, Verdict::Reproduced, "{key}: {}", f.observed);
    }
}
