//! Every study file shipped in `studies/` expands, with the job count its header states.

use std::path::Path;

use wearsim::study::expand;

#[test]
fn shipped_study_files_expand() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../studies");
    let expected = [
        ("quick.toml", 24),
        ("paper-window.toml", 30),
        ("paper-evidence.toml", 50),
        ("paper-half.toml", 160),
        ("paper-reduced.toml", 320),
        ("running-in-step.toml", 18),
        ("kim1986.toml", 20),
        ("kim1986-window.toml", 20),
        ("appendix-discretization.toml", 40),
        ("appendix-discretization-reduced.toml", 18),
        ("appendix-area.toml", 60),
        ("appendix-area-reduced.toml", 24),
        ("appendix-lambda-h.toml", 36),
        ("appendix-lambda-h-reduced.toml", 24),
        ("estimate-calibration.toml", 15),
        ("estimate-holdout-tau.toml", 20),
        ("estimate-holdout-box.toml", 6),
        ("paper-box-estimate.toml", 24),
        ("paper-window-estimate.toml", 30),
        ("particle-rules.toml", 100),
        ("wear-regime.toml", 150),
    ];
    for (file, jobs) in expected {
        let text = std::fs::read_to_string(dir.join(file)).unwrap();
        let study = expand(&text, &dir).unwrap_or_else(|e| panic!("{file}: {e}"));
        assert_eq!(study.jobs.len(), jobs, "{file}");
    }
    let shipped = std::fs::read_dir(&dir)
        .unwrap()
        .filter(|e| e.as_ref().unwrap().path().extension().is_some_and(|x| x == "toml"))
        .count();
    assert_eq!(shipped, expected.len(), "a study file is not checked here");
}
