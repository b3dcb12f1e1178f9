//! From a CSV table to the matrices the library fits: which columns are inputs, which
//! rows train and which validate.
//!
//! Every error names the file, and where a cell is at fault its line and column
//! (`file:line:column`, lines counted with the header as line 1).

use rbf::faer::{Mat, MatRef};
use tabular::{Table, TableError};

/// The values a split column may hold.
///
/// ```
/// assert_eq!(rbf_cli::data::SPLIT_ROLES, ["train", "val"]);
/// ```
pub const SPLIT_ROLES: [&str; 2] = ["train", "val"];

/// Why the columns or rows of a table cannot be used.
///
/// ```
/// let e = rbf_cli::data::DataError::NoInputs { file: "d.csv".into(), available: vec!["y".into()] };
/// assert!(e.to_string().starts_with("d.csv: "));
/// ```
#[derive(Debug, thiserror::Error)]
pub enum DataError {
    /// Reading or parsing the table failed (missing column, bad cell, NaN, I/O).
    #[error(transparent)]
    Table(#[from] TableError),
    /// A split-column cell that is neither `train` nor `val`.
    #[error(
        "{file}:{line}:{column}: column '{name}': '{value}' is not a split role (allowed: {})",
        SPLIT_ROLES.join(", ")
    )]
    BadRole {
        /// File.
        file: String,
        /// 1-based line (the header is line 1).
        line: u64,
        /// 1-based column.
        column: usize,
        /// Column name.
        name: String,
        /// The cell.
        value: String,
    },
    /// No input column is left once the target and split column are set aside.
    #[error("{file}: no numeric input column besides the target and split column (the header has: {})", available.join(", "))]
    NoInputs {
        /// File.
        file: String,
        /// The header.
        available: Vec<String>,
    },
    /// The target was also listed as an input.
    #[error("column '{name}' is both the target and an input; drop it from --inputs")]
    TargetIsInput {
        /// Column name.
        name: String,
    },
    /// An input listed twice.
    #[error("input column '{name}' is listed twice in --inputs")]
    DuplicateInput {
        /// Column name.
        name: String,
    },
    /// No row to train on.
    #[error("{file}: no training rows{why}")]
    NoTrainingRows {
        /// File.
        file: String,
        /// Why (e.g. no cell of the split column says `train`).
        why: String,
    },
}

/// Row indices (0-based data rows, in file order) that train and that validate.
///
/// ```
/// let r = rbf_cli::data::interleaved(5);
/// assert_eq!((r.train, r.val), (vec![0, 2, 4], vec![1, 3]));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TrainVal {
    /// Training rows.
    pub train: Vec<usize>,
    /// Validation rows.
    pub val: Vec<usize>,
}

/// The seed paper's split: even data rows (the first, third, … after the header)
/// train, odd rows validate.
///
/// ```
/// assert_eq!(rbf_cli::data::interleaved(1).val, Vec::<usize>::new());
/// ```
pub fn interleaved(n: usize) -> TrainVal {
    let (train, val) = (0..n).partition(|i| i % 2 == 0);
    TrainVal { train, val }
}

/// Rows marked `train` and `val` in the text column `column`; any other value is an
/// error naming its file, line and column and the allowed values.
///
/// # Errors
/// [`DataError::Table`] if the column is missing, [`DataError::BadRole`],
/// [`DataError::NoTrainingRows`] if no row says `train`.
///
/// ```
/// let t = tabular::Table::from_reader("x,s\n1,train\n2,val\n3,test\n".as_bytes(), "d.csv").unwrap();
/// let e = rbf_cli::data::split_by_column(&t, "s").unwrap_err();
/// assert_eq!(e.to_string(), "d.csv:4:2: column 's': 'test' is not a split role (allowed: train, val)");
/// ```
pub fn split_by_column(table: &Table, column: &str) -> Result<TrainVal, DataError> {
    let col = table.column_index(column)?;
    let mut rows = TrainVal {
        train: Vec::new(),
        val: Vec::new(),
    };
    for (i, cell) in table.text(column)?.into_iter().enumerate() {
        match cell {
            "train" => rows.train.push(i),
            "val" => rows.val.push(i),
            other => {
                return Err(DataError::BadRole {
                    file: table.file().to_string(),
                    line: table.line_of_row(i),
                    column: col + 1,
                    name: column.to_string(),
                    value: other.to_string(),
                });
            }
        }
    }
    if rows.train.is_empty() {
        return Err(DataError::NoTrainingRows {
            file: table.file().to_string(),
            why: format!(" (no cell of column '{column}' says 'train')"),
        });
    }
    Ok(rows)
}

/// The input columns: `explicit` if given (each must exist and differ from the
/// target), otherwise every column but the target and `exclude` that holds numbers.
///
/// A column holds numbers when at least one of its cells parses as one; such a
/// column's other cells must then be numbers too (a typo is reported by
/// [`numeric_matrix`] with its position instead of silently dropping the column).
/// Purely textual columns (labels, dates) are left out.
///
/// # Errors
/// [`DataError::Table`] for a missing explicit column (listing the header),
/// [`DataError::TargetIsInput`], [`DataError::DuplicateInput`],
/// [`DataError::NoInputs`].
///
/// ```
/// let t = tabular::Table::from_reader("a,label,b,y\n1,x,2,3\n4,z,oops,6\n".as_bytes(), "d.csv").unwrap();
/// let cols = rbf_cli::data::input_columns(&t, "y", None, &[]).unwrap();
/// assert_eq!(cols, vec!["a".to_string(), "b".to_string()]);
/// ```
pub fn input_columns(
    table: &Table,
    target: &str,
    explicit: Option<&[String]>,
    exclude: &[&str],
) -> Result<Vec<String>, DataError> {
    if let Some(names) = explicit {
        for (i, name) in names.iter().enumerate() {
            table.column_index(name)?;
            if name == target {
                return Err(DataError::TargetIsInput { name: name.clone() });
            }
            if names[..i].contains(name) {
                return Err(DataError::DuplicateInput { name: name.clone() });
            }
        }
        if !names.is_empty() {
            return Ok(names.to_vec());
        }
    }
    let chosen: Vec<String> = table
        .header()
        .iter()
        .filter(|h| h.as_str() != target && !exclude.contains(&h.as_str()))
        .filter(|h| holds_numbers(table, h))
        .cloned()
        .collect();
    if chosen.is_empty() {
        return Err(DataError::NoInputs {
            file: table.file().to_string(),
            available: table.header().to_vec(),
        });
    }
    Ok(chosen)
}

fn holds_numbers(table: &Table, column: &str) -> bool {
    // An empty table has no evidence either way: count the column in, so that the
    // "too few rows" error is the one the user sees.
    table.is_empty()
        || table
            .text(column)
            .is_ok_and(|cells| cells.iter().any(|c| c.parse::<f64>().is_ok()))
}

/// The named columns as an n × k matrix (rows are the table's data rows).
///
/// # Errors
/// The first missing column, non-numeric or non-finite cell, as `file:line:column`.
///
/// ```
/// let t = tabular::Table::from_reader("a,b\n1,2\n3,4\n".as_bytes(), "d.csv").unwrap();
/// let m = rbf_cli::data::numeric_matrix(&t, &["b".to_string(), "a".to_string()]).unwrap();
/// assert_eq!((m[(1, 0)], m[(1, 1)]), (4.0, 3.0));
/// let e = rbf_cli::data::numeric_matrix(&t, &["c".to_string()]).unwrap_err();
/// assert_eq!(e.to_string(), "d.csv: no column 'c' (the header has: a, b)");
/// ```
pub fn numeric_matrix(table: &Table, names: &[String]) -> Result<Mat<f64>, TableError> {
    let columns = names
        .iter()
        .map(|n| table.numeric(n))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Mat::from_fn(table.len(), names.len(), |i, j| columns[j][i]))
}

/// The rows `rows` of `m`, in that order.
///
/// # Panics
/// If a row index is out of range (a programmer error).
///
/// ```
/// let m = rbf::faer::mat![[1.0], [2.0], [3.0]];
/// assert_eq!(rbf_cli::data::take_rows(m.as_ref(), &[2, 0]), rbf::faer::mat![[3.0], [1.0]]);
/// ```
#[track_caller]
pub fn take_rows(m: MatRef<'_, f64>, rows: &[usize]) -> Mat<f64> {
    Mat::from_fn(rows.len(), m.ncols(), |i, j| m[(rows[i], j)])
}

/// The one column of an n × 1 matrix as a slice-friendly vector.
///
/// ```
/// let m = rbf::faer::mat![[1.0], [2.0]];
/// assert_eq!(rbf_cli::data::column(m.as_ref(), 0), vec![1.0, 2.0]);
/// ```
#[track_caller]
pub fn column(m: MatRef<'_, f64>, j: usize) -> Vec<f64> {
    (0..m.nrows()).map(|i| m[(i, j)]).collect()
}
