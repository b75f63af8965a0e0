//! Units of quantities and columns in the run's unit system (reduced: E, L; SI: Pa, m, N, J/m²).
//!
//! Every unit is declared once: a result field's beside the field (`WearResult::UNITS`, and
//! `EstimateResult::UNITS` for the static estimate's), a series
//! column's beside the column ([`SeriesRow::UNITS`]), and every other quantity a table, summary
//! or front end names (the inputs, the tidy and aggregated tables' own columns, the fields) in
//! [`QUANTITIES`]. A name declared nowhere has no unit ([`declared_unit`] says so); the tests
//! check every column of every table against the declarations.

use std::collections::BTreeMap;

use crate::config::Units;
use crate::estimate::EstimateResult;
use crate::sliding::WearResult;

use super::series::SeriesRow;

/// The units of the quantities that are no field of a row declaring its own: (name, reduced, SI);
/// "" for counts and text, "1" for ratios. Input columns (`surface.length`, `sliding.step`, …) are
/// declared by their key.
pub const QUANTITIES: &[(&str, &str, &str)] = &[
    // Loads, pressures, moduli and energies.
    ("load", "E L²", "N"),
    ("nominal_pressure", "E", "Pa"),
    ("fracture_energies", "E L", "J/m²"),
    ("flow_pressure", "E", "Pa"),
    ("effective_modulus", "E", "Pa"),
    ("youngs_modulus", "E", "Pa"),
    ("shear_strength", "E", "Pa"),
    // The run file's alternatives to τ̃ and 𝒢 (converted before the run).
    ("hardness", "E", "Pa"),
    ("yield_strength", "E", "Pa"),
    ("fracture_toughness", "E √L", "Pa √m"),
    ("mean_pressure", "E", "Pa"),
    ("pressure", "E", "Pa"),
    // Lengths.
    ("length", "L", "m"),
    ("length_y", "L", "m"),
    ("map_length", "L", "m"),
    ("lambda_lower", "L", "m"),
    ("lambda_upper", "L", "m"),
    ("rms_height", "L", "m"),
    ("approach", "L", "m"),
    ("pixel_size", "L", "m"),
    ("nominal_area", "L²", "m²"),
    ("gap", "L", "m"),
    ("displacement", "L", "m"),
    // Ratios and dimensionless inputs.
    ("contact_severity", "1", "1"),
    ("poisson_ratio", "1", "1"),
    ("geometry_factor", "1", "1"),
    ("hurst", "1", "1"),
    ("tolerance", "1", "1"),
    ("taper", "1 (fraction of the side)", "1 (fraction of the side)"),
    ("distance", "1 (fraction of Lx)", "1 (fraction of Lx)"),
    ("running_in", "1 (fraction of Lx)", "1 (fraction of Lx)"),
    ("step_running_in", "px", "px"),
    ("step", "px", "px"),
    ("grid", "px", "px"),
    ("grid_y", "px", "px"),
    // Counts, choices and text.
    ("job", "", ""),
    ("material", "", ""),
    ("units", "", ""),
    ("seed", "", ""),
    ("top", "", ""),
    ("bottom", "", ""),
    ("height_unit", "", ""),
    ("lateral_unit", "", ""),
    ("source", "", ""),
    ("map", "", ""),
    ("window", "", ""),
    ("detrend", "", ""),
    ("generation", "", ""),
    ("modulus", "", ""),
    ("max_iterations", "", ""),
    ("connectivity", "", ""),
    ("device", "", ""),
    ("particle_rule", "", ""),
    ("stopping", "", ""),
    ("model", "", ""),
    ("estimate_samples", "", ""),
    // The static estimate's constants of one's own, written as the run file gives them (text).
    ("estimate_constants", "", ""),
    // The static estimate's maps and its comparison with sliding runs (`estimate-check`).
    ("offset", "px", "px"),
    ("static_maps", "", ""),
    ("critical_diameter_pixels", "px", "px"),
    ("sliding_wear_rate", "L²", "m²"),
    ("sliding_wear_coefficient", "1", "1"),
    // The specific wear rate W/F_N, in the unit tribologists report it in.
    ("specific_wear_rate", "1/E", "mm³/(N·m)"),
    ("sliding_particle_rate", "1/L", "1/m"),
    ("sliding_critical_junctions_mean", "", ""),
    ("wear_rate_error", "1", "1"),
    ("particle_rate_error", "1", "1"),
    ("expected_particles", "", ""),
    ("wear_rate_covered", "", ""),
    ("particle_rate_covered", "", ""),
    ("scored", "", ""),
    ("interval_withheld", "", ""),
    ("warnings", "", ""),
    // Columns the aggregated table adds.
    ("curve", "", ""),
    ("surface_pairs", "", ""),
    ("pairs_with_warnings", "", ""),
    ("interval_method", "", ""),
];

/// The specific wear rate K = W/F_N that tribologists report: the wear volume per sliding
/// distance and normal force, Archard's k over the hardness (K = k/p_m, paper Eq. 2). In a run of
/// SI units in mm³/(N·m) (W in m³/m over F_N in N, times 10⁹ mm³/m³), in reduced units in 1/E.
pub fn specific_wear_rate(units: Units, wear_rate: f64, load: f64) -> f64 {
    let per_force = wear_rate / load;
    match units {
        Units::Si => per_force * 1e9,
        Units::Reduced => per_force,
    }
}

/// Statistics over surface pairs that keep the unit of their column.
const STATISTICS: [&str; 7] = ["_mean", "_std", "_min", "_max", "_total", "_ci_low", "_ci_high"];

/// The declared unit of a quantity (a result field, a series or table column, an input) in a unit
/// system, or `None` when none declares it: reduced units are multiples of E and L; SI units are
/// Pa, m, N and J/m²; "" for counts and text, "1" for ratios. Statistics over surface pairs
/// (`_mean`, `_std`, `_min`, `_max`, `_total`) and the bounds of their intervals (`_ci_low`,
/// `_ci_high`) keep the unit of their column, and the
/// `surface.`/`material.`/`contact.`/`sliding.` prefixes of input columns are looked through.
pub fn declared_unit(units: Units, quantity: &str) -> Option<&'static str> {
    let si = units == Units::Si;
    let declared = |name: &str| {
        [WearResult::UNITS, EstimateResult::UNITS, SeriesRow::UNITS, QUANTITIES]
            .iter()
            .find_map(|table| table.iter().find(|u| u.0 == name))
            .map(|&(_, reduced, si_unit)| if si { si_unit } else { reduced })
    };
    let mut name = quantity.rsplit('.').next().unwrap_or(quantity);
    loop {
        if let Some(unit) = declared(name) {
            return Some(unit);
        }
        name = STATISTICS.iter().find_map(|s| name.strip_suffix(s))?;
    }
}

/// [`declared_unit`] for a quantity the caller names in code (a front end's label): "" when none
/// is declared, which the tests rule out for every column a table emits.
pub fn unit_of(units: Units, quantity: &str) -> &'static str {
    declared_unit(units, quantity).unwrap_or("")
}

/// The units of the given columns (those with one, counts and text left out), for a table's
/// companion file or a summary.
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
        assert_eq!(declared_unit(Units::Reduced, "particles_in_fit_total"), Some(""));
        assert_eq!(unit_of(Units::Si, "wear_rate_ci_high"), "m²");
        assert_eq!(unit_of(Units::Reduced, "nominal_pressure_ci_low"), "E");
        assert_eq!(unit_of(Units::Si, "fracture_energy"), "J/m²");
        assert_eq!(unit_of(Units::Reduced, "surface.length"), "L");
        assert_eq!(unit_of(Units::Reduced, "volume"), "L³");
        assert_eq!(unit_of(Units::Reduced, "sliding.step"), "px");
        // A name declared nowhere has no unit, rather than an empty one.
        assert_eq!(declared_unit(Units::Si, "undeclared_column"), None);
        assert_eq!(declared_unit(Units::Si, "undeclared_column_mean"), None);
    }

    #[test]
    fn a_quantity_declared_twice_has_one_unit() {
        let tables = [WearResult::UNITS, EstimateResult::UNITS, SeriesRow::UNITS, QUANTITIES];
        for (i, a) in tables.iter().enumerate() {
            for b in &tables[i + 1..] {
                for x in a.iter() {
                    if let Some(y) = b.iter().find(|y| y.0 == x.0) {
                        assert_eq!(x, y, "{} is declared with two units", x.0);
                    }
                }
            }
            let mut names: Vec<&str> = a.iter().map(|u| u.0).collect();
            names.sort_unstable();
            names.dedup();
            assert_eq!(names.len(), a.len(), "a name declared twice in one table");
        }
    }
}
