//! Putting the columns a [`UlogTable`] maps onto one time base.
//!
//! The base stream (the topic instance of the table's `base` column, by
//! default the unit's first gyro) gives the rows: its own time stamps,
//! never resampled. Every other stream is linearly interpolated onto them,
//! between its own two samples that bracket the row; a row that falls on
//! one of its samples takes that sample as it is. A row before a stream's
//! first sample, after its last, or inside one of its gaps (a step over
//! `gap_factor` × its median step) has no value there and is dropped; the
//! report counts these per stream, and says how many rows of each stream
//! were interpolated, so a caller can say so when a gyro's was.
//!
//! Why linear and not nearest: two free-running sensors drift in phase;
//! nearest-sample picking turns that drift into a delay that jumps by one
//! sample each time the phase wraps (a time-varying input the model would
//! have to explain), while interpolation gives a fractional delay that
//! changes smoothly and keeps no time error on average. Its cost is a
//! low-pass of the interpolated stream, |H| = |1 − d + d e^{−jωT}| at a
//! fraction d of a step (at d = ½, cos(ωT/2): 0.95 at a tenth of its
//! sampling rate), which is why the base stream is never interpolated.

use crate::error::{UlogError, listing};
use crate::model::Ulog;
use crate::query::{Series, TimeSource};
use crate::source::{FieldSource, UlogTable};

/// The columns on one time base.
#[derive(Debug, Clone, PartialEq)]
pub struct Joined {
    /// The first row's time, µs since boot.
    pub start_us: u64,
    /// Each row's time, µs since boot.
    pub time_us: Vec<u64>,
    /// Each row's time in s from the first row ((µs − start) × 1e-6).
    pub t_s: Vec<f64>,
    /// The columns in the order asked, in the log's units (PX4: rad/s,
    /// m/s², °C), divided by their interval where the table names one.
    pub columns: Vec<(String, Vec<f64>)>,
    /// One entry per stream, the base first.
    pub streams: Vec<StreamReport>,
    /// Rows of the base stream dropped because another stream had no value.
    pub rows_dropped: usize,
}

impl Joined {
    /// A column by name.
    pub fn column(&self, name: &str) -> Option<&[f64]> {
        self.columns
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_slice())
    }

    /// The columns some of whose rows were interpolated, each with its
    /// stream's report: a gyro among them has been resampled, and the
    /// caller says so.
    pub fn interpolated_columns(&self) -> Vec<(&str, &StreamReport)> {
        let asked = |c: &String| self.columns.iter().any(|(n, _)| n == c);
        self.streams
            .iter()
            .filter(|s| s.interpolated_rows > 0)
            .flat_map(|s| {
                s.columns
                    .iter()
                    .filter(|c| asked(c))
                    .map(move |c| (c.as_str(), s))
            })
            .collect()
    }
}

/// How one stream (a topic instance with its time source) met the rows.
#[derive(Debug, Clone, PartialEq)]
pub struct StreamReport {
    /// `topic[instance]`, with the time fields if not `timestamp` alone.
    pub stream: String,
    /// The unit's columns it fills.
    pub columns: Vec<String>,
    pub samples: usize,
    /// Its median time step, s (0 for fewer than two samples).
    pub median_step_s: f64,
    /// Rows on one of its own samples (all of them for the base).
    pub exact_rows: usize,
    /// Rows linearly interpolated between two of its samples.
    pub interpolated_rows: usize,
    /// Rows before its first sample or after its last (dropped).
    pub rows_outside: usize,
    /// Rows inside one of its gaps (dropped).
    pub rows_in_gap: usize,
}

impl StreamReport {
    /// One line for messages.
    pub fn line(&self) -> String {
        let mut s = format!(
            "{} ({}): {} samples, median step {:.3} ms; rows: {} on its samples",
            self.stream,
            self.columns.join(", "),
            self.samples,
            self.median_step_s * 1e3,
            self.exact_rows
        );
        if self.interpolated_rows > 0 {
            s.push_str(&format!(
                ", {} interpolated linearly",
                self.interpolated_rows
            ));
        }
        if self.rows_outside + self.rows_in_gap > 0 {
            s.push_str(&format!(
                ", {} outside its span and {} in its gaps dropped",
                self.rows_outside, self.rows_in_gap
            ));
        }
        s
    }
}

/// A stream's samples and the values of its columns.
struct Stream {
    report: StreamReport,
    time_us: Vec<u64>,
    values: Vec<Vec<f64>>,
}

impl UlogTable {
    /// Reads `columns` from `log` onto the time stamps of the `base` column's
    /// stream (`columns[0]` when the table names none). `gap_factor` is the
    /// step, in median steps, over which a stream is not interpolated (the
    /// record reader's `GAP_FACTOR`).
    pub fn join(&self, log: &Ulog, columns: &[&str], gap_factor: f64) -> Result<Joined, UlogError> {
        let sources = columns
            .iter()
            .map(|&c| {
                self.columns
                    .get(c)
                    .map(|s| (c, s))
                    .ok_or_else(|| self.unmapped(c))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let base = self
            .base
            .as_deref()
            .or(columns.first().copied())
            .unwrap_or_default();
        let base_source = self.columns.get(base).ok_or_else(|| self.unmapped(base))?;
        let mut groups: Vec<Vec<(&str, &FieldSource)>> = vec![Vec::new()];
        for (c, s) in sources {
            if s.stream() == base_source.stream() {
                groups[0].push((c, s));
            } else if let Some(g) = groups[1..]
                .iter_mut()
                .find(|g| g[0].1.stream() == s.stream())
            {
                g.push((c, s));
            } else {
                groups.push(vec![(c, s)]);
            }
        }
        if groups[0].is_empty() {
            groups[0].push((base, base_source));
        }
        let streams = groups
            .iter()
            .map(|g| read_stream(log, g))
            .collect::<Result<Vec<_>, _>>()?;
        align(log, streams, columns, gap_factor)
    }

    fn unmapped(&self, column: &str) -> UlogError {
        let names: Vec<&str> = self.columns.keys().map(String::as_str).collect();
        UlogError::Unmapped {
            column: column.to_string(),
            available: listing(&names, 60),
        }
    }
}

/// Reads one stream's columns, divided by their intervals, and checks its
/// time increases.
fn read_stream(log: &Ulog, group: &[(&str, &FieldSource)]) -> Result<Stream, UlogError> {
    let (column, first) = group[0];
    let in_column = |source| UlogError::Column {
        column: column.to_string(),
        source: Box::new(source),
    };
    let (topic, instance, time, offset) = first.stream();
    let mut fields: Vec<&str> = Vec::new();
    for (_, s) in group {
        for f in std::iter::once(s.field.as_str()).chain(s.interval.as_deref()) {
            if !fields.contains(&f) {
                fields.push(f);
            }
        }
    }
    let series = log
        .series_timed(
            topic,
            instance,
            TimeSource {
                field: time,
                offset,
            },
            &fields,
        )
        .map_err(in_column)?;
    increasing(log, &series).map_err(in_column)?;
    let values = group
        .iter()
        .map(|(c, s)| {
            divided(log, &series, s).map_err(|e| UlogError::Column {
                column: c.to_string(),
                source: Box::new(e),
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    let mut stream = series.label();
    if time != "timestamp" || offset.is_some() {
        stream.push_str(&format!(" at {time}"));
        if let Some(o) = offset {
            stream.push_str(&format!(" + {o}"));
        }
    }
    Ok(Stream {
        report: StreamReport {
            stream,
            columns: group.iter().map(|(c, _)| c.to_string()).collect(),
            samples: series.time_us.len(),
            median_step_s: median_step_us(&series.time_us) * 1e-6,
            exact_rows: 0,
            interpolated_rows: 0,
            rows_outside: 0,
            rows_in_gap: 0,
        },
        time_us: series.time_us,
        values,
    })
}

/// The source's field, divided by its interval field (µs → s) if it names one.
fn divided(log: &Ulog, series: &Series, source: &FieldSource) -> Result<Vec<f64>, UlogError> {
    let v = series.column(&source.field).unwrap_or_default();
    let Some(interval) = &source.interval else {
        return Ok(v.to_vec());
    };
    let dt = series.column(interval).unwrap_or_default();
    v.iter()
        .zip(dt)
        .enumerate()
        .map(|(index, (&x, &dt))| {
            if dt > 0.0 {
                Ok(x / (dt * 1e-6))
            } else {
                Err(UlogError::Interval {
                    file: log.file().to_string(),
                    topic: series.topic.clone(),
                    instance: series.instance,
                    index,
                    field: interval.clone(),
                    value: dt,
                })
            }
        })
        .collect()
}

/// Refuses a series whose time does not strictly increase.
fn increasing(log: &Ulog, s: &Series) -> Result<(), UlogError> {
    match s.time_us.windows(2).position(|w| w[1] <= w[0]) {
        None => Ok(()),
        Some(k) => Err(UlogError::NotIncreasing {
            file: log.file().to_string(),
            topic: s.topic.clone(),
            instance: s.instance,
            index: k + 1,
            previous: s.time_us[k] as i128,
            value: s.time_us[k + 1] as i128,
        }),
    }
}

/// The median of the steps of an increasing time series, µs (0 for fewer
/// than two samples).
fn median_step_us(t: &[u64]) -> f64 {
    let mut steps: Vec<u64> = t.windows(2).map(|w| w[1] - w[0]).collect();
    if steps.is_empty() {
        return 0.0;
    }
    steps.sort_unstable();
    let n = steps.len();
    if n % 2 == 1 {
        steps[n / 2] as f64
    } else {
        (steps[n / 2 - 1] as f64 + steps[n / 2] as f64) / 2.0
    }
}

/// Where a row falls in a stream.
enum Hit {
    Exact(usize),
    Between(usize, f64),
    Outside,
    InGap,
}

/// Every row's place in `s`, by a forward scan (both are increasing).
fn locate(rows: &[u64], s: &[u64], max_step: f64) -> Vec<Hit> {
    let mut j = 0;
    rows.iter()
        .map(|&t| {
            while j + 1 < s.len() && s[j + 1] <= t {
                j += 1;
            }
            match s.get(j) {
                Some(&sj) if sj == t => Hit::Exact(j),
                Some(&sj) if sj < t && j + 1 < s.len() => {
                    let step = (s[j + 1] - sj) as f64;
                    if step > max_step {
                        Hit::InGap
                    } else {
                        Hit::Between(j, (t - sj) as f64 / step)
                    }
                }
                _ => Hit::Outside,
            }
        })
        .collect()
}

/// Puts every stream on the base stream's rows and keeps the rows where
/// all have a value.
fn align(
    log: &Ulog,
    mut streams: Vec<Stream>,
    columns: &[&str],
    gap_factor: f64,
) -> Result<Joined, UlogError> {
    let rows = streams[0].time_us.clone();
    let mut keep = vec![true; rows.len()];
    let mut filled: Vec<(String, Vec<f64>)> = Vec::new();
    for (k, s) in streams.iter_mut().enumerate() {
        let hits = if k == 0 {
            (0..rows.len()).map(Hit::Exact).collect()
        } else {
            locate(&rows, &s.time_us, gap_factor * s.report.median_step_s * 1e6)
        };
        for (i, h) in hits.iter().enumerate() {
            let r = &mut s.report;
            match h {
                Hit::Exact(_) => r.exact_rows += 1,
                Hit::Between(..) => r.interpolated_rows += 1,
                Hit::Outside => r.rows_outside += 1,
                Hit::InGap => r.rows_in_gap += 1,
            }
            keep[i] &= matches!(h, Hit::Exact(_) | Hit::Between(..));
        }
        for (name, v) in s.report.columns.iter().zip(&s.values) {
            let at = |h: &Hit| match *h {
                Hit::Exact(j) => v[j],
                Hit::Between(j, w) => v[j] + (v[j + 1] - v[j]) * w,
                Hit::Outside | Hit::InGap => f64::NAN,
            };
            filled.push((name.clone(), hits.iter().map(at).collect()));
        }
    }
    let kept: Vec<usize> = (0..rows.len()).filter(|&i| keep[i]).collect();
    if kept.len() < 2 {
        let reason = streams
            .iter()
            .map(|s| s.report.line())
            .collect::<Vec<_>>()
            .join("; ");
        return Err(UlogError::NothingJoined {
            file: log.file().to_string(),
            base: streams[0].report.stream.clone(),
            rows: kept.len(),
            reason,
        });
    }
    let time_us: Vec<u64> = kept.iter().map(|&i| rows[i]).collect();
    let start_us = time_us[0];
    let take = |name: &str| -> Vec<f64> {
        let v = filled
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_slice())
            .unwrap_or_default();
        kept.iter().map(|&i| v[i]).collect()
    };
    Ok(Joined {
        start_us,
        t_s: time_us
            .iter()
            .map(|&t| (t - start_us) as f64 * 1e-6)
            .collect(),
        columns: columns.iter().map(|&c| (c.to_string(), take(c))).collect(),
        rows_dropped: rows.len() - kept.len(),
        streams: streams.into_iter().map(|s| s.report).collect(),
        time_us,
    })
}
