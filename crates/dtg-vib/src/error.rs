//! The application library's errors: each variant says what is wrong and,
//! where it helps, how to fix it; the command line adds nothing but the exit.

use nav_sensors::geometry::Channel;
use std::path::PathBuf;

/// Everything the dtg-vib pipeline can refuse.
#[derive(Debug, thiserror::Error)]
pub enum DtgVibError {
    /// The identification loop refused (its message, unchanged).
    #[error(transparent)]
    Sysid(#[from] sysid::SysidError),
    /// An error in one of several records.
    #[error("{record}: {source}")]
    InRecord {
        record: String,
        source: Box<DtgVibError>,
    },
    /// The test record is unreadable or invalid (file:line:column inside).
    #[error(transparent)]
    Record(#[from] nav_sensors::record::RecordError),
    /// The calibration file is unreadable or invalid.
    #[error(transparent)]
    Calibration(#[from] nav_sensors::calibration::CalibrationFileError),
    /// A scenario file is unreadable or invalid.
    #[error(transparent)]
    Scenario(#[from] nav_sensors::sim::ScenarioError),
    /// The simulation failed.
    #[error(transparent)]
    Simulation(#[from] nav_sensors::sim::SimError),
    /// A model cannot be exported or run on-line.
    #[error("export: {0}")]
    Export(#[from] crate::onboard::error::ExportError),
    /// An anisoinertia effect on a record whose angular rate does not vary.
    #[error(
        "channel {channel}: effect {effect} (anisoinertia) needs a varying angular rate, but the rate varies by only {rate_std_deg_s:.3} deg/s (< {min_deg_s} deg/s) over the training rows: its rate products would fit the gyros' own noise and drift; drop it or fit on a rate-table record"
    )]
    EffectNotObservable {
        channel: Channel,
        effect: String,
        rate_std_deg_s: f64,
        min_deg_s: f64,
    },
    /// A model file could not be read or written.
    #[error("{path}: {source}")]
    ModelIo {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// A model file is not a dtg-vib model.
    #[error("{path}: not a dtg-vib model file ({reason})")]
    ModelCorrupt { path: PathBuf, reason: String },
    /// A model file of another format version.
    #[error(
        "{path}: model format_version {found} is not the supported {expected}; refit the model with this version"
    )]
    ModelVersion {
        path: PathBuf,
        found: u64,
        expected: u32,
    },
    /// A figure or the report could not be written.
    #[error(transparent)]
    Report(#[from] plot::ReportError),
    /// Writing an output file failed.
    #[error("{path}: {source}")]
    Output {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// An Allan deviation cannot be computed (too short a series).
    #[error("Allan deviation: {0}")]
    Allan(#[from] nav_sensors::noise::AllanError),
    /// Writing a CSV failed.
    #[error(transparent)]
    Table(#[from] tabular::TableError),
    /// A unit's records or effects (the plug-in of any unit).
    #[error(transparent)]
    Unit(#[from] crate::unit_sensor::error::UnitSensorError),
}
