//! File input and output, one submodule per concern: atomic writes (a temporary sibling renamed
//! into place, so a killed run never leaves a half-written file) of text and JSON files and output
//! folders, NumPy `.npy` arrays, and Zarr stores.

mod atomic;
mod npy;
mod zarr;

pub use atomic::{
    atomic_write, canonical_path, host_name, parent_or_dot, process_gone, read_text, refuse_inputs_inside,
    remove_abandoned_siblings, temporary_sibling, write_json, write_text, write_texts_together, OutputClaim, OutputDir,
    VERSION,
};
pub use npy::{npy_shape, read_npy_2d, read_npy_2d_from, write_npy_bool, write_npy_f64, write_npy_i64, Npy2, NpyType};
pub use zarr::{ZarrArray, ZarrGroup, ZarrType};
