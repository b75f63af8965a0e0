//! The elastic field beneath the surface: the stresses a surface pressure causes in the half-space
//! at a given depth (Boussinesq's problem, solved per wavevector in Fourier space), their von Mises
//! equivalent, and the graded layers through the depth on which the volume is sampled.
//!
//! This is the elastic half of the Fourier-accelerated volume-integral method of Frérot, Bonnet,
//! Molinari & Anciaux (CMAME 2019) for elastic–plastic (J2) contact: the pressure of a contact
//! solve gives the trial stresses layer by layer, and where their von Mises stress exceeds the
//! yield strength the saturated-pressure model of the paper (§2) stops being the elastic–plastic
//! solution it approximates. With no plastic strain yet, it says where and how far beneath the
//! contact yield begins.
//!
//! For a wavevector k = (k₁, k₂), q = |k|, and the transform p̂ of the pressure (compressive
//! positive), the stresses at depth z ≥ 0 are, with E = e^{−qz}:
//!
//! - σ̂_zz = −p̂ (1 + qz) E, σ̂_xz = i k₁ z p̂ E, σ̂_yz = i k₂ z p̂ E;
//! - σ̂_xx = −p̂ [(1 − qz) k₁²/q² + 2ν k₂²/q²] E, σ̂_yy = −p̂ [(1 − qz) k₂²/q² + 2ν k₁²/q²] E,
//!   σ̂_xy = −p̂ (1 − qz − 2ν) (k₁k₂/q²) E:
//!
//! the plane-strain solution of a sinusoidal pressure (Johnson, Contact Mechanics §2.6) turned into
//! the direction of k. The mean pressure p̄ (q = 0) of a periodic box compresses it in uniaxial
//! strain: σ_zz = −p̄, σ_xx = σ_yy = −ν/(1 − ν) p̄ at every depth.

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

/// Boussinesq's stresses beneath a periodic surface pressure, one depth at a time: the pressure's
/// transform is taken once ([`SubsurfaceStress::set_pressure`]), each depth costs six inverse
/// transforms.
pub struct SubsurfaceStress {
    grid: Grid,
    poisson_ratio: f64,
    plan: FftPlan,
    /// The pressure's transform, in the plan's transposed half-spectrum layout.
    pressure: Vec<C64>,
}

impl SubsurfaceStress {
    /// For pressures on `grid` over a half-space of Poisson's ratio `poisson_ratio`.
    pub fn new(grid: Grid, poisson_ratio: f64) -> Result<Self> {
        if !(poisson_ratio > -1.0 && poisson_ratio < 0.5) {
            return Err(Error::param(
                "poisson_ratio",
                format!("{poisson_ratio} is outside (−1, 0.5), the range of an isotropic elastic solid"),
            ));
        }
        let plan = FftPlan::new(grid.nx(), grid.ny());
        let pressure = vec![C64::new(0.0, 0.0); plan.spectrum().len()];
        Ok(Self {
            grid,
            poisson_ratio,
            plan,
            pressure,
        })
    }

    /// Takes the transform of `pressure` (Nx·Ny values, compressive positive, row-major).
    pub fn set_pressure(&mut self, pressure: &[f64]) -> Result<()> {
        if pressure.len() != self.grid.pixels() {
            return Err(Error::param(
                "pressure",
                format!("{} values for a grid of {} pixels", pressure.len(), self.grid.pixels()),
            ));
        }
        if let Some(bad) = pressure.iter().position(|p| !p.is_finite()) {
            return Err(Error::param("pressure", format!("pixel {bad} is not a finite number")));
        }
        self.plan.forward(pressure);
        self.pressure.copy_from_slice(self.plan.spectrum());
        Ok(())
    }

    /// The stresses at depth `depth` ≥ 0 (module documentation) of the pressure last set.
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
        let nu = self.poisson_ratio;
        let uniaxial = nu / (1.0 - nu);
        let components: [(&mut Vec<f64>, Component); 6] = [
            (&mut out.xx, Component::Xx),
            (&mut out.yy, Component::Yy),
            (&mut out.zz, Component::Zz),
            (&mut out.yz, Component::Yz),
            (&mut out.xz, Component::Xz),
            (&mut out.xy, Component::Xy),
        ];
        for (field, component) in components {
            let mean = match component {
                Component::Zz => -1.0,
                Component::Xx | Component::Yy => -uniaxial,
                _ => 0.0,
            };
            self.fill(depth, component, mean);
            self.plan.inverse(field);
            let scale = 1.0 / n as f64;
            field.iter_mut().for_each(|v| *v *= scale);
        }
        Ok(out)
    }

    /// The plan's spectrum ← the multiplier of `component` at `depth` times the pressure's
    /// transform; `mean` is the multiplier of the q = 0 mode.
    fn fill(&mut self, depth: f64, component: Component, mean: f64) {
        let (nx, ny) = (self.grid.nx(), self.grid.ny());
        let (two_pi_x, two_pi_y) = (2.0 * PI / self.grid.length_x(), 2.0 * PI / self.grid.length_y());
        let stride = self.plan.row_stride();
        let nu = self.poisson_ratio;
        let pressure = &self.pressure;
        let spectrum = self.plan.spectrum_mut();
        for qy in 0..=ny / 2 {
            let k2 = two_pi_y * qy as f64;
            for qx in 0..nx {
                let k1 = two_pi_x * wavenumber(qx, nx);
                let at = qy * stride + qx;
                // An odd multiplier has no value of its own at a Nyquist wavenumber (its sign is
                // that of a wavevector and its opposite at once): left out there.
                let nyquist = qx == nx / 2 || qy == ny / 2;
                let m = if qx == 0 && qy == 0 {
                    C64::new(mean, 0.0)
                } else {
                    multiplier(component, k1, k2, depth, nu, nyquist)
                };
                spectrum[at] = m * pressure[at];
            }
        }
    }
}

/// A component of the stress tensor.
#[derive(Clone, Copy)]
enum Component {
    Xx,
    Yy,
    Zz,
    Yz,
    Xz,
    Xy,
}

/// The Boussinesq multiplier of `component` for wavevector (k₁, k₂) ≠ 0 at depth `z` (module
/// documentation); 0 for an odd one at a Nyquist wavenumber.
fn multiplier(component: Component, k1: f64, k2: f64, z: f64, nu: f64, nyquist: bool) -> C64 {
    let q = k1.hypot(k2);
    let decay = (-q * z).exp();
    let (c1, c2) = (k1 * k1 / (q * q), k2 * k2 / (q * q));
    let real = |v: f64| C64::new(v * decay, 0.0);
    match component {
        Component::Zz => real(-(1.0 + q * z)),
        Component::Xx => real(-((1.0 - q * z) * c1 + 2.0 * nu * c2)),
        Component::Yy => real(-((1.0 - q * z) * c2 + 2.0 * nu * c1)),
        Component::Xy if nyquist => C64::new(0.0, 0.0),
        Component::Xy => real(-(1.0 - q * z - 2.0 * nu) * k1 * k2 / (q * q)),
        Component::Xz if nyquist => C64::new(0.0, 0.0),
        Component::Xz => C64::new(0.0, k1 * z * decay),
        Component::Yz if nyquist => C64::new(0.0, 0.0),
        Component::Yz => C64::new(0.0, k2 * z * decay),
    }
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

    /// Hertz's pressure p₀√(1 − r²/a²) on a box 16 a wide: on the axis, σ_z = −p₀/(1 + z²/a²) and
    /// σ_r = −p₀[(1 + ν)(1 − (z/a) atan(a/z)) − 1/(2(1 + z²/a²))] (Johnson, Contact Mechanics
    /// §4.2), and yield by von Mises begins at z = 0.48 a where √(3J₂) = 0.62 p₀ for ν = 0.3
    /// (Johnson §6.2: first yield at p₀ = 1.60 σ_y), to the discretisation's few per cent.
    #[test]
    fn beneath_a_hertzian_pressure_yield_begins_where_johnson_says() {
        let (n, a, p0, nu) = (256usize, 1.0, 1.0, 0.3);
        let length = 16.0 * a;
        let grid = Grid::square(n, length).unwrap();
        let dx = length / n as f64;
        // The centre on a pixel: the axis is pixel (n/2, n/2).
        let pressure: Vec<f64> = (0..n * n)
            .map(|i| {
                let (x, y) = (
                    ((i / n) as f64 - (n / 2) as f64) * dx,
                    ((i % n) as f64 - (n / 2) as f64) * dx,
                );
                let r2 = (x * x + y * y) / (a * a);
                if r2 < 1.0 {
                    p0 * (1.0 - r2).sqrt()
                } else {
                    0.0
                }
            })
            .collect();
        let axis = (n / 2) * n + n / 2;
        let mut field = SubsurfaceStress::new(grid, nu).unwrap();
        field.set_pressure(&pressure).unwrap();
        let (mut peak, mut peak_depth) = (0.0, 0.0);
        for step in 1..=40 {
            let z = 0.05 * step as f64 * a;
            let s = field.layer(z).unwrap();
            let [xx, yy, zz, ..] = s.at(axis);
            let t = z / a;
            let sigma_z = -p0 / (1.0 + t * t);
            let sigma_r = -p0 * ((1.0 + nu) * (1.0 - t * (1.0 / t).atan()) - 0.5 / (1.0 + t * t));
            assert!((zz - sigma_z).abs() < 0.005 * p0, "z = {z}: σ_z {zz} against {sigma_z}");
            assert!((xx - sigma_r).abs() < 0.005 * p0, "z = {z}: σ_r {xx} against {sigma_r}");
            assert!((xx - yy).abs() < 1e-9 * p0, "axisymmetric on the axis");
            let mises = von_mises(s.at(axis));
            if mises > peak {
                (peak, peak_depth) = (mises, z);
            }
        }
        assert!((peak / p0 - 0.6200).abs() < 0.005, "peak √(3J₂) = {peak} p₀");
        assert!((peak_depth / a - 0.48).abs() <= 0.05, "at z = {peak_depth} a");
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
        let err = field.set_pressure(&[0.0; 10]).unwrap_err().to_string();
        assert!(err.contains("pressure") && err.contains("256 pixels"), "{err}");
        let mut nan = vec![0.0; 256];
        nan[5] = f64::NAN;
        assert!(field.set_pressure(&nan).unwrap_err().to_string().contains("pixel 5"));
        assert!(field.layer(-1.0).unwrap_err().to_string().contains("depth"));
    }
}
