//! The conformance test of a contact backend: every pass of [`ContactBackend`] and whole solves,
//! run on small grids against a plain reference written from the trait's documentation (serial
//! loops, one pixel at a time, the reductions in their documented order), for both boundaries and
//! for both laws at the surface bound to each (saturated, p_m finite, and elastic, p_m = ∞; a few
//! passes under an enormous finite p_m too); and each pass repeated on one and
//! on two threads, which must agree bit for bit. A new backend passes the conformance test of
//! `contact/mod.rs` (these passes, then whole solves against the reference's) with its own
//! constructor: exactly when it keeps the reductions' order (as the CPU backend does), else within
//! round-off.

use std::sync::Arc;

use super::backend::{contact_bit, ContactBackend, HeightStats, LoadSums, Stats, SurfaceLaw, Update, LOAD_CHUNK};
use super::cpu::CpuBackend;
use crate::grid::Grid;
use crate::influence::{Boundary, Influence, PairForm};
use crate::surface::{composite_heights, Surface};

/// The plain reference: the fields in host vectors, each pass a serial loop over rows and pixels
/// in row-major order, partials per row (per [`LOAD_CHUNK`] pixels for the load sums) combined in
/// order; 𝒦 by [`Influence::apply`].
struct Reference {
    nx: usize,
    ny: usize,
    influence: Influence,
    h: Vec<f64>,
    p: Vec<f64>,
    u: Vec<f64>,
    t: Vec<f64>,
    /// r = 𝒦t_f of the last `advance`.
    r: Vec<f64>,
    p_old: Vec<f64>,
    u_kept: Vec<f64>,
    bits: Vec<u64>,
    surfaces: Option<(Arc<Surface>, Arc<Surface>)>,
    /// The law bound by `bind_law`, elastic until one is.
    law: SurfaceLaw,
    response_scale: f64,
    /// The kernel in real space (periodic), for `direct_curvature`.
    pair_form: Option<PairForm>,
}

impl Reference {
    fn new(grid: Grid, effective_modulus: f64, boundary: Boundary) -> Self {
        let (nx, ny) = (grid.nx(), grid.ny());
        let mut influence = Influence::new(grid, effective_modulus, boundary).unwrap();
        let response_scale = 2f64.powi(influence.self_influence().log2().floor() as i32);
        let field = || vec![0.0; nx * ny];
        let pair_form = PairForm::new(&mut influence, 1.0 / response_scale, &mut field(), &mut field());
        Self {
            nx,
            ny,
            influence,
            h: field(),
            p: field(),
            u: field(),
            t: field(),
            r: field(),
            p_old: field(),
            u_kept: field(),
            bits: vec![0; (nx * ny).div_ceil(64)],
            surfaces: None,
            law: SurfaceLaw::Elastic,
            response_scale,
            pair_form,
        }
    }

    /// t_f: t − `shift` where t ≠ 0, else 0 (`curvature`, `advance`).
    fn shifted_direction(&self, shift: f64) -> Vec<f64> {
        self.t.iter().map(|&t| if t != 0.0 { t - shift } else { t }).collect()
    }

    /// Asserts that `form` is Σ t_f·𝒦t_f / response_scale summed pixel by pixel, to 10⁻¹².
    fn check_form(&mut self, form: f64, shift: f64, what: &str) {
        let shifted = self.shifted_direction(shift);
        let mut r = vec![0.0; shifted.len()];
        self.influence.apply(&shifted, &mut r);
        let sum: f64 = r.iter().zip(&shifted).map(|(r, t)| r / self.response_scale * t).sum();
        assert!(
            (form - sum).abs() <= 1e-12 * sum.abs().max(f64::MIN_POSITIVE),
            "{what} {form} is not Σ t_f·𝒦t_f = {sum}"
        );
    }

    /// Per-row partials of `f(row index, pixel range)`, combined by `combine` in row order.
    fn rows<R>(&self, mut f: impl FnMut(usize, std::ops::Range<usize>) -> R) -> Vec<R> {
        (0..self.nx).map(|i| f(i, i * self.ny..(i + 1) * self.ny)).collect()
    }
}

impl ContactBackend for Reference {
    fn boundary(&self) -> Boundary {
        self.influence.boundary()
    }

    fn self_influence(&self) -> f64 {
        self.influence.self_influence()
    }

    fn apply_influence(&mut self, input: &[f64], out: &mut [f64]) {
        self.influence.apply(input, out);
    }

    fn write_heights(&mut self, fill: &mut dyn FnMut(&mut [f64])) {
        fill(&mut self.h);
    }

    fn bind_surfaces(&mut self, top: Arc<Surface>, bottom: Arc<Surface>) {
        self.surfaces = Some((top, bottom));
    }

    fn compose(&mut self, offset: usize) {
        let (top, bottom) = self.surfaces.as_ref().unwrap();
        composite_heights(top, bottom, offset, &mut self.h);
    }

    fn bind_law(&mut self, law: SurfaceLaw) {
        self.law = law;
    }

    fn write_pressure(&mut self, fill: &mut dyn FnMut(&mut [f64])) {
        fill(&mut self.p);
    }

    fn pressure(&mut self) -> &[f64] {
        &self.p
    }

    fn contact_map(&mut self) -> &[u64] {
        self.bits.fill(0);
        for (k, &p) in self.p.iter().enumerate() {
            if p > 0.0 {
                self.bits[k / 64] |= 1 << (k % 64);
            }
        }
        &self.bits
    }

    fn height_stats(&mut self) -> HeightStats {
        let h0 = self.h[0];
        let rows = self.rows(|_, range| {
            let (mut s, mut q, mut m, mut f) = (0.0, 0.0, f64::NEG_INFINITY, true);
            for &h in &self.h[range] {
                s += h - h0;
                q += (h - h0) * (h - h0);
                m = m.max(h);
                f = f && h.is_finite();
            }
            (s, q, m, f)
        });
        let mut total = (0.0, 0.0, f64::NEG_INFINITY, true);
        for r in rows {
            total = (total.0 + r.0, total.1 + r.1, total.2.max(r.2), total.3 && r.3);
        }
        let not_finite = self.h.iter().position(|h| !h.is_finite()).map(|k| (k, self.h[k]));
        HeightStats {
            sum: total.0,
            sum_sq: total.1,
            max: total.2,
            not_finite,
        }
    }

    fn initial_guess(&mut self, mean_pressure: f64) -> bool {
        let pm = self.law.flow_pressure();
        let usable = self.p.iter().all(|p| p.is_finite() && *p >= 0.0) && self.p.iter().any(|&p| p > 0.0);
        let before = self.p.clone();
        for p in &mut self.p {
            *p = if usable { p.min(pm) } else { mean_pressure };
        }
        usable && self.p.iter().zip(&before).all(|(a, b)| a.to_bits() == b.to_bits())
    }

    fn load_sums(&mut self) -> LoadSums {
        let mut total = LoadSums::default();
        for chunk in self.p.chunks(LOAD_CHUNK) {
            let mut s = LoadSums::default();
            for &p in chunk {
                s.add(p, self.law);
            }
            total = LoadSums::merge(total, s);
        }
        total
    }

    fn saturate_contact(&mut self) {
        for p in self.p.iter_mut().filter(|p| **p > 0.0) {
            *p = self.law.flow_pressure();
        }
    }

    fn scaled_load(&mut self, s: f64, scale_plastic: bool) -> (f64, f64) {
        let (mut total, pm) = ((0.0, 0.0), self.law.flow_pressure());
        for chunk in self.p.chunks(LOAD_CHUNK) {
            let (mut f, mut df) = (0.0, 0.0);
            for &p in chunk {
                if p > 0.0 && (scale_plastic || p < pm) {
                    if s * p >= pm {
                        f += pm;
                    } else {
                        f += s * p;
                        df += p;
                    }
                }
            }
            total = (total.0 + f, total.1 + df);
        }
        total
    }

    fn scale(&mut self, s: f64, scale_plastic: bool) {
        let pm = self.law.flow_pressure();
        for p in &mut self.p {
            if *p > 0.0 && (scale_plastic || *p < pm) {
                *p = (s * *p).min(pm);
            }
        }
    }

    fn spread_missing_load(&mut self, total: f64, mean: f64) {
        let missing = total - self.p.iter().sum::<f64>();
        let penetration = |k: usize| {
            if mean.is_nan() {
                0.0
            } else {
                (mean - (self.u[k] - self.h[k])).max(0.0)
            }
        };
        let (mut weight_sum, mut n_zero) = (0.0, 0usize);
        for k in 0..self.p.len() {
            if self.p[k] <= 0.0 {
                weight_sum += penetration(k);
                n_zero += 1;
            }
        }
        let shares: Vec<Option<f64>> = (0..self.p.len())
            .map(|k| {
                (self.p[k] <= 0.0).then(|| {
                    if weight_sum > 0.0 {
                        missing * penetration(k) / weight_sum
                    } else {
                        missing / n_zero.max(1) as f64
                    }
                })
            })
            .collect();
        for (p, share) in self.p.iter_mut().zip(shares) {
            if let Some(share) = share {
                *p = share.min(self.law.flow_pressure());
            }
        }
    }

    fn displacement_and_stats(&mut self, reference: f64) -> Stats {
        self.influence.apply(&self.p, &mut self.u);
        self.stats(reference)
    }

    fn stats(&mut self, reference: f64) -> Stats {
        let rows = self.rows(|_, range| {
            let mut s = Stats::default();
            for k in range {
                s.add(self.p[k], self.u[k], self.h[k], reference, self.law);
            }
            s
        });
        Stats::combine(&rows)
    }

    fn direction(&mut self, mean: f64, beta: f64) -> (f64, f64) {
        let (mut total, pm) = ((0.0, 0.0), self.law.flow_pressure());
        for i in 0..self.nx {
            let (mut st, mut sdt) = (0.0, 0.0);
            for k in i * self.ny..(i + 1) * self.ny {
                if self.p[k] > 0.0 && self.p[k] < pm {
                    let d = self.u[k] - self.h[k] - mean;
                    self.t[k] = d + beta * self.t[k];
                    st += self.t[k];
                    sdt += d * self.t[k];
                } else {
                    self.t[k] = 0.0;
                }
            }
            total = (total.0 + st, total.1 + sdt);
        }
        total
    }

    fn response_scale(&self) -> f64 {
        self.response_scale
    }

    /// By Parseval's identity (the same transform as the CPU backend's, so that both agree
    /// exactly), checked here against Σ t_f·𝒦t_f summed pixel by pixel.
    fn curvature(&mut self, shift: f64) -> f64 {
        let shifted = self.shifted_direction(shift);
        let form = self
            .influence
            .quadratic_form_with(&shifted, |_, _| {}, 1.0 / self.response_scale);
        self.check_form(form, shift, "curvature");
        form
    }

    /// The free pixels in row-major order and [`PairForm::form`], checked here against
    /// Σ t_f·𝒦t_f summed pixel by pixel.
    fn direct_curvature(&mut self, shift: f64) -> Option<f64> {
        let pair_form = self.pair_form.as_ref()?;
        let points: Vec<(u32, u32, f64)> = (0..self.nx * self.ny)
            .filter(|&k| self.t[k] != 0.0)
            .map(|k| ((k / self.ny) as u32, (k % self.ny) as u32, self.t[k] - shift))
            .collect();
        if !pair_form.worth(points.len()) {
            return None;
        }
        let form = pair_form.form(&points, &mut Vec::new());
        self.check_form(form, shift, "direct curvature");
        Some(form)
    }

    fn update(&mut self, mean: f64, tau: f64, shift: f64) -> Update {
        let (cg_step, pm) = (shift.is_finite(), self.law.flow_pressure());
        self.p_old.copy_from_slice(&self.p);
        let (mut load, mut sums) = (LoadSums::default(), Vec::new());
        let (mut released, mut clipped) = (false, false);
        for i in 0..self.nx {
            let (mut row_load, mut sum_p) = (LoadSums::default(), 0.0);
            for k in i * self.ny..(i + 1) * self.ny {
                let d = self.u[k] - self.h[k] - mean;
                let p = &mut self.p[k];
                if *p <= 0.0 {
                    if d < 0.0 {
                        *p = (-tau * d).min(pm);
                        released = true;
                    }
                } else if *p >= pm {
                    if d > 0.0 {
                        *p = (pm - tau * d).max(0.0);
                        released = true;
                    }
                } else if cg_step && self.t[k] != 0.0 {
                    let q = *p - tau * (self.t[k] - shift);
                    if q <= 0.0 {
                        *p = 0.0;
                        clipped = true;
                    } else if q >= pm {
                        *p = pm;
                        clipped = true;
                    } else {
                        *p = q;
                    }
                }
                sum_p += self.p[k];
                row_load.add(self.p[k], self.law);
            }
            load = LoadSums::merge(load, row_load);
            sums.push(sum_p);
        }
        Update {
            load,
            total: sums.iter().sum(),
            released,
            clipped,
        }
    }

    /// r afresh whether or not a transform was kept (the reference keeps none).
    fn advance(&mut self, mean: f64, tau: f64, shift: f64, _kept: bool) -> Stats {
        let shifted = self.shifted_direction(shift);
        self.influence.apply(&shifted, &mut self.r);
        let mut parts = Vec::with_capacity(self.nx);
        for i in 0..self.nx {
            let mut s = Stats::default();
            for k in i * self.ny..(i + 1) * self.ny {
                self.u[k] -= tau * self.r[k];
                let p = self.p[k];
                s.add(p, self.u[k], self.h[k], mean, self.law);
                // Each pixel's last move, for the settled-map stop.
                s.add_change(p, p - self.p_old[k], self.u[k] - self.h[k], tau * self.r[k]);
            }
            parts.push(s);
        }
        Stats::combine(&parts)
    }

    fn keep_displacement(&mut self) {
        std::mem::swap(&mut self.u, &mut self.u_kept);
    }

    fn undo(&mut self) {
        self.p.copy_from_slice(&self.p_old);
        self.u.copy_from_slice(&self.u_kept);
    }
}

/// A backend's constructor, as `ContactSolver::on_device` calls it.
pub(crate) type MakeBackend = dyn Fn(Grid, f64, Boundary) -> Box<dyn ContactBackend> + Sync;

/// Deterministic values in [0, 1) (a linear congruential sequence).
pub(crate) fn uniform(seed: u64, n: usize) -> Vec<f64> {
    let mut x = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
    (0..n)
        .map(|_| {
            x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (x >> 11) as f64 / (1u64 << 53) as f64
        })
        .collect()
}

/// Two numbers agree: bit for bit when `exact`, else equal (infinities included) or to round-off
/// of `scale`.
fn agree(a: f64, b: f64, exact: bool, scale: f64, what: &str) {
    if exact {
        assert!(
            a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()),
            "{what}: {a:e} vs reference {b:e}"
        );
    } else {
        assert!(
            a == b || (a.is_nan() && b.is_nan()) || (a - b).abs() <= 1e-10 * scale.abs().max(f64::MIN_POSITIVE),
            "{what}: {a:e} vs reference {b:e}"
        );
    }
}

pub(crate) fn agree_fields(a: &[f64], b: &[f64], exact: bool, what: &str) {
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert_eq!(a.len(), b.len(), "{what}");
    for (k, (&x, &y)) in a.iter().zip(b).enumerate() {
        agree(x, y, exact, scale, &format!("{what}[{k}]"));
    }
}

fn agree_loads(a: &LoadSums, b: &LoadSums, exact: bool, what: &str) {
    assert_eq!(a.n_contact, b.n_contact, "{what}.n_contact");
    agree(a.free, b.free, exact, b.free, &format!("{what}.free"));
    agree(a.plastic, b.plastic, exact, b.plastic, &format!("{what}.plastic"));
    agree(a.max_free, b.max_free, exact, b.max_free, &format!("{what}.max_free"));
}

/// A pressure field with every kind of pixel: zero, free (0 < p < p_m) and plastic (p = p_m).
fn mixed_pressure(n: usize, pm: f64, seed: u64) -> Vec<f64> {
    uniform(seed, n)
        .into_iter()
        .map(|x| match x {
            x if x < 0.4 => 0.0,
            x if x < 0.55 && pm.is_finite() => pm,
            x => x * if pm.is_finite() { pm } else { 0.02 },
        })
        .collect()
}

/// Every pass of `backend` against the reference, in the order a solve calls them, on the same
/// inputs; the values each returns and the pressure each leaves agree.
fn passes(backend: &mut dyn ContactBackend, reference: &mut Reference, pm: f64, exact: bool) {
    let nn = reference.nx * reference.ny;
    let (top, bottom) = (surface(reference, 11), surface(reference, 12));
    for b in [&mut *backend, &mut *reference as &mut dyn ContactBackend] {
        b.bind_surfaces(Arc::clone(&top), Arc::clone(&bottom));
        b.compose(3);
        b.bind_law(SurfaceLaw::of_flow_pressure(pm));
    }
    let hs = (backend.height_stats(), reference.height_stats());
    agree(hs.0.sum, hs.1.sum, exact, hs.1.sum_sq.sqrt(), "height_stats.sum");
    agree(hs.0.sum_sq, hs.1.sum_sq, exact, hs.1.sum_sq, "height_stats.sum_sq");
    assert_eq!((hs.0.max, hs.0.not_finite), (hs.1.max, hs.1.not_finite));
    let p0 = mixed_pressure(nn, pm, 5);
    for b in [&mut *backend, &mut *reference as &mut dyn ContactBackend] {
        b.write_pressure(&mut |p| p.copy_from_slice(&p0));
    }
    assert_eq!(backend.contact_map(), reference.contact_map(), "contact_map");
    assert!((0..nn).all(|k| contact_bit(reference.contact_map(), k) == (p0[k] > 0.0)));
    agree_loads(&backend.load_sums(), &reference.load_sums(), exact, "load_sums");
    for (s, plastic) in [(0.7, false), (1.3, false), (1.1, true)] {
        let (a, b) = (backend.scaled_load(s, plastic), reference.scaled_load(s, plastic));
        agree(a.0, b.0, exact, b.0, "scaled_load");
        agree(a.1, b.1, exact, b.1, "scaled_load'");
    }
    iteration_passes(backend, reference, pm, exact);
}

/// The passes of an iteration and of the load balance, in the order a solve calls them, on the
/// fields [`passes`] left.
fn iteration_passes(backend: &mut dyn ContactBackend, reference: &mut Reference, pm: f64, exact: bool) {
    let nn = reference.nx * reference.ny;
    let pm_eff = if pm.is_finite() { pm } else { f64::MAX };
    let mean_pressure = 0.2 * pm_eff.min(0.05);
    let target = mean_pressure * nn as f64;
    let mut run = |f: &mut dyn FnMut(&mut dyn ContactBackend) -> Vec<f64>, what: &str| {
        both(&mut *backend, &mut *reference, exact, f, what)
    };
    run(
        &mut |b| vec![b.displacement_and_stats(0.0).energy],
        "displacement_and_stats",
    );
    run(&mut |b| every_stat(b), "displacement_and_stats");
    run(
        &mut |b| {
            let fresh = every_stat(b);
            let held = stat_values(&b.stats(1e-3));
            let same = fresh.iter().zip(&held).all(|(x, y)| x.to_bits() == y.to_bits());
            assert!(same, "stats of the held u {held:?} are not a fresh 𝒦p's {fresh:?}");
            held
        },
        "stats",
    );
    run(
        &mut |b| {
            b.scale(1.2, false);
            b.spread_missing_load(target, 2e-3);
            vec![]
        },
        "scale, spread_missing_load",
    );
    run(
        &mut |b| {
            b.spread_missing_load(target, f64::NAN);
            vec![b.displacement_and_stats(0.0).sum]
        },
        "spread_missing_load (even)",
    );
    conjugate_steps(&mut *backend, &mut *reference, pm, exact);
    initial_guesses(&mut *backend, &mut *reference, pm_eff, mean_pressure, exact);
    let input = uniform(9, nn);
    let (mut a, mut b) = (vec![0.0; nn], vec![0.0; nn]);
    backend.apply_influence(&input, &mut a);
    reference.apply_influence(&input, &mut b);
    agree_fields(&a, &b, exact, "apply_influence");
}

/// The initial guesses of a solve's set-up, under a finite p_m (`pm_eff`, enormous for the elastic
/// case), from the pressure the conjugate steps left: one kept, one clipped, one replaced.
fn initial_guesses(
    backend: &mut dyn ContactBackend,
    reference: &mut Reference,
    pm_eff: f64,
    mean_pressure: f64,
    exact: bool,
) {
    let nn = reference.nx * reference.ny;
    let mut run = |f: &mut dyn FnMut(&mut dyn ContactBackend) -> Vec<f64>, what: &str| {
        both(&mut *backend, &mut *reference, exact, f, what)
    };
    // initial_guess reports whether p stayed as it was: at p_m it does, above it or unusable not.
    let kept = |k: bool| f64::from(u8::from(k));
    run(
        &mut |b| {
            b.bind_law(SurfaceLaw::Saturated { flow_pressure: pm_eff });
            b.saturate_contact();
            let k = b.initial_guess(mean_pressure);
            assert!(k, "a usable p at or below p_m is kept");
            vec![kept(k), b.load_sums().free]
        },
        "saturate_contact, initial_guess",
    );
    run(
        &mut |b| {
            b.write_pressure(&mut |p| p[nn / 2] = 2.0 * pm_eff.min(0.05));
            b.bind_law(SurfaceLaw::Saturated {
                flow_pressure: pm_eff.min(0.05),
            });
            let k = b.initial_guess(mean_pressure);
            assert!(!k, "a p above p_m is clipped");
            b.bind_law(SurfaceLaw::Saturated { flow_pressure: pm_eff });
            vec![kept(k), b.load_sums().plastic]
        },
        "initial_guess (above p_m)",
    );
    run(
        &mut |b| {
            b.write_pressure(&mut |p| p.fill(-1.0));
            let k = b.initial_guess(mean_pressure);
            assert!(!k, "an unusable p is replaced");
            vec![kept(k)]
        },
        "initial_guess (unusable)",
    );
}

/// Every number `displacement_and_stats` reports (at a gap offset of 10⁻³), its load sums included.
fn every_stat(b: &mut dyn ContactBackend) -> Vec<f64> {
    stat_values(&b.displacement_and_stats(1e-3))
}

/// Conjugate-gradient steps and their undo from a mixed pressure (the load balance before them
/// left no pixel out of contact). Their mean gaps: 1e-3 releases most non-contact pixels (they
/// penetrate); −1 keeps every one out and −5e-3, about half the height range, some of each.
fn conjugate_steps(backend: &mut dyn ContactBackend, reference: &mut Reference, pm: f64, exact: bool) {
    let nn = reference.nx * reference.ny;
    let mut run = |f: &mut dyn FnMut(&mut dyn ContactBackend) -> Vec<f64>, what: &str| {
        both(&mut *backend, &mut *reference, exact, f, what)
    };
    let p1 = mixed_pressure(nn, pm, 6);
    run(
        &mut |b| {
            b.write_pressure(&mut |p| p.copy_from_slice(&p1));
            vec![b.displacement_and_stats(0.0).energy]
        },
        "write_pressure, displacement_and_stats",
    );
    // `advance` follows every CG step here (the solver calls it only after one that changed no
    // set; its arithmetic is the same either way), from the kept transform or afresh.
    for (beta, tau, shift, mean, kept) in [
        (0.0, 0.5, 0.0, 1e-3, true),
        (0.3, 2.0, f64::NAN, 1e-3, true),
        (0.5, 1e3, 1e-4, 1e-3, false),
        (0.2, 0.5, 0.0, -1.0, true),
        (0.4, 2.0, 1e-4, -5e-3, false),
        (0.0, 1.0, f64::NAN, -5e-3, true),
        (0.1, 0.7, 2e-4, -5e-3, true),
    ] {
        run(
            &mut |b| conjugate_step(b, beta, tau, shift, mean, kept),
            "direction, curvature, update, advance",
        );
        run(
            &mut |b| {
                b.keep_displacement();
                let s = b.displacement_and_stats(1e-3);
                b.undo();
                vec![s.energy, b.stats(2e-3).energy, b.displacement_and_stats(2e-3).energy]
            },
            "keep_displacement, undo",
        );
    }
    // A contact almost all at a bound, as in the paper's setting: nine free pixels, few enough
    // for a backend's pair sum (`direct_curvature`), checked against the pixel sum by the
    // reference. The steps change the sets, so u is recomputed after each.
    let mut sparse = mixed_pressure(nn, pm, 7);
    for p in sparse.iter_mut().filter(|p| **p > 0.0) {
        *p = if pm.is_finite() { pm } else { 0.0 };
    }
    for i in 0..9 {
        sparse[i * 7919 % nn] = 0.3 * pm.min(0.05);
    }
    for (beta, shift) in [(0.0, 1e-4), (0.4, f64::NAN)] {
        run(
            &mut |b| {
                b.write_pressure(&mut |p| p.copy_from_slice(&sparse));
                b.displacement_and_stats(1e-3);
                let mut values = conjugate_step(b, beta, 0.5, shift, 1e-3, false);
                if b.boundary() == Boundary::Periodic {
                    assert!(values[3].is_finite(), "no pair sum for nine free pixels");
                }
                values.push(b.displacement_and_stats(1e-3).energy);
                values
            },
            "direction, curvature (pairs of free pixels), update",
        );
    }
}

/// Every number of a [`Stats`], the settled-map stop's minima included.
fn stat_values(s: &Stats) -> Vec<f64> {
    let l = s.load;
    vec![
        s.n_free,
        s.sum,
        s.sum_sq,
        s.max_free,
        s.min_free,
        s.min_zero,
        s.max_plastic,
        s.n_plastic,
        s.min_pressure,
        s.settle_gap,
        s.settle_pressure,
        s.energy,
        l.free,
        l.plastic,
        l.n_contact as f64,
        l.max_free,
    ]
}

/// One conjugate-gradient step (`direction`, `curvature`, `update`, and with a CG step `advance`,
/// from the transform `curvature` kept or afresh) and every number it reports.
fn conjugate_step(b: &mut dyn ContactBackend, beta: f64, tau: f64, shift: f64, mean: f64, kept: bool) -> Vec<f64> {
    let (st, sdt) = b.direction(mean, beta);
    let shift_t = if shift.is_nan() { 0.0 } else { shift };
    let curvature = b.curvature(shift_t);
    // The pair sum where the backend has one, after the transform (which it leaves in place).
    let direct = b.direct_curvature(shift_t).unwrap_or(f64::NAN);
    let u = b.update(mean, tau, shift);
    let l = u.load;
    let mut values = vec![
        st,
        sdt,
        curvature,
        direct,
        u.total,
        f64::from(u8::from(u.released)),
        f64::from(u8::from(u.clipped)),
        l.free,
        l.plastic,
        l.n_contact as f64,
        l.max_free,
    ];
    if shift.is_finite() {
        values.extend(stat_values(&b.advance(mean, tau, shift, kept)));
    }
    values
}

/// Runs `f` on the backend and on the reference; what it returns and the pressure it leaves agree.
fn both(
    backend: &mut dyn ContactBackend,
    reference: &mut Reference,
    exact: bool,
    f: &mut dyn FnMut(&mut dyn ContactBackend) -> Vec<f64>,
    what: &str,
) {
    let (a, b) = (f(&mut *backend), f(&mut *reference));
    for (k, (&x, &y)) in a.iter().zip(&b).enumerate() {
        agree(x, y, exact, y, &format!("{what} #{k}"));
    }
    agree_fields(backend.pressure(), reference.pressure(), exact, &format!("{what}: p"));
}

/// A surface of the reference's grid, heights in [0, 0.01).
fn surface(reference: &Reference, seed: u64) -> Arc<Surface> {
    let grid = Grid::new(reference.nx, reference.ny, 0.1 * reference.nx as f64).unwrap();
    let heights = uniform(seed, reference.nx * reference.ny)
        .iter()
        .map(|x| 0.01 * x)
        .collect();
    Arc::new(Surface::new("conformance", grid, heights).unwrap())
}

/// Every pass of the backend `make` builds against the reference, on grids of both shapes, both
/// boundaries, saturated and elastic; and on one and two threads, which must agree bit for bit.
pub(crate) fn backend_passes(make: &MakeBackend, exact: bool) {
    for (nx, ny) in GRIDS {
        let grid = Grid::new(nx, ny, 0.1 * nx as f64).unwrap();
        for boundary in [Boundary::Periodic, Boundary::Free] {
            for pm in [0.05, f64::INFINITY] {
                let mut backend = make(grid, 1.1, boundary);
                let mut reference = Reference::new(grid, 1.1, boundary);
                passes(backend.as_mut(), &mut reference, pm, exact);
            }
        }
    }
    // The reductions' order is the backend's own: one thread and two give the same bits.
    let grid = Grid::new(130, 40, 13.0).unwrap();
    let on = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| {
                let mut backend = make(grid, 1.1, Boundary::Periodic);
                let mut reference = Reference::new(grid, 1.1, Boundary::Periodic);
                passes(backend.as_mut(), &mut reference, 0.05, false);
                backend.pressure().to_vec()
            })
    };
    assert_eq!(on(1), on(2), "the backend's passes depend on the thread count");
}

/// The grids of the conformance test (Nx, Ny): rectangular both ways, square, and one whose rows
/// outnumber a rayon task's.
pub(crate) const GRIDS: [(usize, usize); 3] = [(32, 16), (16, 16), (130, 40)];

/// The reference backend (module documentation), for whole solves to compare with.
pub(crate) fn reference(grid: Grid, effective_modulus: f64, boundary: Boundary) -> Box<dyn ContactBackend> {
    Box::new(Reference::new(grid, effective_modulus, boundary))
}

/// The CPU backend's constructor.
pub(crate) fn cpu(grid: Grid, effective_modulus: f64, boundary: Boundary) -> Box<dyn ContactBackend> {
    Box::new(CpuBackend::new(grid, effective_modulus, boundary).unwrap())
}
