//! What the library derives from a study's tables, for the figures of `wearsim.plot`: the curves
//! of a table and their labels, its aggregation over surface pairs with 95 % intervals, the curves of
//! equal d*, the units of its columns, the contact-severity fits of appendix F per material, Kim's
//! ceramics, the intervals themselves and the paper's findings judged on the table. Tables come from
//! Python as a dict of column lists (a DataFrame's `{c: df[c].tolist()}`).

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyString};
use wearsim::config::Units;
use wearsim::output::{Cell, CurveMaterial, Table};

use crate::table_to_py;

/// A table from a dict of equally long column lists: None and NaN are empty cells, whole numbers
/// integers, other numbers floats, everything else text.
fn table_of(columns: &Bound<'_, PyDict>) -> PyResult<Table> {
    let mut names = Vec::new();
    let mut cells: Vec<Vec<Cell>> = Vec::new();
    for (name, values) in columns.iter() {
        let name: String = name.extract()?;
        let column = values
            .try_iter()?
            .map(|v| {
                let v = v?;
                Ok(if v.is_none() {
                    Cell::Empty
                } else if v.is_instance_of::<PyBool>() || v.is_instance_of::<PyString>() {
                    Cell::Text(v.str()?.to_string())
                } else if v.is_instance_of::<PyInt>() {
                    Cell::Int(v.extract()?)
                } else if v.is_instance_of::<PyFloat>() {
                    let f: f64 = v.extract()?;
                    if f.is_nan() {
                        Cell::Empty
                    } else {
                        Cell::Float(f)
                    }
                } else {
                    Cell::Text(v.str()?.to_string())
                })
            })
            .collect::<PyResult<Vec<Cell>>>()?;
        if let Some(first) = cells.first() {
            if first.len() != column.len() {
                return Err(PyValueError::new_err(format!(
                    "invalid table: column `{name}` has {} rows, `{}` has {}",
                    column.len(),
                    names[0],
                    first.len()
                )));
            }
        }
        names.push(name);
        cells.push(column);
    }
    let rows = (0..cells.first().map_or(0, Vec::len))
        .map(|r| cells.iter().map(|c| c[r].clone()).collect())
        .collect();
    Ok(Table { columns: names, rows })
}

/// A study's table (the library's one derivation of its settings, run-in pairs and means) from
/// the columns of its tidy table.
fn study_table_of(columns: &Bound<'_, PyDict>) -> PyResult<wearsim::output::StudyTable> {
    Ok(wearsim::output::StudyTable::of(table_of(columns)?))
}

/// The curves of a tidy or aggregated table: per row the index of its curve, and the setting
/// columns that tell the curves apart.
#[pyfunction]
fn curves(columns: &Bound<'_, PyDict>) -> PyResult<(Vec<usize>, Vec<String>)> {
    let c = wearsim::output::curves(&table_of(columns)?);
    Ok((c.index, c.settings))
}

/// The aggregated table of a tidy table (what `results_aggregated.csv` holds and the figures
/// draw, `StudyTable::means`), as columns.
#[pyfunction]
fn aggregate<'py>(py: Python<'py>, columns: &Bound<'py, PyDict>) -> PyResult<Bound<'py, PyDict>> {
    table_to_py(py, study_table_of(columns)?.means())
}

/// The groups of curves of (nearly) equal d* that Figs. 4c and 5c compare, from (d*, τ̃, 𝒢) per
/// curve: indices of the curves, each group by increasing d*.
#[pyfunction]
fn equal_critical_diameter(curves: Vec<(f64, f64, f64)>, tolerance: f64) -> Vec<Vec<usize>> {
    let curves: Vec<CurveMaterial> = curves
        .into_iter()
        .map(|(critical_diameter, shear_strength, fracture_energy)| CurveMaterial {
            critical_diameter,
            shear_strength,
            fracture_energy,
        })
        .collect();
    wearsim::output::equal_critical_diameter(&curves, tolerance)
}

/// The unit of a column or quantity in the unit system `units` ("reduced" or "si").
#[pyfunction]
fn unit_of(units: &str, quantity: &str) -> PyResult<&'static str> {
    let system = match units {
        "reduced" => Units::Reduced,
        "si" => Units::Si,
        other => {
            return Err(PyValueError::new_err(format!(
                "invalid `units`: {other:?} is neither \"reduced\" nor \"si\""
            )))
        }
    };
    Ok(wearsim::output::unit_of(system, quantity))
}

/// The least-squares power law y = prefactor · xⁿ in log–log over the points with x, y > 0:
/// (prefactor, exponent, R² or None), or None with fewer than two such points.
#[pyfunction]
fn power_law_fit(x: Vec<f64>, y: Vec<f64>) -> PyResult<Option<(f64, f64, Option<f64>)>> {
    if x.len() != y.len() {
        return Err(PyValueError::new_err(format!(
            "invalid `y`: {} values for {} values of `x`",
            y.len(),
            x.len()
        )));
    }
    Ok(wearsim::stats::power_law_fit(&x, &y).map(|f| (f.prefactor, f.exponent, f.r2)))
}

/// The least-squares line y = slope · x + intercept: (slope, intercept, R² or None), or None with
/// fewer than two points or x without spread.
#[pyfunction]
fn line_fit(x: Vec<f64>, y: Vec<f64>) -> PyResult<Option<(f64, f64, Option<f64>)>> {
    if x.len() != y.len() {
        return Err(PyValueError::new_err(format!(
            "invalid `y`: {} values for {} values of `x`",
            y.len(),
            x.len()
        )));
    }
    Ok(wearsim::stats::line_fit(&x, &y).map(|f| (f.slope, f.intercept, f.r2)))
}

/// The job whose series a study's figures show when none is asked for, from the tidy table's
/// `job` and `particles_in_fit` columns: the most particles in the fit window, the lowest job
/// among equals; None without rows.
#[pyfunction]
fn series_job(job: Vec<usize>, particles_in_fit: Vec<usize>) -> PyResult<Option<usize>> {
    if job.len() != particles_in_fit.len() {
        return Err(PyValueError::new_err(format!(
            "invalid `particles_in_fit`: {} values for {} values of `job`",
            particles_in_fit.len(),
            job.len()
        )));
    }
    Ok(wearsim::output::series_job(job.into_iter().zip(particles_in_fit)))
}

/// The mean of `values` (one per surface pair) with its 95 % Student-t interval: (mean, low, high,
/// n), or None with fewer than two finite values. The function behind the aggregated table's
/// `_ci_low` and `_ci_high` columns.
#[pyfunction]
fn mean_interval(values: Vec<f64>) -> Option<(f64, f64, f64, usize)> {
    wearsim::stats::mean_interval(&values).map(|i| (i.estimate, i.low, i.high, i.n))
}

/// A particle count with its exact 95 % Poisson (Garwood) interval: (count, low, high).
#[pyfunction]
fn poisson_interval(count: u64) -> (f64, f64, f64) {
    let i = wearsim::stats::poisson_interval(count);
    (i.estimate, i.low, i.high)
}

/// The label of every curve of a tidy or aggregated table, by curve index.
#[pyfunction]
fn curve_labels(columns: &Bound<'_, PyDict>) -> PyResult<Vec<String>> {
    Ok(wearsim::output::curve_labels(&table_of(columns)?))
}

/// Whether a tidy or aggregated table holds one of Kim et al.'s ceramics (the paper's Table 1).
#[pyfunction]
fn has_kim_materials(columns: &Bound<'_, PyDict>) -> PyResult<bool> {
    Ok(wearsim::output::has_kim_materials(&table_of(columns)?))
}

/// Appendix F on a tidy table: per material a dict (material, points [(S_c, W)], fit (α, n, R²) or
/// None, kim: the Kim ceramic's name or None), and the fit over all materials or None.
#[pyfunction]
#[allow(clippy::type_complexity)]
fn severity_fits<'py>(
    py: Python<'py>,
    columns: &Bound<'py, PyDict>,
) -> PyResult<(Vec<Bound<'py, PyDict>>, Option<(f64, f64, Option<f64>)>)> {
    let (materials, all) = wearsim::output::severity_fits(&table_of(columns)?);
    let fit = |f: wearsim::stats::PowerLawFit| (f.prefactor, f.exponent, f.r2);
    let out = materials
        .into_iter()
        .map(|m| {
            let d = PyDict::new(py);
            d.set_item("material", m.material)?;
            d.set_item("points", m.points)?;
            d.set_item("fit", m.fit.map(fit))?;
            d.set_item("kim", m.kim.map(|k| k.name))?;
            Ok(d)
        })
        .collect::<PyResult<Vec<_>>>()?;
    Ok((out, all.map(fit)))
}

/// The paper's findings judged on a tidy table: one dict per finding (key, paper, rule, observed,
/// verdict, counts (holds, contrary, inconclusive, not run in), pairs_to_decide, kind,
/// verdict_under_holm, verdicts_by_rule, same_data_as, reading, claim, notes), the text of
/// `figures/findings.md` and of `figures/findings_units.csv`: the library's document, byte for byte
/// what `wearsim study plot` writes.
#[pyfunction]
fn findings<'py>(py: Python<'py>, columns: &Bound<'py, PyDict>) -> PyResult<(Vec<Bound<'py, PyDict>>, String, String)> {
    let wearsim::study::findings::FindingsDocument {
        findings,
        markdown,
        units_csv: units,
    } = wearsim::study::findings::document(&study_table_of(columns)?);
    let out = findings
        .into_iter()
        .map(|f| {
            let d = PyDict::new(py);
            d.set_item("kind", f.kind())?;
            d.set_item("verdict_under_holm", f.verdict_under_holm.map(|v| v.name()))?;
            d.set_item(
                "verdicts_by_rule",
                f.verdicts_by_rule.map(|[l, dl, a]| {
                    [
                        ("lineages_left", l.name()),
                        ("decay_lengths", dl.name()),
                        ("every_pair", a.name()),
                    ]
                    .into_iter()
                    .collect::<std::collections::BTreeMap<_, _>>()
                }),
            )?;
            d.set_item("same_data_as", f.same_data_as)?;
            d.set_item("reading", f.reading.map(|v| v.name()))?;
            d.set_item("claim", f.claim)?;
            d.set_item("notes", f.notes.clone())?;
            d.set_item("key", f.key)?;
            d.set_item("paper", f.paper)?;
            d.set_item("rule", f.rule)?;
            d.set_item("observed", f.observed)?;
            d.set_item("verdict", f.verdict.name())?;
            d.set_item("counts", f.counts)?;
            d.set_item("pairs_to_decide", f.pairs_to_decide)?;
            Ok(d)
        })
        .collect::<PyResult<Vec<_>>>()?;
    Ok((out, markdown, units))
}

/// Figures as Python dicts: the library's figure (serde) with its CSV under "csv".
pub(crate) fn figures_to_py<'py>(
    py: Python<'py>,
    figures: &[wearsim::study::figures::Figure],
) -> PyResult<Vec<Bound<'py, PyAny>>> {
    figures
        .iter()
        .map(|f| {
            let d = crate::json_to_py(py, f)?;
            d.set_item("csv", f.to_csv())?;
            Ok(d)
        })
        .collect()
}

/// The figures of a tidy table that need no job file (those against load, Eq. 5, appendix F; the
/// series figures are notes): one dict per figure, as `study_figures`.
#[pyfunction]
#[pyo3(signature = (columns, names=None))]
fn table_figures<'py>(
    py: Python<'py>,
    columns: &Bound<'py, PyDict>,
    names: Option<Vec<String>>,
) -> PyResult<Vec<Bound<'py, PyAny>>> {
    let table = study_table_of(columns)?;
    let figures =
        wearsim::study::figures::study_figures(&table, &[], None, names.as_deref()).map_err(crate::error::to_py)?;
    figures_to_py(py, &figures)
}

/// A series figure (`fig3`, `appB`, `memory`) of sliding runs outside a study
/// (`wearsim::study::figures::run_figure`): `runs` holds (label, series columns, results columns or
/// None) per run; `length_unit` names the unit system by its length unit, "L" or "m".
#[pyfunction]
#[pyo3(signature = (entry, runs, load = None, length_unit = "L"))]
fn run_figure<'py>(
    py: Python<'py>,
    entry: &str,
    runs: Vec<(String, Bound<'py, PyDict>, Option<Bound<'py, PyDict>>)>,
    load: Option<f64>,
    length_unit: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let units = [Units::Reduced, Units::Si]
        .into_iter()
        .find(|u| u.length_unit() == length_unit)
        .ok_or_else(|| {
            PyValueError::new_err(format!(
                "invalid `length_unit` {length_unit:?}: \"L\" (reduced units, lengths in units of L) or \"m\" (SI, a run \
                 file with units = \"si\")"
            ))
        })?;
    let tables = runs
        .iter()
        .map(|(label, series, results)| {
            Ok((
                label.as_str(),
                table_of(series)?,
                results.as_ref().map(table_of).transpose()?,
            ))
        })
        .collect::<PyResult<Vec<_>>>()?;
    let runs: Vec<wearsim::study::figures::RunTables> = tables
        .iter()
        .map(|(label, series, results)| wearsim::study::figures::RunTables {
            label,
            series,
            results: results.as_ref(),
        })
        .collect();
    let figure = wearsim::study::figures::run_figure(entry, &runs, load, units).map_err(crate::error::to_py)?;
    Ok(figures_to_py(py, std::slice::from_ref(&figure))?.remove(0))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(table_figures, m)?)?;
    m.add_function(wrap_pyfunction!(run_figure, m)?)?;
    let registry: Vec<(&str, &str)> = wearsim::study::figures::FIGURES
        .iter()
        .map(|f| (f.name, f.about))
        .collect();
    m.add("FIGURES", registry)?;
    m.add("INTERVAL_LEVEL", wearsim::stats::LEVEL)?;
    m.add("KIM_EXPERIMENTAL_K", wearsim::output::KIM_EXPERIMENTAL_K)?;
    m.add("KIM_SEVERITY_FIT", wearsim::output::KIM_SEVERITY_FIT)?;
    m.add("PAPER_SEVERITY_FIT", wearsim::output::PAPER_SEVERITY_FIT)?;
    m.add_function(wrap_pyfunction!(mean_interval, m)?)?;
    m.add_function(wrap_pyfunction!(poisson_interval, m)?)?;
    m.add_function(wrap_pyfunction!(curve_labels, m)?)?;
    m.add_function(wrap_pyfunction!(has_kim_materials, m)?)?;
    m.add_function(wrap_pyfunction!(severity_fits, m)?)?;
    m.add_function(wrap_pyfunction!(findings, m)?)?;
    m.add("RESOLVED_PARTICLES", wearsim::study::findings::RESOLVED_PARTICLES)?;
    m.add_function(wrap_pyfunction!(curves, m)?)?;
    m.add_function(wrap_pyfunction!(aggregate, m)?)?;
    m.add_function(wrap_pyfunction!(unit_of, m)?)?;
    m.add_function(wrap_pyfunction!(equal_critical_diameter, m)?)?;
    m.add_function(wrap_pyfunction!(power_law_fit, m)?)?;
    m.add_function(wrap_pyfunction!(line_fit, m)?)?;
    m.add_function(wrap_pyfunction!(series_job, m)?)?;
    Ok(())
}
