//! The rate-gyro channel model, forward (truth → output) and inverse
//! (compensation):
//!
//! ```text
//! output = ω_I + Σ_k c_k · r_k(ω_I, f, T)
//! ```
//!
//! with ω_I the rate about the input axis (deg/h), f the specific force in
//! the unit frame (g), r_k the regressor of term k ([`RateTerm::regressor`])
//! and c_k its coefficient. Noise is added by the simulator, not here.

use super::coefficients::RateCoefficients;
use super::input::RateInput;
use super::term::RateTerm;

impl RateCoefficients {
    /// The forward model: the channel output in deg/h for what it senses.
    ///
    /// ```
    /// use nav_sensors::rate::{RateCoefficients, RateInput};
    /// let c = RateCoefficients { bias_deg_h: 1.0, g_y_deg_h_g: 2.0, gg_zz_deg_h_g2: 0.1, ..Default::default() };
    /// let x = RateInput { rate_i_deg_h: 10.0, specific_force_g: nalgebra::Vector3::new(0.0, 0.5, 3.0), ..Default::default() };
    /// assert!((c.output_deg_h(&x) - (10.0 + 1.0 + 1.0 + 0.9)).abs() < 1e-12);
    /// ```
    #[inline]
    pub fn output_deg_h(&self, x: &RateInput) -> f64 {
        x.rate_i_deg_h + self.drift_deg_h(x)
    }

    /// The error part of the output, `output − ω_I`, deg/h.
    ///
    /// ```
    /// let c = nav_sensors::rate::RateCoefficients { bias_deg_h: -0.7, ..Default::default() };
    /// assert_eq!(c.error_deg_h(&Default::default()), -0.7);
    /// ```
    pub fn error_deg_h(&self, x: &RateInput) -> f64 {
        self.drift_deg_h(x)
    }

    fn drift_deg_h(&self, x: &RateInput) -> f64 {
        self.to_array()
            .iter()
            .zip(RateTerm::regressors(x))
            .map(|(c, r)| c * r)
            .sum()
    }

    /// The inverse model (compensation): the rate about I, deg/h, that
    /// produces `measured_deg_h` given the other inputs in `x` (its
    /// `rate_i_deg_h` is ignored). The model is affine in ω_I, so this is exact.
    ///
    /// ```
    /// use nav_sensors::rate::{RateCoefficients, RateInput};
    /// let c = RateCoefficients { bias_deg_h: 3.0, scale_factor_ppm: 200.0, gg_xy_deg_h_g2: 0.05, ..Default::default() };
    /// let mut x = RateInput { specific_force_g: nalgebra::Vector3::new(2.0, 1.0, 0.0), ..Default::default() };
    /// x.rate_i_deg_h = 15.0;
    /// assert!((c.compensate_deg_h(c.output_deg_h(&x), &x) - 15.0).abs() < 1e-10);
    /// ```
    pub fn compensate_deg_h(&self, measured_deg_h: f64, x: &RateInput) -> f64 {
        let zero = RateInput {
            rate_i_deg_h: 0.0,
            ..*x
        };
        let a = self.drift_deg_h(&zero);
        (measured_deg_h - a) / (1.0 + 1e-6 * self.scale_factor_ppm)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    #[test]
    fn forward_is_the_sum_of_documented_terms() {
        let c = RateCoefficients {
            bias_deg_h: 1.0,
            scale_factor_ppm: 100.0,
            g_x_deg_h_g: 0.5,
            g_y_deg_h_g: -0.3,
            g_z_deg_h_g: 2.0,
            gg_xx_deg_h_g2: 0.01,
            gg_yy_deg_h_g2: 0.02,
            gg_zz_deg_h_g2: 0.03,
            gg_xy_deg_h_g2: 0.04,
            gg_xz_deg_h_g2: 0.05,
            gg_yz_deg_h_g2: 0.06,
            temp_deg_h_per_c: 0.02,
        };
        let (w, fx, fy, fz) = (36000.0, 0.2, -0.5, 1.0);
        let x = RateInput {
            rate_i_deg_h: w,
            specific_force_g: Vector3::new(fx, fy, fz),
            specific_force_cov_g2: [0.1, 0.2, 0.3, 0.4, 0.5, 0.6],
            temperature_delta_c: 5.0,
        };
        let expect = w + 1.0 + 100e-6 * w + 0.5 * fx - 0.3 * fy
            + 2.0 * fz
            + 0.01 * (fx * fx + 0.1)
            + 0.02 * (fy * fy + 0.2)
            + 0.03 * (fz * fz + 0.3)
            + 0.04 * (fx * fy + 0.4)
            + 0.05 * (fx * fz + 0.5)
            + 0.06 * (fy * fz + 0.6)
            + 0.02 * 5.0;
        assert!((c.output_deg_h(&x) - expect).abs() < 1e-9);
        assert!((c.compensate_deg_h(expect, &x) - w).abs() < 1e-9);
    }
}
