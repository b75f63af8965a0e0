//! Contact junctions (paper §2): connected components of the contact map with periodic
//! boundaries in x and y, by union–find over the pixels in contact.
//!
//! A junction can close on itself around the periodic box (full contact near p_m, a contact band
//! across the box): it then has no finite extent and is no particle of the model (paper §3 assumes
//! circular junctions that detach as spheres). The labeller finds such junctions while it labels: it
//! keeps, for every pixel, its displacement from its union–find root in unwrapped coordinates, and a
//! neighbour pair of one junction whose displacements disagree by a box length is a loop around the
//! torus (Machta et al. 1996; Newman & Ziff 2001 use the same test for wrapping clusters).
//!
//! The labeller keeps its buffers between calls (a sliding run labels every step), so labelling
//! allocates nothing once the buffers have grown to the largest contact seen; its cost is linear in
//! the number of pixels.

/// Label of a pixel not in contact.
pub const NO_JUNCTION: u32 = u32::MAX;

/// The junction connectivity when none is given: 4, pixels joined through their edges only (the
/// paper's junctions, §2); 8 also joins pixels touching at a corner.
pub const DEFAULT_CONNECTIVITY: u8 = 4;

/// The area of a circle of diameter `d`, π d²/4: a junction's area at its equivalent diameter, and
/// the critical area A* = π d*²/4 of a critical diameter (paper §2). The one definition of it.
#[inline]
pub fn circle_area(d: f64) -> f64 {
    std::f64::consts::PI * d * d / 4.0
}

/// The volume of the spherical particle of diameter `d`, π d³/6 (paper §3: a junction of equivalent
/// diameter d_i detaches as a sphere of that diameter; Eq. 5's shape factor ω = π/6). The one
/// definition of it.
#[inline]
pub fn particle_volume(d: f64) -> f64 {
    std::f64::consts::PI * d.powi(3) / 6.0
}

/// One junction: pixel count and the geometry derived from it (paper §3: circular junctions,
/// spherical particles).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Junction {
    /// Number of pixels.
    pub pixels: usize,
    /// Area A_i = pixels·Δx².
    pub area: f64,
    /// Equivalent diameter d_i = 2√(A_i/π).
    pub diameter: f64,
    /// Volume of the particle it would form, v_i = π d_i³/6.
    pub volume: f64,
    /// The junction wraps the periodic box along x (it closes on itself across the box's length Lx):
    /// it has no finite extent, so it is no particle of the model.
    pub wraps_x: bool,
    /// The same along y.
    pub wraps_y: bool,
}

impl Junction {
    /// Junction of `pixels` pixels of side `dx`.
    pub fn new(pixels: usize, dx: f64) -> Self {
        let area = pixels as f64 * dx * dx;
        let diameter = 2.0 * (area / std::f64::consts::PI).sqrt();
        Self {
            pixels,
            area,
            diameter,
            volume: particle_volume(diameter),
            wraps_x: false,
            wraps_y: false,
        }
    }

    /// Whether the junction wraps the periodic box along x or y: then it is no particle of the model,
    /// and its area, diameter and volume are those of a band or a sheet, not of a circle and a sphere.
    pub fn wraps(&self) -> bool {
        self.wraps_x || self.wraps_y
    }
}

/// Wrap flags of a junction root: bit 0 along x, bit 1 along y.
const WRAPS_X: u8 = 1;
const WRAPS_Y: u8 = 2;

/// Periodic connected-component labelling of contact maps on an Nx × Ny grid (row-major, i along x).
#[derive(Debug, Clone)]
pub struct JunctionLabeller {
    nx: usize,
    ny: usize,
    connectivity: u8,
    /// Junction index of every pixel (`NO_JUNCTION` outside the contact), row-major.
    labels: Vec<u32>,
    /// Union–find parents, indexed by pixel (valid for contact pixels only).
    parent: Vec<u32>,
    /// Displacement (rows, columns) of every contact pixel from its parent in unwrapped coordinates
    /// (0 at roots). Arithmetic wraps at 2³²: displacements within one junction are bounded by its
    /// pixel count, so a loop around the box (a multiple of Nx or Ny) never reads as 0.
    offset: Vec<(i32, i32)>,
    /// Wrap flags (`WRAPS_X`, `WRAPS_Y`) of every root while labelling, of every junction after.
    wraps: Vec<u8>,
    /// Pixels in contact, in row-major order.
    contact: Vec<u32>,
    /// Pixel count per junction.
    sizes: Vec<usize>,
}

impl JunctionLabeller {
    /// Labeller for an `nx × ny` grid with 4- or 8-connectivity.
    pub fn new(nx: usize, ny: usize, connectivity: u8) -> Self {
        assert!(connectivity == 4 || connectivity == 8, "connectivity must be 4 or 8");
        assert!(
            nx.saturating_mul(ny) < u32::MAX as usize,
            "grid too large for 32-bit labels"
        );
        Self {
            nx,
            ny,
            connectivity,
            labels: vec![NO_JUNCTION; nx * ny],
            parent: vec![0; nx * ny],
            offset: vec![(0, 0); nx * ny],
            wraps: vec![0; nx * ny],
            contact: Vec::new(),
            sizes: Vec::new(),
        }
    }

    /// Root of `x` and the displacement of `x` from it, halving the path on the way.
    fn find(parent: &mut [u32], offset: &mut [(i32, i32)], mut x: u32) -> (u32, (i32, i32)) {
        let mut acc = (0i32, 0i32);
        loop {
            let p = parent[x as usize];
            if p == x {
                return (x, acc);
            }
            let (po, xo) = (offset[p as usize], offset[x as usize]);
            // x now points at its grandparent; its displacement follows.
            let o = (xo.0.wrapping_add(po.0), xo.1.wrapping_add(po.1));
            offset[x as usize] = o;
            parent[x as usize] = parent[p as usize];
            acc = (acc.0.wrapping_add(o.0), acc.1.wrapping_add(o.1));
            x = parent[x as usize];
        }
    }

    /// Joins pixel `a` and its neighbour `b`, which lies at `step` (rows, columns) from `a` in
    /// unwrapped coordinates. When both are already in one junction and their displacements
    /// disagree, the junction has a loop around the box: it is flagged as wrapping.
    fn union(parent: &mut [u32], offset: &mut [(i32, i32)], wraps: &mut [u8], a: u32, b: u32, step: (i32, i32)) {
        let (ra, oa) = Self::find(parent, offset, a);
        let (rb, ob) = Self::find(parent, offset, b);
        // Position of b's root relative to a's root.
        let d = (
            oa.0.wrapping_add(step.0).wrapping_sub(ob.0),
            oa.1.wrapping_add(step.1).wrapping_sub(ob.1),
        );
        if ra == rb {
            if d.0 != 0 {
                wraps[ra as usize] |= WRAPS_X;
            }
            if d.1 != 0 {
                wraps[ra as usize] |= WRAPS_Y;
            }
            return;
        }
        // The smaller index becomes the root: deterministic, independent of visiting order.
        let flags = wraps[ra as usize] | wraps[rb as usize];
        if ra < rb {
            parent[rb as usize] = ra;
            offset[rb as usize] = d;
            wraps[ra as usize] = flags;
        } else {
            parent[ra as usize] = rb;
            offset[ra as usize] = (d.0.wrapping_neg(), d.1.wrapping_neg());
            wraps[rb as usize] = flags;
        }
    }

    /// Labels the contact map `in_contact` (Nx·Ny flags, row-major). Junction indices are numbered in
    /// the row-major order of each junction's first pixel. Returns the number of junctions.
    pub fn label(&mut self, in_contact: impl Fn(usize) -> bool) -> usize {
        let (nx, n) = (self.nx, self.ny);
        self.contact.clear();
        for k in 0..nx * n {
            if in_contact(k) {
                self.contact.push(k as u32);
                self.parent[k] = k as u32;
                self.offset[k] = (0, 0);
                self.wraps[k] = 0;
                self.labels[k] = 0; // marks "in contact" until the final numbering
            } else {
                self.labels[k] = NO_JUNCTION;
            }
        }
        let labels = &self.labels;
        let (parent, offset, wraps) = (&mut self.parent, &mut self.offset, &mut self.wraps);
        let diagonal = self.connectivity == 8;
        for &k in &self.contact {
            let (i, j) = (k as usize / n, k as usize % n);
            let up = ((i + nx - 1) % nx) * n;
            let left = i * n + (j + n - 1) % n;
            if labels[left] != NO_JUNCTION {
                Self::union(parent, offset, wraps, k, left as u32, (0, -1));
            }
            if labels[up + j] != NO_JUNCTION {
                Self::union(parent, offset, wraps, k, (up + j) as u32, (-1, 0));
            }
            if diagonal {
                let ul = up + (j + n - 1) % n;
                let ur = up + (j + 1) % n;
                if labels[ul] != NO_JUNCTION {
                    Self::union(parent, offset, wraps, k, ul as u32, (-1, -1));
                }
                if labels[ur] != NO_JUNCTION {
                    Self::union(parent, offset, wraps, k, ur as u32, (-1, 1));
                }
            }
        }
        // Number the roots in order of first appearance; roots are the smallest pixel of their
        // junction, so a root is always met before the other pixels of its junction. A root's wrap
        // flags move to its junction index (an index is never larger than its root's pixel, so the
        // flags of roots not yet numbered are not overwritten).
        self.sizes.clear();
        for idx in 0..self.contact.len() {
            let k = self.contact[idx];
            let (root, _) = Self::find(&mut self.parent, &mut self.offset, k);
            let id = if root == k {
                self.sizes.push(0);
                let id = self.sizes.len() - 1;
                self.wraps[id] = self.wraps[k as usize];
                id as u32
            } else {
                self.labels[root as usize]
            };
            self.labels[k as usize] = id;
            self.sizes[id as usize] += 1;
        }
        self.sizes.len()
    }

    /// Pixels along x (rows).
    pub fn nx(&self) -> usize {
        self.nx
    }

    /// Pixels along y (the length of a row).
    pub fn ny(&self) -> usize {
        self.ny
    }

    /// Junction index per pixel after [`JunctionLabeller::label`] (`NO_JUNCTION` outside contact).
    pub fn labels(&self) -> &[u32] {
        &self.labels
    }

    /// Pixels in contact, row-major.
    pub fn contact_pixels(&self) -> &[u32] {
        &self.contact
    }

    /// Pixel count per junction.
    pub fn sizes(&self) -> &[usize] {
        &self.sizes
    }

    /// Whether junction `id` wraps the periodic box along x and along y (see [`Junction::wraps_x`]).
    pub fn wraps(&self, id: usize) -> (bool, bool) {
        assert!(id < self.sizes.len(), "junction {id} of {}", self.sizes.len());
        (self.wraps[id] & WRAPS_X != 0, self.wraps[id] & WRAPS_Y != 0)
    }

    /// Number of junctions that wrap the periodic box (no particles of the model).
    pub fn wrapping(&self) -> usize {
        self.wraps[..self.sizes.len()].iter().filter(|&&w| w != 0).count()
    }

    /// Junctions with their areas, diameters and volumes for pixel size `dx`.
    pub fn junctions(&self, dx: f64) -> Vec<Junction> {
        let mut out = Vec::new();
        self.junctions_into(dx, &mut out);
        out
    }

    /// [`JunctionLabeller::junctions`] into a buffer kept by the caller (no allocation per step once
    /// it has grown).
    pub fn junctions_into(&self, dx: f64, out: &mut Vec<Junction>) {
        out.clear();
        out.extend(self.sizes.iter().zip(&self.wraps).map(|(&s, &w)| Junction {
            wraps_x: w & WRAPS_X != 0,
            wraps_y: w & WRAPS_Y != 0,
            ..Junction::new(s, dx)
        }));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn label_map(map: &[bool], nx: usize, ny: usize, c: u8) -> (usize, Vec<u32>) {
        let mut l = JunctionLabeller::new(nx, ny, c);
        let count = l.label(|k| map[k]);
        (count, l.labels().to_vec())
    }

    /// Two labellings are the same partition up to renaming.
    fn same_partition(a: &[u32], b: &[u32]) -> bool {
        use std::collections::HashMap;
        let mut ab = HashMap::new();
        let mut ba = HashMap::new();
        a.iter().zip(b).all(|(&x, &y)| {
            (x == NO_JUNCTION) == (y == NO_JUNCTION) && *ab.entry(x).or_insert(y) == y && *ba.entry(y).or_insert(x) == x
        })
    }

    #[test]
    fn junction_crossing_the_periodic_edges_is_one_junction() {
        let n = 8;
        let mut map = vec![false; n * n];
        for k in [0, 7, 56, 63] {
            map[k] = true; // the four corners touch through both periodic edges
        }
        assert_eq!(label_map(&map, n, n, 4).0, 1);
        let mut diag = vec![false; n * n];
        diag[0] = true;
        diag[n * n - 1] = true; // diagonal neighbours across the corner
        assert_eq!(label_map(&diag, n, n, 4).0, 2);
        assert_eq!(label_map(&diag, n, n, 8).0, 1);
        // 4 × 6: a row of contact wraps along y, a column along x.
        let (nx, ny) = (4, 6);
        let mut rect = vec![false; nx * ny];
        for k in [0, 5, 18, 19] {
            rect[k] = true; // (0,0)–(0,5) touch across y, (3,0)–(0,0) across x, (3,1) beside (3,0)
        }
        assert_eq!(label_map(&rect, nx, ny, 4).0, 1);
    }

    /// Wrap flags per junction by a breadth-first walk in unwrapped coordinates: a pixel reached
    /// again at another unwrapped position closes a loop around the box. Independent of the
    /// union–find, for the property tests.
    fn wraps_by_walk(map: &[bool], nx: usize, ny: usize, c: u8) -> Vec<(usize, bool, bool)> {
        let mut seen: Vec<Option<(i64, i64)>> = vec![None; nx * ny];
        let mut out = Vec::new();
        let mut steps = vec![(1i64, 0i64), (-1, 0), (0, 1), (0, -1)];
        if c == 8 {
            steps.extend([(1, 1), (1, -1), (-1, 1), (-1, -1)]);
        }
        for start in 0..nx * ny {
            if !map[start] || seen[start].is_some() {
                continue;
            }
            let (mut size, mut wx, mut wy) = (0, false, false);
            let mut queue = std::collections::VecDeque::from([(start, ((start / ny) as i64, (start % ny) as i64))]);
            seen[start] = queue[0].1.into();
            while let Some((_, (x, y))) = queue.pop_front() {
                size += 1;
                for &(dx, dy) in &steps {
                    let (ux, uy) = (x + dx, y + dy);
                    let m = ux.rem_euclid(nx as i64) as usize * ny + uy.rem_euclid(ny as i64) as usize;
                    if !map[m] {
                        continue;
                    }
                    match seen[m] {
                        None => {
                            seen[m] = Some((ux, uy));
                            queue.push_back((m, (ux, uy)));
                        }
                        Some((px, py)) => {
                            wx |= px != ux;
                            wy |= py != uy;
                        }
                    }
                }
            }
            out.push((size, wx, wy));
        }
        out
    }

    #[test]
    fn junctions_around_the_box_are_flagged_and_others_are_not() {
        let (nx, ny) = (6, 8);
        let flags = |map: &[bool], c| {
            let mut l = JunctionLabeller::new(nx, ny, c);
            let n = l.label(|k| map[k]);
            (0..n).map(|id| l.wraps(id)).collect::<Vec<_>>()
        };
        // Full contact wraps both ways.
        assert_eq!(flags(&vec![true; nx * ny], 4), vec![(true, true)]);
        // A full row (constant x) closes along y; a full column along x.
        let row: Vec<bool> = (0..nx * ny).map(|k| k / ny == 2).collect();
        assert_eq!(flags(&row, 4), vec![(false, true)]);
        let column: Vec<bool> = (0..nx * ny).map(|k| k % ny == 5).collect();
        assert_eq!(flags(&column, 4), vec![(true, false)]);
        // A row with one gap spans the box but does not close: not wrapping.
        let gap: Vec<bool> = (0..nx * ny).map(|k| k / ny == 2 && k % ny != 3).collect();
        assert_eq!(flags(&gap, 4), vec![(false, false)]);
        // A junction across the periodic edges (the four corners) is an ordinary particle.
        let corners: Vec<bool> = (0..nx * ny)
            .map(|k| [0, ny - 1, (nx - 1) * ny, nx * ny - 1].contains(&k))
            .collect();
        assert_eq!(flags(&corners, 4), vec![(false, false)]);
        // A diagonal band closes along both only with 8-connectivity.
        let (n, m) = (6, 6);
        let diagonal: Vec<bool> = (0..n * m).map(|k| k / m == k % m).collect();
        let mut l = JunctionLabeller::new(n, m, 8);
        assert_eq!(l.label(|k| diagonal[k]), 1);
        assert_eq!(l.wraps(0), (true, true));
        assert_eq!(l.wrapping(), 1);
        let mut l4 = JunctionLabeller::new(n, m, 4);
        assert_eq!(l4.label(|k| diagonal[k]), 6);
        assert_eq!(l4.wrapping(), 0);
        // The flags reach the junction records.
        let j = l.junctions(0.5);
        assert!(j[0].wraps() && j[0].wraps_x && j[0].wraps_y);
        assert!(!Junction::new(3, 1.0).wraps());
    }

    #[test]
    fn geometry_of_a_junction() {
        let j = Junction::new(100, 0.01);
        assert!((j.area - 0.01).abs() < 1e-15);
        assert!((j.diameter - 2.0 * (0.01 / std::f64::consts::PI).sqrt()).abs() < 1e-15);
        assert!((j.volume - std::f64::consts::PI * j.diameter.powi(3) / 6.0).abs() < 1e-18);
    }

    fn maps() -> impl Strategy<Value = (usize, usize, Vec<bool>)> {
        (3usize..12, 3usize..12).prop_flat_map(|(nx, ny)| {
            (
                Just(nx),
                Just(ny),
                proptest::collection::vec(proptest::bool::weighted(0.45), nx * ny),
            )
        })
    }

    proptest! {
        #[test]
        fn labels_are_invariant_under_periodic_translation_and_transposition(
            (nx, ny, map) in maps(), di in 0usize..12, dj in 0usize..12, c in prop_oneof![Just(4u8), Just(8u8)]
        ) {
            let nn = nx * ny;
            let (count, labels) = label_map(&map, nx, ny, c);
            // Translate the map, label, translate the labels back.
            let shifted: Vec<bool> = (0..nn).map(|k| map[((k / ny + di) % nx) * ny + (k % ny + dj) % ny]).collect();
            let (count_s, labels_s) = label_map(&shifted, nx, ny, c);
            let back: Vec<u32> =
                (0..nn).map(|k| labels_s[((k / ny + nx - di % nx) % nx) * ny + (k % ny + ny - dj % ny) % ny]).collect();
            prop_assert_eq!(count, count_s);
            prop_assert!(same_partition(&labels, &back));
            // The transposed map is ny × nx: element (j, i) = map(i, j).
            let transposed: Vec<bool> = (0..nn).map(|k| map[(k % nx) * ny + k / nx]).collect();
            let (count_t, labels_t) = label_map(&transposed, ny, nx, c);
            let back_t: Vec<u32> = (0..nn).map(|k| labels_t[(k % ny) * nx + k / ny]).collect();
            prop_assert_eq!(count, count_t);
            prop_assert!(same_partition(&labels, &back_t));
        }

        #[test]
        fn wrap_flags_agree_with_a_walk_in_unwrapped_coordinates(
            (nx, ny, map) in maps(), c in prop_oneof![Just(4u8), Just(8u8)]
        ) {
            let mut l = JunctionLabeller::new(nx, ny, c);
            let n = l.label(|k| map[k]);
            let found: Vec<(usize, bool, bool)> = (0..n).map(|id| {
                let (x, y) = l.wraps(id);
                (l.sizes()[id], x, y)
            }).collect();
            // Both number junctions by their first pixel in row-major order.
            prop_assert_eq!(found, wraps_by_walk(&map, nx, ny, c));
        }

        #[test]
        fn wrap_flags_follow_translation_and_swap_under_transposition(
            (nx, ny, map) in maps(), di in 0usize..12, dj in 0usize..12, c in prop_oneof![Just(4u8), Just(8u8)]
        ) {
            let nn = nx * ny;
            let flags_of = |m: &[bool], a: usize, b: usize| {
                let mut l = JunctionLabeller::new(a, b, c);
                let n = l.label(|k| m[k]);
                let mut f: Vec<(usize, bool, bool)> = (0..n).map(|id| { let (x, y) = l.wraps(id); (l.sizes()[id], x, y) }).collect();
                f.sort();
                f
            };
            let base = flags_of(&map, nx, ny);
            let shifted: Vec<bool> = (0..nn).map(|k| map[((k / ny + di) % nx) * ny + (k % ny + dj) % ny]).collect();
            prop_assert_eq!(&base, &flags_of(&shifted, nx, ny));
            let transposed: Vec<bool> = (0..nn).map(|k| map[(k % nx) * ny + k / nx]).collect();
            let mut swapped: Vec<(usize, bool, bool)> = flags_of(&transposed, ny, nx).into_iter().map(|(s, x, y)| (s, y, x)).collect();
            swapped.sort();
            prop_assert_eq!(base, swapped);
        }

        #[test]
        fn total_area_is_conserved_and_neighbours_share_labels((nx, ny, map) in maps(), c in prop_oneof![Just(4u8), Just(8u8)]) {
            let mut l = JunctionLabeller::new(nx, ny, c);
            l.label(|k| map[k]);
            prop_assert_eq!(l.sizes().iter().sum::<usize>(), map.iter().filter(|&&b| b).count());
            let labels = l.labels();
            for k in 0..nx * ny {
                if !map[k] { continue; }
                let (i, j) = (k / ny, k % ny);
                let down = ((i + 1) % nx) * ny;
                let mut nb = vec![down + j, i * ny + (j + 1) % ny];
                if c == 8 { nb.push(down + (j + 1) % ny); nb.push(down + (j + ny - 1) % ny); }
                for m in nb {
                    if map[m] { prop_assert_eq!(labels[k], labels[m]); }
                }
            }
        }
    }
}
