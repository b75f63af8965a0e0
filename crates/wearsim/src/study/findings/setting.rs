//! The settings of a study as the findings see them: one material, τ̃, 𝒢 and load, with the values
//! of each of its surface pairs (the unit of replication), which pairs are run in, and the groupings
//! the findings compare (curves against load, pairs of settings at one load, contact histories).

use std::collections::BTreeMap;

use crate::output::{kim_of_row, settings as setting_groups, Cell, Table};

/// Which rule says that a surface pair is run in (paper §3: once the memory of the initial contact
/// has faded).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RunInRule {
    /// At most [`RUN_IN_LINEAGES_LEFT`](crate::sliding::RUN_IN_LINEAGES_LEFT) of the junction lineages of s = 0 left at the start of the
    /// fit window, counted in the run's steps (the findings' rule).
    LineagesLeft,
    /// The fit window starts at least [`RUN_IN_DECAY_LENGTHS`](crate::sliding::RUN_IN_DECAY_LENGTHS) fitted decay lengths ℓ after s = 0:
    /// the same 5 % extrapolated from ℓ, which a tail of a few persisting lineages can dominate (the
    /// other defensible rule, whose verdicts findings.md gives where they differ).
    DecayLengths,
    /// Every pair counts as run in: no exclusion (the third rule a verdict is read under).
    All,
}

/// One surface pair of a setting: its seed and every numeric column of its row of the tidy table.
#[derive(Debug, Clone)]
pub(super) struct Pair {
    /// The surface pair's seed as text (settings that share it share the surfaces).
    pub seed: String,
    values: BTreeMap<String, f64>,
    rule: RunInRule,
}

impl Pair {
    pub fn get(&self, name: &str) -> f64 {
        self.values.get(name).copied().unwrap_or(f64::NAN)
    }

    /// s_r/ℓ: where the fit window starts, in decay lengths of this pair's own memory of the initial
    /// contact (NaN when not measured).
    pub fn decay_lengths(&self) -> f64 {
        self.get("running_in_decay_lengths")
    }

    /// N₀(s_r)/N₀(0), the lineages of s = 0 left at the start of the fit window (NaN when not
    /// counted: no junction at s = 0).
    pub fn lineages_left(&self) -> f64 {
        self.get("initial_lineages_left")
    }

    /// Run in under the study's [`RunInRule`]: at most [`RUN_IN_LINEAGES_LEFT`](crate::sliding::RUN_IN_LINEAGES_LEFT) of the lineages of
    /// s = 0 left where the fit window starts (where they were not counted, by the decay lengths),
    /// or the fit window at least [`RUN_IN_DECAY_LENGTHS`](crate::sliding::RUN_IN_DECAY_LENGTHS) of the pair's own decay lengths after
    /// s = 0. A pair whose memory is gone by the first step (no decay fitted, empty cell) is run in.
    pub fn run_in(&self) -> bool {
        self.run_in_by(self.rule)
    }

    /// Run in under `rule`.
    pub fn run_in_by(&self, rule: RunInRule) -> bool {
        let r = Some(self.decay_lengths());
        match rule {
            RunInRule::LineagesLeft => crate::sliding::is_run_in(Some(self.lineages_left()), r),
            RunInRule::DecayLengths => crate::sliding::is_run_in(None, r),
            RunInRule::All => true,
        }
    }

    /// Particles formed in the fit window.
    pub fn particles(&self) -> u64 {
        let n = self.get("particles_in_fit");
        if n.is_finite() && n > 0.0 {
            n.round() as u64
        } else {
            0
        }
    }
}

/// One setting of the study (every input but the surface pair) with its pairs.
#[derive(Debug, Clone)]
pub(super) struct Setting {
    /// Its place among the study's settings: the statistics it enters are keyed by it.
    pub id: usize,
    /// Its curve against load (the aggregated table's `curve`).
    pub curve: usize,
    /// Particles formed in the fit windows of its curve, over every load and pair: 0 for a setting
    /// below the onset of wear at every load of the study.
    pub curve_particles: u64,
    /// Which of the material, τ̃ and 𝒢 take more than one value in the study: the labels name only
    /// those.
    pub varies: [bool; 3],
    /// Every input but the material's name, τ̃, 𝒢 and the load, as text: settings compare within a family.
    pub family: String,
    /// The same inputs by column, for comparisons across one study axis (a box, a grid, λ_l, h_rms).
    pub family_cells: BTreeMap<String, String>,
    /// The load F_N.
    pub load: f64,
    /// The box's side Lx and the sliding distance over which the fit window runs (from its start to
    /// the end of the run): the exposure of the particle counts.
    pub length: f64,
    /// The running-in s_r as a fraction of the box side Lx (`sliding.running_in`).
    pub running_in: f64,
    pub fit_distance: f64,
    pub material: String,
    pub shear_strength: f64,
    pub fracture_energy: f64,
    /// Mean pressure F_N/(Lx Ly) of the box.
    pub pressure: f64,
    pub pixel_size: f64,
    pub critical_diameter: f64,
    /// The ceramic of Kim et al. (the paper's Table 1) whose properties it carries, if any.
    pub kim: Option<&'static str>,
    pub pairs: Vec<Pair>,
}

impl Setting {
    /// The pairs that are run in.
    pub fn run_in_pairs(&self) -> Vec<&Pair> {
        self.pairs.iter().filter(|p| p.run_in()).collect()
    }

    /// The pairs the figures average: those run in, or every pair of a setting where none is (the
    /// fallback of the study's means, [`crate::output::averaged_pairs`]).
    pub fn figure_pairs(&self) -> Vec<&Pair> {
        let run_in: Vec<bool> = self.pairs.iter().map(Pair::run_in).collect();
        crate::output::averaged_pairs(&run_in)
            .into_iter()
            .map(|i| &self.pairs[i])
            .collect()
    }

    /// The pair of a seed.
    pub fn pair(&self, seed: &str) -> Option<&Pair> {
        self.pairs.iter().find(|p| p.seed == seed)
    }

    /// d* in pixels.
    pub fn d_star_px(&self) -> f64 {
        self.critical_diameter / self.pixel_size
    }

    /// "τ̃ = 0.012, F_N/(Lx·Ly) = 0.001 (d* = 16 px)", marked where a pair lies in the paper's
    /// breakdown regime (appendix C): "(d* = 16 px; breakdown regime in 2 of 5 pairs)".
    pub fn label(&self) -> String {
        let breakdown = match self.breakdown_pairs().len() {
            0 => String::new(),
            k => format!("; breakdown regime in {k} of {} pairs", self.pairs.len()),
        };
        format!(
            "{}{}F_N/(Lx·Ly) = {} (d* = {:.0} px{breakdown})",
            self.material_prefix(),
            self.strength_and_energy(),
            param(self.pressure),
            self.d_star_px()
        )
    }

    /// The pairs whose load lies in the paper's breakdown regime (appendix C): a breakdown measure
    /// beyond its limit (`crate::sliding::LoadBreakdown`).
    pub fn breakdown_pairs(&self) -> Vec<&Pair> {
        self.pairs
            .iter()
            .filter(|p| p.get("breakdown_measures") > 0.0)
            .collect()
    }

    /// "τ̃ = 0.012, 𝒢 = 2.5e-7, " where they vary in the study.
    pub fn strength_and_energy(&self) -> String {
        let mut text = String::new();
        if self.varies[1] {
            text += &format!("τ̃ = {}, ", param(self.shear_strength));
        }
        if self.varies[2] {
            text += &format!("𝒢 = {}, ", param(self.fracture_energy));
        }
        text
    }

    fn material_prefix(&self) -> String {
        if self.varies[0] {
            material_prefix(&self.material)
        } else {
            String::new()
        }
    }

    /// "7 of 10 pairs run in": the per-pair measures are in the running-in diagnostic, once per
    /// contact history.
    pub fn run_in_note(&self) -> String {
        format!("{} of {} pairs run in", self.run_in_pairs().len(), self.pairs.len())
    }

    /// The running-in of this setting's contact history pair by pair: how many pairs each rule
    /// runs in, the lineages of s = 0 left at s_r and s_r/ℓ.
    pub fn run_in_table_row(&self) -> String {
        let by = |rule: RunInRule| self.pairs.iter().filter(|p| p.run_in_by(rule)).count();
        let left: Vec<String> = self
            .pairs
            .iter()
            .map(|p| format!("{:.0} %", 100.0 * p.lineages_left()).replace("NaN %", "—"))
            .collect();
        let r: Vec<String> = self.pairs.iter().map(|p| fmt(p.decay_lengths())).collect();
        format!(
            "{} of {} run in by the lineages left, {} by s_r ≥ {} ℓ; lineages of s = 0 left: {}; s_r/ℓ: {}",
            by(RunInRule::LineagesLeft),
            self.pairs.len(),
            by(RunInRule::DecayLengths),
            crate::sliding::RUN_IN_DECAY_LENGTHS,
            left.join(", "),
            r.join(", ")
        )
    }

    /// The label of the contact history (τ̃ and load: the memory does not depend on 𝒢).
    pub fn history_label(&self) -> String {
        format!(
            "{}{}F_N/(Lx·Ly) = {}",
            self.material_prefix(),
            if self.varies[1] {
                format!("τ̃ = {}, ", param(self.shear_strength))
            } else {
                String::new()
            },
            param(self.pressure)
        )
    }
}

fn material_prefix(material: &str) -> String {
    if material == "material" {
        String::new()
    } else {
        format!("{material} ")
    }
}

/// The settings of a tidy table, grouped by the library's grouping (`output::settings`).
pub(super) fn settings(tidy: &Table, rule: RunInRule) -> Vec<Setting> {
    let found = setting_groups(tidy);
    let col = |name: &str| tidy.column(name);
    // A family is every input but the material, τ̃, 𝒢 and what changes along a curve against load.
    let not_family: Vec<&str> = ["material", "material.shear_strength", "fracture_energy"]
        .into_iter()
        .chain(crate::output::ALONG_A_CURVE)
        .collect();
    let numeric: Vec<usize> = (0..tidy.columns.len())
        .filter(|&c| tidy.rows.iter().any(|r| matches!(r[c], Cell::Float(_) | Cell::Int(_))))
        .collect();
    let mut all: Vec<Setting> = found
        .groups
        .iter()
        .enumerate()
        .map(|(id, g)| {
            let first = &tidy.rows[g.rows[0]];
            let num = |name: &str| col(name).map_or(f64::NAN, |i| first[i].number());
            let family_cells: BTreeMap<String, String> = found
                .key_columns
                .iter()
                .filter(|&&c| !not_family.contains(&tidy.columns[c].as_str()))
                .map(|&c| (tidy.columns[c].clone(), first[c].text()))
                .collect();
            let family: Vec<String> = found
                .key_columns
                .iter()
                .filter(|&&c| !not_family.contains(&tidy.columns[c].as_str()))
                .map(|&c| first[c].text())
                .collect();
            let seed = col("surface.seed");
            let pairs = g
                .rows
                .iter()
                .map(|&r| {
                    let row = &tidy.rows[r];
                    Pair {
                        seed: seed.map_or(format!("row {r}"), |s| row[s].text()),
                        values: numeric
                            .iter()
                            .map(|&c| (tidy.columns[c].clone(), row[c].number()))
                            .collect(),
                        rule,
                    }
                })
                .collect();
            Setting {
                id,
                curve: g.curve,
                curve_particles: 0,
                varies: [false; 3],
                family: family.join("|"),
                family_cells,
                load: num("load"),
                length: num("surface.length"),
                running_in: num("sliding.running_in"),
                fit_distance: num("sliding.distance") * num("surface.length") - num("fit_window_start"),
                material: col("material").map_or("material".into(), |i| first[i].text()),
                shear_strength: num("material.shear_strength"),
                fracture_energy: num("fracture_energy"),
                pressure: num("nominal_pressure"),
                pixel_size: num("surface.length") / num("surface.grid"),
                critical_diameter: num("critical_diameter"),
                kim: kim_of_row(tidy, first).map(|k| k.name),
                pairs,
            }
        })
        .collect();
    mark_study_wide(&mut all);
    all
}

/// What a setting knows of the whole study: the particles of its curve over every load, and which of
/// the material, τ̃ and 𝒢 vary (the labels name only those).
fn mark_study_wide(all: &mut [Setting]) {
    let mut by_curve: BTreeMap<usize, u64> = BTreeMap::new();
    for s in all.iter() {
        *by_curve.entry(s.curve).or_default() += s.pairs.iter().map(Pair::particles).sum::<u64>();
    }
    let differ = |f: &dyn Fn(&Setting) -> String| all.iter().any(|s| f(s) != f(&all[0]));
    let varies = [
        differ(&|s| s.material.clone()),
        differ(&|s| format!("{:e}", s.shear_strength)),
        differ(&|s| format!("{:e}", s.fracture_energy)),
    ];
    for s in all.iter_mut() {
        s.curve_particles = by_curve[&s.curve];
        s.varies = varies;
    }
}

/// An input value as given (0.008), in exponent form when small or large (2.5e-7, 3.37e9 Pa),
/// rounded to six significant figures: a value derived from inputs (F_N/(Lx·Ly) of a measured map's
/// box, 2.0000016880560666e8 Pa) is given to the precision it has, 2e8.
pub(super) fn param(x: f64) -> String {
    let x: f64 = format!("{x:.5e}").parse().unwrap_or(x);
    if (1e-3..1e4).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// A result value with three significant figures (the legends' numbers).
pub(super) fn fmt(x: f64) -> String {
    if x.is_nan() {
        "—".into()
    } else if x.is_infinite() {
        if x > 0.0 { "∞" } else { "−∞" }.into()
    } else {
        crate::output::number(x)
    }
}

/// Curves against load: settings grouped by the library's curve (the aggregated table's `curve`
/// column), each sorted by load.
pub(super) fn curves(all: &[Setting]) -> Vec<Vec<&Setting>> {
    let mut groups: BTreeMap<usize, Vec<&Setting>> = BTreeMap::new();
    for s in all {
        groups.entry(s.curve).or_default().push(s);
    }
    groups
        .into_values()
        .map(|mut c| {
            c.sort_by(|a, b| a.pressure.total_cmp(&b.pressure));
            c
        })
        .collect()
}

/// Pairs of curves against load (two loads or more) of one family and material whose d* differs
/// through 𝒢 alone or τ̃ alone: (the curve of the larger d*, of the smaller, "via 𝒢" or "via τ̃").
pub(super) fn curves_differing_in_d_star<'c, 's>(
    curves: &'c [Vec<&'s Setting>],
) -> Vec<(&'c [&'s Setting], &'c [&'s Setting], &'static str)> {
    let long = || curves.iter().filter(|c| c.len() >= 2);
    let mut out = Vec::new();
    for a in long() {
        for b in long() {
            let (a0, b0) = (a[0], b[0]);
            if a0.family != b0.family || a0.material != b0.material {
                continue;
            }
            if a0.shear_strength == b0.shear_strength && a0.fracture_energy > b0.fracture_energy {
                out.push((a.as_slice(), b.as_slice(), "via 𝒢"));
            } else if a0.fracture_energy == b0.fracture_energy && a0.shear_strength < b0.shear_strength {
                out.push((a.as_slice(), b.as_slice(), "via τ̃"));
            }
        }
    }
    out
}

/// Pairs of curves against load (each of two loads or more) of one family, material and τ̃ that
/// differ in 𝒢: (the curve of the larger 𝒢, the tougher; the curve of the smaller).
pub(super) fn curves_differing_in_g<'c, 's>(
    curves: &'c [Vec<&'s Setting>],
) -> Vec<(&'c [&'s Setting], &'c [&'s Setting])> {
    curves_differing_in_d_star(curves)
        .into_iter()
        .filter(|(.., via)| *via == "via 𝒢")
        .map(|(a, b, _)| (a, b))
        .collect()
}

/// Whether two settings differ in the study axes `axes` (at least one of them) and in no other
/// input but the material's name (a study may name its boxes as materials), at equal τ̃ and 𝒢.
pub(super) fn differ_only_in(a: &Setting, b: &Setting, axes: &[&str]) -> bool {
    let differs = |k: &str| a.family_cells.get(k) != b.family_cells.get(k);
    a.shear_strength == b.shear_strength
        && a.fracture_energy == b.fracture_energy
        && axes.iter().any(|k| differs(k))
        && a.family_cells
            .keys()
            .chain(b.family_cells.keys())
            .all(|k| axes.contains(&k.as_str()) || k == "material" || !differs(k))
}

/// The study's distinct nominal pressures, sorted.
pub(super) fn pressures(all: &[Setting]) -> Vec<f64> {
    let mut p: Vec<f64> = all.iter().map(|s| s.pressure).collect();
    p.sort_by(f64::total_cmp);
    p.dedup();
    p
}

/// The highest load of a family at which a setting has at least two run-in pairs: "high loads" in
/// the paper's sentences read as the top of the loads the study can judge, never as whatever lies
/// above the median, nor as a top load where no pair is run in. NaN where no load has two.
pub(super) fn highest_run_in_load(all: &[Setting], family: &str) -> f64 {
    all.iter()
        .filter(|x| x.family == family && x.run_in_pairs().len() >= 2)
        .map(|x| x.pressure)
        .fold(f64::NAN, f64::max)
}

/// Whether a setting is at [`highest_run_in_load`] of its family, in a study of several loads.
pub(super) fn at_highest_load(all: &[Setting], s: &Setting) -> bool {
    pressures(all).len() > 1 && s.pressure == highest_run_in_load(all, &s.family)
}

/// Pairs of settings in the same family at the same load whose d* differs through one parameter:
/// (larger d*, smaller d*, "via 𝒢" or "via τ̃").
pub(super) fn d_star_pairs(all: &[Setting]) -> Vec<(&Setting, &Setting, &'static str)> {
    let mut out = Vec::new();
    for a in all {
        for b in all {
            if a.family != b.family || a.pressure != b.pressure {
                continue;
            }
            if a.shear_strength == b.shear_strength && a.fracture_energy > b.fracture_energy {
                out.push((a, b, "via 𝒢"));
            } else if a.fracture_energy == b.fracture_energy && a.shear_strength < b.shear_strength {
                out.push((a, b, "via τ̃"));
            }
        }
    }
    out
}

/// Settings that share one contact history: the memory of the initial contact does not depend on 𝒢,
/// so each job (family, material, τ̃, load) counts once.
pub(super) fn contact_histories(all: &[Setting]) -> Vec<&Setting> {
    let mut seen = std::collections::BTreeSet::new();
    all.iter()
        .filter(|s| {
            seen.insert(format!(
                "{}|{}|{:e}|{:e}",
                s.family, s.material, s.shear_strength, s.pressure
            ))
        })
        .collect()
}

/// The contact-history curves: one per family, material and τ̃ (whatever 𝒢), sorted by load.
pub(super) fn history_curves(all: &[Setting]) -> Vec<Vec<&Setting>> {
    let mut groups: BTreeMap<String, Vec<&Setting>> = BTreeMap::new();
    for s in contact_histories(all) {
        groups
            .entry(format!("{}|{}|{:e}", s.family, s.material, s.shear_strength))
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
