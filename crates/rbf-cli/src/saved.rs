//! The model file `rbf fit --out` writes and `rbf predict --model` reads.
//!
//! The library's [`RbfModel`] knows its input dimension but not the names of the
//! columns it was fitted on, and `predict` must find its inputs by name (another file
//! may order its columns differently). So the file wraps the library's own model file,
//! unchanged, with the names and its own version:
//!
//! ```json
//! {
//!   "format": "rbf-cli-model",
//!   "format_version": 1,
//!   "target": "y",
//!   "inputs": ["x0", "x1"],
//!   "data": "train.csv",
//!   "rbf": { "format_version": 1, "model": { ... } }
//! }
//! ```
//!
//! The inner object goes back through [`RbfModel::from_reader`], which checks its own
//! version and the model's consistency; numbers round-trip exactly, so a loaded model
//! predicts bit-identically.

use std::io::{Read, Write};
use std::path::Path;

use rbf::{PersistError, RbfModel};
use serde::{Deserialize, Serialize};
use serde_json::Value;

/// The `format` tag of the file.
///
/// ```
/// assert_eq!(rbf_cli::saved::FORMAT, "rbf-cli-model");
/// ```
pub const FORMAT: &str = "rbf-cli-model";

/// Version of the wrapper format; bumped on any incompatible change.
///
/// ```
/// assert_eq!(rbf_cli::saved::FORMAT_VERSION, 1);
/// ```
pub const FORMAT_VERSION: u32 = 1;

/// Why a model file cannot be written or read.
///
/// ```
/// let e = rbf_cli::saved::SavedError::Version { file: "m.json".into(), found: Some(7) };
/// assert_eq!(e.to_string(), "m.json: model file format_version 7, this rbf reads 1; refit the model with this version of rbf");
/// ```
#[derive(Debug, thiserror::Error)]
pub enum SavedError {
    /// The file could not be opened, read or written.
    #[error("{file}: {source}")]
    Io {
        /// File.
        file: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// Not JSON at all (truncated or another kind of file).
    #[error("{file}: corrupt model file, not JSON ({source})")]
    NotJson {
        /// File.
        file: String,
        /// The parser's complaint (with line and column).
        source: serde_json::Error,
    },
    /// JSON, but not a model written by `rbf fit`.
    #[error("{file}: not an rbf model file ({reason}); write one with `rbf fit --out`")]
    NotAModel {
        /// File.
        file: String,
        /// What is missing or wrong.
        reason: String,
    },
    /// A wrapper version this program does not read.
    #[error("{file}: model file format_version {}, this rbf reads {FORMAT_VERSION}; refit the model with this version of rbf", found.map_or("missing".to_string(), |v| v.to_string()))]
    Version {
        /// File.
        file: String,
        /// The version found, if any.
        found: Option<u64>,
    },
    /// The inner library model is corrupt, of another version or inconsistent.
    #[error("{file}: {source}")]
    Model {
        /// File.
        file: String,
        /// The library's error.
        source: PersistError,
    },
}

/// A fitted model with the names of its target and input columns.
///
/// ```
/// use rbf_cli::saved::SavedModel;
/// let saved = SavedModel { target: "y".into(), inputs: vec!["x".into()], data: "d.csv".into(), model: rbf::doc_model() };
/// let mut buf = Vec::new();
/// saved.to_writer(&mut buf).unwrap();
/// let back = SavedModel::from_reader(buf.as_slice(), "mem").unwrap();
/// assert_eq!(back, saved);
/// let x = rbf::faer::mat![[0.3]];
/// assert_eq!(back.model.predict(x.as_ref()), saved.model.predict(x.as_ref()));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct SavedModel {
    /// The target column.
    pub target: String,
    /// The input columns, in the model's input order.
    pub inputs: Vec<String>,
    /// The data file the model was fitted on (for the record).
    pub data: String,
    /// The library model.
    pub model: RbfModel,
}

#[derive(Serialize, Deserialize)]
struct Wrapper {
    format: String,
    format_version: u32,
    target: String,
    inputs: Vec<String>,
    #[serde(default)]
    data: String,
    rbf: Value,
}

impl SavedModel {
    /// Writes the model file as JSON.
    ///
    /// # Errors
    /// [`SavedError::Io`] (the stream is labelled `<stream>`).
    ///
    /// ```
    /// # use rbf_cli::saved::SavedModel;
    /// # let saved = SavedModel { target: "y".into(), inputs: vec!["x".into()], data: String::new(), model: rbf::doc_model() };
    /// let mut buf = Vec::new();
    /// saved.to_writer(&mut buf).unwrap();
    /// assert!(String::from_utf8(buf).unwrap().contains("\"format\": \"rbf-cli-model\""));
    /// ```
    pub fn to_writer(&self, mut writer: impl Write) -> Result<(), SavedError> {
        let io = |source| SavedError::Io {
            file: "<stream>".into(),
            source,
        };
        let mut inner = Vec::new();
        self.model
            .to_writer(&mut inner)
            .map_err(|e| SavedError::Model {
                file: "<stream>".into(),
                source: e,
            })?;
        let rbf: Value = serde_json::from_slice(&inner).map_err(|e| io(e.into()))?;
        let wrapper = Wrapper {
            format: FORMAT.into(),
            format_version: FORMAT_VERSION,
            target: self.target.clone(),
            inputs: self.inputs.clone(),
            data: self.data.clone(),
            rbf,
        };
        serde_json::to_writer_pretty(&mut writer, &wrapper).map_err(|e| io(e.into()))?;
        writer.write_all(b"\n").map_err(io)
    }

    /// Reads a model file; `file` names it in errors.
    ///
    /// # Errors
    /// [`SavedError::NotJson`], [`SavedError::NotAModel`], [`SavedError::Version`],
    /// [`SavedError::Model`] (the inner model's version or consistency),
    /// [`SavedError::Io`].
    ///
    /// ```
    /// use rbf_cli::saved::{SavedError, SavedModel};
    /// let e = SavedModel::from_reader("{\"format\": \"rbf-cli-model\"".as_bytes(), "m.json").unwrap_err();
    /// assert!(matches!(e, SavedError::NotJson { .. }));
    /// let e = SavedModel::from_reader("[1, 2]".as_bytes(), "m.json").unwrap_err();
    /// assert!(matches!(e, SavedError::NotAModel { .. }));
    /// ```
    pub fn from_reader(reader: impl Read, file: &str) -> Result<Self, SavedError> {
        let value: Value =
            serde_json::from_reader(std::io::BufReader::new(reader)).map_err(|e| {
                if e.is_io() {
                    SavedError::Io {
                        file: file.into(),
                        source: e.into(),
                    }
                } else {
                    SavedError::NotJson {
                        file: file.into(),
                        source: e,
                    }
                }
            })?;
        let not_a_model = |reason: String| SavedError::NotAModel {
            file: file.into(),
            reason,
        };
        if value.get("format").and_then(Value::as_str) != Some(FORMAT) {
            return Err(not_a_model(format!("no \"format\": \"{FORMAT}\" entry")));
        }
        let found = value.get("format_version").and_then(Value::as_u64);
        if found != Some(u64::from(FORMAT_VERSION)) {
            return Err(SavedError::Version {
                file: file.into(),
                found,
            });
        }
        let wrapper: Wrapper =
            serde_json::from_value(value).map_err(|e| not_a_model(e.to_string()))?;
        let inner = serde_json::to_vec(&wrapper.rbf).map_err(|e| not_a_model(e.to_string()))?;
        let model =
            RbfModel::from_reader(inner.as_slice()).map_err(|source| SavedError::Model {
                file: file.into(),
                source,
            })?;
        if wrapper.inputs.len() != model.dim() {
            return Err(not_a_model(format!(
                "{} input names for a model of {} inputs",
                wrapper.inputs.len(),
                model.dim()
            )));
        }
        Ok(Self {
            target: wrapper.target,
            inputs: wrapper.inputs,
            data: wrapper.data,
            model,
        })
    }

    /// Saves to a file.
    ///
    /// # Errors
    /// As [`SavedModel::to_writer`], with the path.
    ///
    /// ```
    /// # use rbf_cli::saved::SavedModel;
    /// # let saved = SavedModel { target: "y".into(), inputs: vec!["x".into()], data: String::new(), model: rbf::doc_model() };
    /// let path = std::env::temp_dir().join(format!("rbf-cli-doc-{}.json", std::process::id()));
    /// saved.save(&path).unwrap();
    /// assert_eq!(SavedModel::load(&path).unwrap(), saved);
    /// std::fs::remove_file(&path).unwrap();
    /// ```
    pub fn save(&self, path: impl AsRef<Path>) -> Result<(), SavedError> {
        let path = path.as_ref();
        let name = path.display().to_string();
        let relabel = |e: SavedError| match e {
            SavedError::Io { source, .. } => SavedError::Io {
                file: name.clone(),
                source,
            },
            SavedError::Model { source, .. } => SavedError::Model {
                file: name.clone(),
                source,
            },
            other => other,
        };
        let io = |source| SavedError::Io {
            file: name.clone(),
            source,
        };
        outfile::write_atomic_or(path, io, |out| self.to_writer(out)).map_err(relabel)
    }

    /// Loads from a file.
    ///
    /// # Errors
    /// As [`SavedModel::from_reader`], or the file cannot be opened.
    ///
    /// ```
    /// let e = rbf_cli::saved::SavedModel::load("/nonexistent/m.json").unwrap_err();
    /// assert!(e.to_string().starts_with("/nonexistent/m.json: "));
    /// ```
    pub fn load(path: impl AsRef<Path>) -> Result<Self, SavedError> {
        let path = path.as_ref();
        let name = path.display().to_string();
        let file = std::fs::File::open(path).map_err(|source| SavedError::Io {
            file: name.clone(),
            source,
        })?;
        Self::from_reader(file, &name)
    }
}
