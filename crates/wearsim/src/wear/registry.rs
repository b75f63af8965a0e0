//! The particle rules a run file can name (`[sliding] particle_rule`), each with its parameters, and
//! a rule as a run chose it ([`ParticleRuleSpec`]: the rule and the values of its parameters).

use crate::error::{Error, Result};

use super::interacting::{InteractingRule, INTERACTING_PARAMETERS};
use super::overlap::OverlapRule;
use super::rule::{Allowed, ParameterValue, ParticleRule, RuleParameter, RuleParameters, RuleSetup};

/// A particle rule as a run file names it: its name (`[sliding] particle_rule`), what it does, the
/// parameters it takes from a `[sliding.particle_rule]` table, whether it needs the shear
/// compliance and the junction geometry at each step, and how a run makes it for one critical
/// diameter. Compared, printed and recorded by name.
#[derive(Clone, Copy)]
pub struct ParticleRuleKind {
    pub name: &'static str,
    /// One sentence for the documentation and error messages.
    pub description: &'static str,
    /// The parameters the rule takes, with their defaults.
    pub parameters: &'static [RuleParameter],
    /// The rule needs `LabelledStep::shear` (a run then makes the box's shear compliance once and
    /// the junctions' geometry at each step).
    pub needs_shear: bool,
    /// The rule for one critical diameter d*.
    pub make: fn(&RuleSetup) -> Box<dyn ParticleRule>,
    /// What the rule adds to a sliding run's peak memory, in arrays of Nx·Ny doubles (measured).
    pub memory_arrays: f64,
}

/// The paper's rule (§3), the default.
pub const OVERLAP: ParticleRuleKind = ParticleRuleKind {
    name: "overlap",
    description: "the paper's rule (§3): an active junction at least d* across forms one particle; a junction \
                  overlapping a formed or disabled junction of the previous step is disabled",
    parameters: &[],
    needs_shear: false,
    make: OverlapRule::boxed,
    memory_arrays: 0.0,
};

/// The rule of interacting micro-contacts (Pham-Ba & Molinari 2021): nearby junctions sheared
/// together detach one combined particle when the elastic energy they store pays for it.
pub const INTERACTING: ParticleRuleKind = ParticleRuleKind {
    name: "interacting",
    description: "the paper's rule, except that nearby active junctions whose elastic energy under shear, \
                  interaction included, pays for detaching one particle enclosing them (Pham-Ba & Molinari 2021) \
                  form that one combined particle",
    parameters: INTERACTING_PARAMETERS,
    needs_shear: true,
    make: InteractingRule::boxed,
    // The box's shear compliance (one array) and each step's geometry and FFT windows: a 4096²
    // run's peak rose by 199 MiB, 1.55 arrays.
    memory_arrays: 1.6,
};

/// The particle rules a run file can name; the first is the default.
pub const PARTICLE_RULES: &[ParticleRuleKind] = &[OVERLAP, INTERACTING];

/// The particle rule when none is given: the paper's.
pub const DEFAULT_PARTICLE_RULE: ParticleRuleKind = PARTICLE_RULES[0];

impl ParticleRuleKind {
    /// The rule a run file names; an error naming the field and the choices otherwise.
    pub fn named(name: &str) -> Result<Self> {
        PARTICLE_RULES.iter().find(|k| k.name == name).copied().ok_or_else(|| {
            let choices: Vec<String> = PARTICLE_RULES
                .iter()
                .map(|k| format!("\"{}\" ({})", k.name, k.description))
                .collect();
            Error::param(
                "particle_rule",
                format!("{name:?} is not a particle rule; use one of: {}", choices.join("; ")),
            )
        })
    }

    /// The rule with every parameter at its default.
    pub fn with_defaults(self) -> ParticleRuleSpec {
        ParticleRuleSpec {
            kind: self,
            parameters: RuleParameters(self.parameters.iter().map(|p| (p.name, p.default)).collect()),
        }
    }
}

impl Default for ParticleRuleKind {
    fn default() -> Self {
        DEFAULT_PARTICLE_RULE
    }
}

impl std::fmt::Debug for ParticleRuleKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name)
    }
}

impl PartialEq for ParticleRuleKind {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
    }
}

/// A particle rule as a run chose it: the rule and the value of each of its parameters (given or
/// defaulted). Written `name` for a rule without parameters and `name(key=value, …)` with every
/// parameter otherwise: the form the summary's inputs, the job file and a study's tables record,
/// and that a run file, a study axis and Python accept besides the `[sliding.particle_rule]` table.
#[derive(Debug, Clone, PartialEq)]
pub struct ParticleRuleSpec {
    pub kind: ParticleRuleKind,
    pub parameters: RuleParameters,
}

impl From<ParticleRuleKind> for ParticleRuleSpec {
    fn from(kind: ParticleRuleKind) -> Self {
        kind.with_defaults()
    }
}

impl Default for ParticleRuleSpec {
    fn default() -> Self {
        DEFAULT_PARTICLE_RULE.with_defaults()
    }
}

impl ParticleRuleSpec {
    /// The rule `name` with the parameters `given` (key, value as written), each checked; a
    /// parameter not given takes its default.
    pub fn new(name: &str, given: &[(String, toml::Value)]) -> Result<Self> {
        let kind = ParticleRuleKind::named(name)?;
        let mut spec = kind.with_defaults();
        for (key, value) in given {
            let field = format!("sliding.particle_rule.{key}");
            let Some(declared) = kind.parameters.iter().find(|p| p.name == key) else {
                let known: Vec<String> = kind
                    .parameters
                    .iter()
                    .map(|p| format!("`{}` ({})", p.name, p.description))
                    .collect();
                let known = if known.is_empty() {
                    "none".to_string()
                } else {
                    known.join("; ")
                };
                return Err(Error::param(
                    &field,
                    format!(
                        "the particle rule \"{}\" has no parameter `{key}`; its parameters: {known}",
                        kind.name
                    ),
                ));
            };
            let v = parameter_value(declared, value).map_err(|why| Error::param(&field, why))?;
            let slot = spec
                .parameters
                .0
                .iter_mut()
                .find(|(n, _)| *n == declared.name)
                .expect("declared");
            slot.1 = v;
        }
        Ok(spec)
    }

    /// A `[sliding.particle_rule]` table: `name` and the rule's parameters.
    pub fn from_table(table: &toml::Table) -> Result<Self> {
        let name = match table.get("name") {
            Some(toml::Value::String(s)) => s.as_str(),
            Some(other) => {
                return Err(Error::param(
                    "sliding.particle_rule.name",
                    format!("{other} is not a rule's name; write e.g. name = \"interacting\""),
                ))
            }
            None => {
                return Err(Error::param(
                    "sliding.particle_rule.name",
                    "the table names no rule; add e.g. name = \"interacting\"",
                ))
            }
        };
        let given: Vec<(String, toml::Value)> = table
            .iter()
            .filter(|(k, _)| *k != "name")
            .map(|(k, v)| (k.clone(), v.clone()))
            .collect();
        Self::new(name, &given)
    }

    /// The rule for critical diameter d* on pixels of side `pixel_size`.
    pub fn make(&self, critical_diameter: f64, pixel_size: f64) -> Box<dyn ParticleRule> {
        (self.kind.make)(&RuleSetup {
            critical_diameter,
            pixel_size,
            parameters: &self.parameters,
        })
    }
}

/// The value of `declared` written `value`, or why it is not one.
fn parameter_value(declared: &RuleParameter, value: &toml::Value) -> std::result::Result<ParameterValue, String> {
    match declared.allowed {
        Allowed::Range { min, max } => {
            let x = match value {
                toml::Value::Float(x) => *x,
                toml::Value::Integer(i) => *i as f64,
                other => return Err(format!("{other} is not a number; {}", declared.description)),
            };
            if !(x.is_finite() && (min..=max).contains(&x)) {
                return Err(format!("{x} is outside [{min}, {max}]; {}", declared.description));
            }
            Ok(ParameterValue::Number(x))
        }
        Allowed::Choices(choices) => {
            let s = match value {
                toml::Value::String(s) => s.as_str(),
                other => return Err(format!("{other} is not one of {choices:?}; {}", declared.description)),
            };
            choices
                .iter()
                .find(|c| **c == s)
                .map(|c| ParameterValue::Choice(c))
                .ok_or_else(|| format!("{s:?} is not one of {choices:?}; {}", declared.description))
        }
    }
}

impl std::fmt::Display for ParticleRuleSpec {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.kind.name)?;
        if self.parameters.0.is_empty() {
            return Ok(());
        }
        let values: Vec<String> = self.parameters.0.iter().map(|(n, v)| format!("{n}={v}")).collect();
        write!(f, "({})", values.join(", "))
    }
}

impl std::str::FromStr for ParticleRuleSpec {
    type Err = Error;
    /// `name` or `name(key=value, …)`, as [`ParticleRuleSpec`]'s `Display` writes it.
    fn from_str(s: &str) -> Result<Self> {
        let s = s.trim();
        let Some((name, rest)) = s.split_once('(') else {
            return Self::new(s, &[]);
        };
        let Some(inner) = rest.strip_suffix(')') else {
            return Err(Error::param(
                "particle_rule",
                format!("{s:?} opens a parenthesis it does not close; write e.g. \"interacting(reach=1)\""),
            ));
        };
        let mut given = Vec::new();
        for item in inner.split(',').map(str::trim).filter(|i| !i.is_empty()) {
            let Some((key, value)) = item.split_once('=') else {
                return Err(Error::param(
                    "particle_rule",
                    format!("{item:?} in {s:?} is no key=value; write e.g. \"interacting(reach=1)\""),
                ));
            };
            let value = value.trim();
            let v = value
                .parse::<f64>()
                .map(toml::Value::Float)
                .unwrap_or_else(|_| toml::Value::String(value.to_string()));
            given.push((key.trim().to_string(), v));
        }
        Self::new(name.trim(), &given)
    }
}

impl serde::Serialize for ParticleRuleSpec {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rule_is_written_and_read_back_with_its_parameters() {
        let spec: ParticleRuleSpec = "interacting".parse().unwrap();
        assert_eq!(spec.to_string(), "interacting(reach=1, particle=hull)");
        let back: ParticleRuleSpec = spec.to_string().parse().unwrap();
        assert_eq!(back, spec);
        let two: ParticleRuleSpec = "interacting(reach=2)".parse().unwrap();
        assert_eq!(two.parameters.number("reach"), 2.0);
        assert_eq!("overlap".parse::<ParticleRuleSpec>().unwrap().to_string(), "overlap");
    }

    #[test]
    fn a_wrong_parameter_is_named_with_the_fix() {
        let table: toml::Table = "name = \"interacting\"\nreach = -1\n".parse().unwrap();
        let e = ParticleRuleSpec::from_table(&table).unwrap_err().to_string();
        assert!(
            e.contains("sliding.particle_rule.reach") && e.contains("outside"),
            "{e}"
        );
        let table: toml::Table = "name = \"interacting\"\nreech = 1\n".parse().unwrap();
        let e = ParticleRuleSpec::from_table(&table).unwrap_err().to_string();
        assert!(e.contains("reech") && e.contains("`reach`"), "{e}");
        let table: toml::Table = "name = \"interacting\"\nparticle = \"sphere\"\n".parse().unwrap();
        let e = ParticleRuleSpec::from_table(&table).unwrap_err().to_string();
        assert!(e.contains("\"hull\""), "{e}");
        let e = ParticleRuleSpec::from_table(&toml::Table::new())
            .unwrap_err()
            .to_string();
        assert!(e.contains("sliding.particle_rule.name"), "{e}");
        let e = "overlap(reach=1)".parse::<ParticleRuleSpec>().unwrap_err().to_string();
        assert!(e.contains("has no parameter"), "{e}");
    }
}
