//! Tables derived from one typed row each: their columns are the row's serde fields in order, so a
//! column list is never kept by hand. Numbers in Rust's shortest round-trip form; an undefined value
//! (NaN, a missing input) is an empty cell.

use serde::Serialize;
use serde_json::Value;

/// One cell of a table.
#[derive(Debug, Clone, PartialEq)]
pub enum Cell {
    Float(f64),
    Int(i64),
    Text(String),
    /// An undefined number (NaN) or an input that does not apply.
    Empty,
}

impl Cell {
    /// The cell of a JSON value (null: empty; a number: an integer or a float; the rest as text).
    pub fn of(value: &Value) -> Cell {
        match value {
            Value::Null => Cell::Empty,
            Value::Bool(b) => Cell::Text(b.to_string()),
            Value::Number(n) => match (n.as_i64(), n.as_u64(), n.as_f64()) {
                (Some(i), _, _) => Cell::Int(i),
                (None, Some(u), _) => Cell::Int(i64::try_from(u).unwrap_or(i64::MAX)),
                (_, _, Some(f)) => Cell::Float(f),
                _ => Cell::Empty,
            },
            Value::String(s) => Cell::Text(s.clone()),
            other => Cell::Text(other.to_string()),
        }
    }

    /// The cell as CSV text.
    pub fn text(&self) -> String {
        match self {
            Cell::Float(f) if f.is_finite() => format!("{f:e}"),
            Cell::Float(_) | Cell::Empty => String::new(),
            Cell::Int(i) => i.to_string(),
            Cell::Text(s) => s.clone(),
        }
    }

    /// The cell as a number (NaN where it is not one).
    pub fn number(&self) -> f64 {
        match self {
            Cell::Float(f) => *f,
            Cell::Int(i) => *i as f64,
            _ => f64::NAN,
        }
    }
}

/// A table: named columns and rows of cells.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Table {
    pub columns: Vec<String>,
    pub rows: Vec<Vec<Cell>>,
}

/// A cell as JSON, for [`Table::records`]: a whole float as an integer, so that a count a data frame
/// holds as a float (a column with an empty cell) still reads as a count.
fn cell_value(cell: &Cell) -> Value {
    match cell {
        Cell::Empty => Value::Null,
        Cell::Int(i) => Value::from(*i),
        Cell::Float(f) if f.fract() == 0.0 && f.abs() < 9e15 => Value::from(*f as i64),
        Cell::Float(f) => Value::from(*f),
        Cell::Text(t) => Value::from(t.as_str()),
    }
}

/// The fields of a serialised row, in order (nested `#[serde(flatten)]` structs inline).
fn fields<T: Serialize>(row: &T) -> Vec<(String, Value)> {
    match serde_json::to_value(row).expect("result rows serialise to JSON") {
        Value::Object(map) => map.into_iter().collect(),
        other => vec![("value".into(), other)],
    }
}

/// The column names of row type `T`, from a default row.
pub fn columns<T: Serialize + Default>() -> Vec<String> {
    fields(&T::default()).into_iter().map(|(k, _)| k).collect()
}

impl Table {
    /// The table of `rows`, one column per field of `T`.
    pub fn of<T: Serialize + Default>(rows: &[T]) -> Self {
        Self {
            columns: columns::<T>(),
            rows: rows
                .iter()
                .map(|r| fields(r).iter().map(|(_, v)| Cell::of(v)).collect())
                .collect(),
        }
    }

    /// The unit system of a study's table: its `units` column's first cell ("si"), reduced where it
    /// says otherwise or has no such column. The one reading of it for the figures and their labels.
    pub fn units(&self) -> crate::config::Units {
        match self
            .column("units")
            .and_then(|c| self.rows.first().map(|r| r[c].text()))
        {
            Some(u) if u == "si" => crate::config::Units::Si,
            _ => crate::config::Units::Reduced,
        }
    }

    /// Index of a column.
    pub fn column(&self, name: &str) -> Option<usize> {
        self.columns.iter().position(|c| c == name)
    }

    /// Each row as a `T` (the inverse of [`Table::of`]): a column per field of `T`, by name, an
    /// empty cell an absent value; columns `T` does not have are ignored. The error names the row
    /// and the field that is missing or of the wrong kind, for a table a user passed as `what`.
    pub fn records<T: serde::de::DeserializeOwned>(&self, what: &str) -> crate::error::Result<Vec<T>> {
        self.rows
            .iter()
            .enumerate()
            .map(|(i, row)| {
                let object: serde_json::Map<String, Value> = self
                    .columns
                    .iter()
                    .zip(row)
                    .map(|(name, cell)| (name.clone(), cell_value(cell)))
                    .collect();
                serde_json::from_value(Value::Object(object))
                    .map_err(|e| crate::error::Error::param(what, format!("row {i}: {e}")))
            })
            .collect()
    }

    /// A table read back from CSV text: empty cells are [`Cell::Empty`], whole numbers
    /// [`Cell::Int`], other numbers [`Cell::Float`], the rest text.
    pub fn from_csv(text: &str) -> std::result::Result<Self, csv::Error> {
        let mut reader = csv::Reader::from_reader(text.as_bytes());
        let columns: Vec<String> = reader.headers()?.iter().map(String::from).collect();
        let mut rows = Vec::new();
        for record in reader.records() {
            rows.push(
                record?
                    .iter()
                    .map(|t| {
                        if t.is_empty() {
                            Cell::Empty
                        } else if let Ok(i) = t.parse::<i64>() {
                            Cell::Int(i)
                        } else if let Ok(f) = t.parse::<f64>() {
                            Cell::Float(f)
                        } else {
                            Cell::Text(t.to_string())
                        }
                    })
                    .collect(),
            );
        }
        Ok(Self { columns, rows })
    }

    /// The table as CSV (RFC 4180 quoting: text with commas, quotes or newlines stays one field).
    pub fn to_csv(&self) -> String {
        let mut w = csv::Writer::from_writer(Vec::new());
        let write = |w: &mut csv::Writer<Vec<u8>>| -> csv::Result<()> {
            w.write_record(&self.columns)?;
            for row in &self.rows {
                w.write_record(row.iter().map(Cell::text))?;
            }
            w.flush()?;
            Ok(())
        };
        write(&mut w).expect("writing CSV into memory cannot fail");
        String::from_utf8(w.into_inner().expect("flushed")).expect("cells are UTF-8")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_quotes_text_and_leaves_undefined_numbers_empty() {
        #[derive(Default, Serialize)]
        struct Row {
            name: String,
            x: f64,
            n: Option<u64>,
        }
        let rows = [
            Row {
                name: "a, \"b\"\nc".into(),
                x: f64::NAN,
                n: None,
            },
            Row {
                name: "d".into(),
                x: 2.5e-4,
                n: Some(3),
            },
        ];
        let text = Table::of(&rows).to_csv();
        assert_eq!(text, "name,x,n\n\"a, \"\"b\"\"\nc\",,\nd,2.5e-4,3\n");
    }
}
