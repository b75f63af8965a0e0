//! Studies (paper §4 and its appendices): a study file is a run file whose fields may be lists, or
//! whose materials are a `[[materials]]` array of named tables. The study is their Cartesian
//! product, one job per surface pair × material × contact setting × load (every fracture energy
//! inside the job), in four steps, one file each:
//!
//! - [`expand`](mod@expand): study file → jobs, each a validated single-load run;
//! - [`store`]: the study folder — the stored study, one job file per finished job written
//!   atomically, checked when read back;
//! - [`run`]: runs pending jobs, several at once, resumably (a killed study resumes where it
//!   stopped);
//! - [`collect`](mod@collect): job files → the tidy table and its aggregate over surface pairs;
//! - [`compare`]: the static estimate against the study's sliding runs (errors, coverage, the
//!   calibration's points);
//! - [`findings`]: the paper's qualitative findings checked on a tidy table;
//! - [`figures`]: the paper's figures of a study as data (one registry; the front ends draw them).

pub mod collect;
pub mod compare;
pub mod expand;
pub mod figures;
pub mod findings;
pub mod run;
pub mod store;

pub use collect::{collect, load_results};
pub use expand::{expand, expand_stored, Job, Study};
pub use run::{job_steps, run_job, run_job_observed, run_jobs, shard, workers_for_memory, RunSummary, StudyProgress};
pub use store::{job_path, prepare_folder, stored_result, write_result, Stored};
