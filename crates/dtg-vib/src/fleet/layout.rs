//! The lot's output folder `DIR`: `DIR/lot.json` (which lot, its ids and
//! limits), and per unit `DIR/units/ID/` with `model.json`,
//! `explain.json`, `diagnosis/`, `report/` and `task.json` (written last:
//! the unit is done), or `failed.json` (the unit failed, and why). A
//! task builds its unit's folder under another name and renames it into
//! place, so a unit's folder is either whole or absent.

use super::manifest::{Manifest, Spec};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// A unit's model (`explain --out`).
pub const MODEL: &str = "model.json";
/// A unit's `explain --json`.
pub const EXPLAIN: &str = "explain.json";
/// What `explain` said on stderr.
pub const EXPLAIN_LOG: &str = "explain.log";
/// A unit's diagnosis page folder (`explain --report`).
pub const DIAGNOSIS: &str = "diagnosis";
/// A unit's page folder (the model on its records).
pub const REPORT: &str = "report";
/// The task's record: written last, so its presence says the unit is done.
pub const TASK: &str = "task.json";
/// A failed unit's reason.
pub const FAILED: &str = "failed.json";

/// The lot a folder holds: written by every task (the same each time), read
/// by the summary, which needs neither the manifest nor its files.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LotFile {
    /// The lot's name.
    pub name: String,
    /// The manifest, absolute.
    pub manifest: PathBuf,
    /// The ids, in the manifest's order.
    pub ids: Vec<String>,
    /// The acceptance limits.
    pub spec: Spec,
}

impl LotFile {
    /// The lot of `m`.
    pub fn of(m: &Manifest) -> Self {
        Self {
            name: m.name.clone(),
            manifest: m.path.clone(),
            ids: m.entries.iter().map(|e| e.id.clone()).collect(),
            spec: m.spec.clone(),
        }
    }
}

/// Why the folder cannot hold the lot, or could not be read or written.
#[derive(Debug, thiserror::Error)]
pub enum LayoutError {
    /// A file of the folder.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        #[source]
        source: std::io::Error,
    },
    /// A file of the folder is not what a task writes.
    #[error("{path}: {message}")]
    Json {
        /// The file.
        path: PathBuf,
        /// The parser's message.
        message: String,
    },
    /// The folder holds another manifest's lot.
    #[error(
        "--out {dir}: it holds the lot of {other}, not of {this}: give another --out (a folder holds one lot)"
    )]
    OtherLot {
        /// The folder.
        dir: PathBuf,
        /// Its manifest.
        other: PathBuf,
        /// The manifest given.
        this: PathBuf,
    },
    /// No lot in the folder.
    #[error(
        "--out {dir}: no lot here ({dir}/lot.json is missing): run dtg-vib fleet task or fleet run with --out {dir} first"
    )]
    NoLot {
        /// The folder.
        dir: PathBuf,
    },
}

/// Reads a JSON file of the folder.
pub fn read_json<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T, LayoutError> {
    let text = std::fs::read_to_string(path).map_err(|source| LayoutError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    serde_json::from_str(&text).map_err(|e| LayoutError::Json {
        path: path.to_path_buf(),
        message: e.to_string(),
    })
}

/// Writes a JSON file atomically.
pub fn write_json<T: Serialize>(path: &Path, value: &T) -> Result<(), LayoutError> {
    let text = serde_json::to_string_pretty(value).expect("plain data serialises");
    outfile::write_bytes(path, text + "\n").map_err(|source| LayoutError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// The lot's output folder.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    root: PathBuf,
}

impl Layout {
    /// The folder `dir`.
    pub fn new(dir: impl Into<PathBuf>) -> Self {
        Self { root: dir.into() }
    }

    /// The folder.
    pub fn root(&self) -> &Path {
        &self.root
    }

    /// `DIR/lot.json`.
    pub fn lot_file(&self) -> PathBuf {
        self.root.join("lot.json")
    }

    /// `DIR/units/ID`.
    pub fn unit(&self, id: &str) -> PathBuf {
        self.root.join("units").join(id)
    }

    /// Where this process builds a unit's folder before renaming it into
    /// place: hidden, and its own on any host, so that two runs of one
    /// task (an engine's retry) never write into one folder.
    pub fn staging(&self, id: &str) -> PathBuf {
        self.root
            .join("units")
            .join(format!(".{id}.{}.{}.partial", host(), std::process::id()))
    }

    /// Records that the folder holds `m`'s lot; refuses a folder that holds
    /// another manifest's.
    pub fn claim(&self, m: &Manifest) -> Result<(), LayoutError> {
        let path = self.lot_file();
        if path.exists() {
            let held: LotFile = read_json(&path)?;
            if held.manifest != m.path {
                return Err(LayoutError::OtherLot {
                    dir: self.root.clone(),
                    other: held.manifest,
                    this: m.path.clone(),
                });
            }
        }
        std::fs::create_dir_all(self.root.join("units")).map_err(|source| LayoutError::Io {
            path: self.root.join("units"),
            source,
        })?;
        write_json(&path, &LotFile::of(m))
    }

    /// The lot the folder holds.
    pub fn lot(&self) -> Result<LotFile, LayoutError> {
        let path = self.lot_file();
        if !path.exists() {
            return Err(LayoutError::NoLot {
                dir: self.root.clone(),
            });
        }
        read_json(&path)
    }
}

/// This machine's name (a staging folder's and a task record's).
pub fn host() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .ok()
        .map(|h| h.trim().to_string())
        .filter(|h| !h.is_empty())
        .unwrap_or_else(|| "host".to_string())
}
