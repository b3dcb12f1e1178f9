//! What the loop can refuse: each variant says what is wrong and, where it
//! helps, how to fix it. A plug-in's own error passes through as it is.

use crate::sensor::SensorError;

/// Everything the identification loop can refuse.
#[derive(Debug, thiserror::Error)]
pub enum SysidError {
    /// The plug-in refused (its message, unchanged).
    #[error(transparent)]
    Sensor(SensorError),
    /// Columns cannot form a record.
    #[error(transparent)]
    Signals(#[from] crate::signals::SignalsError),
    /// The k-d tree of operating points cannot be built (non-finite
    /// operating signals reach it only through a hand-edited model).
    #[error("operating points of the model: {0}; refit the model")]
    OperatingPoints(String),
    /// A call that takes records was given none.
    #[error("no record given: pass --data FILE.csv")]
    NoRecords,
    /// Records fitted together must agree in how they were sampled and in
    /// their extra columns.
    #[error(
        "records {first} and {other} cannot be fitted together: {what}; give records of one sampling rate and the same columns"
    )]
    RecordsDiffer {
        /// The first record.
        first: String,
        /// The one that differs.
        other: String,
        /// How.
        what: String,
    },
    /// An error in one of several records.
    #[error("{record}: {source}")]
    InRecord {
        /// The record's name.
        record: String,
        /// The error.
        source: Box<SysidError>,
    },
    /// A record named by a flag is not among the records given.
    #[error("{flag} {name}: not one of the --data records ({known}); name one of them")]
    UnknownRecord {
        /// The flag.
        flag: &'static str,
        /// The name given.
        name: String,
        /// The records' names.
        known: String,
    },
    /// The pre-processing filter cannot be designed or applied.
    #[error("pre-processing filter: {0}")]
    Filter(#[from] iir::FilterError),
    /// A value the pre-processing computed is non-finite or beyond ±1e150
    /// (where squares overflow): said with the record time it belongs to.
    #[error(
        "{what} is {value:e} at t = {t} s (data row {row}), beyond ±1e150 where squares overflow; {hint}"
    )]
    OutOfRange {
        /// What holds the value.
        what: String,
        /// The value.
        value: f64,
        /// Its time, s.
        t: f64,
        /// 1-based data row of the record.
        row: usize,
        /// What to check.
        hint: &'static str,
    },
    /// The diagnosis's mirror (the recipe trained on the model's validation
    /// rows) cannot be fitted: its inner folds, kept a leakage gap apart,
    /// leave one of them no training rows. The model itself fitted; a
    /// longer record, a shorter window or more validation rows let the
    /// diagnosis run.
    #[error(
        "the diagnosis fits the model's mirror on its {n_val} validation windows, too few for {folds} cross-validation folds kept {gap} samples apart (a window of {window} samples plus the filter's reach of {filter_memory}): use a longer record, a shorter --window, a higher --cutoff or a smaller --train-fraction (the model itself fitted)"
    )]
    MirrorFoldsEmpty {
        /// Folds asked for.
        folds: usize,
        /// The model's validation windows, the mirror's training rows.
        n_val: usize,
        /// The leakage gap, samples.
        gap: usize,
        /// The window length, samples.
        window: usize,
        /// The filter's reach, samples.
        filter_memory: usize,
    },
    /// The inner cross-validation's folds, kept a leakage gap apart, leave
    /// one of them no training rows.
    #[error(
        "the {n_train} training windows are too few for {folds} cross-validation folds kept {gap} samples apart (a window of {window} samples plus the filter's reach of {filter_memory}): use a longer record, a shorter --window, a higher --cutoff or a larger --train-fraction"
    )]
    InnerFoldsEmpty {
        /// Folds asked for.
        folds: usize,
        /// Training windows.
        n_train: usize,
        /// The leakage gap, samples.
        gap: usize,
        /// The window length, samples.
        window: usize,
        /// The filter's reach, samples.
        filter_memory: usize,
    },
    /// Every training window is the same point.
    #[error(
        "the windowed signals ({}) do not vary over the training rows, so every window is the same point and the network has nothing to tell apart; window a signal that varies (--window-signals)",
        signals.join(", ")
    )]
    WindowsConstant {
        /// The windowed signals.
        signals: Vec<String>,
    },
    /// Windows cannot be formed.
    #[error(transparent)]
    Window(#[from] crate::window::WindowError),
    /// The sensor has no channel: nothing to fit, predict or diagnose.
    #[error(
        "the sensor has no channel (no output to model): describe at least one (an inertial unit: one gyro)"
    )]
    NoChannels,
    /// The window names each channel's signals, for another number of
    /// channels than the sensor's.
    #[error(
        "the window names the signals of {lists} channels, not of each of the sensor's {channels}: give one list per channel (preprocess.window.channels), or one list for every channel (preprocess.window.signals)"
    )]
    WindowChannels {
        /// The window's per-channel lists.
        lists: usize,
        /// The sensor's channels.
        channels: usize,
    },
    /// A windowed signal is not one a window may read: not a column of the
    /// record, or not an operating signal (an output, say).
    #[error("window signal '{name}' cannot be windowed: a window reads the sensor's operating signals ({}) or an extra column of the record ({})", operating.join(", "), if available.is_empty() { "it has none".to_string() } else { available.join(", ") })]
    WindowSignal {
        /// The signal asked for.
        name: String,
        /// The sensor's operating signals.
        operating: Vec<String>,
        /// The record's extra columns.
        available: Vec<String>,
    },
    /// The window's signals could not be chosen from the records.
    #[error(transparent)]
    WindowSignals(#[from] crate::window::signal_choice::WindowSignalsError),
    /// Too few windows to train and validate.
    #[error("{what}: {have} windows, need at least {need} ({hint})")]
    TooFewSamples {
        /// Which windows.
        what: &'static str,
        /// How many there are.
        have: usize,
        /// How many are needed.
        need: usize,
        /// What to change.
        hint: &'static str,
    },
    /// An option is out of range.
    #[error("{name} = {value}: {reason}")]
    InvalidOption {
        /// The option.
        name: &'static str,
        /// Its value.
        value: String,
        /// Why it cannot be.
        reason: &'static str,
    },
    /// An effect's regressor is constant over the training rows, so the bias
    /// absorbs it and its coefficient has no estimate.
    #[error(
        "channel {channel}: effect {effect} does not vary over the training rows (it stays at {value:.6}), so its coefficient cannot be told from the bias; drop it or fit on a record where it varies"
    )]
    EffectConstant {
        /// The channel's name.
        channel: String,
        /// The effect's id.
        effect: String,
        /// The value it stays at.
        value: f64,
    },
    /// An effect is (nearly) a linear combination of the bias and the effects
    /// before it on the training rows: the record cannot tell them apart.
    #[error(
        "channel {channel}: effect {effect} is (nearly) a linear combination of the bias{} on the training rows (it keeps {kept:.1e} of its variation): this record cannot tell them apart; drop one of them",
        if earlier.is_empty() { String::new() } else { format!(" and {}", earlier.join(", ")) }
    )]
    EffectsCollinear {
        /// The channel's name.
        channel: String,
        /// The effect's id.
        effect: String,
        /// The effects before it.
        earlier: Vec<String>,
        /// The share of its variation it keeps.
        kept: f64,
    },
    /// The RBF fit of one channel failed.
    #[error("channel {channel}: {source}")]
    Fit {
        /// The channel's name.
        channel: String,
        /// Why.
        #[source]
        source: rbf::RbfError,
    },
    /// The record's median sample interval differs from that of the records
    /// the model was fitted on by more than [`crate::signals::INTERVAL_TOLERANCE`].
    #[error(
        "the record is sampled every {record_dt_s} s (median interval) but the model was fitted at {model_dt_s} s, more than {pct} % apart: its filters and windows assume that interval; refit on data at this rate",
        pct = 100.0 * crate::signals::INTERVAL_TOLERANCE
    )]
    SampleInterval {
        /// The record's median, s.
        record_dt_s: f64,
        /// The model's records' median, s.
        model_dt_s: f64,
    },
}

impl SysidError {
    /// The error in record `name` of several (`count` records given): one
    /// record's error is said as it is.
    pub fn in_record(self, name: &str, count: usize) -> Self {
        match count {
            1 => self,
            _ => SysidError::InRecord {
                record: name.to_string(),
                source: Box::new(self),
            },
        }
    }
}
