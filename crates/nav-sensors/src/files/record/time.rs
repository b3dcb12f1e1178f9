//! The time base of a record: the paper format's strict constant interval,
//! and the looser rule for logs read with a unit file — jitter accepted, a
//! gap splits the record into segments.
//!
//! Why jitter is accepted up to [`GAP_FACTOR`] × the median step: an
//! autopilot's sample is the mean over its own integration interval
//! (PX4's `sensor_combined`), so a jittered time stamp moves where a
//! sample sits, not what it holds, and a step of up to three medians is at
//! most two dropped samples — a 50-sample window then spans at most 4%
//! more time than its nominal length. Inside a segment the samples are
//! taken at their mean step ([`super::Record::dt`]). A longer step is a
//! gap: the record is split there, so that no window, filter or
//! cross-validation fold straddles it. Three medians is the convention of
//! the real recordings' README (`data/realdata/README.md`), whose gap
//! counts the reader reproduces.

use std::fmt;
use std::ops::Range;

use super::error::RecordError;

/// Relative tolerance on the sample interval: every `t[i] − t[i−1]` must be
/// within `1e-3·dt` of the median interval `dt`. That accepts timestamps
/// rounded to 5 decimals at 50 Hz (≤ 1e-5 s error in a difference, 5e-4·dt)
/// or stored in single precision over a 100-s test, and still rejects any
/// dropped or repeated sample (a 100% deviation) or a 1% clock glitch.
/// This is the paper format's strict rule ([`Record::new`](super::Record::new),
/// [`Record::read_csv`](super::Record::read_csv)); a record read with a unit file accepts jitter
/// and splits at gaps instead ([`Record::read_with_unit`](super::Record::read_with_unit)).
///
/// ```
/// assert!(nav_sensors::record::INTERVAL_TOLERANCE < 0.01);
/// ```
pub const INTERVAL_TOLERANCE: f64 = 1e-3;

/// A step longer than `GAP_FACTOR` × the median step is a gap (the record is
/// split there); every shorter step is accepted as jitter (see the module
/// documentation for why three).
///
/// ```
/// assert_eq!(nav_sensors::record::GAP_FACTOR, 3.0);
/// ```
pub const GAP_FACTOR: f64 = 3.0;

/// One gap in a log: where it starts and how long the step is.
///
/// ```
/// let g = nav_sensors::record::Gap { after_s: 1.5, step_s: 0.065 };
/// assert_eq!(g.to_string(), "0.065 s after t = 1.5 s");
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gap {
    /// Time of the last sample before the gap, s.
    pub after_s: f64,
    /// The step across the gap, s.
    pub step_s: f64,
}

impl fmt::Display for Gap {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} s after t = {} s", self.step_s, self.after_s)
    }
}

/// What the reader found in a log's time column: the median step, the
/// jitter it accepted, the gaps it split at.
///
/// ```
/// use nav_sensors::record::TimeReport;
/// let t = [0.0, 0.01, 0.021, 0.03, 0.1, 0.11, 0.12];
/// let (segments, report) = TimeReport::split(&t);
/// assert_eq!(segments, vec![0..4, 4..7]);
/// assert_eq!(report.gaps.len(), 1);
/// assert!((report.largest_gap_s().unwrap() - 0.07).abs() < 1e-12);
/// assert_eq!(report.to_string(), "1 gap (largest 0.07 s) split the record into 2 segments; median step 0.01 s, accepted steps 0.9× to 1.1× the median");
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct TimeReport {
    /// The median step over the whole log, s.
    pub median_step_s: f64,
    /// Every gap, in time order.
    pub gaps: Vec<Gap>,
    /// The smallest accepted step over the median (jitter).
    pub min_step_ratio: f64,
    /// The largest accepted step over the median (jitter, dropped samples).
    pub max_step_ratio: f64,
    /// Samples dropped because their segment held a single sample.
    pub dropped_samples: usize,
    /// How many segments (records) the log gave.
    pub segments: usize,
}

impl TimeReport {
    /// Splits strictly increasing times at their gaps: the index ranges of
    /// the segments of at least two samples, and the report.
    ///
    /// ```
    /// let (seg, r) = nav_sensors::record::TimeReport::split(&[0.0, 1.0, 2.0]);
    /// assert_eq!((seg, r.gaps.len(), r.segments), (vec![0..3], 0, 1));
    /// ```
    pub fn split(t: &[f64]) -> (Vec<Range<usize>>, TimeReport) {
        let steps: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
        let median = median(&steps);
        let mut segments = Vec::new();
        let mut gaps = Vec::new();
        let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
        let mut start = 0;
        let mut dropped = 0;
        let mut close = |start: usize, end: usize, segments: &mut Vec<Range<usize>>| {
            if end - start >= 2 {
                segments.push(start..end);
            } else {
                dropped += end - start;
            }
        };
        for (i, &step) in steps.iter().enumerate() {
            if step > GAP_FACTOR * median {
                gaps.push(Gap {
                    after_s: t[i],
                    step_s: step,
                });
                close(start, i + 1, &mut segments);
                start = i + 1;
            } else {
                lo = lo.min(step / median);
                hi = hi.max(step / median);
            }
        }
        close(start, t.len(), &mut segments);
        let report = TimeReport {
            median_step_s: median,
            gaps,
            min_step_ratio: if lo.is_finite() { lo } else { 1.0 },
            max_step_ratio: if hi > 0.0 { hi } else { 1.0 },
            dropped_samples: dropped,
            segments: segments.len(),
        };
        (segments, report)
    }

    /// The longest gap, s (`None` without gaps).
    ///
    /// ```
    /// let (_, r) = nav_sensors::record::TimeReport::split(&[0.0, 1.0, 2.0]);
    /// assert!(r.largest_gap_s().is_none());
    /// ```
    pub fn largest_gap_s(&self) -> Option<f64> {
        self.gaps.iter().map(|g| g.step_s).reduce(f64::max)
    }
}

impl fmt::Display for TimeReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let n = self.gaps.len();
        match self.largest_gap_s() {
            None => write!(f, "no gap")?,
            Some(g) => write!(
                f,
                "{n} gap{} (largest {} s) split the record into {} segment{}",
                if n == 1 { "" } else { "s" },
                round_sig(g),
                self.segments,
                if self.segments == 1 { "" } else { "s" }
            )?,
        }
        write!(
            f,
            "; median step {} s, accepted steps {}× to {}× the median",
            round_sig(self.median_step_s),
            round_sig(self.min_step_ratio),
            round_sig(self.max_step_ratio)
        )?;
        if self.dropped_samples > 0 {
            write!(
                f,
                "; {} isolated sample(s) between gaps dropped",
                self.dropped_samples
            )?;
        }
        Ok(())
    }
}

/// Four significant digits, for messages.
fn round_sig(v: f64) -> f64 {
    if v == 0.0 || !v.is_finite() {
        return v;
    }
    let scale = 10f64.powi(3 - v.abs().log10().floor() as i32);
    (v * scale).round() / scale
}

/// The median (mean of the two middle values for an even count).
pub(crate) fn median(v: &[f64]) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(|a, b| a.total_cmp(b));
    let n = s.len();
    if n == 0 {
        return f64::NAN;
    }
    if n % 2 == 1 {
        s[n / 2]
    } else {
        0.5 * (s[n / 2 - 1] + s[n / 2])
    }
}

/// At least two samples and strictly increasing time (the rule of a whole
/// log before it is split at its gaps); `line(i)` gives the file line of
/// sample i.
pub(crate) fn check_increasing(
    t: &[f64],
    file: &str,
    line: &impl Fn(usize) -> u64,
    column: usize,
) -> Result<(), RecordError> {
    if t.len() < 2 {
        return Err(RecordError::TooShort {
            file: file.to_string(),
            rows: t.len(),
        });
    }
    for i in 1..t.len() {
        if t[i].partial_cmp(&t[i - 1]) != Some(std::cmp::Ordering::Greater) {
            return Err(RecordError::NotIncreasing {
                file: file.to_string(),
                line: line(i),
                column,
                previous: t[i - 1],
                t: t[i],
            });
        }
    }
    Ok(())
}

/// The paper format's rule: at least two samples, strictly increasing time
/// and a constant interval (within [`INTERVAL_TOLERANCE`] of the median).
pub(crate) fn check_time(
    t: &[f64],
    file: &str,
    line: impl Fn(usize) -> u64,
    column: usize,
) -> Result<(), RecordError> {
    check_increasing(t, file, &line, column)?;
    // The median interval, so the row reported is the irregular one (a
    // dropped sample would pull a mean interval away from every other row).
    let mut intervals: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
    let mid = intervals.len() / 2;
    let expected = *intervals
        .select_nth_unstable_by(mid, |a, b| a.total_cmp(b))
        .1;
    for i in 1..t.len() {
        let interval = t[i] - t[i - 1];
        if (interval - expected).abs() > INTERVAL_TOLERANCE * expected {
            return Err(RecordError::IrregularInterval {
                file: file.to_string(),
                line: line(i),
                column,
                interval,
                expected,
                tolerance: INTERVAL_TOLERANCE,
            });
        }
    }
    Ok(())
}

/// The rule of one segment of a log: at least two samples, strictly
/// increasing time, no gap (jitter accepted).
pub(crate) fn check_time_allowing_jitter(
    t: &[f64],
    file: &str,
    line: impl Fn(usize) -> u64,
    column: usize,
) -> Result<(), RecordError> {
    check_increasing(t, file, &line, column)?;
    let (_, report) = TimeReport::split(t);
    if let Some(gap) = report.gaps.first() {
        let i = t
            .iter()
            .position(|&x| x == gap.after_s)
            .expect("a sample time")
            + 1;
        return Err(RecordError::Gap {
            file: file.to_string(),
            line: line(i),
            column,
            step: gap.step_s,
            median: report.median_step_s,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::Record;
    use super::*;

    fn series(t: Vec<f64>) -> Result<Record, RecordError> {
        let n = t.len();
        let g = |name: &str| (name.to_string(), vec![0.0; n]);
        Record::from_series(
            t,
            vec![g("a"), g("b"), g("c")],
            vec![g("ax"), g("ay"), g("az")],
            vec![],
            None,
        )
    }

    #[test]
    fn a_record_of_any_unit_accepts_jitter_and_refuses_a_gap() {
        assert!(series(vec![0.0, 0.01, 0.0205, 0.029, 0.05, 0.06]).is_ok());
        let err = series(vec![0.0, 0.01, 0.02, 0.03, 0.2, 0.21]).unwrap_err();
        assert_eq!(
            err.to_string(),
            "<memory>:6:1: a gap of 0.17 s (the median step is 0.01 s): split the record at its gaps"
        );
    }

    #[test]
    fn names_and_lengths_are_checked() {
        let g = |name: &str, n: usize| (name.to_string(), vec![0.0; n]);
        let t = vec![0.0, 0.01];
        let err = Record::from_series(
            t.clone(),
            vec![g("a", 2), g("a", 2), g("c", 2)],
            vec![g("ax", 2)],
            vec![],
            None,
        )
        .unwrap_err();
        assert_eq!(err.to_string(), "column name 'a' is given twice");
        let err = Record::from_series(t.clone(), vec![g("a", 2)], vec![g("ax", 3)], vec![], None)
            .unwrap_err();
        assert_eq!(err.to_string(), "series 'ax' has 3 samples, expected 2");
        let err = Record::from_series(t.clone(), vec![g("a", 2)], vec![], vec![g("a", 2)], None)
            .unwrap_err();
        assert_eq!(
            err.to_string(),
            "extra column name 'a' is reserved or repeated"
        );
        let err = Record::from_series(t, vec![g("a", 2)], vec![], vec![], Some("temp".into()))
            .unwrap_err();
        assert_eq!(
            err.to_string(),
            "temperature column 'temp' is not among the extra columns"
        );
    }

    #[test]
    fn the_median_of_an_even_count_is_the_mean_of_the_middle_two() {
        assert_eq!(median(&[4.0, 1.0, 3.0, 2.0]), 2.5);
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
    }
}
