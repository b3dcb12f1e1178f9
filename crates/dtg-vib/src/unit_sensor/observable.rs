//! Whether a record lets the loop see the gyro errors at all. The loop's
//! target is each output less the known rate; without a rate reference it
//! is the output itself, which on a still or table-mounted unit is the
//! error plus a constant (the bias takes it), but on a moving vehicle is
//! the vehicle's motion: a fit would model the flight, not the gyro.

use super::sensor::UnitSensor;
use nav_sensors::record::Record;

/// How much the unit turns on a record: the largest standard deviation,
/// over the three axes, of the least-squares rate averaged over 1 s,
/// deg/s (a still unit: its noise averaged down, well under 0.1 deg/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Observability {
    /// The largest 1-s rate standard deviation, deg/s.
    pub rate_std_deg_s: f64,
}

/// Above this 1-s rate standard deviation (deg/s) a record without a rate
/// reference is a moving vehicle's: 0.5 deg/s is 100 times a tactical
/// MEMS gyro's 1-s noise (0.3 deg/√h ARW gives 0.005 deg/s) and well under
/// a hand-held or flying unit's motion (several deg/s).
pub const MOVING_RATE_STD_DEG_S: f64 = 0.5;

/// How much the unit turns on a record (see [`Observability`]).
///
/// ```
/// let s = dtg_vib::unit_sensor::UnitSensor::new(nav_sensors::unit::Unit::builtin("triad").unwrap());
/// let csv: String = std::iter::once("t,gx,gy,gz,ax,ay,az\n".to_string())
///     .chain((0..400).map(|i| format!("{},{},0,0,0,0,9.8\n", i as f64 * 0.01, if (i / 100) % 2 == 0 { 20.0 } else { -20.0 })))
///     .collect();
/// let rec = &nav_sensors::record::Record::from_reader_with_unit(csv.as_bytes(), "m.csv", &s.unit).unwrap().records[0];
/// assert!(dtg_vib::unit_sensor::observability(&s, rec).rate_std_deg_s > 10.0);
/// ```
pub fn observability(sensor: &UnitSensor, record: &Record) -> Observability {
    let n = record.len();
    let per_s = ((1.0 / record.dt()).round() as usize).clamp(1, n.max(1));
    let rows: Vec<nalgebra::Vector3<f64>> = (0..n)
        .map(|i| sensor.unit.least_squares_rate(&record.gyro_row(i)) / 3600.0)
        .collect();
    let means: Vec<nalgebra::Vector3<f64>> = rows
        .chunks(per_s)
        .filter(|c| c.len() == per_s)
        .map(|c| c.iter().sum::<nalgebra::Vector3<f64>>() / c.len() as f64)
        .collect();
    let rate_std_deg_s = largest_axis_std(&means);
    Observability { rate_std_deg_s }
}

/// The largest standard deviation (about the mean) of three-axis samples'
/// axes; 0 for none.
pub(crate) fn largest_axis_std(v: &[nalgebra::Vector3<f64>]) -> f64 {
    let n = v.len().max(1) as f64;
    (0..3)
        .map(|k| {
            let m = v.iter().map(|w| w[k]).sum::<f64>() / n;
            (v.iter().map(|w| (w[k] - m).powi(2)).sum::<f64>() / n).sqrt()
        })
        .fold(0.0, f64::max)
}
