//! Where a result came from: the provenance block every document of wearsim carries.

use serde::{Deserialize, Serialize};

/// Where a result came from: software version, the command line of the process that wrote it, and
/// the date (UTC, RFC 3339).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Provenance {
    pub software: String,
    pub command: String,
    pub date: String,
}

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
            command,
            date: humantime::format_rfc3339_seconds(std::time::SystemTime::now()).to_string(),
        }
    }
}
