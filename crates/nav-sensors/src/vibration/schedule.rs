//! The level schedule of a vibration test: segments at given dB levels with
//! ramps between them.

use serde::{Deserialize, Serialize};

/// One segment of a level schedule.
///
/// `level_db` is relative to the drives' full level (0 dB); omit it for
/// "shaker off". The segment starts with a ramp of `ramp_s` from the previous
/// segment's level, linear in dB between two levels and linear in amplitude
/// from or to "off" (dB has no value for off).
///
/// ```
/// use nav_sensors::vibration::{LevelSchedule, Segment};
/// let s = LevelSchedule::new(vec![Segment { duration_s: 5.0, level_db: None, ramp_s: 0.0 },
///     Segment { duration_s: 5.0, level_db: Some(-6.0), ramp_s: 0.0 }]);
/// assert_eq!(s.segments()[1].level_db, Some(-6.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Segment {
    /// Segment length including its ramp, s.
    pub duration_s: f64,
    /// Level relative to full level, dB; `None` = off.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub level_db: Option<f64>,
    /// Ramp from the previous level at the start of the segment, s.
    #[serde(default)]
    pub ramp_s: f64,
}

/// A sequence of level segments; after the last one the last level holds.
/// An empty schedule is full level throughout.
///
/// ```
/// use nav_sensors::vibration::{LevelSchedule, Segment};
/// let s = LevelSchedule::new(vec![
///     Segment { duration_s: 10.0, level_db: Some(-6.0), ramp_s: 0.0 },
///     Segment { duration_s: 10.0, level_db: Some(0.0), ramp_s: 2.0 },
/// ]);
/// assert!((s.gain(5.0) - 10f64.powf(-6.0 / 20.0)).abs() < 1e-12);
/// assert!((s.gain(11.0) - 10f64.powf(-3.0 / 20.0)).abs() < 1e-12); // half-way up the ramp, in dB
/// assert_eq!(s.gain(15.0), 1.0);
/// assert_eq!(s.total_duration_s(), 20.0);
/// ```
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(transparent)]
pub struct LevelSchedule {
    segments: Vec<Segment>,
}

impl LevelSchedule {
    /// A schedule from its segments.
    ///
    /// ```
    /// use nav_sensors::vibration::{LevelSchedule, Segment};
    /// let s = LevelSchedule::new(vec![Segment { duration_s: 5.0, level_db: None, ramp_s: 0.0 },
    ///     Segment { duration_s: 5.0, level_db: Some(-6.0), ramp_s: 0.0 }]);
    /// assert_eq!(s.segments().len(), 2);
    /// ```
    pub fn new(segments: Vec<Segment>) -> Self {
        Self { segments }
    }

    /// Full level throughout.
    ///
    /// ```
    /// assert_eq!(nav_sensors::vibration::LevelSchedule::constant().gain(123.0), 1.0);
    /// ```
    pub fn constant() -> Self {
        Self::default()
    }

    /// The segments.
    ///
    /// ```
    /// use nav_sensors::vibration::{LevelSchedule, Segment};
    /// let s = LevelSchedule::new(vec![Segment { duration_s: 5.0, level_db: None, ramp_s: 0.0 },
    ///     Segment { duration_s: 5.0, level_db: Some(-6.0), ramp_s: 0.0 }]);
    /// assert!(s.segments()[0].level_db.is_none());
    /// ```
    pub fn segments(&self) -> &[Segment] {
        &self.segments
    }

    /// Sum of the segment durations, s.
    ///
    /// ```
    /// use nav_sensors::vibration::{LevelSchedule, Segment};
    /// let s = LevelSchedule::new(vec![Segment { duration_s: 5.0, level_db: None, ramp_s: 0.0 },
    ///     Segment { duration_s: 5.0, level_db: Some(-6.0), ramp_s: 0.0 }]);
    /// assert_eq!(s.total_duration_s(), 10.0);
    /// ```
    pub fn total_duration_s(&self) -> f64 {
        self.segments.iter().map(|s| s.duration_s).sum()
    }

    /// Amplitude gain (0 for off, 1 at 0 dB) at time `t_s`.
    ///
    /// ```
    /// use nav_sensors::vibration::{LevelSchedule, Segment};
    /// let s = LevelSchedule::new(vec![Segment { duration_s: 5.0, level_db: None, ramp_s: 0.0 },
    ///     Segment { duration_s: 5.0, level_db: Some(-6.0), ramp_s: 0.0 }]);
    /// assert_eq!(s.gain(1.0), 0.0);
    /// assert!((s.gain(7.0) - 0.5012).abs() < 1e-4);
    /// ```
    pub fn gain(&self, t_s: f64) -> f64 {
        if self.segments.is_empty() {
            return 1.0;
        }
        let amp = |s: &Segment| s.level_db.map(|db| 10f64.powf(db / 20.0));
        let mut start = 0.0;
        let mut prev: Option<Option<f64>> = None;
        for seg in &self.segments {
            let end = start + seg.duration_s;
            if t_s < end {
                let this = seg.level_db;
                let tau = t_s - start;
                return match prev {
                    Some(p) if seg.ramp_s > 0.0 && tau < seg.ramp_s => {
                        let x = tau / seg.ramp_s;
                        match (p, this) {
                            (Some(a), Some(b)) => 10f64.powf((a + (b - a) * x) / 20.0),
                            (p, t) => {
                                let a = p.map_or(0.0, |db| 10f64.powf(db / 20.0));
                                let b = t.map_or(0.0, |db| 10f64.powf(db / 20.0));
                                a + (b - a) * x
                            }
                        }
                    }
                    _ => amp(seg).unwrap_or(0.0),
                };
            }
            prev = Some(seg.level_db);
            start = end;
        }
        self.segments.last().and_then(amp).unwrap_or(0.0)
    }

    /// The gain at every sample `k/fs`, `k < n`.
    ///
    /// ```
    /// use nav_sensors::vibration::{LevelSchedule, Segment};
    /// let s = LevelSchedule::new(vec![Segment { duration_s: 5.0, level_db: None, ramp_s: 0.0 },
    ///     Segment { duration_s: 5.0, level_db: Some(-6.0), ramp_s: 0.0 }]);
    /// let e = s.envelope(10, 1.0);
    /// assert_eq!(e[4], 0.0);
    /// assert!(e[5] > 0.5);
    /// ```
    pub fn envelope(&self, n: usize, fs: f64) -> Vec<f64> {
        (0..n).map(|k| self.gain(k as f64 / fs)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ramps_from_off_are_linear_in_amplitude_and_the_last_level_holds() {
        let s = LevelSchedule::new(vec![
            Segment {
                duration_s: 5.0,
                level_db: None,
                ramp_s: 0.0,
            },
            Segment {
                duration_s: 5.0,
                level_db: Some(0.0),
                ramp_s: 2.0,
            },
            Segment {
                duration_s: 5.0,
                level_db: None,
                ramp_s: 1.0,
            },
        ]);
        assert_eq!(s.gain(1.0), 0.0);
        assert!((s.gain(6.0) - 0.5).abs() < 1e-12);
        assert_eq!(s.gain(8.0), 1.0);
        assert!((s.gain(10.5) - 0.5).abs() < 1e-12);
        assert_eq!(s.gain(12.0), 0.0);
        assert_eq!(s.gain(100.0), 0.0);
    }
}
