//! Preparing a measured height map for a periodic contact solution: levelling (plane, quadratic),
//! taper to the mean at the borders, and the periodicity left afterwards.

use crate::error::{Error, Result};

/// How a measured height map is levelled before use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Detrend {
    /// Heights as read.
    #[default]
    None,
    /// The mean removed.
    Mean,
    /// The least-squares plane removed (tilt of the sample).
    Plane,
    /// The least-squares quadratic removed (tilt and form, e.g. the curvature of a ball).
    Curvature,
}

impl Detrend {
    /// The name written in run files.
    pub fn name(self) -> &'static str {
        match self {
            Detrend::None => "none",
            Detrend::Mean => "mean",
            Detrend::Plane => "plane",
            Detrend::Curvature => "curvature",
        }
    }
}

impl std::str::FromStr for Detrend {
    type Err = Error;

    fn from_str(name: &str) -> Result<Self> {
        match name {
            "none" => Ok(Detrend::None),
            "mean" => Ok(Detrend::Mean),
            "plane" => Ok(Detrend::Plane),
            "curvature" => Ok(Detrend::Curvature),
            other => Err(Error::param(
                "detrend",
                format!("\"{other}\"; use \"none\", \"mean\", \"plane\" or \"curvature\""),
            )),
        }
    }
}

/// The preparation of a measured height map: levelling, then an optional taper.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct Preprocess {
    pub detrend: Detrend,
    /// Fraction of each side over which a Tukey window brings the heights to their mean (0: none).
    pub taper: f64,
}

impl Preprocess {
    /// Checks the taper fraction: in [0, 1).
    pub fn validate(&self) -> Result<()> {
        if !(self.taper >= 0.0 && self.taper < 1.0) {
            return Err(Error::param(
                "taper",
                format!("{} must lie in [0, 1) (a fraction of each side)", self.taper),
            ));
        }
        Ok(())
    }
}

/// Solves the small dense system `a x = b` (Gaussian elimination with partial pivoting).
fn solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Option<Vec<f64>> {
    let n = b.len();
    for col in 0..n {
        let pivot = (col..n).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[pivot][col].abs() < 1e-300 {
            return None;
        }
        a.swap(col, pivot);
        b.swap(col, pivot);
        let (upper, lower) = a.split_at_mut(col + 1);
        let pivot_row = &upper[col];
        for (offset, row) in lower.iter_mut().enumerate() {
            let f = row[col] / pivot_row[col];
            for (v, p) in row[col..].iter_mut().zip(&pivot_row[col..]) {
                *v -= f * p;
            }
            b[col + 1 + offset] -= f * b[col];
        }
    }
    let mut x = vec![0.0; n];
    for row in (0..n).rev() {
        x[row] = (b[row] - (row + 1..n).map(|k| a[row][k] * x[k]).sum::<f64>()) / a[row][row];
    }
    Some(x)
}

/// Levels and tapers a height map in place (`rows × cols`, row-major), as `how` says.
pub fn preprocess(heights: &mut [f64], rows: usize, cols: usize, how: &Preprocess) -> Result<()> {
    how.validate()?;
    let basis: usize = match how.detrend {
        Detrend::None => 0,
        Detrend::Mean => 1,
        Detrend::Plane => 3,
        Detrend::Curvature => 6,
    };
    if basis > 0 {
        // Centred, scaled coordinates keep the normal equations well conditioned.
        let f = |i: usize, j: usize| -> [f64; 6] {
            let x = (i as f64 - (rows as f64 - 1.0) / 2.0) / rows as f64;
            let y = (j as f64 - (cols as f64 - 1.0) / 2.0) / cols as f64;
            [1.0, x, y, x * x, x * y, y * y]
        };
        let mut a = vec![vec![0.0; basis]; basis];
        let mut b = vec![0.0; basis];
        for i in 0..rows {
            for j in 0..cols {
                let phi = f(i, j);
                let z = heights[i * cols + j];
                for p in 0..basis {
                    b[p] += phi[p] * z;
                    for q in 0..basis {
                        a[p][q] += phi[p] * phi[q];
                    }
                }
            }
        }
        let c = solve(a, b).ok_or_else(|| Error::param("detrend", "the height map is too small to fit the trend"))?;
        for i in 0..rows {
            for j in 0..cols {
                let phi = f(i, j);
                heights[i * cols + j] -= (0..basis).map(|p| c[p] * phi[p]).sum::<f64>();
            }
        }
    }
    if how.taper > 0.0 {
        let window = |k: usize, n: usize| -> f64 {
            // Tukey window: cosine ramps over a fraction `taper` of the side, half at each end.
            let ramp = how.taper * n as f64 / 2.0;
            let d = (k as f64 + 0.5).min(n as f64 - k as f64 - 0.5);
            if d >= ramp {
                1.0
            } else {
                0.5 * (1.0 - (std::f64::consts::PI * d / ramp).cos())
            }
        };
        let mean = heights.iter().sum::<f64>() / heights.len() as f64;
        for i in 0..rows {
            for j in 0..cols {
                let h = &mut heights[i * cols + j];
                *h = mean + (*h - mean) * window(i, rows) * window(j, cols);
            }
        }
    }
    Ok(())
}

/// How far a height map is from periodic: the RMS jump across each border (last row to first,
/// last column to first) divided by the RMS step between neighbouring pixels inside. About 1 for a
/// periodic surface; much more means the periodic solution sees a ridge or a cliff at the border.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Periodicity {
    pub border_step_x: f64,
    pub border_step_y: f64,
}

/// Border jumps above this many typical steps draw a warning.
pub const NOT_PERIODIC: f64 = 3.0;

/// Measures the periodicity of a `rows × cols` height map.
pub fn periodicity(heights: &[f64], rows: usize, cols: usize) -> Periodicity {
    let at = |i: usize, j: usize| heights[i * cols + j];
    let rms = |pairs: &mut dyn Iterator<Item = f64>| -> f64 {
        let (s, n) = pairs.fold((0.0, 0usize), |(s, n), d| (s + d * d, n + 1));
        (s / n.max(1) as f64).sqrt()
    };
    let inside_x = rms(&mut (0..rows - 1)
        .flat_map(|i| (0..cols).map(move |j| (i, j)))
        .map(|(i, j)| at(i + 1, j) - at(i, j)));
    let inside_y = rms(&mut (0..rows)
        .flat_map(|i| (0..cols - 1).map(move |j| (i, j)))
        .map(|(i, j)| at(i, j + 1) - at(i, j)));
    let border_x = rms(&mut (0..cols).map(|j| at(0, j) - at(rows - 1, j)));
    let border_y = rms(&mut (0..rows).map(|i| at(i, 0) - at(i, cols - 1)));
    Periodicity {
        border_step_x: border_x / inside_x.max(1e-300),
        border_step_y: border_y / inside_y.max(1e-300),
    }
}

impl Periodicity {
    /// A warning when a border jump is large, with what to do.
    pub fn warning(&self, name: &str) -> Option<String> {
        let worst = self.border_step_x.max(self.border_step_y);
        (worst > NOT_PERIODIC).then(|| {
            format!(
                "{name} is not periodic: the jump across its border is {:.1} (along x) and {:.1} (along y) times the \
                 typical step between neighbouring pixels, so the periodic contact solution sees a ridge there; use \
                 detrend = \"plane\" or \"curvature\", a taper, or `wearsim surface fit` to generate periodic surfaces \
                 with the measured statistics",
                self.border_step_x, self.border_step_y
            )
        })
    }
}

/// A levelled map whose RMS height is at most this fraction of its largest |height| before the
/// levelling is flat: what is left is the round-off of the levelling.
const FLAT: f64 = 1e-12;

/// Whether a map of RMS height `levelled_rms` once levelled, and of largest |height| `spread`
/// before, is flat (a map of one value, or a plane levelled away to round-off).
pub fn is_flat(levelled_rms: f64, spread: f64) -> bool {
    levelled_rms <= FLAT * spread || levelled_rms.is_nan()
}

/// The error of a flat map `name` (levelled by `detrend`, left with `rms`): its spectrum is zero,
/// so there is nothing to fit and no surface can carry it.
pub fn flat_map(name: &str, detrend: Detrend, rms: f64) -> Error {
    Error::InvalidSurface {
        name: name.into(),
        message: format!(
            "the map is flat: levelled ({}), its heights are all equal to round-off (RMS {rms:.3e}), so its spectrum \
             is zero; there is nothing to fit and no surface can carry it: check the file (a map of one value, a \
             channel that is not the heights)",
            detrend.name()
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn detrending_removes_planes_and_quadratics_and_tapering_reaches_the_mean_at_the_border() {
        let (rows, cols) = (40, 30);
        let mut h: Vec<f64> = (0..rows * cols)
            .map(|k| 3.0 + 0.5 * (k / cols) as f64 - 0.2 * (k % cols) as f64 + 1e-3 * (k as f64).sin())
            .collect();
        let before = periodicity(&h, rows, cols);
        assert!(before.warning("top").is_some());
        preprocess(
            &mut h,
            rows,
            cols,
            &Preprocess {
                detrend: Detrend::Plane,
                taper: 0.0,
            },
        )
        .unwrap();
        assert!(h.iter().all(|v| v.abs() < 1e-2), "plane left");
        let mut q: Vec<f64> = (0..rows * cols)
            .map(|k| ((k / cols) as f64).powi(2) + (k % cols) as f64)
            .collect();
        preprocess(
            &mut q,
            rows,
            cols,
            &Preprocess {
                detrend: Detrend::Curvature,
                taper: 0.0,
            },
        )
        .unwrap();
        assert!(q.iter().all(|v| v.abs() < 1e-8), "quadratic left");
        let mut t: Vec<f64> = (0..rows * cols).map(|k| (k as f64 * 0.7).sin()).collect();
        preprocess(
            &mut t,
            rows,
            cols,
            &Preprocess {
                detrend: Detrend::Mean,
                taper: 0.2,
            },
        )
        .unwrap();
        assert!(t[0].abs() < 0.05 && t[cols / 2].abs() < 0.05);
        assert!(Preprocess {
            detrend: Detrend::None,
            taper: 1.5
        }
        .validate()
        .is_err());
    }
}
