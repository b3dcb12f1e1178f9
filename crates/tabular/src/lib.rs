//! Numeric CSV tables whose every error says where: file, line and column.
//! It is not a data-frame library: no types but text and `f64`, no joins.
//!
//! Both command lines of the workspace (`rbf` and `dtg-vib`) and the test-record
//! format of `nav-sensors` read comma-separated files with a header row. This
//! crate does that once: it keeps every cell as text, remembers the line each
//! row came from, and parses a column into `f64` only when asked, so a bad cell
//! is reported as `file:line:column` with the offending text.
//!
//! ```
//! use tabular::Table;
//!
//! let csv = "t,az,split\n0.00,0.5,train\n0.02,-0.25,val\n";
//! let table = Table::from_reader(csv.as_bytes(), "inline.csv").unwrap();
//! assert_eq!(table.len(), 2);
//! assert_eq!(table.numeric("az").unwrap(), vec![0.5, -0.25]);
//! assert_eq!(table.text("split").unwrap(), vec!["train", "val"]);
//!
//! // A text cell in a numeric column names file, line and column.
//! let bad = Table::from_reader("t,az\n0.0,oops\n".as_bytes(), "bad.csv").unwrap();
//! let err = bad.numeric("az").unwrap_err();
//! assert_eq!(err.to_string(), "bad.csv:2:2: column 'az': 'oops' is not a number");
//! ```

use std::fmt::Write as _;
use std::io::{Read, Write};
use std::path::Path;

/// Everything that can go wrong reading or writing a table.
///
/// Line numbers are 1-based and count the header as line 1; column numbers are
/// 1-based positions in the header.
#[derive(Debug, thiserror::Error)]
pub enum TableError {
    /// The file could not be opened, read or written.
    #[error("{path}: {source}")]
    Io {
        path: String,
        #[source]
        source: std::io::Error,
    },
    /// The CSV itself is malformed (for example a row with a different number
    /// of fields than the header).
    #[error("{file}:{line}: {message}")]
    Malformed {
        file: String,
        line: u64,
        message: String,
    },
    /// The file has no header row.
    #[error("{file}: empty file, expected a header row of column names")]
    NoHeader { file: String },
    /// Two header cells have the same name.
    #[error("{file}:1:{column}: column name '{name}' appears twice")]
    DuplicateColumn {
        file: String,
        column: usize,
        name: String,
    },
    /// A column that was asked for is not in the header.
    #[error("{file}: no column '{name}' (the header has: {})", available.join(", "))]
    MissingColumn {
        file: String,
        name: String,
        available: Vec<String>,
    },
    /// A cell of a numeric column does not parse as a number.
    #[error("{file}:{line}:{column}: column '{name}': '{value}' is not a number")]
    NotANumber {
        file: String,
        line: u64,
        column: usize,
        name: String,
        value: String,
    },
    /// A cell parses as NaN or an infinity.
    #[error("{file}:{line}:{column}: column '{name}': '{value}' is not finite")]
    NotFinite {
        file: String,
        line: u64,
        column: usize,
        name: String,
        value: String,
    },
    /// A cell beyond [`MAX_MAGNITUDE`]: its square, or a sum of such
    /// squares, would overflow `f64` in any fit.
    #[error(
        "{file}:{line}:{column}: column '{name}': '{value}' is beyond ±1e150, where squares overflow f64; rescale the column"
    )]
    TooLarge {
        file: String,
        line: u64,
        column: usize,
        name: String,
        value: String,
    },
    /// A value handed to [`write_csv`] is not finite or beyond
    /// [`MAX_MAGNITUDE`]: written, it would make a file the readers refuse.
    #[error(
        "{path}: column '{name}', data row {row} would be {value:e}, which no reader takes (a number must be finite and within ±1e150); nothing was written"
    )]
    NotWritable {
        path: String,
        name: String,
        /// 1-based data row (file line − 1).
        row: usize,
        value: f64,
    },
    /// Columns handed to [`write_csv`] differ in length.
    #[error("{path}: column '{name}' has {len} values, expected {expected}")]
    RaggedColumns {
        path: String,
        name: String,
        len: usize,
        expected: usize,
    },
}

/// The largest magnitude a numeric cell may hold. Squares of larger values,
/// and sums of a few million such squares, overflow `f64` (1.8e308) in every
/// fit and filter downstream; no measurement comes near it.
pub const MAX_MAGNITUDE: f64 = 1e150;

/// A CSV table held as text, with the source line of every row.
///
/// ```
/// let t = tabular::Table::from_reader("a,b\n1,2\n3,4\n".as_bytes(), "x.csv").unwrap();
/// assert_eq!(t.header(), &["a".to_string(), "b".to_string()]);
/// assert_eq!(t.numeric("b").unwrap(), vec![2.0, 4.0]);
/// assert_eq!(t.line_of_row(1), 3);
/// ```
#[derive(Debug, Clone)]
pub struct Table {
    file: String,
    header: Vec<String>,
    rows: Vec<csv::StringRecord>,
    lines: Vec<u64>,
}

/// Byte offsets where lines end ('\n', "\r\n" or a lone '\r'), to turn a
/// byte position into a 1-based line number.
struct LineIndex<'a> {
    bytes: &'a [u8],
    ends: Vec<u64>,
}

impl<'a> LineIndex<'a> {
    fn new(bytes: &'a [u8]) -> Self {
        let mut ends = Vec::new();
        for (i, &b) in bytes.iter().enumerate() {
            let crlf_tail = b == b'\n' && i > 0 && bytes[i - 1] == b'\r';
            if b == b'\r' || (b == b'\n' && !crlf_tail) {
                ends.push(i as u64);
            }
        }
        Self { bytes, ends }
    }

    /// The line of the record the csv reader started at byte `pos`: that
    /// position is where it began reading, before the comment and blank
    /// lines it skipped, so those are skipped here too.
    fn line_of(&self, pos: u64) -> u64 {
        let mut start = pos as usize;
        // The csv reader may stop between the '\r' and '\n' of a "\r\n".
        if start > 0 && self.bytes.get(start - 1..=start) == Some(b"\r\n") {
            start += 1;
        }
        let mut line = 1 + self.ends.partition_point(|&e| (e as usize) < start);
        while let Some(&end) = self.ends.get(line - 1) {
            let end = end as usize;
            let text = &self.bytes[start.min(end)..end];
            if !(text.is_empty() || text.starts_with(b"#")) {
                break;
            }
            // Past this line's end: one byte, two for "\r\n".
            start = end + 1 + usize::from(self.bytes.get(end..end + 2) == Some(b"\r\n"));
            line += 1;
        }
        line as u64
    }
}

/// Opens a CSV file for [`Table::read`] and [`NumericTable::read`], with the
/// name errors give it.
fn open(path: &Path) -> Result<(std::io::BufReader<std::fs::File>, String), TableError> {
    let name = path.display().to_string();
    match std::fs::File::open(path) {
        Ok(file) => Ok((std::io::BufReader::new(file), name)),
        Err(source) => Err(TableError::Io { path: name, source }),
    }
}

/// The 0-based index of column `name` in `header`, or
/// [`TableError::MissingColumn`] naming `file` and the columns it has.
fn column_index(file: &str, header: &[String], name: &str) -> Result<usize, TableError> {
    header
        .iter()
        .position(|h| h == name)
        .ok_or_else(|| TableError::MissingColumn {
            file: file.to_string(),
            name: name.to_string(),
            available: header.to_vec(),
        })
}

impl Table {
    /// Reads a CSV file with a header row.
    pub fn read(path: impl AsRef<Path>) -> Result<Self, TableError> {
        let (reader, name) = open(path.as_ref())?;
        Self::from_reader(reader, &name)
    }

    /// Reads CSV text from any reader; `file` names the source in errors.
    pub fn from_reader<R: Read>(reader: R, file: &str) -> Result<Self, TableError> {
        let mut t = Self {
            file: file.to_string(),
            header: Vec::new(),
            rows: Vec::new(),
            lines: Vec::new(),
        };
        scan(
            reader,
            file,
            &mut t,
            |t, h, _| t.header = h.to_vec(),
            |t, rec, line| {
                t.lines.push(line);
                t.rows.push(rec.clone());
            },
        )?;
        Ok(t)
    }

    /// The name the table was read from, as used in error messages.
    pub fn file(&self) -> &str {
        &self.file
    }

    /// The column names, in file order.
    pub fn header(&self) -> &[String] {
        &self.header
    }

    /// Number of data rows (the header excluded).
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// True when the file has a header but no data rows.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// The 1-based file line of data row `row` (0-based).
    #[track_caller]
    pub fn line_of_row(&self, row: usize) -> u64 {
        self.lines[row]
    }

    /// Whether a column of that name exists.
    pub fn has_column(&self, name: &str) -> bool {
        self.header.iter().any(|h| h == name)
    }

    /// The 0-based index of a column, or [`TableError::MissingColumn`].
    pub fn column_index(&self, name: &str) -> Result<usize, TableError> {
        column_index(&self.file, &self.header, name)
    }

    /// A column's cells as text.
    pub fn text(&self, name: &str) -> Result<Vec<&str>, TableError> {
        let j = self.column_index(name)?;
        Ok(self.rows.iter().map(|r| r.get(j).unwrap_or("")).collect())
    }

    /// A column parsed as finite `f64`; the first bad cell is reported with
    /// its file, line and column.
    pub fn numeric(&self, name: &str) -> Result<Vec<f64>, TableError> {
        let j = self.column_index(name)?;
        self.rows
            .iter()
            .enumerate()
            .map(|(i, r)| self.parse_cell(i, j, r.get(j).unwrap_or("")))
            .collect()
    }

    /// Names of the columns whose every cell is a finite number, in file
    /// order. An empty table counts every column as numeric.
    pub fn numeric_columns(&self) -> Vec<String> {
        (0..self.header.len())
            .filter(|&j| {
                self.rows.iter().all(|r| {
                    r.get(j)
                        .and_then(|c| c.parse::<f64>().ok())
                        .is_some_and(f64::is_finite)
                })
            })
            .map(|j| self.header[j].clone())
            .collect()
    }

    fn parse_cell(&self, row: usize, col: usize, cell: &str) -> Result<f64, TableError> {
        parse_number(cell).map_err(|kind| {
            kind.error(
                self.file.clone(),
                self.lines[row],
                col + 1,
                self.header[col].clone(),
                cell.to_string(),
            )
        })
    }
}

/// Why a cell is not a number the tables take.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum CellFault {
    NotANumber,
    NotFinite,
    TooLarge,
}

impl CellFault {
    fn error(
        self,
        file: String,
        line: u64,
        column: usize,
        name: String,
        value: String,
    ) -> TableError {
        match self {
            CellFault::NotANumber => TableError::NotANumber {
                file,
                line,
                column,
                name,
                value,
            },
            CellFault::NotFinite => TableError::NotFinite {
                file,
                line,
                column,
                name,
                value,
            },
            CellFault::TooLarge => TableError::TooLarge {
                file,
                line,
                column,
                name,
                value,
            },
        }
    }
}

/// A cell as a finite `f64` within [`MAX_MAGNITUDE`], or why not.
fn parse_number(cell: &str) -> Result<f64, CellFault> {
    match cell.parse::<f64>() {
        Ok(v) => value_fault(v).map_or(Ok(v), Err),
        Err(_) => Err(CellFault::NotANumber),
    }
}

/// Why a number is not one the tables take (`None`: it is).
fn value_fault(v: f64) -> Option<CellFault> {
    if !v.is_finite() {
        Some(CellFault::NotFinite)
    } else if v.abs() > MAX_MAGNITUDE {
        Some(CellFault::TooLarge)
    } else {
        None
    }
}

/// Reads CSV text with a header row, calling `header` once with `state`, the
/// checked column names and an upper bound on the number of data rows, then
/// `row` with `state`, every data record and its 1-based file line.
fn scan<R: Read, S>(
    mut reader: R,
    file: &str,
    state: &mut S,
    header: impl FnOnce(&mut S, &[String], usize),
    mut row: impl FnMut(&mut S, &csv::StringRecord, u64),
) -> Result<(), TableError> {
    // The csv crate counts lines by '\n' only after the first record, so a
    // CRLF file's lines came out one low and a CR-only file's all as 1:
    // lines are counted here from the bytes, for every convention.
    let mut bytes = Vec::new();
    reader
        .read_to_end(&mut bytes)
        .map_err(|source| TableError::Io {
            path: file.to_string(),
            source,
        })?;
    let lines_at = LineIndex::new(&bytes);
    let line_of = |p: Option<&csv::Position>| p.map_or(0, |p| lines_at.line_of(p.byte()));
    let mut rdr = csv::ReaderBuilder::new()
        .has_headers(true)
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .from_reader(bytes.as_slice());
    let malformed = |e: csv::Error| match e.kind() {
        csv::ErrorKind::Io(_) => TableError::Io {
            path: file.to_string(),
            source: std::io::Error::other(e.to_string()),
        },
        _ => TableError::Malformed {
            file: file.to_string(),
            line: line_of(e.position()),
            message: describe_csv_error(&e),
        },
    };
    let names: Vec<String> = rdr
        .headers()
        .map_err(malformed)?
        .iter()
        .map(str::to_string)
        .collect();
    if names.is_empty() || names.iter().all(String::is_empty) {
        return Err(TableError::NoHeader {
            file: file.to_string(),
        });
    }
    for (i, name) in names.iter().enumerate() {
        if names[..i].contains(name) {
            return Err(TableError::DuplicateColumn {
                file: file.to_string(),
                column: i + 1,
                name: name.clone(),
            });
        }
    }
    // Every data row ends a line, bar perhaps the last.
    header(state, &names, lines_at.ends.len() + 1);
    let mut rec = csv::StringRecord::new();
    while rdr.read_record(&mut rec).map_err(malformed)? {
        row(state, &rec, line_of(rec.position()));
    }
    Ok(())
}

/// A CSV table of numbers, parsed cell by cell as it is read: the memory of
/// its `f64` columns (and one line number a row), not of its text, which a
/// [`Table`] keeps (several times the columns' size for a long record). Every
/// cell must be a number; the first bad cell of each column is remembered
/// and reported, with its file, line and column, when the column is asked
/// for, exactly as [`Table::numeric`] reports it.
///
/// ```
/// use tabular::NumericTable;
/// let t = NumericTable::from_reader("t,az\n0.00,0.5\n0.02,-0.25\n".as_bytes(), "in.csv").unwrap();
/// assert_eq!(t.len(), 2);
/// assert_eq!(t.column("az").unwrap(), &[0.5, -0.25]);
/// let bad = NumericTable::from_reader("t,az\n0.0,oops\n".as_bytes(), "bad.csv").unwrap();
/// assert_eq!(bad.column("az").unwrap_err().to_string(), "bad.csv:2:2: column 'az': 'oops' is not a number");
/// assert_eq!(bad.column("t").unwrap(), &[0.0]);
/// ```
#[derive(Debug, Clone)]
pub struct NumericTable {
    file: String,
    header: Vec<String>,
    columns: Vec<Vec<f64>>,
    /// The first bad cell of each column: its row, fault and text.
    faults: Vec<Option<(usize, CellFault, String)>>,
    lines: Vec<u64>,
}

impl NumericTable {
    /// Reads a CSV file with a header row.
    pub fn read(path: impl AsRef<Path>) -> Result<Self, TableError> {
        let (reader, name) = open(path.as_ref())?;
        Self::from_reader(reader, &name)
    }

    /// Reads CSV text from any reader; `file` names the source in errors.
    /// Malformed CSV is an error here; a cell that is not a number only when
    /// its column is asked for.
    pub fn from_reader<R: Read>(reader: R, file: &str) -> Result<Self, TableError> {
        let mut t = Self {
            file: file.to_string(),
            header: Vec::new(),
            columns: Vec::new(),
            faults: Vec::new(),
            lines: Vec::new(),
        };
        scan(
            reader,
            file,
            &mut t,
            |t, h, rows| {
                t.header = h.to_vec();
                t.columns = (0..h.len()).map(|_| Vec::with_capacity(rows)).collect();
                t.faults = vec![None; h.len()];
                t.lines.reserve_exact(rows);
            },
            |t, rec, line| {
                let row = t.lines.len();
                t.lines.push(line);
                for (j, (col, fault)) in t.columns.iter_mut().zip(t.faults.iter_mut()).enumerate() {
                    let cell = rec.get(j).unwrap_or("");
                    match parse_number(cell) {
                        Ok(v) => col.push(v),
                        Err(kind) => {
                            col.push(f64::NAN);
                            if fault.is_none() {
                                *fault = Some((row, kind, cell.to_string()));
                            }
                        }
                    }
                }
            },
        )?;
        Ok(t)
    }

    /// A table of columns already in numbers (a binary log's, say), so
    /// that they meet every check a CSV's columns meet: names unique, one
    /// length, and a value that is not finite or beyond [`MAX_MAGNITUDE`]
    /// refused when its column is asked for. Data row `i` is line `i + 2`,
    /// the line it has in the CSV [`write_csv`] would write of the table.
    ///
    /// ```
    /// use tabular::NumericTable;
    /// let t = NumericTable::from_columns("log.bin", vec!["t".into(), "y".into()],
    ///     vec![vec![0.0, 0.1], vec![1.0, f64::NAN]]).unwrap();
    /// assert_eq!(t.column("t").unwrap(), &[0.0, 0.1]);
    /// assert_eq!(t.column("y").unwrap_err().to_string(), "log.bin:3:2: column 'y': 'NaN' is not finite");
    /// let ragged = NumericTable::from_columns("log.bin", vec!["a".into(), "b".into()], vec![vec![0.0], vec![]]);
    /// assert!(ragged.is_err());
    /// ```
    pub fn from_columns(
        file: &str,
        header: Vec<String>,
        columns: Vec<Vec<f64>>,
    ) -> Result<Self, TableError> {
        assert_eq!(header.len(), columns.len(), "one name per column");
        for (i, name) in header.iter().enumerate() {
            if header[..i].contains(name) {
                return Err(TableError::DuplicateColumn {
                    file: file.to_string(),
                    column: i + 1,
                    name: name.clone(),
                });
            }
        }
        let n = columns.first().map_or(0, Vec::len);
        if let Some((name, c)) = header.iter().zip(&columns).find(|(_, c)| c.len() != n) {
            return Err(TableError::RaggedColumns {
                path: file.to_string(),
                name: name.clone(),
                len: c.len(),
                expected: n,
            });
        }
        let faults = columns
            .iter()
            .map(|c| {
                c.iter()
                    .enumerate()
                    .find_map(|(row, &v)| value_fault(v).map(|kind| (row, kind, v.to_string())))
            })
            .collect();
        Ok(Self {
            file: file.to_string(),
            header,
            columns,
            faults,
            lines: (0..n as u64).map(|i| i + 2).collect(),
        })
    }

    /// The name the table was read from, as used in error messages.
    pub fn file(&self) -> &str {
        &self.file
    }

    /// The column names, in file order.
    pub fn header(&self) -> &[String] {
        &self.header
    }

    /// Number of data rows (the header excluded).
    pub fn len(&self) -> usize {
        self.lines.len()
    }

    /// True when the file has a header but no data rows.
    pub fn is_empty(&self) -> bool {
        self.lines.is_empty()
    }

    /// The 1-based file line of data row `row` (0-based).
    #[track_caller]
    pub fn line_of_row(&self, row: usize) -> u64 {
        self.lines[row]
    }

    /// Whether a column of that name exists.
    pub fn has_column(&self, name: &str) -> bool {
        self.header.iter().any(|h| h == name)
    }

    /// The 0-based index of a column, or [`TableError::MissingColumn`].
    pub fn column_index(&self, name: &str) -> Result<usize, TableError> {
        column_index(&self.file, &self.header, name)
    }

    /// A column of finite `f64`, or its first bad cell with its file, line
    /// and column (the error [`Table::numeric`] gives).
    pub fn column(&self, name: &str) -> Result<&[f64], TableError> {
        let j = self.column_index(name)?;
        match &self.faults[j] {
            None => Ok(&self.columns[j]),
            Some((row, kind, value)) => Err(kind.error(
                self.file.clone(),
                self.lines[*row],
                j + 1,
                self.header[j].clone(),
                value.clone(),
            )),
        }
    }

    /// Moves a column out (an empty one is left behind), or gives its first
    /// bad cell as [`NumericTable::column`] does.
    pub fn take_column(&mut self, name: &str) -> Result<Vec<f64>, TableError> {
        self.column(name)?;
        let j = self.column_index(name)?;
        Ok(std::mem::take(&mut self.columns[j]))
    }
}

fn describe_csv_error(e: &csv::Error) -> String {
    match e.kind() {
        csv::ErrorKind::UnequalLengths {
            expected_len, len, ..
        } => {
            format!("row has {len} fields but the header has {expected_len}")
        }
        csv::ErrorKind::Utf8 { .. } => "invalid UTF-8 text".to_string(),
        _ => e.to_string(),
    }
}

/// Writes named numeric columns as CSV with a header row.
///
/// Numbers are written in Rust's shortest round-trip form, so reading the file
/// back gives the identical `f64` values (and the same inputs give
/// byte-identical files).
///
/// ```
/// let dir = std::env::temp_dir().join("tabular-doc-write");
/// std::fs::create_dir_all(&dir).unwrap();
/// let path = dir.join("out.csv");
/// tabular::write_csv(&path, &["t", "y"], &[&[0.0, 0.02], &[0.1, 1.0 / 3.0]]).unwrap();
/// let back = tabular::Table::read(&path).unwrap();
/// assert_eq!(back.numeric("y").unwrap(), vec![0.1, 1.0 / 3.0]);
/// ```
pub fn write_csv(
    path: impl AsRef<Path>,
    names: &[&str],
    columns: &[&[f64]],
) -> Result<(), TableError> {
    let path = path.as_ref();
    let io = |source| TableError::Io {
        path: path.display().to_string(),
        source,
    };
    let name = path.display().to_string();
    outfile::write_atomic_or(path, io, |out| {
        write_csv_to(out, &name, names, columns).map_err(|e| match e {
            TableError::Io { source, .. } => io(source),
            other => other,
        })
    })
}

/// The first value [`write_csv`] refuses: non-finite, or beyond
/// [`MAX_MAGNITUDE`] (what [`Table::numeric`] would refuse on reading back).
///
/// ```
/// let e = tabular::first_unwritable("o.csv", &["a"], &[&[1.0, f64::NAN]]).unwrap();
/// assert!(e.to_string().starts_with("o.csv: column 'a', data row 2 would be NaN"));
/// assert!(tabular::first_unwritable("o.csv", &["a"], &[&[1.0, -1e150]]).is_none());
/// ```
pub fn first_unwritable(path: &str, names: &[&str], columns: &[&[f64]]) -> Option<TableError> {
    let n = columns.first().map_or(0, |c| c.len());
    (0..n).find_map(|i| {
        columns.iter().zip(names).find_map(|(c, nm)| {
            let v = c[i];
            (!(v.is_finite() && v.abs() <= MAX_MAGNITUDE)).then(|| TableError::NotWritable {
                path: path.to_string(),
                name: nm.to_string(),
                row: i + 1,
                value: v,
            })
        })
    })
}

/// As [`write_csv`], into any writer; `name` labels errors.
#[track_caller]
pub fn write_csv_to<W: Write>(
    out: &mut W,
    name: &str,
    names: &[&str],
    columns: &[&[f64]],
) -> Result<(), TableError> {
    assert_eq!(names.len(), columns.len(), "one name per column");
    let n = columns.first().map_or(0, |c| c.len());
    for (nm, c) in names.iter().zip(columns) {
        if c.len() != n {
            return Err(TableError::RaggedColumns {
                path: name.to_string(),
                name: nm.to_string(),
                len: c.len(),
                expected: n,
            });
        }
    }
    // Checked before the first byte, so a refused table leaves nothing behind.
    if let Some(e) = first_unwritable(name, names, columns) {
        return Err(e);
    }
    let io = |source| TableError::Io {
        path: name.to_string(),
        source,
    };
    let mut line = names.join(",");
    line.push('\n');
    out.write_all(line.as_bytes()).map_err(io)?;
    for i in 0..n {
        line.clear();
        for (j, c) in columns.iter().enumerate() {
            if j > 0 {
                line.push(',');
            }
            // `{}` on f64 is the shortest string that parses back to the same value.
            let _ = write!(line, "{}", c[i]);
        }
        line.push('\n');
        out.write_all(line.as_bytes()).map_err(io)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(text: &str) -> Table {
        Table::from_reader(text.as_bytes(), "t.csv").unwrap()
    }

    #[test]
    fn missing_column_lists_the_header() {
        let err = table("a,b\n1,2\n").numeric("c").unwrap_err();
        assert_eq!(
            err.to_string(),
            "t.csv: no column 'c' (the header has: a, b)"
        );
    }

    #[test]
    fn nan_and_inf_are_rejected_with_location() {
        let t = table("a,b\n1,2\n3,NaN\n4,inf\n");
        let err = t.numeric("b").unwrap_err();
        assert_eq!(
            err.to_string(),
            "t.csv:3:2: column 'b': 'NaN' is not finite"
        );
    }

    #[test]
    fn line_numbers_hold_for_every_line_ending() {
        // (The csv crate ends a comment only at '\n': a CR-only file gets a blank line instead.)
        for (eol, name) in [("\n", "lf"), ("\r\n", "crlf"), ("\r", "cr")] {
            let skipped = if eol == "\r" { "" } else { "# a comment" };
            let text = ["t,x", skipped, "0,1", "1,2", "2,oops", "3,4"].join(eol) + eol;
            let t = Table::from_reader(text.as_bytes(), name).unwrap();
            assert_eq!(
                (0..t.len()).map(|r| t.line_of_row(r)).collect::<Vec<_>>(),
                [3, 4, 5, 6],
                "{name}"
            );
            let e = t.numeric("x").unwrap_err().to_string();
            assert!(e.starts_with(&format!("{name}:5:2:")), "{e}");
            let ragged = ["t,x", "0,1", "1,2,3"].join(eol) + eol;
            match Table::from_reader(ragged.as_bytes(), name).unwrap_err() {
                TableError::Malformed { line, .. } => assert_eq!(line, 3, "{name}"),
                e => panic!("{e}"),
            }
        }
    }

    /// The numeric reader says what the text table says: the same numbers,
    /// lines and errors, for every line ending, comment and bad cell.
    #[test]
    fn numeric_table_agrees_with_the_text_table() {
        let texts = [
            "t,x,y\n0,1,2\n1,2,3\n".to_string(),
            "t,x,y\r\n# c\r\n0,1,oops\r\n1,NaN,3\r\n2,3,1e200\r\n".to_string(),
            "t,x\r0,1\r1,-2.5e-3\r".to_string(),
            " t , x \n 0 , 1 \n\n1,inf\n".to_string(),
            "t,x\n".to_string(),
        ];
        for text in &texts {
            let a = Table::from_reader(text.as_bytes(), "f.csv").unwrap();
            let b = NumericTable::from_reader(text.as_bytes(), "f.csv").unwrap();
            assert_eq!(a.header(), b.header(), "{text:?}");
            assert_eq!(a.len(), b.len(), "{text:?}");
            for r in 0..a.len() {
                assert_eq!(a.line_of_row(r), b.line_of_row(r), "{text:?}");
            }
            for name in a.header().iter().map(String::as_str).chain(["absent"]) {
                match (a.numeric(name), b.column(name)) {
                    (Ok(x), Ok(y)) => assert_eq!(x, y, "{text:?} {name}"),
                    (Err(x), Err(y)) => assert_eq!(x.to_string(), y.to_string(), "{text:?}"),
                    (x, y) => panic!("{text:?} {name}: {x:?} against {y:?}"),
                }
            }
        }
        for bad in ["a,b\n1,2\n3\n", "", "a,b,a\n1,2,3\n"] {
            let a = Table::from_reader(bad.as_bytes(), "f.csv").unwrap_err();
            let b = NumericTable::from_reader(bad.as_bytes(), "f.csv").unwrap_err();
            assert_eq!(a.to_string(), b.to_string());
        }
        let mut t = NumericTable::from_reader("a,b\n1,x\n".as_bytes(), "f.csv").unwrap();
        assert_eq!(t.take_column("a").unwrap(), vec![1.0]);
        assert!(t.take_column("b").is_err());
    }

    #[test]
    fn ragged_row_is_malformed_with_line() {
        let err = Table::from_reader("a,b\n1,2\n3\n".as_bytes(), "t.csv").unwrap_err();
        match err {
            TableError::Malformed { line, .. } => assert_eq!(line, 3),
            other => panic!("unexpected {other}"),
        }
    }

    #[test]
    fn duplicate_header_is_rejected() {
        let err = Table::from_reader("a,b,a\n1,2,3\n".as_bytes(), "t.csv").unwrap_err();
        assert!(
            matches!(err, TableError::DuplicateColumn { column: 3, .. }),
            "{err}"
        );
    }

    #[test]
    fn empty_file_has_no_header() {
        let err = Table::from_reader("".as_bytes(), "t.csv").unwrap_err();
        assert!(matches!(err, TableError::NoHeader { .. }), "{err}");
    }

    #[test]
    fn numeric_columns_skip_text() {
        let t = table("a,s,b\n1,train,2\n3,val,x\n");
        assert_eq!(t.numeric_columns(), vec!["a".to_string()]);
    }

    #[test]
    fn comment_lines_keep_true_line_numbers() {
        let t = table("a\n# note\n1\nz\n");
        let err = t.numeric("a").unwrap_err();
        assert_eq!(
            err.to_string(),
            "t.csv:4:1: column 'a': 'z' is not a number"
        );
    }

    #[test]
    fn round_trip_is_exact_and_byte_stable() {
        let x: Vec<f64> = (0..50)
            .map(|i| (i as f64 * 0.37).sin() * 1e-7 + i as f64)
            .collect();
        let mut a = Vec::new();
        write_csv_to(&mut a, "mem", &["x"], &[&x]).unwrap();
        let back = Table::from_reader(a.as_slice(), "mem")
            .unwrap()
            .numeric("x")
            .unwrap();
        assert_eq!(back, x);
        let mut b = Vec::new();
        write_csv_to(&mut b, "mem", &["x"], &[&back]).unwrap();
        assert_eq!(a, b);
    }

    #[test]
    fn ragged_columns_are_an_error_not_a_panic() {
        let mut sink = Vec::new();
        let err = write_csv_to(&mut sink, "mem", &["a", "b"], &[&[1.0, 2.0], &[1.0]]).unwrap_err();
        assert!(matches!(
            err,
            TableError::RaggedColumns {
                len: 1,
                expected: 2,
                ..
            }
        ));
    }
}
