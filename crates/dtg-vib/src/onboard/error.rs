//! Why a model cannot be laid out as onboard tables (and so be exported or
//! run on-line).

/// Why a model cannot be exported.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ExportError {
    /// A zero-phase model needs future samples.
    #[error(
        "the model is zero-phase (its low-pass runs forward and backward, over future samples), so it cannot run on-line: fit it again with `dtg-vib fit --causal`"
    )]
    NotCausal,
    /// Something the onboard layout does not carry.
    #[error("channel {channel}: {what} cannot be exported (the onboard evaluator has {supported})")]
    Unsupported {
        /// The channel (its name: X … Z1, or a unit's gyro).
        channel: String,
        /// What the model has.
        what: String,
        /// What is supported instead.
        supported: &'static str,
    },
    /// More channels, accelerometers or window signals than the onboard
    /// layout holds.
    #[error(
        "the model has {found} {what}; the onboard evaluator and the exported C hold at most {max} (dtg_onboard::MAX_CHANNELS, MAX_ACCELS, MAX_SIGNALS): compensate it with dtg-vib compensate --model"
    )]
    TooMany {
        /// "gyros", "accelerometers" or "window signals".
        what: &'static str,
        /// How many the unit has.
        found: usize,
        /// The most the layout holds.
        max: usize,
    },
    /// The tables were refused by the evaluator (an exporter bug).
    #[error("the exported tables do not read back: {0}")]
    Tables(String),
}
