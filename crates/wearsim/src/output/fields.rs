//! The fields store of a sliding run: per-step maps in a Zarr group that xarray opens as a Dataset.

use serde_json::{json, Value};

use crate::config::Units;
use crate::error::{Error, Result};

use super::provenance::Provenance;
use super::units::unit_of;

/// Which steps of a sliding run keep their fields: the loads (indices into the run's `loads`,
/// all when empty) and every `every`-th step of the schedule (the first, s = 0, always).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FieldSelection {
    pub loads: Vec<usize>,
    pub every: usize,
}

/// Longest side of a chunk: a 4096² map is stored in 16 chunks of 1024² so that a reader can load
/// a window of it without decompressing the whole map.
const FIELD_CHUNK: usize = 1024;

/// The per-step maps of a sliding run in a Zarr store that `xarray.open_zarr` opens as a Dataset:
/// `pressure` (contact pressure, the run's pressure unit), `contact` (pressure > 0) and
/// `junctions` (junction labels, 0 outside the contact, 1… per junction, periodic as in the paper's
/// junction counting), each with dimensions (load, s, x, y); coordinates `load`, `s` (sliding
/// distance), `offset` (the same in pixels), `x` and `y` (pixel positions); units as attributes,
/// provenance and the run's inputs on the group.
#[derive(Debug)]
pub struct FieldsWriter {
    group: crate::io::ZarrGroup,
    pressure: crate::io::ZarrArray,
    contact: crate::io::ZarrArray,
    junctions: crate::io::ZarrArray,
    /// Position in the store of each load of the run (None: not kept).
    load_slot: Vec<Option<usize>>,
    every: usize,
}

/// The indices of the loads whose fields are kept, in order and once each; an error naming the
/// option for a step interval of 0 or a load index the run does not have.
fn kept_loads(selection: &FieldSelection, loads: usize) -> Result<Vec<usize>> {
    if selection.every == 0 {
        return Err(Error::param("fields every", "must be at least 1 (every step)"));
    }
    if let Some(&bad) = selection.loads.iter().find(|&&i| i >= loads) {
        return Err(Error::param(
            "fields loads",
            format!(
                "load index {bad} does not exist; the run has {loads} loads, indices 0 … {}",
                loads.saturating_sub(1)
            ),
        ));
    }
    Ok(if selection.loads.is_empty() {
        (0..loads).collect()
    } else {
        let mut k = selection.loads.clone();
        k.sort_unstable();
        k.dedup();
        k
    })
}

/// The coordinates of the store: the loads kept, the sliding distance s and offset (pixels) of the
/// steps kept, and the positions x, y of the pixels.
fn write_coordinates(
    group: &mut crate::io::ZarrGroup,
    grid: crate::grid::Grid,
    units: Units,
    kept_loads: &[f64],
    steps: &[usize],
) -> Result<()> {
    let (nx, ny, dx) = (grid.nx(), grid.ny(), grid.pixel_size());
    let length = unit_of(units, "s");
    group.coordinate_f64(
        "load",
        kept_loads,
        json!({"units": unit_of(units, "load"), "long_name": "normal load F_N"}),
    )?;
    let s: Vec<f64> = steps.iter().map(|&o| o as f64 * dx).collect();
    group.coordinate_f64(
        "s",
        &s,
        json!({"units": length, "long_name": "sliding distance of the top surface along x"}),
    )?;
    let offset = group.array(
        "offset",
        &["s"],
        &[steps.len()],
        &[steps.len().max(1)],
        crate::io::ZarrType::I64,
        json!({"units": "pixels", "long_name": "sliding offset in pixels"}),
    )?;
    offset.write_chunk(
        &[0],
        &steps
            .iter()
            .flat_map(|&o| (o as i64).to_le_bytes())
            .collect::<Vec<u8>>(),
    )?;
    let x: Vec<f64> = (0..nx).map(|i| i as f64 * dx).collect();
    let y: Vec<f64> = (0..ny).map(|j| j as f64 * dx).collect();
    group.coordinate_f64(
        "x",
        &x,
        json!({"units": length, "long_name": "position along x (sliding)"}),
    )?;
    group.coordinate_f64("y", &y, json!({"units": length, "long_name": "position along y"}))?;
    Ok(())
}

impl FieldsWriter {
    /// Creates the store at `path` (a folder that must not exist) for a run of `loads` over the
    /// schedule `offsets` (pixels) on `grid`.
    pub fn create(
        path: &std::path::Path,
        grid: crate::grid::Grid,
        units: Units,
        loads: &[f64],
        offsets: &[usize],
        selection: &FieldSelection,
        inputs: Value,
    ) -> Result<Self> {
        let kept = kept_loads(selection, loads.len())?;
        let mut load_slot = vec![None; loads.len()];
        for (slot, &i) in kept.iter().enumerate() {
            load_slot[i] = Some(slot);
        }
        let steps: Vec<usize> = offsets.iter().step_by(selection.every).copied().collect();
        let (nx, ny, dx) = (grid.nx(), grid.ny(), grid.pixel_size());
        let mut group = crate::io::ZarrGroup::create(
            path,
            json!({
                "title": "wearsim sliding run: contact fields per step",
                "provenance": Provenance::current(),
                "units": units,
                "inputs": inputs,
                "sliding_direction": "x",
                "pixel_size": dx,
            }),
        )?;
        let kept_loads: Vec<f64> = kept.iter().map(|&i| loads[i]).collect();
        write_coordinates(&mut group, grid, units, &kept_loads, &steps)?;
        let dims = ["load", "s", "x", "y"];
        let shape = [kept.len(), steps.len(), nx, ny];
        let chunks = [1, 1, nx.min(FIELD_CHUNK), ny.min(FIELD_CHUNK)];
        let mut map = |name: &str, dtype, attrs: Value| group.array(name, &dims, &shape, &chunks, dtype, attrs);
        let pressure = map(
            "pressure",
            crate::io::ZarrType::F64,
            json!({"units": unit_of(units, "flow_pressure"), "long_name": "contact pressure", "coordinates": "offset"}),
        )?;
        let contact = map(
            "contact",
            crate::io::ZarrType::Bool,
            json!({"long_name": "in contact (pressure > 0)", "coordinates": "offset"}),
        )?;
        let junctions = map(
            "junctions",
            crate::io::ZarrType::U32,
            json!({
                "long_name": "junction label (0: no contact; junctions wrap around the periodic borders)",
                "coordinates": "offset",
            }),
        )?;
        Ok(Self {
            group,
            pressure,
            contact,
            junctions,
            load_slot,
            every: selection.every,
        })
    }

    /// Bytes the kept maps take before compression (13 per pixel and step).
    pub fn raw_bytes(grid: crate::grid::Grid, loads: usize, steps: usize, selection: &FieldSelection) -> u64 {
        let kept = if selection.loads.is_empty() {
            loads
        } else {
            selection.loads.len().min(loads)
        };
        let steps = steps.div_ceil(selection.every.max(1));
        (kept * steps) as u64 * grid.pixels() as u64 * 13
    }

    /// Stores step `step_index` (position in the schedule) of load `load_index` if the selection
    /// keeps it.
    pub fn record(&mut self, load_index: usize, step_index: usize, pressure: &[f64], labels: &[u32]) -> Result<()> {
        let Some(slot) = self.load_slot.get(load_index).copied().flatten() else {
            return Ok(());
        };
        if !step_index.is_multiple_of(self.every) {
            return Ok(());
        }
        let lead = [slot, step_index / self.every];
        self.pressure
            .write_map(&lead, pressure, |v: f64, b| b.extend_from_slice(&v.to_le_bytes()))?;
        self.contact
            .write_map(&lead, pressure, |v: f64, b| b.push(u8::from(v > 0.0)))?;
        self.junctions
            // Junction k is stored as k + 1, so that 0 is "no contact" (NO_JUNCTION wraps to 0).
            .write_map(&lead, labels, |v: u32, b| {
                b.extend_from_slice(&v.wrapping_add(1).to_le_bytes())
            })?;
        Ok(())
    }

    /// Writes the consolidated metadata; the store is complete.
    pub fn finish(self) -> Result<()> {
        self.group.finish()
    }
}
