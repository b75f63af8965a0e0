//! Statistics shared by the fits of the model and the judgement of a study, in three files:
//!
//! - [`fit`]: least-squares lines, power laws in log–log, mean ± standard deviation;
//! - [`interval`]: 95 % confidence intervals over surface pairs (Student t on the pair values, exact
//!   Poisson for particle counts, paired log-ratios of two settings that share their pairs, the
//!   conditional test of two Poisson counts, a ratio of means by a bootstrap over pairs);
//! - [`judge`]: whether an interval lies on the paper's side of a threshold, and how many surface
//!   pairs would decide it, with 80 % power, at the observed effect and spread.

pub mod fit;
pub mod interval;
pub mod judge;

pub use fit::{line_fit, mean_std, poisson_linear_r2, power_law_fit, weighted_line_fit, LineFit, PowerLawFit};
pub use interval::{
    count_ratio, mean_interval, paired_ratio, poisson_interval, ratio_of_means, t_critical, unpaired_ratio, Interval,
    Method, BOOTSTRAP_RESAMPLES, LEVEL,
};
pub use judge::{
    pairs_needed, pairs_needed_for_counts, pairs_needed_for_disjoint_ratios, pairs_needed_unpaired, Region, Side,
    MAX_PAIRS, POWER,
};
