//! What the plug-in of a unit refuses, each saying what and how to fix it.

/// An error of the unit plug-in.
#[derive(Debug, thiserror::Error)]
pub enum UnitSensorError {
    /// A column the unit names is not in the record.
    #[error("the record has no column '{name}' ({unit_file} names it; the record's columns: {}): give the record the unit file was written for, or fix the unit file's name", columns.join(", "))]
    MissingColumn {
        /// The column.
        name: String,
        /// The unit file.
        unit_file: String,
        /// The record's columns.
        columns: Vec<String>,
    },
    /// Every segment of a log is shorter than two windows (`min_samples`):
    /// one to fit or compensate, one more for the filter to settle.
    #[error(
        "{file}: the longest of its {segments} segment(s) between time gaps has {longest} samples: {} windows, need at least 2 (a window of {} samples, and as many again for the filter): record longer stretches without gaps, or shorten --window",
        longest / (min_samples / 2).max(1),
        (min_samples / 2).max(1)
    )]
    TooShort {
        /// The log.
        file: String,
        /// Its segments.
        segments: usize,
        /// Samples of its longest segment.
        longest: usize,
        /// The least kept: two windows.
        min_samples: usize,
    },
    /// The record moves and no rate reference is given: its targets would
    /// be the vehicle's motion, not the gyros' errors.
    #[error(
        "{record}: the unit turns (its rate varies by {rate_std_deg_s:.2} deg/s over 1-s averages, > {max_deg_s} deg/s) and no rate reference is given, so each channel's error is not observable (a fit would model the motion): give the rate with --table-rate or --earth-rate on a still or table-mounted record{redundant}"
    )]
    Moving {
        /// The record.
        record: String,
        /// How much it turns.
        rate_std_deg_s: f64,
        /// The most a still record turns.
        max_deg_s: f64,
        /// What a redundant unit offers, or why this one cannot.
        redundant: String,
    },
    /// The ground calibration could not be applied.
    #[error("calibration: {0}")]
    Calibration(String),
    /// A record's series could not be assembled.
    #[error(transparent)]
    Record(#[from] nav_sensors::record::RecordError),
    /// Named signals could not be built.
    #[error(transparent)]
    Signals(#[from] sysid::SignalsError),
    /// An effect id is wrong for the channel.
    #[error(transparent)]
    Effect(#[from] super::effect::UnitEffectError),
    /// Anisoinertia where the rate is not observable.
    #[error(
        "channel {channel}: effect {effect} (anisoinertia) needs a varying angular rate seen by the other gyros, but the rate varies by only {rate_std_deg_s:.3} deg/s (< {min_deg_s} deg/s) or the other gyros do not span three axes: drop it or fit on a rate-table record of a redundant unit"
    )]
    EffectNotObservable {
        /// The channel.
        channel: String,
        /// The effect.
        effect: String,
        /// How much the rate varies.
        rate_std_deg_s: f64,
        /// The least it must.
        min_deg_s: f64,
    },
}
