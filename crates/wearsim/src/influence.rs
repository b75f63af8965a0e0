//! The influence operator 𝒦 of the elastic half-space: the surface displacement u = 𝒦p under a
//! pixel-wise constant pressure p, for the two boundary conditions a map can have.
//!
//! - **Periodic** (the paper's setting, §2 and appendix A): the map is one period of an infinite
//!   surface; û(q) = 2 p̂(q)/(E*|k|) with the q = 0 mode (the rigid-body position) left to the load,
//!   so u has zero mean. One Nx × Ny FFT round trip.
//! - **Free**: the map is the whole contact, surrounded by an unloaded half-space (a measured map,
//!   which is not periodic). u is the Boussinesq solution, u(x) = 1/(π E*) ∫ p(x′)/|x − x′| dA′,
//!   summed exactly over pixels (Love's closed form for a uniformly loaded rectangle), and evaluated
//!   by Hockney's method: the pressure is zero-padded to 2Nx × 2Ny, circularly convolved with the
//!   pixel influence sampled at the offsets −Nx…Nx−1 (−Ny…Ny−1), and the Nx × Ny corner kept. No
//!   periodic image reaches the map, at four times the FFT work.
//!
//! Both apply the same [`FftPlan::convolve_with`] hooks, so the contact solver's algorithm is written
//! once for both.

use std::f64::consts::PI;
use std::str::FromStr;

use rayon::prelude::*;

use crate::check::positive;
use crate::error::{Error, Result};
use crate::fft::{radial_kernel, FftPlan};
use crate::grid::Grid;

/// Boundary condition of the half-space at the edges of the map.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Boundary {
    /// The map is one period of an infinite surface (the paper's model; required for sliding).
    #[default]
    Periodic,
    /// The map is surrounded by an unloaded half-space (measured maps, indenters).
    Free,
}

impl Boundary {
    /// The name used in run files, on the command line and in Python.
    pub fn name(self) -> &'static str {
        match self {
            Boundary::Periodic => "periodic",
            Boundary::Free => "free",
        }
    }

    /// Whether the top surface may slide by `shift` pixels over a map of this boundary: a sliding
    /// offset wraps the top surface around the periodic box (paper §2), which a free boundary does
    /// not have, so there only offset 0 is a contact of the map as given.
    pub fn allows_offset(self, shift: usize) -> bool {
        match self {
            Boundary::Periodic => true,
            Boundary::Free => shift == 0,
        }
    }
}

impl FromStr for Boundary {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "periodic" => Ok(Boundary::Periodic),
            "free" => Ok(Boundary::Free),
            other => Err(Error::param(
                "boundary",
                format!("{other:?} is not a boundary condition; use \"periodic\" or \"free\""),
            )),
        }
    }
}

/// Arrays of Nx·Ny doubles the operator holds: the spectrum and kernel of an Nx × Ny plan
/// (periodic), or of a 2Nx × 2Ny plan plus its padded input and output (free).
pub fn arrays(boundary: Boundary) -> f64 {
    match boundary {
        Boundary::Periodic => 1.5,
        Boundary::Free => 14.0,
    }
}

/// ∫₀ˣ∫₀ʸ dy′dx′/√(x′² + y′²) = x asinh(y/|x|) + y asinh(x/|y|) (0 on the axes), the primitive of
/// Love's solution for a uniformly loaded rectangle.
fn love_primitive(x: f64, y: f64) -> f64 {
    let a = if x == 0.0 { 0.0 } else { x * (y / x.abs()).asinh() };
    let b = if y == 0.0 { 0.0 } else { y * (x / y.abs()).asinh() };
    a + b
}

/// Displacement at offset (x, y) from the centre of a square pixel of side `dx` under unit pressure,
/// for a half-space of effective modulus E* (Love 1929; Johnson, Contact Mechanics, §3.2).
pub fn pixel_influence(x: f64, y: f64, dx: f64, effective_modulus: f64) -> f64 {
    let h = 0.5 * dx;
    let f = love_primitive(x + h, y + h) - love_primitive(x - h, y + h) - love_primitive(x + h, y - h)
        + love_primitive(x - h, y - h);
    f / (PI * effective_modulus)
}

/// The operator 𝒦 for one grid and boundary: plans, kernel and buffers made once.
pub struct Influence {
    boundary: Boundary,
    nx: usize,
    ny: usize,
    plan: FftPlan,
    /// Fourier multiplier in [`FftPlan::convolve`]'s layout, normalisation folded in.
    kernel: Vec<f64>,
    /// 𝒦ᵢᵢ: the displacement of a unit-pressure pixel at that pixel.
    self_influence: f64,
    /// Free boundary: the 2Nx × 2Ny zero-padded input (only its Nx × Ny corner is ever written)
    /// and output; empty when periodic.
    padded_in: Vec<f64>,
    padded_out: Vec<f64>,
}

impl Influence {
    /// The operator on `grid` for a half-space of effective modulus E* (unit of pressure).
    pub fn new(grid: Grid, effective_modulus: f64, boundary: Boundary) -> Result<Self> {
        positive("effective_modulus", effective_modulus)?;
        let (nx, ny) = (grid.nx(), grid.ny());
        match boundary {
            Boundary::Periodic => {
                let nn = (nx * ny) as f64;
                let (length, aspect) = (grid.length_x(), grid.aspect());
                // û = 2 p̂ / (E* |k|), |k| = 2π|q|/Lx with q = (q_x, q_y Lx/Ly) in units of 2π/Lx;
                // the q = 0 mode is the rigid-body position, set by the load.
                let kernel = radial_kernel(nx, ny, |qx, qy| {
                    let qy = qy * aspect;
                    let q = (qx * qx + qy * qy).sqrt();
                    if q == 0.0 {
                        0.0
                    } else {
                        2.0 / (effective_modulus * 2.0 * PI * q / length) / nn
                    }
                });
                let mut self_influence = 0.0;
                for (qy, row) in kernel.chunks(nx).enumerate() {
                    let w = if qy == 0 || qy == ny / 2 { 1.0 } else { 2.0 };
                    self_influence += w * row.iter().sum::<f64>();
                }
                Ok(Self {
                    boundary,
                    nx,
                    ny,
                    plan: FftPlan::new(nx, ny),
                    kernel,
                    self_influence,
                    padded_in: Vec::new(),
                    padded_out: Vec::new(),
                })
            }
            Boundary::Free => {
                let (mx, my) = (2 * nx, 2 * ny);
                let dx = grid.pixel_size();
                // Offsets 0…N−1 then −N…−1 pixels (index N, offset ±N, never pairs two map pixels).
                let offset = |k: usize, n: usize| if k < n { k as f64 } else { k as f64 - 2.0 * n as f64 };
                let mut real = vec![0.0; mx * my];
                real.par_chunks_mut(my).enumerate().for_each(|(i, row)| {
                    let x = offset(i, nx) * dx;
                    for (j, v) in row.iter_mut().enumerate() {
                        *v = pixel_influence(x, offset(j, ny) * dx, dx, effective_modulus);
                    }
                });
                let self_influence = real[0];
                let mut plan = FftPlan::new(mx, my);
                plan.forward(&real);
                // The sampled kernel is even in both offsets, so its spectrum is real.
                let (half, stride, norm) = (plan.half(), plan.row_stride(), (mx * my) as f64);
                let spectrum = plan.spectrum();
                let mut kernel = vec![0.0; half * mx];
                for (qy, row) in kernel.chunks_mut(mx).enumerate() {
                    for (qx, v) in row.iter_mut().enumerate() {
                        *v = spectrum[qy * stride + qx].re / norm;
                    }
                }
                // `real` becomes the padded input: zero outside the corner the map is copied into.
                real.iter_mut().for_each(|v| *v = 0.0);
                Ok(Self {
                    boundary,
                    nx,
                    ny,
                    plan,
                    kernel,
                    self_influence,
                    padded_in: real,
                    padded_out: vec![0.0; mx * my],
                })
            }
        }
    }

    /// The boundary condition.
    pub fn boundary(&self) -> Boundary {
        self.boundary
    }

    /// 𝒦ᵢᵢ, the displacement of a unit-pressure pixel at that pixel (length per unit pressure).
    pub fn self_influence(&self) -> f64 {
        self.self_influence
    }

    /// `out = 𝒦 p` (Nx·Ny values each, row-major).
    pub fn apply(&mut self, pressure: &[f64], out: &mut [f64]) {
        self.apply_with(pressure, |_, _| {}, out, |_, _| (), None);
    }

    /// `output = 𝒦 input` with the hooks of [`FftPlan::convolve_with`]: `pre(i, row)` may modify
    /// the copy of input row `i` before it is transformed; `post(i, row)` sees output row `i` once
    /// written and returns the value stored in `partials[i]` (when given).
    pub fn apply_with<R: Send>(
        &mut self,
        input: &[f64],
        pre: impl Fn(usize, &mut [f64]) + Sync,
        output: &mut [f64],
        post: impl Fn(usize, &mut [f64]) -> R + Sync,
        partials: Option<&mut [R]>,
    ) {
        let (nx, ny) = (self.nx, self.ny);
        assert!(
            input.len() == nx * ny && output.len() == nx * ny,
            "fields must hold Nx·Ny values"
        );
        match self.boundary {
            Boundary::Periodic => self
                .plan
                .convolve_with(input, pre, &self.kernel, output, post, partials),
            Boundary::Free => {
                self.pad(input, pre);
                self.plan.convolve(&self.padded_in, &self.kernel, &mut self.padded_out);
                self.crop_with(output, post, partials);
            }
        }
    }

    /// `factor · Σ t·(𝒦t)` over the grid, with `pre(i, row)` applied to the copy of row `i` of
    /// `input` first, as in [`Influence::apply_with`]: the quadratic form from the forward
    /// transform alone ([`FftPlan::quadratic_form_with`], half a convolution; `factor` enters each
    /// term). With a free boundary the padded input is zero outside its corner, so the padded
    /// grid's form is the box's.
    pub fn quadratic_form_with(&mut self, input: &[f64], pre: impl Fn(usize, &mut [f64]) + Sync, factor: f64) -> f64 {
        assert_eq!(input.len(), self.nx * self.ny, "fields must hold Nx·Ny values");
        match self.boundary {
            Boundary::Periodic => self.plan.quadratic_form_with(input, pre, &self.kernel, factor),
            Boundary::Free => {
                self.pad(input, pre);
                self.plan
                    .quadratic_form_with(&self.padded_in, |_, _| {}, &self.kernel, factor)
            }
        }
    }

    /// The free boundary's zero-padded input: `input` through `pre` into its Nx × Ny corner.
    /// [`Influence::apply_with`] of the input of the last [`Influence::quadratic_form_with`] (with
    /// its `pre`), from the forward transform that call left (no other use of the operator since):
    /// the other half of the convolution, bit for bit what `apply_with` gives.
    pub fn apply_kept_with<R: Send>(
        &mut self,
        output: &mut [f64],
        post: impl Fn(usize, &mut [f64]) -> R + Sync,
        partials: Option<&mut [R]>,
    ) {
        assert_eq!(output.len(), self.nx * self.ny, "fields must hold Nx·Ny values");
        match self.boundary {
            Boundary::Periodic => self.plan.convolve_kept_with(&self.kernel, output, post, partials),
            Boundary::Free => {
                self.plan
                    .convolve_kept_with(&self.kernel, &mut self.padded_out, |_, _| (), None);
                self.crop_with(output, post, partials);
            }
        }
    }

    /// Free boundary: the map's corner of the padded output into `output`, row by row, with the
    /// `post` hook of [`Influence::apply_with`].
    fn crop_with<R: Send>(
        &self,
        output: &mut [f64],
        post: impl Fn(usize, &mut [f64]) -> R + Sync,
        partials: Option<&mut [R]>,
    ) {
        let (nx, ny) = (self.nx, self.ny);
        let padded = &self.padded_out;
        let keep = |i: usize, out: &mut [f64]| {
            out.copy_from_slice(&padded[i * 2 * ny..i * 2 * ny + ny]);
            post(i, out)
        };
        match partials {
            Some(partials) => {
                assert_eq!(partials.len(), nx, "one partial per row");
                output
                    .par_chunks_mut(ny)
                    .zip(partials.par_iter_mut())
                    .enumerate()
                    .for_each(|(i, (out, slot))| *slot = keep(i, out));
            }
            None => output.par_chunks_mut(ny).enumerate().for_each(|(i, out)| {
                keep(i, out);
            }),
        }
    }

    fn pad(&mut self, input: &[f64], pre: impl Fn(usize, &mut [f64]) + Sync) {
        let ny = self.ny;
        self.padded_in
            .par_chunks_mut(2 * ny)
            .zip(input.par_chunks(ny))
            .enumerate()
            .for_each(|(i, (padded, row))| {
                let corner = &mut padded[..ny];
                corner.copy_from_slice(row);
                pre(i, corner);
            });
    }
}

/// Free pixels per partial of [`PairForm::form`], combined in order.
const PAIR_CHUNK: usize = 16;

/// The periodic operator's real-space kernel, for the quadratic form Σ aᵢ(𝒦a)ᵢ of a field `a`
/// that is zero but on a few pixels: summed over their pairs, it costs n²/2 kernel values
/// against the forward transform of the whole grid by Parseval's identity. In the paper's setting
/// the contact is almost all plastic and the solver's conjugate direction lives on the free
/// pixels alone, a few per cent of the contact, so the pair sum is the cheaper of the two
/// (docs/performance.md: 5–11 times at 1024² to 4096²).
pub struct PairForm {
    /// Kernel values ×`factor` at offsets (a, b), 0 ≤ a ≤ Nx/2, 0 ≤ b ≤ Ny/2 (`table[a·(Ny/2+1)
    /// + b]`): the periodic kernel is even in each offset, so these are all of it.
    table: Vec<f64>,
    /// Where an offset lands in `table`: `rows[dx]` = min(dx, Nx − dx)·(Ny/2+1) for 0 ≤ dx < Nx,
    /// `columns[dy + Ny]` = min(dy mod Ny, Ny − dy mod Ny) for −Ny < dy < Ny (no division in
    /// the pair loop).
    rows: Vec<usize>,
    columns: Vec<usize>,
    /// The most pixels for which the pair sum is taken: n(n+1)/2 ≤ Nx·Ny/4 pairs, a few times
    /// cheaper than the transform where measured (docs/performance.md).
    max_pixels: usize,
}

impl PairForm {
    /// The kernel of a periodic `influence` as its response to a unit pressure on pixel (0, 0),
    /// times `factor` (a power of two keeps the form exactly that of the transform's scaled form);
    /// `None` for a free boundary. `scratch` and `out` are two Nx·Ny work fields, left zero.
    pub fn new(influence: &mut Influence, factor: f64, scratch: &mut [f64], out: &mut [f64]) -> Option<Self> {
        if influence.boundary() != Boundary::Periodic {
            return None;
        }
        let (nx, ny) = (influence.nx, influence.ny);
        let (ax, ay) = (nx / 2 + 1, ny / 2 + 1);
        scratch.iter_mut().for_each(|v| *v = 0.0);
        scratch[0] = 1.0;
        influence.apply(scratch, out);
        scratch[0] = 0.0;
        let mut table = vec![0.0; ax * ay];
        for (a, row) in table.chunks_mut(ay).enumerate() {
            for (b, v) in row.iter_mut().enumerate() {
                *v = out[a * ny + b] * factor;
            }
        }
        out.iter_mut().for_each(|v| *v = 0.0);
        let pairs = (nx * ny / 4) as f64;
        let max_pixels = ((2.0 * pairs + 0.25).sqrt() - 0.5).floor() as usize;
        let rows = (0..nx).map(|dx| dx.min(nx - dx) * ay).collect();
        let columns = (0..2 * ny)
            .map(|d| {
                let m = d % ny;
                m.min(ny - m)
            })
            .collect();
        Some(Self {
            table,
            rows,
            columns,
            max_pixels,
        })
    }

    /// Whether `n` pixels are few enough for [`PairForm::form`] to beat the transform.
    pub fn worth(&self, n: usize) -> bool {
        n <= self.max_pixels
    }

    /// `factor`·Σₖ aₖ(𝒦a)ₖ for `a` zero but at `points` (row x, column y, value), listed in
    /// row-major order: per pixel k, aₖ(aₖ𝒦₀ + 2 Σ_{l>k} a_l 𝒦(x_l − x_k, y_l − y_k)), summed in
    /// order over chunks of 16 pixels, the chunks' partials (in `partials`, resized)
    /// then in order: the same number whatever the thread count.
    pub fn form(&self, points: &[(u32, u32, f64)], partials: &mut Vec<f64>) -> f64 {
        let (table, rows, columns) = (&self.table, &self.rows, &self.columns);
        let ny = columns.len() / 2;
        partials.clear();
        partials.resize(points.len().div_ceil(PAIR_CHUNK), 0.0);
        partials.par_iter_mut().enumerate().for_each(|(c, partial)| {
            let mut sum = 0.0;
            for k in c * PAIR_CHUNK..((c + 1) * PAIR_CHUNK).min(points.len()) {
                let (xk, yk, ak) = points[k];
                // Row-major order: x_l ≥ x_k, so the row offset needs no wrap.
                let columns = &columns[ny - yk as usize..];
                let mut cross = 0.0;
                for &(xl, yl, al) in &points[k + 1..] {
                    cross += al * table[rows[(xl - xk) as usize] + columns[yl as usize]];
                }
                sum += ak * (ak * table[0] + 2.0 * cross);
            }
            *partial = sum;
        });
        partials.iter().sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_a_periodic_map_slides() {
        assert!(Boundary::Periodic.allows_offset(0) && Boundary::Periodic.allows_offset(7));
        assert!(Boundary::Free.allows_offset(0) && !Boundary::Free.allows_offset(1));
    }

    /// Midpoint-rule quadrature of 1/(π E* r) over a pixel, for offsets away from the pixel.
    fn quadrature(x: f64, y: f64, dx: f64, e: f64) -> f64 {
        let m = 200;
        let h = dx / m as f64;
        let mut s = 0.0;
        for a in 0..m {
            for b in 0..m {
                let (u, v) = (x - 0.5 * dx + (a as f64 + 0.5) * h, y - 0.5 * dx + (b as f64 + 0.5) * h);
                s += h * h / (u * u + v * v).sqrt();
            }
        }
        s / (PI * e)
    }

    #[test]
    fn pixel_influence_is_love_solution() {
        let (dx, e) = (0.5, 2.0);
        // At the centre: 4 dx asinh(1) / (π E*) (Johnson, eq. 3.25 at the centre of a square).
        let centre = pixel_influence(0.0, 0.0, dx, e);
        assert!((centre - 4.0 * dx * 1f64.asinh() / (PI * e)).abs() < 1e-14);
        for (x, y) in [(1.0, 0.0), (0.7, -1.3), (-2.0, 3.0)] {
            let (exact, q) = (pixel_influence(x, y, dx, e), quadrature(x, y, dx, e));
            assert!((exact - q).abs() < 1e-5 * q, "({x}, {y}): {exact} vs {q}");
        }
        // Far away the pixel acts as a point load dx²: dx²/(π E* r), to O((dx/r)²).
        let far = pixel_influence(40.0, 30.0, dx, e);
        assert!((far - dx * dx / (PI * e * 50.0)).abs() < 1e-4 * far);
        // Even in both offsets.
        assert_eq!(pixel_influence(0.7, -1.3, dx, e), pixel_influence(-0.7, 1.3, dx, e));
    }

    /// Dense sum u_i = Σ_j 𝒦(x_i − x_j) p_j over the map, without any periodic image.
    fn dense(p: &[f64], nx: usize, ny: usize, dx: f64, e: f64) -> Vec<f64> {
        let mut u = vec![0.0; nx * ny];
        for i in 0..nx {
            for j in 0..ny {
                let mut s = 0.0;
                for k in 0..nx {
                    for l in 0..ny {
                        let (x, y) = ((i as f64 - k as f64) * dx, (j as f64 - l as f64) * dx);
                        s += pixel_influence(x, y, dx, e) * p[k * ny + l];
                    }
                }
                u[i * ny + j] = s;
            }
        }
        u
    }

    #[test]
    fn free_boundary_is_the_dense_boussinesq_sum_on_square_and_rectangular_maps() {
        for (nx, ny) in [(16usize, 16usize), (20, 16), (16, 18)] {
            let grid = Grid::new(nx, ny, 1.3).unwrap();
            let e = 0.8;
            let mut op = Influence::new(grid, e, Boundary::Free).unwrap();
            let p: Vec<f64> = (0..nx * ny).map(|k| ((k * 7919) % 23) as f64 / 23.0).collect();
            let mut u = vec![0.0; nx * ny];
            op.apply(&p, &mut u);
            let expected = dense(&p, nx, ny, grid.pixel_size(), e);
            let scale = expected.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for (a, b) in u.iter().zip(&expected) {
                assert!((a - b).abs() < 1e-12 * scale, "{nx}×{ny}: {a} vs {b}");
            }
            assert_eq!(op.self_influence(), pixel_influence(0.0, 0.0, grid.pixel_size(), e));
        }
    }

    #[test]
    fn free_boundary_sees_no_periodic_image() {
        // A load on the first column displaces the last column as a load 15 pixels away, not 1.
        let (n, e) = (16, 1.0);
        let grid = Grid::square(n, 1.0).unwrap();
        let dx = grid.pixel_size();
        let mut p = vec![0.0; n * n];
        p[3 * n] = 1.0;
        let mut u = vec![0.0; n * n];
        let mut op = Influence::new(grid, e, Boundary::Free).unwrap();
        op.apply(&p, &mut u);
        let far = u[3 * n + n - 1];
        assert!((far - pixel_influence(0.0, 15.0 * dx, dx, e)).abs() < 1e-12 * far);
        assert!(u.iter().all(|&v| v > 0.0));
    }

    #[test]
    fn hooks_see_the_map_rows_of_both_boundaries() {
        let (nx, ny) = (16usize, 18usize);
        let grid = Grid::new(nx, ny, 1.0).unwrap();
        let p: Vec<f64> = (0..nx * ny).map(|k| (k as f64 * 0.37).sin().abs()).collect();
        for boundary in [Boundary::Periodic, Boundary::Free] {
            let mut op = Influence::new(grid, 1.0, boundary).unwrap();
            let mut plain = vec![0.0; nx * ny];
            op.apply(&p.iter().map(|v| 2.0 * v).collect::<Vec<_>>(), &mut plain);
            // `pre` doubles each row; `post` sums each output row.
            let (mut hooked, mut sums) = (vec![0.0; nx * ny], vec![0.0; nx]);
            op.apply_with(
                &p,
                |_, row| row.iter_mut().for_each(|v| *v *= 2.0),
                &mut hooked,
                |_, row| row.iter().sum::<f64>(),
                Some(&mut sums),
            );
            assert_eq!(plain, hooked, "{boundary:?}");
            for (i, s) in sums.iter().enumerate() {
                assert!((s - plain[i * ny..(i + 1) * ny].iter().sum::<f64>()).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn boundary_names_round_trip_and_others_are_refused() {
        for b in [Boundary::Periodic, Boundary::Free] {
            assert_eq!(b.name().parse::<Boundary>().unwrap(), b);
        }
        assert!("open"
            .parse::<Boundary>()
            .unwrap_err()
            .to_string()
            .contains("`boundary`"));
    }

    /// The pair sum of a field with few nonzero pixels is its quadratic form by the transform, on
    /// a grid that is not square, whatever the thread count; a field with too many pixels is left to
    /// the transform.
    #[test]
    fn the_pair_sum_of_a_sparse_field_is_its_quadratic_form() {
        let grid = Grid::new(64, 40, 3.0).unwrap();
        let nn = grid.pixels();
        let mut influence = Influence::new(grid, 2.5, Boundary::Periodic).unwrap();
        let (mut a, mut b) = (vec![0.0; nn], vec![0.0; nn]);
        let form = PairForm::new(&mut influence, 0.25, &mut a, &mut b).unwrap();
        assert!(a.iter().chain(&b).all(|&v| v == 0.0), "the work fields are left zero");
        let mut field = vec![0.0; nn];
        let mut points = Vec::new();
        for k in 0..30 {
            // Pixels in two chunks, some in one row, some near the wrap of a row or of the grid.
            let pixel = (k * 83 + k * k) % nn;
            field[pixel] = (k as f64 * 0.7).sin() + 0.1;
        }
        for (pixel, &v) in field.iter().enumerate().filter(|(_, &v)| v != 0.0) {
            points.push(((pixel / 40) as u32, (pixel % 40) as u32, v));
        }
        let by_transform = influence.quadratic_form_with(&field, |_, _| {}, 0.25);
        let on = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| form.form(&points, &mut Vec::new()))
        };
        let by_pairs = on(1);
        assert!(
            (by_pairs - by_transform).abs() <= 1e-12 * by_transform.abs(),
            "{by_pairs} against {by_transform}"
        );
        assert!(points.len() > 16, "more than one chunk");
        assert_eq!(by_pairs.to_bits(), on(4).to_bits());
        assert!(form.worth(points.len()) && !form.worth(nn / 8));
        assert!(PairForm::new(
            &mut Influence::new(grid, 2.5, Boundary::Free).unwrap(),
            1.0,
            &mut a,
            &mut b
        )
        .is_none());
    }
}
