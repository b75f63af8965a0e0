//! File input and output, one submodule per concern: atomic writes (a temporary sibling renamed
//! into place, so a killed run never leaves a half-written file) of text and JSON files and output
//! folders, NumPy `.npy` arrays, and Zarr stores.

mod atomic;
mod npy;
mod zarr;

pub use atomic::{
    abandon_outputs, atomic_write, canonical_path, checksum_matches, claim_is_stale, create_claim_file, folder_owner,
    host_name, make_folder, marker, parent_or_dot, process_gone, process_start, read_text, refresh_claim,
    refuse_foreign_file, refuse_foreign_folder, refuse_inputs_inside, remove_abandoned_siblings, remove_own_claim,
    temporary_sibling, with_checksum, write_json, write_text, write_texts_together, FolderOwner, OutputClaim,
    OutputDir, CLAIM_EXPIRY, CLAIM_REFRESH, MARKER, VERSION,
};
pub use npy::{
    npy_shape, npy_shape_from, read_npy_2d, read_npy_2d_from, write_npy_bool, write_npy_f64, write_npy_i64, Npy2,
    NpyType,
};
pub use zarr::{ZarrArray, ZarrGroup, ZarrType};
