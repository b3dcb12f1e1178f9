//! The window's signals chosen from the training records (`fit
//! --window-signals auto`): the unit's accelerometers whose vibration is
//! significant in some record ([`sysid::window::signal_choice`]), each calibrated.

use super::range::check_calibrated;
use super::sensor::{MIN_SCALE_G, UnitSensor};
use crate::error::DtgVibError;
use nav_sensors::record::Record;
use nav_sensors::unit::Unit;
use sysid::Signals;
use sysid::window::signal_choice::{ChannelSignals, choose_per_channel};

impl UnitSensor {
    /// The window's signals the named records choose, each record's
    /// accelerometers calibrated alone: the gyros' calibration, which they
    /// do not read, would cost two passes over every row (about 3 s on a
    /// 1M-row record).
    ///
    /// ```
    /// use nav_sensors::sim::{simulate_unit, Scenario};
    /// let unit = nav_sensors::unit::Unit::paper();
    /// let z = simulate_unit(&unit, &Scenario::paper_z_random())?;
    /// let mut s = dtg_vib::unit_sensor::UnitSensor::new(unit);
    /// s.calibration = Some(z.calibration.clone());
    /// let c = s.choose_window_signals(&[("z".into(), &z.record)])?;
    /// assert_eq!(c.signals, vec![vec!["az".to_string()]; 6]);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn choose_window_signals(
        &self,
        records: &[(String, &Record)],
    ) -> Result<ChannelSignals, DtgVibError> {
        let all: Vec<String> = self
            .unit
            .accel_names()
            .iter()
            .map(|n| n.to_string())
            .collect();
        // The accelerometers each gyro's window may read: its own IMU's, or
        // the loop's operating signals when every gyro's are alike.
        let candidates = sysid::window_candidates(self);
        let names = sysid::window::union(&candidates);
        let accels = records
            .iter()
            .map(|(n, r)| {
                let accel: Vec<Vec<f64>> = match &self.calibration {
                    Some(c) => c.compensate_accels(&self.unit, r),
                    None => (0..all.len()).map(|k| r.accel_at(k).to_vec()).collect(),
                };
                let columns = all
                    .iter()
                    .cloned()
                    .zip(accel)
                    .filter(|(a, _)| names.contains(a))
                    .collect();
                let s = Signals::new(r.t().to_vec(), columns).map_err(sysid::SysidError::from)?;
                if self.calibration.is_some() {
                    check_calibrated(&s, names.iter().map(String::as_str)).map_err(|e| {
                        sysid::SysidError::Sensor(Box::new(e)).in_record(n, records.len())
                    })?;
                }
                Ok((n.clone(), s))
            })
            .collect::<Result<Vec<(String, Signals)>, DtgVibError>>()?;
        let borrowed: Vec<(String, &Signals)> =
            accels.iter().map(|(n, s)| (n.clone(), s)).collect();
        let gyros: Vec<String> = self.unit.gyros().iter().map(|g| g.name.clone()).collect();
        Ok(
            choose_per_channel(&candidates, &all, &gyros, &borrowed, MIN_SCALE_G, "g")
                .map_err(sysid::SysidError::from)?,
        )
    }
}

impl UnitSensor {
    /// One line per IMU whose accelerometers were constant in every record
    /// (a still IMU, a dead triad), so that its gyros' windows were chosen
    /// among every accelerometer ([`ChannelSignals::constant`]).
    pub fn constant_imu_notes(&self, chosen: &ChannelSignals) -> Vec<String> {
        chosen
            .constant
            .iter()
            .map(|&i| {
                let c = &chosen.choices[i];
                let first = c.channels.first().and_then(|g| self.unit.gyro_index(g));
                let imu = first.and_then(|k| self.unit.gyros()[k].imu.clone());
                let own = first.map(|k| self.unit.imu_accel_names(k).join(", "));
                format!(
                    "note: IMU {}'s accelerometers ({}) are constant in every record (a still IMU or a dead triad): the windows of {} read {}, chosen among every accelerometer",
                    imu.unwrap_or_default(),
                    own.unwrap_or_default(),
                    c.channels.join(", "),
                    c.taken.join(", ")
                )
            })
            .collect()
    }
}

/// The window's signals of a unit when neither told nor chosen: its
/// accelerometer along its z axis (the axis the built-in tests vibrate
/// along; the paper's window, az), or every accelerometer when none lies
/// along z.
///
/// ```
/// let u = nav_sensors::unit::Unit::builtin("tetra").unwrap();
/// assert_eq!(dtg_vib::unit_sensor::default_window_signals(&u), ["az"]);
/// ```
pub fn default_window_signals(unit: &Unit) -> Vec<String> {
    let along_z = unit
        .accels()
        .iter()
        .find(|a| a.input == nalgebra::Vector3::z());
    match along_z {
        Some(a) => vec![a.name.clone()],
        None => unit.accel_names().iter().map(|n| n.to_string()).collect(),
    }
}
