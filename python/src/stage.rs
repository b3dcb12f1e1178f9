//! Records and calibrations from Python as the files the command reads, in
//! a private temporary folder removed after the call: a DataFrame's columns
//! as a CSV (each number in its shortest round-trip form, so the library
//! reads the bits the frame holds; NaN and infinities as `NaN` and `inf`,
//! which the reader refuses with their line and column, as in a file), a
//! calibration's text as its file. The library then takes its one path, the
//! command's. Messages and record names lose the folder: a frame is named
//! by its label (`DataFrame`, or its `attrs["name"]`), its row `i` being
//! line `i + 2`.

use std::fmt::Write as _;
use std::path::PathBuf;

use numpy::PyReadonlyArray1;
use pyo3::prelude::*;

use crate::error::Error;

/// A record from Python: a log's path, or a frame (label, column names, columns).
pub enum Source {
    Path(PathBuf),
    Frame {
        label: String,
        names: Vec<String>,
        columns: Vec<Vec<f64>>,
    },
}

impl<'a, 'py> FromPyObject<'a, 'py> for Source {
    type Error = PyErr;

    fn extract(ob: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        if let Ok((label, names, columns)) =
            ob.extract::<(String, Vec<String>, Vec<PyReadonlyArray1<'py, f64>>)>()
        {
            let columns = columns
                .iter()
                .map(|c| c.as_array().iter().copied().collect())
                .collect();
            return Ok(Source::Frame {
                label,
                names,
                columns,
            });
        }
        Ok(Source::Path(ob.extract()?))
    }
}

/// A calibration from Python: a file's path, or (file name, text).
#[derive(FromPyObject)]
pub enum CalibrationSource {
    Text(String, String),
    Path(PathBuf),
}

/// The temporary folder of one call.
pub struct Stage {
    dir: tempfile::TempDir,
    prefix: String,
}

impl Stage {
    pub fn new() -> PyResult<Self> {
        let dir = tempfile::Builder::new()
            .prefix("rbf_dtg-")
            .tempdir()
            .map_err(|e| Error::new_err(format!("cannot make a temporary folder: {e}")))?;
        let prefix = format!("{}{}", dir.path().display(), std::path::MAIN_SEPARATOR);
        Ok(Self { dir, prefix })
    }

    /// The folder.
    pub fn dir(&self) -> &std::path::Path {
        self.dir.path()
    }

    /// A path in the folder.
    pub fn file(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    /// The path the library reads `source` from (a frame written first).
    pub fn path(&self, source: &Source) -> PyResult<PathBuf> {
        match source {
            Source::Path(p) => Ok(p.clone()),
            Source::Frame {
                label,
                names,
                columns,
            } => {
                let path = self.file(&label.replace(['/', '\\'], "_"));
                std::fs::write(&path, csv(names, columns))
                    .map_err(|e| Error::new_err(format!("{label}: cannot stage it: {e}")))?;
                Ok(path)
            }
        }
    }

    /// The paths of several records, in order.
    pub fn paths(&self, sources: &[Source]) -> PyResult<Vec<PathBuf>> {
        sources.iter().map(|s| self.path(s)).collect()
    }

    /// The path of a calibration.
    pub fn calibration(&self, source: &CalibrationSource) -> PyResult<PathBuf> {
        match source {
            CalibrationSource::Path(p) => Ok(p.clone()),
            CalibrationSource::Text(name, text) => {
                let path = self.file(name);
                std::fs::write(&path, text)
                    .map_err(|e| Error::new_err(format!("{name}: cannot stage it: {e}")))?;
                Ok(path)
            }
        }
    }

    /// `text` without the folder: what the caller named.
    pub fn clean(&self, text: &str) -> String {
        text.replace(&self.prefix, "")
    }

    /// The one mapping of a library error (as [`crate::error::raise`]), the folder cut out.
    pub fn raise(&self, e: impl Into<anyhow::Error>) -> PyErr {
        let e = e.into();
        Error::new_err(self.clean(&cli_support::failure::message(
            &e,
            cli_support::Style::TRIMMED,
        )))
    }

    /// Records named as the caller named them.
    pub fn rename<T>(&self, records: &mut [(String, T)]) {
        for (name, _) in records {
            *name = self.clean(name);
        }
    }
}

/// A frame as CSV text: the header, then each row; `{}` writes an `f64` in
/// its shortest round-trip form.
fn csv(names: &[String], columns: &[Vec<f64>]) -> String {
    let rows = columns.first().map_or(0, Vec::len);
    let mut text = String::with_capacity(16 * (rows + 1) * names.len().max(1));
    text.push_str(&names.join(","));
    text.push('\n');
    for i in 0..rows {
        for (j, c) in columns.iter().enumerate() {
            if j > 0 {
                text.push(',');
            }
            let _ = write!(text, "{}", c[i]);
        }
        text.push('\n');
    }
    text
}
