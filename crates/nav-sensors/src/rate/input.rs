//! What a rate gyro senses: the input of every term's regressor and of
//! the channel model.

use nalgebra::{Matrix3, Vector3};

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
