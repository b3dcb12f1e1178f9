//! The application library's errors: each variant says what is wrong and,
//! where it helps, how to fix it; the command line adds nothing but the exit.

use nav_sensors::geometry::Channel;
use std::path::PathBuf;

/// Everything the dtg-vib pipeline can refuse.
#[derive(Debug, thiserror::Error)]
pub enum DtgVibError {
    /// The k-d tree of operating points cannot be built (non-finite
    /// accelerations reach it only through a hand-edited model file).
    #[error("operating points of the model: {0}; refit the model")]
    OperatingPoints(String),
    /// A command that takes records was given none.
    #[error("no record given: pass --data FILE.csv")]
    NoRecords,
    /// Records fitted together must agree in how they were sampled and in
    /// their extra columns.
    #[error(
        "records {first} and {other} cannot be fitted together: {what}; give records of one sampling rate and the same columns"
    )]
    RecordsDiffer {
        first: String,
        other: String,
        what: String,
    },
    /// An error in one of several records.
    #[error("{record}: {source}")]
    InRecord {
        record: String,
        source: Box<DtgVibError>,
    },
    /// A record named by a flag is not among the records given.
    #[error("{flag} {name}: not one of the --data records ({known}); name one of them")]
    UnknownRecord {
        flag: &'static str,
        name: String,
        known: String,
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
    /// The pre-processing filter cannot be designed or applied.
    #[error("pre-processing filter: {0}")]
    Filter(#[from] crate::signal::FilterError),
    /// A value the pre-processing computed is non-finite or beyond ±1e150
    /// (where squares overflow): said with the record time it belongs to.
    #[error(
        "{what} is {value:e} at t = {t} s (data row {row}), beyond ±1e150 where squares overflow; {hint}"
    )]
    OutOfRange {
        what: String,
        value: f64,
        t: f64,
        /// 1-based data row of the record.
        row: usize,
        hint: &'static str,
    },
    /// The inner cross-validation's folds, kept a leakage gap apart, leave
    /// one of them no training rows.
    #[error(
        "the {n_train} training windows are too few for {folds} cross-validation folds kept {gap} samples apart (a window of {window} samples plus the filter's reach of {filter_memory}): use a longer record, a shorter --window, a higher --cutoff or a larger --train-fraction"
    )]
    InnerFoldsEmpty {
        folds: usize,
        n_train: usize,
        gap: usize,
        window: usize,
        filter_memory: usize,
    },
    /// Every training window is the same point.
    #[error(
        "the windowed signals ({}) do not vary over the training rows, so every window is the same point and the network has nothing to tell apart; window a signal that varies (--window-signals)",
        signals.join(", ")
    )]
    WindowsConstant { signals: Vec<String> },
    /// Windows cannot be formed.
    #[error(transparent)]
    Window(#[from] crate::window::WindowError),
    /// An effect id, `CHANNEL=ID` pair or effect column is wrong.
    #[error(transparent)]
    Effect(#[from] crate::effects::EffectError),
    /// A windowed signal is neither an accelerometer axis nor an extra column.
    #[error("window signal '{name}' is not a record column (use ax, ay, az or an extra column: {})", if available.is_empty() { "the record has none".to_string() } else { available.join(", ") })]
    WindowSignal {
        name: String,
        available: Vec<String>,
    },
    /// Too few windows to train and validate.
    #[error("{what}: {have} windows, need at least {need} ({hint})")]
    TooFewSamples {
        what: &'static str,
        have: usize,
        need: usize,
        hint: &'static str,
    },
    /// An option is out of range.
    #[error("{name} = {value}: {reason}")]
    InvalidOption {
        name: &'static str,
        value: String,
        reason: &'static str,
    },
    /// An effect's regressor is constant over the training rows, so the bias
    /// absorbs it and its coefficient has no estimate.
    #[error(
        "channel {channel}: effect {effect} does not vary over the training rows (it stays at {value:.6}), so its coefficient cannot be told from the bias; drop it or fit on a record where it varies"
    )]
    EffectConstant {
        channel: Channel,
        effect: String,
        value: f64,
    },
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
    /// An effect is (nearly) a linear combination of the bias and the effects
    /// before it on the training rows: the record cannot tell them apart.
    #[error(
        "channel {channel}: effect {effect} is (nearly) a linear combination of the bias{} on the training rows (it keeps {kept:.1e} of its variation): this record cannot tell them apart; drop one of them",
        if earlier.is_empty() { String::new() } else { format!(" and {}", earlier.join(", ")) }
    )]
    EffectsCollinear {
        channel: Channel,
        effect: String,
        earlier: Vec<String>,
        kept: f64,
    },
    /// The RBF fit of one channel failed.
    #[error("channel {channel}: {source}")]
    Fit {
        channel: Channel,
        #[source]
        source: rbf::RbfError,
    },
    /// The record's sample interval differs from the one the model was fitted at.
    #[error(
        "the record is sampled every {record_dt_s} s but the model was fitted at {model_dt_s} s: its filter and windows assume that interval; refit on data at this rate"
    )]
    SampleInterval { record_dt_s: f64, model_dt_s: f64 },
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
}
