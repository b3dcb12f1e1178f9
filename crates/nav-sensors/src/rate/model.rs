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

use nalgebra::{Matrix3, Vector3};

use super::coefficients::RateCoefficients;
use super::term::RateTerm;

/// What one rate gyro senses at one instant (or over one interval).
///
/// ```
/// use nav_sensors::rate::RateInput;
/// use nalgebra::Vector3;
/// let x = RateInput::sensed(&Vector3::new(0.0, 0.0, 1.0), &Vector3::new(3.0, 0.0, 7.5), &Vector3::new(0.0, 0.0, 1.0));
/// assert_eq!((x.rate_i_deg_h, x.specific_force_g.z), (7.5, 1.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RateInput {
    /// Angular rate about the input axis, deg/h.
    pub rate_i_deg_h: f64,
    /// Specific force in the unit frame, g.
    pub specific_force_g: Vector3<f64>,
    /// Within-interval covariance of the specific force in the unit frame
    /// (xx, yy, zz, xy, xz, yz), g²: what the product of interval means
    /// misses of the interval mean of a product. Zero at an instant and
    /// where unknown.
    pub specific_force_cov_g2: [f64; 6],
    /// Temperature minus the reference temperature, °C.
    pub temperature_delta_c: f64,
}

impl RateInput {
    /// What a gyro with input axis `input` senses of a unit-frame rate
    /// (deg/h) and specific force (g); temperature and covariance zero.
    ///
    /// ```
    /// use nav_sensors::rate::RateInput;
    /// use nalgebra::Vector3;
    /// let x = RateInput::sensed(&Vector3::x(), &Vector3::new(15.0, 2.0, 0.0), &Vector3::zeros());
    /// assert_eq!(x.rate_i_deg_h, 15.0);
    /// ```
    pub fn sensed(
        input: &Vector3<f64>,
        rate_deg_h: &Vector3<f64>,
        specific_force_g: &Vector3<f64>,
    ) -> Self {
        Self {
            rate_i_deg_h: input.dot(rate_deg_h),
            specific_force_g: *specific_force_g,
            ..Self::default()
        }
    }

    /// Sets the within-interval covariance from a unit-frame covariance
    /// matrix (g²), e.g. one of [`crate::dtg::within_interval_covariance`].
    ///
    /// ```
    /// use nav_sensors::rate::{RateInput, RateTerm};
    /// let cov = nalgebra::Matrix3::from_diagonal(&nalgebra::Vector3::new(0.0, 0.0, 0.5));
    /// let x = RateInput { specific_force_g: nalgebra::Vector3::new(0.0, 0.0, 2.0), ..Default::default() }
    ///     .with_covariance(&cov);
    /// assert_eq!(RateTerm::GgZz.regressor(&x), 4.5);
    /// ```
    pub fn with_covariance(mut self, cov: &Matrix3<f64>) -> Self {
        self.specific_force_cov_g2 = [
            cov[(0, 0)],
            cov[(1, 1)],
            cov[(2, 2)],
            cov[(0, 1)],
            cov[(0, 2)],
            cov[(1, 2)],
        ];
        self
    }
}

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
