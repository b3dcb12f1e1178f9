//! Why tables or a step were refused.

use crate::layout::LAYOUT_2;
#[cfg(doc)]
use crate::layout::{MAGIC, MAX_ACCELS, MAX_CHANNELS, MAX_SIGNALS, VERSION};

/// Why tables or a step were refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Error {
    /// The bytes do not start with [`MAGIC`].
    Magic,
    /// A layout version this crate does not read.
    Version {
        /// Version in the tables.
        found: u32,
        /// The newest version read here ([`VERSION`]; from [`LAYOUT_2`] on).
        supported: u32,
    },
    /// More channels or accelerometers than the evaluator's arrays hold.
    TooMany {
        /// "channels", "accelerometers" or "window signals".
        what: &'static str,
        /// How many the tables have.
        found: usize,
        /// The most read here ([`MAX_CHANNELS`], [`MAX_ACCELS`],
        /// [`MAX_SIGNALS`]).
        max: usize,
    },
    /// The tables end before what their header announces.
    Truncated {
        /// Bytes the header announces.
        need: usize,
        /// Bytes given.
        have: usize,
    },
    /// A header field is out of range (an unknown effect kind, a signal or
    /// column index beyond the extra columns, a zero window).
    Header {
        /// The header word, counted from 0.
        word: usize,
    },
    /// The state buffer is smaller than [`Model::state_len`](crate::Model::state_len).
    StateTooSmall {
        /// Elements needed.
        need: usize,
        /// Elements given.
        have: usize,
    },
    /// A step was given another number of gyro outputs or accelerations
    /// than the model has.
    Sensors {
        /// "gyro outputs" or "accelerations".
        what: &'static str,
        /// How many the model has.
        need: usize,
        /// How many were given.
        have: usize,
    },
    /// A step was given another number of extra columns than the model reads.
    Extra {
        /// Columns the model reads ([`Model::n_extra`](crate::Model::n_extra)).
        need: usize,
        /// Columns given.
        have: usize,
    },
}

impl core::fmt::Display for Error {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Error::Magic => f.write_str("not onboard tables (the bytes do not start with DTGO)"),
            Error::Version { found, supported } => write!(
                f,
                "onboard tables of layout version {found}; this evaluator reads versions {LAYOUT_2} to {supported}: export the model again"
            ),
            Error::TooMany { what, found, max } => write!(
                f,
                "onboard tables of {found} {what}; this evaluator holds at most {max}"
            ),
            Error::Sensors { what, need, have } => {
                write!(f, "{have} {what} given; the model has {need}")
            }
            Error::Truncated { need, have } => write!(
                f,
                "onboard tables are {have} bytes, their header announces {need}: the file is cut short"
            ),
            Error::Header { word } => {
                write!(f, "onboard tables: header word {word} is out of range")
            }
            Error::StateTooSmall { need, have } => write!(
                f,
                "state buffer of {have} elements; the model needs {need} (Model::state_len)"
            ),
            Error::Extra { need, have } => {
                write!(f, "{have} extra columns given; the model reads {need}")
            }
        }
    }
}
