//! # wearsim
//!
//! Adhesive wear of rough surfaces in dry sliding, after Brink, Frérot & Molinari, "A parameter-free
//! mechanistic model of the adhesive wear process of rough surfaces in sliding contact",
//! J. Mech. Phys. Solids 147 (2021) 104238.
//!
//! Data flows one way, one module per step, each module using only those listed before it:
//!
//! - [`error`], [`check`] (the rules every input obeys), [`io`] (atomic files, `.npy`), [`fft`],
//!   [`stats`] (least-squares lines) and [`grid`] (Nx × Ny square pixels): the leaves;
//! - [`material`] and [`surface`]: parameters and height fields; [`topography`]: measured height
//!   maps read, prepared and fitted with self-affine parameters;
//! - [`contact`]: the saturated-pressure FFT boundary-element solver;
//! - [`junctions`] and [`wear`]: junctions of a contact map and the wear bookkeeping;
//! - [`sliding`]: the sliding simulation, step by step, and its schedule;
//! - [`config`]: run files turned into validated inputs;
//! - [`output`]: every result document (summaries, series, job files, tables);
//! - [`study`]: study files expanded into jobs, run resumably, collected.
//!
//! Figures are drawn by the front ends (the `wearsim` CLI, the Python package).

pub mod check;
pub mod config;
pub mod contact;
pub mod error;
pub mod fft;
pub mod grid;
pub mod io;
pub mod junctions;
pub mod material;
pub mod output;
pub mod sliding;
pub mod stats;
pub mod study;
pub mod surface;
pub mod topography;
pub mod wear;

pub use contact::{ContactSolver, SolveInfo, SolverOptions, Termination};
pub use error::{Error, Interrupt, Result};
pub use grid::Grid;
/// Version of the library, recorded in every output file.
pub use io::VERSION;
pub use material::{Material, ModulusConvention};
pub use surface::{composite_heights, Generation, SpectrumParams, Surface};
