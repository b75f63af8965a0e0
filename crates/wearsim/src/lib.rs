//! # wearsim
//!
//! Adhesive wear of rough surfaces in dry sliding, after Brink, Frérot & Molinari, "A parameter-free
//! mechanistic model of the adhesive wear process of rough surfaces in sliding contact",
//! J. Mech. Phys. Solids 147 (2021) 104238.
//!
//! Data flows one way, one module per step:
//! [`material`] and [`surface`] parameters → [`surface`] height fields → [`contact`] solution
//! (saturated-pressure FFT boundary elements, on [`fft`]) → [`junctions`] → [`wear`] bookkeeping,
//! driven step by step by [`sliding`] → results written by [`output`].
//! [`config`] turns run files into validated inputs; [`study`] expands study files into many runs,
//! runs them resumably and collects their results (figures are drawn by the CLI front end).

pub mod config;
pub mod contact;
pub mod error;
pub mod fft;
pub mod junctions;
pub mod material;
pub mod output;
pub mod sliding;
pub mod study;
pub mod surface;
pub mod wear;

pub use contact::{ContactSolver, SolveInfo, SolverOptions};
pub use error::{Error, Interrupt, Result};
pub use material::{Material, ModulusConvention};
pub use surface::{Generation, SpectrumParams, Surface};

/// Version of the library, recorded in every output file.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// Composite height of Johnson's equivalent rigid surface at a sliding offset of `offset` pixels
/// along x (SPEC §3): `bottom + np.roll(top, offset, axis=0)`, i.e.
/// `h[i, j] = bottom[i, j] + top[(i − offset) mod N, j]`. Written into `out` (N² values).
pub fn composite_heights(top: &Surface, bottom: &Surface, offset: usize, out: &mut [f64]) {
    use rayon::prelude::*;
    let n = top.n();
    assert_eq!(bottom.n(), n, "surfaces must share the grid");
    let (t, b) = (top.heights(), bottom.heights());
    out.par_chunks_mut(n).enumerate().for_each(|(i, row)| {
        let src = (i + n - offset % n) % n;
        for ((o, &bv), &tv) in row
            .iter_mut()
            .zip(&b[i * n..(i + 1) * n])
            .zip(&t[src * n..(src + 1) * n])
        {
            *o = bv + tv;
        }
    });
}
