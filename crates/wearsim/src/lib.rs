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
//! - [`influence`]: the half-space's influence operator 𝒦, periodic or with a free boundary;
//! - [`material`] and [`surface`]: parameters and height fields; [`topography`]: measured height
//!   maps read, prepared and fitted with self-affine parameters;
//! - [`contact`]: the saturated-pressure FFT boundary-element solver;
//! - [`junctions`] and [`wear`]: junctions of a contact map and the wear bookkeeping;
//! - [`sliding`]: the sliding simulation, step by step, and its schedule;
//! - [`config`]: run files turned into validated inputs;
//! - [`output`]: every result document (summaries, series, job files, tables);
//! - [`run`]: one sliding run from a validated run to its results, the path every front end takes;
//! - [`study`]: study files expanded into jobs, run resumably, collected.
//!
//! Figures are drawn by the front ends (the `wearsim` CLI, the Python package).
//!
//! ## A tour, in reduced units (E = 1, L = 1)
//!
//! Pressures are in E, lengths in L (the box side along x), loads F_N in E·L², fracture energies 𝒢
//! in E·L. A surface pair, one saturated contact, its junctions and the static model
//! (paper §2–3), on a 64² grid:
//!
//! ```
//! use wearsim::junctions::JunctionLabeller;
//! use wearsim::{composite_heights, ContactSolver, Grid, Material, ModulusConvention, SpectrumParams, Surface};
//!
//! let grid = Grid::square(64, 1.0)?; // 64 × 64 pixels, Lx = Ly = 1 L
//! // H = 0.7, λ_l = 16 Δx, λ_u = L/2, h_rms = 0.005 L (paper §4.1), random phases.
//! let spectrum = SpectrumParams::paper_roughness(64, 1.0);
//! let (top_seed, bottom_seed) = wearsim::surface::pair_seeds(1);
//! let top = Surface::generate(grid, &spectrum, top_seed)?;
//! let bottom = Surface::generate(grid, &spectrum, bottom_seed)?;
//! assert!((top.rms_height() - 0.005).abs() < 1e-12);
//!
//! // τ̃ = 0.01 E: p_m = 3√3 τ̃; d* = 2 f 𝒢 μ / τ̃² for 𝒢 = 0.5e-6 E·L (paper Eq. 1).
//! let material = Material::new(1.0, 0.3, 0.01, vec![0.5e-6], 3.0)?;
//! let p_m = material.flow_pressure();
//! let d_star = material.critical_diameter(0.5e-6); // in L
//!
//! // The contact of the composite surface at F_N = 1e-3 E·L² (mean pressure F_N/(Lx·Ly)).
//! let mut heights = vec![0.0; grid.pixels()];
//! composite_heights(&top, &bottom, 0, &mut heights);
//! let mut solver = ContactSolver::new(grid, material.effective_modulus(ModulusConvention::HalfSpace))?;
//! let mut pressure = vec![0.0; grid.pixels()]; // cold start; the result is written here (in E)
//! let info = solver.solve(&heights, grid.mean_pressure(1e-3), p_m, &mut pressure)?;
//! assert!(pressure.iter().all(|&p| p >= 0.0 && p <= p_m * (1.0 + 1e-12)));
//! let contact_area = info.contact_pixels as f64 / grid.pixels() as f64; // a fraction of Lx·Ly
//! assert!(contact_area > 0.0 && contact_area < 0.5);
//!
//! // Junctions: periodic connected components (4-connectivity) of the contact map.
//! let mut labeller = JunctionLabeller::new(grid.nx(), grid.ny(), 4);
//! let junctions = labeller.label(|k| pressure[k] > 0.0);
//! let largest = labeller.sizes().iter().max().copied().unwrap_or(0); // pixels
//! assert!(junctions > 0 && largest > 0);
//! # let _ = d_star;
//! # Ok::<(), wearsim::Error>(())
//! ```
//!
//! A sliding run from a run file (the format of `wearsim slide`): the wear rate W (L², a volume
//! L³ per sliding distance L) and the Archard coefficient k = W p̃ / F_N (1) per fracture energy.
//! `distance` and `running_in` are fractions of Lx:
//!
//! ```
//! use std::path::Path;
//! use wearsim::config::RunConfig;
//! use wearsim::run::SlidingRun;
//!
//! let run = RunConfig::from_toml(
//!     r#"
//!     [surface]
//!     grid = 32
//!     lambda_lower = 0.125
//!     lambda_upper = 0.5
//!     rms_height = 0.01
//!     seed = 3
//!     [material]
//!     youngs_modulus = 1.0
//!     poisson_ratio = 0.3
//!     shear_strength = 0.01
//!     fracture_energies = [0.25e-6]
//!     [sliding]
//!     loads = [2e-3]
//!     distance = 0.5
//!     running_in = 0.25
//!     "#,
//!     Path::new("."),
//! )?;
//! // The surfaces, the setup and the warnings known before the run (here d* of under 4 pixels) ...
//! let prepared = SlidingRun::prepare(&run)?;
//! assert!(!prepared.warnings().is_empty());
//! // ... then every load slid, an observer seeing each step (progress, fields).
//! let outcome = prepared.run(|_step| {})?;
//! let result = &outcome.runs[0].results[0];
//! assert_eq!(outcome.runs[0].load, 2e-3);
//! assert!(result.wear_rate.is_none_or(|w| w >= 0.0));
//! // The documents `wearsim slide` writes: series.csv and summary.json, with every warning once.
//! assert_eq!(outcome.summary()["warnings"], serde_json::json!(outcome.warnings));
//! # Ok::<(), wearsim::Error>(())
//! ```
//!
//! A study: a study file expands into jobs (surface pair × material × load), each a sliding run;
//! [`study::run_jobs`] runs them resumably into a folder, [`study::collect()`] makes the tables. One
//! job, run directly:
//!
//! ```
//! use std::path::Path;
//! use wearsim::study::{expand, run_job};
//!
//! let study = expand(
//!     r#"
//!     [surface]
//!     grid = 32
//!     lambda_lower = 0.125
//!     lambda_upper = 0.5
//!     rms_height = 0.01
//!     seed = [1, 2]
//!     [material]
//!     youngs_modulus = 1.0
//!     poisson_ratio = 0.3
//!     shear_strength = 0.01
//!     fracture_energies = [0.25e-6]
//!     [sliding]
//!     loads = [1e-3, 2e-3]
//!     distance = 0.5
//!     running_in = 0.25
//!     "#,
//!     Path::new("."),
//! )?;
//! assert_eq!(study.jobs.len(), 4); // 2 surface pairs × 2 loads
//! let result = run_job(&study.jobs[0], &wearsim::Interrupt::default())?;
//! assert_eq!(result.load, 1e-3);
//! assert!(result.provenance.dependencies.contains_key("rustfft"));
//! # Ok::<(), wearsim::Error>(())
//! ```

pub mod check;
pub mod config;
pub mod contact;
pub mod cost;
pub mod error;
pub mod estimate;
pub mod fft;
pub mod grid;
pub mod influence;
pub mod io;
pub mod junctions;
pub mod material;
pub mod model;
pub mod output;
pub mod run;
pub mod sliding;
pub mod stats;
pub mod study;
pub mod surface;
pub mod topography;
pub mod volume;
pub mod wear;

pub use contact::{ContactFields, ContactMap, ContactSolver, Device, SolveInfo, SolverOptions, Stopping, Termination};
pub use error::{Error, Interrupt, Result};
pub use grid::Grid;
pub use influence::Boundary;
pub use material::{CriticalDiameter, Material, ModulusConvention};
pub use surface::{composite_heights, Generation, SpectrumParams, Surface};

/// Version of the library, recorded in every output file.
pub use io::VERSION;

/// The versions of the crates that decide wearsim's numbers (FFT, random streams of generated
/// surfaces), as "name version" pairs separated by ", ", taken from the lockfile at build time.
pub use output::DEPENDENCY_VERSIONS;
