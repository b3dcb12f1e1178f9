//! The gyro plug-in of the identification loop for the paper's unit: three
//! two-axis DTGs read as six channels (X, X1, Y, Y1, Z, Z1) and three
//! accelerometers, with their ground calibration and a known rate.
//!
//! It tells [`sysid`] what the loop cannot know: the channels' targets (each
//! output less the rate reference, eq. 4), the inverse error models of the
//! ground calibration, the IEEE Std 813 candidate effects in each channel's
//! (I, O, S) frame and their regressors ([`crate::effects`]), that
//! anisoinertia needs a varying rate, and which vibration axis would tell
//! two look-alike g-terms apart ([`crate::diagnose::separation`]).

use crate::effects::{
    ANISOINERTIA_MIN_RATE_DEG_S, Effect, EffectColumns, UnitColumns, is_unit_column,
    rate_variation_deg_s,
};
use crate::error::DtgVibError;
use crate::pipeline::RateReference;
use nav_sensors::calibration::Calibration;
use nav_sensors::dtg::DtgTerm;
use nav_sensors::geometry::{Axis, Channel, ideal_outputs};
use nav_sensors::record::Record;
use sysid::{Candidacy, OperatingStats, SensorError, Separation, Signals, Wording};

/// The paper's unit as a [`sysid::Sensor`]: its ground calibration (if
/// any) and the rate it saw (if known).
///
/// ```
/// use sysid::Sensor;
/// let unit = dtg_vib::paper_unit::PaperUnit::default();
/// assert_eq!(unit.channels().len(), 6);
/// assert_eq!(unit.operating_signals(), ["ax", "ay", "az"]);
/// assert_eq!(unit.wording().target_unit, "deg/h");
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PaperUnit {
    /// The ground calibration compensated before anything else.
    pub calibration: Option<Calibration>,
    /// The true rate, removed from every channel's output.
    pub rate_reference: RateReference,
}

impl sysid::Effect for Effect {
    fn id(&self) -> String {
        Effect::id(self)
    }
    fn unit(&self) -> String {
        Effect::unit(self)
    }
    fn description(&self) -> String {
        Effect::description(self)
    }
}

/// A record of the paper's unit as the loop's named signals: the six gyro
/// outputs, the three accelerations, then the extra columns, in order.
pub fn to_signals(record: &Record) -> Result<Signals, DtgVibError> {
    let columns = Channel::ALL
        .iter()
        .map(|&c| (c.name().to_string(), record.gyro(c).to_vec()))
        .chain(
            Axis::ALL
                .iter()
                .map(|&a| (a.column().to_string(), record.accel(a).to_vec())),
        )
        .chain(record.extra_names().into_iter().map(|n| {
            let v = record.extra(n).unwrap_or(&[]).to_vec();
            (n.to_string(), v)
        }))
        .collect();
    Ok(Signals::new(record.t().to_vec(), columns).map_err(sysid::SysidError::from)?)
}

/// Named records of the paper's unit as the loop's named signals.
pub fn named_signals(records: &[(String, &Record)]) -> Result<Vec<(String, Signals)>, DtgVibError> {
    records
        .iter()
        .map(|(n, r)| Ok((n.clone(), to_signals(r)?)))
        .collect()
}

/// Named signals as the loop borrows them.
pub fn borrowed(named: &[(String, Signals)]) -> Vec<(String, &Signals)> {
    named.iter().map(|(n, s)| (n.clone(), s)).collect()
}

/// The loop's named signals of the paper's unit as a record.
pub fn to_record(signals: &Signals) -> Result<Record, DtgVibError> {
    let u = columns(signals)?;
    let gyro = std::array::from_fn(|k| u.gyro_column(k).to_vec());
    let accel = std::array::from_fn(|k| u.accel_column(k).to_vec());
    let extra = u
        .extra_names()
        .into_iter()
        .map(|n| (n.to_string(), u.extra(n).unwrap_or(&[]).to_vec()))
        .collect();
    Ok(Record::new(signals.t().to_vec(), gyro, accel, extra)?)
}

/// The unit's columns of named signals, or the first one missing.
fn columns(signals: &Signals) -> Result<UnitColumns<'_>, DtgVibError> {
    UnitColumns::of_signals(signals).ok_or_else(|| {
        let missing = nav_sensors::record::SENSOR_COLUMNS
            .iter()
            .find(|n| signals.column(n).is_none())
            .unwrap_or(&"?");
        DtgVibError::Record(nav_sensors::record::RecordError::MissingColumn {
            file: "<record>".into(),
            name: missing.to_string(),
            header: signals.names().iter().map(|n| n.to_string()).collect(),
        })
    })
}

/// A dtg-vib error as the plug-in's.
fn boxed(e: impl Into<DtgVibError>) -> SensorError {
    Box::new(e.into())
}

impl sysid::Sensor for PaperUnit {
    type Channel = Channel;
    type Effect = Effect;
    type Axis = Axis;

    fn channels(&self) -> Vec<Channel> {
        Channel::ALL.to_vec()
    }

    fn wording(&self) -> Wording {
        Wording {
            target_unit: "deg/h".into(),
            operating_unit: "g".into(),
            spread: "vibration".into(),
            operating_noun: "low-passed specific force".into(),
            regime_hint: "a g- or g²-sensitive term along it may be missing".into(),
            slow_hint: "a temperature or a drift: add its column as col:NAME".into(),
        }
    }

    fn calibrate(&self, raw: &Signals) -> Result<Signals, SensorError> {
        let Some(c) = &self.calibration else {
            return Ok(raw.clone());
        };
        let calibrated = c.compensate(&to_record(raw).map_err(boxed)?);
        check_calibrated(&calibrated).map_err(boxed)?;
        to_signals(&calibrated).map_err(boxed)
    }

    fn targets(&self, calibrated: &Signals) -> Result<Vec<Vec<f64>>, SensorError> {
        let u = columns(calibrated).map_err(boxed)?;
        let reference = self.rate_reference.rate_deg_h().map(|w| ideal_outputs(&w));
        Ok((0..6)
            .map(|k| {
                let mut y = u.gyro_column(k).to_vec();
                if let Some(r) = reference {
                    y.iter_mut().for_each(|v| *v -= r[k]);
                }
                y
            })
            .collect())
    }

    fn operating_signals(&self) -> Vec<String> {
        Axis::ALL.iter().map(|a| a.column().to_string()).collect()
    }

    fn operating_scale(&self) -> f64 {
        MIN_SCALE_G
    }

    fn extra_columns(&self, record: &Signals) -> Vec<String> {
        record
            .names()
            .into_iter()
            .filter(|n| !is_unit_column(n))
            .map(String::from)
            .collect()
    }

    fn candidates(
        &self,
        calibrated: &Signals,
        samples: &[usize],
        _channel: usize,
    ) -> Vec<Candidacy<Effect>> {
        let extra = self.extra_columns(calibrated);
        let extra: Vec<&str> = extra.iter().map(String::as_str).collect();
        let rate_std = columns(calibrated)
            .map(|u| rate_variation_deg_s(u, samples.iter().copied()))
            .unwrap_or(0.0);
        Effect::candidates(&extra)
            .into_iter()
            .map(|e| match is_anisoinertia(&e) && rate_std < ANISOINERTIA_MIN_RATE_DEG_S {
                true => Candidacy::NotExcited {
                    effect: e,
                    reason: format!(
                        "the angular rate does not vary (largest std {rate_std:.3} deg/s < {ANISOINERTIA_MIN_RATE_DEG_S} deg/s): anisoinertia is not observable"
                    ),
                },
                false => Candidacy::Excited(e),
            })
            .collect()
    }

    fn check_excited(
        &self,
        calibrated: &Signals,
        samples: &[usize],
        channel: usize,
        effects: &[Effect],
    ) -> Result<(), SensorError> {
        let Some(ai) = effects.iter().find(|e| is_anisoinertia(e)) else {
            return Ok(());
        };
        let u = columns(calibrated).map_err(boxed)?;
        let v = rate_variation_deg_s(u, samples.iter().copied());
        if v < ANISOINERTIA_MIN_RATE_DEG_S {
            return Err(boxed(DtgVibError::EffectNotObservable {
                channel: Channel::ALL[channel],
                effect: ai.id(),
                rate_std_deg_s: v,
                min_deg_s: ANISOINERTIA_MIN_RATE_DEG_S,
            }));
        }
        Ok(())
    }

    fn parse_effect(&self, _channel: usize, id: &str) -> Result<Effect, SensorError> {
        id.parse::<Effect>().map_err(boxed)
    }

    fn regressors(
        &self,
        calibrated: &Signals,
        channel: usize,
        effects: &[Effect],
    ) -> Result<Vec<Vec<f64>>, SensorError> {
        // No effects, no columns: the record's rates and covariances (0.5 GB
        // for a 1M-sample record) are not worked out for nothing.
        if effects.is_empty() {
            return Ok(Vec::new());
        }
        let ch = Channel::ALL[channel];
        let cols = EffectColumns::new(columns(calibrated).map_err(boxed)?)
            .evaluate(ch, effects)
            .map_err(boxed)?;
        for (e, c) in effects.iter().zip(&cols) {
            check_range(
                || format!("channel {ch}'s effect {}", e.id()),
                c,
                calibrated.t(),
                "the record's accelerations (g) or rates are too large for this effect's products: check their units, or drop the effect",
            )
            .map_err(boxed)?;
        }
        Ok(cols)
    }

    fn separation(
        &self,
        channel: usize,
        group: &[Effect],
        kappa: &[f64],
        operating: &OperatingStats,
    ) -> Separation<Axis> {
        let m = &operating.means;
        let gravity_g = nalgebra::Vector3::new(m[0], m[1], m[2]);
        let variances = &operating.variances;
        let vibration_axis = Axis::ALL
            .into_iter()
            .max_by(|a, b| variances[a.index()].total_cmp(&variances[b.index()]))
            .unwrap_or(Axis::Z);
        crate::diagnose::separate::separation(
            Channel::ALL[channel],
            group,
            kappa,
            &gravity_g,
            variances.iter().sum::<f64>().sqrt(),
            vibration_axis,
        )
    }

    fn caveats(
        &self,
        records: &[(&Signals, Vec<usize>)],
        _channel: usize,
        effect: &Effect,
    ) -> Vec<String> {
        match effect {
            Effect::Term(t) if DtgTerm::SPECIFIC_FORCE.contains(t) => {
                crate::caveats::specific_force_caveats(
                    &nav_sensors::unit::Unit::paper(),
                    records,
                    t.is_quadratic(),
                )
            }
            _ => Vec::new(),
        }
    }

    /// The parity residues K0 … K5 (eq. 6): the fit's keep step holds each
    /// to a bias instability no higher than before, as each channel.
    fn residues(&self) -> Vec<(String, Vec<f64>)> {
        nav_sensors::geometry::Residue::ALL
            .iter()
            .map(|r| (r.name().to_string(), r.coefficients().to_vec()))
            .collect()
    }
}

pub use crate::unit_sensor::MIN_SCALE_G;

/// True for a rate-product (anisoinertia) effect.
fn is_anisoinertia(e: &Effect) -> bool {
    matches!(e, Effect::Term(t) if DtgTerm::ANISOINERTIA.contains(t))
}

/// What to check when a calibrated value is out of range.
const CALIBRATED_HINT: &str = "the calibration's coefficients or the record's values are out of range: check the units of both";

/// The record's values are within ±1e150 (the reader refuses more), but a
/// calibration's polynomial terms (an accelerometer's k3·a³, a gyro's g²
/// sensitivities) can carry them past what the filter and the fit can square.
fn check_calibrated(calibrated: &Record) -> Result<(), DtgVibError> {
    let hint = CALIBRATED_HINT;
    let t = calibrated.t();
    for ch in Channel::ALL {
        check_range(
            || format!("column '{}' after calibration", ch.name()),
            calibrated.gyro(ch),
            t,
            hint,
        )?;
    }
    check_calibrated_accel(t, &Axis::ALL.map(|a| calibrated.accel(a)))
}

/// [`check_calibrated`]'s test of the accelerometer triad (x, y, z) alone:
/// the first value non-finite or beyond ±1e150, with its column and time.
pub(crate) fn check_calibrated_accel(t: &[f64], accel: &[&[f64]; 3]) -> Result<(), DtgVibError> {
    for (axis, a) in Axis::ALL.iter().zip(accel) {
        check_range(
            || format!("column '{}' after calibration", axis.column()),
            a,
            t,
            CALIBRATED_HINT,
        )?;
    }
    Ok(())
}

/// The first value of `x` that is non-finite or beyond ±1e150, as an error
/// naming `what` and the record time.
fn check_range(
    what: impl FnOnce() -> String,
    x: &[f64],
    t: &[f64],
    hint: &'static str,
) -> Result<(), DtgVibError> {
    match x
        .iter()
        .position(|v| !(v.is_finite() && v.abs() <= tabular::MAX_MAGNITUDE))
    {
        None => Ok(()),
        Some(i) => Err(sysid::SysidError::OutOfRange {
            what: what(),
            value: x[i],
            t: t[i],
            row: i + 1,
            hint,
        }
        .into()),
    }
}
