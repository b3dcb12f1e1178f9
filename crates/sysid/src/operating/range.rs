//! The training range per operating signal: each signal's window mean and
//! its vibration level (the window rms about that mean) as the model's
//! training windows spanned them, and how far a new window lies outside.
//!
//! The operating points of [`super::OperatingPoints`] sum the signals'
//! variances into one level, so a network fitted on a z-axis shaker run
//! sees an x-axis run (same gravity, same overall level) as inside. Here
//! each signal keeps its own level: the z run's model saw 0.5 g rms on `az`
//! and a few hundredths on `ax`, and an x run's 0.3 g rms on `ax` lies far
//! outside. A window's distance outside is the Euclidean norm of each
//! coordinate's excess beyond the training interval `[min, max]`, divided by
//! the sensor's [`Sensor::operating_scale`]; the range counts as inside up
//! to the largest such distance of the validation windows (measured, so the
//! data the model was validated on are inside by construction, and a model
//! applied to its own record is unchanged).

use super::fade_settings::FadeSettings;
use super::shape::{ShapeRange, shape};
use crate::error::SysidError;
use crate::prepared::Prepared;
use crate::sensor::Sensor;
use serde::{Deserialize, Serialize};

/// A window's mean of one signal and its rms about that mean (population:
/// divided by the window length).
///
/// ```
/// let (m, level) = sysid::operating::range::mean_and_level(&[1.0, 3.0]);
/// assert_eq!((m, level), (2.0, 1.0));
/// ```
pub fn mean_and_level(a: &[f64]) -> (f64, f64) {
    let (m, var) = mean_and_variance(a);
    (m, var.sqrt())
}

/// A window's mean and variance about it, summed in time order (the onboard
/// evaluator sums in the same order).
pub(crate) fn mean_and_variance(a: &[f64]) -> (f64, f64) {
    let n = a.len().max(1) as f64;
    let m = a.iter().sum::<f64>() / n;
    (m, a.iter().map(|v| (v - m).powi(2)).sum::<f64>() / n)
}

/// Each record's operating-signal columns, looked up once and not once a
/// row: the lookup asks the sensor for its signal names, which allocates.
struct Columns<'p, S: Sensor> {
    sensor: &'p S,
    names: Vec<String>,
    seen: Vec<(&'p crate::signals::Signals, Vec<&'p [f64]>)>,
}

impl<'p, S: Sensor> Columns<'p, S> {
    fn new(prepared: &'p Prepared<S>) -> Self {
        let sensor = prepared.sensor();
        Self {
            sensor,
            names: sensor.operating_signals(),
            seen: Vec::new(),
        }
    }

    /// The operating signals' columns of `record`, in the sensor's order.
    fn of(&mut self, record: &'p crate::signals::Signals) -> Result<&[&'p [f64]], SysidError> {
        let at = match self.seen.iter().position(|(s, _)| std::ptr::eq(*s, record)) {
            Some(at) => at,
            None => {
                let cols = self
                    .names
                    .iter()
                    .map(|name| crate::prepared::signal(self.sensor, record, name))
                    .collect::<Result<Vec<_>, _>>()?;
                self.seen.push((record, cols));
                self.seen.len() - 1
            }
        };
        Ok(&self.seen[at].1)
    }
}

/// Per row in `rows`, each operating signal's mean and variance over the
/// window of `length` samples that ends at the row's sample (the one pass
/// over the windows both the joint points and the range read).
pub(crate) fn moments<S: Sensor>(
    prepared: &Prepared<S>,
    length: usize,
    rows: &[usize],
) -> Result<Vec<Vec<(f64, f64)>>, SysidError> {
    let mut columns = Columns::new(prepared);
    let mut out = Vec::with_capacity(rows.len());
    for &r in rows {
        let (record, end) = prepared.locate(r);
        let span = end + 1 - length.min(end + 1)..=end;
        out.push(
            columns
                .of(record)?
                .iter()
                .map(|a| mean_and_variance(&a[span.clone()]))
                .collect(),
        );
    }
    Ok(out)
}

/// Per row in `rows`, the window (of `length` samples ending at the row's
/// sample) statistics of each operating signal: the means of every signal,
/// then their levels, in the sensor's unit, then their shapes
/// ([`super::shape::shape`]).
pub fn statistics<S: Sensor>(
    prepared: &Prepared<S>,
    length: usize,
    rows: &[usize],
) -> Result<Vec<Vec<f64>>, SysidError> {
    let k = prepared.sensor().operating_signals().len();
    let mut columns = Columns::new(prepared);
    let mut out = Vec::with_capacity(rows.len());
    for &r in rows {
        let (record, end) = prepared.locate(r);
        let span = end + 1 - length.min(end + 1)..=end;
        let mut p = vec![0.0; 3 * k];
        for (j, column) in columns.of(record)?.iter().enumerate() {
            let a = &column[span.clone()];
            let (mean, var) = mean_and_variance(a);
            (p[j], p[k + j], p[2 * k + j]) = (mean, var.sqrt(), shape(a, var));
        }
        out.push(p);
    }
    Ok(out)
}

/// What a model saw of each operating signal, and its fade.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrainingRange {
    /// The operating signals (`ax`, `ay`, `az`).
    pub signals: Vec<String>,
    /// Samples of the window the statistics are taken over (the model's).
    pub window: usize,
    /// Smallest window mean of each signal over the training windows.
    pub mean_min: Vec<f64>,
    /// Largest window mean of each signal.
    pub mean_max: Vec<f64>,
    /// Smallest window rms about the mean (vibration level) of each signal.
    pub level_min: Vec<f64>,
    /// Largest level of each signal.
    pub level_max: Vec<f64>,
    /// Divisor of a coordinate's excess, in the signals' unit
    /// ([`Sensor::operating_scale`]).
    pub scale: f64,
    /// Distance (in `scale`s) up to which a window is inside: the largest of
    /// the fitted records' windows that did not train (validation, gaps).
    pub tolerance: f64,
    /// How the network part fades beyond it.
    pub fade: FadeSettings,
    /// Each channel's network part (the RBF sum without bias and effects)
    /// at rest: averaged over the quietest tenth of the training windows
    /// ([`fade::rest_rows`](super::fade::rest_rows)), in the target's unit;
    /// a record's hold starts there ([`fade`](super::fade)).
    pub network_mean: Vec<f64>,
    /// Each signal's vibration shape over the training windows
    /// ([`super::shape`]; absent in files written before: such a model
    /// judges mean and level alone, as it did).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shape: Option<ShapeRange>,
}

impl TrainingRange {
    /// The range of the training rows `train`, its tolerance measured on the
    /// rows `val` (those that did not train), with each channel's network
    /// mean given.
    pub fn from_training<S: Sensor>(
        prepared: &Prepared<S>,
        length: usize,
        train: &[usize],
        val: &[usize],
        network_mean: Vec<f64>,
    ) -> Result<Self, SysidError> {
        let sensor = prepared.sensor();
        let signals = sensor.operating_signals();
        let k = signals.len();
        let all = statistics(prepared, length, train)?;
        if all.is_empty() {
            return Err(SysidError::TooFewSamples {
                what: "training windows",
                have: 0,
                need: 1,
                hint: "use a longer record",
            });
        }
        let fold =
            |j: usize, f: fn(f64, f64) -> f64| all.iter().map(|p| p[j]).reduce(f).unwrap_or(0.0);
        let scale = sensor.operating_scale();
        let mut range = Self {
            mean_min: (0..k).map(|j| fold(j, f64::min)).collect(),
            mean_max: (0..k).map(|j| fold(j, f64::max)).collect(),
            level_min: (0..k).map(|j| fold(k + j, f64::min)).collect(),
            level_max: (0..k).map(|j| fold(k + j, f64::max)).collect(),
            signals,
            window: length,
            scale,
            tolerance: 0.0,
            fade: FadeSettings::for_window(length, prepared.calibrated().dt()),
            network_mean,
            shape: None,
        };
        // The shapes of every fitted window, validation too: the tolerance
        // stays the mean and level's, and a fitted record is inside.
        let val_stats = statistics(prepared, length, val)?;
        let fitted: Vec<&[f64]> = all.iter().chain(&val_stats).map(Vec::as_slice).collect();
        range.shape = Some(ShapeRange::from_training(&fitted, k, scale));
        let d = range.distances(&val_stats);
        range.tolerance = d.into_iter().fold(0.0, f64::max);
        Ok(range)
    }

    /// Whether the range fits a model of `signals` operating signals and
    /// `channels` channels (a hand-edited file may not): the reason if not.
    pub fn check(&self, signals: &[String], channels: usize) -> Result<(), SysidError> {
        let k = signals.len();
        let bad = |what: String| {
            Err(SysidError::OperatingPoints(format!(
                "training range: {what}"
            )))
        };
        if self.signals != signals {
            return bad(format!(
                "signals {} where the sensor has {}",
                self.signals.join(", "),
                signals.join(", ")
            ));
        }
        for (name, v) in [
            ("mean_min", &self.mean_min),
            ("mean_max", &self.mean_max),
            ("level_min", &self.level_min),
            ("level_max", &self.level_max),
        ] {
            if v.len() != k {
                return bad(format!("{} values of {name} for {k} signals", v.len()));
            }
        }
        if self.network_mean.len() != channels {
            return bad(format!(
                "{} network means for {channels} channels",
                self.network_mean.len()
            ));
        }
        if self.window == 0 || !(self.scale.is_finite() && self.scale > 0.0) {
            return bad(format!(
                "window {} samples, scale {}: need at least one sample and a positive scale",
                self.window, self.scale
            ));
        }
        match &self.shape {
            Some(shape) => shape.check(k).or_else(bad),
            None => Ok(()),
        }
    }

    /// Each window's distance outside the range (0 inside the training
    /// interval of every coordinate), from [`statistics`]: mean and level
    /// in `scale`s, shape in its own ([`super::shape`]).
    pub fn distances(&self, stats: &[Vec<f64>]) -> Vec<f64> {
        stats.iter().map(|p| self.distance(p)).collect()
    }

    /// One window's distance outside the range: the norm of each
    /// coordinate's excess, mean and level in `scale`s, shape (when the
    /// range has one) in its own, summed per signal in this order (the
    /// onboard evaluator sums alike).
    pub fn distance(&self, p: &[f64]) -> f64 {
        let k = self.signals.len();
        let mut sum = 0.0;
        for j in 0..k {
            let m = excess(p[j], self.mean_min[j], self.mean_max[j]) / self.scale;
            let l = excess(p[k + j], self.level_min[j], self.level_max[j]) / self.scale;
            sum += m * m + l * l;
            if let Some(shape) = &self.shape {
                let s = shape.term(j, p[k + j], p[2 * k + j], self.scale);
                sum += s * s;
            }
        }
        sum.sqrt()
    }

    /// Whether a window at distance `d` lies outside (beyond the tolerance).
    pub fn is_outside(&self, d: f64) -> bool {
        d > self.tolerance
    }

    /// What a record's windows (`stats`, from [`statistics`]) have that the
    /// model did not see, in words: which signal's level or mean, and the
    /// range the model saw there. Empty when at most 1% of the windows lie
    /// outside on any one coordinate.
    pub fn lacks(&self, stats: &[Vec<f64>], unit: &str, spread: &str) -> Vec<String> {
        let k = self.signals.len();
        let n = stats.len().max(1);
        // The windows beyond one coordinate's interval, and their extremes.
        let beyond = |coord: usize, lo: f64, hi: f64| -> Option<(f64, f64, f64)> {
            let far = stats
                .iter()
                .filter(|p| excess(p[coord], lo, hi) / self.scale > self.tolerance.max(1.0))
                .count();
            let (vmin, vmax) = stats
                .iter()
                .map(|p| p[coord])
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                    (a.min(v), b.max(v))
                });
            (far * 100 > n).then(|| (100.0 * far as f64 / n as f64, vmin, vmax))
        };
        let mut out = Vec::new();
        let levels: Vec<String> = (0..k)
            .filter_map(|j| {
                let (share, _, vmax) = beyond(k + j, self.level_min[j], self.level_max[j])?;
                Some(format!(
                    "this record has up to {vmax:.2} {unit} rms on {} ({share:.0}% of its windows beyond the {:.2} the model saw there)",
                    self.signals[j], self.level_max[j]
                ))
            })
            .collect();
        if !levels.is_empty() {
            let seen: Vec<usize> = (0..k)
                .filter(|&j| self.level_max[j] > 4.0 * self.scale)
                .collect();
            let names: Vec<&str> = seen.iter().map(|&j| self.signals[j].as_str()).collect();
            let lo = seen
                .iter()
                .map(|&j| self.level_min[j])
                .fold(f64::INFINITY, f64::min);
            let hi = seen.iter().map(|&j| self.level_max[j]).fold(0.0, f64::max);
            let saw = match names.len() {
                0 => format!(
                    "the model saw no {spread} above {:.2} {unit} rms",
                    4.0 * self.scale
                ),
                m if m < k => format!(
                    "the model saw {spread} on {} only ({lo:.2}–{hi:.2} {unit} rms)",
                    names.join(", ")
                ),
                _ => format!(
                    "the model saw {spread} on {} ({lo:.2}–{hi:.2} {unit} rms)",
                    names.join(", ")
                ),
            };
            out.push(format!("{saw}; {}", levels.join(", ")));
        }
        for j in 0..k {
            if let Some((share, vmin, vmax)) = beyond(j, self.mean_min[j], self.mean_max[j]) {
                out.push(format!(
                    "the model saw the mean of {} between {:.2} and {:.2} {unit}; this record's spans {vmin:.2} to {vmax:.2} {unit} ({share:.0}% of its windows beyond)",
                    self.signals[j], self.mean_min[j], self.mean_max[j]
                ));
            }
        }
        out.extend(self.shape_lacks(stats, n));
        out
    }

    /// The signals whose vibration has a shape (spectrum) the model did not
    /// see on more than 1% of the `n` windows `stats`, in words.
    fn shape_lacks(&self, stats: &[Vec<f64>], n: usize) -> Vec<String> {
        let (k, Some(shape)) = (self.signals.len(), &self.shape) else {
            return Vec::new();
        };
        (0..k)
            .filter_map(|j| {
                let far: Vec<f64> = stats
                    .iter()
                    .filter(|p| shape.term(j, p[k + j], p[2 * k + j], self.scale) > self.tolerance.max(1.0))
                    .map(|p| p[2 * k + j])
                    .collect();
                (far.len() * 100 > n).then(|| {
                    let lo = far.iter().copied().fold(f64::INFINITY, f64::min);
                    let hi = far.iter().copied().fold(0.0, f64::max);
                    format!(
                        "the vibration on {} has another spectrum: its shape (rms of the sample-to-sample change over √2 × rms; 1 white, toward 0 slower) reaches {lo:.2}–{hi:.2} where the model saw {:.2}–{:.2} ({:.0}% of its windows beyond)",
                        self.signals[j],
                        shape.min[j],
                        shape.max[j],
                        100.0 * far.len() as f64 / n as f64
                    )
                })
            })
            .collect()
    }
}

/// How far `v` lies beyond `[lo, hi]` (0 inside).
pub(crate) fn excess(v: f64, lo: f64, hi: f64) -> f64 {
    (lo - v).max(v - hi).max(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A range as a z-axis shaker run leaves it: gravity on z, vibration
    /// on z only.
    fn z_run() -> TrainingRange {
        TrainingRange {
            signals: vec!["ax".into(), "ay".into(), "az".into()],
            window: 50,
            mean_min: vec![-0.01, -0.01, 0.98],
            mean_max: vec![0.01, 0.01, 1.02],
            level_min: vec![0.0, 0.0, 0.1],
            level_max: vec![0.03, 0.02, 0.5],
            scale: 0.05,
            tolerance: 0.2,
            fade: FadeSettings::for_window(50, 0.02),
            network_mean: vec![0.0],
            shape: None,
        }
    }

    #[test]
    fn a_window_is_as_far_outside_as_its_coordinates_excess() {
        let r = z_run();
        // Inside every interval.
        assert_eq!(r.distance(&[0.0, 0.0, 1.0, 0.01, 0.01, 0.3]), 0.0);
        // 0.3 g rms on ax: 0.27 g beyond 0.03, 5.4 scales.
        let d = r.distance(&[0.0, 0.0, 1.0, 0.3, 0.01, 0.3]);
        assert!((d - 5.4).abs() < 1e-12, "{d}");
        assert!(r.is_outside(d));
        // Two coordinates beyond add in quadrature.
        let d2 = r.distance(&[0.04, 0.0, 1.0, 0.07, 0.01, 0.3]);
        assert!((d2 - (0.6f64.powi(2) + 0.8f64.powi(2)).sqrt()).abs() < 1e-12);
    }

    /// A range as files written before the shape hold it: no shape, no
    /// fall time constant. It loads, judges mean and level alone and its
    /// weight falls by the same one-pole as it rises (today's fade).
    #[test]
    fn a_range_written_before_the_shape_fades_as_it_did() {
        let mut json = serde_json::to_value(z_run()).unwrap();
        json["fade"]
            .as_object_mut()
            .unwrap()
            .remove("fall_time_constant_s");
        assert!(json.get("shape").is_none());
        let r: TrainingRange = serde_json::from_value(json).unwrap();
        assert_eq!(
            (r.shape.as_ref(), r.fade.fall_time_constant_s),
            (None, None)
        );
        assert_eq!(r.fade.fall_alpha(0.02), r.fade.alpha(0.02));
        // A window of another shape at the z run's level: inside without the
        // shape, outside with it.
        let p = [0.0, 0.0, 1.0, 0.01, 0.01, 0.3, 1.0, 1.0, 0.4];
        assert_eq!(r.distance(&p), 0.0);
        let with = TrainingRange {
            shape: Some(ShapeRange {
                min: vec![0.0, 0.0, 1.05],
                max: vec![2.0, 2.0, 1.35],
                scale: super::super::shape::SHAPE_SCALE,
            }),
            ..r
        };
        assert!(
            (with.distance(&p) - 6.5).abs() < 1e-9,
            "{}",
            with.distance(&p)
        );
    }

    #[test]
    fn the_hint_names_the_axis_and_level_the_model_did_not_see() {
        let r = z_run();
        let x_run: Vec<Vec<f64>> = (0..100)
            .map(|i| vec![0.0, 0.0, 1.0, 0.2 + 0.003 * i as f64, 0.01, 0.01])
            .collect();
        let lacks = r.lacks(&x_run, "g", "vibration");
        assert_eq!(lacks.len(), 1, "{lacks:?}");
        assert!(
            lacks[0].starts_with("the model saw vibration on az only (0.10–0.50 g rms); this record has up to 0.50 g rms on ax (100% of its windows beyond the 0.03"),
            "{}",
            lacks[0]
        );
        // A record like the training one lacks nothing.
        let z: Vec<Vec<f64>> = (0..100)
            .map(|_| vec![0.0, 0.0, 1.0, 0.01, 0.01, 0.3])
            .collect();
        assert!(r.lacks(&z, "g", "vibration").is_empty());
    }
}
