//! The wear models a run can name (`[sliding] model`): a registry, [`WEAR_MODELS`], of what each
//! model is — its name in run files and tables, what it does, the command that runs it alone,
//! whether it takes sliding steps, whether its results are the paper's sliding model (the rows the
//! findings read), what a legend and the cost estimate say of it, and the `[sliding]` keys it never
//! reads. Everything that differs between models is asked of its entry here; only the model's own
//! computation (the sliding run of `sliding`, the static estimate of `estimate`) is reached by an
//! exhaustive match on [`WearModel`], so that a new model is a compile error at each place that
//! runs one.

use crate::error::{Error, Result};

/// Which model turns a run into wear results (`[sliding] model`), chosen once from the run file;
/// its entry of the registry is [`WearModel::kind`]. Serialized by name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum WearModel {
    /// The sliding model of §3: every offset of the schedule solved and its junctions followed.
    #[default]
    Sliding,
    /// The static estimate from a few contact solutions (`crate::estimate`).
    Estimate,
}

/// A wear model's entry of the registry.
#[derive(Debug, Clone, Copy)]
pub struct WearModelKind {
    pub model: WearModel,
    /// The name used in run files, tables (`sliding.model`) and Python.
    pub name: &'static str,
    /// What the model is, in a few words, for messages (`"{name}" ({description})`).
    pub description: &'static str,
    /// The `wearsim` command that runs this model on one run file, if one does (study jobs run
    /// every model).
    pub command: Option<&'static str>,
    /// Whether the model takes sliding steps: its runs have a series, checkpoints, particle counts
    /// and a cost in steps (`wearsim slide` runs it; the cost estimate sizes it; the series figures
    /// draw it).
    pub slides: bool,
    /// Whether the model's results are the paper's sliding model: the rows the paper's findings,
    /// the fits of appendix F and the estimate's calibration read ([`WearModel::in_findings`]).
    pub feeds_findings: bool,
    /// What a figure's legend says first of a curve of this model (none for the paper's model).
    pub curve_label: Option<&'static str>,
    /// What a study's cost estimate, which sizes sliding steps, says of a job of a model that
    /// takes none (none for a model that slides).
    pub cost_note: Option<&'static str>,
    /// The `[sliding]` keys ([`SLIDING_KEYS`]) whose value this model never reads: a study that
    /// lists several values of one varies only the jobs of the models that use it.
    pub ignores: &'static [&'static str],
}

/// Every wear model, in the order of [`WearModel`]'s variants; the first is the default.
pub const WEAR_MODELS: &[WearModelKind] = &[
    WearModelKind {
        model: WearModel::Sliding,
        name: "sliding",
        description: "the paper's sliding simulation",
        command: Some("slide"),
        slides: true,
        feeds_findings: true,
        curve_label: None,
        cost_note: None,
        ignores: &["estimate_samples", "estimate_constants"],
    },
    WearModelKind {
        model: WearModel::Estimate,
        name: "estimate",
        description: "the static estimate from a few contact solutions",
        command: Some("estimate"),
        slides: false,
        feeds_findings: false,
        curve_label: Some("static estimate"),
        cost_note: Some(
            "each takes up to 16 static contact solves per load (its static maps; 4 to 16 unless \
             `estimate_samples` fixes them), seconds at 1024², a minute or two at 4096²",
        ),
        // Static maps at the sample offsets, solved to the settled map; the particles come from
        // the calibration, not from a rule; only the fit window (distance, running-in) enters,
        // through the sliding distance of its interval.
        ignores: &["step_running_in", "step", "particle_rule", "stopping"],
    },
];

/// The keys of a run file's `[sliding]` table.
pub const SLIDING_KEYS: [&str; 11] = [
    "loads",
    "pressures",
    "distance",
    "running_in",
    "step_running_in",
    "step",
    "particle_rule",
    "stopping",
    "model",
    "estimate_samples",
    "estimate_constants",
];

impl WearModel {
    /// Every model, in the registry's order; the first is the default.
    pub const ALL: [WearModel; WEAR_MODELS.len()] = {
        let mut all = [WearModel::Sliding; WEAR_MODELS.len()];
        let mut i = 0;
        while i < all.len() {
            all[i] = WEAR_MODELS[i].model;
            i += 1;
        }
        all
    };

    /// Its entry of the registry.
    pub fn kind(self) -> &'static WearModelKind {
        let kind = &WEAR_MODELS[self as usize];
        debug_assert_eq!(kind.model, self, "WEAR_MODELS is in the order of the variants");
        kind
    }

    /// [`WearModelKind::name`].
    pub fn name(self) -> &'static str {
        self.kind().name
    }

    /// [`WearModelKind::description`].
    pub fn description(self) -> &'static str {
        self.kind().description
    }

    /// [`WearModelKind::slides`].
    pub fn slides(self) -> bool {
        self.kind().slides
    }

    /// [`WearModelKind::feeds_findings`]; every other model's rows are left out of the findings, a
    /// model not known here included.
    pub fn feeds_findings(self) -> bool {
        self.kind().feeds_findings
    }

    /// [`WearModelKind::command`].
    pub fn command(self) -> Option<&'static str> {
        self.kind().command
    }

    /// [`WearModelKind::curve_label`].
    pub fn curve_label(self) -> Option<&'static str> {
        self.kind().curve_label
    }

    /// [`WearModelKind::cost_note`].
    pub fn cost_note(self) -> Option<&'static str> {
        self.kind().cost_note
    }

    /// [`WearModelKind::ignores`].
    pub fn ignores(self) -> &'static [&'static str] {
        self.kind().ignores
    }

    /// Whether this model reads the `[sliding]` key `key`.
    pub fn uses(self, key: &str) -> bool {
        !self.ignores().contains(&key)
    }

    /// The model of a table's `sliding.model` cell: an empty cell is the default model (a job
    /// records its model only when it is not the default), a name not of the registry none.
    pub fn of_cell(text: &str) -> Option<WearModel> {
        if text.is_empty() {
            return Some(WearModel::default());
        }
        WEAR_MODELS.iter().find(|k| k.name == text).map(|k| k.model)
    }

    /// Whether a table row whose `sliding.model` cell reads `text` belongs in the paper's findings
    /// and the fits of appendix F: a model that [feeds them](WearModel::feeds_findings), chosen by
    /// what it is; a model name not known here is left out.
    pub fn in_findings(text: &str) -> bool {
        WearModel::of_cell(text).is_some_and(WearModel::feeds_findings)
    }
}

impl std::str::FromStr for WearModel {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        WEAR_MODELS
            .iter()
            .find(|k| k.name == s)
            .map(|k| k.model)
            .ok_or_else(|| {
                let choices: Vec<String> = WEAR_MODELS
                    .iter()
                    .map(|k| format!("\"{}\" ({})", k.name, k.description))
                    .collect();
                Error::param(
                    "model",
                    format!("{s:?} is not a wear model; use {}", choices.join(" or ")),
                )
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_registry_is_in_the_order_of_the_variants_and_names_each_model_once() {
        for (i, kind) in WEAR_MODELS.iter().enumerate() {
            assert_eq!(kind.model as usize, i, "{}", kind.name);
            assert_eq!(kind.model.kind().name, kind.name);
            // Serialized as its registry name.
            assert_eq!(
                serde_json::to_string(&kind.model).unwrap(),
                format!("\"{}\"", kind.name)
            );
            assert_eq!(kind.name.parse::<WearModel>().unwrap(), kind.model);
            assert!(kind.ignores.iter().all(|k| SLIDING_KEYS.contains(k)), "{}", kind.name);
            // A model that takes no step has something to say in place of the steps it would cost.
            assert_eq!(kind.slides, kind.cost_note.is_none(), "{}", kind.name);
        }
        let mut names: Vec<&str> = WEAR_MODELS.iter().map(|k| k.name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), WEAR_MODELS.len());
        assert_eq!(WearModel::default(), WEAR_MODELS[0].model);
        assert_eq!("estimate".parse::<WearModel>().unwrap(), WearModel::Estimate);
        let err = "sliding-fast".parse::<WearModel>().unwrap_err().to_string();
        assert!(err.contains("\"sliding\" (the paper's sliding simulation)"), "{err}");
    }

    #[test]
    fn a_table_row_is_in_the_findings_by_what_its_model_is() {
        // Every model is named back from its table cell; the default (an empty cell) is the paper's.
        for m in WearModel::ALL {
            assert_eq!(WearModel::of_cell(m.name()), Some(m));
            assert_eq!(m.name().parse::<WearModel>().unwrap(), m);
        }
        assert_eq!(WearModel::of_cell(""), Some(WearModel::default()));
        assert!(WearModel::in_findings("") && WearModel::in_findings("sliding"));
        assert!(!WearModel::in_findings("estimate"));
        // A model name not known here is not the paper's sliding model.
        assert_eq!(WearModel::of_cell("other"), None);
        assert!(!WearModel::in_findings("other"));
    }
}
