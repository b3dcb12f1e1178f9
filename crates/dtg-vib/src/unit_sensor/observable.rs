//! Whether a record lets the loop see the gyro errors at all. The loop's
//! target is each output less the known rate; without a rate reference it
//! is the output itself, which on a still or table-mounted unit is the
//! error plus a constant (the bias takes it), but on a moving vehicle is
//! the vehicle's motion: a fit would model the flight, not the gyro.

use super::preprocess::RateReference;
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

/// A family of rate-dependent effects (IEEE Std 952, 1431 terms) and what
/// every gyro sharing it looks like.
struct RateFamily {
    /// Its effect ids.
    ids: &'static str,
    /// Its name.
    name: &'static str,
    /// The part of it every gyro shares.
    common: &'static str,
    /// What a known reference rate needs to excite it.
    excited_by: &'static str,
}

const RATE_FAMILIES: [RateFamily; 3] = [
    RateFamily {
        ids: "sf, sf@k",
        name: "scale-factor error",
        common: "a scale-factor error equal on every gyro",
        excited_by: "a constant reference rate makes it a constant the bias takes: records at other rates tell them apart",
    },
    RateFamily {
        ids: "ma_x, ma_y, ma_z, ma_*@k",
        name: "misalignment / cross-axis sensitivity",
        common: "a misalignment common to every gyro (the whole unit turned)",
        excited_by: "a constant reference rate makes it a constant the bias takes: records at other rates tell them apart",
    },
    RateFamily {
        ids: "delay, sf@1..4",
        name: "the gyro's frequency response to the rate",
        common: "a delay or bandwidth every gyro shares",
        excited_by: "only where the reference rate changes (a constant rate has no dynamics)",
    },
];

/// What a record can observe of each family of rate-dependent effects
/// under `reference`, one line per family: in parity only the differences
/// between gyros; against a known rate each gyro's own term; nothing
/// without a reference (a still record: no rate term is a candidate).
///
/// ```
/// use dtg_vib::unit_sensor::{RateReference, rate_families_observable};
/// let parity = rate_families_observable(&RateReference::Parity);
/// assert!(parity[0].contains("only its differences between gyros"));
/// let table = rate_families_observable(&RateReference::Table { rate_deg_s: [0.0, 0.0, 10.0] });
/// assert!(table[0].contains("each gyro's own"));
/// assert!(rate_families_observable(&RateReference::None).is_empty());
/// ```
pub fn rate_families_observable(reference: &RateReference) -> Vec<String> {
    let what = |f: &RateFamily| match reference {
        RateReference::Parity => Some(format!(
            "in parity (no rate reference) only its differences between gyros are observable; {} is not",
            f.common
        )),
        RateReference::Earth { .. } | RateReference::Table { .. } => Some(format!(
            "against the rate reference each gyro's own is observable; {}",
            f.excited_by
        )),
        // A still record without a reference: no rate term is a candidate.
        RateReference::None => None,
    };
    RATE_FAMILIES
        .iter()
        .filter_map(|f| Some(format!("{} ({}): {}", f.ids, f.name, what(f)?)))
        .collect()
}
