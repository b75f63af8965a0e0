//! NumPy `.npy` arrays. Headers are parsed before any data is read, so that a header promising more
//! data than the file holds is refused from the file's size instead of by a failed allocation.

use std::io::Read;
use std::path::Path;

use crate::error::{Error, Result};

use super::atomic::atomic_write;

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
    /// The element type, or the header's `descr` when wearsim reads no such type.
    dtype: std::result::Result<NpyType, String>,
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
    // An unknown type is refused by the reader, which knows what the array is for and which types fit it.
    let dtype = NpyType::from_descr(descr).ok_or_else(|| descr.to_string());
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

/// [`npy_shape`] of an array read from a stream of `size` bytes (inside an `.npz` archive): only
/// its header is read.
pub fn npy_shape_from(reader: &mut impl Read, size: u64, path: &Path, what: &str) -> Result<(usize, usize)> {
    let h = read_npy_header(reader, size, path)?;
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
    let names = || accepted.iter().map(|t| t.name()).collect::<Vec<_>>().join(" or ");
    let dtype = match &h.dtype {
        Ok(t) if accepted.contains(t) => *t,
        Ok(t) => {
            return Err(Error::file(
                path,
                format!("{what} is {}; expected {}", t.name(), names()),
            ))
        }
        Err(descr) => {
            return Err(Error::file(
                path,
                format!(
                    "{what} has element type '{descr}', which wearsim does not read; save it as {} (little-endian)",
                    names()
                ),
            ))
        }
    };
    let (rows, cols) = (h.shape[0], h.shape[1]);
    let count = rows.checked_mul(cols);
    let bytes = count.and_then(|c| c.checked_mul(dtype.size()));
    let available = size.saturating_sub(h.data_offset as u64);
    match bytes {
        Some(b) if (b as u64) <= available => {}
        _ => {
            return Err(Error::file(
                path,
                format!(
                    "the .npy header promises a {rows}×{cols} {} array, but the file holds only {available} bytes of \
                     data; the file is truncated or corrupt",
                    dtype.name()
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
    let size = dtype.size();
    let mut values: Vec<f64> = data.chunks_exact(size).map(|b| dtype.decode(b)).collect();
    if h.fortran_order && rows > 1 && cols > 1 {
        let column_major = std::mem::take(&mut values);
        values = (0..rows * cols)
            .map(|k| column_major[(k % cols) * rows + k / cols])
            .collect();
    }
    Ok(Npy2 {
        rows,
        cols,
        dtype,
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_element_type_wearsim_does_not_read_is_refused_with_the_types_that_fit_the_array() {
        // A complex height map: the advice lists the height types, not bool (which heights refuse).
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("c.npy");
        let mut header = "{'descr': '<c16', 'fortran_order': False, 'shape': (2, 2), }".to_string();
        while !(10 + header.len() + 1).is_multiple_of(64) {
            header.push(' ');
        }
        header.push('\n');
        let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
        bytes.extend((header.len() as u16).to_le_bytes());
        bytes.extend(header.as_bytes());
        bytes.extend([0u8; 64]);
        std::fs::write(&path, bytes).unwrap();
        let e = read_npy_2d(&path, &[NpyType::Float64, NpyType::Float32], "a height map")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("'<c16'") && e.contains("float64 or float32") && !e.contains("bool"),
            "{e}"
        );
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
}
