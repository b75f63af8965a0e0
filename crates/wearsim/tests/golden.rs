//! Golden values: a seed is a promise. The same seed must give the same surface, byte for byte, in
//! every release, so that a study can be rerun or extended years later; and the same study file
//! must keep its hash, so that a study folder resumes instead of starting over. These tests pin
//! today's `.npy` bytes of generated surfaces (several seeds, both generation methods, square and
//! rectangular grids) and the hashes of two study files. A new random-number crate, FFT crate,
//! `.npy` writer or TOML serialiser that changes either fails here; keep the stream (sample as
//! before on the new crate) rather than the golden value.

use std::path::Path;

use wearsim::study::expand;
use wearsim::{Generation, Grid, SpectrumParams, Surface};

/// FNV-1a (64 bit) of a byte string: enough to tell one file from another, with no dependency.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// The `.npy` bytes of the surface generated on `grid` with `seed` and `generation`.
fn npy_bytes(grid: Grid, generation: Generation, seed: u64) -> Vec<u8> {
    let spectrum = SpectrumParams {
        hurst: 0.7,
        lambda_lower: 4.0 * grid.pixel_size(),
        lambda_upper: 0.5 * grid.length_x(),
        rms_height: 0.005 * grid.length_x(),
        generation,
    };
    let surface = Surface::generate(grid, &spectrum, seed).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("heights.npy");
    surface.write_npy(&path).unwrap();
    std::fs::read(&path).unwrap()
}

/// (Nx, Ny, Lx, generation, seed, FNV-1a of the `.npy` bytes), taken with wearsim 0.1.0
/// (rand 0.8, rand_chacha 0.3, rand_distr 0.4, rustfft 6, ndarray-npy 0.9).
const SURFACES: [(usize, usize, f64, Generation, u64, u64); 8] = [
    (32, 32, 1.0, Generation::RandomPhase, 0, 0x8d28049e1c2f0ae8),
    (32, 32, 1.0, Generation::RandomPhase, 1, 0x6925dce0991dafd4),
    (32, 32, 1.0, Generation::RandomPhase, 12345, 0x73186b5ea1b2a238),
    (32, 16, 2.0, Generation::RandomPhase, 7, 0x8b9afaf3c8f48f92),
    (32, 32, 1.0, Generation::FilteredNoise, 0, 0xc8e69e6e7a2311a9),
    (32, 32, 1.0, Generation::FilteredNoise, 1, 0x01335924dea56a5f),
    (32, 32, 1.0, Generation::FilteredNoise, 12345, 0x75a3d051a677bffb),
    (32, 16, 2.0, Generation::FilteredNoise, 7, 0x1ea53d074a928265),
];

#[test]
fn generated_surfaces_are_byte_identical_to_the_golden_ones() {
    let mut wrong = Vec::new();
    for (nx, ny, lx, generation, seed, golden) in SURFACES {
        let grid = Grid::new(nx, ny, lx).unwrap();
        let hash = fnv1a(&npy_bytes(grid, generation, seed));
        if hash != golden {
            wrong.push(format!(
                "{nx}×{ny}, Lx = {lx}, {generation:?}, seed {seed}: {hash:#018x}, golden {golden:#018x}"
            ));
        }
    }
    assert!(wrong.is_empty(), "generated surfaces changed:\n{}", wrong.join("\n"));
}

#[test]
fn two_seeds_give_two_surfaces() {
    // Guards the test above against a generator that ignores its seed.
    let grid = Grid::square(16, 1.0).unwrap();
    assert_ne!(
        npy_bytes(grid, Generation::RandomPhase, 0),
        npy_bytes(grid, Generation::RandomPhase, 1)
    );
    assert_ne!(
        npy_bytes(grid, Generation::FilteredNoise, 0),
        npy_bytes(grid, Generation::FilteredNoise, 1)
    );
}

/// Study files and the hash of their canonical TOML, taken with wearsim 0.1.0 (toml 0.8).
const STUDIES: [(&str, &str); 2] = [
    (
        "[surface]\ngrid = 128\nlambda_lower = 0.125\nlambda_upper = 0.25\nrms_height = 0.005\nseed = [1, 2]\n\n\
         [material]\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = [0.008, 0.012]\n\
         fracture_energies = [0.5e-6]\n\n[sliding]\nloads = [5e-4, 1e-3, 2e-3]\ndistance = 0.25\nrunning_in = 0.125\n",
        "8836c2e1cc7b2617",
    ),
    (
        "units = \"si\"\n\n[surface]\ngrid = [64, 32]\nlength = 2e-6\nhurst = 0.8\nlambda_lower = 1e-7\nlambda_upper = 5e-7\nrms_height = 1e-8\n\
         generation = \"filtered-noise\"\nseed = 3\n\n[[materials]]\nname = \"steel\"\nyoungs_modulus = 210e9\n\
         poisson_ratio = 0.3\nshear_strength = 5e9\nfracture_energies = [1.0, 2.5]\n\
         surface = { grid = 32, length = 1e-6 }\n\n\
         [sliding]\nloads = [1e-3]\ndistance = 0.5\nrunning_in = 0.25\n",
        "e5427ddd285a35dd",
    ),
];

#[test]
fn study_hashes_are_the_golden_ones() {
    let mut wrong = Vec::new();
    for (text, golden) in STUDIES {
        let study = expand(text, Path::new(".")).unwrap();
        if study.hash != golden {
            wrong.push(format!(
                "{text}\nhash {}, golden {golden}; canonical:\n{}",
                study.hash, study.canonical
            ));
        }
    }
    assert!(wrong.is_empty(), "study hashes changed:\n{}", wrong.join("\n"));
}
