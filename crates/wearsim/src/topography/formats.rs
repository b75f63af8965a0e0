//! Height maps read from files: `.npy`, `.npz`, text matrices and x y z columns, and length units.

use std::path::Path;

use crate::error::{Error, Result};
use crate::io::{read_npy_2d, read_npy_2d_from, NpyType};

/// The length units [`metres_per`] knows, from the largest (instrument files state any SI prefix of
/// the metre; ångström as `A` or `Å`, micrometre also as `µm`, `μm` or `micron`).
pub const LENGTH_UNITS: [&str; 11] = ["Gm", "Mm", "km", "m", "cm", "mm", "um", "nm", "A", "pm", "fm"];

/// Metres per unit of a length unit name (one of [`LENGTH_UNITS`]); `field` names the setting in
/// the error.
pub fn metres_per(field: &str, unit: &str) -> Result<f64> {
    Ok(match unit {
        "Gm" => 1e9,
        "Mm" => 1e6,
        "km" => 1e3,
        "m" => 1.0,
        "cm" => 1e-2,
        "mm" => 1e-3,
        "um" | "µm" | "μm" | "micron" => 1e-6,
        "nm" => 1e-9,
        "A" | "Å" => 1e-10,
        "pm" => 1e-12,
        "fm" => 1e-15,
        other => {
            return Err(Error::param(
                field,
                format!(
                    "\"{other}\" is not a length unit wearsim knows; use one of {}",
                    LENGTH_UNITS.join(", ")
                ),
            ))
        }
    })
}

/// A height map read from a file, with the physical size the file states (column files do).
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    pub rows: usize,
    pub cols: usize,
    /// Heights, row-major, in the file's height unit.
    pub heights: Vec<f64>,
    /// Side along x (rows) and y (columns) from the file's coordinates, in its lateral unit.
    pub lengths: Option<(f64, f64)>,
    /// What was noticed while reading (header lines skipped, …).
    pub notes: Vec<String>,
}

/// Reads a height map: `.npy` (float or integer), `.npz` (the array `heights`, or the only 2D array),
/// or text — a matrix of numbers separated by spaces, tabs, commas or semicolons (`.txt`, `.csv`,
/// `.dat`, `.asc`, …), each line a scan line along x and the lines stacked along y (the layout
/// profilometers export and SurfaceTopography reads), or three columns x, y, z on a regular grid.
/// `.npy`/`.npz` arrays are indexed `[x, y]`, as wearsim writes them. Lines starting with `#`, `%` or
/// `//` are comments; non-numeric lines before the first number are a header and skipped.
pub fn read(path: &Path) -> Result<Measured> {
    regular_file(path)?;
    match extension(path).as_str() {
        "npy" => {
            let (rows, cols) = crate::io::npy_shape(path, "a height map")?;
            check_memory(path, rows, cols)?;
            let a = read_npy_2d(path, &HEIGHT_TYPES, "a height map")?;
            Ok(a.into())
        }
        "npz" => read_npz(path),
        _ => read_text(path),
    }
}

/// A NumPy array as a height map: `[x, y]`, sizes from the run file.
impl From<crate::io::Npy2> for Measured {
    fn from(a: crate::io::Npy2) -> Self {
        Measured {
            rows: a.rows,
            cols: a.cols,
            heights: a.values,
            lengths: None,
            notes: Vec::new(),
        }
    }
}

/// Refuses a path that is no regular file: a device (`/dev/zero` reads forever), a pipe, a folder.
pub fn regular_file(path: &Path) -> Result<()> {
    let meta = std::fs::metadata(path).map_err(|e| Error::io(path, e))?;
    if meta.is_dir() {
        return Err(Error::file(
            path,
            "is a folder, where a file is needed; give the height map file's path",
        ));
    }
    if !meta.is_file() {
        return Err(Error::file(
            path,
            "is not a regular file (a device, a pipe or a socket); give a height map file (.npy, .npz or text)",
        ));
    }
    Ok(())
}

/// Memory of reading a height map into a surface, in arrays of its pixels' doubles: the file's
/// data, the values, their copy cropped to even sides and the surface made of it.
const READ_ARRAYS: f64 = 4.0;

/// Refuses a height map of `rows × cols` that this process cannot hold, before reading its data.
fn check_memory(path: &Path, rows: usize, cols: usize) -> Result<()> {
    match crate::check::memory_shortfall("reading the height map", rows, cols, READ_ARRAYS) {
        Some(why) => Err(Error::file(
            path,
            why.replace("lower `grid`", "crop or resample the map"),
        )),
        None => Ok(()),
    }
}

/// The shape (rows, cols) of the height map of an `.npy` or `.npz` file, from its header alone:
/// an archive's array is inflated only as far as its header. `None` for text files.
pub fn array_shape(path: &Path) -> Result<Option<(usize, usize)>> {
    match extension(path).as_str() {
        "npy" => {
            regular_file(path)?;
            crate::io::npy_shape(path, "a height map").map(Some)
        }
        "npz" => {
            regular_file(path)?;
            let (mut archive, chosen) = open_npz(path)?;
            let mut entry = archive
                .by_name(&chosen)
                .map_err(|e| Error::file(path, format!("cannot read {chosen}: {e}")))?;
            let size = entry.size();
            crate::io::npy_shape_from(&mut entry, size, &path.join(&chosen), "a height map").map(Some)
        }
        _ => Ok(None),
    }
}

/// The archive of an `.npz` file and the name of its height map's entry.
fn open_npz(path: &Path) -> Result<(zip::ZipArchive<std::fs::File>, String)> {
    let file = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
    let archive =
        zip::ZipArchive::new(file).map_err(|e| Error::file(path, format!("not a NumPy .npz archive ({e})")))?;
    let names: Vec<String> = archive
        .file_names()
        .filter_map(|n| n.ok().map(|n| n.into_owned()))
        .collect();
    let arrays: Vec<&String> = names.iter().filter(|n| n.ends_with(".npy")).collect();
    let chosen = arrays
        .iter()
        .find(|n| n.as_str() == "heights.npy")
        .or_else(|| arrays.iter().find(|n| n.as_str() == "height.npy"))
        .copied()
        .or(if arrays.len() == 1 { Some(arrays[0]) } else { None })
        .ok_or_else(|| {
            Error::file(
                path,
                format!(
                    "holds the arrays {}; name the height map `heights` (np.savez(file, heights=h))",
                    arrays
                        .iter()
                        .map(|a| a.trim_end_matches(".npy"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            )
        })?
        .clone();
    Ok((archive, chosen))
}

fn read_npz(path: &Path) -> Result<Measured> {
    // The header first, inflating nothing more: a small archive may hold gigabytes of zeros.
    if let Some((rows, cols)) = array_shape(path)? {
        check_memory(path, rows, cols)?;
    }
    let (mut archive, chosen) = open_npz(path)?;
    let mut entry = archive
        .by_name(&chosen)
        .map_err(|e| Error::file(path, format!("cannot read {chosen}: {e}")))?;
    // The size the archive states bounds what the header may promise (the reader checks it).
    let size = entry.size();
    let inner = path.join(&chosen);
    let a = read_npy_2d_from(&mut entry, size, &inner, &HEIGHT_TYPES, "a height map")?;
    Ok(a.into())
}

/// Element types a height map may have.
const HEIGHT_TYPES: [NpyType; 5] = [
    NpyType::Float64,
    NpyType::Float32,
    NpyType::Int64,
    NpyType::Int32,
    NpyType::Int16,
];

/// How the numbers of a text file are separated, read once per file from its data lines.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Separator {
    /// Spaces, tabs or commas (decimal points).
    Plain,
    /// `;` or a tab, as spreadsheets with decimal commas write them: a comma inside a field is
    /// then a decimal comma.
    DecimalComma(char),
}

/// The separator of a text file: `;` when its lines hold one, else a tab when they hold one and a
/// comma (a spreadsheet's tab-separated export with decimal commas), else plain.
fn separator(lines: &[&str]) -> Separator {
    if lines.iter().any(|l| l.contains(';')) {
        Separator::DecimalComma(';')
    } else if lines.iter().any(|l| l.contains('\t') && l.contains(',')) {
        Separator::DecimalComma('\t')
    } else {
        Separator::Plain
    }
}

/// Splits a text line into numbers; `None` when a field is not a number.
fn numbers(line: &str, sep: Separator) -> Option<Vec<f64>> {
    let fields: Vec<String> = match sep {
        Separator::Plain => line
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|f| !f.is_empty())
            .map(str::to_string)
            .collect(),
        // A field with both a point and a comma (1.234,5) is not a number: no thousands separators.
        Separator::DecimalComma(c) => line
            .split(c)
            .map(str::trim)
            .filter(|f| !f.is_empty())
            .map(|f| {
                if f.contains('.') {
                    f.to_string()
                } else {
                    f.replace(',', ".")
                }
            })
            .collect(),
    };
    if fields.is_empty() {
        return None;
    }
    fields
        .iter()
        .map(|f| {
            f.parse::<f64>()
                .ok()
                .filter(|v| !v.is_nan() || f.eq_ignore_ascii_case("nan"))
        })
        .collect()
}

/// Whether a line of a plain file is numbers with decimal commas between spaces (`0,12 -0,5`),
/// which cannot be told from comma-separated integers: such a file is refused with the fix.
fn decimal_commas_between_spaces(line: &str) -> bool {
    let tokens: Vec<&str> = line.split_whitespace().collect();
    tokens.len() >= 2
        && tokens.iter().all(|t| {
            let t = t.strip_prefix('-').unwrap_or(t);
            matches!(t.split_once(','), Some((a, b)) if !a.is_empty() && !b.is_empty()
                && a.bytes().all(|c| c.is_ascii_digit()) && b.bytes().all(|c| c.is_ascii_digit()))
        })
}

fn read_text(path: &Path) -> Result<Measured> {
    let text = std::fs::read_to_string(path).map_err(|e| match e.kind() {
        std::io::ErrorKind::InvalidData => Error::file(
            path,
            "is neither a .npy/.npz array nor text; save the height map as .npy, .npz, CSV or whitespace-separated \
             text, or, for an instrument file (AFM, confocal, .x3p, .opd, .sur, …), convert it with \
             `wearsim surface import FILE --out DIR` (in Python: SurfaceTopography's `read_topography` and \
             `wearsim.heights_and_length`)",
        ),
        _ => Error::io(path, e),
    })?;
    // Spreadsheets ("CSV UTF-8") start the file with a byte-order mark.
    let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
    let is_data =
        |line: &str| !(line.is_empty() || line.starts_with('#') || line.starts_with('%') || line.starts_with("//"));
    let data: Vec<&str> = text.lines().map(str::trim).filter(|l| is_data(l)).collect();
    let sep = separator(&data);
    if sep == Separator::Plain {
        if let Some(line) = data.iter().find(|l| decimal_commas_between_spaces(l)) {
            return Err(Error::file(
                path,
                format!(
                    "\"{}\" has decimal commas between spaces, which wearsim cannot tell from commas between \
                     numbers; save the file with `;` or tabs between numbers (a spreadsheet's CSV with semicolons), \
                     or with decimal points",
                    line.chars().take(60).collect::<String>()
                ),
            ));
        }
    }
    let (rows, header) = number_rows(path, text, sep, is_data)?;
    if rows.is_empty() {
        return Err(Error::file(
            path,
            "holds no numbers; expected a height matrix or x y z columns",
        ));
    }
    let mut notes = Vec::new();
    if header > 0 {
        notes.push(format!("skipped {header} header line(s) of {}", path.display()));
    }
    if rows[0].len() == 3 && rows.len() > 3 {
        return columns_to_grid(path, &rows, notes);
    }
    // Each line is a scan line along x, lines stacked along y (as profilometers export and
    // SurfaceTopography reads them): the map is the transpose of the file's matrix.
    let (lines, per_line) = (rows.len(), rows[0].len());
    let mut heights = Vec::with_capacity(lines * per_line);
    for i in 0..per_line {
        heights.extend(rows.iter().map(|line| line[i]));
    }
    Ok(Measured {
        rows: per_line,
        cols: lines,
        heights,
        lengths: None,
        notes,
    })
}

/// The rows of numbers of a text file's data lines (`is_data`), separated by `sep`, with the count
/// of header lines before them (at most 50 lines that are not numbers); an error for a line of
/// another length than the first's, or a line that is not numbers after the first numbers.
fn number_rows(
    path: &Path,
    text: &str,
    sep: Separator,
    is_data: impl Fn(&str) -> bool,
) -> Result<(Vec<Vec<f64>>, usize)> {
    let mut rows: Vec<Vec<f64>> = Vec::new();
    let mut header = 0;
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if !is_data(line) {
            continue;
        }
        match numbers(line, sep) {
            Some(v) => {
                if let Some(first) = rows.first() {
                    if v.len() != first.len() {
                        return Err(Error::file(
                            path,
                            format!(
                                "line {}: {} numbers where the lines before have {}; a height map has the same number \
                                 of values on every line",
                                k + 1,
                                v.len(),
                                first.len()
                            ),
                        ));
                    }
                }
                rows.push(v);
            }
            None if rows.is_empty() && header < 50 => header += 1,
            None => {
                return Err(Error::file(
                    path,
                    format!(
                        "line {}: \"{}\" is not a list of numbers",
                        k + 1,
                        line.chars().take(60).collect::<String>()
                    ),
                ))
            }
        }
    }
    Ok((rows, header))
}

/// x y z columns on a regular grid → a height matrix (rows along x) and the box size.
fn columns_to_grid(path: &Path, rows: &[Vec<f64>], notes: Vec<String>) -> Result<Measured> {
    let axis = |k: usize| -> Result<(Vec<f64>, f64)> {
        let mut v: Vec<f64> = rows.iter().map(|r| r[k]).collect();
        v.sort_by(f64::total_cmp);
        v.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * (a.abs() + b.abs()).max(1e-300));
        if v.len() < 2 {
            return Err(Error::file(
                path,
                "the x y z columns do not span a grid (one value of x or y)",
            ));
        }
        let step = (v[v.len() - 1] - v[0]) / (v.len() - 1) as f64;
        for w in v.windows(2) {
            if ((w[1] - w[0]) - step).abs() > 1e-6 * step.abs() {
                return Err(Error::file(
                    path,
                    format!(
                        "the {} coordinates are not evenly spaced ({} then {}); resample onto a regular grid",
                        ["x", "y"][k],
                        w[0],
                        w[1]
                    ),
                ));
            }
        }
        Ok((v, step))
    };
    let (xs, dx) = axis(0)?;
    let (ys, dy) = axis(1)?;
    if ((dx - dy) / dx).abs() > 1e-6 {
        return Err(Error::file(
            path,
            format!("the pixels are {dx} × {dy}; wearsim needs square pixels"),
        ));
    }
    let (nx, ny) = (xs.len(), ys.len());
    if rows.len() != nx * ny {
        return Err(Error::file(
            path,
            format!(
                "{} points do not fill the {nx} × {ny} grid their coordinates span",
                rows.len()
            ),
        ));
    }
    let mut heights = vec![f64::NAN; nx * ny];
    for r in rows {
        let i = ((r[0] - xs[0]) / dx).round() as usize;
        let j = ((r[1] - ys[0]) / dy).round() as usize;
        if i >= nx || j >= ny || !heights[i * ny + j].is_nan() {
            return Err(Error::file(
                path,
                format!("the point ({}, {}) is off the grid or given twice", r[0], r[1]),
            ));
        }
        heights[i * ny + j] = r[2];
    }
    Ok(Measured {
        rows: nx,
        cols: ny,
        heights,
        lengths: Some((nx as f64 * dx, ny as f64 * dy)),
        notes,
    })
}

pub(super) fn extension(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default()
}

pub(super) fn is_array(path: &Path) -> bool {
    matches!(extension(path).as_str(), "npy" | "npz")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_si_prefix_an_instrument_states_is_a_length_unit_and_the_error_lists_them() {
        for (unit, metres) in [
            ("km", 1e3),
            ("Gm", 1e9),
            ("Mm", 1e6),
            ("cm", 1e-2),
            ("fm", 1e-15),
            ("µm", 1e-6),
        ] {
            assert_eq!(metres_per("unit", unit).unwrap(), metres, "{unit}");
        }
        for unit in LENGTH_UNITS {
            assert!(metres_per("unit", unit).is_ok(), "{unit}");
        }
        let e = metres_per("height_unit", "furlong").unwrap_err().to_string();
        assert!(e.contains("height_unit") && e.contains("km") && e.contains("fm"), "{e}");
    }

    #[test]
    fn spreadsheet_csv_with_a_byte_order_mark_or_decimal_commas_reads_as_written() {
        let dir = tempfile::tempdir().unwrap();
        let read_text = |name: &str, text: &str| {
            let p = dir.path().join(name);
            std::fs::write(&p, text).unwrap();
            read(&p)
        };
        let plain = read_text("plain.csv", "0.001,-0.002,0.5\n0.25,1e-3,-2\n").unwrap();
        // A byte-order mark is no header: every line is a scan line.
        let bom = read_text("bom.csv", "\u{feff}0.001,-0.002,0.5\n0.25,1e-3,-2\n").unwrap();
        assert_eq!(
            (bom.rows, bom.cols, &bom.heights),
            (plain.rows, plain.cols, &plain.heights)
        );
        assert!(bom.notes.is_empty(), "{:?}", bom.notes);
        // Decimal commas with `;` or tabs between numbers, as European spreadsheets write them.
        for (name, text) in [
            ("semi.csv", "\u{feff}0,001;-0,002;0,5\r\n0,25;1e-3;-2\r\n"),
            ("tab.txt", "0,001\t-0,002\t0,5\n0,25\t1e-3\t-2\n"),
        ] {
            let m = read_text(name, text).unwrap();
            assert_eq!(
                (m.rows, m.cols, &m.heights),
                (plain.rows, plain.cols, &plain.heights),
                "{name}"
            );
        }
        // Decimal commas between spaces cannot be told from comma-separated integers: refused.
        let e = read_text("spaces.txt", "0,001 -0,002 0,5\n0,25 0,1 -2,0\n")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("spaces.txt") && e.contains("decimal commas") && e.contains("`;`"),
            "{e}"
        );
        // A thousands separator is not a number.
        let e = read_text("thousands.csv", "3;4\n1.234,5;2\n").unwrap_err().to_string();
        assert!(e.contains("not a list of numbers"), "{e}");
    }

    #[test]
    fn text_matrices_and_columns_are_read_with_their_errors_named() {
        let dir = tempfile::tempdir().unwrap();
        let matrix = dir.path().join("m.csv");
        std::fs::write(&matrix, "# measured\nx,y\n1,2,3\n4,5,6\n").unwrap();
        let m = read(&matrix).unwrap();
        // Lines are scans along x: 3 pixels along x, 2 along y, indexed [x, y].
        assert_eq!(
            (m.rows, m.cols, m.heights.clone()),
            (3, 2, vec![1.0, 4.0, 2.0, 5.0, 3.0, 6.0])
        );
        assert_eq!(m.notes.len(), 1);
        std::fs::write(&matrix, "1 2 3\n4 5\n").unwrap();
        let e = read(&matrix).unwrap_err().to_string();
        assert!(e.contains("line 2") && e.contains("m.csv"), "{e}");
        // Columns on a 4 × 5 grid of pitch 0.5, in any order.
        let xyz = dir.path().join("p.xyz");
        let mut text = String::from("x y z\n");
        for j in (0..5).rev() {
            for i in 0..4 {
                text += &format!("{} {} {}\n", i as f64 * 0.5, j as f64 * 0.5, (10 * i + j) as f64);
            }
        }
        std::fs::write(&xyz, text).unwrap();
        let g = read(&xyz).unwrap();
        assert_eq!((g.rows, g.cols, g.lengths), (4, 5, Some((2.0, 2.5))));
        assert_eq!(g.heights[2 * 5 + 3], 23.0);
        std::fs::write(&xyz, "0 0 1\n0 1 1\n1 0 1\n1 3 1\n").unwrap();
        assert!(read(&xyz).unwrap_err().to_string().contains("evenly spaced"));
        assert!((metres_per("height_unit", "um").unwrap() - 1e-6).abs() < 1e-21);
        assert!(metres_per("height_unit", "inch")
            .unwrap_err()
            .to_string()
            .contains("`height_unit`"));
    }
}
