//! `wearsim fields to-netcdf`: a fields store of `slide --save-fields` converted to NetCDF-4 with CF
//! attributes. Delegates to the Python package (`python -m wearsim.fields`, xarray and h5netcdf of
//! the `fields` extra): no NetCDF writer in Rust is both well kept and free of a C build.

use std::path::PathBuf;
use std::process::Command;

use anyhow::{bail, Result};

#[derive(clap::Args)]
pub struct ToNetcdfArgs {
    /// The fields store, DIR/fields.zarr of `wearsim slide --save-fields`.
    store: PathBuf,
    /// The NetCDF-4 file to write (e.g. fields.nc); written beside and renamed into place.
    out: PathBuf,
    /// zlib compression level of the maps, 0 for none.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u8).range(0..=9))]
    complevel: u8,
    /// The Python interpreter with the wearsim package and its `fields` extra installed
    /// (`pip install "wearsim[fields]"`); default: $WEARSIM_PYTHON, else python3.
    #[arg(long)]
    python: Option<PathBuf>,
    /// Replace OUT even when it is a file that `fields to-netcdf` did not write.
    #[arg(long)]
    overwrite: bool,
}

pub fn to_netcdf(args: &ToNetcdfArgs) -> Result<()> {
    super::polls_interrupt();
    if !args.store.join(".zgroup").is_file() {
        bail!(
            "{} is not a fields store (no .zgroup); give the fields.zarr folder written by `wearsim slide --save-fields`",
            args.store.display()
        );
    }
    // Never into the store nor over a file of it, whatever the spelling; an existing file that the
    // conversion did not write is refused by the Python side, which reads NetCDF attributes.
    wearsim::io::refuse_foreign_file(&args.out, "fields to-netcdf", true, &[args.store.as_path()], |_| true)?;
    let python = super::python_with(
        args.python.as_deref(),
        "wearsim.fields",
        &["xarray", "zarr", "h5netcdf", "h5py"],
        "fields",
        "the conversion",
    )?;
    // Partial files of killed conversions beside it.
    wearsim::io::remove_abandoned_siblings(&args.out);
    super::check_interrupt()?;
    let mut command = Command::new(&python);
    command.args([
        "-m",
        "wearsim.fields",
        "to-netcdf",
        "--complevel",
        &args.complevel.to_string(),
    ]);
    if args.overwrite {
        command.arg("--overwrite");
    }
    command.arg(&args.store).arg(&args.out);
    // A stop signal is passed on: the conversion removes its temporary file and exits.
    super::run_child(command, "the conversion", &args.out)
}
