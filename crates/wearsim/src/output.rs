//! Result files. Every file is written to a temporary sibling and renamed into place, so a killed
//! run never leaves a half-written result behind.

use std::io::{BufWriter, Write};
use std::path::Path;

use serde_json::json;

use crate::config::{RunConfig, SlidingConfig, Units};
use crate::contact::SolverOptions;
use crate::error::{Error, Result};
use crate::material::{Material, ModulusConvention};
use crate::sliding::{results_json, series, LoadRun};

/// Writes `path` atomically: `write` fills a temporary file in the same folder, which is then
/// flushed, synced and renamed over `path`. On error the temporary file is removed.
pub fn atomic_write(path: &Path, write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>) -> Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let file_name = path.file_name().ok_or_else(|| Error::io(path, "not a file path"))?;
    let tmp = dir.join(format!(".{}.tmp{}", file_name.to_string_lossy(), std::process::id()));
    let result = (|| -> std::io::Result<()> {
        let file = std::fs::File::create(&tmp)?;
        let mut w = BufWriter::new(file);
        write(&mut w)?;
        let file = w.into_inner().map_err(|e| e.into_error())?;
        file.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(Error::io(path, e));
    }
    Ok(())
}

/// Writes a text file atomically.
pub fn write_text(path: &Path, text: &str) -> Result<()> {
    atomic_write(path, |w| w.write_all(text.as_bytes()))
}

/// `series.csv` of a sliding run: one row per step, load and fracture energy (SPEC §9), plain CSV
/// for pandas and R; units and provenance are in the summary.
pub fn series_csv(runs: &[LoadRun]) -> String {
    let mut text = String::from("load,fracture_energy,s,junctions,contact_area,n_critical,n_formed,n_shrunk,volume\n");
    for r in series(runs) {
        text += &format!(
            "{:e},{:e},{:e},{},{:e},{},{},{},{:e}\n",
            r.load, r.fracture_energy, r.s, r.junctions, r.contact_area, r.n_critical, r.n_formed, r.n_shrunk, r.volume
        );
    }
    text
}

/// What a sliding run was given, for its summary.
pub struct RunInputs<'a> {
    pub units: Units,
    /// Where the surfaces came from (a run file's [`crate::config::SurfaceSource`], or a description
    /// of arrays handed over by the caller).
    pub surfaces: serde_json::Value,
    pub material: &'a Material,
    pub modulus: ModulusConvention,
    pub solver: SolverOptions,
    pub connectivity: u8,
    pub sliding: &'a SlidingConfig,
}

impl<'a> RunInputs<'a> {
    /// The inputs of a run file with a sliding schedule.
    pub fn of_run(config: &'a RunConfig, sliding: &'a SlidingConfig) -> Self {
        Self {
            units: config.units,
            surfaces: serde_json::to_value(&config.surfaces).expect("plain data serialises"),
            material: &config.material,
            modulus: config.modulus,
            solver: config.solver,
            connectivity: config.connectivity,
            sliding,
        }
    }
}

/// `summary.json` of a sliding run (SPEC §9): inputs, derived quantities, solver statistics and the
/// results per load and fracture energy, with the conventions they follow.
pub fn sliding_summary(inputs: &RunInputs, runs: &[LoadRun], seconds: f64, steps_per_load: usize) -> serde_json::Value {
    let (results, solver) = results_json(runs);
    let m = inputs.material;
    json!({
        "software": format!("wearsim {}", crate::VERSION),
        "units": inputs.units,
        "inputs": {
            "surfaces": inputs.surfaces,
            "material": m,
            "contact": {"modulus": inputs.modulus.name(), "tolerance": inputs.solver.tolerance, "max_iterations": inputs.solver.max_iterations, "connectivity": inputs.connectivity},
            "sliding": inputs.sliding,
        },
        "flow_pressure": m.flow_pressure(),
        "critical_diameter": m.fracture_energies.iter().zip(m.critical_diameters()).map(|(g, d)| json!({"fracture_energy": g, "critical_diameter": d})).collect::<Vec<_>>(),
        "effective_modulus": m.effective_modulus(inputs.modulus),
        "modulus_convention": inputs.modulus.name(),
        "solver": {"tolerance": inputs.solver.tolerance, "residual_definition": "max pixel-wise violation of the optimality conditions / std(h)", "per_load": solver},
        "steps_per_load": steps_per_load,
        "fit": "least-squares lines of V and N*₊ against s over the steps with s ≥ running_in·L",
        "static_wear_rate_convention": "W_static/ω = k_static Σ A_i at s = 0",
        "wear_rate_estimate_convention": "ω d*³ dN*₊/ds with ω = π/6",
        "results": results,
        "seconds": seconds,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failed_write_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.txt");
        let err = atomic_write(&path, |w| {
            w.write_all(b"half")?;
            Err(std::io::Error::other("boom"))
        });
        assert!(err.is_err());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
        write_text(&path, "whole").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "whole");
    }
}
