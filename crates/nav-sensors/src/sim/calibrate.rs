//! The ground calibration a user would have: the truth plus seeded
//! calibration errors, with the hidden effects and the terms ground
//! calibration never covers set to zero. Every coefficient takes two
//! normal draws whether used or not, so the errors of one term do not
//! depend on the others' settings; sensors are drawn in the unit's order,
//! so the paper's unit draws exactly what it always drew.

use std::collections::BTreeMap;

use rand::Rng;
use rand_distr::{Distribution, StandardNormal};

use super::scenario::{CalibrationError, Scenario};
use crate::accel::AccelCoefficients;
use crate::dtg::{DtgCoefficients, DtgTerm};
use crate::files::calibration::{GyroCoefficients, UnitCalibration};
use crate::rate::{RateCoefficients, RateTerm};
use crate::unit::{GyroTerm, Unit};

/// Two independent standard normal draws.
fn normal(rng: &mut impl Rng) -> (f64, f64) {
    (StandardNormal.sample(rng), StandardNormal.sample(rng))
}

/// One term's calibrated value: the truth with a relative and an absolute
/// error when ground calibration determines the term, else zero. Two draws
/// either way, so every channel takes the same share of the stream.
fn drawn(truth: f64, calibrated: bool, relative: f64, absolute: f64, rng: &mut impl Rng) -> f64 {
    let (n1, n2) = normal(rng);
    if calibrated {
        truth * (1.0 + relative * n1) + absolute * n2
    } else {
        0.0
    }
}

/// A DTG channel's calibration: calibrated terms with errors, the others
/// and the hidden ones zero.
fn draw_dtg(
    truth: DtgCoefficients,
    e: &CalibrationError,
    hidden: &[DtgTerm],
    rng: &mut impl Rng,
) -> DtgCoefficients {
    let mut cal = truth;
    for t in DtgTerm::ALL {
        let v = drawn(
            truth.get(t),
            t.is_calibrated(),
            e.relative,
            e.absolute_for(t),
            rng,
        );
        cal.set(t, v);
    }
    let (n1, _) = normal(rng);
    cal.scale_factor_nonlinearity_ppm_per_deg_s *= 1.0 + e.relative * n1;
    for &t in hidden {
        cal.set(t, 0.0);
    }
    cal
}

/// A rate gyro's calibration, as [`draw_dtg`].
fn draw_rate(
    truth: RateCoefficients,
    e: &CalibrationError,
    hidden: &[RateTerm],
    rng: &mut impl Rng,
) -> RateCoefficients {
    let mut cal = truth;
    for t in RateTerm::ALL {
        let v = drawn(
            truth.get(t),
            t.is_calibrated(),
            e.relative,
            e.absolute_for_rate(t),
            rng,
        );
        cal.set(t, v);
    }
    for &t in hidden {
        cal.set(t, 0.0);
    }
    cal
}

/// An accelerometer's calibration.
fn draw_accel(t: AccelCoefficients, e: &CalibrationError, rng: &mut impl Rng) -> AccelCoefficients {
    let mut draw = |value: f64, absolute: f64| {
        let (n1, n2) = normal(rng);
        value * (1.0 + e.relative * n1) + absolute * n2
    };
    AccelCoefficients {
        bias_ug: draw(t.bias_ug, e.accel_bias_ug),
        scale_factor_ppm: draw(t.scale_factor_ppm, e.accel_scale_factor_ppm),
        k2_ug_per_g2: draw(t.k2_ug_per_g2, e.accel_k2_ug_per_g2),
        k3_ug_per_g3: draw(t.k3_ug_per_g3, 0.0),
        misalignment_o_urad: draw(t.misalignment_o_urad, e.accel_misalignment_urad),
        misalignment_p_urad: draw(t.misalignment_p_urad, e.accel_misalignment_urad),
        kip_ug_per_g2: draw(t.kip_ug_per_g2, 0.0),
        kio_ug_per_g2: draw(t.kio_ug_per_g2, 0.0),
    }
}

/// Draws the calibration of any unit: `truth` per gyro (unit order),
/// `hidden` as (gyro index, term), the accelerometers' truth per
/// accelerometer (unit order).
pub(crate) fn unit_ground_calibration(
    unit: &Unit,
    s: &Scenario,
    truth: &[GyroCoefficients],
    hidden: &[(usize, GyroTerm)],
    accels: &[AccelCoefficients],
    rng: &mut impl Rng,
) -> UnitCalibration {
    let e = &s.calibration_error;
    let mut gyros = BTreeMap::new();
    for (k, (g, t)) in unit.gyros().iter().zip(truth).enumerate() {
        let here = hidden.iter().filter(|(c, _)| *c == k).map(|(_, t)| *t);
        let cal = match t {
            GyroCoefficients::Dtg(c) => {
                let h: Vec<DtgTerm> = here
                    .filter_map(|t| {
                        if let GyroTerm::Dtg(t) = t {
                            Some(t)
                        } else {
                            None
                        }
                    })
                    .collect();
                GyroCoefficients::Dtg(draw_dtg(*c, e, &h, rng))
            }
            GyroCoefficients::Rate(c) => {
                let h: Vec<RateTerm> = here
                    .filter_map(|t| {
                        if let GyroTerm::Rate(t) = t {
                            Some(t)
                        } else {
                            None
                        }
                    })
                    .collect();
                GyroCoefficients::Rate(draw_rate(*c, e, &h, rng))
            }
        };
        gyros.insert(g.name.clone(), cal);
    }
    let accels = unit
        .accels()
        .iter()
        .zip(accels)
        .map(|(a, t)| (a.name.clone(), draw_accel(*t, e, rng)))
        .collect();
    UnitCalibration {
        format_version: UnitCalibration::FORMAT_VERSION,
        gyros,
        accels,
    }
}
