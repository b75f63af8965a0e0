//! Where a result came from: the provenance block every document of wearsim carries.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

/// Where a result came from: software version, the versions of the crates that decide its numbers
/// (FFT, random streams), the command line of the process that wrote it, and the date (UTC, RFC 3339).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Provenance {
    pub software: String,
    /// Crate name → version (documents written before wearsim recorded them have none).
    #[serde(default)]
    pub dependencies: BTreeMap<String, String>,
    pub command: String,
    pub date: String,
}

/// The versions of the crates that decide wearsim's numbers (FFT, random streams of generated
/// surfaces), as "name version" pairs separated by ", ", taken from the lockfile at build time.
pub const DEPENDENCY_VERSIONS: &str = env!("WEARSIM_DEPENDENCY_VERSIONS");

impl Provenance {
    /// This process, now.
    pub fn current() -> Self {
        let command = std::env::args_os()
            .map(|a| {
                let a = a.to_string_lossy().to_string();
                if a.is_empty() || a.contains(char::is_whitespace) {
                    format!("'{a}'")
                } else {
                    a
                }
            })
            .collect::<Vec<_>>()
            .join(" ");
        Self {
            software: format!("wearsim {}", crate::io::VERSION),
            dependencies: DEPENDENCY_VERSIONS
                .split(", ")
                .filter_map(|pair| pair.split_once(' '))
                .map(|(name, version)| (name.to_string(), version.to_string()))
                .collect(),
            command,
            date: humantime::format_rfc3339_seconds(std::time::SystemTime::now()).to_string(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn provenance_names_the_locked_fft_and_random_crates() {
        let p = Provenance::current();
        for name in ["rustfft", "realfft", "rand_chacha", "rand_distr"] {
            let version = p.dependencies.get(name).map(String::as_str);
            assert!(
                version.is_some_and(|v| v.starts_with(|c: char| c.is_ascii_digit())),
                "{name}: {version:?} in {:?}",
                p.dependencies
            );
        }
        // Documents written before the versions were recorded still read.
        let old: Provenance = serde_json::from_value(
            serde_json::json!({"software": "wearsim 0.1.0", "command": "wearsim", "date": "2026"}),
        )
        .unwrap();
        assert!(old.dependencies.is_empty());
    }
}
