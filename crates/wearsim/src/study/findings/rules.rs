//! How the findings judge a unit (a setting, two settings, a curve) with the statistics of
//! `stats`: every rule reads an interval over surface pairs and asks on which side of its threshold
//! it lies; an undecided unit names the pairs that would decide it.

use crate::stats::{
    count_ratio, line_fit, mean_interval, paired_ratio, pairs_needed, pairs_needed_for_counts, Interval, Region, Side,
};

use super::setting::{fmt, Pair, Setting};
use super::{Numbers, Tally, Unit};

/// How one unit of a finding came out: judged by an interval (holds, contrary or undecided, then
/// with the surface pairs that would decide it at the observed effect and spread, when any number
/// would), or not run in (fewer than two of its surface pairs are run in). `numbers` are the
/// interval that decided it and the rule's region, when the unit has one; `data` names the
/// statistics it reads, so that a statistic another finding already counts is not counted again.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Outcome {
    /// `None`: not run in.
    pub side: Option<Side>,
    pub text: String,
    pub needed: Option<usize>,
    pub numbers: Option<Numbers>,
    pub data: Vec<String>,
}

impl Outcome {
    pub fn judged(side: Side, text: String, needed: Option<usize>, numbers: Option<Numbers>) -> Outcome {
        Outcome {
            side: Some(side),
            text,
            needed,
            numbers,
            data: Vec::new(),
        }
    }

    /// Fewer than two of its surface pairs are run in: `text` says which.
    pub fn not_run_in(text: String) -> Outcome {
        Outcome {
            side: None,
            text,
            needed: None,
            numbers: None,
            data: Vec::new(),
        }
    }

    pub fn side(&self) -> Option<Side> {
        self.side
    }

    pub fn text(&self) -> &str {
        &self.text
    }

    /// A unit that no interval decides (no spread, no shared load, no particle): `text` says why.
    pub fn undecided(text: String) -> Outcome {
        Outcome::judged(Side::Undecided, text, None, None)
    }

    /// A unit judged by the interval `i` of `quantity` against `region`.
    pub fn by_interval(i: Interval, quantity: &str, region: Region, text: String, needed: Option<usize>) -> Outcome {
        let side = region.side(&i);
        Outcome::judged(
            side,
            text,
            needed,
            Some(Numbers {
                quantity: quantity.to_string(),
                interval: i,
                region,
            }),
        )
    }

    /// The interval that decided the unit, when it has one.
    pub fn numbers(&self) -> Option<&Numbers> {
        self.numbers.as_ref()
    }

    /// The same outcome with its text rewritten (a note added).
    pub fn map_text(mut self, f: impl FnOnce(String) -> String) -> Outcome {
        self.text = f(self.text);
        self
    }

    /// The same outcome reading the statistic `key` as well.
    pub fn reads(mut self, key: String) -> Outcome {
        if !self.data.contains(&key) {
            self.data.push(key);
        }
        self
    }
}

/// The key of a statistic read on settings `a` and `b` together (their order does not matter):
/// "rates 3|7" for the particle rates or wear rates of two settings (W = ω d*³ dN*₊/ds, Eq. 5, so
/// their ratios are one statistic), "slopes W difference 1|2" for the difference of two curves'
/// exponents of W (the crossover's trend, and that of k), "k 4|4" for one setting's mean k.
pub(super) fn key_of(what: &str, a: usize, b: usize) -> String {
    format!("{what} {}|{}", a.min(b), a.max(b))
}

impl Tally {
    /// Files one unit under its outcome.
    pub(super) fn file(&mut self, outcome: Outcome) {
        self.units.push(Unit::of(&outcome));
    }
}

/// "= 0.089 [0.071, 0.107]": an estimate with its interval.
pub(super) fn show(i: &Interval) -> String {
    format!("{} [{}, {}]", fmt(i.estimate), fmt(i.low), fmt(i.high))
}

/// Judges the values of one unit's surface pairs (a mean over pairs, Student t) against `region`.
/// `what` names the quantity, `note` follows the numbers; `pairs` is the number of surface pairs of
/// the unit, of which those with a value (run in, with particles) are a part: the pairs that would
/// decide it are counted in pairs of the unit, in that proportion.
pub(super) fn judge_values(
    label: &str,
    what: &str,
    values: &[f64],
    region: Region,
    note: &str,
    pairs: usize,
) -> Outcome {
    // Every pair exactly 0 (no event in any of them): a sample without spread is no evidence either
    // way, whatever side of the threshold 0 lies on.
    let finite: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    if finite.len() >= 2 && finite.iter().all(|v| *v == 0.0) {
        return Outcome::undecided(format!(
            "{label}: {what} = 0 in each of {} pairs: no spread, no interval{note}",
            finite.len()
        ));
    }
    match mean_interval(values) {
        Some(i) => {
            let side = region.side(&i);
            let scale = pairs.max(i.n) as f64 / i.n as f64;
            let needed = (side == Side::Undecided)
                .then(|| pairs_needed(values, region))
                .flatten()
                .map(|n| (n as f64 * scale).ceil() as usize);
            let text = format!("{label}: {what} = {} ({} pairs{note})", show(&i), i.n);
            Outcome::by_interval(i, what, region, text, needed)
        }
        None => Outcome::undecided(format!(
            "{label}: {what} defined in {} pair{} only, no interval{note}",
            values.iter().filter(|v| v.is_finite()).count(),
            if values.len() == 1 { "" } else { "s" }
        )),
    }
}

/// A rule judged setting by setting on its run-in pairs: the mean of `value` over them with its
/// Student-t interval against `region`. A setting with fewer than two run-in pairs is not run in.
pub(super) fn per_setting(
    all: &[Setting],
    what: &str,
    region: Region,
    value: impl Fn(&Setting, &Pair) -> f64,
) -> Tally {
    let mut tally = Tally::default();
    for s in all {
        tally.file(on_run_in_pairs(s, what, region, &value));
    }
    tally
}

/// One setting judged on its run-in pairs ([`per_setting`]).
pub(super) fn on_run_in_pairs(
    s: &Setting,
    what: &str,
    region: Region,
    value: impl Fn(&Setting, &Pair) -> f64,
) -> Outcome {
    let run = s.run_in_pairs();
    if s.pairs.len() < 2 {
        // A study of one surface pair has no spread to measure: no interval, whatever the pair shows;
        // a pair that is not run in has no value to show either, and says so.
        let Some(p) = run.first() else {
            return Outcome::not_run_in(format!(
                "{}: one surface pair, not run in ({}): no value and no interval",
                s.label(),
                s.run_in_note()
            ))
            .reads(key_of(what, s.id, s.id));
        };
        let v = value(s, p);
        return Outcome::undecided(format!(
            "{}: {what} = {} (one surface pair: no interval)",
            s.label(),
            fmt(v)
        ))
        .reads(key_of(what, s.id, s.id));
    }
    if run.len() < 2 {
        return Outcome::not_run_in(format!("{}: {}", s.label(), s.run_in_note())).reads(key_of(what, s.id, s.id));
    }
    let values: Vec<f64> = run.iter().map(|p| value(s, p)).filter(|v| v.is_finite()).collect();
    let note = if run.len() < s.pairs.len() {
        format!(", {}", s.run_in_note())
    } else {
        String::new()
    };
    judge_values(&s.label(), what, &values, region, &note, s.pairs.len()).reads(key_of(what, s.id, s.id))
}

/// What two settings compare: a column of the tidy table, and whether it is a particle rate (W or
/// dN*₊/ds, for which pairs without particles fall back on the count test).
#[derive(Debug, Clone, Copy)]
pub(super) enum Compared {
    /// The sliding wear rate W: counts scaled by d*³ (Eq. 5) in the count test.
    WearRate,
    /// The particle rate dN*₊/ds: counts as they are.
    ParticleRate,
    /// Another column (and its name): pairs with a zero are compared by paired differences.
    Column(&'static str, &'static str),
    /// A quantity derived from a pair's columns (and its name), compared as a column.
    Derived(fn(&Pair) -> f64, &'static str),
}

impl Compared {
    fn value(self, p: &Pair) -> f64 {
        match self {
            Compared::WearRate => p.get("wear_rate"),
            Compared::ParticleRate => p.get("particle_rate"),
            Compared::Column(c, _) => p.get(c),
            Compared::Derived(f, _) => f(p),
        }
    }

    /// The statistic two settings compare: W and dN*₊/ds are one (W = ω d*³ dN*₊/ds, Eq. 5; the
    /// count test reads the same particles for both).
    fn statistic(self) -> &'static str {
        match self {
            Compared::WearRate | Compared::ParticleRate => "rates",
            Compared::Column(_, name) | Compared::Derived(_, name) => name,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Compared::WearRate => "W",
            Compared::ParticleRate => "dN*₊/ds",
            Compared::Column(_, name) | Compared::Derived(_, name) => name,
        }
    }
}

/// The seeds that `a` and `b` share, both run in (or all shared seeds when `run_in` is false).
fn shared<'s>(a: &'s Setting, b: &'s Setting, run_in: bool) -> Vec<(&'s Pair, &'s Pair)> {
    a.pairs
        .iter()
        .filter_map(|p| b.pair(&p.seed).map(|q| (p, q)))
        .filter(|(p, q)| !run_in || (p.run_in() && q.run_in()))
        .collect()
}

/// Two settings of one study compared pair by pair (they share their surface pairs): the ratio
/// a/b of `q` against `region` (a threshold of 1). The geometric mean of the per-pair ratios with
/// its Student-t interval on the log-ratios; where a pair has no particle (a ratio of 0 or ∞), the
/// count test of two Poisson rates on the particles summed over the shared pairs (for W scaled by
/// (d*_a/d*_b)³, Eq. 5); for other columns with a zero, paired differences a − b against 0.
/// Sliding quantities compare on the pairs run in in both settings.
pub(super) fn compare(a: &Setting, b: &Setting, what: &str, q: Compared, region: Region, run_in: bool) -> Outcome {
    compare_pairs(a, b, what, q, region, run_in).reads(key_of(q.statistic(), a.id, b.id))
}

/// [`compare`] without the key of the statistic it reads.
fn compare_pairs(a: &Setting, b: &Setting, what: &str, q: Compared, region: Region, run_in: bool) -> Outcome {
    let label = format!("{} vs {} ({what})", a.label(), b.label());
    let pairs = shared(a, b, run_in);
    // One shared pair (a study of one surface pair) has no spread to measure; the count test of
    // particle rates still applies to it.
    let one_pair = pairs.len() == 1 && shared(a, b, false).len() == 1;
    if pairs.is_empty() || pairs.len() < 2 && !one_pair {
        return Outcome::not_run_in(format!("{label}: {}; {}", a.run_in_note(), b.run_in_note()));
    }
    // Pairs where the quantity is undefined in either setting (a particle volume without particles)
    // are left out.
    let values: Vec<(f64, f64)> = pairs
        .iter()
        .map(|(p, r)| (q.value(p), q.value(r)))
        .filter(|(x, y)| x.is_finite() && y.is_finite())
        .collect();
    if let Some(i) = paired_ratio(&values) {
        let side = region.side(&i);
        let logs: Vec<f64> = values.iter().map(|(x, y)| (x / y).ln()).collect();
        let needed = (side == Side::Undecided)
            .then(|| pairs_needed(&logs, region.map(f64::ln)))
            .flatten();
        let text = format!("{label}: {} ratio = {} (paired, {} pairs)", q.name(), show(&i), i.n);
        return Outcome::by_interval(i, &format!("{} ratio", q.name()), region, text, needed);
    }
    match q {
        Compared::WearRate | Compared::ParticleRate => compare_counts(a, b, &label, q, region, &pairs),
        Compared::Column(..) | Compared::Derived(..) => {
            let diffs: Vec<f64> = values.iter().map(|(x, y)| x - y).collect();
            let zero = region.map(|_| 0.0);
            judge_values(
                &label,
                &format!("{} a − b", q.name()),
                &diffs,
                zero,
                ", paired differences",
                pairs.len(),
            )
        }
    }
}

/// [`compare`] of particle rates (or W) on settings with a pair without particles: the count test of
/// two Poisson rates on the particles summed over the shared `pairs`, W scaled by (d*_a/d*_b)³.
fn compare_counts(
    a: &Setting,
    b: &Setting,
    label: &str,
    q: Compared,
    region: Region,
    pairs: &[(&Pair, &Pair)],
) -> Outcome {
    let (na, nb): (u64, u64) = (
        pairs.iter().map(|(p, _)| p.particles()).sum(),
        pairs.iter().map(|(_, r)| r.particles()).sum(),
    );
    let scale = match q {
        Compared::WearRate => (a.critical_diameter / b.critical_diameter).powi(3),
        _ => 1.0,
    };
    let scaled = if scale == 1.0 {
        String::new()
    } else {
        format!(" × (d*_a/d*_b)³ = {}", fmt(scale))
    };
    if let Some(text) = below_onset(a, b, na, nb) {
        return Outcome::undecided(format!("{label}: {text}"));
    }
    match count_ratio(na, nb) {
        Some(i) => {
            let i = i.map(|x| x * scale);
            let side = region.side(&i);
            let needed = (side == Side::Undecided)
                .then(|| pairs_needed_for_counts(na, nb, pairs.len(), scale, region))
                .flatten();
            let text = format!(
                "{label}: {} ratio = {} (count test: {na} vs {nb} particles over {} shared pairs{scaled})",
                q.name(),
                show(&i),
                pairs.len()
            );
            Outcome::by_interval(i, &format!("{} ratio", q.name()), region, text, needed)
        }
        None => Outcome::undecided(format!(
            "{label}: no particle in either over {} shared pairs",
            pairs.len()
        )),
    }
}

/// Per surface pair, the exponent of a power law fitted in log–log to `value` against the nominal
/// pressure over the loads of `curve` (least squares; loads where the value is not positive, or
/// where the pair is not run in when `run_in`, are left out; a pair needs two loads). Returns the
/// exponents, one per pair that has one.
pub(super) fn pair_exponents(curve: &[&Setting], run_in: bool, value: impl Fn(&Setting, &Pair) -> f64) -> Vec<f64> {
    exponents_by_seed(curve, run_in, value)
        .into_iter()
        .map(|(_, m)| m)
        .collect()
}

/// [`pair_exponents`] with the seed of each pair.
pub(super) fn exponents_by_seed(
    curve: &[&Setting],
    run_in: bool,
    value: impl Fn(&Setting, &Pair) -> f64,
) -> Vec<(String, f64)> {
    let mut seeds: Vec<&str> = Vec::new();
    for s in curve {
        for p in &s.pairs {
            if !seeds.contains(&p.seed.as_str()) {
                seeds.push(&p.seed);
            }
        }
    }
    seeds
        .into_iter()
        .filter_map(|seed| {
            let (x, y): (Vec<f64>, Vec<f64>) = curve
                .iter()
                .filter_map(|s| s.pair(seed).map(|p| (s, p)))
                .filter(|(_, p)| !run_in || p.run_in())
                .map(|(s, p)| (s.pressure, value(s, p)))
                .filter(|(_, v)| *v > 0.0 && v.is_finite())
                .map(|(x, v)| (x.ln(), v.ln()))
                .unzip();
            line_fit(&x, &y).map(|f| (seed.to_string(), f.slope))
        })
        .collect()
}

/// The label of a curve: its first setting's label without the load.
pub(super) fn curve_label(curve: &[&Setting]) -> String {
    let s = curve[0];
    format!(
        "{}{}d* = {:.0} px, {} loads",
        if s.material == "material" || !s.varies[0] {
            String::new()
        } else {
            format!("{} ", s.material)
        },
        s.strength_and_energy(),
        s.d_star_px(),
        curve.len()
    )
}

/// One unit judged by several parts that must all hold: contrary when any part is, holding when
/// all do, not run in when a part is and none is contrary, else undecided (decided by the largest
/// number of pairs any undecided part needs, when every one names one).
pub(super) fn all_of(label: &str, parts: Vec<Outcome>) -> Outcome {
    let text = format!(
        "{label}: {}",
        parts.iter().map(Outcome::text).collect::<Vec<_>>().join("; ")
    );
    let sides: Vec<Option<Side>> = parts.iter().map(Outcome::side).collect();
    // The part that decides the unit: the first contrary one, else the holding part nearest to its
    // threshold, else the first undecided part with an interval.
    let decisive = |side: Side| {
        let mut on: Vec<&Numbers> = parts
            .iter()
            .filter(|p| p.side() == Some(side))
            .filter_map(Outcome::numbers)
            .collect();
        if side == Side::Holds {
            on.sort_by(|a, b| a.margin().total_cmp(&b.margin()));
        }
        on.first().map(|n| (*n).clone())
    };
    let data: Vec<String> = parts.iter().flat_map(|p| p.data.iter().cloned()).collect();
    let with_data = |mut o: Outcome| {
        for k in &data {
            o = o.reads(k.clone());
        }
        o
    };
    if sides.contains(&Some(Side::Contrary)) {
        return with_data(Outcome::judged(Side::Contrary, text, None, decisive(Side::Contrary)));
    }
    if sides.contains(&None) {
        return with_data(Outcome::not_run_in(text));
    }
    if sides.iter().all(|s| *s == Some(Side::Holds)) {
        return with_data(Outcome::judged(Side::Holds, text, None, decisive(Side::Holds)));
    }
    let needed: Option<Vec<usize>> = parts
        .iter()
        .filter(|p| p.side == Some(Side::Undecided))
        .map(|p| p.needed)
        .collect();
    with_data(Outcome::judged(
        Side::Undecided,
        text,
        needed.and_then(|n| n.into_iter().max()),
        decisive(Side::Undecided),
    ))
}

/// Why a count of 0 against n decides nothing: a setting that forms no particle at any load of the
/// study is below the onset of wear there, which says nothing of how many fine particles it would
/// emit once it wears. `None` where both form particles somewhere.
fn below_onset(a: &Setting, b: &Setting, na: u64, nb: u64) -> Option<String> {
    let none = |s: &Setting, n: u64| n == 0 && s.curve_particles == 0;
    let which: Vec<String> = [(a, na), (b, nb)]
        .into_iter()
        .filter(|(s, n)| none(s, *n))
        .map(|(s, _)| format!("d* = {:.0} px", s.d_star_px()))
        .collect();
    (!which.is_empty() && na + nb > 0).then(|| {
        format!(
            "{na} vs {nb} particles, and {} forms no particle at any load of the study: below the onset of wear, \
             no evidence either way",
            which.join(" and ")
        )
    })
}

/// Two settings on different surfaces (another box or grid: their pairs are independent): the
/// ratio a/b of `q`'s geometric means over each one's run-in pairs, Welch's interval on the logs;
/// where a pair has no particle, the count test on the particles summed over each one's run-in
/// pairs, rates per sliding distance of the fit windows (for W times (d*_a/d*_b)³, Eq. 5).
pub(super) fn compare_unpaired(a: &Setting, b: &Setting, what: &str, q: Compared, region: Region) -> Outcome {
    unpaired(a, b, what, q, region).reads(key_of(q.statistic(), a.id, b.id))
}

/// [`compare_unpaired`] without the key of the statistic it reads.
fn unpaired(a: &Setting, b: &Setting, what: &str, q: Compared, region: Region) -> Outcome {
    let label = format!("{} vs {} ({what})", a.label(), b.label());
    let (ra, rb) = (a.run_in_pairs(), b.run_in_pairs());
    if ra.len() < 2 || rb.len() < 2 {
        return Outcome::not_run_in(format!("{label}: {}; {}", a.run_in_note(), b.run_in_note()));
    }
    let values = |r: &[&Pair]| -> Vec<f64> { r.iter().map(|p| q.value(p)).filter(|v| v.is_finite()).collect() };
    let (va, vb) = (values(&ra), values(&rb));
    if let Some(i) = crate::stats::unpaired_ratio(&va, &vb) {
        let side = region.side(&i);
        let logs = |v: &[f64]| -> Vec<f64> { v.iter().map(|x| x.ln()).collect() };
        let needed = (side == Side::Undecided)
            .then(|| crate::stats::pairs_needed_unpaired(&logs(&va), &logs(&vb), region.map(f64::ln)))
            .flatten();
        let text = format!(
            "{label}: {} ratio = {} (Welch, {} and {} pairs)",
            q.name(),
            show(&i),
            va.len(),
            vb.len()
        );
        return Outcome::by_interval(i, &format!("{} ratio", q.name()), region, text, needed);
    }
    let (na, nb): (u64, u64) = (
        ra.iter().map(|p| p.particles()).sum(),
        rb.iter().map(|p| p.particles()).sum(),
    );
    // Rates per pair and per sliding distance of the fit window.
    let exposure = |s: &Setting, n: usize| {
        let d = if s.fit_distance > 0.0 { s.fit_distance } else { 1.0 };
        d * n as f64
    };
    let mut scale = exposure(b, rb.len()) / exposure(a, ra.len());
    if let Compared::WearRate = q {
        scale *= (a.critical_diameter / b.critical_diameter).powi(3);
    }
    if let Some(text) = below_onset(a, b, na, nb) {
        return Outcome::undecided(format!("{label}: {text}"));
    }
    match (q, count_ratio(na, nb)) {
        (Compared::WearRate | Compared::ParticleRate, Some(i)) => {
            let i = i.map(|x| x * scale);
            let text = format!(
                "{label}: {} ratio = {} (count test: {na} vs {nb} particles over {} and {} pairs, per pair and \
                 fit-window distance)",
                q.name(),
                show(&i),
                ra.len(),
                rb.len()
            );
            Outcome::by_interval(i, &format!("{} ratio", q.name()), region, text, None)
        }
        _ => Outcome::undecided(format!("{label}: {} not positive in every pair; no interval", q.name())),
    }
}
