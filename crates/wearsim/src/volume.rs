//! The elastic field beneath the surface: the stresses that surface tractions — a pressure, and
//! shear tractions where there are — cause in the half-space at a given depth (the problems of
//! Boussinesq and Cerruti, solved per wavevector in Fourier space), their von Mises equivalent, and
//! the graded layers through the depth on which the volume is sampled.
//!
//! With [`EigenstrainStress`], the stress of a plastic strain in the layers, these are the two
//! operators of the Fourier-accelerated volume-integral method of Frérot, Bonnet, Molinari &
//! Anciaux (CMAME 2019) for elastic–plastic (J2) contact: the pressure of a contact solve gives the
//! trial stresses layer by layer, the plastic strain its own, and where their von Mises stress
//! exceeds the yield strength the saturated-pressure model of the wear model (Brink, Frérot &
//! Molinari 2021, §2) stops being the elastic–plastic solution it approximates. The shear
//! tractions are those that free the surface of an eigenstrain's stress. With no plastic strain
//! yet, the surface tractions alone say where and how far beneath the contact yield begins.
//!
//! A traction varying as e^{ik·x} along the surface gives, in the frame x′ along k and y′ across
//! it (q = |k|, z ≥ 0 the depth, E = e^{−qz}), the plane-strain fields of a sinusoidal traction
//! (from Airy's stress function (A + Bz) e^{−qz} e^{iqx′}, A and B set by the surface conditions)
//! and an anti-plane one (a harmonic displacement along y′):
//!
//! - a pressure p̂ (compressive positive): σ_x′x′ = −(1 − qz)E p̂, σ_y′y′ = −2νE p̂,
//!   σ_zz = −(1 + qz)E p̂, σ_x′z = i qz E p̂;
//! - a shear traction τ̂ along x′: σ_x′x′ = i(2 − qz)E τ̂, σ_y′y′ = 2iνE τ̂, σ_zz = i qz E τ̂,
//!   σ_x′z = −(1 − qz)E τ̂;
//! - a shear traction τ̂ along y′: σ_y′z = −E τ̂, σ_x′y′ = iE τ̂;
//!
//! turned back into x, y. The mean traction (q = 0) of a periodic box strains it uniformly: a
//! pressure p̄ in uniaxial strain (σ_zz = −p̄, σ_xx = σ_yy = −ν/(1 − ν) p̄), a shear traction in
//! simple shear (σ_xz = −τ̄_x, σ_yz = −τ̄_y), at every depth.

use std::f64::consts::PI;

use crate::error::{Error, Result};
use crate::fft::{wavenumber, FftPlan, C64};
use crate::grid::Grid;

/// The six components of a stress field at one depth, each Nx·Ny values row-major as the pressure.
#[derive(Debug, Clone, PartialEq)]
pub struct StressLayer {
    /// The depth z beneath the surface (length unit of the grid).
    pub depth: f64,
    pub xx: Vec<f64>,
    pub yy: Vec<f64>,
    pub zz: Vec<f64>,
    pub yz: Vec<f64>,
    pub xz: Vec<f64>,
    pub xy: Vec<f64>,
}

impl StressLayer {
    /// The stress tensor at pixel `i`: (σ_xx, σ_yy, σ_zz, σ_yz, σ_xz, σ_xy).
    pub fn at(&self, i: usize) -> [f64; 6] {
        [self.xx[i], self.yy[i], self.zz[i], self.yz[i], self.xz[i], self.xy[i]]
    }

    /// The von Mises equivalent stress of every pixel ([`von_mises`]).
    pub fn von_mises(&self) -> Vec<f64> {
        (0..self.xx.len()).map(|i| von_mises(self.at(i))).collect()
    }
}

/// The von Mises equivalent stress √(3 J₂) of (σ_xx, σ_yy, σ_zz, σ_yz, σ_xz, σ_xy): the stress
/// that the J2 yield criterion compares with the yield strength σ_y.
pub fn von_mises(s: [f64; 6]) -> f64 {
    let [xx, yy, zz, yz, xz, xy] = s;
    (0.5 * ((xx - yy).powi(2) + (yy - zz).powi(2) + (zz - xx).powi(2)) + 3.0 * (yz * yz + xz * xz + xy * xy)).sqrt()
}

/// The stresses beneath periodic surface tractions (a pressure, and shear tractions where given),
/// one depth at a time: the tractions' transforms are taken once
/// ([`SubsurfaceStress::set_tractions`]), each depth costs six inverse transforms.
pub struct SubsurfaceStress {
    grid: Grid,
    poisson_ratio: f64,
    plan: FftPlan,
    /// The transforms of the pressure and of the shear tractions along x and y (empty where none
    /// was given), in the plan's transposed half-spectrum layout.
    tractions: [Vec<C64>; 3],
}

impl SubsurfaceStress {
    /// For tractions on `grid` over a half-space of Poisson's ratio `poisson_ratio`.
    pub fn new(grid: Grid, poisson_ratio: f64) -> Result<Self> {
        crate::check::poisson_ratio(poisson_ratio)?;
        let plan = FftPlan::new(grid.nx(), grid.ny());
        Ok(Self {
            grid,
            poisson_ratio,
            plan,
            tractions: [Vec::new(), Vec::new(), Vec::new()],
        })
    }

    /// Takes the transform of `pressure` (Nx·Ny values, compressive positive, row-major), with no
    /// shear traction.
    pub fn set_pressure(&mut self, pressure: &[f64]) -> Result<()> {
        self.set_tractions(pressure, None)
    }

    /// Takes the transforms of `pressure` (compressive positive) and, where given, of the shear
    /// tractions (τ_x, τ_y) the other body applies to the surface (Nx·Ny values each, row-major):
    /// at the surface σ_zz = −p, σ_xz = −τ_x, σ_yz = −τ_y.
    pub fn set_tractions(&mut self, pressure: &[f64], shear: Option<(&[f64], &[f64])>) -> Result<()> {
        let fields = [Some(pressure), shear.map(|s| s.0), shear.map(|s| s.1)];
        for (field, name) in fields.iter().zip(["pressure", "shear_x", "shear_y"]) {
            let Some(values) = field else { continue };
            if values.len() != self.grid.pixels() {
                return Err(Error::param(
                    name,
                    format!("{} values for a grid of {} pixels", values.len(), self.grid.pixels()),
                ));
            }
            if let Some(bad) = values.iter().position(|p| !p.is_finite()) {
                return Err(Error::param(name, format!("pixel {bad} is not a finite number")));
            }
        }
        for (slot, field) in self.tractions.iter_mut().zip(fields) {
            slot.clear();
            if let Some(values) = field {
                self.plan.forward(values);
                slot.extend_from_slice(self.plan.spectrum());
            }
        }
        Ok(())
    }

    /// The stresses at depth `depth` ≥ 0 (module documentation) of the tractions last set.
    pub fn layer(&mut self, depth: f64) -> Result<StressLayer> {
        if !(depth >= 0.0 && depth.is_finite()) {
            return Err(Error::param("depth", format!("{depth} is not a depth ≥ 0")));
        }
        let n = self.grid.pixels();
        let mut out = StressLayer {
            depth,
            xx: vec![0.0; n],
            yy: vec![0.0; n],
            zz: vec![0.0; n],
            yz: vec![0.0; n],
            xz: vec![0.0; n],
            xy: vec![0.0; n],
        };
        let fields: [&mut Vec<f64>; 6] = [
            &mut out.xx,
            &mut out.yy,
            &mut out.zz,
            &mut out.yz,
            &mut out.xz,
            &mut out.xy,
        ];
        for (component, field) in fields.into_iter().enumerate() {
            self.fill(depth, component);
            self.plan.inverse(field);
            let scale = 1.0 / n as f64;
            field.iter_mut().for_each(|v| *v *= scale);
        }
        Ok(out)
    }

    /// The plan's spectrum ← stress component `component` (in the order of [`StressLayer::at`]) at
    /// `depth`: per wavevector, the sum over the tractions of its multiplier times the traction's
    /// transform.
    fn fill(&mut self, depth: f64, component: usize) {
        let stride = self.plan.row_stride();
        let nu = self.poisson_ratio;
        let tractions = &self.tractions;
        let spectrum = self.plan.spectrum_mut();
        each_wavevector(&self.grid, stride, |at, wavevectors| {
            let share = 1.0 / wavevectors.len() as f64;
            let mut m = [C64::new(0.0, 0.0); 3];
            for &(k1, k2) in wavevectors {
                for (m, v) in m.iter_mut().zip(mode(k1, k2, depth, nu)[component]) {
                    *m += v * share;
                }
            }
            spectrum[at] = tractions
                .iter()
                .zip(m)
                .filter(|(t, _)| !t.is_empty())
                .map(|(t, m)| m * t[at])
                .sum();
        });
    }
}

/// Visits every wavevector of the plan's transposed half spectrum on `grid` (`stride`: the
/// spectrum's row stride): its index there, and the wavevectors (k₁, k₂) whose mean a multiplier
/// takes there: itself, or at a Nyquist wavenumber, where a wavevector and its opposite are one
/// mode, each sign of it (the odd part of a multiplier, a sign, drops out).
fn each_wavevector(grid: &Grid, stride: usize, mut visit: impl FnMut(usize, &[(f64, f64)])) {
    let (nx, ny) = (grid.nx(), grid.ny());
    let (two_pi_x, two_pi_y) = (2.0 * PI / grid.length_x(), 2.0 * PI / grid.length_y());
    for qy in 0..=ny / 2 {
        for qx in 0..nx {
            let (k1, k2) = (two_pi_x * wavenumber(qx, nx), two_pi_y * qy as f64);
            let signs_x: &[f64] = if qx == nx / 2 { &[1.0, -1.0] } else { &[1.0] };
            let signs_y: &[f64] = if qy == ny / 2 { &[1.0, -1.0] } else { &[1.0] };
            let mut wavevectors = [(0.0, 0.0); 4];
            let mut count = 0;
            for &sx in signs_x {
                for &sy in signs_y {
                    wavevectors[count] = (sx * k1, sy * k2);
                    count += 1;
                }
            }
            visit(qy * stride + qx, &wavevectors[..count]);
        }
    }
}

/// The multipliers of the six stress components (rows, in the order of [`StressLayer::at`]) for
/// the three tractions (columns: the pressure, τ_x, τ_y) at wavevector (k₁, k₂) and depth `z`.
/// In the frame x′ along k, y′ across it (c = k₁/q, s = k₂/q), with E = e^{−qz}, the plane-strain
/// solutions of a sinusoidal traction (module documentation): a pressure gives σ_x′x′ =
/// −(1 − qz)E, σ_y′y′ = −2νE, σ_zz = −(1 + qz)E, σ_x′z = i qz E; a shear along x′ gives σ_x′x′ =
/// i(2 − qz)E, σ_y′y′ = 2iνE, σ_zz = i qz E, σ_x′z = −(1 − qz)E; a shear along y′ (anti-plane)
/// gives σ_y′z = −E, σ_x′y′ = iE; then turned back into x, y. The mean (q = 0): uniaxial strain
/// under the pressure, simple shear under the shear tractions.
fn mode(k1: f64, k2: f64, z: f64, nu: f64) -> [[C64; 3]; 6] {
    let zero = C64::new(0.0, 0.0);
    let q = k1.hypot(k2);
    if q == 0.0 {
        let re = |v: f64| C64::new(v, 0.0);
        let uniaxial = -nu / (1.0 - nu);
        return [
            [re(uniaxial), zero, zero],
            [re(uniaxial), zero, zero],
            [re(-1.0), zero, zero],
            [zero, zero, re(-1.0)],
            [zero, re(-1.0), zero],
            [zero, zero, zero],
        ];
    }
    let (c, s, e, qz) = (k1 / q, k2 / q, (-q * z).exp(), q * z);
    let (re, im) = (|v: f64| C64::new(v * e, 0.0), |v: f64| C64::new(0.0, v * e));
    // Per source in the rotated frame: (x′x′, y′y′, zz, y′z, x′z, x′y′).
    let pressure = [re(-(1.0 - qz)), re(-2.0 * nu), re(-(1.0 + qz)), zero, im(qz), zero];
    let along = [im(2.0 - qz), im(2.0 * nu), im(qz), zero, re(-(1.0 - qz)), zero];
    let across = [zero, zero, zero, re(-1.0), zero, im(1.0)];
    // τ_x = c τ_∥ − s τ_⊥ and τ_y = s τ_∥ + c τ_⊥: the shear tractions' sources.
    let shear_x: [C64; 6] = std::array::from_fn(|i| along[i] * c - across[i] * s);
    let shear_y: [C64; 6] = std::array::from_fn(|i| along[i] * s + across[i] * c);
    let mut out = [[zero; 3]; 6];
    for (j, r) in [pressure, shear_x, shear_y].iter().enumerate() {
        let [xx, yy, zz, yz, xz, xy] = *r;
        out[0][j] = xx * (c * c) + yy * (s * s) - xy * (2.0 * c * s);
        out[1][j] = xx * (s * s) + yy * (c * c) + xy * (2.0 * c * s);
        out[2][j] = zz;
        out[3][j] = xz * s + yz * c;
        out[4][j] = xz * c - yz * s;
        out[5][j] = (xx - yy) * (c * s) + xy * (c * c - s * s);
    }
    out
}

/// The stresses that a plastic strain (an eigenstrain ε*, constant through each of the layers)
/// causes in the periodic half-space, at each layer's mid-plane: the second operator of the
/// volume-integral method (module documentation). Each wavevector costs layers² products of 6 × 6
/// kernels: meant for the few tens of layers that method grades. Per wavevector, the infinite body's response to ε* in z > 0 (the
/// inverse transform along k₃ of Eshelby's σ̂ = C:sym(ξ ⊗ N(ξ) C:ε̂* ξ) − C:ε̂*, N the inverse of
/// the acoustic tensor: a local part and terms in k₃ʲ/(k₃² + q²)², integrated exactly over each
/// layer), plus the field of the surface tractions that free the surface z = 0
/// ([`SubsurfaceStress`]'s solutions). The mean strain of a layer (q = 0) is held by the periodic
/// box: no in-plane strain, no traction on planes z = const.
pub struct EigenstrainStress {
    grid: Grid,
    poisson_ratio: f64,
    shear_modulus: f64,
    layers: Layers,
    plan: FftPlan,
}

impl EigenstrainStress {
    /// For eigenstrains on `grid` in `layers` of a half-space of shear modulus `shear_modulus`
    /// and Poisson's ratio `poisson_ratio`.
    pub fn new(grid: Grid, shear_modulus: f64, poisson_ratio: f64, layers: Layers) -> Result<Self> {
        crate::check::poisson_ratio(poisson_ratio)?;
        crate::check::positive("shear_modulus", shear_modulus)?;
        let plan = FftPlan::new(grid.nx(), grid.ny());
        Ok(Self {
            grid,
            poisson_ratio,
            shear_modulus,
            layers,
            plan,
        })
    }

    /// The stress at each layer's mid-plane of the eigenstrain `strain`: per layer, its six tensor
    /// components (xx, yy, zz, yz, xz, xy), Nx·Ny values each.
    pub fn stress(&mut self, strain: &[[Vec<f64>; 6]]) -> Result<Vec<StressLayer>> {
        let (count, n) = (self.layers.bounds.len(), self.grid.pixels());
        let transforms = self.transforms(strain)?;
        let stride = self.plan.row_stride();
        let size = self.plan.spectrum().len();
        let mut out: Vec<[Vec<C64>; 6]> = (0..count)
            .map(|_| std::array::from_fn(|_| vec![C64::new(0.0, 0.0); size]))
            .collect();
        let mids = self.layers.midplanes();
        each_wavevector(&self.grid, stride, |at, wavevectors| {
            let eps: Vec<[C64; 6]> = transforms.iter().map(|t| std::array::from_fn(|m| t[m][at])).collect();
            let share = 1.0 / wavevectors.len() as f64;
            for &(k1, k2) in wavevectors {
                for (t, r) in self.response(k1, k2, &eps, &mids).iter().enumerate() {
                    for (c, v) in r.iter().enumerate() {
                        out[t][c][at] += v * share;
                    }
                }
            }
        });
        let mut layers = Vec::with_capacity(count);
        for (t, spectra) in out.into_iter().enumerate() {
            let mut fields: [Vec<f64>; 6] = std::array::from_fn(|_| vec![0.0; n]);
            for (field, spectrum) in fields.iter_mut().zip(spectra) {
                self.plan.spectrum_mut().copy_from_slice(&spectrum);
                self.plan.inverse(field);
                field.iter_mut().for_each(|v| *v /= n as f64);
            }
            let [xx, yy, zz, yz, xz, xy] = fields;
            layers.push(StressLayer {
                depth: mids[t],
                xx,
                yy,
                zz,
                yz,
                xz,
                xy,
            });
        }
        Ok(layers)
    }

    /// The transforms of each layer's six eigenstrain fields; an error for a wrong count or size.
    fn transforms(&mut self, strain: &[[Vec<f64>; 6]]) -> Result<Vec<[Vec<C64>; 6]>> {
        let (count, n) = (self.layers.bounds.len(), self.grid.pixels());
        if strain.len() != count || strain.iter().flatten().any(|f| f.len() != n) {
            return Err(Error::param(
                "eigenstrain",
                format!("{count} layers of six fields of {n} values are needed"),
            ));
        }
        if strain.iter().flatten().flatten().any(|v| !v.is_finite()) {
            return Err(Error::param("eigenstrain", "a value is not a finite number"));
        }
        Ok(strain
            .iter()
            .map(|layer| {
                std::array::from_fn(|m| {
                    self.plan.forward(&layer[m]);
                    self.plan.spectrum().to_vec()
                })
            })
            .collect())
    }

    /// The normal displacement of the surface, u_z at z = 0 (positive into the body: the surface
    /// sinks), that the eigenstrain `strain` causes: what a plastic strain does to the gap, which
    /// the volume-integral method adds to the heights between contact solves. The mean (q = 0) is
    /// taken with the box's bottom, below the layers, held: u_z(0) = −Σ ε_zz h over the layers.
    pub fn surface_displacement(&mut self, strain: &[[Vec<f64>; 6]]) -> Result<Vec<f64>> {
        let n = self.grid.pixels();
        let transforms = self.transforms(strain)?;
        let stride = self.plan.row_stride();
        let mut spectrum = vec![C64::new(0.0, 0.0); self.plan.spectrum().len()];
        each_wavevector(&self.grid, stride, |at, wavevectors| {
            let eps: Vec<[C64; 6]> = transforms.iter().map(|t| std::array::from_fn(|m| t[m][at])).collect();
            let share = 1.0 / wavevectors.len() as f64;
            for &(k1, k2) in wavevectors {
                spectrum[at] += self.lift(k1, k2, &eps) * share;
            }
        });
        let mut out = vec![0.0; n];
        self.plan.spectrum_mut().copy_from_slice(&spectrum);
        self.plan.inverse(&mut out);
        out.iter_mut().for_each(|v| *v /= n as f64);
        Ok(out)
    }

    /// The transform of u_z(0) at one wavevector (k₁, k₂) of the eigenstrain transforms `eps`: the
    /// infinite body's, plus the surface displacement of the tractions that free z = 0 (under a
    /// pressure p̂, (1 − ν)p̂/(μq); under a shear traction τ̂ along k, −i(1 − 2ν)τ̂/(2μq), from the
    /// plane-strain fields integrated over the depth).
    fn lift(&self, k1: f64, k2: f64, eps: &[[C64; 6]]) -> C64 {
        let (nu, mu) = (self.poisson_ratio, self.shear_modulus);
        let q = k1.hypot(k2);
        let bounds = &self.layers.bounds;
        if q == 0.0 {
            let lambda = 2.0 * mu * nu / (1.0 - 2.0 * nu);
            return bounds
                .iter()
                .zip(eps)
                .map(|(&(a, b), e)| {
                    -((e[0] + e[1] + e[2]) * lambda + e[2] * (2.0 * mu)) / (lambda + 2.0 * mu) * (b - a)
                })
                .sum();
        }
        let kernels = eshelby_kernels(k1, k2, mu, nu);
        let displacement = eshelby_displacement(k1, k2, mu, nu);
        let mut lift = C64::new(0.0, 0.0);
        let mut tractions = [C64::new(0.0, 0.0); 3];
        for (l, &(a, b)) in bounds.iter().enumerate() {
            let integrals = layer_integrals(q, -b, -a);
            for (col, e) in eps[l].iter().enumerate() {
                lift += (0..4).map(|j| displacement[col][j] * integrals[j]).sum::<C64>() * e;
                for (t, row) in tractions.iter_mut().zip([2, 4, 3]) {
                    *t += (0..4).map(|j| kernels[row][col].1[j] * integrals[j]).sum::<C64>() * e;
                }
            }
        }
        let along = tractions[1] * (k1 / q) + tractions[2] * (k2 / q);
        lift + tractions[0] * ((1.0 - nu) / (mu * q)) - along * C64::new(0.0, (1.0 - 2.0 * nu) / (2.0 * mu * q))
    }

    /// The stress transforms at the mid-planes `mids` of one wavevector (k₁, k₂) of the eigenstrain
    /// transforms `eps` (per layer, its six components).
    fn response(&self, k1: f64, k2: f64, eps: &[[C64; 6]], mids: &[f64]) -> Vec<[C64; 6]> {
        let (nu, mu) = (self.poisson_ratio, self.shear_modulus);
        let zero = C64::new(0.0, 0.0);
        let q = k1.hypot(k2);
        if q == 0.0 {
            return eps.iter().map(|e| mean_stress(e, mu, nu)).collect();
        }
        let kernels = eshelby_kernels(k1, k2, mu, nu);
        let bounds = &self.layers.bounds;
        // The infinite body's stress at depth z: the local part inside a layer, the layers' terms.
        let infinite = |z: f64, rows: &[usize]| -> [C64; 6] {
            let mut s = [zero; 6];
            for (l, &(a, b)) in bounds.iter().enumerate() {
                let integrals = layer_integrals(q, z - b, z - a);
                let inside = a < z && z < b;
                for &row in rows {
                    for (col, e) in eps[l].iter().enumerate() {
                        let (local, p) = &kernels[row][col];
                        let mut v: C64 = (0..4).map(|j| p[j] * integrals[j]).sum();
                        if inside {
                            v += local;
                        }
                        s[row] += v * e;
                    }
                }
            }
            s
        };
        // The tractions on z = 0 that the half-space must be freed of: σ_zz, σ_xz, σ_yz there.
        let at_surface = infinite(0.0, &[2, 4, 3]);
        let tractions = [at_surface[2], at_surface[4], at_surface[3]];
        mids.iter()
            .map(|&z| {
                let mut s = infinite(z, &[0, 1, 2, 3, 4, 5]);
                let m = mode(k1, k2, z, nu);
                for (row, v) in s.iter_mut().enumerate() {
                    *v += (0..3).map(|j| m[row][j] * tractions[j]).sum::<C64>();
                }
                s
            })
            .collect()
    }
}

/// The stress of a layer's mean eigenstrain `e` (q = 0) in the periodic box: the layer keeps its
/// in-plane size (ε_xx = ε_yy = ε_xy = 0) and carries no traction on planes z = const
/// (σ_zz = σ_xz = σ_yz = 0), so σ_xx = λ(ε_zz − tr ε*) − 2μ ε*_xx with
/// ε_zz = (λ tr ε* + 2μ ε*_zz)/(λ + 2μ), and σ_xy = −2μ ε*_xy.
fn mean_stress(e: &[C64; 6], mu: f64, nu: f64) -> [C64; 6] {
    let lambda = 2.0 * mu * nu / (1.0 - 2.0 * nu);
    let trace = e[0] + e[1] + e[2];
    let ezz = (trace * lambda + e[2] * (2.0 * mu)) / (lambda + 2.0 * mu);
    let zero = C64::new(0.0, 0.0);
    [
        (ezz - trace) * lambda - e[0] * (2.0 * mu),
        (ezz - trace) * lambda - e[1] * (2.0 * mu),
        zero,
        zero,
        zero,
        e[5] * (-2.0 * mu),
    ]
}

/// A polynomial in k₃ of degree ≤ 4, lowest power first.
type Poly = [f64; 5];

fn poly_add(a: Poly, b: Poly) -> Poly {
    std::array::from_fn(|i| a[i] + b[i])
}

fn poly_scale(a: Poly, c: f64) -> Poly {
    a.map(|v| v * c)
}

fn poly_mul(a: Poly, b: Poly) -> Poly {
    let mut out = [0.0; 5];
    for i in 0..5 {
        for j in 0..5 - i {
            out[i + j] += a[i] * b[j];
        }
    }
    out
}

/// The components of an eigenstrain, in the order of [`StressLayer::at`].
const PAIRS: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)];

/// For the basis eigenstrain of column `col` (ε*_ij = ε*_ji = 1 for the pair `PAIRS[col]`) at
/// wavevector (k₁, k₂): σ* = C:ε*, ξ = (k₁, k₂, k₃) and v = a|ξ|² − ξ(ξ·a)/(2(1 − ν)) with
/// a = σ*ξ, so that the inverse acoustic tensor gives N a = v/(μ|ξ|⁴) and û = −i v/(μ|ξ|⁴).
fn eshelby_terms(k1: f64, k2: f64, mu: f64, nu: f64, col: usize) -> ([[f64; 3]; 3], [Poly; 3], [Poly; 3]) {
    let lambda = 2.0 * mu * nu / (1.0 - 2.0 * nu);
    let xi: [Poly; 3] = [
        [k1, 0.0, 0.0, 0.0, 0.0],
        [k2, 0.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0, 0.0],
    ];
    let xi2: Poly = [k1 * k1 + k2 * k2, 0.0, 1.0, 0.0, 0.0];
    let (i0, j0) = PAIRS[col];
    let mut e = [[0.0; 3]; 3];
    e[i0][j0] = 1.0;
    e[j0][i0] = 1.0;
    let trace = e[0][0] + e[1][1] + e[2][2];
    let star: [[f64; 3]; 3] = std::array::from_fn(|i| {
        std::array::from_fn(|j| 2.0 * mu * e[i][j] + if i == j { lambda * trace } else { 0.0 })
    });
    let a: [Poly; 3] =
        std::array::from_fn(|i| (0..3).fold([0.0; 5], |acc, j| poly_add(acc, poly_scale(xi[j], star[i][j]))));
    let xa = (0..3).fold([0.0; 5], |acc, i| poly_add(acc, poly_mul(xi[i], a[i])));
    let v: [Poly; 3] = std::array::from_fn(|i| {
        poly_add(
            poly_mul(a[i], xi2),
            poly_scale(poly_mul(xi[i], xa), -1.0 / (2.0 * (1.0 - nu))),
        )
    });
    (star, xi, v)
}

/// Per stress component (rows) and eigenstrain component (columns, both in the order of
/// [`StressLayer::at`], an off-diagonal column meaning ε*_ij = ε*_ji = 1): the local coefficient
/// c∞ and p₀ … p₃ of Eshelby's multiplier written c∞ + Σ pⱼ k₃ʲ/(k₃² + q²)² at wavevector
/// (k₁, k₂), from the polynomials in k₃ of its terms times |ξ|⁴: ε|ξ|⁴ = sym(ξ ⊗ v)/μ and
/// σ̂|ξ|⁴ = C:ε|ξ|⁴ − σ*|ξ|⁴ ([`eshelby_terms`]).
fn eshelby_kernels(k1: f64, k2: f64, mu: f64, nu: f64) -> [[(C64, [C64; 4]); 6]; 6] {
    let lambda = 2.0 * mu * nu / (1.0 - 2.0 * nu);
    let xi2: Poly = [k1 * k1 + k2 * k2, 0.0, 1.0, 0.0, 0.0];
    let xi4 = poly_mul(xi2, xi2);
    // Column by column (one basis eigenstrain each), then read by row.
    let columns: [[(C64, [C64; 4]); 6]; 6] = std::array::from_fn(|col| {
        let (star, xi, v) = eshelby_terms(k1, k2, mu, nu, col);
        let strain: [[Poly; 3]; 3] = std::array::from_fn(|i| {
            std::array::from_fn(|j| poly_scale(poly_add(poly_mul(xi[i], v[j]), poly_mul(xi[j], v[i])), 0.5 / mu))
        });
        let strain_trace = poly_add(poly_add(strain[0][0], strain[1][1]), strain[2][2]);
        PAIRS.map(|(i, j)| {
            let mut p = poly_add(poly_scale(strain[i][j], 2.0 * mu), poly_scale(xi4, -star[i][j]));
            if i == j {
                p = poly_add(p, poly_scale(strain_trace, lambda));
            }
            let local = p[4];
            let rest = poly_add(p, poly_scale(xi4, -local));
            (C64::new(local, 0.0), std::array::from_fn(|k| C64::new(rest[k], 0.0)))
        })
    });
    std::array::from_fn(|row| std::array::from_fn(|col| columns[col][row]))
}

/// Per eigenstrain component: p₀ … p₃ of the infinite body's normal displacement
/// û_z = −i v_z/(μ|ξ|⁴) = Σ pⱼ k₃ʲ/(k₃² + q²)² ([`eshelby_terms`]; no local part).
fn eshelby_displacement(k1: f64, k2: f64, mu: f64, nu: f64) -> [[C64; 4]; 6] {
    std::array::from_fn(|col| {
        let (_, _, v) = eshelby_terms(k1, k2, mu, nu, col);
        std::array::from_fn(|j| C64::new(0.0, -v[2][j] / mu))
    })
}

/// ∫ Jⱼ(s) ds over [s₁, s₂] for the inverse transforms along k₃ of k₃ʲ/(k₃² + q²)², j = 0 … 3:
/// J₀ = (1 + q|s|)e^{−q|s|}/(4q³), J₁ = i s e^{−q|s|}/(4q), J₂ = (1 − q|s|)e^{−q|s|}/(4q),
/// J₃ = i sgn(s)(2 − q|s|)e^{−q|s|}/4.
fn layer_integrals(q: f64, s1: f64, s2: f64) -> [C64; 4] {
    // Antiderivatives of J₀ … J₃ (their real factors) on s ≥ 0 and on s ≤ 0, u = qs.
    let above = |s: f64| -> [f64; 4] {
        let u = q * s;
        let e = (-u).exp();
        [
            -(2.0 + u) * e / (4.0 * q.powi(4)),
            -(1.0 + u) * e / (4.0 * q.powi(3)),
            u * e / (4.0 * q * q),
            (u - 1.0) * e / (4.0 * q),
        ]
    };
    let below = |s: f64| -> [f64; 4] {
        let u = q * s;
        let e = u.exp();
        [
            (2.0 - u) * e / (4.0 * q.powi(4)),
            (u - 1.0) * e / (4.0 * q.powi(3)),
            u * e / (4.0 * q * q),
            -(1.0 + u) * e / (4.0 * q),
        ]
    };
    let mut sum = [0.0; 4];
    let mut piece = |f: &dyn Fn(f64) -> [f64; 4], a: f64, b: f64| {
        let (fa, fb) = (f(a), f(b));
        for j in 0..4 {
            sum[j] += fb[j] - fa[j];
        }
    };
    if s1 < 0.0 {
        piece(&below, s1, s2.min(0.0));
    }
    if s2 > 0.0 {
        piece(&above, s1.max(0.0), s2);
    }
    [
        C64::new(sum[0], 0.0),
        C64::new(0.0, sum[1]),
        C64::new(sum[2], 0.0),
        C64::new(0.0, sum[3]),
    ]
}

/// The layers through the depth on which the volume is sampled: `count` layers from the surface to
/// `depth`, thinnest at the top (no thicker than the pixel, where the stresses of the smallest
/// junctions vary) and growing by a constant ratio below, as the volume-integral method grades
/// them.
#[derive(Debug, Clone, PartialEq)]
pub struct Layers {
    /// Each layer's upper and lower depth, from the surface down.
    pub bounds: Vec<(f64, f64)>,
}

impl Layers {
    /// `count` ≥ 1 layers down to `depth` with the top one at most `pixel` thick (and at most an
    /// even share of the depth): the ratio of consecutive thicknesses r ≥ 1 solves
    /// t₀ (rⁿ − 1)/(r − 1) = depth.
    pub fn graded(pixel: f64, depth: f64, count: usize) -> Result<Self> {
        if !(pixel > 0.0 && pixel.is_finite()) {
            return Err(Error::param("pixel", format!("{pixel} is not a length > 0")));
        }
        if !(depth > 0.0 && depth.is_finite()) {
            return Err(Error::param("depth", format!("{depth} is not a depth > 0")));
        }
        if count == 0 {
            return Err(Error::param("layers", "no layer: at least one is needed"));
        }
        let top = pixel.min(depth / count as f64);
        let total = |r: f64| (0..count).map(|i| top * r.powi(i as i32)).sum::<f64>();
        let (mut low, mut high) = (1.0, 2.0);
        while total(high) < depth {
            high *= 2.0;
        }
        // Bisection to the last bits of the ratio: the layers then reach the depth to round-off.
        for _ in 0..200 {
            let mid = 0.5 * (low + high);
            if total(mid) < depth {
                low = mid;
            } else {
                high = mid;
            }
        }
        let ratio = 0.5 * (low + high);
        let mut bounds = Vec::with_capacity(count);
        let mut upper = 0.0;
        for i in 0..count {
            let lower = if i + 1 == count {
                depth
            } else {
                upper + top * ratio.powi(i as i32)
            };
            bounds.push((upper, lower));
            upper = lower;
        }
        Ok(Self { bounds })
    }

    /// The mid-plane depth of each layer.
    pub fn midplanes(&self) -> Vec<f64> {
        self.bounds.iter().map(|(a, b)| 0.5 * (a + b)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sinusoidal pressure p₀ cos(k x) (Westergaard): the plane-strain field of the module
    /// documentation, exactly, at every depth; σ_yy = ν(σ_xx + σ_zz) as plane strain requires.
    #[test]
    fn a_sinusoidal_pressure_gives_the_plane_strain_field() {
        let (n, length, nu, p0, mode) = (32, 2.0, 0.3, 0.7, 3.0);
        let grid = Grid::square(n, length).unwrap();
        let k = 2.0 * PI * mode / length;
        let dx = length / n as f64;
        let pressure: Vec<f64> = (0..n * n).map(|i| p0 * (k * (i / n) as f64 * dx).cos()).collect();
        let mut field = SubsurfaceStress::new(grid, nu).unwrap();
        field.set_pressure(&pressure).unwrap();
        for z in [0.0, 0.05, 0.3, 1.1] {
            let s = field.layer(z).unwrap();
            let decay = (-k * z).exp();
            for i in (0..n * n).step_by(7) {
                let x = (i / n) as f64 * dx;
                let (c, sn) = ((k * x).cos(), (k * x).sin());
                let want = [
                    -p0 * (1.0 - k * z) * decay * c,
                    -nu * p0 * 2.0 * decay * c,
                    -p0 * (1.0 + k * z) * decay * c,
                    0.0,
                    -p0 * k * z * decay * sn,
                    0.0,
                ];
                for (got, want) in s.at(i).iter().zip(want) {
                    assert!(
                        (got - want).abs() < 1e-12 * p0,
                        "z = {z}, pixel {i}: {got} against {want}"
                    );
                }
            }
        }
    }

    /// A sinusoidal shear traction τ₀ cos(k x) along x: the plane-strain field of the module
    /// documentation; along y, the anti-plane one.
    #[test]
    fn sinusoidal_shear_tractions_give_the_plane_strain_and_anti_plane_fields() {
        let (n, length, nu, t0, mode) = (32, 2.0, 0.3, 0.4, 2.0);
        let grid = Grid::square(n, length).unwrap();
        let k = 2.0 * PI * mode / length;
        let dx = length / n as f64;
        let wave: Vec<f64> = (0..n * n).map(|i| t0 * (k * (i / n) as f64 * dx).cos()).collect();
        let zero = vec![0.0; n * n];
        let mut field = SubsurfaceStress::new(grid, nu).unwrap();
        for along_x in [true, false] {
            let shear = if along_x {
                (&wave[..], &zero[..])
            } else {
                (&zero[..], &wave[..])
            };
            field.set_tractions(&zero, Some(shear)).unwrap();
            for z in [0.0, 0.1, 0.6] {
                let s = field.layer(z).unwrap();
                let decay = (-k * z).exp();
                for i in (0..n * n).step_by(5) {
                    let x = (i / n) as f64 * dx;
                    let (c, sn) = ((k * x).cos(), (k * x).sin());
                    let want = if along_x {
                        [
                            t0 * (k * z - 2.0) * decay * sn,
                            -2.0 * nu * t0 * decay * sn,
                            -t0 * k * z * decay * sn,
                            0.0,
                            -t0 * (1.0 - k * z) * decay * c,
                            0.0,
                        ]
                    } else {
                        [0.0, 0.0, 0.0, -t0 * decay * c, 0.0, -t0 * decay * sn]
                    };
                    for (got, want) in s.at(i).iter().zip(want) {
                        assert!(
                            (got - want).abs() < 1e-12 * t0,
                            "z = {z}, pixel {i}: {got} against {want}"
                        );
                    }
                }
            }
        }
    }

    /// Tractions along a diagonal wavevector give the same field as along an axis, turned: the
    /// invariants of the stress (σ_zz, the in-plane trace, the out-of-plane shear's magnitude)
    /// match the axis-aligned solution; and at the surface, for any tractions, σ_zz = −p,
    /// σ_xz = −τ_x and σ_yz = −τ_y pixel by pixel.
    #[test]
    fn turned_wavevectors_and_the_surface_conditions() {
        let (n, length, nu) = (32usize, 1.0, 0.25);
        let grid = Grid::square(n, length).unwrap();
        let dx = length / n as f64;
        let k = 2.0 * PI * 3.0 / length * std::f64::consts::SQRT_2;
        let phase = |i: usize| 2.0 * PI * 3.0 * ((i / n) as f64 + (i % n) as f64) * dx / length;
        let p: Vec<f64> = (0..n * n).map(|i| phase(i).cos()).collect();
        let mut field = SubsurfaceStress::new(grid, nu).unwrap();
        field.set_pressure(&p).unwrap();
        let z = 0.07;
        let s = field.layer(z).unwrap();
        let e = (-k * z).exp();
        for i in (0..n * n).step_by(3) {
            let [xx, yy, zz, yz, xz, _] = s.at(i);
            let (c, sn) = (phase(i).cos(), phase(i).sin());
            assert!((zz + (1.0 + k * z) * e * c).abs() < 1e-12);
            assert!((xx + yy + (1.0 - k * z + 2.0 * nu) * e * c).abs() < 1e-12);
            assert!(((xz * xz + yz * yz).sqrt() - (k * z * e * sn).abs()).abs() < 1e-12);
        }
        // A shear traction along the same diagonal, τ₀ cos(k·x) along k̂: its invariants too.
        let t0 = 0.6;
        let along: Vec<f64> = p.iter().map(|v| t0 * v / std::f64::consts::SQRT_2).collect();
        field.set_tractions(&vec![0.0; n * n], Some((&along, &along))).unwrap();
        let s = field.layer(z).unwrap();
        for i in (0..n * n).step_by(3) {
            let [xx, yy, zz, yz, xz, _] = s.at(i);
            let (c, sn) = (phase(i).cos(), phase(i).sin());
            assert!((zz + t0 * k * z * e * sn).abs() < 1e-12);
            assert!((xx + yy - t0 * (k * z - 2.0 - 2.0 * nu) * e * sn).abs() < 1e-12);
            assert!(((xz * xz + yz * yz).sqrt() - (t0 * (1.0 - k * z) * e * c).abs()).abs() < 1e-12);
        }
        // Any tractions, Nyquist content included: the surface takes them exactly.
        let noise = |seed: u64| -> Vec<f64> {
            (0..n * n)
                .map(|i| ((i as u64 * 2654435761 + seed * 40503) % 1000) as f64 / 1000.0 - 0.3)
                .collect()
        };
        let (p, tx, ty) = (noise(1), noise(2), noise(3));
        field.set_tractions(&p, Some((&tx, &ty))).unwrap();
        let s = field.layer(0.0).unwrap();
        for i in 0..n * n {
            assert!(
                (s.zz[i] + p[i]).abs() < 1e-12 && (s.xz[i] + tx[i]).abs() < 1e-12 && (s.yz[i] + ty[i]).abs() < 1e-12
            );
        }
    }

    /// A uniform pressure compresses the periodic half-space in uniaxial strain at every depth.
    #[test]
    fn the_mean_pressure_is_uniaxial_strain() {
        let grid = Grid::new(16, 32, 1.0).unwrap();
        let mut field = SubsurfaceStress::new(grid, 0.25).unwrap();
        field.set_pressure(&vec![2.0; 512]).unwrap();
        let s = field.layer(3.0).unwrap();
        let [xx, yy, zz, yz, xz, xy] = s.at(37);
        assert!((zz + 2.0).abs() < 1e-14 && (xx + 2.0 / 3.0).abs() < 1e-14 && (yy - xx).abs() < 1e-14);
        assert!(yz.abs() + xz.abs() + xy.abs() < 1e-14);
        assert!((von_mises(s.at(0)) - 4.0 / 3.0).abs() < 1e-13);
    }

    /// A layer's mean eigenstrain: no in-plane strain, no traction on planes z = const.
    #[test]
    fn a_uniform_eigenstrain_keeps_the_layer_in_plane() {
        let grid = Grid::square(16, 1.0).unwrap();
        let layers = Layers::graded(0.1, 0.4, 4).unwrap();
        let (mu, nu) = (1.0, 0.25);
        let lambda = 2.0 * mu * nu / (1.0 - 2.0 * nu);
        let mut strain: Vec<[Vec<f64>; 6]> = (0..4).map(|_| std::array::from_fn(|_| vec![0.0; 256])).collect();
        strain[1][0] = vec![0.01; 256];
        strain[1][5] = vec![0.002; 256];
        let mut operator = EigenstrainStress::new(grid, mu, nu, layers).unwrap();
        let stress = operator.stress(&strain).unwrap();
        let [xx, yy, zz, yz, xz, xy] = stress[1].at(17);
        let ezz = lambda * 0.01 / (lambda + 2.0 * mu);
        assert!((xx - (lambda * (ezz - 0.01) - 2.0 * mu * 0.01)).abs() < 1e-15);
        assert!((yy - lambda * (ezz - 0.01)).abs() < 1e-15 && (xy + 2.0 * mu * 0.002).abs() < 1e-15);
        assert!(zz.abs() + yz.abs() + xz.abs() < 1e-15);
        assert!(stress[0].at(3).iter().chain(&stress[2].at(3)).all(|v| v.abs() < 1e-15));
        // The layer thickens by ε_zz and lifts the surface by as much times its thickness.
        let lift = operator.surface_displacement(&strain).unwrap();
        assert!(lift.iter().all(|u| (u + ezz * 0.1).abs() < 1e-15), "{}", lift[0]);
    }

    #[test]
    fn graded_layers_start_at_the_pixel_and_reach_the_depth() {
        let layers = Layers::graded(0.01, 1.0, 16).unwrap();
        let thickness: Vec<f64> = layers.bounds.iter().map(|(a, b)| b - a).collect();
        assert!((thickness[0] - 0.01).abs() < 1e-15);
        assert!(thickness.windows(2).all(|w| w[1] > w[0]));
        assert_eq!(layers.bounds.last().unwrap().1, 1.0);
        assert!((thickness.iter().sum::<f64>() - 1.0).abs() < 1e-12);
        // Too few layers for the pixel: evenly spread.
        let even = Layers::graded(1.0, 2.0, 4).unwrap();
        assert!(even.bounds.iter().all(|(a, b)| (b - a - 0.5).abs() < 1e-12));
        assert!(Layers::graded(0.01, 1.0, 0).is_err() && Layers::graded(0.0, 1.0, 4).is_err());
        let mid = layers.midplanes();
        assert!(mid[0] > 0.0 && mid.windows(2).all(|w| w[1] > w[0]));
    }

    #[test]
    fn bad_inputs_are_refused_with_the_field_named() {
        let grid = Grid::square(16, 1.0).unwrap();
        let err = SubsurfaceStress::new(grid, 0.5).err().unwrap().to_string();
        assert!(err.contains("poisson_ratio"), "{err}");
        let mut field = SubsurfaceStress::new(grid, 0.3).unwrap();
        let shear = vec![0.0; 12];
        let err = field
            .set_tractions(&[0.0; 256], Some((&shear, &shear)))
            .unwrap_err()
            .to_string();
        assert!(err.contains("shear_x") && err.contains("256 pixels"), "{err}");
        let err = field.set_pressure(&[0.0; 10]).unwrap_err().to_string();
        assert!(err.contains("pressure") && err.contains("256 pixels"), "{err}");
        let mut nan = vec![0.0; 256];
        nan[5] = f64::NAN;
        assert!(field.set_pressure(&nan).unwrap_err().to_string().contains("pixel 5"));
        assert!(field.layer(-1.0).unwrap_err().to_string().contains("depth"));
    }
}
