//! From a test record of the paper's unit to model inputs: ground-calibration
//! compensation, the optional rate reference, low-pass (zero-phase, or causal
//! in [`Preprocess::causal`] mode), windows and effect columns — the loop's
//! preparation ([`sysid::Prepared`]) of the [`PaperUnit`], read by channel.
//!
//! The same [`Preprocess`] is stored in a fitted model, so compensation and
//! diagnosis see data prepared exactly as the training data were.

use crate::effects::Effect;
use crate::error::DtgVibError;
use crate::paper_unit::{PaperUnit, borrowed, named_signals, to_record, to_signals};
use crate::signal::LowPass;
use crate::window::Windows;
use faer::{Mat, MatRef};
use nav_sensors::calibration::Calibration;
use nav_sensors::geometry::{Axis, Channel};
use nav_sensors::record::Record;

pub use sysid::{FilterSpec, ModelInput, Smoother};

pub use crate::unit_sensor::{Preprocess, RateReference};

/// A record of the paper's unit prepared for fitting, compensation or
/// diagnosis: the loop's [`sysid::Prepared`] of the [`PaperUnit`] (which
/// keeps the calibration and pre-processing it was prepared with), read by
/// channel and with the calibrated record as a [`Record`].
///
/// Row `r` of the windows (and of every per-row quantity) is record sample
/// `first_sample() + r`.
#[derive(Debug, Clone)]
pub struct Prepared {
    inner: sysid::Prepared<PaperUnit>,
    preprocess: Preprocess,
    calibrated: Record,
}

impl Prepared {
    /// Compensates with `calibration` (if any), removes the rate reference,
    /// filters and forms windows.
    pub fn new(
        record: &Record,
        calibration: Option<&Calibration>,
        pre: &Preprocess,
    ) -> Result<Self, DtgVibError> {
        pre.rate_reference.check()?;
        let unit = PaperUnit {
            calibration: calibration.cloned(),
            rate_reference: pre.rate_reference,
        };
        let inner = sysid::Prepared::new(&unit, &to_signals(record)?, &pre.sysid())?;
        Self::of(inner, pre.clone())
    }

    /// Several records prepared one by one (calibration, filter and windows
    /// never cross from one record to the next) and laid end to end, named
    /// (by their file, say) for errors and per-record scores
    /// ([`sysid::Prepared::new_many`]). One record gives exactly
    /// [`Prepared::new`].
    pub fn new_many(
        records: &[(String, &Record)],
        calibration: Option<&Calibration>,
        pre: &Preprocess,
    ) -> Result<Self, DtgVibError> {
        if let [(_, record)] = records {
            return Self::new(record, calibration, pre);
        }
        if let Some((name, _)) = records.first() {
            // Said of the first record, as its preparation would.
            pre.rate_reference
                .check()
                .map_err(|e| DtgVibError::InRecord {
                    record: name.clone(),
                    source: Box::new(e),
                })?;
        }
        let unit = PaperUnit {
            calibration: calibration.cloned(),
            rate_reference: pre.rate_reference,
        };
        let signals = named_signals(records)?;
        let inner = sysid::Prepared::new_many(&unit, &borrowed(&signals), &pre.sysid())?;
        Self::of(inner, pre.clone())
    }

    /// The loop's preparation as the paper unit's.
    pub(crate) fn of(
        inner: sysid::Prepared<PaperUnit>,
        preprocess: Preprocess,
    ) -> Result<Self, DtgVibError> {
        let calibrated = to_record(inner.calibrated())?;
        Ok(Self {
            inner,
            preprocess,
            calibrated,
        })
    }

    /// The loop's preparation.
    pub fn inner(&self) -> &sysid::Prepared<PaperUnit> {
        &self.inner
    }

    /// The ground calibration the record was compensated with, if any.
    pub fn calibration(&self) -> Option<&Calibration> {
        self.inner.sensor().calibration.as_ref()
    }

    /// How the record was prepared.
    pub fn preprocess(&self) -> &Preprocess {
        &self.preprocess
    }

    /// The records and their rows: one entry per record of
    /// [`Prepared::new_many`], and one named `""` for [`Prepared::new`].
    pub fn record_rows(&self) -> Vec<(&str, std::ops::Range<usize>)> {
        self.inner.record_rows()
    }

    /// The calibrated (not filtered) record, the records end to end.
    pub fn calibrated(&self) -> &Record {
        &self.calibrated
    }

    /// Number of rows (windows).
    pub fn rows(&self) -> usize {
        self.inner.rows()
    }

    /// Record sample of row 0.
    pub fn first_sample(&self) -> usize {
        self.inner.first_sample()
    }

    /// The windows as an `rows × dim` matrix.
    pub fn window_matrix(&self) -> Mat<f64> {
        self.inner.window_matrix()
    }

    /// The windows as an `rows × dim` matrix view of the prepared windows
    /// themselves (nothing is copied).
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new((1..=60).map(|i| i as f64 * 0.02).collect(),
    ///     std::array::from_fn(|_| vec![0.0; 60]), [vec![0.0; 60], vec![0.0; 60], (0..60).map(f64::from).collect()],
    ///     vec![]).unwrap();
    /// let pre = dtg_vib::pipeline::Preprocess { filter: None, ..Default::default() };
    /// let p = dtg_vib::pipeline::Prepared::new(&rec, None, &pre).unwrap();
    /// assert_eq!(p.window_view(), p.window_matrix().as_ref());
    /// ```
    pub fn window_view(&self) -> MatRef<'_, f64> {
        self.inner.window_view()
    }

    /// The windows.
    pub fn windows(&self) -> &Windows {
        self.inner.windows()
    }

    /// A channel's filtered, reference-removed output over the whole record, deg/h.
    pub fn target_full(&self, channel: Channel) -> &[f64] {
        self.inner.target_full(channel.index())
    }

    /// A channel's target on the rows, deg/h.
    pub fn target(&self, channel: Channel) -> &[f64] {
        self.inner.target(channel.index())
    }

    /// The filtered effect columns of a channel over the whole record.
    pub fn effect_columns_full(
        &self,
        channel: Channel,
        effects: &[Effect],
    ) -> Result<Vec<Vec<f64>>, DtgVibError> {
        Ok(self.inner.effect_columns_full(channel.index(), effects)?)
    }

    /// The effect columns of a channel on the rows, as an `rows × effects` matrix.
    pub fn effect_matrix(
        &self,
        channel: Channel,
        effects: &[Effect],
    ) -> Result<Mat<f64>, DtgVibError> {
        Ok(self.inner.effect_matrix(channel.index(), effects)?)
    }

    /// A record signal (accelerometer axis or extra column), filtered, over the whole record.
    pub fn signal_full(&self, name: &str) -> Result<Vec<f64>, DtgVibError> {
        Ok(self.inner.signal_full(name)?)
    }

    /// A series over the whole record (one sample per record sample)
    /// through the filter the targets went through, zero-phase or causal:
    /// e.g. a simulator's per-sample noise floor as the model's target sees
    /// it. For a preparation of one record.
    pub fn filter_like_targets(&self, x: &[f64]) -> Result<Vec<f64>, DtgVibError> {
        Ok(self.inner.filter_like_targets(x)?)
    }

    /// True when prepared in causal mode ([`Preprocess::causal`]).
    pub fn causal(&self) -> bool {
        self.inner.causal()
    }

    /// The designed filter, if any.
    pub fn filter(&self) -> Option<&LowPass> {
        self.inner.filter()
    }

    /// Samples over which one sample influences its filtered neighbours on
    /// each side ([`sysid::Prepared::filter_memory`]).
    pub fn filter_memory(&self) -> usize {
        self.inner.filter_memory()
    }
}

/// An accelerometer axis (`ax`, `ay`, `az`) or an extra column of a record.
pub fn signal<'r>(record: &'r Record, name: &str) -> Result<&'r [f64], DtgVibError> {
    if let Some(axis) = Axis::ALL.into_iter().find(|a| a.column() == name) {
        return Ok(record.accel(axis));
    }
    record.extra(name).ok_or_else(|| {
        DtgVibError::Sysid(sysid::SysidError::WindowSignal {
            name: name.to_string(),
            operating: Axis::ALL.iter().map(|a| a.column().to_string()).collect(),
            available: record.extra_names().iter().map(|s| s.to_string()).collect(),
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::window::WindowSpec;
    use nav_sensors::sim::Site;

    fn record(n: usize) -> Record {
        let t: Vec<f64> = (1..=n).map(|i| i as f64 * 0.02).collect();
        let az: Vec<f64> = (0..n).map(|i| 1.0 + (i as f64 * 0.7).sin()).collect();
        let gyro = std::array::from_fn(|k| (0..n).map(|i| k as f64 + 0.1 * az[i]).collect());
        Record::new(
            t,
            gyro,
            [vec![0.0; n], vec![0.0; n], az],
            vec![("temp".into(), vec![20.0; n])],
        )
        .unwrap()
    }

    #[test]
    fn rows_align_windows_targets_and_effects() {
        let rec = record(300);
        let pre = Preprocess {
            filter: None,
            ..Preprocess::default()
        };
        let p = Prepared::new(&rec, None, &pre).unwrap();
        assert_eq!(p.rows(), 251);
        assert_eq!(p.first_sample(), 49);
        let z = p
            .effect_matrix(Channel::Z, &["g_I".parse().unwrap()])
            .unwrap();
        // Channel Z: g_I is az; row r is sample 49 + r, the last element of its window.
        for r in [0, 100, 250] {
            assert_eq!(z[(r, 0)], rec.accel(Axis::Z)[49 + r]);
            assert_eq!(p.windows().row(r)[49], rec.accel(Axis::Z)[49 + r]);
            assert_eq!(p.target(Channel::Z)[r], rec.gyro(Channel::Z)[49 + r]);
        }
    }

    #[test]
    fn a_preprocess_written_before_causal_mode_reads_as_zero_phase() {
        let old = r#"{"filter": {"order": 4, "cutoff_hz": 5.0}, "input_filter": null,
            "window": {"signals": ["az"], "length": 50}, "rate_reference": {"kind": "none"}}"#;
        let p: Preprocess = serde_json::from_str(old).unwrap();
        assert!(!p.causal);
        let az = Preprocess {
            window: WindowSpec::new(vec!["az".into()], 50).unwrap(),
            ..Preprocess::default()
        };
        assert_eq!(p, az);
    }

    #[test]
    fn causal_preparation_never_looks_ahead() {
        let rec = record(400);
        let pre = Preprocess {
            causal: true,
            ..Preprocess::default()
        };
        let mut az = rec.accel(Axis::Z).to_vec();
        az[300..].iter_mut().for_each(|v| *v += 1.0);
        let changed = rec.with_accel([vec![0.0; 400], vec![0.0; 400], az]);
        let (a, b) = (
            Prepared::new(&rec, None, &pre).unwrap(),
            Prepared::new(&changed, None, &pre).unwrap(),
        );
        let e: Vec<Effect> = vec!["gg_II".parse().unwrap()];
        let (ea, eb) = (
            a.effect_columns_full(Channel::Z, &e).unwrap(),
            b.effect_columns_full(Channel::Z, &e).unwrap(),
        );
        // One sample of look-ahead: the covariance of sample 299 uses 300.
        assert_eq!(ea[0][..299], eb[0][..299]);
        assert_ne!(ea[0][299], eb[0][299]);
        assert_ne!(ea[0][301], eb[0][301]);
        // Zero-phase, the same change reaches further back.
        let zp = Preprocess::default();
        let (za, zb) = (
            Prepared::new(&rec, None, &zp).unwrap(),
            Prepared::new(&changed, None, &zp).unwrap(),
        );
        assert_ne!(
            za.effect_columns_full(Channel::Z, &e).unwrap()[0][295],
            zb.effect_columns_full(Channel::Z, &e).unwrap()[0][295]
        );
    }

    #[test]
    fn rate_reference_is_removed_from_every_channel() {
        let rec = record(200);
        let pre = Preprocess {
            filter: None,
            rate_reference: RateReference::Table {
                rate_deg_s: [0.0, 0.0, 1.0],
            },
            ..Preprocess::default()
        };
        let p = Prepared::new(&rec, None, &pre).unwrap();
        let m = nav_sensors::geometry::ideal_outputs(&nalgebra::Vector3::new(0.0, 0.0, 3600.0));
        for ch in Channel::ALL {
            assert!((p.target_full(ch)[7] - (rec.gyro(ch)[7] - m[ch.index()])).abs() < 1e-9);
        }
    }

    #[test]
    fn an_impossible_rate_reference_is_refused_with_its_reason() {
        let rec = record(200);
        let with = |r| Preprocess {
            filter: None,
            rate_reference: r,
            ..Preprocess::default()
        };
        for (r, want) in [
            (
                RateReference::Earth {
                    site: Site {
                        latitude_deg: 95.0,
                        ..Site::default()
                    },
                },
                "latitude = 95",
            ),
            (
                RateReference::Earth {
                    site: Site {
                        latitude_deg: f64::NAN,
                        ..Site::default()
                    },
                },
                "latitude = NaN",
            ),
            (
                RateReference::Table {
                    rate_deg_s: [0.0, f64::INFINITY, 0.0],
                },
                "table rate = [0.0, inf, 0.0]",
            ),
        ] {
            let Err(err) = Prepared::new(&rec, None, &with(r)) else {
                panic!("{want}: accepted");
            };
            let err = err.to_string();
            assert!(err.starts_with(want), "{err}");
        }
        let crossed = RateReference::Earth {
            site: Site {
                latitude_deg: 10.0,
                orientation: nav_sensors::sim::Orientation {
                    x: nav_sensors::sim::Direction::Up,
                    z: nav_sensors::sim::Direction::Up,
                },
            },
        };
        let Err(err) = Prepared::new(&rec, None, &with(crossed)) else {
            panic!("crossed axes: accepted");
        };
        let err = err.to_string();
        assert!(err.contains("orientation"), "{err}");
    }

    #[test]
    fn unknown_window_signal_lists_the_columns() {
        let rec = record(100);
        let pre = Preprocess {
            window: WindowSpec::new(vec!["aw".into()], 10).unwrap(),
            ..Preprocess::default()
        };
        let err = Prepared::new(&rec, None, &pre).unwrap_err();
        assert_eq!(
            err.to_string(),
            "window signal 'aw' is not a record column (use ax, ay, az or an extra column: temp)"
        );
    }

    #[test]
    fn record_shorter_than_a_window_is_an_error() {
        let rec = record(30);
        let err = Prepared::new(
            &rec,
            None,
            &Preprocess {
                filter: None,
                ..Preprocess::default()
            },
        )
        .unwrap_err();
        assert!(
            matches!(
                err,
                DtgVibError::Sysid(sysid::SysidError::Window(
                    crate::window::WindowError::TooShort {
                        samples: 30,
                        length: 50
                    }
                ))
            ),
            "{err}"
        );
    }
}
