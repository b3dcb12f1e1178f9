//! Records calibrated within a process, remembered by what the ground
//! calibration reads.
//!
//! The demo prepares its one simulated record about thirteen times (each
//! fit, mirror, diagnosis and page calibrates it again), each time to the
//! same numbers. The calibration is a pure function of the unit, its
//! calibration and the raw record, so one asked again with the same inputs
//! is taken from here, bit for bit the one computed before. The key is a
//! 128-bit digest ([`sysid::fit::Digester`]), not the arrays; records of
//! more than [`MAX_ROWS`] rows are not remembered (hashing and keeping them
//! would cost time and memory, and a large record's fit calibrates it once).

use nav_sensors::calibration::UnitCalibration;
use nav_sensors::unit::Unit;
use sysid::fit::{Digest, Digester, Store};
use sysid::{SensorError, Signals};

/// Largest record (rows) whose calibration is remembered.
pub const MAX_ROWS: usize = 100_000;

/// Calibrated records remembered; the oldest is dropped beyond this (the
/// explain loop over three records asks for three).
const CAPACITY: usize = 8;

static CALIBRATED: Store<Signals> = Store::new(CAPACITY);

/// `calibrate()` of `raw` by `calibration` on `unit`, taken from the
/// records remembered when the same one was calibrated before. Failures are
/// not remembered: they are computed again, and say so again.
pub(super) fn remembered(
    (unit, calibration): (&Unit, &UnitCalibration),
    raw: &Signals,
    calibrate: impl FnOnce() -> Result<Signals, SensorError>,
) -> Result<Signals, SensorError> {
    remembered_in(&CALIBRATED, (unit, calibration), raw, calibrate)
}

/// [`remembered`] with the store given (a test's own, which tests running
/// alongside cannot fill).
fn remembered_in(
    store: &Store<Signals>,
    (unit, calibration): (&Unit, &UnitCalibration),
    raw: &Signals,
    calibrate: impl FnOnce() -> Result<Signals, SensorError>,
) -> Result<Signals, SensorError> {
    if raw.len() > MAX_ROWS {
        return calibrate();
    }
    let key = digest((unit, calibration), raw);
    if let Some(s) = store.recall(key) {
        return Ok(s);
    }
    let calibrated = calibrate()?;
    store.keep(key, &calibrated);
    Ok(calibrated)
}

/// Everything the calibration reads: the unit, its calibration (each as
/// its full debug text) and the raw record's times, names and columns.
fn digest((unit, calibration): (&Unit, &UnitCalibration), raw: &Signals) -> Digest {
    let mut d = Digester::new();
    d.text(&format!("{unit:?}"));
    d.text(&format!("{calibration:?}"));
    d.f64s(raw.t().iter().copied());
    for (name, column) in raw.columns() {
        d.text(name);
        d.f64s(column.iter().copied());
    }
    d.word(raw.columns().len() as u64);
    d.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A record calibrated again is the one remembered; another record, or
    /// another calibration, is calibrated.
    #[test]
    fn a_calibration_is_remembered_by_what_it_reads() {
        let unit = Unit::paper();
        let cal = UnitCalibration {
            format_version: UnitCalibration::FORMAT_VERSION,
            gyros: Default::default(),
            accels: Default::default(),
        };
        let raw = |v: f64| {
            Signals::new(vec![0.0, 0.02, 0.04], vec![("X".into(), vec![v, 1.0, 2.0])]).unwrap()
        };
        let marked = |v: f64| Ok(raw(v));
        let store = Store::new(CAPACITY);
        let ask = |r: &Signals, c: &UnitCalibration, v: f64| {
            remembered_in(&store, (&unit, c), r, || marked(v))
                .unwrap()
                .columns()[0]
                .1[0]
        };
        assert_eq!(ask(&raw(0.5), &cal, 10.0), 10.0);
        assert_eq!(ask(&raw(0.5), &cal, 11.0), 10.0, "remembered");
        assert_eq!(ask(&raw(0.25), &cal, 12.0), 12.0);
        let mut other = cal.clone();
        other.accels.insert(
            "az".into(),
            nav_sensors::accel::AccelCoefficients {
                bias_ug: 5.0,
                ..Default::default()
            },
        );
        assert_eq!(ask(&raw(0.5), &other, 13.0), 13.0);
    }
}
