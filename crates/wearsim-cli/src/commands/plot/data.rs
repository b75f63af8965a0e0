//! A study loaded for plotting: its jobs and results, and its curves against load, each per
//! nominal pressure a row of the library's aggregated table (statistics over surface pairs,
//! `output::aggregate`) with the label the library gives it (`output::curve_labels`).

use std::sync::Arc;

use anyhow::{anyhow, Result};
use wearsim::config::Units;
use wearsim::output::{
    aggregate, curve_labels, curves as output_curves, equal_critical_diameter, unit_of, Cell, CurveMaterial, JobResult,
    Table, TidyRow,
};
use wearsim::study::Job;

use crate::figures::number;

/// The unit names of a study's axes: those of the library's tables ([`unit_of`]), and values shown
/// in legends with their unit.
#[derive(Debug, Clone, Copy)]
pub(super) struct Units2 {
    pub system: Units,
    si: bool,
}

impl Units2 {
    pub fn of(system: Units) -> Self {
        Self {
            system,
            si: system == Units::Si,
        }
    }
    pub fn length(self) -> &'static str {
        unit_of(self.system, "length")
    }
    pub fn area(self) -> &'static str {
        unit_of(self.system, "wear_rate")
    }
    pub fn volume(self) -> &'static str {
        unit_of(self.system, "volume")
    }
    /// A length for legends (µm in SI).
    pub fn show_length(self, v: f64) -> String {
        if self.si {
            format!("{} µm", number(v * 1e6))
        } else {
            format!("{} L", number(v))
        }
    }
    pub fn show_stress(self, v: f64) -> String {
        if self.si {
            format!("{} GPa", number(v / 1e9))
        } else {
            format!("{} E", number(v))
        }
    }
    /// How a rate per unit nominal area is labelled: W/(Lx·Ly) in reduced units is the W of a box
    /// L × L, the paper's.
    pub fn per_area(self) -> &'static str {
        if self.si {
            "per unit nominal area, m²/m²"
        } else {
            "per unit nominal area, = a box L × L (the paper's)"
        }
    }
}

/// A result column of the tables (its statistics in the aggregated one).
pub(super) type Quantity = &'static str;

/// One point of a curve: (p_N, mean, interval low, interval high, max over pairs).
pub(super) type Point = (f64, f64, f64, f64, f64);

/// One curve against load: a setting (material and varying inputs but the seed) and one fracture
/// energy, as the library groups them (`output::curves`); per nominal pressure p_N = F_N/(Lx·Ly),
/// its row of the library's aggregated table.
pub(super) struct Curve {
    pub label: String,
    /// Index of its material among the study's, in order of appearance.
    pub material: usize,
    /// Index of its fracture energy within its jobs.
    pub energy: usize,
    pub critical_diameter: f64,
    pub shear_strength: f64,
    pub fracture_energy: f64,
    /// The nominal area Lx·Ly of its box.
    pub area: f64,
    /// The aggregated rows of this curve, by increasing nominal pressure.
    pub rows: Vec<Vec<Cell>>,
    /// The aggregated table's columns.
    pub columns: Arc<Vec<String>>,
    /// A curve of a model that takes no sliding step (the static estimate, `sliding.model =
    /// "estimate"`): it counts no particle (its uncertainty is its interval, in the job files), so
    /// none of its points is drawn hollow.
    pub estimate: bool,
}

impl Curve {
    pub fn get(&self, row: &[Cell], column: &str) -> f64 {
        self.columns
            .iter()
            .position(|c| c == column)
            .map_or(f64::NAN, |i| row[i].number())
    }

    /// Per load: the particles formed in the fit window, summed over the surface pairs; none for a
    /// curve of the static estimate.
    pub fn particles(&self) -> Vec<(f64, f64)> {
        if self.estimate {
            return Vec::new();
        }
        self.rows
            .iter()
            .map(|r| (self.get(r, "nominal_pressure"), self.get(r, "particles_in_fit_total")))
            .collect()
    }

    /// Per load where it is defined: a quantity's mean over the surface pairs, its 95 % interval
    /// (NaN with one pair) and its maximum, divided by the nominal area when `per_area`.
    pub fn stats(&self, q: Quantity, per_area: bool) -> Vec<Point> {
        let scale = if per_area { 1.0 / self.area } else { 1.0 };
        self.rows
            .iter()
            .filter_map(|r| {
                let mean = self.get(r, &format!("{q}_mean"));
                mean.is_finite().then(|| {
                    (
                        self.get(r, "nominal_pressure"),
                        mean * scale,
                        self.get(r, &format!("{q}_ci_low")) * scale,
                        self.get(r, &format!("{q}_ci_high")) * scale,
                        self.get(r, &format!("{q}_max")) * scale,
                    )
                })
            })
            .collect()
    }
}

/// A study loaded for plotting.
pub(super) struct Data {
    pub jobs: Vec<Job>,
    pub results: Vec<JobResult>,
    pub units: Units2,
    pub curves: Vec<Curve>,
    /// Material names, in order of appearance.
    pub materials: Vec<String>,
    /// The tidy table (`results.csv`).
    pub tidy: Table,
}

impl Data {
    pub fn new(jobs: Vec<Job>, results: Vec<JobResult>) -> Result<Self> {
        let first = jobs.first().ok_or_else(|| anyhow!("the study has no jobs"))?;
        let units = Units2::of(first.run.units);
        let mut materials: Vec<String> = Vec::new();
        // The library's tables: one tidy row per job and fracture energy, aggregated over pairs.
        let mut tidy_rows = Vec::new();
        let mut origin = Vec::new();
        for (j, r) in results.iter().enumerate() {
            for (e, row) in TidyRow::of_job(r).into_iter().enumerate() {
                tidy_rows.push(row);
                origin.push((j, e));
            }
        }
        let tidy = Table::of(&tidy_rows);
        let of_row = output_curves(&tidy).index;
        let labels = curve_labels(&tidy);
        let aggregated = aggregate(&tidy);
        let columns = Arc::new(aggregated.columns.clone());
        let mut curves: Vec<Curve> = Vec::new();
        for (&c, &(j, e)) in of_row.iter().zip(&origin) {
            if c < curves.len() {
                continue;
            }
            let (job, w) = (&jobs[j], &results[j].results[e]);
            let m = materials.iter().position(|x| *x == job.material).unwrap_or_else(|| {
                materials.push(job.material.clone());
                materials.len() - 1
            });
            let inputs = &results[j].inputs;
            curves.push(Curve {
                label: labels.get(c).cloned().unwrap_or_default(),
                material: m,
                energy: e,
                critical_diameter: w.critical_diameter,
                shear_strength: job.run.material.shear_strength,
                fracture_energy: w.fracture_energy,
                area: inputs.length * inputs.length_y.unwrap_or(inputs.length),
                rows: Vec::new(),
                columns: Arc::clone(&columns),
                estimate: !inputs.model.unwrap_or_default().slides(),
            });
        }
        let curve = aggregated
            .column("curve")
            .ok_or_else(|| anyhow!("the aggregated table has no curve column"))?;
        let pressure = aggregated
            .column("nominal_pressure")
            .ok_or_else(|| anyhow!("the aggregated table has no nominal_pressure column"))?;
        for row in aggregated.rows {
            let c = usize::try_from(row[curve].number() as i64).unwrap_or(usize::MAX);
            curves
                .get_mut(c)
                .ok_or_else(|| anyhow!("aggregated row of an unknown curve {c}"))?
                .rows
                .push(row);
        }
        for c in &mut curves {
            c.rows
                .sort_by(|a, b| a[pressure].number().total_cmp(&b[pressure].number()));
        }
        Ok(Self {
            jobs,
            results,
            units,
            curves,
            materials,
            tidy,
        })
    }

    /// The paper's load axis: the nominal pressure.
    pub fn load_label(&self) -> String {
        format!(
            "nominal pressure p_N = F_N/(Lx·Ly) ({})",
            unit_of(self.units.system, "nominal_pressure")
        )
    }

    /// The jobs of the same setting as `job` (every input but the surface pair, and the load): its
    /// surface pairs, in job order.
    pub fn pairs_of(&self, job: &Job) -> Vec<(&Job, &JobResult)> {
        let key = |j: &Job| {
            let mut inputs = j.inputs();
            inputs.seed = None;
            (j.material.clone(), inputs, j.load().to_bits())
        };
        let mine = key(job);
        self.jobs
            .iter()
            .zip(&self.results)
            .filter(|(j, _)| key(j) == mine)
            .collect()
    }
}

/// Groups of curves of (nearly) equal d* (within 15 %) and different τ̃ or 𝒢, for Figs. 4c/5c: the
/// library's grouping ([`equal_critical_diameter`]).
pub(super) fn equal_d_star(curves: &[Curve]) -> Vec<Vec<&Curve>> {
    let materials: Vec<CurveMaterial> = curves
        .iter()
        .map(|c| CurveMaterial {
            critical_diameter: c.critical_diameter,
            shear_strength: c.shear_strength,
            fracture_energy: c.fracture_energy,
        })
        .collect();
    equal_critical_diameter(&materials, 0.15)
        .into_iter()
        .map(|g| g.into_iter().map(|i| &curves[i]).collect())
        .collect()
}

/// The job whose series are drawn: the one asked for, or the one that formed the most particles
/// after running-in (the library's `series_job`).
pub(super) fn series_job(data: &Data, asked: Option<usize>) -> Result<(&Job, &JobResult)> {
    let index = match asked {
        Some(i) => i,
        None => {
            let particles = data
                .results
                .iter()
                .flat_map(|r| r.results.iter().map(move |w| (r.index, w.particles_in_fit)));
            wearsim::output::series_job(particles).ok_or_else(|| anyhow!("the study has no jobs"))?
        }
    };
    data.jobs
        .iter()
        .zip(&data.results)
        .find(|(j, _)| j.index == index)
        .ok_or_else(|| {
            anyhow!(
                "invalid `--job {index}`: the study has jobs 0 … {}",
                data.jobs.len().saturating_sub(1)
            )
        })
}
