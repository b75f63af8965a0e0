//! Zarr (format 2) stores: the chunked, compressed arrays that xarray, zarr-python and Dask open.

use std::io::Write;
use std::path::Path;

use crate::error::{Error, Result};

use super::atomic::{atomic_write, write_json};

/// The element types a Zarr array of wearsim holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ZarrType {
    F64,
    I64,
    U32,
    Bool,
}

impl ZarrType {
    fn descr(self) -> &'static str {
        match self {
            ZarrType::F64 => "<f8",
            ZarrType::I64 => "<i8",
            ZarrType::U32 => "<u4",
            ZarrType::Bool => "|b1",
        }
    }
}

/// One array of a Zarr store: its folder, shape and chunk shape. Chunks are zlib-compressed
/// C-order blocks named `i.j.k…` (the format's "." separator).
#[derive(Debug, Clone)]
pub struct ZarrArray {
    dir: std::path::PathBuf,
    shape: Vec<usize>,
    chunks: Vec<usize>,
    dtype: ZarrType,
}

/// A Zarr format-2 group being written: arrays are created in it, their metadata collected and
/// written as consolidated metadata (`.zmetadata`) by [`ZarrGroup::finish`], so that
/// `xarray.open_zarr` reads it in one request. Chunk data is written as it comes; the caller makes
/// the whole store appear at once (e.g. inside an `OutputDir`).
#[derive(Debug)]
pub struct ZarrGroup {
    dir: std::path::PathBuf,
    metadata: serde_json::Map<String, serde_json::Value>,
}

/// Compression level of chunks: zlib's fastest, which already shrinks the mostly-zero maps of a
/// contact many times and keeps writing far below a solve's cost.
const ZARR_ZLIB_LEVEL: u32 = 1;

impl ZarrGroup {
    /// Creates the group's folder (which must not exist) with its attributes.
    pub fn create(dir: &Path, attributes: serde_json::Value) -> Result<Self> {
        std::fs::create_dir(dir).map_err(|e| Error::io(dir, e))?;
        let mut group = Self {
            dir: dir.to_path_buf(),
            metadata: serde_json::Map::new(),
        };
        group.put(".zgroup", serde_json::json!({"zarr_format": 2}))?;
        group.put(".zattrs", attributes)?;
        Ok(group)
    }

    fn put(&mut self, key: &str, value: serde_json::Value) -> Result<()> {
        write_json(&self.dir.join(key), &value)?;
        self.metadata.insert(key.to_string(), value);
        Ok(())
    }

    /// Creates the array `name` with named dimensions (xarray's `_ARRAY_DIMENSIONS`) and further
    /// attributes (units, long_name).
    pub fn array(
        &mut self,
        name: &str,
        dimensions: &[&str],
        shape: &[usize],
        chunks: &[usize],
        dtype: ZarrType,
        attributes: serde_json::Value,
    ) -> Result<ZarrArray> {
        assert_eq!(dimensions.len(), shape.len(), "one dimension name per axis");
        assert_eq!(chunks.len(), shape.len(), "one chunk length per axis");
        let dir = self.dir.join(name);
        std::fs::create_dir(&dir).map_err(|e| Error::io(&dir, e))?;
        let zarray = serde_json::json!({
            "zarr_format": 2,
            "shape": shape,
            "chunks": chunks,
            "dtype": dtype.descr(),
            "compressor": {"id": "zlib", "level": ZARR_ZLIB_LEVEL},
            // No fill value: every chunk is written, and a fill value would make xarray mask the
            // zeros of the maps (no contact) as missing.
            "fill_value": null,
            "order": "C",
            "filters": null,
            "dimension_separator": ".",
        });
        let mut attrs = match attributes {
            serde_json::Value::Object(map) => map,
            _ => serde_json::Map::new(),
        };
        attrs.insert("_ARRAY_DIMENSIONS".into(), serde_json::json!(dimensions));
        self.put(&format!("{name}/.zarray"), zarray)?;
        self.put(&format!("{name}/.zattrs"), serde_json::Value::Object(attrs))?;
        Ok(ZarrArray {
            dir,
            shape: shape.to_vec(),
            chunks: chunks.to_vec(),
            dtype,
        })
    }

    /// A one-chunk 1-D array with its values (a coordinate).
    pub fn coordinate_f64(&mut self, name: &str, values: &[f64], attributes: serde_json::Value) -> Result<()> {
        let a = self.array(
            name,
            &[name],
            &[values.len()],
            &[values.len().max(1)],
            ZarrType::F64,
            attributes,
        )?;
        a.write_chunk(&[0], &values.iter().flat_map(|v| v.to_le_bytes()).collect::<Vec<u8>>())
    }

    /// Writes the consolidated metadata; the store is complete.
    pub fn finish(self) -> Result<()> {
        let consolidated = serde_json::json!({"zarr_consolidated_format": 1, "metadata": self.metadata});
        write_json(&self.dir.join(".zmetadata"), &consolidated)
    }
}

impl ZarrArray {
    pub fn dtype(&self) -> ZarrType {
        self.dtype
    }

    /// Writes the chunk at chunk index `index` from its raw little-endian bytes in C order (a
    /// whole chunk: edge chunks are padded to the chunk shape by the caller).
    pub fn write_chunk(&self, index: &[usize], raw: &[u8]) -> Result<()> {
        let name = index.iter().map(|i| i.to_string()).collect::<Vec<_>>().join(".");
        let path = self.dir.join(name);
        atomic_write(&path, |w| {
            let mut z = flate2::write::ZlibEncoder::new(w, flate2::Compression::new(ZARR_ZLIB_LEVEL));
            z.write_all(raw)?;
            z.finish().map(|_| ())
        })
    }

    /// Writes a 2-D map (`nx × ny`, C order, the last two axes) at the leading indices `lead`
    /// (e.g. load and step), split into the array's chunks along the last two axes. `element`
    /// appends one value's bytes.
    pub fn write_map<T: Copy>(
        &self,
        lead: &[usize],
        values: &[T],
        mut element: impl FnMut(T, &mut Vec<u8>),
    ) -> Result<()> {
        let d = self.shape.len();
        assert!(d >= 2 && lead.len() == d - 2, "a map fills the last two axes");
        let (nx, ny) = (self.shape[d - 2], self.shape[d - 1]);
        let (cx, cy) = (self.chunks[d - 2], self.chunks[d - 1]);
        assert_eq!(values.len(), nx * ny, "a map of the array's shape");
        let fill = values[0];
        let mut raw = Vec::new();
        for bx in 0..nx.div_ceil(cx) {
            for by in 0..ny.div_ceil(cy) {
                raw.clear();
                for i in bx * cx..(bx + 1) * cx {
                    for j in by * cy..(by + 1) * cy {
                        // Edge chunks are whole chunks; what lies outside the array is never read.
                        let v = if i < nx && j < ny { values[i * ny + j] } else { fill };
                        element(v, &mut raw);
                    }
                }
                let mut index: Vec<usize> = lead.to_vec();
                index.extend([bx, by]);
                self.write_chunk(&index, &raw)?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zarr_maps_are_split_into_whole_chunks_that_reassemble_to_the_map() {
        use std::io::Read as _;
        let dir = tempfile::tempdir().unwrap();
        let mut group = ZarrGroup::create(&dir.path().join("f.zarr"), serde_json::json!({"title": "t"})).unwrap();
        let (nx, ny) = (5, 3);
        let a = group
            .array(
                "p",
                &["l", "s", "x", "y"],
                &[1, 2, nx, ny],
                &[1, 1, 2, 2],
                ZarrType::U32,
                serde_json::json!({}),
            )
            .unwrap();
        let map: Vec<u32> = (0..(nx * ny) as u32).collect();
        a.write_map(&[0, 1], &map, |v: u32, b| b.extend_from_slice(&v.to_le_bytes()))
            .unwrap();
        group.finish().unwrap();
        let root = dir.path().join("f.zarr");
        let meta: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(root.join(".zmetadata")).unwrap()).unwrap();
        assert_eq!(
            meta["metadata"]["p/.zattrs"]["_ARRAY_DIMENSIONS"],
            serde_json::json!(["l", "s", "x", "y"])
        );
        assert_eq!(meta["metadata"]["p/.zarray"]["chunks"], serde_json::json!([1, 1, 2, 2]));
        let mut back = vec![u32::MAX; nx * ny];
        for bx in 0..3 {
            for by in 0..2 {
                let bytes = std::fs::read(root.join(format!("p/0.1.{bx}.{by}"))).unwrap();
                let mut raw = Vec::new();
                flate2::read::ZlibDecoder::new(&bytes[..])
                    .read_to_end(&mut raw)
                    .unwrap();
                assert_eq!(raw.len(), 2 * 2 * 4, "edge chunks are whole chunks");
                for (e, v) in raw.chunks(4).enumerate() {
                    let (i, j) = (bx * 2 + e / 2, by * 2 + e % 2);
                    if i < nx && j < ny {
                        back[i * ny + j] = u32::from_le_bytes(v.try_into().unwrap());
                    }
                }
            }
        }
        assert_eq!(back, map);
        assert!(!root.join("p/0.0.0.0").exists(), "only the written step has chunks");
    }
}
