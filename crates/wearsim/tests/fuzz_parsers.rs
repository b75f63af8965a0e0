//! Fuzzing of every parser of untrusted input — run files, study files, `.npy` files, job files —
//! with proptest: random text and bytes, and random mutations of valid inputs (characters inserted,
//! deleted or replaced; numbers swapped for extreme values). Each input must end in `Ok` or a typed
//! `Err`, never a panic, an abort or a hang. The corpus in `tests/fuzz-corpus/` (inputs that once
//! broke a parser, and hand-picked nasty ones) is replayed first. `PROPTEST_CASES` raises the count
//! for a longer campaign.

use std::path::{Path, PathBuf};

use proptest::prelude::*;
use wearsim::config::RunConfig;
use wearsim::io::{read_npy_2d, write_npy_f64, NpyType};
use wearsim::output::JobResult;
use wearsim::study::expand;

const RUN: &str = r#"
units = "reduced"
[surface]
grid = 64
length = 1.0
hurst = 0.7
lambda_lower = 0.0625
lambda_upper = 0.25
rms_height = 0.005
seed = 1
generation = "random-phase"
[material]
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = 0.01
fracture_energies = [0.5e-6, 1e-6]
geometry_factor = 3.0
[contact]
modulus = "half-space"
tolerance = 1e-8
max_iterations = 100
connectivity = 4
[sliding]
loads = [5e-4, 1e-3]
distance = 0.5
running_in = 0.25
step_running_in = 4
step = 1
"#;

const STUDY: &str = r#"
[surface]
grid = 64
lambda_lower = 0.0625
lambda_upper = 0.25
rms_height = [0.004, 0.005]
seed = [1, 2]
[[materials]]
name = "a"
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = [0.008, 0.012]
fracture_energies = [0.5e-6]
surface = { rms_height = 0.006 }
[[materials]]
name = "b"
youngs_modulus = 1.0
poisson_ratio = 0.25
shear_strength = 0.01
fracture_energies = [1e-6]
[contact]
connectivity = [4, 8]
[sliding]
loads = [5e-4, 1e-3]
"#;

/// Values that break naive parsers.
const NASTY: [&str; 16] = [
    "nan",
    "inf",
    "-inf",
    "-1",
    "0",
    "1e308",
    "1e-320",
    "5e-324",
    "18446744073709551615",
    "-9223372036854775808",
    "\"\"",
    "[]",
    "[[]]",
    "{}",
    "\"x\"",
    "true",
];

fn mutate(base: &str, edits: &[(usize, u8, usize)]) -> String {
    let mut s: Vec<char> = base.chars().collect();
    for &(at, kind, pick) in edits {
        if s.is_empty() {
            break;
        }
        let at = at % s.len();
        match kind % 4 {
            0 => {
                s.remove(at);
            }
            1 => s.insert(
                at,
                ['=', '[', ']', '"', '\n', ',', '.', '-', 'e', '9', '{', '#'][pick % 12],
            ),
            2 => s[at] = char::from_u32((pick % 0x2fff) as u32 + 32).unwrap_or('x'),
            _ => {
                // Replace the number or token under `at` by a nasty value.
                let start = (0..at)
                    .rev()
                    .find(|&i| s[i] == '=' || s[i] == '[' || s[i] == ',')
                    .map_or(at, |i| i + 1);
                let end = (at..s.len())
                    .find(|&i| s[i] == '\n' || s[i] == ',' || s[i] == ']')
                    .unwrap_or(s.len());
                if start <= end {
                    let value: Vec<char> = format!(" {}", NASTY[pick % NASTY.len()]).chars().collect();
                    s.splice(start..end, value);
                }
            }
        }
    }
    s.into_iter().collect()
}

fn corpus(kind: &str) -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fuzz-corpus")
        .join(kind);
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).collect();
    files.sort();
    files
}

fn parse_run(text: &str) {
    let _ = RunConfig::from_toml(text, Path::new("."));
}

fn parse_study(text: &str) {
    let _ = expand(text, Path::new("."));
}

fn parse_npy(bytes: &[u8]) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("a.npy");
    std::fs::write(&path, bytes).unwrap();
    let all = [
        NpyType::Float64,
        NpyType::Float32,
        NpyType::Int64,
        NpyType::Int32,
        NpyType::Int16,
        NpyType::Int8,
        NpyType::UInt8,
        NpyType::Bool,
    ];
    let _ = read_npy_2d(&path, &all, "an array");
    let _ = wearsim::Surface::read_npy(&path, 1.0);
}

fn parse_job(text: &str) {
    let _ = JobResult::from_json(text);
}

fn valid_npy() -> Vec<u8> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("a.npy");
    let values: Vec<f64> = (0..256).map(|k| (k as f64 * 0.3).sin() * 1e-3).collect();
    write_npy_f64(&path, 16, 16, &values).unwrap();
    std::fs::read(path).unwrap()
}

fn valid_job() -> String {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz-corpus/job/valid.json");
    std::fs::read_to_string(dir).unwrap()
}

#[test]
fn the_corpus_parses_without_a_panic() {
    for f in corpus("run") {
        parse_run(&std::fs::read_to_string(&f).unwrap());
    }
    for f in corpus("study") {
        parse_study(&std::fs::read_to_string(&f).unwrap());
    }
    for f in corpus("npy") {
        parse_npy(&std::fs::read(&f).unwrap());
    }
    for f in corpus("job") {
        parse_job(&std::fs::read_to_string(&f).unwrap());
    }
    // The valid examples are valid.
    assert!(RunConfig::from_toml(RUN, Path::new(".")).is_ok());
    assert_eq!(expand(STUDY, Path::new(".")).unwrap().jobs.len(), 32);
    assert!(JobResult::from_json(&valid_job()).is_ok());
}

fn edits() -> impl Strategy<Value = Vec<(usize, u8, usize)>> {
    proptest::collection::vec((any::<usize>(), any::<u8>(), any::<usize>()), 1..8)
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(1000),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn run_files_never_panic(e in edits(), junk in ".{0,200}") {
        parse_run(&mutate(RUN, &e));
        parse_run(&junk);
    }

    #[test]
    fn study_files_never_panic(e in edits(), junk in ".{0,200}") {
        parse_study(&mutate(STUDY, &e));
        parse_study(&junk);
    }

    #[test]
    fn job_files_never_panic(e in edits(), junk in ".{0,200}") {
        parse_job(&mutate(&valid_job(), &e));
        parse_job(&junk);
    }

    #[test]
    fn npy_files_never_panic(
        flips in proptest::collection::vec((any::<usize>(), any::<u8>()), 1..6),
        cut in any::<usize>(),
        junk in proptest::collection::vec(any::<u8>(), 0..300),
        header in "[ -~]{0,120}",
    ) {
        let valid = valid_npy();
        let mut bytes = valid.clone();
        for (at, b) in flips {
            let at = at % bytes.len();
            bytes[at] = b;
        }
        parse_npy(&bytes);
        parse_npy(&valid[..cut % valid.len()]);
        parse_npy(&junk);
        // A header of arbitrary text behind a valid magic and length.
        let mut h = b"\x93NUMPY\x01\x00".to_vec();
        h.extend_from_slice(&(header.len() as u16).to_le_bytes());
        h.extend_from_slice(header.as_bytes());
        h.extend_from_slice(&[0u8; 64]);
        parse_npy(&h);
    }
}
