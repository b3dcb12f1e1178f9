//! The fixture's temperature during the test.

use serde::{Deserialize, Serialize};

/// A first-order thermal model of the sensor unit on the shaker:
///
/// ```text
/// τ · dT/dt = T_ambient + ramp·t + heating · g(t)² − T,   T(0) = initial
/// ```
///
/// where g(t) is the vibration level's amplitude gain (1 at 0 dB): the
/// shaker and the fixture's damping warm the unit in proportion to the
/// vibration power. The record's `temp` column is T plus white sensor noise.
/// Drift sensitivity (`temp`) acts on `T − reference`.
///
/// ```
/// use nav_sensors::sim::Thermal;
/// let th = Thermal { vibration_heating_c: 4.0, time_constant_s: 10.0, ..Thermal::default() };
/// let t = th.temperatures(&vec![1.0; 1000], 0.1); // 100 s at full level
/// assert!((t[999] - (th.ambient_c + 4.0)).abs() < 1e-3);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Thermal {
    /// Temperature at t = 0, °C.
    pub initial_c: f64,
    /// Ambient (chamber) temperature at t = 0, °C.
    pub ambient_c: f64,
    /// Ambient ramp, °C/s.
    pub ambient_ramp_c_per_s: f64,
    /// Steady-state warming at full vibration level, °C.
    pub vibration_heating_c: f64,
    /// Thermal time constant of the unit, s.
    pub time_constant_s: f64,
    /// Reference temperature of the drift temperature sensitivity, °C.
    pub reference_c: f64,
    /// Temperature sensor noise (standard deviation), °C.
    pub sensor_noise_c: f64,
}

impl Default for Thermal {
    /// 25 °C lab, 3 °C warming at full level with a 60-s time constant,
    /// 0.02 °C sensor noise.
    fn default() -> Self {
        Self {
            initial_c: 25.0,
            ambient_c: 25.0,
            ambient_ramp_c_per_s: 0.0,
            vibration_heating_c: 3.0,
            time_constant_s: 60.0,
            reference_c: 25.0,
            sensor_noise_c: 0.02,
        }
    }
}

impl Thermal {
    /// True temperature at the end of each output interval, °C, given each
    /// interval's mean squared level gain and the interval `dt_s`. Exact
    /// exponential step with the forcing held over each interval, so any
    /// time constant is stable.
    ///
    /// ```
    /// use nav_sensors::sim::Thermal;
    /// let th = Thermal { ambient_ramp_c_per_s: 0.1, time_constant_s: 0.0, vibration_heating_c: 0.0, ..Thermal::default() };
    /// let t = th.temperatures(&[0.0; 10], 1.0);
    /// assert!((t[9] - (25.0 + 0.1 * 9.5)).abs() < 1e-12); // follows the ramp at the interval mid-point
    /// ```
    pub fn temperatures(&self, level_squared: &[f64], dt_s: f64) -> Vec<f64> {
        let decay = if self.time_constant_s > 0.0 {
            (-dt_s / self.time_constant_s).exp()
        } else {
            0.0
        };
        let mut temp = self.initial_c;
        level_squared
            .iter()
            .enumerate()
            .map(|(n, g2)| {
                let t_mid = (n as f64 + 0.5) * dt_s;
                let forcing = self.ambient_c
                    + self.ambient_ramp_c_per_s * t_mid
                    + self.vibration_heating_c * g2;
                temp = forcing + (temp - forcing) * decay;
                temp
            })
            .collect()
    }
}
