//! Which record tells two candidates apart.
//!
//! Two candidates can be collinear on one record whatever the data (under
//! vibration along z, channel X's g_O and g_S both follow a_z). Diagnosed
//! together with a record that excites them differently, the ranking sees
//! them apart; this says, for a suggestion, which candidates were collinear
//! on some record alone and which records separated them, so a user knows
//! what the naming rests on.

use serde::Serialize;

/// Two candidates' correlation on one record.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RecordCorrelation {
    /// The record's name (its file).
    pub file: String,
    /// Correlation of the two (partialled) candidate columns on the record's rows.
    pub correlation: f64,
    /// The record's share of the two columns' summed energy: a record that
    /// hardly excites either separates nothing, whatever its correlation.
    pub energy_share: f64,
}

/// A candidate that one record alone could not tell from a suggestion, and
/// the records that could.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RecordSeparation {
    /// The other candidate's id.
    pub effect: String,
    /// Their correlation over all records together.
    pub correlation: f64,
    /// Their correlation on each record alone.
    pub records: Vec<RecordCorrelation>,
    /// Records on which they are collinear (|r| at or above the threshold,
    /// with at least [`MIN_ENERGY_SHARE`] of their energy).
    pub collinear_on: Vec<String>,
    /// Records that excite them differently (|r| below the threshold, with
    /// at least [`MIN_ENERGY_SHARE`] of their energy).
    pub separated_by: Vec<String>,
}

/// Smallest share of a pair's energy a record must hold to count as
/// separating it, or as unable to: below it the record hardly excites
/// either, and their correlation there is that of what little is left.
pub const MIN_ENERGY_SHARE: f64 = 0.05;

/// Fewest rows of a record for its own correlation to be computed.
const MIN_ROWS: usize = 20;

/// For the candidate `column`, every one of `others` it is not collinear
/// with over all records (|r| < `collinearity`) but is on some record alone,
/// with the records that separate them. `records` gives each record's name
/// and its positions in the columns; with one record the list is empty.
///
/// ```
/// use sysid::diagnose::record_separations;
/// // Record "z" drives both columns alike; record "y" drives them apart.
/// let a: Vec<f64> = (0..200).map(|i| ((i as f64) * 0.7).sin()).collect();
/// let b: Vec<f64> = (0..200)
///     .map(|i| if i < 100 { a[i] } else { ((i as f64) * 1.3).cos() })
///     .collect();
/// let recs = [("z".to_string(), (0..100).collect()), ("y".to_string(), (100..200).collect())];
/// let s = record_separations(&a, &[("b".to_string(), &b[..])], &recs, 0.95);
/// assert_eq!((s[0].collinear_on.as_slice(), s[0].separated_by.as_slice()), (&["z".to_string()][..], &["y".to_string()][..]));
/// ```
pub fn record_separations(
    column: &[f64],
    others: &[(String, &[f64])],
    records: &[(String, Vec<usize>)],
    collinearity: f64,
) -> Vec<RecordSeparation> {
    if records.len() < 2 {
        return Vec::new();
    }
    let all: Vec<usize> = (0..column.len()).collect();
    let mut out = Vec::new();
    for (id, other) in others {
        let joint = correlation(column, other, &all);
        if joint.abs() >= collinearity || !joint.is_finite() {
            continue;
        }
        let energy = |rows: &[usize]| -> f64 {
            rows.iter()
                .map(|&i| column[i] * column[i] + other[i] * other[i])
                .sum()
        };
        let total = energy(&all).max(f64::MIN_POSITIVE);
        let per: Vec<RecordCorrelation> = records
            .iter()
            .filter(|(_, rows)| rows.len() >= MIN_ROWS)
            .map(|(file, rows)| RecordCorrelation {
                file: file.clone(),
                correlation: correlation(column, other, rows),
                energy_share: energy(rows) / total,
            })
            .collect();
        // A record that hardly excites the pair says nothing of it either way.
        let excites = |r: &&RecordCorrelation| r.energy_share >= MIN_ENERGY_SHARE;
        let collinear_on: Vec<String> = per
            .iter()
            .filter(excites)
            .filter(|r| r.correlation.abs() >= collinearity)
            .map(|r| r.file.clone())
            .collect();
        if collinear_on.is_empty() {
            continue;
        }
        let separated_by = per
            .iter()
            .filter(excites)
            .filter(|r| r.correlation.abs() < collinearity)
            .map(|r| r.file.clone())
            .collect();
        out.push(RecordSeparation {
            effect: id.clone(),
            correlation: joint,
            records: per,
            collinear_on,
            separated_by,
        });
    }
    out
}

/// Pearson correlation of `a` and `b` on `rows` (0 where either is constant).
fn correlation(a: &[f64], b: &[f64], rows: &[usize]) -> f64 {
    let pick = |x: &[f64]| -> Vec<f64> { rows.iter().map(|&i| x[i]).collect() };
    stats::correlation(&pick(a), &pick(b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pair_collinear_everywhere_is_not_reported_as_separated() {
        let a: Vec<f64> = (0..100).map(|i| (i as f64 * 0.3).sin()).collect();
        let b: Vec<f64> = a.iter().map(|v| 2.0 * v).collect();
        let recs = [
            ("x".to_string(), (0..50).collect()),
            ("z".to_string(), (50..100).collect()),
        ];
        assert!(record_separations(&a, &[("b".into(), &b)], &recs, 0.95).is_empty());
        // One record: nothing to say.
        assert!(record_separations(&a, &[("b".into(), &b)], &recs[..1], 0.95).is_empty());
    }

    #[test]
    fn a_record_that_barely_excites_the_pair_does_not_separate_it() {
        // z drives both alike; y drives them apart but a thousand times weaker,
        // and x drives them apart at full size.
        let n = 300;
        let s = |i: usize, f: f64| (i as f64 * f).sin();
        let a: Vec<f64> = (0..n)
            .map(|i| match i / 100 {
                0 => s(i, 0.7),
                1 => 1e-3 * s(i, 0.7),
                _ => s(i, 0.7),
            })
            .collect();
        let b: Vec<f64> = (0..n)
            .map(|i| match i / 100 {
                0 => s(i, 0.7),
                1 => 1e-3 * s(i, 1.9),
                _ => s(i, 1.9),
            })
            .collect();
        let recs = [
            ("z".to_string(), (0..100).collect()),
            ("y".to_string(), (100..200).collect()),
            ("x".to_string(), (200..300).collect()),
        ];
        let r = record_separations(&a, &[("b".into(), &b)], &recs, 0.95);
        assert_eq!(r[0].collinear_on, ["z"]);
        assert_eq!(r[0].separated_by, ["x"]);
    }
}
