//! Units of quantities and columns in the run's unit system (reduced: E, L; SI: Pa, m, N, J/m²).

use std::collections::BTreeMap;

use crate::config::Units;
use crate::sliding::WearResult;

/// The unit of a quantity (a result field, a series or table column, an input) in a unit system:
/// reduced units are multiples of E and L; SI units are Pa, m, N and J/m². Dimensionless numbers and
/// counts have "" (counts) or "1" (ratios). Column suffixes `_mean`, `_std`, `_min`, `_max`, `_total`,
/// `_ci_low`, `_ci_high` and the
/// `surface.`/`material.`/`contact.` prefixes are looked through.
pub fn unit_of(units: Units, quantity: &str) -> &'static str {
    let si = units == Units::Si;
    let pick = |reduced: &'static str, si_unit: &'static str| if si { si_unit } else { reduced };
    let mut q = quantity.rsplit('.').next().unwrap_or(quantity);
    // A result field (or a statistic of one over surface pairs): its unit is declared with it.
    let mut field = q;
    loop {
        if let Some(&(_, reduced, si_unit)) = WearResult::UNITS.iter().find(|u| u.0 == field) {
            return pick(reduced, si_unit);
        }
        match ["_mean", "_std", "_min", "_max", "_total", "_ci_low", "_ci_high"]
            .iter()
            .find_map(|s| field.strip_suffix(s))
        {
            Some(shorter) => field = shorter,
            None => break,
        }
    }
    for suffix in ["_ci_low", "_ci_high", "_mean", "_std", "_min", "_max"] {
        q = q.strip_suffix(suffix).unwrap_or(q);
    }
    match q {
        "load" => pick("E L²", "N"),
        "nominal_pressure" => pick("E", "Pa"),
        "fracture_energies" => pick("E L", "J/m²"),
        "flow_pressure" | "effective_modulus" | "youngs_modulus" | "shear_strength" | "mean_pressure" | "pressure" => {
            pick("E", "Pa")
        }
        "s" | "length" | "lambda_lower" | "lambda_upper" | "rms_height" | "approach" | "pixel_size" | "gap"
        | "displacement" => pick("L", "m"),
        "volume" => pick("L³", "m³"),
        "contact_area" => "1 (fraction of Lx·Ly)",
        "contact_severity" | "poisson_ratio" | "geometry_factor" | "hurst" | "tolerance" | "residual" => "1",
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_result_field_states_its_unit_once_beside_its_declaration() {
        let fields: Vec<String> = match serde_json::to_value(WearResult::default()).unwrap() {
            serde_json::Value::Object(map) => map.keys().cloned().collect(),
            other => panic!("a result serialises to an object, not {other}"),
        };
        let declared: Vec<&str> = WearResult::UNITS.iter().map(|u| u.0).collect();
        assert_eq!(declared, fields, "WearResult::UNITS lists the fields in their order");
        // Statistics over pairs keep the unit; counts have none; other tables' columns keep theirs.
        assert_eq!(unit_of(Units::Si, "critical_residence_max"), "m");
        assert_eq!(unit_of(Units::Reduced, "static_wear_rate_mean_mean"), "L²");
        assert_eq!(unit_of(Units::Reduced, "particles_in_fit_total"), "");
        assert_eq!(unit_of(Units::Si, "wear_rate_ci_high"), "m²");
        assert_eq!(unit_of(Units::Reduced, "nominal_pressure_ci_low"), "E");
        assert_eq!(unit_of(Units::Si, "fracture_energy"), "J/m²");
        assert_eq!(unit_of(Units::Reduced, "surface.length"), "L");
        assert_eq!(unit_of(Units::Reduced, "volume"), "L³");
    }
}
