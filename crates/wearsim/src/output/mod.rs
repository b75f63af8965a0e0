//! Every result document wearsim writes, built in one place: the provenance block they share, the
//! summary and series of a sliding run, the summary of one contact solve, surface statistics,
//! junction tables, study job files and the tidy results tables. Front ends (the CLI, the Python
//! bindings) call these and only choose where the files go.
//!
//! Tables are derived from one typed row each ([`SeriesRow`], [`TidyRow`]): their columns are the
//! rows' serde fields in order, so a column list is never kept by hand; every column's unit is
//! declared once (`WearResult::UNITS`, [`SeriesRow::UNITS`], the other quantities in `units`) and a
//! test fails for a column without one. Numbers are written in
//! Rust's shortest round-trip form (`{:e}` for floats); an undefined value (NaN, a missing input) is
//! an empty cell. A study's tables are derived once, in a [`StudyTable`], which every output of a
//! study takes.

mod fields;
mod figure_data;
mod jobs;
mod provenance;
mod series;
mod study_table;
mod summary;
mod tables;
mod units;

pub use fields::{FieldSelection, FieldsWriter};

pub use figure_data::{
    curve_labels, has_kim_materials, kim_material, kim_of_row, number, pretty, severity_fits, KimMaterial,
    MaterialSeverity, KIM_1986, KIM_EXPERIMENTAL_K, KIM_SEVERITY_FIT, PAPER_SEVERITY_FIT,
};
pub use jobs::{
    aggregate, curves, equal_critical_diameter, growth_across_jobs, interval_method, read_job_file, series_job,
    settings, sliding_rows, CurveMaterial, Curves, JobResult, SettingRows, Settings, TidyRow, AGGREGATE_SUFFIXES,
    ALONG_A_CURVE, FIT_WINDOW_COLUMNS, JOB_FORMAT, NOT_A_SETTING, STATISTICS, TOTALLED,
};
pub use provenance::{Provenance, DEPENDENCY_VERSIONS};
pub(crate) use series::distinct;
pub use series::{job_series_rows, lineages_left, series_rows, steps_of_rows, SeriesRow, StepRow};
pub use study_table::{averaged_pairs, write_results_tables, StudyTable};
pub use summary::{
    contact_summary, estimate_rows, estimate_summary, junctions_summary, series_csv, sliding_summary,
    surface_fit_summary, surface_summary, ContactRecord, EstimateRow, SlidingInputs, SurfaceStatistics,
    ESTIMATE_NOTICE, PSD_CONVENTION, RESIDUAL_DEFINITION,
};
pub use tables::{columns, Cell, Table};
pub use units::{declared_unit, specific_wear_rate, unit_of, units_map, QUANTITIES};
