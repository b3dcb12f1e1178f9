//! Training and validation rows of a prepared record.
//!
//! Windows of 50 samples overlap by 49 with their neighbours, and the
//! zero-phase filter spreads each sample over a few more. An interleaved
//! split (the paper's: alternate windows) therefore validates on rows that
//! are nearly copies of training rows and flatters a model; the blocked split
//! trains on the first part and validates on the last, with a gap wide enough
//! that no sample reaches both ([`leakage_gap`]). Blocked is the default.
//!
//! The split itself is rbf's [`Holdout`](rbf::Holdout); this module adds what a record
//! knows: the gap its windows and filter need, and the fewest rows a side
//! may have.

use crate::error::SysidError;
use crate::prepared::Prepared;
use crate::sensor::Sensor;
pub use rbf::Holdout;

/// Fewest rows on either side of a split.
pub const MIN_ROWS: usize = 20;

/// Training and validation rows of `n` rows; `gap` rows after the training
/// block are dropped (blocked only).
///
/// ```
/// use sysid::split::{rows, Holdout};
/// let (train, val) = rows(Holdout::Interleaved, 100, 3).unwrap();
/// assert_eq!((&train[..3], &val[..3]), (&[0, 2, 4][..], &[1, 3, 5][..]));
/// // Blocked: the first half trains; the gap keeps rows 50..53 out of both.
/// let (train, val) = rows(Holdout::default(), 100, 3).unwrap();
/// assert_eq!((train.len(), val[0]), (50, 53));
/// ```
pub fn rows(split: Holdout, n: usize, gap: usize) -> Result<(Vec<usize>, Vec<usize>), SysidError> {
    let (train, val) = match split.fold(n, gap) {
        Ok(fold) => (fold.train, fold.validation),
        Err(rbf::SplitError::Fraction { fraction }) => {
            return Err(SysidError::InvalidOption {
                name: "train fraction",
                value: fraction.to_string(),
                reason: "must lie strictly between 0 and 1",
            });
        }
        // An empty side is a side with too few rows.
        Err(rbf::SplitError::EmptyFold {
            train, validation, ..
        }) => return Err(too_few(train, validation)),
        Err(other) => unreachable!("a hold-out fails only on its fraction or a side: {other}"),
    };
    if train.len() < MIN_ROWS || val.len() < MIN_ROWS {
        return Err(too_few(train.len(), val.len()));
    }
    Ok((train, val))
}

/// The error for a side with fewer than [`MIN_ROWS`] rows (training first).
fn too_few(train: usize, validation: usize) -> SysidError {
    let (what, have) = if train < MIN_ROWS {
        ("training rows", train)
    } else {
        ("validation rows", validation)
    };
    SysidError::TooFewSamples {
        what,
        have,
        need: MIN_ROWS,
        hint: "use a longer record, a shorter --window, or another --train-fraction",
    }
}

/// Rows closer than this to the other side of a split may share samples:
/// a window length plus the filter's reach.
pub fn leakage_gap<S: Sensor>(prepared: &Prepared<S>) -> usize {
    // Row 0's window ends at sample `first_sample()`: a window spans that many
    // samples before its own.
    prepared.first_sample() + prepared.filter_memory()
}

/// Training and validation rows of prepared data: the split applied within
/// each record of a multi-record preparation, so every record trains and
/// validates and no side reaches across a record's boundary.
pub fn split_rows<S: Sensor>(
    prepared: &Prepared<S>,
    split: Holdout,
) -> Result<(Vec<usize>, Vec<usize>), SysidError> {
    let gap = leakage_gap(prepared);
    let parts = prepared.record_rows();
    if parts.len() == 1 {
        return rows(split, prepared.rows(), gap);
    }
    let (mut train, mut val) = (Vec::new(), Vec::new());
    for (name, range) in parts {
        let (t, v) = rows(split, range.len(), gap).map_err(|e| SysidError::InRecord {
            record: name.to_string(),
            source: Box::new(e),
        })?;
        train.extend(t.into_iter().map(|r| r + range.start));
        val.extend(v.into_iter().map(|r| r + range.start));
    }
    Ok((train, val))
}

/// Training rows of every record but `name`, validation rows of `name`
/// (`--split by-record --validate-on NAME`): the question "does a model of
/// these tests hold on that one?".
pub fn by_record_rows<S: Sensor>(
    prepared: &Prepared<S>,
    name: &str,
) -> Result<(Vec<usize>, Vec<usize>), SysidError> {
    let parts = prepared.record_rows();
    if !parts.iter().any(|(n, _)| *n == name) || parts.len() < 2 {
        return Err(SysidError::UnknownRecord {
            flag: "--validate-on",
            name: name.to_string(),
            known: parts.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(", "),
        });
    }
    let (mut train, mut val) = (Vec::new(), Vec::new());
    for (n, range) in parts {
        if n == name { &mut val } else { &mut train }.extend(range);
    }
    if train.len() < MIN_ROWS || val.len() < MIN_ROWS {
        return Err(too_few(train.len(), val.len()));
    }
    Ok((train, val))
}

/// Parses `--split`: `blocked` or `interleaved`.
///
/// ```
/// assert!(sysid::split::parse("interleaved").is_ok());
/// assert!(sysid::split::parse("random").is_err());
/// ```
pub fn parse(name: &str) -> Result<Holdout, SysidError> {
    name.parse().map_err(|_| SysidError::InvalidOption {
        name: "split",
        value: name.trim().to_string(),
        reason: "use blocked or interleaved",
    })
}

/// Record samples between consecutive rows of a split's part: 1 for a
/// blocked part, 2 for the alternate rows of an interleaved one. A series on
/// those rows is sampled at `1 / (spacing · dt)`, which spectra and lags of
/// it must use.
///
/// ```
/// use sysid::split::{row_spacing, rows, Holdout};
/// let (train, val) = rows(Holdout::Interleaved, 100, 0).unwrap();
/// assert_eq!((row_spacing(&train), row_spacing(&val)), (2, 2));
/// let (_, val) = rows(Holdout::default(), 100, 3).unwrap();
/// assert_eq!(row_spacing(&val), 1);
/// ```
pub fn row_spacing(rows: &[usize]) -> usize {
    rows.windows(2)
        .map(|w| w[1] - w[0])
        .min()
        .unwrap_or(1)
        .max(1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocked_rows_never_touch_across_the_gap() {
        let blocked = Holdout::Blocked {
            train_fraction: 0.6,
        };
        let (train, val) = rows(blocked, 1000, 70).unwrap();
        assert_eq!(train.len(), 600);
        assert_eq!(val.first(), Some(&670));
        assert_eq!(val.len(), 330);
    }

    #[test]
    fn too_few_rows_is_an_error_with_a_hint() {
        let err = rows(Holdout::default(), 60, 49).unwrap_err();
        assert!(
            err.to_string().contains("validation rows: 0 windows"),
            "{err}"
        );
        let whole = Holdout::Blocked {
            train_fraction: 1.0,
        };
        assert!(matches!(
            rows(whole, 100, 0),
            Err(SysidError::InvalidOption { .. })
        ));
        assert!(parse("random").is_err());
    }
}
