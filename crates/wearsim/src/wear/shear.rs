//! The elastic energy stored by shearing the junctions of a step, for the particle rule of
//! interacting micro-contacts (Aghababaei, Warner & Molinari 2016; Pham-Ba, Brink & Molinari 2020;
//! Pham-Ba & Molinari 2021).
//!
//! While the surfaces slide, every junction carries the junction shear strength τ̃ along the sliding
//! direction x. The tangential surface displacement of the elastic half-space under a tangential
//! traction q_x is, in Fourier space (the Cerruti solution, Johnson, *Contact Mechanics* §3.6),
//!
//! û_x(k) = (1 − ν k_x²/|k|²) q̂_x(k) / (μ |k|),
//!
//! with the k = 0 mode set to zero as for the normal problem (the box's rigid translation), so the
//! energy is that of the periodic box with the mean shear taken out. The energy stored under a set S
//! of loaded pixels is E(S) = ½ ∫_S τ̃ u_x dA = (τ̃² Δx³/μ)·½ Σ_{k,l ∈ S} C(k − l), with C the
//! compliance above sampled on the grid in pixel units (C(0) the pixel's own). Only ratios of such
//! energies enter the rule, so the factor τ̃² Δx³/μ is left out: [`ShearCompliance`] is C for
//! μ = Δx = 1.

use crate::fft::FftPlan;
use crate::junctions::{Junction, JunctionLabeller};

/// The periodic tangential compliance C of an Nx × Ny box (x along the sliding direction): the
/// displacement u_x at every pixel under a unit traction q_x on pixel (0, 0), for μ = Δx = 1 and
/// Poisson ratio ν. One inverse FFT, made once per run.
#[derive(Debug, Clone)]
pub struct ShearCompliance {
    nx: usize,
    ny: usize,
    values: Vec<f64>,
}

impl ShearCompliance {
    /// C on an `nx × ny` grid for Poisson ratio `poisson_ratio`.
    pub fn new(nx: usize, ny: usize, poisson_ratio: f64) -> Self {
        let mut plan = FftPlan::new(nx, ny);
        let (lx, ly) = (nx as f64, ny as f64);
        // `convolve` takes the kernel with the 1/(Nx·Ny) of the inverse transform folded in.
        let nn = lx * ly;
        let kernel = crate::fft::radial_kernel(nx, ny, |qx, qy| {
            if qx == 0.0 && qy == 0.0 {
                return 0.0;
            }
            let (kx, ky) = (
                2.0 * std::f64::consts::PI * qx / lx,
                2.0 * std::f64::consts::PI * qy / ly,
            );
            let k2 = kx * kx + ky * ky;
            (1.0 - poisson_ratio * kx * kx / k2) / k2.sqrt() / nn
        });
        let mut unit = vec![0.0; nx * ny];
        unit[0] = 1.0;
        let mut values = vec![0.0; nx * ny];
        plan.convolve(&unit, &kernel, &mut values);
        Self { nx, ny, values }
    }

    /// C at the pixel offset (dx, dy), periodic.
    #[inline]
    fn at(&self, dx: i32, dy: i32) -> f64 {
        let x = dx.rem_euclid(self.nx as i32) as usize;
        let y = dy.rem_euclid(self.ny as i32) as usize;
        self.values[x * self.ny + y]
    }

    /// ½ Σ_{k,l ∈ a} C(k − l): the energy stored under the pixels `a` loaded alone.
    pub fn self_energy(&self, a: &[(i32, i32)]) -> f64 {
        let mut sum = 0.0;
        for (i, &(xk, yk)) in a.iter().enumerate() {
            sum += 0.5 * self.at(0, 0);
            for &(xl, yl) in &a[i + 1..] {
                sum += self.at(xk - xl, yk - yl);
            }
        }
        sum
    }

    /// ½ Σ_{k,l ∈ a} C(k − l) as ½ Σ_Δ C(Δ) n(Δ), with n(Δ) = #{(k, l) : k − l = Δ} the
    /// autocorrelation of the set, counted by FFT on a zero-padded window twice its extent and
    /// rounded to the integers it is: the same sum as [`ShearCompliance::self_energy`] in
    /// O(W H log(W H)) for a set of W × H pixels instead of O(n²) for its n pixels.
    pub fn self_energy_by_autocorrelation(&self, a: &[(i32, i32)], plans: &mut PlanCache) -> f64 {
        if a.is_empty() {
            return 0.0;
        }
        let (x0, y0) = a
            .iter()
            .fold((i32::MAX, i32::MAX), |(x, y), p| (x.min(p.0), y.min(p.1)));
        let (ex, ey) = extent(a);
        let (w, h) = (ex as usize + 1, ey as usize + 1);
        let (mx, my) = ((2 * w).next_power_of_two().max(2), (2 * h).next_power_of_two().max(2));
        let (plan, buffer) = plans.get(mx, my);
        buffer.fill(0.0);
        for &(x, y) in a {
            buffer[(x - x0) as usize * my + (y - y0) as usize] = 1.0;
        }
        plan.forward(buffer);
        for c in plan.spectrum_mut() {
            *c = crate::fft::C64::new(c.norm_sqr(), 0.0);
        }
        plan.inverse(buffer);
        let scale = 1.0 / (mx * my) as f64;
        let mut sum = 0.0;
        for (i, row) in buffer.chunks(my).enumerate() {
            let dx = if i < mx / 2 { i as i32 } else { i as i32 - mx as i32 };
            if dx.unsigned_abs() as usize >= w {
                continue;
            }
            for (j, &v) in row.iter().enumerate() {
                let count = (v * scale).round();
                if count != 0.0 {
                    let dy = if j < my / 2 { j as i32 } else { j as i32 - my as i32 };
                    sum += count * self.at(dx, dy);
                }
            }
        }
        0.5 * sum
    }

    /// Σ_{k ∈ a, l ∈ b} C(k − l): what loading `a` and `b` together stores beyond their energies
    /// alone (C is even, so the two halves of the quadratic form are equal).
    pub fn cross_energy(&self, a: &[(i32, i32)], b: &[(i32, i32)]) -> f64 {
        let mut sum = 0.0;
        for &(xk, yk) in a {
            for &(xl, yl) in b {
                sum += self.at(xk - xl, yk - yl);
            }
        }
        sum
    }
}

/// FFT plans and their buffers for [`ShearCompliance::self_energy_by_autocorrelation`], by window
/// size (powers of two), made when first needed and kept for the run.
#[derive(Default)]
pub struct PlanCache {
    plans: std::collections::HashMap<(usize, usize), (FftPlan, Vec<f64>)>,
}

impl std::fmt::Debug for PlanCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "PlanCache({} window sizes)", self.plans.len())
    }
}

impl PlanCache {
    fn get(&mut self, mx: usize, my: usize) -> (&mut FftPlan, &mut Vec<f64>) {
        let (plan, buffer) = self
            .plans
            .entry((mx, my))
            .or_insert_with(|| (FftPlan::new(mx, my), vec![0.0; mx * my]));
        (plan, buffer)
    }
}

/// Below this many pixels a junction's self-energy is summed pair by pair; above, through its
/// autocorrelation (the two give the same sum; this is where the FFT becomes the cheaper).
const DIRECT_PIXELS: usize = 256;

/// The geometry of a step's junctions that the interaction of junctions needs: each junction's
/// pixels as grid coordinates unwrapped around its first pixel (minimum image), its centroid, and
/// whether it has a finite extent under half the box; the self-energies under shear, computed when
/// first asked and shared by the rules of every d*.
#[derive(Debug, Default)]
pub struct JunctionGeometry {
    nx: usize,
    ny: usize,
    /// Pixel coordinates, junction after junction (`starts[j]..starts[j + 1]`).
    pixels: Vec<(i32, i32)>,
    starts: Vec<usize>,
    /// Centroid of each junction in unwrapped grid coordinates (pixels).
    centroids: Vec<(f64, f64)>,
    /// The junction's extent is finite and under half the box along x and y.
    finite: Vec<bool>,
    /// ½ Σ C over each junction's own pixels; NaN until computed.
    self_energies: Vec<std::cell::Cell<f64>>,
    plans: std::cell::RefCell<PlanCache>,
    /// Scratch of `fill`: each junction's next free slot in `pixels`, and its first pixel.
    next: Vec<usize>,
    first: Vec<(i32, i32)>,
}

impl JunctionGeometry {
    /// Fills the geometry of the junctions of `labeller` (`junctions` its geometry in lengths).
    pub fn fill(&mut self, labeller: &JunctionLabeller, junctions: &[Junction]) {
        let (nx, ny) = (labeller.nx(), labeller.ny());
        (self.nx, self.ny) = (nx, ny);
        let n = junctions.len();
        let labels = labeller.labels();
        // Counting sort of the contact pixels by junction.
        self.starts.clear();
        self.starts.resize(n + 1, 0);
        for &k in labeller.contact_pixels() {
            self.starts[labels[k as usize] as usize + 1] += 1;
        }
        for j in 0..n {
            self.starts[j + 1] += self.starts[j];
        }
        self.pixels.clear();
        self.pixels.resize(labeller.contact_pixels().len(), (0, 0));
        let (next, first) = (&mut self.next, &mut self.first);
        next.clear();
        next.extend_from_slice(&self.starts[..n]);
        first.clear();
        first.resize(n, (i32::MIN, 0));
        let (hx, hy) = (nx as i32 / 2, ny as i32 / 2);
        for &k in labeller.contact_pixels() {
            let j = labels[k as usize] as usize;
            let (x, y) = ((k as usize / ny) as i32, (k as usize % ny) as i32);
            if first[j].0 == i32::MIN {
                first[j] = (x, y);
            }
            let (x0, y0) = first[j];
            let ux = x0 + minimum_image(x - x0, nx as i32, hx);
            let uy = y0 + minimum_image(y - y0, ny as i32, hy);
            self.pixels[next[j]] = (ux, uy);
            next[j] += 1;
        }
        self.centroids.clear();
        self.finite.clear();
        for (j, junction) in junctions.iter().enumerate() {
            let p = &self.pixels[self.starts[j]..self.starts[j + 1]];
            let (sx, sy) = p
                .iter()
                .fold((0.0, 0.0), |(a, b), &(x, y)| (a + x as f64, b + y as f64));
            let m = p.len().max(1) as f64;
            self.centroids.push((sx / m, sy / m));
            let (x_extent, y_extent) = extent(p);
            self.finite
                .push(!junction.wraps() && 2 * x_extent < nx as i32 && 2 * y_extent < ny as i32);
        }
        self.self_energies.clear();
        self.self_energies.resize_with(n, || std::cell::Cell::new(f64::NAN));
    }

    /// The pixels of junction `j`, unwrapped around its first pixel.
    pub fn pixels(&self, j: usize) -> &[(i32, i32)] {
        &self.pixels[self.starts[j]..self.starts[j + 1]]
    }

    /// Centroid of junction `j` (pixels, unwrapped around its first pixel).
    pub fn centroid(&self, j: usize) -> (f64, f64) {
        self.centroids[j]
    }

    /// Junction `j` has a finite extent under half the box along both axes.
    pub fn is_finite(&self, j: usize) -> bool {
        self.finite[j]
    }

    /// The shift (whole periods, pixels) that brings junction `j` next to point `to` (minimum image
    /// of its centroid).
    pub fn shift_towards(&self, j: usize, to: (f64, f64)) -> (i32, i32) {
        let (cx, cy) = self.centroids[j];
        let (nx, ny) = (self.nx as f64, self.ny as f64);
        let sx = -((cx - to.0) / nx).round() * nx;
        let sy = -((cy - to.1) / ny).round() * ny;
        (sx as i32, sy as i32)
    }

    /// Distance (pixels) between the centroids of `a` and `b`, minimum image.
    pub fn centroid_distance(&self, a: usize, b: usize) -> f64 {
        let ((ax, ay), (bx, by)) = (self.centroids[a], self.centroids[b]);
        let (nx, ny) = (self.nx as f64, self.ny as f64);
        let dx = (ax - bx) - ((ax - bx) / nx).round() * nx;
        let dy = (ay - by) - ((ay - by) / ny).round() * ny;
        dx.hypot(dy)
    }

    /// The box, pixels along x and y.
    pub fn box_pixels(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// ½ Σ C over junction `j`'s own pixels, computed once per step.
    pub fn self_energy(&self, compliance: &ShearCompliance, j: usize) -> f64 {
        let cell = &self.self_energies[j];
        if cell.get().is_nan() {
            let p = self.pixels(j);
            cell.set(if p.len() < DIRECT_PIXELS {
                compliance.self_energy(p)
            } else {
                compliance.self_energy_by_autocorrelation(p, &mut self.plans.borrow_mut())
            });
        }
        cell.get()
    }
}

/// `d` reduced to (−n/2, n/2].
fn minimum_image(d: i32, n: i32, half: i32) -> i32 {
    if d > half {
        d - n
    } else if d <= -half {
        d + n
    } else {
        d
    }
}

/// The extent (max − min) of `p` along x and y.
pub fn extent(p: &[(i32, i32)]) -> (i32, i32) {
    let (mut x0, mut x1, mut y0, mut y1) = (i32::MAX, i32::MIN, i32::MAX, i32::MIN);
    for &(x, y) in p {
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    if p.is_empty() {
        (0, 0)
    } else {
        (x1 - x0, y1 - y0)
    }
}

/// Area (pixels²) of the convex hull of the pixel squares `p` (each pixel the unit square at its
/// coordinates): Andrew's monotone chain over the corners of each row's outermost pixels.
pub fn hull_area(p: &[(i32, i32)]) -> f64 {
    let mut rows: std::collections::BTreeMap<i32, (i32, i32)> = std::collections::BTreeMap::new();
    for &(x, y) in p {
        let e = rows.entry(x).or_insert((y, y));
        (e.0, e.1) = (e.0.min(y), e.1.max(y));
    }
    let mut points: Vec<(i64, i64)> = Vec::with_capacity(rows.len() * 4);
    for (&x, &(y0, y1)) in &rows {
        let (x, y0, y1) = (x as i64, y0 as i64, y1 as i64);
        points.extend([(x, y0), (x + 1, y0), (x, y1 + 1), (x + 1, y1 + 1)]);
    }
    points.sort_unstable();
    points.dedup();
    if points.len() < 3 {
        return 0.0;
    }
    let cross = |o: (i64, i64), a: (i64, i64), b: (i64, i64)| (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0);
    let mut hull: Vec<(i64, i64)> = Vec::with_capacity(points.len() + 1);
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &(i64, i64)>> = if pass == 0 {
            Box::new(points.iter())
        } else {
            Box::new(points.iter().rev())
        };
        for &q in iter {
            while hull.len() >= start + 2 && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0 {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    let twice: i64 = (0..hull.len())
        .map(|i| {
            let (a, b) = (hull[i], hull[(i + 1) % hull.len()]);
            a.0 * b.1 - a.1 * b.0
        })
        .sum();
    twice.unsigned_abs() as f64 / 2.0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The disc of pixels (i − x0)² + (j − y0)² < r².
    fn disc(x0: i32, y0: i32, r2: i32) -> Vec<(i32, i32)> {
        let r = (r2 as f64).sqrt().ceil() as i32;
        let mut out = Vec::new();
        for i in x0 - r..=x0 + r {
            for j in y0 - r..=y0 + r {
                if (i - x0).pow(2) + (j - y0).pow(2) < r2 {
                    out.push((i, j));
                }
            }
        }
        out
    }

    #[test]
    fn the_compliance_is_the_cerruti_displacement_away_from_the_load() {
        // Away from a unit load, u_x = (1/(2πμ)) [(1 − ν)/r + ν x²/r³] (Johnson eq. 3.86a), up to
        // a constant (the periodic images and the zero mean) and the grid's sampling (about 1 % at
        // 12 pixels): differences between points cancel the constant.
        let (n, nu) = (1024, 0.3);
        let c = ShearCompliance::new(n, n, nu);
        let cerruti = |x: i32, y: i32| {
            let r = ((x * x + y * y) as f64).sqrt();
            ((1.0 - nu) / r + nu * (x * x) as f64 / r.powi(3)) / (2.0 * std::f64::consts::PI)
        };
        for ((a, b), (p, q)) in [
            ((12, 0), (0, 12)),
            ((8, 0), (32, 0)),
            ((0, 8), (0, 32)),
            ((9, 9), (24, 24)),
        ] {
            let (grid, exact) = (c.at(a, b) - c.at(p, q), cerruti(a, b) - cerruti(p, q));
            assert!(
                (grid - exact).abs() < 0.03 * exact.abs(),
                "({a}, {b}) − ({p}, {q}): {grid} vs {exact}"
            );
        }
    }

    #[test]
    fn the_energy_of_a_set_is_its_quadratic_form() {
        let c = ShearCompliance::new(64, 64, 0.3);
        let (a, b) = (disc(20, 20, 20), disc(30, 22, 12));
        let both: Vec<(i32, i32)> = a.iter().chain(&b).copied().collect();
        let sum = c.self_energy(&a) + c.self_energy(&b) + c.cross_energy(&a, &b);
        assert!((c.self_energy(&both) - sum).abs() < 1e-12 * sum);
        // Positive definite: Cauchy–Schwarz bounds the cross term.
        assert!(c.cross_energy(&a, &b) <= 2.0 * (c.self_energy(&a) * c.self_energy(&b)).sqrt());
    }

    #[test]
    fn the_self_energy_by_autocorrelation_is_the_pair_sum() {
        let c = ShearCompliance::new(128, 96, 0.3);
        let mut plans = PlanCache::default();
        // A disc, an irregular blob across the periodic edge (negative coordinates), one pixel.
        let blob: Vec<(i32, i32)> = (0..400)
            .filter(|k| (k * 7919) % 13 < 9)
            .map(|k| (k / 23 - 5, k % 23 - 11))
            .collect();
        for set in [disc(40, 40, 150), blob, vec![(3, 4)]] {
            let (direct, fft) = (c.self_energy(&set), c.self_energy_by_autocorrelation(&set, &mut plans));
            assert!((direct - fft).abs() < 1e-12 * direct.abs(), "{direct} vs {fft}");
        }
    }

    #[test]
    fn hull_of_pixel_squares() {
        assert_eq!(hull_area(&[(0, 0)]), 1.0);
        assert_eq!(hull_area(&[(0, 0), (0, 1), (1, 0), (1, 1)]), 4.0);
        // Two pixels on a diagonal: the hexagon around both squares, 2 + 1 = 3.
        assert_eq!(hull_area(&[(0, 0), (1, 1)]), 3.0);
        // Two 2×2 squares 3 pixels apart along x: a 7 × 2 rectangle.
        let p = [(0, 0), (0, 1), (1, 0), (1, 1), (5, 0), (5, 1), (6, 0), (6, 1)];
        assert_eq!(hull_area(&p), 14.0);
    }
}
