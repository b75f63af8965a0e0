//! What the figures of both front ends read from a study's tables, derived once: the label of each
//! curve, the contact-severity fits of appendix F per material, Kim et al.'s ceramics (paper Table 1)
//! and whether a study holds them, and numbers as legends print them.

use crate::config::Units;
use crate::model::WearModel;
use crate::stats::{power_law_fit, PowerLawFit};

use super::jobs::curves;
use super::tables::{Cell, Table};

/// A number for legends and labels: three significant digits without trailing zeros (0.00901,
/// 0.25, 12, 1500), in exponent form outside 10⁻³ … 10⁴ (2.5e-7).
pub fn number(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return if v == 0.0 { "0".into() } else { format!("{v}") };
    }
    let a = v.abs();
    if (1e-3..1e4).contains(&a) {
        let decimals = (2 - a.log10().floor() as i32).max(0) as usize;
        let s = format!("{v:.decimals$}");
        return if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        };
    }
    let s = format!("{v:.2e}");
    let (mantissa, exponent) = s.split_once('e').unwrap_or((&s, "0"));
    let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
    format!("{mantissa}e{exponent}")
}

/// A number with a ×10ⁿ exponent (`2.5×10⁻⁷`), or plain when it needs none.
pub fn pretty(v: f64) -> String {
    let a = v.abs();
    if v == 0.0 || (1e-3..1e4).contains(&a) {
        return number(v);
    }
    let s = number(v);
    let (mantissa, exponent) = s.split_once('e').unwrap_or((&s, "0"));
    let sup: String = exponent
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            d @ '0'..='9' => ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'][d as usize - '0' as usize],
            other => other,
        })
        .collect();
    if mantissa == "1" {
        format!("10{sup}")
    } else {
        format!("{mantissa}×10{sup}")
    }
}

/// How legends show lengths, stresses and energies in a unit system (µm and GPa in SI).
fn show(units: Units, kind: &str, v: f64) -> String {
    let si = units == Units::Si;
    match (kind, si) {
        ("length", true) => format!("{} µm", number(v * 1e6)),
        ("length", false) => format!("{} L", number(v)),
        ("stress", true) => format!("{} GPa", number(v / 1e9)),
        ("stress", false) => format!("{} E", number(v)),
        ("energy", true) => format!("{} J/m²", number(v)),
        _ => format!("{} E L", pretty(v)),
    }
}

/// How a setting column that tells curves apart is named in a legend, with the paper's symbols.
fn setting_label(column: &str, cell: &Cell, units: Units) -> String {
    let name = column.rsplit('.').next().unwrap_or(column);
    let v = cell.number();
    // An empty particle rule is the paper's, recorded only when another is run.
    if name == "particle_rule" && cell.text().is_empty() {
        return format!("{name} = {}", crate::wear::OVERLAP.name);
    }
    if v.is_nan() {
        return format!("{name} = {}", cell.text());
    }
    match name {
        "shear_strength" => format!("τ̃ = {}", show(units, "stress", v)),
        "youngs_modulus" => format!("E = {}", show(units, "stress", v)),
        "rms_height" => format!("h_rms = {}", show(units, "length", v)),
        "lambda_lower" => format!("λ_l = {}", show(units, "length", v)),
        "lambda_upper" => format!("λ_u = {}", show(units, "length", v)),
        "length" => format!("box {}", show(units, "length", v)),
        "grid" => format!("{}² px", number(v)),
        "step_running_in" => format!("running-in step {} px", number(v)),
        _ => format!("{name} = {}", number(v)),
    }
}

/// The label of every curve of a tidy or aggregated table, by curve index (`output::curves`):
/// what a curve of another model than the paper's says first (`WearModel::curve_label`: "static
/// estimate" for the static estimate; a model name not known here as it is), the material when it
/// is named, each setting that tells the curves apart, then 𝒢 with its d*
/// ("τ̃ = 0.012 E, 𝒢 = 2.5×10⁻⁷ E L (d* = 0.00401 L)").
pub fn curve_labels(table: &Table) -> Vec<String> {
    let found = curves(table);
    let units = table.units();
    let d_star = table
        .column("critical_diameter")
        .or_else(|| table.column("critical_diameter_mean"));
    let mut labels: Vec<String> = Vec::new();
    for (row, &c) in table.rows.iter().zip(&found.index) {
        if c < labels.len() {
            continue;
        }
        let mut parts: Vec<String> = Vec::new();
        // A curve of another model than the paper's says so first, wherever it is drawn (one of a
        // model not known here by its name).
        if let Some(m) = table.column("sliding.model") {
            let name = row[m].text();
            match WearModel::of_cell(&name) {
                Some(model) => parts.extend(model.curve_label().map(String::from)),
                None => parts.push(name),
            }
        }
        if let Some(m) = table.column("material") {
            if row[m].text() != "material" {
                parts.push(row[m].text());
            }
        }
        for s in found
            .settings
            .iter()
            .filter(|s| !["material", "fracture_energy", "sliding.model"].contains(&s.as_str()))
        {
            if let Some(i) = table.column(s) {
                parts.push(setting_label(s, &row[i], units));
            }
        }
        let energy = table.column("fracture_energy").map_or(f64::NAN, |i| row[i].number());
        let d = d_star.map_or(f64::NAN, |i| row[i].number());
        parts.push(format!(
            "𝒢 = {} (d* = {})",
            show(units, "energy", energy),
            show(units, "length", d)
        ));
        labels.push(parts.join(", "));
    }
    labels
}

/// A ceramic of Kim et al. (1986) as the paper's Table 1 gives it (SI units).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct KimMaterial {
    pub name: &'static str,
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
    pub shear_strength: f64,
    pub fracture_energy: f64,
}

/// The paper's Table 1: Kim et al.'s ceramics.
pub const KIM_1986: [KimMaterial; 3] = [
    KimMaterial {
        name: "Si3N4",
        youngs_modulus: 294e9,
        poisson_ratio: 0.27,
        shear_strength: 2.89e9,
        fracture_energy: 91.97,
    },
    KimMaterial {
        name: "SiC",
        youngs_modulus: 392e9,
        poisson_ratio: 0.16,
        shear_strength: 4.80e9,
        fracture_energy: 45.00,
    },
    KimMaterial {
        name: "Al2O3",
        youngs_modulus: 343e9,
        poisson_ratio: 0.25,
        shear_strength: 3.37e9,
        fracture_energy: 46.65,
    },
];

/// Kim et al.'s rolling experiments: k = 6×10⁻⁷ … 1.5×10⁻³ (paper §4.2, Fig. 6c).
pub const KIM_EXPERIMENTAL_K: (f64, f64) = (6e-7, 1.5e-3);

/// Kim et al.'s own fit W = α S_cⁿ to their experiments (paper appendix F): α = 1.56×10⁻⁵ mm³/mm
/// (= 1.56×10⁻¹¹ m²), n = 5.46; and the paper's fit to its simulations, α = 1.233×10⁻⁴ mm³/mm,
/// n = 0.9. (α in m², n.)
pub const KIM_SEVERITY_FIT: (f64, f64) = (1.56e-11, 5.46);
pub const PAPER_SEVERITY_FIT: (f64, f64) = (1.233e-10, 0.9);

/// The Kim material whose properties (E, ν, τ̃, 𝒢 in SI units) match within 1 %, if any: only
/// such materials are compared with Kim's experiments (Fig. 6, appendix F).
pub fn kim_material(
    youngs_modulus: f64,
    poisson_ratio: f64,
    shear_strength: f64,
    fracture_energy: f64,
) -> Option<KimMaterial> {
    let near = |a: f64, b: f64| (a / b - 1.0).abs() < 0.01;
    KIM_1986.into_iter().find(|k| {
        near(youngs_modulus, k.youngs_modulus)
            && near(poisson_ratio, k.poisson_ratio)
            && near(shear_strength, k.shear_strength)
            && near(fracture_energy, k.fracture_energy)
    })
}

/// The Kim material of a row of a tidy table (SI units only): the one test whether a row is one of
/// Kim's ceramics, shared by the figures and the findings (`study::findings`).
pub fn kim_of_row(table: &Table, row: &[Cell]) -> Option<KimMaterial> {
    let num = |name: &str| table.column(name).map_or(f64::NAN, |i| row[i].number());
    let si = table.column("units").is_some_and(|c| row[c].text() == "si");
    si.then(|| {
        kim_material(
            num("material.youngs_modulus"),
            num("material.poisson_ratio"),
            num("material.shear_strength"),
            num("fracture_energy"),
        )
    })
    .flatten()
}

/// Whether any row of a tidy or aggregated table is one of Kim's ceramics (a figure draws Kim's
/// experimental band only then).
pub fn has_kim_materials(table: &Table) -> bool {
    table.rows.iter().any(|r| kim_of_row(table, r).is_some())
}

/// One material's points of appendix F and their fit.
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialSeverity {
    pub material: String,
    /// (S_c, W) of every job of the material with W > 0 and S_c defined.
    pub points: Vec<(f64, f64)>,
    /// W = α S_cⁿ fitted to those points (two distinct S_c or more).
    pub fit: Option<PowerLawFit>,
    /// The Kim ceramic it is, when its properties are Table 1's: only then is the paper's n shown
    /// beside it.
    pub kim: Option<KimMaterial>,
}

/// Appendix F on a tidy table: per material (in order of appearance), the points (S_c, W) of the
/// rows with W > 0 and a contact severity (generated surfaces), the fit W = α S_cⁿ in log–log, and
/// the fit over all materials' points.
pub fn severity_fits(tidy: &Table) -> (Vec<MaterialSeverity>, Option<PowerLawFit>) {
    // Appendix F fits the sliding model's W: rows of the static estimate are left out.
    let (sliding, _) = super::jobs::sliding_rows(tidy);
    let tidy = &sliding;
    let (Some(s_c), Some(w)) = (tidy.column("contact_severity"), tidy.column("wear_rate")) else {
        return (Vec::new(), None);
    };
    let material = tidy.column("material");
    let mut out: Vec<MaterialSeverity> = Vec::new();
    for row in &tidy.rows {
        let (x, y) = (row[s_c].number(), row[w].number());
        if !(x.is_finite() && y > 0.0 && y.is_finite()) {
            continue;
        }
        let name = material.map_or("material".to_string(), |m| row[m].text());
        let i = match out.iter().position(|m| m.material == name) {
            Some(i) => i,
            None => {
                out.push(MaterialSeverity {
                    material: name,
                    points: Vec::new(),
                    fit: None,
                    kim: kim_of_row(tidy, row),
                });
                out.len() - 1
            }
        };
        out[i].points.push((x, y));
    }
    for m in &mut out {
        let (x, y): (Vec<f64>, Vec<f64>) = m.points.iter().copied().unzip();
        m.fit = power_law_fit(&x, &y);
    }
    let (x, y): (Vec<f64>, Vec<f64>) = out.iter().flat_map(|m| m.points.iter().copied()).unzip();
    (out, power_law_fit(&x, &y))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(columns: &[&str], rows: Vec<Vec<Cell>>) -> Table {
        Table {
            columns: columns.iter().map(|c| c.to_string()).collect(),
            rows,
        }
    }

    #[test]
    fn numbers_for_legends() {
        assert_eq!(number(0.25), "0.25");
        assert_eq!(number(0.009012), "0.00901");
        assert_eq!(number(2.5e-7), "2.5e-7");
        assert_eq!(pretty(2.5e-7), "2.5×10⁻⁷");
        assert_eq!(pretty(1e-6), "10⁻⁶");
    }

    #[test]
    fn curve_labels_name_the_settings_that_differ_and_g_with_d_star() {
        let f = |x: f64| Cell::Float(x);
        let t = table(
            &[
                "material",
                "units",
                "material.shear_strength",
                "load",
                "fracture_energy",
                "critical_diameter",
            ],
            vec![
                vec![
                    Cell::Text("material".into()),
                    Cell::Text("reduced".into()),
                    f(0.012),
                    f(1e-3),
                    f(2.5e-7),
                    f(0.004),
                ],
                vec![
                    Cell::Text("material".into()),
                    Cell::Text("reduced".into()),
                    f(0.012),
                    f(2e-3),
                    f(2.5e-7),
                    f(0.004),
                ],
                vec![
                    Cell::Text("material".into()),
                    Cell::Text("reduced".into()),
                    f(0.008),
                    f(1e-3),
                    f(2.5e-7),
                    f(0.009),
                ],
            ],
        );
        assert_eq!(
            curve_labels(&t),
            [
                "τ̃ = 0.012 E, 𝒢 = 2.5×10⁻⁷ E L (d* = 0.004 L)",
                "τ̃ = 0.008 E, 𝒢 = 2.5×10⁻⁷ E L (d* = 0.009 L)"
            ]
        );
    }

    #[test]
    fn kim_materials_and_severity_fits_per_material() {
        assert_eq!(kim_material(294e9, 0.27, 2.89e9, 91.97).map(|k| k.name), Some("Si3N4"));
        assert!(kim_material(1.0, 0.3, 0.012, 0.25e-6).is_none());
        let f = |x: f64| Cell::Float(x);
        let text = |s: &str| Cell::Text(s.into());
        let columns = [
            "material",
            "units",
            "material.youngs_modulus",
            "material.poisson_ratio",
            "material.shear_strength",
            "fracture_energy",
            "contact_severity",
            "wear_rate",
        ];
        // SiC: W = 2 S_c² exactly; a generic material: W = 3 S_c; a row without wear left out.
        let sic = |s: f64, w: f64| {
            vec![
                text("SiC"),
                text("si"),
                f(392e9),
                f(0.16),
                f(4.8e9),
                f(45.0),
                f(s),
                f(w),
            ]
        };
        let other = |s: f64, w: f64| vec![text("soft"), text("si"), f(200e9), f(0.3), f(1e9), f(10.0), f(s), f(w)];
        let t = table(
            &columns,
            vec![
                sic(1.0, 2.0),
                sic(2.0, 8.0),
                other(1.0, 3.0),
                other(2.0, 6.0),
                other(3.0, 0.0),
            ],
        );
        let (materials, all) = severity_fits(&t);
        assert_eq!(materials.len(), 2);
        assert_eq!(materials[0].kim.map(|k| k.name), Some("SiC"));
        assert!(materials[1].kim.is_none() && materials[1].points.len() == 2);
        let fit = materials[0].fit.unwrap();
        assert!((fit.exponent - 2.0).abs() < 1e-12 && (fit.prefactor - 2.0).abs() < 1e-12);
        assert!((materials[1].fit.unwrap().exponent - 1.0).abs() < 1e-12);
        assert!(all.is_some());
        assert!(has_kim_materials(&t));
    }
}
