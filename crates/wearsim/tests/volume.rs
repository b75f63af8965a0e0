//! The field beneath the surface against closed forms (`wearsim::volume`): Hertz's pressure
//! against Johnson's axis stresses and the depth where yield begins, and a compatible plastic
//! strain, which stresses nothing and moves the surface as its displacement does. Integration tests
//! because they take the optimised library: thousands of layer products per wavevector.

use std::f64::consts::PI;

use wearsim::grid::Grid;
use wearsim::volume::{von_mises, EigenstrainStress, Layers, SubsurfaceStress};

/// Hertz's pressure p₀√(1 − r²/a²) on a box 16 a wide: on the axis, σ_z = −p₀/(1 + z²/a²) and
/// σ_r = −p₀[(1 + ν)(1 − (z/a) atan(a/z)) − 1/(2(1 + z²/a²))] (Johnson, Contact Mechanics
/// §4.2), and yield by von Mises begins at z = 0.48 a where √(3J₂) = 0.620 p₀ for ν = 0.3
/// (Johnson §6.2: first yield at p₀ = 1.60 σ_y), to half a per cent of p₀ at 16 pixels per a.
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

/// The largest stress, over μ times the largest eigenstrain, of a compatible eigenstrain
/// ε* = sym ∇v (v = a wave along (1, 2) decaying as e^{−z/d}) in `count` even layers: a
/// compatible strain is the strain of the displacement v, which stresses nothing.
fn compatible_residual(count: usize) -> (f64, f64) {
    let (n, length, mu, nu, d) = (16usize, 4.0, 1.3, 0.3, 0.5);
    let grid = Grid::square(n, length).unwrap();
    let (k1, k2) = (2.0 * PI / length, 4.0 * PI / length);
    let depth = 12.0 * d;
    let layers = Layers::graded(depth / count as f64, depth, count).unwrap();
    let dx = length / n as f64;
    let strain: Vec<[Vec<f64>; 6]> = layers
        .midplanes()
        .iter()
        .map(|&z| {
            let g = (-z / d).exp();
            let at = |i: usize| {
                let phase = k1 * (i / n) as f64 * dx + k2 * (i % n) as f64 * dx;
                // v = (cos φ, ½ sin φ, 0.7 cos(φ + 0.3)) g(z); its gradient ∂_i v_j.
                let (c, s, c3, s3) = (phase.cos(), phase.sin(), (phase + 0.3).cos(), (phase + 0.3).sin());
                let v = [c * g, 0.5 * s * g, 0.7 * c3 * g];
                let grad = |i: usize| -> [f64; 3] {
                    match i {
                        0 => [-k1 * s * g, 0.5 * k1 * c * g, -0.7 * k1 * s3 * g],
                        1 => [-k2 * s * g, 0.5 * k2 * c * g, -0.7 * k2 * s3 * g],
                        _ => v.map(|w| -w / d),
                    }
                };
                let e = |i: usize, j: usize| 0.5 * (grad(i)[j] + grad(j)[i]);
                [e(0, 0), e(1, 1), e(2, 2), e(1, 2), e(0, 2), e(0, 1)]
            };
            std::array::from_fn(|m| (0..n * n).map(|i| at(i)[m]).collect())
        })
        .collect();
    let largest_strain = strain.iter().flatten().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
    let mut operator = EigenstrainStress::new(grid, mu, nu, layers).unwrap();
    let stress = operator.stress(&strain).unwrap();
    let largest = stress
        .iter()
        .flat_map(|s| (0..n * n).flat_map(move |i| s.at(i)))
        .fold(0.0f64, |a, v| a.max(v.abs()));
    // The surface moves as v does: u_z(0) = v_z(0) = 0.7 cos(φ + 0.3).
    let lift = operator.surface_displacement(&strain).unwrap();
    let moved = (0..n * n).fold(0.0f64, |worst, i| {
        let phase = k1 * (i / n) as f64 * dx + k2 * (i % n) as f64 * dx;
        worst.max((lift[i] - 0.7 * (phase + 0.3).cos()).abs())
    });
    (largest / (mu * largest_strain), moved / 0.7)
}

/// A compatible eigenstrain stresses nothing and moves the surface as v does, to the layers'
/// midpoint rule (second order: the stress residual was 0.084, 0.024, 0.0064 of μ ε* at 30,
/// 60, 120 layers).
#[test]
fn a_compatible_eigenstrain_stresses_nothing() {
    let (coarse, fine) = (compatible_residual(120), compatible_residual(240));
    assert!(fine.0 < 2e-3, "{fine:?}");
    assert!(coarse.0 / fine.0 > 3.5, "second order: {coarse:?} then {fine:?}");
    // The surface displacement is v's at the surface, to the same order.
    assert!(fine.1 < 2e-3, "{fine:?}");
    assert!(coarse.1 / fine.1 > 3.5, "second order: {coarse:?} then {fine:?}");
}
