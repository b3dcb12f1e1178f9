//! Training and validation rows.
//!
//! Windows of 50 samples overlap by 49 with their neighbours, and the
//! zero-phase filter spreads each sample over a few more. An interleaved
//! split (the paper's: alternate windows) therefore validates on rows that
//! are nearly copies of training rows and flatters a model; the blocked split
//! trains on the first part and validates on the last, with a gap wide enough
//! that no sample reaches both. Blocked is the default.

use crate::error::DtgVibError;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// How rows are split into training and validation.
///
/// ```
/// use dtg_vib::split::SplitKind;
/// let s: SplitKind = "interleaved".parse().unwrap();
/// let (train, val) = s.rows(100, 3).unwrap();
/// assert_eq!(&train[..3], [0, 2, 4]);
/// assert_eq!(&val[..3], [1, 3, 5]);
/// // Blocked: the first half trains; the gap keeps rows 50..53 out of both.
/// let (train, val) = SplitKind::Blocked { train_fraction: 0.5 }.rows(100, 3).unwrap();
/// assert_eq!((train.len(), val[0]), (50, 53));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum SplitKind {
    /// The first `train_fraction` of the rows train; after a gap, the rest validate.
    Blocked {
        /// Fraction of rows that train, in (0, 1).
        train_fraction: f64,
    },
    /// Even rows train, odd rows validate (the paper's alternate vectors).
    Interleaved,
}

impl Default for SplitKind {
    /// Blocked, half and half.
    fn default() -> Self {
        SplitKind::Blocked {
            train_fraction: 0.5,
        }
    }
}

/// Fewest rows on either side of a split.
pub const MIN_ROWS: usize = 20;

impl SplitKind {
    /// Training and validation rows of `n` rows; `gap` rows after the
    /// training block are dropped (blocked only).
    pub fn rows(&self, n: usize, gap: usize) -> Result<(Vec<usize>, Vec<usize>), DtgVibError> {
        let (train, val): (Vec<usize>, Vec<usize>) = match *self {
            SplitKind::Interleaved => ((0..n).step_by(2).collect(), (1..n).step_by(2).collect()),
            SplitKind::Blocked { train_fraction } => {
                if !(train_fraction > 0.0 && train_fraction < 1.0) {
                    return Err(DtgVibError::InvalidOption {
                        name: "train fraction",
                        value: train_fraction.to_string(),
                        reason: "must lie strictly between 0 and 1",
                    });
                }
                let n_train = (n as f64 * train_fraction).round() as usize;
                (
                    (0..n_train).collect(),
                    ((n_train + gap).min(n)..n).collect(),
                )
            }
        };
        for (what, rows) in [("training rows", &train), ("validation rows", &val)] {
            if rows.len() < MIN_ROWS {
                return Err(DtgVibError::TooFewSamples {
                    what,
                    have: rows.len(),
                    need: MIN_ROWS,
                    hint: "use a longer record, a shorter --window, or another --train-fraction",
                });
            }
        }
        Ok((train, val))
    }
}

/// Record samples between consecutive rows of a split's part: 1 for a
/// blocked part, 2 for the alternate rows of an interleaved one. A series on
/// those rows is sampled at `1 / (spacing · dt)`, which spectra and lags of
/// it must use.
///
/// ```
/// use dtg_vib::split::{row_spacing, SplitKind};
/// let (train, val) = SplitKind::Interleaved.rows(100, 0).unwrap();
/// assert_eq!((row_spacing(&train), row_spacing(&val)), (2, 2));
/// let (_, val) = SplitKind::default().rows(100, 3).unwrap();
/// assert_eq!(row_spacing(&val), 1);
/// ```
pub fn row_spacing(rows: &[usize]) -> usize {
    rows.windows(2)
        .map(|w| w[1] - w[0])
        .min()
        .unwrap_or(1)
        .max(1)
}

impl fmt::Display for SplitKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SplitKind::Blocked { train_fraction } => {
                write!(f, "blocked ({:.0}% train)", train_fraction * 100.0)
            }
            SplitKind::Interleaved => f.write_str("interleaved"),
        }
    }
}

impl FromStr for SplitKind {
    type Err = DtgVibError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim() {
            "blocked" => Ok(SplitKind::default()),
            "interleaved" => Ok(SplitKind::Interleaved),
            other => Err(DtgVibError::InvalidOption {
                name: "split",
                value: other.to_string(),
                reason: "use blocked or interleaved",
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocked_rows_never_touch_across_the_gap() {
        let (train, val) = SplitKind::Blocked {
            train_fraction: 0.6,
        }
        .rows(1000, 70)
        .unwrap();
        assert_eq!(train.len(), 600);
        assert_eq!(val.first(), Some(&670));
        assert_eq!(val.len(), 330);
    }

    #[test]
    fn too_few_rows_is_an_error_with_a_hint() {
        let err = SplitKind::default().rows(60, 49).unwrap_err();
        assert!(
            err.to_string().contains("validation rows: 0 windows"),
            "{err}"
        );
        assert!(matches!(
            SplitKind::Blocked {
                train_fraction: 1.0
            }
            .rows(100, 0),
            Err(DtgVibError::InvalidOption { .. })
        ));
        assert!("random".parse::<SplitKind>().is_err());
    }
}
