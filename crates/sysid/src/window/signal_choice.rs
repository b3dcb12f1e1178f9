//! Which of a sensor's vibration-input signals the windows read, chosen
//! from the training records ([`super::WindowSignals::Auto`], the default;
//! `--window-signals auto`). [`crate::Prepared`] makes the choice on the
//! calibrated records it prepares ([`crate::choose_window_signals`]).
//!
//! A network can only follow what its window sees. The paper windowed the
//! thrust axis alone, which is right for a z shaker but blind on an x or y
//! run: a model fitted on the three runs of a campaign with `az` alone
//! partials its effects out against a window that does not see the x and y
//! vibration, and spreads Y1 by 3% on the x run (docs/campaign.md §6). So
//! every operating signal ([`crate::Sensor::operating_signals`]: an inertial
//! unit's accelerometer axes) that vibrates significantly in some training
//! record is windowed, in the sensor's order.
//!
//! The rule ([`SIGNIFICANT_SHARE`]): on each calibrated record, each
//! signal's dynamic rms (about the record's mean, whole record); a record
//! *vibrates* when its strongest signal's dynamic rms reaches the sensor's
//! [`crate::Sensor::operating_scale`] (the spread it counts as one unit of
//! operating range: 0.05 g for an inertial unit), and a signal is taken when,
//! in some record that vibrates, its dynamic rms is at least
//! [`SIGNIFICANT_SHARE`] of that record's strongest. A rest record (noise
//! alone on every axis, all alike) thus takes nothing by itself, and a
//! shaker's transverse leakage (3–5% of the driven axis on the built-in
//! runs) is not vibration of its own. Measured on the built-in records (the
//! share of the record's strongest axis):
//!
//! | record | ax | ay | az | taken |
//! |---|---|---|---|---|
//! | demo, paper_z_random, z-axis, sine-sweep | 0.050 | 0.030 | 1 | az |
//! | x-axis | 1 | 0.050 | 0.030 | ax |
//! | y-axis | 0.050 | 1 | 0.030 | ay |
//! | triaxial | 1.000 | 1.000 | 1 | ax, ay, az |
//! | flight | 0.58 | 0.74 | 1 | ax, ay, az |
//!
//! The margin: the largest share left out is 0.050, 4× below the threshold;
//! the smallest taken, 0.58, 2.9× above it; the weakest vibrating record
//! (the demo's 0.296 g on az) is 5.9× the 0.05-g scale.
//!
//! When no record vibrates, the one signal of the largest dynamic rms is
//! windowed (the report says so); when no signal varies at all, or the
//! sensor names none, the choice is refused ([`WindowSignalsError`]).
//! Channels that choose among their own signals ([`choose_per_channel`])
//! and find every one constant (a still IMU, a dead accelerometer triad)
//! choose among every channel's instead, the report saying so.

use crate::signals::Signals;
use serde::{Deserialize, Serialize};

/// A signal is windowed when, in some record that vibrates, its dynamic
/// rms is at least this share of the record's strongest signal's.
pub const SIGNIFICANT_SHARE: f64 = 0.2;

/// Why the window's signals could not be chosen.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum WindowSignalsError {
    /// The sensor names no operating signal to choose among.
    #[error(
        "--window-signals auto: the sensor names no vibration-input signal (accelerometer axis) to choose among; name the window's signals with --window-signals SIGNAL[,SIGNAL...]"
    )]
    NoSignals,
    /// No operating signal varies in any record.
    #[error(
        "--window-signals auto: none of {} varies in any record (each is constant), so a window of them tells no sample from another; fit records with vibration, or name a signal that varies with --window-signals",
        signals.join(", ")
    )]
    Constant {
        /// The sensor's operating signals.
        signals: Vec<String>,
    },
    /// A record lacks one of the signals to choose among.
    #[error("window signal '{name}' is not a column of record '{record}'")]
    NotAColumn {
        /// The signal.
        name: String,
        /// The record.
        record: String,
    },
}

/// One operating signal as the choice measured it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SignalVibration {
    /// The signal (`ax`).
    pub signal: String,
    /// Its dynamic rms (about the record's mean) on each record, in
    /// [`WindowSignalsChoice::unit`], the records' order.
    pub rms: Vec<f64>,
    /// Its largest share of the strongest signal's dynamic rms over the
    /// records that vibrate (absent when none does).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub share: Option<f64>,
    /// Whether the windows read it.
    pub taken: bool,
}

/// The window's signals chosen from the training records, with what was
/// measured: the `window_signals` part of a fit's choice report.
///
/// ```
/// use sysid::window::signal_choice::choose_among;
/// let t: Vec<f64> = (0..400).map(|i| i as f64 * 0.02).collect();
/// let shake: Vec<f64> = t.iter().map(|t| 1.0 + 0.3 * (40.0 * t).sin()).collect();
/// let leak: Vec<f64> = t.iter().map(|t| 0.015 * (40.0 * t).sin()).collect();
/// let rec = sysid::Signals::new(t, vec![("ax".into(), leak.clone()), ("ay".into(), leak), ("az".into(), shake)])?;
/// let names = ["ax", "ay", "az"].map(String::from);
/// let c = choose_among(&names, &[("z run".into(), &rec)], 0.05, "g")?;
/// assert_eq!(c.taken, ["az"]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WindowSignalsChoice {
    /// Unit of the rms figures (the sensor's operating unit, `g`).
    pub unit: String,
    /// The dynamic rms a record's strongest signal reaches when the record
    /// vibrates ([`crate::Sensor::operating_scale`]), in [`WindowSignalsChoice::unit`].
    pub vibrates_at: f64,
    /// The records measured, in order.
    pub records: Vec<String>,
    /// Every operating signal of the sensor, in its order.
    pub signals: Vec<SignalVibration>,
    /// The signals windowed, in the sensor's order.
    pub taken: Vec<String>,
    /// The rule, in a sentence.
    pub rule: String,
    /// Set when the rule took none of the channels' own signals: what was
    /// taken instead, and why (no record vibrates, or their own signals
    /// are constant in every record).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fallback: Option<String>,
    /// The channels whose windows this choice is for, when channels choose
    /// among different signals (each gyro among its own IMU's
    /// accelerometers, [`choose_per_channel`]); empty when it is every
    /// channel's.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub channels: Vec<String>,
}

impl WindowSignalsChoice {
    /// One line for a terminal: what was taken and each signal's largest
    /// dynamic rms.
    pub fn line(&self) -> String {
        let measured: Vec<String> = self
            .signals
            .iter()
            .map(|s| {
                let peak = s.rms.iter().copied().fold(0.0, f64::max);
                format!("{} {peak:.4}", s.signal)
            })
            .collect();
        let why = match &self.fallback {
            Some(f) => f.clone(),
            None => format!(
                "taken: ≥ {SIGNIFICANT_SHARE} × the strongest signal's in a record whose strongest reaches {} {}",
                self.vibrates_at, self.unit
            ),
        };
        let of = match self.channels.is_empty() {
            true => String::new(),
            false => format!(" of {}", self.channels.join(",")),
        };
        format!(
            "window signals{of}: {} (auto; largest dynamic rms {} {}; {why})",
            self.taken.join(","),
            measured.join(", "),
            self.unit
        )
    }
}

/// The window's signals chosen by the module's rule from calibrated
/// `records`: `names` are the candidate signals (a sensor's
/// [`crate::Sensor::operating_signals`]), `scale` the dynamic rms a
/// record's strongest signal must reach for the record to vibrate
/// ([`crate::Sensor::operating_scale`]), `unit` theirs.
pub fn choose_among(
    names: &[String],
    records: &[(String, &Signals)],
    scale: f64,
    unit: &str,
) -> Result<WindowSignalsChoice, WindowSignalsError> {
    if names.is_empty() {
        return Err(WindowSignalsError::NoSignals);
    }
    // rms[k][r]: signal k on record r.
    let mut rms = vec![Vec::with_capacity(records.len()); names.len()];
    let mut share: Vec<Option<f64>> = vec![None; names.len()];
    for (record, s) in records {
        let here = names
            .iter()
            .map(|name| {
                let column = s
                    .column(name)
                    .ok_or_else(|| WindowSignalsError::NotAColumn {
                        name: name.clone(),
                        record: record.clone(),
                    })?;
                Ok(dynamic_rms(column))
            })
            .collect::<Result<Vec<f64>, WindowSignalsError>>()?;
        let strongest = here.iter().copied().fold(0.0, f64::max);
        for (k, r) in here.into_iter().enumerate() {
            rms[k].push(r);
            if strongest >= scale && strongest > 0.0 {
                share[k] = Some(share[k].map_or(r / strongest, |s| s.max(r / strongest)));
            }
        }
    }
    let mut taken: Vec<bool> = share
        .iter()
        .map(|s| s.is_some_and(|s| s >= SIGNIFICANT_SHARE))
        .collect();
    let mut fallback = None;
    if !taken.contains(&true) {
        // No record vibrates: the one signal that varies most, so the fit
        // still has a window (as the paper's single axis), said plainly.
        let peak = |k: usize| rms[k].iter().copied().fold(0.0, f64::max);
        let best = (0..names.len())
            .max_by(|&a, &b| peak(a).total_cmp(&peak(b)))
            .expect("at least one signal");
        if peak(best) <= 0.0 {
            return Err(WindowSignalsError::Constant {
                signals: names.to_vec(),
            });
        }
        taken[best] = true;
        fallback = Some(format!(
            "no record vibrates (no signal's dynamic rms reaches {scale} {unit}): the one that varies most taken"
        ));
    }
    Ok(WindowSignalsChoice {
        unit: unit.to_string(),
        vibrates_at: scale,
        records: records.iter().map(|(n, _)| n.clone()).collect(),
        signals: names
            .iter()
            .zip(rms)
            .zip(share.iter().zip(&taken))
            .map(|((signal, rms), (share, taken))| SignalVibration {
                signal: signal.clone(),
                rms,
                share: *share,
                taken: *taken,
            })
            .collect(),
        taken: names
            .iter()
            .zip(&taken)
            .filter(|(_, t)| **t)
            .map(|(n, _)| n.clone())
            .collect(),
        rule: format!(
            "each signal's dynamic rms (about the record's mean) on each record; a record vibrates when its strongest signal's reaches {scale} {unit}; a signal is windowed when it is at least {SIGNIFICANT_SHARE} of the strongest in some record that vibrates"
        ),
        fallback,
        channels: Vec::new(),
    })
}

/// Each channel's window signals, chosen by [`choose_among`] among its own
/// candidates (`candidates[k]`: channel k's, a sensor's
/// [`crate::Sensor::operating_signals_of`]), one choice per distinct list
/// of candidates: channel k's signals and the choices, each naming its
/// channels (`names`) when there are several. Channels that share their
/// candidates (every channel of a sensor of one list) make one choice.
/// `order` is the sensor's order of its signals
/// ([`crate::Sensor::signal_order`]), the window's list's
/// ([`ChannelSignals::window`]).
pub fn choose_per_channel(
    candidates: &[Vec<String>],
    order: &[String],
    names: &[String],
    records: &[(String, &Signals)],
    scale: f64,
    unit: &str,
) -> Result<ChannelSignals, WindowSignalsError> {
    let mut lists: Vec<&Vec<String>> = Vec::new();
    for c in candidates {
        if !lists.contains(&c) {
            lists.push(c);
        }
    }
    let every = super::ordered(super::union(candidates), order);
    let mut choices = Vec::with_capacity(lists.len());
    let mut constant = Vec::new();
    for list in &lists {
        let mut choice = match choose_among(list, records, scale, unit) {
            // Channels whose own signals are constant in every record (a
            // still IMU, a dead accelerometer triad) choose among every
            // candidate, as channels sharing one list do, not fail the
            // others' choice.
            Err(WindowSignalsError::Constant { signals })
                if every.iter().any(|s| !list.contains(s)) =>
            {
                constant.push(choices.len());
                among_every(&every, &signals, records, scale, unit)?
            }
            chosen => chosen?,
        };
        if lists.len() > 1 {
            choice.channels = (0..candidates.len())
                .filter(|&k| candidates[k] == **list)
                .map(|k| names[k].clone())
                .collect();
        }
        choices.push(choice);
    }
    let signals = candidates
        .iter()
        .map(|c| {
            let g = lists
                .iter()
                .position(|l| *l == c)
                .expect("a list of its own");
            choices[g].taken.clone()
        })
        .collect();
    Ok(ChannelSignals {
        signals,
        choices,
        order: order.to_vec(),
        constant,
    })
}

/// [`choose_among`] `every` candidate for channels whose own signals
/// (`own`) are constant in every record, the fallback saying so.
fn among_every(
    every: &[String],
    own: &[String],
    records: &[(String, &Signals)],
    scale: f64,
    unit: &str,
) -> Result<WindowSignalsChoice, WindowSignalsError> {
    let mut choice = choose_among(every, records, scale, unit)?;
    let why = format!(
        "their own {} constant in every record: chosen among every candidate",
        own.join(", ")
    );
    choice.fallback = Some(match choice.fallback {
        Some(also) => format!("{why}; {also}"),
        None => why,
    });
    Ok(choice)
}

/// Each channel's window signals as [`choose_per_channel`] chose them.
#[derive(Debug, Clone, PartialEq)]
pub struct ChannelSignals {
    /// Channel k's signals, in channel order.
    pub signals: Vec<Vec<String>>,
    /// The choices made, one per distinct list of candidates.
    pub choices: Vec<WindowSignalsChoice>,
    /// The sensor's order of its signals ([`crate::Sensor::signal_order`]).
    pub order: Vec<String>,
    /// The choices (indices into `choices`) of channels whose own signals
    /// were constant in every record (a still IMU, a dead accelerometer
    /// triad), made among every candidate instead.
    pub constant: Vec<usize>,
}

impl ChannelSignals {
    /// The window of `length` samples over each channel's signals, the
    /// window's list of them in the sensor's order
    /// ([`super::WindowSpec::per_channel`]).
    pub fn window(&self, length: usize) -> Result<super::WindowSpec, super::WindowError> {
        super::WindowSpec::per_channel(self.signals.clone(), &self.order, length)
    }
}

/// Root mean square about the mean (0 for an empty or non-finite column,
/// which then counts as not varying). Exactly 0 for a column of one value
/// (a still or dead accelerometer), whose mean can differ from that value
/// by a rounding: the fit refuses windows that repeat one point, so a
/// column that never changes must not count as one that varies a little.
fn dynamic_rms(x: &[f64]) -> f64 {
    if x.iter().all(|v| *v == x[0]) {
        return 0.0;
    }
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    let r = (x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt();
    if r.is_finite() { r } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names() -> Vec<String> {
        ["ax", "ay", "az"].map(String::from).to_vec()
    }

    /// A record whose three axes vibrate with these amplitudes, g (a
    /// sine plus a little noise, gravity on az).
    fn record(amp: [f64; 3]) -> Signals {
        let t: Vec<f64> = (0..2000).map(|i| i as f64 * 0.02).collect();
        let col = |k: usize, a: f64| -> Vec<f64> {
            t.iter()
                .enumerate()
                .map(|(i, t)| {
                    let g = if k == 2 { 1.0 } else { 0.0 };
                    g + a * (7.0 * t + k as f64).sin() + 1e-4 * ((i * 7919 + k) % 13) as f64
                })
                .collect()
        };
        let cols = names()
            .into_iter()
            .enumerate()
            .map(|(k, n)| (n, col(k, amp[k])))
            .collect();
        Signals::new(t, cols).unwrap()
    }

    #[test]
    fn a_z_shaker_record_takes_az_alone() {
        // The built-in z run's shares: 5% and 3% transverse.
        let z = record([0.015, 0.009, 0.3]);
        let c = choose_among(&names(), &[("z".into(), &z)], 0.05, "g").unwrap();
        assert_eq!(c.taken, ["az"]);
        assert!(c.fallback.is_none());
        assert!(!c.signals[0].taken && c.signals[2].taken);
        assert!((c.signals[0].share.unwrap() - 0.05).abs() < 0.01, "{c:?}");
    }

    #[test]
    fn three_single_axis_runs_take_every_axis() {
        let x = record([0.3, 0.015, 0.009]);
        let y = record([0.015, 0.3, 0.009]);
        let z = record([0.015, 0.009, 0.3]);
        let recs = [("x".into(), &x), ("y".into(), &y), ("z".into(), &z)];
        let c = choose_among(&names(), &recs, 0.05, "g").unwrap();
        assert_eq!(c.taken, ["ax", "ay", "az"]);
        // Two of them alone: their two axes, in the sensor's order.
        let c = choose_among(&names(), &recs[..2], 0.05, "g").unwrap();
        assert_eq!(c.taken, ["ax", "ay"]);
    }

    #[test]
    fn a_rest_record_does_not_take_its_noise() {
        // At rest every axis is noise of one size: none vibrates, so the
        // z run's choice stands.
        let rest = record([0.0, 0.0, 0.0]);
        let z = record([0.015, 0.009, 0.3]);
        let recs = [("rest".into(), &rest), ("z".into(), &z)];
        let c = choose_among(&names(), &recs, 0.05, "g").unwrap();
        assert_eq!(c.taken, ["az"]);
        // The rest record alone: the fallback, said.
        let c = choose_among(&names(), &recs[..1], 0.05, "g").unwrap();
        assert_eq!(c.taken.len(), 1);
        assert!(c.fallback.unwrap().contains("no record vibrates"));
    }

    #[test]
    fn constant_signals_and_no_signals_are_refused() {
        let t: Vec<f64> = (0..100).map(|i| i as f64).collect();
        let flat = Signals::new(
            t,
            names().into_iter().map(|n| (n, vec![0.5; 100])).collect(),
        )
        .unwrap();
        let err = choose_among(&names(), &[("flat".into(), &flat)], 0.05, "g").unwrap_err();
        assert!(matches!(err, WindowSignalsError::Constant { .. }), "{err}");
        assert!(
            err.to_string().contains("none of ax, ay, az varies"),
            "{err}"
        );
        let err = choose_among(&[], &[("flat".into(), &flat)], 0.05, "g").unwrap_err();
        assert!(
            err.to_string().contains("names no vibration-input signal"),
            "{err}"
        );
    }

    #[test]
    fn a_column_of_one_value_does_not_vary() {
        // 0.5 m/s² in g: its mean over 1200 samples is not exactly itself.
        let v = 0.5 / 9.80665;
        let column = vec![v; 1200];
        assert_ne!(column.iter().sum::<f64>() / 1200.0, v);
        assert_eq!(dynamic_rms(&column), 0.0);
        assert!(dynamic_rms(&[v, v, v + 1e-9]) > 0.0);
    }

    #[test]
    fn a_missing_column_is_named() {
        let t: Vec<f64> = (0..100).map(|i| i as f64).collect();
        let r = Signals::new(t, vec![("ax".into(), vec![0.0; 100])]).unwrap();
        let err = choose_among(&names(), &[("r".into(), &r)], 0.05, "g").unwrap_err();
        assert!(err.to_string().contains("'ay'"), "{err}");
    }
}
