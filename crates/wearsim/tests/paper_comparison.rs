//! docs/paper-comparison.md keeps the verdict of every finding on the main job and on the evidence
//! study in one generated table; this test recomputes both from the committed results (the main
//! job's `tests/data/paper-window-results.csv`, the evidence study's job files) and holds the
//! document to them, so that no row drifts from what `wearsim study plot` writes. Every finding the
//! document names by its key exists, and its section tables give numbers, not verdicts.
//!
//! After a change of the rules: `WEARSIM_BLESS_DOCS=1 cargo test --test integration paper_comparison`
//! rewrites the table, then read the document's prose against it.

use wearsim::study::findings::{comparison_table, findings, Finding};

const BEGIN: &str =
    "<!-- findings table: generated from the findings, checked by crates/wearsim/tests/paper_comparison.rs -->";
const END: &str = "<!-- end of the findings table -->";

fn document() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/paper-comparison.md")
}

#[test]
fn the_paper_comparison_agrees_with_the_findings_of_both_studies() {
    let main: Vec<Finding> = findings(&crate::paper_window::table());
    let evidence = crate::evidence::evidence_findings();
    let table = comparison_table(&[
        ("main job (L/8, one τ̃)", &main),
        ("evidence study (L/4, two τ̃)", &evidence),
    ]);
    let path = document();
    let text = std::fs::read_to_string(&path).unwrap();
    let (start, end) = (
        text.find(BEGIN).expect("the table's opening marker") + BEGIN.len(),
        text.find(END).expect("the table's closing marker"),
    );
    let expected = format!("\n{table}");
    if text[start..end] != expected {
        if std::env::var_os("WEARSIM_BLESS_DOCS").is_some() {
            let updated = format!("{}{expected}{}", &text[..start], &text[end..]);
            std::fs::write(&path, updated).unwrap();
        } else {
            panic!(
                "docs/paper-comparison.md's findings table differs from the findings; the table they give:\n{table}\n\
                 (WEARSIM_BLESS_DOCS=1 rewrites it)"
            );
        }
    }
    // Every key the document names is a finding's: a code span of lower-case words joined by hyphens.
    let keys: Vec<&str> = main.iter().map(|f| f.key).collect();
    let spans: Vec<&str> = text.split('`').skip(1).step_by(2).collect();
    for name in spans {
        let key_like = name.starts_with(|c: char| c.is_ascii_lowercase())
            && name.contains('-')
            && name
                .chars()
                .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-' || c == '.')
            && !name.ends_with(".toml")
            && !name.ends_with(".md");
        assert!(
            !key_like || keys.contains(&name),
            "docs/paper-comparison.md names `{name}`, no finding's key"
        );
    }
    // Verdicts live in the generated table: no other table of the document has a verdict column.
    let outside = format!("{}{}", &text[..start], &text[end..]);
    for line in outside.lines().filter(|l| l.starts_with("| ")) {
        assert!(
            !line.contains("| verdict |"),
            "a table outside the generated one gives verdicts: {line}"
        );
    }
}
