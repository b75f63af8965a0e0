//! Units of quantities and columns in the run's unit system (reduced: E, L; SI: Pa, m, N, J/m²).

use std::collections::BTreeMap;

use crate::config::Units;

/// The unit of a quantity (a result field, a series or table column, an input) in a unit system:
/// reduced units are multiples of E and L; SI units are Pa, m, N and J/m². Dimensionless numbers and
/// counts have "" (counts) or "1" (ratios). Column suffixes `_mean`, `_std`, `_min`, `_max` and the
/// `surface.`/`material.`/`contact.` prefixes are looked through.
pub fn unit_of(units: Units, quantity: &str) -> &'static str {
    let mut q = quantity.rsplit('.').next().unwrap_or(quantity);
    for suffix in ["_mean", "_std", "_min", "_max"] {
        q = q.strip_suffix(suffix).unwrap_or(q);
    }
    let si = units == Units::Si;
    let pick = |reduced: &'static str, si_unit: &'static str| if si { si_unit } else { reduced };
    match q {
        "load" => pick("E L²", "N"),
        "nominal_pressure" => pick("E", "Pa"),
        "fracture_energy" | "fracture_energies" => pick("E L", "J/m²"),
        "flow_pressure" | "effective_modulus" | "youngs_modulus" | "shear_strength" | "mean_pressure" | "pressure" => {
            pick("E", "Pa")
        }
        "critical_diameter"
        | "s"
        | "length"
        | "lambda_lower"
        | "lambda_upper"
        | "rms_height"
        | "approach"
        | "memory_decay_length"
        | "critical_residence"
        | "fit_window_start"
        | "pixel_size"
        | "gap"
        | "displacement" => pick("L", "m"),
        "wear_rate" | "wear_rate_estimate" | "static_wear_rate" => pick("L²", "m²"),
        "volume" | "initial_volume" | "wear_volume_intercept" => pick("L³", "m³"),
        "particle_rate" => pick("1/L", "1/m"),
        "contact_area" => "1 (fraction of Lx·Ly)",
        "contact_severity"
        | "wear_coefficient"
        | "static_wear_coefficient"
        | "wear_rate_r2"
        | "memory_decay_r2"
        | "running_in_decay_lengths"
        | "poisson_ratio"
        | "geometry_factor"
        | "hurst"
        | "tolerance"
        | "residual" => "1",
        _ => "",
    }
}

/// The units of the given columns (those with one), for a table's companion file or a summary.
pub fn units_map<'a>(units: Units, columns: impl IntoIterator<Item = &'a str>) -> BTreeMap<String, String> {
    columns
        .into_iter()
        .map(|c| (c.to_string(), unit_of(units, c)))
        .filter(|(_, u)| !u.is_empty())
        .map(|(c, u)| (c, u.to_string()))
        .collect()
}
