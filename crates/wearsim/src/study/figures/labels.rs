//! The words of the figures: the units of their axes and legends, and the legend texts every
//! figure against load shares.

use crate::config::Units;
use crate::output::{number, unit_of};

use super::model::Axis;

/// The legend entry of the ringed points of the figures against load.
pub const BREAKDOWN_LEGEND: &str = "ringed: in the breakdown regime of the paper's appendix C (junctions merging, the \
largest junction a quarter of the box, or N* behind linear growth) in at least one surface pair";

/// The legend title of the figures against load: what points and bars are.
pub const MEANS: &str = "mean over surface pairs; bars: 95 % confidence interval of the mean (Student t)";

/// The same on a figure with log axes, whose bars are the interval drawn in log space.
pub const MEANS_ON_LOG_AXES: &str = "mean over surface pairs; bars: 95 % confidence interval of the mean \
(Student t); on a log axis drawn in log space: mean ×/÷ e^(t·se/mean)";

/// The units of a study's axes and legends.
#[derive(Debug, Clone, Copy)]
pub(super) struct Shown {
    pub(super) system: Units,
}

impl Shown {
    pub(super) fn si(self) -> bool {
        self.system == Units::Si
    }
    pub(super) fn unit(self, quantity: &str) -> &'static str {
        unit_of(self.system, quantity)
    }
    /// A length for legends (µm in SI).
    pub(super) fn length(self, v: f64) -> String {
        if self.si() {
            format!("{} µm", number(v * 1e6))
        } else {
            format!("{} L", number(v))
        }
    }
    pub(super) fn stress(self, v: f64) -> String {
        if self.si() {
            format!("{} GPa", number(v / 1e9))
        } else {
            format!("{} E", number(v))
        }
    }
    /// The label of a rate `quantity` divided by the nominal area Lx·Ly: in reduced units the rate
    /// of a box L × L, the paper's; in SI a volume per sliding distance per area is a wear depth per
    /// sliding distance (m/m), a particle rate per area particles per metre slid per m².
    pub(super) fn per_area(self, quantity: &str, label: &str) -> String {
        let unit = match (self.si(), quantity) {
            (false, _) => "per unit nominal area, = a box L × L (the paper's)",
            (true, "particle_rate") => "per unit nominal area, particles per m slid per m², 1/m³",
            (true, _) => "per unit nominal area: wear depth per sliding distance, m/m",
        };
        format!("{label} / (Lx·Ly) ({unit})")
    }
    /// The paper's load axis.
    pub(super) fn load_axis(self) -> Axis {
        Axis {
            label: format!("nominal pressure p_N = F_N/(Lx·Ly) ({})", self.unit("nominal_pressure")),
            log: true,
            fallback: (1e-4, 1e-2),
        }
    }
    pub(super) fn distance_axis(self) -> Axis {
        Axis {
            label: format!("sliding distance s ({})", self.unit("length")),
            log: false,
            fallback: (0.0, 1.0),
        }
    }
}
