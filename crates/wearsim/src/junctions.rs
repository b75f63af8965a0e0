//! Contact junctions (paper §2): connected components of the contact map with periodic
//! boundaries in x and y, by union–find over the pixels in contact.
//!
//! The labeller keeps its buffers between calls (a sliding run labels every step), so labelling
//! allocates nothing once the buffers have grown to the largest contact seen; its cost is linear in
//! the number of pixels.

/// Label of a pixel not in contact.
pub const NO_JUNCTION: u32 = u32::MAX;

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
            volume: std::f64::consts::PI * diameter.powi(3) / 6.0,
        }
    }
}

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
            contact: Vec::new(),
            sizes: Vec::new(),
        }
    }

    fn find(parent: &mut [u32], mut x: u32) -> u32 {
        // Path halving.
        while parent[x as usize] != x {
            let p = parent[x as usize];
            parent[x as usize] = parent[p as usize];
            x = p;
        }
        x
    }

    fn union(parent: &mut [u32], a: u32, b: u32) {
        let (ra, rb) = (Self::find(parent, a), Self::find(parent, b));
        if ra != rb {
            // The smaller index becomes the root: deterministic, independent of visiting order.
            let (lo, hi) = if ra < rb { (ra, rb) } else { (rb, ra) };
            parent[hi as usize] = lo;
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
                self.labels[k] = 0; // marks "in contact" until the final numbering
            } else {
                self.labels[k] = NO_JUNCTION;
            }
        }
        let labels = &self.labels;
        let parent = &mut self.parent;
        let diagonal = self.connectivity == 8;
        for &k in &self.contact {
            let (i, j) = (k as usize / n, k as usize % n);
            let up = ((i + nx - 1) % nx) * n;
            let left = i * n + (j + n - 1) % n;
            if labels[left] != NO_JUNCTION {
                Self::union(parent, k, left as u32);
            }
            if labels[up + j] != NO_JUNCTION {
                Self::union(parent, k, (up + j) as u32);
            }
            if diagonal {
                let ul = up + (j + n - 1) % n;
                let ur = up + (j + 1) % n;
                if labels[ul] != NO_JUNCTION {
                    Self::union(parent, k, ul as u32);
                }
                if labels[ur] != NO_JUNCTION {
                    Self::union(parent, k, ur as u32);
                }
            }
        }
        // Number the roots in order of first appearance; roots are the smallest pixel of their
        // junction, so a root is always met before the other pixels of its junction.
        self.sizes.clear();
        for idx in 0..self.contact.len() {
            let k = self.contact[idx];
            let root = Self::find(&mut self.parent, k);
            let id = if root == k {
                self.sizes.push(0);
                (self.sizes.len() - 1) as u32
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
        out.extend(self.sizes.iter().map(|&s| Junction::new(s, dx)));
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
