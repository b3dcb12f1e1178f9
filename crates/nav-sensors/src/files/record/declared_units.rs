//! The units a unit file declares (`[units]`), checked against what the
//! data can tell: a log read in the wrong unit is off by a factor the
//! physics shows (3600 between deg/s and deg/h, 9.80665 between g and
//! m/s², 57.3 between rad and deg). Each check returns the likely unit,
//! one line naming the columns; none refuses, since a test rig may
//! legitimately read outside these ranges.
//!
//! - specific force: the median magnitude of the accelerometers' specific
//!   force is 1 g on Earth whatever the unit does (at rest exactly, on a
//!   hand-held or flying unit on average);
//! - still gyro noise: the white-noise density of a still record's gyros,
//!   from first differences (σ_diff/√2 · √Δt), lies within every gyro
//!   grade's span [`GYRO_DENSITY_SPAN_DEG_H_RT_HZ`];
//! - a turning record's rates: the gravity direction the accelerometers
//!   read one quarter second after another turns as the gyros' integrated
//!   rate turns it. Another unit is proposed only when its rates explain
//!   that turn ([`TILT_EXPLAINED`]); where no unit does (a rotorcraft, whose
//!   accelerometers read the thrust that turns with it), the check is
//!   silent.

use std::fmt;

use nalgebra::{Rotation3, Vector3};

use super::Record;
use crate::unit::{RateUnit, SpecificForceUnit, Unit};

/// The white-noise density of every gyro grade, deg/h/√Hz: from below the
/// quietest navigation-grade gyro (0.0005 deg/√h ARW is 0.03 deg/h/√Hz;
/// 0.02 here, ARW 0.00033 deg/√h) to 10× a consumer MEMS gyro's (0.03
/// deg/s/√Hz, 108 deg/h/√Hz). A quiet MEMS log in deg/s taken for deg/h
/// (a PX4 autopilot's, 30–40 deg/h/√Hz, reads 0.01) falls below it. The
/// span is wider than 3600, so a noisy MEMS log so taken (250 deg/h/√Hz
/// reads 0.07, a navigation-grade figure) is not caught here: the tilt
/// check on a turning record is the one that tells.
pub const GYRO_DENSITY_SPAN_DEG_H_RT_HZ: (f64, f64) = (0.02, 1080.0);

/// A specific-force magnitude within this factor of 1 g is taken as read
/// in the right unit (a hand-held or vibrating unit's median stays within
/// 10 % of 1 g; the next unit is 9.8× away).
const FORCE_FACTOR: f64 = 1.5;

/// A tilt check needs this much turning, deg, summed over the record's
/// steps (less is noise and linear acceleration).
const MIN_TILT_DEG: f64 = 20.0;

/// The tilt check's step, s: gravity averaged over it (the noise and the
/// hand's or vehicle's linear acceleration averaged down) and turned by the
/// gyros from one step's middle to the next.
const TILT_STEP_S: f64 = 0.25;

/// A unit's rates explain the accelerometers' tilt change, and better than
/// another unit's, when their miss is at most this share of the other's or
/// of the tilt change itself (a gyro that turns nothing). A rotorcraft's
/// accelerometers read its thrust, which turns with the body (the real
/// three-IMU quadrotor flights: declared deg/s misses by 6.7 and 8.2 deg per
/// step, turning nothing by 2.4 and 6.2), so no unit explains their tilt
/// and the check says nothing; a hand-held log's deg/s rates miss by 0.26
/// deg where turning nothing misses by 1.01.
pub const TILT_EXPLAINED: f64 = 0.5;

/// A declared unit the data contradict.
#[derive(Debug, Clone, PartialEq)]
pub enum DeclaredUnitWarning {
    /// The accelerometers' median specific-force magnitude is not 1 g.
    SpecificForce {
        /// The accelerometer columns.
        columns: Vec<String>,
        /// The median magnitude, in the declared unit's g.
        magnitude_g: f64,
        /// `[units] specific_force`.
        declared: SpecificForceUnit,
        /// The unit in which it reads 1 g.
        likely: SpecificForceUnit,
    },
    /// A still record's gyro noise density is outside every gyro grade.
    GyroNoise {
        /// The gyro column.
        column: String,
        /// Its density as declared, deg/h/√Hz.
        density_deg_h_rt_hz: f64,
        /// `[units] rate`.
        declared: RateUnit,
        /// The unit in which it lies within the grades.
        likely: RateUnit,
    },
    /// A turning record's gyros turn gravity otherwise than the
    /// accelerometers see it turn.
    TiltChange {
        /// The gyro columns.
        columns: Vec<String>,
        /// The accelerometers' tilt change, deg, summed over the steps.
        tilt_deg: f64,
        /// The mean angle, deg, between the accelerometers' gravity and the
        /// gyros' propagation of it, as declared and in the likely unit.
        miss_deg: (f64, f64),
        /// `[units] rate`.
        declared: RateUnit,
        /// The unit that makes them agree.
        likely: RateUnit,
    },
}

impl fmt::Display for DeclaredUnitWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::SpecificForce {
                columns,
                magnitude_g,
                declared,
                likely,
            } => write!(
                f,
                "columns {}: the specific force reads {magnitude_g:.4} g in magnitude as [units] specific_force = \"{declared}\" declares, where Earth's gravity gives 1 g: the log is likely in {likely}; set specific_force = \"{likely}\"",
                columns.join(", ")
            ),
            Self::GyroNoise {
                column,
                density_deg_h_rt_hz,
                declared,
                likely,
            } => write!(
                f,
                "column {column}: its still noise is {density_deg_h_rt_hz:.3e} deg/h/√Hz as [units] rate = \"{declared}\" declares, outside every gyro grade ({} to {} deg/h/√Hz): the log is likely in {likely}; set rate = \"{likely}\"",
                GYRO_DENSITY_SPAN_DEG_H_RT_HZ.0, GYRO_DENSITY_SPAN_DEG_H_RT_HZ.1
            ),
            Self::TiltChange {
                columns,
                tilt_deg,
                miss_deg,
                declared,
                likely,
            } => write!(
                f,
                "columns {}: integrated as [units] rate = \"{declared}\" declares, the rates miss the accelerometers' tilt change ({tilt_deg:.0} deg over {TILT_STEP_S}-s steps) by {:.1} deg per {TILT_STEP_S} s step, and by {:.1} deg in {likely}: the log is likely in {likely}; set rate = \"{likely}\"",
                columns.join(", "),
                miss_deg.0,
                miss_deg.1
            ),
        }
    }
}

/// The declared units of `unit` checked on `record` (read with it, so in
/// deg/h and g): the specific-force check always, the gyro-noise check when
/// `still` (the caller's turning detector says the unit does not turn), the
/// tilt check when not.
///
/// ```
/// use nav_sensors::record::{Record, declared_unit_warnings};
/// use nav_sensors::unit::Unit;
/// // A triad log in g (az = 1) where the unit declares m/s².
/// let csv: String = std::iter::once("t,gx,gy,gz,ax,ay,az\n".to_string())
///     .chain((0..200).map(|i| format!("{},0.01,0,0,0,0,1\n", i as f64 * 0.01)))
///     .collect();
/// let triad = Unit::builtin("triad").unwrap();
/// let rec = &Record::from_reader_with_unit(csv.as_bytes(), "g.csv", &triad).unwrap().records[0];
/// let w = declared_unit_warnings(&triad, rec, true);
/// assert!(w[0].to_string().starts_with("columns ax, ay, az: the specific force reads 0.1020 g"), "{}", w[0]);
/// ```
pub fn declared_unit_warnings(
    unit: &Unit,
    record: &Record,
    still: bool,
) -> Vec<DeclaredUnitWarning> {
    let mut out: Vec<DeclaredUnitWarning> = specific_force(unit, record).into_iter().collect();
    if still {
        out.extend(gyro_noise(unit, record));
    } else {
        out.extend(tilt_change(unit, record));
    }
    out
}

const FORCE_UNITS: [SpecificForceUnit; 2] =
    [SpecificForceUnit::G, SpecificForceUnit::MetresPerSecond2];
const RATE_UNITS: [RateUnit; 3] = [
    RateUnit::DegPerHour,
    RateUnit::DegPerSecond,
    RateUnit::RadPerSecond,
];

fn specific_force(unit: &Unit, record: &Record) -> Option<DeclaredUnitWarning> {
    let magnitudes: Vec<f64> = (0..record.len())
        .map(|i| unit.specific_force(&record.accel_row(i)).norm())
        .collect();
    let m = super::time::median(&magnitudes);
    let declared = unit.units().specific_force;
    if (m.ln()).abs() <= FORCE_FACTOR.ln() {
        return None;
    }
    let as_read_in = |u: SpecificForceUnit| m * u.to_g() / declared.to_g();
    let likely = FORCE_UNITS
        .into_iter()
        .find(|&u| as_read_in(u).ln().abs() <= FORCE_FACTOR.ln())?;
    Some(DeclaredUnitWarning::SpecificForce {
        columns: record.accel_names().to_vec(),
        magnitude_g: m,
        declared,
        likely,
    })
}

fn gyro_noise(unit: &Unit, record: &Record) -> Vec<DeclaredUnitWarning> {
    let declared = unit.units().rate;
    let (lo, hi) = GYRO_DENSITY_SPAN_DEG_H_RT_HZ;
    let dt = record.dt();
    let mut out = Vec::new();
    for (k, name) in record.gyro_names().iter().enumerate() {
        let d: Vec<f64> = record.gyro_at(k).windows(2).map(|w| w[1] - w[0]).collect();
        let mean = d.iter().sum::<f64>() / d.len() as f64;
        let var = d.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / d.len() as f64;
        let density = (var / 2.0).sqrt() * dt.sqrt();
        let within = |v: f64| (lo..=hi).contains(&v);
        if density == 0.0 || within(density) {
            continue;
        }
        let likely = RATE_UNITS
            .into_iter()
            .find(|&u| within(density * u.to_deg_h() / declared.to_deg_h()));
        if let Some(likely) = likely {
            out.push(DeclaredUnitWarning::GyroNoise {
                column: name.clone(),
                density_deg_h_rt_hz: density,
                declared,
                likely,
            });
        }
    }
    out
}

/// What the tilt check weighs on a record (a step is [`TILT_STEP_S`]):
/// how far the accelerometers' gravity turns, and how far the gyros' rates
/// miss it read in the declared unit, in the unit that explains it best,
/// and by a gyro that turns nothing. None when the record is shorter than
/// three steps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TiltMisses {
    /// The gravity direction's change summed over the steps, deg.
    pub tilt_deg: f64,
    /// The mean miss per step with the declared rate unit, deg.
    pub as_declared_deg: f64,
    /// The rate unit whose reading misses least.
    pub likely: RateUnit,
    /// Its mean miss per step, deg.
    pub best_deg: f64,
    /// The mean miss per step of a gyro that turns nothing (the tilt
    /// change per step), deg.
    pub unturned_deg: f64,
}

/// The tilt check's figures on `record` read with `unit`
/// ([`TiltMisses`]).
pub fn tilt_misses(unit: &Unit, record: &Record) -> Option<TiltMisses> {
    figures(unit, record, 0.0)
}

/// [`tilt_misses`], or None as soon as gravity turns by less than
/// `min_tilt_deg` (the misses are the costly part).
fn figures(unit: &Unit, record: &Record, min_tilt_deg: f64) -> Option<TiltMisses> {
    let n = record.len();
    let per_s = ((TILT_STEP_S / record.dt()).round() as usize).max(1);
    if n < 3 * per_s {
        return None;
    }
    let gravity: Vec<Vector3<f64>> = (0..n / per_s)
        .map(|c| {
            (c * per_s..(c + 1) * per_s)
                .map(|i| unit.specific_force(&record.accel_row(i)))
                .sum::<Vector3<f64>>()
        })
        .collect();
    let t = record.t();
    let tilt: f64 = gravity
        .windows(2)
        .map(|w| w[0].angle(&w[1]))
        .sum::<f64>()
        .to_degrees();
    if tilt < min_tilt_deg {
        return None;
    }
    let rate: Vec<Vector3<f64>> = (0..n)
        .map(|i| unit.least_squares_rate(&record.gyro_row(i)))
        .collect();
    // The mean angle between each step's gravity and the previous step's,
    // turned by the gyros' rate (× `scale`) over the samples
    // between their middles: in the body frame gravity turns by −ω.
    let miss = |scale: f64| -> f64 {
        let mut sum = 0.0;
        for c in 1..gravity.len() {
            let (from, to) = ((c - 1) * per_s + per_s / 2, c * per_s + per_s / 2);
            let mut r = Rotation3::identity();
            for i in from..to {
                let w = rate[i] * scale / 3600.0_f64;
                r = Rotation3::new(-w.map(f64::to_radians) * (t[i + 1] - t[i])) * r;
            }
            sum += (r * gravity[c - 1]).angle(&gravity[c]);
        }
        (sum / (gravity.len() - 1) as f64).to_degrees()
    };
    let declared = unit.units().rate;
    let (likely, best) = RATE_UNITS
        .into_iter()
        .map(|u| (u, miss(u.to_deg_h() / declared.to_deg_h())))
        .min_by(|a, b| a.1.total_cmp(&b.1))?;
    Some(TiltMisses {
        tilt_deg: tilt,
        as_declared_deg: miss(1.0),
        likely,
        best_deg: best,
        unturned_deg: miss(0.0),
    })
}

fn tilt_change(unit: &Unit, record: &Record) -> Option<DeclaredUnitWarning> {
    let m = figures(unit, record, MIN_TILT_DEG)?;
    // Another unit must explain the tilt clearly better than the declared,
    // and explain it at all: better than a gyro that turns nothing (whose
    // miss is the tilt change per step). Where no unit does, the
    // accelerometers read thrust or manoeuvre, not gravity, and the check
    // cannot tell.
    let declared = unit.units().rate;
    if m.likely == declared
        || m.best_deg > TILT_EXPLAINED * m.as_declared_deg
        || m.best_deg > TILT_EXPLAINED * m.unturned_deg
    {
        return None;
    }
    Some(DeclaredUnitWarning::TiltChange {
        columns: record.gyro_names().to_vec(),
        tilt_deg: m.tilt_deg,
        miss_deg: (m.as_declared_deg, m.best_deg),
        declared,
        likely: m.likely,
    })
}
