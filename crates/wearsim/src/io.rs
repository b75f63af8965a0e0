//! File input and output: atomic writes (a temporary sibling renamed into place, so a killed run
//! never leaves a half-written file), text and JSON files, and NumPy `.npy` arrays.
//!
//! `.npy` headers are parsed here before any data is read, so that a header promising more data
//! than the file holds is refused from the file's size instead of by a failed allocation.

use std::io::{BufWriter, Read, Write};
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

use crate::error::{Error, Result};

/// Counter that makes temporary names unique within a process (with the process id, across
/// processes sharing a folder).
static TMP_COUNTER: AtomicU64 = AtomicU64::new(0);

/// A temporary sibling of `path`, unique to this process and call: `.{name}.{pid}-{k}.tmp`.
pub fn temporary_sibling(path: &Path) -> Result<std::path::PathBuf> {
    let name = path.file_name().ok_or_else(|| Error::file(path, "not a file path"))?;
    let k = TMP_COUNTER.fetch_add(1, Ordering::Relaxed);
    Ok(parent_or_dot(path).join(format!(".{}.{}-{k}.tmp", name.to_string_lossy(), std::process::id())))
}

/// The folder holding `path` (`.` for a bare file name).
pub fn parent_or_dot(path: &Path) -> &Path {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    }
}

/// Writes `path` atomically: `write` fills a temporary sibling (named uniquely for this process),
/// which is then flushed, synced and renamed over `path`. On error the temporary file is removed
/// and `path` is untouched.
pub fn atomic_write(path: &Path, write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>) -> Result<()> {
    let tmp = temporary_sibling(path)?;
    let result = (|| -> std::io::Result<()> {
        let file = std::fs::File::create(&tmp)?;
        let mut w = BufWriter::new(file);
        write(&mut w)?;
        let file = w.into_inner().map_err(|e| e.into_error())?;
        file.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(Error::io(path, e));
    }
    Ok(())
}

/// Writes a text file atomically.
pub fn write_text(path: &Path, text: &str) -> Result<()> {
    atomic_write(path, |w| w.write_all(text.as_bytes()))
}

/// Writes a value as pretty-printed JSON, atomically.
pub fn write_json(path: &Path, value: &impl serde::Serialize) -> Result<()> {
    let text = serde_json::to_string_pretty(value).map_err(|e| Error::file(path, format!("cannot encode: {e}")))?;
    write_text(path, &(text + "\n"))
}

/// Reads a whole text file.
pub fn read_text(path: &Path) -> Result<String> {
    std::fs::read_to_string(path).map_err(|e| Error::io(path, e))
}

/// A command's output folder, written as a whole: files go into a temporary sibling folder, which
/// replaces the output folder in one step on [`OutputDir::commit`], so a command's outputs appear
/// together or not at all and never mix with an earlier run's. Made before any work, so that a
/// folder that cannot be written is found before the computation; dropped without a commit, it
/// removes its temporary folder.
#[derive(Debug)]
pub struct OutputDir {
    target: std::path::PathBuf,
    staging: std::path::PathBuf,
    committed: bool,
}

/// The marker file that says which command wrote a folder.
const MARKER: &str = ".wearsim.json";

impl OutputDir {
    /// Prepares to write the outputs of `command` into `target`. An existing `target` must be a
    /// folder that is empty or holds an earlier run of the same command (which the new outputs
    /// replace whole); another command's results, or files wearsim did not write, are refused unless
    /// `overwrite` is set.
    pub fn begin(target: &Path, command: &str, overwrite: bool) -> Result<Self> {
        if target.exists() && !target.is_dir() {
            return Err(Error::file(target, "exists and is not a folder; give another --out"));
        }
        if target.is_dir() && !overwrite {
            let mut entries = std::fs::read_dir(target).map_err(|e| Error::io(target, e))?;
            if entries.next().is_some() {
                let marker = std::fs::read_to_string(target.join(MARKER)).ok();
                let writer = marker
                    .as_deref()
                    .and_then(|t| serde_json::from_str::<serde_json::Value>(t).ok())
                    .and_then(|v| v.get("command").and_then(|c| c.as_str()).map(String::from));
                match writer {
                    Some(c) if c == command => {}
                    Some(c) => {
                        return Err(Error::file(
                            target,
                            format!(
                                "holds the results of `wearsim {c}`; give another --out, or --overwrite to replace \
                                 them with those of `wearsim {command}`"
                            ),
                        ))
                    }
                    None => return Err(Error::file(
                        target,
                        "holds files that wearsim did not write; give another --out, or --overwrite to replace the \
                             folder",
                    )),
                }
            }
        }
        let parent = parent_or_dot(target);
        std::fs::create_dir_all(parent).map_err(|e| Error::io(parent, e))?;
        let staging = temporary_sibling(target)?;
        std::fs::create_dir(&staging).map_err(|e| Error::io(&staging, e))?;
        let dir = Self {
            target: target.to_path_buf(),
            staging,
            committed: false,
        };
        let provenance = serde_json::json!({"command": command, "software": format!("wearsim {}", crate::VERSION)});
        write_json(&dir.join(MARKER), &provenance)?;
        Ok(dir)
    }

    /// Where a file of the outputs is written (inside the temporary folder until the commit).
    pub fn join(&self, name: &str) -> std::path::PathBuf {
        self.staging.join(name)
    }

    /// The folder the outputs will have once committed.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Puts the outputs in place: the temporary folder replaces `target` (an earlier folder there is
    /// moved aside first and removed after).
    pub fn commit(mut self) -> Result<()> {
        let aside = if self.target.exists() {
            let aside = temporary_sibling(&self.target)?;
            std::fs::rename(&self.target, &aside).map_err(|e| Error::io(&self.target, e))?;
            Some(aside)
        } else {
            None
        };
        if let Err(e) = std::fs::rename(&self.staging, &self.target) {
            if let Some(aside) = &aside {
                let _ = std::fs::rename(aside, &self.target);
            }
            return Err(Error::io(&self.target, e));
        }
        self.committed = true;
        if let Some(aside) = aside {
            let _ = std::fs::remove_dir_all(aside);
        }
        Ok(())
    }
}

impl Drop for OutputDir {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.staging);
        }
    }
}

/// Writes several files so that they appear together: each into a temporary sibling, then all
/// renamed into place (a failed write leaves none of them changed).
pub fn write_texts_together(files: &[(&Path, &str)]) -> Result<()> {
    let mut written: Vec<(std::path::PathBuf, &Path)> = Vec::new();
    let result = (|| -> Result<()> {
        for (path, text) in files {
            let tmp = temporary_sibling(path)?;
            written.push((tmp.clone(), path));
            write_text(&tmp, text)?;
        }
        for (tmp, path) in &written {
            std::fs::rename(tmp, path).map_err(|e| Error::io(path, e))?;
        }
        Ok(())
    })();
    if result.is_err() {
        for (tmp, _) in &written {
            let _ = std::fs::remove_file(tmp);
        }
    }
    result
}

/// Element types of `.npy` files that wearsim reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NpyType {
    Float64,
    Float32,
    Int64,
    Int32,
    Int16,
    Int8,
    UInt8,
    Bool,
}

impl NpyType {
    fn from_descr(descr: &str) -> Option<Self> {
        // Byte order: '<' little-endian, '|' not applicable, '=' native (little-endian on every
        // platform wearsim targets).
        let (order, code) = descr.split_at(1.min(descr.len()));
        if !matches!(order, "<" | "|" | "=") {
            return None;
        }
        Some(match code {
            "f8" => NpyType::Float64,
            "f4" => NpyType::Float32,
            "i8" => NpyType::Int64,
            "i4" => NpyType::Int32,
            "i2" => NpyType::Int16,
            "i1" => NpyType::Int8,
            "u1" => NpyType::UInt8,
            "b1" => NpyType::Bool,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            NpyType::Float64 | NpyType::Int64 => 8,
            NpyType::Float32 | NpyType::Int32 => 4,
            NpyType::Int16 => 2,
            NpyType::Int8 | NpyType::UInt8 | NpyType::Bool => 1,
        }
    }

    /// Name as NumPy writes it.
    pub fn name(self) -> &'static str {
        match self {
            NpyType::Float64 => "float64",
            NpyType::Float32 => "float32",
            NpyType::Int64 => "int64",
            NpyType::Int32 => "int32",
            NpyType::Int16 => "int16",
            NpyType::Int8 => "int8",
            NpyType::UInt8 => "uint8",
            NpyType::Bool => "bool",
        }
    }

    fn decode(self, b: &[u8]) -> f64 {
        match self {
            NpyType::Float64 => f64::from_le_bytes(b.try_into().expect("8 bytes")),
            NpyType::Float32 => f32::from_le_bytes(b.try_into().expect("4 bytes")) as f64,
            NpyType::Int64 => i64::from_le_bytes(b.try_into().expect("8 bytes")) as f64,
            NpyType::Int32 => i32::from_le_bytes(b.try_into().expect("4 bytes")) as f64,
            NpyType::Int16 => i16::from_le_bytes(b.try_into().expect("2 bytes")) as f64,
            NpyType::Int8 => b[0] as i8 as f64,
            NpyType::UInt8 => b[0] as f64,
            NpyType::Bool => (b[0] != 0) as u8 as f64,
        }
    }
}

/// A 2D array read from a `.npy` file, as f64 in row-major (C) order whatever the file's order.
#[derive(Debug, Clone, PartialEq)]
pub struct Npy2 {
    pub rows: usize,
    pub cols: usize,
    /// The element type of the file.
    pub dtype: NpyType,
    pub values: Vec<f64>,
}

/// Parsed `.npy` header: element type, memory order, shape, and where the data starts.
struct NpyHeader {
    dtype: NpyType,
    fortran_order: bool,
    shape: Vec<usize>,
    data_offset: usize,
}

fn parse_npy_header(bytes: &[u8]) -> std::result::Result<NpyHeader, String> {
    if bytes.len() < 10 || &bytes[..6] != b"\x93NUMPY" {
        return Err("not a NumPy .npy file (no \\x93NUMPY magic)".into());
    }
    let (len, start) = match bytes[6] {
        1 => (u16::from_le_bytes([bytes[8], bytes[9]]) as usize, 10),
        2 | 3 if bytes.len() >= 12 => (
            u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize,
            12,
        ),
        v => return Err(format!("unsupported .npy format version {v}")),
    };
    let header = bytes.get(start..start + len).ok_or("the .npy header is cut short")?;
    let header = std::str::from_utf8(header).map_err(|_| "the .npy header is not text")?;
    let field = |key: &str| -> std::result::Result<&str, String> {
        let at = header
            .find(&format!("'{key}'"))
            .ok_or(format!("the .npy header has no '{key}'"))?;
        let rest = header[at + key.len() + 2..].trim_start();
        Ok(rest.strip_prefix(':').ok_or("malformed .npy header")?.trim_start())
    };
    let descr = field("descr")?;
    let descr = descr
        .strip_prefix('\'')
        .and_then(|d| d.split('\'').next())
        .ok_or("malformed 'descr' in the .npy header")?;
    let dtype = NpyType::from_descr(descr).ok_or(format!(
        "element type '{descr}' is not supported; save the array as float64, float32, an integer type or bool \
         (little-endian)"
    ))?;
    let fortran_order = field("fortran_order")?.starts_with("True");
    let shape_text = field("shape")?;
    let shape_text = shape_text
        .strip_prefix('(')
        .and_then(|s| s.split(')').next())
        .ok_or("malformed 'shape' in the .npy header")?;
    let shape = shape_text
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| {
            s.trim_end_matches('L')
                .parse::<usize>()
                .map_err(|_| format!("malformed dimension '{s}' in the .npy header"))
        })
        .collect::<std::result::Result<Vec<_>, _>>()?;
    Ok(NpyHeader {
        dtype,
        fortran_order,
        shape,
        data_offset: start + len,
    })
}

/// Opens a `.npy` file and parses its header: the open file (positioned after the header), its size
/// and the header.
fn open_npy(path: &Path) -> Result<(std::fs::File, u64, NpyHeader)> {
    let mut file = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
    let size = file.metadata().map_err(|e| Error::io(path, e))?.len();
    let h = read_npy_header(&mut file, size, path)?;
    Ok((file, size, h))
}

/// Reads and parses a `.npy` header from `reader` (a stream of `size` bytes in all), leaving it at
/// the first data byte; `path` names the source in messages.
fn read_npy_header(reader: &mut impl Read, size: u64, path: &Path) -> Result<NpyHeader> {
    let mut head = vec![0u8; 12];
    let got = read_up_to(reader, &mut head).map_err(|e| Error::io(path, e))?;
    head.truncate(got);
    let header_len = match head.get(6) {
        Some(1) if got >= 10 => 10 + u16::from_le_bytes([head[8], head[9]]) as usize,
        Some(2 | 3) if got >= 12 => 12 + u32::from_le_bytes([head[8], head[9], head[10], head[11]]) as usize,
        _ => 0,
    };
    if header_len as u64 > size.min(1 << 20) {
        return Err(Error::file(
            path,
            format!("not a valid .npy file: its header ({header_len} bytes) runs past the file"),
        ));
    }
    head.resize(header_len.max(got), 0);
    read_up_to(reader, &mut head[got..]).map_err(|e| Error::io(path, e))?;
    // The header is exactly `header_len` bytes (its length field included), so the reader now
    // stands at the data; a stream shorter than the header was refused above.
    parse_npy_header(&head).map_err(|m| Error::file(path, m))
}

/// The shape of a 2D `.npy` array, read from its header alone; `what` names the array in messages.
pub fn npy_shape(path: &Path, what: &str) -> Result<(usize, usize)> {
    let (_, _, h) = open_npy(path)?;
    match h.shape[..] {
        [rows, cols] => Ok((rows, cols)),
        _ => Err(Error::file(
            path,
            format!(
                "{what} must be a 2D array; this one has shape {:?} ({} dimensions)",
                h.shape,
                h.shape.len()
            ),
        )),
    }
}

/// Reads a 2D `.npy` array of one of the `accepted` element types. The header's promise is checked
/// against the file's size before any data is read; `what` names the array in messages.
pub fn read_npy_2d(path: &Path, accepted: &[NpyType], what: &str) -> Result<Npy2> {
    let (mut file, size, h) = open_npy(path)?;
    read_npy_data(&mut file, size, h, path, accepted, what)
}

/// [`read_npy_2d`] from a stream of `size` bytes (an array inside an `.npz` archive); `path` names
/// the source in messages.
pub fn read_npy_2d_from(
    reader: &mut impl Read,
    size: u64,
    path: &Path,
    accepted: &[NpyType],
    what: &str,
) -> Result<Npy2> {
    let h = read_npy_header(reader, size, path)?;
    read_npy_data(reader, size, h, path, accepted, what)
}

fn read_npy_data(
    file: &mut impl Read,
    size: u64,
    h: NpyHeader,
    path: &Path,
    accepted: &[NpyType],
    what: &str,
) -> Result<Npy2> {
    if h.shape.len() != 2 {
        return Err(Error::file(
            path,
            format!(
                "{what} must be a 2D array; this one has shape {:?} ({} dimensions)",
                h.shape,
                h.shape.len()
            ),
        ));
    }
    if !accepted.contains(&h.dtype) {
        let names: Vec<&str> = accepted.iter().map(|t| t.name()).collect();
        return Err(Error::file(
            path,
            format!("{what} is {}; expected {}", h.dtype.name(), names.join(" or ")),
        ));
    }
    let (rows, cols) = (h.shape[0], h.shape[1]);
    let count = rows.checked_mul(cols);
    let bytes = count.and_then(|c| c.checked_mul(h.dtype.size()));
    let available = size.saturating_sub(h.data_offset as u64);
    match bytes {
        Some(b) if (b as u64) <= available => {}
        _ => {
            return Err(Error::file(
                path,
                format!(
                    "the .npy header promises a {rows}×{cols} {} array, but the file holds only {available} bytes of \
                     data; the file is truncated or corrupt",
                    h.dtype.name()
                ),
            ))
        }
    }
    let bytes = bytes.expect("checked above");
    let mut data = vec![0u8; bytes];
    let got = read_up_to(file, &mut data).map_err(|e| Error::io(path, e))?;
    if got != bytes {
        return Err(Error::file(path, "the .npy data is cut short"));
    }
    let size = h.dtype.size();
    let mut values: Vec<f64> = data.chunks_exact(size).map(|b| h.dtype.decode(b)).collect();
    if h.fortran_order && rows > 1 && cols > 1 {
        let column_major = std::mem::take(&mut values);
        values = (0..rows * cols)
            .map(|k| column_major[(k % cols) * rows + k / cols])
            .collect();
    }
    Ok(Npy2 {
        rows,
        cols,
        dtype: h.dtype,
        values,
    })
}

fn read_up_to(r: &mut impl Read, buf: &mut [u8]) -> std::io::Result<usize> {
    let mut filled = 0;
    while filled < buf.len() {
        match r.read(&mut buf[filled..])? {
            0 => break,
            k => filled += k,
        }
    }
    Ok(filled)
}

/// Writes a `rows × cols` float64 array as `.npy`, atomically.
pub fn write_npy_f64(path: &Path, rows: usize, cols: usize, values: &[f64]) -> Result<()> {
    write_npy(path, rows, cols, values)
}

/// Writes a `rows × cols` boolean array as a NumPy `bool` `.npy`, atomically.
pub fn write_npy_bool(path: &Path, rows: usize, cols: usize, values: &[bool]) -> Result<()> {
    write_npy(path, rows, cols, values)
}

/// Writes a `rows × cols` int64 array as `.npy`, atomically (junction labels, −1 outside contact).
pub fn write_npy_i64(path: &Path, rows: usize, cols: usize, values: &[i64]) -> Result<()> {
    write_npy(path, rows, cols, values)
}

fn write_npy<T: ndarray_npy::WritableElement>(path: &Path, rows: usize, cols: usize, values: &[T]) -> Result<()> {
    use ndarray_npy::WriteNpyExt;
    let array = ndarray::ArrayView2::from_shape((rows, cols), values)
        .map_err(|e| Error::file(path, format!("{} values do not fill {rows}×{cols}: {e}", values.len())))?;
    atomic_write(path, |w| array.write_npy(w).map_err(std::io::Error::other))
}

// ---------------------------------------------------------------------------------------------
// Zarr (format 2) stores: the chunked, compressed arrays that xarray, zarr-python and Dask open.

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
/// the whole store appear at once (e.g. inside an [`OutputDir`]).
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
    fn failed_write_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.txt");
        let err = atomic_write(&path, |w| {
            w.write_all(b"half")?;
            Err(std::io::Error::other("boom"))
        });
        assert!(err.is_err());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
        write_text(&path, "whole").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "whole");
    }

    #[test]
    fn an_output_folder_appears_whole_and_refuses_another_commands_results() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        let first = OutputDir::begin(&out, "slide", false).unwrap();
        write_text(&first.join("summary.json"), "{}").unwrap();
        write_text(&first.join("series.csv"), "a\n").unwrap();
        assert!(!out.exists(), "nothing appears before the commit");
        first.commit().unwrap();
        assert!(out.join("series.csv").is_file());
        // The same command replaces the folder whole: no file of the earlier run survives.
        let again = OutputDir::begin(&out, "slide", false).unwrap();
        write_text(&again.join("summary.json"), "{\"new\": 1}").unwrap();
        again.commit().unwrap();
        assert!(!out.join("series.csv").exists());
        // Another command is refused without --overwrite, and the folder is left alone.
        let e = OutputDir::begin(&out, "contact", false).unwrap_err().to_string();
        assert!(e.contains("wearsim slide") && e.contains("--overwrite"), "{e}");
        // A run that fails before its commit leaves no trace.
        let failed = OutputDir::begin(&out, "slide", false).unwrap();
        write_text(&failed.join("series.csv"), "half").unwrap();
        drop(failed);
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
        assert_eq!(
            std::fs::read_to_string(out.join("summary.json")).unwrap(),
            "{\"new\": 1}"
        );
        // A file in the way is refused before any work.
        let file = dir.path().join("file");
        std::fs::write(&file, "x").unwrap();
        assert!(OutputDir::begin(&file, "slide", true)
            .unwrap_err()
            .to_string()
            .contains("not a folder"));
        std::fs::write(dir.path().join("mine.txt"), "x").unwrap();
        assert!(OutputDir::begin(dir.path(), "slide", false)
            .unwrap_err()
            .to_string()
            .contains("did not write"));
    }

    #[test]
    fn npy_round_trip_and_orders() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.npy");
        let values: Vec<f64> = (0..6).map(|k| k as f64 * 0.5).collect();
        write_npy_f64(&path, 2, 3, &values).unwrap();
        let a = read_npy_2d(&path, &[NpyType::Float64], "heights").unwrap();
        assert_eq!((a.rows, a.cols, a.values.clone()), (2, 3, values.clone()));
        assert!(read_npy_2d(&path, &[NpyType::Bool], "map")
            .unwrap_err()
            .to_string()
            .contains("float64"));
        // Fortran order: the same logical array.
        let mut bytes = std::fs::read(&path).unwrap();
        let at = bytes.windows(5).position(|w| w == b"False").unwrap();
        bytes[at..at + 5].copy_from_slice(b"True ");
        let data_at = bytes.len() - 48;
        let column_major = [0.0, 1.5, 0.5, 2.0, 1.0, 2.5];
        for (k, v) in column_major.iter().enumerate() {
            bytes[data_at + 8 * k..data_at + 8 * k + 8].copy_from_slice(&f64::to_le_bytes(*v));
        }
        std::fs::write(&path, &bytes).unwrap();
        assert_eq!(
            read_npy_2d(&path, &[NpyType::Float64], "heights").unwrap().values,
            values
        );
        let labels = dir.path().join("l.npy");
        write_npy_i64(&labels, 1, 2, &[-1, 7]).unwrap();
        assert_eq!(
            read_npy_2d(&labels, &[NpyType::Int64], "labels").unwrap().values,
            vec![-1.0, 7.0]
        );
    }

    #[test]
    fn a_header_promising_more_than_the_file_holds_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("big.npy");
        write_npy_f64(&path, 2, 2, &[0.0; 4]).unwrap();
        let mut bytes = std::fs::read(&path).unwrap();
        // Promise 100000² values in the same header length (the shape fills some of the padding).
        let at = bytes.windows(6).position(|w| w == b"(2, 2)").unwrap();
        let end = bytes[at..].iter().position(|&b| b == b'\n').unwrap() + at;
        let mut header = b"(100000, 100000), }".to_vec();
        header.resize(end - at, b' ');
        bytes.splice(at..end, header);
        std::fs::write(&path, &bytes).unwrap();
        let e = read_npy_2d(&path, &[NpyType::Float64], "heights")
            .unwrap_err()
            .to_string();
        assert!(e.contains("100000×100000") && e.contains("truncated"), "{e}");
        std::fs::write(&path, b"\x93NUMPY\x01\x00\xff\xff").unwrap();
        assert!(read_npy_2d(&path, &[NpyType::Float64], "heights").is_err());
        std::fs::write(&path, b"not numpy").unwrap();
        assert!(read_npy_2d(&path, &[NpyType::Float64], "heights")
            .unwrap_err()
            .to_string()
            .contains("NumPy"));
    }

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
