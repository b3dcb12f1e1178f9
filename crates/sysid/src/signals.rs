//! A record as the loop sees it: sample times and named columns of equal
//! length. What the columns mean (which are outputs, which are inputs, in
//! which units) is the plug-in's knowledge, not the loop's.

/// Relative tolerance on sampling intervals: records (or the segments of a
/// log split at its gaps) fitted together, and a record against the model's
/// interval, are accepted when their median sampling intervals agree within
/// 0.5 %. Two logs of one nominal rate differ by more than their jitter (a
/// real 250 Hz PX4 log's two halves by 0.3 %: the autopilot's clock and
/// dropped samples), and a 0.5 % time-scale error moves a 50-sample
/// window's span by a quarter of a sample; two nominal rates (200 and 250
/// Hz) differ by 20 %. docs/formats.md states it.
pub const INTERVAL_TOLERANCE: f64 = 5e-3;

/// Why columns cannot form a record.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SignalsError {
    /// A column's length differs from the time column's.
    #[error("column '{name}' has {len} samples, the time column {expected}")]
    Length {
        /// The column.
        name: String,
        /// Its length.
        len: usize,
        /// The time column's length.
        expected: usize,
    },
    /// Two columns share a name.
    #[error("column '{name}' is given twice")]
    Duplicate {
        /// The name.
        name: String,
    },
    /// Fewer than two samples: no sample interval.
    #[error("{len} samples: a record needs at least two")]
    TooShort {
        /// Samples given.
        len: usize,
    },
}

/// Sample times (s) and named columns of equal length.
///
/// ```
/// use sysid::Signals;
/// let s = Signals::new(vec![0.0, 0.5, 1.0], vec![("p".into(), vec![1.0, 2.0, 3.0])])?;
/// assert_eq!(s.dt(), 0.5);
/// assert_eq!(s.column("p"), Some(&[1.0, 2.0, 3.0][..]));
/// assert!(Signals::new(vec![0.0, 1.0], vec![("p".into(), vec![1.0])]).is_err());
/// # Ok::<(), sysid::SignalsError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Signals {
    t: Vec<f64>,
    columns: Vec<(String, Vec<f64>)>,
}

impl Signals {
    /// A record of `t` (s) and `columns`, each as long as `t`, named once.
    pub fn new(t: Vec<f64>, columns: Vec<(String, Vec<f64>)>) -> Result<Self, SignalsError> {
        if t.len() < 2 {
            return Err(SignalsError::TooShort { len: t.len() });
        }
        for (k, (name, v)) in columns.iter().enumerate() {
            if v.len() != t.len() {
                return Err(SignalsError::Length {
                    name: name.clone(),
                    len: v.len(),
                    expected: t.len(),
                });
            }
            if columns[..k].iter().any(|(n, _)| n == name) {
                return Err(SignalsError::Duplicate { name: name.clone() });
            }
        }
        Ok(Self { t, columns })
    }

    /// Sample times, s.
    pub fn t(&self) -> &[f64] {
        &self.t
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// Never true: a record has at least two samples.
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// The mean sample interval, s: the span over the intervals.
    pub fn dt(&self) -> f64 {
        (self.t[self.t.len() - 1] - self.t[0]) / (self.t.len() - 1) as f64
    }

    /// The median sample interval, s: what records are compared by (a
    /// dropped sample lengthens the mean, not the median).
    pub fn median_dt(&self) -> f64 {
        let mut steps: Vec<f64> = self.t.windows(2).map(|w| w[1] - w[0]).collect();
        let mid = steps.len() / 2;
        let (_, m, _) = steps.select_nth_unstable_by(mid, f64::total_cmp);
        let m = *m;
        if steps.len() % 2 == 1 {
            return m;
        }
        let below = steps[..mid]
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max);
        0.5 * (below + m)
    }

    /// A column by name.
    pub fn column(&self, name: &str) -> Option<&[f64]> {
        self.columns
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_slice())
    }

    /// The columns' names, in order.
    pub fn names(&self) -> Vec<&str> {
        self.columns.iter().map(|(n, _)| n.as_str()).collect()
    }

    /// The columns, in order.
    pub fn columns(&self) -> &[(String, Vec<f64>)] {
        &self.columns
    }

    /// The record's parts laid end to end, each after the first without its
    /// first `skip` samples, time restamped on the first part's grid; the
    /// first part's columns, found by name in the others (the parts share
    /// their columns and sample interval: [`crate::Prepared::new_many`]
    /// checks both).
    pub(crate) fn concat(parts: &[&Signals], skip: usize) -> Signals {
        let drop = |k: usize| if k == 0 { 0 } else { skip };
        let (t0, dt) = (parts[0].t[0], parts[0].dt());
        let n: usize = parts
            .iter()
            .enumerate()
            .map(|(k, p)| p.len() - drop(k))
            .sum();
        let t = (0..n).map(|i| t0 + i as f64 * dt).collect();
        let columns = parts[0]
            .columns
            .iter()
            .map(|(name, _)| {
                let v = parts
                    .iter()
                    .enumerate()
                    .flat_map(|(k, p)| p.column(name).unwrap_or(&[])[drop(k)..].iter().copied())
                    .collect();
                (name.clone(), v)
            })
            .collect();
        Signals { t, columns }
    }
}
