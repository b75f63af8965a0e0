//! The paper's qualitative findings (Brink, Frérot & Molinari 2021, §2–4 and appendix B), checked
//! on a study's tidy table under rules stated once: each finding names what it compares, the
//! threshold and the particles a setting needs, counts every setting (or pair of settings, or
//! curve) of the study as holding, contrary, unresolved or not run in, and takes its verdict from
//! those counts ([`Tally::verdict`]). `wearsim study plot` prints them and writes
//! `figures/findings.md`; the tests check the README's main job against them.

use std::collections::BTreeMap;

use crate::output::{aggregate, Cell, Table};
use crate::sliding::RUN_IN_DECAY_LENGTHS;

/// Whether a study reproduces a finding of the paper, from the counts of a [`Tally`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    /// Holds in every judged case, and at least half of all cases are judged.
    Reproduced,
    /// Holds in more judged cases than it is contrary in, and at least half of all cases are judged.
    Partly,
    /// Contrary in at least as many judged cases as it holds in, and at least half are judged.
    NotReproduced,
    /// Fewer than half of the cases are judged (unresolved or not run in): no verdict either way.
    Inconclusive,
    /// No case of the study speaks to the finding.
    NotTestable,
}

impl Verdict {
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Reproduced => "reproduced",
            Verdict::Partly => "partly reproduced",
            Verdict::NotReproduced => "not reproduced",
            Verdict::Inconclusive => "inconclusive",
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
    /// The rule: what is compared, the threshold, the particles a case needs.
    pub rule: String,
    /// What the study shows: the counts, then the cases with their numbers.
    pub observed: String,
    pub verdict: Verdict,
}

/// Particles formed in a setting's fit window, summed over its surface pairs, below which its wear
/// rate is not compared: with fewer, W rests on a handful of events (relative noise ≳ 1/√20).
pub const RESOLVED_PARTICLES: f64 = 20.0;

/// How each case of a finding came out: every case of the study lands in exactly one list, with
/// its label and numbers.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Tally {
    pub holds: Vec<String>,
    pub contrary: Vec<String>,
    /// Fewer than [`RESOLVED_PARTICLES`] particles (or nothing to compare).
    pub unresolved: Vec<String>,
    /// Fit window starting before [`RUN_IN_DECAY_LENGTHS`] decay lengths of the initial contact's memory.
    pub not_run_in: Vec<String>,
}

impl Tally {
    pub fn total(&self) -> usize {
        self.holds.len() + self.contrary.len() + self.unresolved.len() + self.not_run_in.len()
    }

    /// The verdict from the counts alone: judged cases are those that hold or are contrary; with
    /// fewer than half of all cases judged, the study is inconclusive whatever the judged ones say.
    pub fn verdict(&self) -> Verdict {
        let (holds, contrary) = (self.holds.len(), self.contrary.len());
        let judged = holds + contrary;
        if judged == 0 {
            Verdict::NotTestable
        } else if 2 * judged < self.total() {
            Verdict::Inconclusive
        } else if contrary == 0 {
            Verdict::Reproduced
        } else if holds > contrary {
            Verdict::Partly
        } else {
            Verdict::NotReproduced
        }
    }

    /// "holds in 7 of 12 settings: …; contrary in 2: …; unresolved in 3 (< 20 particles): …".
    pub fn summary(&self, unit: &str) -> String {
        let list = |v: &[String]| {
            if v.is_empty() {
                String::new()
            } else {
                format!(": {}", v.join("; "))
            }
        };
        let mut text = format!(
            "holds in {} of {} {unit}{}",
            self.holds.len(),
            self.total(),
            list(&self.holds)
        );
        text += &format!("; contrary in {}{}", self.contrary.len(), list(&self.contrary));
        text += &format!(
            "; unresolved in {} (< {RESOLVED_PARTICLES} particles){}",
            self.unresolved.len(),
            list(&self.unresolved)
        );
        text += &format!(
            "; not run in: {} (running-in < {RUN_IN_DECAY_LENGTHS} decay lengths){}",
            self.not_run_in.len(),
            list(&self.not_run_in)
        );
        text
    }
}

/// One setting of the study (every input but the surface pair), averaged over surface pairs.
#[derive(Debug, Clone)]
struct Setting {
    /// Its curve against load (the aggregated table's `curve`).
    curve: usize,
    /// Every input but the material's name, τ̃, 𝒢 and the load, as text: settings compare within a family.
    family: String,
    material: String,
    shear_strength: f64,
    fracture_energy: f64,
    /// Mean pressure F_N/(Lx Ly) of the box.
    pressure: f64,
    pixel_size: f64,
    values: BTreeMap<String, f64>,
}

impl Setting {
    fn get(&self, name: &str) -> f64 {
        self.values.get(name).copied().unwrap_or(f64::NAN)
    }

    /// Particles in the fit window, summed over the surface pairs.
    fn particles(&self) -> f64 {
        self.get("particles_in_fit_total")
    }

    fn resolved(&self) -> bool {
        self.particles() >= RESOLVED_PARTICLES
    }

    /// Run in: the fit window starts after [`RUN_IN_DECAY_LENGTHS`] decay lengths (mean over pairs).
    /// Tables without the column (older versions) are not checked.
    fn run_in(&self) -> bool {
        let r = self.get("running_in_decay_lengths_mean");
        r.is_nan() || r >= RUN_IN_DECAY_LENGTHS
    }

    /// d* in pixels.
    fn d_star_px(&self) -> f64 {
        self.get("critical_diameter_mean") / self.pixel_size
    }

    fn label(&self) -> String {
        let name = if self.material == "material" {
            String::new()
        } else {
            format!("{} ", self.material)
        };
        format!(
            "{name}τ̃ = {}, 𝒢 = {}, F_N/(Lx·Ly) = {} (d* = {:.0} px)",
            param(self.shear_strength),
            param(self.fracture_energy),
            param(self.pressure),
            self.d_star_px()
        )
    }

    /// The label with the particle count, for an unresolved case.
    fn with_particles(&self) -> String {
        format!("{}: {:.0} particles", self.label(), self.particles())
    }

    fn with_decay(&self) -> String {
        format!(
            "{}: running-in = {} decay lengths",
            self.label(),
            fmt(self.get("running_in_decay_lengths_mean"))
        )
    }

    /// Files the setting as unresolved or not run in when it is; true when it can be judged.
    fn judgeable(&self, tally: &mut Tally) -> bool {
        if !self.resolved() {
            tally.unresolved.push(self.with_particles());
            false
        } else if !self.run_in() {
            tally.not_run_in.push(self.with_decay());
            false
        } else {
            true
        }
    }
}

fn settings(tidy: &Table) -> Vec<Setting> {
    let agg = aggregate(tidy);
    let col = |name: &str| agg.column(name);
    let skip = [
        "material",
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
            let grid = num("surface.grid");
            let mut family = Vec::new();
            let mut values = BTreeMap::new();
            for (c, cell) in agg.columns.iter().zip(row) {
                if ["_mean", "_min", "_max", "_total"].iter().any(|s| c.ends_with(s)) {
                    values.insert(c.clone(), cell.number());
                } else if !skip.contains(&c.as_str()) {
                    family.push(match cell {
                        Cell::Empty => String::new(),
                        other => other.text(),
                    });
                }
            }
            Setting {
                curve: col("curve").map_or(0, |i| row[i].number() as usize),
                family: family.join("|"),
                material: col("material").map_or("material".into(), |i| row[i].text()),
                shear_strength: num("material.shear_strength"),
                fracture_energy: num("fracture_energy"),
                pressure: num("nominal_pressure"),
                pixel_size: length / grid,
                values,
            }
        })
        .collect()
}

/// An input value as given (0.008), in exponent form when small or large (2.5e-7, 3.37e9 Pa).
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

/// Curves against load: settings grouped by the library's curve (`output::curves`, the aggregated
/// table's `curve` column), in the order they first appear, each sorted by load.
fn curves(all: &[Setting]) -> Vec<Vec<&Setting>> {
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

/// The study's distinct nominal pressures, sorted.
fn pressures(all: &[Setting]) -> Vec<f64> {
    let mut p: Vec<f64> = all.iter().map(|s| s.pressure).collect();
    p.sort_by(f64::total_cmp);
    p.dedup();
    p
}

/// Whether a pressure is in the upper half of the study's pressures (the "high loads" of the paper's
/// statements): at or above the median of the distinct pressures.
fn high(all: &[Setting], pressure: f64) -> bool {
    let p = pressures(all);
    p.len() > 1 && pressure >= p[p.len() / 2]
}

/// Pairs of settings in the same family at the same load whose d* differs through one parameter:
/// (larger d*, smaller d*, "via 𝒢" or "via τ̃").
fn d_star_pairs(all: &[Setting]) -> Vec<(&Setting, &Setting, &'static str)> {
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

/// Tallies a rule judged setting by setting: each setting unresolved or not run in when it is,
/// else holding or contrary as `holds` says of its `value`, listed as "label: name = value".
fn per_setting(all: &[Setting], name: &str, value: impl Fn(&Setting) -> f64, holds: impl Fn(f64) -> bool) -> Tally {
    let mut tally = Tally::default();
    for s in all {
        if s.judgeable(&mut tally) {
            let v = value(s);
            let line = format!("{}: {name} = {}", s.label(), fmt(v));
            if holds(v) {
                tally.holds.push(line)
            } else {
                tally.contrary.push(line)
            }
        }
    }
    tally
}

/// Tallies a comparison of two settings: unresolved or not run in when either is, else holds or is
/// contrary as `holds` says, with the pair's numbers.
fn compare(tally: &mut Tally, a: &Setting, b: &Setting, what: &str, holds: bool, numbers: String) {
    let pair = format!("{} vs {} ({what}): {numbers}", a.label(), b.label());
    if !(a.resolved() && b.resolved()) {
        tally.unresolved.push(format!(
            "{pair}, particles {:.0} vs {:.0}",
            a.particles(),
            b.particles()
        ));
    } else if !(a.run_in() && b.run_in()) {
        tally.not_run_in.push(format!(
            "{pair}, running-in {} vs {} decay lengths",
            fmt(a.get("running_in_decay_lengths_mean")),
            fmt(b.get("running_in_decay_lengths_mean"))
        ));
    } else if holds {
        tally.holds.push(pair);
    } else {
        tally.contrary.push(pair);
    }
}

fn finding(key: &'static str, paper: &'static str, rule: String, unit: &str, tally: Tally) -> Finding {
    Finding {
        key,
        paper,
        rule,
        observed: tally.summary(unit),
        verdict: tally.verdict(),
    }
}

/// Static model (§2, Fig. 2): k_static < 1 and rising with load, per curve.
fn static_k_below_one_and_rising(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    for c in curves(all) {
        let k: Vec<f64> = c.iter().map(|s| s.get("static_wear_coefficient_mean_mean")).collect();
        let (first, last) = (k[0], k[k.len() - 1]);
        let line = format!("{} → {} ({})", fmt(first), fmt(last), c[0].label());
        if c.len() < 2 || !k.iter().any(|&x| x > 0.0) {
            tally
                .unresolved
                .push(format!("{line}: no junction of d* at any load, or one load"));
        } else if last > first && k.iter().all(|&x| x < 1.0) {
            tally.holds.push(line);
        } else {
            tally.contrary.push(line);
        }
    }
    finding(
        "static-k-below-one-and-rising",
        "static model (§2, Fig. 2): k_static grows with load, towards 1",
        "per curve (one material against load): k_static, averaged over every offset and pair, below 1 at every load \
         and higher at the highest load than at the lowest; unresolved when k_static = 0 at every load"
            .into(),
        "curves",
        tally,
    )
}

/// Static model (§2, Fig. 2b): the harder material wears more at equal 𝒢 and load.
fn static_wear_grows_with_hardness(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    for a in all {
        for b in all {
            if a.family == b.family
                && a.fracture_energy == b.fracture_energy
                && a.pressure == b.pressure
                && a.shear_strength > b.shear_strength
            {
                let (wa, wb) = (a.get("static_wear_rate_mean_mean"), b.get("static_wear_rate_mean_mean"));
                let line = format!("{} vs {}: W_static/ω {} vs {}", a.label(), b.label(), fmt(wa), fmt(wb));
                if wa == 0.0 && wb == 0.0 {
                    tally.unresolved.push(format!("{line} (no junction of d* in either)"));
                } else if wa > wb {
                    tally.holds.push(line);
                } else {
                    tally.contrary.push(line);
                }
            }
        }
    }
    finding(
        "static-wear-grows-with-hardness",
        "static model (§2, Fig. 2b): W_static grows with hardness, against Archard's law",
        "per pair of settings at equal 𝒢 and load differing in τ̃: the harder one's W_static (mean over offsets and \
         pairs) is larger; unresolved when both are 0"
            .into(),
        "pairs",
        tally,
    )
}

/// Sliding (§3, Fig. 3): V(s) linear after running-in, per setting.
fn volume_linear_after_running_in(all: &[Setting]) -> Finding {
    let tally = per_setting(all, "R²", |s| s.get("wear_rate_r2_mean"), |v| v >= 0.9);
    finding(
        "volume-linear-after-running-in",
        "sliding model (§3, Fig. 3): V(s) becomes linear after running-in",
        format!(
            "per setting: R² of the line fitted to V(s) over the fit window, mean over pairs, ≥ 0.9; judged with ≥ \
             {RESOLVED_PARTICLES} particles and run in"
        ),
        "settings",
        tally,
    )
}

/// Sliding (§4.1, Fig. 4): k below about 0.1, per setting.
fn sliding_k_below_0_1(all: &[Setting]) -> Finding {
    let tally = per_setting(all, "k", |s| s.get("wear_coefficient_mean"), |v| v < 0.12);
    finding(
        "sliding-k-below-0.1",
        "sliding model (§4.1, Fig. 4): k stays below around 0.1 in all cases",
        format!(
            "per setting: k (mean over pairs) < 0.12 (\"around 0.1\"); judged with ≥ {RESOLVED_PARTICLES} particles and \
             run in"
        ),
        "settings",
        tally,
    )
}

/// Sliding (§4.1, Fig. 4): k an order of magnitude below the static model's, per setting.
fn sliding_k_below_static(all: &[Setting]) -> Finding {
    let tally = per_setting(
        all,
        "k_static/k",
        |s| {
            let (ks, k) = (
                s.get("static_wear_coefficient_mean_mean"),
                s.get("wear_coefficient_mean"),
            );
            ks / k
        },
        |v| v >= 5.0,
    );
    finding(
        "sliding-k-below-static",
        "sliding model (§4.1, Fig. 4): wear rates and k an order of magnitude smaller than in the static model",
        format!(
            "per setting: k_static (mean over offsets and pairs) / k (mean over pairs) ≥ 5 (nearer 10 than 1); judged \
             with ≥ {RESOLVED_PARTICLES} particles and run in"
        ),
        "settings",
        tally,
    )
}

/// Sliding (§4.1, Fig. 4a–b): at high loads, the larger d* wears more.
fn larger_d_star_wears_more_at_high_load(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    for (a, b, what) in d_star_pairs(all).into_iter().filter(|(a, ..)| high(all, a.pressure)) {
        let (wa, wb) = (a.get("wear_rate_mean"), b.get("wear_rate_mean"));
        compare(&mut tally, a, b, what, wa > wb, format!("W {} vs {}", fmt(wa), fmt(wb)));
    }
    finding(
        "larger-d-star-wears-more-at-high-load",
        "sliding model (§4.1, Fig. 4a–b): at high loads, materials with larger d* wear more",
        format!(
            "per pair of settings at one load in the upper half of the study's loads, differing in 𝒢 or in τ̃ alone: \
             the larger d* has the larger W (mean over pairs); judged when both have ≥ {RESOLVED_PARTICLES} particles \
             and are run in"
        ),
        "pairs",
        tally,
    )
}

/// Sliding (§4.1, Fig. 4a): at low loads, the smaller 𝒢 wears more.
fn smaller_g_wears_more_at_low_load(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    let pairs = d_star_pairs(all)
        .into_iter()
        .filter(|(a, _, what)| *what == "via 𝒢" && !high(all, a.pressure));
    for (a, b, what) in pairs {
        let (wa, wb) = (a.get("wear_rate_mean"), b.get("wear_rate_mean"));
        compare(&mut tally, a, b, what, wb > wa, format!("W {} vs {}", fmt(wa), fmt(wb)));
    }
    finding(
        "smaller-g-wears-more-at-low-load",
        "sliding model (§4.1, Fig. 4a): at low loads, the systems with smaller 𝒢 wear more",
        format!(
            "per pair of settings at one load in the lower half of the study's loads, differing in 𝒢 alone: the smaller \
             𝒢 has the larger W; judged when both have ≥ {RESOLVED_PARTICLES} particles and are run in"
        ),
        "pairs",
        tally,
    )
}

/// Sliding (§4.1, Fig. S.1a): the onset of wear is delayed to higher loads for larger 𝒢.
fn delayed_onset_for_large_g(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    let curves = curves(all);
    // The lowest load at which a curve forms any particle in its fit window.
    let onset = |c: &[&Setting]| c.iter().find(|s| s.particles() > 0.0).map(|s| s.pressure);
    for a in &curves {
        for b in &curves {
            let (a0, b0) = (a[0], b[0]);
            if a0.family != b0.family
                || a0.shear_strength != b0.shear_strength
                || a0.fracture_energy <= b0.fracture_energy
            {
                continue;
            }
            let (oa, ob) = (onset(a), onset(b));
            let show = |o: Option<f64>| o.map_or("none".into(), param);
            let line = format!(
                "𝒢 = {} vs {} at τ̃ = {}: first wear at F_N/(Lx·Ly) = {} vs {}",
                param(a0.fracture_energy),
                param(b0.fracture_energy),
                param(a0.shear_strength),
                show(oa),
                show(ob)
            );
            let lowest = b0.pressure;
            match (oa, ob) {
                (_, None) => tally.unresolved.push(format!("{line} (neither wears)")),
                (Some(x), Some(y)) if x == lowest && y == lowest => {
                    tally.unresolved.push(format!("{line} (both wear at the lowest load)"))
                }
                (None, Some(_)) => tally.holds.push(line),
                (Some(x), Some(y)) if x > y => tally.holds.push(line),
                _ => tally.contrary.push(line),
            }
        }
    }
    finding(
        "delayed-onset-for-large-g",
        "sliding model (§4.1, Fig. S.1a): for large 𝒢 the onset of wear is delayed to higher loads",
        "per pair of curves at equal τ̃ differing in 𝒢: the larger 𝒢 forms its first particle at a higher load (or at \
         none); unresolved when neither wears or both wear at the lowest load"
            .into(),
        "pairs of curves",
        tally,
    )
}

/// Sliding (§4.1, Fig. 5): at each load, the hardest and least tough material emits the most particles.
fn hardest_least_tough_emits_most_particles(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    for p in pressures(all) {
        let at: Vec<&Setting> = all.iter().filter(|s| s.pressure == p).collect();
        let hardest = at.iter().map(|s| s.shear_strength).fold(0.0f64, f64::max);
        let least_tough = at.iter().map(|s| s.fracture_energy).fold(f64::INFINITY, f64::min);
        let Some(best) = at
            .iter()
            .max_by(|a, b| a.get("particle_rate_mean").total_cmp(&b.get("particle_rate_mean")))
        else {
            continue;
        };
        if at.len() < 2 {
            continue;
        }
        let line = format!(
            "most particles: {} with dN*₊/ds = {}",
            best.label(),
            fmt(best.get("particle_rate_mean"))
        );
        if best.judgeable(&mut tally) {
            if best.shear_strength == hardest && best.fracture_energy == least_tough {
                tally.holds.push(line);
            } else {
                tally.contrary.push(line);
            }
        }
    }
    finding(
        "hardest-least-tough-emits-most-particles",
        "sliding model (§4.1, Fig. 5): the hardest and least tough material emits the most (smallest) particles",
        format!(
            "per load with two settings or more: the setting with the largest dN*₊/ds (mean over pairs) has the largest \
             τ̃ and the smallest 𝒢 of that load; judged when it has ≥ {RESOLVED_PARTICLES} particles and is run in"
        ),
        "loads",
        tally,
    )
}

/// Appendix B (Fig. B.9b): Eq. 5 slightly underestimates W, per setting.
fn equation_5_slightly_below_w(all: &[Setting]) -> Finding {
    let tally = per_setting(
        all,
        "Eq. 5 / W",
        |s| s.get("wear_rate_estimate_mean") / s.get("wear_rate_mean"),
        |v| (0.6..=1.0).contains(&v),
    );
    finding(
        "equation-5-slightly-below-w",
        "appendix B (Fig. B.9b): ω d*³ dN*₊/ds (Eq. 5) slightly underestimates the summed W",
        format!(
            "per setting: Eq. 5 / W (means over pairs) in [0.6, 1]; judged with ≥ {RESOLVED_PARTICLES} particles and run in"
        ),
        "settings",
        tally,
    )
}

/// §5: d* is a typical particle size, per setting: the particles' cube-mean diameter, the mean
/// particle volume W/(dN*₊/ds) as a sphere of ω = π/6, within 1.0–1.2 d*.
fn particle_size_near_critical_diameter(all: &[Setting]) -> Finding {
    let tally = per_setting(
        all,
        "d̄/d*",
        |s| {
            let volume = s.get("wear_rate_mean") / s.get("particle_rate_mean");
            (volume / (std::f64::consts::PI / 6.0)).cbrt() / s.get("critical_diameter_mean")
        },
        |v| (1.0..=1.2).contains(&v),
    );
    finding(
        "particle-size-near-critical-diameter",
        "§5: d* is a typical particle size, not only a minimum",
        format!(
            "per setting: the particles' cube-mean diameter d̄ = (W / (ω dN*₊/ds))^(1/3), ω = π/6 (means over \
             pairs), in [1.0, 1.2] d*; judged with ≥ {RESOLVED_PARTICLES} particles and run in"
        ),
        "settings",
        tally,
    )
}

/// Sliding (§3, Fig. 3): V₀ much larger than the later increments, per setting.
fn initial_volume_much_larger_than_increments(all: &[Setting]) -> Finding {
    let tally = per_setting(
        all,
        "V₀/(W·Δx)",
        |s| s.get("initial_volume_mean") / (s.get("wear_rate_mean") * s.pixel_size),
        |v| v >= 5.0,
    );
    finding(
        "initial-volume-much-larger-than-increments",
        "sliding model (§3, Fig. 3): V₀ is much larger than the later increments δV",
        format!(
            "per setting: V₀ over the mean increment of a one-pixel step, V₀/(W·Δx), ≥ 5; judged with ≥ \
             {RESOLVED_PARTICLES} particles and run in"
        ),
        "settings",
        tally,
    )
}

/// Settings that share one contact history: the memory of the initial contact does not depend on 𝒢,
/// so each job (family, material, τ̃, load) counts once.
fn contact_histories(all: &[Setting]) -> Vec<&Setting> {
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

fn history_label(s: &Setting) -> String {
    let name = if s.material == "material" {
        String::new()
    } else {
        format!("{} ", s.material)
    };
    format!(
        "{name}τ̃ = {}, F_N/(Lx·Ly) = {}",
        param(s.shear_strength),
        param(s.pressure)
    )
}

/// Sliding (§3): the number of contacts present at s = 0 decays exponentially, per contact history.
fn memory_decays_exponentially(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    for s in contact_histories(all) {
        let (r2, l) = (s.get("memory_decay_r2_mean"), s.get("memory_decay_length_mean"));
        let line = format!("{}: R² = {}, ℓ = {}", history_label(s), fmt(r2), fmt(l));
        if !r2.is_finite() {
            tally.unresolved.push(format!("{line} (no decay fitted)"));
        } else if r2 >= 0.8 {
            tally.holds.push(line);
        } else {
            tally.contrary.push(line);
        }
    }
    finding(
        "memory-decays-exponentially",
        "sliding model (§3): the number of contacts present at s = 0 decays exponentially with s",
        "per contact history (one τ̃ and load: the memory does not depend on 𝒢): R² of the line fitted to ln N₀(s), \
         mean over pairs, ≥ 0.8; unresolved when no decay was fitted"
            .into(),
        "contact histories",
        tally,
    )
}

/// Sliding (§3): the running-in is long enough, per contact history.
fn running_in_sufficient(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    for s in contact_histories(all) {
        let r = s.get("running_in_decay_lengths_mean");
        let line = format!(
            "{}: running-in = {} decay lengths ℓ = {}",
            history_label(s),
            fmt(r),
            fmt(s.get("memory_decay_length_mean"))
        );
        if r.is_nan() {
            tally.unresolved.push(format!("{line} (not measured)"));
        } else if r >= RUN_IN_DECAY_LENGTHS {
            tally.holds.push(line);
        } else {
            tally.contrary.push(line);
        }
    }
    finding(
        "running-in-sufficient",
        "sliding model (§3): a running-in of L/4 is a safety margin after which the system is run in; the decay of \
         the initial contact's memory is not predictable",
        format!(
            "per contact history (one τ̃ and load): the fit window starts after ≥ {RUN_IN_DECAY_LENGTHS} decay lengths \
             of the memory (mean over pairs), so ≤ 5 % of the initial lineages remain"
        ),
        "contact histories",
        tally,
    )
}

/// The paper's findings checked on a study's tidy table (`results.csv`), each under its rule.
pub fn findings(tidy: &Table) -> Vec<Finding> {
    let all = settings(tidy);
    vec![
        static_k_below_one_and_rising(&all),
        static_wear_grows_with_hardness(&all),
        volume_linear_after_running_in(&all),
        sliding_k_below_0_1(&all),
        sliding_k_below_static(&all),
        larger_d_star_wears_more_at_high_load(&all),
        smaller_g_wears_more_at_low_load(&all),
        delayed_onset_for_large_g(&all),
        hardest_least_tough_emits_most_particles(&all),
        equation_5_slightly_below_w(&all),
        particle_size_near_critical_diameter(&all),
        initial_volume_much_larger_than_increments(&all),
        memory_decays_exponentially(&all),
        running_in_sufficient(&all),
    ]
}

/// The findings as Markdown: how the cases are counted, then one table row per finding with its rule.
pub fn markdown(findings: &[Finding]) -> String {
    let mut text = format!(
        "Every setting (one material, τ̃, 𝒢 and load, averaged over its surface pairs), pair of settings or \
         curve of the study is counted under each finding's rule: it holds, is contrary, is unresolved (fewer \
         than {RESOLVED_PARTICLES} particles in its fit window, summed over its pairs) or is not run in (fit \
         window starting before {RUN_IN_DECAY_LENGTHS} decay lengths of the initial contact's memory). The \
         verdict follows from the counts: reproduced when it holds in every judged case, partly when it holds in \
         more than it is contrary in, not reproduced otherwise, inconclusive when fewer than half of the cases are \
         judged, not testable when none is.\n\n\
         | finding (paper) | rule | this study | verdict |\n|---|---|---|---|\n"
    );
    for f in findings {
        text += &format!(
            "| {} | {} | {} | {} |\n",
            f.paper,
            f.rule.replace('|', "/"),
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
        table_on(flip, None)
    }

    /// [`table`] on a box of 1 × `length_y` (square without).
    fn table_on(flip: bool, length_y: Option<f64>) -> Table {
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
            let inputs = InputRecord {
                seed: Some(seed),
                shear_strength: tau,
                grid: Some(64),
                length: 1.0,
                length_y,
                ..InputRecord::default()
            };
            rows.push(TidyRow {
                job,
                material: "m".into(),
                nominal_pressure: inputs.nominal_pressure(load),
                inputs,
                load,
                result: WearResult {
                    fracture_energy: 0.5e-6,
                    critical_diameter: if hard { 0.004 } else { 0.009 },
                    wear_rate: Some(if hard { 1e-5 } else { 2e-5 } * if high { 2.0 } else { 1.0 }),
                    wear_rate_r2: Some(0.95),
                    wear_volume_intercept: Some(1e-4),
                    fit_window_start: 0.25,
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
                    memory_fit_initial_junctions: Some(40.0),
                    running_in_decay_lengths: Some(8.0),
                    critical_residence: Some(0.01),
                    box_wrapping_steps: 0,
                },
                flow_pressure: 3.0 * 3f64.sqrt() * tau,
                warnings: String::new(),
                ..TidyRow::default()
            });
        }
        Table::of(&rows)
    }

    fn verdict_of(f: &[Finding], key: &str) -> Verdict {
        f.iter().find(|x| x.key == key).unwrap().verdict
    }

    #[test]
    fn findings_on_a_hand_made_study() {
        let f = findings(&table(false));
        assert_eq!(verdict_of(&f, "static-k-below-one-and-rising"), Verdict::Reproduced);
        assert_eq!(verdict_of(&f, "static-wear-grows-with-hardness"), Verdict::Reproduced);
        assert_eq!(verdict_of(&f, "volume-linear-after-running-in"), Verdict::Reproduced);
        assert_eq!(
            verdict_of(&f, "larger-d-star-wears-more-at-high-load"),
            Verdict::Reproduced
        );
        assert_eq!(
            verdict_of(&f, "hardest-least-tough-emits-most-particles"),
            Verdict::Reproduced
        );
        assert_eq!(verdict_of(&f, "equation-5-slightly-below-w"), Verdict::Reproduced);
        assert_eq!(verdict_of(&f, "running-in-sufficient"), Verdict::Reproduced);
        // Mean particle volume W/(dN*₊/ds) as a sphere, over d*: (2e-5/500/(π/6))^(1/3)/0.004 = 1.061
        // holds, (1e-5/500/(π/6))^(1/3)/0.004 = 0.842 is contrary; two of each.
        let size = f
            .iter()
            .find(|x| x.key == "particle-size-near-critical-diameter")
            .unwrap();
        assert_eq!(size.verdict, Verdict::NotReproduced, "{}", size.observed);
        for ratio in ["1.061", "0.842", "1.016", "0.806"] {
            assert!(size.observed.contains(&format!("d̄/d* = {ratio}")), "{}", size.observed);
        }
        assert!(
            size.observed.starts_with("holds in 2 of 4 settings"),
            "{}",
            size.observed
        );
        // Four settings of 40 particles each (20 per pair, two pairs): every one counted.
        let linear = f.iter().find(|x| x.key == "volume-linear-after-running-in").unwrap();
        assert!(
            linear.observed.starts_with("holds in 4 of 4 settings"),
            "{}",
            linear.observed
        );
        // The memory counts each contact history once (two τ̃ × two loads), whatever 𝒢.
        let memory = f.iter().find(|x| x.key == "memory-decays-exponentially").unwrap();
        assert!(
            memory.observed.starts_with("holds in 4 of 4 contact histories"),
            "{}",
            memory.observed
        );
        // The hard material's static wear rate cut tenfold: the finding fails.
        let flipped = findings(&table(true));
        assert_eq!(
            verdict_of(&flipped, "static-wear-grows-with-hardness"),
            Verdict::NotReproduced
        );
        assert!(markdown(&f).lines().filter(|l| l.starts_with("| ")).count() == f.len() + 1);
    }

    /// Sets one column of the rows of one shear strength and load.
    fn set(tidy: &mut Table, tau: f64, load: f64, column: &str, value: Cell) {
        let c = |name: &str| tidy.columns.iter().position(|c| c == name).unwrap();
        let (ct, cl, cv) = (c("material.shear_strength"), c("load"), c(column));
        for r in tidy.rows.iter_mut() {
            if r[ct].number() == tau && r[cl].number() == load {
                r[cv] = value.clone();
            }
        }
    }

    #[test]
    fn every_setting_is_counted_holding_contrary_unresolved_or_not_run_in() {
        let mut tidy = table(false);
        // τ̃ = 0.008 at the low load: 4 particles per pair, 8 in all (unresolved); τ̃ = 0.012 at the
        // high load: V(s) far from a line (contrary); τ̃ = 0.008 at the high load: running-in of one
        // decay length (not run in).
        set(&mut tidy, 0.008, 1e-3, "particles_in_fit", Cell::Int(4));
        set(&mut tidy, 0.012, 2e-3, "wear_rate_r2", Cell::Float(0.5));
        set(&mut tidy, 0.008, 2e-3, "running_in_decay_lengths", Cell::Float(1.0));
        let f = findings(&tidy);
        let linear = f.iter().find(|x| x.key == "volume-linear-after-running-in").unwrap();
        assert!(
            linear.observed.starts_with("holds in 1 of 4 settings"),
            "{}",
            linear.observed
        );
        assert!(linear
            .observed
            .contains("contrary in 1: m τ̃ = 0.012, 𝒢 = 5e-7, F_N/(Lx·Ly) = 0.002"));
        assert!(linear.observed.contains("R² = 0.500"));
        assert!(linear
            .observed
            .contains("unresolved in 1 (< 20 particles): m τ̃ = 0.008"));
        assert!(linear.observed.contains(": 8 particles"));
        assert!(linear.observed.contains("not run in: 1"));
        // Half judged, one holding and one contrary: not reproduced.
        assert_eq!(linear.verdict, Verdict::NotReproduced);
        // The running-in finding counts the short one as contrary.
        let run_in = f.iter().find(|x| x.key == "running-in-sufficient").unwrap();
        assert!(run_in.observed.starts_with("holds in 3 of 4"), "{}", run_in.observed);
        assert_eq!(run_in.verdict, Verdict::Partly);
        // Both hard settings unresolved too: fewer than half judged, inconclusive whatever they show.
        set(&mut tidy, 0.012, 1e-3, "particles_in_fit", Cell::Int(1));
        set(&mut tidy, 0.012, 2e-3, "particles_in_fit", Cell::Int(1));
        assert_eq!(
            verdict_of(&findings(&tidy), "volume-linear-after-running-in"),
            Verdict::NotTestable
        );
        set(&mut tidy, 0.008, 2e-3, "running_in_decay_lengths", Cell::Float(4.0));
        assert_eq!(
            verdict_of(&findings(&tidy), "volume-linear-after-running-in"),
            Verdict::Inconclusive
        );
    }

    #[test]
    fn the_verdict_follows_from_the_counts() {
        let tally = |h: usize, c: usize, u: usize, n: usize| Tally {
            holds: vec![String::new(); h],
            contrary: vec![String::new(); c],
            unresolved: vec![String::new(); u],
            not_run_in: vec![String::new(); n],
        };
        assert_eq!(tally(0, 0, 3, 1).verdict(), Verdict::NotTestable);
        assert_eq!(tally(1, 0, 2, 1).verdict(), Verdict::Inconclusive);
        assert_eq!(tally(2, 0, 1, 1).verdict(), Verdict::Reproduced);
        assert_eq!(tally(7, 2, 3, 0).verdict(), Verdict::Partly);
        assert_eq!(tally(2, 2, 0, 0).verdict(), Verdict::NotReproduced);
        let text = tally(7, 2, 3, 0).summary("settings");
        assert!(text.starts_with("holds in 7 of 12 settings"), "{text}");
        assert!(text.contains("contrary in 2"));
        assert!(text.contains("unresolved in 3 (< 20 particles)"));
    }

    #[test]
    fn the_pressure_of_a_setting_is_the_load_over_the_box_area() {
        let square = settings(&table(false));
        assert!(square.iter().all(|s| s.pressure == 1e-3 || s.pressure == 2e-3));
        // The same rows on a box of 1 × 0.5: twice the pressure.
        let oblong = settings(&table_on(false, Some(0.5)));
        assert!(oblong.iter().all(|s| s.pressure == 2e-3 || s.pressure == 4e-3));
    }
}
