//! The paper's qualitative findings (Brink, Frérot & Molinari 2021, §2–4 and appendix B), checked
//! on a study's tidy table: each finding says what the paper reports, what the study shows, and
//! whether the study reproduces it, does not, or cannot test it (no setting of the study speaks to
//! it, or its settings are not resolved). `wearsim study plot` prints them and writes
//! `figures/findings.md`; the tests check the README's main job against them.

use std::collections::BTreeMap;

use crate::output::{aggregate, Cell, Table};

/// Whether a study reproduces a finding of the paper.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    Reproduced,
    NotReproduced,
    NotTestable,
}

impl Verdict {
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Reproduced => "reproduced",
            Verdict::NotReproduced => "not reproduced",
            Verdict::NotTestable => "not testable here",
        }
    }
}

/// One finding of the paper checked on a study.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Finding {
    /// Short name, stable (tests refer to it).
    pub key: &'static str,
    /// What the paper reports, with its section.
    pub paper: &'static str,
    /// What the study shows, with numbers.
    pub observed: String,
    pub verdict: Verdict,
}

/// Particles after running-in below which a setting's wear rate is too noisy to compare.
const RESOLVED_PARTICLES: f64 = 5.0;

/// One setting of the study (every input but the surface pair), averaged over surface pairs.
#[derive(Debug, Clone)]
struct Setting {
    /// Material name, shear strength τ̃ and every input but τ̃, 𝒢 and the load, as text.
    family: String,
    shear_strength: f64,
    fracture_energy: f64,
    /// Mean pressure F_N/(Lx Ly) of the box.
    pressure: f64,
    pixel_size: f64,
    /// "m" in SI studies, "L" in reduced ones: the unit of lengths in the observations.
    length_unit: &'static str,
    values: BTreeMap<String, f64>,
}

impl Setting {
    fn get(&self, name: &str) -> f64 {
        self.values.get(name).copied().unwrap_or(f64::NAN)
    }

    fn resolved(&self) -> bool {
        self.get("particles_in_fit_mean") >= RESOLVED_PARTICLES
    }

    fn label(&self) -> String {
        format!(
            "τ̃ = {}, 𝒢 = {:.2e}, F_N/L² = {:.2e}",
            param(self.shear_strength),
            self.fracture_energy,
            self.pressure
        )
    }
}

fn settings(tidy: &Table) -> Vec<Setting> {
    let agg = aggregate(tidy);
    let col = |name: &str| agg.column(name);
    let skip = [
        "material.shear_strength",
        "fracture_energy",
        "load",
        "nominal_pressure",
        "contact_severity",
        "curve",
        "surface_pairs",
        "pairs_with_warnings",
    ];
    agg.rows
        .iter()
        .map(|row| {
            let num = |name: &str| col(name).map_or(f64::NAN, |i| row[i].number());
            let length = num("surface.length");
            // Ly is empty on square grids.
            let length_y = Some(num("surface.length_y"))
                .filter(|l| l.is_finite())
                .unwrap_or(length);
            let grid = num("surface.grid");
            let mut family = Vec::new();
            let mut values = BTreeMap::new();
            for (c, cell) in agg.columns.iter().zip(row) {
                if c.ends_with("_mean") || c.ends_with("_min") || c.ends_with("_max") {
                    values.insert(c.clone(), cell.number());
                } else if !skip.contains(&c.as_str()) {
                    family.push(match cell {
                        Cell::Empty => String::new(),
                        other => other.text(),
                    });
                }
            }
            Setting {
                family: family.join("|"),
                shear_strength: num("material.shear_strength"),
                fracture_energy: num("fracture_energy"),
                pressure: num("load") / (length * length_y),
                pixel_size: length / grid,
                length_unit: if col("units").is_some_and(|i| row[i].text() == "si") {
                    "m"
                } else {
                    "L"
                },
                values,
            }
        })
        .collect()
}

/// An input value as given (0.008), in exponent form when large (3.37e9 Pa).
fn param(x: f64) -> String {
    if (1e-3..1e4).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

fn fmt(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else if (1e-2..1e3).contains(&x.abs()) {
        format!("{x:.3}")
    } else {
        format!("{x:.2e}")
    }
}

/// Curves of one material against load: settings grouped by family, τ̃ and 𝒢, sorted by load.
fn curves(all: &[Setting]) -> Vec<Vec<&Setting>> {
    let mut groups: BTreeMap<String, Vec<&Setting>> = BTreeMap::new();
    for s in all {
        groups
            .entry(format!("{}|{:e}|{:e}", s.family, s.shear_strength, s.fracture_energy))
            .or_default()
            .push(s);
    }
    groups
        .into_values()
        .map(|mut c| {
            c.sort_by(|a, b| a.pressure.total_cmp(&b.pressure));
            c
        })
        .collect()
}

fn verdict(testable: bool, ok: bool) -> Verdict {
    match (testable, ok) {
        (false, _) => Verdict::NotTestable,
        (true, true) => Verdict::Reproduced,
        (true, false) => Verdict::NotReproduced,
    }
}

/// The paper's findings checked on a study's tidy table (`results.csv`).
pub fn findings(tidy: &Table) -> Vec<Finding> {
    let all = settings(tidy);
    let curves = curves(&all);
    let mut out = Vec::new();

    // 1. Static model: k_static < 1 and rising with load.
    {
        let live: Vec<&Vec<&Setting>> = curves
            .iter()
            .filter(|c| c.len() >= 2 && c.iter().any(|s| s.get("static_wear_coefficient_mean_mean") > 0.0))
            .collect();
        let mut lines = Vec::new();
        let mut ok = true;
        for c in &live {
            let k: Vec<f64> = c.iter().map(|s| s.get("static_wear_coefficient_mean_mean")).collect();
            let rising = k.last() > k.first();
            let below = k.iter().all(|&x| x < 1.0);
            ok &= rising && below;
            lines.push(format!(
                "{} → {} (τ̃ = {}, 𝒢 = {:.2e})",
                fmt(k[0]),
                fmt(*k.last().unwrap_or(&f64::NAN)),
                param(c[0].shear_strength),
                c[0].fracture_energy
            ));
        }
        out.push(Finding {
            key: "static-k-below-one-and-rising",
            paper: "static model (§2, Fig. 2): k_static grows with load, towards 1",
            observed: format!(
                "k_static (mean over offsets, lowest → highest load): {}",
                lines.join("; ")
            ),
            verdict: verdict(!live.is_empty(), ok),
        });
    }

    // 2. Static model: W_static grows with hardness at fixed 𝒢 and load.
    {
        let mut pairs = 0;
        let mut holding = 0;
        let mut worst = String::new();
        for a in &all {
            for b in &all {
                if a.family == b.family
                    && a.fracture_energy == b.fracture_energy
                    && a.pressure == b.pressure
                    && a.shear_strength > b.shear_strength
                    && a.get("static_wear_rate_mean_mean") > 0.0
                {
                    pairs += 1;
                    if a.get("static_wear_rate_mean_mean") > b.get("static_wear_rate_mean_mean") {
                        holding += 1;
                    } else if worst.is_empty() {
                        worst = format!("; not at {}", a.label());
                    }
                }
            }
        }
        out.push(Finding {
            key: "static-wear-grows-with-hardness",
            paper: "static model (§2, Fig. 2b): W_static grows with hardness, against Archard's law",
            observed: format!(
                "harder material wears more (static) in {holding} of {pairs} comparisons at equal 𝒢 and load{worst}"
            ),
            verdict: verdict(pairs > 0, holding == pairs),
        });
    }

    // 3. Sliding: V(s) linear after running-in.
    {
        let resolved: Vec<&Setting> = all.iter().filter(|s| s.resolved()).collect();
        let r2: Vec<f64> = resolved
            .iter()
            .map(|s| s.get("wear_rate_r2_mean"))
            .filter(|x| x.is_finite())
            .collect();
        let min = r2.iter().copied().fold(f64::INFINITY, f64::min);
        let mean = r2.iter().sum::<f64>() / r2.len().max(1) as f64;
        out.push(Finding {
            key: "volume-linear-after-running-in",
            paper: "sliding model (§3, Fig. 3): V(s) becomes linear after running-in",
            observed: format!(
                "R² of the line fitted to V(s) after running-in, over the {} settings with ≥ {RESOLVED_PARTICLES} particles: mean {}, lowest {}",
                r2.len(),
                fmt(mean),
                fmt(min)
            ),
            verdict: verdict(!r2.is_empty(), mean >= 0.9 && min >= 0.8),
        });
    }

    // 4. Sliding k an order of magnitude below the static k, and below about 0.1.
    {
        let resolved: Vec<&Setting> = all.iter().filter(|s| s.resolved()).collect();
        let ratios: Vec<f64> = resolved
            .iter()
            .map(|s| s.get("static_wear_coefficient_mean_mean") / s.get("wear_coefficient_mean"))
            .filter(|x| x.is_finite())
            .collect();
        let k_max = resolved
            .iter()
            .map(|s| s.get("wear_coefficient_mean"))
            .fold(0.0f64, f64::max);
        let (lo, hi) = (
            ratios.iter().copied().fold(f64::INFINITY, f64::min),
            ratios.iter().copied().fold(0.0f64, f64::max),
        );
        out.push(Finding {
            key: "sliding-k-below-static-and-0.1",
            paper: "sliding model (§4.1, Fig. 4): k an order of magnitude below the static model's, below about 0.1",
            observed: format!(
                "k_static / k = {} … {} over the resolved settings; largest sliding k = {}",
                fmt(lo),
                fmt(hi),
                fmt(k_max)
            ),
            verdict: verdict(!ratios.is_empty(), hi >= 5.0 && k_max <= 0.12),
        });
    }

    // 5. At the highest load, the larger d* wears more (via 𝒢 and via τ̃).
    {
        let top = all.iter().map(|s| s.pressure).fold(0.0f64, f64::max);
        let at_top: Vec<&Setting> = all.iter().filter(|s| s.pressure == top && s.resolved()).collect();
        let mut lines = Vec::new();
        let mut ok = true;
        let mut tested = 0;
        for a in &at_top {
            for b in &at_top {
                let same_tau = a.shear_strength == b.shear_strength && a.fracture_energy > b.fracture_energy;
                let same_g = a.fracture_energy == b.fracture_energy && a.shear_strength < b.shear_strength;
                if a.family == b.family && (same_tau || same_g) {
                    // a has the larger d*.
                    tested += 1;
                    let (wa, wb) = (a.get("wear_rate_mean"), b.get("wear_rate_mean"));
                    ok &= wa > wb;
                    lines.push(format!(
                        "d* {} vs {}: W {} vs {} ({})",
                        fmt(a.get("critical_diameter_mean")),
                        fmt(b.get("critical_diameter_mean")),
                        fmt(wa),
                        fmt(wb),
                        if same_tau { "larger 𝒢" } else { "smaller τ̃" }
                    ));
                }
            }
        }
        out.push(Finding {
            key: "larger-d-star-wears-more-at-high-load",
            paper: "sliding model (§4.1, Fig. 4a–b): at high loads, materials with larger d* wear more",
            observed: format!(
                "at F_N/L² = {}, between resolved settings differing in 𝒢 or τ̃: {}",
                fmt(top),
                if lines.is_empty() {
                    "no pair".into()
                } else {
                    lines.join("; ")
                }
            ),
            verdict: verdict(tested > 0, ok),
        });
    }

    // 6. The hardest, least tough material emits the most particles.
    {
        let top = all.iter().map(|s| s.pressure).fold(0.0f64, f64::max);
        let at_top: Vec<&Setting> = all.iter().filter(|s| s.pressure == top).collect();
        let best = at_top
            .iter()
            .max_by(|a, b| a.get("particle_rate_mean").total_cmp(&b.get("particle_rate_mean")));
        let hardest = at_top.iter().map(|s| s.shear_strength).fold(0.0f64, f64::max);
        let least_tough = at_top.iter().map(|s| s.fracture_energy).fold(f64::INFINITY, f64::min);
        let ok = best.is_some_and(|b| b.shear_strength == hardest && b.fracture_energy == least_tough);
        out.push(Finding {
            key: "hardest-least-tough-emits-most-particles",
            paper: "sliding model (§4.1, Fig. 5): the hardest and least tough material emits the most (smallest) particles",
            observed: best.map_or("no setting".into(), |b| {
                format!("most particles at the highest load: {} with dN*₊/ds = {}", b.label(), fmt(b.get("particle_rate_mean")))
            }),
            verdict: verdict(at_top.len() > 1, ok),
        });
    }

    // 7. Eq. 5 slightly underestimates W.
    {
        let ratios: Vec<f64> = all
            .iter()
            .filter(|s| s.resolved())
            .map(|s| s.get("wear_rate_estimate_mean") / s.get("wear_rate_mean"))
            .filter(|x| x.is_finite())
            .collect();
        let (lo, hi) = (
            ratios.iter().copied().fold(f64::INFINITY, f64::min),
            ratios.iter().copied().fold(0.0f64, f64::max),
        );
        out.push(Finding {
            key: "equation-5-slightly-below-w",
            paper: "appendix B (Fig. B.9b): ω d*³ dN*₊/ds (Eq. 5) slightly underestimates the summed W",
            observed: format!("Eq. 5 / W = {} … {} over the resolved settings", fmt(lo), fmt(hi)),
            verdict: verdict(!ratios.is_empty(), lo >= 0.6 && hi <= 1.0),
        });
    }

    // 8. V₀ much larger than later increments.
    {
        let ratios: Vec<f64> = all
            .iter()
            .filter(|s| s.resolved() && s.get("initial_volume_mean") > 0.0)
            .map(|s| s.get("initial_volume_mean") / (s.get("wear_rate_mean") * s.pixel_size))
            .filter(|x| x.is_finite())
            .collect();
        let lo = ratios.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = ratios.iter().copied().fold(0.0f64, f64::max);
        out.push(Finding {
            key: "initial-volume-much-larger-than-increments",
            paper: "sliding model (§3, Fig. 3): V₀ is much larger than the later increments δV",
            observed: format!(
                "V₀ / (W·Δx), V₀ over the mean increment of a one-pixel step: {} … {}",
                fmt(lo),
                fmt(hi)
            ),
            verdict: verdict(!ratios.is_empty(), lo >= 5.0),
        });
    }

    // 9. The memory of the initial contact decays exponentially.
    {
        let r2: Vec<f64> = all
            .iter()
            .map(|s| s.get("memory_decay_r2_mean"))
            .filter(|x| x.is_finite())
            .collect();
        let mean = r2.iter().sum::<f64>() / r2.len().max(1) as f64;
        let lengths: Vec<f64> = all
            .iter()
            .map(|s| s.get("memory_decay_length_mean"))
            .filter(|x| x.is_finite())
            .collect();
        out.push(Finding {
            key: "memory-decays-exponentially",
            paper: "sliding model (§3): the number of contacts present at s = 0 decays exponentially with s",
            observed: format!(
                "R² of ln N₀ against s: mean {} over {} settings; decay lengths {} … {} {}",
                fmt(mean),
                r2.len(),
                fmt(lengths.iter().copied().fold(f64::INFINITY, f64::min)),
                fmt(lengths.iter().copied().fold(0.0f64, f64::max)),
                all.first().map_or("L", |s| s.length_unit)
            ),
            verdict: verdict(!r2.is_empty(), mean >= 0.8),
        });
    }
    out
}

/// The findings as a Markdown table.
pub fn markdown(findings: &[Finding]) -> String {
    let mut text = String::from("| finding (paper) | this study | verdict |\n|---|---|---|\n");
    for f in findings {
        text += &format!(
            "| {} | {} | {} |\n",
            f.paper,
            f.observed.replace('|', "/"),
            f.verdict.name()
        );
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::InputRecord;
    use crate::output::TidyRow;
    use crate::sliding::WearResult;

    /// A hand-made study: two hardnesses, one 𝒢, two loads, two surface pairs.
    fn table(flip: bool) -> Table {
        let mut rows = Vec::new();
        for (job, (tau, load, seed)) in [
            (0.008, 1e-3, 1),
            (0.008, 2e-3, 1),
            (0.012, 1e-3, 1),
            (0.012, 2e-3, 1),
            (0.008, 1e-3, 2),
            (0.008, 2e-3, 2),
            (0.012, 1e-3, 2),
            (0.012, 2e-3, 2),
        ]
        .into_iter()
        .enumerate()
        {
            let hard = tau == 0.012;
            let high = load == 2e-3;
            let k_static = if high { 0.8 } else { 0.4 } * if hard { 1.0 } else { 0.5 };
            let static_rate = k_static * load / (3.0 * 3f64.sqrt() * tau) * if flip && hard { 0.1 } else { 1.0 };
            rows.push(TidyRow {
                job,
                material: "m".into(),
                inputs: InputRecord {
                    seed: Some(seed),
                    shear_strength: tau,
                    grid: Some(64),
                    length: 1.0,
                    ..InputRecord::default()
                },
                load,
                result: WearResult {
                    fracture_energy: 0.5e-6,
                    critical_diameter: if hard { 0.004 } else { 0.009 },
                    wear_rate: Some(if hard { 1e-5 } else { 2e-5 } * if high { 2.0 } else { 1.0 }),
                    wear_rate_r2: Some(0.95),
                    wear_coefficient: Some(0.05),
                    particle_rate: Some(if hard { 500.0 } else { 100.0 }),
                    wear_rate_estimate: Some(if hard { 0.9e-5 } else { 1.8e-5 } * if high { 2.0 } else { 1.0 }),
                    particles_in_fit: 20,
                    initial_volume: 1e-4,
                    static_wear_coefficient: k_static,
                    static_wear_rate: static_rate,
                    static_wear_coefficient_mean: k_static,
                    static_wear_coefficient_std: 0.01,
                    static_wear_rate_mean: static_rate,
                    static_wear_rate_std: 0.0,
                    junctions_mean: 30.0,
                    critical_junctions_mean: 3.0,
                    memory_decay_length: Some(0.03),
                    memory_decay_r2: Some(0.9),
                },
                flow_pressure: 3.0 * 3f64.sqrt() * tau,
                warnings: String::new(),
                ..TidyRow::default()
            });
        }
        Table::of(&rows)
    }

    #[test]
    fn findings_on_a_hand_made_study() {
        let f = findings(&table(false));
        let get = |key: &str| f.iter().find(|x| x.key == key).unwrap().verdict;
        assert_eq!(get("static-k-below-one-and-rising"), Verdict::Reproduced);
        assert_eq!(get("static-wear-grows-with-hardness"), Verdict::Reproduced);
        assert_eq!(get("volume-linear-after-running-in"), Verdict::Reproduced);
        assert_eq!(get("larger-d-star-wears-more-at-high-load"), Verdict::Reproduced);
        assert_eq!(get("hardest-least-tough-emits-most-particles"), Verdict::Reproduced);
        assert_eq!(get("equation-5-slightly-below-w"), Verdict::Reproduced);
        // The hard material's static wear rate cut tenfold: the finding fails.
        let flipped = findings(&table(true));
        assert_eq!(
            flipped
                .iter()
                .find(|x| x.key == "static-wear-grows-with-hardness")
                .unwrap()
                .verdict,
            Verdict::NotReproduced
        );
        assert!(markdown(&f).lines().count() == f.len() + 2);
    }

    #[test]
    fn the_pressure_of_a_setting_is_the_load_over_the_box_area() {
        let square = settings(&table(false));
        assert!(square.iter().all(|s| s.pressure == 1e-3 || s.pressure == 2e-3));
        // The same rows on a box of 1 × 0.5: twice the pressure.
        let mut tidy = table(false);
        let i = tidy.columns.iter().position(|c| c == "surface.length_y").unwrap();
        tidy.rows.iter_mut().for_each(|r| r[i] = Cell::Float(0.5));
        let oblong = settings(&tidy);
        assert!(oblong.iter().all(|s| s.pressure == 2e-3 || s.pressure == 4e-3));
    }
}
