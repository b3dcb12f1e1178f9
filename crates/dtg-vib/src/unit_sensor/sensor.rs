//! The unit as the loop's sensor ([`sysid::Sensor`]): its channels,
//! effects, rate reference, pre-processing and wording.

use nalgebra::{DMatrix, Vector3};
use nav_sensors::calibration::UnitCalibration;
use nav_sensors::dtg::{DtgTerm, within_interval_covariance};
use nav_sensors::geometry::Axis;
use nav_sensors::rate::RateTerm;
use nav_sensors::unit::{GyroTerm, Sensed, Unit};
use sysid::{Candidacy, OperatingStats, SensorError, Separation, Signals, Wording};

use super::calibrated;
use super::dynamic::{self, ACCEL_PREFIX, Dynamic, Stimulus, expand_dynamic};
use super::effect::{ANISOINERTIA_MIN_RATE_DEG_S, UnitEffect, UnitEffectError};
use super::error::UnitSensorError;
use super::observable::largest_axis_std;
use super::preprocess::RateReference;
use super::range;
use super::separate;
use super::signals::{to_record, to_signals};

/// A unit as a [`sysid::Sensor`]: the unit, its ground calibration (if
/// any) and the rate it saw (if known).
///
/// ```
/// use sysid::Sensor;
/// let tetra = nav_sensors::unit::Unit::builtin("tetra").unwrap();
/// let s = dtg_vib::unit_sensor::UnitSensor::new(tetra);
/// assert_eq!(s.channels(), ["g1", "g2", "g3", "g4"]);
/// assert_eq!(s.operating_signals(), ["ax", "ay", "az"]);
/// assert_eq!(s.parse_effect(1, "g_y").unwrap().unit(), "deg/h/g");
/// assert!(s.parse_effect(1, "g_I").is_err()); // a DTG term on a rate gyro
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct UnitSensor {
    /// The unit.
    pub unit: Unit,
    /// The ground calibration compensated before anything else.
    pub calibration: Option<UnitCalibration>,
    /// The true rate (unit frame), removed from every channel's output.
    pub rate_reference: RateReference,
}

impl UnitSensor {
    /// The unit without calibration or rate reference.
    pub fn new(unit: Unit) -> Self {
        Self {
            unit,
            calibration: None,
            rate_reference: RateReference::None,
        }
    }

    /// The channel's own column, or which one is missing.
    fn gyro_column<'a>(&self, s: &'a Signals, k: usize) -> Result<&'a [f64], UnitSensorError> {
        let name = &self.unit.gyros()[k].name;
        s.column(name).ok_or_else(|| self.missing(s, name))
    }

    fn missing(&self, s: &Signals, name: &str) -> UnitSensorError {
        UnitSensorError::MissingColumn {
            name: name.to_string(),
            unit_file: self.unit.file().to_string(),
            columns: s.names().iter().map(|n| n.to_string()).collect(),
        }
    }

    /// The specific force in the unit frame, per sample, g.
    fn specific_force(&self, s: &Signals) -> Result<Vec<Vector3<f64>>, UnitSensorError> {
        let cols = self
            .unit
            .accel_names()
            .iter()
            .map(|n| s.column(n).ok_or_else(|| self.missing(s, n)))
            .collect::<Result<Vec<_>, _>>()?;
        Ok((0..s.len())
            .map(|i| {
                let row: Vec<f64> = cols.iter().map(|c| c[i]).collect();
                self.unit.specific_force(&row)
            })
            .collect())
    }

    /// The gyro outputs per sample, deg/h, in file order.
    fn gyro_rows(&self, s: &Signals) -> Result<Vec<Vec<f64>>, UnitSensorError> {
        let cols = (0..self.unit.gyros().len())
            .map(|k| self.gyro_column(s, k))
            .collect::<Result<Vec<_>, _>>()?;
        Ok((0..s.len())
            .map(|i| cols.iter().map(|c| c[i]).collect())
            .collect())
    }

    /// The rate reference at each sample of a calibrated record, deg/h,
    /// or `None` without one.
    pub(crate) fn reference_rates(
        &self,
        s: &Signals,
    ) -> Result<Option<Vec<Vector3<f64>>>, UnitSensorError> {
        if self.rate_reference == RateReference::None {
            return Ok(None);
        }
        Ok(self
            .rate_reference
            .rates_deg_h(&self.unit, &self.gyro_rows(s)?))
    }

    /// How much the least-squares rate varies over `samples`: the largest
    /// standard deviation of its three axes, deg/s.
    pub(super) fn rate_variation_deg_s(&self, s: &Signals, samples: &[usize]) -> f64 {
        let Ok(rows) = self.gyro_rows(s) else {
            return 0.0;
        };
        let rates: Vec<Vector3<f64>> = samples
            .iter()
            .filter(|&&i| i < rows.len())
            .map(|&i| self.unit.least_squares_rate(&rows[i]) / 3600.0)
            .collect();
        largest_axis_std(&rates)
    }
}

impl UnitSensor {
    /// The rate the dynamic effects read, per sample, deg/h: the reference
    /// where one is given, the unit's least-squares rate H⁺m otherwise.
    fn dynamic_rate(&self, s: &Signals) -> Result<Vec<Vector3<f64>>, UnitSensorError> {
        if let Some(w) = self.reference_rates(s)? {
            return Ok(w);
        }
        let rows = self.gyro_rows(s)?;
        Ok(rows
            .iter()
            .map(|m| self.unit.least_squares_rate(m))
            .collect())
    }

    /// The columns of the dynamic effects among `effects`, in their order.
    fn dynamic_columns(
        &self,
        s: &Signals,
        channel: usize,
        effects: &[UnitEffect],
    ) -> Result<Vec<Vec<f64>>, UnitSensorError> {
        let dynamic: Vec<&Dynamic> = effects
            .iter()
            .filter_map(|e| match e {
                UnitEffect::Dynamic(d) => Some(d),
                _ => None,
            })
            .collect();
        let rate = match dynamic.iter().any(|d| d.reads_rate()) {
            true => self.dynamic_rate(s)?,
            false => Vec::new(),
        };
        let input = self.unit.gyros()[channel].input;
        let t = s.t();
        let dt_s = match t.len() {
            0 | 1 => 1.0,
            n => (t[n - 1] - t[0]) / (n - 1) as f64,
        };
        dynamic
            .iter()
            .map(|d| {
                self.check_dynamic(channel, d)?;
                let accel = match &d.stimulus {
                    Stimulus::Accel(n) => s.column(n).ok_or_else(|| self.missing(s, n))?,
                    _ => &[],
                };
                Ok(d.column(&input, &rate, accel, dt_s))
            })
            .collect()
    }

    /// The dynamic effects a channel fitted in parity is offered: the
    /// research's causal linear model (scale factor and misalignments with
    /// their rate taps to 4 samples, every accelerometer's taps to 5);
    /// none against a true or no rate reference, where the record is still
    /// or table-mounted and the rate does not vary.
    fn flight_candidates(&self, channel: usize) -> Vec<UnitEffect> {
        if self.rate_reference != RateReference::Parity {
            return Vec::new();
        }
        let input = self.unit.gyros()[channel].input;
        let accels = self.unit.accel_names();
        FLIGHT_EFFECTS
            .iter()
            .flat_map(|item| expand_dynamic(item, &input, &accels).unwrap_or_default())
            .filter_map(|id| id.parse().ok())
            .collect()
    }

    /// A dynamic effect the channel can take: an accelerometer of the
    /// unit, a misalignment about an axis other than the input's.
    fn check_dynamic(&self, channel: usize, d: &Dynamic) -> Result<(), UnitEffectError> {
        let g = &self.unit.gyros()[channel];
        let wrong = |valid: Vec<String>| UnitEffectError::WrongDynamic {
            channel: g.name.clone(),
            id: d.to_string(),
            valid,
        };
        match &d.stimulus {
            Stimulus::Accel(n) if !self.unit.accel_names().contains(&n.as_str()) => Err(wrong(
                self.unit
                    .accel_names()
                    .iter()
                    .map(|a| format!("{ACCEL_PREFIX}{a}"))
                    .collect(),
            )),
            Stimulus::AxisRate(a) if dynamic::is_input_axis(&g.input, *a) => Err(wrong(
                Axis::ALL
                    .iter()
                    .filter(|x| !dynamic::is_input_axis(&g.input, **x))
                    .map(|x| format!("ma_{x}"))
                    .chain(std::iter::once("sf (its input axis)".to_string()))
                    .collect(),
            )),
            _ => Ok(()),
        }
    }
}

/// For gyro `j`, the least-squares rate operator of the other gyros (row j
/// of H zeroed), or `None` when they do not span three dimensions (a unit
/// of three gyros): a channel's own output never enters its regressors.
pub(crate) fn rate_without(unit: &Unit, j: usize) -> Option<DMatrix<f64>> {
    let mut h = unit.measurement_matrix().clone();
    h.row_mut(j).fill(0.0);
    let svd = h.clone().svd(true, true);
    if svd.singular_values.min() < 1e-6 {
        return None;
    }
    svd.pseudo_inverse(1e-12).ok()
}

/// The dynamic effects a channel fitted in parity is offered (as
/// `--effects` items): the delay, and the taps that on the real three-IMU
/// flights meet the issue's acceptance (docs/tutorial.md, "Flight data").
pub const FLIGHT_EFFECTS: [&str; 4] = ["delay", "sf@0..4", "ma_*@0..4", "acc:*@0..5"];

/// Smallest spread an operating point's coordinate is divided by, g: a
/// coordinate the training windows held constant (gravity along x in a
/// Z-axis test) measures a change of 0.05 g (a 3° tilt of gravity) as one
/// unit, not as infinitely many; an accelerometer bias that differs between
/// two runs by a few mg is not a new operating point.
pub const MIN_SCALE_G: f64 = 0.05;

/// A plug-in error as the loop's.
fn boxed(e: impl Into<UnitSensorError>) -> SensorError {
    Box::new(e.into())
}

fn is_anisoinertia(e: &UnitEffect) -> bool {
    matches!(e, UnitEffect::Term(GyroTerm::Dtg(t)) if DtgTerm::ANISOINERTIA.contains(t))
}

impl UnitSensor {
    /// `raw` compensated with the ground calibration `c`, checked in range.
    fn calibrated(&self, c: &UnitCalibration, raw: &Signals) -> Result<Signals, SensorError> {
        let record = to_record(&self.unit, raw).map_err(boxed)?;
        let out = c
            .compensate(&self.unit, &record)
            .map_err(|e| boxed(UnitSensorError::Calibration(e.to_string())))?;
        let calibrated = to_signals(&out).map_err(boxed)?;
        let names = self.unit.gyro_names().into_iter();
        range::check_calibrated(&calibrated, names.chain(self.unit.accel_names()))
            .map_err(|e| Box::new(e) as SensorError)?;
        Ok(calibrated)
    }
}

impl sysid::Sensor for UnitSensor {
    type Channel = String;
    type Effect = UnitEffect;
    type Axis = Axis;

    fn channels(&self) -> Vec<String> {
        self.unit
            .gyro_names()
            .iter()
            .map(|n| n.to_string())
            .collect()
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
        calibrated::remembered((&self.unit, c), raw, || self.calibrated(c, raw))
    }

    fn targets(&self, calibrated: &Signals) -> Result<Vec<Vec<f64>>, SensorError> {
        let reference = self.reference_rates(calibrated).map_err(boxed)?;
        (0..self.unit.gyros().len())
            .map(|k| {
                let mut y = self.gyro_column(calibrated, k).map_err(boxed)?.to_vec();
                if let Some(w) = &reference {
                    let input = self.unit.gyros()[k].input;
                    y.iter_mut().zip(w).for_each(|(v, w)| *v -= input.dot(w));
                }
                Ok(y)
            })
            .collect()
    }

    /// The unit's accelerometers; for a unit of several IMUs with more
    /// accelerometers than the loop's operating points take, the first
    /// gyro's IMU's (they share the vehicle's specific force).
    fn operating_signals(&self) -> Vec<String> {
        let all = self.unit.accel_names();
        let names = match all.len() > sysid::operating::MAX_COORDINATES - 1 {
            true if !self.unit.gyros().is_empty() => self.unit.imu_accel_names(0),
            _ => all,
        };
        names.iter().map(|n| n.to_string()).collect()
    }

    /// Gyro `channel`'s IMU's accelerometers (every accelerometer when the
    /// unit groups none into IMUs).
    fn operating_signals_of(&self, channel: usize) -> Vec<String> {
        match channel < self.unit.gyros().len() {
            true => self.unit.imu_accel_names(channel),
            false => self.unit.accel_names(),
        }
        .iter()
        .map(|n| n.to_string())
        .collect()
    }

    /// The unit's accelerometers in its file's order (`[[accel]]`), the
    /// order an exported model's list of window signals keeps.
    fn signal_order(&self) -> Vec<String> {
        self.unit
            .accel_names()
            .iter()
            .map(|n| n.to_string())
            .collect()
    }

    fn operating_scale(&self) -> f64 {
        MIN_SCALE_G
    }

    fn extra_columns(&self, record: &Signals) -> Vec<String> {
        let own =
            |n: &str| self.unit.gyro_names().contains(&n) || self.unit.accel_names().contains(&n);
        record
            .names()
            .into_iter()
            .filter(|n| !own(n))
            .map(String::from)
            .collect()
    }

    fn candidates(
        &self,
        calibrated: &Signals,
        samples: &[usize],
        channel: usize,
    ) -> Vec<Candidacy<UnitEffect>> {
        let model = &self.unit.gyros()[channel].model;
        let own_rate = rate_without(&self.unit, channel).is_some();
        let rate_std = self.rate_variation_deg_s(calibrated, samples);
        UnitEffect::terms_of(model)
            .into_iter()
            .chain(self.flight_candidates(channel))
            .chain(
                self.extra_columns(calibrated)
                    .into_iter()
                    .map(|c| UnitEffect::column(&c, Some(&self.unit))),
            )
            .map(|e| {
                if !is_anisoinertia(&e) {
                    return Candidacy::Excited(e);
                }
                let reason = if !own_rate {
                    "the other gyros do not span three axes, so the rate this channel sees cannot be told without its own output: anisoinertia is not observable".to_string()
                } else if rate_std < ANISOINERTIA_MIN_RATE_DEG_S {
                    format!(
                        "the angular rate does not vary (largest std {rate_std:.3} deg/s < {ANISOINERTIA_MIN_RATE_DEG_S} deg/s): anisoinertia is not observable"
                    )
                } else {
                    return Candidacy::Excited(e);
                };
                Candidacy::NotExcited { effect: e, reason }
            })
            .collect()
    }

    fn check_excited(
        &self,
        calibrated: &Signals,
        samples: &[usize],
        channel: usize,
        effects: &[UnitEffect],
    ) -> Result<(), SensorError> {
        let Some(ai) = effects.iter().find(|e| is_anisoinertia(e)) else {
            return Ok(());
        };
        let v = self.rate_variation_deg_s(calibrated, samples);
        if v < ANISOINERTIA_MIN_RATE_DEG_S || rate_without(&self.unit, channel).is_none() {
            return Err(boxed(UnitSensorError::EffectNotObservable {
                channel: self.unit.gyros()[channel].name.clone(),
                effect: ai.id(),
                rate_std_deg_s: v,
                min_deg_s: ANISOINERTIA_MIN_RATE_DEG_S,
            }));
        }
        Ok(())
    }

    fn parse_effect(&self, channel: usize, id: &str) -> Result<UnitEffect, SensorError> {
        let e = id
            .parse::<UnitEffect>()
            .map_err(boxed)?
            .resolved(&self.unit);
        let g = &self.unit.gyros()[channel];
        if let UnitEffect::Dynamic(d) = &e {
            self.check_dynamic(channel, d).map_err(boxed)?;
        }
        if !e.fits(&g.model) {
            return Err(boxed(UnitEffectError::WrongModel {
                channel: g.name.clone(),
                model: g.model.name(),
                id: id.to_string(),
                valid: UnitEffect::terms_of(&g.model)
                    .iter()
                    .map(|e| match e {
                        UnitEffect::Term(t) => t.id(),
                        UnitEffect::Column(_) | UnitEffect::Temperature(_) => "col:NAME",
                        UnitEffect::Dynamic(_) => "sf, ma_x, delay, acc:ACCEL (@LAG)",
                    })
                    .collect(),
            }));
        }
        Ok(e)
    }

    fn regressors(
        &self,
        calibrated: &Signals,
        channel: usize,
        effects: &[UnitEffect],
    ) -> Result<Vec<Vec<f64>>, SensorError> {
        if effects.is_empty() {
            return Ok(Vec::new());
        }
        let gyro = &self.unit.gyros()[channel];
        for e in effects {
            if !e.fits(&gyro.model) {
                return Err(self
                    .parse_effect(channel, &e.id())
                    .err()
                    .unwrap_or_else(|| {
                        boxed(UnitSensorError::Calibration(format!("effect {e}")))
                    }));
            }
        }
        let dynamic = self
            .dynamic_columns(calibrated, channel, effects)
            .map_err(boxed)?;
        let force = self.specific_force(calibrated).map_err(boxed)?;
        let covariance = within_interval_covariance(&force);
        let needs_rate = effects.iter().any(is_anisoinertia);
        let rates: Vec<Vector3<f64>> = match (needs_rate, rate_without(&self.unit, channel)) {
            (true, Some(op)) => self
                .gyro_rows(calibrated)
                .map_err(boxed)?
                .iter()
                .map(|m| {
                    let w = &op * nalgebra::DVector::from_column_slice(m);
                    Vector3::new(w[0], w[1], w[2])
                })
                .collect(),
            _ => vec![Vector3::zeros(); force.len()],
        };
        let sensed: Vec<Sensed> = (0..force.len())
            .map(|i| Sensed {
                rate_deg_h: rates[i],
                specific_force_g: force[i],
                specific_force_cov_g2: covariance[i],
                ..Sensed::default()
            })
            .collect();
        let extra = self.extra_columns(calibrated);
        let mut dynamic = dynamic.into_iter();
        let columns = effects
            .iter()
            .map(|e| match e {
                UnitEffect::Dynamic(_) => Ok(dynamic.next().unwrap_or_default()),
                UnitEffect::Term(t) => Ok(sensed.iter().map(|s| gyro.regressor(*t, s)).collect()),
                UnitEffect::Column(c) | UnitEffect::Temperature(c) => calibrated
                    .column(c)
                    .filter(|_| extra.contains(c))
                    .map(<[f64]>::to_vec)
                    .ok_or_else(|| {
                        boxed(UnitEffectError::MissingColumn {
                            name: c.clone(),
                            available: extra.clone(),
                        })
                    }),
            })
            .collect::<Result<Vec<Vec<f64>>, SensorError>>()?;
        for (e, c) in effects.iter().zip(&columns) {
            range::check_range(
                || format!("channel {}'s effect {}", gyro.name, e.id()),
                c,
                calibrated.t(),
                range::REGRESSOR_HINT,
            )
            .map_err(|e| Box::new(e) as SensorError)?;
        }
        Ok(columns)
    }

    fn separation(
        &self,
        channel: usize,
        group: &[UnitEffect],
        kappa: &[f64],
        operating: &OperatingStats,
    ) -> Separation<Axis> {
        separate::separation(&self.unit, channel, group, kappa, operating)
    }

    fn caveats(
        &self,
        records: &[(&Signals, Vec<usize>)],
        _channel: usize,
        effect: &UnitEffect,
    ) -> Vec<String> {
        let quadratic = match effect {
            UnitEffect::Term(GyroTerm::Dtg(t)) if DtgTerm::SPECIFIC_FORCE.contains(t) => {
                t.is_quadratic()
            }
            UnitEffect::Term(GyroTerm::Rate(t)) if RateTerm::SPECIFIC_FORCE.contains(t) => {
                t.is_quadratic()
            }
            _ => return Vec::new(),
        };
        crate::caveats::specific_force_caveats(&self.unit, records, quadratic)
    }

    /// The unit's parity residues (eq. 6's for the paper's geometry, the
    /// rows of V otherwise): the fit's keep step holds each to a bias
    /// instability no higher than before, as each gyro.
    fn residues(&self) -> Vec<(String, Vec<f64>)> {
        let g = self.unit.geometry();
        let c = g.residue_coefficients();
        g.residue_names()
            .iter()
            .enumerate()
            .map(|(r, name)| (name.clone(), (0..c.ncols()).map(|j| c[(r, j)]).collect()))
            .collect()
    }

    /// The rate-dependent families, as the rate reference lets a record
    /// observe them.
    fn observable(&self) -> Vec<String> {
        super::observable::rate_families_observable(&self.rate_reference)
    }
}
