//! The particle rule of interacting micro-contacts: nearby junctions sheared together detach one
//! combined particle when the elastic energy they store pays for it (Aghababaei, Warner & Molinari,
//! Nat. Commun. 2016 and PNAS 2017; Aghababaei, Brink & Molinari, PRL 2018; Pham-Ba, Brink &
//! Molinari, IJSS 2020; Pham-Ba & Molinari, Tribol. Lett. 2021).
//!
//! The model's criterion for one junction (paper eq. 1) is an energy balance: the elastic energy a
//! junction of diameter d stores under the shear strength τ̃, E_el(d) ∝ τ̃² d³/μ (for a uniformly
//! sheared disc, E_el = (2 − ν) τ̃² d³/(12 μ)), against the energy of detaching a particle of that
//! diameter, ∝ 𝒢 d²; the two are equal at d = d*. So detaching a particle of diameter D costs
//! E_el(d*) (D/d*)², and a group M of junctions, sheared together, stores
//! Φ_M Σ_{m ∈ M} E_el(d_m), where Φ_M = E(M) / Σ_m E(m) is the ratio of the energy stored when its
//! junctions are loaded together (their elastic interaction included) to the sum of their energies
//! loaded alone, both computed on the grid ([`ShearCompliance`]): about 1.3 for two junctions in
//! contact along the shear, falling to 1 a few diameters apart (and a little below 1 beyond, in the
//! periodic box, whose zero-mean displacement makes distant junctions unload each other). The group
//! detaches one combined particle of diameter D_M when
//!
//!   Φ_M Σ_m d_m³ ≥ d* D_M²,
//!
//! which for a lone junction (Φ = 1, D = d) is d ≥ d*: the paper's criterion, exactly. No parameter
//! enters beyond the model's own (τ̃, 𝒢, μ and ν through d* and Φ, the geometry factor through d*).
//!
//! Two choices the papers leave open are the rule's parameters: how far to look for neighbours
//! (`reach`: two junctions are neighbours when at least one is d*/2 across or more, which a pair
//! needs to pass the criterion at all since Φ ≤ 2 for two junctions, and the gap between them,
//! centroid distance less their equivalent radii, is at most `reach` times the larger diameter) and
//! the shape of the combined particle (`particle`: the convex hull of its junctions, D_M² =
//! 4 A_hull/π, as Pham-Ba & Molinari 2021 find the particles of interacting micro-contacts to
//! enclose; or `members`, D_M² = Σ d_m²). Groups grow by single linkage: neighbour pairs in order of
//! their gap, each joining the two groups if the joined group passes the criterion. A group grows
//! only through neighbour pairs, so a junction under d*/2 joins a group only beside a member at
//! least d*/2 across. A group that would spread over more than half the box along x or y forms no
//! particle (it would meet its own periodic image), nor does a junction that wraps the box join
//! one; the run counts, in a warning, the groups refused for the box that would have paid at least
//! for their members' own area.
//!
//! Everything else is the paper's rule: only active junctions (overlapping no formed or disabled
//! junction of the previous step) join or form; the junctions of a combined particle count as formed
//! for the next step; N* counts the junctions at least d* across as in every rule.

use crate::junctions::particle_volume;

use super::overlap::OverlapRule;
use super::rule::{
    Allowed, JunctionState, LabelledStep, ParameterValue, ParticleRule, RuleParameter, RuleSetup, ShearStep, StepWear,
};
use super::shear::{hull_area, JunctionGeometry, ShearCompliance};

/// The parameters of the rule (`[sliding.particle_rule]`).
pub const INTERACTING_PARAMETERS: &[RuleParameter] = &[
    RuleParameter {
        name: "reach",
        description: "how far a junction looks for neighbours: the gap between two junctions (centroid distance \
                      less their equivalent radii) at most `reach` times the larger one's diameter, a number in [0, 8]",
        default: ParameterValue::Number(1.0),
        allowed: Allowed::Range { min: 0.0, max: 8.0 },
    },
    RuleParameter {
        name: "particle",
        description: "the size of a combined particle: \"hull\", the equivalent diameter of the convex hull of its \
                      junctions (Pham-Ba & Molinari 2021), or \"members\", that of their total area",
        default: ParameterValue::Choice("hull"),
        allowed: Allowed::Choices(&["hull", "members"]),
    },
];

/// The rule of interacting micro-contacts for one critical diameter d* (module documentation).
#[derive(Debug, Clone)]
pub struct InteractingRule {
    /// d* in pixels.
    critical_pixels: f64,
    pixel_size: f64,
    reach: f64,
    hull: bool,
    /// The paper's bookkeeping (states carried by pixel overlap, N*₊, V), which counts the
    /// combined particles too.
    paper: OverlapRule,
    /// Combined particles formed so far, and groups refused because of the box.
    combined: usize,
    refused: usize,
    groups: Groups,
    cells: Cells,
}

/// Scratch of the neighbour search: candidates binned by centroid, a linked list per cell.
#[derive(Debug, Clone, Default)]
struct Cells {
    head: Vec<usize>,
    next: Vec<usize>,
}

/// The groups of one step: union–find over junction ids with each root's energies and size.
#[derive(Debug, Clone, Default)]
struct Groups {
    parent: Vec<usize>,
    /// Next member of the same group (a circular list).
    next: Vec<usize>,
    count: Vec<usize>,
    /// E(M): the energy stored by the group loaded together (grid units).
    energy: Vec<f64>,
    /// Σ_m E(m): its junctions' energies loaded alone.
    alone: Vec<f64>,
    /// Σ_m d_m³ (pixels³).
    cubes: Vec<f64>,
    /// Σ_m d_m² (pixels²): D² of the members' total area.
    squares: Vec<f64>,
    /// D_M² (pixels²) of the group's particle.
    size2: Vec<f64>,
    /// Whole-period shift of each junction into its group's frame (pixels).
    shift: Vec<(i32, i32)>,
    /// Scratch: the pixels of a tentative group.
    pixels: Vec<(i32, i32)>,
    /// Pairs of groups (roots) refused for the box at this step.
    refused: Vec<(usize, usize)>,
}

impl Groups {
    fn reset(&mut self, n: usize) {
        self.parent.clear();
        self.parent.extend(0..n);
        self.next.clear();
        self.next.extend(0..n);
        self.count.clear();
        self.count.resize(n, 1);
        self.refused.clear();
        for v in [
            &mut self.energy,
            &mut self.alone,
            &mut self.cubes,
            &mut self.squares,
            &mut self.size2,
        ] {
            v.clear();
            v.resize(n, f64::NAN);
        }
        self.shift.clear();
        self.shift.resize(n, (0, 0));
    }

    fn root(&mut self, mut j: usize) -> usize {
        while self.parent[j] != j {
            self.parent[j] = self.parent[self.parent[j]];
            j = self.parent[j];
        }
        j
    }

    /// Junction `j` belongs to a group of two or more (its root's count, without compressing).
    fn is_joined(&self, mut j: usize) -> bool {
        while self.parent[j] != j {
            j = self.parent[j];
        }
        self.count[j] > 1
    }

    /// The members of the group of root `r`.
    fn members(&self, r: usize) -> impl Iterator<Item = usize> + '_ {
        let mut at = Some(r);
        std::iter::from_fn(move || {
            let j = at?;
            let n = self.next[j];
            at = (n != r).then_some(n);
            Some(j)
        })
    }
}

impl InteractingRule {
    /// The rule for a run's setup.
    pub fn new(setup: &RuleSetup) -> Self {
        let p = setup.parameters;
        Self {
            critical_pixels: setup.critical_diameter / setup.pixel_size,
            pixel_size: setup.pixel_size,
            reach: p.number("reach"),
            hull: p.choice("particle") == "hull",
            paper: OverlapRule::new(setup.critical_diameter),
            combined: 0,
            refused: 0,
            groups: Groups::default(),
            cells: Cells::default(),
        }
    }

    pub(super) fn boxed(setup: &RuleSetup) -> Box<dyn ParticleRule> {
        Box::new(Self::new(setup))
    }

    /// Combined particles formed so far (each counted once in N*₊).
    pub fn combined_particles(&self) -> usize {
        self.combined
    }

    /// The neighbour pairs among this step's active, finite junctions, by increasing gap (pixels).
    /// A pair is looked for from its larger junction (a seed, at least d*/2 across): its partner,
    /// no larger, lies within (1 + reach) of its diameter, so candidates are binned by centroid
    /// into cells and a seed visits the cells within that distance.
    fn neighbour_pairs(&mut self, step: &LabelledStep, geometry: &JunctionGeometry) -> Vec<(f64, usize, usize)> {
        let dx = self.pixel_size;
        let diameter = |j: usize| step.junctions[j].diameter / dx;
        let (nx, ny) = geometry.box_pixels();
        let cell = (0.5 * self.critical_pixels).max(4.0);
        let (cx, cy) = (
            ((nx as f64 / cell).floor() as usize).max(1),
            ((ny as f64 / cell).floor() as usize).max(1),
        );
        let bin = |j: usize| {
            let (x, y) = geometry.centroid(j);
            let bx = ((x.rem_euclid(nx as f64) / nx as f64 * cx as f64) as usize).min(cx - 1);
            let by = ((y.rem_euclid(ny as f64) / ny as f64 * cy as f64) as usize).min(cy - 1);
            bx * cy + by
        };
        // Candidates binned by cell (a linked list per cell).
        let cells = &mut self.cells;
        cells.head.clear();
        cells.head.resize(cx * cy, usize::MAX);
        cells.next.clear();
        cells.next.resize(step.junctions.len(), usize::MAX);
        let disabled = self.paper.disabled();
        for j in (0..step.junctions.len()).filter(|&j| !disabled[j] && geometry.is_finite(j)) {
            let b = bin(j);
            cells.next[j] = cells.head[b];
            cells.head[b] = j;
        }
        let mut pairs = Vec::new();
        for b0 in 0..cx * cy {
            let mut i = cells.head[b0];
            while i != usize::MAX {
                let di = diameter(i);
                if 2.0 * di >= self.critical_pixels {
                    let radius = di * (1.0 + self.reach);
                    let (bx, by) = ((b0 / cy) as i64, (b0 % cy) as i64);
                    let xs = cell_range(bx, (radius * cx as f64 / nx as f64).ceil() as i64 + 1, cx);
                    let ys = cell_range(by, (radius * cy as f64 / ny as f64).ceil() as i64 + 1, cy);
                    for x in xs {
                        for y in ys.clone() {
                            let b = x * cy + y;
                            let mut j = cells.head[b];
                            while j != usize::MAX {
                                let dj = diameter(j);
                                // From the larger junction only (ties: the smaller id).
                                if j != i && (dj < di || (dj == di && j > i)) {
                                    let gap = geometry.centroid_distance(i, j) - 0.5 * (di + dj);
                                    if gap <= self.reach * di {
                                        pairs.push((gap, i.min(j), i.max(j)));
                                    }
                                }
                                j = cells.next[j];
                            }
                        }
                    }
                }
                i = cells.next[i];
            }
        }
        pairs.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
        pairs
    }

    /// Joins the groups of `i` and `j` if the joined group passes the criterion; counts a group
    /// refused for the box.
    fn try_join(&mut self, step: &LabelledStep, shear: ShearStep, i: usize, j: usize) {
        let (g, c) = (shear.geometry, shear.compliance);
        let (a, b) = (self.groups.root(i), self.groups.root(j));
        if a == b {
            return;
        }
        for r in [a, b] {
            if self.groups.energy[r].is_nan() {
                let e = g.self_energy(c, r);
                let d = step.junctions[r].diameter / self.pixel_size;
                (self.groups.energy[r], self.groups.alone[r]) = (e, e);
                (self.groups.cubes[r], self.groups.squares[r], self.groups.size2[r]) = (d.powi(3), d * d, d * d);
            }
        }
        let (ea, eb) = (self.groups.energy[a], self.groups.energy[b]);
        let alone = self.groups.alone[a] + self.groups.alone[b];
        let cubes = self.groups.cubes[a] + self.groups.cubes[b];
        // D² of the members' total area, which no particle enclosing them undercuts.
        let squares = self.groups.squares[a] + self.groups.squares[b];
        let passes = |energy: f64, size2: f64| energy / alone * cubes >= self.critical_pixels * size2;
        // The energy is a positive quadratic form, so E(a ∪ b) ≤ (√E(a) + √E(b))²: a bound that
        // spares the cross term where even it cannot pay for the smallest particle.
        let bound = (ea.sqrt() + eb.sqrt()).powi(2);
        if !passes(bound, squares) {
            return;
        }
        // Bring b's frame next to a's: j nearest to i.
        let (ci, si) = (g.centroid(i), self.groups.shift[i]);
        let t = g.shift_towards(j, (ci.0 + si.0 as f64, ci.1 + si.1 as f64));
        let sj = self.groups.shift[j];
        let move_b = (t.0 - sj.0, t.1 - sj.1);
        // The joined group's pixels in one frame, and the box guard.
        let mut pixels = std::mem::take(&mut self.groups.pixels);
        pixels.clear();
        for (r, extra) in [(a, (0, 0)), (b, move_b)] {
            for m in self.groups.members(r) {
                let s = self.groups.shift[m];
                pixels.extend(g.pixels(m).iter().map(|&(x, y)| (x + s.0 + extra.0, y + s.1 + extra.1)));
            }
        }
        let (ex, ey) = super::shear::extent(&pixels);
        let (nx, ny) = g.box_pixels();
        let too_wide = 2 * (ex + 1) > nx as i32 || 2 * (ey + 1) > ny as i32;
        let size2 = if too_wide {
            squares
        } else if self.hull {
            4.0 * hull_area(&pixels) / std::f64::consts::PI
        } else {
            squares
        };
        self.groups.pixels = pixels;
        if !passes(bound, size2) {
            return;
        }
        let energy = ea + eb + cross_energy(c, g, &self.groups, a, b);
        if !passes(energy, size2) {
            return;
        }
        if too_wide {
            // It would pay at least for the members' own area: a particle refused for the box,
            // counted once per pair of groups and step.
            let key = (a.min(b), a.max(b));
            if !self.groups.refused.contains(&key) {
                self.groups.refused.push(key);
                self.refused += 1;
            }
            return;
        }
        let members_b: Vec<usize> = self.groups.members(b).collect();
        for m in members_b {
            let s = self.groups.shift[m];
            self.groups.shift[m] = (s.0 + move_b.0, s.1 + move_b.1);
        }
        let gr = &mut self.groups;
        gr.parent[b] = a;
        gr.next.swap(a, b);
        gr.count[a] += gr.count[b];
        (gr.energy[a], gr.alone[a], gr.cubes[a], gr.size2[a]) = (energy, alone, cubes, size2);
        gr.squares[a] = squares;
    }
}

/// The cells within `r` of cell `c` on a periodic axis of `n` cells, each once.
fn cell_range(c: i64, r: i64, n: usize) -> impl Iterator<Item = usize> + Clone {
    let n = n as i64;
    let (from, to) = if 2 * r + 1 >= n { (0, n - 1) } else { (c - r, c + r) };
    (from..=to).map(move |x| x.rem_euclid(n) as usize)
}

/// Σ over the members of groups `a` and `b` of the junctions' cross energies.
fn cross_energy(c: &ShearCompliance, g: &JunctionGeometry, groups: &Groups, a: usize, b: usize) -> f64 {
    let mut sum = 0.0;
    for m in groups.members(a) {
        for n in groups.members(b) {
            sum += c.cross_energy(g.pixels(m), g.pixels(n));
        }
    }
    sum
}

impl ParticleRule for InteractingRule {
    fn step(&mut self, step: &LabelledStep, scratch: &mut [bool]) -> StepWear {
        let shear = step
            .shear
            .expect("the interacting rule declares needs_shear, so every step hands it the shear");
        self.paper.mark_disabled(step, scratch);
        self.groups.reset(step.junctions.len());
        for (_, i, j) in self.neighbour_pairs(step, shear.geometry) {
            self.try_join(step, shear, i, j);
        }
        // The combined particles first, then every junction as the paper's rule settles it.
        for r in 0..step.junctions.len() {
            if self.groups.parent[r] == r && self.groups.count[r] > 1 {
                self.paper
                    .add_particle(particle_volume(self.groups.size2[r].sqrt() * self.pixel_size));
                self.combined += 1;
            }
        }
        let groups = &self.groups;
        self.paper.settle(step, |j| groups.is_joined(j))
    }

    fn states(&self) -> &[JunctionState] {
        self.paper.states()
    }

    /// The paper's bookkeeping ([`OverlapRule`]'s state, under `paper`), the combined particles
    /// formed and the groups refused for the box.
    fn carried(&self) -> serde_json::Value {
        serde_json::json!({
            "paper": self.paper.carried(),
            "combined": self.combined,
            "refused": self.refused,
        })
    }

    fn restore(&mut self, carried: serde_json::Value) -> std::result::Result<(), String> {
        let count = |key: &str| {
            carried[key]
                .as_u64()
                .map(|n| n as usize)
                .ok_or_else(|| format!("no count `{key}`"))
        };
        let (combined, refused) = (count("combined")?, count("refused")?);
        self.paper.restore(carried["paper"].clone())?;
        (self.combined, self.refused) = (combined, refused);
        Ok(())
    }

    fn combined_particles(&self) -> Option<usize> {
        Some(self.combined)
    }

    fn warnings(&self, load: f64) -> Vec<String> {
        if self.refused == 0 {
            return Vec::new();
        }
        vec![format!(
            "F_N = {load:.4e}: the interacting rule (d* = {:.1} px) refused {} group(s) of junctions as one particle \
             because they would spread over more than half the box: a particle that large would meet its own \
             periodic image; their junctions were taken one by one as in the paper's rule; enlarge the box",
            self.critical_pixels, self.refused
        )]
    }
}

#[cfg(test)]
mod tests {
    use super::super::rule::RuleParameters;
    use super::*;
    use crate::junctions::{Junction, JunctionLabeller};
    use proptest::prelude::*;

    /// The rule's parameters: `reach` and `particle`.
    fn parameters(reach: f64, particle: &'static str) -> RuleParameters {
        RuleParameters(vec![
            ("reach", ParameterValue::Number(reach)),
            ("particle", ParameterValue::Choice(particle)),
        ])
    }

    /// A box of `n²` pixels with discs (r² < `r2`) at the given centres, as a contact map.
    fn discs(n: usize, centres: &[(i32, i32)], r2: i32) -> Vec<bool> {
        let mut map = vec![false; n * n];
        for &(x0, y0) in centres {
            for x in 0..n as i32 {
                for y in 0..n as i32 {
                    if (x - x0).pow(2) + (y - y0).pow(2) < r2 {
                        map[x as usize * n + y as usize] = true;
                    }
                }
            }
        }
        map
    }

    /// Runs the overlap rule and the interacting rule with `parameters` over the maps for critical
    /// diameter `d_star` (pixels, Δx = 1): their records, and the interacting rule's combined
    /// particles.
    fn both(
        n: usize,
        maps: &[Vec<bool>],
        d_star: f64,
        parameters: RuleParameters,
    ) -> (Vec<StepWear>, Vec<StepWear>, InteractingRule) {
        let setup = RuleSetup {
            critical_diameter: d_star,
            pixel_size: 1.0,
            parameters: &parameters,
        };
        let mut interacting = InteractingRule::new(&setup);
        let mut overlap = OverlapRule::new(d_star);
        let compliance = ShearCompliance::new(n, n, 0.3);
        let mut geometry = JunctionGeometry::default();
        let mut labeller = JunctionLabeller::new(n, n, 8);
        let mut scratch = vec![false; n * n];
        let (mut a, mut b) = (Vec::new(), Vec::new());
        for map in maps {
            labeller.label(|k| map[k]);
            let junctions: Vec<Junction> = labeller.junctions(1.0);
            geometry.fill(&labeller, &junctions);
            let shear = Some(ShearStep {
                compliance: &compliance,
                geometry: &geometry,
            });
            let step = LabelledStep {
                labeller: &labeller,
                junctions: &junctions,
                slid: 1.0,
                shear,
            };
            a.push(overlap.step(&step, &mut scratch));
            b.push(interacting.step(&step, &mut scratch));
            assert!(scratch.iter().all(|&s| !s));
        }
        (a, b, interacting)
    }

    #[test]
    fn a_lone_junction_detaches_at_exactly_d_star() {
        // One disc of 193 pixels: d = 2√(193/π) = 15.676 px.
        let d = 2.0 * (193.0 / std::f64::consts::PI).sqrt();
        let map = discs(64, &[(32, 32)], 64);
        for (d_star, formed) in [(d * (1.0 - 1e-12), 1), (d, 1), (d * (1.0 + 1e-12), 0)] {
            let (o, i, rule) = both(64, std::slice::from_ref(&map), d_star, parameters(1.0, "hull"));
            assert_eq!((i[0].n_formed, rule.combined_particles()), (formed, 0), "d* = {d_star}");
            assert_eq!(o, i);
        }
    }

    #[test]
    fn two_close_junctions_below_d_star_detach_together_and_far_apart_not_at_all() {
        // Two discs of d = 15.68 px; d* = 17 px is above each. In contact along the shear they store
        // Φ ≈ 1.30 times their energies alone: 1.30 · 2 · 15.68³ ≈ 10,000 ≥ 17 · D² with the hull's
        // D² ≈ 4 · 450/π ≈ 575, so they form one particle of the hull's size.
        let close = discs(128, &[(56, 64), (72, 64)], 64);
        let (o, i, rule) = both(128, std::slice::from_ref(&close), 17.0, parameters(1.0, "hull"));
        assert_eq!((o[0].n_formed, i[0].n_formed, rule.combined_particles()), (0, 1, 1));
        assert_eq!(
            i[0].n_critical, 0,
            "N* counts junctions at least d* across in every rule"
        );
        assert!(i[0].volume > 2.0 * Junction::new(193, 1.0).volume);
        // The members' total area (D² = Σ d²) is a smaller particle than the hull.
        let (_, m, _) = both(128, std::slice::from_ref(&close), 17.0, parameters(1.0, "members"));
        assert!(m[0].n_formed == 1 && m[0].volume < i[0].volume);
        // Four diameters apart in a 256² box they are no neighbours (gap 48 px > reach · d) and stay
        // below d*.
        let far = discs(256, &[(96, 128), (160, 128)], 64);
        let (o, i, rule) = both(256, std::slice::from_ref(&far), 17.0, parameters(1.0, "hull"));
        assert_eq!((o[0].n_formed, i[0].n_formed, rule.combined_particles()), (0, 0, 0));
        // With a reach long enough they are neighbours, and the group fits the box, but the hull
        // spanning them is far too large a particle for the energy they store: still nothing.
        let (_, i, rule) = both(256, std::slice::from_ref(&far), 17.0, parameters(8.0, "hull"));
        assert_eq!((i[0].n_formed, rule.combined_particles(), rule.refused), (0, 0, 0));
    }

    #[test]
    fn the_junctions_of_a_combined_particle_are_formed_for_the_next_step() {
        let close = discs(128, &[(56, 64), (72, 64)], 64);
        let shifted = discs(128, &[(57, 64), (73, 64)], 64);
        let (_, i, rule) = both(128, &[close, shifted], 17.0, parameters(1.0, "hull"));
        assert_eq!(
            (i[1].n_formed, rule.combined_particles()),
            (1, 1),
            "their successors are disabled"
        );
    }

    #[test]
    fn a_group_wider_than_half_the_box_forms_no_particle_and_is_said() {
        // The close pair of the test above, each just under d*, joined would pay for its particle;
        // in a 48-pixel box it spans 31 pixels along x, more than half the box: refused, once.
        let close = discs(48, &[(12, 24), (28, 24)], 64);
        let (o, i, rule) = both(48, std::slice::from_ref(&close), 15.8, parameters(1.0, "members"));
        assert_eq!(o, i);
        assert_eq!((i[0].n_formed, rule.combined_particles(), rule.refused), (0, 0, 1));
        let w = rule.warnings(1e-3);
        assert!(w.len() == 1 && w[0].contains("half the box"), "{w:?}");
        // Small junctions that could not pay for their particle are not counted as refused.
        let specks = discs(32, &[(4, 16), (12, 16), (20, 16), (28, 16)], 2);
        let (_, _, rule) = both(32, std::slice::from_ref(&specks), 6.0, parameters(8.0, "members"));
        assert_eq!(rule.refused, 0);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        /// The binned neighbour search finds exactly the pairs a search over every pair finds.
        #[test]
        fn the_neighbour_search_finds_every_pair(
            map in proptest::collection::vec(proptest::bool::weighted(0.25), 48 * 40),
            d_star in 1.0f64..12.0,
            reach in 0.0f64..3.0,
        ) {
            let (nx, ny) = (48, 40);
            let mut labeller = JunctionLabeller::new(nx, ny, 4);
            labeller.label(|k| map[k]);
            let junctions = labeller.junctions(1.0);
            let mut geometry = JunctionGeometry::default();
            geometry.fill(&labeller, &junctions);
            let compliance = ShearCompliance::new(nx, ny, 0.3);
            let step = LabelledStep {
                labeller: &labeller,
                junctions: &junctions,
                slid: 1.0,
                shear: Some(ShearStep { compliance: &compliance, geometry: &geometry }),
            };
            let mut rule = InteractingRule::new(&RuleSetup {
                critical_diameter: d_star,
                pixel_size: 1.0,
                parameters: &parameters(reach, "hull"),
            });
            let mut scratch = vec![false; nx * ny];
            rule.paper.mark_disabled(&step, &mut scratch);
            let mut found: Vec<(usize, usize)> =
                rule.neighbour_pairs(&step, &geometry).into_iter().map(|(_, i, j)| (i, j)).collect();
            found.sort_unstable();
            let mut every = Vec::new();
            for i in 0..junctions.len() {
                for j in i + 1..junctions.len() {
                    let (di, dj) = (junctions[i].diameter, junctions[j].diameter);
                    let gap = geometry.centroid_distance(i, j) - 0.5 * (di + dj);
                    let finite = geometry.is_finite(i) && geometry.is_finite(j);
                    if finite && 2.0 * di.max(dj) >= d_star && gap <= reach * di.max(dj) {
                        every.push((i, j));
                    }
                }
            }
            prop_assert_eq!(found, every);
        }

        /// Wherever no junctions join, the rule is the paper's: the same N*, N*₊ and V at every
        /// step, on random sequences of contact maps.
        #[test]
        fn without_a_combined_particle_the_rule_is_the_papers(
            maps in proptest::collection::vec(proptest::collection::vec(proptest::bool::weighted(0.3), 16 * 16), 1..5),
            d_star in 1.0f64..6.0,
        ) {
            let (o, i, rule) = both(16, &maps, d_star, parameters(0.0, "hull"));
            if rule.combined_particles() == 0 {
                prop_assert_eq!(o, i);
            } else {
                prop_assert!(i.last().unwrap().volume > 0.0);
            }
        }
    }
}
