//! A backend that wraps another and logs the calls that steer a solve (the tests of the solver's
//! path in `contact/mod.rs` read the log), or that breaks one rule of the trait on purpose (a
//! backend the conformance test, `contact::conformance`, must fail).

use std::sync::{Arc, Mutex};

use super::backend::{ContactBackend, HeightStats, LoadSums, Stats, SurfaceLaw, Update};
use crate::influence::Boundary;
use crate::surface::Surface;

/// What a [`Spy`] saw of a solve, in call order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Call {
    /// `direction`: an iteration starts.
    Direction,
    /// `update`, with the plastic load Σ p (p ≥ p_m) of the new p.
    Update { plastic: f64 },
    /// The statistics of a new state (`displacement_and_stats`, `stats`, `advance`), with its
    /// plastic load.
    Stats { plastic: f64 },
    /// `undo`.
    Undo,
}

/// A backend that does what the one it wraps does and logs the calls that steer a solve; or,
/// `broken`, one that counts the plastic pixels of the load sums as free: a backend the
/// conformance test must fail.
pub(crate) struct Spy {
    inner: Box<dyn ContactBackend>,
    calls: Arc<Mutex<Vec<Call>>>,
    broken: bool,
}

impl Spy {
    /// The spy on `inner` and its log.
    pub(crate) fn new(inner: Box<dyn ContactBackend>) -> (Self, Arc<Mutex<Vec<Call>>>) {
        let calls = Arc::new(Mutex::new(Vec::new()));
        let spy = Self {
            inner,
            calls: Arc::clone(&calls),
            broken: false,
        };
        (spy, calls)
    }

    /// `inner` with its load sums broken.
    pub(crate) fn broken(inner: Box<dyn ContactBackend>) -> Self {
        Self {
            broken: true,
            ..Self::new(inner).0
        }
    }

    fn log(&self, call: Call) {
        self.calls.lock().unwrap().push(call);
    }

    fn logged(&self, stats: Stats) -> Stats {
        self.log(Call::Stats {
            plastic: stats.load.plastic,
        });
        stats
    }
}

impl ContactBackend for Spy {
    fn boundary(&self) -> Boundary {
        self.inner.boundary()
    }
    fn self_influence(&self) -> f64 {
        self.inner.self_influence()
    }
    fn apply_influence(&mut self, i: &[f64], o: &mut [f64]) {
        self.inner.apply_influence(i, o)
    }
    fn write_heights(&mut self, f: &mut dyn FnMut(&mut [f64])) {
        self.inner.write_heights(f)
    }
    fn bind_surfaces(&mut self, t: Arc<Surface>, b: Arc<Surface>) {
        self.inner.bind_surfaces(t, b)
    }
    fn compose(&mut self, o: usize) {
        self.inner.compose(o)
    }
    fn bind_law(&mut self, law: SurfaceLaw) {
        self.inner.bind_law(law)
    }
    fn write_pressure(&mut self, f: &mut dyn FnMut(&mut [f64])) {
        self.inner.write_pressure(f)
    }
    fn pressure(&mut self) -> &[f64] {
        self.inner.pressure()
    }
    fn contact_map(&mut self) -> &[u64] {
        self.inner.contact_map()
    }
    fn height_stats(&mut self) -> HeightStats {
        self.inner.height_stats()
    }
    fn initial_guess(&mut self, m: f64) -> bool {
        self.inner.initial_guess(m)
    }
    fn load_sums(&mut self) -> LoadSums {
        let s = self.inner.load_sums();
        if !self.broken {
            return s;
        }
        LoadSums {
            free: s.free + s.plastic,
            plastic: 0.0,
            ..s
        }
    }
    fn saturate_contact(&mut self) {
        self.inner.saturate_contact()
    }
    fn scaled_load(&mut self, s: f64, sp: bool) -> (f64, f64) {
        self.inner.scaled_load(s, sp)
    }
    fn scale(&mut self, s: f64, sp: bool) {
        self.inner.scale(s, sp)
    }
    fn spread_missing_load(&mut self, t: f64, m: f64) {
        self.inner.spread_missing_load(t, m)
    }
    fn displacement_and_stats(&mut self, r: f64) -> Stats {
        let stats = self.inner.displacement_and_stats(r);
        self.logged(stats)
    }
    fn stats(&mut self, r: f64) -> Stats {
        let stats = self.inner.stats(r);
        self.logged(stats)
    }
    fn direction(&mut self, m: f64, b: f64) -> (f64, f64) {
        self.log(Call::Direction);
        self.inner.direction(m, b)
    }
    fn response_scale(&self) -> f64 {
        self.inner.response_scale()
    }
    fn curvature(&mut self, s: f64) -> f64 {
        self.inner.curvature(s)
    }
    fn direct_curvature(&mut self, s: f64) -> Option<f64> {
        self.inner.direct_curvature(s)
    }
    fn update(&mut self, m: f64, t: f64, s: f64) -> Update {
        let update = self.inner.update(m, t, s);
        self.log(Call::Update {
            plastic: update.load.plastic,
        });
        update
    }
    fn advance(&mut self, m: f64, t: f64, s: f64, k: bool) -> Stats {
        let stats = self.inner.advance(m, t, s, k);
        self.logged(stats)
    }
    fn keep_displacement(&mut self) {
        self.inner.keep_displacement()
    }
    fn undo(&mut self) {
        self.log(Call::Undo);
        self.inner.undo()
    }
}
