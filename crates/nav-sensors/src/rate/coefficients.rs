//! The coefficient table of one rate-gyro channel, with units in the field names.

use serde::{Deserialize, Serialize};

use super::term::RateTerm;

/// The deterministic error coefficients of one rate gyro (IEEE Std 952 /
/// 1431 terms, acceleration terms in the unit frame), each named with its
/// unit. Missing fields in a file read as zero. The same table serves as
/// truth and as ground calibration (where `temp_deg_h_per_c` is zero).
///
/// ```
/// use nav_sensors::rate::{RateCoefficients, RateTerm};
/// let mut c = RateCoefficients { bias_deg_h: 2.0, ..Default::default() };
/// c.set(RateTerm::GY, 0.5);
/// assert_eq!(c.get(RateTerm::GY), 0.5);
/// assert_eq!(c.g_y_deg_h_g, 0.5);
/// let back: RateCoefficients = toml::from_str("bias_deg_h = 2.0\ng_y_deg_h_g = 0.5\n").unwrap();
/// assert_eq!(back, c);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RateCoefficients {
    /// `bias`, deg/h.
    pub bias_deg_h: f64,
    /// `scale_factor`, ppm.
    pub scale_factor_ppm: f64,
    /// `g_x`, deg/h/g.
    pub g_x_deg_h_g: f64,
    /// `g_y`, deg/h/g.
    pub g_y_deg_h_g: f64,
    /// `g_z`, deg/h/g.
    pub g_z_deg_h_g: f64,
    /// `gg_xx`, deg/h/g².
    pub gg_xx_deg_h_g2: f64,
    /// `gg_yy`, deg/h/g².
    pub gg_yy_deg_h_g2: f64,
    /// `gg_zz`, deg/h/g².
    pub gg_zz_deg_h_g2: f64,
    /// `gg_xy`, deg/h/g².
    pub gg_xy_deg_h_g2: f64,
    /// `gg_xz`, deg/h/g².
    pub gg_xz_deg_h_g2: f64,
    /// `gg_yz`, deg/h/g².
    pub gg_yz_deg_h_g2: f64,
    /// `temp`, deg/h/°C about the scenario's reference temperature.
    pub temp_deg_h_per_c: f64,
}

impl RateCoefficients {
    /// The coefficient of one term, in [`RateTerm::unit`].
    ///
    /// ```
    /// use nav_sensors::rate::{RateCoefficients, RateTerm};
    /// let c = RateCoefficients { gg_xz_deg_h_g2: -0.04, ..Default::default() };
    /// assert_eq!(c.get(RateTerm::GgXz), -0.04);
    /// ```
    pub fn get(&self, term: RateTerm) -> f64 {
        self.to_array()[term.index()]
    }

    /// Sets the coefficient of one term.
    ///
    /// ```
    /// use nav_sensors::rate::{RateCoefficients, RateTerm};
    /// let mut c = RateCoefficients::default();
    /// c.set(RateTerm::Temp, 0.02);
    /// assert_eq!(c.temp_deg_h_per_c, 0.02);
    /// ```
    pub fn set(&mut self, term: RateTerm, value: f64) {
        let slot = match term {
            RateTerm::Bias => &mut self.bias_deg_h,
            RateTerm::ScaleFactor => &mut self.scale_factor_ppm,
            RateTerm::GX => &mut self.g_x_deg_h_g,
            RateTerm::GY => &mut self.g_y_deg_h_g,
            RateTerm::GZ => &mut self.g_z_deg_h_g,
            RateTerm::GgXx => &mut self.gg_xx_deg_h_g2,
            RateTerm::GgYy => &mut self.gg_yy_deg_h_g2,
            RateTerm::GgZz => &mut self.gg_zz_deg_h_g2,
            RateTerm::GgXy => &mut self.gg_xy_deg_h_g2,
            RateTerm::GgXz => &mut self.gg_xz_deg_h_g2,
            RateTerm::GgYz => &mut self.gg_yz_deg_h_g2,
            RateTerm::Temp => &mut self.temp_deg_h_per_c,
        };
        *slot = value;
    }

    /// The coefficients in [`RateTerm::ALL`] order.
    ///
    /// ```
    /// let c = nav_sensors::rate::RateCoefficients { bias_deg_h: 1.5, ..Default::default() };
    /// assert_eq!(c.to_array()[0], 1.5);
    /// ```
    pub fn to_array(&self) -> [f64; 12] {
        [
            self.bias_deg_h,
            self.scale_factor_ppm,
            self.g_x_deg_h_g,
            self.g_y_deg_h_g,
            self.g_z_deg_h_g,
            self.gg_xx_deg_h_g2,
            self.gg_yy_deg_h_g2,
            self.gg_zz_deg_h_g2,
            self.gg_xy_deg_h_g2,
            self.gg_xz_deg_h_g2,
            self.gg_yz_deg_h_g2,
            self.temp_deg_h_per_c,
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn set_then_get_every_term() {
        let mut c = RateCoefficients::default();
        for (k, t) in RateTerm::ALL.into_iter().enumerate() {
            c.set(t, k as f64 + 0.5);
        }
        for (k, t) in RateTerm::ALL.into_iter().enumerate() {
            assert_eq!(c.get(t), k as f64 + 0.5, "{t}");
        }
    }
}
