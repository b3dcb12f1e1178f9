//! Saving and loading models as JSON with a format version.
//!
//! Floats are written by serde_json's shortest round-trip representation and parsed
//! with its `float_roundtrip` feature, so a loaded model holds bit-identical numbers
//! and predicts bit-identically.

use std::fs::File;
use std::io::{BufReader, BufWriter, Read, Write};
use std::path::{Path, PathBuf};

use serde::Serialize;

use super::fitted::RbfModel;

/// Version of the model file format; bumped on any incompatible change.
///
/// ```
/// assert_eq!(rbf::FORMAT_VERSION, 1);
/// ```
pub const FORMAT_VERSION: u32 = 1;

/// Why a model could not be saved or loaded.
///
/// ```
/// let e = rbf::PersistError::Version { found: Some(9), expected: rbf::FORMAT_VERSION };
/// assert!(e.to_string().contains("9"));
/// ```
#[derive(Debug, thiserror::Error)]
pub enum PersistError {
    /// Reading or writing failed.
    #[error("{}: {source}", path.as_ref().map_or("<stream>".to_string(), |p| p.display().to_string()))]
    Io {
        /// The file, when there is one.
        path: Option<PathBuf>,
        /// The I/O error.
        source: std::io::Error,
    },
    /// Not JSON, or not a model.
    #[error("corrupt model file: {0}")]
    Corrupt(#[source] serde_json::Error),
    /// A missing or different `format_version`.
    #[error("model file format_version {} is not the supported {expected}", found.map_or("missing".to_string(), |v| v.to_string()))]
    Version {
        /// Version found (None when absent or not an integer).
        found: Option<u64>,
        /// Version this library reads.
        expected: u32,
    },
    /// Well-formed JSON describing an inconsistent model (shapes, non-finite values).
    #[error("inconsistent model file: {0}")]
    Inconsistent(String),
}

#[derive(Serialize)]
struct FileRef<'a> {
    format_version: u32,
    model: &'a RbfModel,
}

impl RbfModel {
    /// Writes the model as JSON (`{"format_version": 1, "model": {...}}`).
    ///
    /// # Errors
    /// [`PersistError::Inconsistent`] for a model that would not load back (a
    /// non-finite or out-of-range number), [`PersistError::Io`] or
    /// [`PersistError::Corrupt`] (serialisation).
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// let mut buf = Vec::new();
    /// m.to_writer(&mut buf).unwrap();
    /// assert_eq!(rbf::RbfModel::from_reader(buf.as_slice()).unwrap(), m);
    /// ```
    pub fn to_writer(&self, writer: impl Write) -> Result<(), PersistError> {
        // A model that could not be loaded back is not written.
        self.check_consistency()?;
        let mut w = BufWriter::new(writer);
        serde_json::to_writer_pretty(
            &mut w,
            &FileRef {
                format_version: FORMAT_VERSION,
                model: self,
            },
        )
        .map_err(PersistError::Corrupt)?;
        w.flush()
            .map_err(|source| PersistError::Io { path: None, source })
    }

    /// Reads a model written by [`RbfModel::to_writer`], checking the format version
    /// and the model's consistency.
    ///
    /// # Errors
    /// [`PersistError::Io`], [`PersistError::Corrupt`], [`PersistError::Version`],
    /// [`PersistError::Inconsistent`].
    ///
    /// ```
    /// let e = rbf::RbfModel::from_reader(r#"{"format_version": 0, "model": {}}"#.as_bytes()).unwrap_err();
    /// assert!(matches!(e, rbf::PersistError::Version { found: Some(0), .. }));
    /// assert!(matches!(rbf::RbfModel::from_reader("{".as_bytes()), Err(rbf::PersistError::Corrupt(_))));
    /// ```
    pub fn from_reader(reader: impl Read) -> Result<Self, PersistError> {
        let value: serde_json::Value =
            serde_json::from_reader(BufReader::new(reader)).map_err(|e| {
                if e.is_io() {
                    PersistError::Io {
                        path: None,
                        source: e.into(),
                    }
                } else {
                    PersistError::Corrupt(e)
                }
            })?;
        let found = value
            .get("format_version")
            .and_then(serde_json::Value::as_u64);
        if found != Some(u64::from(FORMAT_VERSION)) {
            return Err(PersistError::Version {
                found,
                expected: FORMAT_VERSION,
            });
        }
        let model_value = value
            .get("model")
            .cloned()
            .ok_or_else(|| PersistError::Inconsistent("no \"model\" entry".into()))?;
        let model: RbfModel = serde_json::from_value(model_value).map_err(PersistError::Corrupt)?;
        model.validate().map_err(PersistError::Inconsistent)?;
        Ok(model)
    }

    /// Checks the consistency of a model deserialised by other means, e.g.
    /// embedded with serde in an application's own file: shapes agree with
    /// `dim`, the centres and outputs, widths are positive, coefficients finite.
    /// [`RbfModel::from_reader`] runs the same check.
    ///
    /// # Errors
    /// [`PersistError::Inconsistent`] naming the first disagreement.
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// assert!(m.check_consistency().is_ok());
    /// let mut v = serde_json::to_value(&m).unwrap();
    /// v["dim"] = serde_json::json!(m.dim() + 1);
    /// let bad: rbf::RbfModel = serde_json::from_value(v).unwrap();
    /// assert!(matches!(bad.check_consistency(), Err(rbf::PersistError::Inconsistent(_))));
    /// ```
    pub fn check_consistency(&self) -> Result<(), PersistError> {
        self.validate().map_err(PersistError::Inconsistent)
    }

    /// Saves the model to a JSON file.
    ///
    /// # Errors
    /// As [`RbfModel::to_writer`], with the path in I/O errors.
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// let path = std::env::temp_dir().join(format!("rbf-doc-{}.json", std::process::id()));
    /// m.save_json(&path).unwrap();
    /// let back = rbf::RbfModel::load_json(&path).unwrap();
    /// std::fs::remove_file(&path).unwrap();
    /// assert_eq!(back, m);
    /// ```
    pub fn save_json(&self, path: impl AsRef<Path>) -> Result<(), PersistError> {
        let path = path.as_ref();
        let io = |source| PersistError::Io {
            path: Some(path.into()),
            source,
        };
        outfile::write_atomic_or(path, io, |w| {
            self.to_writer(w).map_err(|e| match e {
                PersistError::Io { source, .. } => io(source),
                other => other,
            })
        })
    }

    /// Loads a model from a JSON file.
    ///
    /// # Errors
    /// As [`RbfModel::from_reader`], with the path in I/O errors.
    ///
    /// ```
    /// let e = rbf::RbfModel::load_json("/nonexistent/model.json").unwrap_err();
    /// assert!(e.to_string().contains("/nonexistent/model.json"));
    /// ```
    pub fn load_json(path: impl AsRef<Path>) -> Result<Self, PersistError> {
        let path = path.as_ref();
        let file = File::open(path).map_err(|source| PersistError::Io {
            path: Some(path.into()),
            source,
        })?;
        Self::from_reader(file).map_err(|e| match e {
            PersistError::Io { source, .. } => PersistError::Io {
                path: Some(path.into()),
                source,
            },
            other => other,
        })
    }
}
