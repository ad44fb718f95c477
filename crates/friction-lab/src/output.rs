//! Writing results: files are staged in a temporary folder and the folder is renamed into
//! place whole (see [`crate::artifacts`]); no NaN or infinity is ever written.

use crate::error::AppError;
use friction_models::params::show;
use std::io::Write;
use std::path::Path;

/// Writes `bytes` to `path` (in a temporary folder being assembled) and flushes it to disk.
pub fn write_file(path: &Path, bytes: &[u8]) -> Result<(), AppError> {
    let io = |source| AppError::Io {
        path: path.to_path_buf(),
        source,
    };
    let mut file = std::fs::File::create(path).map_err(io)?;
    file.write_all(bytes).map_err(io)?;
    file.set_permissions(readable_by_all()).map_err(io)?;
    file.sync_all().map_err(io)?;
    Ok(())
}

/// `n` and the noun in its number, for the lines a command prints: `1 body`, `2 bodies`.
pub fn counted(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// A cell of a CSV table.
#[derive(Clone, Debug, PartialEq)]
pub enum Cell {
    /// A number, written in the shortest form that reads back to the same double
    /// ([`show`]).
    Num(f64),
    /// A label.
    Text(String),
}

impl Cell {
    /// An empty cell: a quantity that does not exist for the row.
    pub fn empty() -> Cell {
        Cell::Text(String::new())
    }

    /// A number, or an empty cell where it is undefined (NaN): numeric columns hold numbers
    /// or nothing, never `NaN`.
    pub fn num(x: f64) -> Cell {
        if x.is_nan() {
            Cell::empty()
        } else {
            Cell::Num(x)
        }
    }
}

/// A number of data row `row` (0-based) in `column` of the CSV file `path`, as the files write
/// it ([`show`]); a non-finite number is refused, naming its row and column.
pub fn csv_number(path: &Path, column: &str, row: usize, x: f64) -> Result<String, AppError> {
    if x.is_finite() {
        Ok(show(x))
    } else {
        Err(AppError::NonFinite {
            path: path.to_path_buf(),
            what: format!("column `{column}` of data row {}", row + 1),
            value: x,
        })
    }
}

/// The error of the CSV writer of the file `path`.
pub fn csv_error(path: &Path) -> impl Fn(csv::Error) -> AppError + '_ {
    move |e| AppError::Io {
        path: path.to_path_buf(),
        source: std::io::Error::other(e),
    }
}

/// A CSV table: a header row and rows of cells.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Table {
    /// Column names.
    pub header: Vec<String>,
    /// Rows, each as long as the header.
    pub rows: Vec<Vec<Cell>>,
}

impl Table {
    /// An empty table with these column names.
    pub fn new(header: &[&str]) -> Self {
        Table {
            header: header.iter().map(|s| s.to_string()).collect(),
            rows: Vec::new(),
        }
    }

    /// The table as CSV bytes; fails on a non-finite number, naming its row and column.
    pub fn to_csv(&self, path: &Path) -> Result<Vec<u8>, AppError> {
        let mut w = csv::Writer::from_writer(Vec::new());
        let io = csv_error(path);
        w.write_record(&self.header).map_err(&io)?;
        for (i, row) in self.rows.iter().enumerate() {
            let mut record = Vec::with_capacity(row.len());
            for (cell, name) in row.iter().zip(&self.header) {
                record.push(match cell {
                    Cell::Num(x) => csv_number(path, name, i, *x)?,
                    Cell::Text(s) => s.clone(),
                });
            }
            w.write_record(&record).map_err(&io)?;
        }
        w.into_inner().map_err(|e| io(e.into_error().into()))
    }
}

/// Serialises `value` as pretty JSON. serde_json would write a NaN as `null`, so callers
/// pass only numbers that have already been checked (the same numbers go into a CSV
/// through [`Table::to_csv`], which refuses non-finite values).
pub fn to_json<T: serde::Serialize>(value: &T, path: &Path) -> Result<Vec<u8>, AppError> {
    let mut bytes = serde_json::to_vec_pretty(value).map_err(|e| AppError::Io {
        path: path.to_path_buf(),
        source: std::io::Error::other(e),
    })?;
    bytes.push(b'\n');
    Ok(bytes)
}

/// Results are shared files: rw-r--r--.
#[cfg(unix)]
fn readable_by_all() -> std::fs::Permissions {
    use std::os::unix::fs::PermissionsExt;
    std::fs::Permissions::from_mode(0o644)
}

/// Results are shared files: the platform's default permissions.
#[cfg(not(unix))]
fn readable_by_all() -> std::fs::Permissions {
    std::fs::File::open(".")
        .and_then(|f| f.metadata())
        .map(|m| m.permissions())
        .unwrap_or_else(|_| unreachable!())
}

/// Output folders are shared: rwxr-xr-x rather than the temporary folder's private mode.
pub fn share_folder(dir: &Path) -> std::io::Result<()> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(dir, std::fs::Permissions::from_mode(0o755))?;
    }
    #[cfg(not(unix))]
    let _ = dir;
    Ok(())
}
